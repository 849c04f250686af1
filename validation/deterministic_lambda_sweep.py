"""μ of the deterministic solver over a roughness sweep at fixed load, speed, sliding and temperature: the limit
"μ falls monotonically with λ̄ (within 2 standard errors), steeply below λ̄ ≈ 1 and gently above" of
docs/explanation/mixed-regime.md (the trend of the paper's Fig. 2).

    python validation/deterministic_lambda_sweep.py --spacing 16 --passes 11

Case A's conditions (0.5 GPa / 5 mm / 5 m/s / SR 0.3 / 90 °C, ATF) with Rq1 = Rq2 = each of ``--rq-um``; one grid
spacing Δx = β/``--spacing`` for all (the same nodes), and the same roughness shape at the same times, scaled to each
Rq, so that neighbouring runs are paired. Writes validation/results/deterministic_lambda_sweep.json (resumable: a
run already in the file at the same model version, spacing and passes is kept) with μ, its standard error, the
asperity share, λ̄, the smooth μ, and per neighbouring pair the slope d ln μ / d ln λ̄ and whether μ falls within
2 standard errors (paired differences of the μ(t) series, kept in validation/results/deterministic_lambda_sweep/).

    python validation/deterministic_lambda_sweep.py --spacing 16 --passes 11 --rq-um 0.5 0.8 --courant 0.5 0.125

    python validation/deterministic_lambda_sweep.py --spacing 8 --passes 6 --conditions 1.0 10 2 0.4 50 --tag J \
        --rq-um 0.05 0.1 0.2 0.3 0.5 0.8

``--conditions`` P_GPA R_MM U_M_S SR T_C: another contact (default case A's), with ``--tag``: its own result file
(deterministic_lambda_sweep_<tag>.json) and series directory; e.g. case J's, where the traction is Eyring-saturated
(X_h ≈ 960) and the film law's μ falls as the roughness grows (its rough inlet feeds a thicker film).

``--courant``: instead, the time-step check of the runs already in the sweep: each ``--rq-um`` rerun at each Courant
number, paired with the sweep's run at the default (validation/results/deterministic_lambda_sweep_courant.json).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solvers.deterministic import MODEL_VERSION, DeterministicOptions, solve_deterministic
from ehl_dataset.solvers.time_average import time_mean

RESULTS = Path(__file__).resolve().parent / "results"
CONDITIONS = (0.5, 5.0, 5.0, 0.3, 90.0)
"""p_h [GPa], r_eq [mm], u_r [m/s], SR, T [°C]: case A of the validation set."""
RQ_UM = (0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.8)
MAX_PASSES = 40.0


SERIES = RESULTS / "deterministic_lambda_sweep"
"""The μ(t) series of each run (``<Rq>.npz``: t_s, mu over the averaging window); a tagged sweep's in SERIES_<tag>."""


def series_dir(tag: str | None) -> Path:
    return SERIES if not tag else SERIES.with_name(f"{SERIES.name}_{tag}")


def series(run: dict, tag: str | None = None) -> tuple[np.ndarray, np.ndarray]:
    data = np.load(series_dir(tag) / f"{run['rq_um']:g}.npz")
    return data["t_s"], data["mu"]


def paired(run_a: dict, run_b: dict, tag: str | None = None) -> tuple[float, float]:
    """(mean, standard error) of μ_b(t) − μ_a(t) over the common times (the series of b interpolated)."""
    (ta, ma), (tb, mb) = series(run_a, tag), series(run_b, tag)
    inside = (ta >= tb[0]) & (ta <= tb[-1])
    mean = time_mean(np.interp(ta[inside], tb, mb) - ma[inside])
    return mean.mean, mean.standard_error


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--spacing", type=float, default=16.0)
    parser.add_argument("--passes", type=float, default=11.0)
    parser.add_argument("--rq-um", type=float, nargs="+", default=list(RQ_UM))
    parser.add_argument("--conditions", type=float, nargs=5, default=list(CONDITIONS),
                        metavar=("P_GPA", "R_MM", "U_M_S", "SR", "T_C"))
    parser.add_argument("--tag", default=None, help="name of another contact's sweep (with --conditions)")
    parser.add_argument("--courant", type=float, nargs="+", default=None,
                        help="time-step check of the sweep's runs at these Courant numbers")
    args = parser.parse_args(argv)
    if args.courant:
        if args.tag:
            parser.error("--courant checks case A's sweep only (no --tag)")
        return courant_check(args)
    conditions = tuple(args.conditions)
    if conditions != tuple(CONDITIONS) and not args.tag:
        parser.error("--conditions other than case A's need a --tag")
    path = RESULTS / (f"deterministic_lambda_sweep_{args.tag}.json" if args.tag else "deterministic_lambda_sweep.json")
    record = json.loads(path.read_text()) if path.exists() else {}
    key = (MODEL_VERSION, args.spacing, args.passes, list(conditions))
    if (record.get("model_version"), record.get("points_per_beta"), record.get("passes"),
            list(record.get("conditions", []))) != key:
        record = {"conditions": conditions, "model_version": MODEL_VERSION, "points_per_beta": args.spacing,
                  "passes": args.passes, "runs": {}}
    state = load_lubricant("atf").state(conditions[4] + 273.15)
    beta = baseline_profile().correlation_length
    for rq in sorted(args.rq_um):
        name = f"{rq:g}"
        if name in record["runs"]:
            continue
        case = ContactCase.from_engineering(*conditions, rq, rq)
        options = DeterministicOptions(dx_m=beta / args.spacing, max_passes=MAX_PASSES, mu_sem_target=1.0,
                                       min_average_passes=args.passes - 1.5)
        start = time.time()
        # the baseline profile (spacing in its β; runs paired across Rq and versions), not the default
        result = solve_deterministic(case, state, Effects.full(), options, roughness=baseline_profile())
        e = result.extra
        window = slice(e["average_from_step"], None)
        mu = np.asarray(e["mu_series"][window], dtype=float)
        record["runs"][name] = {
            "rq_um": rq, "lambda_bar": result.lambda_bar, "mu": float(np.mean(mu)),
            "mu_sem": time_mean(mu).standard_error, "asperity_load_share": result.asperity_load_share,
            "smooth_mu": e.get("smooth_mu"), "h_central_m": result.h_central, "converged": result.converged,
            "message": result.message, "n_steps": e["n_steps"], "wall_time_s": time.time() - start}
        series_dir(args.tag).mkdir(parents=True, exist_ok=True)
        np.savez_compressed(series_dir(args.tag) / f"{rq:g}.npz", t_s=np.asarray(e["t_series_s"][window], dtype=float),
                            mu=mu)
        _compare(record, args.tag)
        path.write_text(json.dumps(record, indent=1))
        run = record["runs"][name]
        print(f"Rq {rq:g} µm: λ̄ {run['lambda_bar']:.3g}, μ {run['mu']:.5f} ± {run['mu_sem']:.5f}, share "
              f"{run['asperity_load_share']:.3f}, {run['wall_time_s']:.0f} s", flush=True)
    return 0


def courant_check(args) -> int:
    """Rerun sweep points at other Courant numbers, paired with the sweep's run (same roughness, same times)."""
    sweep = json.loads((RESULTS / "deterministic_lambda_sweep.json").read_text())
    if sweep["model_version"] != MODEL_VERSION:
        raise SystemExit(f"the sweep was made under {sweep['model_version']}, not {MODEL_VERSION}: rerun it first")
    path = RESULTS / "deterministic_lambda_sweep_courant.json"
    record = json.loads(path.read_text()) if path.exists() else {}
    if record.get("model_version") != MODEL_VERSION:
        record = {"model_version": MODEL_VERSION, "points_per_beta": sweep["points_per_beta"],
                  "passes": sweep["passes"], "default_courant": DeterministicOptions().courant, "runs": {}}
    state = load_lubricant("atf").state(CONDITIONS[4] + 273.15)
    beta = baseline_profile().correlation_length
    for rq in args.rq_um:
        base = sweep["runs"][f"{rq:g}"]
        for courant in args.courant:
            name = f"{rq:g}_courant_{courant:g}"
            if name in record["runs"]:
                continue
            case = ContactCase.from_engineering(*CONDITIONS, rq, rq)
            options = DeterministicOptions(dx_m=beta / sweep["points_per_beta"], max_passes=MAX_PASSES,
                                           mu_sem_target=1.0, min_average_passes=sweep["passes"] - 1.5,
                                           courant=courant)
            start = time.time()
            # the sweep's baseline profile, not the default
            result = solve_deterministic(case, state, Effects.full(), options, roughness=baseline_profile())
            e = result.extra
            window = slice(e["average_from_step"], None)
            mu = np.asarray(e["mu_series"][window], dtype=float)
            t = np.asarray(e["t_series_s"][window], dtype=float)
            t_base, mu_base = series(base)
            inside = (t_base >= t[0]) & (t_base <= t[-1])
            paired_mean = time_mean(np.interp(t_base[inside], t, mu) - mu_base[inside])
            record["runs"][name] = {
                "rq_um": rq, "courant": courant, "mu": float(np.mean(mu)), "mu_sem": time_mean(mu).standard_error,
                "asperity_load_share": result.asperity_load_share, "base_mu": base["mu"],
                "base_asperity_load_share": base["asperity_load_share"],
                "paired_delta_mu": paired_mean.mean, "paired_delta_mu_sem": paired_mean.standard_error,
                "converged": result.converged, "wall_time_s": time.time() - start}
            path.write_text(json.dumps(record, indent=1))
            run = record["runs"][name]
            print(f"Rq {rq:g} µm at Courant {courant:g}: μ {run['mu']:.5f} (share {run['asperity_load_share']:.4f}) "
                  f"against {base['mu']:.5f} (share {base['asperity_load_share']:.4f}): paired "
                  f"{run['paired_delta_mu'] / base['mu']:+.2%} ± {run['paired_delta_mu_sem'] / base['mu']:.2%}",
                  flush=True)
    return 0


def _compare(record: dict, tag: str | None = None) -> None:
    """Per neighbouring pair (ordered by falling λ̄): paired Δμ ± SE, falls within 2 SE, d ln μ / d ln λ̄."""
    runs = sorted(record["runs"].values(), key=lambda r: -r["lambda_bar"])
    pairs = []
    for thick, thin in zip(runs, runs[1:]):
        mean, sem = paired(thick, thin, tag)
        slope = math.log(thin["mu"] / thick["mu"]) / math.log(thin["lambda_bar"] / thick["lambda_bar"])
        pairs.append({"lambda_bar": [thick["lambda_bar"], thin["lambda_bar"]], "delta_mu": mean, "delta_mu_sem": sem,
                      "mu_rises_as_lambda_falls_within_2_sem": bool(mean > -2.0 * sem),
                      "d_ln_mu_d_ln_lambda": slope})
    record["pairs"] = pairs


if __name__ == "__main__":
    sys.exit(main())
