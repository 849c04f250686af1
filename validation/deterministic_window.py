"""The periodic window (ehl_dataset.solvers.periodic_window) against a fully resolved wide contact: does a window at
the local mean conditions of the Hertzian centre reproduce the local traction, asperity share and film of the full
run there, and what does feeding it the smooth central film instead of the resolved one change?

    python validation/deterministic_window.py --inputs 1.0 10 5 0.2 75 0.4 0.4 --spacing 8 --passes 4 --tag V1

1. The full deterministic run (cached in validation/results/deterministic_window_<tag>_full.npz): its time-averaged
   profiles of total and contact pressure, shear stress and lubricant content, averaged over the centre |x| < 0.2 a.
2. Windows of ``--lengths`` correlation lengths at the same grid spacing, at that mean pressure, holding that content
   (fed "resolved"), and holding the content of the smooth solution's central film (fed "smooth").
Writes validation/results/deterministic_window_<tag>.json.

    python validation/deterministic_window.py --inputs 1.0 10 5 0.2 75 0.4 0.4 --spacing 8 --passes 4 --tag V1 \
        --across --lengths 8 --window-spacing 8 --courant 1

``--across``: windows at five Gauss–Legendre points of |x| < 0.9 a, each fed the resolved local mean pressure and
film; their shear integrated over that zone plus the resolved shear outside it gives a two-scale whole-contact μ
(deterministic_window_<tag>_across_beta<n>.json).
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
from ehl_dataset.solvers.deterministic import MODEL_VERSION, DeterministicOptions, solve_deterministic
from ehl_dataset.solvers.periodic_window import WindowOptions, solve_window

RESULTS = Path(__file__).resolve().parent / "results"
CENTRE = 0.2
"""Half width of the central band [a] over which the full run's profiles are averaged."""
PROFILES = ("mean_pressure_profile_pa", "mean_contact_pressure_profile_pa", "mean_shear_stress_profile_pa",
            "mean_content_film_profile_m")


def full_run(case, state, spacing: float, passes: float, path: Path) -> dict:
    if path.exists():
        data = np.load(path)
        return {k: data[k] for k in data.files}
    beta = baseline_profile().correlation_length
    start = time.time()
    result = solve_deterministic(case, state, Effects.full(),
                                 DeterministicOptions(dx_m=beta / spacing, max_passes=passes, mu_sem_target=0.0),
                                 roughness=baseline_profile())  # spacing in baseline β: not the default profile
    data = {"x_m": result.x, "film_m": result.film, **{k: result.extra[k] for k in PROFILES},
            "mu": result.mu, "mu_sem": result.mu_sem, "share": result.asperity_load_share,
            "converged": result.converged, "wall_time_s": time.time() - start, "n_steps": result.extra["n_steps"],
            "n_nodes": result.extra["n_nodes"], "model_version": MODEL_VERSION}
    np.savez_compressed(path, **data)
    return data


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--inputs", nargs=7, type=float, required=True, metavar="X")
    parser.add_argument("--spacing", type=float, default=8.0)
    parser.add_argument("--passes", type=float, default=4.0)
    parser.add_argument("--lengths", type=float, nargs="+", default=[8.0, 16.0])
    parser.add_argument("--tag", required=True)
    parser.add_argument("--across", action="store_true",
                        help="instead: windows of the first --lengths at --window-spacing across the Hertzian zone "
                             "(Gauss-Legendre points of |x| < 0.9 a), each fed the resolved local pressure and film, "
                             "and the whole-contact mu they give with the resolved shear outside that zone")
    parser.add_argument("--window-spacing", type=float, default=None, help="points per β of the windows")
    parser.add_argument("--courant", type=float, default=None, help="Courant number of the windows")
    args = parser.parse_args(argv)
    case = ContactCase.from_engineering(*args.inputs)
    state = load_lubricant("atf").state(case.temperature)
    full = full_run(case, state, args.spacing, args.passes, RESULTS / f"deterministic_window_{args.tag}_full.npz")
    if args.across:
        return across(case, state, full, args)
    x = full["x_m"] / case.half_width
    centre = np.abs(x) < CENTRE
    local = {k: float(np.mean(full[k][centre])) for k in PROFILES}
    p_bar = local["mean_pressure_profile_pa"]
    resolved = {"mu_local": local["mean_shear_stress_profile_pa"] / p_bar,
                "asperity_share": local["mean_contact_pressure_profile_pa"] / p_bar,
                "content_film_m": local["mean_content_film_profile_m"], "mean_pressure_pa": p_bar,
                "contact_mu": float(full["mu"]), "contact_mu_sem": float(full["mu_sem"]),
                "wall_time_s": float(full["wall_time_s"]), "n_nodes": int(full["n_nodes"]),
                "n_steps": int(full["n_steps"])}
    from ehl_dataset.solvers.steady import solve_steady
    from ehl_dataset.solvers.levels import get_level

    full_plan = Effects.full()
    smooth = solve_steady(case, state, get_level("standard"),
                          Effects(False, False, full_plan.shear_thinning, full_plan.compressibility, full_plan.mode, {}))
    smooth_centre = float(np.mean(smooth.film[np.abs(smooth.x / case.half_width) < CENTRE]))
    record = {"inputs": args.inputs, "model_version": MODEL_VERSION, "points_per_beta": args.spacing,
              "passes": args.passes, "a_over_beta": case.half_width / baseline_profile().correlation_length,
              "centre_half_width_a": CENTRE, "resolved_centre": resolved, "smooth_central_film_m": smooth_centre,
              "windows": []}
    out = RESULTS / f"deterministic_window_{args.tag}.json"
    print(json.dumps(record), flush=True)
    for feed, film in (("resolved", local["mean_content_film_profile_m"]), ("smooth", smooth_centre)):
        for length in args.lengths:
            options = WindowOptions(length_beta=length, points_per_beta=args.spacing)
            result = solve_window(case, state, p_bar, film, options, roughness=baseline_profile())  # the full run's
            row = {"feed": feed, "length_beta": length, "fed_film_m": film, "mu_local": result.mu_local,
                   "mu_local_sem": result.mu_local_sem, "asperity_share": result.asperity_share,
                   "asperity_share_sem": result.asperity_share_sem, "content_film_m": result.content_film_m,
                   "mean_film_m": result.mean_film_m, "min_film_m": result.min_film_m,
                   "converged": result.converged, "message": result.message, "wall_time_s": result.wall_time_s,
                   "n_nodes": result.n_nodes, "n_steps": result.n_steps,
                   "mu_local_relative_to_resolved": result.mu_local / resolved["mu_local"] - 1.0}
            record["windows"].append(row)
            out.write_text(json.dumps(record, indent=1))
            print(json.dumps(row), flush=True)
    return 0


ACROSS_POINTS = 5
ACROSS_EDGE = 0.9
"""Windows at the Gauss–Legendre points of |x| < ACROSS_EDGE·a (ACROSS_POINTS of them) for ``--across``."""


def across(case, state, full: dict, args) -> int:
    """Two-scale whole-contact μ: ∫τ̄ dx / W' with τ̄ from windows inside |x| < 0.9 a and from the resolved run
    outside; compared with the resolved run's own μ and its own ∫τ̄ over the same zone."""
    x = full["x_m"] / case.half_width
    nodes, weights = np.polynomial.legendre.leggauss(ACROSS_POINTS)
    positions, weights = ACROSS_EDGE * nodes, ACROSS_EDGE * weights * case.half_width
    spacing = args.window_spacing or args.spacing
    extra = {"courant": args.courant} if args.courant else {}
    options = WindowOptions(length_beta=args.lengths[0], points_per_beta=spacing, **extra)
    tau = full["mean_shear_stress_profile_pa"]
    inside = np.abs(x) < ACROSS_EDGE
    dx = float(full["x_m"][1] - full["x_m"][0])
    outside_force = float(np.sum(tau[~inside])) * dx
    resolved_inside = float(np.sum(tau[inside])) * dx
    rows, window_inside = [], 0.0
    for position, weight in zip(positions, weights):
        p_bar = float(np.interp(position, x, full["mean_pressure_profile_pa"]))
        film = float(np.interp(position, x, full["mean_content_film_profile_m"]))
        result = solve_window(case, state, p_bar, film, options, roughness=baseline_profile())  # the full run's
        window_inside += weight * result.shear_stress_pa
        rows.append({"x_over_a": position, "pressure_pa": p_bar, "film_m": film,
                     "resolved_shear_pa": float(np.interp(position, x, tau)), "window_shear_pa": result.shear_stress_pa,
                     "mu_local": result.mu_local, "mu_local_sem": result.mu_local_sem,
                     "asperity_share": result.asperity_share, "converged": result.converged,
                     "wall_time_s": result.wall_time_s})
        print(json.dumps(rows[-1]), flush=True)
    load = case.load_per_length
    record = {"inputs": args.inputs, "model_version": MODEL_VERSION, "full_points_per_beta": args.spacing,
              "window_points_per_beta": spacing, "window_length_beta": args.lengths[0],
              "window_courant": options.courant, "windows": rows,
              "resolved_mu": float(full["mu"]), "resolved_mu_sem": float(full["mu_sem"]),
              "resolved_zone_force_per_length_n_m": resolved_inside, "window_zone_force_per_length_n_m": window_inside,
              "outside_force_per_length_n_m": outside_force,
              "two_scale_mu": (window_inside + outside_force) / load,
              "resolved_profile_mu": (resolved_inside + outside_force) / load,
              "window_time_s": sum(r["wall_time_s"] for r in rows)}
    tag = f"{args.tag}_across_beta{spacing:g}"
    (RESULTS / f"deterministic_window_{tag}.json").write_text(json.dumps(record, indent=1))
    print(json.dumps({k: v for k, v in record.items() if k != "windows"}), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
