"""Which variable should the pressure-fluctuation closure's c depend on? (docs/narrow_contacts.md, "Beyond a/β 15")

    python benchmarks/closure_forms.py

For every contact below λ̄ 1 with X_h < 150 that the deterministic model solved (the calibration group and the wide
group of benchmarks/results/micro_pressure_closure.json, plus the resolved wide runs X1, a/β 17.7, and X2, a/β 23.6:
benchmarks/results/deterministic_run_X1.json, _X2.json), the film law's μ on a grid of c (``fast``, isothermal);
then each candidate form of c is fitted by least squares of ln(μ_film law/μ_deterministic) and judged by its
leave-one-out error. Writes benchmarks/results/closure_forms.json. Exploratory: the shipped model is unchanged.
"""

from __future__ import annotations

import json
import platform
from pathlib import Path

import numpy as np
from scipy.optimize import minimize

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solver import SOLVER_VERSION, solve_contact
from ehl_dataset.solvers.homogenised import HomogenisedOptions
from ehl_dataset.solvers.planner import dimensionless_numbers

RESULTS = Path(__file__).resolve().parent / "results"
GRID = np.round(np.arange(0.0, 0.61, 0.03), 3)
FORMS = {
    "shipped: c0 below a/β 15, 0 above": (lambda th, r: 0.167 if r["a_over_beta"] < 15 else 0.0, []),
    "c0 everywhere": (lambda th, r: th[0], [0.17]),
    "c0 exp(-λ̄/λ0)": (lambda th, r: th[0] * np.exp(-r["lambda_bar"] / abs(th[1])), [0.3, 0.4]),
    "c0 / (1 + (L_in/(β L0))²)": (lambda th, r: th[0] / (1 + (r["inlet_over_beta"] / abs(th[1])) ** 2), [0.2, 4.0]),
}


def contacts() -> list[dict]:
    closure = json.loads((RESULTS / "micro_pressure_closure.json").read_text())
    out = [{"label": p["label"], "inputs": p["inputs"], "mu_det": p["mu_det"]} for p in closure["points"]
           if p["group"].startswith(("lambda_bar <= 1, X_h < 150, closure", "wide, lambda_bar <= 1"))]
    for tag in ("X1", "X2"):
        run = json.loads((RESULTS / f"deterministic_run_{tag}.json").read_text())
        out.append({"label": f"{tag} resolved", "inputs": run["inputs"], "mu_det": run["mu"]})
    return out


def main() -> int:
    lubricant = load_lubricant("atf")
    rows = []
    for p in contacts():
        case = ContactCase.from_engineering(*p["inputs"])
        results = [solve_contact(case, lubricant, "fast", "isothermal", model="homogenised",
                                 homogenised=HomogenisedOptions(closure="film_law", micro_pressure_coefficient=float(c)))
                   for c in GRID]
        nums = dimensionless_numbers(case, lubricant)
        rows.append({**p, "mu_grid": [r.mu for r in results], "a_over_beta": float(nums["a_over_beta"]),
                     "lambda_bar": nums["lambda_bar"], "eyring_number": nums["eyring_number"],
                     "inlet_over_beta": float(results[0].extra["inlet_over_beta"])})

    def error(r, c):
        return float(np.log(np.interp(float(np.clip(c, 0.0, GRID[-1])), GRID, r["mu_grid"]) / r["mu_det"]))

    def fit(sample, form, x0):
        if not x0:
            return []
        return minimize(lambda th: sum(error(r, form(th, r)) ** 2 for r in sample), x0, method="Nelder-Mead",
                        options={"maxiter": 2000}).x.tolist()

    forms = {}
    for name, (form, x0) in FORMS.items():
        loo = [float(np.expm1(error(r, form(fit(rows[:i] + rows[i + 1:], form, x0), r)))) for i, r in enumerate(rows)]
        wide = [abs(e) for e, r in zip(loo, rows) if r["a_over_beta"] >= 15]
        forms[name] = {"parameters": fit(rows, form, x0), "leave_one_out_median_abs": float(np.median(np.abs(loo))),
                       "leave_one_out_p90_abs": float(np.percentile(np.abs(loo), 90)),
                       "wide_median_abs": float(np.median(wide)), "wide_max_abs": float(max(wide)),
                       "leave_one_out": dict(zip([r["label"] for r in rows], loo))}
        print(f"{name}: parameters {np.round(forms[name]['parameters'], 3)}, leave-one-out median "
              f"{forms[name]['leave_one_out_median_abs']:.1%}, p90 {forms[name]['leave_one_out_p90_abs']:.1%}; wide "
              f"({len(wide)}) median {forms[name]['wide_median_abs']:.1%}, max {forms[name]['wide_max_abs']:.0%}")
    (RESULTS / "closure_forms.json").write_text(json.dumps(
        {"command": "python benchmarks/closure_forms.py", "solver_version": SOLVER_VERSION,
         "machine": platform.platform(), "c_grid": GRID.tolist(), "forms": forms, "contacts": rows}, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
