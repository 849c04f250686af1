"""Sensitivity of the deterministic solver's μ to its time step, its numerical tolerance and the physical boundary-film
thickness h_b, on one case at one spacing, paired with the base run of validation/deterministic_convergence.py
(same roughness, same window).

    python validation/deterministic_sensitivity.py --case A --spacing 32 --passes 11
    python validation/deterministic_sensitivity.py --case A --spacing 32 --passes 40 --tag courant \
        --variant base --variant courant_0.5 --variant courant_0.25          # (det-7: base at Courant 1)

Variants: Courant 1, 0.5, 0.25 and 0.125 (the default is 0.25 since det-2026.11-9, 0.5 in det-8, 1 before: under
det-7 the base run and ``courant_1`` are the same, under det-8 the base run and ``courant_0.5``), Newton tolerance 1e-9 (10× looser), the
conductance's film floor (``film_floor``, a regularisation) × 10 and × 0.1, h_b × 0.5 and × 2 (physical, reported). Writes validation/results/deterministic_sensitivity_<case>[_<tag>].json (μ, its standard error, and for each variant the
paired difference to the base run with its standard error) and the μ(t) series of every run in
validation/results/deterministic_sensitivity/<case>[_<tag>]_<variant>.npz.
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
from ehl_dataset.solvers.deterministic import (BOUNDARY_FILM_M, FILM_FLOOR, MODEL_VERSION, DeterministicOptions,
                                               solve_deterministic)
from ehl_dataset.solvers.time_average import time_mean

sys.path.insert(0, str(Path(__file__).resolve().parent))
from deterministic_validation import CASES, LUBRICANT, MAX_PASSES  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
VARIANTS = {
    "base": {},
    "courant_1": {"courant": 1.0},
    "courant_0.5": {"courant": 0.5},
    "courant_0.25": {"courant": 0.25},
    "courant_0.125": {"courant": 0.125},
    "tolerance_1e-9": {"newton_tolerance": 1e-9},
    "film_floor_x10": {"film_floor": 10.0 * FILM_FLOOR},
    "film_floor_x0.1": {"film_floor": 0.1 * FILM_FLOOR},
    "h_b_x0.5": {"boundary_film_m": 0.5 * BOUNDARY_FILM_M},
    "h_b_x2": {"boundary_film_m": 2.0 * BOUNDARY_FILM_M},
}


def series_path(case: str, name: str) -> Path:
    """``case`` is the case letter with the run's tag (``A`` or ``A_courant``)."""
    return RESULTS / "deterministic_sensitivity" / f"{case}_{name}.npz"


def paired_difference(case: str, name: str):
    """(mean, standard error) of μ_variant(t) − μ_base(t) over the times both runs covered, the variant's series
    interpolated at the base run's times (the runs see the same roughness at the same times, so the difference
    fluctuates less than either series); None without both series."""
    if name == "base" or not (series_path(case, "base").exists() and series_path(case, name).exists()):
        return None
    base, other = np.load(series_path(case, "base")), np.load(series_path(case, name))
    inside = (base["t_s"] >= other["t_s"][0]) & (base["t_s"] <= other["t_s"][-1])
    if np.count_nonzero(inside) < 2:
        return None
    difference = np.interp(base["t_s"][inside], other["t_s"], other["mu"]) - base["mu"][inside]
    mean = time_mean(difference)
    return mean.mean, mean.standard_error


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", required=True, choices=sorted(CASES))
    parser.add_argument("--spacing", type=int, default=32, help="β/n")
    parser.add_argument("--passes", type=float, default=11.0)
    parser.add_argument("--variant", action="append", default=[], choices=sorted(VARIANTS))
    parser.add_argument("--tag", default="", help="suffix of the result files (a separate record)")
    args = parser.parse_args(argv)
    key = args.case + (f"_{args.tag}" if args.tag else "")
    case = ContactCase.from_engineering(*CASES[args.case])
    state = load_lubricant(LUBRICANT).state(case.temperature)
    beta = baseline_profile().correlation_length
    path = RESULTS / f"deterministic_sensitivity_{key}.json"
    series_path(key, "base").parent.mkdir(parents=True, exist_ok=True)
    record = json.loads(path.read_text()) if path.exists() else {}
    if (record.get("model_version"), record.get("spacing"), record.get("passes")) != (MODEL_VERSION, args.spacing,
                                                                                       args.passes):
        record = {"case": args.case, "inputs": CASES[args.case], "model_version": MODEL_VERSION,
                  "spacing": args.spacing, "passes": args.passes, "runs": {}}
    for name in args.variant or list(VARIANTS):
        if name in record["runs"]:
            continue
        options = DeterministicOptions(dx_m=beta / args.spacing, max_passes=MAX_PASSES, mu_sem_target=1.0,
                                       min_average_passes=args.passes - 1.5, **VARIANTS[name])
        start = time.time()
        # the baseline profile, as the paired base run of deterministic_convergence.py (not the default)
        result = solve_deterministic(case, state, Effects.full(), options, roughness=baseline_profile())
        e = result.extra
        window = slice(e["average_from_step"], None)
        mu_window = np.asarray(e["mu_series"][window], dtype=float)
        t_window = np.asarray(e["t_series_s"][window], dtype=float)
        record["runs"][name] = {"mu": float(np.mean(mu_window)), "mu_sem": time_mean(mu_window).standard_error,
                                "asperity_load_share": float(np.mean(e["share_series"][window])),
                                "h_min_m": result.h_min, "converged": result.converged,
                                "message": result.message, "substep_steps": e.get("substep_steps"),
                                "wall_time_s": time.time() - start, "n_steps": e["n_steps"]}
        np.savez_compressed(series_path(key, name), t_s=t_window, mu=mu_window)
        if "base" in record["runs"]:
            base = record["runs"]["base"]["mu"]
            for other, run in record["runs"].items():
                run["mu_relative_to_base"] = run["mu"] / base - 1.0
                paired = paired_difference(key, other)
                if paired is not None:
                    run["paired_difference_relative"], run["paired_difference_sem_relative"] = (
                        paired[0] / base, paired[1] / base)
        path.write_text(json.dumps(record, indent=1))
        print(name, record["runs"][name], flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
