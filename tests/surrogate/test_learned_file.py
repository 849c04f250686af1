"""The learned form of a coefficient file: numpy evaluation of the JSON weights, calibrated interval, validation."""

import json
import math
import warnings

import numpy as np
import pytest

from efficiency.friction import friction_from_spec
from ehl_dataset.validation import InputError
from surrogate.coefficients import content_hash, load_coefficients, write_coefficients
from surrogate.evaluate import FrictionSurrogate
from surrogate.learned_fit import fit_learned
from surrogate.mlp import conformal_quantile, feature_matrix
from surrogate.synthetic import eq9_table


@pytest.fixture(scope="module")
def learned(eq9_data, atf, e_reduced):
    rows = eq9_data.sample(600, random_state=3).reset_index(drop=True)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return fit_learned(rows, atf, e_reduced, members=5, seed=0)


@pytest.fixture(scope="module")
def learned_file(learned, tmp_path_factory):
    return write_coefficients(learned, tmp_path_factory.mktemp("learned") / "learned.json",
                              source={"path": "synthetic"})


def test_numpy_evaluation_reproduces_scikit_learn(learned):
    """Member k was fitted without fold k and predicted it with scikit-learn (the out-of-fold predictions); the JSON
    weights evaluated in numpy (float32 products) give the same ln mu on those rows to round-off."""
    from sklearn.model_selection import KFold

    x = feature_matrix(learned.prepared.features)
    members = learned.ensemble.member_predictions(x)
    folds = KFold(5, shuffle=True, random_state=0).split(x)
    for k, (_, test) in enumerate(folds):
        np.testing.assert_allclose(members[k, test], learned.result.oof_ln_mu[test], rtol=0, atol=2e-5)


def test_file_round_trip_and_same_inputs_as_eq9(learned, learned_file, coefficient_file):
    surrogate = FrictionSurrogate.load(learned_file)
    assert surrogate.form == "learned" and surrogate.has_interval
    doc = json.loads(learned_file.read_text())  # plain JSON: numbers and strings only, nothing to execute
    assert doc["form"] == "learned" and doc["format_version"] == 2
    t = learned.prepared.table
    args = (t.p_h, t.r_eq, t.u_r, t.sr, t.temperature, t.rq1, t.rq2)
    mean, _ = learned.ensemble.predict(feature_matrix(learned.prepared.features))
    np.testing.assert_allclose(np.log(surrogate.mu(*args, warn=False)), mean, rtol=0, atol=1e-12)
    # the Eq. 9 file of the same lubricant takes the same inputs and records the same kind of ranges
    eq9 = load_coefficients(coefficient_file)
    assert set(eq9.input_ranges) == set(surrogate.coefficients.input_ranges)


def test_interval_is_calibrated_on_fresh_noise(learned, learned_file, atf, e_reduced, true_params):
    """The synthetic rows are exact Eq. 9 plus N(0, 0.05^2) in ln mu. New noise at the fitted points: the 90 %
    interval must hold about 90 % of them (85-95 %: the acceptance band of the brief) — the noise dominates the
    model error there."""
    surrogate = FrictionSurrogate.load(learned_file)
    t = learned.prepared.table
    fresh = eq9_table(t[["p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2"]], true_params, atf, e_reduced,
                      noise_sd=0.05, seed=99)
    mu, low, high = surrogate.mu_interval(fresh.p_h, fresh.r_eq, fresh.u_r, fresh.sr, fresh.temperature, fresh.rq1,
                                          fresh.rq2, warn=False)
    inside = (fresh.mu.to_numpy() >= low) & (fresh.mu.to_numpy() <= high)
    assert 0.85 <= inside.mean() <= 0.95
    assert np.all(low < mu) and np.all(mu < high)


def test_conformal_rank():
    """The ceil((n + 1) q)-th smallest score (split conformal, Lei et al. 2018): n = 19, q = 0.9 -> the 18th."""
    scores = np.arange(1.0, 20.0)[::-1]
    assert conformal_quantile(scores, 0.9) == 18.0
    assert math.isinf(conformal_quantile(scores[:5], 0.9))


def test_friction_from_spec_loads_a_learned_file_with_clipping(learned_file):
    friction = friction_from_spec(str(learned_file))
    assert isinstance(friction, FrictionSurrogate) and friction.clip_to_fitted_ranges
    low_p = friction.coefficients.input_ranges["p_h_pa"][0]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mu = friction(np.array([0.5 * low_p, low_p]), 0.02, 5.0, 0.2, 353.15, 3e-7, 3e-7)
    assert mu[0] == pytest.approx(mu[1], rel=1e-12)  # clipped to the fitted p_h range: the same μ
    assert friction.last_stats()["clipped_inputs"]["p_h"] == 1


@pytest.mark.parametrize("edit, field", [
    (lambda d: d["learned"]["layers"][1].update(weights=[[[0.0]]]), "learned.layers[1].weights"),
    (lambda d: d["learned"].update(features=["W"]), "learned.features"),
    (lambda d: d["learned"]["interval"].update(s0=-1.0), "learned.interval.s0"),
    (lambda d: d["learned"]["layers"][0]["biases"][0].__setitem__(0, "x"), "learned.layers[0].biases"),
    (lambda d: d.update(format_version=3), "format_version"),
])
def test_corrupt_learned_file_is_one_clear_error(learned_file, tmp_path, edit, field):
    doc = json.loads(learned_file.read_text())
    edit(doc)
    doc["content_sha256"] = content_hash(doc)
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(InputError) as info:
        load_coefficients(path)
    assert info.value.parameter == field and "bad.json" in str(info.value)


def test_edited_weights_fail_the_content_hash(learned_file, tmp_path):
    doc = json.loads(learned_file.read_text())
    doc["learned"]["y_mean"] += 1e-3
    path = tmp_path / "edited.json"
    path.write_text(json.dumps(doc))
    with pytest.raises(InputError, match="content_sha256"):
        load_coefficients(path)


def test_split_conformal_recalibration_on_held_out_rows(learned, atf, e_reduced, true_params):
    """recalibrate: q(0.9) is the ceil(0.9 (n + 1))-th smallest normalised score of the held-out rows (Lei et al.
    2018); with it, the 90 % interval holds 85-95 % of another fresh noisy sample at the same points."""
    from surrogate.features import compute_features
    from surrogate.mlp import recalibrate

    t = learned.prepared.table[["p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2"]]
    held, test = (eq9_table(t, true_params, atf, e_reduced, noise_sd=0.05, seed=s) for s in (98, 99))
    feats = compute_features(held.p_h, held.r_eq, held.u_r, held.sr, held.temperature, held.rq1, held.rq2, atf,
                             e_reduced)
    x = feature_matrix(feats)
    ensemble = recalibrate(learned.ensemble, x, np.log(held.mu.to_numpy()))
    mean, spread = ensemble.predict(x)
    scores = np.abs(np.log(held.mu.to_numpy()) - mean) / (spread + ensemble.s0)
    assert ensemble.score_quantiles[0.9] == conformal_quantile(scores, 0.9)
    inside = np.abs(np.log(test.mu.to_numpy()) - mean) <= ensemble.half_width(spread, 0.9)
    assert 0.85 <= inside.mean() <= 0.95
