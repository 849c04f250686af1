"""Finite-volume discretisation of the (unified) Reynolds equation with its exact Newton derivatives.

Dimensionless form (X = x/a, P = p/p_h, H = h r_eq/a², ρ̄ = ρ/ρ0, T = t u_r/a; paper Eq. 1–2):

    ∂/∂X (ε ∂P/∂X) − ∂(ρ̄H)/∂X − ∂(ρ̄H)/∂T = 0,     ε = ρ̄ H³ cosh(τ_m/τ0) / (η̄ λ̄),   λ̄ = 12 η0 u_r r_eq²/(a³ p_h)

Node i owns the control volume between the face midpoints; the flux through face k (between nodes k and k+1) is

    Q_k = ½(ε_k + ε_{k+1}) (P_{k+1} − P_k)/Δ_k − C_k,

with the Couette flux C_k = m_k (first-order upwind, m = ρ̄H, u_r > 0) or the linear-upwind value
m_k + ½Δ_k/Δ_{k−1} (m_k − m_{k−1}) (second order on smooth grids). The residual of node i is
R_i = Q_i − Q_{i−1} − w_i (m_i − m_i^old)/ΔT (w_i the control-volume width; the last term only for time steps,
e.g. the steady solver's pseudo-transient continuation). The deterministic mixed model has its own discretisation
(:mod:`ehl_dataset.discretisation.mixed_system`).

:func:`assemble` returns R and the two banded derivative blocks ∂R/∂P and ∂R/∂H (columns i−2 … i+1), from which the
Newton solver forms the full Jacobian ∂R/∂P + (∂R/∂H)·K with the dense deflection matrix K.
"""

from __future__ import annotations

import numba
import numpy as np

BAND = 4
"""Band width of the local derivative blocks: columns i − 2, i − 1, i, i + 1 (array offset j − i + 2)."""
_u = np.uintp
"""Index cast for inner loops whose indices are never negative: numba checks a signed index for Python's wrap-around,
which keeps a loop from vectorising."""


@numba.njit(cache=True)
def face_flux(x, p, eps, eps_p, eps_h, m, m_p, m_h, k, order, poiseuille=1.0, harmonic=False):
    """Flux Q_k through face k (between nodes k and k+1) and its partials.

    Returns (Q_k, ∂Q/∂P_{k−1}, ∂Q/∂P_k, ∂Q/∂P_{k+1}, ∂Q/∂H_{k−1}, ∂Q/∂H_k, ∂Q/∂H_{k+1}). ``order`` scales the
    linear-upwind correction of the Couette flux (1: second order, 0: first-order upwind); ``poiseuille`` the
    pressure-driven part (1 in every present caller);
    ``harmonic`` uses the face mean 2 ε_k ε_{k+1}/(ε_k + ε_{k+1}) instead of the arithmetic one (series
    resistances: controlled by the smaller coefficient, zero next to a node with ε = 0).
    """
    delta = x[k + 1] - x[k]
    grad = (p[k + 1] - p[k]) / delta
    ea, eb = eps[k], eps[k + 1]
    if harmonic:
        total = ea + eb
        if total > 0.0:
            eps_face = poiseuille * 2.0 * ea * eb / total
            w_a = poiseuille * 2.0 * eb * eb / (total * total)  # ∂ε_face/∂ε_k
            w_b = poiseuille * 2.0 * ea * ea / (total * total)
        else:
            eps_face = w_a = w_b = 0.0
    else:
        w_a = w_b = 0.5 * poiseuille
        eps_face = w_a * (ea + eb)
    c = 0.0
    if order > 0.0 and k >= 1:
        c = order * 0.5 * delta / (x[k] - x[k - 1])
    couette = m[k] + c * (m[k] - m[k - 1]) if c > 0.0 else m[k]
    q = eps_face * grad - couette
    q_p_km1 = c * m_p[k - 1] if c > 0.0 else 0.0
    q_p_k = w_a * eps_p[k] * grad - eps_face / delta - (1.0 + c) * m_p[k]
    q_p_kp1 = w_b * eps_p[k + 1] * grad + eps_face / delta
    q_h_km1 = c * m_h[k - 1] if c > 0.0 else 0.0
    q_h_k = w_a * eps_h[k] * grad - (1.0 + c) * m_h[k]
    q_h_kp1 = w_b * eps_h[k + 1] * grad
    return q, q_p_km1, q_p_k, q_p_kp1, q_h_km1, q_h_k, q_h_kp1


@numba.njit(cache=True)
def assemble(x, p, eps, eps_p, eps_h, m, m_p, m_h, squeeze, m_old, face_order, face_poiseuille, harmonic=False):
    """Residual R (N) and banded derivatives dR/dP, dR/dH (N × 4) of the discrete Reynolds equation.

    Inputs per node: ``eps`` ε, ``eps_p`` ∂ε/∂P, ``eps_h`` ∂ε/∂H, ``m`` ρ̄H, ``m_p`` ∂m/∂P, ``m_h`` ∂m/∂H,
    ``squeeze`` w_i/ΔT (zeros for steady runs), ``m_old`` ρ̄H at the previous time step; per face (N − 1)
    ``face_order`` the weight of the linear-upwind correction (1 second order, 0 first order) and
    ``face_poiseuille`` the weight of the Poiseuille term (1 in every present caller); ``harmonic`` the
    face mean of ε (see :func:`face_flux`). Rows 0 and N − 1
    (the boundary nodes, P = 0) are left zero.
    """
    n = x.size
    res = np.zeros(n)
    dp = np.zeros((n, BAND))
    dh = np.zeros((n, BAND))
    for k in range(n - 1):
        q, q_p_km1, q_p_k, q_p_kp1, q_h_km1, q_h_k, q_h_kp1 = face_flux(x, p, eps, eps_p, eps_h, m, m_p, m_h, k,
                                                                         face_order[k], face_poiseuille[k], harmonic)
        if 1 <= k <= n - 2:  # +Q_k in row k: offsets (k-1)->1, k->2, k+1->3
            res[k] += q
            dp[k, 1] += q_p_km1
            dp[k, 2] += q_p_k
            dp[k, 3] += q_p_kp1
            dh[k, 1] += q_h_km1
            dh[k, 2] += q_h_k
            dh[k, 3] += q_h_kp1
        i = k + 1
        if 1 <= i <= n - 2:  # −Q_k in row k+1: offsets (k-1)->0, k->1, k+1->2
            res[i] -= q
            dp[i, 0] -= q_p_km1
            dp[i, 1] -= q_p_k
            dp[i, 2] -= q_p_kp1
            dh[i, 0] -= q_h_km1
            dh[i, 1] -= q_h_k
            dh[i, 2] -= q_h_kp1
    for i in range(1, n - 1):
        if squeeze[i] != 0.0:
            res[i] -= squeeze[i] * (m[i] - m_old[i])
            dp[i, 2] -= squeeze[i] * m_p[i]
            dh[i, 2] -= squeeze[i] * m_h[i]
    return res, dp, dh


@numba.njit(cache=True)
def full_jacobian(dp, dh, kmat, rows):
    """Jacobian of the interior residuals w.r.t. (P_1 … P_{N−2}, H0): ∂R/∂P + (∂R/∂H)·K, and ∂R/∂H0.

    ``kmat`` is the dense deflection matrix (∂H/∂P); ``rows`` the interior node indices 1 … N − 2. Returns a
    matrix of shape (N − 2, N − 1) whose last column is ∂R/∂H0 = Σ_j ∂R/∂H_j.
    """
    n = kmat.shape[0]
    n_in = n - 2
    jac = np.zeros((n_in, n_in + 1))
    for r in range(n_in):
        i = rows[r]
        for o in range(BAND):
            j = i + o - 2
            if j < 0 or j >= n:
                continue
            coef = dh[i, o]
            if coef != 0.0:
                for c in range(n_in):
                    jac[_u(r), _u(c)] += coef * kmat[_u(j), _u(c + 1)]
                jac[r, n_in] += coef
            if 1 <= j <= n - 2:
                jac[r, j - 1] += dp[i, o]
    return jac


@numba.njit(cache=True)
def jacobian_diagonal(dp, dh, kmat, rows):
    """Diagonal ∂R_i/∂P_i + Σ_o ∂R_i/∂H_j K[j, i] of :func:`full_jacobian` (interior rows), without forming it."""
    n = kmat.shape[0]
    n_in = rows.size
    diag = np.zeros(n_in)
    for r in range(n_in):
        i = rows[r]
        for o in range(BAND):
            j = i + o - 2
            if j < 0 or j >= n:
                continue
            diag[r] += dh[i, o] * kmat[j, i]
            if j == i:
                diag[r] += dp[i, o]
    return diag


@numba.njit(cache=True)
def newton_matrix(dp, dh, kmat, rows, d_a, d_b, load_row):
    """The semi-smooth Newton matrix of the complementarity system, in one pass over the dense block.

    Rows r < N − 2: d(φ_r)/d(P_1 … P_{N−2}, H0) = d_a[r] e_r − d_b[r] J_r with J = :func:`full_jacobian` (``d_a``,
    ``d_b`` the Fischer–Burmeister partials, b = −κR); the last row is ``load_row`` (∂ of the load error).
    Returns the square matrix of size N − 1.
    """
    n = kmat.shape[0]
    n_in = n - 2
    system = np.zeros((n_in + 1, n_in + 1))
    for r in range(n_in):
        i = rows[r]
        scale = -d_b[r]
        for o in range(BAND):
            j = i + o - 2
            if j < 0 or j >= n:
                continue
            coef = scale * dh[i, o]
            if coef != 0.0:
                for c in range(n_in):  # unsigned indices: no wrap-around checks, a vectorised loop
                    system[_u(r), _u(c)] += coef * kmat[_u(j), _u(c + 1)]
                system[r, n_in] += coef
            if 1 <= j <= n - 2:
                system[r, j - 1] += scale * dp[i, o]
        system[r, r] += d_a[r]
    for c in range(n_in + 1):
        system[n_in, c] = load_row[c]
    return system
