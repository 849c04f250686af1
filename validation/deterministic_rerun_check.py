"""Rerun recorded runs of the validation set under the installed deterministic model and compare them with their
records: the evidence that a new model version may be paired with the old one's runs
(``deterministic_validation.SAME_NUMERICS``).

    python validation/deterministic_rerun_check.py A:16 B:16 C:16 G:8 I:8
    python validation/deterministic_rerun_check.py --replace H:8     # the rerun becomes the run's record

Each argument is CASE:POINTS_PER_BETA of a run in validation/results/deterministic/ (run with the same options as
the validation script: the middle spacing as the long run). Writes
validation/results/deterministic_rerun_check_<installed model version>.json.
Runs laid out for another length (records without ``layout_passes``) see other roughness and are refused. With
``--replace`` the rerun's record replaces the recorded one (for a version whose runs the validation pairs with the
old ones, ``SAME_NUMERICS``: e.g. to record the new version's per-step balance); each row is written as it finishes.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
import numpy as np  # noqa: E402
from deterministic_validation import (BALANCE_TARGET, RUNS, checkpoint_path, layout_passes,  # noqa: E402
                                      run_case_specs, run_path, solve_and_record, spacings)

from ehl_dataset.dataset.checkpoint import FileCheckpoint  # noqa: E402
from ehl_dataset.solvers.deterministic import MODEL_VERSION  # noqa: E402

OUT = RUNS.parent / f"deterministic_rerun_check_{MODEL_VERSION}.json"


def rerun(name: str, n: int, replace: bool = False) -> dict:
    path = run_path(name, n)
    record = json.loads(path.read_text())
    if record.get("layout_passes") != layout_passes(name):
        raise SystemExit(f"{name} beta/{n}: recorded without layout_passes={layout_passes(name):g}: another "
                         f"roughness, not comparable")
    start = time.perf_counter()
    long = n == spacings(name)[1]
    new = solve_and_record(name, n, long, out=path if replace else None)
    if not replace:
        FileCheckpoint(checkpoint_path(name, n, long)).remove()
    extra = new["extra"]
    return {"run": f"{name} beta/{n}", "recorded_version": record["solver_version"], "version": MODEL_VERSION,
            "mu_recorded": record["mu"], "mu": new["mu"], "mu_relative_change": new["mu"] / record["mu"] - 1.0,
            "share_recorded": record["asperity_load_share"], "share": new["asperity_load_share"],
            "substep_steps_recorded": record["extra"]["substep_steps"], "substep_steps": extra["substep_steps"],
            "round_off_stops_recorded": record["extra"].get("round_off_stops"),
            "round_off_stops": extra["round_off_stops"],
            "max_mass_error_recorded": record["residuals"]["max_mass_error"],
            "max_mass_error": new["residuals"]["max_mass_error"],
            "mass_error_steps_over_1e-10_recorded": over_target(record),
            "mass_error_steps_over_1e-10": over_target(new), "n_steps": extra["n_steps"],
            "converged": new["converged"], "replaced": replace, "wall_time_s": time.perf_counter() - start}


def over_target(record: dict) -> int:
    """Steps of a run's record whose global mass balance exceeds :data:`BALANCE_TARGET`."""
    return int(np.sum(np.asarray(record["extra"]["mass_error_series"]) > BALANCE_TARGET))


def main(argv=None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    replace = "--replace" in args
    specs = [a for a in args if a != "--replace"]
    return run_case_specs("deterministic_rerun_check.py", specs, lambda name, n: rerun(name, n, replace), OUT,
                          "--replace" if replace else "")


if __name__ == "__main__":
    raise SystemExit(main())
