"""Steady smooth line contact: the full-system Newton solve of :mod:`ehl_dataset.solvers.newton` on a clustered grid
(paper Eq. 1, 3–6 without the time term and roughness), with load and viscosity-exponent continuation.

Also the Hertzian scales of a case (:class:`ContactScales`) and the Dowson–Higginson film parameter λ̄, which the
transient solver shares. A smooth contact under constant load and speed has a steady solution, which is what a
transient run would settle to, so :func:`ehl_dataset.solver.solve_contact` sends every smooth case here.
"""

from __future__ import annotations

import math
import threading
import time
from collections import OrderedDict
from contextlib import contextmanager
from dataclasses import dataclass, replace
from typing import NamedTuple

import numpy as np

from ..discretisation.deflection import influence_matrix
from ..discretisation.grid import clustered_grid
from ..model.contact import ContactCase
from ..model.effects import Effects
from ..model.film_formulas import dowson_higginson_min_film, moes_central_film
from ..model.lubricant import LubricantState
from ..model.thermal import thermal_couette_traction
from ..model.traction import friction_components, full_film_mask
from ..validation import SolverError
from .levels import AccuracyLevel
from .newton import NewtonOutcome, ReynoldsProblem, newton_solve
from .result import ContactResult

PSEUDO_DT = 0.3
"""Initial pseudo time step [a/u_r] of the pseudo-transient Newton globalisation."""

M_EASY = 30.0
"""Moes load parameter above which the Hertz pressure is a good enough Newton start."""
LAMBDA_FACTOR = 4.0
"""Growth factor of λ̄ between the stages of the light-load continuation."""

START_FILM_EXPONENT = 0.7
"""Exponent q of the start film of the light-load continuation's first stage, which runs at the heavier load λ̄_easy
(λ̄ ∝ u_r at a given p_h): H_c(λ̄_easy) = H_c·(λ̄_easy/λ̄)^q from Moes' H_c of the contact, q the speed exponent of
the EHL film formulas (Dowson–Higginson: h ∝ u^0.7); 0 starts it from the contact's own film. On the first 150
contacts of ``benchmarks/bench_stage1_floor.py``: 33.0 Newton iterations a contact on average against 36.1 with
q = 0, the same converged solutions to 1e-14."""

FINE_PSEUDO_DT = 0.0
COARSENING = 6.0
"""Spacing ratio of the continuation grid to the level's grid in :func:`solve_steady`. On 300 random smooth contacts of
the paper factorial at `standard` (seed 7, the ratios interleaved contact by contact): median CPU 44.1, 38.8, 36.8,
36.0 and 37.5 ms at 3, 4, 5, 6 and 7 (the continuation takes fewer Newton iterations on the coarser grid; the level's
grid about two more, 7.4 instead of 5.6 at 6); an intermediate grid between the two did not help (the level's grid
takes about five iterations from any interpolated start). The converged solutions agree within the Newton
tolerances (μ within 6e-9 of those at 3)."""
COARSE_MIN_NODES = 60
"""Fewest nodes of the :data:`COARSENING` grid; a coarser one is skipped for the :data:`FALLBACK_COARSENING` grid. At
`fast` the 6× grid has about 37 nodes and its continuation fails or needs the fallback on 31 of 200 random factorial
contacts (median CPU 22.8 against 18.7 ms with the 3× grid); at `standard` it has 72 or more."""
FALLBACK_COARSENING = 3.0
"""Spacing ratio of a second continuation grid, tried when the route through the :data:`COARSENING` grid does not
converge (at `fast` that grid can be too coarse for a light-load continuation: 37 nodes on 75W90 at 0.5 GPa, 10 mm,
20 m/s, SR 0.7, 50 °C, where 72 nodes converge and the level's grid from scratch does not)."""

COARSE_TOLERANCE = 1e-3
"""Newton tolerance (residual, load and step) of the continuation on the coarse grid of :func:`solve_steady`, whose
solution only starts the Newton iteration on the level's grid (the level's own, tighter tolerances apply there). On
100 random paper-factorial contacts at `standard`, solved both ways interleaved: Newton iterations a contact 22.6 →
19.9, median CPU 13.4 → 12.6 ms, the same iterations on the level's grid (7.06), μ, h_min, h_c, p_max within 6.3e-10
of the solutions with the level's tolerances on the coarse grid."""

STEADY_CACHE_SIZE = 64
"""Number of steady solutions kept per process (:func:`solve_steady`). The steady smooth solve does not depend on the
roughness, and a factorial solves each load, speed and temperature once per roughness pair (the film-law model starts
from the smooth solution): the pairs after the first reuse it."""
_STEADY_CACHE: OrderedDict = OrderedDict()
_STEADY_CACHE_LOCK = threading.Lock()
WARM_START_MAX_LOG_LAMBDA = math.log(10.0)
"""Largest |ln(λ̄/λ̄_n)| between a contact and a kept solution that may start its Newton iteration
(:func:`neighbour_warm_starts`)."""
_WARM_STARTS = {"enabled": False}


class _Kept(NamedTuple):
    """A converged steady solution kept per process: grid, Newton outcome, iterations and record of its solve, λ̄
    and Moes' H_c of its contact, and its cache key."""

    x: np.ndarray
    outcome: NewtonOutcome
    iterations: int
    record: dict
    lam: float
    h_c: float
    key: tuple


@contextmanager
def neighbour_warm_starts(enabled: bool = True):
    """Within this context, :func:`solve_steady` starts the Newton iteration of a contact on the level's grid from the
    kept solution of a neighbouring contact (the same grid, level, materials and Newton effects, λ̄ within a factor
    exp(:data:`WARM_START_MAX_LOG_LAMBDA`), the closest in ln λ̄), its film constant shifted by the change of Moes'
    central film, instead of from the continuation on the coarse grid; if that Newton iteration does not converge the
    contact is solved as without the context. The converged solution is the same discrete solution within the level's
    Newton tolerances (``tests/ehl_dataset/test_stage1_speed.py``), but which neighbour starts a contact depends on
    what the process solved before: the last digits of a result then depend on the order of the solves.

    Parameters
    ----------
    enabled : bool
        Whether neighbour starts are used inside the context [-].
    """
    previous = _WARM_STARTS["enabled"]
    _WARM_STARTS["enabled"] = bool(enabled)
    try:
        yield
    finally:
        _WARM_STARTS["enabled"] = previous

__all__ = ["ContactScales", "dowson_higginson_lambda", "moes_h_c", "steady_grid", "solve_steady",
           "solve_steady_problem", "neighbour_warm_starts"]


@dataclass(frozen=True)
class ContactScales:
    """Hertzian scales and dimensionless numbers of a case (SI): ``a`` [m], ``p_h`` [Pa], ``r_eq`` [m],
    ``load`` W' [N/m], ``e_reduced`` [Pa]; ``lam`` λ̄ = 12 η0 u_r r_eq²/(a³ p_h); ``shear`` S = η0|u_s| r_eq/(τ0 a²);
    ``film_scale`` a²/r_eq [m] (h = H a²/r_eq)."""

    a: float
    p_h: float
    r_eq: float
    load: float
    e_reduced: float
    lam: float
    shear: float

    @property
    def film_scale(self) -> float:
        return self.a**2 / self.r_eq

    @classmethod
    def of(cls, case: ContactCase, state: LubricantState, shear_thinning: bool = True) -> "ContactScales":
        a = case.half_width
        lam = 12.0 * state.eta0 * case.u_r * case.r_eq**2 / (a**3 * case.p_h)
        shear = state.eta0 * abs(case.u_s) * case.r_eq / (state.tau0 * a**2) if shear_thinning else 0.0
        return cls(a, case.p_h, case.r_eq, case.load_per_length, case.e_reduced, lam, shear)


def dowson_higginson_lambda(case: ContactCase, state: LubricantState) -> tuple[float, float]:
    """(h_min from Dowson–Higginson [m], λ̄ = h_min,DH / S_c) as the paper defines λ̄ (inf for smooth surfaces)."""
    h_dh = float(dowson_higginson_min_film(state.eta0, case.u_r, state.alpha1, case.e_reduced, case.r_eq,
                                           case.load_per_length))
    s_c = case.s_c
    return h_dh, (h_dh / s_c if s_c > 0.0 else math.inf)


def _initial_guess(x: np.ndarray, problem: ReynoldsProblem, case: ContactCase, state: LubricantState,
                   scales: ContactScales) -> tuple[np.ndarray, float]:
    """Hertz pressure and the film constant that puts the central film at Moes' estimate."""
    p = np.sqrt(np.clip(1.0 - x**2, 0.0, None))
    p[0] = p[-1] = 0.0
    h_c = float(moes_central_film(state.eta0, case.u_r, state.alpha1, case.e_reduced, case.r_eq,
                                  case.load_per_length)) / scales.film_scale
    h_rigid = problem.film(p, 0.0)
    centre = int(np.argmin(np.abs(x)))
    h0 = h_c - h_rigid[centre]
    h0 = max(h0, -float(np.min(h_rigid)) + 0.5 * h_c)
    return p, h0


def _newton_with_homotopy(problem: ReynoldsProblem, p0, h00, tolerances) -> tuple[NewtonOutcome, int, list[float]]:
    """Newton from (p0, h00); on failure a continuation in the viscosity exponent c·ln(η/η0), c: 0 → 1."""
    outcome = newton_solve(problem, p0, h00, pseudo_dt=PSEUDO_DT, **tolerances)
    total = outcome.iterations
    if outcome.converged:
        return outcome, total, [1.0]
    stages: list[float] = []
    c, step = 0.0, 0.25
    p, h0 = p0, h00
    while c < 1.0:
        trial = min(1.0, c + step)
        out = newton_solve(problem, p, h0, homotopy=trial, pseudo_dt=PSEUDO_DT, **tolerances)
        total += out.iterations
        if out.converged:
            c, p, h0 = trial, out.p, out.h0
            stages.append(trial)
            outcome = out
            step = min(step * 1.5, 0.5)
        else:
            step *= 0.5
            if step < 1e-2:
                out.message = f"continuation stalled at viscosity exponent factor {c:.3f}: {out.message}"
                return out, total, stages
    return outcome, total, stages


def solve_steady_problem(problem: ReynoldsProblem, p0: np.ndarray, h00: float, lvl: AccuracyLevel,
                         ) -> tuple[NewtonOutcome, int, list]:
    """Solve the steady problem, with continuation where a direct Newton solve is not robust.

    Light loads (Moes M = √(3.70/λ̄) below :data:`M_EASY`) start from the Hertz guess at the heavier load
    λ̄ = 3.70/M_EASY² and raise λ̄ (a speed/load continuation, λ̄ ∝ U/W²) by factors of :data:`LAMBDA_FACTOR`; each
    stage falls back to the viscosity-exponent continuation if needed. Returns the final outcome, the total
    number of Newton iterations and the continuation record [(λ̄, [c values]), ...].
    """
    tolerances = dict(tol_residual=lvl.tol_residual, tol_load=lvl.tol_load, tol_step=lvl.tol_step,
                      max_iterations=lvl.max_iterations)
    target = problem.lam
    lam_easy = 3.70 / M_EASY**2
    lams = [target]
    if target > lam_easy:
        n_stages = int(np.ceil(np.log(target / lam_easy) / np.log(LAMBDA_FACTOR)))
        lams = list(lam_easy * (target / lam_easy) ** (np.arange(n_stages + 1) / n_stages))
    record = []
    total = 0
    p, h0 = p0, h00
    centre = int(np.argmin(np.abs(problem.x)))
    for k, lam in enumerate(lams):
        problem.lam = float(lam)
        if k > 0:  # scale the film for the new speed: H_c ∝ λ̄^0.5 roughly at light load
            h_prev = problem.film(p, h0)[centre]
            h0 = h0 + h_prev * ((lams[k] / lams[k - 1]) ** 0.5 - 1.0)
        elif len(lams) > 1 and START_FILM_EXPONENT:
            # the first stage runs at the heavier load λ̄_easy: start it from its own (thinner) film, kept open
            # where the start's film is thinnest
            h_rigid = problem.film(p, 0.0)
            h_c = (float(h_rigid[centre]) + h0) * (lam / target) ** START_FILM_EXPONENT
            h0 = max(h_c - float(h_rigid[centre]), -float(np.min(h_rigid)) + 0.5 * h_c)
        outcome, its, stages = _newton_with_homotopy(problem, p, h0, tolerances)
        total += its
        record.append((float(lam), stages))
        if not outcome.converged:
            problem.lam = target
            if k < len(lams) - 1:
                outcome.message = f"load continuation failed at lambda={lam:.3g} (target {target:.3g}): " \
                                  f"{outcome.message}"
            return outcome, total, record
        p, h0 = outcome.p, outcome.h0
    problem.lam = target
    return outcome, total, record


def _problem_on(x: np.ndarray, case: ContactCase, state: LubricantState, plan: Effects,
                scales: ContactScales) -> ReynoldsProblem:
    return ReynoldsProblem(x=x, kmat=influence_matrix(x), gap=0.5 * x**2, lam=scales.lam, p_h=case.p_h,
                           state=state, compressible=plan.compressibility and state.compressible,
                           shear=scales.shear)


def steady_grid(lvl: AccuracyLevel, coarsening: float = 1.0, h_c: float = math.inf) -> np.ndarray:
    """The clustered steady grid of a level (``coarsening`` > 1 multiplies both spacings).

    ``h_c`` is the expected dimensionless central film H_c = h_c r_eq/a²; the fine spacing is capped at
    ``lvl.inlet_resolution``·H_c^(2/3), the length scale of the inlet zone at heavy load.
    """
    dx_fine = min(lvl.dx_fine, lvl.inlet_resolution * h_c ** (2.0 / 3.0))
    dx_coarse = max(lvl.dx_coarse, dx_fine)
    return clustered_grid(lvl.x_start, lvl.x_end, dx_fine * coarsening, dx_coarse * coarsening,
                          (lvl.inlet_band, lvl.outlet_band), lvl.transition)


def moes_h_c(case: ContactCase, state: LubricantState, scales: ContactScales) -> float:
    """Moes' central film in units of a²/r_eq (a scale for grids and initial guesses)."""
    return float(moes_central_film(state.eta0, case.u_r, state.alpha1, case.e_reduced, case.r_eq,
                                   case.load_per_length)) / scales.film_scale


def solve_steady(case: ContactCase, state: LubricantState, lvl: AccuracyLevel, plan: Effects,
                 coarsening: float | None = None) -> ContactResult:
    """Steady, isothermal, smooth line contact (paper Eq. 1, 3–6 without the time term and roughness); with
    ``plan.thermal`` the Couette traction of the isothermal film is corrected for shear heating and the flash
    temperature (:mod:`ehl_dataset.model.thermal`; pressure and film stay isothermal), the isothermal μ kept in
    ``extra["thermal"]["mu_isothermal"]``.

    Two grids: the continuation (which may take tens of Newton iterations) runs on a grid
    :data:`COARSENING` times coarser, to :data:`COARSE_TOLERANCE`, and its interpolated solution starts the Newton
    iteration on the level's grid, which then needs only a few iterations. If the coarse stage fails, the fine grid is solved from scratch.
    ``coarsening`` replaces :data:`COARSENING` (the converged solution then differs within the Newton tolerances, so
    a caller that must reproduce earlier bits passes the ratio they were made with).
    """
    start = time.perf_counter()
    coarsening = COARSENING if coarsening is None else float(coarsening)
    scales = ContactScales.of(case, state, plan.shear_thinning)
    key = _cache_key(case, state, lvl, plan) + (coarsening,)
    with _STEADY_CACHE_LOCK:
        cached = _STEADY_CACHE.get(key)
        if cached is not None:
            _STEADY_CACHE.move_to_end(key)
    if cached is not None:
        x, outcome, iterations, record = cached[:4]
        result = _result_from_steady(case, state, lvl, plan, scales, x, outcome, iterations)
        result.extra["continuation"] = {**record, "reused": True}
        result.wall_time = time.perf_counter() - start
        return result
    h_c = moes_h_c(case, state, scales)
    x = steady_grid(lvl, h_c=h_c)
    problem = _problem_on(x, case, state, plan, scales)
    record: dict = {}
    iterations = 0
    outcome = None
    neighbour = _neighbour(x, key, scales.lam) if _WARM_STARTS["enabled"] else None
    if neighbour is not None:
        outcome = newton_solve(problem, neighbour.outcome.p, neighbour.outcome.h0 + (h_c - neighbour.h_c),
                               pseudo_dt=FINE_PSEUDO_DT, tol_residual=lvl.tol_residual, tol_load=lvl.tol_load,
                               tol_step=lvl.tol_step, max_iterations=lvl.max_iterations)
        iterations += outcome.iterations
        record["warm_start"] = {"nodes": int(x.size), "iterations": outcome.iterations,
                                "converged": outcome.converged, "from_lambda": neighbour.lam}
        if not outcome.converged:
            outcome = None
    coarse_problems = []
    coarse_level = replace(lvl, tol_residual=max(lvl.tol_residual, COARSE_TOLERANCE),
                           tol_load=max(lvl.tol_load, COARSE_TOLERANCE), tol_step=max(lvl.tol_step, COARSE_TOLERANCE))
    grids = [steady_grid(lvl, coarsening, h_c=h_c)]
    if grids[0].size < COARSE_MIN_NODES:
        grids = []  # too coarse for the continuation
    if FALLBACK_COARSENING != coarsening:
        grids.append(steady_grid(lvl, FALLBACK_COARSENING, h_c=h_c))
    for attempt, x_coarse in enumerate(grids):
        if (outcome is not None and outcome.converged) or not x_coarse.size < 0.6 * x.size:
            break
        coarse = _problem_on(x_coarse, case, state, plan, scales)
        coarse_problems.append(coarse)
        p0, h00 = _initial_guess(x_coarse, coarse, case, state, scales)
        coarse_out, its, stages = solve_steady_problem(coarse, p0, h00, coarse_level)
        iterations += its
        suffix = "" if attempt == 0 else "_fallback"
        record["coarse" + suffix] = {"nodes": int(x_coarse.size), "stages": stages, "converged": coarse_out.converged}
        if coarse_out.converged:
            p_fine = np.interp(x, x_coarse, coarse_out.p)
            outcome = newton_solve(problem, p_fine, coarse_out.h0, pseudo_dt=FINE_PSEUDO_DT,
                                   tol_residual=lvl.tol_residual, tol_load=lvl.tol_load, tol_step=lvl.tol_step,
                                   max_iterations=lvl.max_iterations)
            iterations += outcome.iterations
            record["fine" + suffix] = {"nodes": int(x.size), "iterations": outcome.iterations}
    if outcome is None or not outcome.converged:
        p0, h00 = _initial_guess(x, problem, case, state, scales)
        outcome, its, stages = solve_steady_problem(problem, p0, h00, lvl)
        iterations += its
        record["fine_from_scratch"] = {"nodes": int(x.size), "stages": stages}
    record["linear"] = _linear_counts(problem, *coarse_problems)
    if outcome.converged:
        for array in (x, outcome.p, outcome.h):
            array.flags.writeable = False
        with _STEADY_CACHE_LOCK:
            _STEADY_CACHE[key] = _Kept(x, outcome, iterations, record, float(scales.lam), float(h_c), key)
            while len(_STEADY_CACHE) > STEADY_CACHE_SIZE:
                _STEADY_CACHE.popitem(last=False)
    result = _result_from_steady(case, state, lvl, plan, scales, x, outcome, iterations)
    result.extra["continuation"] = record
    result.wall_time = time.perf_counter() - start
    return result


def _linear_counts(*problems: ReynoldsProblem | None) -> dict:
    """The linear-solve counters (:meth:`~ehl_dataset.solvers.newton.LinearSolver.counts`) summed over the problems
    of one solve (dense LU factorisations, GMRES solves with the banded preconditioner and their iterations, fallbacks
    from it to the dense LU)."""
    total: dict = {}
    for problem in problems:
        if problem is not None:
            for key, value in problem.linear.counts().items():
                total[key] = total.get(key, 0) + value
    return total


def _neighbour(x: np.ndarray, key: tuple, lam: float) -> _Kept | None:
    """The kept solution on the grid ``x`` with the same level, materials and Newton effects as ``key`` whose λ̄ is
    closest to ``lam`` in ln λ̄ (within :data:`WARM_START_MAX_LOG_LAMBDA`); None if there is none."""
    case = key[0]
    with _STEADY_CACHE_LOCK:
        kept = list(_STEADY_CACHE.values())
    best, distance = None, WARM_START_MAX_LOG_LAMBDA
    for entry in reversed(kept):
        other = entry.key[0]
        if (entry.key[2:] != key[2:] or (other.material1, other.material2) != (case.material1, case.material2)
                or entry.x.size != x.size or not np.array_equal(entry.x, x)):
            continue
        gap = abs(math.log(lam / entry.lam))
        if gap <= distance:
            best, distance = entry, gap
    return best


def _cache_key(case: ContactCase, state: LubricantState, lvl: AccuracyLevel, plan: Effects) -> tuple:
    """What the steady pressure and film depend on: the contact without its roughness, the lubricant state, the level
    and the two effects the Newton problem uses (the thermal correction is recomputed from the solution)."""
    return (replace(case, rq1=0.0, rq2=0.0), state, lvl, bool(plan.shear_thinning),
            bool(plan.compressibility and state.compressible))


def _result_from_steady(case, state, lvl, plan, scales: ContactScales, x, outcome: NewtonOutcome,
                        iterations: int) -> ContactResult:
    x_m = x * scales.a
    p_pa = outcome.p * scales.p_h
    h_m = outcome.h * scales.film_scale
    if not np.all(np.isfinite(p_pa)) or not np.all(np.isfinite(h_m)):
        raise SolverError(f"non-finite pressure or film for case {case.to_dict()}")
    eta = state.viscosity(p_pa)
    parts = friction_components(x_m, p_pa, h_m, eta, case.u_s, state.tau0, case.load_per_length)
    extra_thermal = {}
    converged, message = bool(outcome.converged), outcome.message
    if plan.thermal:
        thermal = thermal_couette_traction(x_m, h_m, state.temperature_table(p_pa), full_film_mask(p_pa), case.u1,
                                           case.u2, state.tau0, state.thermal)
        isothermal = parts
        parts = friction_components(x_m, p_pa, h_m, eta, case.u_s, state.tau0, case.load_per_length,
                                    couette_stress=thermal.shear_stress)
        extra_thermal = {"thermal": {**thermal.summary(), "mu_isothermal": isothermal["mu"],
                                     "properties": state.thermal.to_dict()},
                         "surface_temperature_rise_k": thermal.surface_rise,
                         "film_centre_temperature_rise_k": thermal.film_centre_rise}
        if not thermal.converged:
            converged = False
            message = (f"thermal correction not converged after {thermal.iterations} iterations (relative change "
                       f"{thermal.change:.2g}); {message}")
    h_dh, lambda_bar = dowson_higginson_lambda(case, state)
    residuals = {"reynolds": outcome.residual, "load": outcome.load, "step": outcome.step,
                 "complementarity": outcome.complementarity}
    message = message if converged else f"not converged: {message}"
    return ContactResult(
        mu=parts["mu"], h_min=float(np.min(h_m)), h_central=float(np.interp(0.0, x_m, h_m)),
        p_max=float(np.max(p_pa)), converged=converged, iterations=int(iterations),
        wall_time=0.0, level=lvl.name, effects=plan.to_dict(), mu_std=0.0, lambda_bar=lambda_bar,
        asperity_load_share=0.0, residuals=residuals, message=message, x=x_m, pressure=p_pa, film=h_m,
        extra={"mu_poiseuille": parts["mu_poiseuille"], "mu_couette": parts["mu_couette"], "n_nodes": int(x.size),
               "h0_m": outcome.h0 * scales.film_scale, "h_min_dowson_higginson_m": h_dh,
               "domain_a": (lvl.x_start, lvl.x_end), **extra_thermal},
    )
