"""Prediction intervals of the two-branch ln μ regression (paper Eq. 9a/9b), vectorised.

For an OLS branch with design row x (the branch's terms at the contact), coefficient covariance
Σ = σ̂² (XᵀX)⁻¹, residual variance σ̂² and ν residual degrees of freedom, the (1 − α) prediction interval of a new
observation of ln μ is (e.g. Montgomery, Peck & Vining, *Introduction to Linear Regression Analysis*, Eq. 3.54;
statsmodels ``get_prediction().summary_frame(alpha)``, columns ``obs_ci_lower``/``obs_ci_upper``)

    ln μ̂ ± t_{1−α/2, ν} · √(σ̂² + xᵀ Σ x).

The interval on μ is its exponential (an interval on ln μ maps to one on μ with the same coverage). In the λ̄ band
where the evaluator blends the branches (ln μ = (1 − w) ln μ_9a + w ln μ_9b, :mod:`surrogate.model`) the half widths
are blended with the same weight: the interval of a weighted mean of two predictions whose errors are taken as fully
correlated (the conservative choice; independent errors would give a narrower band).
"""

from __future__ import annotations

import numpy as np
from scipy import stats

from .forms import Formula, Term
from .model import blend_weight

DEFAULT_ALPHA = 0.10
"""1 − coverage of the intervals reported by default (90 % prediction intervals)."""


def t_quantile(alpha: float, df_resid: float) -> float:
    """Two-sided Student-t quantile t_{1−α/2, ν}.

    Parameters
    ----------
    alpha : float
        1 − coverage of the interval [-].
    df_resid : float
        Residual degrees of freedom ν of the fit [-].

    Returns
    -------
    float
        The quantile [-].
    """
    return float(stats.t.ppf(1.0 - alpha / 2.0, df_resid))


def branch_prediction_se(terms: tuple[Term, ...], covariance: np.ndarray, resid_variance: float,
                         features: dict[str, np.ndarray]) -> np.ndarray:
    """Standard error of a new observation of ln μ on one branch, √(σ̂² + xᵀ Σ x), at every point of ``features``.

    Parameters
    ----------
    terms : tuple of Term
        The branch's regressors (:mod:`surrogate.forms`) [-].
    covariance : numpy.ndarray
        (k, k) covariance Σ of the branch's coefficients [-].
    resid_variance : float
        Residual variance σ̂² of ln μ [-].
    features : dict of numpy.ndarray
        Feature arrays (:func:`surrogate.features.compute_features`) [-].

    Returns
    -------
    numpy.ndarray
        Standard error of prediction of ln μ, flat [-].
    """
    columns = [np.asarray(t.column(features), dtype=float).ravel() for t in terms]
    n = columns[0].size if columns else 0
    quad = np.zeros(n)
    # xᵀ Σ x = Σ_jk x_j Σ_jk x_k, accumulated column by column (no (n, k) matrix in memory)
    for j, xj in enumerate(columns):
        inner = np.zeros(n)
        for k, xk in enumerate(columns):
            if covariance[j, k] != 0.0:
                inner += covariance[j, k] * xk
        quad += xj * inner
    return np.sqrt(np.maximum(quad, 0.0) + resid_variance)


def prediction_half_width(formula: Formula, covariance: dict[str, np.ndarray], resid_variance: dict[str, float],
                          df_resid: dict[str, float], features: dict[str, np.ndarray], blend_half_width: float,
                          alpha: float = DEFAULT_ALPHA) -> np.ndarray:
    """Half width of the (1 − α) prediction interval of ln μ of the two-branch model (module docstring).

    Parameters
    ----------
    formula : Formula
        The two-branch formula [-].
    covariance : dict of numpy.ndarray
        Coefficient covariance per branch [-].
    resid_variance : dict of float
        Residual variance of ln μ per branch [-].
    df_resid : dict of float
        Residual degrees of freedom per branch [-].
    features : dict of numpy.ndarray
        Feature arrays [-].
    blend_half_width : float
        δ of the λ̄ blend band [-].
    alpha : float
        1 − coverage [-].

    Returns
    -------
    numpy.ndarray
        Half width of the interval of ln μ, shaped like ``features["lam"]`` [-].
    """
    if not 0.0 < alpha < 1.0:
        from ehl_dataset.validation import InputError

        raise InputError("alpha", alpha, "(0, 1)")
    lam = np.asarray(features["lam"], dtype=float).ravel()
    flat = {key: np.asarray(value, dtype=float).ravel() for key, value in features.items()}
    weight = blend_weight(lam, formula.lambda_threshold, blend_half_width)
    out = np.zeros_like(lam)
    for branch, need, share in (("mixed", weight < 1.0, 1.0 - weight), ("full_film", weight > 0.0, weight)):
        index = np.flatnonzero(need)
        if not index.size:
            continue
        sub = {key: value[index] for key, value in flat.items()}
        se = branch_prediction_se(formula.terms[branch], covariance[branch], resid_variance[branch], sub)
        out[index] += share[index] * t_quantile(alpha, df_resid[branch]) * se
    return out.reshape(np.shape(features["lam"]))
