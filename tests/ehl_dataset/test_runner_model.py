"""The contact model of a dataset run (``--model``): recorded in the solver configuration, passed to the solver,
checked on resume; files written before it was recorded read as ``auto``."""

import shutil
from pathlib import Path

import pytest

from ehl_dataset.dataset.factorial import factorial_from_dict
from ehl_dataset.dataset.runner import resume_run, run_factorial
from ehl_dataset.dataset.store import read_metadata, read_table
from ehl_dataset.solver import MODELS
from ehl_dataset.solvers.result import ContactResult
from ehl_dataset.validation import InputError

PLAN = factorial_from_dict({"name": "m", "level": "fast", "axes": {
    "p_h_gpa": [0.5], "r_eq_mm": [20.0], "u_r_m_s": [5.0], "sr": [0.1, 0.7], "temp_c": [75.0],
    "roughness_um": [[0.4, 0.4]]}})
MU_BY_MODEL = {name: 0.01 * (i + 1) for i, name in enumerate(MODELS)}


def model_solve(case, lubricant, level="fast", effects="auto", model="auto"):
    """Stand-in that returns a μ naming the model it was asked for."""
    return ContactResult(mu=MU_BY_MODEL[model], h_min=1e-7, h_central=1e-7, p_max=case.p_h, converged=True,
                         iterations=1, wall_time=0.0, level=level, effects={"mode": effects}, lambda_bar=0.5)


SOLVER = f"{__name__}:model_solve"


def test_the_model_is_recorded_passed_to_the_solver_and_checked_on_resume(tmp_path):
    path = tmp_path / "m.h5"
    run_factorial(path, PLAN, workers=0, solver=SOLVER, model="smooth", progress="none")
    assert read_metadata(path)["solver"]["model"] == "smooth"
    assert (read_table(path)["mu"] == MU_BY_MODEL["smooth"]).all()
    with pytest.raises(InputError, match=r"solver\.model='auto'.*'smooth' as recorded"):
        resume_run(path, workers=0, model="auto")
    with pytest.raises(InputError, match=r"solver\.model"):
        run_factorial(path, PLAN, workers=0, solver=SOLVER, progress="none")  # the factorial's model: auto
    assert resume_run(path, workers=0, model="smooth", progress="none").computed == 0
    with pytest.raises(InputError, match="invalid model='homogenized'"):
        run_factorial(tmp_path / "x.h5", PLAN, workers=0, solver=SOLVER, model="homogenized")
    assert not (tmp_path / "x.h5").exists()


def test_the_factorial_names_a_default_model(tmp_path):
    plan = factorial_from_dict({**PLAN.to_dict(), "model": "smooth"})
    run_factorial(tmp_path / "f.h5", plan, workers=0, solver=SOLVER, progress="none")
    assert (read_table(tmp_path / "f.h5")["mu"] == MU_BY_MODEL["smooth"]).all()


def test_a_file_without_a_recorded_model_reads_as_auto(tmp_path):
    old = Path(__file__).parent / "data" / "smoke_partial_v7.h5"
    path = tmp_path / "old.h5"
    shutil.copy(old, path)
    assert "model" not in read_metadata(path)["solver"]
    with pytest.raises(InputError, match=r"solver\.model='smooth'.*'auto' as recorded"):
        resume_run(path, workers=0, model="smooth")


def gridded_solve(case, lubricant, level="fast", effects="auto", model="auto"):
    """Stand-in: a deterministic run on 401 nodes at 0.5 µm over 2,000 steps for SR 0.7, a steady solve on a graded
    grid of 300 nodes for SR 0.1."""
    if case.sr > 0.5:
        return ContactResult(mu=0.05, h_min=1e-7, h_central=1e-7, p_max=case.p_h, converged=True, iterations=9,
                             wall_time=0.0, level=level, effects={"transient": True}, lambda_bar=0.5,
                             extra={"dx_m": 5e-7, "n_nodes": 401, "n_steps": 2000})
    return ContactResult(mu=0.02, h_min=1e-7, h_central=1e-7, p_max=case.p_h, converged=True, iterations=9,
                         wall_time=0.0, level=level, effects={"transient": False}, lambda_bar=0.5,
                         extra={"n_nodes": 300})


def test_the_grid_and_time_steps_of_each_point_are_stored(tmp_path):
    """In ``dataset run``, every point stores the grid spacing, nodes and time steps its
    solve took (a steady solve: no time steps, and no uniform spacing); files written before these columns read them
    as not recorded (NaN, -1)."""
    import numpy as np

    path = tmp_path / "g.h5"
    run_factorial(path, PLAN, workers=0, solver=f"{__name__}:gridded_solve", progress="none")
    table = read_table(path).set_index("sr")
    assert table.loc[0.7, "dx"] == 5e-7 and table.loc[0.7, "n_nodes"] == 401 and table.loc[0.7, "n_steps"] == 2000
    assert np.isnan(table.loc[0.1, "dx"]) and table.loc[0.1, "n_nodes"] == 300 and table.loc[0.1, "n_steps"] == 0
    old = Path(__file__).parent / "data" / "smoke_partial_v7.h5"
    legacy = read_table(old, status=None)
    assert legacy["dx"].isna().all() and (legacy["n_nodes"] == -1).all() and (legacy["n_steps"] == -1).all()
