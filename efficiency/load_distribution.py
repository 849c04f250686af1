"""Load distribution of a gear mesh as a contact complementarity problem (Conry & Seireg), SI units.

At one mesh position the unknowns are the normal loads F_q ≥ 0 at the Q candidate contact points and the
rigid-body normal approach δ of the two gears. With the compliance matrix C (symmetric positive definite: tooth
bending, shear, foundation with face coupling, plus Hertzian contact) and the unloaded separations ε:

    compatibility  g = C F + ε − δ ≥ 0,   F ≥ 0,   F_q g_q = 0   (no tension, no penetration, complementarity),
    equilibrium    Σ_q F_q = W = T_in / (r_b1 cos ψ_b)            (Σ moments of the normal loads = input torque),

(Conry & Seireg, J. Eng. Ind. 95 (1973) 1115; the paper's §2 LDP). These are the KKT conditions of the strictly
convex quadratic programme  min ½ Fᵀ C F + εᵀ F  subject to F ≥ 0, Σ F = W  (δ is the multiplier of the load
constraint), solved here by a primal active-set method in the manner of Lawson & Hanson's NNLS (Solving Least
Squares Problems, 1974, ch. 23): every iterate is feasible, each sub-problem is an equality-constrained solve on
the active set (Cholesky), points are added while a gap is negative and removed by a step back to feasibility.
It terminates in a finite number of steps; a warm start from the previous mesh position's loads makes it a few
steps per position. The solution reports ``converged`` and its residuals; it never hides a failure.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numba import njit

from ehl_dataset.validation import SolverError, check_range

from .compliance import weber_secant


@dataclass(frozen=True)
class ContactSolution:
    """Solution of one contact problem (:func:`solve_contact`).

    Parameters
    ----------
    loads : ndarray
        (Q,) normal loads F_q ≥ 0 [N].
    approach : float
        Rigid-body normal approach δ (normal displacement of gear 1 relative to gear 2) [m].
    gaps : ndarray
        (Q,) loaded separations g = C F + ε − δ, 0 where loaded [m].
    stiffness : float
        Tangent normal mesh stiffness dW/dδ = 1ᵀ C_AA⁻¹ 1 on the active set [N/m].
    iterations : int
        Active-set iterations used [-].
    converged : bool
        All conditions hold within the tolerances [-].
    equilibrium_residual : float
        |Σ F − W| / W [-].
    max_penetration : float
        max(−g, 0) [m].
    min_load : float
        min F [N].
    """

    loads: np.ndarray
    approach: float
    gaps: np.ndarray
    stiffness: float
    iterations: int
    converged: bool
    equilibrium_residual: float
    max_penetration: float
    min_load: float


def solve_contact(compliance: np.ndarray, separation: np.ndarray, total_load: float,
                  initial_loads: np.ndarray | None = None, gap_tolerance: float = 1e-12,
                  max_iterations: int | None = None, bulk_iterations: int = 8) -> ContactSolution:
    """Solve the complementarity problem of the module docstring for the loads (primal active set, warm-startable).

    Parameters
    ----------
    compliance : ndarray
        (Q, Q) symmetric positive definite compliance matrix [m/N].
    separation : ndarray
        (Q,) unloaded normal separations ε [m].
    total_load : float
        Total normal load W, > 0 [N].
    initial_loads : ndarray, optional
        (Q,) warm start, ≥ 0 (rescaled to sum W); default all load on the closest point [N].
    gap_tolerance : float
        Accepted penetration, far below any modification or deflection [m].
    max_iterations : int, optional
        Largest number of active-set iterations; default from the problem size [-].
    bulk_iterations : int
        Number of initial iterations that add all penetrating points at once [-].

    Returns
    -------
    ContactSolution
        Loads, approach, gaps, stiffness and convergence record.

    Raises
    ------
    SolverError
        When no point can carry the load or the compliance is not positive definite on the active set.
    """
    total_load = check_range("total_load", total_load, 0.0, 1e12, low_inclusive=False, unit="N")
    c = np.asarray(compliance, dtype=float)
    eps = np.asarray(separation, dtype=float)
    q = eps.size
    if q == 0:
        raise SolverError("no contact point on the active path of contact: the load cannot be carried")
    if not (np.all(np.isfinite(c)) and np.all(np.isfinite(eps))):
        raise SolverError("non-finite compliance or separation in the contact problem")
    max_iterations = max_iterations or 4 * q + 20

    loads = np.zeros(q)
    if initial_loads is not None and np.sum(np.clip(initial_loads, 0, None)) > 0:
        loads = np.clip(np.asarray(initial_loads, dtype=float), 0.0, None)
        loads *= total_load / loads.sum()
    else:
        loads[int(np.argmin(eps))] = total_load
    status, approach, stiffness, iteration = _active_set(c, eps, total_load, loads, gap_tolerance, max_iterations,
                                                         bulk_iterations)
    if status == _NOT_POSITIVE_DEFINITE:
        raise SolverError("compliance matrix not positive definite on the active set")
    converged = status == _CONVERGED

    gaps = c @ loads + eps - approach
    penetration = float(max(-gaps.min(), 0.0))
    equilibrium = abs(loads.sum() - total_load) / total_load
    converged = converged and penetration <= gap_tolerance and equilibrium <= 1e-9
    return ContactSolution(loads=loads, approach=float(approach), gaps=gaps, stiffness=stiffness,
                           iterations=iteration, converged=bool(converged), equilibrium_residual=float(equilibrium),
                           max_penetration=penetration, min_load=float(loads.min()))


def solve_contact_weber(tooth: np.ndarray, separation: np.ndarray, total_load: float, contact_terms, scale: float,
                        load_per_length: np.ndarray, initial_loads: np.ndarray | None = None,
                        tolerance: float = 1e-4, max_rounds: int = 50, gap_tolerance: float = 1e-12):
    """The complementarity problem with Weber's load-dependent contact compliance, by secant iteration.

    The compliance is ``tooth + diag(scale · c_H(w))`` with c_H from :func:`efficiency.compliance.weber_secant` and
    the load per unit contact-line length w = scale · F. Each round solves the linear problem (warm-started) and
    updates c_H at the new loads (unloaded points keep theirs) until the largest relative change of c_H at a loaded
    point is within ``tolerance``; c_H varies like ln w, so this contracts fast (4–6 rounds).

    Parameters
    ----------
    tooth : ndarray
        (Q, Q) tooth (bending, shear, foundation) compliance matrix [m/N].
    separation : ndarray
        (Q,) unloaded normal separations ε [m].
    total_load : float
        Total normal load W [N].
    contact_terms : tuple
        Load-independent parts of Weber's compliance (:func:`efficiency.compliance.weber_log_terms`) [-].
    scale : float
        cos ψ_b / Δz, converting a point load to a load per contact-line length [1/m].
    load_per_length : ndarray
        Starting w of every point, e.g. the previous position's [N/m].
    initial_loads : ndarray, optional
        (Q,) warm start of the loads [N].
    tolerance : float
        Accepted relative change of c_H between rounds [-].
    max_rounds : int
        Largest number of secant rounds [-].
    gap_tolerance : float
        Accepted penetration [m].

    Returns
    -------
    tuple
        (ContactSolution, final load per length w [N/m], last relative change of c_H [-]).
    """
    total_load = check_range("total_load", total_load, 0.0, 1e12, low_inclusive=False, unit="N")
    eps = np.ascontiguousarray(separation, dtype=float)
    q = eps.size
    if q == 0:
        raise SolverError("no contact point on the active path of contact: the load cannot be carried")
    loads = np.zeros(q)
    if initial_loads is not None and np.sum(np.clip(initial_loads, 0, None)) > 0:
        loads = np.clip(np.asarray(initial_loads, dtype=float), 0.0, None)
        loads *= total_load / loads.sum()
    else:
        loads[int(np.argmin(eps))] = total_load
    w = np.ascontiguousarray(load_per_length, dtype=float).copy()
    l1, l2, k1, k2, q1, q2 = contact_terms
    status, approach, stiffness, iterations, change, used = _weber_rounds(
        np.ascontiguousarray(tooth), eps, total_load, loads, w, np.ascontiguousarray(l1),
        np.ascontiguousarray(l2), k1, k2, q1, q2, scale, tolerance, max_rounds, gap_tolerance, 4 * q + 20, 8)
    if status == _NOT_POSITIVE_DEFINITE:
        raise SolverError("compliance matrix not positive definite on the active set")
    gaps = tooth @ loads + used * loads + eps - approach
    penetration = float(max(-gaps.min(), 0.0))
    equilibrium = abs(loads.sum() - total_load) / total_load
    converged = (status == _CONVERGED and penetration <= gap_tolerance and equilibrium <= 1e-9
                 and change <= tolerance)
    sol = ContactSolution(loads=loads, approach=float(approach), gaps=gaps, stiffness=float(stiffness),
                          iterations=int(iterations), converged=bool(converged),
                          equilibrium_residual=float(equilibrium), max_penetration=penetration,
                          min_load=float(loads.min()))
    return sol, w, float(change)


@njit(cache=True)
def _weber_rounds(tooth, eps, total_load, loads, w, l1, l2, k1, k2, q1, q2, scale, tolerance, max_rounds,
                  gap_tolerance, max_iterations, bulk_iterations):
    """Secant rounds of :func:`solve_contact_weber`; ``loads`` and ``w`` are updated in place."""
    n = eps.size
    c_contact = scale * weber_secant(w, l1, l2, k1, k2, q1, q2)
    status, approach, stiffness, total = 1, np.nan, np.nan, 0
    change = np.inf
    compliance = np.empty_like(tooth)
    used = c_contact
    for _ in range(max_rounds):
        used = c_contact
        compliance[:, :] = tooth
        for i in range(n):
            compliance[i, i] += c_contact[i]
        status, approach, stiffness, iterations = _active_set(compliance, eps, total_load, loads, gap_tolerance,
                                                              max_iterations, bulk_iterations)
        total += iterations
        if status == 2:
            break
        for i in range(n):
            if loads[i] > 0.0:
                w[i] = loads[i] * scale
        updated = scale * weber_secant(w, l1, l2, k1, k2, q1, q2)
        change = 0.0
        for i in range(n):
            if loads[i] > 0.0:
                change = max(change, abs(updated[i] - c_contact[i]) / c_contact[i])
        c_contact = updated
        if change <= tolerance:
            break
    return status, approach, stiffness, total, change, used


_CONVERGED, _NOT_CONVERGED, _NOT_POSITIVE_DEFINITE = 0, 1, 2


@njit(cache=True)
def _cholesky_solve_two(a, rhs1, rhs2):
    """Solve A x = rhs1 and A y = rhs2 by Cholesky (in numba); returns (x, y, ok)."""
    n = a.shape[0]
    low = np.zeros((n, n))
    for i in range(n):
        for j in range(i + 1):
            acc = a[i, j]
            for k in range(j):
                acc -= low[i, k] * low[j, k]
            if i == j:
                if acc <= 0.0:
                    return rhs1, rhs2, False
                low[i, i] = np.sqrt(acc)
            else:
                low[i, j] = acc / low[j, j]
    x = rhs1.copy()
    y = rhs2.copy()
    for i in range(n):
        for k in range(i):
            x[i] -= low[i, k] * x[k]
            y[i] -= low[i, k] * y[k]
        x[i] /= low[i, i]
        y[i] /= low[i, i]
    for i in range(n - 1, -1, -1):
        for k in range(i + 1, n):
            x[i] -= low[k, i] * x[k]
            y[i] -= low[k, i] * y[k]
        x[i] /= low[i, i]
        y[i] /= low[i, i]
    return x, y, True


@njit(cache=True)
def _active_set(c, eps, total_load, loads, gap_tolerance, max_iterations, bulk_iterations):
    """Primal active-set iterations (see the module docstring); ``loads`` (feasible) is updated in place.

    Returns (status, approach, stiffness, iterations).
    """
    q = eps.size
    active = loads > 0.0
    approach = np.nan
    stiffness = np.nan
    last_added = -1
    iteration = 0
    status = 1
    while iteration < max_iterations:
        iteration += 1
        idx = np.flatnonzero(active)
        n = idx.size
        sub = np.empty((n, n))
        for i in range(n):
            for j in range(n):
                sub[i, j] = c[idx[i], idx[j]]
        u, v, ok = _cholesky_solve_two(sub, np.ones(n), eps[idx])
        if not ok:
            return 2, approach, stiffness, iteration
        stiffness = u.sum()
        approach = (total_load + v.sum()) / stiffness
        trial = approach * u - v
        if np.all(trial > 0.0):
            loads[:] = 0.0
            loads[idx] = trial
            gaps = c @ loads + eps - approach
            gaps[idx] = 0.0
            j = int(np.argmin(gaps))
            if gaps[j] >= -gap_tolerance:
                status = 0
                break
            if iteration <= bulk_iterations:
                # Early iterations add every penetrating point at once (the step back keeps feasibility);
                # later ones add only the worst, the finitely terminating Lawson-Hanson rule.
                count = 0
                for i in range(q):
                    if gaps[i] < -gap_tolerance:
                        active[i] = True
                        count += 1
                last_added = j if count == 1 else -1
            else:
                active[j] = True
                last_added = j
            continue
        # Step from the current feasible loads towards the trial solution until the first load reaches zero.
        alpha = np.inf
        first = -1
        for i in range(n):
            if trial[i] <= 0.0:
                current = loads[idx[i]]
                ratio = current / (current - trial[i])
                if ratio < alpha:
                    alpha = ratio
                    first = idx[i]
        if alpha == 0.0 and first == last_added:
            break  # degenerate: the new point cannot take load; the residual check decides
        for i in range(n):
            k = idx[i]
            loads[k] = loads[k] + alpha * (trial[i] - loads[k])
            if loads[k] <= 1e-13 * total_load or k == first:
                loads[k] = 0.0
                active[k] = False
        last_added = -1
    return status, approach, stiffness, iteration
