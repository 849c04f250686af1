"""Per-step global lubricant balance of the deterministic solver on one validation case, and its dependence on the
round-off stop margin of the Newton solve (docs/explanation/mixed-regime.md, "Mass balance").

    python validation/deterministic_mass_balance.py --case A --spacing 32 --passes 4 [--margin 100]

The balance of a step is |Σ mass rows| / reference flux (``MixedProblem.mass_balance_error``). ``--margin`` replaces
``ROUND_OFF_MARGIN`` for this run only (a model other than the recorded version: for the study of the stop rule).
Appends a row to validation/results/deterministic_mass_balance.json.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

import ehl_dataset.solvers.deterministic as deterministic
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile

sys.path.insert(0, str(Path(__file__).resolve().parent))
from deterministic_validation import CASES, LUBRICANT  # noqa: E402

OUT = Path(__file__).resolve().parent / "results" / "deterministic_mass_balance.json"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", required=True, choices=sorted(CASES))
    parser.add_argument("--spacing", type=int, default=32, help="points per correlation length")
    parser.add_argument("--passes", type=float, default=4.0)
    parser.add_argument("--margin", type=float, default=None, help="round-off stop margin (default: the model's)")
    args = parser.parse_args(argv)
    if args.margin is not None:
        deterministic.ROUND_OFF_MARGIN = args.margin
    case = ContactCase.from_engineering(*CASES[args.case])
    state = load_lubricant(LUBRICANT).state(case.temperature)
    beta = baseline_profile().correlation_length
    options = deterministic.DeterministicOptions(dx_m=beta / args.spacing, max_passes=args.passes, mu_sem_target=0.0)
    start = time.perf_counter()
    # the validation case's roughness (spacing in its β), not the package's default profile
    result = deterministic.solve_deterministic(case, state, Effects.full(), options, roughness=baseline_profile())
    series = np.asarray(result.extra["mass_error_series"])
    row = {"case": args.case, "points_per_beta": args.spacing, "passes": args.passes,
           "model_version": deterministic.MODEL_VERSION, "round_off_margin": deterministic.ROUND_OFF_MARGIN,
           "mu": result.mu, "converged": result.converged, "message": result.message, "n_steps": int(series.size),
           "n_nodes": result.extra["n_nodes"], "round_off_stops": result.extra["round_off_stops"],
           "mass_error_max": float(series.max()), "mass_error_p99": float(np.percentile(series, 99)),
           "mass_error_median": float(np.median(series)), "share_of_steps_above_1e-10": float(np.mean(series > 1e-10)),
           "max_load_error": result.residuals["max_load_error"], "wall_time_s": time.perf_counter() - start}
    rows = json.loads(OUT.read_text())["rows"] if OUT.exists() else []
    rows.append(row)
    OUT.write_text(json.dumps({"command": "python validation/deterministic_mass_balance.py", "rows": rows}, indent=1))
    print(json.dumps(row))
    return 0


if __name__ == "__main__":
    sys.exit(main())
