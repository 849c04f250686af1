"""Benchmark of the dataset store and runner: JSON to ``benchmarks/results/store.json``.

Measures
1. the store's own cost per point: ``DatasetStore.record`` + its share of ``flush`` (quick factorial, in process),
   and for the paper's 42,000-row file: creation time, file size, full-table read time;
2. the runner's overhead: points/s with a near-zero-cost stand-in solver (workers 0, 1, 2) — the ceiling the
   pipeline itself imposes;
3. points/s on the quick factorial with the real EHL solver at its level (``fast``) with 1 and 2 workers, and the
   ok/failed counts (``--skip-solver`` leaves this out; ``--sample N`` times a seeded random sample of N points).

Usage: ``python benchmarks/bench_store.py [--repeats 5] [--skip-solver | --sample N] [--out FILE.json]``
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from ehl_dataset.dataset.factorial import canonical_json, load_factorial
from ehl_dataset.dataset.runner import execute, run_factorial, solver_config
from ehl_dataset.dataset.store import OK, DatasetStore, read_table
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solvers.result import ContactResult

# _common.py sits next to this file (sys.path: see bench_ehl_mixed.py)
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import machine_info  # noqa: E402


def instant_solve(case, lubricant, level="fast", effects="auto"):
    """A stand-in that costs ~nothing (to expose the pipeline's own overhead)."""
    return ContactResult(mu=0.05, h_min=1e-7, h_central=1.2e-7, p_max=case.p_h, converged=True, iterations=1,
                         wall_time=0.0, level=level, effects={"mode": effects, "reasons": {"lambda_bar": 1.0}},
                         lambda_bar=1.0)


def machine() -> dict:
    import h5py

    return {**machine_info(), "h5py": h5py.__version__, "hdf5": h5py.version.hdf5_version,
            "load_average_1_5_15": list(os.getloadavg())}


def store_overhead(tmp: Path, repeats: int) -> dict:
    plan = load_factorial("quick")
    lub = load_lubricant(plan.lubricant)
    points = plan.points()
    record = ContactResult(mu=0.05, h_min=1e-7, h_central=1.2e-7, p_max=1e9, converged=True, iterations=12,
                           wall_time=0.3, level="fast", effects=json.loads(_PLANNER_LIKE_EFFECTS),
                           lambda_bar=1.0).to_record()
    per_point = []
    for r in range(repeats):
        path = tmp / f"overhead_{r}.h5"
        store = DatasetStore.create(path, points, factorial=plan.to_dict(), solver={"function": "bench"},
                                    lubricant=lub.to_json_dict(), overwrite=True)
        t0 = time.perf_counter()
        for i in range(plan.size):
            store.record(i, status=OK, record=record, worker="host:1", worker_time=0.3)
            if (i + 1) % 32 == 0:  # results arrive in flush batches of a few seconds; 32 rows per flush here
                store.flush()
        store.flush()
        elapsed = time.perf_counter() - t0
        store.close()
        per_point.append(elapsed / plan.size)
    return {"factorial": "quick", "n_points": plan.size, "rows_per_flush": 32, "repeats": repeats,
            "median_store_time_per_point_s": statistics.median(per_point),
            "all_store_time_per_point_s": per_point}


def paper_file(tmp: Path) -> dict:
    plan = load_factorial("paper2009")
    lub = load_lubricant(plan.lubricant)
    path = tmp / "paper.h5"
    t0 = time.perf_counter()
    DatasetStore.create(path, plan.points(), factorial=plan.to_dict(), solver={"function": "bench"},
                        lubricant=lub.to_json_dict(), overwrite=True).close()
    create = time.perf_counter() - t0
    t0 = time.perf_counter()
    table = read_table(path, status=None)
    read = time.perf_counter() - t0
    return {"n_points": plan.size, "create_s": create, "file_size_bytes": path.stat().st_size,
            "bytes_per_point": path.stat().st_size / plan.size, "read_table_all_rows_s": read,
            "rows_read": len(table)}


def sampled_store(path: Path, sample: int, solver) -> DatasetStore:
    """A store holding a seeded random sample of the quick factorial's points (same sample every time)."""
    plan = load_factorial("quick")
    lub = load_lubricant(plan.lubricant)
    rows = np.sort(np.random.default_rng(2009).choice(plan.size, size=sample, replace=False))
    points = plan.points()[rows]
    factorial = {**plan.to_dict(), "name": f"quick-sample{sample}", "sample_rows": rows.tolist(),
                 "points_sha256": hashlib.sha256(np.ascontiguousarray(points).tobytes()).hexdigest()}
    return DatasetStore.create(path, points, factorial=factorial, solver=solver_config(solver, plan.level, "auto"),
                               lubricant=json.loads(canonical_json(lub.to_json_dict())), overwrite=True)


def pipeline(tmp: Path, solver, workers_list, repeats: int, label: str, sample: int | None = None) -> list[dict]:
    out = []
    for workers in workers_list:
        rates, ok, failed, summaries = [], None, None, []
        for r in range(repeats):
            if sample:
                with sampled_store(tmp / f"{label}_{workers}_{r}.h5", sample, solver) as store:
                    summary = execute(store, solver=solver, workers=workers, progress="none")
            else:
                summary = run_factorial(tmp / f"{label}_{workers}_{r}.h5", "quick", workers=workers,
                                        solver=solver, overwrite=True, progress="none")
            rates.append(summary.points_per_s)
            ok, failed = summary.ok, summary.failed
            summaries.append(summary.to_dict())
        table = read_table(tmp / f"{label}_{workers}_{repeats - 1}.h5", status=None)
        solver_times = table.loc[table["status"] == "ok", "wall_time"]
        out.append({"solver": label, "workers": workers, "repeats": repeats,
                    "points": summaries[-1]["n_points"], "sample_of_quick": sample,
                    "median_points_per_s": statistics.median(rates), "all_points_per_s": rates,
                    "ok": ok, "failed": failed,
                    "median_solver_wall_time_s": float(np.median(solver_times)) if len(solver_times) else math.nan,
                    "store_time_per_point_s": summaries[-1]["store_time_per_point_s"],
                    "errors": sorted(set(table.loc[table["status"] == "failed", "error"]))[:5]})
        print(json.dumps(out[-1]), flush=True)
    return out


_PLANNER_LIKE_EFFECTS = json.dumps({"compressibility": True, "mode": "auto", "roughness": False,
                                    "shear_thinning": True, "transient": False,
                                    "reasons": {"decisions": {"roughness": "x" * 150, "transient": "y" * 60,
                                                              "shear_thinning": "z" * 70, "compressibility": "w" * 60},
                                                "numbers": {f"n{i}": 1.0 / 3.0 for i in range(11)}}})


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--solver-repeats", type=int, default=1)
    parser.add_argument("--skip-solver", action="store_true")
    parser.add_argument("--sample", type=int, default=0,
                        help="with the real solver, time a seeded random sample of N quick points (0: all 324)")
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "store.json"))
    args = parser.parse_args()
    result = {"benchmark": "bench_store", "machine": machine(), "started": time.strftime("%Y-%m-%dT%H:%M:%SZ",
                                                                                         time.gmtime())}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        result["store_overhead"] = store_overhead(tmp, args.repeats)
        print(json.dumps(result["store_overhead"]), flush=True)
        result["paper_file"] = paper_file(tmp)
        print(json.dumps(result["paper_file"]), flush=True)
        result["pipeline_instant_solver"] = pipeline(tmp, instant_solve, [0, 1, 2], args.repeats, "instant")
        if not args.skip_solver:
            result["quick_real_solver"] = pipeline(tmp, "ehl_dataset.solver:solve_contact", [1, 2],
                                                   args.solver_repeats, "solve_contact", args.sample or None)
    result["machine"]["load_average_end"] = list(os.getloadavg())
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(result, indent=1) + "\n")
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
