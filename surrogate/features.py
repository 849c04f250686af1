"""Dimensionless features of the paper's friction regression (Li & Kahraman 2009, Sect. 2.1;
docs/explanation/surrogate.md).

All inputs are SI arrays (broadcast together); the lubricant supplies η0(T) and α1(T) at the *inlet* temperature.
With the Hertz line-contact load per unit length W' = 2π r_eq p_h²/E':

==========  =====================================  ===========================================================
feature     formula                                remark
==========  =====================================  ===========================================================
``W``       W̄ = −log10(p_h/E')                     load
``alpha``   ᾱ = log10(α1 E')                       pressure–viscosity (α1 at T)
``r``       r̄ = log10(r_eq E'/W')                  = 2 W̄ − log10(2π) exactly under Hertz loading: r̄ carries
                                                    no information beyond W̄ (collinear; see
                                                    docs/explanation/surrogate.md)
``V``       V̄ = −log10(u_r η0/W')                  speed × viscosity over load (η0 at T)
``lam``     λ̄ = h_min,DH/S_c                       Dowson–Higginson minimum film over composite roughness
``SR``      SR = |u1 − u2|/u_r                     slide-to-roll ratio (magnitude)
``Sc``      S̄_c = S_c E'/W'                        S_c = √(Rq1² + Rq2²)
``Seq``     S̄_eq = S_eq E'/W'                      S_eq = Rq1 Rq2/(Rq1 + Rq2)
==========  =====================================  ===========================================================

The paper's text prints S̄_eq as "S_eq E'_eq E'_eq W'" (a typesetting error); we use S_eq E'/W', the same scaling
as S̄_c.
"""

from __future__ import annotations

import math

import numpy as np

from ehl_dataset.model.film_formulas import dowson_higginson_min_film

FEATURE_NAMES: tuple[str, ...] = ("W", "alpha", "r", "V", "lam", "SR", "Sc", "Seq")
"""Keys of the feature dictionary, in the order used by tables and the learned model."""

LOG10_2PI = math.log10(2.0 * math.pi)


def load_per_length(p_h, r_eq, e_reduced):
    """Hertz line-contact load per unit length W' = 2π r_eq p_h²/E'.

    Parameters
    ----------
    p_h : array_like
        Hertz pressure [Pa].
    r_eq : array_like
        Equivalent radius of curvature [m].
    e_reduced : float
        Reduced modulus E' [Pa].

    Returns
    -------
    ndarray
        W' [N/m].
    """
    return 2.0 * np.pi * np.asarray(r_eq, dtype=float) * np.asarray(p_h, dtype=float) ** 2 / e_reduced


def composite_roughness(rq1, rq2):
    """Composite RMS roughness S_c = √(Rq1² + Rq2²).

    Parameters
    ----------
    rq1 : array_like
        RMS roughness of surface 1 [m].
    rq2 : array_like
        RMS roughness of surface 2 [m].

    Returns
    -------
    ndarray
        S_c [m].
    """
    return np.hypot(np.asarray(rq1, dtype=float), np.asarray(rq2, dtype=float))


def equivalent_roughness(rq1, rq2):
    """Equivalent roughness S_eq = Rq1 Rq2/(Rq1 + Rq2) (0 where both are 0).

    Parameters
    ----------
    rq1 : array_like
        RMS roughness of surface 1 [m].
    rq2 : array_like
        RMS roughness of surface 2 [m].

    Returns
    -------
    ndarray
        S_eq [m].
    """
    rq1 = np.asarray(rq1, dtype=float)
    rq2 = np.asarray(rq2, dtype=float)
    total = rq1 + rq2
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(total > 0, rq1 * rq2 / np.where(total > 0, total, 1.0), 0.0)


def compute_features(p_h, r_eq, u_r, sr, temperature, rq1, rq2, lubricant, e_reduced: float) -> dict[str, np.ndarray]:
    """The eight features of the paper's regression (Li & Kahraman 2009, Sect. 2.1; table in the module docstring).

    No validation here (pure arithmetic): callers validate (:mod:`surrogate.evaluate`).

    Parameters
    ----------
    p_h : array_like
        Hertz pressure [Pa].
    r_eq : array_like
        Equivalent radius of curvature [m].
    u_r : array_like
        Rolling velocity [m/s].
    sr : array_like
        Slide-to-roll ratio, sign ignored [-].
    temperature : array_like
        Inlet temperature [K].
    rq1 : array_like
        RMS roughness of surface 1 [m].
    rq2 : array_like
        RMS roughness of surface 2 [m].
    lubricant : Lubricant
        Supplies η0(T) and α1(T) at the inlet temperature [-].
    e_reduced : float
        Reduced modulus E' [Pa].

    Returns
    -------
    dict of str to ndarray
        ``W``, ``alpha``, ``r``, ``V``, ``lam``, ``SR``, ``Sc``, ``Seq`` [-] broadcast together, plus the
        Dowson–Higginson minimum film ``h_min_dh`` [m] and the load per length ``w_prime`` [N/m].
    """
    p_h, r_eq, u_r, sr, temperature, rq1, rq2 = np.broadcast_arrays(
        *(np.asarray(v, dtype=float) for v in (p_h, r_eq, u_r, sr, temperature, rq1, rq2)))
    eta0, alpha1 = lubricant_properties(lubricant, temperature)
    w_prime = load_per_length(p_h, r_eq, e_reduced)
    s_c = composite_roughness(rq1, rq2)
    s_eq = equivalent_roughness(rq1, rq2)
    h_min = dowson_higginson_min_film(eta0, u_r, alpha1, e_reduced, r_eq, w_prime)
    scale = e_reduced / w_prime
    with np.errstate(divide="ignore", invalid="ignore"):
        lam = h_min / s_c
        return {
            "W": -np.log10(p_h / e_reduced),
            "alpha": np.log10(alpha1 * e_reduced),
            "r": np.log10(r_eq * scale),
            "V": -np.log10(u_r * eta0 / w_prime),
            "lam": lam,
            "SR": np.abs(sr),
            "Sc": s_c * scale,
            "Seq": s_eq * scale,
            "h_min_dh": h_min,
            "w_prime": w_prime,
        }


def lubricant_properties(lubricant, temperature):
    """Inlet viscosity η0 and pressure–viscosity coefficient α1 at the temperatures, computed once per distinct value.

    Factorial tables and gear meshes have few distinct temperatures; evaluating the Walther law only on those makes
    feature computation several times faster for large arrays.

    Parameters
    ----------
    lubricant : Lubricant
        The lubricant [-].
    temperature : array_like
        Temperatures [K].

    Returns
    -------
    tuple of ndarray
        (η0 [Pa·s], α1 [1/Pa]), shaped like ``temperature``.
    """
    temperature = np.asarray(temperature, dtype=float)
    flat = temperature.ravel()
    if flat.size > 64:
        levels, inverse = np.unique(flat, return_inverse=True)
        if levels.size * 8 < flat.size:
            eta = np.asarray(lubricant.dynamic_viscosity(levels), dtype=float)[inverse].reshape(temperature.shape)
            alpha = np.asarray(lubricant.alpha1(levels), dtype=float)[inverse].reshape(temperature.shape)
            return eta, alpha
    return (np.asarray(lubricant.dynamic_viscosity(temperature), dtype=float),
            np.asarray(lubricant.alpha1(temperature), dtype=float))


def at_lambda_one(features: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Features of the same contact with both roughnesses scaled so that λ̄ = 1 exactly.

    Scaling Rq1 and Rq2 by k scales S_c, S_eq (hence S̄_c, S̄_eq) by k and λ̄ by 1/k; everything else is unchanged.
    With k = λ̄ this gives the point on the branch boundary closest to the contact: used to measure the jump
    between Eq. 9a and Eq. 9b.

    Parameters
    ----------
    features : dict of str to ndarray
        Features of :func:`compute_features` [-].

    Returns
    -------
    dict of str to ndarray
        The same keys with ``lam`` = 1 and ``Sc``, ``Seq`` scaled.
    """
    out = dict(features)
    lam = np.asarray(features["lam"], dtype=float)
    out["Sc"] = features["Sc"] * lam
    out["Seq"] = features["Seq"] * lam
    out["lam"] = np.ones_like(lam)
    return out
