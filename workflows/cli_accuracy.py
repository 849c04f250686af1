"""``gearloss accuracy``: each EHL accuracy level's error against the reference level versus wall time.

Writes ``<stem>.md`` (tables), ``<stem>.png`` (error vs time, log axes) and ``<stem>.json`` (raw runs) into
``--out`` (default ``gearloss_accuracy``, outside ``docs/``; ``--out docs/validation`` regenerates the shipped reports), stem ``accuracy_levels_rough`` unless ``--stem`` says otherwise (docs/validation/index.md is
the hand-written summary of all accuracy results). See :mod:`workflows.accuracy`. ``--mixed`` measures the contact
models of the mixed regime against the deterministic reference set instead (:mod:`workflows.accuracy_mixed`).
"""

from __future__ import annotations

import sys

DEFAULT_OUT = "gearloss_accuracy"
"""Default report directory: outside docs/, so a trial run never overwrites the shipped reports."""
CONVERGENCE_CASES = ("gear-typical", "full-film-9")
"""Cases of the convergence study: one the planner solves rough (film law, steady), one smooth and steady."""


def register(subparsers) -> None:
    parser = subparsers.add_parser("accuracy", help="EHL accuracy levels: error against the reference vs time",
                                   description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=None, metavar="N",
                        help="use the first N cases of the fixed set (default: all 16)")
    parser.add_argument("--only", nargs="+", default=None, metavar="NAME",
                        help="use only the named cases of the fixed set (see workflows/accuracy.py)")
    parser.add_argument("--levels", nargs="+", default=None, metavar="LEVEL",
                        help="levels to measure (default: fast standard)")
    parser.add_argument("--reference", default="reference", metavar="LEVEL", help="reference level")
    parser.add_argument("--effects", choices=("auto", "full", "smooth"), default="auto",
                        help="effects of the measured levels (default auto: the planner's savings are measured; "
                             "smooth: steady smooth physics for every case)")
    parser.add_argument("--reference-effects", choices=("auto", "full", "smooth"), default="full",
                        help="effects of the reference solves (default full; rough cases then run the deterministic "
                             "model: hours per case at the reference level; the mixed regime's accuracy is --mixed)")
    parser.add_argument("--stem", default=None,
                        help="file name stem of the report (default accuracy_levels_rough, workflows.accuracy.DEFAULT_STEM)")
    parser.add_argument("--lubricant", default="atf", metavar="NAME|FILE")
    parser.add_argument("--convergence", action="store_true",
                        help="also refine the level's grid on two cases (steady solves)")
    parser.add_argument("--convergence-base", default="fast", metavar="LEVEL",
                        help="level refined by factors 0.5, 1, 2, 4 in the convergence study (default fast)")
    parser.add_argument("--note", action="append", default=[], metavar="TEXT",
                        help="a remark printed under the report's header (repeatable)")
    parser.add_argument("--out", "--out-dir", dest="out_dir", default=DEFAULT_OUT, metavar="DIR",
                        help="directory of the report (default gearloss_accuracy; the shipped reports in docs/ are "
                             "regenerated with --out docs/validation)")
    parser.add_argument("--mixed", action="store_true",
                        help="mixed regime: contact models against the deterministic reference set "
                             "(data/reference/deterministic_validation.json); stem accuracy_mixed")
    parser.add_argument("--models", nargs="+", default=None, metavar="MODEL",
                        help="with --mixed: models to measure (default: the steady ones, smooth-standard "
                             "homogenised-transverse-standard homogenised-isotropic-standard; also "
                             "homogenised-film_law-standard, deterministic-fast, deterministic-standard: minutes per "
                             "case)")
    parser.add_argument("--reference-file", default=None, metavar="FILE",
                        help="with --mixed: the reference set (default data/reference/deterministic_validation.json)")
    parser.add_argument("--rescore", default=None, metavar="REPORT_JSON",
                        help="with --mixed: measure the runs of an earlier report (its <stem>.json, e.g. "
                             "docs/validation/accuracy_mixed.json) against the reference without solving again; the runs keep "
                             "the versions they were made with; with --models, only those of the report's models")
    parser.add_argument("--json", action="store_true", help="print one JSON object")
    parser.set_defaults(handler=run_accuracy)


def run_mixed(args) -> int:
    """``gearloss accuracy --mixed``: :mod:`workflows.accuracy_mixed`."""
    from pathlib import Path

    from workflows import accuracy_mixed
    from workflows.cli_output import emit

    stem = args.stem or accuracy_mixed.DEFAULT_STEM
    models = tuple(args.models) if args.models else accuracy_mixed.CHEAP_MODELS
    reference = args.reference_file or accuracy_mixed.REFERENCE_FILE
    Path(args.out_dir).mkdir(parents=True, exist_ok=True)
    if args.rescore:
        study = accuracy_mixed.rescore_study(args.rescore, reference, args.models)
        models = tuple(study["models"])
        command = f"gearloss accuracy --mixed --rescore {args.rescore} --out {args.out_dir}"
        if args.models:
            command += f" --models {' '.join(models)}"
    else:
        study = accuracy_mixed.run_mixed_study(
            models, reference, args.lubricant, checkpoint=Path(args.out_dir) / f"{stem}.partial.json",
            progress=lambda text: print(f"[accuracy] {text}", file=sys.stderr, flush=True))
        command = (f"gearloss accuracy --mixed --models {' '.join(models)} --lubricant {args.lubricant} "
                   f"--out {args.out_dir}")
    if args.reference_file:
        command += f" --reference-file {args.reference_file}"
    if args.stem:
        command += f" --stem {args.stem}"
    paths = accuracy_mixed.write_mixed_report(study, args.out_dir, command, stem)
    if not args.rescore:
        (Path(args.out_dir) / f"{stem}.partial.json").unlink(missing_ok=True)
    payload = {"models": list(models), "n_cases": len(study["cases"]), "summary": accuracy_mixed.summary(study),
               "markdown_path": str(paths["markdown"]), "plot_path": str(paths["plot"]),
               "json_path": str(paths["json"])}

    emit(payload, args.json, lambda data: _human_summary(data, "p90", "mu_error_p90"))
    return 0


def _human_summary(data: dict, spread: str, spread_key: str) -> str:
    """One line per level or model of a study's summary (median and ``spread`` of the μ error, time), then the
    files written."""
    rows = [f"{name}: median err mu {row['mu_error_median']:.3g}, {spread} {row[spread_key]:.3g}; "
            f"mean time {row['wall_time_mean_s']:.3g} s/case ({row['converged']}/{row['n_cases']} converged)"
            for name, row in data["summary"].items()]
    return "\n".join(rows + [f"wrote {data['markdown_path']}, {data['plot_path']}"])


def run_accuracy(args) -> int:
    from ehl_dataset.solvers.levels import get_level
    from ehl_dataset.validation import InputError
    from workflows import accuracy
    from workflows.cli_output import emit

    if args.mixed:
        return run_mixed(args)
    args.stem = args.stem or accuracy.DEFAULT_STEM
    cases = accuracy.ACCURACY_CASES
    if args.cases is not None:
        if not 1 <= args.cases <= len(cases):
            raise InputError("--cases", args.cases, f"an integer in [1, {len(cases)}]")
        cases = cases[: args.cases]
    if args.only:
        names = [spec[0] for spec in accuracy.ACCURACY_CASES]
        for name in args.only:
            if name not in names:
                raise InputError("--only", name, f"one of {names}")
        cases = tuple(spec for spec in cases if spec[0] in args.only)
    levels = tuple(args.levels) if args.levels else accuracy.DEFAULT_LEVELS
    for name in (*levels, args.reference, args.convergence_base):
        get_level(name)

    def progress(text: str) -> None:
        print(f"[accuracy] {text}", file=sys.stderr, flush=True)

    from pathlib import Path

    Path(args.out_dir).mkdir(parents=True, exist_ok=True)
    study = accuracy.run_study(cases, levels, args.reference, args.lubricant, args.reference_effects, args.effects,
                               progress=progress, checkpoint=Path(args.out_dir) / f"{args.stem}.partial.json")
    convergence = []
    if args.convergence:
        by_name = {spec[0]: spec for spec in accuracy.ACCURACY_CASES}
        for name in CONVERGENCE_CASES:
            for kind in accuracy.REFINEMENTS:
                result = accuracy.convergence_study(by_name[name], kind, base_level=args.convergence_base,
                                                    lubricant=args.lubricant)
                convergence.append(result)
                progress(f"convergence {name} {kind}: order mu {result['order_mu']:.2f}")
    command = (f"gearloss accuracy --levels {' '.join(levels)} --reference {args.reference} --effects {args.effects}"
               f" --reference-effects {args.reference_effects} --lubricant {args.lubricant} --stem {args.stem}"
               f" --out {args.out_dir}")
    if args.cases is not None:
        command += f" --cases {args.cases}"
    if args.only:
        command += f" --only {' '.join(args.only)}"
    if args.convergence:
        command += f" --convergence --convergence-base {args.convergence_base}"
    study.provenance["command"] = command
    if args.note:
        study.provenance["notes"] = list(args.note)
    paths = accuracy.write_report(study, args.out_dir, convergence, stem=args.stem)
    (Path(args.out_dir) / f"{args.stem}.partial.json").unlink(missing_ok=True)
    payload = {
        "reference_level": study.reference_level,
        "levels": list(study.levels),
        "n_cases": len(study.cases),
        "summary": study.summary(),
        "markdown_path": str(paths["markdown"]),
        "plot_path": str(paths["plot"]),
        "json_path": str(paths["json"]),
        "git_commit": study.provenance.get("git_commit"),
    }

    emit(payload, args.json, lambda data: _human_summary(data, "max", "mu_error_max"))
    return 0
