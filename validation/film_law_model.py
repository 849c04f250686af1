"""The film-law homogenised model (ehl_dataset.solvers.film_law_model) against the deterministic model, and what it
costs (docs/explanation/mixed-regime.md, "Film-law closure").

    python validation/film_law_model.py            # writes validation/results/film_law_model.json and a table

Three comparisons, all with the ATF:
* the deterministic model's wide route (periodic windows) on the factorial corners with r_eq 80 mm
  (benchmarks/results/ehl_mixed_corners_fast_deterministic.json, level fast) — the film law and the smooth pressure
  are the same in both, so this isolates the closure of the traction;
* resolved deterministic contacts: V1 and W1 (docs/explanation/mixed-regime.md, "Wide contacts"), the validation set
  (data/reference/deterministic_validation.json) and the roughness sweep (benchmarks/results/
  deterministic_lambda_sweep.json): narrow contacts, a/β 1.5–12, outside the closure's validated range, reported to
  show where it fails;
* μ(λ̄) of the closure on three wide contacts, Rq1 = Rq2 from 0.01 to 1 µm (the trend a fit inherits);
* the same closure with the dry-contact table's asperity load at the film law's mean gap (p_a, μ_d p_a, fluid at
  p̄ − p_a): the variant the model does not take, and why.
Wall times are the film-law solve and the steady smooth solve of the same point, one process, other jobs possibly on
the machine (noted in the JSON).
"""

from __future__ import annotations

import json
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.dry_contact import dry_contact_table
from ehl_dataset.model.flow_factors import lubricated_shear_stress
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solver import SOLVER_VERSION, solve_contact
from ehl_dataset.solvers.film_law_model import FILM_LAW_MODEL_VERSION
from ehl_dataset.solvers.homogenised import HomogenisedOptions

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from _common import machine_info  # noqa: E402  (shared with the speed benchmarks)

ROOT = Path(__file__).resolve().parents[1]
CORNERS = ROOT / "benchmarks" / "results" / "ehl_mixed_corners_fast_deterministic.json"
REFERENCE = ROOT / "data" / "reference" / "deterministic_validation.json"
SWEEP = ROOT / "validation" / "results" / "deterministic_lambda_sweep.json"
OUT = ROOT / "validation" / "results" / "film_law_model.json"
RESOLVED_WIDE = {  # docs/explanation/mixed-regime.md, "Wide contacts": resolved at β/8, Courant 1
    "V1": ([1.0, 10, 5, 0.2, 75, 0.4, 0.4], 0.0233, 0.0009, "det-2026.11-7"),
    "W1": ([1.0, 20, 5, 0.2, 75, 0.4, 0.4], 0.0226, 0.0006, "det-2026.11-6"),
}
TREND_CONTACTS = ([1.0, 20, 5, 0.2, 75], [1.0, 80, 5, 0.2, 75], [2.0, 40, 2, 0.5, 100])
TREND_RQ_UM = (0.01, 0.05, 0.1, 0.2, 0.4, 0.7, 1.0)
MIN_MU = 1e-3
"""Relative errors are reported for sliding contacts (SR > 0) where the reference |μ| ≥ MIN_MU; pure rolling
(μ of order 1e-3 or less, the rolling part only) is compared by absolute values."""


def film_law(case, lubricant):
    """Isothermal, as the deterministic model (the planner's runs add the thermal correction where it matters); on
    the baseline profile every deterministic result compared here was computed on, not the package's default."""
    return solve_contact(case, lubricant, "standard", "isothermal", model="homogenised",
                         homogenised=HomogenisedOptions(closure="film_law"), roughness=baseline_profile())


def with_table_load(case, lubricant, result) -> tuple[float, float]:
    """μ of the variant with the dry-contact table's asperity load at the film law's mean gap (module docstring),
    and the share of the load the table gives the asperities."""
    state = lubricant.state(case.temperature)
    table = dry_contact_table(baseline_profile(), case.rq1, case.rq2, case.e_reduced)  # the film law's profile
    x, p, film = result.x, result.pressure, result.film
    p_a = np.asarray(table.asperity_pressure(film))
    shear = lubricated_shear_stress(table, film, state.viscosity(np.maximum(p - p_a, 0.0)), case.u_s, state.tau0,
                                    result.extra["boundary_film_m"])
    inside = shear + math.copysign(1.0, case.u_s) * (case.u_s != 0.0) * state.mu_d * p_a
    load = case.load_per_length
    def integral(f):
        return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(x))) / load

    return integral(inside) + result.extra["mu_poiseuille"] + result.extra["mu_outside_zone"], integral(p_a)


def run(case_args, lubricant, mu_ref, label, group):
    case = ContactCase.from_engineering(*case_args)
    start = time.perf_counter()
    result = film_law(case, lubricant)
    wall = time.perf_counter() - start
    start = time.perf_counter()
    smooth = solve_contact(case, lubricant, "standard", model="smooth")
    smooth_wall = time.perf_counter() - start
    table_mu, table_share = with_table_load(case, lubricant, result)
    row = {"group": group, "label": label, "case": list(case_args), "a_over_beta": result.extra["a_over_beta"],
           "lambda_bar": result.lambda_bar, "mu_reference": mu_ref, "mu": result.mu, "mu_smooth": smooth.mu,
           "mu_with_table_load": table_mu, "table_asperity_share": table_share, "converged": result.converged,
           "message": result.message, "narrow_contact": result.extra["narrow_contact"],
           "film_law_extrapolated": result.extra["film_law_extrapolated"],
           "wall_time_s": wall, "smooth_wall_time_s": smooth_wall}
    if case_args[3] > 0.0 and abs(mu_ref) >= MIN_MU:
        for key, name in (("mu", "error"), ("mu_smooth", "smooth_error"), ("mu_with_table_load", "table_load_error")):
            row[name] = row[key] / mu_ref - 1.0
    print(f"{group:10s} {label:28s} a/β {row['a_over_beta']:6.1f} λ̄ {row['lambda_bar']:6.2f} ref {mu_ref:8.5f} "
          f"film-law {result.mu:8.5f} ({100 * row.get('error', math.nan):+6.1f} %) smooth "
          f"{100 * row.get('smooth_error', math.nan):+6.1f} % table load {100 * row.get('table_load_error', math.nan):+6.1f} %"
          f"  {wall:.2f} s", flush=True)
    return row


def summary(rows) -> dict:
    out = {}
    for group in sorted({r["group"] for r in rows}):
        sel = [r for r in rows if r["group"] == group and "error" in r]
        if not sel:
            continue
        entry = {"n": len(sel)}
        for name in ("error", "smooth_error", "table_load_error"):
            errors = np.abs([r[name] for r in sel])
            entry[f"median_abs_{name}"] = float(np.median(errors))
            entry[f"p90_abs_{name}"] = float(np.percentile(errors, 90))
            entry[f"max_abs_{name}"] = float(np.max(errors))
        out[group] = entry
    walls = [r["wall_time_s"] for r in rows]
    smooth_walls = [r["smooth_wall_time_s"] for r in rows]
    out["timing"] = {"n": len(walls), "median_wall_s": statistics.median(walls), "mean_wall_s": statistics.fmean(walls),
                     "max_wall_s": max(walls), "mean_smooth_wall_s": statistics.fmean(smooth_walls),
                     "mean_ratio_to_smooth": statistics.fmean(walls) / statistics.fmean(smooth_walls)}
    rolling = [r for r in rows if r["group"] == "wide" and r["case"][3] == 0.0]
    if rolling:
        out["pure_rolling_max_abs_mu"] = {"film_law": max(abs(r["mu"]) for r in rolling),
                                          "deterministic_wide": max(abs(r["mu_reference"]) for r in rolling)}
    return out


def main() -> int:
    lubricant = load_lubricant("atf")
    rows = []
    corners = json.loads(CORNERS.read_text())
    for row in corners["rows"]:
        if row.get("route") == "wide" and row.get("converged"):
            rows.append(run(row["case"], lubricant, row["mu"], "corner", "wide"))
    for name, (inputs, mu_ref, _, _) in RESOLVED_WIDE.items():
        rows.append(run(inputs, lubricant, mu_ref, name, "resolved"))
    for case in json.loads(REFERENCE.read_text())["cases"]:
        inputs = list(case["inputs"].values())
        rows.append(run(inputs, lubricant, case["mu_extrapolated"], f"validation {case['case']}", "narrow"))
    sweep = json.loads(SWEEP.read_text())
    for run_ in sorted(sweep["runs"].values(), key=lambda r: r["rq_um"]):
        rows.append(run(list(sweep["conditions"]) + [run_["rq_um"], run_["rq_um"]], lubricant, run_["mu"],
                        f"sweep Rq {run_['rq_um']} µm", "narrow"))
    trend = []
    for inputs in TREND_CONTACTS:
        points = []
        for rq in TREND_RQ_UM:
            result = film_law(ContactCase.from_engineering(*inputs, rq, rq), lubricant)
            points.append({"rq_um": rq, "lambda_bar": result.lambda_bar, "mu": result.mu,
                           "a_over_beta": result.extra["a_over_beta"]})
        trend.append({"inputs": inputs, "points": points})
        print("trend", inputs, [(round(q["lambda_bar"], 2), round(q["mu"], 4)) for q in points], flush=True)
    report = {"benchmark": "film_law_model", "model_version": FILM_LAW_MODEL_VERSION, "solver_version": SOLVER_VERSION,
              "corners_source": str(CORNERS.relative_to(ROOT)), "corners_level": corners.get("level"),
              "resolved_wide": {k: {"inputs": v[0], "mu": v[1], "mu_sem": v[2], "model_version": v[3]}
                                for k, v in RESOLVED_WIDE.items()},
              "summary": summary(rows), "trend": trend, "rows": rows, "machine": machine_info()}
    OUT.write_text(json.dumps(report, indent=1, default=float))
    print(json.dumps(report["summary"], indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
