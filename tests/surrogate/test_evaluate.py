"""The vectorised evaluator: input checks, SR → 0, extrapolation warnings, continuity across λ̄ = 1."""

import warnings

import numpy as np
import pytest

from ehl_dataset.validation import InputError
from surrogate.coefficients import load_coefficients
from surrogate.evaluate import FrictionSurrogate, SurrogateExtrapolationWarning
from surrogate.features import compute_features
from surrogate.model import branch_ln_mu

BASE = dict(p_h=1.0e9, r_eq=0.02, u_r=5.0, sr=0.2, temperature=348.15, rq1=0.2e-6, rq2=0.2e-6)


@pytest.fixture(scope="module")
def surrogate(coefficient_file):
    return FrictionSurrogate(load_coefficients(coefficient_file))


def _call(surrogate, **changes):
    return surrogate.mu(**(BASE | changes))


@pytest.mark.parametrize("name, value, accepted", [
    ("p_h", np.nan, "finite"), ("p_h", -1e9, "(0, inf) Pa"), ("u_r", 0.0, "(0, inf) m/s"),
    ("r_eq", -0.01, "(0, inf) m"), ("rq2", 0.0, "(0, inf) m"), ("sr", 2.5, "[-2, 2]"),
    ("temperature", 500.0, "K for atf"), ("temperature", np.inf, "finite"),
])
def test_bad_inputs_raise_one_clear_error(surrogate, name, value, accepted):
    values = np.full(4, BASE[name], dtype=float)
    values[2] = value
    with pytest.raises(InputError) as info:
        _call(surrogate, **{name: values})
    assert info.value.parameter == name
    assert accepted in str(info.value) and "at index 2" in str(info.value)


def test_vectorised_output_has_the_broadcast_shape_and_is_finite(surrogate):
    p = np.linspace(0.6e9, 2.4e9, 7)[:, None]
    u = np.linspace(1.5, 19.0, 5)[None, :]
    mu = _call(surrogate, p_h=p, u_r=u)
    assert mu.shape == (7, 5) and np.all(np.isfinite(mu)) and np.all(mu > 0)


def test_sr_to_zero_is_finite_and_equals_the_floor_value(surrogate):
    """ln SR terms diverge at SR = 0; the documented policy evaluates |SR| < sr_floor at sr_floor, so μ is finite,
    constant below the floor, symmetric in the sign of SR and continuous at the floor."""
    floor = surrogate.coefficients.sr_floor
    mu = _call(surrogate, sr=np.array([0.0, 1e-9, -0.5 * floor, floor, -floor]))
    assert np.all(np.isfinite(mu))
    np.testing.assert_allclose(mu, mu[3], rtol=1e-14)


def test_extrapolation_warns_and_names_the_input(surrogate):
    hi = surrogate.coefficients.input_ranges["u_r_m_s"][1]
    with pytest.warns(SurrogateExtrapolationWarning, match=r"u_r \(0 below .*, 1 above"):
        mu = _call(surrogate, u_r=np.array([5.0, 2 * hi]))
    assert np.all(np.isfinite(mu))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        _call(surrogate)  # inside the ranges: silent


def _lambda_line(surrogate, lam_targets):
    """Inputs that hit the requested λ̄ exactly by scaling the roughness of the BASE contact (λ̄ ∝ 1/S_c)."""
    f0 = compute_features(**BASE, lubricant=surrogate.lubricant, e_reduced=surrogate.e_reduced)
    scale = float(f0["lam"]) / np.asarray(lam_targets)
    return BASE | {"rq1": BASE["rq1"] * scale, "rq2": BASE["rq2"] * scale}


def test_blend_makes_mu_continuous_across_lambda_one(surrogate):
    """With the blend (δ = 0.1) ln μ is C¹ in λ̄: the step over a 2e-6 wide interval around λ̄ = 1 must be of the
    order of the slope × 2e-6, while the hard-switch jump equals Eq. 9b − Eq. 9a at λ̄ = 1."""
    eps = 1e-6
    args = _lambda_line(surrogate, [1 - eps, 1 + eps])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", SurrogateExtrapolationWarning)
        ln_mu = surrogate.ln_mu(**args)
    assert abs(ln_mu[1] - ln_mu[0]) < 1e-3
    feats = surrogate.features(**_lambda_line(surrogate, [1.0]), warn=False)
    p = surrogate.coefficients.params
    jump = branch_ln_mu(surrogate.formula.terms["full_film"], p["full_film"], feats) - branch_ln_mu(
        surrogate.formula.terms["mixed"], p["mixed"], feats)
    assert abs(jump[0]) > 10 * abs(ln_mu[1] - ln_mu[0])  # the two fitted branches do not meet by themselves


def test_outside_the_band_each_branch_is_used_unblended(surrogate):
    args = _lambda_line(surrogate, [0.5, 0.89, 1.11, 3.0])
    feats = surrogate.features(**args, warn=False)
    p = surrogate.coefficients.params
    ln_mu = surrogate.ln_mu(**args, warn=False)
    mixed = branch_ln_mu(surrogate.formula.terms["mixed"], p["mixed"], feats)
    full = branch_ln_mu(surrogate.formula.terms["full_film"], p["full_film"], feats)
    np.testing.assert_allclose(ln_mu[:2], mixed[:2], rtol=1e-12)
    np.testing.assert_allclose(ln_mu[2:], full[2:], rtol=1e-12)


def test_factorial_corners_are_finite(surrogate):
    """Hard cases: every corner of the paper's factorial (0.5/2.5 GPa, 5/80 mm, 1/20 m/s, SR 0/1,
    25/100 °C, Rq 0.05/1.0 µm) evaluates to a finite μ in (0, 1) without warnings (all inside the fitted ranges)."""
    import itertools

    corners = np.array(list(itertools.product([0.5e9, 2.5e9], [0.005, 0.08], [1.0, 20.0], [0.0, 1.0],
                                              [298.15, 373.15], [0.05e-6, 1.0e-6], [0.05e-6, 1.0e-6])))
    with warnings.catch_warnings():
        warnings.simplefilter("error", SurrogateExtrapolationWarning)
        mu = surrogate.mu(*corners.T)
    assert np.all(np.isfinite(mu)) and np.all((mu > 0) & (mu < 1))


def test_clipping_policy_holds_inputs_at_the_fitted_boundary(surrogate):
    """With clip_to_fitted_ranges, an input beyond the fitted range gives exactly μ at the range's end (Eq. 9 is not
    extrapolated), the warning says so, and inside the ranges the two policies agree to the last digit."""
    clipped = FrictionSurrogate(surrogate.coefficients, clip_to_fitted_ranges=True)
    lo, hi = surrogate.coefficients.input_ranges["p_h_pa"]
    with pytest.warns(SurrogateExtrapolationWarning, match="clipped to"):
        beyond = _call(clipped, p_h=np.array([0.1 * lo, 10 * hi]))
    at_ends = _call(surrogate, p_h=np.array([lo, hi]))
    np.testing.assert_allclose(beyond, at_ends, rtol=1e-13)
    np.testing.assert_array_equal(_call(clipped), _call(surrogate))


def test_gear_friction_factory_clips_surrogates(surrogate):
    from efficiency.friction import friction_from_spec

    model = friction_from_spec(str(surrogate.coefficients.path))
    assert model.clip_to_fitted_ranges


def test_clipped_inputs_are_counted_per_input_and_evaluation(surrogate):
    """last_stats() of a clipping surrogate: per input, how many points of the last evaluation were moved to the
    fitted range (|SR| below the fitted minimum counts: it is evaluated at the SR floor); a second call replaces
    the counts. A surrogate that does not clip counts only the points."""
    clipped = FrictionSurrogate(surrogate.coefficients, clip_to_fitted_ranges=True)
    assert clipped.last_stats() == {}
    lo, hi = surrogate.coefficients.input_ranges["p_h_pa"]
    with pytest.warns(SurrogateExtrapolationWarning):
        _call(clipped, p_h=np.array([0.1 * lo, 0.5 * (lo + hi), 10 * hi, 20 * hi]))
    stats = clipped.last_stats()
    assert stats["surrogate_points"] == 4
    assert stats["clipped_inputs"] == {"p_h": 3, "r_eq": 0, "u_r": 0, "sr": 0, "temperature": 0, "rq1": 0, "rq2": 0}
    _call(clipped, p_h=np.array([lo, hi]))
    assert clipped.last_stats()["clipped_inputs"]["p_h"] == 0
    _call(surrogate, p_h=np.array([lo, hi]))
    assert surrogate.last_stats() == {"surrogate_points": 2}
