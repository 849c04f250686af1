"""``gearloss pipeline quick|paper``: factorial → friction surrogate → Design D, in one process.

``quick`` runs the 324-point ``quick`` factorial at the fast level, ``paper`` the 42,000-point
``paper2009`` factorial (the long run; ``--scheduler ADDRESS`` sends the points to a Dask cluster). Both write
``DIR/dataset.h5`` (continued if present), ``DIR/<lubricant>_<factorial>.json`` (+ ``.summary.txt``) and print
Design D's P [kW], η, TE, σ_c, σ_b at the study's operating point and the time of each stage. See
:mod:`workflows.pipeline` and docs/pipeline.md.
"""

from __future__ import annotations

import argparse

from .cli_output import emit


def register(subparsers) -> None:
    parser = subparsers.add_parser("pipeline", help="end-to-end: EHL factorial -> surrogate -> gear Design D")
    sub = parser.add_subparsers(dest="pipeline_command", metavar="COMMAND")
    parser.set_defaults(handler=lambda args: parser.print_help() or 2)
    for name, default, help_text in (
            ("quick", "quick", "quick factorial (324 points, fast level): the demo run"),
            ("paper", "paper2009", "the paper's 42,000-point factorial: the long run (many CPU-hours; Dask for clusters)")):
        p = sub.add_parser(name, help=help_text, description=help_text)
        p.add_argument("--out-dir", default=f"gearloss_{name}",
                       help=f"directory for dataset.h5 and the coefficient file (default gearloss_{name})")
        p.add_argument("--workers", type=int, default=1, help="local worker processes for stage 1 (default 1)")
        p.add_argument("--factorial", default=default,
                       help=f"factorial name or TOML file (default {default})")
        p.add_argument("--design", default="D", help="published design of the study to evaluate (default D)")
        p.add_argument("--progress", choices=("auto", "bar", "log", "none"), default="auto",
                       help="stage-1 progress on stderr (default auto: a bar on a terminal, log lines otherwise)")
        p.add_argument("--time-limit-s", type=float, default=None, metavar="SECONDS",
                       help="wall-time budget per point [s]; a point that spends it is stored as not converged with "
                            "its message (default: none)")
        p.add_argument("--allow-unstable", action="store_true",
                       help="keep a regression flagged unstable (ill-conditioned) instead of stopping")
        p.add_argument("--no-clip", action="store_true",
                       help="evaluate the fitted surrogate outside its fitted input ranges (default: clip the gear "
                            "contact conditions to those ranges and report how many points were clipped)")
        if name == "paper":
            p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                           help="Dask scheduler address (tcp://host:8786); default: local processes")
        p.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
        p.set_defaults(handler=run_pipeline_command)


def run_pipeline_command(args: argparse.Namespace) -> int:
    from ehl_dataset.dataset.runner import check_time_limit
    from ehl_dataset.validation import check_range

    from .pipeline import run_pipeline

    check_range("workers", args.workers, 1, 1024)
    check_time_limit(args.time_limit_s)
    result = run_pipeline(args.out_dir, args.factorial, workers=args.workers,
                          scheduler=getattr(args, "scheduler", None), progress=args.progress, design=args.design,
                          allow_unstable=args.allow_unstable, clip_to_fitted_ranges=not args.no_clip,
                          time_limit_s=args.time_limit_s)
    payload = result.to_dict()
    design = result.stage("design").details
    payload.update({k: design[k] for k in ("power_loss_w", "efficiency", "te_pp_m", "sigma_c_pa", "sigma_b_pa",
                                           "converged")})
    emit(payload, args.json, _human)
    return 0 if design["converged"] else 3


def _human(p: dict) -> str:
    s = p["stages"]
    data, fit, design = s["dataset"], s["fit"], s["design"]
    lines = [
        f"stage 1 dataset   {data['artefact']}: factorial {data['factorial']}, {data['n_points']} points, "
        f"{data['computed']} computed{' (resumed)' if data['resumed'] else ''}; ok {data['ok']}, failed "
        f"{data['failed']}, non-converged {data['non_converged']} — {data['wall_time_s']:.1f} s",
    ]
    for message, count in (data.get("failures") or {}).items():
        lines.append(f"                  {count} failed: {message}")
    branches = ", ".join(f"{b}: n={v['n_obs']}, adj R² {v['adj_r2']:.3f}" for b, v in fit["branches"].items())
    lines.append(f"stage 2 fit       {fit['artefact']}: {fit['n_used']} rows used ({branches}); CV RMSE ln μ "
                 f"{fit['cv_rmse_ln_mu']:.3f}; stable {fit['stable']} — {fit['wall_time_s']:.1f} s")
    lines.append(f"stage 3 design {design['design']} at {design['torque_nm']:.0f} N·m, {design['speed_rpm']:.0f} rpm, "
                 f"{design['oil_temperature_k'] - 273.15:.0f} °C, Rq {design['rq1_m'] * 1e6:.2g} µm, M_P "
                 f"{design['profile_crown_m'] * 1e6:.3g} µm, M_L {design['lead_crown_m'] * 1e6:.3g} µm — "
                 f"{design['wall_time_s'] * 1e3:.0f} ms")
    lines.append(f"  P = {design['power_loss_w'] / 1e3:.3f} kW, η = {design['efficiency'] * 100:.3f} %, "
                 f"TE p-p = {design['te_pp_m'] * 1e6:.3f} µm, σ_c = {design['sigma_c_pa'] / 1e9:.3f} GPa, "
                 f"σ_b = {design['sigma_b_pa'] / 1e6:.0f} MPa, mean μ = {design['mu_mean']:.4f}, "
                 f"converged {design['converged']}")
    clipped = design.get("clipped_to_fitted_range")
    if clipped:
        moved = ", ".join(f"{k} {v}" for k, v in clipped.items() if k != "contact_points" and v)
        lines.append(f"  surrogate inputs clipped to the fitted ranges at {moved or 'no'} of "
                     f"{clipped['contact_points']} contact points")
    for warning in fit["warnings"] + design["warnings"]:
        lines.append(f"  warning: {warning}")
    lines.append(f"total {p['wall_time_s']:.1f} s")
    return "\n".join(lines)
