"""Prediction intervals of Eq. 9 and the format-2 coefficient file (covariance, residual variance, versions)."""

import json
import warnings

import numpy as np
import pytest
import statsmodels.api as sm

from ehl_dataset.validation import InputError
from surrogate.coefficients import FORMAT_VERSION, content_hash, load_coefficients
from surrogate.evaluate import FrictionSurrogate
from surrogate.forms import design_matrix
from surrogate.intervals import prediction_half_width, t_quantile


def _rewrite(path, tmp_path, edit, name="edited.json"):
    doc = json.loads(path.read_text())
    edit(doc)
    doc["content_sha256"] = content_hash(doc)
    out = tmp_path / name
    out.write_text(json.dumps(doc))
    return out


def test_interval_equals_statsmodels_obs_ci_on_each_branch(eq9_fit):
    """The vectorised interval equals statsmodels' get_prediction().summary_frame(alpha) obs_ci (Montgomery, Peck &
    Vining, Eq. 3.54: t_{1-a/2,n-p} sqrt(s^2 (1 + x0' (X'X)^-1 x0))) to round-off, on the fitted rows and away
    from them."""
    prepared = eq9_fit.prepared
    feats, ln_mu = prepared.features, prepared.ln_mu
    formula = eq9_fit.formula
    lam = feats["lam"]
    for branch, mask in (("mixed", lam <= 1.0), ("full_film", lam > 1.0)):
        sub = {k: v[mask] for k, v in feats.items()}
        x = design_matrix(formula.terms[branch], sub)
        reference = sm.OLS(ln_mu[mask], x).fit()
        # new points: the fitted rows with the load changed (W, r, V, Sc, Seq shift together)
        new = {k: v.copy() for k, v in sub.items()}
        new["W"] = new["W"] + 0.05
        for rows in (sub, new):
            frame = reference.get_prediction(design_matrix(formula.terms[branch], rows)).summary_frame(alpha=0.1)
            expected = (frame["obs_ci_upper"] - frame["obs_ci_lower"]).to_numpy() / 2.0
            fit = eq9_fit.branches[branch]
            cov = {b: f.covariance for b, f in eq9_fit.branches.items()}
            var = {b: f.resid_std_error ** 2 for b, f in eq9_fit.branches.items()}
            df = {b: f.df_resid for b, f in eq9_fit.branches.items()}
            # half width 0: no blend, each branch alone (rows with lam on the branch's side)
            half = prediction_half_width(formula, cov, var, df, rows, 0.0, alpha=0.1)
            if branch == "mixed":
                keep = rows["lam"] <= 1.0
            else:
                keep = rows["lam"] > 1.0
            np.testing.assert_allclose(half[keep], expected[keep], rtol=1e-7)
            assert fit.df_resid == int(reference.df_resid)


def test_t_quantile_is_student_t():
    # t_{0.95, 10} = 1.8125 (tables of Student's t); large df -> normal quantile 1.6449
    assert t_quantile(0.10, 10) == pytest.approx(1.812461, abs=1e-6)
    assert t_quantile(0.10, 1e9) == pytest.approx(1.644854, abs=1e-6)


def test_surrogate_interval_brackets_mu_and_matches_blend(coefficient_file, eq9_fit):
    surrogate = FrictionSurrogate.load(coefficient_file)
    assert surrogate.has_interval and surrogate.coefficients.form == "eq9"
    t = eq9_fit.prepared.table
    args = (t.p_h, t.r_eq, t.u_r, t.sr, t.temperature, t.rq1, t.rq2)
    mu, low, high = surrogate.mu_interval(*args, warn=False)
    np.testing.assert_allclose(mu, surrogate.mu(*args, warn=False), rtol=1e-14)
    assert np.all(low < mu) and np.all(mu < high)
    # the noise of the synthetic table is N(0, 0.05^2) in ln mu: a 90 % interval holds ~90 % of the fitted rows
    inside = (t.mu.to_numpy() >= low) & (t.mu.to_numpy() <= high)
    assert 0.85 <= inside.mean() <= 0.95
    # wider at 99 % than at 90 %
    _, half90 = surrogate.ln_mu_interval(*args, alpha=0.10, warn=False)
    _, half99 = surrogate.ln_mu_interval(*args, alpha=0.01, warn=False)
    assert np.all(half99 > half90)


def test_format_version_1_loads_without_interval(coefficient_file, tmp_path):
    def to_v1(doc):
        doc["format_version"] = 1
        doc.pop("form")
        for branch in doc["branches"].values():
            branch.pop("covariance")
            branch.pop("resid_variance")

    old = FrictionSurrogate.load(_rewrite(coefficient_file, tmp_path, to_v1))
    assert not old.has_interval
    mu, low, high = old.mu_interval(1e9, 0.02, 5.0, 0.2, 353.15, 2e-7, 3e-7, warn=False)
    assert low is None and high is None
    assert mu == pytest.approx(float(FrictionSurrogate.load(coefficient_file).mu(1e9, 0.02, 5.0, 0.2, 353.15, 2e-7,
                                                                                  3e-7, warn=False)), rel=1e-14)


@pytest.mark.parametrize("edit, field, accepted", [
    (lambda d: d.update(format_version=FORMAT_VERSION + 1), "format_version", "newer gearloss"),
    (lambda d: d.update(form="spline"), "form", "'eq9', 'learned'"),
    (lambda d: d["branches"]["mixed"].pop("covariance"), "branches.mixed.covariance", "matrix"),
    (lambda d: d["branches"]["mixed"]["covariance"][0].pop(), "branches.mixed.covariance[0]", "list of 10"),
    (lambda d: d["branches"]["full_film"].update(resid_variance=-1.0), "branches.full_film.resid_variance",
     "non-negative"),
    (lambda d: d["branches"]["full_film"].update(df_resid=0), "branches.full_film.df_resid", "positive integer"),
])
def test_corrupt_or_newer_file_is_one_clear_error(coefficient_file, tmp_path, edit, field, accepted):
    path = _rewrite(coefficient_file, tmp_path, edit)
    with pytest.raises(InputError) as info:
        load_coefficients(path)
    message = str(info.value)
    assert info.value.parameter == field and accepted in message and str(path) in message
    assert "\n" not in message


def test_truncated_file_names_the_file(coefficient_file, tmp_path):
    path = tmp_path / "cut.json"
    path.write_text(coefficient_file.read_text()[:500])
    with pytest.raises(InputError, match="cut.json"):
        load_coefficients(path)


def test_shipped_format_1_files_still_load():
    for name in ("atf", "atf_quick"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            surrogate = FrictionSurrogate.load(name)
        if surrogate.coefficients.document["format_version"] == 1:
            assert not surrogate.has_interval


# ---------------------------------------------------------------------------------------------------------------
# Calibration off the training design (split conformal on the even rows of an off-grid sample)
# ---------------------------------------------------------------------------------------------------------------
def _offgrid_sample(atf, e_reduced, params, noise_sd, n=1600, seed=3):
    """Contacts drawn uniformly inside the synthetic factorial's box (log-uniform r_eq, u_r, SR), ln μ from the same
    Eq. 9 coefficients plus N(0, noise_sd²): the fit's residual variance does not describe these points when
    noise_sd differs from the training noise."""
    import pandas as pd

    from surrogate.synthetic import eq9_table

    rng = np.random.default_rng(seed)

    def log_uniform(low, high):
        return np.exp(rng.uniform(np.log(low), np.log(high), n))

    inputs = pd.DataFrame({"point": np.arange(n), "p_h": rng.uniform(0.5e9, 2.5e9, n),
                           "r_eq": log_uniform(5e-3, 80e-3), "u_r": log_uniform(1.0, 20.0),
                           "sr": log_uniform(0.05, 1.0), "temperature": rng.uniform(298.15, 373.15, n),
                           "rq1": rng.uniform(0.05e-6, 1e-6, n), "rq2": rng.uniform(0.05e-6, 1e-6, n)})
    return eq9_table(inputs, params, atf, e_reduced, noise_sd=noise_sd, seed=seed)


def _with_calibration(surrogate, calibration, tmp_path):
    from surrogate.coefficients import validate_coefficients

    doc = {**surrogate.coefficients.document, "interval_calibration": calibration}
    doc["content_sha256"] = content_hash(doc)
    path = tmp_path / "calibrated.json"
    path.write_text(json.dumps(doc))
    return path


@pytest.mark.parametrize("noise_sd", [0.02, 0.15])
def test_planted_mis_scaled_interval_is_detected_and_recalibrated(coefficient_file, eq9_fit, atf, e_reduced,
                                                                   true_params, tmp_path, noise_sd):
    """Off-grid noise 0.02 (interval 2.5x too wide) or 0.15 (3x too narrow) against the training noise 0.05: the
    plain statsmodels interval misses its 90 % badly; the split-conformal factor from the even rows recovers
    z_0.95 * noise_sd / s (s the branch's residual standard error; the score is |r|/se with se ~ s) and the odd
    rows are covered 90 % +- 4 % (1,600 rows: the binomial SD of a coverage of 0.9 over 800 rows is 1.1 %; the
    calibration quantile of ~330 mixed and ~70 full-film even rows adds about as much, and up to ~12 % on the
    full-film factor, hence its 15 % tolerance)."""
    from surrogate.offgrid import eq9_interval_calibration, offgrid_errors

    plain = FrictionSurrogate.load(coefficient_file)
    table = _offgrid_sample(atf, e_reduced, true_params, noise_sd)
    plain_coverage = offgrid_errors(plain, table)["overall"]["coverage"]
    if noise_sd < 0.05:
        assert plain_coverage > 0.99   # P(|Z| < 1.645 * 2.5) = 0.99996
    else:
        assert plain_coverage < 0.55   # P(|Z| < 1.645 / 3) = 0.41
    calibration, odd = eq9_interval_calibration(plain, table)
    assert np.array_equal(odd, np.arange(len(table)) % 2 == 1)
    for branch, fit in eq9_fit.branches.items():
        expected = 1.6449 * noise_sd / fit.resid_std_error
        assert calibration["score_quantiles"][branch]["0.9"] == pytest.approx(expected, rel=0.15)
    calibrated = FrictionSurrogate.load(_with_calibration(plain, calibration, tmp_path))
    assert calibrated.coefficients.score_quantiles is not None
    result = offgrid_errors(calibrated, table, coverage_rows=odd)
    assert result["overall"]["n_coverage"] == int(odd.sum())
    assert 0.86 <= result["overall"]["coverage"] <= 0.94


def test_calibration_uses_even_rows_and_coverage_counts_odd_rows_only(coefficient_file, atf, e_reduced,
                                                                       true_params, tmp_path):
    from surrogate.offgrid import eq9_interval_calibration, offgrid_errors

    plain = FrictionSurrogate.load(coefficient_file)
    table = _offgrid_sample(atf, e_reduced, true_params, 0.05, n=400)
    calibration, odd = eq9_interval_calibration(plain, table)
    # the odd rows take no part in the calibration: corrupting them leaves it unchanged
    spoiled = table.copy()
    spoiled.loc[odd, "mu"] *= 10.0
    assert eq9_interval_calibration(plain, spoiled)[0] == calibration
    # ... and the even rows take no part in the coverage: corrupting them leaves it unchanged
    calibrated = FrictionSurrogate.load(_with_calibration(plain, calibration, tmp_path))
    reference = offgrid_errors(calibrated, table, coverage_rows=odd)["overall"]["coverage"]
    spoiled = table.copy()
    spoiled.loc[~odd, "mu"] *= 10.0
    assert offgrid_errors(calibrated, spoiled, coverage_rows=odd)["overall"]["coverage"] == reference
    # while counting every row would see them
    assert offgrid_errors(calibrated, spoiled)["overall"]["coverage"] < reference - 0.3


def test_calibrated_half_width_is_the_statsmodels_one_rescaled(coefficient_file, eq9_fit, atf, e_reduced,
                                                                true_params, tmp_path):
    """Away from the blend band the calibrated half width is q_b(c)/t_{1-a/2,nu} times the statsmodels one; a file
    without the table keeps the plain interval and says so; an uncalibrated coverage is refused."""
    from surrogate.offgrid import eq9_interval_calibration

    plain = FrictionSurrogate.load(coefficient_file)
    assert "not calibrated" in plain.coefficients.interval_method
    calibration, _ = eq9_interval_calibration(plain, _offgrid_sample(atf, e_reduced, true_params, 0.03, n=400))
    calibrated = FrictionSurrogate.load(_with_calibration(plain, calibration, tmp_path))
    assert "split-conformal" in calibrated.coefficients.interval_method
    t = eq9_fit.prepared.table
    args = (t.p_h, t.r_eq, t.u_r, t.sr, t.temperature, t.rq1, t.rq2)
    lam = eq9_fit.prepared.features["lam"]
    for alpha in (0.1, 0.05, 0.5):
        _, half_plain = plain.ln_mu_interval(*args, alpha=alpha, warn=False)
        _, half_cal = calibrated.ln_mu_interval(*args, alpha=alpha, warn=False)
        for branch, mask in (("mixed", lam <= 0.9), ("full_film", lam >= 1.1)):
            ratio = calibration["score_quantiles"][branch][f"{1 - alpha:g}"] / t_quantile(alpha, eq9_fit.branches[
                branch].df_resid)
            np.testing.assert_allclose(half_cal[mask], ratio * half_plain[mask], rtol=1e-12)
    with pytest.raises(InputError, match="coverage"):
        calibrated.ln_mu_interval(*args, alpha=0.01, warn=False)


def test_too_few_calibration_rows_is_an_error(coefficient_file, atf, e_reduced, true_params):
    from surrogate.offgrid import eq9_interval_calibration

    plain = FrictionSurrogate.load(coefficient_file)
    with pytest.raises(InputError, match="calibration rows"):
        eq9_interval_calibration(plain, _offgrid_sample(atf, e_reduced, true_params, 0.05, n=20))


@pytest.mark.parametrize("edit, field", [
    (lambda c: c["score_quantiles"]["mixed"].pop("0.9"), "interval_calibration.score_quantiles.mixed"),
    (lambda c: c["score_quantiles"]["full_film"].update({"0.9": -1.0}),
     "interval_calibration.score_quantiles.full_film.0.9"),
    (lambda c: c["score_quantiles"].pop("full_film"), "interval_calibration.score_quantiles.full_film"),
    (lambda c: c.pop("method"), "interval_calibration.method"),
])
def test_corrupt_calibration_is_one_clear_error(coefficient_file, atf, e_reduced, true_params, tmp_path, edit, field):
    from surrogate.offgrid import eq9_interval_calibration

    plain = FrictionSurrogate.load(coefficient_file)
    calibration, _ = eq9_interval_calibration(plain, _offgrid_sample(atf, e_reduced, true_params, 0.05, n=200))
    calibration = json.loads(json.dumps(calibration))
    edit(calibration)
    path = _with_calibration(plain, calibration, tmp_path)
    with pytest.raises(InputError) as info:
        load_coefficients(path)
    assert info.value.parameter == field and str(path) in str(info.value)
