"""Alternative friction models on the same data: cross-validated error and evaluation speed in one table.

Models: the paper's two-branch Eq. 9 (``li_kahraman_2009_eq9``, with the coefficient file's blend, and
``li_kahraman_2009_eq9_hard_switch``, the paper's switch at λ̄ = 1 without blend), the
gradient-boosted trees of :mod:`surrogate.learned` (``hist_gradient_boosting``), and the published formulas of
:mod:`surrogate.published` (not fitted: their "CV" error is simply their error on every usable row).
Both fitted models use the same shuffled k folds. Evaluation rate: points per second of a vectorised evaluation
from the raw SI inputs (features included) on all usable rows, median of ``repeats`` runs.
"""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from .fit import error_metrics, fit_params, prepare_table
from .forms import LI_KAHRAMAN_2009
from .learned import LearnedFriction
from .model import predict_ln_mu
from .published import PUBLISHED_MODELS, published_mu

INPUTS = ("p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2")


def _median_time(fn, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return float(np.median(times))


def compare_models(table, lubricant, e_reduced: float, *, k_folds: int = 5, seed: int = 0,
                   blend_half_width: float = 0.1, repeats: int = 3,
                   learned_max_iter: int = 400) -> dict[str, Any]:
    """Cross-validated errors and speed of the paper's regression (with and without the blend) and a learned model.

    Parameters
    ----------
    table : pandas.DataFrame
        Dataset rows with the columns of the HDF5 store (SI units) [-].
    lubricant : Lubricant
        The dataset's lubricant [-].
    e_reduced : float
        Reduced modulus E' [Pa].
    k_folds : int
        Number of cross-validation folds [-].
    seed : int
        Seed of the fold shuffle and of the learned model [-].
    blend_half_width : float
        Half width δ of the branch blend band in λ̄ [-].
    repeats : int
        Repeats of each timing (the median is reported) [-].
    learned_max_iter : int
        Boosting iterations of the learned model [-].

    Returns
    -------
    dict
        ``models``: rows of {model, kind, metrics (:func:`surrogate.fit.error_metrics`), fit time [s], evaluation
        points per second, ...}; and the row counts, folds and seed of the data.
    """
    from sklearn.model_selection import KFold

    from .features import compute_features

    prepared = prepare_table(table, lubricant, e_reduced)
    feats, ln_mu = prepared.features, prepared.ln_mu
    inputs = [prepared.table[c].to_numpy(dtype=float) for c in INPUTS]
    n = ln_mu.size
    folds = list(KFold(k_folds, shuffle=True, random_state=seed).split(np.arange(n)))
    rows = []

    # --- paper Eq. 9, with the blend and with the paper's hard switch at λ̄ = 1 ------------------------------
    pred = {blend_half_width: np.empty(n), 0.0: np.empty(n)}
    start = time.perf_counter()
    for train, test in folds:
        params = fit_params(LI_KAHRAMAN_2009, {k: v[train] for k, v in feats.items()}, ln_mu[train])
        for delta, out in pred.items():
            out[test] = predict_ln_mu(LI_KAHRAMAN_2009, params, {k: v[test] for k, v in feats.items()}, delta)
    fit_time = (time.perf_counter() - start) / k_folds
    params = fit_params(LI_KAHRAMAN_2009, feats, ln_mu)
    for delta, out in pred.items():
        eval_time = _median_time(lambda: predict_ln_mu(LI_KAHRAMAN_2009, params, compute_features(
            *inputs, lubricant, e_reduced), delta), repeats)
        name = "li_kahraman_2009_eq9" if delta == blend_half_width else "li_kahraman_2009_eq9_hard_switch"
        rows.append({"model": name, "kind": f"regression (OLS, 24 coefficients), blend half width {delta:g}",
                     "metrics": error_metrics(ln_mu, out), "fit_time_s": fit_time,
                     "eval_points_per_s": n / eval_time})
        if blend_half_width == 0.0:
            break

    # --- gradient-boosted trees ------------------------------------------------------------------------------
    pred = np.empty(n)
    start = time.perf_counter()
    for train, test in folds:
        model = LearnedFriction(lubricant, e_reduced, random_state=seed, max_iter=learned_max_iter)
        model.fit_features({k: v[train] for k, v in feats.items()}, ln_mu[train])
        pred[test] = model.predict_ln_mu_features({k: v[test] for k, v in feats.items()})
    fit_time = (time.perf_counter() - start) / k_folds
    model = LearnedFriction(lubricant, e_reduced, random_state=seed, max_iter=learned_max_iter)
    model.fit_features(feats, ln_mu)
    eval_time = _median_time(lambda: model.mu(*inputs), repeats)
    rows.append({"model": "hist_gradient_boosting", "kind": "scikit-learn HistGradientBoostingRegressor on ln mu",
                 "metrics": error_metrics(ln_mu, pred), "fit_time_s": fit_time,
                 "eval_points_per_s": n / eval_time})

    # --- published formulas (not fitted) ---------------------------------------------------------------------
    for name in PUBLISHED_MODELS:
        try:
            mu = published_mu(name, *inputs, lubricant, e_reduced)
        except Exception as err:  # e.g. roughness outside Benedict & Kelley's range: report, don't abort
            rows.append({"model": name, "kind": "published formula", "error": str(err)})
            continue
        eval_time = _median_time(lambda: published_mu(name, *inputs, lubricant, e_reduced), repeats)
        ok = mu > 0
        metrics = error_metrics(ln_mu[ok], np.log(mu[ok]))
        metrics["n_nonpositive"] = int((~ok).sum())
        rows.append({"model": name, "kind": "published formula (not fitted; error on all rows)",
                     "metrics": metrics, "fit_time_s": 0.0, "eval_points_per_s": n / eval_time})
    solver = {}
    if "wall_time" in prepared.table.columns:
        wall = prepared.table["wall_time"].to_numpy(dtype=float)
        wall = wall[np.isfinite(wall) & (wall > 0)]
        if wall.size:
            solver = {"median_wall_time_s": float(np.median(wall)), "points_per_s": float(1.0 / np.median(wall)),
                      "level": ",".join(sorted(set(prepared.table.get("level", ["?"]).astype(str))))}
    return {"n_rows": n, "k_folds": k_folds, "seed": seed, "exclusions": prepared.exclusions, "models": rows,
            "ehl_solver": solver}


def format_table(result: dict[str, Any]) -> str:
    """Plain-text table of a :func:`compare_models` result.

    Parameters
    ----------
    result : dict
        What :func:`compare_models` returns [-].

    Returns
    -------
    str
        The table.
    """
    head = (f"{'model':33s} {'CV RMSE ln mu':>13s} {'mean|rel err|':>13s} {'p95|rel err|':>12s} "
            f"{'bias ln mu':>10s} {'points/s':>11s}")
    lines = [f"{result['n_rows']} rows, {result['k_folds']}-fold CV (published formulas: not fitted)", head]
    for row in result["models"]:
        if "error" in row:
            lines.append(f"{row['model']:33s} not applicable: {row['error']}")
            continue
        m = row["metrics"]
        lines.append(f"{row['model']:33s} {m['rmse_ln_mu']:13.4f} {m['mean_rel_err_mu']:13.2%} "
                     f"{m['p95_rel_err_mu']:12.2%} {m['bias_ln_mu']:10.3f} {row['eval_points_per_s']:11.3g}")
    solver = result.get("ehl_solver") or {}
    if solver:
        lines.append(f"{'EHL solver (the data, level ' + solver['level'] + ')':33s} {'reference':>13s} "
                     f"{'':>13s} {'':>12s} {'':>10s} {solver['points_per_s']:11.3g}")
    return "\n".join(lines)
