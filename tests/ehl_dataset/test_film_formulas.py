"""Closed-form film formulas: pinned conventions and limits."""

import pytest

from ehl_dataset.model import film_formulas as ff


def _args(u, g, w, e_red=2.26e11, r=0.02):
    """(eta0, u_r, alpha, E', r_eq, w') reproducing the dimensionless groups U, G, W."""
    return (u * e_red * r, 1.0, g / e_red, e_red, r, w * e_red * r)


def test_dimensionless_groups_roundtrip():
    u, g, w = ff.dimensionless_groups(*_args(1e-11, 5000, 1e-4))
    assert (float(u), float(g), float(w)) == pytest.approx((1e-11, 5000, 1e-4))


def test_moes_agrees_with_dowson_toyoda_at_their_common_point():
    """Moes (1992) and Dowson–Toyoda (1979) are independent fits to Newtonian incompressible solutions; at
    U = 1e−11, G = 5000, W = 1e−4 (well inside both ranges) they agree to 2 % (measured 1.9 %). This pins the
    velocity convention of the Moes groups (mean velocity in U, M = W (2U)^−1/2): with U built on the sum velocity
    the two would differ by 60 %."""
    a = _args(1e-11, 5000, 1e-4)
    assert ff.moes_central_film(*a) == pytest.approx(ff.dowson_toyoda_central_film(*a), rel=0.02)


def test_moes_rigid_isoviscous_limit():
    """With G → 0 and light load the Moes formula tends to its rigid–isoviscous asymptote H_RI = 3/M
    (Venner & Lubrecht 2000), i.e. h_c = 6 η0 u_r R/w' (Martin-type solution)."""
    a = _args(1e-8, 1e-3, 1e-7)  # M = 1e-7/√2e-8 ≈ 7e-4, L ≈ 0
    eta0, u_r, _, _, r, w = a
    assert ff.moes_central_film(*a) == pytest.approx(6.0 * eta0 * u_r * r / w, rel=0.02)


def test_formula_values():
    """Direct evaluation of the published power laws at U = 1e−11, G = 5000, W = 1e−4."""
    a = _args(1e-11, 5000, 1e-4)
    r = a[4]
    assert ff.dowson_higginson_min_film(*a) / r == pytest.approx(2.65 * 1e-11**0.70 * 5000**0.54 * 1e-4**-0.13)
    assert ff.pan_hamrock_min_film(*a) / r == pytest.approx(1.714 * 1e-4**-0.128 * 1e-11**0.694 * 5000**0.568)
    assert ff.pan_hamrock_central_film(*a) / r == pytest.approx(2.922 * 1e-4**-0.166 * 1e-11**0.692 * 5000**0.470)
    m, l_ = ff.moes_parameters(*a)
    assert float(m) == pytest.approx(1e-4 / (2e-11) ** 0.5) and float(l_) == pytest.approx(5000 * (2e-11) ** 0.25)
