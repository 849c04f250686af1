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

Calibration off the training design. The statsmodels interval assumes one residual variance everywhere. Fitted on a
factorial grid, σ̂² is set by the grid's corners, where Eq. 9 fits worst, and the interval is too wide for contacts
inside the box (on the quick factorial its 90 % interval held all 200 off-grid contacts). A coefficient file may
therefore carry ``interval_calibration``: per branch b and coverage c, the split-conformal quantile q_b(c) of the
normalised score |ln μ − ln μ̂| / se(x) over held-out solved contacts (Papadopoulos et al. 2002; Lei et al. 2018,
*J. Am. Stat. Assoc.* 113, Sect. 2.2 and 5.2: the ⌈(n + 1) c⌉-th smallest score), se(x) = √(σ̂² + xᵀ Σ x) being the
statsmodels prediction standard error above. The calibrated interval is

    ln μ̂ ± q_b(c) · √(σ̂² + xᵀ Σ x),

the statsmodels interval with t_{1−α/2, ν} replaced by an empirical factor: its shape over the box is still that of
the regression; only its level is set by contacts drawn like those it will be used on. Rows are assigned to the
branch of their λ̄ (≤ threshold: mixed) and scored against the blended standard error; inside the blend band the
half widths are blended as above. Files without the table keep the plain statsmodels interval.
"""

from __future__ import annotations

import numpy as np
from scipy import stats

from .forms import Formula, Term
from .model import blend_weight

DEFAULT_ALPHA = 0.10
"""1 − coverage of the intervals reported by default (90 % prediction intervals)."""
CALIBRATED_COVERAGES = (0.5, 0.68, 0.8, 0.9, 0.95)
"""Coverages whose score quantile a calibrated Eq. 9 file stores (0.9 required)."""
TOO_FEW_CALIBRATION_ROWS = ">= 9 held-out rows for a 90 % interval"
"""What the error of a branch with too few held-out rows accepts (the ⌈(n + 1)·0.9⌉-th smallest score exists from
n = 9 on): callers tell this shortfall of a small sample from other bad input by it."""

CALIBRATION_METHOD = ("split conformal per branch: the statsmodels prediction standard error sqrt(s^2 + x'Cx) "
                      "scaled by the ceil((n+1)c)-th smallest |ln mu - ln mu_hat|/se over held-out solved contacts")


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


def _branch_parts(formula: Formula, covariance, resid_variance, features, blend_half_width):
    """Blend weight and, per branch, the rows it contributes to, their share and their prediction standard error."""
    lam = np.asarray(features["lam"], dtype=float).ravel()
    flat = {key: np.asarray(value, dtype=float).ravel() for key, value in features.items()}
    weight = blend_weight(lam, formula.lambda_threshold, blend_half_width)
    parts = []
    for branch, need, share in (("mixed", weight < 1.0, 1.0 - weight), ("full_film", weight > 0.0, weight)):
        index = np.flatnonzero(need)
        if not index.size:
            continue
        sub = {key: value[index] for key, value in flat.items()}
        se = branch_prediction_se(formula.terms[branch], covariance[branch], resid_variance[branch], sub)
        parts.append((branch, index, share[index], se))
    return lam, parts


def prediction_half_width(formula: Formula, covariance: dict[str, np.ndarray], resid_variance: dict[str, float],
                          df_resid: dict[str, float], features: dict[str, np.ndarray], blend_half_width: float,
                          alpha: float = DEFAULT_ALPHA,
                          score_quantiles: dict[str, dict[float, float]] | None = None) -> np.ndarray:
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
    score_quantiles : dict, optional
        Calibrated factors {branch: {coverage: q}} (:func:`calibrate_scores`); they replace t_{1−α/2, ν}, and
        1 − α must be one of the stored coverages. None: the plain statsmodels interval [-].

    Returns
    -------
    numpy.ndarray
        Half width of the interval of ln μ, shaped like ``features["lam"]`` [-].
    """
    if not 0.0 < alpha < 1.0:
        from ehl_dataset.validation import InputError

        raise InputError("alpha", alpha, "(0, 1)")
    lam, parts = _branch_parts(formula, covariance, resid_variance, features, blend_half_width)
    out = np.zeros_like(lam)
    for branch, index, share, se in parts:
        if score_quantiles is None:
            factor = t_quantile(alpha, df_resid[branch])
        else:
            from .mlp import quantile_for

            factor = quantile_for(score_quantiles[branch], 1.0 - alpha)
        out[index] += share * factor * se
    return out.reshape(np.shape(features["lam"]))


def prediction_se(formula: Formula, covariance: dict[str, np.ndarray], resid_variance: dict[str, float],
                  features: dict[str, np.ndarray], blend_half_width: float) -> np.ndarray:
    """Standard error of a new observation of ln μ of the two-branch model, blended like the half width.

    Parameters
    ----------
    formula : Formula
        The two-branch formula [-].
    covariance : dict of numpy.ndarray
        Coefficient covariance per branch [-].
    resid_variance : dict of float
        Residual variance of ln μ per branch [-].
    features : dict of numpy.ndarray
        Feature arrays [-].
    blend_half_width : float
        δ of the λ̄ blend band [-].

    Returns
    -------
    numpy.ndarray
        (1 − w)·se_mixed + w·se_full_film, flat [-].
    """
    lam, parts = _branch_parts(formula, covariance, resid_variance, features, blend_half_width)
    out = np.zeros_like(lam)
    for _, index, share, se in parts:
        out[index] += share * se
    return out


def calibrate_scores(residual: np.ndarray, se: np.ndarray, lam: np.ndarray, lambda_threshold: float,
                     coverages: tuple[float, ...] = CALIBRATED_COVERAGES) -> dict[str, dict[float, float]]:
    """Split-conformal factors per branch from held-out residuals (module docstring).

    Parameters
    ----------
    residual : numpy.ndarray
        ln μ_solved − ln μ̂ on the held-out contacts [-].
    se : numpy.ndarray
        Prediction standard error there (:func:`prediction_se`) [-].
    lam : numpy.ndarray
        λ̄ of the contacts (branch assignment) [-].
    lambda_threshold : float
        λ̄ separating the branches [-].
    coverages : tuple of float
        Coverages to store [-].

    Returns
    -------
    dict
        {branch: {coverage: q}} for every coverage the branch's number of rows allows.

    Raises
    ------
    InputError
        When a branch has too few held-out rows for a 90 % factor (fewer than 9), or a score is not finite.
    """
    from ehl_dataset.validation import InputError

    from .mlp import conformal_quantile

    residual, se, lam = (np.asarray(a, dtype=float).ravel() for a in (residual, se, lam))
    score = np.abs(residual) / se
    if not np.all(np.isfinite(score)):
        raise InputError("calibration rows", int(np.sum(~np.isfinite(score))), "finite residuals and standard errors")
    out = {}
    for branch, mask in (("mixed", lam <= lambda_threshold), ("full_film", lam > lambda_threshold)):
        quantiles = {c: q for c in coverages if np.isfinite(q := conformal_quantile(score[mask], c))}
        if 0.9 not in quantiles:
            raise InputError(f"calibration rows ({branch})", int(mask.sum()), TOO_FEW_CALIBRATION_ROWS)
        out[branch] = quantiles
    return out
