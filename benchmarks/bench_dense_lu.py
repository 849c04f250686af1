"""Benchmark: the dense linear solve of every Newton iteration of the steady solver (and of the transient mixed
solver deleted at ehl-2026.11-15, whose rough-case floor ``--floor-from`` computes from its recorded reports).

    python benchmarks/bench_dense_lu.py [--sizes 150 300 500 750 1000] [--repeats 7]
        [--floor-from benchmarks/results/ehl_mixed_random20_standard.json ...] [--out FILE]

The full-system Newton of ``ehl_dataset.solvers.newton`` solves one dense (N − 1) × (N − 1) system per iteration
(``scipy.linalg.solve``, LU with partial pivoting, ≈ ⅔ N³ flops; the elastic coupling K makes the Jacobian dense).
Measured here on random diagonally dominant matrices with one BLAS thread (the solver's own setting): the median
time per solve for each N, and the power law t = c·N^k fitted to them.

``--floor-from`` reads the transient solver's recorded benchmark reports (bench_ehl_mixed.py, before ehl-2026.11-15) and computes for each row the *floor*
n_steps × t(n_nodes) (n_steps: the steps run, at least the planned base run for a budget-stopped row): the time
a run of that many time steps on that grid would take if every step needed a single Newton iteration (one LU) and
nothing else cost anything. The measured per-row cost record (Newton iterations per
step) is reported next to it. The floor is what an algorithmic change of the time stepping alone cannot go below;
reaching ≈ 1 s per case needs the linear algebra itself to change (e.g. O(N log N) multilevel or Krylov solves).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

import numpy as np
import scipy.linalg
from threadpoolctl import threadpool_limits

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import RESULTS_DIR, emit_json, machine_info  # noqa: E402


def lu_solve_times(sizes, repeats: int, seed: int = 0) -> dict[int, float]:
    """Median wall time [s] of ``scipy.linalg.solve`` on an N × N diagonally dominant system, per N."""
    rng = np.random.default_rng(seed)
    out = {}
    with threadpool_limits(limits=1):
        for n in sizes:
            a = rng.standard_normal((n, n)) + n * np.eye(n)
            b = rng.standard_normal(n)
            times = []
            for _ in range(repeats):
                start = time.perf_counter()
                scipy.linalg.solve(a, b, check_finite=True, assume_a="gen")
                times.append(time.perf_counter() - start)
            out[int(n)] = statistics.median(times)
    return out


def power_law(times: dict[int, float]) -> tuple[float, float]:
    """(c, k) of the least-squares fit log t = log c + k log N."""
    n = np.log(np.array(list(times), dtype=float))
    t = np.log(np.array(list(times.values())))
    k, log_c = np.polyfit(n, t, 1)
    return float(np.exp(log_c)), float(k)


def floor_rows(report: dict, c: float, k: float) -> list[dict]:
    """Per row of a bench_ehl_mixed report: the one-LU-per-step floor and the measured cost record."""
    rows = []
    for row in report.get("rows", []):
        n_nodes, n_steps = row.get("n_nodes"), row.get("n_steps")
        if not n_nodes or not n_steps:
            continue
        n_steps = max(n_steps, row.get("n_steps_planned") or 0)  # a budget-stopped run still needs its planned steps
        floor = n_steps * c * n_nodes**k
        entry = {"case": row["case"], "n_nodes": n_nodes, "n_steps": n_steps, "floor_s": floor,
                 "cpu_time_s": row.get("cpu_time_s"), "converged": row.get("converged")}
        if row.get("newton_step_iterations") is not None:
            entry["newton_iterations_per_step"] = row["newton_step_iterations"] / n_steps
        rows.append(entry)
    return rows


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sizes", type=int, nargs="*", default=[150, 300, 500, 750, 1000])
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--floor-from", nargs="*", default=[])
    parser.add_argument("--out", default=str(RESULTS_DIR / "dense_lu.json"))
    args = parser.parse_args(argv)
    times = lu_solve_times(args.sizes, args.repeats)
    c, k = power_law(times)
    report = {"benchmark": "dense_lu", "median_solve_time_s": {str(n): t for n, t in times.items()},
              "power_law": {"c": c, "k": k, "formula": "t [s] = c * N**k"}, "repeats": args.repeats}
    for path in args.floor_from:
        rows = floor_rows(json.loads(Path(path).read_text()), c, k)
        floors = [r["floor_s"] for r in rows]
        report.setdefault("floors", {})[Path(path).name] = {
            "n_rows": len(rows), "mean_floor_s": statistics.fmean(floors) if floors else None,
            "median_floor_s": statistics.median(floors) if floors else None,
            "max_floor_s": max(floors, default=None), "rows": rows}
    report["machine"] = machine_info()
    emit_json(report, args.out, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
