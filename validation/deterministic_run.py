"""One deterministic mixed-EHL run of any contact, for cases outside the validation set (e.g. wide contacts):
μ, asperity share, the central and Hertz-zone mean film, the cost.

    python validation/deterministic_run.py --inputs 1.0 20 5 0.2 75 0.4 0.4 --spacing 8 --passes 4 --tag W1

``--inputs``: p_h [GPa], r_eq [mm], u_r [m/s], SR, T [°C], Rq1 [µm], Rq2 [µm]; ``--spacing`` points per correlation
length; ``--passes`` the fixed window (no averaging target). Writes validation/results/deterministic_run_<tag>.json.
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
from ehl_dataset.solvers.deterministic import MODEL_VERSION, DeterministicOptions, solve_deterministic

RESULTS = Path(__file__).resolve().parent / "results"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--inputs", nargs=7, type=float, required=True, metavar="X")
    parser.add_argument("--spacing", type=float, default=8.0)
    parser.add_argument("--passes", type=float, default=4.0)
    parser.add_argument("--tag", required=True)
    args = parser.parse_args(argv)
    case = ContactCase.from_engineering(*args.inputs)
    state = load_lubricant("atf").state(case.temperature)
    beta = baseline_profile().correlation_length
    start = time.time()
    result = solve_deterministic(case, state, Effects.full(),
                                 DeterministicOptions(dx_m=beta / args.spacing, max_passes=args.passes,
                                                      mu_sem_target=0.0),
                                 roughness=baseline_profile())  # spacing in baseline β: not the default profile
    inside = np.abs(result.x) < case.half_width
    record = {"inputs": args.inputs, "points_per_beta": args.spacing, "passes": args.passes,
              "model_version": MODEL_VERSION, "a_over_beta": case.half_width / beta, "mu": result.mu,
              "mu_sem": result.mu_sem, "asperity_load_share": result.asperity_load_share, "h_min_m": result.h_min,
              "h_central_m": result.h_central, "mean_film_hertz_m": float(np.mean(result.film[inside])),
              "lambda_bar": result.lambda_bar, "converged": result.converged, "message": result.message,
              "wall_time_s": time.time() - start,
              "extra": {k: v for k, v in result.extra.items() if isinstance(v, (int, float, str))}}
    (RESULTS / f"deterministic_run_{args.tag}.json").write_text(json.dumps(record, indent=1))
    print(json.dumps({k: v for k, v in record.items() if k != "extra"}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
