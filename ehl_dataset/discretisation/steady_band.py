"""Banded form of the steady Newton matrix in deflection variables (the preconditioner of the steady smooth solve).

The semi-smooth Newton matrix of :func:`ehl_dataset.discretisation.reynolds.newton_matrix` is, for the interior
pressures ΔP (M = N − 2 unknowns) and the film constant ΔH0,

    S = [ L + E K_I    E·1 ]        L, E banded (4 entries a row: L on the interior pressures, E on the film at the
        [ ℓᵀ           0   ]        nodes i − 2 … i + 1), K_I the interior columns of the dense deflection matrix,
                                    ℓ the load row;

dense because the deflection couples every node. Written in the deflection variables V with ΔP = B V, B a banded
approximation of K_II⁻¹ (the inverse of the log kernel is nearly local: its coefficients decay like 1/m²,
:func:`~ehl_dataset.discretisation.deflection.inverse_kernel_band`), S B = L B + E (K_I B) has a dominant band;
:func:`newton_band` returns that band in LAPACK storage, whose LU (``dgbtrf``, O(M·w²)) preconditions a Krylov
solve with the exact S (:class:`ehl_dataset.solvers.krylov.SteadyBandedPreconditioner`; the same idea as the banded
preconditioner of the deterministic mixed solver, :func:`~ehl_dataset.discretisation.mixed_system.preconditioner_band`).

On the clustered (non-uniform) steady grid B is the uniform-grid band of unit spacing scaled by the control-volume
width of its row, B[r, r + k] = b_k/w_r: exact for a uniform grid far from the ends, a local approximation elsewhere;
the Krylov iteration corrects what the band leaves out.
"""

from __future__ import annotations

import numba
import numpy as np

from .reynolds import BAND

_u = np.uintp
"""Index cast: numba checks every signed index for a negative value (Python's wrap-around), which keeps the inner
loops below from vectorising; their indices are never negative, and as unsigned integers they are not checked
(``newton_band`` 236 → 104 µs on a 425-node grid)."""


@numba.njit(cache=True)
def newton_bands(dp, dh, rows, d_a, d_b):
    """Local parts of the Newton matrix rows of :func:`~ehl_dataset.discretisation.reynolds.newton_matrix`.

    Returns (``lb``, ``eb``), each (M, 4): row r (node i = ``rows[r]``) of S is
    Σ_o lb[r, o] ΔP_{r+o−2} + Σ_o eb[r, o] (ΔV_{r+o−1} + ΔH0), with ΔV the deflection change at the nodes (all N)
    and ΔP indexed over the interior nodes; entries outside the grid are zero. ``d_a``, ``d_b`` are the
    Fischer–Burmeister partials (the row is d_a e_r − d_b J_r).
    """
    n = dp.shape[0]
    m = rows.size
    lb = np.zeros((m, BAND))
    eb = np.zeros((m, BAND))
    for r in range(m):
        i = rows[r]
        scale = -d_b[r]
        for o in range(BAND):
            j = i + o - 2
            if 0 <= j < n:
                eb[r, o] = scale * dh[i, o]
            if 1 <= j <= n - 2:
                lb[r, o] = scale * dp[i, o]
        lb[r, 2] += d_a[r]
    return lb, eb


@numba.njit(cache=True)
def band_matvec(lb, eb, v, kv):
    """The first M entries of S v (:func:`newton_bands`): ``v`` (M + 1: ΔP, ΔH0), ``kv`` = K_I ΔP (N entries)."""
    m = lb.shape[0]
    n = kv.size
    out = np.zeros(m)
    h0 = v[m]
    for r in range(m):
        total = 0.0
        for o in range(BAND):
            c = r + o - 2
            if 0 <= c < m:
                total += lb[r, o] * v[c]
            j = r + o - 1
            if 0 <= j < n:
                total += eb[r, o] * (kv[j] + h0)
        out[r] = total
    return out


@numba.njit(cache=True)
def inverse_band(weights, coefficients):
    """B ≈ K_II⁻¹ in diagonal storage, (M, 2w + 1): B[r, r + k] = b_k / w_r for the interior nodes r (``weights`` w
    the control-volume widths of all N nodes, ``coefficients`` b_{−w … w} of unit spacing); entries outside the
    grid are zero."""
    m = weights.size - 2
    width = (coefficients.size - 1) // 2
    out = np.zeros((m, coefficients.size))
    for r in range(m):
        for k in range(-width, width + 1):
            c = r + k
            if 0 <= c < m:
                out[r, k + width] = coefficients[k + width] / weights[r + 1]
    return out


@numba.njit(cache=True)
def deflection_band(kmat, binv, half):
    """(K_I B)[j, c] for every node j and the interior columns c = j − 1 − ``half`` … j − 1 + ``half``, (N,
    2·half + 1); ``binv`` from :func:`inverse_band`."""
    n = kmat.shape[0]
    m = n - 2
    width = (binv.shape[1] - 1) // 2
    out = np.zeros((n, 2 * half + 1))
    for j in range(n):
        for t in range(-half, half + 1):
            c = j - 1 + t
            if c < 0 or c >= m:
                continue
            total = 0.0
            for k in range(-width, width + 1):
                q = c - k  # B[q, c] = binv[q, k + width] with c = q + k
                if 0 <= q < m:
                    total += kmat[j, q + 1] * binv[q, k + width]
            out[j, t + half] = total
    return out


@numba.njit(cache=True)
def apply_inverse_band(binv, v):
    """B v for B in the storage of :func:`inverse_band`."""
    m = binv.shape[0]
    width = (binv.shape[1] - 1) // 2
    out = np.zeros(m)
    for r in range(m):
        total = 0.0
        for k in range(-width, width + 1):
            c = r + k
            if 0 <= c < m:
                total += binv[r, k + width] * v[c]
        out[r] = total
    return out


@numba.njit(cache=True)
def newton_band(lb, eb, binv, kb, kl):
    """LAPACK band storage ((3·kl + 1) × M in Fortran order, for ``dgbtrf`` with kl = ku) of the band |r − c| ≤ ``kl`` of S B
    (:func:`newton_bands`, B :func:`inverse_band`, ``kb`` :func:`deflection_band` with half ≥ kl + 2), and the
    column E·1 of ΔH0: M[r, c] = Σ_o lb[r, o] B[r + o − 2, c] + Σ_o eb[r, o] (K_I B)[r + o − 1, c]."""
    m = lb.shape[0]
    n = kb.shape[0]
    width = (binv.shape[1] - 1) // 2
    half = (kb.shape[1] - 1) // 2
    ku = kl
    band_t = np.zeros((m, 2 * kl + ku + 1))  # the transpose, so that the band itself is in Fortran order
    col_h0 = np.zeros(m)
    row = np.zeros(2 * kl + 1)  # row r of the band, columns r − kl … r + kl, summed before it is stored
    for r in range(m):
        row[:] = 0.0
        offset = kl - r
        for o in range(BAND):
            q = r + o - 2  # L: interior column q, times row q of B
            a = lb[r, o]
            if a != 0.0 and 0 <= q < m:
                for c in range(max(0, q - width, r - kl), min(m, q + width + 1, r + kl + 1)):
                    row[_u(c + offset)] += a * binv[_u(q), _u(c - q + width)]
            j = r + o - 1  # E: node j, times row j of K_I B
            e = eb[r, o]
            if e != 0.0 and 0 <= j < n:
                col_h0[r] += e
                shift = half + 1 - j
                for c in range(max(0, r - kl, j - 1 - half), min(m, r + kl + 1, j + half)):
                    row[_u(c + offset)] += e * kb[_u(j), _u(c + shift)]
        diagonal = kl + ku + r
        for c in range(max(0, r - kl), min(m, r + kl + 1)):
            band_t[_u(c), _u(diagonal - c)] = row[_u(c + offset)]
    return band_t.T, col_h0


@numba.njit(cache=True)
def band_lu_solve(lu, piv, kl, b):
    """Solve M x = b with the LU factors of ``dgbtrf`` (kl = ku, ``piv`` 0-based as SciPy returns it): LAPACK
    ``dgbtrs``'s forward elimination with the row interchanges, then the banded upper triangle (kl + ku
    superdiagonals)."""
    m = b.size
    kv = 2 * kl
    x = b.copy()
    for j in range(m - 1):
        p = piv[j]
        if p != j:
            t = x[p]
            x[p] = x[j]
            x[j] = t
        xj = x[j]
        if xj != 0.0:
            for t in range(1, min(kl, m - 1 - j) + 1):
                x[_u(j + t)] -= lu[_u(kv + t), _u(j)] * xj
    for j in range(m - 1, -1, -1):
        x[j] /= lu[kv, j]
        xj = x[j]
        if xj != 0.0:
            for i in range(max(0, j - kv), j):
                x[_u(i)] -= lu[_u(kv + i - j), _u(j)] * xj
    return x
