"""What a fresh ``gearloss contact solve`` of a smooth contact loads: the steady solver and what it needs (numpy, numba,
scipy.linalg), not the stages and models it does not run. Each module left out is import time saved on every cold
start (docs/validation/speed.md, the cold-start row). Checked in a fresh interpreter through ``sys.modules``; a
structural test, not a timing test. Run as the program, the command leaves its objects to the operating system at
exit (:func:`gc.freeze`, no teardown of numba's state), with its whole output; called in process, it does not.
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

NOT_ON_THE_SMOOTH_PATH = (
    # the dataset store, parallel runs, the surrogate fit, plots, profilometer files
    "h5py", "dask", "distributed", "statsmodels", "pandas", "sklearn", "matplotlib", "SurfaceTopography",
    # scipy parts only the mixed models or other stages use (scipy.optimize: ~20 % of a cold solve before)
    "scipy.optimize", "scipy.interpolate", "scipy.integrate", "scipy.stats",
    # the mixed models and the dataset layer
    "ehl_dataset.solvers.homogenised", "ehl_dataset.solvers.film_law_model", "ehl_dataset.solvers.asperity_model",
    "ehl_dataset.solvers.deterministic", "ehl_dataset.solvers.wide_contact", "ehl_dataset.model.dry_contact",
    "ehl_dataset.dataset",
)

SMOOTH_CASE = ["contact", "solve", "--p-h-gpa", "1", "--r-eq-mm", "20", "--u-r", "5", "--sr", "0.2", "--temp-c", "90",
               "--json"]


def loaded_after(argv: list[str]) -> tuple[dict, list[str]]:
    """(the command's JSON output, every module name in ``sys.modules`` after ``gearloss argv``), in a fresh
    interpreter."""
    code = ("import json, sys\nfrom workflows.cli import main\ncode = main(sys.argv[1:])\n"
            "print(json.dumps(sorted(sys.modules)))\nsys.exit(code)")
    run = subprocess.run([sys.executable, "-c", code, *argv], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.strip().splitlines()
    return json.loads("\n".join(lines[:-1])), json.loads(lines[-1])


def test_smooth_contact_solve_loads_only_the_smooth_path():
    result, modules = loaded_after(SMOOTH_CASE)
    assert result["converged"] and result["model"] == "smooth"
    loaded = set(modules)
    unexpected = sorted(name for name in loaded
                        if any(name == m or name.startswith(m + ".") for m in NOT_ON_THE_SMOOTH_PATH))
    assert unexpected == []
    # the test sees the solve path: its own modules are there
    assert {"numba", "scipy.linalg", "ehl_dataset.solvers.steady", "ehl_dataset.model.thermal"} <= loaded


@pytest.mark.parametrize("closure", ["transverse", "isotropic"])
def test_a_rough_contact_loads_the_mixed_model_with_the_closure_asked_for(closure):
    """The mixed model is imported where its route runs: ``--model homogenised`` on a rough contact gets the
    homogenised model with the closure of ``--closure`` (the default, transverse, through the model's default
    options)."""
    argv = [*SMOOTH_CASE[:-1], "--rq1-um", "0.3", "--rq2-um", "0.3", "--level", "fast", "--model", "homogenised",
            "--closure", closure, "--json"]
    result, modules = loaded_after(argv)
    assert result["model"] == "homogenised" and result["closure"] == closure
    assert "ehl_dataset.solvers.homogenised" in modules


def test_run_as_the_program_it_skips_the_teardown_and_prints_everything():
    run = subprocess.run([sys.executable, "-m", "workflows.cli", *SMOOTH_CASE], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert json.loads(run.stdout)["converged"]
    code = ("import gc, sys\nfrom workflows.cli import main\nsys.argv = ['gearloss', *sys.argv[1:]]\n"
            "in_process = main(sys.argv[1:])\nfrozen_in_process = gc.get_freeze_count()\ncode = main()\n"
            "print(in_process, code, frozen_in_process, gc.get_freeze_count() > 0)")
    run = subprocess.run([sys.executable, "-c", code, *SMOOTH_CASE], capture_output=True, text=True)
    assert run.stdout.strip().splitlines()[-1] == "0 0 0 True"
