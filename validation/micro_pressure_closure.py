"""Calibration and check of the film law's micro-EHL pressure-fluctuation closure
(ehl_dataset.model.micro_pressure; docs/explanation/mixed-regime.md, "Pressure-fluctuation closure").

    python validation/micro_pressure_closure.py

Points: every rough contact (SR > 0) the deterministic model solved and converged, at ``fast`` on the
factorial (benchmarks/results/ehl_mixed_random200_fast_deterministic.json, ehl_mixed_corners_fast_deterministic.json),
grid-converged on the validation set (data/reference/deterministic_validation.json, its μ_extrapolated), and the wide
contacts resolved whole (validation/results/deterministic_run_X1.json, _X2.json). Each is solved by the film-law
model at ``fast``, isothermal (as the deterministic model is), without the closure (c = 0), with the shipped
c(L_in/β), and (the calibration set) on a grid of c. The calibration set is the unsaturated contacts the closure is
for, narrow and wide: λ̄ ≤ 1 and X_h < 150, within the planner's closure range (λ̄ ≥ NARROW_CLOSURE_LAMBDA, roughness
parameter α ≤ NARROW_CLOSURE_ROUGHNESS). c = c0/(1 + (L_in/(β·L0))²) with (c0, L0) minimising
Σ ln²(μ_film law/μ_deterministic) over it (μ(c) interpolated on the grid); the leave-one-out error (c0, L0 refitted
without the point, the point then solved at its c) is the honest estimate of the closure's error on a new point.
Calibration-group points that came after the shipped fit (SHIPPED_FIT_POINTS) are reported as an out-of-sample check
at the shipped c. Writes validation/results/micro_pressure_closure.json.
"""

from __future__ import annotations

import json
import platform
import sys
from pathlib import Path

import numpy as np
from scipy.optimize import minimize

sys.path.insert(0, str(Path(__file__).resolve().parent))
from deterministic_validation import CASES, LUBRICANT, REFERENCE  # noqa: E402

from ehl_dataset.model.contact import ContactCase  # noqa: E402
from ehl_dataset.model.lubricant import load_lubricant  # noqa: E402
from ehl_dataset.model.micro_pressure import (MICRO_PRESSURE_C0, MICRO_PRESSURE_INLET_SCALE,  # noqa: E402
                                              micro_pressure_coefficient)
from ehl_dataset.model.roughness import baseline_profile  # noqa: E402
from ehl_dataset.solver import SOLVER_VERSION, solve_contact  # noqa: E402
from ehl_dataset.solvers.homogenised import HomogenisedOptions  # noqa: E402
from ehl_dataset.solvers.levels import (NARROW_CLOSURE_LAMBDA, NARROW_CLOSURE_ROUGHNESS,  # noqa: E402
                                        NARROW_FILM_LAW_EYRING)
from ehl_dataset.solvers.planner import dimensionless_numbers, narrow_film_law_range, thresholds_for  # noqa: E402
from ehl_dataset.solvers.wide_contact import WIDE_A_OVER_BETA  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
BENCHMARK_RESULTS = ROOT / "benchmarks" / "results"
"""The factorial runs of benchmarks/bench_ehl_mixed.py the points come from."""
RESULTS = ROOT / "validation" / "results"
OUT = RESULTS / "micro_pressure_closure.json"
SOURCES = {"random": "ehl_mixed_random200_fast_deterministic.json", "corner": "ehl_mixed_corners_fast_deterministic.json"}
LEVEL = "fast"


def points(lubricant) -> list[dict]:
    """The deterministic points: label, inputs (engineering units), μ of the deterministic model, its version, the
    planner's numbers."""
    out = []
    for row in json.loads(REFERENCE.read_text())["cases"]:
        out.append({"label": f"case {row['case']}", "inputs": list(CASES[row["case"]]), "mu_det": row["mu_extrapolated"],
                    "det_version": row["solver_version"]})
    for kind, name in SOURCES.items():
        data = json.loads((BENCHMARK_RESULTS / name).read_text())
        for i, row in enumerate(data["rows"]):
            if row.get("converged") and row["case"][3] > 0:
                out.append({"label": f"{kind} {i}", "inputs": list(row["case"]), "mu_det": row["mu"],
                            "det_version": data.get("solver_version")})
    for tag in ("X1", "X2"):
        run = json.loads((RESULTS / f"deterministic_run_{tag}.json").read_text())
        out.append({"label": f"{tag} resolved", "inputs": list(run["inputs"]), "mu_det": run["mu"],
                    "det_version": run["model_version"]})
    beta = baseline_profile().correlation_length  # the deterministic points' profile: a/β in its β
    for p in out:
        nums = dimensionless_numbers(ContactCase.from_engineering(*p["inputs"]), lubricant, beta)
        p.update({key: nums[key] for key in ("lambda_bar", "eyring_number", "roughness_parameter", "a_over_beta")})
    return out


def group(p: dict) -> str:
    within, limit = narrow_film_law_range(p, thresholds_for("standard"))
    if limit == "lambda_bar":
        return "lambda_bar > 1"
    if limit == "eyring_number":
        return "lambda_bar <= 1, X_h >= 150"
    return "lambda_bar <= 1, X_h < 150, " + ("closure range" if within else "outside closure range")


CALIBRATION = "lambda_bar <= 1, X_h < 150, closure range"

SHIPPED_FIT_POINTS = ("case A", "case G", "random 2", "random 3", "random 7", "random 13", "random 21", "random 37",
                      "random 39", "random 42", "random 43", "random 53", "random 65", "random 67", "random 69",
                      "random 97", "random 98", "random 100", "random 101", "random 102", "random 103", "random 104",
                      "random 133", "random 151", "random 154", "random 165", "random 180", "random 186", "corner 5",
                      "corner 15", "corner 31", "X1 resolved", "X2 resolved")
"""The calibration points the shipped (c0, L0) were fitted on (EHL solver ehl-2026.11-14). Points of the calibration
group that come later were not seen by the fit: their error at the shipped c is an out-of-sample check
(``holdout`` in the output)."""


def closure_c(theta, inlet_over_beta: float) -> float:
    """c = c0/(1 + (L_in/(β·L0))²) at θ = (c0, L0), the form of
    :func:`ehl_dataset.model.micro_pressure.micro_pressure_coefficient`."""
    return abs(theta[0]) / (1.0 + (inlet_over_beta / abs(theta[1])) ** 2)


def film_law_solve(p: dict, lubricant, c: float | None):
    """The film-law solve of point ``p`` at c (None: the shipped c(L_in/β)); raises if it does not converge."""
    case = ContactCase.from_engineering(*p["inputs"])
    # on the baseline profile the deterministic points were computed on, not the package's default
    result = solve_contact(case, lubricant, LEVEL, "isothermal", model="homogenised",
                           homogenised=HomogenisedOptions(closure="film_law", micro_pressure_coefficient=c),
                           roughness=baseline_profile())
    if not result.converged:
        raise RuntimeError(f"{p['label']}: film law not converged: {result.message}")
    return result


def film_law_mu(p: dict, lubricant, c: float | None) -> float:
    """μ of the film law at point ``p`` and c (None: the shipped c(L_in/β))."""
    return film_law_solve(p, lubricant, c).mu


def stats(errors) -> dict:
    e = np.abs(np.asarray(errors))
    return {"n": int(e.size), "median_abs": float(np.median(e)), "p90_abs": float(np.percentile(e, 90)),
            "median": float(np.median(errors))}


def main() -> int:
    lubricant = load_lubricant(LUBRICANT)
    pts = points(lubricant)
    grid = np.round(np.arange(0.0, 0.601, 0.03), 3)
    for p in pts:
        p["group"] = group(p)
        bare = film_law_solve(p, lubricant, 0.0)
        p["inlet_over_beta"] = float(bare.extra["inlet_over_beta"])
        p["mu_by_c"] = {0.0: bare.mu, **{float(c): film_law_mu(p, lubricant, float(c))
                                         for c in (grid[1:] if p["group"] == CALIBRATION else [])}}
        print(p["label"], p["group"], f"det {p['mu_det']:.4f}", f"c=0 {p['mu_by_c'][0.0]:.4f}", flush=True)
    cal = [p for p in pts if p["group"] == CALIBRATION]

    def fitted(sample):
        """(c0, L0) minimising the squared log error over ``sample``, μ(c) interpolated on the grid (monotone in c)."""
        def loss(theta):
            return sum(np.log(np.interp(min(closure_c(theta, q["inlet_over_beta"]), grid[-1]), grid,
                                        [q["mu_by_c"][float(g)] for g in grid]) / q["mu_det"]) ** 2 for q in sample)
        theta = minimize(loss, [MICRO_PRESSURE_C0, MICRO_PRESSURE_INLET_SCALE], method="Nelder-Mead",
                         options={"xatol": 1e-4, "fatol": 1e-8, "maxiter": 4000}).x
        return [abs(float(v)) for v in theta]

    theta_fit = fitted(cal)
    leave_one_out = []
    for i, p in enumerate(cal):
        theta_i = fitted(cal[:i] + cal[i + 1:])
        c_i = closure_c(theta_i, p["inlet_over_beta"])
        leave_one_out.append(film_law_mu(p, lubricant, c_i) / p["mu_det"] - 1.0)
        p["leave_one_out_theta"], p["leave_one_out_c"], p["leave_one_out_error"] = theta_i, c_i, leave_one_out[-1]
    for p in pts:
        p["c_shipped"] = micro_pressure_coefficient(p["inlet_over_beta"])
        p["mu_shipped"] = film_law_mu(p, lubricant, None)
        p["error_without"] = p["mu_by_c"][0.0] / p["mu_det"] - 1.0
        p["error_with"] = p["mu_shipped"] / p["mu_det"] - 1.0
        p["holdout"] = p["group"] == CALIBRATION and p["label"] not in SHIPPED_FIT_POINTS
    holdout = [p for p in pts if p["holdout"]]
    groups = {}
    for name in sorted({p["group"] for p in pts}):
        for width, sel in (("narrow", [p for p in pts if p["group"] == name and p["a_over_beta"] < WIDE_A_OVER_BETA]),
                           ("wide", [p for p in pts if p["group"] == name and p["a_over_beta"] >= WIDE_A_OVER_BETA])):
            if sel:
                groups[f"{name} ({width})"] = {"without_closure": stats([p["error_without"] for p in sel]),
                                               "with_closure": stats([p["error_with"] for p in sel])}
    summary = {"command": "python validation/micro_pressure_closure.py", "solver_version": SOLVER_VERSION,
               "machine": platform.platform(), "level": LEVEL, "form": "c = c0 / (1 + (L_in/(beta L0))^2)",
               "fitted": {"c0": theta_fit[0], "inlet_scale": theta_fit[1]},
               "shipped": {"c0": MICRO_PRESSURE_C0, "inlet_scale": MICRO_PRESSURE_INLET_SCALE},
               "leave_one_out": stats(leave_one_out), "calibration_points": [p["label"] for p in cal],
               "shipped_fit_points": list(SHIPPED_FIT_POINTS),
               "calibration_at_shipped_c": stats([p["error_with"] for p in cal]),
               "holdout_at_shipped_c": stats([p["error_with"] for p in holdout]) if holdout else None,
               "holdout_points": [p["label"] for p in holdout],
               "limits": {"narrow_closure_lambda": NARROW_CLOSURE_LAMBDA,
                          "narrow_closure_roughness": NARROW_CLOSURE_ROUGHNESS,
                          "narrow_film_law_eyring": NARROW_FILM_LAW_EYRING},
               "groups": groups, "c_grid": grid.tolist(),
               "points": [{**p, "mu_by_c": [p["mu_by_c"][float(c)] for c in grid if float(c) in p["mu_by_c"]]}
                          for p in pts]}
    OUT.write_text(json.dumps(summary, indent=1) + "\n")
    print(json.dumps({k: summary[k] for k in ("fitted", "shipped", "leave_one_out", "calibration_at_shipped_c",
                                              "holdout_at_shipped_c", "groups")}, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
