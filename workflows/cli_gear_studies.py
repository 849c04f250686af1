"""``gearloss gear sweep`` and ``gearloss gear modifications``: the design studies of Li & Kahraman 2009, §3.

``sweep`` evaluates the feasible designs of the study's space (paper2009: Φ 15–30°, Ψ 15–30°, N 20–53, Λ_wd
1.85–3.376) at the study's operating point (250 N·m, 4000 rpm, ATF 90 °C, Rq 0.4 µm, M_P 15 µm, M_L 12 µm): P, η,
TE p-p, σ_c, σ_b per design into a CSV (``--out``), then searches for designs like D (P < 0.3 kW, σ_b < 235 MPa,
σ_c < 1.175 GPa, TE < 0.25 µm). ``--limit N`` / ``--stride K`` / ``--fix NAME=VALUE`` choose subsets.
``modifications`` evaluates one design over M_P × M_L × torque (paper Fig. 6). Friction: ``--friction
COEFFS.json|xu2007|benedict_kelley|iso14179|constant:MU`` (default ``atf``, the shipped fit of the paper factorial;
published formulas with the study's lubricant). ``gearloss report sweep|modifications`` draws the figures.
See :mod:`efficiency.studies` and docs/explanation/gear-model.md.
"""

from __future__ import annotations

import argparse

from ehl_dataset.validation import InputError

from .cli_output import emit

FIXABLE = {"teeth": "teeth", "n": "teeth", "pressure_angle_deg": "normal_pressure_angle_deg",
           "normal_pressure_angle_deg": "normal_pressure_angle_deg", "helix_angle_deg": "helix_angle_deg",
           "working_depth": "working_depth"}


def _common(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--study", default="paper2009", help="study NAME or TOML file (default paper2009)")
    parser.add_argument("--friction", default="atf",
                        help="COEFFS.json (or shipped name) | xu2007 | benedict_kelley | iso14179 | constant:MU "
                             "(default atf, the shipped fit of the paper factorial; published formulas are evaluated "
                             "with the study's lubricant)")
    parser.add_argument("--positions", type=int, default=24, help="mesh positions per cycle (default 24)")
    parser.add_argument("--slices", type=int, default=30, help="slices across the face (default 30)")
    parser.add_argument("--out", metavar="FILE.csv", help="write the full table as CSV (SI units)")
    parser.add_argument("--json", action="store_true", help="print one JSON object (SI units)")


def _design_options(parser: argparse.ArgumentParser) -> None:
    """The design options read by ``workflows.cli_gear_geometry.build_pair`` (plus Table 1 names for --design)."""
    parser.add_argument("--design", metavar="NAME|FILE",
                        help="a published design of the study (A, B, C, D; default D) or a design TOML file")
    parser.add_argument("--teeth", type=int, help="paper parametrisation: teeth N of each gear")
    parser.add_argument("--working-depth", type=float, help="paper parametrisation: working depth ratio Λ_wd")
    parser.add_argument("--teeth1", type=int, help="general pair: teeth of gear 1")
    parser.add_argument("--teeth2", type=int, help="general pair: teeth of gear 2")
    parser.add_argument("--module-mm", type=float, help="general pair: normal module [mm]")
    parser.add_argument("--shift1", type=float, default=0.0, help="general pair: profile shift x1")
    parser.add_argument("--shift2", type=float, default=0.0, help="general pair: profile shift x2")
    parser.add_argument("--addendum-coefficient", type=float, default=1.0, help="general pair: h_aP/m_n (1.0)")
    parser.add_argument("--dedendum-coefficient", type=float, default=1.25, help="general pair: h_fP/m_n (1.25)")
    parser.add_argument("--no-tip-reduction", action="store_true", help="general pair: no tip reduction")
    parser.add_argument("--pressure-angle-deg", type=float, help="normal pressure angle [deg]")
    parser.add_argument("--helix-angle-deg", type=float, help="helix angle [deg]")
    parser.add_argument("--face-width-mm", type=float, help="face width [mm] (paper 25)")
    parser.add_argument("--center-distance-mm", type=float, help="centre distance [mm] (paper 91.5)")
    parser.add_argument("--root-fillet-coefficient", type=float, help="rack tip radius ρ_fP/m_n")
    parser.add_argument("--thickness-allowance-mm", type=float, help="normal tooth thinning per gear [mm]")


def register(gear_subparsers) -> None:
    sweep = gear_subparsers.add_parser(
        "sweep", help="the paper's design sweep (P, TE, σ_c, σ_b of every feasible design) and the design-D search",
        description="Evaluate the feasible designs of the study's space at its operating point (Li & Kahraman "
                    "2009, Fig. 3-5) and search for designs like D.")
    _common(sweep)
    sweep.add_argument("--limit", type=int, help="evaluate only the first N feasible designs (after --stride)")
    sweep.add_argument("--stride", type=int, default=1, help="evaluate every K-th feasible design (default 1)")
    sweep.add_argument("--fix", action="append", default=[], metavar="NAME=VALUE",
                       help="fix a design parameter (teeth, pressure_angle_deg, helix_angle_deg, working_depth); "
                            "repeatable, e.g. --fix pressure_angle_deg=22.5 --fix helix_angle_deg=20")
    sweep.add_argument("--show", type=int, default=5, help="designs to list in the search report (default 5)")
    sweep.set_defaults(handler=run_sweep)

    mods = gear_subparsers.add_parser(
        "modifications", help="profile and lead crown study of one design over torques (paper Fig. 6)",
        description="P, η, TE, σ_c, σ_b of one design for M_P × M_L × input torque (Li & Kahraman 2009, Fig. 6).")
    _design_options(mods)
    _common(mods)
    mods.add_argument("--torques-nm", default="50,250,500", help="input torques [N·m] (default 50,250,500)")
    mods.add_argument("--profile-crowns-um", default="0:30:5",
                      help="profile crowns M_P [µm]: list a,b,c or range start:stop:step (default 0:30:5)")
    mods.add_argument("--lead-crowns-um", default="0:30:5",
                      help="lead crowns M_L [µm]: list or start:stop:step (default 0:30:5)")
    mods.set_defaults(handler=run_modifications)


def parse_values(text: str, name: str) -> list[float]:
    """``a,b,c`` or an inclusive range ``start:stop:step``."""
    try:
        if ":" in text:
            start, stop, step = (float(v) for v in text.split(":"))
            if step <= 0 or stop < start:
                raise ValueError
            count = int((stop - start) / step + 1e-9) + 1
            return [round(start + i * step, 12) for i in range(count)]
        values = [float(v) for v in text.split(",") if v.strip()]
        if not values:
            raise ValueError
        return values
    except ValueError:
        raise InputError(name, text, "numbers a,b,c or a range start:stop:step with step > 0") from None


def _fixed(items: list[str]) -> dict[str, float]:
    out = {}
    for item in items:
        key, sep, value = item.partition("=")
        column = FIXABLE.get(key.strip().replace("-", "_").lower())
        if not sep or column is None:
            raise InputError("fix", item, f"NAME=VALUE with NAME one of {sorted(set(FIXABLE))}")
        try:
            out[column] = float(value)
        except ValueError:
            raise InputError("fix", item, "NAME=VALUE with a numeric VALUE") from None
    return out


def _setup(args):
    from ehl_dataset.validation import check_range
    from efficiency.design_io import load_study
    from efficiency.friction import friction_from_spec
    from efficiency.mesh_cycle import MeshOptions
    from efficiency.studies import StudyPoint

    check_range("positions", args.positions, 2, 1000)
    check_range("slices", args.slices, 2, 500)
    study = load_study(args.study)
    friction = friction_from_spec(args.friction, study.operating_point.lubricant)
    options = MeshOptions(positions=args.positions, slices=args.slices)
    return study, friction, StudyPoint.from_operating_point(study.operating_point), options


def _write_csv(table, path) -> str:
    from pathlib import Path

    path = Path(path)
    if path.suffix.lower() != ".csv":
        raise InputError("out", str(path), "a file name ending in .csv")
    path.parent.mkdir(parents=True, exist_ok=True)
    table.to_csv(path, index=False)
    return str(path)


def _design_record(row) -> dict:
    keys = ("teeth", "normal_pressure_angle_deg", "helix_angle_deg", "working_depth", "normal_module_m",
            "tip_diameter_m", "power_loss_w", "efficiency", "te_pp_m", "sigma_c_pa", "sigma_b_pa", "worst_ratio")
    return {k: (int(row[k]) if k == "teeth" else float(row[k])) for k in keys if k in row}


def run_sweep(args: argparse.Namespace) -> int:
    import math
    import time

    import numpy as np

    from efficiency.friction import describe_friction
    from efficiency.studies import design_sweep, find_design_like_d, no_error, rank_by_limits

    started = time.perf_counter()
    study, friction, point, options = _setup(args)
    if args.limit is not None and args.limit < 1:
        raise InputError("limit", args.limit, "a whole number ≥ 1")
    if args.stride < 1:
        raise InputError("stride", args.stride, "a whole number ≥ 1")
    table = design_sweep(study.space, friction, point, study.limits, options, where=_fixed(args.fix),
                         stride=args.stride, limit=args.limit)
    n = len(table)
    if n == 0:
        raise InputError("fix/limit", args.fix or args.limit, "a selection containing at least one feasible design")
    valid = table["converged"].astype(bool) & no_error(table)
    limits = study.search_limits or {}
    matches = find_design_like_d(table, limits)
    nearest = rank_by_limits(table, limits)
    payload = {
        "study": study.name, "friction_model": describe_friction(friction), "designs_evaluated": n,
        "space_size": study.space.size, "converged": int(valid.sum()), "failed": int(n - valid.sum()),
        "positions": options.positions, "slices": options.slices,
        "time_per_design_s": float(np.median(table["wall_time_s"])),
        "power_loss_w_range": [float(table["power_loss_w"].min()), float(table["power_loss_w"].max())],
        "te_pp_m_range": [float(table["te_pp_m"].min()), float(table["te_pp_m"].max())],
        "sigma_c_pa_range": [float(table["sigma_c_pa"].min()), float(table["sigma_c_pa"].max())],
        "sigma_b_pa_range": [float(table["sigma_b_pa"].min()), float(table["sigma_b_pa"].max())],
        "designs_with_warnings": int((table["warning"].fillna("").astype(str) != "").sum()),
        "designs_not_valid": int((valid & ~table["valid"].fillna(False).astype(bool)).sum()),
        "warnings": _warning_digest(table),
        "search_limits": limits, "matches": int(len(matches)),
        "best_matches": [_design_record(r) for _, r in matches.head(args.show).iterrows()],
        "nearest": [_design_record(r) for _, r in nearest.head(args.show).iterrows()],
    }
    if args.out:
        payload["out"] = _write_csv(table, args.out)
    payload["wall_time_s"] = time.perf_counter() - started
    emit(payload, args.json, _human_sweep)
    # exit 1: designs that raised or did not converge; designs outside the validity are
    # counted and flagged per row (valid, not_valid_because), part of a study's result
    return 0 if not math.isnan(payload["time_per_design_s"]) and payload["failed"] == 0 else 1


def _warning_digest(table, keep: int = 3) -> dict[str, int]:
    """The most frequent kinds of warning (category and message up to its details) → number of rows; the full
    messages are in the table's ``warning`` column (``--out``)."""
    text = table["warning"].fillna("").astype(str)
    kinds = text[text != ""].str.split(" | ", regex=False).explode().str.split(": ", regex=False).str[:2].str.join(": ")
    counts = kinds.value_counts()
    return {str(k): int(v) for k, v in counts.head(keep).items()}


def _fmt_design(d: dict) -> str:
    text = (f"N={d['teeth']} Φ={d['normal_pressure_angle_deg']:g}° Ψ={d['helix_angle_deg']:g}° "
            f"Λ_wd={d['working_depth']:g} (m={d['normal_module_m'] * 1e3:.3f} mm, d_o={d['tip_diameter_m'] * 1e3:.2f} mm): "
            f"P={d['power_loss_w'] / 1e3:.3f} kW, TE={d['te_pp_m'] * 1e6:.3f} µm, σ_c={d['sigma_c_pa'] / 1e9:.3f} GPa, "
            f"σ_b={d['sigma_b_pa'] / 1e6:.0f} MPa")
    if "worst_ratio" in d:
        text += f", worst value/limit {d['worst_ratio']:.2f}"
    return text


def _human_sweep(p: dict) -> str:
    lines = [
        f"study {p['study']}, friction {p['friction_model']}: {p['designs_evaluated']} feasible designs evaluated "
        f"({p['converged']} converged, {p['failed']} failed) of a {p['space_size']}-design space; "
        f"{p['positions']} positions × {p['slices']} slices, median {p['time_per_design_s'] * 1e3:.1f} ms per design",
        f"P {p['power_loss_w_range'][0] / 1e3:.3f}–{p['power_loss_w_range'][1] / 1e3:.3f} kW, TE "
        f"{p['te_pp_m_range'][0] * 1e6:.3f}–{p['te_pp_m_range'][1] * 1e6:.3f} µm, σ_c "
        f"{p['sigma_c_pa_range'][0] / 1e9:.3f}–{p['sigma_c_pa_range'][1] / 1e9:.3f} GPa, σ_b "
        f"{p['sigma_b_pa_range'][0] / 1e6:.0f}–{p['sigma_b_pa_range'][1] / 1e6:.0f} MPa",
        f"designs outside the models' validity (flagged in the valid column): {p['designs_not_valid']}",
        f"designs like D (all search limits met): {p['matches']}",
    ]
    lines += ["  " + _fmt_design(d) for d in p["best_matches"]]
    if not p["matches"]:
        lines.append("nearest designs (largest value/limit first criterion):")
        lines += ["  " + _fmt_design(d) for d in p["nearest"]]
    for message, count in p["warnings"].items():
        lines.append(f"warning ({count} designs): {message}")
    if "out" in p:
        lines.append(f"table written to {p['out']}")
    lines.append(f"wall time {p['wall_time_s']:.1f} s")
    return "\n".join(lines)


def _study_pair(args, study):
    if args.design is not None and args.design in study.designs:
        return args.design, study.design(args.design)
    others = any(getattr(args, k) is not None for k in ("teeth", "working_depth", "teeth1", "teeth2", "module_mm"))
    if args.design is None and not others:
        return "D", study.design("D")
    from .cli_gear_geometry import build_pair

    return args.design or "options", build_pair(args)


def run_modifications(args: argparse.Namespace) -> int:
    import time

    from ehl_dataset.validation import check_range
    from efficiency.friction import describe_friction
    from efficiency.studies import modification_study, no_error

    started = time.perf_counter()
    study, friction, point, options = _setup(args)
    torques = parse_values(args.torques_nm, "torques-nm")
    for t in torques:
        check_range("torques-nm", t, 0.0, 1e7, low_inclusive=False, unit="N·m")
    profile = parse_values(args.profile_crowns_um, "profile-crowns-um")
    lead = parse_values(args.lead_crowns_um, "lead-crowns-um")
    for name, values in (("profile-crowns-um", profile), ("lead-crowns-um", lead)):
        for v in values:
            check_range(name, v, 0.0, 1000.0, unit="µm")
    name, pair = _study_pair(args, study)
    table = modification_study(pair, friction, [v * 1e-6 for v in profile], [v * 1e-6 for v in lead], torques,
                               point, options)
    ok = table["converged"].astype(bool) & no_error(table)
    rows = [{k: (bool(r[k]) if k == "converged" else str(r[k]) if k == "error" else float(r[k]))
             for k in ("torque_nm", "profile_crown_m", "lead_crown_m", "power_loss_w", "efficiency", "te_pp_m",
                       "sigma_c_pa", "sigma_b_pa", "converged", "error")} | {"valid": bool(r["valid"])}
            for _, r in table.iterrows()]
    payload = {"study": study.name, "design": name, "friction_model": describe_friction(friction),
               "speed_rpm": point.input_speed * 30.0 / 3.141592653589793, "cases": len(table),
               "converged": int(ok.sum()), "not_valid": int((ok & ~table["valid"].fillna(False).astype(bool)).sum()),
               "warnings": _warning_digest(table), "rows": rows}
    if args.out:
        payload["out"] = _write_csv(table, args.out)
    payload["wall_time_s"] = time.perf_counter() - started
    emit(payload, args.json, _human_modifications)
    return 0 if bool(ok.all()) else 1


def _human_modifications(p: dict) -> str:
    lines = [f"design {p['design']} ({p['study']}), friction {p['friction_model']}, {p['speed_rpm']:.0f} rpm: "
             f"{p['cases']} cases, {p['converged']} converged",
             f"{'T [N·m]':>8} {'M_P [µm]':>9} {'M_L [µm]':>9} {'P [kW]':>8} {'η [%]':>8} {'TE [µm]':>8} "
             f"{'σ_c [GPa]':>9} {'σ_b [MPa]':>9}"]
    for r in p["rows"]:
        lines.append(f"{r['torque_nm']:8.0f} {r['profile_crown_m'] * 1e6:9.1f} {r['lead_crown_m'] * 1e6:9.1f} "
                     f"{r['power_loss_w'] / 1e3:8.3f} {r['efficiency'] * 100:8.3f} {r['te_pp_m'] * 1e6:8.3f} "
                     f"{r['sigma_c_pa'] / 1e9:9.3f} {r['sigma_b_pa'] / 1e6:9.0f}"
                     + ("" if r["converged"] else f"  NOT CONVERGED {r['error']}"))
    for message, count in p["warnings"].items():
        lines.append(f"warning ({count} cases): {message}")
    if "out" in p:
        lines.append(f"table written to {p['out']}")
    lines.append(f"wall time {p['wall_time_s']:.1f} s")
    return "\n".join(lines)
