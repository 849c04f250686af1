"""The effect planner: decisions on clear-cut cases, the recorded reasons, and planned-versus-full agreement."""

import json
import math

import pytest

from ehl_dataset.contact import ContactCase
from ehl_dataset.effects import Effects
from ehl_dataset.film_formulas import dowson_higginson_min_film
from ehl_dataset.lubricant import load_lubricant
from ehl_dataset.planner import THRESHOLDS, dimensionless_numbers, plan_effects, resolve_effects
from ehl_dataset.validation import InputError

ATF = load_lubricant("atf")


def case(p_h_gpa=1.0, r_eq_mm=20.0, u_r=5.0, sr=0.2, temp_c=90.0, rq1_um=0.4, rq2_um=0.4):
    return ContactCase.from_engineering(p_h_gpa, r_eq_mm, u_r, sr, temp_c, rq1_um, rq2_um)


def test_smooth_surfaces_are_solved_steady_at_every_level():
    """S_c = 0 → λ̄ = ∞: no roughness, no transient; exact, so also at the reference level."""
    for level in ("fast", "standard", "reference"):
        plan = plan_effects(case(rq1_um=0, rq2_um=0), ATF, level)
        assert not plan.roughness and not plan.transient
        assert plan.mode == "auto"
        assert plan.reasons["numbers"]["lambda_bar"] == "inf"
        assert "S_c=0" in plan.reasons["decisions"]["roughness"]


def test_hardest_corner_needs_everything():
    """2.5 GPa, 5 mm, 1 m/s, 100 °C, Rq 1 µm, SR 1: λ̄ ≈ 0.02 (heavy asperity contact), Eyring X ≫ 1,
    ρ(2.5 GPa)/ρ0 − 1 = 0.280 (Dowson–Higginson, paper Eq. 6: (1 + 2.266·2.5)/(1 + 1.683·2.5) − 1)."""
    plan = plan_effects(case(2.5, 5, 1, 1.0, 100, 1.0, 1.0), ATF, "fast")
    assert plan.roughness and plan.transient and plan.shear_thinning and plan.compressibility
    nums = plan.reasons["numbers"]
    assert nums["lambda_bar"] < 0.05
    assert nums["eyring_number"] > 1e3
    assert nums["density_change"] == pytest.approx((1 + 2.266 * 2.5) / (1 + 1.683 * 2.5) - 1, rel=1e-12)
    assert nums["p_h_over_p_a"] == pytest.approx(2.5 / 0.4)


def test_thick_film_is_solved_smooth_except_at_reference():
    """0.5 GPa, 80 mm, 20 m/s, 25 °C, Rq 0.05 µm: λ̄ ≈ 60 ≫ 3 → steady smooth; SR = 0 → u_s = 0, X = 0 exactly →
    Newtonian flow at every level; the reference level keeps roughness (it skips only what is exactly absent)."""
    thick = case(0.5, 80, 20, 0.0, 25, 0.05, 0.05)
    plan = plan_effects(thick, ATF, "standard")
    assert plan.reasons["numbers"]["lambda_bar"] > 30
    assert not plan.roughness and not plan.transient
    assert not plan.shear_thinning and plan.reasons["numbers"]["eyring_number"] == 0.0
    assert plan.compressibility
    ref = plan_effects(thick, ATF, "reference")
    assert ref.roughness and ref.transient and not ref.shear_thinning


@pytest.mark.parametrize("level", ["fast", "standard"])
def test_threshold_straddle(level):
    """Roughness is skipped exactly from λ̄ = lambda_smooth on: S_c chosen for λ̄ = 0.98 and 1.02 × threshold."""
    base = case(1.0, 20, 10, 0.3, 50, 0, 0)
    h_dh = dimensionless_numbers(base, ATF)["h_min_dh_m"]
    threshold = THRESHOLDS[level].lambda_smooth
    for factor, rough in ((0.98, True), (1.02, False)):
        rq = h_dh / (factor * threshold) / math.sqrt(2)
        plan = plan_effects(ContactCase(base.p_h, base.r_eq, base.u_r, base.sr, base.temperature, rq, rq), ATF, level)
        assert plan.roughness is rough and plan.transient is rough
        assert plan.reasons["numbers"]["lambda_bar"] == pytest.approx(factor * threshold, rel=1e-9)
        assert plan.reasons["thresholds"]["lambda_smooth"] == threshold


def test_numbers_follow_their_formulas():
    """λ̄ = h_min,DH/S_c with S_c = √(Rq1² + Rq2²) (paper Sect. 2.1); DH: h ∝ u_r^0.70 (Dowson & Higginson 1977),
    so doubling u_r multiplies λ̄ by 2^0.7; X = η(p_h)·u_s/(τ0 h_DH); Moes M = W(2U)^-1/2, L = G(2U)^1/4."""
    c = case(1.5, 10, 4.0, 0.4, 75, 0.2, 0.5)
    nums = dimensionless_numbers(c, ATF)
    state = ATF.state(c.temperature)
    h = dowson_higginson_min_film(state.eta0, c.u_r, state.alpha1, c.e_reduced, c.r_eq, c.load_per_length)
    assert nums["lambda_bar"] == pytest.approx(h / math.sqrt(0.2e-6**2 + 0.5e-6**2), rel=1e-12)
    faster = dimensionless_numbers(case(1.5, 10, 8.0, 0.4, 75, 0.2, 0.5), ATF)
    assert faster["lambda_bar"] / nums["lambda_bar"] == pytest.approx(2**0.7, rel=1e-12)
    assert nums["eyring_number"] == pytest.approx(
        float(state.viscosity(1.5e9)) * 0.4 * 4.0 / (5e6 * h), rel=1e-12)
    assert nums["tau_m_over_tau0"] == pytest.approx(math.asinh(nums["eyring_number"]))
    u = state.eta0 * 4.0 / (c.e_reduced * c.r_eq)
    w = c.load_per_length / (c.e_reduced * c.r_eq)
    assert nums["moes_m"] == pytest.approx(w / math.sqrt(2 * u), rel=1e-12)
    assert nums["moes_l"] == pytest.approx(state.alpha1 * c.e_reduced * (2 * u) ** 0.25, rel=1e-12)


def test_shear_thinning_threshold_and_reason():
    """Small sliding at light load gives X below 0.1 (fast skips shear thinning, standard keeps it when X > 0.05)."""
    c = case(0.5, 40, 10, 0.002, 50, 0.05, 0.05)
    x = dimensionless_numbers(c, ATF)["eyring_number"]
    assert 0.0 < x < THRESHOLDS["fast"].eyring_newtonian
    fast = plan_effects(c, ATF, "fast")
    assert not fast.shear_thinning
    assert "Newtonian" in fast.reasons["decisions"]["shear_thinning"]
    std = plan_effects(c, ATF, "standard")
    assert std.shear_thinning is (x > THRESHOLDS["standard"].eyring_newtonian)


def test_reasons_are_json_and_complete():
    plan = plan_effects(case(), ATF, "standard")
    text = json.dumps(plan.to_dict(), allow_nan=False)
    back = json.loads(text)
    assert back["reasons"]["level"] == "standard"
    for key in ("lambda_bar", "eyring_number", "sr", "density_change", "p_h_over_p_a", "moes_m", "moes_l",
                "h_min_dh_m", "s_c_m"):
        assert key in back["reasons"]["numbers"]
    assert set(back["reasons"]["decisions"]) == {"roughness", "transient", "shear_thinning", "compressibility"}


def test_bad_input():
    with pytest.raises(InputError, match="level"):
        plan_effects(case(), ATF, "ultra")
    with pytest.raises(InputError, match="temperature"):
        plan_effects(ContactCase(1e9, 0.02, 5.0, 0.2, 600.0, 4e-7, 4e-7), ATF, "standard")
    with pytest.raises(InputError, match="effects"):
        resolve_effects("some", case(), ATF)
    assert resolve_effects("full", case(), ATF) == Effects.full()
    assert resolve_effects("auto", case(), ATF).mode == "auto"
