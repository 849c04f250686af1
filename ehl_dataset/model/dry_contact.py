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
p_a(d) is therefore very steep at d ≈ 0 (vertical in the purely elastic limit). See docs/homogenised_closures.md.

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
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
import scipy.fft as sfft
from scipy.interpolate import PchipInterpolator

from ehl_dataset.data_files import data_path
from ehl_dataset.roughness import RoughnessProfile, baseline_profile
from ehl_dataset.validation import InputError, SolverError, check_range

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
    """Zero-mean elastic deflection u_e [m] of the periodic pressure ``p`` [Pa] (last axis: uniform nodes of
    ``spacing`` [m]), û(k) = 4 p̂(k)/(E'|k|): the project's V(x) = −4/(πE') ∫ ln|x − x'| p(x') dx' for a periodic p,
    up to the constant (k = 0) term, which is set to zero."""
    p = np.asarray(p, dtype=float)
    n = p.shape[-1]
    mult = elastic_multiplier(n, n * spacing, e_reduced)
    return sfft.irfft(sfft.rfft(p, axis=-1) * mult, n=n, axis=-1)


@dataclass
class ContactSolution:
    """Solution of :func:`solve_contact` for R windows (arrays (R, N) or (R,)); SI units.

    ``pressure`` p, ``separation`` d of each window, ``gap`` g ≥ 0 (0 on contact nodes), ``plastic`` u_p ≥ 0,
    ``deflection`` u_e (zero mean), ``iterations`` outer (active-set) iterations, ``inner_iterations`` PCG
    iterations in all, ``residual`` the largest violation of the contact conditions (|r| on free nodes, −r on open
    ones, r on yielded ones) over all windows [m].
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
        return sfft.irfft(sfft.rfft(v, axis=-1) * self.mult, n=self.n, axis=-1)

    def precondition(self, v):
        return sfft.irfft(sfft.rfft(v, axis=-1) * self.inv, n=self.n, axis=-1)


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
        x, its = _pcg(ops, free, rhs, p, 1e-11 if tight else 1e-4, 500)
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

    ``z`` heights [m], shape (N,) or (R, N) (R independent periodic windows of uniform ``spacing`` [m]);
    ``e_reduced`` E' [Pa]; ``hardness`` H [Pa] (``math.inf``: purely elastic). Give either ``separation`` d [m]
    (scalar or one per window; displacement control, the primary mode) or ``mean_pressure`` p̄ [Pa] (load control:
    d is found per window by a safeguarded secant iteration on ln p̄(d), for tests and one-off use; it fails at a
    full elastic contact, where p̄(d) is vertical). ``p0`` optional start (warm start). Converged when the
    contact conditions hold to ``tol`` × rms(z) in every window; raises SolverError otherwise.
    """
    z = np.atleast_2d(np.asarray(z, dtype=float))
    rows, n = z.shape
    check_range("e_reduced", e_reduced, 0.0, 1e15, low_inclusive=False, unit="Pa")
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
    elastic = not math.isfinite(hardness)  # then p̄(d) → ∞ only as d → 0⁺: stay above 0

    def lower(d, step):
        return np.maximum(d - step, 0.25 * d) if elastic else d - step

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

    ``window_correlation_lengths`` window length L/β; ``n_windows`` independent windows averaged (each uses two
    disjoint stretches of the profile, one per surface); ``points_per_correlation_length`` β/Δ (resolution);
    ``blend_correlation_lengths`` length/β of the variance-preserving cross-fade that makes a stretch periodic;
    ``levels_per_decade`` mean-pressure steps per decade; ``first_level`` lowest p̄ as a fraction of
    p_scale = min(H, E'·s_rms/2) (s_rms the composite rms slope); ``max_pressure_pa`` the ladder stops at this p̄
    or at ``full_contact_fraction``; ``tol`` CG tolerance (relative pressure change).
    """

    window_correlation_lengths: float = 512.0
    n_windows: int = 4
    points_per_correlation_length: float = 32.0
    blend_correlation_lengths: float = 4.0
    levels_per_decade: int = 8
    first_level: float = 1e-4
    max_pressure_pa: float = 3.0e9
    full_contact_fraction: float = 0.995
    tol: float = 1e-9
    floor_points_per_decade: int = 8

    def __post_init__(self):
        check_range("window_correlation_lengths", self.window_correlation_lengths, 4.0, 1e5)
        if not isinstance(self.n_windows, int) or not 1 <= self.n_windows <= 64:
            raise InputError("n_windows", self.n_windows, "an integer in [1, 64]")
        check_range("points_per_correlation_length", self.points_per_correlation_length, 2.0, 1024.0)
        check_range("blend_correlation_lengths", self.blend_correlation_lengths, 0.0, 100.0)
        check_range("first_level", self.first_level, 1e-9, 0.1)
        check_range("max_pressure_pa", self.max_pressure_pa, 1e5, 1e12)
        check_range("full_contact_fraction", self.full_contact_fraction, 0.5, 1.0)
        check_range("tol", self.tol, 1e-15, 1e-3)


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
        y[tail] = np.cos(theta) * z[(start + n_blend + tail) % size] + np.sin(theta) * z[(start + tail) % size]
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
    spacing_target = beta / settings.points_per_correlation_length
    n_nodes = sfft.next_fast_len(int(math.ceil(settings.window_correlation_lengths
                                               * settings.points_per_correlation_length - 1e-6)), real=True)
    n_nodes += n_nodes % 2
    n_window = int(round(n_nodes * spacing_target / profile.spacing))
    n_blend = int(math.ceil(settings.blend_correlation_lengths * beta / profile.spacing))
    stretch = n_window + n_blend
    needed = 2 * settings.n_windows * stretch
    if needed > profile.z.size:
        raise InputError("roughness profile", profile.source or "<profile>",
                         f"at least {needed} samples for {settings.n_windows} windows of "
                         f"{settings.window_correlation_lengths:g} correlation lengths",
                         f"it has {profile.z.size}; lower n_windows or window_correlation_lengths")
    length = n_window * profile.spacing
    rows = []
    for w in range(settings.n_windows):
        y1 = _periodic_stretch(profile.z, 2 * w * stretch, n_window, n_blend) * (rq1 / rq0)
        y2 = _periodic_stretch(profile.z, (2 * w + 1) * stretch, n_window, n_blend) * (rq2 / rq0)
        rows.append(y1 + y2)
    z = _resample_periodic(np.array(rows), n_nodes)
    z -= z.mean(axis=1, keepdims=True)
    return z, length / n_nodes
