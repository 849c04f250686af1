"""A periodic window of a wide rough contact at given local mean conditions: the deterministic model of
:mod:`ehl_dataset.solvers.deterministic` on one period of length L (many correlation lengths β, a few per cent of
a wide contact), loaded with a mean pressure p̄ and holding a mean lubricant content ρ̄(p̄)·h̄ (docs/
explanation/mixed-regime.md).

Where a line contact is many correlation lengths wide, the roughness is a statistically homogeneous micro-scale
inside a macro-contact whose mean pressure and mean film vary on the scale a ≫ β. Around a point of the Hertzian
zone the local state is then that of a periodic cell: the same equations (paper Eq. 1–8 with the contact
complementarity, mass-conserving cavitation, only the fluid pressure driving flow), the two roughness profiles
moving through it with their surfaces, the deflection of the periodic pressure (its mean belongs to the film
constant), the mean total pressure held at p̄ by the film constant H0 — and, with no inlet or outlet, the lubricant
content of the window conserved exactly: it stays what it was at the start, ρ̄(p̄)·h̄ per unit length. What the
window cannot give by itself is h̄: in the contact it is set by the flux the inlet delivers, so the caller supplies
it (from a resolved run, a macro model, or a sweep of h̄).

Outputs are local means per unit area: the shear stress τ̄ = ⟨θ τ_Eyring + (h/2)∂p_f/∂x⟩ + μ_d ⟨p_c⟩ sign(u_s)
[Pa] and μ_local = τ̄/p̄, the asperity share ⟨p_c⟩/p̄, the mean film and content, their time averages with
autocorrelation-corrected standard errors (:mod:`ehl_dataset.solvers.time_average`).

Each roughness profile is a stretch of length L of the case's profile made periodic (its end-to-end trend removed,
scaled back to its Rq), moving at its surface speed and read periodically.
"""

from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ..model.contact import ContactCase
from ..model.lubricant import LubricantState
from ..model.roughness import SEGMENT_GAP_CORRELATION_LENGTHS, RoughnessProfile, default_profile
from ..validation import InputError, check_range
from .deterministic import (BOUNDARY_FILM_M, COURANT, YIELD_PRESSURE_PA, DeterministicOptions, MixedProblem,
                            _advance, local_shear_stress)
from .steady import ContactScales
from .time_average import time_mean


RETRY_NEWTON_ITERATIONS = 50
"""Newton iterations of the second attempt at a step that failed with ``WindowOptions.newton_iterations`` at every
sub-step split (the whole-contact solver's default)."""


@dataclass(frozen=True)
class WindowOptions:
    """``length_beta`` window length L in correlation lengths; ``points_per_beta`` grid points per resolution
    length of the profile (its correlation length for a Gaussian-ACF profile, its short cut-off wavelength for a
    band-limited one: :attr:`~ehl_dataset.model.roughness.RoughnessProfile.resolution_length`); ``courant`` u_r Δt/Δx;
    ``ramp_passes`` the roughness amplitude grows from 0 to 1 over this many passes (one pass: L at u_r);
    ``startup_passes`` after the ramp before averaging; ``average_passes`` the averaging window, at least
    ``relative_periods`` periods L/|u_s| of the relative motion of the two surfaces when they slide, at most
    ``max_passes`` in all; ``boundary_film_m`` h_b (None: :data:`~ehl_dataset.solvers.deterministic.BOUNDARY_FILM_M`);
    ``yield_pressure_pa`` the contact-pressure cap; the Newton and face options as in
    :class:`~ehl_dataset.solvers.deterministic.DeterministicOptions`, except ``newton_iterations`` (15, not 50):
    in the Hertzian zone colliding asperities make a third of the full steps fail, and a Newton solve that has not
    converged in 15 iterations is cheaper to split into sub-steps (measured on W1's centre, 16 β at β/8, 256
    steps: 97 s with 50, 55 s with 25, 39 s with 15, 29 s with 10 iterations); a step that fails at every split
    is tried once more with :data:`RETRY_NEWTON_ITERATIONS` (counted in ``series["retried_steps"]``)."""

    length_beta: float = 16.0
    points_per_beta: float = 16.0
    courant: float = COURANT
    ramp_passes: float = 0.5
    startup_passes: float = 1.0
    average_passes: float = 4.0
    relative_periods: float = 1.0
    max_passes: float = 40.0
    boundary_film_m: float | None = None
    yield_pressure_pa: float = YIELD_PRESSURE_PA
    newton_tolerance: float = 1e-10
    newton_iterations: int = 15
    max_substeps: int = 32
    face_mean: str = "kirchhoff"
    couette_flux: str = "minmod"
    band: int = 12
    clock: Callable[[], float] = field(default=time.perf_counter, compare=False)

    def __post_init__(self):
        check_range("length_beta", self.length_beta, 2.0, 1000.0)
        check_range("points_per_beta", self.points_per_beta, 2.0, 256.0)
        check_range("courant", self.courant, 0.0, 8.0, low_inclusive=False)
        check_range("average_passes", self.average_passes, 0.0, 1000.0, low_inclusive=False)
        check_range("max_passes", self.max_passes, 1.0, 10000.0)

    def numerics(self) -> DeterministicOptions:
        """The Newton and time-step rules in the form :func:`~ehl_dataset.solvers.deterministic._advance` reads."""
        return DeterministicOptions(courant=self.courant, newton_tolerance=self.newton_tolerance,
                                    newton_iterations=self.newton_iterations, max_substeps=self.max_substeps,
                                    face_mean=self.face_mean, couette_flux=self.couette_flux, band=self.band)


@dataclass
class WindowResult:
    """Time-averaged local state of a window (SI): ``mu_local`` τ̄/p̄ and ``mu_local_sem``; ``shear_stress_pa`` τ̄;
    ``asperity_share`` ⟨p_c⟩/p̄ and its standard error; ``mean_film_m`` ⟨h⟩ and ``content_film_m`` ⟨θ max(h, h_b)⟩
    (the lubricant per unit area over ρ̄, conserved); ``min_film_m`` the time-averaged minimum film;
    ``converged`` False with ``message`` when a step failed; ``series`` the per-step records (those above, the
    dimensionless lubricant content Σ w ρ̄θ max(H, H_b) of the window, which the discrete equations conserve, and
    the relative error of the mean total pressure)."""

    mu_local: float
    mu_local_sem: float
    shear_stress_pa: float
    asperity_share: float
    asperity_share_sem: float
    mean_film_m: float
    content_film_m: float
    min_film_m: float
    converged: bool
    message: str
    wall_time_s: float
    n_nodes: int
    n_steps: int
    dx_m: float
    length_m: float
    mean_pressure_pa: float
    series: dict = field(default_factory=dict, repr=False)


def periodic_stretch(profile: RoughnessProfile, start_m: float, length_m: float, rq_m: float):
    """(ξ [m], z [m]) of the stretch [start, start + L) of ``profile`` made periodic over L: the straight line
    through its two ends removed (so that z(L) = z(0)), the mean removed, scaled to Rq = ``rq_m``; read it with
    ``np.interp(x, ξ, z, period=L)``."""
    samples = int(round(length_m / profile.spacing))
    if samples < 4:
        raise InputError("length_m", length_m, f">= 4 profile samples ({4 * profile.spacing:.3g} m)")
    index = (int(round(start_m / profile.spacing)) + np.arange(samples + 1)) % profile.z.size
    z = profile.z[index].astype(float)
    z = z - (z[-1] - z[0]) * np.arange(samples + 1) / samples
    z = z[:-1] - np.mean(z[:-1])
    rms = math.sqrt(float(np.mean(z**2)))
    xi = np.arange(samples) * (length_m / samples)
    return xi, (z * (rq_m / rms) if rms > 0.0 else z)


def solve_window(case: ContactCase, state: LubricantState, mean_pressure_pa: float, mean_film_m: float,
                 options: WindowOptions = WindowOptions(), roughness: RoughnessProfile | None = None,
                 time_limit_s: float | None = None) -> WindowResult:
    """Solve the periodic window of ``case`` (speeds, roughness, Hertz scales) at the local mean pressure
    ``mean_pressure_pa`` [Pa] holding the lubricant of a smooth film ``mean_film_m`` [m] at that pressure (the
    content ρ̄(p̄)·h̄ per unit length, conserved). See the module docstring."""
    clock = options.clock
    start = clock()
    check_range("mean_pressure_pa", mean_pressure_pa, 0.0, 1e10, low_inclusive=False, unit="Pa")
    check_range("mean_film_m", mean_film_m, 0.0, 1e-3, low_inclusive=False, unit="m")
    if case.s_c == 0.0:
        raise InputError("rq1, rq2", (case.rq1, case.rq2), "a rough case (a smooth window is uniform)")
    profile = roughness if roughness is not None else default_profile()
    scales = ContactScales.of(case, state, True)
    a, beta = scales.a, profile.correlation_length
    length_m = options.length_beta * beta
    grid_per_beta = (options.points_per_beta if profile.grid_length_m is None  # Gaussian ACF: exactly as always
                     else options.points_per_beta * beta / profile.resolution_length)
    n = int(round(options.length_beta * grid_per_beta))
    dx_m = length_m / n
    h_b_m = options.boundary_film_m if options.boundary_film_m is not None else BOUNDARY_FILM_M
    x = np.arange(n) * (dx_m / a)
    p_bar = mean_pressure_pa / case.p_h
    problem = MixedProblem(x, scales, state, h_b_m / scales.film_scale, options.yield_pressure_pa / case.p_h,
                           True, options.face_mean, options.band, options.couette_flux, mean_pressure=p_bar)
    h0 = mean_film_m / scales.film_scale
    z = problem.pack(np.full(n, p_bar), np.ones(n), np.zeros(n), h0)
    flat = np.zeros(n)
    problem.m_ref = float(problem.content(z, problem.film(z, flat))[0])

    gap_between = SEGMENT_GAP_CORRELATION_LENGTHS * beta
    xi1, z1 = periodic_stretch(profile, 0.0, length_m, case.rq1)
    xi2, z2 = periodic_stretch(profile, length_m + gap_between, length_m, case.rq2)
    length_x = length_m / a
    d_t = options.courant * problem.dx
    steps_per_pass = length_x / d_t
    n_ramp = int(math.ceil(options.ramp_passes * steps_per_pass))
    first_average = n_ramp + int(math.ceil(options.startup_passes * steps_per_pass))
    sliding = abs(case.u_s) / case.u_r
    average = max(options.average_passes, options.relative_periods / sliding if sliding > 0 else 0.0)
    n_steps = min(first_average + int(math.ceil(average * steps_per_pass)),
                  int(math.ceil(options.max_passes * steps_per_pass)))
    u1, u2 = case.u1 / case.u_r, case.u2 / case.u_r  # in units of u_r (T = t u_r/a)

    def gap_at(t):
        amplitude = min(1.0, t / (n_ramp * d_t)) if n_ramp else 1.0
        r1 = np.interp((x - u1 * t) * a, xi1, z1, period=length_m)
        r2 = np.interp((x - u2 * t) * a, xi2, z2, period=length_m)
        return -amplitude * (r1 + r2) / scales.film_scale

    numerics = options.numerics()
    retry = dataclasses.replace(numerics, newton_iterations=RETRY_NEWTON_ITERATIONS)
    retried = 0
    record = {"t_s": [], "mu_local": [], "shear_stress_pa": [], "asperity_share": [], "mean_film_m": [],
              "content_film_m": [], "min_film_m": [], "lubricant_content": [], "mean_pressure_error": []}
    s = {"z": z, "m": problem.content(z, problem.film(z, flat)), "z_prev": None, "dt_prev": None}
    s["m_prev"] = s["m"]
    converged, message = True, "converged"
    k = 0
    while k < n_steps:
        if time_limit_s is not None and clock() - start > time_limit_s:
            converged, message = False, f"wall-time limit of {time_limit_s:g} s reached after {k} of {n_steps} steps"
            break
        outcome = _advance(problem, s, gap_at, k * d_t, d_t, numerics)
        if outcome is None and options.newton_iterations < RETRY_NEWTON_ITERATIONS:
            outcome = _advance(problem, s, gap_at, k * d_t, d_t, retry)
            retried += outcome is not None
        if outcome is None:
            converged = False
            message = (f"not converged: Newton failed at step {k + 1} with {options.max_substeps} sub-steps and "
                       f"{max(options.newton_iterations, RETRY_NEWTON_ITERATIONS)} iterations")
            break
        z, h, _, _ = outcome
        k += 1
        _record_step(record, problem, case, state, scales, z, h, k * d_t * a / case.u_r, mean_pressure_pa)
    window = slice(first_average, None)
    mu = time_mean(np.asarray(record["mu_local"][window])) if k > first_average + 1 else None
    share = time_mean(np.asarray(record["asperity_share"][window])) if k > first_average + 1 else None
    if mu is None:
        converged = False
        message = message if message != "converged" else "not converged: no averaging window"
    mean = (lambda key: float(np.mean(record[key][window])) if mu is not None else math.nan)  # noqa: E731
    return WindowResult(
        mu_local=mu.mean if mu else math.nan, mu_local_sem=mu.standard_error if mu else math.nan,
        shear_stress_pa=mean("shear_stress_pa"), asperity_share=share.mean if share else math.nan,
        asperity_share_sem=share.standard_error if share else math.nan, mean_film_m=mean("mean_film_m"),
        content_film_m=mean("content_film_m"), min_film_m=mean("min_film_m"), converged=converged,
        message=message, wall_time_s=clock() - start, n_nodes=n, n_steps=k, dx_m=dx_m, length_m=length_m,
        mean_pressure_pa=float(mean_pressure_pa),
        series={**{key: np.asarray(v) for key, v in record.items()}, "average_from_step": first_average,
                "mass_error": problem.mass_balance_error(), "retried_steps": retried, **problem.cost})


def _record_step(record, problem: MixedProblem, case, state, scales, z, h, t_s, p_bar_pa):
    """Append the window means of one state (module docstring)."""
    pf, th, pc, _ = problem.unpack(z)
    h_m = np.maximum(h, problem.h_b) * scales.film_scale
    fluid, boundary = local_shear_stress(problem, case, state, scales, z, h)
    contact = float(np.mean(pc)) * case.p_h
    tau = float(np.mean(fluid + boundary))
    record["t_s"].append(t_s)
    record["shear_stress_pa"].append(tau)
    record["mu_local"].append(tau / p_bar_pa)
    record["asperity_share"].append(contact / p_bar_pa)
    record["mean_film_m"].append(float(np.mean(h)) * scales.film_scale)
    record["content_film_m"].append(float(np.mean(th * h_m)))
    record["min_film_m"].append(float(np.min(h)) * scales.film_scale)
    record["lubricant_content"].append(float(problem.weights @ problem.content(z, h)))
    record["mean_pressure_error"].append(float(np.mean(pf + pc)) * case.p_h / p_bar_pa - 1.0)
