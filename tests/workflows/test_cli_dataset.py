"""``gearloss dataset run|resume|info`` in process: outputs, JSON keys, exit codes and one-line errors."""

import json
import math

import pytest

from ehl_dataset.model.film_formulas import dowson_higginson_min_film
from ehl_dataset.solvers.result import ContactResult
from workflows.cli import main

PLAN = ('name = "cli"\nlevel = "fast"\n[axes]\np_h_gpa = [0.5, 1.5]\nr_eq_mm = [20]\nu_r_m_s = [5, 20]\n'
        'sr = [0.1, 0.7]\ntemp_c = [75]\nroughness_um = [[0.05, 0.05], [0.4, 0.4]]\n')


def film_solve(case, lubricant, level="fast", effects="auto"):
    """Stand-in solver: Dowson–Higginson minimum film and λ̄ = h_min/S_c; μ = μ_d/(1 + λ̄)."""
    state = lubricant.state(case.temperature)
    h = float(dowson_higginson_min_film(state.eta0, case.u_r, state.alpha1, case.e_reduced, case.r_eq,
                                        case.load_per_length))
    lam = h / case.s_c
    if case.p_h > 1e9 and case.u_r > 10 and case.sr > 0.5 and case.rq1 > 1e-7:
        raise ValueError("deliberate failure for the info listing")
    return ContactResult(mu=state.mu_d / (1 + lam), h_min=h, h_central=h, p_max=case.p_h, converged=True,
                         iterations=1, wall_time=case.p_h / 1e11, level=level, effects={"mode": effects},
                         lambda_bar=lam)


SOLVER = f"{__name__}:film_solve"


@pytest.fixture()
def plan_file(tmp_path):
    path = tmp_path / "plan.toml"
    path.write_text(PLAN)
    return path


def test_run_info_resume_round(tmp_path, plan_file, capsys):
    out = tmp_path / "cli.h5"
    code = main(["dataset", "run", "--factorial", str(plan_file), "--out", str(out), "--workers", "0",
                 "--solver", SOLVER, "--progress", "none", "--json"])
    payload = json.loads(capsys.readouterr().out)
    assert code == 0
    assert payload["ok"] == 15 and payload["failed"] == 1 and payload["pending"] == 0 and payload["n_points"] == 16
    assert payload["wall_time_s"] > 0 and payload["points_per_s"] > 0 and payload["store_time_per_point_s"] >= 0

    assert main(["dataset", "info", str(out), "--json", "--slowest", "3"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["counts"] == {"pending": 0, "ok": 15, "failed": 1}
    assert info["solver"]["function"] == SOLVER and info["lubricant_name"] == "atf"
    slow = info["slowest"]
    assert [row["p_h_pa"] for row in slow] == [1.5e9] * 3  # wall_time = p_h/1e11 in the stand-in
    assert slow[0]["wall_time_s"] == pytest.approx(0.015)
    assert info["failures"][0]["error"].startswith("ValueError: deliberate failure")
    assert math.isclose(info["solver_time_s"], 15 * 0.0 + sum([0.005] * 8 + [0.015] * 7), rel_tol=1e-12)

    assert main(["dataset", "info", str(out)]) == 0
    text = capsys.readouterr().out
    assert "factorial  cli: 16 points = 2 p_h_gpa x 1 r_eq_mm x 2 u_r_m_s x 2 sr x 1 temp_c x 2 roughness_um" in text
    assert "status     ok 15, failed 1, pending 0" in text and "slowest    point" in text
    assert "failed     point 15: ValueError: deliberate failure" in text

    # resume recomputes the failed row only (it fails again: deterministic), nothing else
    assert main(["dataset", "resume", str(out), "--workers", "0", "--progress", "none", "--json"]) == 0
    again = json.loads(capsys.readouterr().out)
    assert again["computed"] == 1 and again["ok"] == 15 and again["failed"] == 1


def test_running_the_same_command_again_continues_and_a_different_one_is_refused(tmp_path, plan_file, capsys):
    out = tmp_path / "cli.h5"
    args = ["dataset", "run", "--factorial", str(plan_file), "--out", str(out), "--workers", "0", "--solver",
            SOLVER, "--progress", "none"]
    assert main(args) == 0
    assert main(args + ["--json"]) == 0
    assert json.loads(capsys.readouterr().out.splitlines()[-1])["computed"] == 1  # only the failed row again
    assert main(args + ["--lubricant", "gear_oil_75w90"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "invalid --lubricant=gear_oil_75w90" in err and str(out) in err
    assert main(args + ["--level", "standard"]) == 2
    assert "invalid --level=standard" in capsys.readouterr().err
    # a copy of the plan under another name lists the same points in the same order: it may continue the file
    copy = tmp_path / "copy.toml"
    copy.write_text(PLAN.replace('name = "cli"', 'name = "copy"'))
    assert main(["dataset", "run", "--factorial", str(copy), "--out", str(out), "--solver", SOLVER, "--workers", "0",
                 "--progress", "none"]) == 0
    # another model is refused like another level (the stand-in solver takes no model: refused at the start)
    assert main(args + ["--model", "smooth"]) == 2
    assert "invalid --model=smooth" in capsys.readouterr().err
    assert main(["dataset", "run", "--factorial", "quick", "--out", str(out), "--solver", SOLVER]) == 2
    assert "invalid --factorial=" in capsys.readouterr().err
    assert main(args + ["--overwrite", "--level", "standard", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["computed"] == 16


@pytest.mark.parametrize("argv, fragment", [
    (["dataset", "run", "--factorial", "nope", "--out", "{tmp}/a.h5"], "invalid --factorial=nope"),
    (["dataset", "run", "--factorial", "smoke", "--out", "{tmp}/a.h5", "--workers", "-1", "--solver", SOLVER],
     "invalid --workers=-1"),
    (["dataset", "run", "--factorial", "smoke", "--out", "{tmp}/a.h5", "--level", "bogus", "--solver", SOLVER],
     "invalid --level='bogus'"),
    (["dataset", "run", "--factorial", "smoke", "--out", "{tmp}/a.h5", "--solver", "no_module:f"],
     "invalid --solver=no_module:f"),
    (["dataset", "run", "--factorial", "smoke", "--out", "{tmp}/a.h5", "--lubricant", "water"],
     "invalid --lubricant=water"),
    (["dataset", "info", "{tmp}/missing.h5"], "file not found"),
    (["dataset", "info", "{tmp}/plan.toml"], "not a readable HDF5 file"),
])
def test_bad_input_is_one_line_and_exit_2(tmp_path, plan_file, capsys, argv, fragment):
    argv = [a.replace("{tmp}", str(tmp_path)) for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and fragment in err, err
    assert not (tmp_path / "a.h5").exists()


# one steady smooth point (Rq 0.05 µm, λ̄ 7.0) and one transient rough point (Rq 0.4 µm, λ̄ 0.87), narrow contact
# all effects: the rough point runs the deterministic transient solver, which honours the budget (the planner's own
# rough model at fast is steady); the smooth surfaces are solved steady whatever the effects
BUDGET_PLAN = ('name = "budget"\nlevel = "fast"\neffects = "full"\n[axes]\np_h_gpa = [0.5]\nr_eq_mm = [5]\n'
               'u_r_m_s = [20]\nsr = [0.1]\ntemp_c = [75]\nroughness_um = [[0.0, 0.0], [0.4, 0.4]]\n')


def test_time_limit_stops_a_rough_point_and_is_recorded_in_the_session(tmp_path, capsys):
    plan = tmp_path / "budget.toml"
    plan.write_text(BUDGET_PLAN)
    out = tmp_path / "budget.h5"
    code = main(["dataset", "run", "--factorial", str(plan), "--out", str(out), "--workers", "0",  # the baseline
                 "--time-limit-s", "0.001", "--progress", "none", "--json", "--roughness", "baseline_synthetic"])
    payload = json.loads(capsys.readouterr().out)  # profile: its deterministic solve (effects full) takes seconds
    assert code == 0 and payload["ok"] == 2 and payload["non_converged"] == 1 and payload["pending"] == 0
    assert main(["dataset", "info", str(out), "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["sessions"][0]["time_limit_s"] == 0.001 and "time_limit_s" not in info["solver"]
    # a resume with another budget is compatible; the stopped point is an ok row and is not recomputed
    assert main(["dataset", "resume", str(out), "--workers", "0", "--time-limit-s", "60", "--progress", "none",
                 "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["computed"] == 0
    # ... unless the resume asks for it: the second pass solves the stopped point
    assert main(["dataset", "resume", str(out), "--workers", "0", "--retry-not-converged", "--progress", "none",
                 "--json"]) == 0
    second = json.loads(capsys.readouterr().out)
    assert second["computed"] == 1 and second["non_converged"] == 0


@pytest.mark.parametrize("value", ["0", "-1", "nan", "inf"])
def test_a_bad_time_limit_is_one_line_and_exit_2(tmp_path, plan_file, capsys, value):
    out = tmp_path / "a.h5"
    assert main(["dataset", "run", "--factorial", str(plan_file), "--out", str(out), "--workers", "0",
                 "--time-limit-s", value]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "invalid --time-limit-s=" in err, err
    assert not out.exists()
    assert main(["dataset", "run", "--factorial", str(plan_file), "--out", str(out), "--workers", "0", "--solver",
                 SOLVER, "--progress", "none"]) == 0
    assert main(["dataset", "resume", str(out), "--workers", "0", "--time-limit-s", value]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "invalid --time-limit-s=" in err, err
    # the stand-in solver has no time_limit_s parameter: a valid budget is refused for it, in one line
    assert main(["dataset", "resume", str(out), "--workers", "0", "--time-limit-s", "5"]) == 2
    assert "film_solve does not accept it" in capsys.readouterr().err
