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
