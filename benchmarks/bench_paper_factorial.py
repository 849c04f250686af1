"""Wall time of the paper factorial (stage 1, 42,000 points) through ``gearloss pipeline paper``, and whether its fit is
the shipped one.

Runs ``gearloss pipeline paper --workers N --out-dir DIR`` in a child process and records: the stage-1 wall time of
the dataset store's session record, the converged and failed counts, the child's user and system CPU time
(``resource.getrusage(RUSAGE_CHILDREN)``: the pipeline and its workers), the load averages before and after, and for
both branches of the fit the largest coefficient change against the shipped ``data/coefficients/atf.json`` in units
of its standard error (the fit of the same data is the same to round-off).

    python benchmarks/bench_paper_factorial.py --workers 2   # → benchmarks/results/paper_factorial.json

About 11 minutes on 2 idle cores (EHL solver ehl-2026.11-17). Stop other jobs first: the wall time scales with the
CPU the workers get (the load averages are recorded).
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import RESULTS_DIR, machine_info  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SHIPPED_FIT = ROOT / "data" / "coefficients" / "atf.json"


def _load() -> list[float] | None:
    return [round(v, 2) for v in os.getloadavg()] if hasattr(os, "getloadavg") else None


def fit_change_in_standard_errors(fitted: Path, shipped: Path = SHIPPED_FIT) -> dict:
    """Per branch: max |Δ coefficient|/standard error of the shipped file, and both adjusted R² [-]."""
    new, old = (json.loads(p.read_text(encoding="utf-8"))["branches"] for p in (fitted, shipped))
    out = {}
    for name, branch in old.items():
        params_old = np.asarray(branch["params"], dtype=float)
        params_new = np.asarray(new[name]["params"], dtype=float)
        se = np.asarray(branch["std_errors"], dtype=float)
        out[name] = {"max_change_over_standard_error": float(np.max(np.abs(params_new - params_old) / se)),
                     "adj_r2": float(new[name]["adj_r2"]), "adj_r2_shipped": float(branch["adj_r2"]),
                     "n_obs": int(new[name]["n_obs"]), "n_obs_shipped": int(branch["n_obs"])}
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--out-dir", default=None, help="pipeline output directory (default: a temporary one)")
    parser.add_argument("--out", default=str(RESULTS_DIR / "paper_factorial.json"))
    args = parser.parse_args(argv)
    from ehl_dataset.dataset.store import FAILED, OK, PENDING
    from ehl_dataset.solver import SOLVER_VERSION

    with tempfile.TemporaryDirectory() as scratch:
        out_dir = Path(args.out_dir or scratch)
        command = ["gearloss", "pipeline", "paper", "--workers", str(args.workers), "--out-dir", str(out_dir)]
        load_start = _load()
        start = time.perf_counter()
        completed = subprocess.run(command, capture_output=True, text=True)
        wall = time.perf_counter() - start
        usage = resource.getrusage(resource.RUSAGE_CHILDREN)
        load_end = _load()
        if completed.returncode != 0:
            print(completed.stdout[-2000:], completed.stderr[-2000:], file=sys.stderr)
            return completed.returncode
        with h5py.File(out_dir / "dataset.h5", "r") as store:
            sessions = json.loads(store.attrs["sessions"])
            points = store["points"]
            converged = np.asarray(points["converged"])
            status = np.asarray(points["status"])
        fit = fit_change_in_standard_errors(out_dir / "atf_paper2009.json")
    report = {"benchmark": "paper_factorial", "solver_version": SOLVER_VERSION,
              "command": "python benchmarks/bench_paper_factorial.py " + " ".join(argv if argv is not None
                                                                                  else sys.argv[1:]),
              "pipeline_command": " ".join(command[:-1] + ["DIR"]),
              "machine": {**machine_info(), "load_average_start": load_start, "load_average_end": load_end},
              "stage1_wall_s": float(sum(s["wall_time_s"] for s in sessions)),
              "stage1_points_computed": int(sum(s["computed"] for s in sessions)),
              "pipeline_wall_s": wall, "cpu_user_s": usage.ru_utime, "cpu_system_s": usage.ru_stime,
              "fit_against_shipped": fit,
              "pipeline_stdout_tail": completed.stdout.strip().splitlines()[-12:]}
    report["converged"] = int(np.count_nonzero(converged))
    names = {PENDING: "pending", OK: "ok", FAILED: "failed"}
    report["status_counts"] = {names.get(int(k), str(k)): int(v) for k, v in zip(*np.unique(status, return_counts=True))}
    Path(args.out).write_text(json.dumps(report, indent=1) + "\n", encoding="utf-8")
    print(f"stage 1 {report['stage1_wall_s']:.0f} s ({report['stage1_wall_s'] / 60:.1f} min) on {args.workers} "
          f"workers; fit change ≤ {max(v['max_change_over_standard_error'] for v in fit.values()):.1e} s.e.")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
