"""Rerun recorded runs of the validation set under the installed deterministic model and compare them with their
records: the evidence that a new model version may be paired with the old one's runs
(``deterministic_validation.SAME_NUMERICS``).

    python benchmarks/deterministic_rerun_check.py A:16 B:16 C:16 G:8 I:8

Each argument is CASE:POINTS_PER_BETA of a run in benchmarks/results/deterministic/ (run with the same options as
the validation script: the middle spacing as the long run). Writes
benchmarks/results/deterministic_rerun_check_<installed model version>.json.
Runs laid out for another length (records without ``layout_passes``) see other roughness and are refused.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from deterministic_validation import (CASES, LUBRICANT, RUNS, layout_passes, long_max_passes,  # noqa: E402
                                      options_for, run_case_specs, run_path, spacings)

from ehl_dataset.model.contact import ContactCase  # noqa: E402
from ehl_dataset.model.effects import Effects  # noqa: E402
from ehl_dataset.model.lubricant import load_lubricant  # noqa: E402
from ehl_dataset.solvers.deterministic import MODEL_VERSION, solve_deterministic  # noqa: E402

OUT = RUNS.parent / f"deterministic_rerun_check_{MODEL_VERSION}.json"


def rerun(name: str, n: int) -> dict:
    record = json.loads(run_path(name, n).read_text())
    if record.get("layout_passes") != layout_passes(name):
        raise SystemExit(f"{name} beta/{n}: recorded without layout_passes={layout_passes(name):g}: another "
                         f"roughness, not comparable")
    case = ContactCase.from_engineering(*CASES[name])
    state = load_lubricant(LUBRICANT).state(case.temperature)
    start = time.perf_counter()
    result = solve_deterministic(case, state, Effects.full(), options_for(n, n == spacings(name)[1],
                                                                                 long_max_passes(name),
                                                                                 layout_passes(name)))
    return {"run": f"{name} beta/{n}", "recorded_version": record["solver_version"], "version": MODEL_VERSION,
            "mu_recorded": record["mu"], "mu": result.mu, "mu_relative_change": result.mu / record["mu"] - 1.0,
            "share_recorded": record["asperity_load_share"], "share": result.asperity_load_share,
            "substep_steps_recorded": record["extra"]["substep_steps"],
            "substep_steps": result.extra["substep_steps"],
            "round_off_stops_recorded": record["extra"].get("round_off_stops"),
            "round_off_stops": result.extra["round_off_stops"],
            "max_mass_error_recorded": record["residuals"]["max_mass_error"],
            "max_mass_error": result.residuals["max_mass_error"], "converged": result.converged,
            "wall_time_s": time.perf_counter() - start}


def main(argv=None) -> int:
    return run_case_specs("deterministic_rerun_check.py", argv if argv is not None else sys.argv[1:], rerun, OUT)


if __name__ == "__main__":
    raise SystemExit(main())
