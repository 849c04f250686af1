"""``gearloss dataset run|resume|info``: a factorial of EHL contacts into one HDF5 file (docs/reference/dataset-format.md).

Exit status (workflows.exit_codes): 0 when the session ends with no pending rows (failed rows are reported, not an
error), 2 for bad input, 130 / 143 when interrupted by SIGINT / SIGTERM (finished points are on disk; the resume
command is printed).
"""

from __future__ import annotations

import argparse
import os

from ehl_dataset.names import LEVELS, MODELS

from .cli_help import EFFECTS_CHOICES, EFFECTS_HELP, model_help



def register(subparsers) -> None:
    parser = subparsers.add_parser("dataset", help="run a factorial of EHL contacts into HDF5, resume, inspect")
    commands = parser.add_subparsers(dest="dataset_command", metavar="COMMAND")
    parser.set_defaults(handler=lambda args: parser.print_help() or 2)

    run = commands.add_parser("run", help="compute a factorial into a new HDF5 file (or continue the same run)")
    run.add_argument("--factorial", required=True, help="shipped name (paper2009, quick, smoke) or TOML file")
    run.add_argument("--out", required=True, help="HDF5 file to write")
    run.add_argument("--lubricant", help="lubricant NAME or FILE (default: the factorial's)")
    run.add_argument("--level", choices=LEVELS, help="solver accuracy level (default: the factorial's)")
    run.add_argument("--effects", choices=EFFECTS_CHOICES, help=EFFECTS_HELP + "; default: the factorial's")
    run.add_argument("--model", choices=MODELS, help=model_help("default: the factorial's, auto for the shipped ones except smoke"))
    run.add_argument("--overwrite", action="store_true", help="replace an existing file instead of continuing it")
    add_roughness_options(run, "the file records its name and sha256; default: baseline_synthetic")
    _execution_options(run)
    run.set_defaults(handler=_run)

    resume = commands.add_parser("resume", help="continue a run: compute every row that is not ok")
    resume.add_argument("file", help="HDF5 file of the run")
    resume.add_argument("--factorial", help="refuse unless the file records this factorial")
    resume.add_argument("--lubricant", help="refuse unless the file records this lubricant")
    resume.add_argument("--level", choices=LEVELS, help="refuse unless the file records this level")
    resume.add_argument("--effects", choices=EFFECTS_CHOICES, help="refuse unless the file records this plan")
    resume.add_argument("--model", choices=MODELS, help=model_help("refuse unless the file records this model; a file that records "
                                                   "none ran auto"))
    resume.add_argument("--retry-not-converged", action="store_true",
                        help="also recompute the rows stored not converged (e.g. stopped by an earlier "
                             "--time-limit-s), overwriting their earlier result")
    add_roughness_options(resume, "default: the profile the file records; a profile file must be given again "
                                  "(its path is not recorded); refused unless it is the recorded one")
    _execution_options(resume, solver_default=None)
    resume.set_defaults(handler=_resume)

    info = commands.add_parser("info", help="counts by status, time spent, slowest points, configuration (solver, "
                                                "lubricant, roughness profile)")
    info.add_argument("file", help="HDF5 file of a run")
    info.add_argument("--slowest", type=int, default=5, help="how many of the slowest points to list")
    info.add_argument("--json", action="store_true", help="print one JSON object")
    info.set_defaults(handler=_info)


def add_roughness_options(parser: argparse.ArgumentParser, default_text: str) -> None:
    """``--roughness NAME | --roughness-file FILE`` and ``--roughness-unit``: the roughness profile of the rough
    points (:func:`ehl_dataset.dataset.roughness_choice.choose_roughness`); ``default_text`` ends the help."""
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--roughness", default=None, metavar="NAME",
                       help="registered roughness profile every rough point takes, scaled to its Rq1/Rq2: "
                            "baseline_synthetic (Gaussian ACF, beta 15 um) or flank_ground (self-affine, "
                            f"ground-flank-like); `gearloss roughness show NAME` describes one ({default_text})")
    group.add_argument("--roughness-file", default=None, metavar="FILE",
                       help="a measured profile instead (two columns x, z in .txt/.csv, or a profilometer file with "
                            "the roughness extra); every worker reads it at this path and checks its sha256")
    parser.add_argument("--roughness-unit", default="um", choices=["um", "mm", "m"],
                        help="unit of both columns of --roughness-file (default um)")


def roughness_choice(args):
    """The :class:`~ehl_dataset.dataset.roughness_choice.RoughnessChoice` of the parsed options (None: none given)."""
    from ehl_dataset.dataset.roughness_choice import choose_roughness

    return choose_roughness(args.roughness, args.roughness_file, args.roughness_unit)


def _execution_options(parser: argparse.ArgumentParser, solver_default: str | None = "default") -> None:
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1,
                        help="local worker processes (0: in this process; default: CPU count)")
    parser.add_argument("--scheduler", help="Dask scheduler ADDRESS (tcp://host:8786) or 'dask-local'")
    parser.add_argument("--window", type=int, help="tasks in flight (default: 4 per worker)")
    parser.add_argument("--max-attempts", type=int, default=3, help="computations of a point whose task fails")
    parser.add_argument("--flush-interval", type=float, default=5.0, help="seconds between writes to disk")
    parser.add_argument("--progress", choices=("auto", "bar", "log", "none"), default="auto")
    parser.add_argument("--log-every", type=float, default=30.0, help="seconds between progress log lines")
    parser.add_argument("--time-limit-s", type=float, default=None, metavar="SECONDS",
                        help="wall-time budget per point [s]; a point that spends it is stored as not converged with "
                             "its message (default: none)")
    parser.add_argument("--no-warm-up", action="store_true",
                        help="do not compute the first point in the coordinator before the workers start")
    parser.add_argument("--solver", default=None,
                        help="MODULE:FUNCTION with the signature of ehl_dataset.solver.solve_contact "
                             + ("(default: ehl_dataset.solver:solve_contact)" if solver_default
                                else "(default: the one recorded in the file)"))
    parser.add_argument("--json", action="store_true", help="print one JSON object")


def _options(args) -> dict:
    return {"window": args.window, "max_attempts": args.max_attempts, "flush_interval_s": args.flush_interval,
            "progress": args.progress, "log_every_s": args.log_every, "warm_up": not args.no_warm_up,
            "time_limit_s": args.time_limit_s}


def _finish(summary, as_json: bool) -> int:
    import sys

    from workflows.cli_output import emit

    from .exit_codes import NOT_VALID, OK, SIGNAL_EXIT

    payload = summary.to_dict()
    from ehl_dataset.dataset.store import read_metadata

    payload["roughness"] = read_metadata(summary.path)["roughness"]
    if summary.interrupted:
        payload["resume_command"] = f"gearloss dataset resume {summary.path}"
    emit(payload, as_json, _human_summary)
    if summary.interrupted:
        print(f"gearloss: interrupted by {summary.interrupted}: finished points are in {summary.path}; resume with: "
              f"{payload['resume_command']}", file=sys.stderr, flush=True)
        return SIGNAL_EXIT.get(summary.interrupted, NOT_VALID)
    return OK if summary.pending == 0 else NOT_VALID


def _human_summary(p: dict) -> str:
    lines = [f"{p['path']}: {p['computed']} points computed in {p['wall_time_s']:.1f} s "
             f"({p['points_per_s']:.3g} points/s, store {p['store_time_per_point_s'] * 1e3:.2f} ms/point)",
             f"  rows: ok {p['ok']}, failed {p['failed']}, pending {p['pending']} of {p['n_points']}; "
             f"not converged {p['non_converged']}"]
    if "roughness" in p:
        from ehl_dataset.model.roughness_identity import describe_roughness

        lines.append(f"  roughness profile: {describe_roughness(p['roughness'])}")
    if p["interrupted"]:
        lines.append(f"  interrupted by {p['interrupted']}: finished points are on disk; continue with "
                     f"'gearloss dataset resume {p['path']}'")
    return "\n".join(lines)


def _run(args) -> int:
    from ehl_dataset.dataset.runner import DEFAULT_SOLVER, run_factorial

    summary = run_factorial(args.out, args.factorial, lubricant=args.lubricant, level=args.level,
                            effects=args.effects, model=args.model, workers=args.workers,
                            scheduler=args.scheduler, solver=args.solver or DEFAULT_SOLVER,
                            overwrite=args.overwrite, roughness=roughness_choice(args), **_options(args))
    return _finish(summary, args.json)


def _resume(args) -> int:
    from ehl_dataset.dataset.runner import resume_run

    summary = resume_run(args.file, workers=args.workers, scheduler=args.scheduler, solver=args.solver,
                         factorial=args.factorial, lubricant=args.lubricant, level=args.level,
                         effects=args.effects, model=args.model, retry_not_converged=args.retry_not_converged,
                         roughness=roughness_choice(args), **_options(args))
    return _finish(summary, args.json)


def _info(args) -> int:
    from ehl_dataset.dataset.store import summarize
    from workflows.cli_output import emit

    emit(summarize(args.file, slowest=args.slowest), args.json, _human_info)
    return 0


def _human_info(p: dict) -> str:
    fac, sol, counts = p["factorial"], p["solver"], p["counts"]
    from ehl_dataset.dataset.factorial import AXIS_KEYS

    axes = fac.get("axes", {})
    shape = " x ".join(f"{len(axes[k])} {k}" for k in AXIS_KEYS if k in axes)
    lines = [
        f"{p['path']}  (format v{p['format_version']}, gearloss {p['package_version']}, created {p['created']}, "
        f"git {p['git_revision'] or 'unknown'})",
        f"factorial  {fac.get('name')}: {p['n_points']} points = {shape}",
        f"solver     {sol.get('function')} version {sol.get('version')}, level {sol.get('level')}, "
        f"effects {sol.get('effects')}, model {sol.get('model', 'auto')}",
        f"lubricant  {p['lubricant_name']}",
        f"roughness  " + (f"{p['roughness']['name']} (sha256 {p['roughness']['sha256']})" if p.get("roughness")
                          else "not recorded"),
        f"status     ok {counts['ok']}, failed {counts['failed']}, pending {counts['pending']}; "
        f"not converged {p['non_converged']}; most computations of one point {p['max_attempts']}",
        f"time       solver {p['solver_time_s']:.1f} s in total (median {p['median_solver_time_s']:.3g} s/point), "
        f"workers {p['worker_time_s']:.1f} s, {p['n_sessions']} session(s) {p['session_wall_time_s']:.1f} s wall"
        + (f" ({p['open_sessions']} not closed: still running, or killed)" if p["open_sessions"] else ""),
    ]
    for row in p["slowest"]:
        lines.append(
            f"slowest    point {row['point']}: {row['wall_time_s']:.3g} s  p_h {row['p_h_pa'] / 1e9:g} GPa, "
            f"r_eq {row['r_eq_m'] * 1e3:g} mm, u_r {row['u_r_m_s']:g} m/s, SR {row['sr']:g}, "
            f"T {row['temperature_k'] - 273.15:g} C, Rq {row['rq1_m'] * 1e6:g}/{row['rq2_m'] * 1e6:g} um")
    for row in p["failures"]:
        lines.append(f"failed     point {row['point']}: {row['error']}")
    return "\n".join(lines)
