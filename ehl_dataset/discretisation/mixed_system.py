"""Discrete equations of the deterministic mixed-EHL line contact (paper Eq. 1–3, 6; docs/explanation/mixed-regime.md).

Dimensionless variables as in :mod:`ehl_dataset.discretisation.reynolds`: X = x/a, P = p/p_h, H = h r_eq/a²,
T = t u_r/a. The grid is uniform (spacing Δ), node-centred finite volumes of width w_i (Δ, Δ/2 at the ends).

Unknowns per node i, interleaved: z[3i] = P_f (fluid pressure), z[3i+1] = θ (fraction of the gap filled with
lubricant, mass-conserving cavitation), z[3i+2] = P_c (solid contact pressure of the boundary film); z[3N] = H0.
The film is H = H0 + G(X, T) + K (P_f + P_c): the solid contact pressure deflects the surfaces like the fluid's.

Equations per node:

* row 3i, mass balance of cell i (Elrod–Adams / Jakobsson–Floberg–Olsson, in flux form, so that lubricant mass is
  conserved exactly, including through cavitation and contacts):

      Q_{i+½} − Q_{i−½} − w_i ∂m_i/∂T = 0,   m = ρ̄ θ max(H, H_b),   Q = ε_face (P_{f,i+1} − P_{f,i})/Δ − m_upwind,

  ε = ρ̄ H³ cosh(τ_m/τ0)/(η̄ λ̄) (paper Eq. 1b), the Couette flux m upwinded to second order (linear upwind,
  first order at the first face); node 0 is the flooded inlet (θ = 1), node N−1 the outflow (Couette flux
  m_{N−1} leaves the domain). Only the fluid pressure drives flow: the contact pressure P_c is absent from Q
  (solid contact pressure drives no flow; Liu, Wang, Chung & Berkebile, Tribol. Lett. 69 (2021) 164). The
  content uses max(H, H_b): where asperities interfere plastically (H < H_b at the hardness) their tips are
  flattened and the gap that holds lubricant is the boundary film, never a negative volume;
* row 3i+1, cavitation: 0 ≤ P_f ⊥ 1 − θ ≥ 0 as a Fischer–Burmeister equation φ(P_f, 1 − θ) = 0 (P_f = 0 at both
  ends);
* row 3i+2, contact with a boundary film of thickness H_b and elastic–perfectly-plastic asperities:
  0 ≤ P_c ≤ P_Y box-complementary to κ(H − H_b) (P_c = 0 where H > H_b, H = H_b while 0 < P_c < P_Y, H ≤ H_b at
  the hardness P_c = P_Y: plastic flattening), Billups' nested form Φ = φ(P_c, −φ(P_Y − P_c, −κ(H − H_b))),
  κ = 1/K_ii.

The time derivative is BDF2 with variable steps (or backward Euler): w_i ∂m/∂T ≈ c_i m_i + old_i, the caller
gives c_i = w_i a0/ΔT and old_i = w_i (a1 m_i^n + a2 m_i^{n−1})/ΔT (zeros for a steady solve).

The Jacobian is returned in band form: ``A[r, o, k]`` = ∂F_r/∂z_{3j+k} with j = i + o − 2 (the node of row r is
i = r // 3; offsets −2 … 2), and ``D[r, o]`` = ∂F_r/∂H_j: the film couples every node to every other through K,
which the Krylov solver applies by FFT (:mod:`ehl_dataset.solvers.krylov`).
"""

from __future__ import annotations

import math

import numba
import numpy as np

OFFSETS = 5
"""Node offsets −2 … 2 of the local band of the Jacobian."""
FACE_MEANS = {"harmonic": 1, "arithmetic": 0, "logarithmic": 2, "kirchhoff": 3}
"""Face conductance ε_{i+½} from the nodal values: harmonic (series resistances: exact for 1-D flow through a
varying film at constant viscosity), arithmetic, logarithmic (exact for an exponentially varying conductance at
constant film), or kirchhoff: ε = A·H³ split into the film factor H³ and the fluid factor A = ρ̄ cosh(τ_m/τ0)/(η̄ λ̄),
the face value the logarithmic mean of A times the harmonic mean of H³. Between two nodes at the same film, the
flux of a conductance that varies exponentially with pressure is the Kirchhoff integral (1/Δ)∫ε dP, which the
logarithmic mean of A gives exactly and which grows monotonically with the pressure difference; the harmonic mean
of such a conductance gives a flux 2ε_a ΔP e^{−kΔP}/(1 + e^{−kΔP}) that falls again beyond kΔP ≈ 1.28, a spurious
maximum at which the Newton matrix is singular (docs/validation/deterministic-reference.md, "Robustness and cost")."""


@numba.njit(cache=True)
def fischer_burmeister(a, b):
    """φ(a, b) = a + b − √(a² + b²) and its partials (a generalised gradient at a = b = 0); the cancellation-free
    form 2ab/(a + b + √(a² + b²)) is used for a + b > 0."""
    r = math.sqrt(a * a + b * b)
    if r < 1e-300:
        c = 1.0 - 1.0 / math.sqrt(2.0)
        return 0.0, c, c
    s = a + b
    phi = 2.0 * a * b / (s + r) if s > 0.0 else s - r
    return phi, 1.0 - a / r, 1.0 - b / r


LOG_MEAN_SERIES = 1e-2
"""|ln(a/b)| below which the partials of the logarithmic mean are taken from their Taylor series (5 terms, relative
error < 1e-13 there); above it the closed forms lose at most ≈ eps/ln² ≈ 2e-12 to cancellation."""


@numba.njit(cache=True)
def logarithmic_mean(a, b):
    """L(a, b) = (a − b)/ln(a/b) for a, b > 0 (L(a, a) = a) and its partials (∂L/∂a, ∂L/∂b), accurate to a few ulp
    however close a and b are.

    With t = ln(a/b): L = (a − b)/t, ∂L/∂a = (t − 1 + e^{−t})/t², ∂L/∂b = (e^t − 1 − t)/t². Written as
    ``(a − b)/log(a/b)`` they lose ≈ eps/|t| relative accuracy (the rounding of a/b is an absolute error of eps in a
    logarithm near 0), and the partials eps/t²: on the flooded inlet of the deterministic solver, where the fluid
    factor changes by 1e-4–1e-6 from node to node, the Poiseuille flux then carries a noise of 1e-12–1e-10 of the
    inlet flux, which set a floor of 2–5e-10 under the global mass balance (docs/explanation/mixed-regime.md, "Mass
    balance"). Here a − b is exact (Sterbenz) for b/2 ≤ a ≤ 2b, t = log1p((a − b)/b) is accurate to a few ulp, and
    the partials come from their Taylor series where |t| < :data:`LOG_MEAN_SERIES`. Far from a = b (|a − b| > b/2)
    t = ln a − ln b: log1p(d/b) would read d/b = −1 + 1e-18 as −1 when a < 1e-16·b (a micro-EHL pressure peak of a
    viscous oil next to an unloaded node) and return t = −∞, L = 0 and NaN partials (det-2026.11-11 and -12)."""
    d = a - b
    if d == 0.0:
        return a, 0.5, 0.5
    t = math.log1p(d / b) if abs(d) <= 0.5 * b else math.log(a) - math.log(b)
    if abs(t) < LOG_MEAN_SERIES:
        t2 = t * t
        even = 0.5 + t2 * (1.0 / 24.0 + t2 / 720.0)
        odd = t * (1.0 / 6.0 + t2 / 120.0)
        return d / t, even - odd, even + odd
    return d / t, (t - 1.0 + b / a) / (t * t), (-t - 1.0 + a / b) / (t * t)


@numba.njit(cache=True)
def _face(ea, eb, mean):
    """ε_face and its partials with respect to the two nodal values."""
    if mean == 1:
        total = ea + eb
        if total > 0.0:
            return 2.0 * ea * eb / total, 2.0 * eb * eb / (total * total), 2.0 * ea * ea / (total * total)
        return 0.0, 0.0, 0.0
    if mean == 2 and ea > 0.0 and eb > 0.0:
        return logarithmic_mean(ea, eb)
    return 0.5 * (ea + eb), 0.5, 0.5


@numba.njit(cache=True)
def _face_partials(k, eps, eps_p, eps_h, cube, cube_h, mean):
    """ε at face k + ½ and its partials (∂/∂P_f,k, ∂/∂H_k, ∂/∂P_f,k+1, ∂/∂H_k+1); ``cube`` H³ per node and
    ``cube_h`` its derivative (for the kirchhoff mean)."""
    return _face_partials_of(k, k + 1, eps, eps_p, eps_h, cube, cube_h, mean)


@numba.njit(cache=True)
def _face_partials_of(k, k1, eps, eps_p, eps_h, cube, cube_h, mean):
    """:func:`_face_partials` of the face between nodes ``k`` and ``k1`` (k1 = k + 1, or 0 across a period)."""
    if mean == 3:
        fa = eps[k] / cube[k]
        fb = eps[k1] / cube[k1]
        lm, la, lb = _face(fa, fb, 2)
        hm, ha, hb = _face(cube[k], cube[k1], 1)
        fa_p = eps_p[k] / cube[k]
        fb_p = eps_p[k1] / cube[k1]
        fa_h = (eps_h[k] - fa * cube_h[k]) / cube[k]
        fb_h = (eps_h[k1] - fb * cube_h[k1]) / cube[k1]
        return (lm * hm, la * fa_p * hm, la * fa_h * hm + lm * ha * cube_h[k], lb * fb_p * hm,
                lb * fb_h * hm + lm * hb * cube_h[k1])
    ef, wa, wb = _face(eps[k], eps[k1], mean)
    return ef, wa * eps_p[k], wa * eps_h[k], wb * eps_p[k1], wb * eps_h[k1]


@numba.njit(cache=True)
def assemble(dx, pf, th, pc, h, eps, eps_p, eps_h, rho, rho_p, h_b, kappa, p_yield, stor_coef, stor_old, mean,
             order, cube, cube_h, periodic=False):
    """Residual (3N) and band Jacobians (A, D) of the node equations; the load row is the caller's.

    ``periodic``: the grid is one period of a periodic window (node N ≡ node 0): N faces, the face N−1 + ½ joins
    node N−1 to node 0, every node has a mass row with its time term and a cavitation complementarity (no inlet, no
    outflow); the band offsets then count modulo N.

    Per node: ``pf``, ``th``, ``pc``, ``h`` the state; ``eps``, ``eps_p``, ``eps_h`` ε and its partials in P_f and H;
    ``rho``, ``rho_p`` ρ̄ and ∂ρ̄/∂P_f; ``cube``, ``cube_h`` the film factor H³ of ε and its derivative in H;
    ``stor_coef``, ``stor_old`` the time-derivative terms (module docstring).
    Scalars: ``h_b`` H_b, ``kappa`` κ, ``p_yield`` P_Y (inf: elastic), ``mean`` the face mean code
    (:data:`FACE_MEANS`), ``order`` of the Couette flux: 1 linear upwind (second order), 0 first-order upwind, 2
    minmod-limited linear upwind (second order where smooth, never against the flow at a content jump).
    """
    n = pf.size
    res = np.zeros(3 * n)
    jac = np.zeros((3 * n, OFFSETS, 3))
    dfilm = np.zeros((3 * n, OFFSETS))
    hm = np.maximum(h, h_b)
    m = rho * th * hm
    m_p = rho_p * th * hm
    m_t = rho * hm
    m_h = np.where(h > h_b, rho * th, 0.0)
    faces = n if periodic else n - 1
    for k in range(faces):
        k1 = (k + 1) % n  # the downstream node (node 0 across the periodic face)
        km = (k - 1) % n  # the upstream neighbour of node k (periodic or k >= 1)
        has_up = periodic or k >= 1
        ef, ef_pk, ef_hk, ef_pk1, ef_hk1 = _face_partials_of(k, k1, eps, eps_p, eps_h, cube, cube_h, mean)
        grad = (pf[k1] - pf[k]) / dx
        c = 0.5 * order if has_up else 0.0
        m_km1 = m[km] if has_up else 0.0
        # downstream weight: the minmod-limited form (order 2) uses the smaller of the upwind and downwind
        # differences, or none at an extremum, so that a content jump (a film closing on a contact) cannot make a
        # face carry lubricant against the flow (TVD; second order where the content is smooth)
        cd = 0.0
        if order == 2.0:
            c = 0.0
            if periodic or (k >= 1 and k + 1 < n - 1):
                d_up = m[k] - m_km1
                d_down = m[k1] - m[k]
                if d_up * d_down > 0.0:
                    if abs(d_up) <= abs(d_down):
                        c = 0.5
                    else:
                        cd = 0.5
        m_kp1 = m[k1]
        q = ef * grad - (m[k] + c * (m[k] - m_km1) + cd * (m_kp1 - m[k]))
        q_pf_k = ef_pk * grad - ef / dx - (1.0 + c - cd) * m_p[k]
        q_th_k = -(1.0 + c - cd) * m_t[k]
        q_h_k = ef_hk * grad - (1.0 + c - cd) * m_h[k]
        q_pf_k1 = ef_pk1 * grad + ef / dx - cd * m_p[k1]
        q_th_k1 = -cd * m_t[k1]
        q_h_k1 = ef_hk1 * grad - cd * m_h[k1]
        for side in range(2):
            node = k if side == 0 else k1
            if node < 1 and not periodic:
                continue
            sign = 1.0 if side == 0 else -1.0
            r = 3 * node
            o = 2 - side  # band offset of node k in the row of ``node``
            res[r] += sign * q
            jac[r, o, 0] += sign * q_pf_k
            jac[r, o, 1] += sign * q_th_k
            dfilm[r, o] += sign * q_h_k
            jac[r, o + 1, 0] += sign * q_pf_k1
            jac[r, o + 1, 1] += sign * q_th_k1
            dfilm[r, o + 1] += sign * q_h_k1
            if has_up:
                jac[r, o - 1, 0] += sign * c * m_p[km]
                jac[r, o - 1, 1] += sign * c * m_t[km]
                dfilm[r, o - 1] += sign * c * m_h[km]
    if not periodic:
        last = 3 * (n - 1)
        res[last] -= m[n - 1]
        jac[last, 2, 0] -= m_p[n - 1]
        jac[last, 2, 1] -= m_t[n - 1]
        dfilm[last, 2] -= m_h[n - 1]
    for i in range(0 if periodic else 1, n):
        r = 3 * i
        res[r] -= stor_coef[i] * m[i] + stor_old[i]
        jac[r, 2, 0] -= stor_coef[i] * m_p[i]
        jac[r, 2, 1] -= stor_coef[i] * m_t[i]
        dfilm[r, 2] -= stor_coef[i] * m_h[i]
    if not periodic:
        res[0] = th[0] - 1.0
        jac[0, 2, 1] = 1.0
    for i in range(n):
        r = 3 * i + 1
        if not periodic and (i == 0 or i == n - 1):
            res[r] = pf[i]
            jac[r, 2, 0] = 1.0
        else:
            phi, da, db = fischer_burmeister(pf[i], 1.0 - th[i])
            res[r] = phi
            jac[r, 2, 0] = da
            jac[r, 2, 1] = -db
        r = 3 * i + 2
        b = -kappa * (h[i] - h_b)
        psi, da2, db2 = fischer_burmeister(p_yield - pc[i], b)
        big, da1, db1 = fischer_burmeister(pc[i], -psi)
        res[r] = big
        jac[r, 2, 2] = da1 + db1 * da2
        dfilm[r, 2] = db1 * db2 * kappa
    return res, jac, dfilm


@numba.njit(cache=True)
def local_matvec(jac, dfilm, v, dh, periodic=False):
    """Σ_j A_rj v_j + Σ_j D_rj dH_j for the band arrays of :func:`assemble` (``v`` the 3N local unknowns and more,
    ``dh`` the film change at every node; ``periodic``: the offsets count modulo N)."""
    n3 = jac.shape[0]
    n = n3 // 3
    out = np.zeros(n3)
    for r in range(n3):
        i = r // 3
        total = 0.0
        for o in range(OFFSETS):
            j = i + o - 2
            if periodic:
                j %= n
            elif j < 0 or j >= n:
                continue
            total += (jac[r, o, 0] * v[3 * j] + jac[r, o, 1] * v[3 * j + 1] + jac[r, o, 2] * v[3 * j + 2]
                      + dfilm[r, o] * dh[j])
        out[r] = total
    return out


@numba.njit(cache=True)
def preconditioner_band(jac, dfilm, binv, kl):
    """LAPACK band storage (2·kl + kl + 1 rows) of the banded approximation M of the Jacobian in the variables
    z' = per node (ΔV, ΔP_f, Δθ), where ΔV = K(ΔP_f + ΔP_c) is the deflection change: then
    ΔP_c = B ΔV − ΔP_f with B ≈ K⁻¹ banded (``binv``, :func:`~ehl_dataset.discretisation.deflection.inverse_kernel_band`)
    and ΔH = ΔV + ΔH0, so every row is local. Returns the band array and the ΔH0 column."""
    n3 = jac.shape[0]
    n = n3 // 3
    width = (binv.size - 1) // 2
    ku = kl
    band = np.zeros((2 * kl + ku + 1, n3))
    col_h0 = np.zeros(n3)
    for r in range(n3):
        i = r // 3
        for o in range(OFFSETS):
            j = i + o - 2
            if j < 0 or j >= n:
                continue
            a_pf = jac[r, o, 0]
            a_th = jac[r, o, 1]
            a_pc = jac[r, o, 2]
            d_h = dfilm[r, o]
            if a_pf != 0.0 or a_pc != 0.0:
                c = 3 * j + 1
                band[kl + ku + r - c, c] += a_pf - a_pc
            if a_th != 0.0:
                c = 3 * j + 2
                band[kl + ku + r - c, c] += a_th
            if d_h != 0.0:
                c = 3 * j
                band[kl + ku + r - c, c] += d_h
                col_h0[r] += d_h
            if a_pc != 0.0:
                for mm in range(-width, width + 1):
                    node = j - mm
                    if node < 0 or node >= n:
                        continue
                    c = 3 * node
                    band[kl + ku + r - c, c] += a_pc * binv[mm + width]
    return band, col_h0
