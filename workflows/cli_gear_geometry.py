"""``gearloss gear geometry`` and ``gearloss gear feasibility``: the geometry of one pair, and the feasible count of
the paper's design space.

A design is given by ``--design FILE.toml``, by the paper's parametrisation (``--teeth N --pressure-angle-deg
--helix-angle-deg --working-depth [--center-distance-mm --face-width-mm]``: identical gears, 1:1) or as a general
pair (``--teeth1 --teeth2 --module-mm --pressure-angle-deg --helix-angle-deg --face-width-mm [--shift1 --shift2
--center-distance-mm]``). Output: diameters in mm, contact ratios, base pitch, backlash, tip thickness and the
feasibility verdict with every violated limit; ``--json`` prints SI values with unit-suffixed keys.
"""

from __future__ import annotations

import argparse

from ehl_dataset.validation import InputError

from .cli_output import emit


def add_design_options(parser) -> None:
    """The design options read by :func:`build_pair` (shared by ``gear geometry`` and ``gear evaluate``)."""
    source = parser.add_argument_group("design source (one of)")
    source.add_argument("--design", metavar="FILE", help="design TOML file with a [design] table")
    paper = parser.add_argument_group("paper parametrisation (identical gears, 1:1, standard centre distance)")
    paper.add_argument("--teeth", type=int, help="number of teeth N of each gear")
    paper.add_argument("--working-depth", type=float, help="working depth ratio Λ_wd (whole depth / m_n)")
    general = parser.add_argument_group("general pair")
    general.add_argument("--teeth1", type=int, help="teeth of gear 1 (pinion, driving)")
    general.add_argument("--teeth2", type=int, help="teeth of gear 2")
    general.add_argument("--module-mm", type=float, help="normal module m_n [mm]")
    general.add_argument("--shift1", type=float, default=0.0, help="profile shift coefficient x1 (default 0)")
    general.add_argument("--shift2", type=float, default=0.0, help="profile shift coefficient x2 (default 0)")
    general.add_argument("--addendum-coefficient", type=float, default=1.0, help="basic rack h_aP/m_n (1.0)")
    general.add_argument("--dedendum-coefficient", type=float, default=1.25, help="basic rack h_fP/m_n (1.25)")
    general.add_argument("--no-tip-reduction", action="store_true",
                         help="keep the full addendum of shifted gears (no k·m_n tip reduction)")
    common = parser.add_argument_group("common")
    common.add_argument("--pressure-angle-deg", type=float, help="normal pressure angle [deg]")
    common.add_argument("--helix-angle-deg", type=float, help="helix angle [deg] (0 = spur)")
    common.add_argument("--face-width-mm", type=float, help="face width [mm] (paper: 25)")
    common.add_argument("--center-distance-mm", type=float,
                        help="operating centre distance [mm] (paper: 91.5; general: zero backlash if omitted)")
    common.add_argument("--root-fillet-coefficient", type=float,
                        help="generating rack tip radius ρ_fP/m_n (paper default 0.25, general 0.38)")
    common.add_argument("--thickness-allowance-mm", type=float,
                        help="normal tooth thinning A_sn of each gear [mm] (paper default: ISO/TR 10064-2 backlash)")
    mfg = parser.add_argument_group("manufacturing data of a general pair (override the basic-rack values)")
    mfg.add_argument("--tip-diameter-mm", type=float, nargs=2, metavar=("DA1", "DA2"), help="tip diameters [mm]")
    mfg.add_argument("--root-diameter-mm", type=float, nargs=2, metavar=("DF1", "DF2"), help="root diameters [mm]")
    mfg.add_argument("--tooth-thickness-mm", type=float, nargs=2, metavar=("SN1", "SN2"),
                     help="normal tooth thicknesses on the reference circle [mm] (instead of an allowance)")


def register(gear_subparsers) -> None:
    geometry = gear_subparsers.add_parser(
        "geometry", help="geometry and feasibility of one helical gear pair",
        description="Geometry (ISO 21771) and feasibility (Li & Kahraman 2009 limits) of one helical gear pair.")
    add_design_options(geometry)
    common = geometry.add_argument_group("output")
    common.add_argument("--torque-nm", type=float,
                        help="pinion torque [N·m]: also print the ISO 6336 reference values at this torque")
    common.add_argument("--strict", action="store_true", help="exit status 1 when the design is infeasible")
    common.add_argument("--study-limits", action="store_true",
                        help="judge with the paper study's limits (backlash 0.04 mm, tip thickness and root "
                             "clearance 0.2 m_n) even for a pair outside it (default: only for the paper "
                             "parametrisation; other pairs get the physical limits)")
    common.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    geometry.set_defaults(handler=run_geometry)

    feas = gear_subparsers.add_parser(
        "feasibility", help="count the feasible designs of the paper's design space",
        description="Screen the study's full-factorial design space (paper2009: 30,464 designs) against the "
                    "feasibility limits; prints the count per criterion.")
    feas.add_argument("--study", default="paper2009", help="study NAME or TOML file (default paper2009)")
    feas.add_argument("--backlash-policy", choices=("iso10064", "constant", "module", "backlash"),
                      help="how the teeth are thinned for backlash (default: the study's)")
    feas.add_argument("--backlash-policy-value", type=float,
                      help="constant: A_sn [mm]; module: A_sn/m_n; backlash: j_bn [mm]")
    feas.add_argument("--root-fillet-coefficient", type=float, help="rack tip radius ρ_fP/m_n (default: study's)")
    feas.add_argument("--min-tip-thickness-module", type=float, help="tip thickness limit in m_n (default 0.2)")
    feas.add_argument("--json", action="store_true", help="print one JSON object")
    feas.set_defaults(handler=run_feasibility)


# ---------------------------------------------------------------------- geometry
def build_pair(args: argparse.Namespace):
    """The :class:`GearPair` described by the command-line options."""
    import math

    from efficiency.design_io import load_design, paper_design
    from efficiency.geometry import GearPair

    paper_given = args.teeth is not None or args.working_depth is not None
    general_given = any(v is not None for v in (args.teeth1, args.teeth2, args.module_mm))
    chosen = sum((args.design is not None, paper_given, general_given))
    if chosen != 1:
        raise InputError("design", "options", "exactly one of --design FILE, the paper options (--teeth, "
                         "--working-depth, ...) or the general options (--teeth1, --teeth2, --module-mm, ...)")
    if args.design is not None:
        return load_design(args.design)
    if paper_given:
        for name in ("teeth", "working_depth", "pressure_angle_deg", "helix_angle_deg"):
            if getattr(args, name) is None:
                raise InputError(name.replace("_", "-"), None, "required with the paper parametrisation")
        return paper_design(
            args.teeth, args.pressure_angle_deg, args.helix_angle_deg, args.working_depth,
            center_distance_mm=91.5 if args.center_distance_mm is None else args.center_distance_mm,
            face_width_mm=25.0 if args.face_width_mm is None else args.face_width_mm,
            root_fillet_coefficient=0.25 if args.root_fillet_coefficient is None else args.root_fillet_coefficient,
            thickness_allowance_mm=args.thickness_allowance_mm)
    for name in ("teeth1", "teeth2", "module_mm", "pressure_angle_deg", "face_width_mm"):
        if getattr(args, name) is None:
            raise InputError(name.replace("_", "-"), None, "required for a general pair")
    allowance = 0.0 if args.thickness_allowance_mm is None else args.thickness_allowance_mm * 1e-3
    if args.tooth_thickness_mm is not None and args.thickness_allowance_mm is not None:
        raise InputError("tooth-thickness-mm", args.tooth_thickness_mm, "either --tooth-thickness-mm or "
                         "--thickness-allowance-mm, not both")

    def mm_pair(values):
        return None if values is None else (values[0] * 1e-3, values[1] * 1e-3)

    return GearPair(
        z1=args.teeth1, z2=args.teeth2, normal_module=args.module_mm * 1e-3,
        normal_pressure_angle=math.radians(args.pressure_angle_deg),
        helix_angle=math.radians(args.helix_angle_deg or 0.0), face_width=args.face_width_mm * 1e-3,
        x1=args.shift1, x2=args.shift2, addendum_coefficient=args.addendum_coefficient,
        dedendum_coefficient=args.dedendum_coefficient,
        root_fillet_coefficient=0.38 if args.root_fillet_coefficient is None else args.root_fillet_coefficient,
        center_distance=None if args.center_distance_mm is None else args.center_distance_mm * 1e-3,
        thickness_allowance1=allowance, thickness_allowance2=allowance, tip_reduction=not args.no_tip_reduction,
        tip_diameters=mm_pair(args.tip_diameter_mm), root_diameters_given=mm_pair(args.root_diameter_mm),
        normal_thicknesses_given=mm_pair(args.tooth_thickness_mm))


def run_geometry(args: argparse.Namespace) -> int:
    import time

    from efficiency import iso6336
    from efficiency.feasibility import FeasibilityLimits, check_design

    start = time.perf_counter()
    pair = build_pair(args)
    in_study = args.teeth is not None or args.working_depth is not None or args.study_limits
    limits = FeasibilityLimits() if in_study else FeasibilityLimits.physical()
    report = check_design(pair, limits)
    payload = pair.summary()
    payload["feasibility_limits"] = "paper study" if in_study else "physical"
    payload["feasible"] = report.feasible
    payload["violations"] = [v.as_dict() for v in report.violations]
    if args.torque_nm is not None:
        payload["iso6336"] = iso6336.reference_values(pair, args.torque_nm)
        payload["iso6336"]["torque1_nm"] = float(args.torque_nm)
    payload["wall_time_s"] = time.perf_counter() - start
    emit(payload, args.json, lambda p: _human_geometry(p, report))
    return 1 if (args.strict and not report.feasible) else 0


def _human_geometry(p: dict, report) -> str:
    import math

    def mm(values):
        return " / ".join(f"{v * 1e3:.4f}" for v in values)

    lines = [
        f"gear pair z1/z2 = {p['z1']}/{p['z2']}, m_n = {p['normal_module_m'] * 1e3:.4f} mm, "
        f"α_n = {math.degrees(p['normal_pressure_angle_rad']):.3f}°, β = {math.degrees(p['helix_angle_rad']):.3f}°, "
        f"b = {p['face_width_m'] * 1e3:.3f} mm, x1/x2 = {p['x1']:.4f}/{p['x2']:.4f}",
        f"centre distance a = {p['center_distance_m'] * 1e3:.4f} mm (reference a0 = "
        f"{p['standard_center_distance_m'] * 1e3:.4f} mm), α_wt = {math.degrees(p['working_pressure_angle_rad']):.4f}°,"
        f" β_b = {math.degrees(p['base_helix_angle_rad']):.4f}°",
        "diameters [mm]            gear 1 / gear 2",
        f"  reference d             {mm(p['reference_diameter_m'])}",
        f"  base d_b                {mm(p['base_diameter_m'])}",
        f"  working pitch d_w       {mm(p['working_pitch_diameter_m'])}",
        f"  tip d_a                 {mm(p['tip_diameter_m'])}",
        f"  root d_f                {mm(p['root_diameter_m'])}",
        f"  form d_Ff               {mm(p['form_diameter_m'])}",
        f"  start of active profile {mm(p['sap_diameter_m'])}",
        f"tip thickness normal [mm] {mm(p['tip_normal_thickness_m'])}",
        f"root clearance [mm]       {mm(p['root_clearance_m'])}",
        f"base pitch p_bt = {p['transverse_base_pitch_m'] * 1e3:.5f} mm, p_bn = {p['normal_base_pitch_m'] * 1e3:.5f} mm",
        f"contact ratios ε_α = {p['contact_ratio']:.5f}, ε_β = {p['overlap_ratio']:.5f}, "
        f"ε_γ = {p['total_contact_ratio']:.5f}",
        f"backlash j_wt = {p['circumferential_backlash_m'] * 1e3:.4f} mm (circumferential), "
        f"j_bn = {p['normal_backlash_m'] * 1e3:.4f} mm (normal)",
        f"verdict: {report}",
    ]
    if "iso6336" in p:
        r = p["iso6336"]
        lines += [
            f"ISO 6336 at T1 = {r['torque1_nm']:g} N·m: F_t = {r['tangential_load_n']:.1f} N, Z_H = {r['z_h']:.5f}, "
            f"Z_E = {r['z_e_sqrt_pa'] / 1e3:.4f} √MPa, Z_ε = {r['z_eps']:.4f}, Z_β = {r['z_beta']:.5f}, "
            f"σ_H0 = {r['sigma_h0_pa'] / 1e6:.2f} MPa",
            f"  c'_th = {r['c_th_n_per_m2'] / 1e9:.4f}, c' = {r['c_single_n_per_m2'] / 1e9:.4f}, "
            f"c_γα = {r['c_gamma_alpha_n_per_m2'] / 1e9:.4f}, c_γβ = {r['c_gamma_beta_n_per_m2'] / 1e9:.4f} N/(mm·µm)",
            f"  Y_F = {r['y_f1']:.4f}/{r['y_f2']:.4f}, Y_S = {r['y_s1']:.4f}/{r['y_s2']:.4f}, Y_β = {r['y_beta']:.4f},"
            f" σ_F0 = {r['sigma_f0_1_pa'] / 1e6:.1f}/{r['sigma_f0_2_pa'] / 1e6:.1f} MPa",
        ]
    return "\n".join(lines)


# ---------------------------------------------------------------------- feasibility count
def run_feasibility(args: argparse.Namespace) -> int:
    import dataclasses
    import time

    from efficiency.design_io import load_study
    from efficiency.feasibility import count_feasible

    start = time.perf_counter()
    study = load_study(args.study)
    space, limits = study.space, study.limits
    changes = {}
    if args.backlash_policy is not None:
        changes["backlash_policy"] = args.backlash_policy
    if args.backlash_policy_value is not None:
        policy = changes.get("backlash_policy", space.backlash_policy)
        scale = 1e-3 if policy in ("constant", "backlash") else 1.0
        changes["backlash_policy_value"] = args.backlash_policy_value * scale
    if args.root_fillet_coefficient is not None:
        changes["root_fillet_coefficient"] = args.root_fillet_coefficient
    space = dataclasses.replace(space, **changes)
    if args.min_tip_thickness_module is not None:
        limits = dataclasses.replace(limits, min_tip_thickness=args.min_tip_thickness_module)
    counts = count_feasible(space, limits)
    payload = {
        "study": study.name, "total": counts.pop("total"), "feasible": counts.pop("feasible"),
        "satisfied_by_criterion": counts, "paper_feasible_count": study.paper_feasible_count,
        "backlash_policy": space.backlash_policy, "backlash_policy_value": space.backlash_policy_value,
        "root_fillet_coefficient": space.root_fillet_coefficient,
        "limits": dataclasses.asdict(limits), "wall_time_s": time.perf_counter() - start,
    }
    emit(payload, args.json, _human_feasibility)
    return 0


def _human_feasibility(p: dict) -> str:
    lines = [f"{p['study']}: {p['feasible']} of {p['total']} designs feasible"
             + (f" (paper: about {p['paper_feasible_count']})" if p["paper_feasible_count"] else ""),
             f"backlash policy {p['backlash_policy']} ({p['backlash_policy_value']:g}), "
             f"rack tip radius {p['root_fillet_coefficient']:g} m_n",
             "designs satisfying each criterion:"]
    lines += [f"  {name:16s} {count}" for name, count in p["satisfied_by_criterion"].items()]
    lines.append(f"({p['wall_time_s']:.2f} s)")
    return "\n".join(lines)
