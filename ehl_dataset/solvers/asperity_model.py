"""Asperity-load closure of the film-law homogenised model: the roughness that survives inside the conjunction
carries part of the load (docs/explanation/mixed-regime.md, "The asperity-load closure").

The film-law model (:mod:`ehl_dataset.solvers.film_law_model`) gives the smooth pressure p̄(x), the film of the
measured film law h̄(x) and the gap-averaged Eyring traction, with the whole load on the fluid. This closure adds the
load the asperities carry, in four steps.

1. **Surviving roughness.** Inside an EHL conjunction a harmonic roughness component of wavelength λ is flattened
   by the fluid pressure; its amplitude ratio is a function of one parameter (Venner, Couhier, Lubrecht & Greenwood,
   Tribology Series 32 (1997) 103; with slip: "Waviness amplitude reduction in EHL line contacts", J. Tribol. 120
   (1998) 705):

       A_d/A_i = F(∇) = 1/(1 + 0.15∇ + 0.015∇²),   ∇ = c_∇ · (λ_c/a) · M^¾ / L^½,

   with a the Hertz half width, M, L Moes' line-contact parameters and λ_c = λ·u_m/u_i the wavelength that a
   roughness on surface i (speed u_i, mean speed u_m) imposes on the film carried at u_m (the complementary
   component of Hooke, Proc. IMechE J 217 (2003) 17: a faster surface writes shorter film waves, which survive; a
   stationary rough surface is flattened). Flattening takes pressure: removing the part (1 − F) of the roughness
   needs an r.m.s. pressure E'Δq_f/4, Δq_f the r.m.s. slope of the removed part of the composite profile (Johnson,
   Contact Mechanics 1985 §13.1, as in :mod:`ehl_dataset.model.micro_pressure`), and the film cannot exert much more
   than the contact pressure, so the removal is limited to φ = min(1, [c_p·p_h/(E'Δq_f/4)]^n): rough, steep
   roughness under a light load survives (the reference's cases B and C). Over the profile's own periodogram C(k)
   (:func:`ehl_dataset.model.roughness.periodogram`) each surface keeps the power-weighted fraction

       r_i = [Σ_k C(k) (1 − φ(1 − F(∇_i(k))))² / Σ_k C(k)]^½,   σ_s = [(r_1 Rq_1)² + (r_2 Rq_2)²]^½,   r = σ_s/σ.

   c_∇ (:data:`NABLA_SCALE`), c_p (:data:`PRESSURE_SCALE`) and n (:data:`FLATTENING_EXPONENT`, chosen among 1, 2, 3)
   are calibrated on the deterministic reference (and only there).

2. **Dry contact of the surviving roughness.** The dry-contact table of the pair (elastic–plastic contact of the
   actual profiles; a pair without a shipped table of its own takes the nearest shipped table of the profile
   scaled to it, :func:`ehl_dataset.model.dry_contact.similar_dry_contact_table`) scaled by elastic
   similarity to σ_s: p_a,s(d) = r·p_a(d/r), contact fraction A_s(d) = A(d/r) (exact for linear elasticity; the
   plastic cap of the scaled table is r·H instead of H, which matters only where the contact fraction is large).

3. **Load balance** (Johnson, Greenwood & Poon, Wear 19 (1972) 91; Gelinck & Schipper, Tribol. Int. 33 (2000) 175):
   the fluid carries the rest of the load, (1 − s)·w, and its film is the film law's scaled by Moes' central-film
   ratio at the fluid load, h(x; s) = h̄(x)·H_c(w(1 − s))/H_c(w) (:func:`fluid_film_ratio`). The asperity pressure
   at the local film, capped by the local pressure, p_a(x) = min(p_a,s(h(x; s)), p̄(x)), gives the share

       s = ∫ p_a(x) dx / w,

   solved for s in [0, 1) (one scalar root: the left side grows with s, the right side falls as the film grows).

4. **Traction**: μ = [μ_d ∫p_a dx + ∫(1 − A_s)·τ̄(p̄ − p_a, h) dx + rolling + outside]/w, with τ̄ the film law's
   gap- and pressure-averaged Eyring stress (:func:`~ehl_dataset.solvers.film_law_model.
   fluctuation_averaged_shear_stress`) evaluated at the fluid pressure p̄ − p_a and the film h, the rolling part
   (h/2)∂(p̄ − p_a)/∂x, the stress outside the zone the film law's, and μ_d the lubricant's boundary friction
   (``boundary_friction``, the value the deterministic reference uses). With a thermal plan the film law's thermal
   correction of the Couette part is kept as its ratio to the isothermal stress at s = 0.

Limits: s → 0 where the film is thick against σ_s (the film-law μ); smooth surfaces are the caller's (the smooth
solve); as the film vanishes s → ∫_zone p̄ dx/w (the load inside the film-law zone) and μ → μ_d·s plus the film
law's stress outside the zone and the fluid shear of the open fraction 1 − A_s. The cost is the film-law solve plus
a scalar root and one stress average, two with the thermal correction (``benchmarks/bench_asperity_model.py``).
"""

from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np

from ..model.amplitude_reduction import AMPLITUDE_A, amplitude_factor, profile_spectrum, surface_amplitude_factors
from ..model.contact import ContactCase
from ..model.dry_contact import profile_hash, similar_dry_contact_table, windows_that_fit
from ..model.effects import Effects
from ..names import DEFAULT_FLUCTUATIONS
from ..model.film_formulas import moes_central_film
from ..model.lubricant import LubricantState
from ..model.roughness import RoughnessProfile, default_profile
from ..validation import check_range
from .film_law_model import (composite_height_quantiles, fluctuation_averaged_shear_stress, pressure_spread,
                             solve_film_law)
from .levels import AccuracyLevel
from .planner import CLOSURE_MEASURED_LAMBDA
from .result import ContactResult

ASPERITY_MODEL_VERSION = "asperity-2026.11-2"
"""Version of this closure (amplitude reduction with its flattening limit, scaled dry-contact table, Moes load
balance, c_∇ and c_p)."""

NABLA_SCALE = 4.0
"""c_∇, the scale of the amplitude-reduction parameter ∇ [-] (1 in the published sinusoidal-waviness fit).
Fitted with :data:`PRESSURE_SCALE` on the deterministic validation set by `python validation/asperity_model_loo.py`
(validation/results/asperity_model_loo.json, which also holds the leave-one-out errors)."""

PRESSURE_SCALE = 2.639
"""c_p, the r.m.s. micro-pressure the film can exert to flatten roughness, in Hertz pressures [-]; fitted with
:data:`NABLA_SCALE`."""

FLATTENING_EXPONENT = 3.0
"""n of the flattening limit φ = min(1, [c_p·p_h/(E'Δq_f/4)]^n) [-]; fitted with :data:`NABLA_SCALE`."""

def surviving_fractions(profile: RoughnessProfile, case: ContactCase, state: LubricantState,
                        pressure_scale: float = PRESSURE_SCALE, nabla_scale: float = NABLA_SCALE,
                        flattening_exponent: float = FLATTENING_EXPONENT) -> tuple[float, float, float]:
    """Power-weighted fractions (r_1, r_2) of each surface's roughness that survive in the conjunction, and the
    flattening limit φ (module docstring, step 1), from the periodogram of ``profile``.

    Parameters
    ----------
    profile : RoughnessProfile
        Shape of both surfaces (its spectrum is used, not its Rq) [m].
    case : ContactCase
        Operating conditions [SI].
    state : LubricantState
        The lubricant at the case's temperature [SI].
    pressure_scale : float
        c_p, the micro-pressure the film can exert in units of the Hertz pressure (large: no limit) [-].
    nabla_scale : float
        c_∇ [-].
    flattening_exponent : float
        n of the flattening limit [-].

    Returns
    -------
    tuple of float
        (r_1, r_2, φ) [-], each in [0, 1].
    """
    check_range("nabla_scale", nabla_scale, 0.0, 1e3, low_inclusive=False)
    check_range("pressure_scale", pressure_scale, 0.0, 1e3, low_inclusive=False)
    wavelength, weight = profile_spectrum(profile)
    k2 = (2.0 * math.pi / wavelength) ** 2
    factors = surface_amplitude_factors(wavelength, case, state, nabla_scale)
    slope2 = sum(rq**2 * float(np.sum(weight * k2 * (1.0 - f) ** 2)) for rq, f in zip((case.rq1, case.rq2), factors))
    needed = 0.25 * case.e_reduced * math.sqrt(slope2)
    phi = 1.0 if needed <= 0.0 else min(1.0, (pressure_scale * case.p_h / needed) ** flattening_exponent)
    r = [float(np.sqrt(np.sum(weight * (1.0 - phi * (1.0 - f)) ** 2))) for f in factors]
    return r[0], r[1], phi


class SurvivingTable:
    """The dry-contact table of a roughness pair with its heights scaled by r (elastic similarity, module docstring
    step 2): p_a(d) = r·p_a0(d/r), A(d) = A0(d/r).

    Parameters
    ----------
    table : DryContactTable
        Table of the undeformed pair [-].
    r : float
        Height scale: the surviving fraction σ_s/σ times the scale of a similar table, in (0, 100] [-].
    """

    def __init__(self, table, r: float):
        check_range("r", r, 0.0, 100.0, low_inclusive=False)
        self.table, self.r = table, float(r)

    @property
    def sigma(self) -> float:
        """Surviving composite rms roughness σ_s [m]."""
        return self.table.sigma * self.r

    def asperity_pressure(self, d) -> np.ndarray:
        """Mean asperity pressure [Pa] at separations d [m]."""
        return self.r * np.asarray(self.table.asperity_pressure(np.asarray(d, dtype=float) / self.r))

    def contact_fraction(self, d) -> np.ndarray:
        """Contact area fraction [-] at separations d [m]."""
        return np.asarray(self.table.contact_fraction(np.asarray(d, dtype=float) / self.r))


def fluid_film_ratio(case: ContactCase, state: LubricantState, fluid_fraction) -> np.ndarray:
    """H_c(w·f)/H_c(w): Moes' central film at the fluid's part f of the load over the film at the full load.

    Parameters
    ----------
    case : ContactCase
        Operating conditions [SI].
    state : LubricantState
        The lubricant at the case's temperature [SI].
    fluid_fraction : array_like
        f = 1 − s, in (0, 1] [-].

    Returns
    -------
    ndarray
        The ratio (≥ 1) [-].
    """
    f = np.asarray(fluid_fraction, dtype=float)
    args = (state.eta0, case.u_r, state.alpha1, case.e_reduced, case.r_eq)
    return moes_central_film(*args, case.load_per_length * f) / moes_central_film(*args, case.load_per_length)


def _integral(x, f) -> float:
    return float(np.sum(0.5 * (f[1:] + f[:-1]) * np.diff(x)))


def asperity_closure(film_law: ContactResult, case: ContactCase, state: LubricantState,
                     profile: RoughnessProfile | None, boundary_film_m: float,
                     micro_pressure_coefficient: float | None = None,
                     pressure_scale: float = PRESSURE_SCALE, nabla_scale: float = NABLA_SCALE,
                     flattening_exponent: float = FLATTENING_EXPONENT,
                     fluctuations: str = DEFAULT_FLUCTUATIONS) -> ContactResult:
    """The asperity-load closure (module docstring, steps 1–4) applied to a film-law result of the same contact.

    Parameters
    ----------
    film_law : ContactResult
        :func:`~ehl_dataset.solvers.film_law_model.solve_film_law` of ``case`` (its zone nodes, pressure, film and μ
        parts) [-].
    case : ContactCase
        Operating conditions [SI].
    state : LubricantState
        The lubricant at the case's temperature [SI].
    profile : RoughnessProfile, optional
        Shape of both surfaces; None: the default profile (:func:`~ehl_dataset.model.roughness.default_profile`) [-].
    boundary_film_m : float
        Floor h_b of the micro gaps in the Eyring shear [m].
    micro_pressure_coefficient : float, optional
        c of the film law's pressure fluctuations; None: the form ``fluctuations`` [-].
    pressure_scale : float
        c_p of the flattening limit [-].
    nabla_scale : float
        c_∇ of the amplitude reduction [-].
    flattening_exponent : float
        n of the flattening limit [-].
    fluctuations : str
        Form of the pressure spread where no c is given (:data:`ehl_dataset.names.FLUCTUATIONS`); the film-law
        result should have been solved with the same [-].

    Returns
    -------
    ContactResult
        μ, the asperity load share s, the fluid film h(x; s) on the zone nodes and the closure's record in
        ``extra``; converged only if the film law converged and the balance was solved.
    """
    start = time.perf_counter()
    profile = profile if profile is not None else default_profile()
    x, p_bar, film0 = film_law.x, film_law.pressure, film_law.film
    load = case.load_per_length
    r1, r2, phi = surviving_fractions(profile, case, state, pressure_scale, nabla_scale, flattening_exponent)
    sigma_s = math.hypot(r1 * case.rq1, r2 * case.rq2)
    r = sigma_s / case.s_c
    extra = dict(film_law.extra)
    record = {"model_version": ASPERITY_MODEL_VERSION, "nabla_scale": nabla_scale, "pressure_scale": pressure_scale,
              "flattening_exponent": flattening_exponent,
              "flattening_limit": phi, "surviving_fraction_1": r1,
              "surviving_fraction_2": r2, "surviving_sigma_m": sigma_s, "boundary_friction": state.mu_d,
              "film_law_mu": film_law.mu}
    if r <= 0.0 or not film_law.converged:
        extra.update(closure="asperity", asperity=record | {"share_residual": 0.0})
        return replace(film_law, extra=extra, wall_time=film_law.wall_time + time.perf_counter() - start)
    # the windows the profile is long enough for; a shipped table of the profile scaled to the pair where the pair's
    # own does not ship (elastic similarity, :func:`similar_dry_contact_table`)
    base, scale, pair = similar_dry_contact_table(profile, case.rq1, case.rq2, case.e_reduced,
                                                  settings=windows_that_fit(profile))
    table = SurvivingTable(base, r * scale)
    record.update(table_rq_m=[float(pair[0]), float(pair[1])], table_scale=float(scale))

    def asperity_pressure(s):
        film = film0 * float(fluid_film_ratio(case, state, 1.0 - s))
        return film, np.minimum(table.asperity_pressure(film), p_bar)

    def balance(s):
        return s - _integral(x, asperity_pressure(s)[1]) / load

    s_max = 1.0 - 1e-9
    if balance(0.0) >= 0.0:
        share = 0.0
    else:
        from scipy.optimize import brentq  # imported here: only the asperity closure needs it (a slow import)

        share = brentq(balance, 0.0, s_max, xtol=1e-12, rtol=1e-10)
    film, p_a = asperity_pressure(share)
    residual = abs(balance(share))
    p_fluid = np.maximum(p_bar - p_a, 0.0)
    open_fraction = 1.0 - table.contact_fraction(film)
    heights = composite_height_quantiles(profile, case.rq1, case.rq2)
    spread = extra.get("micro_pressure", {})
    same_profile = extra.get("profile_sha256") == profile_hash(profile)
    same_form = (spread.get("form") == fluctuations if micro_pressure_coefficient is None
                 else spread.get("form") == "given" and spread.get("coefficient") == micro_pressure_coefficient)
    same_spread = same_profile and "std_pa" in spread and same_form
    # the film law's spread is this one when it was formed the same way on the same profile
    pressure_std = (float(spread["std_pa"]) if same_spread else
                    pressure_spread(profile, case, state, extra["inlet_over_beta"], micro_pressure_coefficient,
                                    fluctuations)[2])

    def couette(p, h, weight):
        tau = fluctuation_averaged_shear_stress(state.viscosity, p, pressure_std, case.u_s, h, heights, state.tau0,
                                                boundary_film_m)
        return _integral(x, weight * tau)

    # where the asperities carry nearly the whole local load the gamma quadrature of the fluctuations underflows
    # (shape (p/σ_p)² ≲ 1e-4): the fluid pressure in the traction is floored at 0.05 σ_p (and 1e-4 of the mean
    # contact pressure), the shear of a nearly unloaded film
    p_floor = max(0.05 * pressure_std, 1e-4 * load / (x[-1] - x[0]))
    # isothermal: the film law's Couette part is ∫τ̄(p̄, h̄)dx/w on the same nodes, so the fluid's replaces it; with
    # the thermal correction, the film law's part is scaled by the isothermal ratio fluid/film law
    if share == 0.0:
        ratio, mu_couette = 1.0, extra["mu_couette"]
    else:
        wet = couette(np.maximum(p_fluid, p_floor), film, open_fraction)
        if "thermal" in extra:
            # the film law's isothermal zone integral is this average when it was taken with the same spread, floor
            # and profile
            dry = extra["thermal"].get("zone_couette_isothermal_n_per_m")
            same_average = (dry is not None and same_profile and extra.get("boundary_film_m") == boundary_film_m
                            and spread.get("std_pa") == pressure_std)
            if not same_average:
                dry = couette(p_bar, film0, 1.0)
            ratio = wet / dry if dry != 0.0 else 1.0
            mu_couette = extra["mu_couette"] * ratio
        else:
            mu_couette = wet / load
            ratio = mu_couette / extra["mu_couette"] if extra["mu_couette"] != 0.0 else 1.0
    mu_poiseuille = extra["mu_poiseuille"] + (_integral(x, 0.5 * film * np.gradient(p_fluid, x))
                                              - _integral(x, 0.5 * film0 * np.gradient(p_bar, x))) / load
    mu_asperity = math.copysign(1.0, case.u_s) * (case.u_s != 0.0) * state.mu_d * _integral(x, p_a) / load
    parts = {"mu_couette": mu_couette, "mu_poiseuille": mu_poiseuille, "mu_outside_zone": extra["mu_outside_zone"],
             "mu_asperity": mu_asperity}
    mu = float(sum(parts.values()))
    converged = bool(np.isfinite(mu)) and residual < 1e-6
    message = film_law.message if converged else f"not converged: load balance residual {residual:.3g}"
    if converged and not film_law.lambda_bar >= CLOSURE_MEASURED_LAMBDA:
        message += (f"; lambda_bar {film_law.lambda_bar:.3g} below the asperity closure's measured range "
                    f"(lambda_bar >= {CLOSURE_MEASURED_LAMBDA:g}; docs/explanation/roughness.md)")
    record.update(share_residual=residual, fluid_film_ratio=float(film[0] / film0[0]),
                  contact_fraction_max=float(np.max(1.0 - open_fraction)), fluid_couette_ratio=ratio)
    extra.update(parts, closure="asperity", asperity=record)
    effects = dict(film_law.effects)
    effects["reasons"] = {**dict(effects.get("reasons") or {}),
                          "model": "homogenised mixed EHL (asperity-load closure: film law, surviving roughness, "
                                   "dry-contact load share)"}
    return replace(film_law, mu=mu, h_min=float(np.min(film)), h_central=float(np.interp(0.0, x, film)),
                   converged=converged, asperity_load_share=float(share), film=film, message=message,
                   effects=effects, extra=extra, wall_time=film_law.wall_time + time.perf_counter() - start,
                   residuals={**film_law.residuals, "load_share": residual})


def solve_asperity(case: ContactCase, state: LubricantState, lvl: AccuracyLevel, plan: Effects,
                   roughness: RoughnessProfile | None, boundary_film_m: float,
                   micro_pressure_coefficient: float | None = None, pressure_scale: float = PRESSURE_SCALE,
                   nabla_scale: float = NABLA_SCALE, fluctuations: str = DEFAULT_FLUCTUATIONS) -> ContactResult:
    """Homogenised solve with the asperity-load closure: the film-law solve, then :func:`asperity_closure`.

    Parameters
    ----------
    case : ContactCase
        Operating conditions (rough: S_c > 0) [SI].
    state : LubricantState
        The lubricant at the case's temperature [SI].
    lvl : AccuracyLevel
        Steady grid and tolerances [-].
    plan : Effects
        The effect plan (thermal correction of the traction or not) [-].
    roughness : RoughnessProfile, optional
        Shape of both surfaces; None: the default profile (:func:`~ehl_dataset.model.roughness.default_profile`) [-].
    boundary_film_m : float
        Floor h_b of the micro gaps in the Eyring shear [m].
    micro_pressure_coefficient : float, optional
        c of the film law's pressure fluctuations; None: its function of the inlet length [-].
    pressure_scale : float
        c_p of the flattening limit [-].
    nabla_scale : float
        c_∇ of the amplitude reduction [-].
    fluctuations : str
        Form of the film law's pressure spread where no c is given (:data:`ehl_dataset.names.FLUCTUATIONS`) [-].

    Returns
    -------
    ContactResult
        The result (module docstring); it says whether the solve converged.
    """
    film_law = solve_film_law(case, state, lvl, plan, roughness, boundary_film_m,
                              micro_pressure_coefficient=micro_pressure_coefficient, fluctuations=fluctuations)
    return asperity_closure(film_law, case, state, roughness, boundary_film_m, micro_pressure_coefficient,
                            pressure_scale, nabla_scale, fluctuations=fluctuations)
