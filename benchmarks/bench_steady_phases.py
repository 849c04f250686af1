"""Benchmark: where a warm steady smooth solve spends its CPU time — the coarse-grid continuation against the Newton
iteration on the level's grid, and the linear solves in each.

    python benchmarks/bench_steady_phases.py [--n 200] [--seed 45] [--out benchmarks/results/steady_phases.json]

The first ``--n`` contacts of ``benchmarks/bench_stage1_floor.py``'s seeded sample (paper-factorial axes, ATF,
``standard``, smooth), solved afresh in one warm process twice: with the default linear solve (the banded
preconditioner on systems of at least ``newton.BANDED_MIN_UNKNOWNS`` unknowns) and as before it
(``newton.BANDED_PRECONDITIONER = False``, ``steady.START_FILM_EXPONENT = 0``). The Newton solves and the linear
solves are timed (``time.process_time``) by wrapping ``steady.newton_solve`` and ``newton.LinearSolver.solve``; a
solve on the level's grid is "fine", every other one (the continuation's grid) "coarse". Reported per contact
(means): CPU time, Newton iterations and linear-solve CPU per phase, and the CPU time of one linear solve on each
grid. The load average is recorded at the start and the end.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from collections import defaultdict
from pathlib import Path

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solver import SOLVER_VERSION, solve_contact
from ehl_dataset.solvers import newton, steady
from ehl_dataset.solvers.levels import get_level

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import machine_info  # noqa: E402
from bench_stage1_floor import sample_rows  # noqa: E402


def load_average() -> list[float] | None:
    return [round(v, 2) for v in os.getloadavg()] if hasattr(os, "getloadavg") else None


def measure(rows: np.ndarray, lub) -> dict:
    """Per-phase CPU time and iterations of the smooth solves of ``rows`` (means per contact, ms)."""
    totals = defaultdict(float)
    current = {"phase": "coarse", "fine_nodes": 0}
    newton_solve = steady.newton_solve
    linear_solve = newton.LinearSolver.solve

    def timed_newton(problem, *args, **kwargs):
        phase = "fine" if problem.x.size == current["fine_nodes"] else "coarse"
        start = time.process_time()
        out = newton_solve(problem, *args, **kwargs)
        totals[f"{phase}_newton_cpu_ms"] += (time.process_time() - start) * 1e3
        totals[f"{phase}_iterations"] += out.iterations
        return out

    def timed_linear(self, system, rhs):
        phase = "fine" if rhs.size + 1 == current["fine_nodes"] else "coarse"
        start = time.process_time()
        out = linear_solve(self, system, rhs)
        totals[f"{phase}_linear_cpu_ms"] += (time.process_time() - start) * 1e3
        totals[f"{phase}_linear_solves"] += 1
        return out

    steady.newton_solve, newton.LinearSolver.solve = timed_newton, timed_linear
    cpus = []
    try:
        for row in rows:
            case = ContactCase(*row)
            state = lub.state(case.temperature)
            scales = steady.ContactScales.of(case, state)
            current["fine_nodes"] = steady.steady_grid(get_level("standard"), h_c=steady.moes_h_c(case, state, scales)).size
            steady._STEADY_CACHE.clear()
            start = time.process_time()
            solve_contact(case, lub, "standard", "auto", model="smooth")
            cpus.append((time.process_time() - start) * 1e3)
    finally:
        steady.newton_solve, newton.LinearSolver.solve = newton_solve, linear_solve
    n = len(rows)
    out = {key: value / n for key, value in sorted(totals.items())}
    for phase in ("coarse", "fine"):
        solves = totals[f"{phase}_linear_solves"]
        out[f"{phase}_ms_per_linear_solve"] = totals[f"{phase}_linear_cpu_ms"] / solves if solves else None
    out.update({"cpu_ms_mean": float(np.mean(cpus)), "cpu_ms_median": float(np.median(cpus))})
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=200, help="contacts")
    parser.add_argument("--seed", type=int, default=45)
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "steady_phases.json"))
    args = parser.parse_args(argv)
    lub = load_lubricant("atf")
    rows = sample_rows(max(args.n, 1), args.seed)[: args.n].copy()
    rows[:, 5:] = 0.0
    solve_contact(ContactCase(*rows[0]), lub, "standard", "auto", model="smooth")  # numba code loaded
    report = {"benchmark": "steady_phases", "solver_version": SOLVER_VERSION,
              "command": "python benchmarks/bench_steady_phases.py " + " ".join(argv if argv is not None
                                                                               else sys.argv[1:]),
              "machine": {**machine_info(), "load_average_start": load_average()}, "contacts": args.n,
              "note": "means per contact; CPU times of the solving process (time.process_time) on a shared machine"}
    report["default"] = measure(rows, lub)
    exponent = steady.START_FILM_EXPONENT
    newton.BANDED_PRECONDITIONER, steady.START_FILM_EXPONENT = False, 0.0
    try:
        report["previous"] = measure(rows, lub)
    finally:
        newton.BANDED_PRECONDITIONER, steady.START_FILM_EXPONENT = True, exponent
    report["machine"]["load_average_end"] = load_average()
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(report, indent=1) + "\n")
    for key in ("default", "previous"):
        print(key, {k: round(v, 2) for k, v in report[key].items() if v is not None}, file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
