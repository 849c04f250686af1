"""Which variable should the pressure-fluctuation closure's c depend on? (docs/narrow_contacts.md, "The switch at a/β 15")

    python benchmarks/closure_forms.py

For every contact below λ̄ 1 with X_h < 150 that the deterministic model solved (the calibration group and the wide
group of benchmarks/results/micro_pressure_closure.json, plus the resolved wide runs X1, a/β 17.7, and X2, a/β 23.6:
benchmarks/results/deterministic_run_X1.json, _X2.json), the film law's μ on a grid of c (``fast``, isothermal);
then each candidate form of c is fitted by least squares of ln(μ_film law/μ_deterministic) and judged by its
leave-one-out error; and how much of the paper factorial is wide, below λ̄ 1 and unsaturated (a seeded sample).
Writes benchmarks/results/closure_forms.json. Exploratory: the shipped model is unchanged.
"""

from __future__ import annotations

import itertools
import json
import platform
import sys
from pathlib import Path

import numpy as np
from scipy.optimize import minimize

sys.path.insert(0, str(Path(__file__).resolve().parent))
from micro_pressure_closure import LEVEL, film_law_mu  # noqa: E402

from ehl_dataset.model.contact import ContactCase  # noqa: E402
from ehl_dataset.dataset.factorial import load_factorial  # noqa: E402
from ehl_dataset.model.lubricant import load_lubricant  # noqa: E402
from ehl_dataset.solver import SOLVER_VERSION, solve_contact  # noqa: E402
from ehl_dataset.solvers.film_law_model import micro_pressure_coefficient_for  # noqa: E402
from ehl_dataset.solvers.homogenised import HomogenisedOptions  # noqa: E402
from ehl_dataset.solvers.planner import NARROW_FILM_LAW_EYRING, dimensionless_numbers  # noqa: E402
from ehl_dataset.solvers.wide_contact import WIDE_A_OVER_BETA  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
OUT = RESULTS / "closure_forms.json"
GRID = np.round(np.arange(0.0, 0.61, 0.03), 3)
SHIPPED = "shipped: c0 below a/β 15, 0 above"
INLET = "c0 / (1 + (L_in/(β L0))²)"
FORMS = {
    SHIPPED: (lambda th, r: micro_pressure_coefficient_for(r["a_over_beta"]), []),
    "c0 everywhere": (lambda th, r: th[0], [0.17]),
    "c0 exp(-λ̄/λ0)": (lambda th, r: th[0] * np.exp(-r["lambda_bar"] / abs(th[1])), [0.3, 0.4]),
    INLET: (lambda th, r: th[0] / (1 + (r["inlet_over_beta"] / abs(th[1])) ** 2), [0.2, 4.0]),
}


def contacts() -> list[dict]:
    closure = json.loads((RESULTS / "micro_pressure_closure.json").read_text())
    out = [{"label": p["label"], "inputs": p["inputs"], "mu_det": p["mu_det"]} for p in closure["points"]
           if p["group"].startswith(("lambda_bar <= 1, X_h < 150, closure", "wide, lambda_bar <= 1"))]
    for tag in ("X1", "X2"):
        run = json.loads((RESULTS / f"deterministic_run_{tag}.json").read_text())
        out.append({"label": f"{tag} resolved", "inputs": run["inputs"], "mu_det": run["mu"]})
    return out


def wide_unsaturated_share(lubricant, n: int = 1500, seed: int = 0) -> dict:
    """Share of the paper factorial (data/factorials/paper2009.toml, SR > 0) that is wide (a/β ≥ 15), below λ̄ 1
    and unsaturated (X_h < 150), from ``n`` points drawn without replacement, and the a/β of those points."""
    factorial = load_factorial("paper2009")
    names = ["p_h_gpa", "r_eq_mm", "u_r_m_s", "sr", "temp_c", "roughness_um"]
    levels = [[v for v in getattr(factorial, k) if k != "sr" or v > 0] for k in names]
    combos = list(itertools.product(*(range(len(v)) for v in levels)))
    picks = np.random.default_rng(seed).choice(len(combos), n, replace=False)
    a_over_beta = []
    for i in picks:
        p, r, u, sr, t, rq = (levels[k][j] for k, j in enumerate(combos[i]))
        nums = dimensionless_numbers(ContactCase.from_engineering(p, r, u, sr, t, *rq), lubricant)
        if (nums["a_over_beta"] >= WIDE_A_OVER_BETA and nums["lambda_bar"] <= 1.0
                and nums["eyring_number"] < NARROW_FILM_LAW_EYRING):
            a_over_beta.append(round(float(nums["a_over_beta"]), 1))
    return {"points": n, "seed": seed, "share": len(a_over_beta) / n,
            "a_over_beta": {f"{v:g}": a_over_beta.count(v) for v in sorted(set(a_over_beta))}}


def inlet_over_beta(p: dict, lubricant) -> float:
    """L_in/β of the film law at the contact (its ``extra``; the same at every c)."""
    result = solve_contact(ContactCase.from_engineering(*p["inputs"]), lubricant, LEVEL, "isothermal",
                           model="homogenised", homogenised=HomogenisedOptions(closure="film_law"))
    return float(result.extra["inlet_over_beta"])


def main() -> int:
    lubricant = load_lubricant("atf")
    rows = []
    for p in contacts():
        nums = dimensionless_numbers(ContactCase.from_engineering(*p["inputs"]), lubricant)
        rows.append({**p, "mu_grid": [film_law_mu(p, lubricant, float(c)) for c in GRID],
                     "a_over_beta": float(nums["a_over_beta"]), "lambda_bar": nums["lambda_bar"],
                     "eyring_number": nums["eyring_number"], "inlet_over_beta": inlet_over_beta(p, lubricant)})

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
    OUT.write_text(json.dumps(
        {"command": "python benchmarks/closure_forms.py", "solver_version": SOLVER_VERSION,
         "machine": platform.platform(), "c_grid": GRID.tolist(), "forms": forms, "contacts": rows,
         "paper_factorial_wide_unsaturated": wide_unsaturated_share(lubricant)}, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
