"""Human-readable lines of stage 2 in either form (``gearloss lubricant fit``, ``gearloss pipeline``): the fit, the
off-grid validation and the adaptive design, and the options that choose them."""

from __future__ import annotations

OFFGRID_HELP = ("seeded random contacts inside the factorial's ranges, solved by the same route, on which the fit's "
                "error of mu (median, 90th percentile, max per branch) and interval coverage are measured and "
                "recorded in the coefficient file (default 200; 0: none; else at least 35 with eq9, 17 with "
                "learned: its even rows calibrate the interval)")
FORM_HELP = ("form of the friction surrogate: eq9 (paper Eq. 9, statsmodels OLS, with prediction intervals) or "
             "learned (ensemble of small perceptrons with calibrated intervals, JSON weights); default eq9 (learned with "
             "--adaptive)")


def add_form_options(parser, *, adaptive: bool = False) -> None:
    """``--form``, ``--offgrid-points`` (and, for ``lubricant fit``, ``--adaptive``, ``--budget``, ``--initial``,
    ``--batch``, ``--target-median``, ``--target-p90``) on ``parser``."""
    from .offgrid_defaults import OFFGRID_POINTS

    parser.add_argument("--form", choices=("eq9", "learned"), default=None, help=FORM_HELP)
    parser.add_argument("--offgrid-points", type=int, default=OFFGRID_POINTS, metavar="N", help=OFFGRID_HELP)
    if adaptive:
        parser.add_argument("--adaptive", action="store_true",
                            help="train on an adaptive design instead of the factorial: a Sobol' start in the "
                                 "factorial's ranges, then batches where the learned ensemble disagrees most "
                                 "(resumable, DIR/adaptive/batch_NNN.h5); implies --form learned unless given")
        parser.add_argument("--budget", type=int, default=None, metavar="N",
                            help="largest number of adaptive training solves (default: a tenth of the factorial's "
                                 "points, at least 128)")
        parser.add_argument("--initial", type=int, default=None, metavar="N",
                            help="points of the adaptive design's Sobol' start (default 128; in a box the size of "
                                 "the paper factorial's, 1,024 met the off-grid error of the whole grid on their own: "
                                 "docs/validation/surrogate-off-grid.md)")
        parser.add_argument("--batch", type=int, default=None, metavar="N",
                            help="points per adaptive batch after the start (default 64)")
        parser.add_argument("--target-median", type=float, default=None, metavar="FRACTION",
                            help="stop the adaptive design once the off-grid median |rel err mu| is at most this")
        parser.add_argument("--target-p90", type=float, default=None, metavar="FRACTION",
                            help="stop the adaptive design once the off-grid 90th percentile |rel err mu| is at "
                                 "most this")


def fit_line(fit: dict) -> str:
    """The ``stage 2 fit`` line of either form."""
    if fit.get("form") == "learned":
        text = (f"stage 2 fit       {fit['artefact']}: learned ensemble of {fit['members']} perceptrons on "
                f"{fit['n_used']} rows; out-of-fold RMSE ln μ {fit['cv_rmse_ln_mu']:.3f}, median |rel err μ| "
                f"{fit['cv_median_rel_err_mu']:.1%}")
    else:
        branches = ", ".join(f"{b}: n={v['n_obs']}, adj R² {v['adj_r2']:.3f}" for b, v in fit["branches"].items())
        text = (f"stage 2 fit       {fit['artefact']}: {fit['n_used']} rows used ({branches}); CV RMSE ln μ "
                f"{fit['cv_rmse_ln_mu']:.3f}; stable {fit['stable']}")
    return text + f" — {fit['wall_time_s']:.1f} s"


def stage2_lines(stages: dict) -> list[str]:
    """Lines of the adaptive design, the off-grid sample and the fit's off-grid errors (after :func:`fit_line`)."""
    from surrogate.offgrid import offgrid_lines

    lines = []
    adaptive = stages.get("adaptive")
    if adaptive:
        lines.append(f"adaptive design   {adaptive['artefact']}: {adaptive['solves']} solves in "
                     f"{len(adaptive['rounds'])} rounds, stopped: {adaptive['stopped']} — "
                     f"{adaptive['wall_time_s']:.1f} s")
    offgrid = stages.get("offgrid")
    if offgrid:
        lines.append(f"off-grid sample   {offgrid['artefact']}: {offgrid['n_points']} points (seed {offgrid['seed']}),"
                     f" {offgrid['computed']} computed; ok {offgrid['ok']}, failed {offgrid['failed']} — "
                     f"{offgrid['wall_time_s']:.1f} s")
        lines += ["  " + line for line in offgrid_lines(stages.get("fit", {}).get("offgrid"))]
    return lines


def form_arguments(args, factorial_points: int) -> dict:
    """The keyword arguments of :func:`workflows.pipeline.run_lubricant_fit` from the options of
    :func:`add_form_options` (checked: :class:`~ehl_dataset.validation.InputError` names the option)."""
    from ehl_dataset.validation import check_range

    from .surrogate_stage import check_offgrid_points

    adaptive = bool(getattr(args, "adaptive", False))
    form = args.form or ("learned" if adaptive else "eq9")
    out = {"form": form, "offgrid_points": check_offgrid_points(args.offgrid_points, form, "--offgrid-points")}
    if adaptive:
        budget = args.budget if args.budget is not None else max(128, factorial_points // 10)
        out.update(adaptive_budget=int(check_range("budget", budget, 20, 10**7)),
                   target_median=args.target_median, target_p90=args.target_p90)
        for option in ("initial", "batch"):
            if getattr(args, option, None) is not None:
                out[f"adaptive_{option}"] = int(check_range(option, getattr(args, option), 20 if option == "initial"
                                                            else 1, 10**7))
    else:
        for option in ("budget", "initial", "batch", "target_median", "target_p90"):
            if getattr(args, option, None) is not None:
                from ehl_dataset.validation import InputError

                raise InputError(option, getattr(args, option), "only with --adaptive")
    return out


BAND_COMBINATION = ("every contact point at the same end of its mu interval: errors fully correlated across the "
                    "mesh, conservative for a fit's systematic error")


def band_entries(loss, friction) -> dict:
    """The band of P and η of a power-loss result (:mod:`efficiency.power_loss`), the friction model's off-grid
    validation and, for a coefficient file, the roughness profile of its dataset (``friction_roughness``:
    ``{"name", "sha256"}``, null where the file records none), as the JSON entries of ``gear evaluate`` (SI; the
    band absent when the model has no interval)."""
    out = {}
    if loss.power_loss_band is not None:
        out.update(power_loss_band_w=list(loss.power_loss_band), efficiency_band=list(loss.efficiency_band),
                   band_coverage=loss.band_coverage, band_combination=BAND_COMBINATION)
    elif hasattr(friction, "has_interval"):
        out["band_note"] = "no band: the coefficient file records no prediction interval (format 1); refit it"
    offgrid = getattr(friction, "offgrid", None)
    if offgrid:
        out["friction_offgrid"] = offgrid
    coefficients = getattr(friction, "coefficients", None)
    if coefficients is not None and hasattr(coefficients, "roughness"):  # a coefficient file: null = not recorded
        out["friction_roughness"] = coefficients.roughness
    return out


def band_lines(p: dict) -> list[str]:
    """Human lines of :func:`band_entries`."""
    lines = []
    if "power_loss_band_w" in p:
        low, high = p["power_loss_band_w"]
        eta_low, eta_high = p["efficiency_band"]
        lines.append(f"{p['band_coverage']:.0%} band from the surrogate's μ intervals: P {low / 1e3:.4g} to "
                     f"{high / 1e3:.4g} kW, η {eta_low * 100:.3f} to {eta_high * 100:.3f} % ({p['band_combination']})")
    elif p.get("band_note"):
        lines.append(p["band_note"])
    overall = (p.get("friction_offgrid") or {}).get("overall")
    if overall and overall.get("n"):
        cov = overall.get("coverage")
        lines.append(f"surrogate off-grid error of μ ({overall['n']} random contacts in its ranges): median "
                     f"{overall['median_rel_err_mu']:.1%}, 90th percentile {overall['p90_rel_err_mu']:.1%}, max "
                     f"{overall['max_rel_err_mu']:.1%}" + (f"; 90% interval covers {cov:.1%}" if cov is not None
                                                            else ""))
    return lines
