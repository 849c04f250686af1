"""Benchmark: steady smooth EHL solve time per accuracy level and grid size.

    python benchmarks/bench_ehl_smooth.py [--repeats 3] [--out benchmarks/results/ehl_smooth.json]

Cases: 12 points of the paper's factorial (docs/reference/dataset-format.md) spanning p_h, r_eq, u_r, SR and T, ATF lubricant, smooth
steady effects. Reports per level the median / max wall time per solve (one BLAS thread, the solver's own
setting), the median number of grid nodes and Newton iterations, and the machine.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
from pathlib import Path

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers.levels import LEVELS

# _common.py sits next to this file (sys.path: see bench_ehl_mixed.py)
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import machine_info  # noqa: E402

CASES = [(0.5, 5, 1, 0.0, 25), (0.5, 80, 20, 1.0, 100), (1.0, 10, 2, 0.2, 50), (1.0, 40, 10, 0.7, 75),
         (1.5, 20, 5, 0.4, 100), (1.5, 5, 15, 1.0, 25), (2.0, 80, 1, 0.1, 75), (2.0, 10, 20, 0.05, 50),
         (2.5, 80, 1, 1.0, 25), (2.5, 5, 20, 1.0, 100), (2.5, 40, 5, 0.0, 50), (0.5, 20, 15, 0.7, 50)]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--levels", nargs="*", default=list(LEVELS))
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "ehl_smooth.json"))
    args = parser.parse_args(argv)
    lub = load_lubricant("atf")
    plan = Effects.smooth_steady(benchmark=True)
    solve_contact(ContactCase.from_engineering(*CASES[0]), lub, "fast", plan)  # JIT/cache warm-up
    report = {"benchmark": "ehl_smooth", "cases": CASES, "repeats": args.repeats, "levels": {},
              "machine": {**machine_info(),
                          "load_average_1min": os.getloadavg()[0] if hasattr(os, "getloadavg") else None}}
    for name in args.levels:
        times, nodes, iterations, converged = [], [], [], 0
        for case_args in CASES:
            case = ContactCase.from_engineering(*case_args)
            best = []
            for _ in range(args.repeats):
                start = time.perf_counter()
                res = solve_contact(case, lub, name, plan)
                best.append(time.perf_counter() - start)
            times.append(statistics.median(best))
            nodes.append(res.extra["n_nodes"])
            iterations.append(res.iterations)
            converged += bool(res.converged)
        report["levels"][name] = {"median_time_s": statistics.median(times), "max_time_s": max(times),
                                  "mean_time_s": statistics.fmean(times), "median_nodes": statistics.median(nodes),
                                  "max_nodes": max(nodes), "median_iterations": statistics.median(iterations),
                                  "converged": converged, "n_cases": len(CASES)}
        print(f"{name:10s} median {report['levels'][name]['median_time_s'] * 1e3:7.1f} ms  "
              f"max {max(times) * 1e3:7.1f} ms  nodes {statistics.median(nodes):.0f} (max {max(nodes)})  "
              f"iterations {statistics.median(iterations):.0f}  converged {converged}/{len(CASES)}")
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(report, indent=2))
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
