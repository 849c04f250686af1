"""Which variable should the pressure-fluctuation closure's c depend on? (docs/explanation/mixed-regime.md, "Why c depends on
the inlet length")

    python validation/closure_forms.py

On the calibration contacts of the closure (every unsaturated contact below λ̄ 1 within the planner's closure range
that the deterministic model solved, narrow and wide, with the resolved wide runs X1 and X2: the calibration group of
validation/results/micro_pressure_closure.json, whose film-law μ on a grid of c it reuses), each candidate form of c is
fitted by least squares of ln(μ_film law/μ_deterministic) and judged by its leave-one-out error; and how much of the
paper factorial is wide, below λ̄ 1 and unsaturated (a seeded sample). The form in L_in/β is the one shipped since
EHL solver ehl-2026.11-14; ehl-2026.11-13 shipped the switch (c 0.167 below a/β 15, 0 above). Writes
validation/results/closure_forms.json.
"""

from __future__ import annotations

import itertools
import json
import platform
from pathlib import Path

import numpy as np
from scipy.optimize import minimize

from ehl_dataset.model.contact import ContactCase  # noqa: E402
from ehl_dataset.dataset.factorial import load_factorial  # noqa: E402
from ehl_dataset.model.lubricant import load_lubricant  # noqa: E402
from ehl_dataset.model.roughness import baseline_profile  # noqa: E402
from ehl_dataset.solver import SOLVER_VERSION  # noqa: E402
from ehl_dataset.solvers.levels import NARROW_FILM_LAW_EYRING  # noqa: E402
from ehl_dataset.solvers.planner import dimensionless_numbers  # noqa: E402
from ehl_dataset.solvers.wide_contact import WIDE_A_OVER_BETA  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
OUT = RESULTS / "closure_forms.json"
SWITCH = "ehl-2026.11-13: c 0.167 below a/β 15, 0 above"
INLET = "c0 / (1 + (L_in/(β L0))²)"
FORMS = {
    SWITCH: (lambda th, r: 0.167 if r["a_over_beta"] < WIDE_A_OVER_BETA else 0.0, []),
    "c0 everywhere": (lambda th, r: th[0], [0.17]),
    "c0 exp(-λ̄/λ0)": (lambda th, r: th[0] * np.exp(-r["lambda_bar"] / abs(th[1])), [0.3, 0.4]),
    INLET: (lambda th, r: th[0] / (1 + (r["inlet_over_beta"] / abs(th[1])) ** 2), [0.2, 4.0]),
}


def contacts() -> tuple[list[dict], list[float]]:
    """The calibration contacts of the closure and the c grid of their film-law μ (micro_pressure_closure.json)."""
    closure = json.loads((RESULTS / "micro_pressure_closure.json").read_text())
    keep = ("label", "inputs", "mu_det", "a_over_beta", "lambda_bar", "eyring_number", "inlet_over_beta")
    rows = [{**{k: p[k] for k in keep}, "mu_grid": p["mu_by_c"]} for p in closure["points"]
            if p["label"] in closure["calibration_points"]]
    return rows, closure["c_grid"]


def wide_unsaturated_share(lubricant, n: int = 1500, seed: int = 0) -> dict:
    """Share of the paper factorial (data/factorials/paper2009.toml, SR > 0) that is wide (a/β ≥ 15), below λ̄ 1
    and unsaturated (X_h < 150), from ``n`` points drawn without replacement, and the a/β of those points."""
    factorial = load_factorial("paper2009")
    names = ["p_h_gpa", "r_eq_mm", "u_r_m_s", "sr", "temp_c", "roughness_um"]
    levels = [[v for v in getattr(factorial, k) if k != "sr" or v > 0] for k in names]
    combos = list(itertools.product(*(range(len(v)) for v in levels)))
    picks = np.random.default_rng(seed).choice(len(combos), n, replace=False)
    a_over_beta = []
    beta = baseline_profile().correlation_length  # the calibration contacts' β (a/β of the same profile)
    for i in picks:
        p, r, u, sr, t, rq = (levels[k][j] for k, j in enumerate(combos[i]))
        nums = dimensionless_numbers(ContactCase.from_engineering(p, r, u, sr, t, *rq), lubricant, beta)
        if (nums["a_over_beta"] >= WIDE_A_OVER_BETA and nums["lambda_bar"] <= 1.0
                and nums["eyring_number"] < NARROW_FILM_LAW_EYRING):
            a_over_beta.append(round(float(nums["a_over_beta"]), 1))
    return {"points": n, "seed": seed, "share": len(a_over_beta) / n,
            "a_over_beta": {f"{v:g}": a_over_beta.count(v) for v in sorted(set(a_over_beta))}}


def main() -> int:
    lubricant = load_lubricant("atf")
    rows, grid = contacts()
    GRID = np.asarray(grid)

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
        {"command": "python validation/closure_forms.py", "solver_version": SOLVER_VERSION,
         "machine": platform.platform(), "c_grid": grid, "forms": forms, "contacts": rows,
         "paper_factorial_wide_unsaturated": wide_unsaturated_share(lubricant)}, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
