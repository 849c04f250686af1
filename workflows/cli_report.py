"""``gearloss report efficiency-map|mesh-cycle|sweep|modifications``: the figures of a design and of the paper's
studies as PNG files (matplotlib), each with the command that made it and the solver version written under it.

The friction model is the project's fitted coefficient file (``--friction``, default the shipped ``atf``, the fit of the paper factorial);
``--compare`` adds published formulas (default ``xu2007``) drawn alongside. With a friction model that has
prediction intervals the efficiency map carries the 90 % band of P and η per cell (``--table`` writes it as CSV).
The operating conditions default to the study's (data/studies/paper2009.toml: 250 N·m, 4000 rpm, ATF 90 °C,
Rq 0.4 µm, M_P 15 µm, M_L 12 µm). See :mod:`workflows.report` and docs/how-to/studies-and-reports.md.
"""

from __future__ import annotations

import argparse

from ehl_dataset.validation import InputError

from .cli_output import emit


def register(subparsers) -> None:
    parser = subparsers.add_parser("report", help="figures: efficiency map, loss over the mesh cycle and the line "
                                                  "of action, the paper's design and modification studies",
                                   description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="report_command", metavar="FIGURE")
    parser.set_defaults(handler=lambda args: parser.print_help() or 2)
    from .cli_gear_studies import _design_options

    emap = sub.add_parser("efficiency-map", help="η and P of a design over input torque × speed",
                          description="Efficiency and power loss of one design over input torque × speed; cells "
                                      "outside the models' validity are hatched. With a friction model that has "
                                      "prediction intervals (a coefficient file of format 2 or a learned file) "
                                      "every cell carries the 90 % band of P and η, fully correlated over the "
                                      "mesh, and the figure draws the band's width.")
    _design_options(emap)
    emap.add_argument("--torques-nm", default="25:500:25",
                      help="input torques [N·m]: list a,b,c or range start:stop:step")
    emap.add_argument("--speeds-rpm", default="500:6000:500",
                      help="input speeds [rpm]: list a,b,c or range start:stop:step")
    emap.add_argument("--table", default=None, metavar="FILE.csv",
                      help="also write the map as a CSV table, one row per cell (SI units, the unit in each column "
                           "name; the band columns power_loss_low_w ... efficiency_high empty without a band)")
    _conditions(emap)
    _common(emap, "efficiency_map.png")
    emap.set_defaults(handler=run_efficiency_map)

    cycle = sub.add_parser("mesh-cycle", help="P over the mesh cycle and the loss along the line of action",
                           description="Instantaneous friction power loss P(φ) over one mesh cycle, and the "
                                       "cycle-mean loss, μ and SR along the line of action, for each friction model.")
    _design_options(cycle)
    cycle.add_argument("--torque-nm", type=float, default=None, help="input torque [N·m] (default: the study's)")
    cycle.add_argument("--speed-rpm", type=float, default=None, help="input speed [rpm] (default: the study's)")
    _conditions(cycle)
    _common(cycle, "mesh_cycle_loss.png")
    cycle.set_defaults(handler=run_mesh_cycle)

    sweep = sub.add_parser("sweep", help="the paper's design sweep (Fig. 3-5) with the fitted coefficients",
                           description="P of the feasible designs against N, m, d_o, Φ, Ψ, Λ_wd with the paper's "
                                       "sole-influence lines, and P against TE, σ_c, σ_b with designs A-D "
                                       "(Li & Kahraman 2009, Fig. 3-5). Writes sweep_power_loss.png and "
                                       "sweep_tradeoffs.png into --out-dir.")
    sweep.add_argument("--stride", type=int, default=1, help="evaluate every K-th feasible design in the scatter")
    sweep.add_argument("--limit", type=int, default=None, help="at most N designs in the scatter (default: all)")
    sweep.add_argument("--out-dir", default=".", help="directory of the two figures")
    _common(sweep, None)
    sweep.set_defaults(handler=run_sweep)

    mods = sub.add_parser("modifications", help="the paper's tooth-modification study (Fig. 6)",
                          description="P, TE, σ_c, σ_b of one design over profile crown × lead crown × torque "
                                      "(Li & Kahraman 2009, Fig. 6).")
    _design_options(mods)
    mods.add_argument("--torques-nm", default="50,250,500", help="input torques [N·m]")
    mods.add_argument("--profile-crowns-um", default="0:30:5", help="profile crowns M_P [µm]: list or start:stop:step")
    mods.add_argument("--lead-crowns-um", default="0:30:5", help="lead crowns M_L [µm]: list or start:stop:step")
    _common(mods, "modifications_design_d.png")
    mods.set_defaults(handler=run_modifications)


def _conditions(parser) -> None:
    group = parser.add_argument_group("operating conditions (default: the study's)")
    group.add_argument("--oil-temp-c", type=float, default=None, help="oil inlet temperature [°C]")
    group.add_argument("--rq-um", type=float, default=None, help="RMS roughness of both flanks [µm]")
    group.add_argument("--profile-crown-um", type=float, default=None, help="profile crown M_P [µm]")
    group.add_argument("--lead-crown-um", type=float, default=None, help="lead crown M_L [µm]")


def _common(parser, out: str | None) -> None:
    parser.add_argument("--study", default="paper2009", help="study NAME or TOML file")
    parser.add_argument("--friction", default="atf",
                        help="friction model of the figure: a coefficient file (shipped name or path) or any "
                             "--friction MODEL of gear evaluate")
    parser.add_argument("--compare", nargs="*", default=["xu2007"], metavar="MODEL",
                        help="further friction models drawn for comparison (published formulas: xu2007, "
                             "benedict_kelley, iso14179; none: --compare with no name)")
    parser.add_argument("--positions", type=int, default=24, help="mesh positions per cycle")
    parser.add_argument("--slices", type=int, default=30, help="slices across the face")
    if out is not None:
        parser.add_argument("--out", default=out, metavar="FILE.png", help="the figure to write")
    parser.add_argument("--json", action="store_true", help="print one JSON object (SI units) with the figure's data")


def _setup(args):
    """Study, friction models {spec: model}, study point (with the options' conditions) and mesh options —
    all checked before anything is computed."""
    import dataclasses
    import math

    from ehl_dataset.validation import check_range
    from efficiency.design_io import load_study
    from efficiency.friction import friction_from_spec
    from efficiency.mesh_cycle import MeshOptions
    from efficiency.modifications import Modifications
    from efficiency.studies import StudyPoint

    check_range("positions", args.positions, 2, 1000)
    check_range("slices", args.slices, 2, 500)
    out = getattr(args, "out", None)
    if out is not None and not str(out).lower().endswith(".png"):
        raise InputError("out", out, "a file name ending in .png")
    study = load_study(args.study)
    lubricant = study.operating_point.lubricant
    specs = [args.friction] + [c for c in args.compare if c != args.friction]
    frictions = {spec: friction_from_spec(spec, lubricant) for spec in specs}
    point = StudyPoint.from_operating_point(study.operating_point)
    # the options' values in SI; the operating point (StudyPoint, Modifications) checks each once when it is built
    changes = {}
    if getattr(args, "oil_temp_c", None) is not None:
        changes["oil_temperature"] = args.oil_temp_c + 273.15
    if getattr(args, "rq_um", None) is not None:
        changes.update(rq1=args.rq_um * 1e-6, rq2=args.rq_um * 1e-6)
    mp, ml = getattr(args, "profile_crown_um", None), getattr(args, "lead_crown_um", None)
    if mp is not None or ml is not None:
        mods = point.modifications
        changes["modifications"] = Modifications(profile_crown=mods.profile_crown if mp is None else mp * 1e-6,
                                                 lead_crown=mods.lead_crown if ml is None else ml * 1e-6)
    if getattr(args, "torque_nm", None) is not None:
        changes["input_torque"] = args.torque_nm
    if getattr(args, "speed_rpm", None) is not None:
        changes["input_speed"] = args.speed_rpm * math.pi / 30.0
    point = dataclasses.replace(point, **changes)
    options = MeshOptions(positions=args.positions, slices=args.slices)
    return study, frictions, point, options


def _values(text: str, name: str, low: float, high: float, unit: str, low_inclusive: bool = False) -> list[float]:
    """The values of a list/range option, each in (low, high] (or [low, high])."""
    from ehl_dataset.validation import check_range

    from .cli_gear_studies import parse_values

    values = parse_values(text, name)
    for v in values:
        check_range(name, v, low, high, low_inclusive=low_inclusive, unit=unit)
    return values


def _point_text(point) -> str:
    import math

    return (f"{point.input_torque:.0f} N·m, {point.input_speed * 30 / math.pi:.0f} rpm, oil "
            f"{point.oil_temperature - 273.15:.0f} °C, Rq {point.rq1 * 1e6:.2g} µm, M_P "
            f"{point.modifications.profile_crown * 1e6:.3g} µm, M_L {point.modifications.lead_crown * 1e6:.3g} µm")


def run_efficiency_map(args: argparse.Namespace) -> int:
    import math

    from . import report
    from .cli_gear_studies import _study_pair

    torques = _values(args.torques_nm, "torques-nm", 0.0, 1e7, "N·m")
    speeds = _values(args.speeds_rpm, "speeds-rpm", 0.0, 1e6, "rpm")
    if args.table is not None and not str(args.table).lower().endswith(".csv"):
        raise InputError("table", args.table, "a file name ending in .csv")
    study, frictions, point, options = _setup(args)
    name, pair = _study_pair(args, study)
    spec = args.friction
    result = report.efficiency_map(pair, frictions[spec], torques, speeds, point, options, design=name,
                                   friction_name=spec)
    study_point = (point.input_torque, point.input_speed * 30 / math.pi)
    figure = report.efficiency_map_figure(result, args.out, args.command_line, study_point,
                                          report.coefficients_note({spec: frictions[spec]}))
    payload = {**result.to_dict(), "figure": figure, "table": None, "conditions": _point_text(point)}
    if args.table is not None:
        from pathlib import Path

        Path(args.table).parent.mkdir(parents=True, exist_ok=True)
        result.to_table().to_csv(args.table, index=False)
        payload["table"] = str(args.table)
    emit(payload, args.json, _map_text)
    return 0


def _map_text(p: dict) -> str:
    """Human lines of ``report efficiency-map``: what was written, the range of η and, with a band, its width."""
    import numpy as np

    lines = [f"wrote {p['figure']}" + (f" and {p['table']}" if p["table"] else "") + f": design {p['design']}, "
             f"friction {p['friction_model']}, {len(p['torque_nm'])} torques × {len(p['speed_rpm'])} speeds, η "
             f"{_range(p['efficiency'], 100)} %, {int(p['valid'].sum())} of {p['valid'].size} cells inside the "
             f"validity ({p['wall_time_s']:.1f} s)"]
    if p["power_loss_low_w"] is None:
        lines.append(p["band_note"])
    else:
        with np.errstate(invalid="ignore", divide="ignore"):
            width = (np.asarray(p["efficiency_high"]) - np.asarray(p["efficiency_low"]))
            below = 1.0 - np.asarray(p["power_loss_low_w"]) / np.asarray(p["power_loss_w"])
            above = np.asarray(p["power_loss_high_w"]) / np.asarray(p["power_loss_w"]) - 1.0
        lines.append(f"{p['band_note']}: width of η's band {_range(width, 100)} percentage points; P_low "
                     f"{_range(below, 100, '.1f')} % below P, P_high {_range(above, 100, '.1f')} % above")
    return "\n".join(lines)


def _range(values, scale, fmt: str = ".3f") -> str:
    import numpy as np

    finite = np.asarray(values, dtype=float)[np.isfinite(np.asarray(values, dtype=float))]
    return f"{finite.min() * scale:{fmt}}–{finite.max() * scale:{fmt}}" if finite.size else "n/a"


def run_mesh_cycle(args: argparse.Namespace) -> int:
    from . import report
    from .cli_gear_studies import _study_pair

    study, frictions, point, options = _setup(args)
    name, pair = _study_pair(args, study)
    result = report.mesh_cycle_loss(pair, frictions, point, options, design=name)
    figure = report.mesh_cycle_figure(result, args.out, args.command_line, report.coefficients_note(frictions))
    payload = {**result.to_dict(), "figure": figure, "conditions": _point_text(point)}

    def human(p):
        lines = [f"wrote {p['figure']}: design {p['design']}, {p['conditions']}"]
        for model, m in p["models"].items():
            lines.append(f"  {model}: P = {m['power_loss_w'] / 1e3:.4f} kW, η = {m['efficiency'] * 100:.3f} %")
        return "\n".join(lines)

    emit(payload, args.json, human)
    return 0


def run_sweep(args: argparse.Namespace) -> int:
    from . import report

    if args.stride < 1:
        raise InputError("stride", args.stride, "a whole number ≥ 1")
    if args.limit is not None and args.limit < 1:
        raise InputError("limit", args.limit, "a whole number ≥ 1")
    study, frictions, point, options = _setup(args)
    table, lines, designs = report.study_sweep(study, frictions, point, options, stride=args.stride,
                                               limit=args.limit)
    figures = report.sweep_figures(table, lines, designs, study, args.out_dir, args.command_line, _point_text(point),
                                   report.coefficients_note(frictions))
    payload = {"figures": figures, "study": study.name, "friction_models": list(frictions),
               "designs_evaluated": int(len(table)), "designs_not_valid": int((~table["valid"].fillna(False)
                                                                                .astype(bool)).sum()),
               "table1": {model: {d: {k: row[k] for k in ("power_loss_w", "te_pp_m", "sigma_c_pa", "sigma_b_pa",
                                                          "valid")} for d, row in rows.items()}
                          for model, rows in designs.items()},
               "lines": {model: {column: {column: line[column].tolist(),
                                          "power_loss_w": line["power_loss_w"].tolist(),
                                          "valid": line["valid"].fillna(False).astype(bool).tolist()}
                                 for column, line in by_column.items()}
                         for model, by_column in lines.items()},
               "conditions": _point_text(point)}

    def human(p):
        out = [f"wrote {', '.join(p['figures'])}: {p['designs_evaluated']} designs ({p['designs_not_valid']} outside "
               f"the validity), friction {', '.join(p['friction_models'])}"]
        for model, rows in p["table1"].items():
            out.append(f"  {model}: " + ", ".join(f"{d} P = {r['power_loss_w'] / 1e3:.3f} kW" for d, r in rows.items()))
        return "\n".join(out)

    emit(payload, args.json, human)
    return 0


def run_modifications(args: argparse.Namespace) -> int:
    from . import report
    from .cli_gear_studies import _study_pair

    torques = _values(args.torques_nm, "torques-nm", 0.0, 1e7, "N·m")
    profile = _values(args.profile_crowns_um, "profile-crowns-um", 0.0, 1000.0, "µm", low_inclusive=True)
    lead = _values(args.lead_crowns_um, "lead-crowns-um", 0.0, 1000.0, "µm", low_inclusive=True)
    study, frictions, point, options = _setup(args)
    name, pair = _study_pair(args, study)
    tables = report.study_modifications(pair, frictions, [v * 1e-6 for v in profile], [v * 1e-6 for v in lead],
                                        torques, point, options)
    figure = report.modifications_figure(tables, name, args.out, args.command_line, report.coefficients_note(frictions))
    payload = {"figure": figure, "design": name, "friction_models": list(tables),
               "cases": int(len(next(iter(tables.values())))),
               "rows": {model: table[["torque_nm", "profile_crown_m", "lead_crown_m", "power_loss_w", "te_pp_m",
                                      "sigma_c_pa", "sigma_b_pa", "valid"]].to_dict(orient="list")
                        for model, table in tables.items()}}
    emit(payload, args.json, lambda p: f"wrote {p['figure']}: design {p['design']}, {p['cases']} cases per friction "
                                       f"model ({', '.join(p['friction_models'])})")
    return 0
