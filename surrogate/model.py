"""Evaluation of the two-branch ln μ regression on feature arrays (pure, vectorised).

The paper switches from Eq. 9a to Eq. 9b at λ̄ = 1; two separately fitted branches do not meet there, so μ jumps.
We optionally blend ln μ over a narrow band λ̄ ∈ [1 − δ, 1 + δ]:

    ln μ = (1 − w) ln μ_9a + w ln μ_9b,   w = s((λ̄ − (1 − δ))/(2δ)),   s(t) = 3t² − 2t³ clipped to [0, 1],

which is C¹ in λ̄ and reproduces each branch exactly outside the band (δ = 0 is the paper's hard switch).
"""

from __future__ import annotations

import numpy as np

from .forms import Formula, Term

Features = dict[str, np.ndarray]


def branch_ln_mu(terms: tuple[Term, ...], params: np.ndarray, features: Features) -> np.ndarray:
    """ln μ of one branch: Σ_k params[k] · term_k(features) (no design matrix is built).

    Parameters
    ----------
    terms : tuple of Term
        The branch's regression terms [-].
    params : ndarray
        The branch's coefficients, in the order of ``terms`` [-].
    features : dict of str to ndarray
        Features [-].

    Returns
    -------
    ndarray
        ln μ of the branch, shaped like ``features["lam"]`` [-].
    """
    total = None
    for term, coefficient in zip(terms, params):
        contribution = coefficient * np.asarray(term.column(features), dtype=float)
        total = contribution if total is None else total + contribution
    return np.broadcast_to(total, np.shape(features["lam"])).astype(float, copy=False)


def blend_weight(lam, threshold: float, half_width: float) -> np.ndarray:
    """Weight w of the full-film branch: 0 for λ̄ ≤ thr − δ, 1 for λ̄ ≥ thr + δ, smoothstep between.

    Parameters
    ----------
    lam : array_like
        Film parameter λ̄ [-].
    threshold : float
        λ̄ where the branches meet [-].
    half_width : float
        Half width δ of the blend band [-].

    Returns
    -------
    ndarray
        w, between 0 and 1 [-].
    """
    lam = np.asarray(lam, dtype=float)
    if half_width <= 0.0:
        return (lam > threshold).astype(float)
    t = np.clip((lam - (threshold - half_width)) / (2.0 * half_width), 0.0, 1.0)
    return t * t * (3.0 - 2.0 * t)


def _subset(features: Features, index: np.ndarray) -> Features:
    return {key: np.asarray(value)[index] for key, value in features.items()}


def predict_ln_mu(formula: Formula, params: dict[str, np.ndarray], features: Features,
                  blend_half_width: float = 0.0) -> np.ndarray:
    """ln μ of the two-branch model (paper Eq. 9a for λ̄ ≤ threshold, Eq. 9b above) on feature arrays.

    Each branch is evaluated only where it is needed; within ``blend_half_width`` of the threshold the branches are
    blended by :func:`blend_weight`.

    Parameters
    ----------
    formula : Formula
        Regression form [-].
    params : dict of str to ndarray
        Coefficients per branch [-].
    features : dict of str to ndarray
        Features (:func:`surrogate.features.compute_features`) [-].
    blend_half_width : float
        Half width δ of the blend band in λ̄ (0: hard switch) [-].

    Returns
    -------
    ndarray
        ln μ, shaped like ``features["lam"]`` [-].
    """
    lam = np.asarray(features["lam"], dtype=float).ravel()
    flat = {key: np.asarray(value, dtype=float).ravel() for key, value in features.items()}
    threshold = formula.lambda_threshold
    weight = blend_weight(lam, threshold, blend_half_width)
    out = np.empty_like(lam)
    need_mixed = np.flatnonzero(weight < 1.0)
    need_full = np.flatnonzero(weight > 0.0)
    mixed = branch_ln_mu(formula.terms["mixed"], params["mixed"], _subset(flat, need_mixed))
    full = branch_ln_mu(formula.terms["full_film"], params["full_film"], _subset(flat, need_full))
    out[need_mixed] = mixed
    both, in_mixed, in_full = np.intersect1d(need_mixed, need_full, assume_unique=True, return_indices=True)
    out[need_full] = full
    if both.size:
        w = weight[both]
        out[both] = (1.0 - w) * mixed[in_mixed] + w * full[in_full]
    return out.reshape(np.shape(features["lam"]))
