"""Fitting the learned form of a coefficient file (``form = "learned"``): the rows of a dataset prepared exactly as
for Eq. 9 (:func:`surrogate.fit.prepare_table`: same exclusions, same features, same fitted ranges and SR floor),
then the ensemble of :mod:`surrogate.mlp`. The result records what a coefficient file of either form records
(input ranges, exclusions, cross-validated errors), so stage 3 can swap one file for the other.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pandas as pd

from .fit import PreparedTable, RANGE_KEYS, branch_masks, error_metrics, prepare_table
from .mlp import MlpFitResult, fit_mlp_ensemble

LEARNED_FORMULA_NAME = "mlp_ensemble"
LEARNED_FORMULA_VERSION = 1
LAMBDA_THRESHOLD = 1.0
"""λ̄ at which reports split errors into the ``mixed`` and ``full_film`` branches (the learned model has none)."""


@dataclass
class LearnedFit:
    """Result of :func:`fit_learned`: the ensemble and everything its coefficient file records.

    Parameters
    ----------
    result : MlpFitResult
        The ensemble, its out-of-fold predictions and the fit's statistics [-].
    exclusions : dict of str to int
        Rows excluded from the fit, per reason [-].
    n_input_rows : int
        Rows of the input table [-].
    n_used : int
        Rows used by the fit [-].
    input_ranges : dict of str to list
        Fitted (low, high) of each input, keyed with the unit in the name [-].
    sr_floor : float
        Smallest |SR| of the fitted rows [-].
    cv : dict
        Out-of-fold errors, overall and per λ̄ branch (:func:`surrogate.fit.error_metrics`) [-].
    e_reduced : float
        Reduced modulus E' of the dataset [Pa].
    lubricant : dict
        The lubricant's definition (provenance) [-].
    fit_time_s : float
        Wall time of the fit [s].
    prepared : PreparedTable, optional
        The prepared table the fit used [-].
    """

    result: MlpFitResult
    exclusions: dict[str, int]
    n_input_rows: int
    n_used: int
    input_ranges: dict[str, list[float]]
    sr_floor: float
    cv: dict[str, Any]
    e_reduced: float
    lubricant: dict[str, Any]
    fit_time_s: float
    prepared: PreparedTable | None = field(default=None, repr=False)

    @property
    def ensemble(self):
        return self.result.ensemble


def fitted_ranges(prepared: PreparedTable) -> dict[str, list[float]]:
    """``input_ranges`` of a coefficient file: the range of each input over the rows used (|SR| for SR, λ̄).

    Parameters
    ----------
    prepared : PreparedTable
        The rows used by a fit [-].

    Returns
    -------
    dict of str to list
        (min, max) per input, keyed with the unit in the name (``p_h_pa``, ...).
    """
    used = prepared.table
    ranges = {}
    for column, key in RANGE_KEYS.items():
        values = (np.abs(used["sr"].to_numpy(dtype=float)) if column == "sr_abs"
                  else prepared.features["lam"] if column == "lam" else used[column].to_numpy(dtype=float))
        ranges[key] = [float(np.min(values)), float(np.max(values))]
    return ranges


def fit_learned(table: pd.DataFrame, lubricant, e_reduced: float, *, members: int = 5,
                hidden: tuple[int, ...] = (16, 16), l2: float = 1e-3, seed: int = 0,
                calibration: np.ndarray | None = None) -> LearnedFit:
    """Fit the learned surrogate on a dataset table (columns of the HDF5 store, SI units).

    Parameters
    ----------
    table : pandas.DataFrame
        Dataset rows (inputs, ``mu``, ``status``, ``converged``) [SI].
    lubricant : Lubricant
        The lubricant the dataset was computed with [-].
    e_reduced : float
        Reduced modulus E' [Pa].
    members : int
        Ensemble members = cross-validation folds [-].
    hidden : tuple of int
        Hidden layer widths [-].
    l2 : float
        L2 penalty on standardised data [-].
    seed : int
        Seed [-].
    calibration : numpy.ndarray, optional
        Boolean mask over the rows of ``table``: the rows whose out-of-fold scores set the interval (default: every
        usable row; :func:`surrogate.mlp.fit_mlp_ensemble`) [-].

    Returns
    -------
    LearnedFit
        The fit, with its out-of-fold errors (``cv``: overall and per λ̄ branch, :func:`surrogate.fit.error_metrics`).
    """
    started = time.perf_counter()
    prepared = prepare_table(table, lubricant, e_reduced)
    mask = None
    if calibration is not None:
        kept = prepared.kept_rows if prepared.kept_rows is not None else np.arange(len(table))
        mask = np.asarray(calibration, dtype=bool)[kept]
    result = fit_mlp_ensemble(prepared.features, prepared.ln_mu, members=members, hidden=hidden, l2=l2, seed=seed,
                              calibration=mask)
    cv: dict[str, Any] = {"k": members, "seed": seed, "method": "out-of-fold predictions of the ensemble members",
                          "overall": error_metrics(prepared.ln_mu, result.oof_ln_mu)}
    for branch, mask in branch_masks(prepared.features["lam"], LAMBDA_THRESHOLD).items():
        cv[branch] = (error_metrics(prepared.ln_mu[mask], result.oof_ln_mu[mask]) if mask.any() else {"n": 0})
    ranges = fitted_ranges(prepared)
    return LearnedFit(result=result, exclusions=prepared.exclusions, n_input_rows=prepared.n_input_rows,
                      n_used=int(prepared.ln_mu.size), input_ranges=ranges, sr_floor=ranges["sr_abs"][0], cv=cv,
                      e_reduced=float(e_reduced), lubricant=lubricant.to_json_dict(),
                      fit_time_s=time.perf_counter() - started, prepared=prepared)


def learned_summary_text(fit: LearnedFit) -> str:
    """A plain-text summary of a learned fit (written beside its coefficient file).

    Parameters
    ----------
    fit : LearnedFit
        The fit [-].

    Returns
    -------
    str
        The summary.
    """
    s = fit.result.settings
    lines = [f"learned friction surrogate: ensemble of {s['members']} ReLU perceptrons {tuple(s['hidden'])}, "
             f"L-BFGS, L2 {s['l2']:g}, seed {s['seed']}",
             f"rows: {fit.n_input_rows} in, {fit.n_used} used; excluded "
             + (", ".join(f"{k} {v}" for k, v in fit.exclusions.items() if v) or "none")]
    for key in ("overall", "mixed", "full_film"):
        m = fit.cv.get(key, {})
        if m.get("n"):
            lines.append(f"out-of-fold {key:9s}: n = {m['n']}, RMSE ln mu = {m['rmse_ln_mu']:.4f}, median |rel err mu| "
                         f"= {m['median_rel_err_mu']:.2%}, 95th percentile {m['p95_rel_err_mu']:.2%}")
    q = fit.ensemble.score_quantiles
    lines.append(f"interval: ln mu +- q (s + s0), s0 = {fit.ensemble.s0:.4g}; q(90 %) = {q.get(0.9, float('nan')):.3f}")
    return "\n".join(lines)
