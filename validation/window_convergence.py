"""Grid and window-length convergence of the periodic window (ehl_dataset.solvers.periodic_window) at fixed local
mean conditions.

    python validation/window_convergence.py --inputs 1.0 20 5 0.2 75 0.4 0.4 --pressure-gpa 1.0 --film-nm 678 \
        --length 16 --spacings 8 16 32 --tag W1

``--inputs`` the case (p_h [GPa], r_eq [mm], u_r [m/s], SR, T [°C], Rq1, Rq2 [µm]: speeds, roughness, lubricant
temperature); ``--pressure-gpa`` and ``--film-nm`` the window's mean pressure and the smooth film whose lubricant it
holds (W1: the Hertzian peak pressure and the central mean film of its resolved run, docs/explanation/mixed-regime.md).
Windows at every spacing read the same roughness at the same times, so their differences are paired (mean and
standard error of μ_local(t) differences over the averaging window). Writes
validation/results/window_convergence_<tag>.json.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solvers.deterministic import MODEL_VERSION
from ehl_dataset.solvers.periodic_window import WindowOptions, solve_window
from ehl_dataset.solvers.time_average import time_mean

RESULTS = Path(__file__).resolve().parent / "results"


def _window_series(result) -> tuple[np.ndarray, np.ndarray]:
    start = result.series["average_from_step"]
    return result.series["t_s"][start:], result.series["mu_local"][start:]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--inputs", nargs=7, type=float, required=True, metavar="X")
    parser.add_argument("--pressure-gpa", type=float, required=True)
    parser.add_argument("--film-nm", type=float, required=True)
    parser.add_argument("--length", type=float, nargs="+", default=[16.0], help="window lengths [β]")
    parser.add_argument("--spacings", type=float, nargs="+", default=[8.0, 16.0, 32.0], help="points per β")
    parser.add_argument("--tag", required=True)
    args = parser.parse_args(argv)
    case = ContactCase.from_engineering(*args.inputs)
    state = load_lubricant("atf").state(case.temperature)
    out = RESULTS / f"window_convergence_{args.tag}.json"
    record = {"inputs": args.inputs, "pressure_pa": args.pressure_gpa * 1e9, "film_m": args.film_nm * 1e-9,
              "model_version": MODEL_VERSION, "runs": []}
    finest = None
    for length in args.length:
        for spacing in args.spacings:
            # the baseline profile of the resolved run the pressure and film come from, not the default
            result = solve_window(case, state, args.pressure_gpa * 1e9, args.film_nm * 1e-9,
                                  WindowOptions(length_beta=length, points_per_beta=spacing),
                                  roughness=baseline_profile())
            row = {"length_beta": length, "points_per_beta": spacing, "mu_local": result.mu_local,
                   "mu_local_sem": result.mu_local_sem, "asperity_share": result.asperity_share,
                   "content_film_m": result.content_film_m, "mean_film_m": result.mean_film_m,
                   "min_film_m": result.min_film_m, "converged": result.converged, "message": result.message,
                   "n_nodes": result.n_nodes, "n_steps": result.n_steps, "wall_time_s": result.wall_time_s,
                   "newton_iterations": result.series["newton_iterations"],
                   "gmres_iterations": result.series["gmres_iterations"]}
            t, mu = _window_series(result)
            if finest is not None and length == finest[0]:
                coarse_t, coarse_mu = finest[1], finest[2]
                inside = (coarse_t >= t[0]) & (coarse_t <= t[-1])
                diff = time_mean(np.interp(coarse_t[inside], t, mu) - coarse_mu[inside])
                row["paired_step_from_previous"] = diff.mean
                row["paired_step_sem"] = diff.standard_error
            finest = (length, t, mu)
            record["runs"].append(row)
            out.write_text(json.dumps(record, indent=1, default=float))
            print(json.dumps(row, default=float), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
