"""Off-grid validation of a friction surrogate: its error of μ on contacts solved off the training design.

A factorial is a grid; gear contacts are not. The honest error of a fit is measured on a seeded random sample of
contacts inside the factorial's ranges (:mod:`surrogate.sampling`), solved by the route of the dataset (same solver,
level, effect plan, contact model and lubricant). For every usable row (status ``ok``, converged, μ > 0, rough
surfaces, SR ≠ 0 — the exclusions of the fit, :func:`surrogate.fit.prepare_table`) the relative error
|μ_surrogate/μ_solved − 1| is summarised per branch (λ̄ ≤ 1 ``mixed``, λ̄ > 1 ``full_film``, by the λ̄ of the
contact) and overall: median, 90th percentile, maximum; and the share of solved μ inside the surrogate's 90 %
prediction interval (its coverage; None when the file has no interval).

The sample also calibrates the intervals: its even rows set the learned form's conformal quantiles and an Eq. 9
file's split-conformal factors (:func:`eq9_interval_calibration`, :mod:`surrogate.intervals`); the coverage is then
counted on the odd rows only.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
import pandas as pd

from .fit import INPUT_COLUMNS, branch_masks, prepare_table

COVERAGE = 0.90
"""Nominal coverage of the intervals whose share of the off-grid μ is reported."""


def error_summary(rel_err: np.ndarray, inside: np.ndarray | None) -> dict[str, Any]:
    """Median, 90th percentile and maximum of the relative errors, and the share inside the interval.

    Parameters
    ----------
    rel_err : numpy.ndarray
        |μ_surrogate/μ_solved − 1| per contact [-].
    inside : numpy.ndarray or None
        Whether each solved μ lies inside the interval (None: no interval) [-].

    Returns
    -------
    dict
        ``n``, ``median_rel_err_mu``, ``p90_rel_err_mu``, ``max_rel_err_mu``, ``coverage`` [-].
    """
    rel_err = np.asarray(rel_err, dtype=float)
    if rel_err.size == 0:
        return {"n": 0}
    return {"n": int(rel_err.size), "median_rel_err_mu": float(np.median(rel_err)),
            "p90_rel_err_mu": float(np.percentile(rel_err, 90)), "max_rel_err_mu": float(np.max(rel_err)),
            "coverage": None if inside is None else float(np.mean(inside))}


def calibration_rows(n: int) -> np.ndarray:
    """The rows of an off-grid sample that calibrate a learned interval: the even positions (the odd ones measure
    its coverage). The sample is an independent uniform draw, so both halves are alike.

    Parameters
    ----------
    n : int
        Rows of the sample [-].

    Returns
    -------
    numpy.ndarray
        Boolean mask [-].
    """
    return np.arange(n) % 2 == 0


def eq9_interval_calibration(surrogate, table: pd.DataFrame) -> tuple[dict[str, Any], np.ndarray]:
    """Split-conformal factors of an Eq. 9 file's interval from the even rows of a solved off-grid sample.

    Parameters
    ----------
    surrogate : FrictionSurrogate
        An Eq. 9 surrogate with covariances (format 2) [-].
    table : pandas.DataFrame
        The solved off-grid sample (columns of the dataset store) [SI].

    Returns
    -------
    tuple
        (the ``interval_calibration`` table of the file, boolean mask over the rows of ``table`` left to measure
        the coverage: the odd ones).

    Raises
    ------
    InputError
        For a surrogate without covariances, or too few usable even rows on a branch.
    """
    from ehl_dataset.validation import InputError

    from .intervals import CALIBRATION_METHOD, calibrate_scores, prediction_se

    c = surrogate.coefficients
    if c.form != "eq9" or c.covariance is None:
        raise InputError("coefficient file", c.path or "<dict>", "an Eq. 9 file of format 2 (with covariances)")
    calibrate = calibration_rows(len(table))
    prepared = prepare_table(table, surrogate.lubricant, surrogate.e_reduced)
    rows = calibrate[prepared.kept_rows]
    used = prepared.table[rows]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ln_mu = np.log(surrogate.mu(*[used[col].to_numpy(dtype=float) for col in INPUT_COLUMNS], warn=False))
    features = {k: v[rows] for k, v in prepared.features.items()}
    se = prediction_se(c.formula, c.covariance, c.resid_variance, features, c.blend_half_width)
    quantiles = calibrate_scores(prepared.ln_mu[rows] - ln_mu, se, features["lam"], c.formula.lambda_threshold)
    lam = features["lam"]
    table_out = {"method": CALIBRATION_METHOD,
                 "rows": "the even rows of the off-grid sample (the odd rows measure the coverage)",
                 "calibration_rows": {"mixed": int(np.sum(lam <= c.formula.lambda_threshold)),
                                      "full_film": int(np.sum(lam > c.formula.lambda_threshold))},
                 "score_quantiles": {b: {f"{cov:g}": q for cov, q in sorted(qs.items())} for b, qs in quantiles.items()},
                 "t_quantile_90": {b: t_quantile_90(c.df_resid[b]) for b in quantiles}}
    return table_out, ~calibrate


def t_quantile_90(df_resid: float) -> float:
    """Student's t_{0.95, ν}: the factor of the plain statsmodels 90 % interval, stored beside the calibrated one.

    Parameters
    ----------
    df_resid : float
        Residual degrees of freedom [-].

    Returns
    -------
    float
        The quantile [-].
    """
    from .intervals import t_quantile

    return t_quantile(1.0 - COVERAGE, df_resid)


def offgrid_errors(surrogate, table: pd.DataFrame, *, coverage: float = COVERAGE,
                   coverage_rows: np.ndarray | None = None) -> dict[str, Any]:
    """Errors of ``surrogate`` on the solved rows of ``table`` (module docstring).

    Parameters
    ----------
    surrogate : FrictionSurrogate
        The surrogate to judge (evaluated on the raw inputs; the sample lies inside the factorial's ranges) [-].
    table : pandas.DataFrame
        Solved sample (columns of the dataset store) [SI].
    coverage : float
        Nominal coverage of the interval [-].
    coverage_rows : numpy.ndarray, optional
        Boolean mask over the rows of ``table``: the coverage counts only these (the rows not used to calibrate
        the interval); None: all [-].

    Returns
    -------
    dict
        ``overall``, ``mixed``, ``full_film`` (:func:`error_summary`; errors over all usable rows, coverage over the
        usable ``coverage_rows``), ``exclusions``, ``n_rows``, ``coverage_nominal``, ``coverage_rows`` and
        ``per_point`` (arrays: λ̄, solved and predicted μ, interval bounds) for figures.
    """
    prepared = prepare_table(table, surrogate.lubricant, surrogate.e_reduced)
    used = prepared.table
    inputs = [used[c].to_numpy(dtype=float) for c in INPUT_COLUMNS]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mu, low, high = surrogate.mu_interval(*inputs, alpha=1.0 - coverage, warn=False)
    solved = used["mu"].to_numpy(dtype=float)
    rel = np.abs(mu / solved - 1.0)
    inside = None if low is None else (solved >= low) & (solved <= high)
    counted = (np.ones(len(used), dtype=bool) if coverage_rows is None
               else np.asarray(coverage_rows, dtype=bool)[prepared.kept_rows])
    out: dict[str, Any] = {"n_rows": int(len(table)), "exclusions": prepared.exclusions,
                           "coverage_nominal": coverage,
                           "interval_method": surrogate.coefficients.interval_method,
                           "coverage_rows": "all" if coverage_rows is None else
                           "the odd rows of the sample, not used to calibrate the interval",
                           "overall": _summary(rel, inside, counted)}
    for branch, mask in branch_masks(prepared.features["lam"], 1.0).items():
        out[branch] = _summary(rel[mask], None if inside is None else inside[mask], counted[mask])
    out["per_point"] = {"lambda_bar": prepared.features["lam"], "mu_solved": solved, "mu_predicted": mu,
                        "mu_low": low, "mu_high": high}
    return out


def _summary(rel, inside, counted) -> dict[str, Any]:
    out = error_summary(rel, None if inside is None else inside[counted])
    if inside is not None and out.get("n"):
        out["n_coverage"] = int(counted.sum())
    return out


def offgrid_report(errors: dict[str, Any], sample: dict[str, Any]) -> dict[str, Any]:
    """The ``offgrid`` table of a coefficient file: the errors without the per-point arrays, and the sample.

    Parameters
    ----------
    errors : dict
        Result of :func:`offgrid_errors` [-].
    sample : dict
        Description of the sample (name, kind, seed, n_points, route, solver version, dataset sha256) [-].

    Returns
    -------
    dict
        JSON-ready table.
    """
    return {k: v for k, v in errors.items() if k != "per_point"} | {"sample": sample}


def offgrid_lines(offgrid: dict[str, Any] | None) -> list[str]:
    """Human-readable lines of a file's off-grid validation (``surrogate predict``, ``gear evaluate``).

    Parameters
    ----------
    offgrid : dict, optional
        The ``offgrid`` table of a coefficient file; None: none recorded [-].

    Returns
    -------
    list of str
        The lines.
    """
    if not offgrid:
        return ["off-grid validation: none recorded in the coefficient file"]
    sample = offgrid.get("sample", {})
    lines = [f"off-grid validation on {sample.get('n_points', '?')} random contacts in the fitted ranges "
             f"(seed {sample.get('seed', '?')}, level {sample.get('level', '?')}):"]
    if offgrid.get("interval_method"):
        counted = "" if offgrid.get("coverage_rows", "all") == "all" else f", coverage on {offgrid['coverage_rows']}"
        lines.append(f"  interval: {offgrid['interval_method']}{counted}")
    if offgrid.get("interval_calibration"):  # a sample with too few usable rows on a branch to calibrate
        lines.append(f"  interval {offgrid['interval_calibration']}")
    for key in ("overall", "mixed", "full_film"):
        m = offgrid.get(key) or {}
        if not m.get("n"):
            continue
        cov = m.get("coverage")
        lines.append(f"  {key:9s} n = {m['n']:4d}: |rel err mu| median {m['median_rel_err_mu']:.1%}, 90th percentile "
                     f"{m['p90_rel_err_mu']:.1%}, max {m['max_rel_err_mu']:.1%}; "
                     + (f"{offgrid.get('coverage_nominal', COVERAGE):.0%} interval covers {cov:.1%}"
                        if cov is not None else "no interval"))
    return lines
