"""``gearloss surrogate fit|predict|compare``: lubricant friction surrogates (stage 2,
docs/explanation/surrogate.md)."""

from __future__ import annotations

import sys


def register(subparsers) -> None:
    parser = subparsers.add_parser("surrogate", help="fit, evaluate and compare friction surrogates (paper Eq. 9)")
    sub = parser.add_subparsers(dest="surrogate_command", metavar="COMMAND")
    parser.set_defaults(handler=lambda args: parser.print_help() or 2)

    fit = sub.add_parser("fit", help="fit the two-branch ln mu regression to a dataset and write a coefficient file")
    fit.add_argument("dataset", help="HDF5 dataset (gearloss dataset run) or CSV table with the same columns")
    fit.add_argument("--out", required=True, help="coefficient file to write (NAME.json; NAME.summary.txt beside)")
    fit.add_argument("--lubricant", default=None, help="lubricant name or TOML file (CSV tables only)")
    fit.add_argument("--k-folds", type=int, default=5, help="cross-validation folds (default 5)")
    fit.add_argument("--seed", type=int, default=0, help="seed of the CV shuffle (default 0)")
    fit.add_argument("--blend", type=float, default=0.1,
                     help="half width of the lambda band where the branches are blended (0 = hard switch; 0.1)")
    fit.add_argument("--allow-unstable", action="store_true", help="write the file even if the fit is unstable")
    fit.add_argument("--figures", default=None, metavar="DIR", help="also write diagnostic figures into DIR")
    fit.add_argument("--form", choices=("eq9", "learned"), default="eq9",
                     help="eq9 (paper Eq. 9, statsmodels OLS, prediction intervals) or learned (ensemble of small "
                          "perceptrons, calibrated intervals); default eq9")
    fit.add_argument("--offgrid", default=None, metavar="DATASET",
                     help="solved off-grid sample (HDF5, e.g. DIR/offgrid.h5 of gearloss lubricant fit) whose errors "
                          "of mu and interval coverage the coefficient file records")
    fit.add_argument("--json", action="store_true", help="print one JSON object")
    fit.set_defaults(handler=_fit)

    pred = sub.add_parser("predict", help="friction coefficient of one contact from a coefficient file")
    pred.add_argument("coefficients", help="coefficient file (path or shipped name)")
    pred.add_argument("--p-h-gpa", type=float, required=True, help="maximum Hertz pressure [GPa]")
    pred.add_argument("--r-eq-mm", type=float, required=True, help="equivalent radius [mm]")
    pred.add_argument("--u-r", type=float, required=True, help="rolling velocity (u1 + u2)/2 [m/s]")
    pred.add_argument("--sr", type=float, required=True, help="slide-to-roll ratio [-]")
    pred.add_argument("--temp-c", type=float, required=True, help="oil inlet temperature [°C]")
    pred.add_argument("--rq1-um", type=float, required=True, help="RMS roughness of surface 1 [µm]")
    pred.add_argument("--rq2-um", type=float, required=True, help="RMS roughness of surface 2 [µm]")
    from .cli_validity import add_validity_options

    add_validity_options(pred)
    pred.add_argument("--coverage", type=float, default=0.9,
                      help="coverage of the printed prediction interval of mu (default 0.9)")
    pred.add_argument("--offgrid", action="store_true",
                      help="also print the off-grid validation the coefficient file records (always in --json)")
    pred.add_argument("--json", action="store_true", help="print one JSON object")
    pred.set_defaults(handler=_predict)

    cmp_ = sub.add_parser("compare", help="Eq. 9 vs scikit-learn vs published formulas: CV error and speed")
    cmp_.add_argument("dataset", help="HDF5 dataset or CSV table")
    cmp_.add_argument("--lubricant", default=None, help="lubricant name or TOML file (CSV tables only)")
    cmp_.add_argument("--k-folds", type=int, default=5, help="cross-validation folds (default 5)")
    cmp_.add_argument("--seed", type=int, default=0, help="seed of the CV shuffle (default 0)")
    cmp_.add_argument("--blend", type=float, default=0.1, help="blend half width for Eq. 9 (default 0.1)")
    cmp_.add_argument("--json", action="store_true", help="print one JSON object")
    cmp_.set_defaults(handler=_compare)


def _check_folds(k: int) -> None:
    from ehl_dataset.validation import InputError

    if k < 2:
        raise InputError("k_folds", k, "an integer >= 2")


def _fit(args) -> int:
    import warnings

    from surrogate.coefficients import summary_path, write_coefficients
    from surrogate.dataset_io import load_dataset
    from surrogate.fit import fit_surrogate
    from workflows.cli_output import emit

    from workflows.surrogate_stage import validate_offgrid

    _check_folds(args.k_folds)
    data = load_dataset(args.dataset, args.lubricant)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        if args.form == "learned":
            from surrogate.learned_fit import fit_learned

            fit = fit_learned(data.table, data.lubricant, data.e_reduced, members=args.k_folds, seed=args.seed)
        else:
            fit = fit_surrogate(data.table, data.lubricant, data.e_reduced, k_folds=args.k_folds, seed=args.seed,
                                blend_half_width=args.blend, allow_unstable=args.allow_unstable)
    path = write_coefficients(fit, args.out, source=data.source, roughness=data.roughness)
    offgrid = validate_offgrid(path, args.offgrid) if args.offgrid else None
    if args.form == "learned":
        return _fit_learned_output(args, fit, path, offgrid, caught)
    figures = []
    if args.figures:
        from surrogate.diagnostics import plot_figures

        figures = [str(p) for p in plot_figures(fit, args.figures, title=data.source["path"])]  # the dataset's file name
    notes = [str(w.message) for w in caught]
    for note in notes:
        print(f"gearloss: warning: {note}", file=sys.stderr)
    payload = {
        "coefficients_path": str(path),
        "summary_path": str(summary_path(path)),
        "n_input_rows": fit.n_input_rows,
        "n_used": fit.n_used,
        "exclusions": fit.exclusions,
        "stable": fit.stable,
        "branches": {b: {"n_obs": f.n_obs, "adj_r2": f.adj_r2, "resid_std_error": f.resid_std_error,
                         "condition_number_standardized": f.condition_number_standardized,
                         "max_vif": max(f.vif.values()) if f.vif else None, "messages": f.messages}
                     for b, f in fit.branches.items()},
        "cv_rmse_ln_mu": fit.cv["overall"]["rmse_ln_mu"],
        "cv_mean_rel_err_mu": fit.cv["overall"]["mean_rel_err_mu"],
        "jump_at_lambda_1": fit.jump,
        "accuracy_level": data.source.get("accuracy_level"),
        "figures": figures,
        "warnings": notes,
        "wall_time_s": fit.fit_time_s,
        "offgrid": offgrid,
    }
    emit(payload, args.json, _fit_text)
    return 0


def _fit_learned_output(args, fit, path, offgrid, caught) -> int:
    from surrogate.coefficients import summary_path
    from surrogate.offgrid import offgrid_lines
    from workflows.cli_output import emit

    notes = [str(w.message) for w in caught]
    for note in notes:
        print(f"gearloss: warning: {note}", file=sys.stderr)
    payload = {"coefficients_path": str(path), "summary_path": str(summary_path(path)), "form": "learned",
               "n_input_rows": fit.n_input_rows, "n_used": fit.n_used, "exclusions": fit.exclusions,
               "members": fit.ensemble.members, "cross_validation": fit.cv,
               "interval_score_quantiles": {f"{c:g}": q for c, q in fit.ensemble.score_quantiles.items()},
               "offgrid": offgrid, "warnings": notes, "wall_time_s": fit.fit_time_s}

    def text(p):
        cv = p["cross_validation"]["overall"]
        return "\n".join([f"wrote {p['coefficients_path']} (+ {p['summary_path']})",
                          f"learned ensemble of {p['members']} perceptrons on {p['n_used']} rows: out-of-fold RMSE "
                          f"ln mu = {cv['rmse_ln_mu']:.4f}, median |rel err mu| = {cv['median_rel_err_mu']:.2%}"]
                         + (offgrid_lines(p["offgrid"]) if p["offgrid"] else []))

    emit(payload, args.json, text)
    return 0


def _fit_text(p) -> str:
    lines = [f"wrote {p['coefficients_path']} (+ {p['summary_path']})",
             f"rows: {p['n_input_rows']} in, {p['n_used']} used; excluded "
             + ", ".join(f"{k} {v}" for k, v in p["exclusions"].items() if v)]
    for branch, b in p["branches"].items():
        lines.append(f"{branch:9s}: n = {b['n_obs']}, adjusted R² = {b['adj_r2']:.4f} (paper: ≈ 0.92), "
                     f"residual SE ln mu = {b['resid_std_error']:.4f}, cond(standardised) = "
                     f"{b['condition_number_standardized']:.3g}, max VIF = {b['max_vif']:.3g}")
    lines.append(f"CV: RMSE ln mu = {p['cv_rmse_ln_mu']:.4f}, mean |rel err mu| = {p['cv_mean_rel_err_mu']:.2%}")
    jump = p["jump_at_lambda_1"]
    if jump.get("n"):
        lines.append(f"jump of the unblended branches at lambda = 1: median |d ln mu| = "
                     f"{jump['median_abs_delta_ln_mu']:.3f}, p95 = {jump['p95_abs_delta_ln_mu']:.3f}")
    lines.append(f"stable: {p['stable']}")
    if p.get("offgrid"):
        from surrogate.offgrid import offgrid_lines

        lines.extend(offgrid_lines(p["offgrid"]))
    lines.extend(f"figure: {f}" for f in p["figures"])
    return "\n".join(lines)


def _predict(args) -> int:
    import time
    import warnings

    import numpy as np

    from ehl_dataset.model.contact import ContactCase
    from ehl_dataset.validation import InputError, check_range
    from surrogate.evaluate import FrictionSurrogate
    from surrogate.validity import clipping_note, judge

    from .cli_validity import finish

    start = time.perf_counter()
    # the contact's inputs checked once, against the contact's table of limits; Eq. 9 needs rough surfaces
    case = ContactCase.from_engineering(args.p_h_gpa, args.r_eq_mm, args.u_r, args.sr, args.temp_c, args.rq1_um,
                                        args.rq2_um)
    for option, rq in (("rq1_um", case.rq1), ("rq2_um", case.rq2)):
        if rq == 0.0:
            raise InputError(option, getattr(args, option), "(0, 100] um: the surrogate is fitted to rough surfaces")
    surrogate = FrictionSurrogate.load(args.coefficients, clip_to_fitted_ranges=not args.no_clip)
    inputs = (case.p_h, case.r_eq, case.u_r, case.sr, case.temperature, case.rq1, case.rq2)
    check_range("coverage", args.coverage, 0.0, 1.0, low_inclusive=False, high_inclusive=False)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        feats = surrogate.features(*inputs, warn=False)
        mu_arr, low_arr, high_arr = surrogate.mu_interval(*inputs, alpha=1.0 - args.coverage, warn=False)
        mu = float(np.ravel(mu_arr)[0])
    notes = [str(w.message) for w in caught]
    # the policy of gear evaluate (surrogate.validity): inputs clipped to the fitted ranges, counted per input
    arrays = surrogate.validate(*inputs)
    _, outside = surrogate.clip(arrays)
    check = judge(1.0 if any(outside.values()) else 0.0, outside, 1, clip=not args.no_clip)
    doc = surrogate.coefficients.document
    lam = float(np.ravel(feats["lam"])[0])
    payload = {
        "mu": mu,
        "lambda_bar": lam,
        "branch": "mixed" if lam <= surrogate.formula.lambda_threshold else "full_film",
        "h_min_dh_m": float(np.ravel(feats["h_min_dh"])[0]),
        "clipped_inputs": outside if not args.no_clip else {k: 0 for k in outside},
        "extrapolated_inputs": outside if args.no_clip else {k: 0 for k in outside},
        "note": clipping_note(outside, 1, clipped=not args.no_clip) if any(outside.values()) else "",
        "warnings": notes,
        "mu_low": None if low_arr is None else float(np.ravel(low_arr)[0]),
        "mu_high": None if high_arr is None else float(np.ravel(high_arr)[0]),
        "interval_coverage": args.coverage if low_arr is not None else None,
        "interval_note": "" if low_arr is not None else ("no prediction interval: the coefficient file (format 1) "
                                                         "records no coefficient covariance; refit to get one"),
        "form": surrogate.form,
        "offgrid": surrogate.offgrid,
        "formula": doc["formula"]["name"],
        "lubricant": surrogate.lubricant.name,
        "roughness": surrogate.coefficients.roughness,
        "coefficients": surrogate.coefficients.path,
        "wall_time_s": time.perf_counter() - start,
    }
    options = {"p_h": "p-h-gpa", "r_eq": "r-eq-mm", "u_r": "u-r", "sr": "sr", "temperature": "temp-c",
               "rq1": "rq1-um", "rq2": "rq2-um"}
    first = next((k for k, v in outside.items() if v), None)
    return finish(payload, [check], args, lambda p: _predict_text(p, args.offgrid),
                  options={"friction_surrogate_range": options.get(first, "p-h-gpa")})


def _predict_text(p, show_offgrid: bool = False) -> str:
    text = (f"mu = {p['mu']:.5f}  (lambda_bar = {p['lambda_bar']:.3f}, branch {p['branch']}, {p['formula']}, "
            f"lubricant {p['lubricant']})")
    if p.get("mu_low") is not None:
        text += f"\n{p['interval_coverage']:.0%} prediction interval of mu: [{p['mu_low']:.5f}, {p['mu_high']:.5f}]"
    elif p.get("interval_note"):
        text += f"\n{p['interval_note']}"
    if show_offgrid:
        from surrogate.offgrid import offgrid_lines

        text += "\n" + "\n".join(offgrid_lines(p.get("offgrid")))
    return text


def _compare(args) -> int:
    import time
    import warnings

    from surrogate.compare import compare_models, format_table
    from surrogate.dataset_io import load_dataset
    from workflows.cli_output import emit

    _check_folds(args.k_folds)
    start = time.perf_counter()
    data = load_dataset(args.dataset, args.lubricant)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = compare_models(data.table, data.lubricant, data.e_reduced, k_folds=args.k_folds, seed=args.seed,
                                blend_half_width=args.blend)
    result["dataset"] = data.source
    result["wall_time_s"] = time.perf_counter() - start
    emit(result, args.json, format_table)
    return 0
