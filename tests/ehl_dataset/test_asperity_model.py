"""The asperity-load closure of the homogenised model (ehl_dataset.solvers.asperity_model): limits, load balance,
monotonicity, and the committed calibration (validation/asperity_model_loo.py)."""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.dry_contact import PAPER_RQ_PAIRS_UM, dry_contact_table
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile, named_profile
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers import asperity_model as am
from ehl_dataset.solvers.homogenised import BOUNDARY_FILM_M, HomogenisedOptions

ROOT = Path(__file__).resolve().parents[2]
LOO = ROOT / "validation" / "results" / "asperity_model_loo.json"
REFERENCE = ROOT / "data" / "reference" / "deterministic_validation.json"


@pytest.fixture(scope="module")
def lub():
    return load_lubricant("atf")


def film_law(case, lub):
    return solve_contact(case, lub, "fast", "isothermal", model="homogenised",
                         homogenised=HomogenisedOptions(closure="film_law"))


def asperity(case, lub):
    return solve_contact(case, lub, "fast", "isothermal", model="homogenised",
                         homogenised=HomogenisedOptions(closure="asperity"))


def test_amplitude_factor_is_the_published_fit():
    """F(∇) = 1/(1 + 0.15∇ + 0.015∇²) (Venner, Couhier, Lubrecht & Greenwood 1997): F(0) = 1, F(10) = 1/4."""
    assert am.amplitude_factor(0.0) == 1.0
    assert am.amplitude_factor(10.0) == pytest.approx(0.25, rel=1e-12)


def test_surviving_roughness_comes_from_the_profile_spectrum(lub):
    """Shorter wavelengths survive a conjunction (F falls with λ): the flank-like profile (self-affine down to 2.5 µm)
    keeps more of its roughness than the Gaussian-ACF baseline (β 15 µm) at the same contact; a stationary rough
    surface (u_i = 0, F = 0: its complementary wavelength λ·u_m/u_i is infinite) keeps only 1 − φ, nothing without
    the flattening limit (c_p = 1000), which also flattens more of a moving surface."""
    case = ContactCase.from_engineering(1.0, 5, 2, 0.5, 100, 0.5, 0.5)
    state = lub.state(case.temperature)
    base = am.surviving_fractions(baseline_profile(), case, state)
    flank = am.surviving_fractions(named_profile("flank_ground"), case, state)
    assert 0.0 < base[0] < flank[0] <= 1.0 and 0.0 < base[1] < flank[1] <= 1.0
    # surface 1 is the faster one (SR > 0): shorter film waves, more survives
    assert base[0] > base[1]
    unlimited = am.surviving_fractions(baseline_profile(), case, state, pressure_scale=1e3)
    assert unlimited[2] == 1.0 and unlimited[0] <= base[0]
    sliding = ContactCase.from_engineering(1.0, 5, 2, 2.0, 100, 0.5, 0.5)  # u2 = 0: F = 0, only φ limits
    _, r2, phi = am.surviving_fractions(baseline_profile(), sliding, state)
    assert r2 == pytest.approx(1.0 - phi, rel=1e-12)
    assert am.surviving_fractions(baseline_profile(), sliding, state, pressure_scale=1e3)[1] == 0.0


def test_smooth_surfaces_give_the_smooth_solve(lub):
    """S_c = 0: nothing to carry load, the steady smooth solution."""
    case = ContactCase.from_engineering(1.0, 5, 5, 0.3, 90, 0.0, 0.0)
    res = asperity(case, lub)
    smooth = solve_contact(case, lub, "fast", "smooth")
    assert res.asperity_load_share == 0.0
    assert res.mu == pytest.approx(smooth.mu, rel=1e-12)


def test_thick_film_gives_no_share_and_the_film_law(lub):
    """λ̄ ≈ 3.7 (reference case F: 1 GPa, 5 mm, 20 m/s, SR 0.7, 100 °C, Rq 0.05 µm): share < 1e-6 and the film-law μ
    within 1e-6."""
    case = ContactCase.from_engineering(1.0, 5, 20, 0.7, 100, 0.05, 0.05)
    res, fl = asperity(case, lub), film_law(case, lub)
    assert res.converged
    assert res.asperity_load_share < 1e-6
    assert res.mu == pytest.approx(fl.mu, rel=1e-6)
    # with the thermal correction of the traction (the planner's plan) likewise
    options = {"model": "homogenised"}
    thermal = solve_contact(case, lub, "fast", "auto", homogenised=HomogenisedOptions(closure="asperity"), **options)
    thermal_fl = solve_contact(case, lub, "fast", "auto", homogenised=HomogenisedOptions(closure="film_law"), **options)
    assert "thermal" in thermal.extra
    assert thermal.mu == pytest.approx(thermal_fl.mu, rel=1e-6)


def test_load_balance_and_share_rise_with_roughness(lub):
    """The share solves s = ∫min(p_a,s(h(x; s)), p̄) dx / w with h the film law's film times Moes' ratio at the fluid
    load (recomputed here from the table and film law), and grows with Rq at fixed load and speed (0.5 GPa, 5 mm,
    2 m/s, SR 0.7, 25 °C: reference case C's conditions)."""
    shares = []
    for rq in (0.5, 0.7, 1.0):
        case = ContactCase.from_engineering(0.5, 5, 2, 0.7, 25, rq, rq)
        state = lub.state(case.temperature)
        fl = film_law(case, lub)
        res = am.asperity_closure(fl, case, state, None, BOUNDARY_FILM_M)
        assert res.converged
        rec = res.extra["asperity"]
        table = am.SurvivingTable(dry_contact_table(None, case.rq1, case.rq2, case.e_reduced),
                                  rec["surviving_sigma_m"] / case.s_c)
        s = res.asperity_load_share
        film = fl.film * float(am.fluid_film_ratio(case, state, 1.0 - s))
        p_a = np.minimum(table.asperity_pressure(film), fl.pressure)
        carried = float(np.sum(0.5 * (p_a[1:] + p_a[:-1]) * np.diff(fl.x))) / case.load_per_length
        assert carried == pytest.approx(s, abs=1e-9)
        np.testing.assert_allclose(res.film, film, rtol=1e-12)
        assert res.extra["mu_asperity"] == pytest.approx(state.mu_d * s, rel=1e-9)
        shares.append(s)
    assert 0.0 < shares[0] < shares[1] < shares[2]


def test_vanishing_film_gives_boundary_friction(lub):
    """Film → 0 (the film law's film times 1e-4 and 1e-8 before the balance, case C's conditions): the asperities
    carry all the load inside the film-law zone (the limit of s is ∫_zone p̄ dx/w), their friction is μ_d·s, and
    the fluid shear of the open fraction is small: μ − μ_d·s − μ_outside within 0.1 μ_d (μ_d = 0.10), and the
    two films agree within 1e-4 on μ."""
    case = ContactCase.from_engineering(0.5, 5, 2, 0.7, 25, 1.0, 1.0)
    state = lub.state(case.temperature)
    fl = film_law(case, lub)
    zone = float(np.sum(0.5 * (fl.pressure[1:] + fl.pressure[:-1]) * np.diff(fl.x))) / case.load_per_length
    results = [am.asperity_closure(replace(fl, film=fl.film * f), case, state, None, BOUNDARY_FILM_M)
               for f in (1e-4, 1e-8)]
    for res in results:
        assert res.asperity_load_share == pytest.approx(zone, rel=1e-6)
        assert res.extra["mu_asperity"] == pytest.approx(state.mu_d * zone, rel=1e-9)
        assert abs(res.mu - res.extra["mu_asperity"] - res.extra["mu_outside_zone"]) < 0.1 * state.mu_d
    assert results[0].mu == pytest.approx(results[1].mu, rel=1e-4)


def test_fluid_film_ratio_is_one_at_full_load_and_grows(lub):
    """Moes' central film falls with load: the ratio is 1 at f = 1 and above 1 below it."""
    case = ContactCase.from_engineering(1.0, 5, 2, 0.5, 100, 0.5, 0.5)
    state = lub.state(case.temperature)
    ratio = am.fluid_film_ratio(case, state, np.array([1.0, 0.7, 0.3]))
    assert ratio[0] == pytest.approx(1.0, rel=1e-14)
    assert 1.0 < ratio[1] < ratio[2]


def test_leave_one_out_file_matches_the_reference_and_the_shipped_constants():
    """validation/results/asperity_model_loo.json (python validation/asperity_model_loo.py): the shipped constants are
    its fit on all 12 cases, its reference values are the reference file's, and its leave-one-out errors follow from
    its μ and shares. The acceptance it measures (|Δμ| ≤ 15 %, |Δshare| ≤ 0.10 on the cases with μ uncertainty
    < 5 %, median |Δμ| ≤ 7 %) is read from it, and the median is within 7 %."""
    data = json.loads(LOO.read_text())
    ref = {row["case"]: row for row in json.loads(REFERENCE.read_text())["cases"]}
    assert data["summary"]["nabla_scale"] == am.NABLA_SCALE
    assert data["summary"]["pressure_scale"] == am.PRESSURE_SCALE
    assert data["summary"]["flattening_exponent"] == am.FLATTENING_EXPONENT
    # asperity-2026.11-2 changed only pairs without a table of their own; every case's pair ships one
    assert data["model_version"] in ("asperity-2026.11-1", am.ASPERITY_MODEL_VERSION)
    shipped = {tuple(pair) for pair in PAPER_RQ_PAIRS_UM}
    assert all((row["inputs"]["rq1_um"], row["inputs"]["rq2_um"]) in shipped for row in ref.values())
    assert {r["case"] for r in data["cases"]} == set(ref)
    for r in data["cases"]:
        assert r["mu_reference"] == ref[r["case"]]["mu_extrapolated"]
        assert r["loo_mu_error"] == pytest.approx(r["loo_mu"] / r["mu_reference"] - 1.0, rel=1e-12)
        assert r["loo_share_difference"] == pytest.approx(r["loo_share"] - r["share_reference"], abs=1e-12)
    median = float(np.median(np.abs([r["loo_mu_error"] for r in data["cases"]])))
    assert median == pytest.approx(data["summary"]["loo_mu_error_median_abs"], rel=1e-12)
    assert median <= 0.07


@pytest.mark.slow
def test_any_registered_profile_runs_through_the_closure(lub):
    """The flank-like profile (``flank_ground``: its own spectrum and a dry-contact table of the windows it is long
    enough for, computed on first use, about a minute) at case C's conditions: converged, more of its roughness
    survives than of the baseline's, and a share between the baseline's and 1."""
    from ehl_dataset.model.effects import Effects
    from ehl_dataset.solvers.homogenised import solve_homogenised
    from ehl_dataset.solvers.levels import get_level

    case = ContactCase.from_engineering(0.5, 5, 2, 0.7, 25, 1.0, 1.0)
    state = lub.state(case.temperature)
    plan = Effects.smooth_steady(model="isothermal homogenised")
    base = solve_homogenised(case, state, get_level("fast"), plan, baseline_profile(), closure="asperity")
    flank = solve_homogenised(case, state, get_level("fast"), plan, named_profile("flank_ground"), closure="asperity")
    assert base.converged and flank.converged
    assert flank.extra["asperity"]["surviving_fraction_1"] > base.extra["asperity"]["surviving_fraction_1"]
    assert base.asperity_load_share < flank.asperity_load_share < 1.0


def test_closure_reuses_the_film_laws_spread_and_isothermal_traction_only_where_they_are_the_same(lub):
    """The closure takes σ_p and the isothermal zone traction from its film-law result when they were formed the same
    way on the same profile: with those records removed (so both are recomputed) the closure gives the same μ and
    share to rounding, on a thermal contact where asperities carry load; asked for another spread form it does not
    take the film law's σ_p."""
    case = ContactCase.from_engineering(0.8, 5.0, 3.0, 1.0, 90.0, 0.5, 0.5)
    state = lub.state(case.temperature)
    fl = solve_contact(case, lub, "fast", "auto", model="homogenised",
                       homogenised=HomogenisedOptions(closure="film_law"))
    assert "thermal" in fl.extra and fl.extra["micro_pressure"]["form"] == "spectral"
    reused = am.asperity_closure(fl, case, state, None, BOUNDARY_FILM_M)
    assert reused.asperity_load_share > 0.1
    bare = replace(fl, extra={k: v for k, v in fl.extra.items() if k != "profile_sha256"})
    recomputed = am.asperity_closure(bare, case, state, None, BOUNDARY_FILM_M)
    assert reused.mu == pytest.approx(recomputed.mu, rel=1e-13)
    assert reused.asperity_load_share == pytest.approx(recomputed.asperity_load_share, rel=1e-13)
    other = am.asperity_closure(fl, case, state, None, BOUNDARY_FILM_M, fluctuations="inlet")
    assert other.mu != pytest.approx(reused.mu, rel=1e-6)
