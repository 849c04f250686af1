"""Amplitude reduction of roughness inside an EHL line contact, per Fourier component of a profile
(docs/explanation/mixed-regime.md, "Pressure fluctuations from the flattened spectrum" and "The asperity-load
closure").

A harmonic roughness component of wavelength λ that passes through an EHL conjunction is flattened by the fluid
pressure; the ratio of its deformed to its undeformed amplitude is a function of one parameter (Venner, Couhier,
Lubrecht & Greenwood, Tribology Series 32 (1997) 103; with slip: "Waviness amplitude reduction in EHL line contacts
under rolling-sliding", J. Tribol. 120 (1998) 705):

    A_d/A_i = F(∇) = 1/(1 + 0.15∇ + 0.015∇²),   ∇ = (λ_c/a)·M^¾/L^½,

a the Hertz half width, M and L Moes' line-contact parameters, and λ_c = λ·u_m/u_i the wavelength that a roughness on
surface i (speed u_i, mean speed u_m) writes on the film carried at u_m (Hooke's complementary component, Proc.
IMechE J 217 (2003) 17): a faster surface writes shorter film waves, which survive; the roughness of a stationary
surface is flattened completely. Short wavelengths pass through the conjunction (F → 1); long ones are flattened
(F → 0), and flattening them takes pressure.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from .contact import ContactCase
from .dry_contact import profile_hash
from .film_formulas import moes_parameters
from .lubricant import LubricantState
from .roughness import RoughnessProfile, periodogram

AMPLITUDE_A = (0.15, 0.015)
"""Coefficients of F(∇) = 1/(1 + A1∇ + A2∇²), the pure-rolling line-contact fit of Venner et al. (1997) [-]."""


def amplitude_factor(nabla) -> np.ndarray:
    """F(∇) = 1/(1 + 0.15∇ + 0.015∇²), the ratio of deformed to undeformed roughness amplitude in an EHL line
    contact (Venner, Couhier, Lubrecht & Greenwood, Tribology Series 32 (1997) 103).

    Parameters
    ----------
    nabla : array_like
        ∇ = (λ/a)·M^¾/L^½, possibly scaled [-].

    Returns
    -------
    ndarray
        A_d/A_i [-].
    """
    nabla = np.asarray(nabla, dtype=float)
    return 1.0 / (1.0 + AMPLITUDE_A[0] * nabla + AMPLITUDE_A[1] * nabla**2)


@functools.lru_cache(maxsize=8)
def _spectrum(key: str, profile: RoughnessProfile) -> tuple[np.ndarray, np.ndarray]:
    k, power = periodogram(profile)
    return 2.0 * math.pi / k, power / np.sum(power)


def profile_spectrum(profile: RoughnessProfile) -> tuple[np.ndarray, np.ndarray]:
    """Wavelengths of the profile's periodogram and their shares of its variance, cached per profile hash.

    Parameters
    ----------
    profile : RoughnessProfile
        The profile [-].

    Returns
    -------
    tuple of ndarray
        (λ_j [m], w_j [-]) with Σ w_j = 1.
    """
    return _spectrum(profile_hash(profile), profile)


def nabla_per_wavelength(case: ContactCase, state: LubricantState) -> float:
    """∇/λ = M^¾/(L^½·a) of the contact: ∇ of a film wavelength λ_c is λ_c times this [1/m].

    Parameters
    ----------
    case : ContactCase
        Operating conditions [SI].
    state : LubricantState
        The lubricant at the case's temperature (η0, α) [SI].

    Returns
    -------
    float
        ∇/λ [1/m].
    """
    m, l_ = (float(v) for v in moes_parameters(state.eta0, case.u_r, state.alpha1, case.e_reduced, case.r_eq,
                                                case.load_per_length))
    return m**0.75 / math.sqrt(l_) / case.half_width


def surface_amplitude_factors(wavelength_m, case: ContactCase, state: LubricantState,
                              nabla_scale: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """F of each wavelength for the roughness of surface 1 and of surface 2 (module docstring): ∇ from the
    complementary wavelength λ·u_m/u_i, scaled by ``nabla_scale``; a stationary surface (u_i ≤ 0) gets F = 0.

    Parameters
    ----------
    wavelength_m : array_like
        Roughness wavelengths λ on the surface [m].
    case : ContactCase
        Operating conditions [SI].
    state : LubricantState
        The lubricant at the case's temperature [SI].
    nabla_scale : float
        Factor on ∇ (1: the published fit) [-].

    Returns
    -------
    tuple of ndarray
        (F_1, F_2) [-].
    """
    wavelength = np.asarray(wavelength_m, dtype=float)
    base = nabla_scale * nabla_per_wavelength(case, state)
    return tuple(np.zeros_like(wavelength) if u_i <= 0.0 else amplitude_factor(base * wavelength * case.u_r / u_i)
                 for u_i in (case.u1, case.u2))


def flattened_slope_rms(profile: RoughnessProfile, case: ContactCase, state: LubricantState,
                        nabla_scale: float = 1.0) -> float:
    """R.m.s. slope Δq_f of the part of the composite roughness that the conjunction flattens.

    Each surface i (Rq_i, the shape of ``profile``) loses the part 1 − F(∇_i(λ)) of every component; the removed
    parts of the two surfaces are independent, so

        Δq_f² = Σ_i Rq_i² Σ_j w_j k_j² (1 − F_i(λ_j))²,   k_j = 2π/λ_j,

    with w_j the share of the profile's variance at λ_j (:func:`profile_spectrum`). Δq_f ≤ Δq, the r.m.s. slope of
    the composite roughness; Δq_f = Δq where everything is flattened, 0 where everything passes.

    Parameters
    ----------
    profile : RoughnessProfile
        Shape of both surfaces (its spectrum, not its Rq) [-].
    case : ContactCase
        Operating conditions, with Rq1 and Rq2 [SI].
    state : LubricantState
        The lubricant at the case's temperature [SI].
    nabla_scale : float
        Factor on ∇ [-].

    Returns
    -------
    float
        Δq_f [-].
    """
    wavelength, weight = profile_spectrum(profile)
    k2 = (2.0 * math.pi / wavelength) ** 2
    factors = surface_amplitude_factors(wavelength, case, state, nabla_scale)
    slope2 = sum(rq**2 * float(np.sum(weight * k2 * (1.0 - f) ** 2)) for rq, f in zip((case.rq1, case.rq2), factors))
    return math.sqrt(slope2)
