"""Transient mixed-EHL line contact by semi-system relaxation (Hu & Zhu 2000, J. Tribol. 122:1–9).

An independent solver for the transient mixed problem of paper Eq. 1–8 (moving roughness, asperity contact),
meant for heavy asperity interference (λ̄ ≲ 1), where the full-system Newton of :mod:`ehl_dataset.ehl_transient`
cycles. Same discrete equations (finite volumes of :mod:`ehl_dataset.reynolds`, the unified Reynolds equation of
:class:`ehl_dataset.ehl_newton.ReynoldsProblem`), a different solution method:

* **Unified Reynolds** (Hu & Zhu): the Poiseuille coefficient ε = ρ̄H³cosh(τ_m/τ0)/(η̄λ̄) (paper Eq. 1b) is
  dropped where the film is below h_closed (with the same C¹ fade between 2 h_closed and h_closed as the Newton
  solver), so in asperity contact the equation reduces to ∂(ρh)/∂x + ∂(ρh)/∂t = 0 (paper Eq. 2).
* **Semi-system iteration**: each sweep solves the Reynolds equation linearised in P with a *banded* Jacobian:
  the exact local derivatives of the Poiseuille, Couette and squeeze terms, with the film's dependence on the
  pressure H = H0 + G + K P kept only through the deflection coefficients K_ij of the own node and its
  ``bandwidth`` neighbours (the differential-deflection idea of Hu & Zhu: in a contact zone the reduced equation
  involves H_i − H_{i−1}, whose own-node coefficient K_ii − K_{i−1,i} is what determines the pressure there).
  The far-field deflection is lagged (evaluated with the current pressure, dense matrix product). The band is
  max(:data:`BANDWIDTH`, :data:`BAND_FRACTION`·N); the lagged far field makes it a relaxation, not a Newton, method.
* **Load balance** every sweep: H0 is an extra unknown of the bordered banded system (Schur complement on one
  row), so ∫P dX = π/2 holds to first order after each sweep, not by a slow relaxation of H0.
* **Cavitation**: primal–dual active set (held at P = 0 where the local update P − R/J_ii ≤ 0), P ≥ 0 by projection.
* **Asperity contact** (:data:`CONTACT_MODEL` = "gap"): a node whose film falls below h_closed gets the row
  H_i = H_closed (pressure from elasticity, as in a dry contact) and leaves the contact set when it would need
  tension. Hu & Zhu's reduced transport equation ("transport") let negative films persist and cycled. Caveat: the
  gap rows are not mass-conserving at a contact entry, which admits spurious contact states (docs/ehl_mixed_relaxation.md).
* Steps are damped (at most ``MAX_STEP`` p_h per sweep, relaxation ``OMEGA``).

A time step converges when the Reynolds residual on pressurised nodes (relative to the Couette flux at the centre of
the smooth solution), the load error and the last pressure change are below the level's tolerances
(:data:`TOLERANCES`). The run starts from the steady smooth solution on the rough grid (H1's Newton solver, by
import), ramps the roughness amplitude in, and averages μ, μ_std, h_min, the asperity load share over the last
``average_fraction`` of the steps. A step that does not converge within :data:`MAX_SWEEPS` sweeps is retried with
2, 4, 8 sub-steps; if it still fails the run is returned ``converged=False`` with the residual history.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numba
import numpy as np
import scipy.linalg

from .contact import ContactCase
from .deflection import influence_matrix
from .effects import Effects
from .ehl_newton import ReynoldsProblem, newton_solve
from .reynolds import assemble
from .levels import AccuracyLevel, get_level
from .lubricant import Lubricant
from .result import ContactResult
from .traction import friction_components
from .validation import InputError, SolverError

H_CLOSED_M = 1e-9
"""Film [m] below which the Poiseuille term is dropped (unified Reynolds; same as the Newton solver)."""
BANDWIDTH = 40
"""Deflection neighbours (each side) kept implicit in the semi-system Jacobian (3 diverges at ω = 1 already on
smooth problems: the lagged far field of the log kernel is too large; 40 converges in 3–8 sweeps, measured)."""
BAND_FRACTION = 0.25
"""The band is at least this fraction of the grid: with a fixed 40-node band the lagged far field stalls the
iteration on the 480-node heavy-load grids (2.5 GPa, 80 mm: residual 1.8e-4 after 200 sweeps, measured); the full
band converges there in a median of 5 sweeps per step."""
OMEGA = 1.0
"""Relaxation factor of the pressure correction."""
SECOND_ORDER_COUETTE = True
"""Linear-upwind (second-order) Couette flux in the rough time steps; False: first-order upwind (monotone)."""
CONTACT_MODEL = "gap"
"""Asperity-contact nodes: "gap" holds the film at h_closed there (H_i = H_closed, P_i ≥ 0 from elasticity: a
dry-contact complementarity, nodes enter when H_i < H_closed and leave when they would need tension); "transport"
keeps Hu & Zhu's reduced equation ∂(ρh)/∂x + ∂(ρh)/∂t = 0, which lets negative films persist (measured)."""
FACE_MEAN = "arithmetic"
"""Face mean of the Poiseuille coefficient: "arithmetic" (the discretisation of :mod:`ehl_dataset.reynolds`,
shared with the Newton solver) or "harmonic" (:func:`ehl_dataset.reynolds.face_flux` with ``harmonic``; tried against the 2-cycles, changes μ by
4 % at λ̄ = 3 on the fast grid and is not needed with the "gap" contact model; kept as an option)."""
LAG_EPSILON = "fade"
"""Picard (lagged) treatment of ε: "all" nodes, only in and below the "fade" band of the unified Reynolds
equation, or "none" (exact derivatives); see :func:`_linearised`."""
ADAPTIVE = True
"""Halve the relaxation factor when a sweep does not lower max residual + load error, grow it by 1.5 when it does."""
OMEGA_MIN = 0.05
"""Smallest adaptive relaxation factor."""
MAX_STEP = 0.5
"""Largest pressure change per sweep [p_h]."""
MAX_SWEEPS = 200
"""Sweeps allowed per time step before it is retried with sub-steps."""
MAX_RETRIES = 3
"""Sub-step halvings of a failing time step before the run is marked not converged."""


@dataclass(frozen=True)
class Tolerances:
    """Per time step: ``residual`` max |R|/m_ref on pressurised nodes, ``load`` relative load error, ``step``
    max pressure change of the last sweep [p_h]."""

    residual: float
    load: float
    step: float


TOLERANCES = {"fast": Tolerances(1e-4, 1e-4, 1e-4), "standard": Tolerances(2e-5, 2e-5, 2e-5),
              "reference": Tolerances(5e-6, 5e-6, 5e-6)}
"""Stopping rules per accuracy level (unknown level names use ``standard``)."""


@numba.njit(cache=True)
def semi_system_bands(dp, dh, kmat, lower, upper):
    """Banded semi-system Jacobian of the interior Reynolds residuals and its H0 column.

    J_ij = ∂R_i/∂P_j|local + Σ_o ∂R_i/∂H_{i+o−2} K_{i+o−2, j} for i − ``lower`` ≤ j ≤ i + ``upper`` (interior
    nodes 1 … N − 2), in the storage of :func:`scipy.linalg.solve_banded` (ab[upper + r − c, c] = J[r, c]); the
    column ∂R_i/∂H0 = Σ_o ∂R_i/∂H_{i+o−2}. ``dp``, ``dh`` from :func:`ehl_dataset.reynolds.assemble`
    (offsets −2 … +1).
    """
    n = kmat.shape[0]
    n_in = n - 2
    ab = np.zeros((lower + upper + 1, n_in))
    col_h0 = np.zeros(n_in)
    for r in range(n_in):
        i = r + 1
        for o in range(4):
            j = i + o - 2
            if j < 0 or j >= n:
                continue
            coef = dh[i, o]
            col_h0[r] += coef
            if 1 <= j <= n - 2 and -lower <= j - i <= upper:
                ab[upper + r - (j - 1), j - 1] += dp[i, o]
            if coef != 0.0:
                lo = max(1, i - lower)
                hi = min(n - 2, i + upper)
                for jj in range(lo, hi + 1):
                    ab[upper + r - (jj - 1), jj - 1] += coef * kmat[j, jj]
    return ab, col_h0


def _linearised(problem: ReynoldsProblem, p, h):
    """Reynolds residual and banded derivatives; with :data:`LAG_FADE` the derivatives of ε are dropped where the
    film is inside the fade band (h_closed, 2 h_closed) or below it (Picard in ε there, as in Hu & Zhu's
    Gauss–Seidel, whose coefficients are those of the previous sweep): ∂ε/∂H of the fade is ~1/h_closed and
    sends a Newton-type step far past the 1 nm band."""
    eps, eps_p, eps_h, m, m_p, m_h = problem.fluid(p, h)
    if LAG_EPSILON == "all":
        eps_h = np.zeros_like(eps_h)
        eps_p = np.zeros_like(eps_p)
    elif LAG_EPSILON == "fade" and problem.h_closed > 0.0:
        band = h < 2.0 * problem.h_closed
        eps_h = np.where(band, 0.0, eps_h)
        eps_p = np.where(band, 0.0, eps_p)
    return assemble(problem.x, p, eps, eps_p, eps_h, m, m_p, m_h, problem.squeeze, problem.m_old,
                    problem.face_order(), problem.face_poiseuille(), FACE_MEAN == "harmonic")


@numba.njit(cache=True)
def _contact_rows(ab, col_h0, kmat, idx, lower, upper):
    """Replace the interior rows ``idx`` of the banded system by the contact condition H_i = H_closed:
    ∂H_i/∂P_j = K_ij (within the band), ∂H_i/∂H0 = 1 (residual H_i − H_closed, judged against m_ref)."""
    n_in = ab.shape[1]
    for r in idx:
        for c in range(max(0, r - lower), min(n_in, r + upper + 1)):
            ab[upper + r - c, c] = kmat[r + 1, c + 1]
        col_h0[r] = 1.0


@numba.njit(cache=True)
def _identity_rows(ab, col_h0, idx, lower, upper):
    """Replace the interior rows ``idx`` by δP_i = (right-hand side) (cavitated nodes held at P = 0)."""
    n_in = ab.shape[1]
    for r in idx:
        for c in range(max(0, r - lower), min(n_in, r + upper + 1)):
            ab[upper + r - c, c] = 0.0
        ab[upper, r] = 1.0
        col_h0[r] = 0.0


@dataclass
class StepOutcome:
    """One time step: ``p``, ``h0``, ``h`` (dimensionless), ``converged``, ``sweeps``, final norms."""

    p: np.ndarray
    h0: float
    h: np.ndarray
    converged: bool
    sweeps: int
    residual: float
    load: float
    step: float
    history: list = None
    contact: np.ndarray | None = None


def relax_step(problem: ReynoldsProblem, p0: np.ndarray, h00: float, m_ref: float, tol: Tolerances,
               max_sweeps: int | None = None, bandwidth: int | None = None) -> StepOutcome:
    """Semi-system relaxation of one (time-step or steady) discrete problem from (``p0``, ``h00``).

    See the module docstring. Never raises for non-convergence: ``converged=False`` with the norms.
    """
    n = problem.x.size
    p = np.asarray(p0, dtype=float).copy()
    p[0] = p[-1] = 0.0
    h0 = float(h00)
    w_in = problem.weights[1:-1] / (0.5 * math.pi)
    bandwidth = max(BANDWIDTH, int(BAND_FRACTION * n)) if bandwidth is None else int(bandwidth)
    max_sweeps = MAX_SWEEPS if max_sweeps is None else int(max_sweeps)
    lower, upper = max(bandwidth, 2), max(bandwidth, 1)
    step = math.inf
    r_free = load_err = math.inf
    history = []
    omega_adapt = 1.0
    merit_prev = math.inf
    gap_model = CONTACT_MODEL == "gap" and problem.h_closed > 0.0
    contact = np.zeros(n - 2, dtype=bool)
    for sweep in range(max_sweeps + 1):
        h = problem.film(p, h0)
        res, dp, dh = _linearised(problem, p, h)
        ab, col_h0 = semi_system_bands(dp, dh, problem.kmat, lower, upper)
        r_in = res[1:-1]
        if gap_model:
            contact |= h[1:-1] < problem.h_closed
            if contact.any():
                _contact_rows(ab, col_h0, problem.kmat, np.nonzero(contact)[0], lower, upper)
                r_in = np.where(contact, h[1:-1] - problem.h_closed, r_in)
        diag = ab[upper]
        # cavitated nodes (primal-dual active set): the local (Jacobi) update P_i − R_i/J_ii would be ≤ 0
        jacobi = -r_in / np.where(diag != 0.0, diag, 1.0)
        held = (p[1:-1] + jacobi <= 0.0) & ~contact
        free = ~held
        r_free = float(np.max(np.abs(r_in[free]))) / m_ref if free.any() else 0.0
        load_err = problem.load(p)
        worst = int(np.argmax(np.where(free, np.abs(r_in), 0.0))) + 1
        history.append((r_free, load_err, step, omega_adapt, float(problem.x[worst]), float(p[worst]),
                        float(h[worst]), int(held.sum())))
        if r_free <= tol.residual and abs(load_err) <= tol.load and step <= tol.step:
            return StepOutcome(p, h0, h, True, sweep, r_free, load_err, step, history,
                               np.concatenate([[False], contact, [False]]))
        merit = r_free + abs(load_err)
        if ADAPTIVE:
            omega_adapt = min(1.0, omega_adapt * 1.5) if merit < merit_prev else max(OMEGA_MIN, 0.5 * omega_adapt)
        merit_prev = merit
        if sweep == max_sweeps or not np.all(np.isfinite(res)):
            break
        if held.any():  # held rows: δP_i = −P_i
            _identity_rows(ab, col_h0, np.nonzero(held)[0], lower, upper)
            r_in = np.where(held, p[1:-1], r_in)
        try:
            sol = scipy.linalg.solve_banded((lower, upper), ab, np.column_stack([-r_in, -col_h0]),
                                            check_finite=False)
        except (np.linalg.LinAlgError, ValueError):
            break
        d_r, d_h = sol[:, 0], sol[:, 1]
        # bordered system: choose δH0 so that the load balance holds after the step (to first order)
        denom = float(w_in @ d_h)
        d_h0 = -(load_err + float(w_in @ d_r)) / denom if abs(denom) > 1e-300 else 0.0
        delta = d_r + d_h0 * d_h
        largest = float(np.max(np.abs(delta))) if delta.size else 0.0
        omega = OMEGA * omega_adapt * (min(1.0, MAX_STEP / largest) if largest > 0.0 else 1.0)
        p_new = p.copy()
        trial = p[1:-1] + omega * delta
        if gap_model:
            contact &= trial > 0.0  # a contact node that would need tension separates
        p_new[1:-1] = np.maximum(trial, 0.0)
        h0 += omega * d_h0
        step = float(np.max(np.abs(p_new - p)))
        p = p_new
    h = problem.film(p, h0)
    return StepOutcome(p, h0, h, False, max_sweeps, r_free, problem.load(p), step, history)


def solve_mixed_relaxation(case: ContactCase, lubricant: Lubricant | str, level: str | AccuracyLevel = "fast",
                           effects: Effects | None = None, *, keep_series: bool = True) -> ContactResult:
    """Transient mixed-EHL solve of one rough line contact by semi-system relaxation; returns a ContactResult.

    ``effects`` defaults to :meth:`Effects.full` (roughness, transient, shear thinning, compressibility); the
    ``roughness`` and ``transient`` flags must be on (this solver is only for rough surfaces). Bad input raises
    :class:`InputError`; a run whose time steps do not converge is returned ``converged=False`` with a message and
    the residual history (averages over the steps that converged).
    """
    from threadpoolctl import threadpool_limits

    from .solver import checked_inputs

    lubricant = checked_inputs(case, lubricant)
    plan = Effects.full() if effects is None else effects
    if not isinstance(plan, Effects):
        raise InputError("effects", plan, "None or an Effects instance")
    if case.s_c <= 0.0:
        raise InputError("rq1_m, rq2_m", (case.rq1, case.rq2), "composite roughness S_c > 0 (smooth surfaces: "
                         "use ehl_dataset.solver.solve_contact)")
    if not plan.roughness:
        raise InputError("effects.roughness", plan.roughness, "True (this is the rough-surface solver)")
    state = lubricant.state(case.temperature)
    lvl = get_level(level)
    with threadpool_limits(limits=1):
        return _solve(case, state, lvl, plan, keep_series)


def _solve(case, state, lvl: AccuracyLevel, plan: Effects, keep_series: bool) -> ContactResult:
    from .ehl_transient import _baseline_profile, roughness_grid, time_steps
    from .roughness import plan_surfaces
    from .solver import ContactScales, dowson_higginson_lambda, moes_h_c, solve_steady, solve_steady_problem

    start = time.perf_counter()
    tol = TOLERANCES.get(lvl.name, TOLERANCES["standard"])
    scales = ContactScales.of(case, state, plan.shear_thinning)
    a, film_scale = scales.a, scales.film_scale
    profile = _baseline_profile()
    x, capped = roughness_grid(case, lvl, profile.correlation_length, moes_h_c(case, state, scales))
    dx = float(np.min(np.diff(x[(x > lvl.inlet_band[1]) & (x < lvl.outlet_band[1])])))
    problem = ReynoldsProblem(x=x, kmat=influence_matrix(x), gap=0.5 * x**2, lam=scales.lam, p_h=case.p_h,
                              state=state, compressible=plan.compressibility and state.compressible,
                              shear=scales.shear)
    h_dh, lambda_bar = dowson_higginson_lambda(case, state)

    # 1. steady smooth start (Newton solver of ehl_newton/solver, by import), moved onto the rough grid
    smooth_plan = Effects(False, False, plan.shear_thinning, plan.compressibility, plan.mode, {})
    smooth = solve_steady(case, state, lvl, smooth_plan)
    if not smooth.converged:
        return _failed(case, lvl, plan, lambda_bar, start, f"smooth start: {smooth.message}", smooth.residuals)
    p_start = np.interp(x * a, smooth.x, smooth.pressure) / case.p_h
    newton_tol = dict(tol_residual=lvl.tol_residual, tol_load=lvl.tol_load, tol_step=lvl.tol_step,
                      max_iterations=lvl.max_iterations)
    first = newton_solve(problem, p_start, smooth.extra["h0_m"] / film_scale, **newton_tol)
    if not first.converged:
        first, _, _ = solve_steady_problem(problem, p_start, smooth.extra["h0_m"] / film_scale, lvl)
    if not first.converged:
        return _failed(case, lvl, plan, lambda_bar, start, f"smooth start on the rough grid: {first.message}",
                       {"reynolds": first.residual, "load": first.load})
    m_ref = float(np.interp(0.0, x, problem.fluid(first.p, first.h)[3]))

    # 2. time stepping, roughness ramped in over the start of the run (the Newton solver's time grid)
    d_t, t_end, n_steps, t_ramp = time_steps(lvl, dx)
    time_scale = a / case.u_r
    surfaces = plan_surfaces(case, x * a, t_end * time_scale, profile)
    problem.h_closed = H_CLOSED_M / film_scale
    problem.second_order = SECOND_ORDER_COUETTE
    p, h0 = first.p, first.h0
    m_prev = problem.fluid(p, first.h)[3]
    t = 0.0
    hist = {k: [] for k in ("t", "mu", "share", "h_min", "h_min_interior", "h_ends", "h_c", "p_max", "load",
                             "residual", "sweeps")}
    total_sweeps = 0
    failure = ""
    out = None
    for _ in range(n_steps):
        ok = False
        for attempt in range(MAX_RETRIES + 1):
            n_sub = 2**attempt
            d_sub = d_t / n_sub
            p_try, h0_try, m_try, ok = p, h0, m_prev, True
            for k in range(n_sub):
                t_k = t + (k + 1) * d_sub
                r1, r2 = surfaces.at(t_k * time_scale)
                ramp = min(1.0, t_k / t_ramp) if t_ramp > 0.0 else 1.0
                problem.gap = 0.5 * x**2 - ramp * (r1 + r2) / film_scale
                problem.squeeze = problem.weights / d_sub
                problem.m_old = m_try
                out = relax_step(problem, p_try, h0_try, m_ref, tol)
                total_sweeps += out.sweeps
                if not out.converged:
                    ok = False
                    break
                p_try, h0_try = out.p, out.h0
                m_try = problem.fluid(p_try, out.h)[3]
            if ok:
                break
        if not ok:
            failure = (f"time step at t = {(t + d_t) * time_scale:.3e} s did not converge in {MAX_SWEEPS} sweeps "
                       f"with {2**MAX_RETRIES} sub-steps (residual {out.residual:.2e}, load {out.load:.2e}, "
                       f"step {out.step:.2e})")
            break
        t += d_t
        p, h0, m_prev = p_try, h0_try, m_try
        _record(hist, t, case, state, x * a, p * case.p_h, out.h * film_scale, out)

    converged = not failure
    steps = len(hist["t"])
    if steps == 0:
        return _failed(case, lvl, plan, lambda_bar, start, failure,
                       {"reynolds": out.residual, "load": out.load, "step": out.step})
    first_avg = int(steps * (1.0 - lvl.average_fraction)) if converged else steps // 2
    win = slice(first_avg, steps)
    mu = np.asarray(hist["mu"][win])
    film = problem.film(p, h0) * film_scale
    residuals = {"reynolds": float(np.max(hist["residual"])), "load": float(np.max(np.abs(hist["load"]))),
                 "step_tolerance": tol.step}
    extra = {"solver": "semi-system relaxation (Hu & Zhu 2000)", "n_nodes": int(x.size), "dx_m": dx * a,
             "dt_s": d_t * time_scale, "n_steps": steps, "n_steps_planned": n_steps, "average_from_step": first_avg,
             "sweeps_total": int(total_sweeps), "roughness_resolution_capped": bool(capped),
             "surfaces_independent": bool(surfaces.independent), "h_min_dowson_higginson_m": h_dh,
             "h_closed_m": H_CLOSED_M, "max_load_error": float(np.max(np.abs(hist["load"]))),
             "mu_smooth_start": float(smooth.mu), "bandwidth": BANDWIDTH,
             "h_min_interior_m": float(np.min(hist["h_min_interior"][win])),
             "h_min_domain_ends_m": float(np.min(hist["h_ends"][win])),
             "contact_model": CONTACT_MODEL, "face_mean": FACE_MEAN}
    if keep_series:
        extra.update({"mu_series": np.asarray(hist["mu"]), "t_series_s": np.asarray(hist["t"]) * time_scale,
                      "share_series": np.asarray(hist["share"]), "h_min_series_m": np.asarray(hist["h_min"]),
                      "residual_series": np.asarray(hist["residual"]), "sweeps_series": np.asarray(hist["sweeps"])})
    result = ContactResult(
        mu=float(mu.mean()), mu_std=float(mu.std()), h_min=float(max(np.min(hist["h_min"][win]), 0.0)),
        h_central=float(np.mean(hist["h_c"][win])), p_max=float(np.max(hist["p_max"][win])),
        converged=converged, iterations=int(total_sweeps), wall_time=time.perf_counter() - start, level=lvl.name,
        effects=plan.to_dict(), lambda_bar=lambda_bar, asperity_load_share=float(np.mean(hist["share"][win])),
        residuals=residuals, message="converged" if converged else f"not converged: {failure}",
        x=x * a, pressure=p * case.p_h, film=film, extra=extra)
    if not all(np.isfinite([result.mu, result.h_central, result.p_max])):
        raise SolverError(f"non-finite relaxation result for case {case.to_dict()}")
    return result


def _record(hist, t, case, state, x_m, p_pa, h_m, out: StepOutcome):
    contact = h_m <= H_CLOSED_M
    if out.contact is not None:
        contact |= out.contact  # held at h_closed to the step tolerance
    parts = friction_components(x_m, p_pa, np.maximum(h_m, H_CLOSED_M), state.viscosity(p_pa), case.u_s,
                                state.tau0, case.load_per_length, state.mu_d, contact)
    dx = np.diff(x_m)
    load = float(np.sum(0.5 * (p_pa[1:] + p_pa[:-1]) * dx))
    pc = p_pa * contact
    contact_load = float(np.sum(0.5 * (pc[1:] + pc[:-1]) * dx))
    hist["t"].append(t)
    hist["mu"].append(parts["mu"])
    hist["share"].append(contact_load / load if load > 0.0 else 0.0)
    hist["h_min"].append(float(np.min(h_m)))
    hist["h_min_interior"].append(float(np.min(h_m[1:-1])))
    hist["h_ends"].append(float(min(h_m[0], h_m[-1])))
    hist["h_c"].append(float(np.interp(0.0, x_m, h_m)))
    hist["p_max"].append(float(np.max(p_pa)))
    hist["load"].append(load / case.load_per_length - 1.0)
    hist["residual"].append(out.residual)
    hist["sweeps"].append(out.sweeps)


def _failed(case, lvl, plan, lambda_bar, start, message, residuals) -> ContactResult:
    nan = float("nan")
    return ContactResult(mu=nan, h_min=nan, h_central=nan, p_max=nan, converged=False, iterations=0,
                         wall_time=time.perf_counter() - start, level=lvl.name, effects=plan.to_dict(),
                         lambda_bar=lambda_bar, residuals=dict(residuals), message=f"not converged: {message}")
