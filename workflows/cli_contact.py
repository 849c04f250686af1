"""``gearloss contact solve``: one EHL line contact from the command line (engineering units in, SI JSON out)."""

from __future__ import annotations

from ehl_dataset.names import (CLOSURES, CONTACT_EFFECT_PLANS, DEFAULT_CLOSURE, DEFAULT_FLUCTUATIONS, DEFAULT_LEVEL,
                               FLUCTUATIONS, LEVELS, MODELS)


def register(subparsers) -> None:
    parser = subparsers.add_parser("contact", help="one EHL line contact")
    contact_sub = parser.add_subparsers(dest="contact_command", metavar="COMMAND")
    parser.set_defaults(handler=lambda args: parser.print_help() or 2)
    solve = contact_sub.add_parser(
        "solve", help="solve one line contact (smooth steady, homogenised or deterministic mixed, as the effect plan says)",
        description="Solve one EHL line contact. Inputs in engineering units; --json prints SI units.")
    solve.add_argument("--p-h-gpa", type=float, required=True, help="maximum Hertz pressure [GPa]")
    solve.add_argument("--r-eq-mm", type=float, required=True, help="equivalent radius of curvature [mm]")
    solve.add_argument("--u-r", type=float, required=True, help="rolling (entrainment) velocity [m/s]")
    solve.add_argument("--sr", type=float, default=0.0, help="slide-to-roll ratio (u1 - u2)/u_r [-] (default 0)")
    solve.add_argument("--temp-c", type=float, default=90.0, help="oil inlet temperature [°C] (default 90)")
    solve.add_argument("--rq1-um", type=float, default=0.0, help="RMS roughness of surface 1 [µm] (default 0)")
    solve.add_argument("--rq2-um", type=float, default=0.0, help="RMS roughness of surface 2 [µm] (default 0)")
    shape = solve.add_mutually_exclusive_group()
    shape.add_argument("--roughness", default=None, metavar="NAME",
                       help="shipped roughness profile by its registered name, scaled to Rq1/Rq2: baseline_synthetic "
                            "(the default: Gaussian ACF, beta 15 um) or flank_ground (self-affine, ground-flank-like); "
                            "`gearloss roughness show NAME` describes one. The result records the profile's name and "
                            "sha256 (roughness_name, roughness_sha256)")
    shape.add_argument("--roughness-file", default=None, metavar="FILE",
                       help="measured roughness profile instead (two columns x, z; detrended, resampled, scaled to "
                            "Rq1/Rq2); the result records the file's name and sha256")
    solve.add_argument("--roughness-unit", default="um", choices=["um", "mm", "m"],
                       help="unit of both columns of --roughness-file (default um)")
    solve.add_argument("--lubricant", default="atf",
                       help="shipped lubricant name (atf, gear_oil_75w90, validation_barus, "
                            "validation_barus_incompressible, validation_roelands_huang) or a TOML file")
    solve.add_argument("--level", default=DEFAULT_LEVEL, choices=LEVELS, help="accuracy level")
    solve.add_argument("--effects", default="auto", choices=CONTACT_EFFECT_PLANS,
                       help="effect plan: auto (planner), isothermal (the planner's plan without the thermal "
                            "correction of the traction), full (everything), smooth (steady smooth solve, "
                            "isothermal)")
    solve.add_argument("--model", default="auto", choices=MODELS,
                       help="contact model: auto (the effect plan decides), smooth (steady smooth surfaces), "
                            "homogenised (steady two-scale mixed model; a prototype, see "
                            "docs/explanation/mixed-regime.md), deterministic (the deterministic mixed reference solver; "
                            "slow: minutes per case)")
    solve.add_argument("--closure", default=DEFAULT_CLOSURE, choices=CLOSURES,
                       help="closure of the homogenised model: the flow factors transverse (1-D roughness, no side "
                            "leakage, as the paper's model) or isotropic (side leakage), film_law (smooth "
                            "pressure, the measured film law of resolved rough contacts and the dry-contact table's "
                            "traction; for wide contacts, docs/explanation/mixed-regime.md), or asperity (film_law "
                            "plus the load and friction of the roughness that survives in the conjunction: the "
                            "planner's production closure); default transverse with --model homogenised; with "
                            "--model auto, film_law or asperity replaces the planner's asperity closure")
    solve.add_argument("--fluctuations", default=DEFAULT_FLUCTUATIONS, choices=FLUCTUATIONS,
                       help="micro-EHL pressure spread of the film_law and asperity closures: inlet (calibrated on "
                            "the baseline profile, c(L_in/beta)) or spectral (from the part of the profile's spectrum "
                            "the conjunction flattens; no fitted constant); default spectral")
    solve.add_argument("--dx-um", type=float, default=None,
                       help="grid spacing of the deterministic model [µm] (default: the level's grid rule)")
    solve.add_argument("--wide", default="auto", choices=["auto", "resolve", "windows"],
                       help="how the deterministic model covers the contact: auto (periodic windows across the "
                            "Hertzian zone fed by the film law when a/β > 15 and no --dx-um is given, else the whole "
                            "contact resolved), resolve, windows (docs/explanation/mixed-regime.md, \"Wide contacts\")")
    solve.add_argument("--time-limit-s", type=float, default=None,
                       help="wall-time budget of a deterministic (rough, transient) solve [s]; when spent the result is marked "
                            "not converged (default: none)")
    solve.add_argument("--json", action="store_true", help="print one JSON object (SI units)")
    solve.set_defaults(handler=_solve, leave_objects_at_exit=True)  # writes only its output


def _solve(args) -> int:
    """Resolve the command's inputs once (the case, range-checked; the lubricant, level, effect plan and route:
    :func:`~ehl_dataset.solvers.problem.resolve_contact`), solve, and print the result's schema
    (:meth:`~ehl_dataset.solvers.result.ContactResult.to_dict`) with the case's Hertzian quantities."""
    from ehl_dataset.model.contact import ContactCase
    from ehl_dataset.solver import solve_problem
    from ehl_dataset.solvers.problem import resolve_contact

    case = ContactCase.from_engineering(args.p_h_gpa, args.r_eq_mm, args.u_r, args.sr, args.temp_c,
                                        args.rq1_um, args.rq2_um)
    roughness, identity = _roughness(args)
    deterministic = None
    if args.dx_um is not None or args.wide != "auto":
        from ehl_dataset.solvers.deterministic import deterministic_options

        overrides = {"wide": args.wide}
        if args.dx_um is not None:
            overrides["dx_m"] = args.dx_um * 1e-6
        deterministic = deterministic_options(args.level, **overrides)
    homogenised = None  # the default closure: the homogenised model's default options (loaded only if it runs)
    if args.closure != DEFAULT_CLOSURE or args.fluctuations != DEFAULT_FLUCTUATIONS:
        from ehl_dataset.solvers.homogenised import HomogenisedOptions

        homogenised = HomogenisedOptions(closure=args.closure, fluctuations=args.fluctuations)
    problem = resolve_contact(case, args.lubricant, args.level, args.effects, roughness, args.time_limit_s,
                              args.model, deterministic, homogenised)
    result = solve_problem(problem)
    rough = case.s_c > 0.0  # smooth surfaces use no profile
    payload = {**result.to_dict(), "load_per_length_n_m": case.load_per_length, "half_width_m": case.half_width,
               "lubricant": problem.lubricant.name,
               "roughness_name": identity["name"] if rough else None,
               "roughness_sha256": identity["sha256"] if rough else None}
    from workflows.cli_output import emit

    emit(payload, args.json, _human)
    return 0 if result.converged else 1


def _roughness(args):
    """The profile the solve is given (None: the models' default) and its record ``{"name", "sha256"}``: a
    registered name (an unknown one is an error listing the registered names), a user's file, or the default."""
    from ehl_dataset.model.roughness_identity import roughness_identity

    if args.roughness_file is not None:
        from ehl_dataset.model.roughness import load_profile

        return (load_profile(args.roughness_file, unit=args.roughness_unit),
                roughness_identity(path=args.roughness_file))
    if args.roughness is None:
        return None, roughness_identity()
    from ehl_dataset.model.roughness import PROFILES, named_profile
    from ehl_dataset.validation import InputError

    if args.roughness not in PROFILES:
        raise InputError("roughness", args.roughness, f"a registered profile name, one of {sorted(PROFILES)} "
                         "(a measured profile: --roughness-file FILE)")
    profile = named_profile(args.roughness)
    return profile, roughness_identity(profile)


def _human(d: dict) -> str:
    lam = "inf (smooth)" if d["lambda_bar"] is None else f"{d['lambda_bar']:.3f}"
    status = "converged" if d["converged"] else f"NOT CONVERGED ({d['message']})"
    lines = [
        f"mu            {d['mu']:.5f}" + (f"  (standard error of the time average {d['mu_sem']:.5f}, "
                                              f"std over time {d['mu_std']:.5f})" if d["mu_std"] else ""),
        f"h_min         {d['h_min_m'] * 1e9:.2f} nm",
        f"h_central     {d['h_central_m'] * 1e9:.2f} nm",
        f"p_max         {d['p_max_pa'] / 1e9:.4f} GPa",
        f"lambda_bar    {lam}",
        f"status        {status} after {d['iterations']} iterations, {d['wall_time_s'] * 1e3:.1f} ms",
        f"level         {d['level']}; effects {', '.join(k for k in ('roughness', 'transient', 'shear_thinning', 'compressibility', 'thermal') if d['effects'].get(k))}",
        f"model         {d['model']}" + (f" ({d['closure']} closure)" if d.get("closure") else "")
        + (f", {d['route']} route" if d.get("route") else ""),
    ]
    if d.get("roughness_name"):
        lines.append(f"roughness     {d['roughness_name']} (sha256 {d['roughness_sha256'][:12]}...)")
    if d["effects"].get("roughness") and d.get("asperity_load_share") is not None:
        lines.append(f"asperities    {100 * d['asperity_load_share']:.1f} % of the load")
    if d["converged"] and d.get("message") and d["message"] != "converged":
        lines.append(f"note          {d['message'].removeprefix('converged; ')}")
    if d.get("thermal"):
        t = d["thermal"]
        lines.append(f"thermal       mu isothermal {t['mu_isothermal']:.5f}; max rise of the surfaces "
                     f"{t['max_surface_rise_k']:.1f} K, of the film centre above them {t['max_film_centre_rise_k']:.1f} K")
    return "\n".join(lines)
