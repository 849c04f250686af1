"""The factorial runner: local processes, failures recorded, worker deaths retried, SIGKILL + resume, Dask.

Where the physics is not the point, an analytic stand-in solver is injected (Dowson–Higginson film, a monotone
μ(λ̄)): deterministic, cheap and picklable. One test runs the real EHL solver end to end.
"""

import io
import json
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from ehl_dataset.dataset.factorial import factorial_from_dict
from ehl_dataset.dataset.runner import resume_run, run_factorial
from ehl_dataset.dataset.store import read_metadata, read_table
from ehl_dataset.model.film_formulas import dowson_higginson_min_film
from ehl_dataset.solvers.result import ContactResult
from ehl_dataset.validation import InputError, SolverError

REPO = Path(__file__).resolve().parents[2]
PHYSICS = ["mu", "mu_std", "h_min", "h_central", "lambda_bar", "asperity_load_share", "p_max", "iterations",
           "converged", "effects", "level"]


# --------------------------------------------------------------------------------------------------------------
# Stand-in solvers (top-level, so workers can unpickle them)
# --------------------------------------------------------------------------------------------------------------
def analytic_solve(case, lubricant, level="fast", effects="auto"):
    """Dowson–Higginson minimum film, λ̄ = h_min/S_c, μ = μ_d/(1 + λ̄) + Eyring-like 0.01·asinh(SR): a cheap,
    deterministic stand-in with the solver's signature."""
    state = lubricant.state(case.temperature)
    h = float(dowson_higginson_min_film(state.eta0, case.u_r, state.alpha1, case.e_reduced, case.r_eq,
                                        case.load_per_length))
    lam = h / case.s_c if case.s_c > 0 else math.inf
    mu = state.mu_d / (1.0 + lam) + 0.01 * math.asinh(case.sr)
    return ContactResult(mu=mu, h_min=h, h_central=4.0 / 3.0 * h, p_max=case.p_h, converged=True, iterations=1,
                         wall_time=1e-3, level=level, effects={"mode": effects, "reasons": {"lambda_bar": lam}},
                         lambda_bar=lam, asperity_load_share=max(0.0, 1.0 - lam) / 2)


def slow_solve(case, lubricant, level="fast", effects="auto"):
    """The stand-in, taking 0.2 s (long enough to kill a run part-way)."""
    time.sleep(0.2)
    return analytic_solve(case, lubricant, level, effects)


def stubborn_solve(case, lubricant, level="fast", effects="auto"):
    """0.2 s up to p_h = 1 GPa; above, touches the file named by $GEARLOSS_TEST_MARKER and blocks for 120 s
    (a long solve in flight when the run is stopped)."""
    if case.p_h > 1e9:
        Path(os.environ["GEARLOSS_TEST_MARKER"]).touch()
        time.sleep(120)
    return slow_solve(case, lubricant, level, effects)


def raising_solve(case, lubricant, level="fast", effects="auto"):
    """Raises for the heavily loaded, fast-sliding points."""
    if case.p_h > 1e9 and case.sr > 0.5:
        raise SolverError(f"deliberate failure at p_h={case.p_h:g} Pa")
    return analytic_solve(case, lubricant, level, effects)


def dying_solve(case, lubricant, level="fast", effects="auto"):
    """Kills its worker process (like a segfault in compiled code) at one point."""
    if case.p_h > 1e9 and case.u_r > 10 and case.sr > 0.5 and case.rq1 > 1e-7:
        os._exit(13)
    time.sleep(0.02)
    return analytic_solve(case, lubricant, level, effects)


def flaky_outputs_solve(case, lubricant, level="fast", effects="auto"):
    """NaN with converged=True at p_h > 1 GPa and SR > 0.5; converged=False at u_r > 10 (with a message)."""
    result = analytic_solve(case, lubricant, level, effects)
    if case.p_h > 1e9 and case.sr > 0.5:
        result.mu = math.nan
    elif case.u_r > 10:
        result.converged = False
        result.message = "residual 3e-3 above tolerance 1e-4 after 50 iterations"
    return result


def blas_threads_solve(case, lubricant, level="fast", effects="auto"):
    """Reports, as ``iterations``, the most threads any loaded BLAS/OpenMP library would use during the solve."""
    from threadpoolctl import threadpool_info

    result = analytic_solve(case, lubricant, level, effects)
    result.iterations = max([info["num_threads"] for info in threadpool_info()] or [1])
    return result


def warning_solve(case, lubricant, level="fast", effects="auto"):
    """Warns three times from one line and once from another (like an ill-conditioned Newton step)."""
    import warnings

    for _ in range(3):
        warnings.warn("ill-conditioned matrix", RuntimeWarning)
    warnings.warn("slow convergence", UserWarning)
    return analytic_solve(case, lubricant, level, effects)


def plan_dict(**axes):
    base = {"p_h_gpa": [0.5, 1.5], "r_eq_mm": [20.0], "u_r_m_s": [5.0, 20.0], "sr": [0.1, 0.7], "temp_c": [75.0],
            "roughness_um": [[0.05, 0.05], [0.4, 0.4]]}
    base.update(axes)
    return {"name": "test", "level": "fast", "effects": "auto", "axes": base}


@pytest.fixture()
def plan():
    return factorial_from_dict(plan_dict())


def physics(path):
    return read_table(path, status=None)[["point", *PHYSICS]]


# --------------------------------------------------------------------------------------------------------------
def test_local_processes_give_the_same_rows_as_in_process(tmp_path, plan):
    serial = run_factorial(tmp_path / "serial.h5", plan, workers=0, solver=analytic_solve, progress="none")
    pool = run_factorial(tmp_path / "pool.h5", plan, workers=2, solver=analytic_solve, progress="none")
    assert serial.ok == pool.ok == plan.size == 16 and pool.pending == pool.failed == 0
    assert pool.executor["executor"] == "local" and pool.executor["workers"] == 2
    a, b = physics(tmp_path / "serial.h5"), physics(tmp_path / "pool.h5")
    assert a.equals(b)
    table = read_table(tmp_path / "pool.h5")
    assert (table["attempts"] == 1).all() and table["worker"].str.contains(":").all()
    assert len({w for w in table["worker"]}) >= 2  # the coordinator's warm-up point plus pool workers
    # the stored μ is exactly what the solve function returned for that point
    row = table.iloc[5]
    case_values = [row[c] for c in ("p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2")]
    from ehl_dataset.model.contact import ContactCase
    from ehl_dataset.model.lubricant import load_lubricant
    assert row["mu"] == analytic_solve(ContactCase(*case_values), load_lubricant("atf")).mu
    sessions = read_metadata(tmp_path / "pool.h5")["sessions"]
    assert len(sessions) == 1 and sessions[0]["computed"] == 16 and sessions[0]["interrupted"] is None


def test_a_point_that_raises_is_recorded_failed_and_the_rest_complete(tmp_path, plan):
    summary = run_factorial(tmp_path / "r.h5", plan, workers=2, solver=raising_solve, progress="none")
    table = read_table(tmp_path / "r.h5", status=None)
    expected_failed = (table["p_h"] > 1e9) & (table["sr"] > 0.5)
    assert summary.failed == int(expected_failed.sum()) == 4 and summary.ok == 12 and summary.pending == 0
    failed = table[table["status"] == "failed"]
    assert (failed.index == table[expected_failed].index).all()
    assert failed["error"].str.match(r"SolverError: deliberate failure at p_h=1\.5e\+09 Pa \(at test_runner\.py").all()
    assert failed["mu"].isna().all() and (failed["attempts"] == 1).all()  # deterministic errors: no retry


def test_nan_outputs_fail_and_non_converged_results_are_kept_flagged(tmp_path, plan):
    run_factorial(tmp_path / "r.h5", plan, workers=0, solver=flaky_outputs_solve, progress="none")
    table = read_table(tmp_path / "r.h5", status=None)
    nan_rows = (table["p_h"] > 1e9) & (table["sr"] > 0.5)
    assert (table.loc[nan_rows, "status"] == "failed").all()
    assert table.loc[nan_rows, "error"].str.contains("non-finite outputs: mu=nan").all()
    slow_rows = ~nan_rows & (table["u_r"] > 10)
    assert (table.loc[slow_rows, "status"] == "ok").all() and not table.loc[slow_rows, "converged"].any()
    assert table.loc[slow_rows, "error"].str.startswith("not converged: residual 3e-3").all()
    assert table.loc[~nan_rows & ~slow_rows, "converged"].all()


def test_a_worker_death_is_retried_alone_and_only_its_point_fails(tmp_path, plan):
    summary = run_factorial(tmp_path / "r.h5", plan, workers=2, solver=dying_solve, max_attempts=2,
                            progress="none", warm_up=False)
    table = read_table(tmp_path / "r.h5", status=None)
    killer = (table["p_h"] > 1e9) & (table["u_r"] > 10) & (table["sr"] > 0.5) & (table["rq1"] > 1e-7)
    assert killer.sum() == 1 and summary.failed == 1 and summary.ok == 15
    bad = table[killer].iloc[0]
    assert bad["status"] == "failed" and bad["attempts"] == 2 and "BrokenProcessPool" in bad["error"]
    assert (table.loc[~killer, "attempts"] == 1).all()  # innocent neighbours are not charged


def test_progress_log_lines_report_rate_and_eta(tmp_path, plan):
    stream = io.StringIO()
    run_factorial(tmp_path / "r.h5", plan, workers=0, solver=analytic_solve, progress="log", stream=stream,
                  log_every_s=0.0)
    lines = stream.getvalue().splitlines()
    assert len(lines) == 17  # one per point, and the final line
    assert "test: 16/16 points (this run: ok 16, failed 0" in lines[-1] and "points/s" in lines[-1] and "ETA" in lines[0]


def test_resume_is_refused_for_another_factorial_solver_version_or_lubricant(tmp_path, plan, monkeypatch):
    path = tmp_path / "r.h5"
    run_factorial(path, plan, workers=0, solver=analytic_solve, progress="none")
    with pytest.raises(InputError, match="factorial"):
        resume_run(path, factorial=factorial_from_dict(plan_dict(temp_c=[80.0])), workers=0)
    with pytest.raises(InputError, match="lubricant"):
        resume_run(path, lubricant="gear_oil_75w90", workers=0)
    with pytest.raises(InputError, match=r"solver\.level"):
        resume_run(path, level="standard", workers=0)
    with pytest.raises(InputError, match="lubricant"):
        run_factorial(path, plan, lubricant="gear_oil_75w90", solver=analytic_solve, workers=0)
    monkeypatch.setattr(analytic_solve, "solver_version", "9.9", raising=False)
    with pytest.raises(InputError, match=r"solver\.version='9\.9'"):
        resume_run(path, workers=0)


def test_modified_input_columns_are_detected(tmp_path, plan):
    import h5py

    path = tmp_path / "r.h5"
    run_factorial(path, plan, workers=0, solver=analytic_solve, progress="none")
    with h5py.File(path, "r+") as h5:
        h5["points/p_h"][3] = 1.6e9
    with pytest.raises(InputError, match="input columns"):
        resume_run(path, workers=0)


def test_sigkill_part_way_then_resume_completes_without_recomputing(tmp_path):
    """Acceptance: a real ``gearloss dataset run`` killed with SIGKILL, then resumed: the file is
    complete, no finished point is computed again, and the rows equal an uninterrupted run's."""
    plan_file = tmp_path / "plan.toml"
    plan_file.write_text(
        'name = "killme"\nlevel = "fast"\n[axes]\np_h_gpa = [0.5, 1.0, 1.5, 2.0]\nr_eq_mm = [10, 20]\n'
        'u_r_m_s = [2, 5, 10]\nsr = [0.2, 0.5]\ntemp_c = [60]\nroughness_um = [[0.1, 0.1]]\n')
    path = tmp_path / "run.h5"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(REPO), os.environ.get("PYTHONPATH", "")])}
    command = [sys.executable, "-m", "workflows.cli", "dataset", "run", "--factorial", str(plan_file), "--out",
               str(path), "--workers", "2", "--solver", f"{__name__}:slow_solve", "--flush-interval", "0.1",
               "--progress", "none"]
    process = subprocess.Popen(command, cwd=REPO, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 60
    try:
        while time.monotonic() < deadline and process.poll() is None:
            time.sleep(0.05)
            if path.exists():
                try:
                    counts = read_metadata(path)["counts"]
                except InputError:
                    continue
                if counts["ok"] >= 8:
                    process.send_signal(signal.SIGKILL)
                    break
        process.wait(timeout=30)
    finally:
        if process.poll() is None:
            process.kill()
    assert process.returncode == -signal.SIGKILL, process.stderr.read().decode()[-2000:]
    before = read_table(path, status=None)
    ok_before = before[before["status"] == "ok"]
    assert 8 <= len(ok_before) < 48, "the run must be killed part-way"
    assert read_metadata(path)["sessions"][0].get("ended") is None  # the killed session never closed

    # the workers die with the coordinator (PR_SET_PDEATHSIG), a few milliseconds after it: until then their
    # inherited descriptor holds the HDF5 lock and a resume is refused as "locked"
    for attempt in range(100):
        try:
            summary = resume_run(path, workers=2, progress="none")
            break
        except InputError as err:
            if "locked" not in str(err) or attempt == 99:
                raise
            time.sleep(0.1)
    assert summary.ok == 48 and summary.pending == 0 and summary.computed == 48 - len(ok_before)
    after = read_table(path, status=None)
    # no finished point computed twice; a row the kill caught inside a flush was never committed (its status is
    # written last), so it is computed again and may count that uncommitted computation too
    assert (after.loc[ok_before.index, "attempts"] == 1).all()
    assert after["attempts"].between(1, 2).all()
    kept = after.loc[ok_before.index]
    assert (kept["finished_at"] == ok_before["finished_at"]).all() and (kept["worker"] == ok_before["worker"]).all()

    reference = tmp_path / "reference.h5"
    run_factorial(reference, plan_file, workers=0, solver=analytic_solve, progress="none")
    assert physics(path).equals(physics(reference))


def test_sigterm_stops_the_run_at_once_with_finished_points_on_disk(tmp_path):
    """SIGTERM while long solves are in flight: the run stops within seconds (workers terminated), every result
    already received is written (though the flush interval is 60 s), the session is closed, exit status 143."""
    plan_file = tmp_path / "plan.toml"
    plan_file.write_text(
        'name = "stopme"\nlevel = "fast"\n[axes]\np_h_gpa = [0.5, 1.0, 1.5, 2.0]\nr_eq_mm = [10, 20]\n'
        'u_r_m_s = [2, 5, 10]\nsr = [0.2, 0.5]\ntemp_c = [60]\nroughness_um = [[0.1, 0.1]]\n')
    path, marker = tmp_path / "run.h5", tmp_path / "long_solve_started"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(REPO), os.environ.get("PYTHONPATH", "")]),
           "GEARLOSS_TEST_MARKER": str(marker)}
    command = [sys.executable, "-m", "workflows.cli", "dataset", "run", "--factorial", str(plan_file), "--out",
               str(path), "--workers", "2", "--solver", f"{__name__}:stubborn_solve", "--flush-interval", "60",
               "--progress", "none", "--json"]
    process = subprocess.Popen(command, cwd=REPO, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    try:
        deadline = time.monotonic() + 90
        while time.monotonic() < deadline and process.poll() is None and not marker.exists():
            time.sleep(0.05)
        time.sleep(0.5)  # both workers inside a 120 s solve (the window holds only p_h > 1 GPa points now)
        process.send_signal(signal.SIGTERM)
        sent = time.monotonic()
        out, err = process.communicate(timeout=60)
        stop_time = time.monotonic() - sent
    finally:
        if process.poll() is None:
            process.kill()
    assert process.returncode == 143, err.decode()[-2000:]
    assert stop_time < 15.0
    summary = json.loads(out)
    meta = read_metadata(path)
    assert summary["interrupted"] == "SIGTERM" and summary["ok"] == 24 and summary["pending"] == 24
    assert meta["counts"]["ok"] == 24  # everything received was written before exiting
    assert meta["sessions"][0]["interrupted"] == "SIGTERM" and meta["sessions"][0]["ended"]


@pytest.mark.slow
def test_dask_local_cluster_gives_the_same_rows_as_local_processes(tmp_path, plan, monkeypatch):
    """Acceptance: a run through a Dask LocalCluster (2 worker processes) equals the local default."""
    pytest.importorskip("distributed")
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join([str(REPO), os.environ.get("PYTHONPATH", "")]))
    local = run_factorial(tmp_path / "local.h5", plan, workers=2, solver=analytic_solve, progress="none")
    dask = run_factorial(tmp_path / "dask.h5", plan, workers=2, scheduler="dask-local", solver=analytic_solve,
                         progress="none")
    assert dask.executor["executor"] == "dask" and dask.executor["workers"] == 2
    assert local.ok == dask.ok == 16
    assert physics(tmp_path / "local.h5").equals(physics(tmp_path / "dask.h5"))
    workers = set(read_table(tmp_path / "dask.h5")["worker"])
    assert len(workers) == 2 and not any(w.endswith(f":{os.getpid()}") for w in workers)


@pytest.mark.slow
def test_real_solver_end_to_end(tmp_path):
    """The real EHL solver (fast level) through worker processes: every row ok, the stored values are exactly
    those of a direct solve, and λ̄ is the Dowson–Higginson film over S_c (paper Sect. 2.1)."""
    from ehl_dataset.model.contact import ContactCase
    from ehl_dataset.model.lubricant import load_lubricant
    from ehl_dataset.solver import solve_contact

    plan = factorial_from_dict(plan_dict(p_h_gpa=[0.5, 1.0], u_r_m_s=[20.0], sr=[0.3], temp_c=[50.0, 75.0],
                                         roughness_um=[[0.05, 0.05]]))
    summary = run_factorial(tmp_path / "real.h5", plan, workers=2, progress="none")
    table = read_table(tmp_path / "real.h5", status=None)
    assert summary.ok == 4 and (table["status"] == "ok").all() and table["converged"].all(), table["error"]
    meta = read_metadata(tmp_path / "real.h5")
    assert meta["solver"]["function"] == "ehl_dataset.solver:solve_contact" and meta["solver"]["level"] == "fast"
    lub = load_lubricant("atf")
    row = table.iloc[-1]
    case = ContactCase(*[float(row[c]) for c in ("p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2")])
    direct = solve_contact(case, lub, level="fast").to_record()
    for name in ("mu", "h_min", "h_central", "p_max", "lambda_bar", "iterations"):
        assert row[name] == direct[name], name
    state = lub.state(case.temperature)
    h_dh = dowson_higginson_min_film(state.eta0, case.u_r, state.alpha1, case.e_reduced, case.r_eq,
                                     case.load_per_length)
    assert row["lambda_bar"] == pytest.approx(h_dh / case.s_c, rel=1e-9)
    assert (table["mu"] > 0).all() and (table["mu"] < lub.mu_d).all() and (table["h_min"] > 0).all()


def test_warm_up_covers_each_distinct_effect_plan_once():
    """The coordinator pre-computes one point per distinct plan of the planner (so each compiled path is built
    once before the workers fork); injected solvers get just the first point."""
    from ehl_dataset.dataset.factorial import load_factorial
    from ehl_dataset.dataset.runner import DEFAULT_SOLVER, warm_up_indices
    from ehl_dataset.model.contact import ContactCase
    from ehl_dataset.model.lubricant import load_lubricant
    from ehl_dataset.solvers.planner import plan_effects

    plan, lub = load_factorial("quick"), load_lubricant("atf")
    points = plan.points()
    candidates = list(range(plan.size))
    chosen = warm_up_indices(points, candidates, lub.to_json_dict(), "fast", "auto", DEFAULT_SOLVER)

    keys = {}

    def key(i):
        if i not in keys:
            e = plan_effects(ContactCase(*(float(v) for v in points[i])), lub, "fast")
            keys[i] = e.roughness, e.transient, e.shear_thinning
        return keys[i]

    all_keys = {key(i) for i in candidates}
    assert len(all_keys) >= 2 and sorted(key(i) for i in chosen) == sorted(all_keys)
    assert all(key(i) != key(j) for i in chosen for j in chosen if i < j)
    # each chosen point is a narrowest contact of its plan (cheapest rough grid): minimal p_h·r_eq
    for i in chosen:
        same = [j for j in candidates if key(j) == key(i)]
        assert points[i][0] * points[i][1] == min(points[j][0] * points[j][1] for j in same)
    assert warm_up_indices(points, candidates, lub.to_json_dict(), "fast", "auto", analytic_solve) == [0]
    assert warm_up_indices(points, candidates, lub.to_json_dict(), "fast", "full", DEFAULT_SOLVER) == [0]


def test_progress_bar_shows_rate_and_counts(tmp_path, plan):
    stream = io.StringIO()
    run_factorial(tmp_path / "r.h5", plan, workers=0, solver=raising_solve, progress="bar", stream=stream)
    text = stream.getvalue()
    assert "16/16" in text and "pt/s" in text and "failed 4" in text and "ETA" in text


def test_each_solve_runs_on_one_blas_thread(tmp_path, plan):
    """One core per case (docs/how-to/run-a-dataset.md, "Workers"): LAPACK inside a solve is single-threaded wherever the point runs, which also
    makes a point's result independent of where it ran."""
    for workers in (0, 2):
        run_factorial(tmp_path / f"w{workers}.h5", plan, workers=workers, solver=blas_threads_solve,
                      progress="none")
        assert (read_table(tmp_path / f"w{workers}.h5")["iterations"] == 1).all()


def test_solver_warnings_are_counted_into_the_row_not_printed(tmp_path, plan, capfd):
    run_factorial(tmp_path / "r.h5", plan, workers=2, solver=warning_solve, progress="none")
    table = read_table(tmp_path / "r.h5")
    assert len(table) == 16
    assert table["warnings"].str.fullmatch(
        r"RuntimeWarning x3 \(test_runner\.py:\d+\); UserWarning x1 \(test_runner\.py:\d+\)").all()
    assert "ill-conditioned" not in capfd.readouterr().err
    assert (read_table(tmp_path / "r.h5", status=None)["warnings"] != "").all()


def test_default_solver_records_the_solvers_own_version():
    """The store's resume check compares this string: it must be the solver's SOLVER_VERSION, not the package's."""
    from ehl_dataset import solver
    from ehl_dataset.dataset.runner import DEFAULT_SOLVER, solver_config

    assert solver_config(DEFAULT_SOLVER, "fast", "auto")["version"] == solver.SOLVER_VERSION


# --------------------------------------------------------------------------------------------------------------
# Wall-time budget per point (time_limit_s)
# --------------------------------------------------------------------------------------------------------------
def budget_solve(case, lubricant, level="fast", effects="auto", time_limit_s=None):
    """The stand-in, telling which budget it was given: raises (a failed row, recomputed by a resume) at
    p_h > 1 GPa with SR > 0.5, returns converged=False at u_r > 10 (an ok row that a resume keeps)."""
    if case.p_h > 1e9 and case.sr > 0.5:
        raise SolverError(f"deliberate failure, budget {time_limit_s}")
    result = analytic_solve(case, lubricant, level, effects)
    if case.u_r > 10:
        result.converged = False
        result.message = f"stopped, budget {time_limit_s}"
    return result


# p_h 0.5 GPa, r_eq 5 mm, u_r 20 m/s, SR 0.1, 75 °C, all effects (the deterministic transient solver: the
# planner's own rough model at fast is steady): smooth surfaces are solved steady whatever the effects, Rq 0.4 µm
# transient rough (λ̄ 0.87); the narrowest contact, so the smooth start of the rough solve is short.
BUDGET_PLAN = {"name": "budget", "level": "fast", "effects": "full",
               "axes": {"p_h_gpa": [0.5], "r_eq_mm": [5.0], "u_r_m_s": [20.0], "sr": [0.1], "temp_c": [75.0],
                        "roughness_um": [[0.0, 0.0], [0.4, 0.4]]}}


def test_a_point_that_spends_its_budget_is_stored_not_converged_with_the_message(tmp_path):
    """The real solver (fast level) with a 1 ms budget: the rough point stops before its first time step and is
    stored ok, not converged, with the solver's message; the steady smooth point ignores the budget; nothing
    raises; the session records the budget."""
    from ehl_dataset.dataset.runner import PointTask, compute_point
    from ehl_dataset.dataset.store import OK
    from ehl_dataset.model.lubricant import load_lubricant

    plan = factorial_from_dict(BUDGET_PLAN)
    rough = tuple(float(v) for v in plan.points()[1])
    task = PointTask(1, rough, json.dumps(load_lubricant("atf").to_json_dict()), "fast", "full", time_limit_s=1e-3)
    out = compute_point(task)
    assert out["status"] == OK and out["record"] is not None and not out["record"]["converged"]
    assert "wall-time limit of 0.001 s reached after 0 of" in out["error"]

    summary = run_factorial(tmp_path / "b.h5", plan, workers=0, time_limit_s=1e-3, progress="none")
    assert summary.ok == 2 and summary.failed == 0 and summary.pending == 0 and summary.non_converged == 1
    table = read_table(tmp_path / "b.h5", status=None)
    smooth, stopped = table.iloc[0], table.iloc[1]
    assert smooth["converged"] and smooth["error"] == ""
    assert stopped["status"] == "ok" and not stopped["converged"]
    assert stopped["error"].startswith("not converged:") and "wall-time limit of 0.001 s reached after 0 of" in \
        stopped["error"]
    meta = read_metadata(tmp_path / "b.h5")
    assert meta["sessions"][0]["time_limit_s"] == 1e-3 and "time_limit_s" not in meta["solver"]
    # a resume (here without a budget) does not recompute the stopped point: it is an ok row
    assert resume_run(tmp_path / "b.h5", workers=0, progress="none").computed == 0


@pytest.mark.parametrize("bad", [0, 0.0, -1, -1.0, math.nan, math.inf, -math.inf, "1", True])
def test_invalid_budgets_are_refused_naming_time_limit_s(tmp_path, plan, bad):
    path = tmp_path / "r.h5"
    with pytest.raises(InputError, match="invalid time_limit_s="):
        run_factorial(path, plan, workers=0, solver=analytic_solve, progress="none", time_limit_s=bad)
    assert not path.exists()
    run_factorial(path, plan, workers=0, solver=budget_solve, progress="none")
    before = read_metadata(path)
    with pytest.raises(InputError, match="invalid time_limit_s="):
        resume_run(path, workers=0, progress="none", time_limit_s=bad)
    assert read_metadata(path)["sessions"] == before["sessions"]  # refused before a session began


def test_a_budget_for_a_solver_without_the_keyword_is_refused_at_the_start(tmp_path, plan):
    """Custom solvers without ``time_limit_s`` keep working without a budget; with one, the run is refused at
    once (every point would otherwise fail on a TypeError)."""
    path = tmp_path / "r.h5"
    with pytest.raises(InputError, match=r"invalid time_limit_s=5\.0.*analytic_solve does not accept it"):
        run_factorial(path, plan, workers=0, solver=analytic_solve, progress="none", time_limit_s=5.0)
    assert not path.exists()
    assert run_factorial(path, plan, workers=0, solver=analytic_solve, progress="none").ok == 16
    with pytest.raises(InputError, match="time_limit_s"):
        resume_run(path, workers=0, progress="none", time_limit_s=5.0)


def test_the_budget_is_not_part_of_the_solver_configuration(tmp_path, plan):
    """Runs and resumes with different budgets (or none) continue each other; the budget reaches the solver of the
    rows computed in each session; non-converged rows are ok and are not recomputed by a resume."""
    from ehl_dataset.dataset.runner import solver_config

    path = tmp_path / "r.h5"
    first = run_factorial(path, plan, workers=0, solver=budget_solve, progress="none", time_limit_s=2.5)
    assert first.failed == 4 and first.non_converged == 6
    meta = read_metadata(path)
    assert meta["solver"] == solver_config(budget_solve, "fast", "auto")
    table = read_table(path, status=None)
    failed = table["status"] == "failed"
    stopped = (table["status"] == "ok") & ~table["converged"]
    assert table.loc[failed, "error"].str.contains("budget 2.5").all()
    assert table.loc[stopped, "error"].str.contains("budget 2.5").all()

    again = resume_run(path, workers=0, progress="none")  # no budget: compatible
    assert again.computed == 4 and again.failed == 4
    assert read_table(path, status=None).loc[failed, "error"].str.contains("budget None").all()
    third = run_factorial(path, plan, workers=0, solver=budget_solve, progress="none", time_limit_s=60)
    assert third.computed == 4
    after = read_table(path, status=None)
    assert after.loc[failed, "error"].str.contains("budget 60.0").all() and (after.loc[failed, "attempts"] == 3).all()
    assert after.loc[stopped, "error"].str.contains("budget 2.5").all() and (after.loc[stopped, "attempts"] == 1).all()
    meta = read_metadata(path)
    assert [s["time_limit_s"] for s in meta["sessions"]] == [2.5, None, 60.0]
    assert meta["solver"] == solver_config(budget_solve, "fast", "auto")


def test_a_non_converged_message_is_stored_with_one_prefix():
    """The deterministic solver's messages already start with "not converged"; the stored error text names it once."""
    from ehl_dataset.dataset.runner import judge_record

    status, text = judge_record({"converged": False}, "not converged: wall-time limit of 1 s reached")
    assert text == "not converged: wall-time limit of 1 s reached"
    assert judge_record({"converged": False}, "stalled")[1] == "not converged: stalled"


def test_resume_can_retry_the_points_a_budget_stopped(tmp_path):
    """Two passes: a 1 ms budget stops the rough point (stored ok, not converged); a plain resume leaves it; a
    resume with retry_not_converged and no budget solves it (converged, μ in [0, μ_d], attempts 2) and does not
    touch the converged smooth point."""
    from ehl_dataset.model.lubricant import load_lubricant

    from ehl_dataset.dataset.roughness_choice import choose_roughness
    from ehl_dataset.model.roughness import BASELINE_NAME

    plan = factorial_from_dict(BUDGET_PLAN)
    path = tmp_path / "two_pass.h5"  # on the baseline profile: its deterministic solve takes seconds
    run_factorial(path, plan, workers=0, time_limit_s=1e-3, progress="none", roughness=choose_roughness(BASELINE_NAME))
    first = read_table(path, status=None)
    assert not first.iloc[1]["converged"] and first.iloc[0]["converged"]
    assert resume_run(path, workers=0, progress="none").computed == 0
    summary = resume_run(path, workers=0, progress="none", retry_not_converged=True)
    assert summary.computed == 1 and summary.non_converged == 0
    second = read_table(path, status=None)
    mu_d = load_lubricant("atf").mu_d
    assert second.iloc[1]["converged"] and 0.0 <= second.iloc[1]["mu"] <= mu_d and second.iloc[1]["error"] == ""
    assert second.iloc[1]["attempts"] == 2 and second.iloc[0]["attempts"] == 1
    assert second.iloc[0]["mu"] == first.iloc[0]["mu"]
    assert read_metadata(path)["sessions"][-1]["retry_not_converged"] is True
    with pytest.raises(InputError, match="retry_not_converged"):
        resume_run(path, workers=0, progress="none", retry_not_converged="yes")
