"""``gearloss contact solve``: JSON output in SI units and one-line errors for bad input."""

import json
import subprocess
import sys

import pytest

from workflows.cli import main

BASE = ["contact", "solve", "--p-h-gpa", "1.2", "--r-eq-mm", "20", "--u-r", "5", "--sr", "0.3", "--temp-c", "90",
        "--level", "fast"]


def test_json_output_keys_and_units(capsys):
    assert main(BASE + ["--effects", "smooth", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("mu", "h_min_m", "h_central_m", "p_max_pa", "converged", "wall_time_s", "effects", "level",
                "iterations", "lambda_bar"):
        assert key in out
    assert out["converged"] is True and out["level"] == "fast"
    # SI units: a film of tens of nm to µm in metres, a pressure near p_h = 1.2e9 Pa
    assert 1e-8 < out["h_central_m"] < 1e-5 and 1.0e9 < out["p_max_pa"] < 1.4e9
    assert out["lambda_bar"] is None  # smooth surfaces: λ̄ infinite, JSON null


def test_thermal_correction_reported_and_switchable(capsys):
    """Smooth, 5 m/s, SR 0.3: the planner corrects the traction for shear heating (docs/explanation/planner.md); the JSON
    carries the isothermal μ and the temperature rises; --effects isothermal gives that μ without the correction."""
    assert main(BASE + ["--json"]) == 0
    hot = json.loads(capsys.readouterr().out)
    assert main(BASE + ["--effects", "isothermal", "--json"]) == 0
    cold = json.loads(capsys.readouterr().out)
    assert hot["effects"]["thermal"] and not cold["effects"]["thermal"] and cold["thermal"] is None
    assert hot["thermal"]["mu_isothermal"] == pytest.approx(cold["mu"], rel=1e-12)
    assert hot["mu"] < cold["mu"] and hot["thermal"]["max_surface_rise_k"] > 0


def test_validation_fluid_by_name_and_by_file(capsys, tmp_path):
    """A Newtonian Barus fluid can be chosen by shipped name or by a TOML file path."""
    from ehl_dataset.data_files import data_path

    assert main(BASE + ["--lubricant", "validation_barus", "--json"]) == 0
    by_name = json.loads(capsys.readouterr().out)
    copy = tmp_path / "my_fluid.toml"
    copy.write_text(data_path("lubricants", "validation_barus.toml").read_text())
    assert main(BASE + ["--lubricant", str(copy), "--json"]) == 0
    by_file = json.loads(capsys.readouterr().out)
    assert by_file["h_min_m"] == pytest.approx(by_name["h_min_m"], rel=1e-12)


@pytest.mark.parametrize("args, parameter", [
    (["--p-h-gpa", "nan"], "invalid --p-h-gpa=nan: accepted a finite number"),
    (["--p-h-gpa", "-1"], "invalid --p-h-gpa=-1: accepted (0, 10] GPa"),
    (["--p-h-gpa", "0"], "invalid --p-h-gpa=0: accepted (0, 10] GPa"),
    (["--temp-c", "200"], "invalid --temp-c=200: accepted [0, 150] °C for lubricant atf"),
    (["--lubricant", "no_such_oil"], "lubricant"),
    (["--level", "ultra"], "level"),
    (["--time-limit-s", "-3"], "invalid --time-limit-s=-3"),
])
def test_bad_input_one_line_nonzero_exit(capsys, args, parameter):
    argv = list(BASE)
    for flag, value in zip(args[::2], args[1::2]):
        if flag in argv:
            argv[argv.index(flag) + 1] = value
        else:
            argv += [flag, value]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and parameter in err


def test_time_limit_flag_reaches_the_deterministic_transient_solver(capsys):
    """--time-limit-s: a rough case whose budget is spent is reported not converged, with the reason (exit 1)."""
    assert main(BASE + ["--rq1-um", "0.4", "--rq2-um", "0.4", "--effects", "full", "--time-limit-s", "0.001",
                        "--json"]) == 1
    out = json.loads(capsys.readouterr().out)
    assert out["converged"] is False and "wall-time limit" in out["message"]


def test_console_script_subprocess():
    """One real process: the installed module entry point prints a single JSON object."""
    proc = subprocess.run([sys.executable, "-m", "workflows.cli"] + BASE + ["--effects", "smooth", "--json"],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 0, proc.stderr
    assert json.loads(proc.stdout)["converged"] is True


def test_checkpoint_flag_is_refused_where_no_deterministic_run_takes_it(capsys, tmp_path):
    """--checkpoint FILE belongs to a resolved deterministic run (saved every 10 min, continued after a stop;
    tests/ehl_dataset/test_deterministic.py checks the continuation): with another model it is one error line."""
    path = tmp_path / "run.pickle"
    assert main(BASE + ["--rq1-um", "0.4", "--rq2-um", "0.4", "--model", "homogenised", "--checkpoint", str(path),
                        "--json"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "checkpoint" in err and str(path) in err
    assert not path.exists()


def test_deterministic_model_json_carries_its_grid_steps_and_the_requested_model(capsys):
    """``--model deterministic --dx-um D`` reports the run's grid and steps. A narrow rough
    contact (0.5 GPa, 5 mm, a = 44 µm, Rq 0.3 µm) at D = 4 µm: the grid spans the domain (−2.5a, 1.5a) with
    round(4a/D) + 1 nodes, so dx_m = 4a/(n − 1); the run lasts at least the ramp, the start-up and the shortest
    averaging window, and at most the level's cap, in time steps of Courant·dx/u_r; the effects record the transient
    solve that ran (at ``fast`` the planner would have chosen the steady film-law model) and the JSON μ is the
    Python API's."""
    import math

    from ehl_dataset import ContactCase, solve_contact
    from ehl_dataset.model.lubricant import load_lubricant
    from ehl_dataset.solvers.deterministic import deterministic_options
    from ehl_dataset.solvers.planner import plan_effects

    inputs = dict(p_h_gpa=0.5, r_eq_mm=5, u_r=5, sr=0.3, temp_c=90, rq1_um=0.3, rq2_um=0.3)
    argv = ["contact", "solve"] + [item for k, v in inputs.items() for item in (f"--{k.replace('_', '-')}", str(v))]
    assert main(argv + ["--model", "deterministic", "--dx-um", "4", "--level", "fast", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("mu", "mu_sem", "asperity_load_share", "h_min_m", "lambda_bar", "dx_m", "n_nodes", "n_steps",
                "converged", "effects", "wall_time_s"):
        assert key in out
    case = ContactCase.from_engineering(0.5, 5, 5, 0.3, 90, 0.3, 0.3)
    options = deterministic_options("fast", dx_m=4e-6)
    span = (options.domain[1] - options.domain[0]) * case.half_width
    assert out["n_nodes"] == round(span / 4e-6) + 1
    assert out["dx_m"] == pytest.approx(span / (out["n_nodes"] - 1), rel=1e-12)
    steps_per_pass = span / (options.courant * out["dx_m"])
    shortest = sum(math.ceil(passes * steps_per_pass) for passes in
                   (options.ramp_passes, options.startup_passes, options.min_average_passes))
    assert shortest <= out["n_steps"] <= math.ceil(options.max_passes * steps_per_pass)
    assert out["converged"] is True and out["route"] == "resolve"
    assert out["effects"]["roughness"] and out["effects"]["transient"]
    planner = plan_effects(case, load_lubricant("atf"), "fast").reasons["decisions"]["model"]
    assert planner.startswith("homogenised model")
    assert out["effects"]["reasons"]["decisions"]["model"] == f"model=deterministic requested (the planner: {planner})"
    assert 0.0 < out["mu_sem"] < out["mu"] and 0.0 <= out["asperity_load_share"] <= 1.0
    api = solve_contact(case, "atf", "fast", model="deterministic", deterministic=options)
    assert out["mu"] == pytest.approx(api.mu, rel=1e-12) and out["n_steps"] == api.extra["n_steps"]
