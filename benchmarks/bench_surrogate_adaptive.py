"""Benchmark: adaptive sampling against the factorial for the learned friction surrogate, side by side.

1. The factorial route: ``run_lubricant_fit`` of the factorial (default ``quick``, 324 points) with the learned
   form and the off-grid validation sample (200 seeded random contacts in the factorial's ranges); its off-grid
   median and 90th percentile of |Δμ/μ| become the targets.
2. The adaptive route: the same off-grid sample (same seed, so the same points: its solved file is reused), a
   Sobol' start and batches where the ensemble disagrees most, until the targets are met or the budget is spent.

Recorded: solves and wall time of each route (stage 1 of the factorial from its store's sessions, so a reused run
directory reports the time it was computed in), the off-grid errors and interval coverage of both fits, every
adaptive round, the load average. Usage::

    python benchmarks/bench_surrogate_adaptive.py --work-dir DIR [--factorial quick] [--workers 1] [--budget 324]
        [--initial 32] [--batch 16] [--out benchmarks/results/surrogate_adaptive.json]
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import sys
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import machine_info  # noqa: E402


def _session_time(path: Path) -> float:
    from ehl_dataset.dataset.store import read_metadata

    return float(sum(s.get("wall_time_s") or 0.0 for s in read_metadata(path)["sessions"]))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--work-dir", required=True)
    parser.add_argument("--factorial", default="quick")
    parser.add_argument("--workers", type=int, default=1)
    parser.add_argument("--budget", type=int, default=324)
    parser.add_argument("--initial", type=int, default=32)
    parser.add_argument("--batch", type=int, default=16)
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "surrogate_adaptive.json"))
    args = parser.parse_args(argv)

    from ehl_dataset.dataset.factorial import load_factorial
    from ehl_dataset.model.lubricant import load_lubricant
    from surrogate.dataset_io import load_dataset
    from workflows import adaptive
    from workflows.pipeline import check_inputs, run_lubricant_fit
    from workflows.surrogate_stage import fit_and_write

    warnings.simplefilter("ignore")
    work = Path(args.work_dir)
    factorial = load_factorial(args.factorial)
    load_start = os.getloadavg()[0]
    grid_dir = work / "grid"
    started = time.perf_counter()
    grid = run_lubricant_fit("atf", factorial, out_dir=grid_dir, workers=args.workers, form="learned",
                             offgrid_points=200, progress="none").to_dict()
    grid_wall = time.perf_counter() - started
    grid_fit = grid["stages"]["fit"]
    targets = grid_fit["offgrid"]["overall"]
    run = check_inputs(factorial, out_dir=grid_dir, lubricant="atf", design=None)

    adaptive_dir = work / "adaptive"
    adaptive_dir.mkdir(parents=True, exist_ok=True)
    if not (adaptive_dir / "offgrid.h5").exists():
        shutil.copy(grid_dir / "offgrid.h5", adaptive_dir / "offgrid.h5")
    adaptive.INITIAL_POINTS, adaptive.BATCH_POINTS = args.initial, args.batch
    rounds = []
    started = time.perf_counter()
    result = adaptive.run_adaptive(adaptive_dir, factorial, load_lubricant("atf"), level=run.level,
                                   effects=run.effects, model=run.model, budget=args.budget, initial=args.initial,
                                   batch=args.batch, offgrid_table=load_dataset(adaptive_dir / "offgrid.h5").table,
                                   target_median=targets["median_rel_err_mu"], target_p90=targets["p90_rel_err_mu"],
                                   workers=args.workers, progress="none", log=rounds.append)
    adaptive_wall = time.perf_counter() - started
    batches = [adaptive_dir / "adaptive" / name for name in result.batch_files]
    _, fit_details, _ = fit_and_write(batches, adaptive_dir / "atf_adaptive_learned.json", form="learned",
                                      offgrid_path=adaptive_dir / "offgrid.h5")
    out = {
        "benchmark": "surrogate_adaptive",
        "machine": {**machine_info(), "load_average_1min_at_start": load_start,
                    "load_average_1min_at_end": os.getloadavg()[0]},
        "workers": args.workers,
        "factorial": {"name": factorial.name, "solves": grid["stages"]["dataset"]["n_points"],
                      "stage1_wall_time_s_from_sessions": _session_time(grid_dir / "dataset.h5"),
                      "this_call_wall_time_s": grid_wall, "offgrid": grid_fit["offgrid"]},
        "adaptive": {"solves": result.solves, "stopped": result.stopped, "initial": args.initial,
                     "batch": args.batch, "budget": args.budget, "wall_time_s": adaptive_wall,
                     "solve_time_s_from_sessions": sum(_session_time(p) for p in batches),
                     "rounds": result.rounds, "offgrid": fit_details["offgrid"]},
        "targets": {"median_rel_err_mu": targets["median_rel_err_mu"], "p90_rel_err_mu": targets["p90_rel_err_mu"]},
    }
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(out, indent=1) + "\n")
    print(json.dumps({k: out[k] for k in ("factorial", "adaptive", "targets")}, indent=1)[:3000])
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
