"""Coefficient files: round trip, validation of tampered and incomplete files."""

import json

import numpy as np
import pytest

from ehl_dataset.validation import InputError
from surrogate.coefficients import content_hash, load_coefficients, summary_path
from surrogate.evaluate import FrictionSurrogate


def _rewrite(path, tmp_path, edit, rehash=True):
    doc = json.loads(path.read_text())
    edit(doc)
    if rehash:
        doc["content_sha256"] = content_hash(doc)
    out = tmp_path / "edited.json"
    out.write_text(json.dumps(doc))
    return out


def test_round_trip_preserves_coefficients_and_predictions(coefficient_file, eq9_fit):
    loaded = load_coefficients(coefficient_file)
    for branch, fit in eq9_fit.branches.items():
        np.testing.assert_array_equal(loaded.params[branch], fit.params)  # JSON floats round-trip exactly (repr)
        np.testing.assert_array_equal(loaded.std_errors[branch], fit.std_errors)
    doc = loaded.document
    assert doc["branches"]["mixed"]["n_obs"] == eq9_fit.branches["mixed"].n_obs
    assert doc["cross_validation"]["overall"]["rmse_ln_mu"] == eq9_fit.cv["overall"]["rmse_ln_mu"]
    assert doc["lubricant"]["name"] == "atf" and doc["e_reduced_pa"] == eq9_fit.e_reduced
    summary = summary_path(coefficient_file).read_text()
    assert summary.count("Dep. Variable:") == 2 and "Adj. R-squared:" in summary and "lam*ln(SR)" in summary
    # the evaluator on the fitted rows reproduces the fit's own predictions (same features, same params)
    prepared = eq9_fit.prepared
    t = prepared.table
    mu = FrictionSurrogate(loaded).mu(t.p_h, t.r_eq, t.u_r, t.sr, t.temperature, t.rq1, t.rq2, warn=False)
    assert np.sqrt(np.mean((np.log(mu) - prepared.ln_mu) ** 2)) == pytest.approx(0.05, rel=0.15)


def test_edited_coefficient_is_rejected_by_the_content_hash(coefficient_file, tmp_path):
    def edit(doc):
        doc["branches"]["mixed"]["params"][1] *= 1.01

    with pytest.raises(InputError, match="content_sha256.*modified after it was written"):
        load_coefficients(_rewrite(coefficient_file, tmp_path, edit, rehash=False))


@pytest.mark.parametrize("field, edit", [
    ("branches.full_film.params", lambda d: d["branches"]["full_film"].__setitem__("params", [1.0, 2.0])),
    ("branches.mixed.terms", lambda d: d["branches"]["mixed"]["terms"].reverse()),
    ("input_ranges.p_h_pa", lambda d: d["input_ranges"].pop("p_h_pa")),
    ("evaluation.sr_floor", lambda d: d["evaluation"].__setitem__("sr_floor", -0.1)),
    ("lubricant.viscosity", lambda d: d["lubricant"].pop("viscosity")),
    ("formula.name/version", lambda d: d["formula"].__setitem__("version", 99)),
    ("format", lambda d: d.__setitem__("format", "something else")),
    ("branches.mixed.std_errors", lambda d: d["branches"]["mixed"].__setitem__("std_errors", [None] * 10)),
])
def test_incomplete_or_inconsistent_files_name_the_field(coefficient_file, tmp_path, field, edit):
    """Even with a recomputed hash, structural damage is caught and the error names the field."""
    with pytest.raises(InputError) as info:
        load_coefficients(_rewrite(coefficient_file, tmp_path, edit))
    assert info.value.parameter == field
    assert field in str(info.value)


def test_not_json_is_a_clear_error(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text("{not json")
    with pytest.raises(InputError, match="valid JSON"):
        load_coefficients(bad)
