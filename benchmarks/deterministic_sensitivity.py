"""Sensitivity of the deterministic solver's μ to its time step, its numerical tolerance and the physical boundary-film
thickness h_b, on one case at one spacing, paired with the base run of benchmarks/deterministic_convergence.py
(same roughness, same window).

    python benchmarks/deterministic_sensitivity.py --case A --spacing 32 --passes 11

Variants: Courant 0.5 (time step halved), Newton tolerance 1e-9 (10× looser), h_b × 0.5 and × 2 (physical, reported).
Writes benchmarks/results/deterministic_sensitivity_<case>.json.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solvers.deterministic import (BOUNDARY_FILM_M, MODEL_VERSION, DeterministicOptions,
                                               solve_deterministic)

sys.path.insert(0, str(Path(__file__).resolve().parent))
from deterministic_validation import CASES, LUBRICANT, MAX_PASSES  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
VARIANTS = {
    "base": {},
    "courant_0.5": {"courant": 0.5},
    "tolerance_1e-9": {"newton_tolerance": 1e-9},
    "h_b_x0.5": {"boundary_film_m": 0.5 * BOUNDARY_FILM_M},
    "h_b_x2": {"boundary_film_m": 2.0 * BOUNDARY_FILM_M},
}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", required=True, choices=sorted(CASES))
    parser.add_argument("--spacing", type=int, default=32, help="β/n")
    parser.add_argument("--passes", type=float, default=11.0)
    parser.add_argument("--variant", action="append", default=[], choices=sorted(VARIANTS))
    args = parser.parse_args(argv)
    case = ContactCase.from_engineering(*CASES[args.case])
    state = load_lubricant(LUBRICANT).state(case.temperature)
    beta = baseline_profile().correlation_length
    path = RESULTS / f"deterministic_sensitivity_{args.case}.json"
    record = json.loads(path.read_text()) if path.exists() else {}
    if record.get("model_version") != MODEL_VERSION or record.get("spacing") != args.spacing:
        record = {"case": args.case, "inputs": CASES[args.case], "model_version": MODEL_VERSION,
                  "spacing": args.spacing, "passes": args.passes, "runs": {}}
    for name in args.variant or list(VARIANTS):
        if name in record["runs"]:
            continue
        options = DeterministicOptions(dx_m=beta / args.spacing, max_passes=MAX_PASSES, mu_sem_target=1.0,
                                       min_average_passes=args.passes - 1.5, **VARIANTS[name])
        start = time.time()
        result = solve_deterministic(case, state, Effects.full(), options)
        e = result.extra
        window = slice(e["average_from_step"], None)
        record["runs"][name] = {"mu": float(np.mean(e["mu_series"][window])),
                                "asperity_load_share": float(np.mean(e["share_series"][window])),
                                "h_min_m": result.h_min, "converged": result.converged,
                                "wall_time_s": time.time() - start, "n_steps": e["n_steps"]}
        if "base" in record["runs"]:
            base = record["runs"]["base"]["mu"]
            for run in record["runs"].values():
                run["mu_relative_to_base"] = run["mu"] / base - 1.0
        path.write_text(json.dumps(record, indent=1))
        print(name, record["runs"][name], flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
