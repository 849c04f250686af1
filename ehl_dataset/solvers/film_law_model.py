"""Film-law homogenised model of a wide rough contact: the deterministic wide route with its periodic windows
replaced by the ensemble average over the roughness pair's dry-contact table (docs/explanation/mixed-regime.md,
"Film-law closure").

The deterministic model of a contact many correlation lengths wide (:mod:`ehl_dataset.solvers.wide_contact`) takes
the smooth solve's pressure p̄(x), the lubricant content of the measured film law,

    h̄(x) = h̄_c ρ(p̄_c)/ρ(p̄(x)),   h̄_c = h_s + σ·c·(L_in/β)^k/(h_s/σ + d)   (fed_central_film),

and solves periodic windows for the local mean traction. Here that traction is the average over the gaps
g = h̄(x) + z of the roughness pair (z the composite heights of the actual profiles, the windows of the dry-contact
tables, :func:`ehl_dataset.model.dry_contact.composite_windows`), at the local mean pressure:

    τ̄(x) = ⟨τ0 asinh(η(p̄) u_s/(τ0 max(h̄ + z, h_b)))⟩_z,

plus the rolling part (h̄/2)∂p̄/∂x, inside |x| < e·a; outside, the smooth solve's local shear stress (paper Eq. 7).

The rolling part is the force balance of the film, exact for the right film and pressure; over the whole domain it
integrates to −∫(p̄/2)∂h/∂x dx, the pressure on the slope of the film. With h̄ inside and h_s outside, the film steps
by h̄ − h_s at both zone edges, and the steps add the spurious (h̄ − h_s)(p̄(ea) − p̄(−ea))/2 per unit length. Where
the Hertz zone is wide and the pressure nearly symmetric this is negligible; on a point-like contact at light load
(a/β < 1.8, :data:`~ehl_dataset.solvers.levels.POINT_CONTACT_A_OVER_BETA`) the film law's h̄ is several h_s, the
pressure peaks near the inlet and the steps dominate μ (at 37 MPa, a/β 0.54: −0.0141 of a total −0.0070 against the
deterministic model's +0.029). There the rolling term outside the zone takes the smooth film shifted by the zone's
excess at the nearer edge (:func:`continuous_outside_film`), which has no step. Elsewhere the smooth film is kept:
on the paper factorial (a/β ≥ 2.95) the continuous film would move μ by a median 0.06 % (≤ 0.8 % on wide contacts,
up to 15 % on the lightest narrow corner) with the median error against the deterministic model about the same
(validation/narrow_point_contacts.py --factorial-check), and keeping the steps there leaves the dataset fitted on
it as computed.
The fluid carries the whole load and no asperity friction is added: in the deterministic reference the micro-EHL
pressure between colliding asperities holds them apart (asperity share ≤ 0.02 down to λ̄ 0.12 on the roughness
sweep, ≤ 0.004 in the windows of the widest factorial corners), whereas the dry-contact table at the law's film
gives part of the load to the asperities and, with μ_d on it, μ up to 325 % above the windows (measured,
validation/film_law_model.py). The micro-EHL pressure is modelled statistically: the pressure is gamma-distributed about p̄ with the calibrated
spread σ_p = c·E'Δq/4, c a function of the inlet length in correlation lengths L_in/β
(:mod:`ehl_dataset.model.micro_pressure`; c → 0 where the inlet is many β long), and the stress is averaged over
pressures and gaps, taken independent:

    τ̄(x) = ⟨τ0 asinh(η(p) u_s/(τ0 max(h̄ + z, h_b)))⟩_{z, p ~ Γ(p̄(x), σ_p)}.

Where the traction is not Eyring-saturated the deterministic model's μ is 1.5–2.2× the film law's without it (the mean
of a convex τ(p) over the fluctuations), and with it within the leave-one-out error of the calibration
(docs/explanation/mixed-regime.md). With ``plan.thermal`` the Couette stresses carry the thermal correction of the
smooth solver (shear heating and flash temperature, :mod:`ehl_dataset.model.thermal`) computed for a smooth film of the
model's mean film: outside the zone as is, inside as the node-wise ratio thermal/isothermal that scales the gap average
(the heat source is the mean film's shear, not the gap-averaged one: an approximation).

Measured against the windows on the factorial's widest corners this holds within a few per cent where the
viscosity is saturated in the Eyring sense (validation/film_law_model.py, docs page above). The result says when a
contact is narrower than the route's validated a/β (with the closure's spread) or the film law is extrapolated; the
planner says whether a contact is within the closure's measured range.

The cost is one steady smooth solve, a table lookup and, where c > 0, the pressure average: this is a production
model, not a reference.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..model.contact import ContactCase
from ..names import DEFAULT_FLUCTUATIONS, FLUCTUATIONS
from ..model.dry_contact import composite_windows, profile_hash, windows_that_fit
from ..model.effects import Effects
from ..model.lubricant import LubricantState
from ..model.micro_pressure import (composite_slope_rms, flattening_pressure_rms, gamma_pressure_quantiles,
                                    micro_pressure_coefficient as inlet_micro_pressure_coefficient,
                                    spectral_pressure_std)
from ..model.roughness import RoughnessProfile, default_profile, profile_record
from ..model.thermal import ThermalTraction, thermal_couette_traction
from ..model.traction import eyring_shear_stress, full_film_mask
from ..validation import InputError, check_range
from .levels import POINT_CONTACT_A_OVER_BETA, AccuracyLevel
from .result import ContactResult
from .steady import dowson_higginson_lambda, solve_steady
from .wide_contact import (CENTRE_BAND, FILM_LAW_C, FILM_LAW_D, FILM_LAW_K, WIDE_A_OVER_BETA, WIDE_MODEL_VERSION,
                           WideOptions, _integral_outside, fed_central_film, film_law_extrapolation, inlet_length)

FILM_LAW_MODEL_VERSION = "film-law-2026.11-4"
"""Version of this closure (film law of :mod:`ehl_dataset.solvers.wide_contact`, gap-averaged traction; -2: the
micro-EHL pressure-fluctuation closure on narrow contacts; -3: its c a function of L_in/β on every contact; -4: the
rolling term outside the zone on the film continuous with the zone's on point-like contacts, a/β < 1.8)."""

HEIGHT_QUANTILES = 256
"""Number of equal-probability levels (midpoints) of the composite height distribution in the gap average."""

_QUANTILE_CACHE: dict[tuple[str, float, float], np.ndarray] = {}


def composite_height_quantiles(profile: RoughnessProfile, rq1: float, rq2: float,
                               count: int = HEIGHT_QUANTILES) -> np.ndarray:
    """Quantiles [m] of the composite roughness z = R1 + R2 of the pair (``profile`` scaled to Rq1, Rq2 [m]) at the
    levels (i + ½)/count, pooled over the dry-contact tables' windows (cached per profile and Rq pair)."""
    key = (profile_hash(profile), float(rq1), float(rq2), int(count))
    if key not in _QUANTILE_CACHE:
        z, _ = composite_windows(profile, rq1, rq2, windows_that_fit(profile))
        _QUANTILE_CACHE[key] = np.quantile(z.ravel(), (np.arange(count) + 0.5) / count)
    return _QUANTILE_CACHE[key]


SATURATED_EYRING_ARGUMENT = 20.0
"""Eyring argument y = η|u_s|/(τ0 g) above which the gap average of asinh y takes the asymptotic series
asinh y = ln 2y + 1/(4y²) − 3/(32y⁴) + 5/(96y⁶) + R, |R| ≤ 35/(1024y⁸) ≤ 1.4e-12 (Abramowitz & Stegun 4.6.31; a
relative 4e-13): every term is a power of the gap g times a function of η, so the average over the gaps needs the
moments ⟨ln g⟩, ⟨g²⟩, ⟨g⁴⟩, ⟨g⁶⟩ once per node instead of one asinh per gap and pressure level."""
NEWTONIAN_EYRING_ARGUMENT = 0.02
"""Eyring argument below which the gap average takes the Taylor series asinh y = y − y³/6 + 3y⁵/40 − 5y⁷/112 + R,
|R| ≤ 35y⁹/1152 (relative to y at most 8e-16; Abramowitz & Stegun 4.6.31), with the moments ⟨g⁻¹⟩ … ⟨g⁻⁷⟩."""

_EXACT_BLOCK = 1 << 16
"""Entries of the exact (η, gap) average formed at once (memory bound of :func:`_mean_asinh_over_gaps`)."""


def _mean_asinh_over_gaps(arguments, gaps) -> np.ndarray:
    """⟨asinh(A_nk/g_nj)⟩_j [-] for A ≥ 0 of shape (nodes, levels) and the gaps g > 0 of shape (nodes, J) [m].

    Where even the widest gap of node n leaves A/g ≥ :data:`SATURATED_EYRING_ARGUMENT` the asymptotic series, where
    even the narrowest leaves A/g ≤ :data:`NEWTONIAN_EYRING_ARGUMENT` the Taylor series (both with moments of the gaps
    over j), elsewhere the exact mean: the same average to a relative 4e-13."""
    arguments = np.asarray(arguments, dtype=float)
    out = np.empty(arguments.shape)
    saturated = arguments >= SATURATED_EYRING_ARGUMENT * gaps.max(axis=1)[:, None]
    newtonian = arguments <= NEWTONIAN_EYRING_ARGUMENT * gaps.min(axis=1)[:, None]
    if saturated.any():
        rows = np.nonzero(saturated)[0]
        g2 = gaps * gaps
        m2, m4, m6 = (g2.mean(axis=1)[rows], (g2 * g2).mean(axis=1)[rows], (g2 * g2 * g2).mean(axis=1)[rows])
        a = arguments[saturated]
        t = 1.0 / (a * a)
        out[saturated] = (np.log(2.0 * a) - np.log(gaps).mean(axis=1)[rows]
                          + t * (0.25 * m2 - t * (0.09375 * m4 - t * (5.0 / 96.0) * m6)))
    if newtonian.any():
        rows = np.nonzero(newtonian)[0]
        inv = 1.0 / gaps
        inv2 = inv * inv
        m1, m3 = inv.mean(axis=1)[rows], (inv * inv2).mean(axis=1)[rows]
        m5, m7 = (inv * inv2 * inv2).mean(axis=1)[rows], (inv * inv2 * inv2 * inv2).mean(axis=1)[rows]
        a = arguments[newtonian]
        a2 = a * a
        out[newtonian] = a * (m1 - a2 * (m3 / 6.0 - a2 * (0.075 * m5 - a2 * (5.0 / 112.0) * m7)))
    rows, levels = np.nonzero(~(saturated | newtonian))
    chunk = max(1, _EXACT_BLOCK // max(gaps.shape[1], 1))
    for start in range(0, rows.size, chunk):
        r, k = rows[start:start + chunk], levels[start:start + chunk]
        out[r, k] = np.arcsinh(arguments[r, k][:, None] / gaps[r]).mean(axis=1)
    return out


def gap_averaged_shear_stress(eta, u_s: float, film_m, heights_m, tau0: float, floor_m: float) -> np.ndarray:
    """⟨τ0 asinh(η u_s/(τ0 max(h̄ + z, h_b)))⟩ over the equal-probability heights z [m] (Eyring Couette stress of
    the gaps of a rough film of mean gap h̄ [m]; gaps below h_b floored at it) [Pa], one value per (η, h̄) node.
    Where the Eyring argument is above :data:`SATURATED_EYRING_ARGUMENT` or below :data:`NEWTONIAN_EYRING_ARGUMENT` in
    every gap, series of asinh with moments of the gaps (relative error below 4e-13, :func:`_mean_asinh_over_gaps`)."""
    eta, film = (np.ravel(v) for v in np.broadcast_arrays(np.asarray(eta, dtype=float),
                                                           np.asarray(film_m, dtype=float)))
    gap = np.maximum(film[:, None] + np.asarray(heights_m, dtype=float)[None, :], floor_m)
    if u_s == 0.0:
        return np.zeros(eta.size)
    mean = _mean_asinh_over_gaps((eta * (abs(u_s) / tau0))[:, None], gap)[:, 0]
    return math.copysign(tau0, u_s) * mean


def fluctuation_averaged_shear_stress(viscosity, p_mean, pressure_std: float, u_s: float, film_m, heights_m,
                                      tau0: float, floor_m: float, block: int = 64) -> np.ndarray:
    """⟨τ0 asinh(η(p) u_s/(τ0 max(h̄ + z, h_b)))⟩ over the gap heights z [m] and, independently, the pressures p of a
    gamma distribution of mean p̄ and standard deviation σ_p = ``pressure_std`` [Pa]
    (:func:`ehl_dataset.model.micro_pressure.gamma_pressure_quantiles`) [Pa], one value per (p̄, h̄) node;
    ``viscosity`` η(p) [Pa s] of an array of pressures [Pa]. σ_p = 0 gives :func:`gap_averaged_shear_stress`. Where
    the Eyring argument is above :data:`SATURATED_EYRING_ARGUMENT` or below :data:`NEWTONIAN_EYRING_ARGUMENT` in every
    gap of a pressure level, series of asinh with moments of the gaps (relative error below 4e-13)."""
    if pressure_std <= 0.0:
        return gap_averaged_shear_stress(viscosity(p_mean), u_s, film_m, heights_m, tau0, floor_m)
    p_mean = np.asarray(p_mean, dtype=float)
    film = np.asarray(film_m, dtype=float)
    heights = np.asarray(heights_m, dtype=float)
    if u_s == 0.0:
        return np.zeros(p_mean.size)
    out = np.empty(p_mean.size)
    for start in range(0, p_mean.size, block):
        nodes = slice(start, start + block)
        pressures = gamma_pressure_quantiles(p_mean[nodes], pressure_std)
        eta = np.asarray(viscosity(pressures.ravel()), dtype=float).reshape(pressures.shape)
        gap = np.maximum(film[nodes, None] + heights[None, :], floor_m)
        out[nodes] = _mean_asinh_over_gaps(eta * (abs(u_s) / tau0), gap).mean(axis=1)
    return math.copysign(tau0, u_s) * out


def _thermal_ratio(case: ContactCase, state: LubricantState, x_m, p_pa, film_m, liquid
                   ) -> tuple[ThermalTraction, np.ndarray]:
    """The thermal correction of the traction (:func:`ehl_dataset.model.thermal.thermal_couette_traction`: shear
    heating of the film and flash temperature of the surfaces) for a smooth film of the model's mean film ``film_m``
    [m] on the smooth solve's nodes, and the node-wise ratio thermal / isothermal Couette stress (1 where the film
    carries no shear) that scales the gap-averaged stress."""
    thermal = thermal_couette_traction(x_m, film_m, state.temperature_table(p_pa), liquid, case.u1, case.u2,
                                       state.tau0, state.thermal)
    isothermal = eyring_shear_stress(state.viscosity(p_pa), case.u_s, np.maximum(film_m, 1e-300), state.tau0)
    ratio = np.ones_like(isothermal)
    sheared = liquid & (np.abs(isothermal) > 0.0)
    ratio[sheared] = thermal.shear_stress[sheared] / isothermal[sheared]
    return thermal, ratio


def continuous_outside_film(x_m, smooth_film_m, zone, zone_film_m) -> np.ndarray:
    """The mean film outside the film-law zone that joins the zone's film without a step.

    The smooth solve's film shifted by the zone's excess at the nearer zone edge, h_s(x) + h̄(±ea) − h_s(±ea): the
    rough surfaces' mean lines held apart by the same extra distance as at the zone edge (module docstring).

    Parameters
    ----------
    x_m : array_like
        Nodes of the smooth solve [m].
    smooth_film_m : array_like
        Smooth film h_s on the nodes [m].
    zone : array_like of bool
        Mask of the zone's nodes (contiguous) [-].
    zone_film_m : array_like
        Film-law film h̄ on the zone's nodes [m].

    Returns
    -------
    numpy.ndarray
        The shifted film on every node (inside the zone the values are h_s shifted by the outlet excess and unused)
        [m].
    """
    x_m, h_s = np.asarray(x_m, dtype=float), np.asarray(smooth_film_m, dtype=float)
    inside = np.flatnonzero(zone)
    inlet_shift = float(zone_film_m[0] - h_s[inside[0]])
    outlet_shift = float(zone_film_m[-1] - h_s[inside[-1]])
    return h_s + np.where(x_m < 0.0, inlet_shift, outlet_shift)


def pressure_spread(profile: RoughnessProfile, case: ContactCase, state: LubricantState, inlet_over_beta: float,
                    micro_pressure_coefficient: float | None, fluctuations: str) -> tuple[float, float | None, float]:
    """(c, Δq, σ_p [Pa]) of the micro-EHL pressure spread σ_p = c·E'Δq/4: c as given, else the ``inlet`` form's
    c(L_in/β) (:func:`~ehl_dataset.model.micro_pressure.micro_pressure_coefficient`) or the ``spectral`` form's
    σ_p = E'Δq_f/4 (:func:`~ehl_dataset.model.micro_pressure.spectral_pressure_std`, c = Δq_f/Δq). Δq is None where
    c = 0 (not computed)."""
    if micro_pressure_coefficient is None and fluctuations == "spectral":
        slope_rms = composite_slope_rms(profile, case.rq1, case.rq2)
        pressure_std, flattened = spectral_pressure_std(profile, case, state)
        return (flattened / slope_rms if slope_rms > 0.0 else 0.0), slope_rms, pressure_std
    coefficient = (inlet_micro_pressure_coefficient(inlet_over_beta) if micro_pressure_coefficient is None
                   else micro_pressure_coefficient)
    if coefficient <= 0.0:
        return coefficient, None, 0.0
    slope_rms = composite_slope_rms(profile, case.rq1, case.rq2)
    return coefficient, slope_rms, coefficient * flattening_pressure_rms(case.e_reduced, slope_rms)


def solve_film_law(case: ContactCase, state: LubricantState, lvl: AccuracyLevel, plan: Effects,
                   roughness: RoughnessProfile | None, boundary_film_m: float,
                   edge: float = WideOptions.edge, micro_pressure_coefficient: float | None = None,
                   continuous_film: bool | None = None, fluctuations: str = DEFAULT_FLUCTUATIONS) -> ContactResult:
    """Film-law homogenised solve of a rough contact (module docstring) on the level's steady grid.

    ``boundary_film_m`` h_b [m], the floor of the micro gaps in the Eyring shear; ``edge`` the half width of the
    film-law zone [a]; ``micro_pressure_coefficient`` c of the pressure-fluctuation closure σ_p = c·E'Δq/4
    (:mod:`ehl_dataset.model.micro_pressure`; None: :func:`~ehl_dataset.model.micro_pressure.micro_pressure_coefficient`
    of the contact's inlet length L_in/β, 0 turns the closure off); ``fluctuations`` the form of σ_p where no c is
    given (:data:`~ehl_dataset.names.FLUCTUATIONS`: ``inlet`` the calibrated c(L_in/β), ``spectral``
    :func:`~ehl_dataset.model.micro_pressure.spectral_pressure_std`, recorded as c = Δq_f/Δq); ``continuous_film`` whether the rolling term
    outside the zone takes the film that joins the zone's without a step (:func:`continuous_outside_film`) instead of
    the smooth film (None: on a point-like contact, a/β below
    :data:`~ehl_dataset.solvers.levels.POINT_CONTACT_A_OVER_BETA`; module docstring). The smooth case (S_c = 0) is the
    caller's (it returns the smooth solution)."""
    start = time.perf_counter()
    check_range("edge", edge, 0.1, 1.0)
    if micro_pressure_coefficient is not None:
        check_range("micro_pressure_coefficient", micro_pressure_coefficient, 0.0, 1.0)
    if fluctuations not in FLUCTUATIONS:
        raise InputError("fluctuations", fluctuations, f"one of {list(FLUCTUATIONS)}")
    profile = roughness if roughness is not None else default_profile()
    heights = composite_height_quantiles(profile, case.rq1, case.rq2)
    smooth_plan = Effects(False, False, plan.shear_thinning, plan.compressibility, plan.mode, {})
    smooth = solve_steady(case, state, lvl, smooth_plan)
    _, lambda_bar = dowson_higginson_lambda(case, state)
    a, sigma = case.half_width, case.s_c
    a_over_beta = a / profile.correlation_length
    x_m, p_s, h_s = smooth.x, smooth.pressure, smooth.film
    centre = np.abs(x_m / a) < CENTRE_BAND
    h_smooth_centre = float(np.mean(h_s[centre]))
    inlet_over_beta = inlet_length(case, h_smooth_centre) / profile.correlation_length
    h_centre = fed_central_film(h_smooth_centre, sigma, inlet_over_beta)
    rho_centre = float(state.density(float(np.mean(p_s[centre]))))

    zone = np.abs(x_m) <= edge * a
    xz, pz = x_m[zone], p_s[zone]
    film = h_centre * rho_centre / np.asarray(state.density(pz), dtype=float)
    coefficient, slope_rms, pressure_std = pressure_spread(profile, case, state, inlet_over_beta,
                                                           micro_pressure_coefficient, fluctuations)
    shear = fluctuation_averaged_shear_stress(state.viscosity, pz, pressure_std, case.u_s, film, heights,
                                              state.tau0, boundary_film_m)
    rolling = 0.5 * film * np.gradient(p_s, x_m)[zone]
    liquid = full_film_mask(p_s)
    couette_outside = eyring_shear_stress(state.viscosity(p_s), case.u_s, np.maximum(h_s, 1e-300), state.tau0)
    thermal_extra = {}
    if plan.thermal:
        thermal, ratio = _thermal_ratio(case, state, x_m, p_s, np.where(zone, np.interp(x_m, xz, film), h_s), liquid)
        shear_isothermal, couette_isothermal = shear, couette_outside
        shear, couette_outside = shear * ratio[zone], thermal.shear_stress
        thermal_extra = {"summary": thermal.summary(), "converged": thermal.converged}
    if continuous_film is None:
        continuous_film = a_over_beta < POINT_CONTACT_A_OVER_BETA
    outside_film = continuous_outside_film(x_m, h_s, zone, film) if continuous_film else h_s
    outside_stress = np.where(liquid, couette_outside + 0.5 * outside_film * np.gradient(p_s, x_m), 0.0)
    load = case.load_per_length

    def integral(f):
        return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(xz)))

    outside = _integral_outside(x_m, outside_stress, edge * a)
    parts = {"mu_couette": integral(shear) / load, "mu_poiseuille": integral(rolling) / load,
             "mu_outside_zone": outside / load}
    if plan.thermal:
        outside_isothermal = _integral_outside(
            x_m, np.where(liquid, couette_isothermal + 0.5 * outside_film * np.gradient(p_s, x_m), 0.0), edge * a)
        thermal_extra["zone_couette_isothermal"] = integral(shear_isothermal)
        thermal_extra["mu_isothermal"] = (thermal_extra["zone_couette_isothermal"] + integral(rolling)
                                          + outside_isothermal) / load
    mu = sum(parts.values())
    converged = bool(smooth.converged) and bool(np.all(np.isfinite([mu, *film])))
    thermal_failed = bool(thermal_extra) and not thermal_extra["converged"]
    warnings = []
    if a_over_beta < WIDE_A_OVER_BETA:
        warnings.append(f"narrow contact (a/β = {a_over_beta:.1f} < {WIDE_A_OVER_BETA:g}): micro-EHL pressure-"
                        f"fluctuation closure c = {coefficient:.3g} (L_in/β = {inlet_over_beta:.3g}), sigma_p = "
                        f"{pressure_std / 1e9:.3g} GPa; its measured range is the planner's (docs/explanation/mixed-regime.md)")
    extrapolated = film_law_extrapolation(h_smooth_centre, sigma, inlet_over_beta)
    if extrapolated:
        warnings.append(f"film law extrapolated ({extrapolated})")
    if thermal_failed:
        converged = False
        message = "not converged: thermal correction of the traction did not converge"
    elif not converged:
        message = f"not converged: {smooth.message}" if not smooth.converged else "not converged: non-finite traction"
    else:
        message = "; ".join(["converged", *warnings])
    recorded = plan.to_dict()
    recorded["reasons"] = dict(recorded.get("reasons") or {})
    recorded["reasons"]["model"] = ("homogenised mixed EHL (film-law closure: smooth pressure, measured film law, "
                                    "gap-averaged Eyring traction)")
    recorded["roughness"], recorded["transient"] = True, False
    return ContactResult(
        mu=float(mu), h_min=float(np.min(film)), h_central=float(np.interp(0.0, xz, film)),
        p_max=float(np.max(p_s)), converged=converged, iterations=int(smooth.iterations),
        wall_time=time.perf_counter() - start, level=lvl.name, effects=recorded, lambda_bar=lambda_bar,
        asperity_load_share=0.0, residuals=dict(smooth.residuals), message=message, x=xz,
        pressure=pz, film=film,
        extra={"model": "homogenised", "closure": "film_law", "model_version": FILM_LAW_MODEL_VERSION,
               "wide_model_version": WIDE_MODEL_VERSION, "n_nodes": int(x_m.size), **parts,
               "film_law": {"c": FILM_LAW_C, "d": FILM_LAW_D, "k": FILM_LAW_K}, "a_over_beta": a_over_beta,
               "fed_central_film_m": h_centre, "smooth_central_film_m": h_smooth_centre,
               "inlet_over_beta": inlet_over_beta, "film_law_extrapolated": extrapolated,
               "narrow_contact": a_over_beta < WIDE_A_OVER_BETA, "smooth_mu": smooth.mu,
               "rolling_film_outside": "continuous" if continuous_film else "smooth",
               **({"thermal": {**thermal_extra["summary"], "mu_isothermal": thermal_extra["mu_isothermal"],
                               "zone_couette_isothermal_n_per_m": thermal_extra["zone_couette_isothermal"],
                               "properties": state.thermal.to_dict()}} if thermal_extra else {}),
               "smooth_h_min_m": smooth.h_min, "boundary_film_m": boundary_film_m, "zone_edge": edge,
               "micro_pressure": {"form": fluctuations if micro_pressure_coefficient is None else "given",
                                  "coefficient": coefficient, "slope_rms": slope_rms, "std_pa": pressure_std},
               "profile_sha256": profile_hash(profile),
               "floored_gap_fraction_max": float(np.mean(film[:, None] + heights[None, :] < boundary_film_m,
                                                          axis=1).max()), **profile_record(profile),
               "roughness_windows": {key: getattr(windows_that_fit(profile), key)
                                     for key in ("n_windows", "window_correlation_lengths")}},
    )
