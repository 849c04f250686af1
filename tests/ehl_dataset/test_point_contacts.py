"""Point-like rough contacts (Hertz half width of the order of the roughness correlation length β): the planner's
routing to the asperity-load closure, the film law's rolling term on a film without steps, and the factorial box
left unchanged. The reference numbers are the deterministic model's (validation/narrow_point_contacts.py,
validation/results/narrow_point_contacts.json)."""

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.roughness import baseline_profile, default_profile
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers.film_law_model import continuous_outside_film, solve_film_law
from ehl_dataset.solvers.homogenised import HomogenisedOptions
from ehl_dataset.solvers.levels import POINT_CONTACT_A_OVER_BETA, REGISTRY
from ehl_dataset.solvers.planner import plan_effects, planned_closure
from ehl_dataset.solvers.problem import resolve_contact

ROOT = Path(__file__).resolve().parents[2]

# design D of the paper's study at 10 m/s, 90 °C, Rq 0.4/0.4 µm: the contact point near the end of a contact line
# where the film law gave μ = −0.00697 (film-law-2026.11-3)
END_OF_LINE = ContactCase(36856271.7, 0.0124162, 9.987, 0.054, 363.15, 4e-7, 4e-7)


def test_the_film_step_at_the_zone_edges_is_what_made_mu_negative():
    """The rolling term (h/2)∂p/∂x integrates to −∫(p/2)∂h/∂x: with the film law's h̄ inside the zone and the smooth
    h_s outside, the film steps by Δ = h̄ − h_s at x = ±0.9a and adds (Δ_in p̄(−0.9a) − Δ_out p̄(0.9a))/2 per unit
    length. On the contact-line end (a/β 0.54, h̄ = 7.2 h_s, p̄(−0.9a) = 24.5 MPa against 5.7 MPa at +0.9a) the film
    law with the steps and the inlet spread is μ −0.00697 (the value that stopped the gear evaluation); the film continuous at the edges
    changes μ by exactly that term (to the trapezoid rule's 0.1 %) and makes it positive."""
    problem = resolve_contact(END_OF_LINE, "atf", "standard", "isothermal", roughness=baseline_profile())
    args = (problem.case, problem.state, problem.steady_level, problem.plan, baseline_profile(),
            problem.homogenised.boundary_film_m)
    steps = solve_film_law(*args, continuous_film=False, fluctuations="inlet")
    joined = solve_film_law(*args, continuous_film=True, fluctuations="inlet")
    smooth = solve_contact(END_OF_LINE, "atf", "standard", "isothermal", model="smooth")
    assert steps.mu == pytest.approx(-0.00697, abs=1e-5)
    assert steps.extra["rolling_film_outside"] == "smooth" and joined.extra["rolling_film_outside"] == "continuous"
    x, film = steps.x, steps.film
    step_in = film[0] - np.interp(x[0], smooth.x, smooth.film)
    step_out = film[-1] - np.interp(x[-1], smooth.x, smooth.film)
    assert step_in > 5 * np.interp(x[0], smooth.x, smooth.film)
    term = (step_in * np.interp(x[0], smooth.x, smooth.pressure)
            - step_out * np.interp(x[-1], smooth.x, smooth.pressure)) / (2 * END_OF_LINE.load_per_length)
    assert joined.mu - steps.mu == pytest.approx(term, rel=0.01)
    assert joined.mu > 0
    # the zone's own terms are the same; only the rolling term outside it changes
    for key in ("mu_couette", "mu_poiseuille"):
        assert joined.extra[key] == steps.extra[key]


def test_the_contact_line_end_is_within_the_reference_uncertainty():
    """The deterministic reference on the contact-line end (validation/narrow_point_contacts.py, det-2026.11-21, the
    whole contact on the paper's domain, averaged over 30 passes, paired roughness layouts): μ = 0.0290 ± 0.0036
    (standard error) at the spacing min(a, β)/16 and 0.0343 ± 0.0037 at /32, asperity share 0.17 and 0.22. Its
    uncertainty u = √(0.0037² + 0.0053²) = 0.0065: the finer run's standard error and the change between the two
    grids. The planner's model (asperity-load closure, film continuous at the zone edges) is within u of the finer
    run; the smooth model (0.0024) and the film law (−0.0070 with the film steps, +0.0072 without) are not."""
    reference, uncertainty = 0.0343, math.hypot(0.0037, 0.0343 - 0.0290)
    routed = solve_contact(END_OF_LINE, "atf", "standard", "isothermal")
    assert routed.converged and routed.extra["closure"] == "asperity"
    assert routed.mu > 0 and abs(routed.mu - reference) <= uncertainty
    assert 0.1 <= routed.asperity_load_share <= 0.4
    smooth = solve_contact(END_OF_LINE, "atf", "standard", "isothermal", model="smooth")
    film_law = solve_contact(END_OF_LINE, "atf", "standard", "isothermal", model="homogenised",
                             homogenised=HomogenisedOptions(closure="film_law"))
    for other in (smooth, film_law):
        assert abs(other.mu - reference) > 3 * uncertainty


def test_continuous_outside_film_joins_the_zone_film():
    """Outside the zone the smooth film is shifted by the zone's excess at the nearer edge: the shifted film equals
    the zone's film at both edge nodes, and a zone film equal to the smooth one leaves it unchanged."""
    x = np.linspace(-2.5, 1.5, 81)
    h_s = 1e-7 * (1.0 + x ** 2)
    zone = np.abs(x) <= 0.9
    zone_film = 3e-7 + 1e-8 * x[zone]
    shifted = continuous_outside_film(x, h_s, zone, zone_film)
    inside = np.flatnonzero(zone)
    assert shifted[inside[0]] == pytest.approx(zone_film[0], rel=1e-14)
    assert shifted[inside[-1]] == pytest.approx(zone_film[-1], rel=1e-14)
    np.testing.assert_allclose(np.diff(shifted[: inside[0] + 1]), np.diff(h_s[: inside[0] + 1]), rtol=1e-12)
    np.testing.assert_array_equal(continuous_outside_film(x, h_s, zone, h_s[zone]), h_s)


def test_the_planner_routes_point_like_contacts_to_the_asperity_closure():
    """a/β 0.54 < 1.8 at ``fast`` and ``standard``: steady homogenised model with the asperity-load closure, recorded
    in the plan's reasons; the reference level keeps the deterministic model; a contact of the factorial's smallest
    a/β (2.95, reference case A's 0.5 GPa and 5 mm) is not point-like; every rough contact the homogenised model
    runs takes the asperity closure. β of the baseline profile, on which these contacts were measured."""
    beta = baseline_profile().correlation_length
    for level in ("fast", "standard"):
        plan = plan_effects(END_OF_LINE, _atf(), level, beta)
        assert plan.roughness and not plan.transient
        assert plan.reasons["closure"] == "asperity" and planned_closure(plan) == "asperity"
        decision = plan.reasons["decisions"]["model"]
        assert "asperity-load closure: point-like contact (a/beta=0.539 < 1.8" in decision
        assert "alpha=107" in decision
        assert REGISTRY[level].planner.a_over_beta_point_contact == POINT_CONTACT_A_OVER_BETA == 1.8
    assert plan_effects(END_OF_LINE, _atf(), "reference", beta).transient
    case_a = ContactCase.from_engineering(0.5, 5, 5, 0.3, 90, 0.3, 0.3)
    plan_a = plan_effects(case_a, _atf(), "standard", beta)
    assert plan_a.reasons["numbers"]["a_over_beta"] == pytest.approx(2.947, abs=1e-3)
    assert "point-like" not in plan_a.reasons["decisions"]["model"] and planned_closure(plan_a) == "asperity"
    baseline = baseline_profile()
    assert resolve_contact(case_a, "atf", "standard", roughness=baseline).homogenised.closure == "asperity"
    assert resolve_contact(END_OF_LINE, "atf", "standard", roughness=baseline).homogenised.closure == "asperity"


def test_no_contact_of_the_paper_factorial_is_point_like():
    """The smallest a/β of data/factorials/paper2009.toml (p_h 0.5 GPa, r_eq 5 mm: a = 4 r_eq p_h/E' = 44.2 µm,
    β = 15.0 µm on the baseline, less on the default flank profile) is 2.95 > 1.8: no (p_h, r_eq, roughness)
    combination is planned as point-like on either profile."""
    axes = tomllib.loads((ROOT / "data" / "factorials" / "paper2009.toml").read_text())["axes"]
    beta = baseline_profile().correlation_length
    smallest = ContactCase.from_engineering(min(axes["p_h_gpa"]), min(axes["r_eq_mm"]), 1.0, 0.0, 25.0)
    assert smallest.half_width / beta == pytest.approx(2.947, abs=1e-3)
    assert smallest.half_width / beta > POINT_CONTACT_A_OVER_BETA
    for p_h in axes["p_h_gpa"]:
        for r_eq in axes["r_eq_mm"]:
            for rq1, rq2 in axes["roughness_um"]:
                case = ContactCase.from_engineering(p_h, r_eq, min(axes["u_r_m_s"]), 0.2, 100.0, rq1, rq2)
                for profile_beta in (beta, default_profile().correlation_length):
                    plan = plan_effects(case, _atf(), "standard", profile_beta)
                    assert "point-like" not in plan.reasons["decisions"]["model"]


def _atf():
    from ehl_dataset.model.lubricant import load_lubricant

    return load_lubricant("atf")


@pytest.mark.slow
def test_design_d_evaluates_with_the_ehl_solver_at_its_point_like_contacts():
    """``gearloss gear evaluate`` of the paper's design D with ``--friction ehl:fast:isothermal`` (default mesh, 30
    slices) stopped at a contact-line end: μ −0.0070 from the film law at p_h 37 MPa, a/β 0.54 (film-law-2026.11-3).
    The evaluation now completes with μ > 0 at every loaded point, that contact among them (about 600 solves, 23 s
    CPU; a 5- or 10-slice mesh has no contact narrower than a/β 1.36, where the film law's μ stayed positive)."""
    import warnings

    from efficiency.design_io import load_study
    from efficiency.friction import friction_from_spec
    from efficiency.mesh_cycle import MeshOptions
    from efficiency.studies import StudyPoint, evaluate_design

    study = load_study("paper2009")
    point = StudyPoint.from_operating_point(study.operating_point)
    friction = friction_from_spec("ehl:fast:isothermal")
    beta = baseline_profile().correlation_length
    seen = []

    def recording(*args):
        mu = friction(*args)
        arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in args), mu)
        for row in zip(*(a.ravel() for a in arrays)):
            if row[0] > 0:
                seen.append((ContactCase(*row[:7]).half_width / beta, row[7]))
        return mu

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        row = evaluate_design(study.design("D"), recording, point, MeshOptions())
    assert row["error"] == "" and row["converged"]
    assert math.isfinite(row["power_loss_w"]) and row["power_loss_w"] > 0
    a_over_beta, mu = np.array(seen).T
    assert a_over_beta.min() < 0.6
    assert np.all(mu > 0)
