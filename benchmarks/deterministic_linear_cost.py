"""Benchmark: the operation counts and CPU time of the deterministic solver's Newton–Krylov solves on short `fast`
runs, one row per point and installed model version (docs/explanation/mixed-regime.md, "Cost").

    python benchmarks/deterministic_linear_cost.py
    python benchmarks/deterministic_linear_cost.py --band 8 2.0GPa-5mm-5ms-SR0.4-100C-Rq0.3   # another band, one point
    PYTHONPATH=/path/to/other/checkout python benchmarks/deterministic_linear_cost.py   # another version, same file

Each point runs ``solve_deterministic`` at the ``fast`` level's options for 2 passes (0.5 averaged), the same
roughness for every version. The counts (Newton and GMRES iterations, factorisations of the banded preconditioner,
round-off stops) do not depend on the machine's load; the process CPU time does, a little (caches shared with other
jobs): the load average is recorded with each row. Rows of the same point, version and band are replaced. Writes
benchmarks/results/deterministic_linear_cost.json.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time
from pathlib import Path

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solvers.deterministic import (MODEL_VERSION, DeterministicOptions, deterministic_options,
                                               solve_deterministic)

OUT = Path(__file__).resolve().parent / "results" / "deterministic_linear_cost.json"
POINTS = {
    "2.0GPa-5mm-5ms-SR0.4-100C-Rq0.3": (2.0, 5.0, 5.0, 0.4, 100.0, 0.3, 0.3),
    "1.5GPa-5mm-1ms-SR1.0-100C-Rq0.4": (1.5, 5.0, 1.0, 1.0, 100.0, 0.4, 0.4),
    "0.5GPa-5mm-5ms-SR0.3-90C-Rq0.3": (0.5, 5.0, 5.0, 0.3, 90.0, 0.3, 0.3),
}
"""A heavily loaded point of the random sample (draw 32 of seed 1), validation case H's conditions and case A's."""
COUNTS = ("n_steps", "newton_iterations", "gmres_iterations", "factorisations", "round_off_stops", "substep_steps")


def run_point(name: str, band: int) -> dict:
    case = ContactCase.from_engineering(*POINTS[name])
    state = load_lubricant("atf").state(case.temperature)
    options = deterministic_options("fast", max_passes=2.0, min_average_passes=0.5, mu_sem_target=1.0, band=band)
    start = time.process_time()
    # the same roughness for every version: the baseline profile the recorded rows ran on, not the default
    result = solve_deterministic(case, state, Effects.full(), options, roughness=baseline_profile())
    cpu = time.process_time() - start
    row = {"point": name, "inputs": POINTS[name], "model_version": MODEL_VERSION, "band": band, "converged": result.converged,
           "mu": result.mu, "cpu_time_s": cpu, "load_average_1min": os.getloadavg()[0]}
    row.update({key: int(result.extra[key]) for key in COUNTS})
    row["gmres_per_newton"] = row["gmres_iterations"] / max(row["newton_iterations"], 1)
    row["newton_per_step"] = row["newton_iterations"] / max(row["n_steps"], 1)
    return row


def warm_up() -> None:
    """A short run, so that numba's compilation (cached per checkout) is not timed."""
    case = ContactCase.from_engineering(*POINTS["0.5GPa-5mm-5ms-SR0.3-90C-Rq0.3"])
    options = deterministic_options("fast", ramp_passes=0.1, startup_passes=0.1, min_average_passes=0.1,
                                    max_passes=0.4, mu_sem_target=1.0)
    solve_deterministic(case, load_lubricant("atf").state(case.temperature), Effects.full(), options,
                        roughness=baseline_profile())


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("points", nargs="*", help=f"some of {', '.join(POINTS)} (default: all)")
    parser.add_argument("--band", type=int, default=DeterministicOptions().band,
                        help="half-width of the preconditioner's inverse-kernel band (DeterministicOptions.band)")
    args = parser.parse_args(argv)
    unknown = sorted(set(args.points) - set(POINTS))
    if unknown:
        parser.error(f"unknown points {unknown}; choose from {list(POINTS)}")
    names = args.points or list(POINTS)
    warm_up()
    record = json.loads(OUT.read_text()) if OUT.exists() else {"benchmark": "deterministic_linear_cost", "rows": []}
    for name in names:
        row = run_point(name, args.band)
        key = (name, MODEL_VERSION, args.band)
        record["rows"] = [r for r in record["rows"] if (r["point"], r["model_version"], r["band"]) != key]
        record["rows"].append(row)
        record["machine"] = {"platform": platform.platform(), "cpu_count": os.cpu_count(),
                             "python": platform.python_version(), "numpy": np.__version__}
        OUT.write_text(json.dumps(record, indent=1) + "\n")
        print(json.dumps(row), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
