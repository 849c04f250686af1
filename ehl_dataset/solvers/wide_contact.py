"""Wide rough contacts in the deterministic model: periodic windows across the Hertzian zone, fed by the measured
film law (docs/explanation/mixed-regime.md, "Wide contacts").

A contact many correlation lengths β wide cannot be resolved for the thousands of time steps a time average needs
(a/β up to ≈ 250 in the paper's factorial). Its Hertzian zone is a statistically homogeneous micro-scale inside a
smooth macro-contact, so the local mean state at a point x of the zone is that of a periodic window
(:mod:`ehl_dataset.solvers.periodic_window`) at the local mean pressure p̄(x) holding the local lubricant content.
Two macro quantities feed the windows:

* p̄(x): the steady smooth solve's pressure (the roughness leaves the mean pressure of the Hertzian zone Hertzian;
  measured on the resolved case V1, docs/explanation/mixed-regime.md);
* the lubricant content: at the centre the measured film law of resolved rough contacts,

      h̄_c = h_s + σ·c·(L_in/β)^k/(h_s/σ + d),      c, d, k = FILM_LAW_C, FILM_LAW_D, FILM_LAW_K,

  (h_s the smooth central film, σ = √(Rq1² + Rq2²), L_in = a·(h_s r_eq/a²)^(2/3) the length of the smooth inlet
  build-up zone, β the correlation length; ``python validation/deterministic_film_law.py``, fitted on resolved runs
  of the shipped profile: the more correlation lengths the inlet spans, the more lubricant the valleys carry in);
  across the zone the mean flux of a Couette-dominated film is constant, so h̄(x) = h̄_c ρ(p̄_c)/ρ(p̄(x)) (within
  3 % on the resolved case V1).

μ = [Σ w_i τ̄_i + ∫_{|x| > e·a} τ_s dx] / W': the windows' mean shear stress τ̄ (fluid shear + μ_d p_c) at the
Gauss–Legendre points of |x| < e·a, and outside that zone the smooth solve's local shear stress (Eyring Couette +
rolling part, paper Eq. 7). Its standard error combines the windows' errors; the film law's own scatter is reported
in ``extra`` (its effect on μ is measured in the docs, not included in ``mu_sem``).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import trapezoid

from ..model.contact import ContactCase
from ..model.effects import Effects
from ..model.lubricant import LubricantState
from ..model.roughness import RoughnessProfile, default_profile, profile_record
from ..model.traction import eyring_shear_stress, full_film_mask
from ..validation import InputError, check_range
from .deterministic import MODEL_VERSION, BOUNDARY_FILM_M, DeterministicOptions, grid_spacing, solve_deterministic
from .levels import WIDE_A_OVER_BETA, get_level
from .periodic_window import WindowOptions, solve_window
from .result import ContactResult
from .steady import dowson_higginson_lambda, solve_steady

WIDE_MODEL_VERSION = "wide-2026.11-1"
"""Version of the wide-contact route (film law, window layout); recorded next to the deterministic model version."""

FILM_LAW_C = 0.378
FILM_LAW_D = 0.364
FILM_LAW_K = 0.444
"""Film law Δ/σ = c·(L_in/β)^k/(H + d), H = h_s/σ: least-squares fit over resolved deterministic runs
(``python validation/deterministic_film_law.py``; points, residuals and leave-one-group-out errors in
validation/results/deterministic_film_law.json)."""
FILM_LAW_RANGE = {"H": (0.13, 5.4), "inlet_over_beta": (1.1, 4.3)}
"""The range of H and L_in/β the law was fitted over; outside it the result says the law was extrapolated."""

CENTRE_BAND = 0.2
"""Half width [a] of the central band over which the smooth film h_s is averaged (as in the law's fit)."""

def inlet_length(case: ContactCase, smooth_film_m: float) -> float:
    """L_in = a·(h_s r_eq/a²)^(2/3) [m]: the length over which a smooth EHL inlet builds its pressure (the
    heavy-load inlet scaling of the dimensionless central film; Moes 1992, as in the solvers' grid rules)."""
    a = case.half_width
    return a * (smooth_film_m * case.r_eq / a**2) ** (2.0 / 3.0)


def fed_central_film(smooth_film_m: float, sigma_m: float, inlet_over_beta: float, offset_sigma: float = 0.0) -> float:
    """Mean content film [m] of the Hertzian centre of a rough contact from the smooth central film [m], the
    composite roughness σ [m] and the inlet length in correlation lengths L_in/β (the film law of the module
    docstring), plus ``offset_sigma``·σ (the law's scatter, for sensitivity studies)."""
    check_range("smooth_film_m", smooth_film_m, 0.0, 1e-3, low_inclusive=False, unit="m")
    check_range("sigma_m", sigma_m, 0.0, 1e-4, unit="m")
    check_range("inlet_over_beta", inlet_over_beta, 0.0, 1e6, low_inclusive=False)
    check_range("offset_sigma", offset_sigma, -1.0, 1.0)
    if sigma_m == 0.0:
        return float(smooth_film_m)
    excess = FILM_LAW_C * inlet_over_beta**FILM_LAW_K / (smooth_film_m / sigma_m + FILM_LAW_D) + offset_sigma
    return float(smooth_film_m + sigma_m * excess)


def film_law_extrapolation(smooth_film_m: float, sigma_m: float, inlet_over_beta: float) -> str:
    """'' inside the law's fitted range (:data:`FILM_LAW_RANGE`), else which variable is outside it."""
    values = {"H": smooth_film_m / sigma_m if sigma_m > 0.0 else math.inf, "inlet_over_beta": inlet_over_beta}
    outside = [f"{k} = {v:.3g} outside {FILM_LAW_RANGE[k][0]:g}–{FILM_LAW_RANGE[k][1]:g}"
               for k, v in values.items() if not FILM_LAW_RANGE[k][0] <= v <= FILM_LAW_RANGE[k][1]]
    return "; ".join(outside)


@dataclass(frozen=True)
class WideOptions:
    """``points`` Gauss–Legendre windows in |x| < ``edge``·a; ``window`` their options (length, grid, time step);
    ``film_offset_sigma`` added to the film law's excess Δ/σ (0: the law; ± its scatter for a sensitivity study)."""

    points: int = 5
    edge: float = 0.9
    film_offset_sigma: float = 0.0
    window: WindowOptions = field(default_factory=lambda: WindowOptions(length_beta=8.0, points_per_beta=16.0))

    def __post_init__(self):
        check_range("points", self.points, 1, 20)
        check_range("edge", self.edge, 0.1, 1.0)
        check_range("film_offset_sigma", self.film_offset_sigma, -1.0, 1.0)
        if not isinstance(self.window, WindowOptions):
            raise InputError("window", type(self.window).__name__, "a WindowOptions")


def smooth_shear_stress(x_m, pressure_pa, film_m, state: LubricantState, u_s: float) -> np.ndarray:
    """Local shear stress [Pa] of a smooth film: Eyring Couette stress + (h/2)∂p/∂x where the film is full (paper
    Eq. 7), zero in the cavitated zone."""
    film = full_film_mask(pressure_pa)
    h = np.maximum(film_m, 1e-300)
    stress = eyring_shear_stress(state.viscosity(pressure_pa), u_s, h, state.tau0) + 0.5 * h * np.gradient(
        pressure_pa, x_m)
    return np.where(film, stress, 0.0)


def _integral_outside(x_m, f, half_zone_m: float) -> float:
    """∫ f dx over |x| > half_zone_m (trapezoid on the nodes with the zone edges inserted)."""
    x = np.union1d(x_m, [-half_zone_m, half_zone_m])
    g = np.interp(x, x_m, f)
    total = 0.0
    for part in (x <= -half_zone_m, x >= half_zone_m):
        if part.sum() > 1:
            total += float(trapezoid(g[part], x[part]))
    return total


def solve_wide(case: ContactCase, state: LubricantState, plan: Effects, options: WideOptions = WideOptions(),
               roughness: RoughnessProfile | None = None, time_limit_s: float | None = None,
               level_name: str = "reference", deterministic_version: str = "") -> ContactResult:
    """The deterministic model of a wide rough contact by periodic windows (module docstring)."""
    start = time.perf_counter()
    if case.s_c == 0.0:
        raise InputError("rq1, rq2", (case.rq1, case.rq2), "a rough case for the wide-contact route")
    profile = roughness if roughness is not None else default_profile()
    smooth_plan = Effects(False, False, plan.shear_thinning, plan.compressibility, plan.mode, {})
    smooth = solve_steady(case, state, get_level("standard"), smooth_plan)
    a = case.half_width
    _, lambda_bar = dowson_higginson_lambda(case, state)
    recorded = plan.to_dict()
    recorded["reasons"] = dict(recorded.get("reasons") or {})
    recorded["roughness"] = recorded["transient"] = True  # every window time-steps its moving roughness
    recorded["reasons"]["model"] = (
        f"deterministic mixed EHL by {options.points} periodic windows across the Hertzian zone (a/β = "
        f"{a / profile.correlation_length:.0f}), fed the smooth pressure and the film law")
    extra = {"model": "deterministic", "route": "wide", "wide_model_version": WIDE_MODEL_VERSION,
             "model_version": deterministic_version, "film_law": {"c": FILM_LAW_C, "d": FILM_LAW_D,
                                                                   "k": FILM_LAW_K,
                                                                   "offset_sigma": options.film_offset_sigma},
             "a_over_beta": a / profile.correlation_length, "smooth_mu": smooth.mu, "smooth_h_min_m": smooth.h_min,
             **profile_record(profile)}
    if not smooth.converged:
        return _failed(case, plan, recorded, level_name, start, lambda_bar, f"smooth start: {smooth.message}", extra)
    x_m, p_s, h_s = smooth.x, smooth.pressure, smooth.film
    centre = np.abs(x_m / a) < CENTRE_BAND
    sigma = case.s_c
    h_smooth_centre = float(np.mean(h_s[centre]))
    inlet_over_beta = inlet_length(case, h_smooth_centre) / profile.correlation_length
    h_centre = fed_central_film(h_smooth_centre, sigma, inlet_over_beta, options.film_offset_sigma)
    extrapolated = film_law_extrapolation(h_smooth_centre, sigma, inlet_over_beta)
    rho_centre = float(state.density(float(np.mean(p_s[centre]))))
    nodes, weights = np.polynomial.legendre.leggauss(options.points)
    positions, weights = options.edge * nodes * a, options.edge * weights * a
    windows, inside, variance, share = [], 0.0, 0.0, 0.0
    converged, message = True, "converged"
    for position, weight in zip(positions, weights):
        p_bar = float(np.interp(position, x_m, p_s))
        film = h_centre * rho_centre / float(state.density(p_bar))
        remaining = None
        if time_limit_s is not None:
            remaining = time_limit_s - (time.perf_counter() - start)
            if remaining <= 0.0:
                converged, message = False, f"wall-time limit of {time_limit_s:g} s reached before window " \
                                            f"{len(windows) + 1} of {options.points}"
                break
        window = solve_window(case, state, p_bar, film, options.window, profile, remaining)
        windows.append({"x_m": float(position), "mean_pressure_pa": p_bar, "fed_film_m": film,
                        "shear_stress_pa": window.shear_stress_pa, "mu_local": window.mu_local,
                        "mu_local_sem": window.mu_local_sem, "asperity_share": window.asperity_share,
                        "content_film_m": window.content_film_m, "min_film_m": window.min_film_m,
                        "converged": window.converged, "message": window.message,
                        "wall_time_s": window.wall_time_s, "n_nodes": window.n_nodes, "n_steps": window.n_steps})
        if not window.converged:
            converged, message = False, f"not converged: window at x = {position / a:+.2f} a: {window.message}"
            break
        inside += weight * window.shear_stress_pa
        variance += (weight * window.mu_local_sem * p_bar) ** 2
        share += weight * window.asperity_share * p_bar
    extra["windows"] = windows
    if not converged:
        return _failed(case, plan, recorded, level_name, start, lambda_bar, message, extra)
    load = case.load_per_length
    outside = _integral_outside(x_m, smooth_shear_stress(x_m, p_s, h_s, state, case.u_s), options.edge * a)
    mu = (inside + outside) / load
    zone = np.abs(x_m) <= a
    mean_film = h_centre * rho_centre / np.asarray(state.density(p_s[zone]), dtype=float)
    if extrapolated:
        message = f"converged; film law extrapolated ({extrapolated})"
    extra.update({"mu_outside_zone": outside / load, "fed_central_film_m": h_centre,
                  "inlet_over_beta": inlet_over_beta, "film_law_extrapolated": extrapolated,
                  "smooth_central_film_m": h_smooth_centre,
                  "n_nodes": sum(w["n_nodes"] for w in windows), "n_steps": sum(w["n_steps"] for w in windows),
                  "dx_m": profile.resolution_length / options.window.points_per_beta})
    return ContactResult(
        mu=float(mu), h_min=float(np.min(mean_film)), h_central=float(np.interp(0.0, x_m[zone], mean_film)),
        p_max=float(np.max(p_s)), converged=True, iterations=0, wall_time=time.perf_counter() - start,
        level=level_name, effects=recorded, mu_sem=math.sqrt(variance) / load, lambda_bar=lambda_bar,
        asperity_load_share=share / load, residuals={}, message=message, x=x_m[zone], pressure=p_s[zone], film=mean_film,
        extra=extra)


def takes_windows(case: ContactCase, profile: RoughnessProfile, options: DeterministicOptions) -> bool:
    """Whether a deterministic run of ``case`` goes by windows (``options.wide``; module docstring)."""
    if options.wide == "windows":
        return True
    return (options.wide == "auto" and options.dx_m is None and case.s_c > 0.0
            and case.half_width / profile.correlation_length > WIDE_A_OVER_BETA)


def wide_options(case: ContactCase, profile: RoughnessProfile, options: DeterministicOptions) -> WideOptions:
    """The window layout of a wide run from the deterministic options: the whole-contact grid rule without the inlet
    term (or ``dx_m``), the same time step, Newton and face options."""
    h_b_m = options.boundary_film_m if options.boundary_film_m is not None else BOUNDARY_FILM_M
    dx_m = options.dx_m if options.dx_m is not None else grid_spacing(profile, case.rq1, case.rq2, h_b_m, options)[0]
    window = WindowOptions(length_beta=options.window_length_beta, points_per_beta=profile.resolution_length / dx_m,
                           courant=options.courant, boundary_film_m=options.boundary_film_m,
                           yield_pressure_pa=options.yield_pressure_pa, newton_tolerance=options.newton_tolerance,
                           max_substeps=options.max_substeps, face_mean=options.face_mean,
                           couette_flux=options.couette_flux, band=options.band, clock=options.clock)
    return WideOptions(points=options.wide_windows, window=window)


def solve_deterministic_contact(case: ContactCase, state: LubricantState, plan: Effects,
                                options: DeterministicOptions, roughness: RoughnessProfile | None = None,
                                time_limit_s: float | None = None, level_name: str = "reference",
                                checkpoint=None) -> ContactResult:
    """The deterministic model on any contact: the whole contact resolved
    (:func:`~ehl_dataset.solvers.deterministic.solve_deterministic`) or, for a wide one, windows fed by the film law
    (:func:`solve_wide`), as ``options.wide`` says. ``checkpoint`` (a resolved contact only): the saved state a long
    run continues from (:func:`~ehl_dataset.solvers.deterministic.solve_deterministic`)."""
    profile = roughness if roughness is not None else default_profile()
    if takes_windows(case, profile, options):
        if checkpoint is not None:
            raise InputError("checkpoint", str(getattr(checkpoint, "path", checkpoint)),
                             "None for a wide contact solved by windows (a checkpoint holds one resolved run: "
                             "wide='resolve' solves the whole contact)")
        return solve_wide(case, state, plan, wide_options(case, profile, options), profile, time_limit_s, level_name,
                          MODEL_VERSION)
    return solve_deterministic(case, state, plan, options, roughness, time_limit_s, level_name, checkpoint=checkpoint)


def _failed(case, plan, recorded, level_name, start, lambda_bar, message, extra) -> ContactResult:
    nan = math.nan
    return ContactResult(mu=nan, h_min=nan, h_central=nan, p_max=nan, converged=False, iterations=0,
                         wall_time=time.perf_counter() - start, level=level_name, effects=recorded,
                         lambda_bar=lambda_bar, message=message, extra=extra)


