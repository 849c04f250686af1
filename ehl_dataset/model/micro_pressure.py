"""Micro-EHL pressure fluctuations of a rough contact as a distribution, for the film-law closure
(docs/explanation/mixed-regime.md, "The film-law model (production)").

In the deterministic model of a narrow rough contact (a few correlation lengths wide) the local fluid pressure
fluctuates about its time mean by about one Hertz pressure (standard deviation 0.58–2.0 p_h over |x| < 0.8a on the
validation cases A, C, G, I), with a skewed distribution: never below zero, a long tail above. Where the Eyring
traction is not saturated, τ grows nearly exponentially with p, and its mean over that distribution is several times
τ at the mean pressure (validation/micro_ehl_fluctuations.py). This module gives the distribution a closure uses:

- shape: a gamma distribution with the local mean pressure p̄ and standard deviation σ_p (it has support p ≥ 0 and
  the skew; with the deterministic runs' own σ_p(x) it reproduces their pressure-averaged Couette stress within
  1–12 % on cases A, C, G, I: `python validation/micro_ehl_fluctuations.py A:16 G:8 I:8 C:16`);
- scale: σ_p = c · E'Δq/4, where E'Δq/4 is the r.m.s. of the pressure that flattens the composite roughness
  completely, and c < 1 the fraction an EHL film lets through, a function of the inlet length in correlation
  lengths calibrated against the deterministic model (:func:`micro_pressure_coefficient`). Two elastic half-spaces in plane strain under a surface pressure p̂(k)
  approach by 4p̂/(E'|k|) (E' the reduced modulus, 2/E' = Σ(1 − ν_i²)/E_i; Johnson, Contact Mechanics, 1985, §13.1:
  p* = πE*Δ/λ flattens a sinusoid of amplitude Δ, E* = E'/2), so flattening heights z takes a pressure of r.m.s.
  E'·rms(z')/4 = E'Δq/4, Δq the r.m.s. slope of z = R1 + R2.
"""

from __future__ import annotations

import functools
import math

import numpy as np
from scipy.special import gammaincinv

from .amplitude_reduction import flattened_slope_rms
from .dry_contact import composite_windows, profile_hash, windows_that_fit
from .roughness import RoughnessProfile

MICRO_PRESSURE_C0 = 0.305
"""c0 of c = c0/(1 + (L_in/(β·L0))²) [-] (:func:`micro_pressure_coefficient`), fitted with
:data:`MICRO_PRESSURE_INLET_SCALE` by `python validation/micro_pressure_closure.py`
(validation/results/micro_pressure_closure.json, EHL solver ehl-2026.11-14)."""

MICRO_PRESSURE_INLET_SCALE = 2.99
"""L0 of c = c0/(1 + (L_in/(β·L0))²) [-]: the inlet length, in correlation lengths, at which c is half of c0."""


def micro_pressure_coefficient(inlet_over_beta: float) -> float:
    """Coefficient c of the pressure-fluctuation closure σ_p = c·E'Δq/4 at the contact's inlet length.

    L_in is the film law's inlet length (:func:`ehl_dataset.solvers.wide_contact.inlet_length`), β the correlation
    length:

        c = c0 / (1 + (L_in/(β·L0))²)   (:data:`MICRO_PRESSURE_C0`, :data:`MICRO_PRESSURE_INLET_SCALE`).

    An effective closure calibrated against the deterministic model on every unsaturated contact below λ̄ 1 within the
    planner's closure range, narrow and wide (docs/explanation/mixed-regime.md, "The film-law model (production)").
    Physically: where the inlet is long against β, the fluid smooths the micro-EHL pressure before the asperities reach
    the Hertz zone (c → 0: the deterministic windows agree with the film law without fluctuations at L_in/β 6–12), and
    where it is a few β, each asperity carries its own pressure peak through the contact (c ≈ 0.2 at L_in/β 2–3). The
    spread is not the deterministic run's own σ_p (0.76 GPa at the centre of case A, β/16, about twice c·E'Δq/4) because
    the closure pairs it with the smooth pressure and gaps independent of the pressure.

    Parameters
    ----------
    inlet_over_beta : float
        L_in/β [-].

    Returns
    -------
    float
        c [-].
    """
    if not inlet_over_beta >= 0.0:
        raise ValueError(f"inlet_over_beta = {inlet_over_beta!r}: accepted range [0, inf)")
    return MICRO_PRESSURE_C0 / (1.0 + (inlet_over_beta / MICRO_PRESSURE_INLET_SCALE) ** 2)


SPECTRAL_PRESSURE_SCALE = 1.0
"""k of the spectral form σ_p = k·E'Δq_f/4 (:func:`spectral_pressure_std`) [-]: 1, the r.m.s. pressure that flattens
the flattened part of the roughness. Fitted freely on the calibration set of the inlet form (33 contacts of the
baseline profile), k = 1.005 (`python validation/flank_reference/closure_check.py`,
validation/results/flank_reference_closures.json); the theoretical 1 is used."""


def spectral_pressure_std(profile: RoughnessProfile, case, state) -> tuple[float, float]:
    """Micro-EHL pressure spread of the spectral form, σ_p = k·E'Δq_f/4 (:data:`SPECTRAL_PRESSURE_SCALE`).

    Δq_f is the r.m.s. slope of the part of the composite roughness the conjunction flattens, from the amplitude
    reduction of each component of the profile's spectrum (:func:`ehl_dataset.model.amplitude_reduction.
    flattened_slope_rms`, the published ∇ unscaled): roughness that passes through the conjunction changes the gaps,
    not the pressure; roughness that is flattened does so by a pressure of r.m.s. E'Δq_f/4 (module docstring). Unlike
    the inlet form it needs no correlation length and no fitted constant, so it carries over between profiles of
    different spectra (docs/explanation/mixed-regime.md, "Pressure fluctuations from the flattened spectrum").

    Parameters
    ----------
    profile : RoughnessProfile
        Shape of both surfaces [-].
    case : ContactCase
        Operating conditions with Rq1, Rq2 [SI].
    state : LubricantState
        The lubricant at the case's temperature [SI].

    Returns
    -------
    tuple of float
        (σ_p [Pa], Δq_f [-]).
    """
    slope = flattened_slope_rms(profile, case, state)
    return SPECTRAL_PRESSURE_SCALE * flattening_pressure_rms(case.e_reduced, slope), slope


PRESSURE_QUANTILES = 32
"""Equal-probability levels (midpoints) of the pressure distribution in the closure's average."""

SPLINE_SHAPES = (0.2, 1e8)
"""Range of the gamma shape k = (p̄/σ_p)² in which :func:`gamma_pressure_quantiles` interpolates the levels
(:func:`_normalised_level_spline`) instead of inverting the incomplete gamma function at every node [-]."""
SPLINE_STEP = 0.0025
"""Knot spacing in ln k of :func:`_normalised_level_spline` [-]."""

_SLOPE_CACHE: dict[tuple[str, float, float], float] = {}


@functools.lru_cache(maxsize=4)
def _normalised_level_spline(count: int):
    """Cubic spline in ln k of the logarithm of the gamma distribution's equal-probability levels over their mean,
    ln(x_i/x̄) with x_i = P⁻¹(k, (i + ½)/count) (``scipy.special.gammaincinv``), on knots every :data:`SPLINE_STEP`
    from k = 0.1 to 2e8 (beyond :data:`SPLINE_SHAPES` on both sides, so that the end conditions do not reach the range
    used). Over :data:`SPLINE_SHAPES` each level is within a relative 1e-11 of the direct inversion
    (tests/ehl_dataset/test_micro_pressure.py). Built once per process (≈0.2 s)."""
    from scipy.interpolate import CubicSpline  # a slow import, needed only with pressure fluctuations

    log_k = np.arange(math.log(0.1), math.log(2e8) + SPLINE_STEP, SPLINE_STEP)
    levels = (np.arange(count) + 0.5) / count
    x = gammaincinv(np.exp(log_k)[:, None], levels[None, :])
    return CubicSpline(log_k, np.log(x / x.mean(axis=1, keepdims=True)), axis=0)


def composite_slope_rms(profile: RoughnessProfile, rq1: float, rq2: float) -> float:
    """R.m.s. slope Δq of the composite roughness z = R1 + R2 of a pair.

    Pooled over the dry-contact tables' periodic windows (:func:`ehl_dataset.model.dry_contact.composite_windows`), by
    the exact derivative of their Fourier series (cached per profile and Rq pair).

    Parameters
    ----------
    profile : RoughnessProfile
        Shape of both surfaces [-].
    rq1 : float
        RMS roughness of surface 1 [m].
    rq2 : float
        RMS roughness of surface 2 [m].

    Returns
    -------
    float
        Δq [-].
    """
    key = (profile_hash(profile), float(rq1), float(rq2))
    if key not in _SLOPE_CACHE:
        z, spacing = composite_windows(profile, rq1, rq2, windows_that_fit(profile))
        k = 2.0 * np.pi * np.fft.rfftfreq(z.shape[1], spacing)
        slope = np.fft.irfft(1j * k * np.fft.rfft(z, axis=1), n=z.shape[1], axis=1)
        _SLOPE_CACHE[key] = float(np.sqrt(np.mean(slope ** 2)))
    return _SLOPE_CACHE[key]


def flattening_pressure_rms(e_reduced: float, slope_rms: float) -> float:
    """R.m.s. E'·Δq/4 of the pressure that flattens a composite roughness of r.m.s. slope Δq between two elastic
    half-spaces (plane strain; module docstring).

    Parameters
    ----------
    e_reduced : float
        Reduced modulus E' [Pa].
    slope_rms : float
        Δq [-].

    Returns
    -------
    float
        E'·Δq/4 [Pa].
    """
    return 0.25 * e_reduced * slope_rms


_NORMAL_FLOOR = np.finfo(float).tiny / np.finfo(float).eps
"""Smallest value [Pa] whose every share above one rounding unit is a normal float (≈ 1e-292): the product form of
:func:`gamma_pressure_quantiles` is exact to rounding when the mean and the scaled levels' mean are above it."""


def gamma_pressure_quantiles(mean_pa, std_pa, count: int = PRESSURE_QUANTILES) -> np.ndarray:
    """Equal-probability levels (i + ½)/count of a gamma distribution of pressure (mean p̄, standard deviation σ_p).

    Rescaled so that their mean is p̄ exactly (the quadrature conserves the load; it truncates the tail, so its
    standard deviation is below σ_p where σ_p > p̄). p̄ ≤ 0 gives zeros; σ_p = 0 gives p̄.

    The gamma law has shape k = (p̄/σ_p)² and scale θ = σ_p²/p̄; its quantiles are θ·P⁻¹(k, q) with P the regularised
    lower incomplete gamma function (``scipy.special.gammaincinv``, as ``scipy.stats.gamma.ppf`` computes them).
    Where θ over- or underflows, or the levels that carry the mean fall below the normal floating-point range (p̄ far
    below σ_p: k ≲ 2.2e-5 at 32 levels, or p̄ itself below 1e-292 Pa), the levels are formed in log space instead: the scale cancels in the rescaling, the level
    i gets the weight x_i/x_max of its standard quantile x_i = P⁻¹(k, q_i), and where x_i underflows the small-x
    inverse of P(k, x) ≈ x^k/Γ(k + 1) (Abramowitz & Stegun 6.5.29), ln x_i = (ln q_i + ln Γ(k + 1))/k, exact to a
    relative O(x_i). As k → 0 the weights of all but the top level vanish: the mass concentrates at 0 with the whole
    load count·p̄ on the top level (a small probability of large pressures). For shapes within
    :data:`SPLINE_SHAPES` the rescaled levels are p̄ times a cubic spline in ln k of x_i/x̄
    (:func:`_normalised_level_spline`, each level within a relative 1e-11 of the direct inversion, about 40 times
    cheaper).

    Parameters
    ----------
    mean_pa : array_like
        Mean pressures p̄ [Pa].
    std_pa : float or array_like
        Standard deviation σ_p, a scalar or one per entry of ``mean_pa`` [Pa].
    count : int
        Number of levels [-].

    Returns
    -------
    ndarray
        Shape (len(mean_pa), count), finite for finite p̄ [Pa].
    """
    mean = np.maximum(np.asarray(mean_pa, dtype=float).ravel(), 0.0)
    std = np.broadcast_to(np.asarray(std_pa, dtype=float), mean.shape)
    levels = (np.arange(count) + 0.5) / count
    out = np.repeat(mean[:, None], count, axis=1)
    spread = (mean > 0.0) & (std > 0.0)
    if not spread.any():
        return out
    with np.errstate(over="ignore", under="ignore", invalid="ignore", divide="ignore"):
        shape_all = (mean / np.where(spread, std, 1.0)) ** 2
    splined = spread & (shape_all >= SPLINE_SHAPES[0]) & (shape_all <= SPLINE_SHAPES[1])
    if splined.any():
        ratio = np.exp(_normalised_level_spline(count)(np.log(shape_all[splined])))
        out[splined] = ratio * (mean[splined] / ratio.mean(axis=1))[:, None]
    spread &= ~splined
    if not spread.any():
        return out
    m, s = mean[spread], std[spread]
    with np.errstate(over="ignore", under="ignore", invalid="ignore", divide="ignore"):
        shape = (m / s) ** 2
        standard = gammaincinv(shape[:, None], levels[None, :])
        scale = s ** 2 / m
        quantiles = standard * scale[:, None]
        total = quantiles.mean(axis=1)
    # the product form (what scipy.stats.gamma.ppf returns, rescaled) where every level that carries the mean is a
    # normal float; log space elsewhere
    direct = np.isfinite(scale) & np.isfinite(total) & (total >= _NORMAL_FLOOR) & (m >= _NORMAL_FLOOR)
    quantiles[direct] *= (m[direct] / total[direct])[:, None]
    narrow = ~np.isfinite(shape)  # σ_p/p̄ below 1e-154: the distribution is p̄ to double precision
    quantiles[narrow] = m[narrow, None]
    rest = ~direct & ~narrow
    if rest.any():
        quantiles[rest] = _log_space_levels(m[rest], shape[rest], standard[rest], levels)
    out[spread] = quantiles
    return out


def _log_space_levels(mean: np.ndarray, shape: np.ndarray, standard: np.ndarray, levels: np.ndarray) -> np.ndarray:
    """Gamma levels rescaled to ``mean`` [Pa] from the log of the standard quantiles ``standard`` (one row per
    ``shape`` k): ln x_i where x_i is a normal float, the small-x inverse (ln q_i + ln Γ(k + 1))/k where it is not;
    weights exp(ln x_i − max ln x), scaled so that the row sums to count·p̄. Where even the top level's ln x
    overflows (k underflowed to 0, or 1/k near the largest float): the limit k → 0, the whole load on the top level."""
    from scipy.special import gammaln

    count = levels.size
    tiny = np.finfo(float).tiny
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        inverse_k = 1.0 / shape
        small_x = (np.log(levels)[None, :] + gammaln(1.0 + shape)[:, None]) * inverse_k[:, None]
        log_x = np.where(np.isfinite(standard) & (standard >= tiny), np.log(standard), small_x)
    limit = ~np.isfinite(log_x.max(axis=1))  # 1/k so large that even the top level's ln x overflows
    log_x[limit] = -np.inf
    log_x[limit, -1] = 0.0
    weights = np.exp(log_x - log_x.max(axis=1, keepdims=True))
    return weights * (count * mean / weights.sum(axis=1))[:, None]
