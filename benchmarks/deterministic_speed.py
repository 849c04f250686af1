"""Benchmark: the deterministic mixed solver's time per case on random factorial points, one core.

The comparison with the transient mixed solver on the same points in the same run is recorded in
``benchmarks/results/deterministic_speed_fast_det-2026.11-13.json`` (EHL solver ehl-2026.11-14, commit 8019d33): that solver was
deleted at ehl-2026.11-15, so this script now runs the deterministic side only
(a new run under the current version writes its own rows; the transient rows of the recorded file are not reused).

    python benchmarks/deterministic_speed.py                 # the first 50 draws of the seed-1 random sample
    python benchmarks/deterministic_speed.py --n 20          # fewer; given again, it resumes and runs the rest
    python benchmarks/deterministic_speed.py --shard 0/2 & python benchmarks/deterministic_speed.py --shard 1/2
    python benchmarks/deterministic_speed.py --merge          # the shards' rows into the one results file

The points are the first ``--n`` draws of ``bench_ehl_mixed.random_cases(200, seed=1)`` (the 200-point sweep of
``benchmarks/results/ehl_mixed_random200_fast_deterministic.json``). For each point, one after the other in this
process, ``solve_contact(..., level, model="deterministic")`` gets ``--time-limit-s``; a stopped run counts at its time (the medians are lower bounds where
runs stop). Rows are written after each solve (resumable; rows of another EHL solver or deterministic model version
are not reused; ``--shard I/N`` runs every N-th point from the I-th into its own file, and every process skips the
points any results file of the level already holds). Writes ``benchmarks/results/deterministic_speed_<level>.json``:
per-point rows (wall and process CPU time, μ, converged, route), medians and means (the per-point time ratio
deterministic/transient where a file holds both).
"""

from __future__ import annotations

import argparse
import json
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solver import SOLVER_VERSION, solve_contact
from ehl_dataset.solvers.deterministic import MODEL_VERSION

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import RESULTS_DIR, machine_info, write_report  # noqa: E402
from bench_ehl_mixed import random_cases  # noqa: E402

SOLVERS = {"deterministic": {"model": "deterministic"}}


def solve_row(point, solver: str, level: str, time_limit_s: float, lub) -> dict:
    case = ContactCase.from_engineering(*point)
    wall, cpu = time.perf_counter(), time.process_time()
    res = solve_contact(case, lub, level, time_limit_s=time_limit_s, **SOLVERS[solver])
    return {"case": list(point), "solver": solver, "converged": bool(res.converged),
            "mu": float(res.mu) if res.mu is not None else math.nan, "lambda_bar": float(res.lambda_bar),
            "route": res.extra.get("route"), "time_limited": bool(res.extra.get("time_limited", False)),
            "message": res.message or "", "wall_time_s": time.perf_counter() - wall,
            "cpu_time_s": time.process_time() - cpu}


def summarise(rows: list[dict]) -> dict:
    """Per solver: points, converged, time-limited, median / mean / 90th-percentile CPU time; where the rows hold the
    transient solver's too (the recorded file), over the points both solved, with the median time ratio."""
    out: dict = {}
    names = sorted({r["solver"] for r in rows}, key=lambda s: s != "deterministic")
    by = {s: {tuple(r["case"]): r for r in rows if r["solver"] == s} for s in names}
    points = [c for c in by.get("deterministic", {}) if all(c in by[s] for s in names)]
    for s in names:
        t = [by[s][c]["cpu_time_s"] for c in points]
        out[s] = {"points": len(t), "converged": sum(by[s][c]["converged"] for c in points),
                  "time_limited": sum(by[s][c]["time_limited"] for c in points),
                  "median_cpu_time_s": statistics.median(t) if t else math.nan,
                  "mean_cpu_time_s": statistics.fmean(t) if t else math.nan,
                  "p90_cpu_time_s": float(np.percentile(t, 90)) if t else math.nan}
    if "transient" in by:
        ratio = [by["deterministic"][c]["cpu_time_s"] / by["transient"][c]["cpu_time_s"] for c in points]
        out["paired_points"] = len(points)
        out["median_time_ratio_deterministic_over_transient"] = statistics.median(ratio) if ratio else math.nan
    return out


def _rows_of(path: Path) -> list[dict]:
    """The rows of a results file made under the current EHL solver and deterministic model versions."""
    if not path.exists():
        return []
    old = json.loads(path.read_text(encoding="utf-8"))
    if old.get("solver_version") != SOLVER_VERSION or old.get("model_version") != MODEL_VERSION:
        return []
    return old["rows"]


def _write(path: Path, rows: list[dict], args) -> None:
    write_report(path, {"benchmark": "deterministic_speed", "level": args.level, "sample": "random seed 1",
                        "time_limit_s": args.time_limit_s, "solver_version": SOLVER_VERSION,
                        "model_version": MODEL_VERSION, "summary": summarise(rows), "rows": rows,
                        "machine": machine_info()})


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--n", type=int, default=50)
    parser.add_argument("--level", default="fast")
    parser.add_argument("--time-limit-s", type=float, default=600.0)
    parser.add_argument("--shard", default=None, help="I/N: every N-th point from the I-th, into its own file")
    parser.add_argument("--merge", action="store_true", help="merge the shard files into the results file")
    args = parser.parse_args(argv)
    main_file = RESULTS_DIR / f"deterministic_speed_{args.level}.json"

    def siblings() -> list[Path]:  # every results file of the level: the merged one and the shards'
        return [main_file, *sorted(RESULTS_DIR.glob(f"deterministic_speed_{args.level}_shard*.json"))]

    if args.merge:
        merged = {(tuple(r["case"]), r["solver"]): r for path in siblings() for r in _rows_of(path)}
        _write(main_file, list(merged.values()), args)
        print(json.dumps(summarise(list(merged.values())), indent=1))
        return 0
    first, every = (int(v) for v in args.shard.split("/")) if args.shard else (0, 1)
    out = RESULTS_DIR / f"deterministic_speed_{args.level}_shard{first}of{every}.json" if args.shard else main_file
    rows = _rows_of(out)
    lub = load_lubricant("atf")
    for i, point in enumerate(random_cases(200, 1)[:args.n]):
        if i % every != first:
            continue
        for solver in SOLVERS:
            done = {(tuple(r["case"]), r["solver"]) for path in siblings() for r in _rows_of(path)}
            if (tuple(point), solver) in done:
                continue
            row = solve_row(point, solver, args.level, args.time_limit_s, lub)
            rows.append(row)
            print(f"{i:3d} {solver:13s} {point} mu={row['mu']:.4g} conv={row['converged']} "
                  f"{row['cpu_time_s']:.1f} s", flush=True)
            _write(out, rows, args)
    print(json.dumps(summarise(rows), indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
