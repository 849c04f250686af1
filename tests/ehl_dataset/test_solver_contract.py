"""The solve_contact contract that the dataset store, the planner and the gear model rely on."""

import math
from dataclasses import replace

import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers.levels import LEVELS, get_level
from ehl_dataset.solvers.result import RECORD_UNITS, ContactResult
from ehl_dataset.validation import InputError

CASE = ContactCase.from_engineering(1.2, 20, 5, 0.3, 90)


def test_result_fields_and_record():
    """Every ContactResult field is filled; to_record() has exactly the stored columns; plan and level recorded."""
    lub = load_lubricant("atf")
    plan = Effects.smooth_steady(reason="test")
    res = solve_contact(CASE, lub, "fast", plan)
    assert isinstance(res, ContactResult) and res.converged
    record = res.to_record()
    assert set(record) == set(RECORD_UNITS)
    assert record["level"] == "fast" and res.effects == plan.to_dict()
    assert all(math.isfinite(record[k]) for k in ("mu", "h_min", "h_central", "p_max", "wall_time"))
    assert record["lambda_bar"] == math.inf and record["asperity_load_share"] == 0.0 and record["mu_std"] == 0.0
    assert res.h_min <= res.h_central and res.p_max > CASE.p_h * 0.9
    assert res.x.shape == res.pressure.shape == res.film.shape
    assert set(res.residuals) >= {"reynolds", "load"}


def test_lambda_bar_uses_dowson_higginson():
    """λ̄ = h_min,DH / S_c (paper Sect. 2.1) for a rough case, even when the solve itself is smooth."""
    lub = load_lubricant("atf")
    rough = ContactCase.from_engineering(1.2, 20, 5, 0.3, 90, 0.2, 0.2)
    res = solve_contact(rough, lub, "fast", Effects.smooth_steady())
    assert res.lambda_bar == pytest.approx(res.extra["h_min_dowson_higginson_m"] / rough.s_c)


def test_effects_auto_records_a_plan():
    res = solve_contact(CASE, load_lubricant("atf"), "fast", "auto")
    assert res.converged and isinstance(res.effects, dict) and "roughness" in res.effects


def test_levels_are_named_and_ordered():
    """fast < standard < reference in resolution; unknown names are an InputError naming the parameter."""
    assert {"fast", "standard", "reference"} <= set(LEVELS)
    assert LEVELS["fast"].dx_fine > LEVELS["standard"].dx_fine > LEVELS["reference"].dx_fine
    with pytest.raises(InputError, match="level"):
        get_level("ultra")


@pytest.mark.parametrize("kwargs, parameter", [
    (dict(effects="bogus"), "effects"),
    (dict(level="nope"), "level"),
])
def test_bad_arguments(kwargs, parameter):
    with pytest.raises(InputError, match=parameter):
        solve_contact(CASE, load_lubricant("atf"), **kwargs)


def test_temperature_outside_lubricant_data():
    hot = ContactCase.from_engineering(1.2, 20, 5, 0.3, 200)
    with pytest.raises(InputError, match="temperature"):
        solve_contact(hot, load_lubricant("atf"), "fast")


def test_non_convergence_is_reported_not_hidden():
    """With an iteration cap of 1 the solve cannot converge: converged=False, residuals and a message. (A level's
    steady numerics may be changed; a level the registry does not know is refused, not replaced by another.)"""
    level = replace(get_level("fast"), max_iterations=1)
    with pytest.raises(InputError, match="invalid level='capped'"):
        solve_contact(CASE, load_lubricant("atf"), replace(level, name="capped"), Effects.smooth_steady())
    res = solve_contact(CASE, load_lubricant("atf"), level, Effects.smooth_steady())
    assert res.converged is False
    assert res.message.startswith("not converged")
    assert res.residuals["reynolds"] > level.tol_residual or res.residuals["step"] > level.tol_step


def test_a_requested_model_is_recorded_as_it_ran_with_the_planners_choice_kept():
    """The homogenised model asked for on a narrow rough contact whose plan has the transient on (at ``reference``
    the planner's own choice, the deterministic model) runs steady: the record says transient off, why, and what the
    planner chose; the deterministic model asked for on smooth surfaces solves the steady smooth contact and records
    no roughness."""
    from ehl_dataset.solvers.planner import plan_effects

    narrow = ContactCase.from_engineering(0.5, 5, 5, 0.3, 90, 0.3, 0.3)
    planned = plan_effects(narrow, load_lubricant("atf"), "reference")
    assert planned.transient and "deterministic" in planned.reasons["decisions"]["model"]
    steady = solve_contact(narrow, "atf", "fast", planned, model="homogenised")
    decisions = steady.effects["reasons"]["decisions"]
    assert steady.effects["roughness"] and not steady.effects["transient"]
    assert decisions["transient"].startswith("model=homogenised requested: transient off (the planner: ")
    assert decisions["model"].startswith("model=homogenised requested (the planner: ")
    smooth = ContactCase.from_engineering(0.5, 5, 5, 0.3, 90, 0.0, 0.0)
    forced = solve_contact(smooth, "atf", "fast", model="deterministic")
    assert not forced.effects["roughness"] and not forced.effects["transient"]
    assert "smooth surfaces, steady smooth solve" in forced.effects["reasons"]["decisions"]["model"]
    # the smooth limit: the smooth solver's μ within 0.5 %
    assert forced.mu == pytest.approx(solve_contact(smooth, "atf", "fast", model="smooth").mu, rel=5e-3)


def test_to_dict_is_the_contact_schema_and_resolving_once_gives_the_same_result():
    """``ContactResult.to_dict``: SI values under unit-named keys, λ̄ = ∞ of smooth surfaces as None (JSON has no
    infinity), the plan and its reasons as recorded; ``solve_problem(resolve_contact(...))`` is ``solve_contact``
    (same μ bit for bit), and a resolved problem records the route the plan chose (the steady smooth solver here)."""
    import json

    from ehl_dataset.solver import solve_problem
    from ehl_dataset.solvers.problem import resolve_contact

    problem = resolve_contact(CASE, "atf", "fast", "auto")
    assert problem.route == "steady" and problem.state.temperature == CASE.temperature
    res = solve_problem(problem)
    assert res.mu == solve_contact(CASE, load_lubricant("atf"), "fast").mu
    d = res.to_dict()
    assert (d["mu"], d["h_min_m"], d["h_central_m"], d["p_max_pa"]) == (res.mu, res.h_min, res.h_central, res.p_max)
    assert d["lambda_bar"] is None and d["model"] == "smooth" and d["level"] == "fast"
    assert d["effects"]["mode"] == "auto" and d["wall_time_s"] == res.wall_time
    json.loads(json.dumps(d, default=float))
