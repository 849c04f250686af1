"""Benchmark: mixed EHL solves (rough surfaces) of any contact model — wall time and convergence over factorial points.

    python benchmarks/bench_ehl_mixed.py --level fast --sample corners        # the 64 corners of the paper plan
    python benchmarks/bench_ehl_mixed.py --level standard --sample random --n 50 --seed 1
    python benchmarks/bench_ehl_mixed.py --sample corners --shard 0/2 & python ... --shard 1/2   # one per core
    python benchmarks/bench_ehl_mixed.py --sample corners --merge results/ehl_mixed_corners_fast_shard*.json
    python benchmarks/bench_ehl_mixed.py --model homogenised --closure transverse --sample random --n 500 --seed 2
    python benchmarks/bench_ehl_mixed.py --model smooth --sample random --n 500 --seed 2    # the same points, smooth

Corners: p_h {0.5, 2.5} GPa × r_eq {5, 80} mm × u_r {1, 20} m/s × SR {0, 1} × T {25, 100} °C × Rq1 = Rq2
{0.05, 1.0} µm (docs/reference/dataset-format.md), ATF, effects=full (``--effects``). Random: uniform draws from the paper's levels. Writes per-case rows
and a summary (converged count, mean/median time of all and of converged cases, projected time for 42,000 points on
this machine with one process per core) to benchmarks/results/ehl_mixed_<sample>_<level>.json
(``..._<sample>_<level>_<model>[_<closure>].json`` with ``--model`` other than auto). ``--model`` is one of
ehl_dataset.solver.MODELS; ``--closure`` the homogenised model's flow factors. ``cpu_time_s`` of each row is the
process CPU time, unaffected by other jobs on the machine (one BLAS thread).
"""

from __future__ import annotations

import argparse
import itertools
import json
import math
import re
import statistics
import sys
import time
from pathlib import Path

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import DEFAULT_PROFILE, PROFILES, named_profile
from ehl_dataset.solver import SOLVER_VERSION, solve_contact
from ehl_dataset.solvers.homogenised import HomogenisedOptions

# _common.py sits next to this file. Run as a script (`python benchmarks/bench_ehl_mixed.py` or, inside benchmarks/,
# `python bench_ehl_mixed.py`) Python already puts this directory first on sys.path; adding it explicitly also covers
# loading this file as a module (runpy, tests), where sys.path[0] is the caller's directory instead.
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import RESULTS_DIR, machine_info, merge_shards, projected_hours, summarize_rows, write_report  # noqa: E402

P_H, R_EQ, U_R = [0.5, 1.0, 1.5, 2.0, 2.5], [5, 10, 20, 40, 80], [1, 2, 5, 10, 15, 20]
SR, TEMP = [0, 0.05, 0.1, 0.2, 0.4, 0.7, 1.0], [25, 50, 75, 100]
RQ = [(0.05, 0.05), (0.1, 0.1), (0.2, 0.2), (0.3, 0.3), (0.4, 0.4), (0.5, 0.5), (0.7, 0.7), (1.0, 1.0), (0.2, 0.5),
      (0.4, 1.0)]

COST_FIELDS = ("newton_iterations", "gmres_iterations", "factorisations", "round_off_stops")
"""The cost record of a deterministic run (``extra`` keys; None for the other models)."""


def corner_cases():
    return [(p, r, u, s, t, q, q) for p, r, u, s, t, q in itertools.product([0.5, 2.5], [5, 80], [1, 20], [0, 1],
                                                                              [25, 100], [0.05, 1.0])]


def random_cases(n: int, seed: int):
    rng = np.random.default_rng(seed)
    return [(float(rng.choice(P_H)), float(rng.choice(R_EQ)), float(rng.choice(U_R)), float(rng.choice(SR)),
             float(rng.choice(TEMP)), *RQ[int(rng.integers(len(RQ)))]) for _ in range(n)]


FLANK_DEFAULT_SINCE = "ehl-2026.11-17"
"""EHL solver version from which the package's default roughness is ``flank_ground`` (``baseline_synthetic`` before)."""


def row_roughness(row: dict) -> str:
    """The roughness profile a result row was solved on: its ``roughness`` entry; for a row without one, the default
    of its solver version (``baseline_synthetic`` before :data:`FLANK_DEFAULT_SINCE` and for rows from before the
    version was recorded per row), else "not recorded"."""
    if "roughness" in row:
        return str(row["roughness"])
    if row.get("solver_version") is None:
        return "baseline_synthetic"
    version = re.fullmatch(r"ehl-(\d+)\.(\d+)-(\d+)", str(row["solver_version"]))
    since = re.fullmatch(r"ehl-(\d+)\.(\d+)-(\d+)", FLANK_DEFAULT_SINCE)
    if version and tuple(map(int, version.groups())) < tuple(map(int, since.groups())):
        return "baseline_synthetic"
    return "not recorded"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--level", default="fast")
    parser.add_argument("--sample", choices=["corners", "random"], default="corners")
    parser.add_argument("--n", type=int, default=50)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--out", default=None)
    parser.add_argument("--shard", default=None, help="I/N: run every N-th case starting at I (one process per core)")
    parser.add_argument("--merge", nargs="+", default=None, help="shard JSON files to merge into one report")
    parser.add_argument("--max-r-eq-mm", type=float, default=None,
                        help="keep only the drawn points with r_eq <= this [mm] (same draws, a subset)")
    parser.add_argument("--min-r-eq-mm", type=float, default=None,
                        help="keep only the points with r_eq >= this [mm] (e.g. the wide corners)")
    parser.add_argument("--indices", type=int, nargs="+", default=None,
                        help="run only these positions of the drawn sample (0-based, in the order of the draws), e.g. "
                             "the points a calibration needs first; with --resume the rest can follow later")
    parser.add_argument("--time-limit-s", type=float, default=None,
                        help="wall-time budget per case [s]; a case that spends it counts as not finished, and the "
                             "mean time is then a lower bound (reported as such)")
    parser.add_argument("--model", default="auto", help="contact model (ehl_dataset.solver.MODELS)")
    parser.add_argument("--closure", default="transverse", help="flow factors of --model homogenised")
    parser.add_argument("--effects", default="full", choices=("full", "isothermal", "auto"),
                        help="effect plan of every solve (default full; isothermal: the film-law closure without its "
                             "thermal correction, like the deterministic solver, which has none)")
    parser.add_argument("--roughness", default=DEFAULT_PROFILE, choices=sorted(PROFILES),
                        help="shipped roughness profile of both surfaces (default: the package's default, "
                             f"{DEFAULT_PROFILE}); recorded in every row, and --resume refuses a file whose rows were "
                             "solved on another")
    parser.add_argument("--resume", action="store_true",
                        help="keep the rows of the output file that exists, run only the cases it lacks, and rewrite "
                             "the report after every case (a long run that is stopped loses at most one case)")
    args = parser.parse_args(argv)
    cases = corner_cases() if args.sample == "corners" else random_cases(args.n, args.seed)
    if args.indices is not None:
        cases = [cases[i] for i in args.indices]
    if args.max_r_eq_mm is not None:
        cases = [c for c in cases if c[1] <= args.max_r_eq_mm]
    if args.min_r_eq_mm is not None:
        cases = [c for c in cases if c[1] >= args.min_r_eq_mm]
    lub = load_lubricant("atf")
    suffix = "" if args.model == "auto" else f"_{args.model}" + (f"_{args.closure}" if args.model == "homogenised"
                                                                    else "")
    homogenised = HomogenisedOptions(closure=args.closure) if args.model == "homogenised" else None
    effects = Effects.full() if args.effects == "full" else args.effects
    if args.merge:
        return _report(args, lub, merge_shards(args.merge), suffix)
    if args.shard:
        index, count = (int(v) for v in args.shard.split("/"))
        cases = cases[index::count]
        suffix += f"_shard{index}of{count}"
    out = Path(args.out or RESULTS_DIR / f"ehl_mixed_{args.sample}_{args.level}{suffix}.json")
    rows = json.loads(out.read_text())["rows"] if args.resume and out.exists() else []
    other = sorted({row_roughness(r) for r in rows} - {args.roughness})
    if other:
        print(f"--resume: {out} holds rows solved on roughness {', '.join(other)}, not {args.roughness}; resume with "
              "that --roughness or write another --out", file=sys.stderr)
        return 2
    profile = named_profile(args.roughness)
    done = {tuple(r["case"]) for r in rows}
    for case_args in cases:
        if tuple(case_args) in done:
            continue
        case = ContactCase.from_engineering(*case_args)
        start, cpu_start = time.perf_counter(), time.process_time()
        try:
            res = solve_contact(case, lub, args.level, effects, time_limit_s=args.time_limit_s,
                                model=args.model, homogenised=homogenised, roughness=profile)
            row = {"case": case_args, "converged": res.converged, "mu": res.mu, "mu_std": res.mu_std,
                   "finite": bool(np.isfinite([res.mu, res.h_min, res.h_central]).all()), "h_min_m": res.h_min,
                   "h_central_m": res.h_central,
                   "lambda_bar": res.lambda_bar, "asperity_load_share": res.asperity_load_share,
                   "max_load_error": res.extra.get("max_load_error"), "n_nodes": res.extra.get("n_nodes"),
                   "yielded_load_share": res.extra.get("yielded_load_share"), "p_max_pa": res.p_max,
                   "couette_fallback_steps": res.extra.get("couette_fallback_steps"),
                   "n_steps": res.extra.get("n_steps"), "substep_steps": res.extra.get("substep_steps"),
                   "n_steps_planned": res.extra.get("n_steps_planned"), "mu_sem": res.mu_sem,
                   "mu_inefficiency_steps": res.extra.get("mu_inefficiency_steps"),
                   "mu_sem_target_met": res.extra.get("mu_sem_target_met"),
                   "asperity_load_share_sem": res.extra.get("asperity_load_share_sem"),
                   **{key: res.extra.get(key) for key in COST_FIELDS},  # the deterministic solver's cost record
                   # a converged run may have had only its averaging-window extension cut by the budget
                   "time_limited": bool(res.extra.get("time_limited", False)) and not res.converged,
                   "route": res.extra.get("route"), "film_law_extrapolated": res.extra.get("film_law_extrapolated"),
                   "model_version": res.extra.get("model_version"),
                   "wide_model_version": res.extra.get("wide_model_version"),
                   "message": res.message}
        except Exception as err:  # recorded, the sweep goes on
            row = {"case": case_args, "converged": False, "error": f"{type(err).__name__}: {err}"}
        row["solver_version"] = SOLVER_VERSION  # per row: a resumed file may span versions
        row["roughness"] = args.roughness
        row["wall_time_s"] = time.perf_counter() - start
        row["cpu_time_s"] = time.process_time() - cpu_start  # one BLAS thread: unaffected by other processes
        rows.append(row)
        print(json.dumps(row, default=float), flush=True)
        if args.resume:
            _report(args, lub, rows, suffix, out, quiet=True)
    return _report(args, lub, rows, suffix, out)


def newton_cost_summary(rows) -> dict:
    """Medians over the rows with a cost record: Newton iterations per time step (each one dense LU), Newton
    solves per time step, and the share of the time-stepping iterations spent in solves that failed."""
    rec = [r for r in rows if r.get("newton_step_iterations") is not None and r.get("n_steps")]
    if not rec:
        return {}
    return {"median_newton_iterations_per_step": statistics.median(r["newton_step_iterations"] / r["n_steps"]
                                                                   for r in rec),
            "median_newton_solves_per_step": statistics.median(r["newton_solves"] / r["n_steps"] for r in rec),
            "median_failed_iteration_share": statistics.median(
                r["newton_iterations_failed"] / max(r["newton_step_iterations"], 1) for r in rec)}


def _report(args, lub, rows, suffix, out: Path | None = None, quiet: bool = False) -> int:
    ok = [r for r in rows if r["converged"]]
    summary = {**summarize_rows(rows),
               "converged_mu_in_0_mu_d_for_sr_gt_0": all(0.0 <= r["mu"] <= lub.mu_d for r in ok if r["case"][3] > 0),
               "converged_max_abs_mu_sr_0": max((abs(r["mu"]) for r in ok if r["case"][3] == 0), default=None),
               "converged_max_load_error": max((r["max_load_error"] for r in ok if r.get("max_load_error") is not None),
                                               default=None),
               "converged_lambda_bar_min": min((r["lambda_bar"] for r in ok), default=math.nan),
               "time_limited": sum(bool(r.get("time_limited")) for r in rows),
               **newton_cost_summary(rows),
               "time_limit_s": getattr(args, "time_limit_s", None)}
    if summary["time_limited"]:
        extrapolated = [_extrapolated_time(r) for r in rows]
        summary["mean_time_extrapolated_s"] = statistics.fmean(extrapolated)
        summary["projected_42000_points_h_extrapolated"] = projected_hours(summary["mean_time_extrapolated_s"])
        summary["note"] = (f"{summary['time_limited']} cases stopped at the wall-time limit: the mean time and the "
                           "projection are lower bounds; the extrapolated figures scale each stopped case's time by "
                           "planned/completed time steps (an estimate, not a measurement, and a low one: steps after the "
                           "roughness ramp-in cost more; two 80 mm points needed 2.5-2.7x it, "
                           "results/ehl_mixed_standard_80mm_long.json)")
    summary["converged_all_finite"] = all(r.get("finite", False) for r in ok)
    cpu = [r["cpu_time_s"] for r in rows if "cpu_time_s" in r]
    if cpu:
        summary["mean_cpu_time_s"] = statistics.fmean(cpu)
        summary["p95_cpu_time_s"] = float(np.percentile(cpu, 95))
    report = {"benchmark": "ehl_mixed", "level": args.level, "sample": args.sample, "model": args.model,
              "closure": args.closure if args.model == "homogenised" else None,
              "effects": args.effects, "summary": summary,
              "solver_version": SOLVER_VERSION,
              "rows_by_version": rows_by_version(rows),
              "rows": rows, "machine": machine_info()}
    write_report(out or args.out or RESULTS_DIR / f"ehl_mixed_{args.sample}_{args.level}{suffix}.json", report)
    if not quiet:
        print(json.dumps(summary, indent=2, default=float))
    return 0


def rows_by_version(rows) -> dict:
    """How many rows each (solver version, model version) made, as "solver/model" keys; rows written before the
    versions were recorded per row count as "unrecorded"."""
    counts: dict[str, int] = {}
    for row in rows:
        key = (f"{row['solver_version']}/{row.get('model_version')}" if "solver_version" in row
               else "unrecorded")
        counts[key] = counts.get(key, 0) + 1
    return counts


def _extrapolated_time(row) -> float:
    """Wall time [s] of a case, a case stopped at the wall-time limit scaled by planned/completed time steps
    (the row's ``n_steps``/``n_steps_planned``; rows written before version -6 carry them only in the message)."""
    done, planned = row.get("n_steps"), row.get("n_steps_planned")
    if planned is None:
        match = re.search(r"after (\d+) of (\d+) time steps", row.get("message", ""))
        done, planned = (int(match.group(1)), int(match.group(2))) if match else (None, None)
    if not row.get("time_limited") or not done or not planned:
        return row["wall_time_s"]
    return row["wall_time_s"] * planned / done


if __name__ == "__main__":
    sys.exit(main())
