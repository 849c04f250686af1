"""Compiled per-iteration arithmetic of the steady Newton solve (:mod:`ehl_dataset.solvers.newton`).

The same formulas as :meth:`~ehl_dataset.solvers.newton.ReynoldsProblem.rheology`,
:meth:`~ehl_dataset.solvers.newton.ReynoldsProblem.fluid` and the Fischer–Burmeister complementarity of
:func:`~ehl_dataset.solvers.newton.newton_solve`, each in one compiled pass over the nodes instead of a chain of array
expressions (a steady solve evaluates them some thirty times on a few hundred nodes, where the per-expression cost of
array code dominates). The results agree with the array expressions to round-off
(``tests/ehl_dataset/test_newton_kernels.py``).

The viscosity–pressure laws of :class:`~ehl_dataset.model.lubricant.ViscosityPressureLaw` enter as a law code and a
parameter vector (:func:`law_parameters`); the density is Dowson–Higginson's (paper Eq. 6) or constant.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from ..discretisation.reynolds import assemble, jacobian_diagonal
from ..model.lubricant import DH_GAMMA_PER_PA, DH_LAMBDA_PER_PA, LubricantState, ViscosityPressureLaw

LAW_CODES = {"barus": 0, "roelands": 1, "two_slope": 2}
"""Code of each viscosity–pressure law in the compiled rheology."""


def law_parameters(state) -> tuple[int, np.ndarray] | None:
    """(law code, parameters) of the state's viscosity–pressure law for :func:`rheology`, or None when the state is
    not a :class:`~ehl_dataset.model.lubricant.LubricantState` with one of the laws of :data:`LAW_CODES` (the caller
    then evaluates the state's own methods).

    Parameters (SI): α1 [1/Pa], α2 [1/Pa], p_t, p_a, p_b [Pa], ln η0 + 9.67 [-], Roelands z [-], p0 [Pa] and the
    cubic's c0 … c3 of the two-slope transition.
    """
    law = getattr(state, "law", None)
    if type(state) is not LubricantState or type(law) is not ViscosityPressureLaw or law.kind not in LAW_CODES:
        return None
    c0, c1, c2, c3 = (float(c) for c in law.cubic)
    params = np.array([law.alpha1, law.alpha2, law.p_t, law.p_a, law.p_b, math.log(law.eta0) + 9.67, law.z, law.p0,
                       c0, c1, c2, c3], dtype=float)
    return LAW_CODES[law.kind], params


@numba.njit(cache=True)
def _exponent(code, params, pp):
    """φ = ln(η/η0) and dφ/dp [1/Pa] at a pressure pp ≥ 0 [Pa] (:class:`ViscosityPressureLaw`)."""
    alpha1 = params[0]
    if code == 0:
        return alpha1 * pp, alpha1
    if code == 1:
        coefficient, z, p0 = params[5], params[6], params[7]
        base = 1.0 + pp / p0
        return coefficient * (base**z - 1.0), coefficient * z / p0 * base ** (z - 1.0)
    alpha2, p_t, p_a, p_b = params[1], params[2], params[3], params[4]
    if pp < p_a:
        return alpha1 * pp, alpha1
    if pp > p_b:
        return alpha1 * p_t + alpha2 * (pp - p_t), alpha2
    c0, c1, c2, c3 = params[8], params[9], params[10], params[11]
    return c0 + pp * (c1 + pp * (c2 + pp * c3)), c1 + pp * (2 * c2 + 3 * c3 * pp)


@numba.njit(cache=True)
def rheology(p, p_h, homotopy, code, params, compressible, cap, floor):
    """(φ scaled by ``homotopy``, ∂φ/∂P, ρ̄, ∂ρ̄/∂P) at dimensionless pressures ``p`` (pressure scale ``p_h`` [Pa]):
    :meth:`~ehl_dataset.solvers.newton.ReynoldsProblem.rheology` — below p = 0 both laws continued linearly from
    p = 0, φ clipped to [−``floor``, ``cap``] with a zero derivative where clipped; ρ̄ = ρ/ρ0 of Dowson–Higginson
    where ``compressible``, else 1."""
    n = p.size
    phi = np.empty(n)
    phi_p = np.empty(n)
    rho = np.empty(n)
    rho_p = np.empty(n)
    slope_phi0 = _exponent(code, params, 0.0)[1]
    slope_rho0 = (DH_GAMMA_PER_PA - DH_LAMBDA_PER_PA) * p_h
    for i in range(n):
        pa = p[i] * p_h
        if pa < 0.0:
            value = homotopy * (slope_phi0 * pa)
            slope = homotopy * slope_phi0 * p_h
        else:
            exponent, derivative = _exponent(code, params, pa)
            value = homotopy * exponent
            slope = homotopy * derivative * p_h
        if value > cap or value < -floor:
            value = min(max(value, -floor), cap)
            slope = 0.0
        phi[i] = value
        phi_p[i] = slope
        if not compressible:
            rho[i] = 1.0
            rho_p[i] = 0.0
        elif pa < 0.0:
            rho[i] = 1.0 + slope_rho0 * p[i]
            rho_p[i] = slope_rho0
        else:
            rho[i] = (1.0 + DH_GAMMA_PER_PA * pa) / (1.0 + DH_LAMBDA_PER_PA * pa)
            rho_p[i] = (DH_GAMMA_PER_PA - DH_LAMBDA_PER_PA) / (1.0 + DH_LAMBDA_PER_PA * pa) ** 2 * p_h
    return phi, phi_p, rho, rho_p


@numba.njit(cache=True)
def fluid(phi, phi_p, rho, rho_p, h, shear, lam):
    """ε, ∂ε/∂P, ∂ε/∂H, m = ρ̄H, ∂m/∂P, ∂m/∂H (:meth:`~ehl_dataset.solvers.newton.ReynoldsProblem.fluid`): ε =
    ρ̄ H³ √(1/η̄² + (S/H)²)/λ̄, the Eyring flow factor over the viscosity (shear number S, λ̄ as there)."""
    n = h.size
    eps = np.empty(n)
    eps_p = np.empty(n)
    eps_h = np.empty(n)
    m = np.empty(n)
    m_p = np.empty(n)
    for i in range(n):
        hp = max(h[i], 1e-12)
        inv_eta2 = math.exp(-2.0 * phi[i])
        shear2 = (shear / hp) ** 2
        g2 = max(inv_eta2 + shear2, 1e-300)
        e = rho[i] * hp**3 * math.sqrt(g2) / lam
        eps[i] = e
        eps_p[i] = e * (rho_p[i] / rho[i] - phi_p[i] * inv_eta2 / g2)
        eps_h[i] = e * (3.0 / hp - shear2 / (hp * g2))
        m[i] = rho[i] * h[i]
        m_p[i] = rho_p[i] * h[i]
    return eps, eps_p, eps_h, m, m_p, rho.copy()


@numba.njit(cache=True)
def residual(x, p, h, p_h, homotopy, code, params, compressible, cap, floor, shear, lam, squeeze, m_old, face_order,
             face_poiseuille):
    """Reynolds residual R, banded ∂R/∂P and ∂R/∂H (:func:`~ehl_dataset.discretisation.reynolds.assemble`) and m,
    ∂m/∂P, ∂m/∂H of :meth:`~ehl_dataset.solvers.newton.ReynoldsProblem.residual`, in one call."""
    phi, phi_p, rho, rho_p = rheology(p, p_h, homotopy, code, params, compressible, cap, floor)
    eps, eps_p, eps_h, m, m_p, m_h = fluid(phi, phi_p, rho, rho_p, h, shear, lam)
    res, dp, dh = assemble(x, p, eps, eps_p, eps_h, m, m_p, m_h, squeeze, m_old, face_order, face_poiseuille)
    return res, dp, dh, m, m_p, m_h


@numba.njit(cache=True)
def complementarity(a, res, kappa, m_ref):
    """Fischer–Burmeister φ(a, b) = a + b − √(a² + b²) of a = P_i and b = −κ_i R_i on the interior nodes, its partials
    ∂φ/∂a and ∂φ/∂R_i (= −κ_i ∂φ/∂b), and the norms of :func:`~ehl_dataset.solvers.newton.newton_solve`: max |R|/m_ref
    on the pressurised nodes (a > b, a ≥ 0) and max |φ| on the others.

    ``a`` the interior pressures (less a cavitation offset), ``res`` the residual at all N nodes, ``kappa`` the
    Jacobi scaling per interior node. Returns (φ, ∂φ/∂a, ∂φ/∂R, r_free, r_cav)."""
    n = a.size
    phi = np.empty(n)
    d_a = np.empty(n)
    d_b = np.empty(n)
    r_free = 0.0
    r_cav = 0.0
    corner = 1.0 - 1.0 / math.sqrt(2.0)
    for i in range(n):
        ai = a[i]
        bi = -res[i + 1] * kappa[i]
        root = math.sqrt(ai * ai + bi * bi)
        if root < 1e-14:
            d_a[i] = corner
            d_b[i] = corner * kappa[i]
        else:
            d_a[i] = 1.0 - ai / root
            d_b[i] = (1.0 - bi / root) * kappa[i]
        total = ai + bi
        # a + b − root cancels when one argument is huge: for a + b > 0 the equal form 2ab/(a + b + root)
        phi[i] = 2.0 * ai * bi / (total + root) if total > 0.0 else total - root
        if ai > bi and ai >= 0.0:
            r_free = max(r_free, abs(res[i + 1]))
        else:
            r_cav = max(r_cav, abs(phi[i]))
    return phi, d_a, d_b, r_free / m_ref, r_cav


@numba.njit(cache=True)
def iteration_state(p, res, dp, dh, kmat, rows, weights, m_ref, kappa, rescale):
    """The state of one iteration of :func:`~ehl_dataset.solvers.newton.newton_solve` on a plain problem: the relative
    load error Σ w P/(π/2) − 1, the Jacobi scaling κ_i = 1/|∂R_i/∂P_i + Σ_o ∂R_i/∂H_j K_ji| (floored at 1e-12 of
    the largest; recomputed where ``rescale``, else ``kappa`` kept) and :func:`complementarity`.

    Returns (load error, κ, φ, ∂φ/∂a, ∂φ/∂R, r_free, r_cav)."""
    load_err = np.dot(weights, p) / (0.5 * math.pi) - 1.0
    if rescale:
        diag = jacobian_diagonal(dp, dh, kmat, rows)
        largest = 0.0
        for i in range(diag.size):
            diag[i] = abs(diag[i])
            largest = max(largest, diag[i])
        lowest = 1e-12 * max(largest, 1e-300)
        kappa = np.empty(diag.size)
        for i in range(diag.size):
            kappa[i] = 1.0 / max(diag[i], lowest)
    phi, d_a, d_b, r_free, r_cav = complementarity(p[1:-1], res, kappa, m_ref)
    return load_err, kappa, phi, d_a, d_b, r_free, r_cav


@numba.njit(cache=True)
def line_search(p, h0, delta, merit0, max_pressure_step, kappa, m_ref, transient, monotone, x, kmat, gap, p_h,
                homotopy, code, params, compressible, cap, floor, shear, lam, squeeze, m_old, face_order,
                face_poiseuille, weights):
    """The damped step of :func:`~ehl_dataset.solvers.newton.newton_solve` on a plain problem (the film must stay
    open): from (P, H0) along the correction ``delta`` (interior ΔP, then ΔH0), ω = min(1, ``max_pressure_step``/
    max|ΔP|) halved up to 30 times until the film H = H0 + gap + K P is open, the residual finite and — unless
    ``transient`` (pseudo-transient continuation, which takes any finite step) — the merit |φ|² + load error²
    decreased by the Armijo factor 1 − 1e-4 ω (or ω < 0.3 when not ``monotone``).

    Returns (accepted, ω, P, H0, H, R, ∂R/∂P, ∂R/∂H, m, ∂m/∂P, ∂m/∂H) at the accepted step."""
    n = p.size
    d_p = np.zeros(n)
    d_p[1:n - 1] = delta[:n - 2]
    d_h0 = delta[n - 2]
    largest = 0.0
    for i in range(n):
        largest = max(largest, abs(d_p[i]))
    omega = min(1.0, max_pressure_step / largest) if largest > 0.0 else 1.0
    for _ in range(30):
        p_new = p + omega * d_p
        h0_new = h0 + omega * d_h0
        h_new = h0_new + gap + np.dot(kmat, p_new)
        is_open = True
        for i in range(n):
            if not h_new[i] > 0.0:
                is_open = False
                break
        if is_open:
            res, dp, dh, m, m_p, m_h = residual(x, p_new, h_new, p_h, homotopy, code, params, compressible, cap,
                                                floor, shear, lam, squeeze, m_old, face_order, face_poiseuille)
            finite = True
            for i in range(n):
                if not math.isfinite(res[i]):
                    finite = False
                    break
            if finite:
                if transient:
                    return True, omega, p_new, h0_new, h_new, res, dp, dh, m, m_p, m_h
                phi = complementarity(p_new[1:-1], res, kappa, m_ref)[0]
                load = np.dot(weights, p_new) / (0.5 * math.pi) - 1.0
                merit = np.dot(phi, phi) + load**2
                if merit <= (1.0 - 1e-4 * omega) * merit0 or (not monotone and omega < 0.3):
                    return True, omega, p_new, h0_new, h_new, res, dp, dh, m, m_p, m_h
        omega *= 0.5
    empty = np.empty(0)
    band = np.empty((0, 4))
    return False, omega, p, h0, p, empty, band, band, empty, empty, empty
