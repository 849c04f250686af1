"""Benchmark: the stage-1 floor — warm and cold smooth solves, the default model, the paper factorial's wall time.

    python benchmarks/bench_stage1_floor.py [--n 1000] [--baseline-n 200] [--default-n 200] [--previous-n 0] [--seed 45]
        [--cold-repeats 3] [--factorial sample|full|none] [--conditions 200] [--workers 2]
        [--out benchmarks/results/stage1_floor.json]

In one run, on contacts drawn (seeded) from the axes of ``data/factorials/paper2009.toml`` (ATF, ``standard``):

* ``warm_smooth`` — steady smooth solves (``model="smooth"``, the planner's effects) in a warm process (numba code
  loaded), each contact solved afresh (the per-process cache of steady solutions is emptied before every solve; the
  per-grid influence matrices stay cached, as in any long run). Median, percentiles of wall and CPU time.
  ``linear``: the linear-solve counters of the steady solves summed (dense LU factorisations, GMRES solves with the
  banded preconditioner and their iterations, fallbacks from it to the dense LU).
* ``dense_baseline`` — the first ``--baseline-n`` of the same contacts with the dense Newton path
  (``ehl_dataset.solvers.newton.REUSE_FACTORISATION = False``: one LU factorisation per Newton iteration, exact
  linear solves of the same discretisation), and the largest relative difference of μ, h_min, h_c, p_max between the
  two paths (the default path's inexact Newton iteration converges to the same discrete solution within the Newton
  tolerances).
* ``previous_path`` (``--previous-n``) — the first contacts solved as before the banded preconditioner
  (``newton.BANDED_PRECONDITIONER = False``: the reused dense LU; ``steady.START_FILM_EXPONENT = 0``), in the same
  run, and the largest relative difference of the outputs to the default path.
* ``default_model`` — the first ``--default-n`` contacts with their roughness pair and the paper factorial's effects
  (``isothermal``): the default model (``model="auto"``: the film-law homogenised model on rough contacts, the smooth
  solve where the planner finds the surfaces separated) against the smooth solve of the same contact and effects.
* ``cold`` — fresh interpreters: ``python -c pass``, ``gearloss --version``, ``gearloss --help`` and a smooth
  ``gearloss contact solve`` (1 GPa, 20 mm, 5 m/s, SR 0.2, 90 °C), wall time including the interpreter start and the
  CPU time (user + system) of the child process.
* ``factorial`` — ``sample``: ``--conditions`` seeded (p_h, r_eq, u_r, SR, T) conditions of the paper factorial with
  all their roughness pairs (the factorial's own order, so that a worker meets the pairs of a condition together as
  in the full run), computed by the dataset runner's worker function (``compute_point``) on a local process pool of
  ``--workers`` processes with the runner's window of 4 tasks per worker, without the HDF5 store; the wall time is
  extrapolated linearly to the 42,000 points (labelled as such). ``full``: every point of the factorial the same way.
  ``--warm-start``: with the runner's neighbour warm starts (``execute(..., warm_start=True)``).

The machine is described (CPU model, cores, load averages at the start, between the parts and at the end): on a shared
machine the load changes the wall times, the CPU times less.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import resource
import statistics
import subprocess
import sys
import time
from collections import deque
from pathlib import Path

import numpy as np

from ehl_dataset.dataset.executors import make_executor
from ehl_dataset.dataset.factorial import canonical_json, load_factorial
from ehl_dataset.dataset.runner import PointTask, compute_point
from ehl_dataset.dataset.store import OK
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solver import SOLVER_VERSION, solve_contact
from ehl_dataset.solvers import newton, steady

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import machine_info  # noqa: E402

OUTPUTS = ("mu", "h_min", "h_central", "p_max")
COLD_CASE = ["--p-h-gpa", "1", "--r-eq-mm", "20", "--u-r", "5", "--sr", "0.2", "--temp-c", "90"]


def cpu_model() -> str:
    """The ``model name`` line of /proc/cpuinfo (Linux), else ``platform.processor()``."""
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def load_average() -> list[float] | None:
    return [round(v, 2) for v in os.getloadavg()] if hasattr(os, "getloadavg") else None


def stats(values) -> dict:
    """Median, mean and percentiles (10, 90, 99) [same unit as ``values``] and the count."""
    v = np.asarray(values, dtype=float)
    if v.size == 0:
        return {"n": 0}
    return {"n": int(v.size), "median": float(np.median(v)), "mean": float(np.mean(v)),
            "p10": float(np.percentile(v, 10)), "p90": float(np.percentile(v, 90)),
            "p99": float(np.percentile(v, 99)), "max": float(np.max(v))}


def sample_rows(n: int, seed: int) -> np.ndarray:
    """``n`` seeded rows (p_h, r_eq, u_r, sr, T, rq1, rq2) [SI] of the paper factorial (with replacement)."""
    points = load_factorial("paper2009").points()
    table = np.column_stack([points[name] for name in points.dtype.names])
    return table[np.random.default_rng(seed).integers(0, table.shape[0], n)]


def timed_solve(row, lub, effects: str, model: str) -> tuple[float, float, object]:
    """(wall [s], CPU [s], result) of one solve, the steady-solution cache emptied first."""
    cache = getattr(steady, "_STEADY_CACHE", None)  # absent before the cache existed (a baseline checkout)
    if cache is not None:
        cache.clear()
    case = ContactCase(*row)
    wall, cpu = time.perf_counter(), time.process_time()
    result = solve_contact(case, lub, "standard", effects, model=model)
    return time.perf_counter() - wall, time.process_time() - cpu, result


def warm_smooth(rows: np.ndarray, lub) -> tuple[dict, list]:
    smooth = rows.copy()
    smooth[:, 5:] = 0.0
    walls, cpus, results = [], [], []
    for row in smooth:
        wall, cpu, res = timed_solve(row, lub, "auto", "smooth")
        walls.append(wall)
        cpus.append(cpu)
        results.append(res)
    return {"wall_s": stats(walls), "cpu_s": stats(cpus),
            "converged": int(sum(r.converged for r in results)),
            "iterations": stats([r.iterations for r in results]),
            "nodes": stats([r.extra["n_nodes"] for r in results]),
            "linear": linear_totals(results)}, results


def linear_totals(results: list) -> dict:
    """The steady solves' linear-solve counters (``extra["continuation"]["linear"]``: dense LU factorisations, GMRES
    solves with the banded preconditioner and their iterations, fallbacks to the dense LU) summed over the results,
    and the contacts with at least one fallback."""
    totals, with_fallback = {}, 0
    for res in results:
        counts = res.extra.get("continuation", {}).get("linear") or {}
        for key, value in counts.items():
            totals[key] = totals.get(key, 0) + int(value)
        with_fallback += bool(counts.get("fallbacks"))
    return {**totals, "contacts_with_fallback": with_fallback}


def dense_baseline(rows: np.ndarray, lub, fast_results: list) -> dict:
    smooth = rows.copy()
    smooth[:, 5:] = 0.0
    newton.REUSE_FACTORISATION = False
    try:
        walls, cpus, diffs, converged, dense_results = [], [], {k: 0.0 for k in OUTPUTS}, 0, []
        for row, fast in zip(smooth, fast_results):
            wall, cpu, res = timed_solve(row, lub, "auto", "smooth")
            dense_results.append(res)
            walls.append(wall)
            cpus.append(cpu)
            converged += bool(res.converged)
            for key in OUTPUTS:
                diffs[key] = max(diffs[key], abs(getattr(fast, key) / getattr(res, key) - 1.0))
    finally:
        newton.REUSE_FACTORISATION = True
    return {"wall_s": stats(walls), "cpu_s": stats(cpus), "converged": converged,
            "max_relative_difference_to_reuse": diffs, "linear": linear_totals(dense_results)}


def previous_path(rows: np.ndarray, lub, fast_results: list) -> dict:
    """The contacts solved as before the banded preconditioner: ``newton.BANDED_PRECONDITIONER = False`` (GMRES
    preconditioned with an older dense LU, else a fresh LU) and ``steady.START_FILM_EXPONENT = 0`` (the light-load
    continuation starts from the contact's own film); CPU and wall time, and the largest relative difference of the
    outputs to the default path."""
    smooth = rows.copy()
    smooth[:, 5:] = 0.0
    exponent = getattr(steady, "START_FILM_EXPONENT", 0.0)
    newton.BANDED_PRECONDITIONER = False
    steady.START_FILM_EXPONENT = 0.0
    try:
        walls, cpus, diffs, results = [], [], {k: 0.0 for k in OUTPUTS}, []
        for row, fast in zip(smooth, fast_results):
            wall, cpu, res = timed_solve(row, lub, "auto", "smooth")
            walls.append(wall)
            cpus.append(cpu)
            results.append(res)
            for key in OUTPUTS:
                diffs[key] = max(diffs[key], abs(getattr(fast, key) / getattr(res, key) - 1.0))
    finally:
        newton.BANDED_PRECONDITIONER = True
        steady.START_FILM_EXPONENT = exponent
    return {"wall_s": stats(walls), "cpu_s": stats(cpus), "converged": int(sum(r.converged for r in results)),
            "iterations": stats([r.iterations for r in results]),
            "max_relative_difference_to_default": diffs, "linear": linear_totals(results)}


def default_model(rows: np.ndarray, lub) -> dict:
    ratios, smooth_walls, default_walls, smooth_cpus, default_cpus, models = [], [], [], [], [], []
    converged = 0
    for row in rows:
        smooth_row = row.copy()
        smooth_row[5:] = 0.0
        ws, cs, _ = timed_solve(smooth_row, lub, "isothermal", "smooth")
        wd, cd, res = timed_solve(row, lub, "isothermal", "auto")
        converged += bool(res.converged)
        models.append(str(res.extra.get("model", "smooth")))
        smooth_walls.append(ws)
        default_walls.append(wd)
        smooth_cpus.append(cs)
        default_cpus.append(cd)
        ratios.append(cd / cs)
    return {"effects": "isothermal", "smooth_wall_s": stats(smooth_walls), "default_wall_s": stats(default_walls),
            "smooth_cpu_s": stats(smooth_cpus), "default_cpu_s": stats(default_cpus),
            "cpu_ratio_default_over_smooth": stats(ratios),
            "contacts_above_3x": int(sum(r > 3.0 for r in ratios)),
            "ratio_of_median_cpu": statistics.median(default_cpus) / statistics.median(smooth_cpus),
            "models": {m: models.count(m) for m in sorted(set(models))}, "converged": converged}


def console_script(name: str) -> str:
    """The console script ``name`` installed beside this interpreter (not a shell shim)."""
    candidate = Path(sys.executable).parent / name
    return str(candidate) if candidate.exists() else name


def cold(repeats: int) -> dict:
    gearloss = console_script("gearloss")
    commands = {"python_pass": [sys.executable, "-c", "pass"], "gearloss_version": [gearloss, "--version"],
                "gearloss_help": [gearloss, "--help"],
                "contact_solve_smooth": [gearloss, "contact", "solve", *COLD_CASE]}
    out = {}
    for name, command in commands.items():
        walls, cpus = [], []
        for _ in range(repeats):
            before = resource.getrusage(resource.RUSAGE_CHILDREN)
            start = time.perf_counter()
            subprocess.run(command, check=True, capture_output=True)
            walls.append(time.perf_counter() - start)
            after = resource.getrusage(resource.RUSAGE_CHILDREN)
            cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
        out[name] = {"command": " ".join(["gearloss" if c == gearloss else c for c in command[:1]] + command[1:]),
                     "wall_s": stats(walls), "cpu_s": stats(cpus), "load_average": load_average()}
    out["contact_solve_smooth"]["command"] = "gearloss contact solve " + " ".join(COLD_CASE)
    out["python_pass"]["command"] = "python -c pass"
    # without it the package's own modules are compiled from source at every start (site-packages keep theirs)
    out["bytecode_written"] = not os.environ.get("PYTHONDONTWRITEBYTECODE")
    return out


def factorial_indices(mode: str, conditions: int, seed: int) -> tuple[np.ndarray, int]:
    factorial = load_factorial("paper2009")
    pairs = len(factorial.roughness_um)
    if mode == "full":
        return np.arange(factorial.size), factorial.size
    picks = np.sort(np.random.default_rng(seed).choice(factorial.size // pairs, conditions, replace=False))
    return (picks[:, None] * pairs + np.arange(pairs)[None, :]).ravel(), factorial.size


def run_factorial_sample(indices: np.ndarray, workers: int, lub, warm_start: bool = False) -> dict:
    factorial = load_factorial("paper2009")
    points = factorial.points()
    lubricant_json = canonical_json(lub.to_json_dict())
    tasks = deque(PointTask(int(i), tuple(float(v) for v in points[i]), lubricant_json, factorial.level,
                            factorial.effects, model=factorial.model, warm_start=warm_start) for i in indices)
    executor = make_executor(workers, None)
    window = 4 * executor.n_workers
    in_flight, results = {}, []
    start = time.perf_counter()
    try:
        while tasks or in_flight:
            while tasks and len(in_flight) < window:
                task = tasks.popleft()
                in_flight[executor.submit(compute_point, task)] = task.index
            done, _ = executor.wait_first(list(in_flight), timeout=0.5)
            for future in done:
                in_flight.pop(future)
                results.append(future.result())
    finally:
        executor.shutdown(cancel=True)
    wall = time.perf_counter() - start
    records = [r["record"] or {} for r in results]
    return {"points": len(results), "workers": workers, "warm_start": warm_start, "wall_s": wall,
            "ok": int(sum(r["status"] == OK for r in results)),
            "converged": int(sum(bool(rec.get("converged")) for rec in records)),
            "worker_time_s": stats([r["worker_time"] for r in results])}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=1000, help="warm smooth solves")
    parser.add_argument("--baseline-n", type=int, default=200, help="of them, also on the dense path")
    parser.add_argument("--default-n", type=int, default=200, help="of them, with roughness and the default model")
    parser.add_argument("--previous-n", type=int, default=0,
                        help="of them, also as before the banded preconditioner (reused dense LU, old start film)")
    parser.add_argument("--seed", type=int, default=45)
    parser.add_argument("--cold-repeats", type=int, default=3)
    parser.add_argument("--factorial", choices=("sample", "full", "none"), default="sample")
    parser.add_argument("--conditions", type=int, default=200, help="conditions x 10 roughness pairs (sample)")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--warm-start", action="store_true", help="factorial with neighbour warm starts")
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "stage1_floor.json"))
    args = parser.parse_args(argv)
    report = {"benchmark": "stage1_floor", "solver_version": SOLVER_VERSION,
              "command": "python benchmarks/bench_stage1_floor.py " + " ".join(argv if argv is not None
                                                                              else sys.argv[1:]),
              "machine": {**machine_info(), "cpu_model": cpu_model(), "load_average_start": load_average()},
              "note": "wall times on a machine shared with other runs: see the load averages; CPU times are the "
                      "process's own"}
    lub = load_lubricant("atf")
    rows = sample_rows(max(args.n, 1), args.seed)
    first = rows[0].copy()
    first[5:] = 0.0
    solve_contact(ContactCase(*first), lub, "standard", "auto", model="smooth")  # numba code loaded
    solve_contact(ContactCase(*rows[0]), lub, "standard", "isothermal")
    results = []
    if args.n:
        t0 = time.perf_counter()
        report["warm_smooth"], results = warm_smooth(rows, lub)
        report["warm_smooth"]["load_average_end"] = load_average()
        print(f"warm smooth: median {report['warm_smooth']['wall_s']['median'] * 1e3:.1f} ms wall, "
              f"{report['warm_smooth']['cpu_s']['median'] * 1e3:.1f} ms CPU ({time.perf_counter() - t0:.0f} s)",
              file=sys.stderr)
    if args.n and args.baseline_n:
        report["dense_baseline"] = dense_baseline(rows[:args.baseline_n], lub, results[:args.baseline_n])
        report["dense_baseline"]["load_average_end"] = load_average()
        print(f"dense baseline: median {report['dense_baseline']['cpu_s']['median'] * 1e3:.1f} ms CPU", file=sys.stderr)
    if args.n and args.previous_n:
        report["previous_path"] = previous_path(rows[:args.previous_n], lub, results[:args.previous_n])
        report["previous_path"]["load_average_end"] = load_average()
        print(f"previous path: median {report['previous_path']['cpu_s']['median'] * 1e3:.1f} ms CPU", file=sys.stderr)
    if args.n and args.default_n:
        report["default_model"] = default_model(rows[:args.default_n], lub)
        report["default_model"]["load_average_end"] = load_average()
        print(f"default model: median CPU ratio {report['default_model']['cpu_ratio_default_over_smooth']['median']:.2f}",
              file=sys.stderr)
    if args.cold_repeats:
        report["cold"] = cold(args.cold_repeats)
        print("cold: " + ", ".join(f"{k} {v['wall_s']['median']:.2f} s wall, {v['cpu_s']['median']:.2f} s CPU"
                                   for k, v in report["cold"].items() if isinstance(v, dict)),
              file=sys.stderr)
    if args.factorial != "none":
        indices, total = factorial_indices(args.factorial, args.conditions, args.seed)
        load_start = load_average()
        run = run_factorial_sample(indices, args.workers, lub, args.warm_start)
        run.update({"mode": args.factorial, "load_average_start": load_start, "load_average_end": load_average(),
                    "factorial_points": total})
        if args.factorial == "sample":
            run["extrapolated_full_wall_s"] = run["wall_s"] * total / run["points"]
            run["label"] = (f"EXTRAPOLATED from a seeded sample of {args.conditions} conditions x all roughness pairs "
                            f"({run['points']} points) to {total} points, linear in the point count")
        report["factorial"] = run
        print(f"factorial ({args.factorial}): {run['points']} points in {run['wall_s']:.1f} s"
              + (f", extrapolated {run['extrapolated_full_wall_s'] / 60:.1f} min" if args.factorial == "sample"
                 else ""), file=sys.stderr)
    report["machine"]["load_average_end"] = load_average()
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(report, indent=1) + "\n")
    print(f"wrote {args.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
