"""Calibrate the asperity-load closure's constants (c_∇, c_p, n) on the deterministic validation set, with leave-one-out errors.

The closure (:mod:`ehl_dataset.solvers.asperity_model`) post-processes the film-law solve, so each reference case
(data/reference/deterministic_validation.json) is solved once by the film law (``standard`` level, isothermal like
the reference) and the closure is evaluated on a grid of (c_∇, c_p, n). The fit minimises

    Σ_i [ ln(μ_i/μ_ref,i)² / (0.05² + u_μ,i²) + (s_i − s_ref,i)² / (0.05² + u_s,i²) ],

u_μ,i the case's relative μ uncertainty and u_s,i its share uncertainty (so a case the reference knows poorly, B,
weighs little). Leave-one-out: for each case all three are fitted on the other eleven and the case predicted with
it. The film-law model's own errors on the same cases are listed beside. Writes
validation/results/asperity_model_loo.json:

    python validation/asperity_model_loo.py
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers.asperity_model import ASPERITY_MODEL_VERSION, asperity_closure
from ehl_dataset.solvers.homogenised import BOUNDARY_FILM_M, HomogenisedOptions
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from workflows.accuracy_mixed import load_reference, reference_case

RESULT = Path(__file__).resolve().parent / "results" / "asperity_model_loo.json"
NABLA_GRID = 2.0 ** np.arange(0, 6)
"""c_∇ values scanned [-]."""
PRESSURE_GRID = np.round(np.exp(np.linspace(math.log(1.0), math.log(4.0), 11)), 4)
"""c_p values scanned [-]."""
EXPONENT_GRID = (1.0, 2.0, 3.0)
"""n values scanned [-]."""
GRID = np.array([(a, b, n) for a in NABLA_GRID for b in PRESSURE_GRID for n in EXPONENT_GRID])
"""The (c_∇, c_p, n) triples [-]."""
MU_FLOOR, SHARE_FLOOR = 0.05, 0.05
"""Model tolerances added in quadrature to each case's own uncertainty in the fit's weights [-]."""
ACCEPT_UNCERTAINTY = 0.05
"""Cases whose relative μ uncertainty is below this are held to the acceptance limits [-]."""


def objective(mu, share, ref_mu, ref_share, u_mu, u_share) -> np.ndarray:
    """The fit's weighted sum of squares per (c_∇, c_p, n) triple (rows: cases, columns: grid)."""
    w_mu = 1.0 / (MU_FLOOR**2 + u_mu**2)
    w_s = 1.0 / (SHARE_FLOOR**2 + u_share**2)
    return np.sum(w_mu[:, None] * np.log(mu / ref_mu[:, None]) ** 2
                  + w_s[:, None] * (share - ref_share[:, None]) ** 2, axis=0)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULT))
    args = parser.parse_args(argv)
    lub = load_lubricant("atf")
    rows = load_reference()
    profile = baseline_profile()  # the reference was computed on the baseline profile, not the package's default
    names = [row["case"] for row in rows]
    mu = np.empty((len(rows), len(GRID)))
    share = np.empty_like(mu)
    film_law, closure_seconds, film_law_seconds, smooth_seconds = [], [], [], []
    for i, row in enumerate(rows):
        case = reference_case(row)
        state = lub.state(case.temperature)
        start = time.perf_counter()
        smooth = solve_contact(case, lub, "standard", "smooth")
        smooth_seconds.append(time.perf_counter() - start)
        start = time.perf_counter()
        fl = solve_contact(case, lub, "standard", "isothermal", model="homogenised",
                           homogenised=HomogenisedOptions(closure="film_law"), roughness=profile)
        film_law_seconds.append(time.perf_counter() - start)
        film_law.append(fl)
        for j, (cn, cp, n) in enumerate(GRID):
            start = time.perf_counter()
            res = asperity_closure(fl, case, state, profile, BOUNDARY_FILM_M, pressure_scale=float(cp),
                                   nabla_scale=float(cn), flattening_exponent=float(n))
            closure_seconds.append(time.perf_counter() - start)
            if not res.converged:
                raise RuntimeError(f"case {row['case']} c_nabla {cn:.3g} c_p {cp:.3g} n {n:g}: {res.message}")
            mu[i, j], share[i, j] = res.mu, res.asperity_load_share
        print(f"{row['case']}: film law mu {fl.mu:.4f}, smooth {smooth.mu:.4f}", flush=True)
    ref_mu = np.array([row["mu_extrapolated"] for row in rows])
    u_mu = np.array([row["mu_uncertainty"] for row in rows]) / ref_mu
    ref_share = np.array([row.get("asperity_load_share_extrapolated", 0.0) for row in rows])
    u_share = np.array([row.get("asperity_load_share_uncertainty", 0.0) for row in rows])
    best = int(np.argmin(objective(mu, share, ref_mu, ref_share, u_mu, u_share)))
    table = []
    for i, name in enumerate(names):
        keep = np.arange(len(rows)) != i
        j = int(np.argmin(objective(mu[keep], share[keep], ref_mu[keep], ref_share[keep], u_mu[keep],
                                    u_share[keep])))
        table.append({
            "case": name, "lambda_bar": rows[i]["lambda_bar"], "mu_reference": ref_mu[i],
            "mu_uncertainty_relative": u_mu[i], "share_reference": ref_share[i], "share_uncertainty": u_share[i],
            "held_to_acceptance": bool(u_mu[i] < ACCEPT_UNCERTAINTY),
            "loo_nabla_scale": float(GRID[j][0]), "loo_pressure_scale": float(GRID[j][1]),
            "loo_flattening_exponent": float(GRID[j][2]), "loo_mu": mu[i, j],
            "loo_mu_error": mu[i, j] / ref_mu[i] - 1.0,
            "loo_share": share[i, j], "loo_share_difference": share[i, j] - ref_share[i],
            "fit_mu": mu[i, best], "fit_mu_error": mu[i, best] / ref_mu[i] - 1.0, "fit_share": share[i, best],
            "film_law_mu": film_law[i].mu, "film_law_mu_error": film_law[i].mu / ref_mu[i] - 1.0,
            "film_law_share": film_law[i].asperity_load_share})
    held = [r for r in table if r["held_to_acceptance"]]
    loo_abs = np.abs([r["loo_mu_error"] for r in table])
    summary = {
        "nabla_scale": float(GRID[best][0]), "pressure_scale": float(GRID[best][1]),
        "flattening_exponent": float(GRID[best][2]),
        "loo_mu_error_median_abs": float(np.median(loo_abs)),
        "loo_mu_error_max_abs_held": float(max(abs(r["loo_mu_error"]) for r in held)),
        "loo_share_difference_max_abs_held": float(max(abs(r["loo_share_difference"]) for r in held)),
        "film_law_mu_error_median_abs": float(np.median(np.abs([r["film_law_mu_error"] for r in table]))),
        "acceptance": {"mu_error_max_abs_held": 0.15, "share_difference_max_abs_held": 0.10,
                       "mu_error_median_abs": 0.07},
        "cases_held": [r["case"] for r in held],
        "cases_not_held": [r["case"] for r in table if not r["held_to_acceptance"]],
    }
    summary["accepted"] = bool(summary["loo_mu_error_max_abs_held"] <= 0.15
                               and summary["loo_share_difference_max_abs_held"] <= 0.10
                               and summary["loo_mu_error_median_abs"] <= 0.07)
    cost = {"smooth_median_s": float(np.median(smooth_seconds)), "film_law_median_s": float(np.median(film_law_seconds)),
            "closure_median_s": float(np.median(closure_seconds))}
    out = {"description": __doc__.split("\n\n")[0], "command": "python validation/asperity_model_loo.py",
           "model_version": ASPERITY_MODEL_VERSION, "reference_file": "data/reference/deterministic_validation.json",
           "level": "standard", "effects": "isothermal", "grid": GRID.tolist(), "summary": summary,
           "cost_one_core": cost, "cases": table,
           "scan": {"mu": mu.tolist(), "share": share.tolist()}}
    Path(args.out).write_text(json.dumps(out, indent=1, default=float) + "\n", encoding="utf-8")
    print(json.dumps(summary, indent=1))
    for r in table:
        print(f"{r['case']}: c_nabla {r['loo_nabla_scale']:.3g} c_p {r['loo_pressure_scale']:.3g} "
              f"n {r['loo_flattening_exponent']:g} "
              f"dmu {100 * r['loo_mu_error']:+.1f} % (film law "
              f"{100 * r['film_law_mu_error']:+.1f} %), share {r['loo_share']:.3f} vs {r['share_reference']:.3f}"
              f"{'' if r['held_to_acceptance'] else '  (reference uncertainty %.0f %%)' % (100 * r['mu_uncertainty_relative'])}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
