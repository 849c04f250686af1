"""Published friction formulas: units pinned by hand-evaluated values in the published units."""

import math

import numpy as np
import pytest

from ehl_dataset.validation import InputError
from surrogate.published import (BK_CONSTANT_IMPERIAL, BK_CONSTANT_SI, RA_PER_RQ, XU_2007_COEFFICIENTS,
                                 benedict_kelley_mu, iso_14179_2_mu, xu_2007_mu)


def test_xu_2007_in_published_units():
    """Xu et al. 2007 (J. Mech. Des. 129, 58), units P_h GPa, V_e m/s, ν0 mPa·s, R m, S µm: hand evaluation at
    P_h = 1 GPa, SR = 0.2, V_e = 5 m/s, ν0 = 10 mPa·s, R = 20 mm, S = 0.4 µm:
    f = b1 + 0.2 b4 + b5 e^-0.2 + b9 e^0.4 = −5.7596, μ = e^f · 0.2^b3 · 5^b6 · 10^b7 · 0.02^b8 = 0.01324."""
    b1, b2, b3, b4, b5, b6, b7, b8, b9 = XU_2007_COEFFICIENTS
    f = b1 + b4 * 0.2 + b5 * math.exp(-0.2) + b9 * math.exp(0.4)
    assert f == pytest.approx(-5.7596, abs=1e-4)
    by_hand = math.exp(f) * 0.2**b3 * 5**b6 * 10**b7 * 0.02**b8
    assert by_hand == pytest.approx(0.01322, rel=1e-3)
    mu = xu_2007_mu(p_h=1e9, r_eq=0.02, u_r=5.0, sr=0.2, eta0=0.010, rq1=0.4e-6, rq2=0.4e-6)
    assert mu == pytest.approx(by_hand, rel=1e-12)


def test_xu_2007_other_unit_readings_give_unphysical_mu():
    """Pins the units: reading P_h in MPa or ν0 in Pa·s makes μ leave any physical range (0.005–0.15)."""
    b = XU_2007_COEFFICIENTS
    assert 1000**b[1] * 0.01322 > 10  # P_h in MPa
    f_pas = b[0] + b[3] * 0.2 * math.log10(0.01) + b[4] * math.exp(-0.2 * math.log10(0.01)) + b[8] * math.exp(0.4)
    mu_pas = math.exp(f_pas) * 0.2 ** b[2] * 5 ** b[5] * 0.01 ** b[6] * 0.02 ** b[7]
    assert not 0.005 < mu_pas < 0.15


def test_benedict_kelley_si_constant_is_the_imperial_one_converted():
    """3.17e8 for W [lb/in], η [cP], V [in/s] ⇔ 29.66 for W' [N/m], η [cP], V [m/s] (1 lbf/in = 175.127 N/m)."""
    assert BK_CONSTANT_SI == pytest.approx(29.66, rel=1e-3)
    # same physical case evaluated in imperial units by hand
    w, eta, u_r, sr, rq = 3.0e5, 0.010, 10.0, 0.3, 0.3e-6
    w_lb_in = w / 175.126835
    vs_in, vt_in = sr * u_r / 0.0254, 2 * u_r / 0.0254
    s_uin = rq * RA_PER_RQ * 1e6 / 0.0254
    imperial = 0.0127 * 50 / (50 - s_uin) * math.log10(BK_CONSTANT_IMPERIAL * w_lb_in / (eta * 1e3 * vs_in * vt_in**2))
    assert benedict_kelley_mu(w, u_r, sr, eta, rq, rq) == pytest.approx(imperial, rel=1e-12)
    assert 0.02 < imperial < 0.1  # a typical gear friction level


def test_benedict_kelley_is_capped_at_the_pitch_point_and_limited_in_roughness():
    sr = np.array([0.0, 1e-6, 1e-3, 0.3])
    mu = benedict_kelley_mu(3e5, 10.0, sr, 0.010, 0.3e-6, 0.3e-6, mu_cap=0.1)
    assert np.all(np.isfinite(mu)) and mu[0] == 0.1 and np.all(mu <= 0.1)
    assert mu[3] < mu[2]  # decreasing with sliding speed away from the cap
    with pytest.raises(InputError, match="roughness"):
        benedict_kelley_mu(3e5, 10.0, 0.3, 0.010, 1.7e-6, 1.7e-6)  # Ra ≈ 1.36 µm > 50 µin


def test_iso_14179_2_in_published_units():
    """ISO/TR 14179-2 μ_mz = 0.048 (F/b/(v_Σ ρ))^0.2 η^−0.05 Ra^0.25 X_L with F/b N/mm, v m/s, ρ mm, η mPa·s,
    Ra µm: at 300 N/mm, v_Σ = 10 m/s, ρ = 10 mm, η = 20 mPa·s, Ra = 0.5 µm: 0.048·3^0.2·20^−0.05·0.5^0.25 = 0.04328."""
    by_hand = 0.048 * 3**0.2 * 20**-0.05 * 0.5**0.25
    assert by_hand == pytest.approx(0.04328, rel=1e-3)
    rq = 0.5e-6 / RA_PER_RQ
    mu = iso_14179_2_mu(w_prime=3.0e5, r_eq=0.010, u_r=5.0, eta0=0.020, rq1=rq, rq2=rq)
    assert mu == pytest.approx(by_hand, rel=1e-12)


def test_published_mu_uses_the_lubricant_viscosity_and_accepts_short_names(atf, e_reduced):
    """published_mu maps the surrogate inputs: η0 = η(T) of the lubricant, W' = 2π r p²/E' (Hertz)."""
    from surrogate.published import published_mu

    p, r, u, sr, t, rq = 1.1e9, 0.015, 6.0, 0.25, 353.15, 0.3e-6
    eta0 = float(atf.dynamic_viscosity(t))
    w = 2 * math.pi * r * p**2 / e_reduced
    assert published_mu("xu2007", p, r, u, sr, t, rq, rq, atf, e_reduced) == pytest.approx(
        xu_2007_mu(p, r, u, sr, eta0, rq, rq), rel=1e-12)
    assert published_mu("benedict_kelley", p, r, u, sr, t, rq, rq, atf, e_reduced) == pytest.approx(
        benedict_kelley_mu(w, u, sr, eta0, rq, rq, mu_cap=atf.mu_d), rel=1e-12)
    assert published_mu("iso_tr_14179_2", p, r, u, sr, t, rq, rq, atf, e_reduced) == pytest.approx(
        iso_14179_2_mu(w, r, u, eta0, rq, rq), rel=1e-12)
    with pytest.raises(InputError, match="model"):
        published_mu("unknown", p, r, u, sr, t, rq, rq, atf, e_reduced)
