"""``gearloss gear evaluate``: loaded tooth contact of one gear pair over a mesh cycle.

The design is given exactly as for ``gearloss gear geometry`` (``--design FILE.toml``, the paper's parametrisation
``--teeth --pressure-angle-deg --helix-angle-deg --working-depth [--center-distance-mm --face-width-mm]`` or a
general pair ``--teeth1 --teeth2 --module-mm ...``); the operating point by ``--torque-nm --speed-rpm``; the flank
modifications by ``--profile-crown-um --lead-crown-um --lead-slope-um --tip-relief-um --tip-relief-length-mm``
(per gear, default none); the resolution by ``--slices --positions``. Prints peak-to-peak transmission error,
maximum contact pressure and root stress with the mesh positions where they occur, the mesh stiffness, and the
ISO 6336 nominal values alongside; ``--json`` prints one JSON object in SI units.

With ``--friction MODEL`` (and ``--oil-temp-c --rq-um --lubricant``; :func:`efficiency.friction.friction_from_spec`)
it also computes the mechanical power loss of Li & Kahraman 2009, Eq. 10–11: the cycle mean P (``power_loss_w``),
the efficiency η (``efficiency``) and P(φ_m) at every mesh position (``power_loss_instant_w``); a coefficient file's
surrogate reports how many loaded points it clipped to its fitted ranges, per input
(``friction_clipped_inputs`` of ``friction_points``), and the off-grid validation its file records
(``friction_offgrid``; printed per branch with ``--offgrid``). Without ``--friction`` no power loss is computed.
"""

from __future__ import annotations

import argparse
import math
from dataclasses import dataclass
from typing import Any


def register(gear_subparsers) -> None:
    parser = gear_subparsers.add_parser(
        "evaluate", help="load distribution, transmission error, stresses and (with --friction) power loss",
        description="Loaded tooth contact of one gear pair (slice model, Conry-Seireg complementarity): "
                    "peak-to-peak transmission error, max Hertz pressure, max root stress, mesh stiffness; with "
                    "--friction the sliding friction power loss and efficiency (Li & Kahraman 2009, Eq. 10-11).")
    from .cli_gear_geometry import add_design_options

    add_design_options(parser)
    load = parser.add_argument_group("operating point and modifications")
    load.add_argument("--torque-nm", type=float, default=250.0, help="input torque on gear 1 [N·m] (default 250)")
    load.add_argument("--speed-rpm", type=float, default=4000.0, help="speed of gear 1 [rpm] (default 4000)")
    load.add_argument("--profile-crown-um", type=float, help="profile crown M_P per gear [µm] (default 0)")
    load.add_argument("--lead-crown-um", type=float, help="lead crown M_L per gear [µm] (default 0)")
    load.add_argument("--lead-slope-um", type=float,
                      help="lead slope / misalignment f_Hβ across the face [µm] (sign: + opens the far end)")
    load.add_argument("--tip-relief-um", type=float, help="linear tip relief C_a per gear [µm]")
    load.add_argument("--tip-relief-length-mm", type=float, help="roll length of the tip relief per gear [mm]")
    model = parser.add_argument_group("model and resolution")
    model.add_argument("--slices", type=int, default=30, help="slices across the face (default 30)")
    model.add_argument("--positions", type=int, default=None,
                       help="mesh positions per cycle (default: chosen per design, 24-48, so that the load-sharing "
                            "breakpoints fall on sampling-cell boundaries)")
    model.add_argument("--outputs", default="te,stresses",
                       help="comma-separated subset of te,stresses to compute (default both; '' for loads only)")
    model.add_argument("--contact-model", choices=("weber", "linear"), default="weber",
                       help="Hertzian contact compliance (default weber)")
    model.add_argument("--coupling-length-factor", type=float, default=None,
                       help="face-coupling length of the tooth in tooth depths (default 0.6, from a 3-D FE check)")
    model.add_argument("--foundation-coupling-length-factor", type=float, default=None,
                       help="face-coupling length of the gear body in tooth depths (default: as the tooth)")
    model.add_argument("--load-sharing", choices=("elastic", "rigid-uniform", "independent-slices"),
                       default="elastic",
                       help="elastic (default), rigid-uniform (uniform load per contact length: Wimmer's H_VL; "
                            "unmodified flanks only) or independent-slices (no face coupling)")
    friction = parser.add_argument_group("friction power loss (computed only with --friction)")
    friction.add_argument("--friction", metavar="MODEL",
                          help="friction model: a coefficient file (surrogate), xu2007, benedict_kelley, iso14179, "
                               "constant:MU, ehl:LEVEL[:auto|full] (EHL solver at every point, slow) or "
                               "ehl-grid:LEVEL[:auto|full][:NSxNP] (EHL on a small grid, interpolated)")
    friction.add_argument("--oil-temp-c", type=float, default=90.0, help="oil inlet temperature [°C] (default 90)")
    friction.add_argument("--rq-um", type=float, nargs="+", default=[0.4], metavar="RQ",
                          help="RMS roughness of the flanks [µm]: one value for both or RQ1 RQ2 (default 0.4)")
    friction.add_argument("--lubricant", default="atf",
                          help="lubricant name or TOML file for the EHL and published models (default atf; a "
                               "coefficient file carries its own)")
    friction.add_argument("--offgrid", action="store_true",
                          help="also print the off-grid validation the coefficient file records: median, 90th "
                               "percentile and max error of mu per branch and the interval's coverage (always in "
                               "--json, as friction_offgrid; null when the model records none)")
    iso = parser.add_argument_group("ISO/TR 14179-2 mean friction and mesh loss (with --iso14179-2)")
    iso.add_argument("--iso14179-2", dest="iso14179_2", action="store_true",
                     help="also report the standard's μ_mz, H_V and P_VZP (uses --oil-temp-c)")
    iso.add_argument("--oil-type", default="mineral",
                     help="base oil for X_L of ISO/TR 14179-2 (this block and --friction iso14179): mineral "
                          "(0.846), pao (0.65), ester (0.65), polyglycol (0.585), reference (1.0, the formula as "
                          "printed)")
    iso.add_argument("--ra-um", type=float, nargs="+", metavar="RA",
                     help="arithmetic mean roughness Ra [µm] of the flanks (one or two values); default "
                          "√(2/π)·Rq from --rq-um (Gaussian surface)")
    iso.add_argument("--nu40-cst", type=float, help="oil kinematic viscosity at 40 °C [cSt] (with --nu100-cst; "
                                                    "default: from --lubricant)")
    iso.add_argument("--nu100-cst", type=float, help="oil kinematic viscosity at 100 °C [cSt]")
    iso.add_argument("--density-kg-m3", type=float, default=880.0, help="oil density at 15 °C [kg/m³] (880)")
    iso.add_argument("--eta-oil-mpas", type=float,
                     help="oil dynamic viscosity at the oil temperature [mPa·s] (instead of ν40/ν100 or a lubricant)")
    from .cli_validity import add_validity_options

    add_validity_options(parser)
    parser.add_argument("--per-position", action="store_true", help="include per-position arrays in the output")
    parser.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    parser.set_defaults(handler=run_evaluate)


def _modifications(args):
    """Modifications from the design file's optional ``[modifications]`` table, overridden by the options."""
    from ehl_dataset.validation import InputError
    from efficiency.modifications import modifications_from_mapping

    table = {}
    if getattr(args, "design", None):
        from efficiency.design_io import read_toml

        table = dict(read_toml(args.design).get("modifications", {}))
    for option in ("profile_crown_um", "lead_crown_um", "lead_slope_um", "tip_relief_um", "tip_relief_length_mm"):
        value = getattr(args, option)
        if value is not None:
            table[option] = value
    try:
        return modifications_from_mapping(table)
    except InputError as err:  # name the option in engineering units
        raise InputError(err.parameter.replace("modifications.", "").replace("_", "-"), err.value,
                         err.accepted) from None


def _pair_from_args(args):
    from .cli_gear_geometry import build_pair

    return build_pair(args)


@dataclass(frozen=True)
class EvaluateInputs:
    """The inputs of ``gear evaluate``, resolved once from the options (each value checked once, where it is built).

    Parameters
    ----------
    pair : GearPair
        The design [SI].
    point : StudyPoint
        Operating point: input torque [N·m], speed [rad/s], oil temperature [K], flank roughness [m] and the flank
        modifications (the design studies' operating point).
    options : MeshOptions
        Resolution and contact model of the mesh evaluation [-].
    friction : callable or None
        The friction model of ``--friction`` (None: no power loss) [-].
    lubricant : Lubricant or None
        The ``--lubricant``, loaded once where a model needs it (the ISO/TR 14179-2 block without an oil viscosity
        option; the published and EHL friction models) [-].
    """

    pair: Any
    point: Any
    options: Any
    friction: Any = None
    lubricant: Any = None


def resolve_inputs(args: argparse.Namespace) -> EvaluateInputs:
    """Build the design, the operating point, the mesh options, the lubricant and the friction model from the
    options, once; inner code takes them as they are."""
    from ehl_dataset.model.lubricant import load_lubricant
    from ehl_dataset.validation import InputError
    from efficiency.mesh_cycle import DEFAULT_COUPLING_LENGTH_FACTOR, MeshOptions
    from efficiency.studies import StudyPoint

    pair = _pair_from_args(args)
    rq = list(args.rq_um)
    if len(rq) not in (1, 2):
        raise InputError("rq-um", rq, "one value (both flanks) or two values RQ1 RQ2 [µm]")
    point = StudyPoint(args.torque_nm, args.speed_rpm * math.pi / 30.0, args.oil_temp_c + 273.15, rq[0] * 1e-6,
                       rq[-1] * 1e-6, _modifications(args))
    coupling = DEFAULT_COUPLING_LENGTH_FACTOR if args.coupling_length_factor is None else args.coupling_length_factor
    options = MeshOptions(positions=args.positions, slices=args.slices,
                          outputs=frozenset(o.strip() for o in args.outputs.split(",") if o.strip()),
                          contact_model=args.contact_model, coupling_length_factor=coupling,
                          foundation_coupling_length_factor=args.foundation_coupling_length_factor,
                          load_sharing=args.load_sharing)
    lubricant = None
    if args.iso14179_2 and args.nu40_cst is None and args.eta_oil_mpas is None:
        lubricant = load_lubricant(args.lubricant)
    friction = None
    if args.friction is not None:
        from efficiency.friction import friction_from_spec

        friction = friction_from_spec(args.friction, lubricant if lubricant is not None else args.lubricant,
                                      clip_to_fitted_ranges=not args.no_clip, oil_type=args.oil_type)
    return EvaluateInputs(pair, point, options, friction, lubricant)


def run_evaluate(args: argparse.Namespace) -> int:
    import time

    from ehl_dataset.validation import InputError
    from efficiency import iso6336
    from efficiency.loss_factor import ohlendorf_loss_factor, wimmer_loss_factor
    from efficiency.mesh_cycle import evaluate_mesh

    started = time.perf_counter()
    if args.offgrid and args.friction is None:
        raise InputError("offgrid", True, "only with --friction COEFFS (a coefficient file)")
    inputs = resolve_inputs(args)
    pair, point, options = inputs.pair, inputs.point, inputs.options
    mods = point.modifications
    result = evaluate_mesh(pair, point.input_torque, speed_rad_s=point.input_speed, modifications=mods,
                           options=options)
    payload = {
        "speed_rpm": args.speed_rpm,
        "profile_crown_m": mods.profile_crown, "lead_crown_m": mods.lead_crown, "lead_slope_m": mods.lead_slope,
        "contact_model": options.contact_model, "load_sharing": options.load_sharing,
        "loss_factor_ohlendorf": ohlendorf_loss_factor(pair), "loss_factor_wimmer": wimmer_loss_factor(pair),
        **result.to_dict(per_position=args.per_position),
    }
    try:
        ref = iso6336.reference_values(pair, point.input_torque)
        payload["iso6336"] = {k: ref[k] for k in ("sigma_h0_pa", "sigma_f0_1_pa", "sigma_f0_2_pa",
                                                  "c_single_n_per_m2", "c_gamma_alpha_n_per_m2")}
    except InputError as err:
        payload["iso6336"] = {"error": str(err)}
    if args.iso14179_2:
        payload["iso14179_2"] = _iso14179(inputs, args)
    if inputs.friction is not None:
        payload.update(_power_loss(result, inputs, args))
    payload["wall_time_s"] = time.perf_counter() - started
    from efficiency.validity import mesh_checks

    from .cli_validity import finish

    checks = mesh_checks(result, pair) + payload.pop("friction_checks", [])
    return finish(payload, checks, args, lambda p: _human(p, args.offgrid), converged=result.converged,
                  options={"contact_pressure": "torque-nm", "root_stress": "torque-nm", "deflection": "torque-nm",
                           "friction_surrogate_range": "friction"})


def _iso14179(inputs: EvaluateInputs, args) -> dict:
    """ISO/TR 14179-2 μ_mz, H_V, P_VZP (efficiency.iso14179) from the oil and roughness options."""
    from ehl_dataset.validation import InputError, check_range
    from efficiency.iso14179 import SimpleOil, iso_14179_2_mesh, lubricant_factor
    from surrogate.published import RA_PER_RQ

    point = inputs.point
    temperature = point.oil_temperature
    if args.ra_um:
        if len(args.ra_um) not in (1, 2):
            raise InputError("ra-um", args.ra_um, "one value (both flanks) or two values RA1 RA2 [µm]")
        ra1 = check_range("ra-um", args.ra_um[0], 0.0, 100.0, low_inclusive=False, unit="µm") * 1e-6
        ra2 = check_range("ra-um", args.ra_um[-1], 0.0, 100.0, low_inclusive=False, unit="µm") * 1e-6
    else:
        ra1, ra2 = RA_PER_RQ * point.rq1, RA_PER_RQ * point.rq2
    x_l = lubricant_factor(args.oil_type)
    if (args.nu40_cst is None) != (args.nu100_cst is None):
        raise InputError("nu40-cst/nu100-cst", (args.nu40_cst, args.nu100_cst), "both or neither")
    if args.eta_oil_mpas is not None:
        if args.nu40_cst is not None:
            raise InputError("eta-oil-mpas", args.eta_oil_mpas, "either --eta-oil-mpas or --nu40-cst/--nu100-cst")
        eta = check_range("eta-oil-mpas", args.eta_oil_mpas, 0.01, 1e5, unit="mPa·s") * 1e-3
        source = "eta-oil-mpas"
    elif args.nu40_cst is not None:
        oil = SimpleOil(nu40=args.nu40_cst * 1e-6, nu100=args.nu100_cst * 1e-6, density15=args.density_kg_m3,
                        oil_type=args.oil_type)
        eta, source = oil.dynamic_viscosity(temperature), "nu40/nu100 (Walther)"
    else:
        from surrogate.features import lubricant_properties

        eta, _ = lubricant_properties(inputs.lubricant, temperature)
        eta, source = float(eta), f"lubricant {args.lubricant}"
    out = iso_14179_2_mesh(inputs.pair, point.input_torque, point.input_speed, eta, ra1, ra2, x_l)
    out.update(oil_type=args.oil_type, viscosity_source=source, oil_temperature_k=temperature)
    return out


def _power_loss(mesh, inputs: EvaluateInputs, args) -> dict:
    """Mean and instantaneous friction power loss (Li & Kahraman 2009, Eq. 10-11) with the resolved model."""
    import warnings

    from efficiency.friction_accuracy import load_weighted_mu, pitch_region_share
    from efficiency.power_loss import mesh_power_loss

    point, friction = inputs.point, inputs.friction
    temperature, rq1, rq2 = point.oil_temperature, point.rq1, point.rq2
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        loss = mesh_power_loss(mesh, friction, temperature, rq1, rq2)
    instant = loss.power_loss_instant
    out = {
        "friction_model": loss.friction_model, "oil_temperature_k": temperature, "rq1_m": rq1, "rq2_m": rq2,
        "input_power_w": loss.input_power, "power_loss_w": loss.power_loss, "efficiency": loss.efficiency,
        "power_loss_instant_w": instant, "power_loss_instant_min_w": float(instant.min()),
        "power_loss_instant_max_w": float(instant.max()), "mu_mean": load_weighted_mu(loss, mesh),
        "pitch_region_power_share": pitch_region_share(loss, mesh), "power_loss_time_s": loss.wall_time_s,
    }
    from .cli_fit_lines import band_entries

    out.update(band_entries(loss, friction))
    out.setdefault("friction_offgrid", getattr(friction, "offgrid", None) or None)
    if "ehl_solves" in loss.extra:
        out["ehl_solves"] = int(loss.extra["ehl_solves"])
        out["ehl_points"] = int(loss.extra["ehl_points"])
    if "clipped_inputs" in loss.extra:  # a coefficient file's surrogate, held inside its fitted ranges
        out["friction_points"] = int(loss.extra["surrogate_points"])
        out["friction_clipped_inputs"] = {k: int(v) for k, v in loss.extra["clipped_inputs"].items()}
    messages = sorted({str(w.message) for w in caught})
    if messages:
        out["friction_warnings"] = messages
    from efficiency.validity import friction_checks

    out["friction_checks"] = friction_checks(loss, mesh, friction, temperature, rq1, rq2, clip=not args.no_clip)
    return out


def _human(p: dict, show_offgrid: bool = False) -> str:
    """The human-readable output; with ``show_offgrid`` the friction model's off-grid validation per branch
    (:func:`surrogate.offgrid.offgrid_lines`) in place of its one-line summary."""
    lines = [
        f"torque {p['torque_nm']:.4g} N·m at {p['speed_rpm']:.5g} rpm; M_P {p['profile_crown_m'] * 1e6:.3g} µm, "
        f"M_L {p['lead_crown_m'] * 1e6:.3g} µm, lead slope {p['lead_slope_m'] * 1e6:.3g} µm; "
        f"{p['positions']} positions × {p['slices']} slices, contact model {p['contact_model']}",
        f"normal load W = {p['normal_load_n']:.1f} N, max line load {p['max_load_per_length_n_per_m'] / 1e3:.1f} N/mm",
        ("mesh stiffness: rigid teeth" if p['mesh_stiffness_per_width_n_per_m2'] is None else
         f"mesh stiffness (cycle mean) {p['mesh_stiffness_per_width_n_per_m2'] / 1e9:.2f} N/(mm·µm)"),
        f"loss factor H_V = P/(μ P_in) of this load sharing ({p['load_sharing']}) {p['loss_factor']:.5f}; "
        f"Ohlendorf H_V {p['loss_factor_ohlendorf']:.5f}, Wimmer H_VL (rigid, uniform) {p['loss_factor_wimmer']:.5f}",
    ]
    if "te_pp_m" in p:
        lines.append(f"transmission error peak-to-peak {p['te_pp_m'] * 1e6:.3f} µm (mean {p['te_mean_m'] * 1e6:.2f} µm)")
    if "sigma_c_pa" in p:
        lines.append(f"max contact pressure σ_c {p['sigma_c_pa'] / 1e6:.0f} MPa at φ = "
                     f"{p['sigma_c_position_rad'] * 1e3:.2f} mrad")
        lines.append(f"max root stress σ_b {p['sigma_b_pa'] / 1e6:.0f} MPa (gear {p['sigma_b_gear']}) at φ = "
                     f"{p['sigma_b_position_rad'] * 1e3:.2f} mrad")
    iso = p.get("iso6336", {})
    if "sigma_h0_pa" in iso:
        lines.append(f"ISO 6336 nominal: σ_H0 {iso['sigma_h0_pa'] / 1e6:.0f} MPa, σ_F0 {iso['sigma_f0_1_pa'] / 1e6:.0f}"
                     f"/{iso['sigma_f0_2_pa'] / 1e6:.0f} MPa, c_γα {iso['c_gamma_alpha_n_per_m2'] / 1e9:.2f} N/(mm·µm)")
    if "power_loss_w" in p:
        lines.append(f"friction: {p['friction_model']}; oil {p['oil_temperature_k'] - 273.15:.4g} °C, Rq "
                     f"{p['rq1_m'] * 1e6:.3g}/{p['rq2_m'] * 1e6:.3g} µm"
                     + (f"; {p['ehl_solves']} EHL solves for {p['ehl_points']} loaded points" if "ehl_solves" in p
                        else ""))
        lines.append(f"power loss P = {p['power_loss_w'] / 1e3:.4g} kW of {p['input_power_w'] / 1e3:.4g} kW, "
                     f"efficiency η = {p['efficiency'] * 100:.3f} %, load-weighted μ = {p['mu_mean']:.4f}")
        from .cli_fit_lines import band_lines

        if show_offgrid:
            from surrogate.offgrid import offgrid_lines

            lines.extend(band_lines({k: v for k, v in p.items() if k != "friction_offgrid"}))
            lines.extend(offgrid_lines(p["friction_offgrid"]) if p.get("friction_offgrid") is not None else
                         ["off-grid validation: none recorded by this friction model (a coefficient file "
                          "fitted with an off-grid sample records one)"])
        else:
            lines.extend(band_lines(p))
        lines.append(f"instantaneous P(φ) {p['power_loss_instant_min_w'] / 1e3:.4g} to "
                     f"{p['power_loss_instant_max_w'] / 1e3:.4g} kW over the cycle "
                     f"({p['power_loss_time_s'] * 1e3:.0f} ms)")
        if "friction_clipped_inputs" in p:
            moved = ", ".join(f"{k} {v}" for k, v in p["friction_clipped_inputs"].items() if v)
            lines.append(f"surrogate inputs clipped to the fitted ranges: {moved or 'none'} of {p['friction_points']} "
                         "loaded points")
        for message in p.get("friction_warnings", []):
            lines.append(f"warning: {message}")
    if "iso14179_2" in p:
        q = p["iso14179_2"]
        lines.append(f"ISO/TR 14179-2: μ_mz {q['mu_mz']:.4f} (X_L {q['x_l']:.3g} {q['oil_type']}, η "
                     f"{q['eta_oil_mpas']:.3g} mPa·s, Ra {q['ra_um']:.3g} µm), H_V {q['loss_factor_ohlendorf']:.4f}, "
                     f"P_VZP {q['p_vzp_w']:.1f} W")
    lines.append(f"converged {p['converged']} (equilibrium residual {p['equilibrium_residual']:.1e}, "
                 f"{p['active_set_iterations']} active-set iterations), {p['wall_time_s'] * 1e3:.0f} ms")
    return "\n".join(lines)
