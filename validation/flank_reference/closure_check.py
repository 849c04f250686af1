"""The production closures against the deterministic reference on both shipped roughness profiles: the film-law model
and the asperity-load closure, each with the two forms of the micro-EHL pressure spread (``inlet``: c(L_in/β)·E'Δq/4,
calibrated on the baseline profile; ``spectral``: E'Δq_f/4 from the flattened part of the profile's spectrum), and
the asperity closure's constants (c_∇, c_p, n) fitted on the baseline validation set alone and on both sets, with
leave-one-out errors.

Reference cases:

* the 12 grid-converged validation cases on the baseline profile (data/reference/deterministic_validation.json: μ
  and share extrapolated, with their uncertainties);
* the flank-like reference (``flank_ground``, validation/flank_reference/run_sweeps.py): every point with a finished
  segment. Its estimate is the multilevel one, μ(λ_s/4) over the long window plus the paired steps to the finer
  spacings; its uncertainty combines the standard errors with the last grid step (the grid error still possible),
  or, where only λ_s/4 has run, with the whole roughness effect |μ − μ_smooth| (the share: the share itself): a
  point whose grid has not been checked weighs little and is not held to the acceptance.

Also the scale k of the spectral form σ_p = k·E'Δq_f/4 fitted freely on the 33 contacts that calibrate the inlet
form (validation/results/micro_pressure_closure.json, their film-law μ tabulated against c).

    python validation/flank_reference/closure_check.py     # → validation/results/flank_reference_closures.json

Isothermal, level ``standard`` (as validation/asperity_model_loo.py); the fit minimises

    Σ_i [ ln(μ_i/μ_ref,i)² / (0.05² + u_μ,i²) + (s_i − s_ref,i)² / (0.05² + u_s,i²) ].
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from run_sweeps import RESULTS as SEGMENTS, paired_step  # noqa: E402

from ehl_dataset.model.amplitude_reduction import flattened_slope_rms  # noqa: E402
from ehl_dataset.model.contact import ContactCase  # noqa: E402
from ehl_dataset.model.lubricant import load_lubricant  # noqa: E402
from ehl_dataset.model.micro_pressure import composite_slope_rms  # noqa: E402
from ehl_dataset.model.roughness import baseline_profile, named_profile  # noqa: E402
from ehl_dataset.solver import SOLVER_VERSION, solve_contact  # noqa: E402
from ehl_dataset.solvers.asperity_model import (ASPERITY_MODEL_VERSION, FLATTENING_EXPONENT, NABLA_SCALE,  # noqa: E402
                                                PRESSURE_SCALE, asperity_closure)
from ehl_dataset.solvers.homogenised import BOUNDARY_FILM_M, HomogenisedOptions  # noqa: E402
from workflows.accuracy_mixed import load_reference, reference_case  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
RESULT = ROOT / "results" / "flank_reference_closures.json"
MICRO_PRESSURE = ROOT / "results" / "micro_pressure_closure.json"
NABLA_GRID = 2.0 ** np.arange(0, 6)
PRESSURE_GRID = np.round(np.exp(np.linspace(0.0, math.log(4.0), 11)), 4)
EXPONENT_GRID = (1.0, 2.0, 3.0)
GRID = [(a, b, n) for a in NABLA_GRID for b in PRESSURE_GRID for n in EXPONENT_GRID]
"""(c_∇, c_p, n) scanned, as validation/asperity_model_loo.py."""
MU_FLOOR = SHARE_FLOOR = 0.05
ACCEPT_UNCERTAINTY = 0.05
"""Cases whose relative μ uncertainty is below this are held to the acceptance (|Δμ| ≤ 15 %, |Δshare| ≤ 0.10)."""
FORMS = ("inlet", "spectral")


def flank_reference() -> list[dict]:
    """One row per flank-reference point with a finished segment: the multilevel μ and share with uncertainties."""
    runs: dict[str, dict[int, dict]] = {}
    for path in sorted(SEGMENTS.glob("*_ls*.json")):
        if path.name.endswith(".error.json"):
            continue
        seg = json.loads(path.read_text(encoding="utf-8"))
        if seg.get("converged"):
            runs.setdefault(seg["point"], {})[seg["spacing_divisor"]] = seg
    rows = []
    for name, by_n in sorted(runs.items()):
        spacings = sorted(by_n)
        base = by_n[spacings[0]]
        mu, share = base["mu"], base["asperity_load_share"]
        var_mu, var_s = base["mu_sem"] ** 2, base.get("asperity_load_share_sem", 0.0) ** 2
        last_mu = last_s = None
        for coarse, fine in zip(spacings, spacings[1:]):
            step, sem, _ = paired_step(by_n[coarse], by_n[fine])
            a = {w[0]: w[1] for w in by_n[coarse]["share_windows"]}
            b = {w[0]: w[1] for w in by_n[fine]["share_windows"]}
            common = sorted(set(a) & set(b))
            step_s = float(np.mean([b[t] - a[t] for t in common])) if common else 0.0
            if math.isfinite(step):
                mu, var_mu, last_mu = mu + step, var_mu + sem**2, step
            share, last_s = share + step_s, step_s
        grid_mu = abs(mu - base["smooth_mu"]) if last_mu is None else abs(last_mu)
        grid_s = abs(share) if last_s is None else abs(last_s)
        p, r, u, sr, t, rq1, rq2 = (base["inputs"][k] for k in ("p_h_gpa", "r_eq_mm", "u_r_m_s", "sr", "temp_c",
                                                                 "rq1_um", "rq2_um"))
        rows.append({"case": f"flank {name}", "profile": "flank_ground", "inputs": [p, r, u, sr, t, rq1, rq2],
                     "spacings": spacings, "lambda_bar": base["lambda_bar"], "mu": mu,
                     "mu_uncertainty": math.sqrt(var_mu + grid_mu**2), "share": max(share, 0.0),
                     "share_uncertainty": math.sqrt(var_s + grid_s**2), "smooth_mu": base["smooth_mu"],
                     "grid_checked": last_mu is not None})
    return rows


def baseline_reference() -> list[dict]:
    rows = []
    for row in load_reference():
        i = row["inputs"]
        rows.append({"case": f"baseline {row['case']}", "profile": "baseline_synthetic",
                     "inputs": [i[k] for k in ("p_h_gpa", "r_eq_mm", "u_r_m_s", "sr", "temp_c", "rq1_um", "rq2_um")],
                     "lambda_bar": row["lambda_bar"], "mu": row["mu_extrapolated"],
                     "mu_uncertainty": row["mu_uncertainty"],
                     "share": row.get("asperity_load_share_extrapolated", 0.0),
                     "share_uncertainty": row.get("asperity_load_share_uncertainty", 0.0), "grid_checked": True,
                     "_case": reference_case(row)})
    return rows


def spectral_scale_fit(lub) -> dict:
    """k of σ_p = k·E'Δq_f/4 fitted on the inlet form's calibration set (its μ(c) tables), with leave-one-out."""
    data = json.loads(MICRO_PRESSURE.read_text(encoding="utf-8"))
    grid = np.asarray(data["c_grid"])
    chosen = set(data["calibration_points"])
    profile = baseline_profile()
    points = []
    for pt in data["points"]:
        if pt["label"] not in chosen:
            continue
        case = ContactCase.from_engineering(*pt["inputs"])
        state = lub.state(case.temperature)
        ratio = flattened_slope_rms(profile, case, state) / composite_slope_rms(profile, case.rq1, case.rq2)
        points.append((pt["label"], ratio, np.asarray(pt["mu_by_c"]), pt["mu_det"]))
    ks = np.linspace(0.0, 3.0, 601)

    def errors(k, pts):
        return np.array([math.log(np.interp(min(k * ratio, grid[-1]), grid, mus) / ref) for _, ratio, mus, ref in pts])

    def fit(pts):
        return ks[int(np.argmin([np.sum(errors(k, pts) ** 2) for k in ks]))]

    k_all = fit(points)
    loo = [float(np.expm1(errors(fit(points[:i] + points[i + 1:]), [p])[0])) for i, p in enumerate(points)]
    at_one = np.expm1(errors(1.0, points))
    return {"k_fitted": float(k_all), "n": len(points), "loo_median_abs": float(np.median(np.abs(loo))),
            "loo_p90_abs": float(np.percentile(np.abs(loo), 90)),
            "k1_median_abs": float(np.median(np.abs(at_one))), "k1_p90_abs": float(np.percentile(np.abs(at_one), 90)),
            "inlet_form_loo": data["leave_one_out"]}


def objective(mu, share, rows, idx):
    ref = np.array([rows[i]["mu"] for i in idx])
    u_mu = np.array([rows[i]["mu_uncertainty"] / rows[i]["mu"] for i in idx])
    ref_s = np.array([rows[i]["share"] for i in idx])
    u_s = np.array([rows[i]["share_uncertainty"] for i in idx])
    w_mu, w_s = 1.0 / (MU_FLOOR**2 + u_mu**2), 1.0 / (SHARE_FLOOR**2 + u_s**2)
    return np.sum(w_mu[:, None] * np.log(mu[idx] / ref[:, None]) ** 2
                  + w_s[:, None] * (share[idx] - ref_s[:, None]) ** 2, axis=0)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--out", default=str(RESULT))
    args = parser.parse_args(argv)
    lub = load_lubricant("atf")
    rows = baseline_reference() + flank_reference()
    profiles = {"baseline_synthetic": baseline_profile(), "flank_ground": named_profile("flank_ground")}
    shipped = GRID.index((NABLA_SCALE, PRESSURE_SCALE, FLATTENING_EXPONENT))
    scans = {}
    for form in FORMS:
        mu = np.empty((len(rows), len(GRID)))
        share = np.empty_like(mu)
        film_law = []
        for i, row in enumerate(rows):
            case = row.get("_case") or ContactCase.from_engineering(*row["inputs"])
            state = lub.state(case.temperature)
            profile = profiles[row["profile"]]
            fl = solve_contact(case, lub, "standard", "isothermal", roughness=profile, model="homogenised",
                               homogenised=HomogenisedOptions(closure="film_law", fluctuations=form))
            film_law.append(fl.mu)
            for j, (cn, cp, n) in enumerate(GRID):
                res = asperity_closure(fl, case, state, profile, BOUNDARY_FILM_M, pressure_scale=float(cp),
                                       nabla_scale=float(cn), flattening_exponent=float(n), fluctuations=form)
                if not res.converged:
                    raise RuntimeError(f"{row['case']} ({cn:g}, {cp:g}, {n:g}): {res.message}")
                mu[i, j], share[i, j] = res.mu, res.asperity_load_share
            print(f"{form}: {row['case']}: film law {fl.mu:.4f}, reference {row['mu']:.4f}", flush=True)
        scans[form] = (mu, share, np.array(film_law))
    baseline_idx = [i for i, r in enumerate(rows) if r["profile"] == "baseline_synthetic"]
    everything = list(range(len(rows)))
    variants = {}
    for form in FORMS:
        mu, share, film_law = scans[form]
        variants[f"film_law_{form}"] = {"mu": film_law.tolist(), "share": [0.0] * len(rows)}
        variants[f"asperity_{form}_shipped_constants"] = {"constants": list(GRID[shipped]),
                                                          "mu": mu[:, shipped].tolist(),
                                                          "share": share[:, shipped].tolist()}
        for label, fit_set in (("fitted_on_baseline", baseline_idx), ("fitted_on_both", everything)):
            best = int(np.argmin(objective(mu, share, rows, fit_set)))
            loo_mu, loo_share, loo_constants = [], [], []
            for i in everything:
                rest = [k for k in fit_set if k != i]
                j = int(np.argmin(objective(mu, share, rows, rest)))
                loo_mu.append(mu[i, j])
                loo_share.append(share[i, j])
                loo_constants.append(list(GRID[j]))
            variants[f"asperity_{form}_{label}"] = {"constants": list(GRID[best]), "mu": mu[:, best].tolist(),
                                                   "share": share[:, best].tolist(), "loo_mu": loo_mu,
                                                   "loo_share": loo_share, "loo_constants": loo_constants}
    summary = {}
    for name, v in variants.items():
        key_mu = "loo_mu" if "loo_mu" in v else "mu"
        key_s = "loo_share" if "loo_share" in v else "share"
        err = np.array([v[key_mu][i] / r["mu"] - 1.0 for i, r in enumerate(rows)])
        ds = np.array([v[key_s][i] - r["share"] for i, r in enumerate(rows)])
        held = np.array([r["mu_uncertainty"] / r["mu"] < ACCEPT_UNCERTAINTY for r in rows])
        summary[name] = {
            "errors_are": "leave-one-out" if key_mu == "loo_mu" else "as shipped (no fit)",
            "median_abs_mu_error": float(np.median(np.abs(err))),
            "median_abs_mu_error_baseline": float(np.median(np.abs(err[baseline_idx]))),
            "median_abs_mu_error_flank": float(np.median(np.abs(np.delete(err, baseline_idx)))),
            "max_abs_mu_error_held": float(np.max(np.abs(err[held]))),
            "max_abs_share_difference_held": float(np.max(np.abs(ds[held]))),
            "accepted": bool(np.max(np.abs(err[held])) <= 0.15 and np.max(np.abs(ds[held])) <= 0.10
                             and np.median(np.abs(err)) <= 0.07)}
    out = {"description": __doc__.split("\n\n")[0], "command": "python validation/flank_reference/closure_check.py",
           "solver_version": SOLVER_VERSION, "asperity_model_version": ASPERITY_MODEL_VERSION,
           "level": "standard", "effects": "isothermal", "grid": [list(g) for g in GRID],
           "spectral_scale": spectral_scale_fit(lub), "summary": summary,
           "cases": [{k: v for k, v in r.items() if not k.startswith("_")} for r in rows], "variants": variants}
    Path(args.out).write_text(json.dumps(out, indent=1, default=float) + "\n", encoding="utf-8")
    print(json.dumps({"spectral_scale": out["spectral_scale"], "summary": summary}, indent=1))
    names = list(variants)
    print("| case | λ̄ | reference μ (± rel.) | share ± | " + " | ".join(names) + " |")
    for i, r in enumerate(rows):
        cells = []
        for name in names:
            v = variants[name]
            m = v.get("loo_mu", v["mu"])[i]
            s = v.get("loo_share", v["share"])[i]
            cells.append(f"{100 * (m / r['mu'] - 1):+.0f} % / {s:.2f}")
        print(f"| {r['case']} | {r['lambda_bar']:.2f} | {r['mu']:.4f} (± {100 * r['mu_uncertainty'] / r['mu']:.0f} %) | "
              f"{r['share']:.2f} ± {r['share_uncertainty']:.2f} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
