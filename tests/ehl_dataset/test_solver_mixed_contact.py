"""Asperity contact in the transient mixed solver: the complementarity conditions (cavitation, plastic pressure cap,
closed-film dry contact), the cap's inactivity below the hardness, and a property test on random factorial cases."""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, Phase, given, settings
from hypothesis import strategies as st

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers.newton import _fb
import ehl_dataset.solvers.transient as transient

LUB = load_lubricant("atf")


def test_fischer_burmeister_zero_set_and_no_cancellation():
    """φ(a, b) = 0 ⇔ a ≥ 0, b ≥ 0, ab = 0 (Fischer 1992); with a huge b the value must still be a (the limit
    φ → a as b → ∞), not the 0 that a + b − √(a² + b²) gives in floating point. Smoothed: φ_s = 0 ⇔ ab = s²."""
    a = np.array([0.0, 2.0, 0.0, -1.0, 1.0, -1.37])
    b = np.array([3.0, 0.0, 0.0, 0.0, -1.0, 1.6e20])
    phi = _fb(a, b)[0]
    assert phi[:3] == pytest.approx([0.0, 0.0, 0.0], abs=1e-15)
    assert phi[3] == pytest.approx(-2.0)  # a + b − |a| with b = 0, a < 0
    assert phi[4] == pytest.approx(-math.sqrt(2.0))
    assert phi[5] == pytest.approx(-1.37, rel=1e-12)
    s = 1e-3
    assert _fb(np.array([0.5]), np.array([s * s / 0.5]), s)[0][0] == pytest.approx(0.0, abs=1e-15)


def test_yield_cap_is_the_hardness_of_case_hardened_steel():
    """P_Y = 6.8 GPa: 60 HRC ≈ 697 HV (ASTM E140) × 9.807 MPa per HV unit = 6.84 GPa."""
    assert transient.YIELD_PRESSURE_PA == pytest.approx(697 * 9.807e6, rel=0.01)


def test_plastic_cap_is_inactive_below_the_hardness():
    """A rough case whose pressures stay below P_Y (p_h 1 GPa, λ̄ ≈ 2.4, p_max ≈ 1.3 p_h) gives the same result with
    the cap at the hardness and with no cap (P_Y → ∞): the box complementarity reduces to the cavitation one when
    P < P_Y. Equal to the Newton tolerance of the fast level (1e−5): asserted μ to 1e−4 relative."""
    case = ContactCase.from_engineering(1.0, 20, 10, 0.5, 50, 0.1, 0.1)
    capped = solve_contact(case, LUB, "fast", Effects.full())
    free = solve_contact(case, LUB, "fast", Effects.full(),
                         transient_options=transient.TransientOptions(yield_pressure_pa=1e30))
    assert capped.converged and free.converged
    assert capped.p_max < transient.YIELD_PRESSURE_PA
    assert capped.mu == pytest.approx(free.mu, rel=1e-4)
    assert capped.p_max == pytest.approx(free.p_max, rel=1e-4)
    assert capped.extra["yielded_load_share"] == 0.0
    assert capped.extra["yield_pressure_pa"] == pytest.approx(6.8e9)
    assert "plastic_cap" in capped.effects["reasons"]


@pytest.mark.slow
@settings(max_examples=4, deadline=None, derandomize=True, phases=[Phase.explicit, Phase.generate],
          suppress_health_check=[HealthCheck.too_slow])
@given(p_h=st.sampled_from([0.5, 1.5, 2.5]), r_eq=st.sampled_from([5, 20]), u_r=st.sampled_from([1, 5, 20]),
       sr=st.sampled_from([0.0, 0.2, 1.0]), temp=st.sampled_from([25, 100]), rq=st.sampled_from([0.05, 0.3, 1.0]))
def test_random_factorial_cases_are_converged_and_bounded_or_marked(p_h, r_eq, u_r, sr, temp, rq):
    """Issue 3 acceptance (property): a random case inside the paper's ranges (r_eq ≤ 20 mm to bound the test
    time) either converges with a finite μ in [0, μ_d] for SR > 0 (|μ| ≤ 0.01 in pure rolling, where μ is the
    Poiseuille part only and can be slightly negative), the load balanced to 1e−3 at every step and p ≥ 0, or is
    returned as not converged with a message; never a silent number."""
    case = ContactCase.from_engineering(p_h, r_eq, u_r, sr, temp, rq, rq)
    res = solve_contact(case, LUB, "fast", Effects.full())
    if res.converged:
        assert math.isfinite(res.mu) and math.isfinite(res.p_max)
        if sr > 0:
            assert 0.0 <= res.mu <= LUB.mu_d
        else:
            assert abs(res.mu) <= 0.01
        assert res.extra["max_load_error"] < 1e-3
        assert np.min(res.pressure) >= -1e-6 * case.p_h
        assert 0.0 <= res.asperity_load_share <= 1.0
    else:
        assert res.message.startswith("not converged") and res.residuals


@pytest.mark.slow
def test_mu_rises_steeply_when_lambda_falls_below_one():
    """Issue 3 limit (paper Fig. 2 shape: μ nearly flat for λ̄ > 1, steep for λ̄ ≤ 1): at fixed load, speed and
    sliding (1 GPa, 20 mm, 5 m/s, SR 0.5, 75 °C), rougher surfaces Rq 0.05 → 0.2 µm take λ̄ from 3.3 to 0.84.
    Measured: μ 0.0295 → 0.0479, asperity share 0 → 0.26. Asserted: μ rises by more than 30 % above the
    smooth-surface value (which Rq does not change; at λ̄ = 3.3 the rough run equals it to 0.14 %), a share of at
    least 10 % appears, and μ stays below μ_d. With the second version's flux-through closure μ rose from 0.030 to 0.052 but then fell
    again to 0.031 at λ̄ 0.17 (film inflation, docs/ehl_solver.md)."""
    results = [solve_contact(ContactCase.from_engineering(1.0, 20, 5, 0.5, 75, rq, rq), LUB, "fast", Effects.full())
               for rq in (0.05, 0.2)]
    assert all(r.converged for r in results), [r.message for r in results]
    assert results[0].lambda_bar > 3.0 and results[1].lambda_bar < 1.0
    assert results[1].mu > 1.3 * results[0].mu
    assert results[1].mu <= LUB.mu_d
    assert results[0].asperity_load_share < 0.01 and results[1].asperity_load_share > 0.1


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="1-D model: lubricant trapped in the roughness valleys keeps carrying load as "
                   "the entrained film vanishes; at 1 GPa / 5 mm / SR 0.5 / 100 C / Rq 0.5 um, u_r 1 -> 0.05 m/s "
                   "(lambda 0.045 -> 0.006) measured mu 0.067 -> 0.068, share 0.63 -> 0.66; see docs/ehl_solver.md")
def test_mu_approaches_mu_d_as_lambda_goes_to_zero():
    """Issue 3 limit: as λ̄ → 0, μ → μ_d and the asperity share → 1. λ̄ → 0 by slowing the surfaces at fixed
    roughness (1 GPa, 5 mm, SR 0.5, 100 °C, Rq 0.5 µm, u_r = 0.05 m/s, λ̄ = 0.006): asserted share ≥ 0.9 and
    μ ≥ 0.9 μ_d."""
    res = solve_contact(ContactCase.from_engineering(1.0, 5, 0.05, 0.5, 100, 0.5, 0.5), LUB, "fast", Effects.full())
    assert res.converged, res.message
    assert res.lambda_bar < 0.01
    assert res.asperity_load_share >= 0.9
    assert res.mu >= 0.9 * LUB.mu_d
