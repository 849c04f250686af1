"""Dry elastic–perfectly-plastic contact of a roughness pair: the micro-scale tables of the homogenised model.

Problem (one periodic window of length L, plane strain, SI units)
-----------------------------------------------------------------
The composite roughness z = R1 + R2 of the two surfaces (positive = material towards the other body) is pressed
against a rigid flat whose plane lies at the separation d above the mean plane of z. With the elastic deflection
u_e of the project's convention

    u_e(x) = −4/(πE') ∫ ln|x − x'| p(x') dx'   ⇔   û_e(k) = 4 p̂(k)/(E'|k|)  (k ≠ 0),   û_e(0) = 0,

and the plastic cap of an elastic–perfectly-plastic half-space (Almqvist et al. 2007; Sahlin et al. 2010), the
pressure p and the raw gap r = d − z + u_e satisfy, node by node,

    0 < p < H  ⇒  r = 0,      p = 0  ⇒  r ≥ 0,      p = H  ⇒  r ≤ 0  (the interference −r is plastic flow u_p).

The local gap is g = max(r, 0) off contact and 0 in contact, the plastic deformation u_p = max(−r, 0) on yielded
nodes. ``û_e(0) = 0`` — the micro-deflection has zero mean — is the scale-separation convention: the mean (k = 0)
deflection produced by the mean pressure belongs to the macro problem, which computes it with the line-contact
kernel from the total (fluid + asperity) pressure. Consequence, exact for every window:

    ⟨g⟩ = d − ⟨z⟩ + ⟨u_p⟩ = d + ⟨u_p⟩        (z has zero mean in every window),

so in the elastic range the mean gap (lubricant volume per area) *is* d, d ≥ 0, and p_a(d) rises to the
full-contact pressure as d → 0⁺. Below d = 0 only plastic flow makes room; for a mostly elastic pair (small Rq)
p_a(d) is therefore very steep at d ≈ 0 (vertical in the purely elastic limit). See docs/explanation/mixed-regime.md.

Solver
------
Load-controlled conjugate gradients of Polonsky & Keer (Wear 231 (1999) 206–219), on a periodic window with the
spectral (FFT) influence operator, with the pressure cap of Almqvist et al. (Tribol. Int. 40 (2007) 574): nodes
at p = H are held like the zero-pressure nodes and released when their gap opens; the load step scales the
pressures and clips them at H (the scale factor found by a short monotone Newton iteration). Many windows are
solved at once as rows of one array (independent problems, shared FFTs).

Tables
------
:func:`compute_dry_contact_table` steps the mean pressure p̄ over a geometric ladder (warm-started), averages
each quantity over the windows at equal p̄ (the windows' d differ by sampling only; the spread is stored), and
:class:`DryContactTable` interpolates them as C¹ functions of d. :func:`dry_contact_table` returns the shipped
table (data/roughness/dry_contact/) or the disk-cached one (``$GEARLOSS_CACHE_DIR``, default ~/.cache/gearloss),
computing and caching it if needed.
"""

from __future__ import annotations

import functools
import hashlib
import json
import math
import os
import time
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path

import numpy as np
import scipy.fft as sfft
from scipy.interpolate import CubicHermiteSpline, PchipInterpolator

from ..data_files import data_path
from .roughness import RoughnessProfile, default_profile
from ..validation import InputError, SolverError, check_range

TABLE_FORMAT = "gearloss-dry-contact-2"
"""Version tag of the table format and of the algorithm; part of the cache key (bump it when results change)."""
DEFAULT_HARDNESS_PA = 6.8e9
"""Hardness (plastic cap) of 60 HRC gear steel [Pa] (the project's YIELD_PRESSURE_PA)."""
STEEL_E_REDUCED_PA = 2.0 / (2 * (1 - 0.3**2) / 206e9)
"""Reduced modulus E' of two steel bodies (E = 206 GPa, ν = 0.3) [Pa] = 226.4 GPa."""
MOMENT_ORDERS = (1, -1, -2, -3)
"""Orders k of the floored gap moments ⟨max(g, h)^k⟩ stored on the floor grid."""
FLOOR_GRID_DECADES = (-5.0, 1.0)
"""The floor grid h/σ spans 10^-5 … 10^1 (log-spaced, :attr:`DryContactSettings.floor_points_per_decade`)."""
QUANTILE_NODES = 24
"""Gauss–Legendre nodes of the stored quantile function of the open (non-contact) gaps."""
FFT_WORKERS = max(1, min(2, os.cpu_count() or 1))
"""Threads of the batched FFTs of the table computation (the windows are independent rows)."""
CACHE_ENV = "GEARLOSS_CACHE_DIR"
"""Environment variable that overrides the cache directory (default ~/.cache/gearloss)."""


# ---------------------------------------------------------------------------------------------------------------
# Elasticity and the contact solver
# ---------------------------------------------------------------------------------------------------------------
def elastic_multiplier(n: int, length: float, e_reduced: float) -> np.ndarray:
    """Fourier multiplier of the periodic deflection, 4/(E'|k|) with k = 2πm/L (m = 0 … n/2), 0 for k = 0."""
    k = 2.0 * math.pi * np.fft.rfftfreq(n, d=length / n)
    out = np.zeros_like(k)
    out[1:] = 4.0 / (e_reduced * k[1:])
    return out


def periodic_deflection(p, spacing: float, e_reduced: float) -> np.ndarray:
    """Zero-mean elastic deflection of a periodic pressure, û(k) = 4 p̂(k)/(E'|k|).

    The project's V(x) = −4/(πE') ∫ ln|x − x'| p(x') dx' for a periodic p, up to the constant (k = 0) term, which is
    set to zero.

    Parameters
    ----------
    p : array_like
        Pressure on uniform nodes (last axis) [Pa].
    spacing : float
        Node spacing [m].
    e_reduced : float
        Reduced modulus E' [Pa].

    Returns
    -------
    ndarray
        u_e [m].
    """
    p = np.asarray(p, dtype=float)
    n = p.shape[-1]
    mult = elastic_multiplier(n, n * spacing, e_reduced)
    return sfft.irfft(sfft.rfft(p, axis=-1) * mult, n=n, axis=-1)


@dataclass
class ContactSolution:
    """Solution of :func:`solve_contact` for R windows (arrays (R, N) or (R,)); SI units.

    Parameters
    ----------
    pressure : ndarray
        Contact pressure p [Pa].
    separation : ndarray
        Separation d of each window [m].
    gap : ndarray
        Gap g ≥ 0, 0 on contact nodes [m].
    plastic : ndarray
        Plastic displacement u_p ≥ 0 [m].
    deflection : ndarray
        Elastic deflection u_e, zero mean [m].
    iterations : int
        Outer (active-set) iterations [-].
    inner_iterations : int
        PCG iterations in all [-].
    residual : float
        Largest violation of the contact conditions (|r| on free nodes, −r on open ones, r on yielded ones) over all
        windows [m].
    """

    pressure: np.ndarray
    separation: np.ndarray
    gap: np.ndarray
    plastic: np.ndarray
    deflection: np.ndarray
    iterations: int
    inner_iterations: int
    residual: float


class _Operators:
    """FFT operators of R periodic windows of N nodes: K (deflection) and the preconditioner M ≈ K⁻¹."""

    def __init__(self, n: int, spacing: float, e_reduced: float):
        self.n = n
        self.mult = elastic_multiplier(n, n * spacing, e_reduced)
        k = 2.0 * math.pi * np.fft.rfftfreq(n, d=spacing)
        self.inv = 0.25 * e_reduced * np.maximum(k, k[1])  # E'|k|/4; the k = 0 mode gets the k1 value (SPD)

    def deflect(self, v):
        workers = FFT_WORKERS if v.ndim > 1 and v.shape[0] > 1 else 1
        return sfft.irfft(sfft.rfft(v, axis=-1, workers=workers) * self.mult, n=self.n, axis=-1, workers=workers)

    def precondition(self, v):
        workers = FFT_WORKERS if v.ndim > 1 and v.shape[0] > 1 else 1
        return sfft.irfft(sfft.rfft(v, axis=-1, workers=workers) * self.inv, n=self.n, axis=-1, workers=workers)


def _rowsum(a):
    return a.sum(axis=1, keepdims=True)


def _safe_div(a, b):
    return np.where(b > 0, a / np.where(b > 0, b, 1.0), 0.0)


def _pcg(ops: _Operators, free, rhs, x0, tol: float, max_iterations: int):
    """Preconditioned CG for K_FF x_F = rhs_F row by row (x = 0 off the free set F); M = P_F K⁻¹ P_F.
    Stops when every row's residual norm is ≤ tol × its initial norm. Returns (x, iterations)."""
    x = np.where(free, x0, 0.0)
    r = np.where(free, rhs - ops.deflect(x), 0.0)
    r0 = np.sqrt(_rowsum(r * r))
    s = np.where(free, ops.precondition(r), 0.0)
    d = s
    rs = _rowsum(r * s)
    its = 0
    for its in range(1, max_iterations + 1):
        if np.all(np.sqrt(_rowsum(r * r)) <= tol * r0):
            its -= 1
            break
        q = np.where(free, ops.deflect(d), 0.0)
        a = _safe_div(rs, _rowsum(d * q))
        x = x + a * d
        r = r - a * q
        s = np.where(free, ops.precondition(r), 0.0)
        rs_new = _rowsum(r * s)
        d = s + _safe_div(rs_new, rs) * d
        rs = rs_new
    return x, its


def _kkt_residual(p, r, hardness):
    """Largest violation [m] per row of: r = 0 where 0 < p < H, r ≥ 0 where p = 0, r ≤ 0 where p = H."""
    free = (p > 0.0) & (p < hardness)
    out = np.max(np.abs(np.where(free, r, 0.0)), axis=1)
    out = np.maximum(out, np.max(np.where(p <= 0.0, -r, 0.0), axis=1))
    return np.maximum(out, np.max(np.where(p >= hardness, r, 0.0), axis=1))


def _solve_separation(ops: _Operators, z, d, hardness, p0, tol_gap, max_iterations, pdas_iterations=25):
    """Box-constrained QP  min ½pᵀKp − pᵀ(z − d),  0 ≤ p ≤ H, per row (d: (R, 1)). Returns p, Kp, r, its, inner.

    Primal–dual active-set iterations (PDAS, Hintermüller, Ito & Kunisch, SIAM J. Optim. 13 (2002) 865): with
    the lower set A (p = 0) and upper set U (p = H) fixed, the free pressures solve K_FF p_F = (z − d − K p_U)_F
    (preconditioned CG, :func:`_pcg`); a free node with p < 0 joins A, one with p > H joins U, a node of A whose
    gap r < 0 or of U whose r > 0 is freed. PDAS usually ends in 5–10 steps. K is not an M-matrix, so PDAS can
    cycle on a few nodes (seen at small plastic spots); a repeated pair of sets, or ``pdas_iterations`` steps,
    hands the projected iterate to the preconditioned Polonsky–Keer iteration (:func:`_pk_preconditioned`), and
    that, if it stalls, to a projected Newton method (:func:`_projected_newton`)."""
    p = np.clip(p0, 0.0, hardness)
    kp = ops.deflect(p)
    r = kp - z + d
    if np.all(_kkt_residual(p, r, hardness) <= tol_gap):
        return p, kp, r, 0, 0
    lower = (p <= 0.0) & (r >= 0.0)
    upper = (p >= hardness) & (r <= 0.0)
    upper_value = hardness if math.isfinite(hardness) else 0.0
    inner = 0
    tight = False
    seen = set()
    iteration = 0
    for iteration in range(1, pdas_iterations + 1):
        free = ~(lower | upper)
        p_upper = np.where(upper, upper_value, 0.0)
        rhs = z - d - (ops.deflect(p_upper) if upper.any() else 0.0)
        x, its = _pcg(ops, free, rhs, p, 1e-10 if tight else 1e-2, 500)
        inner += its
        p = np.where(free, x, p_upper)
        kp = ops.deflect(p)
        r = kp - z + d
        new_lower = (free & (p < 0.0)) | (lower & (r >= 0.0))
        new_upper = (free & (p > hardness)) | (upper & (r <= 0.0))
        unchanged = np.array_equal(new_lower, lower) and np.array_equal(new_upper, upper)
        lower, upper = new_lower, new_upper
        if unchanged:
            if tight and np.all(_kkt_residual(p, r, hardness) <= tol_gap):
                return p, kp, r, iteration, inner
            tight = True
            continue
        key = hashlib.sha1(np.packbits(lower).tobytes() + np.packbits(upper).tobytes()).hexdigest()
        if key in seen:
            break  # cycling
        seen.add(key)
    p = np.clip(p, 0.0, hardness)
    try:
        p, kp, r, its, more = _pk_preconditioned(ops, z, d, hardness, p, tol_gap, 20 * max_iterations)
        return p, kp, r, iteration + its, inner + more
    except SolverError:
        pass
    p, kp, r, its, more = _projected_newton(ops, z, d, hardness, p, tol_gap, max_iterations)
    return p, kp, r, iteration + its, inner + more


def _pk_preconditioned(ops: _Operators, z, d, hardness, p0, tol_gap, max_iterations):
    """Polonsky & Keer's constrained CG (displacement control), preconditioned on the free set by M = K⁻¹
    (P_F M P_F, Vollebregt-type FFT preconditioner), with the plastic cap: nodes at 0 or H are held; a held node
    whose gap has the wrong sign (penetration at p = 0, opening at p = H) takes a steepest-descent step of
    exact length on the set of such nodes and the conjugacy restarts; the iterate is projected on [0, H].
    Returns p, Kp, r, iterations, iterations (each iteration is one CG step)."""
    rows = z.shape[0]
    p = np.clip(p0, 0.0, hardness)
    t = np.zeros_like(p)
    g_old = np.ones((rows, 1))
    restart = np.ones((rows, 1), dtype=bool)
    best = math.inf
    stalled = 0
    for iteration in range(1, max_iterations + 1):
        kp = ops.deflect(p)
        r = kp - z + d
        residual = float(_kkt_residual(p, r, hardness).max())
        if residual <= tol_gap:
            return p, kp, r, iteration - 1, iteration - 1
        if residual < 0.5 * best:
            best, stalled = residual, 0
        else:
            stalled += 1
            if stalled > 400:
                break
        free = (p > 0.0) & (p < hardness)
        wrong = ((p <= 0.0) & (r < 0.0)) | ((p >= hardness) & (r > 0.0))
        r_free = np.where(free, r, 0.0)
        s = np.where(free, ops.precondition(r_free), 0.0)
        g_norm = _rowsum(r_free * s)
        t = np.where(free, s + np.where(restart, 0.0, _safe_div(g_norm, g_old)) * t, 0.0)
        g_old = np.where(g_norm > 0, g_norm, 1.0)
        q = ops.deflect(t)
        tau = _safe_div(_rowsum(r_free * t), _rowsum(np.where(free, q, 0.0) * t))
        p_new = p - tau * t
        if wrong.any():
            v = np.where(wrong, r, 0.0)
            tau_w = _safe_div(_rowsum(v * v), _rowsum(v * ops.deflect(v)))
            p_new = np.where(wrong, p - tau_w * r, p_new)
        p = np.clip(p_new, 0.0, hardness)
        restart = wrong.any(axis=1, keepdims=True)
    raise SolverError(f"preconditioned Polonsky–Keer iteration stalled (violation {residual:.2e} m)")


def _projected_newton(ops: _Operators, z, d, hardness, p0, tol_gap, max_iterations, inner_tol=1e-3):
    """The same QP by a projected Newton method (Bertsekas, SIAM J. Control Optim. 20 (1982) 221): the Newton
    step on the free set (nodes not held at a bound by the sign of their gap), projected on the box, with a
    non-monotone Armijo backtracking along the projection arc (reference: the largest of the last five energies).
    Robust but slower than PDAS; used to finish when PDAS cycles."""
    rows = z.shape[0]
    p = np.clip(p0, 0.0, hardness)
    kp = ops.deflect(p)
    r = kp - z + d
    history = [_rowsum(0.5 * p * kp - p * (z - d))]
    previous_sets = None
    inner = 0
    upper_value = hardness if math.isfinite(hardness) else 0.0
    for iteration in range(1, max_iterations + 1):
        residual = _kkt_residual(p, r, hardness)
        if np.all(residual <= tol_gap):
            return p, kp, r, iteration - 1, inner
        lower = (p <= 0.0) & (r >= 0.0)
        upper = (p >= hardness) & (r <= 0.0)
        free = ~(lower | upper)
        tight = previous_sets is not None and np.array_equal(lower, previous_sets[0]) \
            and np.array_equal(upper, previous_sets[1])
        previous_sets = (lower, upper)
        p_upper = np.where(upper, upper_value, 0.0)
        rhs = z - d - (ops.deflect(p_upper) if upper.any() else 0.0)
        x, its = _pcg(ops, free, rhs, p, 1e-11 if tight else inner_tol, 500)
        inner += its
        direction = np.where(free, x, p_upper) - p
        reference = np.max(np.concatenate(history[-5:], axis=1), axis=1, keepdims=True)
        alpha = np.ones((rows, 1))
        for _ in range(20):
            trial = np.clip(p + alpha * direction, 0.0, hardness)
            kt = ops.deflect(trial)
            e_trial = _rowsum(0.5 * trial * kt - trial * (z - d))
            ok = (e_trial <= reference + 1e-4 * _rowsum(r * (trial - p))) | (residual[:, None] <= tol_gap)
            if np.all(ok):
                break
            alpha = np.where(ok, alpha, 0.5 * alpha)
        p, kp = trial, kt
        r = kp - z + d
        history.append(_rowsum(0.5 * p * kp - p * (z - d)))
    residual = _kkt_residual(p, r, hardness)
    if np.all(residual <= tol_gap):
        return p, kp, r, max_iterations, inner
    raise SolverError(f"dry contact active-set solver did not converge in {max_iterations} iterations "
                      f"(contact-condition violation {float(residual.max()):.2e} m > {tol_gap:.2e} m)")


def solve_contact(z, spacing: float, e_reduced: float, separation=None, *, mean_pressure: float | None = None,
                  hardness: float = DEFAULT_HARDNESS_PA, p0=None, tol: float = 1e-9,
                  max_iterations: int = 200) -> ContactSolution:
    """Elastic–perfectly-plastic contact of periodic rough windows against a rigid flat.

    Give either ``separation`` (displacement control, the primary mode) or ``mean_pressure`` (load control: d is found
    per window by a safeguarded secant iteration on ln p̄(d), for tests and one-off use; it fails at a full elastic
    contact, where p̄(d) is vertical). Converged when the contact conditions hold to ``tol`` × rms(z) in every window.

    Parameters
    ----------
    z : array_like
        Heights, shape (N,) or (R, N): R independent periodic windows [m].
    spacing : float
        Uniform node spacing [m].
    e_reduced : float
        Reduced modulus E' [Pa].
    separation : float or array_like, optional
        Separation d, scalar or one per window [m].
    mean_pressure : float, optional
        Mean pressure p̄ (load control) [Pa].
    hardness : float
        Hardness H (``math.inf``: purely elastic) [Pa].
    p0 : array_like, optional
        Starting pressure (warm start) [Pa].
    tol : float
        Tolerance on the contact conditions, relative to rms(z) [-].
    max_iterations : int
        Largest number of active-set iterations [-].

    Returns
    -------
    ContactSolution
        Pressure, gap, plastic displacement and deflection per window.

    Raises
    ------
    SolverError
        When the contact conditions are not met within ``max_iterations``.
    """
    z = np.atleast_2d(np.asarray(z, dtype=float))
    rows, n = z.shape
    check_range("e_reduced", e_reduced, 0.0, 1e20, low_inclusive=False, unit="Pa")
    check_range("spacing", spacing, 0.0, 1.0, low_inclusive=False, unit="m")
    if not (isinstance(hardness, (int, float)) and hardness > 0 and not math.isnan(hardness)):
        raise InputError("hardness", hardness, "a number > 0 [Pa] (math.inf: purely elastic)")
    if (separation is None) == (mean_pressure is None):
        raise InputError("separation/mean_pressure", (separation, mean_pressure), "exactly one of the two")
    scale = float(np.sqrt(np.mean(z * z))) or 1e-9
    ops = _Operators(n, spacing, e_reduced)
    p = np.zeros_like(z) if p0 is None else np.clip(np.broadcast_to(np.asarray(p0, float), z.shape), 0.0, hardness)
    if separation is not None:
        d = np.broadcast_to(np.asarray(separation, dtype=float).reshape(-1, 1), (rows, 1)).copy()
        if not np.all(np.isfinite(d)):
            raise InputError("separation", separation, "finite numbers [m]")
        p, kp, r, its, inner = _solve_separation(ops, z, d, hardness, p, tol * scale, max_iterations)
    else:
        check_range("mean_pressure", mean_pressure, 0.0, min(hardness, 1e15), low_inclusive=False,
                    high_inclusive=False, unit="Pa")
        p, kp, r, d, its, inner = _solve_load(ops, z, float(mean_pressure), hardness, p, tol * scale,
                                              max_iterations)
    residual = float(_kkt_residual(p, r, hardness).max())
    gap = np.where(p > 0.0, 0.0, np.maximum(r, 0.0))
    plastic = np.where(p >= hardness, np.maximum(-r, 0.0), 0.0)
    return ContactSolution(p, d[:, 0].copy(), gap, plastic, kp, its, inner, residual)


def _solve_load(ops, z, mean_pressure, hardness, p, tol_gap, max_iterations):
    """Load control by an Illinois-safeguarded secant iteration on f(d) = ln p̄(d) − ln p̄_target per row."""
    rows = z.shape[0]
    scale = float(np.sqrt(np.mean(z * z))) or 1e-9
    target = math.log(mean_pressure)
    total_its = total_inner = 0

    def evaluate(d, p_start):
        nonlocal total_its, total_inner
        p_new, kp, r, its, inner = _solve_separation(ops, z, d, hardness, p_start, tol_gap, max_iterations)
        total_its += its
        total_inner += inner
        mean = p_new.mean(axis=1, keepdims=True)
        return p_new, kp, r, np.log(np.maximum(mean, 1e-300)) - target

    # bracket: d_hi with p̄ < target (start at the highest peak), d_lo with p̄ > target
    d_hi = z.max(axis=1, keepdims=True) - 1e-3 * scale
    p_hi, kp, r, f_hi = evaluate(d_hi, np.zeros_like(z))
    step = 0.5 * scale
    elastic = not math.isfinite(hardness)  # then p̄(d) → ∞ only as ⟨g⟩ = d − ⟨z⟩ → 0⁺: stay above ⟨z⟩
    z_mean = z.mean(axis=1, keepdims=True)

    def lower(d, step):
        return np.maximum(d - step, z_mean + 0.25 * (d - z_mean)) if elastic else d - step

    d_lo = lower(d_hi, step)
    p_lo, kp, r, f_lo = evaluate(d_lo, p_hi)
    for _ in range(60):
        need = f_lo < 0
        if not need.any():
            break
        d_hi = np.where(need, d_lo, d_hi)
        f_hi = np.where(need, f_lo, f_hi)
        p_hi = np.where(need, p_lo, p_hi)
        step *= 1.6
        d_lo = np.where(need, lower(d_lo, step), d_lo)
        p_lo, kp, r, f_lo = evaluate(d_lo, p_lo)
    else:
        raise SolverError("load control: could not bracket the mean pressure")
    side = np.zeros((rows, 1))
    for _ in range(100):
        d_new = d_hi - f_hi * (d_lo - d_hi) / np.where(f_lo != f_hi, f_lo - f_hi, 1.0)
        d_new = np.clip(d_new, np.minimum(d_lo, d_hi), np.maximum(d_lo, d_hi))
        p_new, kp, r, f_new = evaluate(d_new, np.where(f_hi > -f_lo, p_lo, p_hi))
        if np.all(np.abs(f_new) < 1e-12) or np.all(np.abs(d_lo - d_hi) < 1e-14 * scale):
            p = p_new
            d = d_new
            break
        low_side = f_new > 0  # too much pressure: new lower bound of d
        d_lo = np.where(low_side, d_new, d_lo)
        f_lo = np.where(low_side, f_new, f_lo)
        p_lo = np.where(low_side, p_new, p_lo)
        d_hi = np.where(low_side, d_hi, d_new)
        f_hi = np.where(low_side, f_hi, f_new)
        p_hi = np.where(low_side, p_hi, p_new)
        # Illinois: halve the stale end's function value when the same side moves twice
        f_hi = np.where(low_side & (side > 0), 0.5 * f_hi, f_hi)
        f_lo = np.where(~low_side & (side < 0), 0.5 * f_lo, f_lo)
        side = np.where(low_side, 1.0, -1.0)
    else:
        raise SolverError("load control: the secant iteration on the separation did not converge")
    return p, kp, r, d, total_its, total_inner


# ---------------------------------------------------------------------------------------------------------------
# Windows of the composite roughness
# ---------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class DryContactSettings:
    """Numerical settings of a dry-contact table (all part of the cache key).

    The separation ladder starts at the highest summit and steps down adaptively (between ``min_step``·σ and
    ``max_step``·σ, at most ``max_contact_step`` change of the contact fraction) until p_a ≥ ``max_pressure_pa`` or
    the contact fraction ≥ ``full_contact_fraction``.

    Parameters
    ----------
    window_correlation_lengths : float
        Window length L/β [-].
    n_windows : int
        Independent windows averaged, each using two disjoint stretches of the profile, one per surface [-].
    points_per_correlation_length : float
        Resolution β/Δ [-].
    blend_correlation_lengths : float
        Length/β of the variance-preserving cross-fade that makes a stretch periodic [-].
    steps_per_decade : float
        Target number of separation steps per decade of p_a [-].
    min_step : float
        Smallest separation step, in units of σ [-].
    max_step : float
        Largest separation step, in units of σ [-].
    max_contact_step : float
        Largest change of the contact fraction per step [-].
    max_pressure_pa : float
        Highest mean asperity pressure of the table [Pa].
    full_contact_fraction : float
        Contact fraction at which the ladder stops [-].
    min_contact_nodes : int
        Rows start once this many nodes touch [-].
    tol : float
        Solver tolerance on the contact conditions, in units of the rms height [-].
    floor_points_per_decade : int
        Density of the floor grid h/σ = 10^-5 … 10^1 of the stored gap moments [-].
    """

    window_correlation_lengths: float = 512.0
    n_windows: int = 8
    points_per_correlation_length: float = 32.0
    blend_correlation_lengths: float = 4.0
    steps_per_decade: float = 8.0
    min_step: float = 0.002
    max_step: float = 0.2
    max_contact_step: float = 0.05
    max_pressure_pa: float = 3.0e9
    full_contact_fraction: float = 0.995
    min_contact_nodes: int = 64
    tol: float = 1e-9
    floor_points_per_decade: int = 6

    def __post_init__(self):
        check_range("window_correlation_lengths", self.window_correlation_lengths, 4.0, 1e5)
        if not isinstance(self.n_windows, int) or not 1 <= self.n_windows <= 64:
            raise InputError("n_windows", self.n_windows, "an integer in [1, 64]")
        check_range("points_per_correlation_length", self.points_per_correlation_length, 2.0, 1024.0)
        check_range("blend_correlation_lengths", self.blend_correlation_lengths, 0.0, 100.0)
        check_range("steps_per_decade", self.steps_per_decade, 1.0, 100.0)
        check_range("min_step", self.min_step, 1e-6, 0.1)
        check_range("max_step", self.max_step, self.min_step, 2.0)
        check_range("max_contact_step", self.max_contact_step, 1e-3, 1.0)
        check_range("max_pressure_pa", self.max_pressure_pa, 1e5, 1e12)
        check_range("full_contact_fraction", self.full_contact_fraction, 0.5, 1.0)
        check_range("min_contact_nodes", self.min_contact_nodes, 1, 1e9)
        check_range("tol", self.tol, 1e-15, 1e-3)
        check_range("floor_points_per_decade", self.floor_points_per_decade, 1, 64)


def _periodic_stretch(z: np.ndarray, start: int, n_window: int, n_blend: int) -> np.ndarray:
    """Samples start+n_blend … start+n_blend+n_window−1 of the periodic profile ``z``, made periodic by fading the
    last n_blend samples into the n_blend samples that precede the window: y = cos θ·z[j] + sin θ·z[j − n_window],
    θ rising smoothly from 0 to π/2. The two summands are independent (n_window ≫ β) and cos² + sin² = 1, so the
    height variance (and the Gaussian marginal of a Gaussian profile) is kept."""
    size = z.size
    idx = (start + n_blend + np.arange(n_window)) % size
    y = z[idx].copy()
    if n_blend > 0:
        m = np.arange(1, n_blend + 1) / (n_blend + 1.0)
        theta = 0.5 * math.pi * (3 * m**2 - 2 * m**3)
        tail = np.arange(n_window - n_blend, n_window)
        before = start + n_blend + tail - n_window  # the n_blend samples that precede the window
        y[tail] = np.cos(theta) * z[(start + n_blend + tail) % size] + np.sin(theta) * z[before % size]
    return y


def _resample_periodic(y: np.ndarray, n_new: int) -> np.ndarray:
    """Band-limited (Fourier) resampling of periodic samples ``y`` (last axis) to ``n_new`` points."""
    n = y.shape[-1]
    if n_new == n:
        return y.copy()
    spec = sfft.rfft(y, axis=-1)
    if n % 2 == 0:
        spec[..., -1] *= 0.5  # split the old Nyquist term between ±k
    out = np.zeros(y.shape[:-1] + (n_new // 2 + 1,), dtype=complex)
    m = min(spec.shape[-1], out.shape[-1])
    out[..., :m] = spec[..., :m]
    return sfft.irfft(out, n=n_new, axis=-1) * (n_new / n)


MIN_WINDOW_CORRELATION_LENGTHS = 64.0
"""Shortest window [correlation lengths] :func:`windows_that_fit` shortens to for a short measured trace."""


def _window_layout(profile: RoughnessProfile, settings: DryContactSettings) -> tuple[int, int, int]:
    """(nodes of a window, profile samples of a window, profile samples of its blend) of :func:`composite_windows`."""
    beta = profile.correlation_length
    spacing_target = beta / settings.points_per_correlation_length
    n_nodes = sfft.next_fast_len(int(math.ceil(settings.window_correlation_lengths
                                               * settings.points_per_correlation_length - 1e-6)), real=True)
    n_nodes += n_nodes % 2
    n_window = int(round(n_nodes * spacing_target / profile.spacing))
    n_blend = int(math.ceil(settings.blend_correlation_lengths * beta / profile.spacing))
    return n_nodes, n_window, n_blend


def _samples_needed(profile: RoughnessProfile, settings: DryContactSettings) -> int:
    """Samples of ``profile`` that :func:`composite_windows` reads with ``settings``."""
    _, n_window, n_blend = _window_layout(profile, settings)
    return 2 * settings.n_windows * (n_window + n_blend)


def windows_that_fit(profile: RoughnessProfile, settings: DryContactSettings | None = None) -> DryContactSettings:
    """``settings`` (default :class:`DryContactSettings`) if ``profile`` is long enough for them; else the most
    windows (down to 1) of the same length that fit, and then, with one window, the longest window (down to
    :data:`MIN_WINDOW_CORRELATION_LENGTHS` correlation lengths, in halvings) that fits: a measured trace of a few
    millimetres (a few hundred correlation lengths) still gives the composite height and slope statistics of the
    film-law model, from less data. InputError naming the length needed when not even that fits."""
    settings = settings or DryContactSettings()
    if not (math.isfinite(profile.correlation_length) and profile.correlation_length > 0):
        return settings  # composite_windows names the problem
    candidate = settings
    while _samples_needed(profile, candidate) > profile.z.size:
        if candidate.n_windows > 1:
            candidate = replace(candidate, n_windows=candidate.n_windows - 1)
        elif candidate.window_correlation_lengths / 2 >= MIN_WINDOW_CORRELATION_LENGTHS:
            candidate = replace(candidate, window_correlation_lengths=candidate.window_correlation_lengths / 2)
        else:
            shortest = replace(candidate, window_correlation_lengths=MIN_WINDOW_CORRELATION_LENGTHS)
            raise InputError("roughness profile", profile.source or "<profile>",
                             f"at least {_samples_needed(profile, shortest)} samples (two stretches of "
                             f"{MIN_WINDOW_CORRELATION_LENGTHS:g} correlation lengths of "
                             f"{profile.correlation_length * 1e6:.3g} µm)", f"it has {profile.z.size}")
    return candidate


def composite_windows(profile: RoughnessProfile, rq1: float, rq2: float,
                      settings: DryContactSettings | None = None) -> tuple[np.ndarray, float]:
    """The composite roughness z = R1 + R2 [m] of ``settings.n_windows`` independent periodic windows, shape
    (n_windows, N), and the node spacing [m].

    Window w takes surface 1 from stretch 2w and surface 2 from stretch 2w + 1 of ``profile`` (consecutive,
    disjoint stretches of n_window + n_blend samples), each periodised (:func:`_periodic_stretch`), scaled by
    Rq_i / Rq_profile, resampled by Fourier interpolation to N ≥ L/Δ nodes (Δ = β/points_per_correlation_length,
    β = ``profile.correlation_length``), summed, and shifted to zero mean (the window mean is a long-wave part
    that the macro contact conforms to). Raises InputError when the profile is too short.
    """
    settings = settings or DryContactSettings()
    check_range("rq1", rq1, 0.0, 1e-4, unit="m")
    check_range("rq2", rq2, 0.0, 1e-4, unit="m")
    if rq1 == 0.0 and rq2 == 0.0:
        raise InputError("rq1, rq2", (rq1, rq2), "at least one positive Rq")
    beta = profile.correlation_length
    rq0 = profile.rq
    if not (math.isfinite(beta) and beta > 0 and rq0 > 0):
        raise InputError("roughness profile", profile.source, "a rough profile with a finite correlation length")
    n_nodes, n_window, n_blend = _window_layout(profile, settings)
    stretch = n_window + n_blend
    needed = 2 * settings.n_windows * stretch
    if needed > profile.z.size:
        raise InputError("roughness profile", profile.source or "<profile>",
                         f"at least {needed} samples for {settings.n_windows} windows of "
                         f"{settings.window_correlation_lengths:g} correlation lengths",
                         f"it has {profile.z.size}; lower n_windows or window_correlation_lengths "
                         "(windows_that_fit finds the settings a profile allows)")
    length = n_window * profile.spacing
    rows = []
    for w in range(settings.n_windows):
        y1 = _periodic_stretch(profile.z, 2 * w * stretch, n_window, n_blend) * (rq1 / rq0)
        y2 = _periodic_stretch(profile.z, (2 * w + 1) * stretch, n_window, n_blend) * (rq2 / rq0)
        rows.append(y1 + y2)
    z = _resample_periodic(np.array(rows), n_nodes)
    z -= z.mean(axis=1, keepdims=True)
    return z, length / n_nodes


# ---------------------------------------------------------------------------------------------------------------
# Table computation
# ---------------------------------------------------------------------------------------------------------------
def floor_grid(sigma: float, points_per_decade: int) -> np.ndarray:
    """Floor values h [m] of the stored gap moments: σ·10^u, u from −5 to 1 (``points_per_decade`` per decade)."""
    lo, hi = FLOOR_GRID_DECADES
    count = int(round((hi - lo) * points_per_decade)) + 1
    return sigma * np.logspace(lo, hi, count)


def quantile_rule() -> tuple[np.ndarray, np.ndarray]:
    """Levels t_q and weights w_q of the quadrature ∫₀¹ f(Q(t)) dt ≈ Σ w_q f(Q(t_q)) over the quantile function Q
    of the open gaps: Gauss–Legendre in s with t = s³ (clusters levels at the smallest gaps, where g ∝ t^{3/2})."""
    x, w = np.polynomial.legendre.leggauss(QUANTILE_NODES)
    s = 0.5 * (x + 1.0)
    return s**3, 0.5 * w * 3.0 * s**2


def _gap_statistics(gap: np.ndarray, floors: np.ndarray, levels: np.ndarray) -> dict:
    """CDF F(h) = P(g ≤ h), the open-gap floored moments ⟨max(g, h)^k·1[g > 0]⟩ (k in MOMENT_ORDERS) on the floor
    grid, and the quantiles of the open (g > 0) gaps at ``levels``, pooled over all nodes of all windows. (The
    full floored moment adds the contact atom: ⟨max(g, h)^k⟩ = open moment + contact fraction·h^k; storing the
    open part keeps it exact where the atom dominates by many orders of magnitude.)"""
    g = np.sort(gap.ravel())
    m = g.size
    idx = np.searchsorted(g, floors, side="right")
    cdf = idx / m
    moments = np.empty((len(MOMENT_ORDERS), floors.size))
    positive = g > 0.0
    zeros = m - int(positive.sum())
    for row, k in enumerate(MOMENT_ORDERS):
        powers = np.where(positive, np.power(np.where(positive, g, 1.0), float(k)), 0.0)
        suffix = np.concatenate([np.cumsum(powers[::-1])[::-1], [0.0]])  # suffix[i] = Σ_{j ≥ i} g_j^k
        moments[row] = ((idx - zeros) * floors**k + suffix[idx]) / m
    open_gaps = g[positive]
    quantiles = np.quantile(open_gaps, levels) if open_gaps.size else np.zeros(levels.size)
    return {"cdf": cdf, "moments": moments, "quantiles": quantiles}


def compute_dry_contact_table(profile: RoughnessProfile, rq1: float, rq2: float,
                              e_reduced: float = STEEL_E_REDUCED_PA, hardness: float = DEFAULT_HARDNESS_PA,
                              settings: DryContactSettings | None = None, *, progress=None) -> "DryContactTable":
    """Compute the dry-contact table of a roughness pair.

    The separation d steps down from the highest summit of the composite windows (:func:`composite_windows`),
    warm-started, with an adaptive step (:class:`DryContactSettings`); at every d the contact problem of all windows is
    solved (:func:`solve_contact`) and the statistics are pooled over all nodes (equal-d averaging: the macro film sees
    one d for all the roughness under it).

    Parameters
    ----------
    profile : RoughnessProfile
        Shape of both surfaces [-].
    rq1 : float
        RMS roughness of surface 1 [m].
    rq2 : float
        RMS roughness of surface 2 [m].
    e_reduced : float
        Reduced modulus E' [Pa].
    hardness : float
        Hardness H [Pa].
    settings : DryContactSettings, optional
        Numerical settings; None: the defaults [-].
    progress : callable, optional
        Called with (d/σ, p_a in Pa) after every step [-].

    Returns
    -------
    DryContactTable
        The table.
    """
    settings = settings or DryContactSettings()
    check_range("e_reduced", e_reduced, 1e6, 1e13, unit="Pa")
    check_range("hardness", hardness, 1e6, 1e13, unit="Pa")
    started = time.perf_counter()
    z, spacing = composite_windows(profile, rq1, rq2, settings)
    rows, n = z.shape
    sigma = math.hypot(rq1, rq2)
    ops = _Operators(n, spacing, e_reduced)
    scale = float(np.sqrt(np.mean(z * z)))
    floors = floor_grid(sigma, settings.floor_points_per_decade)
    levels, _ = quantile_rule()
    records = []
    d = float(z.max())
    p = np.zeros_like(z)
    step = 0.05 * sigma
    target = math.log(10.0) / settings.steps_per_decade
    iterations = inner = 0
    residual = 0.0
    for _ in range(400):
        d -= step
        d_col = np.full((rows, 1), d)
        p, kp, r, its, more = _solve_separation(ops, z, d_col, hardness, p, settings.tol * scale, 200)
        iterations += its
        inner += more
        residual = max(residual, float(_kkt_residual(p, r, hardness).max()))
        contact = p > 0.0
        n_contact = int(contact.sum())
        p_mean = float(p.mean())
        if progress is not None:
            progress(d / sigma, p_mean)
        if n_contact >= settings.min_contact_nodes:
            gap = np.where(contact, 0.0, np.maximum(r, 0.0))
            plastic = np.where(p >= hardness, np.maximum(-r, 0.0), 0.0)
            window_p = p.mean(axis=1)
            window_c = contact.mean(axis=1)
            spread = math.sqrt(rows) if rows > 1 else math.inf
            record = {"separation": d, "pressure": p_mean, "contact_fraction": n_contact / p.size,
                      "plastic_fraction": float((p >= hardness).mean()), "mean_gap": float(gap.mean()),
                      "mean_plastic": float(plastic.mean()),
                      "pressure_se": float(window_p.std(ddof=1) / spread) if rows > 1 else math.inf,
                      "contact_fraction_se": float(window_c.std(ddof=1) / spread) if rows > 1 else math.inf}
            record.update(_gap_statistics(gap, floors, levels))
            records.append(record)
        if p_mean >= settings.max_pressure_pa or n_contact >= settings.full_contact_fraction * p.size:
            break
        # next step: ~1/steps_per_decade of a decade of p_a, bounded in d and in the contact fraction
        if len(records) >= 2 and records[-1]["pressure"] > 0 and records[-2]["pressure"] > 0:
            a, b = records[-2], records[-1]
            dd = a["separation"] - b["separation"]
            slope = math.log(b["pressure"] / a["pressure"]) / dd
            cf_slope = (b["contact_fraction"] - a["contact_fraction"]) / dd
            step = target / max(slope, 1e-30)
            if cf_slope > 0:
                step = min(step, settings.max_contact_step / cf_slope)
        else:
            step = 0.05 * sigma
        step = min(max(step, settings.min_step * sigma), settings.max_step * sigma)
    else:
        raise SolverError("dry-contact ladder did not reach its end in 400 steps")
    if len(records) < 4:
        raise SolverError(f"dry-contact table has only {len(records)} rows; refine the settings")
    arrays = {f"tab_{key}": np.array([rec[key] for rec in records]) for key in records[0]}
    meta = {"format": TABLE_FORMAT, "rq1_m": rq1, "rq2_m": rq2, "sigma_m": sigma, "e_reduced_pa": e_reduced,
            "hardness_pa": hardness, "settings": asdict(settings), "profile_sha256": profile_hash(profile),
            "profile_source": profile.source, "correlation_length_m": profile.correlation_length,
            "window_rms_m": scale, "node_spacing_m": spacing, "nodes_per_window": n, "windows": rows,
            "iterations": iterations, "pcg_iterations": inner, "max_contact_residual_m": residual,
            "seconds": time.perf_counter() - started}
    meta["key"] = table_key(profile, rq1, rq2, e_reduced, hardness, settings)
    return DryContactTable(meta=meta, floors=floors, levels=levels, **arrays)


def profile_hash(profile: RoughnessProfile) -> str:
    """SHA-256 of a profile's heights (float64 bytes) and spacing (:attr:`RoughnessProfile.content_hash`, computed
    once per profile object)."""
    return profile.content_hash


def table_key(profile: RoughnessProfile, rq1: float, rq2: float, e_reduced: float, hardness: float,
              settings: DryContactSettings | None = None) -> str:
    """Content hash (hex, 24 characters) identifying a table: format version, profile hash, Rq1, Rq2, E', H and all
    settings. Dimensional values are keyed as given (plasticity breaks the σ, E' scaling of the elastic problem)."""
    return _table_key(profile_hash(profile), rq1, rq2, e_reduced, hardness, settings)


def _table_key(profile_digest: str, rq1: float, rq2: float, e_reduced: float, hardness: float,
               settings: DryContactSettings | None = None) -> str:
    """:func:`table_key` from the profile's hash (so that many keys of one profile hash it once)."""
    settings = settings or DryContactSettings()
    payload = {"format": TABLE_FORMAT, "profile": profile_digest, "rq1": float(rq1).hex(),
               "rq2": float(rq2).hex(), "e_reduced": float(e_reduced).hex(), "hardness": float(hardness).hex(),
               "settings": asdict(settings)}
    return hashlib.sha256(json.dumps(payload, sort_keys=True).encode()).hexdigest()[:24]


# ---------------------------------------------------------------------------------------------------------------
# Interpolation
# ---------------------------------------------------------------------------------------------------------------
def pchip_slopes(x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Node slopes of the monotone piecewise-cubic Hermite interpolant (Fritsch & Butland 1984: weighted harmonic
    mean of the adjacent secants, 0 at a local extremum), with the end slopes set to the end secants (which keeps
    the end intervals monotone and gives the continuations beyond the table a slope of the data's trend)."""
    h = np.diff(x)
    delta = np.diff(y) / h
    m = np.empty_like(y)
    m[0], m[-1] = delta[0], delta[-1]
    w1 = 2 * h[1:] + h[:-1]
    w2 = h[1:] + 2 * h[:-1]
    same = delta[:-1] * delta[1:] > 0
    with np.errstate(divide="ignore", invalid="ignore"):
        inner = (w1 + w2) / (w1 / delta[:-1] + w2 / delta[1:])
    m[1:-1] = np.where(same, inner, 0.0)
    return m


class _Curve:
    """C¹ function of d: monotone cubic Hermite through (x, y) (or through ln y when ``log``; node slopes from
    :func:`pchip_slopes`), continued beyond the ends.

    ``top`` (d > x_max): ``"linear"``; ``"exp"`` y0·e^{s(d−x)}, s = y0'/y0 (decay to 0); ``("gauss", w)``
    y0·exp(s t − t²/(2w²)), t = d − x (the Gaussian tail of the summit heights, w = σ); ``("power", k)``
    A(d − c)^k matched to value and slope (the large-gap law of a moment ⟨g^k⟩); ``"zero"``.
    ``bottom`` (d < x_min): ``"linear"``; ``("limit", L)`` L − (L − y0)e^{s(d−x)} matched to value and slope
    (approach to the limit L as d → −∞; for L = 0 and an end slope pointing away from 0, y0 e^{rt}(1 + (s0/y0 − r)t)
    with r = |s0/y0|). Every continuation matches the value and the slope at the end (C¹); a
    continuation whose matched parameters are not admissible falls back to the constant end value.
    """

    def __init__(self, x, y, *, log=False, top="linear", bottom="linear"):
        self.x = np.asarray(x, dtype=float)
        y = np.asarray(y, dtype=float)
        self.log = log
        values = np.log(y) if log else y
        self.spline = CubicHermiteSpline(self.x, values, pchip_slopes(self.x, values), extrapolate=False)
        self.dspline = self.spline.derivative()
        self.ends = []
        for xe, policy in ((self.x[0], bottom), (self.x[-1], top)):
            ye, se = self._inside(np.array([xe]))
            self.ends.append((float(xe), float(ye[0]), float(se[0]), policy))

    def _inside(self, d):
        v = self.spline(d)
        s = self.dspline(d)
        if self.log:
            v = np.exp(v)
            s = s * v
        return v, s

    @staticmethod
    def _outside(d, end):
        x0, y0, s0, policy = end
        t = d - x0
        kind = policy[0] if isinstance(policy, tuple) else policy
        if kind == "linear":
            return y0 + s0 * t, np.full_like(t, s0)
        if kind == "zero":
            return np.zeros_like(t), np.zeros_like(t)
        if kind == "gauss" and y0 > 0:  # y0 exp(r t − t²/(2 w²)), r = y0'/y0: Gaussian-tail decay (t > 0)
            rate, width = s0 / y0, policy[1]
            if rate <= 0:
                v = y0 * np.exp(rate * t - 0.5 * (t / width) ** 2)
                return v, (rate - t / width**2) * v
        if kind == "exp" and y0 > 0:
            rate = s0 / y0  # decay: rate < 0 above the table (t > 0)
            if rate * t.mean() < 0:
                v = y0 * np.exp(rate * t)
                return v, rate * v
        if kind == "power" and s0 != 0 and y0 != 0:
            k = policy[1]
            shift = k * y0 / s0  # = x0 − c > 0 required
            if shift > 0:
                base = (t + shift) / shift
                v = y0 * base**k
                return v, k * v / (t + shift)
        if kind == "limit":
            limit = policy[1]
            gap = limit - y0
            if gap != 0:
                rate = -s0 / gap
                if rate > 0:
                    e = np.exp(rate * t)
                    return limit - gap * e, -gap * rate * e
                if limit == 0.0:  # slope away from 0: y0 e^{rt}(1 + (s0/y0 − r)t), r = |s0/y0|, still → 0 (t < 0)
                    r = abs(s0 / y0)
                    c = s0 / y0 - r
                    e = np.exp(r * t)
                    return y0 * e * (1 + c * t), y0 * e * (r * (1 + c * t) + c)
        return np.full_like(t, y0), np.zeros_like(t)

    def __call__(self, d, derivative=False):
        d = np.asarray(d, dtype=float)
        flat = d.reshape(-1)
        value = np.empty_like(flat)
        slope = np.empty_like(flat)
        lo, hi = self.x[0], self.x[-1]
        inside = (flat >= lo) & (flat <= hi)
        if inside.any():
            value[inside], slope[inside] = self._inside(flat[inside])
        for mask, end in ((flat < lo, self.ends[0]), (flat > hi, self.ends[1])):
            if mask.any():
                value[mask], slope[mask] = self._outside(flat[mask], end)
        out = slope if derivative else value
        return out.reshape(d.shape) if d.ndim else float(out[0])


class _ShiftedAbove:
    """Open-gap moment ⟨max(g, h_b)^k·1[g > 0]⟩ as a C¹ function of d: the table's curve up to d_max; above it the
    open gaps of the top row shifted by t = d − d_max (asperities unloading: every open gap grows with the flat),
    Y(t) = (1 − cf(d)) Σ_q w_q max(Q_q + t, h_b)^k, times 1 + (a + c t) e^{−2t/σ} with a, c matching the value and
    the slope at d_max (C¹; the correction of the quadrature dies out within σ). Y has the far-field law
    ⟨(ḡ + t)^k⟩ of the shifted distribution."""

    def __init__(self, inner: _Curve, table: "DryContactTable", k: int, h_b: float):
        self.inner, self.table, self.k, self.h_b = inner, table, k, h_b
        self.top = float(inner.x[-1])
        self.quantiles = table.tab_quantiles[0]
        _, self.weights = quantile_rule()
        y0, s0 = inner.ends[1][1], inner.ends[1][2]
        v0, d0 = self._base(np.array([self.top]))
        v0, d0 = float(v0[0]), float(d0[0])
        self.b = 2.0 / table.sigma
        self.a = y0 / v0 - 1.0 if v0 > 0 else 0.0
        self.c = (s0 - d0 * (1 + self.a)) / v0 + self.a * self.b if v0 > 0 else 0.0

    def _base(self, d):
        t = d - self.top
        g = np.maximum(self.quantiles[None, :] + t[:, None], self.h_b)
        moving = (self.quantiles[None, :] + t[:, None]) > self.h_b
        mean = (g**self.k * self.weights).sum(axis=1)
        dmean = (np.where(moving, self.k * g ** (self.k - 1.0), 0.0) * self.weights).sum(axis=1)
        cf = np.asarray(self.table._contact_curve(d), dtype=float)
        dcf = np.asarray(self.table._contact_curve(d, derivative=True), dtype=float)
        return (1 - cf) * mean, (1 - cf) * dmean - dcf * mean

    def __call__(self, d, derivative=False):
        d = np.asarray(d, dtype=float)
        flat = d.reshape(-1)
        out = np.asarray(self.inner(flat, derivative), dtype=float).reshape(-1).copy()
        above = flat > self.top
        if above.any():
            t = flat[above] - self.top
            v, dv = self._base(flat[above])
            e = np.exp(-self.b * t)
            factor = 1 + (self.a + self.c * t) * e
            dfactor = (self.c - self.b * (self.a + self.c * t)) * e
            out[above] = dv * factor + v * dfactor if derivative else v * factor
        return out.reshape(d.shape) if d.ndim else float(out[0])


@dataclass(eq=False)
class DryContactTable:
    """Dry-contact table of one roughness pair (one row per separation d), with C¹ interpolation in d.

    Every method takes d as a scalar or array and returns the same shape; methods named ``d_*`` are derivatives with
    respect to d. Outside the table: above it (large d) p_a and the contact fraction decay like a Gaussian tail,
    y0·exp(s t − t²/2σ²) with the end slope s (C¹), the plastic fraction exponentially, ⟨g⟩ continues linearly, the
    open-gap moments follow the top row's open gaps shifted by d − d_max; below it (small d) p_a continues linearly
    with the end slope, the fractions tend to 1, ⟨g⟩ → 0 and ⟨max(g, h_b)^k⟩ → h_b^k exponentially (C¹). Never NaN.
    Build it with :func:`dry_contact_table` or :meth:`load`.

    Parameters
    ----------
    meta : dict
        Provenance: Rq1, Rq2, σ, E', H, settings, profile hash, key, cost [-].
    floors : ndarray
        Floor grid h of the stored gap moments [m].
    levels : ndarray
        Quantile levels of :func:`quantile_rule` [-].
    tab_separation : ndarray
        (n,) separations d, descending as computed [m].
    tab_pressure : ndarray
        (n,) mean asperity pressure p_a [Pa].
    tab_contact_fraction : ndarray
        (n,) contact fraction [-].
    tab_plastic_fraction : ndarray
        (n,) plastic (yielded) fraction [-].
    tab_mean_gap : ndarray
        (n,) mean gap ⟨g⟩, the lubricant volume per area [m].
    tab_mean_plastic : ndarray
        (n,) mean plastic displacement ⟨u_p⟩ [m].
    tab_pressure_se : ndarray
        (n,) sampling standard error of p_a (spread of the independent windows' means / √windows) [Pa].
    tab_contact_fraction_se : ndarray
        (n,) sampling standard error of the contact fraction [-].
    tab_cdf : ndarray
        (n, n_h) P(g ≤ h) on ``floors`` [-].
    tab_moments : ndarray
        (n, 4, n_h) open-gap moments ⟨max(g, h)^k·1[g > 0]⟩ for k in :data:`MOMENT_ORDERS`, in m^k [-].
    tab_quantiles : ndarray
        (n, n_q) quantiles of the open gaps at ``levels`` [m].
    """

    meta: dict
    floors: np.ndarray
    levels: np.ndarray
    tab_separation: np.ndarray
    tab_pressure: np.ndarray
    tab_contact_fraction: np.ndarray
    tab_plastic_fraction: np.ndarray
    tab_mean_gap: np.ndarray
    tab_mean_plastic: np.ndarray
    tab_pressure_se: np.ndarray
    tab_contact_fraction_se: np.ndarray
    tab_cdf: np.ndarray
    tab_moments: np.ndarray
    tab_quantiles: np.ndarray
    _cache: dict = field(default_factory=dict, repr=False)

    ARRAYS = ("floors", "levels") + tuple(f"tab_{name}" for name in (
        "separation", "pressure", "contact_fraction", "plastic_fraction", "mean_gap", "mean_plastic", "pressure_se",
        "contact_fraction_se", "cdf", "moments", "quantiles"))

    # -- description --------------------------------------------------------------------------------------------
    @property
    def sigma(self) -> float:
        """Composite rms roughness σ = √(Rq1² + Rq2²) [m]."""
        return float(self.meta["sigma_m"])

    @property
    def key(self) -> str:
        return str(self.meta["key"])

    @property
    def d_range(self) -> tuple[float, float]:
        """Smallest and largest tabulated separation [m]."""
        return float(self.tab_separation.min()), float(self.tab_separation.max())

    def _ascending(self, values):
        return np.asarray(values)[::-1]

    @functools.cached_property
    def _x(self):
        return self._ascending(self.tab_separation)

    # -- curves ---------------------------------------------------------------------------------------------------
    @functools.cached_property
    def _pressure_curve(self):
        return _Curve(self._x, self._ascending(self.tab_pressure), log=True, top=("gauss", self.sigma),
                      bottom="linear")

    @functools.cached_property
    def _contact_curve(self):
        return _Curve(self._x, self._ascending(self.tab_contact_fraction), log=True, top=("gauss", self.sigma),
                      bottom=("limit", 1.0))

    @functools.cached_property
    def _plastic_curve(self):
        return _Curve(self._x, self._ascending(self.tab_plastic_fraction), top="exp", bottom=("limit", 1.0))

    @functools.cached_property
    def _gap_curve(self):
        return _Curve(self._x, self._ascending(self.tab_mean_gap), top="linear", bottom=("limit", 0.0))

    @functools.cached_property
    def _quantile_spline(self):
        return PchipInterpolator(self._x, self._ascending(self.tab_quantiles), axis=0, extrapolate=False)

    def asperity_pressure(self, d):
        """Mean asperity (dry-contact) pressure p_a(d), ≥ 0, decreasing in d.

        Parameters
        ----------
        d : float or array_like
            Separation of the mean planes [m].

        Returns
        -------
        ndarray
            p_a [Pa].
        """
        return self._pressure_curve(d)

    def d_asperity_pressure(self, d):
        """dp_a/dd, ≤ 0.

        Parameters
        ----------
        d : float or array_like
            Separation of the mean planes [m].

        Returns
        -------
        ndarray
            dp_a/dd [Pa/m].
        """
        return self._pressure_curve(d, derivative=True)

    def contact_fraction(self, d):
        """Fraction of the nominal area in dry contact (p > 0).

        Parameters
        ----------
        d : float or array_like
            Separation of the mean planes [m].

        Returns
        -------
        ndarray
            Between 0 and 1 [-].
        """
        return self._contact_curve(d)

    def d_contact_fraction(self, d):
        """Derivative of the contact fraction with respect to d.

        Parameters
        ----------
        d : float or array_like
            Separation of the mean planes [m].

        Returns
        -------
        ndarray
            d(contact fraction)/dd [1/m].
        """
        return self._contact_curve(d, derivative=True)

    def lubricated_fraction(self, d):
        """1 − contact fraction: the fraction of the area covered by lubricant.

        Parameters
        ----------
        d : float or array_like
            Separation of the mean planes [m].

        Returns
        -------
        ndarray
            Between 0 and 1 [-].
        """
        return 1.0 - self._contact_curve(d)

    def plastic_fraction(self, d):
        """Fraction of the nominal area at the hardness (yielded), at most the contact fraction.

        Parameters
        ----------
        d : float or array_like
            Separation of the mean planes [m].

        Returns
        -------
        ndarray
            Between 0 and 1 [-].
        """
        return np.minimum(np.maximum(self._plastic_curve(d), 0.0), self._contact_curve(d))

    def mean_gap(self, d, h_b: float = 0.0):
        """Mean gap ⟨max(g, h_b)⟩ (h_b = 0: the lubricant volume per area, ⟨g⟩ = d + ⟨u_p⟩).

        Parameters
        ----------
        d : float or array_like
            Separation of the mean planes [m].
        h_b : float
            Film-breakdown floor of the gaps [m].

        Returns
        -------
        ndarray
            Mean gap [m].
        """
        if h_b == 0.0:
            return self._gap_curve(d)
        return self.gap_moment(d, 1, h_b)

    def d_mean_gap(self, d, h_b: float = 0.0):
        """d⟨max(g, h_b)⟩/dd.

        Parameters
        ----------
        d : float or array_like
            Separation of the mean planes [m].
        h_b : float
            Film-breakdown floor of the gaps [m].

        Returns
        -------
        ndarray
            Derivative [-].
        """
        if h_b == 0.0:
            return self._gap_curve(d, derivative=True)
        return self.d_gap_moment(d, 1, h_b)

    def gap_moment(self, d, k: int, h_b: float, part: str = "all"):
        """Floored gap moment ⟨max(g, h_b)^k⟩ over the whole area or over the open gaps only.

        ``part="all"``: contact spots count as gaps h_b; ``part="open"``: ⟨max(g, h_b)^k·1[g > 0]⟩. Below 10⁻⁵σ the open
        part is held at its value at 10⁻⁵σ.

        Parameters
        ----------
        d : float or array_like
            Separation of the mean planes [m].
        k : int
            Order, in :data:`MOMENT_ORDERS` (1, −1, −2, −3) [-].
        h_b : float
            Film-breakdown floor, > 0 and ≤ 10σ [m].
        part : str
            ``all`` or ``open`` [-].

        Returns
        -------
        ndarray
            The moment, in m^k [-].
        """
        return self._moment_curve(k, h_b, part)(d)

    def d_gap_moment(self, d, k: int, h_b: float, part: str = "all"):
        """d/dd of :meth:`gap_moment`.

        Parameters
        ----------
        d : float or array_like
            Separation of the mean planes [m].
        k : int
            Order, in :data:`MOMENT_ORDERS` [-].
        h_b : float
            Film-breakdown floor [m].
        part : str
            ``all`` or ``open`` [-].

        Returns
        -------
        ndarray
            The derivative, in m^(k−1) [-].
        """
        return self._moment_curve(k, h_b, part)(d, derivative=True)

    def _moment_curve(self, k: int, h_b: float, part: str):
        """C¹ curve of the open-gap moment in d (log-Hermite for k < 0; above the table the power law A(d − c)^k
        of a distribution that only shifts, below it → 0); for ``part="all"`` the contact atom
        contact_fraction(d)·h_b^k is added (so the atom decays with the contact fraction above the table and the
        moment tends to h_b^k below it)."""
        if part not in ("all", "open"):
            raise InputError("part", part, "'all' or 'open'")
        key = (int(k), float(h_b))
        curve = self._cache.get(key)
        if curve is None:
            column = self._ascending(np.maximum(self._open_moment_column(k, h_b), 1e-300))
            inner = _Curve(self._x, column, log=k < 0, top=("power", float(k)), bottom=("limit", 0.0))
            curve = _ShiftedAbove(inner, self, k, float(h_b))
            if len(self._cache) > 64:
                self._cache.clear()
            self._cache[key] = curve
        if part == "open":
            return curve
        atom = float(h_b) ** k
        contact = self._contact_curve

        def full(d, derivative=False):
            return curve(d, derivative) + atom * contact(d, derivative)
        return full

    def _open_moment_column(self, k: int, h_b: float) -> np.ndarray:
        """⟨max(g, h_b)^k·1[g > 0]⟩ at every table row: cubic Hermite in (ln h, ln O) between floor-grid points
        with the exact slope d ln O/d ln h = k h^k (F(h) − F(0))/O."""
        if k not in MOMENT_ORDERS:
            raise InputError("k", k, f"one of {MOMENT_ORDERS}")
        h_b = float(h_b)
        floors = self.floors
        if not (math.isfinite(h_b) and 0.0 < h_b <= floors[-1]):
            raise InputError("h_b", h_b, f"a floor in (0, {floors[-1]:.3g}] m (0 < h_b ≤ 10σ)")
        row = MOMENT_ORDERS.index(k)
        values = self.tab_moments[:, row, :]
        if h_b <= floors[0]:
            return values[:, 0].copy()
        u = np.log(floors)
        i = min(int(np.searchsorted(u, math.log(h_b), side="right")) - 1, u.size - 2)
        du = u[i + 1] - u[i]
        t = (math.log(h_b) - u[i]) / du
        open_cdf = np.maximum(self.tab_cdf - self.tab_contact_fraction[:, None], 0.0)
        ok = (values[:, i] > 0) & (values[:, i + 1] > 0)
        v0 = np.where(ok, values[:, i], 1.0)
        v1 = np.where(ok, values[:, i + 1], 1.0)
        y0, y1 = np.log(v0), np.log(v1)
        m0 = k * floors[i] ** k * open_cdf[:, i] / v0
        m1 = k * floors[i + 1] ** k * open_cdf[:, i + 1] / v1
        h00, h10, h01, h11 = 2 * t**3 - 3 * t**2 + 1, t**3 - 2 * t**2 + t, -2 * t**3 + 3 * t**2, t**3 - t**2
        hermite = np.exp(h00 * y0 + h10 * du * m0 + h01 * y1 + h11 * du * m1)
        linear = values[:, i] * (1 - t) + values[:, i + 1] * t
        return np.where(ok, hermite, linear)

    def open_gap_expectation(self, d, func, h_b: float = 0.0):
        """⟨f(max(g, h_b))·1[g > 0]⟩: the average over the nominal area of f on the open (lubricated) gaps.

        That is (1 − contact fraction) × the mean of f over the open gaps, by a 24-point quadrature of the open
        gaps' quantile function (:func:`quantile_rule`), typically within 1 % of the exact pooled average for smooth f
        (a few % for the strongly singular g⁻³). Outside the table the quantiles are shifted by d − d_max above it and
        scaled with the mean gap below it.

        Parameters
        ----------
        d : float or array_like
            Separation of the mean planes [m].
        func : callable
            f, called once with an array of floored gaps in m of shape (number of d values, 24); row i belongs to the
            i-th d, so per-d parameters can be broadcast as ``param[:, None]`` [-].
        h_b : float
            Film-breakdown floor of the gaps [m].

        Returns
        -------
        ndarray
            The expectation, in the unit of f, shaped like ``d`` [-].
        """
        d = np.asarray(d, dtype=float)
        flat = d.reshape(-1)
        lo, hi = self._x[0], self._x[-1]
        q = np.empty((flat.size, self.levels.size))
        inside = (flat >= lo) & (flat <= hi)
        q[inside] = self._quantile_spline(flat[inside])
        above = flat > hi
        q[above] = self.tab_quantiles[0][None, :] + (flat[above] - hi)[:, None]
        below = flat < lo
        if below.any():
            ratio = self._gap_curve(flat[below]) / max(float(self.tab_mean_gap[-1]), 1e-300)
            q[below] = self.tab_quantiles[-1][None, :] * ratio[:, None]
        _, weights = quantile_rule()
        cf = np.clip(np.asarray(self.contact_fraction(flat), dtype=float).reshape(-1), 0.0, 1.0)
        values = np.asarray(func(np.maximum(q, h_b)), dtype=float)
        out = (1.0 - cf) * (values * weights).sum(axis=1)
        return out.reshape(d.shape) if d.ndim else float(out[0])

    def gap_expectation(self, d, func, h_b: float = 0.0):
        """⟨f(max(g, h_b))⟩ over the whole nominal area.

        The contact spots (g = 0) contribute f(h_b) (``func`` is then called with an array of shape (number of d values,
        1) filled with h_b), the open gaps as in :meth:`open_gap_expectation`.

        Parameters
        ----------
        d : float or array_like
            Separation of the mean planes [m].
        func : callable
            f of an array of floored gaps in m [-].
        h_b : float
            Film-breakdown floor of the gaps [m].

        Returns
        -------
        ndarray
            The expectation, in the unit of f [-].
        """
        d = np.asarray(d, dtype=float)
        flat = d.reshape(-1)
        cf = np.clip(np.asarray(self.contact_fraction(flat), dtype=float).reshape(-1), 0.0, 1.0)
        at_floor = np.asarray(func(np.full((flat.size, 1), float(h_b))), dtype=float).reshape(-1)
        out = cf * at_floor + np.asarray(self.open_gap_expectation(flat, func, h_b)).reshape(-1)
        return out.reshape(d.shape) if d.ndim else float(out[0])

    def separation_at_pressure(self, p_a):
        """Inverse of :meth:`asperity_pressure`: the separation at which the mean asperity pressure is ``p_a``.

        Newton iterations on ln p_a(d) from a PCHIP guess; exact inverse also outside the table.

        Parameters
        ----------
        p_a : float or array_like
            Mean asperity pressure, > 0 [Pa].

        Returns
        -------
        ndarray
            d [m].
        """
        p_a = np.asarray(p_a, dtype=float)
        if np.any(~(p_a > 0)) or not np.all(np.isfinite(p_a)):
            raise InputError("p_a", "array" if p_a.ndim else float(p_a), "finite pressures > 0 [Pa]")
        x = self._x
        lp = np.log(self._ascending(self.tab_pressure))
        guess = PchipInterpolator(lp[::-1], x[::-1], extrapolate=True)
        d = np.clip(guess(np.log(p_a)), x[0] - 10 * self.sigma, x[-1] + 10 * self.sigma)
        for _ in range(30):
            value = self.asperity_pressure(d)
            slope = self.d_asperity_pressure(d)
            f = np.log(np.maximum(value, 1e-300)) - np.log(p_a)
            fp = slope / np.maximum(value, 1e-300)
            step = np.where(fp < 0, f / np.where(fp < 0, fp, -1.0), 0.0)
            step = np.clip(step, -self.sigma, self.sigma)
            d = d - step
            if np.all(np.abs(step) <= 1e-12 * self.sigma):
                break
        return d if d.ndim else float(d)

    def summary(self) -> dict:
        """Short description of the table.

        Returns
        -------
        dict
            Rq pair, σ, E', H [SI, units in the keys], d range in σ, p_a range, rows, cost.
        """
        return {"rq1_m": self.meta["rq1_m"], "rq2_m": self.meta["rq2_m"], "sigma_m": self.sigma,
                "e_reduced_pa": self.meta["e_reduced_pa"], "hardness_pa": self.meta["hardness_pa"],
                "rows": int(self.tab_separation.size), "d_over_sigma": [float(v / self.sigma) for v in self.d_range],
                "p_a_pa": [float(self.tab_pressure.min()), float(self.tab_pressure.max())],
                "max_contact_fraction": float(self.tab_contact_fraction.max()), "seconds": self.meta.get("seconds"),
                "key": self.key}

    # -- storage --------------------------------------------------------------------------------------------------
    def save(self, path: str | Path) -> Path:
        """Write the table as a compressed .npz (CDF and quantiles in float32, ~50 kB) with its metadata as JSON.

        Parameters
        ----------
        path : str or Path
            The file [-].

        Returns
        -------
        Path
            The file written.
        """
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        arrays = {}
        for name in self.ARRAYS:
            value = np.asarray(getattr(self, name))
            arrays[name] = value.astype(np.float32) if name in ("tab_cdf", "tab_quantiles") else value
        tmp = path.with_name(path.name + f".tmp{os.getpid()}.npz")
        np.savez_compressed(tmp, meta=np.array(json.dumps(self.meta)), **arrays)
        os.replace(tmp, path)
        return path

    @classmethod
    def load(cls, path: str | Path) -> "DryContactTable":
        """Read a table written by :meth:`save`.

        Parameters
        ----------
        path : str or Path
            The file [-].

        Returns
        -------
        DryContactTable
            The table.
        """
        with np.load(Path(path), allow_pickle=False) as data:
            meta = json.loads(str(data["meta"]))
            if meta.get("format") != TABLE_FORMAT:
                raise InputError("dry-contact table", str(path), f"format {TABLE_FORMAT}",
                                 f"file has {meta.get('format')}")
            arrays = {name: np.asarray(data[name], dtype=float) for name in cls.ARRAYS}
        return cls(meta=meta, **arrays)


# ---------------------------------------------------------------------------------------------------------------
# Shipped tables, disk cache
# ---------------------------------------------------------------------------------------------------------------
SHIPPED_DIR = ("roughness", "dry_contact")
"""Data sub-directory of the shipped tables (``data/roughness/dry_contact/<key>.npz``)."""
PAPER_RQ_PAIRS_UM = ((0.05, 0.05), (0.1, 0.1), (0.2, 0.2), (0.3, 0.3), (0.4, 0.4), (0.5, 0.5), (0.7, 0.7),
                     (1.0, 1.0), (0.2, 0.5), (0.4, 1.0))
"""The (Rq1, Rq2) pairs [µm] of the paper's factorial, whose tables (shipped profiles
:data:`SHIPPED_TABLE_PROFILES`, steel E', H = 6.8 GPa, default settings) ship with the package."""

SHIPPED_TABLE_PROFILES = ("baseline_synthetic", "flank_ground")
"""Names of the shipped profiles whose dry-contact tables ship (:func:`build_shipped_tables`)."""


def cache_directory() -> Path:
    """Directory of computed tables: ``$GEARLOSS_CACHE_DIR/dry_contact`` or ``~/.cache/gearloss/dry_contact``."""
    root = os.environ.get(CACHE_ENV)
    base = Path(root) if root else Path.home() / ".cache" / "gearloss"
    return base / "dry_contact"


def dry_contact_table(profile: RoughnessProfile | None = None, rq1: float = 0.4e-6, rq2: float = 0.4e-6,
                      e_reduced: float = STEEL_E_REDUCED_PA, hardness: float = DEFAULT_HARDNESS_PA,
                      settings: DryContactSettings | None = None, *, cache: bool = True,
                      cache_dir: str | Path | None = None) -> DryContactTable:
    """The dry-contact table of ``profile`` scaled to ``rq1``, ``rq2``, for the reduced modulus and hardness given.

    Looked up by its content key (:func:`table_key`) among the shipped tables (data/roughness/dry_contact/), then in
    the cache directory; otherwise computed (:func:`compute_dry_contact_table`, seconds to a minute) and, with
    ``cache``, written to the cache.

    Parameters
    ----------
    profile : RoughnessProfile, optional
        Shape of both surfaces; None: the default profile (:func:`~ehl_dataset.model.roughness.default_profile`) [-].
    rq1 : float
        RMS roughness of surface 1 [m].
    rq2 : float
        RMS roughness of surface 2 [m].
    e_reduced : float
        Reduced modulus E' [Pa].
    hardness : float
        Hardness H of the softer surface (``math.inf``: purely elastic) [Pa].
    settings : DryContactSettings, optional
        Numerical settings; None: the defaults, with as many windows as the profile holds (:func:`windows_that_fit`;
        the defaults themselves on the baseline) [-].
    cache : bool
        Write a computed table to the cache [-].
    cache_dir : str or Path, optional
        Cache directory; None: :func:`cache_directory` [-].

    Returns
    -------
    DryContactTable
        The table.
    """
    profile = profile if profile is not None else default_profile()
    settings = settings or windows_that_fit(profile)
    key = table_key(profile, rq1, rq2, e_reduced, hardness, settings)
    shipped = data_path(*SHIPPED_DIR, f"{key}.npz")
    if shipped.is_file():
        return _shipped_table(str(shipped))
    directory = Path(cache_dir) if cache_dir is not None else cache_directory()
    cached = directory / f"{key}.npz"
    if cache and cached.is_file():
        try:
            return DryContactTable.load(cached)
        except (OSError, ValueError, KeyError):
            pass  # unreadable or stale: recompute
    table = compute_dry_contact_table(profile, rq1, rq2, e_reduced, hardness, settings)
    if cache:
        try:
            table.save(cached)
        except OSError:
            pass  # a read-only cache is not an error
    return table


def similar_dry_contact_table(profile: RoughnessProfile | None = None, rq1: float = 0.4e-6, rq2: float = 0.4e-6,
                              e_reduced: float = STEEL_E_REDUCED_PA, hardness: float = DEFAULT_HARDNESS_PA,
                              settings: DryContactSettings | None = None,
                              pairs=PAPER_RQ_PAIRS_UM) -> tuple[DryContactTable, float, tuple[float, float]]:
    """A dry-contact table for (``rq1``, ``rq2``) without computing one where a shipped table of the same profile can
    be scaled to it: (table, scale, (Rq1, Rq2) of the table [m]), to be read as p_a(d) = scale·p_table(d/scale),
    A(d) = A_table(d/scale).

    A shipped table of the pair itself has scale 1. Otherwise the shipped table of ``pairs`` nearest in composite
    roughness S = √(Rq1² + Rq2²) and in the mixing angle
    θ = atan(min(Rq)/max(Rq)) is taken with scale S/S_table. Both surfaces are stretches of one stationary profile, so
    the composite heights normalised by S have the same spectrum at every θ (only the realisation differs), and
    scaling all heights by a factor scales the elastic contact pressures and separations by it (Johnson, *Contact
    Mechanics*, 1985, §13; exact for the same θ); the plastic cap H becomes scale·H. Without a shipped table of the
    profile (a user's profile) the pair's own table is computed or read from the cache (:func:`dry_contact_table`).
    A cached table of a shipped profile is not used: the result does not depend on what a machine has cached.

    Parameters
    ----------
    profile : RoughnessProfile, optional
        Shape of both surfaces; None: the default profile [-].
    rq1, rq2 : float
        RMS roughness of the two surfaces [m].
    e_reduced : float
        Reduced modulus E' [Pa].
    hardness : float
        Hardness H of the softer surface [Pa].
    settings : DryContactSettings, optional
        Numerical settings; None: the windows that fit (:func:`windows_that_fit`) [-].
    pairs : sequence of (float, float)
        The shipped (Rq1, Rq2) pairs to look for [µm] [-].

    Returns
    -------
    tuple
        (DryContactTable, scale [-], (Rq1, Rq2) of the table [m]).
    """
    profile = profile if profile is not None else default_profile()
    settings = settings or windows_that_fit(profile)
    check_range("rq1", rq1, 0.0, 1e-4, unit="m")
    check_range("rq2", rq2, 0.0, 1e-4, unit="m")
    if rq1 == 0.0 and rq2 == 0.0:
        raise InputError("rq1, rq2", (rq1, rq2), "at least one positive Rq")
    digest = profile_hash(profile)
    own = data_path(*SHIPPED_DIR, f"{_table_key(digest, rq1, rq2, e_reduced, hardness, settings)}.npz")
    if own.is_file():
        return _shipped_table(str(own)), 1.0, (rq1, rq2)
    target_s, target_theta = math.hypot(rq1, rq2), math.atan2(min(rq1, rq2), max(rq1, rq2))
    best = None
    for rq1_um, rq2_um in pairs:
        a, b = rq1_um * 1e-6, rq2_um * 1e-6
        path = data_path(*SHIPPED_DIR, f"{_table_key(digest, a, b, e_reduced, hardness, settings)}.npz")
        if not path.is_file():
            continue
        distance = abs(math.log(target_s / math.hypot(a, b))) + abs(target_theta - math.atan2(min(a, b), max(a, b)))
        if best is None or distance < best[0]:
            best = (distance, path, (a, b))
    if best is None:
        return dry_contact_table(profile, rq1, rq2, e_reduced, hardness, settings), 1.0, (rq1, rq2)
    _, path, pair = best
    return _shipped_table(str(path)), target_s / math.hypot(*pair), pair


@functools.lru_cache(maxsize=64)
def _shipped_table(path: str) -> DryContactTable:
    """A shipped table, read once per process (tables are not modified after loading; their curves are cached on
    them)."""
    return DryContactTable.load(Path(path))


def build_shipped_tables(directory: str | Path | None = None, pairs=PAPER_RQ_PAIRS_UM, progress=print,
                         profiles=SHIPPED_TABLE_PROFILES) -> Path:
    """Compute the tables of the shipped profiles ``profiles`` (names of
    :data:`ehl_dataset.model.roughness.PROFILES`) for the (Rq1, Rq2) ``pairs`` [µm] (steel E', H = 6.8 GPa, default
    settings, windowed as :func:`windows_that_fit` allows: what the homogenised models ask for) into ``directory``
    (default data/roughness/dry_contact/) with an index.json.
    Regenerate: ``python -c "from ehl_dataset.model.dry_contact import build_shipped_tables as b; b()"``."""
    from .roughness import named_profile

    target = Path(directory) if directory is not None else data_path(*SHIPPED_DIR)
    target.mkdir(parents=True, exist_ok=True)
    index = {"format": TABLE_FORMAT, "e_reduced_pa": STEEL_E_REDUCED_PA, "hardness_pa": DEFAULT_HARDNESS_PA,
             "profiles": {}, "tables": []}
    for name in profiles:
        profile = named_profile(name)
        settings = windows_that_fit(profile)
        index["profiles"][name] = {"sha256": profile_hash(profile), "settings": asdict(settings)}
        for rq1_um, rq2_um in pairs:
            table = compute_dry_contact_table(profile, rq1_um * 1e-6, rq2_um * 1e-6, settings=settings)
            table.save(target / f"{table.key}.npz")
            row = table.summary()
            index["tables"].append({"profile": name, "rq_um": [rq1_um, rq2_um], "key": table.key,
                                    "rows": row["rows"], "d_over_sigma": row["d_over_sigma"], "p_a_pa": row["p_a_pa"],
                                    "max_contact_fraction": row["max_contact_fraction"],
                                    "seconds": round(row["seconds"], 1)})
            if progress:
                progress(f"{name} {rq1_um}/{rq2_um} um: {row['rows']} rows, {row['seconds']:.1f} s -> {table.key}.npz")
    (target / "index.json").write_text(json.dumps(index, indent=1) + "\n")
    return target
