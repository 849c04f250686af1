"""Benchmark: where the CPU time of a cold smooth ``gearloss contact solve`` goes, phase by phase.

    python benchmarks/bench_cold_phases.py [--repeats 7] [--out benchmarks/results/cold_phases.json]

Each repeat is a fresh interpreter (this script with ``--child``) doing what the command does, in the order it does
it, with the CPU time of the process (``time.process_time``, every thread) read between the phases: the interpreter
start (up to the script's first line), ``import numpy``, ``import numba``, ``import scipy.linalg``, the command line
(``workflows.cli`` and the contact group), the rest of ``ehl_dataset.solver`` (the package's own modules), numba's
first-dispatch set-up (its typing and target registries, ``cpu_target.target_context.refresh()``, done once per
process before the first compiled function runs, whether it is loaded from the cache or compiled), resolving the
contact (lubricant, level, effect plan: one cached kernel), the first solve (the solver's other cached kernels, the
per-process tables, the solve), a second solve of the same contact with the per-process solution cache emptied (the
solve alone), and the end of the process as the command ends it (:func:`gc.freeze`, then the interpreter's exit;
CPU time of the child as its parent sees it minus its last reading). Medians over the repeats, with the load average.
The contact is the cold case of ``bench_stage1_floor.py`` (1 GPa, 20 mm, 5 m/s, SR 0.2, 90 °C, ATF, ``standard``).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import time
from pathlib import Path

PHASES = ("interpreter_start", "numpy", "numba", "scipy_linalg", "command_line", "ehl_dataset_solver",
          "numba_first_dispatch_setup", "resolve_contact", "first_solve", "second_solve")


def child() -> None:
    marks = [time.process_time()]
    import numpy  # noqa: F401
    marks.append(time.process_time())
    import numba  # noqa: F401
    marks.append(time.process_time())
    import scipy.linalg  # noqa: F401
    marks.append(time.process_time())
    import workflows.cli  # noqa: F401
    import workflows.cli_contact  # noqa: F401
    marks.append(time.process_time())
    from ehl_dataset.model.contact import ContactCase
    from ehl_dataset.solver import solve_problem
    from ehl_dataset.solvers import steady
    from ehl_dataset.solvers.problem import resolve_contact
    marks.append(time.process_time())
    from numba.core.registry import cpu_target

    cpu_target.target_context.refresh()
    marks.append(time.process_time())
    problem = resolve_contact(ContactCase.from_engineering(1.0, 20.0, 5.0, 0.2, 90.0, 0.0, 0.0), "atf", "standard",
                              "auto")
    marks.append(time.process_time())
    first = solve_problem(problem)
    marks.append(time.process_time())
    steady._STEADY_CACHE.clear()
    second = solve_problem(problem)
    marks.append(time.process_time())
    assert first.converged and second.mu == first.mu
    phases = dict(zip(PHASES, [marks[0]] + [b - a for a, b in zip(marks, marks[1:])]))
    print(json.dumps({"phases": phases, "process_time_at_end": time.process_time(), "modules": len(sys.modules)}))
    sys.stdout.flush()
    import gc

    gc.freeze()  # as gearloss contact solve ends


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "cold_phases.json"))
    parser.add_argument("--child", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args(argv)
    if args.child:
        child()
        return 0
    runs = []
    load_start = list(os.getloadavg())
    for _ in range(args.repeats):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        out = subprocess.run([sys.executable, __file__, "--child"], check=True, capture_output=True, text=True,
                             cwd=Path(__file__).resolve().parents[1]).stdout
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        run = json.loads(out.strip().splitlines()[-1])
        total = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
        run["phases"]["exit"] = total - run["process_time_at_end"]
        run["total_cpu_s"] = total
        runs.append(run)
    names = [*PHASES, "exit"]
    report = {"benchmark": "cold_phases",
              "command": "python benchmarks/bench_cold_phases.py " + " ".join(argv if argv is not None
                                                                           else sys.argv[1:]),
              "machine": {"cpu_count": os.cpu_count(), "python": sys.version.split()[0],
                          "load_average_start": load_start, "load_average_end": list(os.getloadavg()),
                          "bytecode_written": not os.environ.get("PYTHONDONTWRITEBYTECODE")},
              "unit": "s of CPU time of the child process, median over the repeats",
              "phases_cpu_s": {n: statistics.median(r["phases"][n] for r in runs) for n in names},
              "total_cpu_s": statistics.median(r["total_cpu_s"] for r in runs),
              "repeats": args.repeats, "modules_loaded": statistics.median(r["modules"] for r in runs)}
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(report, indent=1) + "\n")
    for n in names:
        print(f"{n:28s} {report['phases_cpu_s'][n] * 1e3:7.0f} ms", file=sys.stderr)
    print(f"{'total':28s} {report['total_cpu_s'] * 1e3:7.0f} ms  (load {report['machine']['load_average_end'][0]:.1f})",
          file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
