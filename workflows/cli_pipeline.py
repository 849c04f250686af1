"""``gearloss pipeline quick|paper|smoke``: factorial → friction surrogate → Design D, in one process.

``quick`` runs the 324-point ``quick`` factorial at the fast level, ``paper`` the 42,000-point ``paper2009``
factorial (the long run; ``--scheduler ADDRESS`` sends the points to a Dask cluster), ``smoke`` the 96-point
``smoke`` factorial with smooth-surface solves (every stage in seconds; its fit is not a friction model). Each run
writes ``DIR/dataset.h5`` and ``DIR/<lubricant>_<factorial>.json`` (+ ``.summary.txt``), DIR named after the
factorial, level, model, effects and a chosen roughness profile (``gearloss_quick_fast_isothermal``,
``..._flank_ground`` with ``--roughness flank_ground``; ``--out-dir`` chooses another), and prints Design D's
P [kW], η, TE, σ_c, σ_b at the study's operating point and the time of each stage. Running the same command again
resumes an interrupted run. See :mod:`workflows.pipeline` and docs/getting-started.md.
"""

from __future__ import annotations

import argparse
import sys

from ehl_dataset.names import LEVELS, MODELS

from .cli_fit_lines import add_form_options, fit_line, stage2_lines
from .cli_help import ACCURACY_EPILOG, EFFECTS_CHOICES, EFFECTS_HELP, model_help
from .cli_output import emit

COMMANDS = (
    ("quick", "quick", "quick factorial (324 points, fast level): the main job, under a minute with 2 workers"),
    ("paper", "paper2009", "the paper's 42,000-point factorial (standard level): the long run (12 min with 2 "
                           "workers on a 2-core machine, solver ehl-2026.11-15; Dask for clusters)"),
    ("smoke", "smoke", "smoke factorial (96 points, smooth-surface solves): every stage end to end in seconds, to "
                       "check an installation; its fit is not a friction model"),
)

EPILOG = """\
resuming: a run stopped by Ctrl-C (exit 130), SIGTERM (exit 143) or a crash keeps every finished point in
DIR/dataset.h5; the same command again continues it (only points not yet ok are computed). Runs of another
factorial, level or model go to their own directory; --overwrite starts a run afresh.
""" + ACCURACY_EPILOG + "; gearloss contact solve defaults to standard."


def register(subparsers) -> None:
    parser = subparsers.add_parser("pipeline", help="end-to-end: EHL factorial -> surrogate -> gear Design D",
                                   description=__doc__.split("\n\n")[1], epilog=EPILOG)
    sub = parser.add_subparsers(dest="pipeline_command", metavar="COMMAND")
    parser.set_defaults(handler=lambda args: parser.print_help() or 2)
    for name, default, help_text in COMMANDS:
        p = sub.add_parser(name, help=help_text, description=help_text, epilog=EPILOG)
        p.add_argument("--out-dir", default=None, metavar="DIR",
                       help="directory for dataset.h5 and the coefficient file (default: gearloss_<factorial>_"
                            "<level>[_<model>][_<effects>][_<roughness profile>], e.g. "
                            + ("gearloss_smoke_fast_smooth" if name == "smoke"
                                                                    else f"gearloss_{default}_" + (
                                                                        "fast" if name == "quick" else "standard")
                                                                    + "_isothermal") + ")")
        p.add_argument("--overwrite", action="store_true",
                       help="start afresh: replace the dataset and coefficient file in the output directory "
                            "instead of resuming them")
        p.add_argument("--workers", type=int, default=1, help="local worker processes for stage 1")
        p.add_argument("--factorial", default=default, help="factorial name or TOML file")
        p.add_argument("--level", default=None, choices=LEVELS,
                       help="EHL accuracy level of stage 1 (default: the factorial's: fast for quick and smoke, "
                            "standard for paper)")
        p.add_argument("--model", default=None, choices=MODELS, help=model_help("default: the factorial's (smooth for smoke, auto "
                                                                "otherwise)"))
        p.add_argument("--effects", choices=EFFECTS_CHOICES, default=None,
                       help=EFFECTS_HELP + "; default: the factorial's (isothermal for quick and paper, the "
                                              "paper's model; auto for smoke)")
        _add_roughness_options(p)
        p.add_argument("--design", default="D",
                       help="published design of the study to evaluate (A, B, C, D) or a design TOML file")
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
        add_form_options(p)
        p.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
        p.set_defaults(handler=run_pipeline_command)


def _add_roughness_options(parser: argparse.ArgumentParser) -> None:
    from .cli_dataset import add_roughness_options

    add_roughness_options(parser, "stage 1 and the off-grid sample solve on it; the dataset and the coefficient file "
                                  "record its name and sha256, the default directory name carries it; default: "
                                  "baseline_synthetic")


def run_pipeline_command(args: argparse.Namespace) -> int:
    from ehl_dataset.validation import check_range

    from . import exit_codes
    from .cli_dataset import roughness_choice
    from .pipeline import check_inputs, run_pipeline
    from .surrogate_stage import check_offgrid_points

    check_range("workers", args.workers, 1, 1024)
    run = check_inputs(args.factorial, out_dir=args.out_dir, level=args.level, model=args.model,
                       design=args.design, overwrite=args.overwrite, workers=args.workers,
                       time_limit_s=args.time_limit_s, effects=args.effects, roughness=roughness_choice(args))
    resume = _resume_command(args, run)
    offgrid_points = check_offgrid_points(args.offgrid_points, args.form or "eq9", "--offgrid-points")
    announce(f"gearloss pipeline {args.pipeline_command}: factorial", run, resume, args.overwrite)
    result = run_pipeline(run.out_dir, run.factorial, workers=args.workers,
                          scheduler=getattr(args, "scheduler", None), progress=args.progress, level=run.level,
                          model=run.model, design=args.design, allow_unstable=args.allow_unstable,
                          clip_to_fitted_ranges=not args.no_clip, time_limit_s=args.time_limit_s,
                          overwrite=args.overwrite, resume_command=resume, checked=run, form=args.form or "eq9",
                          offgrid_points=offgrid_points)
    payload = result.to_dict()
    design = result.stage("design").details
    payload.update({k: design[k] for k in ("power_loss_w", "efficiency", "te_pp_m", "sigma_c_pa", "sigma_b_pa",
                                           "converged", "valid")})
    payload["resume_command"] = resume
    emit(payload, args.json, _human)
    return exit_codes.OK if (design["converged"] and design["valid"]) else exit_codes.NOT_VALID


def announce(title: str, run, resume: str, overwrite: bool) -> None:
    """The start lines on stderr: what runs (``title`` then the factorial, level, model), new or resumed, where the
    output goes and the command that resumes it; the smoke label for a smooth-surface run."""
    from .pipeline import SMOKE_LABEL

    n = run.factorial.size
    state = (f"resuming: {run.resumable} of {n} points done" if run.resumable and not overwrite
             else f"new run of {n} points")
    effects = "" if run.effects == "auto" else f", effects {run.effects}"
    if run.roughness is not None:
        effects += f", roughness {run.roughness.name}"
    print(f"{title} {run.factorial.name}, level {run.level}, model {run.model}{effects}; {state}\n  output: {run.dataset} "
          f"and {run.coefficients}\n  Ctrl-C stops and keeps the finished points; resume with: {resume}",
          file=sys.stderr, flush=True)
    if run.smoke:
        print(f"  {SMOKE_LABEL}", file=sys.stderr, flush=True)


def _resume_command(args, run) -> str:
    return resume_command(args, ["pipeline", args.pipeline_command, "--out-dir", str(run.out_dir)])


def resume_command(args, fallback: list[str]) -> str:
    """The command that continues a run: the one typed, without --overwrite (a resume must not start afresh);
    ``fallback`` the arguments when the typed ones are unknown (a call from Python)."""
    import shlex

    argv = [a for a in getattr(args, "argv", []) if a != "--overwrite"]
    return "gearloss " + shlex.join(argv or fallback)


def dataset_fit_lines(data: dict, fit: dict) -> list[str]:
    """The human summary of stages 1 (dataset) and 2 (fit) from their ``to_dict()`` payloads."""
    lines = [
        f"stage 1 dataset   {data['artefact']}: factorial {data['factorial']} (level {data['level']}, model "
        f"{data['model']}" + ("" if data.get("effects", "auto") == "auto" else f", effects {data['effects']}")
        + (f", roughness {data['roughness']['name']}" if data.get("roughness") else "")
        + f"), {data['n_points']} points, {data['computed']} computed"
        f"{' (resumed)' if data['resumed'] else ''}; ok {data['ok']}, failed {data['failed']}, non-converged "
        f"{data['non_converged']} — {data['wall_time_s']:.1f} s"]
    for message, count in (data.get("failures") or {}).items():
        lines.append(f"                  {count} failed: {message}")
    lines.append(fit_line(fit))
    return lines


def _human(p: dict) -> str:
    s = p["stages"]
    data, fit, design = s["dataset"], s["fit"], s["design"]
    lines = [p["label"]] if p.get("label") else []
    lines += dataset_fit_lines(data, fit) + stage2_lines(s)
    lines.append(f"stage 3 design {design['design']} at {design['torque_nm']:.0f} N·m, {design['speed_rpm']:.0f} rpm, "
                 f"{design['oil_temperature_k'] - 273.15:.0f} °C, Rq {design['rq1_m'] * 1e6:.2g} µm, M_P "
                 f"{design['profile_crown_m'] * 1e6:.3g} µm, M_L {design['lead_crown_m'] * 1e6:.3g} µm — "
                 f"{design['wall_time_s'] * 1e3:.0f} ms")
    lines.append(f"  P = {design['power_loss_w'] / 1e3:.3f} kW, η = {design['efficiency'] * 100:.3f} %, "
                 f"TE p-p = {design['te_pp_m'] * 1e6:.3f} µm, σ_c = {design['sigma_c_pa'] / 1e9:.3f} GPa, "
                 f"σ_b = {design['sigma_b_pa'] / 1e6:.0f} MPa, mean μ = {design['mu_mean']:.4f}, "
                 f"converged {design['converged']}, valid {design['valid']}")
    if design.get("power_loss_low_w") == design.get("power_loss_low_w"):  # not NaN: the surrogate has intervals
        lines.append(f"  90 % band of P from the surrogate's μ intervals (fully correlated): "
                     f"{design['power_loss_low_w'] / 1e3:.3f} to {design['power_loss_high_w'] / 1e3:.3f} kW")
    clipped = design.get("clipped_to_fitted_range")
    if clipped:
        moved = ", ".join(f"{k} {v}" for k, v in clipped.items() if k != "contact_points" and v)
        lines.append(f"  surrogate inputs clipped to the fitted ranges: {moved or 'none'} of "
                     f"{clipped['contact_points']} points")
    if design.get("not_valid_because"):
        lines.append(f"  NOT VALID: {design['not_valid_because']}")
    for warning in fit["warnings"] + design["warnings"]:
        lines.append(f"  warning: {warning}")
    lines.append(f"total {p['wall_time_s']:.1f} s")
    return "\n".join(lines)
