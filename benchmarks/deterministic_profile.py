"""Where the time of one deterministic run goes: cProfile of ``solve_contact(..., model="deterministic")`` on one
contact (default: the median-time point of benchmarks/results/deterministic_speed_fast_det-2026.11-13.json, 0.5 GPa, 80 mm, 20 m/s,
SR 0.7, 25 °C, Rq 1/1 µm: five periodic windows at `fast`), reported as the cumulative time of the functions that
matter and their call counts. cProfile adds a per-call overhead, so the shares of many small calls are upper
bounds; the run's own time without the profiler is in the speed benchmark.

    python benchmarks/deterministic_profile.py [--case P_GPA R_MM U_MS SR T_C RQ1_UM RQ2_UM] [--level fast]
"""

from __future__ import annotations

import argparse
import cProfile
import pstats
import time

from _common import RESULTS_DIR, emit_json, machine_info

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.solver import SOLVER_VERSION, solve_contact
from ehl_dataset.solvers.deterministic import MODEL_VERSION

WATCHED = {
    "gmres (krylov.py)": ("krylov.py", "gmres"),
    "preconditioner apply (krylov.py)": ("krylov.py", "apply"),
    "banded solve of the preconditioner": ("krylov.py", "_solve"),
    "Jacobian action (deterministic.py)": ("deterministic.py", "jacobian_product"),
    "deflection by FFT (deterministic.py)": ("deterministic.py", "deflection"),
    "scipy.fft dispatch and pocketfft": ("_backend.py", "__ua_function__"),
    "scipy.ndimage.convolve1d": ("_filters.py", "convolve1d"),
    "residual evaluation (deterministic.py)": ("deterministic.py", "evaluate"),
    "numpy mean": ("fromnumeric.py", "mean"),
}
"""Label → (file name, function name) of the profile rows reported."""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--case", nargs=7, type=float, default=[0.5, 80.0, 20.0, 0.7, 25.0, 1.0, 1.0])
    parser.add_argument("--level", default="fast")
    parser.add_argument("--out", default=str(RESULTS_DIR / "deterministic_profile_fast.json"))
    args = parser.parse_args()
    warm = ContactCase.from_engineering(1.0, 5, 5, 0.5, 25, 0.3, 0.3)
    solve_contact(warm, "atf", args.level, model="deterministic", time_limit_s=5)  # numba compiled outside
    case = ContactCase.from_engineering(*args.case)
    profiler = cProfile.Profile()
    start = time.perf_counter()
    profiler.enable()
    result = solve_contact(case, "atf", args.level, model="deterministic")
    profiler.disable()
    wall = time.perf_counter() - start
    stats = pstats.Stats(profiler).stats
    rows = {}
    for label, (file_name, function) in WATCHED.items():
        hits = [(v[1], v[3]) for (path, _, name), v in stats.items() if path.endswith(file_name) and name == function]
        rows[label] = {"calls": sum(c for c, _ in hits), "cumulative_s": sum(t for _, t in hits)}
    emit_json({"machine": machine_info(), "solver_version": SOLVER_VERSION, "model_version": MODEL_VERSION,
               "case": args.case, "level": args.level, "profiled_wall_time_s": wall, "mu": result.mu,
               "converged": result.converged, "route": result.extra.get("route"),
               "n_nodes": result.extra.get("n_nodes"), "n_steps": result.extra.get("n_steps"), "profile": rows},
              args.out, indent=1)


if __name__ == "__main__":
    main()
