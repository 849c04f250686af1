"""Benchmark: evaluation rate of the friction surrogate's two forms on 1 million contact points.

Both forms are fitted on the same synthetic rows (the small factorial of :mod:`surrogate.synthetic`, exact Eq. 9
plus N(0, 0.05²) in ln μ) and written to coefficient files; the timed calls are what stage 3 calls:
``FrictionSurrogate.mu`` (validated inputs, features, clipping to the fitted ranges) and ``mu_interval`` (μ and its
90 % prediction interval). Medians of ``--repeats`` runs of wall time and of process CPU time (the machine is shared:
the load average is recorded; CPU time is what the evaluation costs one core). Usage::

    python benchmarks/bench_surrogate_learned.py [--repeats 5] [--points 1000000]
        [--out benchmarks/results/surrogate_learned.json]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import machine_info  # noqa: E402


def _timed(fn, repeats: int) -> dict:
    wall, cpu = [], []
    for _ in range(repeats):
        c0, w0 = time.process_time(), time.perf_counter()
        fn()
        cpu.append(time.process_time() - c0)
        wall.append(time.perf_counter() - w0)
    return {"median_wall_s": statistics.median(wall), "median_cpu_s": statistics.median(cpu), "all_wall_s": wall,
            "all_cpu_s": cpu}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--points", type=int, default=1_000_000)
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "surrogate_learned.json"))
    args = parser.parse_args(argv)

    from ehl_dataset.model.lubricant import load_lubricant
    from ehl_dataset.model.materials import STEEL, reduced_modulus
    from surrogate.coefficients import write_coefficients
    from surrogate.evaluate import FrictionSurrogate
    from surrogate.fit import fit_surrogate
    from surrogate.learned_fit import fit_learned
    from surrogate.synthetic import SMALL_LEVELS, eq9_table, factorial_inputs, reference_coefficients

    warnings.simplefilter("ignore")
    atf = load_lubricant("atf")
    e = reduced_modulus(STEEL, STEEL)
    table = eq9_table(factorial_inputs(SMALL_LEVELS), reference_coefficients(atf, e), atf, e, noise_sd=0.05, seed=0)
    load_start = os.getloadavg()[0]
    rng = np.random.default_rng(0)
    n = args.points
    inputs = (rng.uniform(0.5e9, 2.5e9, n), rng.uniform(0.005, 0.08, n), rng.uniform(1.0, 20.0, n),
              rng.uniform(0.05, 1.0, n), np.full(n, 353.15), np.full(n, 0.3e-6), np.full(n, 0.4e-6))
    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        eq9 = write_coefficients(fit_surrogate(table, atf, e, allow_unstable=True), Path(tmp) / "eq9.json")
        t1 = time.perf_counter()
        learned = write_coefficients(fit_learned(table, atf, e), Path(tmp) / "learned.json")
        t2 = time.perf_counter()
        for name, path, fit_s in (("eq9", eq9, t1 - t0), ("learned", learned, t2 - t1)):
            surrogate = FrictionSurrogate.load(path, clip_to_fitted_ranges=True)
            entry = {"fit_s": fit_s, "rows": len(table)}
            for call in ("mu", "mu_interval"):
                method = getattr(surrogate, call)
                timing = _timed(lambda: method(*inputs, warn=False), args.repeats)
                timing["points_per_s_wall"] = n / timing["median_wall_s"]
                timing["points_per_s_cpu"] = n / timing["median_cpu_s"]
                entry[call] = timing
            results[name] = entry
    out = {"benchmark": "surrogate_learned", "points": n, "repeats": args.repeats,
           "machine": {**machine_info(), "load_average_1min_at_start": load_start,
                       "load_average_1min_at_end": os.getloadavg()[0]},
           "data": {"rows": len(table), "source": "small factorial, exact Eq. 9 + N(0, 0.05^2) in ln mu"},
           "forms": results}
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(out, indent=1) + "\n")
    for name, entry in results.items():
        for call in ("mu", "mu_interval"):
            t = entry[call]
            print(f"{name:8s} {call:12s} wall {t['median_wall_s']:.3f} s ({t['points_per_s_wall']:.3g}/s), cpu "
                  f"{t['median_cpu_s']:.3f} s ({t['points_per_s_cpu']:.3g}/s)")
    print(f"load average {load_start:.1f} -> {os.getloadavg()[0]:.1f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
