"""Transient mixed-EHL line contact with moving roughness (paper Eq. 1–8).

The same discretisation and Newton solver as the steady smooth solve (:mod:`ehl_dataset.discretisation.reynolds`,
:mod:`ehl_dataset.solvers.newton`), on a grid that is uniform over the contact at the roughness resolution
(:func:`roughness_grid`), with

* the squeeze term ∂(ρh)/∂t by backward Euler (the previous step is the initial guess of the next),
* the film of paper Eq. 3, H = H0(t) + X²/2 + K P − R1(X − U1 T) − R2(X − U2 T); the two profiles come from
  :func:`ehl_dataset.model.roughness.plan_surfaces` (independent stretches of the shipped baseline profile scaled
  to Rq1, Rq2) and move with their surface speeds,
* the unified Reynolds equation (Hu & Zhu 2000): where the film is below :data:`H_CLOSED_M` the Poiseuille term is
  dropped and the equation reduces to ∂x(u_r ρh) + ∂t(ρh) = 0 (paper Eq. 2); those nodes are asperity contacts,
  whose traction is q = μ_d p (paper after Eq. 7),
* the load balance ∫p dx = W' at every step (H0(t) the unknown).

The run starts from the steady smooth solution, ramps the roughness amplitude in over the first part of the
start-up phase, lasts ``n_passes`` × the domain length / u_r (the start-up
transient is the time the disturbance needs to be carried through the domain), and μ, μ_std, the asperity load
share, the film and the pressure are averaged over the last ``average_fraction`` of the steps.

The model choices that comparison runs vary (how lubricant crosses an asperity contact, which flux the faces of a
contact carry, the hardness cap) are the fields of :class:`TransientOptions`; the defaults are what every dataset
uses. What each alternative gives, measured, is in docs/ehl_solver.md ("Asperity contact in the transient runs").
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..discretisation.deflection import influence_matrix
from ..discretisation.grid import banded_grid
from ..model.contact import ContactCase
from ..model.effects import Effects
from ..model.lubricant import LubricantState
from ..model.roughness import baseline_profile, plan_surfaces
from ..model.traction import friction_components
from ..validation import InputError, SolverError
from .levels import AccuracyLevel
from .newton import ReynoldsProblem, newton_solve
from .result import ContactResult
from .steady import ContactScales, dowson_higginson_lambda, moes_h_c, solve_steady, solve_steady_problem
from .time_average import RELIABLE_LENGTH, time_mean

H_CLOSED_M = 1e-9
"""Film [m] below which the Poiseuille term is dropped (unified Reynolds, Hu & Zhu 2000: a vanishing film)."""
YIELD_PRESSURE_PA = 6.8e9
"""Plastic pressure cap of asperity contacts [Pa]: the indentation hardness of case-hardened gear steel, 60 HRC ≈
697 HV (ASTM E140 conversion) ≈ 6.8 GPa (elastic–perfectly-plastic asperities, p ≤ H; Johnson 1985, §6)."""
FB_SMOOTHING = 1e-3
"""Smoothing s [p_h] of the complementarity functions at (nearly) closed-film nodes of rough runs: there
P·(−κR) = s² instead of P·(−κR) = 0 (and likewise at the pressure cap), an O(s) perturbation that lets Newton
converge where the exact (non-smooth) conditions make it cycle between active sets."""
SMOOTHING_FILM = 10.0
"""Nodes whose film is below this multiple of H_CLOSED_M at the start of a time step get the smoothed conditions."""
RAMP_FRACTION = 0.5
"""Fraction of the start-up (non-averaged) part of a run over which the roughness amplitude grows from 0 to 1."""
MAX_PRESSURE_STEP = 3.0
"""Largest pressure change per Newton iteration in a time step [p_h]: asperity contacts need pressures of several p_h."""
CLOSED_MARGIN = 1.01
"""A node counts as closed (asperity contact, and in the asperity load share) when h ≤ 1.01 H_CLOSED_M: the solver
holds closed nodes at H_CLOSED_M to its tolerance. Nodes closed at the start of a time step take the
elastic–plastic dry-contact condition (:func:`ehl_dataset.solvers.newton._capped`)."""
STEP_ITERATIONS = 40
"""Newton iterations allowed per time step (and per contact round) before the step is retried."""
MAX_SUBSTEPS = 16
"""Largest number of sub-steps of the regular attempts (the careful last attempts go to 4·MAX_SUBSTEPS)."""
RELAX_AFTER = 4
"""Consecutive time steps solved at the first attempt after which the starting sub-step count is halved again."""
ROUNDS_AFTER_FAILURE = 1
"""Contact rounds allowed after a Newton solve of the step failed (the added contact nodes sometimes rescue it;
more rounds from the same start only repeat the failure at 40 iterations each)."""


MU_FLOOR = 0.01
"""|μ| below which the standard-error target of the time average is taken relative to this value instead (pure
rolling: μ ≈ 0.001, whose relative error is not a useful accuracy measure)."""
CHECK_FRACTION = 0.25
"""An extended window is tested every CHECK_FRACTION × the base averaging window (in steps)."""


STEP_ATTEMPTS = ((1, False), (2, False), (4, False), (1, True), (4, True), (MAX_SUBSTEPS, True))
"""(sub-steps, Couette-only contact faces): the regular attempts of a time step that starts at one sub-step."""
CAREFUL_ATTEMPTS = ((4, False), (MAX_SUBSTEPS, True), (4 * MAX_SUBSTEPS, True))
"""Last attempts of a step, with the careful Newton settings: pressure steps of at most CAREFUL_PRESSURE_STEP and
CAREFUL_ITERATIONS iterations. Same discrete equations, only the globalisation differs (why they exist:
docs/ehl_solver.md, "Numerics, and why": careful attempts)."""
CAREFUL_PRESSURE_STEP = 1.0
"""Largest pressure change per Newton iteration [p_h] in the careful attempts."""
CAREFUL_ITERATIONS = 100
"""Newton iterations per solve in the careful attempts."""

CLOSURES = ("patch", "upstream_film")


@dataclass(frozen=True)
class TransientOptions:
    """Model choices of a transient mixed run, and its wall clock. The defaults are the production model (every
    dataset uses them); the alternatives exist for comparison runs (docs/ehl_solver.md, "Asperity contact in the
    transient runs", measures what each gives).

    ``closure``: how lubricant crosses a closed patch (asperity contact). ``"patch"``: the net flux that enters
    the patch is delivered to the first open node behind it
    (:func:`ehl_dataset.discretisation.reynolds.reroute_patch_fluxes`; mass-conserving). ``"upstream_film"``:
    closed nodes carry the Couette flux of the nearest open node upstream (:func:`_pass_through_film`; ignores the
    Poiseuille back-flow in front of the contact and so creates lubricant: films inflate at small λ̄).
    ``contact_faces_couette``: False: the faces between an open node and an asperity contact carry the unified
    Reynolds flux, whose Poiseuille part is driven by the contact pressure (Hu & Zhu's unified equation, paper
    Eq. 1–2); True: those faces carry the Couette flux only at every step (the solid contact pressure drives no
    lubricant; with False the run still falls back to it on steps where Newton fails, :func:`step_attempts`).
    ``contact_rounds``: times a time step is redone with the open nodes whose film fell below H_c added to the
    closed (contact) set.
    ``yield_pressure_pa``: the plastic pressure cap of asperity contacts [Pa] (:data:`YIELD_PRESSURE_PA`; ``inf``
    switches the cap off).
    ``clock``: the wall clock [s] that the budget ``time_limit_s`` and the result's ``wall_time`` read
    (``time.perf_counter``; a stand-in makes a budget a count of time steps in tests).
    """

    closure: str = "patch"
    contact_faces_couette: bool = False
    contact_rounds: int = 4
    yield_pressure_pa: float = YIELD_PRESSURE_PA
    clock: Callable[[], float] = time.perf_counter

    def __post_init__(self):
        if self.closure not in CLOSURES:
            raise InputError("closure", self.closure, f"one of {list(CLOSURES)}")
        if isinstance(self.contact_rounds, bool) or not isinstance(self.contact_rounds, int) or self.contact_rounds < 0:
            raise InputError("contact_rounds", self.contact_rounds, "an integer >= 0")
        if not (isinstance(self.yield_pressure_pa, (int, float)) and self.yield_pressure_pa > 0):
            raise InputError("yield_pressure_pa", self.yield_pressure_pa, "a pressure > 0 Pa (inf: no cap)")


def step_attempts(start: int = 1) -> tuple[tuple[int, bool], ...]:
    """(sub-steps, Couette-only contact faces) tried in turn for a time step, beginning with ``start`` sub-steps.

    Unified contact faces at start, 2·start, 4·start sub-steps, then whatever of the base sequence
    STEP_ATTEMPTS ((1, F), (2, F), (4, F), (1, T), (4, T), (MAX_SUBSTEPS, T)) was not tried yet (then the
    CAREFUL_ATTEMPTS, which the run adds with careful Newton settings). The attempts with Couette-only
    contact faces are the fallback for steps where Newton cycles between the contact pressure and the flux it
    throttles (better conditioned, still mass-conserving); such steps are counted in
    ``extra["couette_fallback_steps"]``. If all fail the run is returned not converged. Newton's success is not
    monotone in the step size, so a larger ``start`` never removes an attempt of the base sequence.

    The run adapts ``start`` (:func:`next_start`): a step that needed k sub-steps with unified faces makes the next
    steps begin at k (a finer time step is only more accurate), so the failing attempts, 40 Newton iterations per
    contact round each, are not repeated every step (docs/ehl_solver.md, "Numerics, and why": adaptive start).
    """
    start = int(min(max(start, 1), MAX_SUBSTEPS))
    first = tuple((k, False) for k in (start, 2 * start, 4 * start) if k <= MAX_SUBSTEPS)
    return first + tuple(a for a in STEP_ATTEMPTS if a not in first)


def next_start(start: int, used: int, couette: bool, first_attempt: bool, calm_steps: int) -> tuple[int, int]:
    """The sub-step count the next time step begins with, and the updated count of calm steps.

    ``used``: sub-steps of the attempt that solved this step, ``couette``: whether that attempt had Couette-only
    contact faces, ``first_attempt``: whether it was the first tried. A step that the unified faces solved only
    with more sub-steps raises the start to ``used`` (a Couette-face success leaves it: the fallback says nothing
    about the step size the unified faces need); after RELAX_AFTER steps solved at the first attempt the start is
    halved (down to 1), so the run returns to the level's time step once the hard stretch has passed.
    """
    if not first_attempt:
        return (start if couette else max(start, used)), 0
    calm_steps += 1
    if start > 1 and calm_steps >= RELAX_AFTER:
        return start // 2, 0
    return start, calm_steps



def roughness_grid(case: ContactCase, lvl: AccuracyLevel, correlation_length_m: float,
                   h_c: float = math.inf) -> tuple[np.ndarray, bool]:
    """Grid [a] for a rough run: spacing ``dx_rough`` correlation lengths (at most ``dx_rough_max``·a) over the
    contact band −1.15a…1.06a, in the inlet band also at most ``inlet_resolution``·H_c^(2/3) (the heavy-load inlet
    scale, as in the steady grid), growing to ``dx_coarse`` outside. If that exceeds ``max_nodes_rough`` nodes
    the roughness spacing is coarsened until it fits; the flag says so.
    """
    a = case.half_width
    dx_r = min(lvl.dx_rough * correlation_length_m / a, lvl.dx_rough_max)
    capped = False
    while True:
        dx_in = min(dx_r, lvl.inlet_resolution * h_c ** (2.0 / 3.0), lvl.dx_fine * 4.0)
        bands = ((lvl.inlet_band[0], lvl.outlet_band[1], dx_r), (lvl.inlet_band[0], lvl.inlet_band[1], dx_in))
        x = banded_grid(lvl.x_start, lvl.x_end, bands, max(lvl.dx_coarse, dx_r), lvl.transition)
        if x.size <= lvl.max_nodes_rough:
            return x, capped
        capped = True
        dx_r *= 1.25


def time_steps(lvl: AccuracyLevel, dx: float) -> tuple[float, float, int, float]:
    """(Δt, t_end, n_steps, t_ramp) of a rough run's base window, in units of a/u_r, for the roughness spacing
    ``dx`` [a]: Δt = ``courant``·dx stretched to t_end/n_steps, t_end = ``n_passes`` × the domain length, between
    8 and ``max_steps_rough`` steps. The roughness amplitude is ramped in over t_ramp, the first RAMP_FRACTION of
    the start-up phase (excluded from the averages anyway): switching it on at once is a shock the first Newton
    steps cannot absorb at low λ̄. Shared by the Newton and the relaxation transient solvers."""
    t_end = lvl.n_passes * (lvl.x_end - lvl.x_start)
    n_steps = min(max(int(math.ceil(t_end / (lvl.courant * dx))), 8), lvl.max_steps_rough)
    return t_end / n_steps, t_end, n_steps, RAMP_FRACTION * (1.0 - lvl.average_fraction) * t_end


def solve_transient(case: ContactCase, state: LubricantState, lvl: AccuracyLevel, plan: Effects,
                    roughness=None, time_limit_s: float | None = None,
                    options: TransientOptions = TransientOptions()) -> ContactResult:
    """Transient mixed solve of one rough contact; see the module docstring. ``roughness``: the profile both
    surfaces take (a :class:`~ehl_dataset.model.roughness.RoughnessProfile`, scaled to Rq1 and Rq2); None: the
    shipped baseline. ``time_limit_s``: wall-time budget [s]; checked before every time step, and when it is spent
    the run ends ``converged=False`` ("wall-time limit ..."). ``options``: :class:`TransientOptions`."""
    clock = options.clock
    start = clock()
    scales = ContactScales.of(case, state, plan.shear_thinning)
    a, film_scale = scales.a, scales.film_scale
    profile = roughness if roughness is not None else baseline_profile()
    x, capped = roughness_grid(case, lvl, profile.correlation_length, moes_h_c(case, state, scales))
    dx = float(np.min(np.diff(x[(x > lvl.inlet_band[1]) & (x < lvl.outlet_band[1])])))  # roughness spacing
    kmat = influence_matrix(x)
    problem = ReynoldsProblem(x=x, kmat=kmat, gap=0.5 * x**2, lam=scales.lam, p_h=case.p_h, state=state,
                              compressible=plan.compressibility and state.compressible, shear=scales.shear)
    tolerances = dict(tol_residual=lvl.tol_residual, tol_load=lvl.tol_load, tol_step=lvl.tol_step,
                      max_iterations=lvl.max_iterations)

    # 1. the steady smooth solution, moved onto the uniform grid
    smooth_plan = Effects(False, False, plan.shear_thinning, plan.compressibility, plan.mode, {})
    smooth = solve_steady(case, state, lvl, smooth_plan)
    if not smooth.converged:
        return _failed(case, state, lvl, plan, smooth.iterations, clock() - start, f"smooth start: {smooth.message}",
                       smooth.residuals)
    p0 = np.interp(x * a, smooth.x, smooth.pressure) / case.p_h
    h0 = smooth.extra["h0_m"] / film_scale
    first = newton_solve(problem, p0, h0, **tolerances)
    iterations = smooth.iterations + first.iterations
    if not first.converged:  # e.g. a coarse uniform grid at heavy load: globalised solve with continuation
        first, its, _ = solve_steady_problem(problem, p0, h0, lvl)
        iterations += its
    if not first.converged:
        return _failed(case, state, lvl, plan, iterations, clock() - start,
                       f"smooth start on the rough grid: {first.message}", _residuals(first))
    m_ref = float(np.interp(0.0, x, problem.fluid(first.p, first.h)[3]))

    # 2. time stepping with the roughness switched on
    d_t, t_end, n_steps, t_ramp = time_steps(lvl, dx)
    # the averaging window starts after the start-up transient of the base run and may be extended (same time
    # step) until the standard error of the time-averaged μ meets the level's target, up to max_passes
    first_avg_base = int(n_steps * (1.0 - lvl.average_fraction))
    n_max = n_steps
    if lvl.mu_sem_target > 0.0 and lvl.max_passes > lvl.n_passes:
        n_max = int(round(n_steps * lvl.max_passes / lvl.n_passes))
    check_every = max(int(CHECK_FRACTION * (n_steps - first_avg_base)), 1)
    time_scale = a / case.u_r
    # laid out for the base run (a run that stops there is the same whatever its cap); an extension reads on
    surfaces = plan_surfaces(case, x * a, t_end * time_scale, profile)
    problem.h_closed = H_CLOSED_M / film_scale
    problem.p_cap = options.yield_pressure_pa / case.p_h
    problem.closure = options.closure
    problem.scaled_norm = True
    # a time step that needs many iterations is cheaper to redo with sub-steps than to iterate on
    step_tolerances = dict(tolerances, max_iterations=min(lvl.max_iterations, STEP_ITERATIONS),
                           max_pressure_step=MAX_PRESSURE_STEP)
    careful_tolerances = dict(step_tolerances,
                              max_iterations=max(step_tolerances["max_iterations"], CAREFUL_ITERATIONS),
                              max_pressure_step=CAREFUL_PRESSURE_STEP)
    p, h0 = first.p, first.h0
    m_prev = problem.fluid(p, first.h)[3]
    t = 0.0
    history = {k: [] for k in ("t", "mu", "share", "h_min", "h_c", "p_max", "load", "yielded")}
    worst = {"reynolds": 0.0, "load": 0.0, "step": 0.0, "complementarity": 0.0}
    failure = ""
    time_limited = False
    fallback_steps = substep_steps = careful_steps = calm_steps = 0
    cost = NewtonCost()
    start_substeps = 1
    for step in range(n_max):
        if step >= n_steps and (step - n_steps) % check_every == 0:
            so_far = time_mean(history["mu"][first_avg_base:])
            if so_far.within(_sem_tolerance(lvl, so_far.mean)):
                break
        if time_limit_s is not None and clock() - start > time_limit_s:
            time_limited = True
            if step >= n_steps:  # the base run is complete: the budget only ends the window's extension
                break
            failure = (f"wall-time limit of {time_limit_s:g} s reached after {step} of {n_steps} time steps "
                       f"(t = {t * time_scale:.3e} s)")
            break
        outcome, d_sub = None, d_t
        attempts = [(k, couette, False) for k, couette in step_attempts(start_substeps)]
        attempts += [(k, couette, True) for k, couette in CAREFUL_ATTEMPTS]
        for attempt, (n_sub, couette_faces, careful) in enumerate(attempts):
            newton_options = careful_tolerances if careful else step_tolerances
            problem.contact_faces_couette = options.contact_faces_couette or couette_faces
            d_sub = d_t / n_sub
            ok, p_try, h0_try, m_try = True, p, h0, m_prev
            for k in range(n_sub):
                t_k = t + (k + 1) * d_sub
                r1, r2 = surfaces.at(t_k * time_scale)
                ramp = min(1.0, t_k / t_ramp) if t_ramp > 0 else 1.0
                problem.gap = 0.5 * x**2 - ramp * (r1 + r2) / film_scale
                problem.squeeze = problem.weights / d_sub
                problem.m_old = m_try
                # smoothed complementarity only where the film is (nearly) closed at the start of the step: the
                # exact conditions elsewhere (the inlet build-up sets the film and is sensitive to any smoothing)
                film_start = problem.film(p_try, h0_try)[1:-1]
                problem.smoothing = np.where(film_start < SMOOTHING_FILM * problem.h_closed, FB_SMOOTHING, 0.0)
                # nodes closed at the start of the step take the elastic-plastic dry-contact condition
                closed = np.zeros(x.size, dtype=bool)
                closed[1:-1] = film_start < CLOSED_MARGIN * problem.h_closed
                problem.closed = closed
                if options.closure == "upstream_film":
                    problem.closed_film = _pass_through_film(problem.film(p_try, h0_try), closed, problem.h_closed)
                # monotone=False: a damped step (ω < 0.3) is accepted without a decrease of the merit
                outcome = newton_solve(problem, p_try, h0_try, m_ref=m_ref, monotone=False, freeze_scaling=True,
                                       **newton_options)
                failures = int(not outcome.converged)
                cost.count(outcome)
                for _ in range(options.contact_rounds):
                    # an open node whose film fell below H_c during the step is an asperity contact too: add it to
                    # the closed set and redo the step (the closed set only grows within a step, so this ends)
                    penetrated = ~problem.closed & (outcome.h < problem.h_closed)
                    penetrated[[0, -1]] = False
                    if not penetrated.any():
                        break
                    problem.closed = problem.closed | penetrated
                    problem.smoothing = np.where(problem.closed[1:-1], FB_SMOOTHING, problem.smoothing)
                    # a round starts from the previous round's solution when that converged
                    start_p, start_h0 = (outcome.p, outcome.h0) if outcome.converged else (p_try, h0_try)
                    outcome = newton_solve(problem, start_p, start_h0, m_ref=m_ref, monotone=False,
                                           freeze_scaling=True, **newton_options)
                    failures += int(not outcome.converged)
                    cost.count(outcome)
                    if failures > ROUNDS_AFTER_FAILURE:
                        break
                if not outcome.converged:
                    ok = False
                    break
                p_try, h0_try = outcome.p, outcome.h0
                m_try = problem.fluid(p_try, outcome.h)[3]
            if ok:
                break
        if not ok:
            failure = f"time step at t = {t * time_scale:.3e} s did not converge ({outcome.message})"
            break
        t += d_t
        fallback_steps += int(problem.contact_faces_couette and not options.contact_faces_couette)
        substep_steps += int(n_sub > 1)
        careful_steps += int(careful)
        start_substeps, calm_steps = next_start(start_substeps, n_sub, couette_faces, attempt == 0,
                                                   calm_steps)
        p, h0, m_prev = p_try, h0_try, m_try
        for key, value in _residuals(outcome).items():
            worst[key] = max(worst[key], abs(value))
        _record(history, t, case, state, x * a, p * case.p_h, outcome.h * film_scale, H_CLOSED_M,
                options.yield_pressure_pa)

    iterations += cost.iterations
    converged = not failure
    steps = len(history["t"])
    if steps == 0:
        return _failed(case, state, lvl, plan, iterations, clock() - start, failure, worst,
                       {"n_steps": 0, "n_steps_planned": int(n_steps), "time_limited": time_limited})
    first_avg = first_avg_base if (converged and steps >= n_steps) else max(steps // 2, 0)
    window = slice(first_avg, steps)
    mu = np.asarray(history["mu"][window])
    mu_mean = time_mean(mu) if mu.size >= 2 else None
    sem = mu_mean.standard_error if mu_mean else math.nan
    share_sem = time_mean(history["share"][window]).standard_error if mu.size >= 2 else math.nan
    target_met = bool(mu_mean) and mu_mean.within(_sem_tolerance(lvl, mu_mean.mean))
    h_dh, lambda_bar = dowson_higginson_lambda(case, state)
    film = outcome.h * film_scale
    result = ContactResult(
        mu=float(mu.mean()), mu_std=float(mu.std()),
        h_min=float(max(np.min(history["h_min"][window]), 0.0)),
        h_central=float(np.mean(history["h_c"][window])),
        p_max=float(np.max(history["p_max"][window])), converged=converged, iterations=int(iterations),
        wall_time=clock() - start, level=lvl.name, effects=_recorded_plan(plan, options.yield_pressure_pa),
        lambda_bar=lambda_bar,
        asperity_load_share=float(np.mean(history["share"][window])), residuals=worst,
        mu_sem=sem,
        message=_message(converged, failure, steps, fallback_steps, careful_steps)
        + _window_note(converged, lvl, target_met, sem, mu_mean, steps, n_steps,
                       time_limit_s if (converged and time_limited) else None),
        x=x * a, pressure=p * case.p_h, film=film,
        extra={"n_nodes": int(x.size), "dx_m": float(dx * a), "dt_s": float(d_t * time_scale),
               "n_steps": int(steps), "n_steps_planned": int(n_steps), "n_steps_max": int(n_max),
               "time_limited": time_limited,
               "mu_inefficiency_steps": mu_mean.inefficiency if mu_mean else math.nan,
               "mu_effective_samples": mu_mean.effective_samples if mu_mean else math.nan,
               "mu_sem_reliable": bool(mu_mean.reliable) if mu_mean else False,
               "mu_sem_target": float(lvl.mu_sem_target), "mu_sem_target_met": target_met,
               "asperity_load_share_sem": float(share_sem),
               "averaging_time_s": float((steps - first_avg) * d_t * time_scale),
               "courant_effective": float(d_t / dx), "average_from_step": int(first_avg),
               "roughness_resolution_capped": capped, "roughness_profile": profile.source,
               "roughness_correlation_length_m": float(profile.correlation_length),
               "surfaces_independent": bool(surfaces.disjoint_until(t * time_scale)),
               "h_min_dowson_higginson_m": h_dh, "h_closed_m": H_CLOSED_M,
               "yield_pressure_pa": options.yield_pressure_pa,
               "yielded_load_share": float(np.mean(history["yielded"][window])),
               "fb_smoothing": FB_SMOOTHING,
               "contact_faces_couette": options.contact_faces_couette,
               "couette_fallback_steps": int(fallback_steps),
               "substep_steps": int(substep_steps),
               "careful_steps": int(careful_steps),
               "max_load_error": float(np.max(np.abs(history["load"]))),
               **cost.as_extra(),
               "mu_series": np.asarray(history["mu"]), "t_series_s": np.asarray(history["t"]) * time_scale},
    )
    if not all(np.isfinite([result.mu, result.h_central, result.p_max])):
        raise SolverError(f"non-finite transient result for case {case.to_dict()}")
    return result


class NewtonCost:
    """What the time stepping spent on Newton solves (a cost record; it changes no solved value): solves and
    iterations of the solves that converged and of those that failed (a failed solve runs to its iteration cap and
    is then retried with sub-steps). Each iteration is one dense LU factorisation of N × N, the dominant cost
    (measured: docs/ehl_solver.md, "Where the time of a rough run goes")."""

    FIELDS = ("newton_solves", "newton_solves_failed", "newton_step_iterations", "newton_iterations_failed")
    """The ``extra`` keys of the record (:meth:`as_extra`)."""

    def __init__(self):
        self.solves = self.failed = self.iterations = self.failed_iterations = 0

    def count(self, outcome) -> None:
        """Add one :class:`~ehl_dataset.solvers.newton.NewtonOutcome`."""
        self.solves += 1
        self.iterations += int(outcome.iterations)
        if not outcome.converged:
            self.failed += 1
            self.failed_iterations += int(outcome.iterations)

    def as_extra(self) -> dict[str, int]:
        """The record as ``extra`` fields of a result."""
        return dict(zip(self.FIELDS, (self.solves, self.failed, self.iterations, self.failed_iterations)))


def _message(converged: bool, failure: str, steps: int, fallback_steps: int, careful_steps: int) -> str:
    """"converged", with how many steps needed the Couette-face fallback or the careful Newton settings when any did
    (a run dominated by the fallback is solved with different contact-face physics, and says so)."""
    if not converged:
        return f"not converged: {failure}"
    notes = []
    if fallback_steps:
        notes.append(f"{fallback_steps} of {steps} steps with Couette-only contact faces")
    if careful_steps:
        notes.append(f"{careful_steps} with careful Newton settings")
    return "converged" + (f" ({', '.join(notes)})" if notes else "")


def _sem_tolerance(lvl: AccuracyLevel, mean: float) -> float:
    """Standard error the time-averaged μ may have at this level: ``mu_sem_target`` × max(|μ|, MU_FLOOR)."""
    return lvl.mu_sem_target * max(abs(mean), MU_FLOOR)


def _window_note(converged: bool, lvl: AccuracyLevel, target_met: bool, sem: float, mu_mean, steps: int,
                 n_steps: int, budget_s: float | None = None) -> str:
    """"; ..." when a converged run's time-averaged μ missed the level's standard-error target or reliability
    (window at its cap, or its extension stopped by the wall-time budget ``budget_s``)."""
    if not converged or lvl.mu_sem_target <= 0.0 or target_met or mu_mean is None:
        return ""
    where = (f"the wall-time limit of {budget_s:g} s stopped the extension" if budget_s is not None
             else "the level's cap")
    why = (f"standard error of the time-averaged mu {sem:.2g} above the target {lvl.mu_sem_target:g} x "
           f"max(|mu|, {MU_FLOOR:g})" if sem > _sem_tolerance(lvl, mu_mean.mean) else
           f"averaging window shorter than {RELIABLE_LENGTH:g} correlation times (its standard error is uncertain)")
    return f"; {why} after {steps} steps ({steps / n_steps:.2g} x the base run, {where})"


def _pass_through_film(film: np.ndarray, closed: np.ndarray, h_closed: float) -> np.ndarray:
    """Film [dimensionless] whose Couette flux a closed node carries: that of the nearest open node upstream.

    In a line contact a closed node that carried only ρ̄H_c would starve everything downstream of it (there is no
    side flow in 1-D), and the film behind every asperity contact would collapse. The lubricant trapped in the
    roughness valleys passes through an asperity contact (the 1-D trace of the flow around it), so the flux leaving
    a closed patch is the flux that entered it; mass is conserved. Frozen over a time step (explicit in time).
    """
    out = np.maximum(film, h_closed)
    last = out[0]
    for i in range(film.size):
        if closed[i]:
            out[i] = last
        else:
            last = out[i]
    return out


def _recorded_plan(plan: Effects, yield_pressure_pa: float) -> dict:
    """The effect plan with the plastic pressure cap recorded (``Effects`` has no flag for it)."""
    record = plan.to_dict()
    record["reasons"] = dict(record.get("reasons") or {})
    record["reasons"]["plastic_cap"] = (f"asperity pressure capped at the hardness {yield_pressure_pa / 1e9:.1f} GPa "
                                        "(60 HRC case-hardened steel, elastic-perfectly-plastic asperities)")
    return record


def _residuals(outcome) -> dict[str, float]:
    return {"reynolds": outcome.residual, "load": outcome.load, "step": outcome.step,
            "complementarity": outcome.complementarity}


def _record(history, t, case, state, x_m, p_pa, h_m, h_closed_m, p_yield_pa=math.inf):
    contact = h_m <= CLOSED_MARGIN * h_closed_m
    eta = state.viscosity(p_pa)
    parts = friction_components(x_m, p_pa, np.maximum(h_m, h_closed_m), eta, case.u_s, state.tau0,
                                case.load_per_length, state.mu_d, contact)
    load = float(np.sum(0.5 * (p_pa[1:] + p_pa[:-1]) * np.diff(x_m)))
    contact_load = float(np.sum(0.5 * ((p_pa * contact)[1:] + (p_pa * contact)[:-1]) * np.diff(x_m)))
    history["t"].append(t)
    history["mu"].append(parts["mu"])
    history["share"].append(contact_load / load if load > 0 else 0.0)
    history["h_min"].append(float(np.min(h_m)))
    history["h_c"].append(float(np.interp(0.0, x_m, h_m)))
    history["p_max"].append(float(np.max(p_pa)))
    history["load"].append(load / case.load_per_length - 1.0)
    yielded = p_pa >= (1.0 - 1e-6) * p_yield_pa
    yielded_load = float(np.sum(0.5 * ((p_pa * yielded)[1:] + (p_pa * yielded)[:-1]) * np.diff(x_m)))
    history["yielded"].append(yielded_load / load if load > 0 else 0.0)


def _failed(case, state, lvl, plan, iterations, wall_time, message, residuals, extra=None) -> ContactResult:
    """A run that ended without an averaged result (``wall_time`` [s] spent): NaN outputs and the message."""
    _, lambda_bar = dowson_higginson_lambda(case, state)
    nan = float("nan")
    return ContactResult(mu=nan, h_min=nan, h_central=nan, p_max=nan, converged=False, iterations=int(iterations),
                         wall_time=wall_time, level=lvl.name, effects=plan.to_dict(),
                         lambda_bar=lambda_bar, residuals=dict(residuals), message=f"not converged: {message}",
                         extra=dict(extra or {}))
