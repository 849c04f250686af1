"""Progress of a run: counts of the whole file on resume, and a time to go predicted from the
measured cost of the points done."""

import io

from ehl_dataset.dataset.factorial import factorial_from_dict
from ehl_dataset.dataset.runner import CostModel, resume_run, run_factorial
from ehl_dataset.solvers.result import ContactResult

PLAN = {"name": "prog", "level": "fast",
        "axes": {"p_h_gpa": [0.5, 1.5], "r_eq_mm": [10.0, 40.0], "u_r_m_s": [5.0], "sr": [0.1, 0.7],
                 "temp_c": [75.0], "roughness_um": [[0.05, 0.05], [0.4, 0.4]]}}
FAIL_HIGH_LOAD = {"on": False}


def flaky_solve(case, lubricant, level="fast", effects="auto"):
    """Fails at p_h 1.5 GPa while ``FAIL_HIGH_LOAD["on"]`` (an interrupted first half), then succeeds."""
    if FAIL_HIGH_LOAD["on"] and case.p_h > 1e9:
        raise RuntimeError("not yet")
    return ContactResult(mu=0.05, h_min=1e-7, h_central=1e-7, p_max=case.p_h, converged=True, iterations=1,
                         wall_time=0.0, level=level, effects={"mode": effects}, lambda_bar=2.0)


SOLVER = f"{__name__}:flaky_solve"


def test_cost_model_predicts_from_like_points_and_divides_by_the_measured_speed_up():
    """Eight points (p_h x r_eq x SR, one roughness pair), computed in C order. After the four at p_h 0.5 GPa,
    costing 1 s (r_eq 10 mm) and 8 s (r_eq 40 mm), the four at 1.5 GPa are predicted from their r_eq group:
    1 + 1 + 8 + 8 = 18 s of work; 18 s done in 9 s of wall time is a speed-up of 2, so 9 s to go. With only the two
    cheap points done, the 40 mm points fall back to the roughness pair's mean (1 s) until one is measured; then
    they are predicted at 8 s each."""
    plan = factorial_from_dict({**PLAN, "axes": {**PLAN["axes"], "roughness_um": [[0.4, 0.4]]}})
    points = plan.points()
    assert len(points) == 8
    r_eq = points["r_eq"]
    model = CostModel(points, workers=1)
    model.remaining = set(range(8))
    for i in range(4):
        model.observe(i, 1.0 if r_eq[i] < 0.02 else 8.0)
    assert sorted(model.remaining) == [4, 5, 6, 7]
    assert model.predict(4) == 1.0 and model.predict(7) == 8.0
    assert model.seconds_to_go(elapsed=9.0) == 9.0

    cheap = CostModel(points, workers=1)
    cheap.remaining = set(range(8))
    cheap.observe(0, 1.0)
    cheap.observe(1, 1.0)
    assert cheap.seconds_to_go(elapsed=2.0) == 6.0  # six points at the pair's mean of 1 s, speed-up 1
    cheap.observe(2, 8.0)
    assert cheap.predict(7) == 8.0 and cheap.predict(6) == 8.0 and cheap.predict(5) == 1.0


def test_a_resumed_run_counts_from_the_points_already_done(tmp_path):
    """A first run leaves the 8 points at 1.5 GPa failed; the resume says how many are done and counts 9/16 ...
    16/16, not 1/8 ... 8/8."""
    path = tmp_path / "prog.h5"
    FAIL_HIGH_LOAD["on"] = True
    try:
        first = run_factorial(path, factorial_from_dict(PLAN), workers=0, solver=SOLVER, progress="none")
    finally:
        FAIL_HIGH_LOAD["on"] = False
    assert first.ok == 8 and first.failed == 8
    stream = io.StringIO()
    summary = resume_run(path, workers=0, progress="log", stream=stream, log_every_s=0.0)
    lines = stream.getvalue().splitlines()
    assert summary.computed == 8 and summary.ok == 16
    assert lines[0] == f"resuming {path}: 8 of 16 points done, 8 to compute"
    assert "prog: 9/16 points" in lines[1] and "prog: 16/16 points" in lines[-1] and " done prog" in lines[-1]
