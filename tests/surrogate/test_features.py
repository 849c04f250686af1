"""Dimensionless features of the paper's regression (Li & Kahraman 2009, Sect. 2.1)."""

import math

import numpy as np
import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.film_formulas import dowson_higginson_min_film
from surrogate.features import at_lambda_one, compute_features


def _case_features(case, atf, e_reduced):
    return compute_features(case.p_h, case.r_eq, case.u_r, case.sr, case.temperature, case.rq1, case.rq2, atf,
                            e_reduced)


def test_features_match_their_definitions(atf, e_reduced):
    """Each feature against its formula evaluated independently through ContactCase and Lubricant.state."""
    case = ContactCase(1.2e9, 0.02, 7.0, -0.3, 353.15, 0.3e-6, 0.5e-6)
    f = _case_features(case, atf, e_reduced)
    state = atf.state(case.temperature)
    w = case.load_per_length
    h_min = dowson_higginson_min_film(state.eta0, case.u_r, state.alpha1, e_reduced, case.r_eq, w)
    assert f["W"] == pytest.approx(-math.log10(case.p_h / e_reduced), rel=1e-12)
    assert f["alpha"] == pytest.approx(math.log10(state.alpha1 * e_reduced), rel=1e-12)
    assert f["r"] == pytest.approx(math.log10(case.r_eq * e_reduced / w), rel=1e-12)
    assert f["V"] == pytest.approx(-math.log10(case.u_r * state.eta0 / w), rel=1e-12)
    assert f["lam"] == pytest.approx(h_min / case.s_c, rel=1e-12)
    assert f["SR"] == pytest.approx(0.3)
    assert f["Sc"] == pytest.approx(case.s_c * e_reduced / w, rel=1e-12)
    assert f["Seq"] == pytest.approx(case.s_eq * e_reduced / w, rel=1e-12)


def test_r_bar_is_a_function_of_p_h_alone(atf, e_reduced):
    """Under Hertz loading W' = 2π r p²/E', so r̄ = log10(E'²/(2π p_h²)) = 2 W̄ − log10(2π) for every r_eq."""
    p = np.array([0.5e9, 1.3e9, 2.5e9])[:, None]
    r = np.array([0.005, 0.02, 0.08])[None, :]
    f = compute_features(p, r, 5.0, 0.2, 343.15, 0.2e-6, 0.2e-6, atf, e_reduced)
    np.testing.assert_allclose(f["r"], 2 * f["W"] - math.log10(2 * math.pi), rtol=1e-12)


def test_moving_to_lambda_one_scales_the_roughness(atf, e_reduced):
    """Scaling both Rq by λ̄ gives λ̄ = 1 (λ̄ ∝ 1/S_c): at_lambda_one must equal recomputing with scaled roughness."""
    case = ContactCase(0.9e9, 0.01, 3.0, 0.4, 323.15, 0.2e-6, 0.5e-6)
    f = _case_features(case, atf, e_reduced)
    k = float(f["lam"])
    g = compute_features(case.p_h, case.r_eq, case.u_r, case.sr, case.temperature, k * case.rq1, k * case.rq2, atf,
                         e_reduced)
    moved = at_lambda_one(f)
    assert g["lam"] == pytest.approx(1.0, rel=1e-12)
    for key in ("Sc", "Seq", "W", "V"):
        assert moved[key] == pytest.approx(g[key], rel=1e-12)
