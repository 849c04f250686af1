"""``gearloss lubricant show|fit``: a lubricant definition checked and tabulated, and the route from a user's own
lubricant to its friction coefficient file (factorial → HDF5 → Eq. 9 fit) in one command (docs/how-to/fit-a-lubricant.md, "Your
own lubricant").
"""

from __future__ import annotations

import argparse

from ehl_dataset.names import LEVELS, MODELS

from .cli_fit_lines import add_form_options, fit_line, form_arguments, stage2_lines
from .cli_help import ACCURACY_EPILOG, EFFECTS_CHOICES, EFFECTS_HELP, model_help
from .cli_output import emit

SHOW_TEMPERATURES_C = (40.0, 100.0)
SHOW_PRESSURES_GPA = (0.0, 0.5, 1.0, 2.0)
"""Default table of ``lubricant show``: the two ISO 3448 viscosity-grade temperatures, and pressures across the
factorial's Hertz pressures (paper2009: 0.5–2.5 GPa)."""

FIT_EPILOG = """\
resuming: a run stopped by Ctrl-C (exit 130), SIGTERM (exit 143) or a crash keeps every finished point in
DIR/dataset.h5; the same command again continues it. A changed lubricant file (any field, [sources] included) is a
different lubricant: the run is refused, use another --out-dir or --overwrite.
using the result: gearloss gear evaluate --friction DIR/<lubricant>_<factorial>.json ...
""" + ACCURACY_EPILOG + "."


def register(subparsers) -> None:
    parser = subparsers.add_parser("lubricant", help="check a lubricant file; fit its friction surrogate",
                                   description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="lubricant_command", metavar="COMMAND")
    parser.set_defaults(handler=lambda args: parser.print_help() or 2)

    show = sub.add_parser("show", help="check a lubricant (name or TOML file) and tabulate its properties",
                          description="Load and check a lubricant (a shipped name or a TOML file; format in "
                                      "docs/reference/data.md) and print its properties at the given temperatures: "
                                      "kinematic and dynamic viscosity, density, the pressure–viscosity "
                                      "coefficient, η(p) at the given pressures, the Eyring stress and the "
                                      "boundary friction, with the data range and the sources.")
    show.add_argument("lubricant", help="shipped name (atf, gear_oil_75w90, ...) or TOML file")
    show.add_argument("--temp-c", type=float, nargs="+", default=list(SHOW_TEMPERATURES_C),
                      help="temperatures [°C] (default: 40 100)")
    show.add_argument("--p-gpa", type=float, nargs="+", default=list(SHOW_PRESSURES_GPA),
                      help="pressures [GPa] of the η(p) columns (default: 0 0.5 1 2)")
    show.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    show.set_defaults(handler=_show)

    fit = sub.add_parser("fit", help="factorial of EHL contacts -> HDF5 -> friction coefficient file, resumable",
                         description="Stages 1 and 2 for a lubricant: the factorial's EHL contacts into "
                                     "DIR/dataset.h5, the two-branch regression of ln μ (paper Eq. 9) into "
                                     "DIR/<lubricant>_<factorial>.json (+ .summary.txt). The lubricant's "
                                     "temperature range must cover the factorial's temperatures (checked before "
                                     "anything is computed).", epilog=FIT_EPILOG)
    fit.add_argument("lubricant", help="TOML file of the lubricant (format in docs/reference/data.md) or a shipped name")
    fit.add_argument("--factorial", default="quick",
                     help="quick (324 points, fast level), paper2009 (42,000 points, standard level), smoke (96 "
                          "smooth-surface points: checks the route, not a friction model) or a factorial TOML "
                          "file (default: quick)")
    fit.add_argument("--level", default=None, choices=LEVELS, help="EHL accuracy level (default: the factorial's)")
    fit.add_argument("--model", default=None, choices=MODELS, help=model_help("default: the factorial's"))
    fit.add_argument("--effects", choices=EFFECTS_CHOICES, default=None,
                     help=EFFECTS_HELP + "; default: the factorial's (isothermal for quick and paper2009)")
    fit.add_argument("--out-dir", default=None, metavar="DIR",
                     help="output directory (default: gearloss_<lubricant>_<factorial>_<level>[_<model>]"
                          "[_<effects>][_<roughness profile>])")
    from .cli_dataset import add_roughness_options

    add_roughness_options(fit, "the dataset, the off-grid sample and every adaptive batch solve on it and record its "
                               "name and sha256, as does the coefficient file; default: baseline_synthetic")
    fit.add_argument("--overwrite", action="store_true", help="start afresh instead of resuming DIR's run")
    fit.add_argument("--workers", type=int, default=1, help="local worker processes (default 1)")
    fit.add_argument("--scheduler", default=None, metavar="ADDRESS",
                     help="Dask scheduler address (tcp://host:8786) or dask-local; default: local processes")
    fit.add_argument("--progress", choices=("auto", "bar", "log", "none"), default="auto",
                     help="stage-1 progress on stderr (default auto: a bar on a terminal, log lines otherwise)")
    fit.add_argument("--time-limit-s", type=float, default=None, metavar="SECONDS",
                     help="wall-time budget per point [s]; a point that spends it is stored as not converged")
    fit.add_argument("--allow-unstable", action="store_true",
                     help="keep a regression flagged unstable (ill-conditioned) instead of stopping")
    add_form_options(fit, adaptive=True)
    fit.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    fit.set_defaults(handler=_fit)


def lubricant_table(lubricant, temperatures_k, pressures_pa) -> dict:
    """Properties of ``lubricant`` (SI) at each temperature [K] (checked against its data range): ν [m²/s], η0
    [Pa·s], ρ0 [kg/m³], α1 [1/Pa], η(p) [Pa·s] at ``pressures_pa``; with its constants and sources."""
    rows = []
    for t in temperatures_k:
        state = lubricant.state(t)
        rows.append({"temperature_k": float(t), "nu_m2_s": float(lubricant.kinematic_viscosity(t)),
                     "eta0_pa_s": state.eta0, "rho0_kg_m3": state.rho0, "alpha1_per_pa": state.alpha1,
                     "eta_pa_s": [float(v) for v in state.viscosity(list(pressures_pa))]})
    return {"name": lubricant.name, "description": lubricant.definition.get("description", ""),
            "temperature_range_k": [lubricant.t_min, lubricant.t_max], "pressure_law": lubricant.pressure_law,
            "compressible": lubricant.compressible, "eyring_stress_pa": lubricant.tau0,
            "boundary_friction": lubricant.mu_d, "pressures_pa": [float(p) for p in pressures_pa], "rows": rows,
            "sources": dict(lubricant.sources)}


def _show(args) -> int:
    from ehl_dataset.model.lubricant import CELSIUS_ZERO_K, load_lubricant
    from ehl_dataset.validation import check_range

    from . import exit_codes

    lub = load_lubricant(args.lubricant)
    pressures = [check_range("p_gpa", p, 0.0, 10.0, unit="GPa") * 1e9 for p in args.p_gpa]
    temperatures = [t + CELSIUS_ZERO_K for t in args.temp_c]  # checked by Lubricant.state, reported in °C
    emit(lubricant_table(lub, temperatures, pressures), args.json, _show_human)
    return exit_codes.OK


def _show_human(p: dict) -> str:
    lo, hi = (t - 273.15 for t in p["temperature_range_k"])
    lines = [f"lubricant {p['name']}: {p['description']}",
             f"  data range {lo:g} to {hi:g} °C; pressure–viscosity law {p['pressure_law']}; "
             f"{'compressible (Dowson–Higginson)' if p['compressible'] else 'incompressible'}; Eyring stress "
             f"{p['eyring_stress_pa'] / 1e6:g} MPa; boundary friction {p['boundary_friction']:g}"]
    heads = " ".join(f"η({q / 1e9:g} GPa) [Pa·s]".rjust(17) for q in p["pressures_pa"])
    lines.append(f"  {'T [°C]':>7} {'ν [mm²/s]':>10} {'η0 [mPa·s]':>11} {'ρ0 [kg/m³]':>11} {'α1 [1/GPa]':>11} {heads}")
    for r in p["rows"]:
        etas = " ".join(f"{v:17.4g}" for v in r["eta_pa_s"])
        lines.append(f"  {r['temperature_k'] - 273.15:7.1f} {r['nu_m2_s'] * 1e6:10.3f} {r['eta0_pa_s'] * 1e3:11.3f} "
                     f"{r['rho0_kg_m3']:11.1f} {r['alpha1_per_pa'] * 1e9:11.2f} {etas}")
    for key, text in p["sources"].items():
        lines.append(f"  source of {key}: {text}")
    return "\n".join(lines)


def _fit(args: argparse.Namespace) -> int:
    from ehl_dataset.validation import check_range

    from . import exit_codes
    from .cli_dataset import roughness_choice
    from .cli_pipeline import announce, dataset_fit_lines
    from .pipeline import check_inputs, run_lubricant_fit

    check_range("workers", args.workers, 1, 1024)
    run = check_inputs(args.factorial, out_dir=args.out_dir, level=args.level, model=args.model,
                       lubricant=args.lubricant, design=None, overwrite=args.overwrite, workers=args.workers,
                       time_limit_s=args.time_limit_s, effects=args.effects, roughness=roughness_choice(args))
    resume = _resume_command(args, run)
    stage2 = form_arguments(args, run.factorial.size)  # checked before the run is announced
    announce(f"gearloss lubricant fit: lubricant {run.lubricant_name}, factorial", run, resume, args.overwrite)
    result = run_lubricant_fit(args.lubricant, run.factorial, out_dir=run.out_dir, workers=args.workers,
                               scheduler=args.scheduler, level=run.level, model=run.model, progress=args.progress,
                               allow_unstable=args.allow_unstable, time_limit_s=args.time_limit_s,
                               overwrite=args.overwrite, resume_command=resume, checked=run, **stage2)
    payload = result.to_dict()
    payload["coefficients"] = result.stage("fit").artefact
    payload["resume_command"] = resume
    payload["use_with"] = f"gearloss gear evaluate --friction {payload['coefficients']}"

    def human(p):
        s = p["stages"]
        lines = ([p["label"]] if p.get("label") else [])
        lines += dataset_fit_lines(s["dataset"], s["fit"]) if "dataset" in s else [fit_line(s["fit"])]
        lines += stage2_lines(s)
        lines.append(f"coefficient file {p['coefficients']} — use it with: {p['use_with']} ...")
        lines.append(f"total {p['wall_time_s']:.1f} s")
        return "\n".join(lines)

    emit(payload, args.json, human)
    solved = [s.details for s in result.stages if s.name in ("dataset", "offgrid")]
    return exit_codes.OK if not any(d["failed"] or d["non_converged"] for d in solved) else exit_codes.NOT_VALID


def _resume_command(args, run) -> str:
    from .cli_pipeline import resume_command

    return resume_command(args, ["lubricant", "fit", args.lubricant, "--factorial", args.factorial, "--out-dir",
                                 str(run.out_dir)])
