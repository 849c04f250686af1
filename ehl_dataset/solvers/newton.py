"""Damped Newton solver with an active set for cavitation, for the coupled Reynolds–film–load problem.

Unknowns: the interior pressures P_1 … P_{N−2} and the film constant H0 (dimensionless, see
:mod:`ehl_dataset.discretisation.reynolds`). Equations: the discrete Reynolds equation at every interior node, the film equation
H = H0 + G(X) + K P (G the rigid gap, minus roughness in mixed runs; K the dense deflection matrix), and the load
balance Σ w_j P_j = π/2 (the dimensionless form of ∫p dx = W' = π a p_h/2).

The full Jacobian ∂R/∂P + (∂R/∂H)·K couples the local deflection into the Reynolds discretisation exactly (the
"full-system" Newton of Houpert & Hamrock 1986, which stays convergent at heavy load where Gauss–Seidel type
relaxation stalls). Cavitation p ≥ 0 is a complementarity condition, P_i ≥ 0, −R_i ≥ 0, P_i R_i = 0, solved by the
primal–dual active-set (semi-smooth Newton) rule: a node is cavitated when P_i < −κ_i R_i, and its row becomes P_i = 0.
Steps are damped by backtracking on the residual norm and kept where the film stays open.
"""

from __future__ import annotations

import logging
import math
from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
import scipy.linalg

from ..discretisation.reynolds import assemble, full_jacobian, jacobian_diagonal, newton_matrix
from ..discretisation.steady_band import band_matvec, newton_bands
from . import newton_kernels
from .krylov import STEADY_BAND, STEADY_INVERSE_WIDTH, SteadyBandedPreconditioner, SteadyGridBand, gmres

LOG = logging.getLogger(__name__)
"""Every Newton iteration is logged at DEBUG level (norms, step, where the pressure moved most):
``logging.getLogger("ehl_dataset.solvers.newton").setLevel(logging.DEBUG)`` to trace a solve."""
EXPONENT_CAP = 600.0
"""Cap on ln(η/η0) so that viscosities stay finite in double precision during wild Newton iterates."""
EXPONENT_FLOOR = 10.0
"""Floor −10 on ln(η/η0) for the linear continuation below p = 0 (wild Newton iterates only)."""
REUSE_FACTORISATION = True
"""Whether :class:`LinearSolver` reuses factorisations (False: the dense path, one LU per Newton iteration, kept as the
baseline of ``benchmarks/bench_stage1_floor.py``, whose linear solves are exact; with ``inexact`` solves the
default path converges to the same solution within the Newton tolerances)."""
REUSE_MIN_UNKNOWNS = 200
"""Newton systems of at least this many unknowns reuse an LU factorisation across iterations (:class:`LinearSolver`);
smaller ones are factorised every iteration, which costs less than a Krylov solve there."""
KRYLOV_TOLERANCE = 1e-10
"""Relative residual ‖b − S δ‖/‖b‖ to which :class:`LinearSolver` solves a Newton system by GMRES when it solves
exactly (not ``inexact``, or the floor of :func:`forcing_term`): far below the Newton tolerances, so that the iterates
are those of exact linear solves up to round-off."""
KRYLOV_ITERATIONS = 10
"""GMRES iterations allowed with a reused factorisation before the Newton matrix is factorised afresh (GMRES gives up
from the third iteration on when its mean residual reduction would not reach :data:`KRYLOV_TOLERANCE` within them)."""
BANDED_PRECONDITIONER = True
"""Whether :class:`LinearSolver` solves Newton systems of at least :data:`BANDED_MIN_UNKNOWNS` unknowns by GMRES
preconditioned with the banded LU of the Newton matrix in deflection variables
(:class:`~ehl_dataset.solvers.krylov.SteadyBandedPreconditioner`), factorised afresh every iteration (O(N·w²))
instead of a dense LU (O(N³)); False: the reused dense factorisation (or, with :data:`REUSE_FACTORISATION` False, one
dense LU per iteration)."""
BANDED_MIN_UNKNOWNS = 200
"""Newton systems of at least this many unknowns take the banded preconditioner (:data:`BANDED_PRECONDITIONER`), for
problems solved exactly (:attr:`ReynoldsProblem.banded_min_unknowns`)."""
INEXACT_BANDED_MIN_UNKNOWNS = 40
"""The same threshold for problems solved by the inexact Newton iteration (:func:`forcing_term`): with the loose
forcing term GMRES with the banded preconditioner beats a dense LU already on the continuation grid (59 unknowns and
more at `standard`). On random paper-factorial contacts at `standard` (interleaved), median CPU of a steady smooth
solve against the threshold 200: 50 on contacts 0–199 13.43 → 12.94 ms, 40 on contacts 400–599 12.87 → 12.20 ms;
the same Newton iteration counts to ±0.3 %, μ, h_min, h_c, p_max within 1e-10."""
BANDED_KRYLOV_ITERATIONS = 40
"""GMRES iterations allowed with the banded preconditioner before the dense LU is used instead (a fallback, counted)."""
FORCING_CAP = 1e-2
"""Largest relative residual ‖b − S δ‖/‖b‖ of a GMRES solve with the banded preconditioner in an inexact Newton
iteration (:class:`LinearSolver` with ``inexact``; :func:`forcing_term`)."""
FORCING_SCALE = 0.1
"""Factor c of the forcing term η = min(:data:`FORCING_CAP`, c·‖F‖∞^½) (:func:`forcing_term`)."""
INEXACT_NEWTON = True
"""Whether a :class:`LinearSolver` solves by default to the forcing term (:func:`forcing_term`) rather than to
:data:`KRYLOV_TOLERANCE`."""


def forcing_term(rhs: np.ndarray) -> float:
    """Relative residual η to which an inexact Newton iteration solves its linear system S δ = −F (``rhs`` = −F):
    η = min(:data:`FORCING_CAP`, max(:data:`FORCING_SCALE`·‖F‖∞^½, :data:`KRYLOV_TOLERANCE`)). η = O(‖F‖^½) keeps the
    local convergence superlinear, of order 1.5 (Dembo, Eisenstat & Steihaug 1982, Thm. 3.3); the converged solution
    is the one of exact solves within the Newton tolerances. On 100 random paper-factorial contacts at `standard`
    (``benchmarks/bench_stage1_floor.py``'s sample, contacts 200–299, solved every way interleaved; steady smooth solve,
    median CPU, GMRES iterations a contact, Newton iterations on the level's grid): η = min(1e-3, ‖F‖) 14.3 ms, 52,
    7.74; this η 12.9 ms, 39, 7.79; all converged, μ, h_min, h_c, p_max within 1.3e-7 of each other. Against exact
    solves (1e-10, with the wide band they need) on contacts 0–99: 13.4 against 18.5 ms (with η = min(1e-3, ‖F‖)).

    Parameters
    ----------
    rhs : numpy.ndarray
        Right-hand side −F of the Newton system [-].

    Returns
    -------
    float
        The forcing term η [-].
    """
    size = float(np.max(np.abs(rhs)))
    return min(FORCING_CAP, max(FORCING_SCALE * math.sqrt(size), KRYLOV_TOLERANCE))


@dataclass
class ReynoldsProblem:
    """A discrete line-contact problem in dimensionless variables (see :mod:`ehl_dataset.discretisation.reynolds`).

    ``x`` nodes [a]; ``kmat`` dense deflection matrix [dimensionless]; ``gap`` rigid gap X²/2 minus roughness;
    ``lam`` λ̄ = 12 η0 u_r r_eq²/(a³ p_h); ``p_h`` [Pa]; ``state`` the :class:`~ehl_dataset.model.lubricant.LubricantState`;
    ``compressible``; ``shear`` S = η0 |u_s| r_eq/(τ0 a²) (0 switches the Eyring flow factor off);
    ``second_order`` linear-upwind Couette flux; ``squeeze`` w_i/ΔT and ``m_old`` for time steps (zero: steady);
    ``film_may_close`` lets Newton iterates pass through a closed film (the homogenised model, whose mean gap may
    close where the asperities carry the load; else a step must keep the film open). (The closed-film, plastic-cap
    and patch-closure fields of the transient mixed solver went with it at ehl-2026.11-15.)
    """

    x: np.ndarray
    kmat: np.ndarray
    gap: np.ndarray
    lam: float
    p_h: float
    state: object
    compressible: bool = True
    shear: float = 0.0
    second_order: bool = True
    squeeze: np.ndarray | None = None
    m_old: np.ndarray | None = None
    film_may_close: bool = False
    weights: np.ndarray = field(init=False, repr=False)
    rows: np.ndarray = field(init=False, repr=False)
    linear: "LinearSolver" = field(init=False, repr=False, compare=False)
    law: tuple | None = field(init=False, repr=False, compare=False)
    inexact_newton: ClassVar[bool] = True
    """Whether the banded-preconditioned Newton systems are solved to the forcing term (:func:`forcing_term`)."""
    preconditioner_widths: ClassVar[tuple[int, int]] = (STEADY_INVERSE_WIDTH, STEADY_BAND)
    """Half widths of B and of the factorised band of :class:`~ehl_dataset.solvers.krylov.SteadyGridBand`."""
    banded_min_unknowns: ClassVar[int] = INEXACT_BANDED_MIN_UNKNOWNS
    """Fewest unknowns of a Newton system solved with the banded preconditioner (smaller ones: dense LU)."""

    def __post_init__(self):
        self.x = np.ascontiguousarray(self.x, dtype=float)
        self.kmat = np.ascontiguousarray(self.kmat, dtype=float)
        dx = np.diff(self.x)
        w = np.zeros_like(self.x)
        w[:-1] += 0.5 * dx
        w[1:] += 0.5 * dx
        self.weights = w
        self.rows = np.arange(1, self.x.size - 1)
        self.linear = LinearSolver(inexact=None if self.inexact_newton else False)
        self.law = newton_kernels.law_parameters(self.state)
        if self.squeeze is None:
            self.squeeze = np.zeros_like(self.x)
            self.m_old = np.zeros_like(self.x)

    # -- film and fluid --------------------------------------------------------------------------------------
    def film(self, p: np.ndarray, h0: float) -> np.ndarray:
        """H = H0 + gap + K P."""
        return h0 + self.gap + self.kmat @ p

    def load(self, p: np.ndarray) -> float:
        """Relative load-balance error Σ w P/(π/2) − 1."""
        return float(self.weights @ p) / (0.5 * math.pi) - 1.0

    def rheology(self, p: np.ndarray, homotopy: float = 1.0):
        """(φ = ln(η/η0) scaled by ``homotopy``, ∂φ/∂P, ρ̄, ∂ρ̄/∂P) at dimensionless pressures ``p`` (compiled,
        :func:`~ehl_dataset.solvers.newton_kernels.rheology`, for the lubricant laws it knows)."""
        if self.law is not None:
            return newton_kernels.rheology(np.asarray(p, dtype=float), *self._law_arguments(homotopy))
        pa = p * self.p_h
        law = self.state.law
        # Below p = 0 (only in Newton iterates; the solution has p ≥ 0) the laws are continued linearly from p = 0
        # so that η and ρ stay C¹ there: a kink at p = 0 makes Newton cycle in closed-film (mixed) regions.
        negative = pa < 0.0
        slope_phi0 = float(law.exponent_derivative(np.array([0.0]))[0]) if negative.any() else 0.0
        phi = homotopy * np.where(negative, slope_phi0 * pa, law.exponent(pa))
        phi_p = homotopy * np.where(negative, slope_phi0, law.exponent_derivative(pa)) * self.p_h
        clipped = (phi > EXPONENT_CAP) | (phi < -EXPONENT_FLOOR)
        phi = np.clip(phi, -EXPONENT_FLOOR, EXPONENT_CAP)
        phi_p = np.where(clipped, 0.0, phi_p)
        if self.compressible:
            rho = self.state.density(pa) / self.state.rho0
            rho_p = self.state.density_derivative(pa) * self.p_h / self.state.rho0
            if negative.any():
                slope_rho0 = float(self.state.density_derivative(np.array([0.0]))[0]) * self.p_h / self.state.rho0
                rho = np.where(negative, 1.0 + slope_rho0 * p, rho)
                rho_p = np.where(negative, slope_rho0, rho_p)
        else:
            rho = np.ones_like(p)
            rho_p = np.zeros_like(p)
        return phi, phi_p, rho, rho_p

    def fluid(self, p: np.ndarray, h: np.ndarray, homotopy: float = 1.0):
        """ε, ∂ε/∂P, ∂ε/∂H, m = ρ̄H, ∂m/∂P, ∂m/∂H at the nodes (viscosity exponent scaled by ``homotopy``)."""
        phi, phi_p, rho, rho_p = self.rheology(p, homotopy)
        if self.law is not None:
            return newton_kernels.fluid(phi, phi_p, rho, rho_p, np.asarray(h, dtype=float), float(self.shear),
                                        float(self.lam))
        hp = np.maximum(h, 1e-12)  # a wild iterate's film
        inv_eta2 = np.exp(-2.0 * phi)
        shear2 = (self.shear / hp) ** 2
        g2 = np.maximum(inv_eta2 + shear2, 1e-300)  # (cosh(τ_m/τ0)/η̄)², Eyring flow factor over viscosity
        g = np.sqrt(g2)
        eps = rho * hp**3 * g / self.lam
        dlng_dp = -phi_p * inv_eta2 / g2
        dlng_dh = -shear2 / (hp * g2)
        eps_p = eps * (rho_p / rho + dlng_dp)
        eps_h = eps * (3.0 / hp + dlng_dh)
        m = rho * h
        return eps, eps_p, eps_h, m, rho_p * h, rho

    def face_order(self) -> np.ndarray:
        """Weight of the linear-upwind Couette correction per face: 1 (second order) or 0 (first order)."""
        return np.full(self.x.size - 1, 1.0 if self.second_order else 0.0)

    def face_poiseuille(self) -> np.ndarray:
        """Weight of the Poiseuille term per face: 1 everywhere."""
        return np.ones(self.x.size - 1)

    def residual(self, p, h, homotopy=1.0):
        """Reynolds residual R (N), banded ∂R/∂P, ∂R/∂H, and m = ρ̄H with ∂m/∂P, ∂m/∂H."""
        if (self.law is not None and type(self).fluid is ReynoldsProblem.fluid
                and type(self).rheology is ReynoldsProblem.rheology):
            res, dp, dh, m, m_p, m_h = newton_kernels.residual(
                self.x, np.asarray(p, dtype=float), np.asarray(h, dtype=float), *self._law_arguments(homotopy),
                *self._equation_arguments())
            return res, dp, dh, (m, m_p, m_h)
        eps, eps_p, eps_h, m, m_p, m_h = self.fluid(p, h, homotopy)
        res, dp, dh = assemble(self.x, p, eps, eps_p, eps_h, m, m_p, m_h, self.squeeze, self.m_old,
                               self.face_order(), self.face_poiseuille())
        return res, dp, dh, (m, m_p, m_h)

    def compiled_arguments(self, homotopy: float) -> tuple | None:
        """The trailing arguments of :func:`~ehl_dataset.solvers.newton_kernels.line_search` for this problem, or None
        where :func:`newton_solve` must take its array form: a subclass that changes the residual, the film or the
        cavitation condition, a film allowed to close, or a lubricant law the kernels do not know."""
        cls = type(self)
        plain = all(getattr(cls, name) is getattr(ReynoldsProblem, name)
                    for name in ("residual", "fluid", "rheology", "film", "load", "cavitation_offset", "face_order",
                                 "face_poiseuille", "jacobian_diagonal"))
        if not plain or self.law is None or self.film_may_close:
            return None
        return (self.x, self.kmat, np.ascontiguousarray(self.gap, dtype=float), *self._law_arguments(homotopy),
                *self._equation_arguments(), self.weights)

    def _law_arguments(self, homotopy: float) -> tuple:
        """(p_h, homotopy, law code, law parameters, compressible, exponent cap, exponent floor): the lubricant's part
        of the arguments of the compiled kernels (:mod:`~ehl_dataset.solvers.newton_kernels`)."""
        return (float(self.p_h), float(homotopy), self.law[0], self.law[1],
                bool(self.compressible and self.state.compressible), EXPONENT_CAP, EXPONENT_FLOOR)

    def _equation_arguments(self) -> tuple:
        """(S, λ̄, squeeze, m_old, face orders, face Poiseuille weights): the discretisation's part of them."""
        return (float(self.shear), float(self.lam), self.squeeze, self.m_old, self.face_order(),
                self.face_poiseuille())

    def cavitation_offset(self, h):
        """(s, ∂s/∂H) per node when the cavitation condition applies to P − s(H) rather than to P (the homogenised
        model, whose unknown is the total pressure and whose fluid pressure is P − p_a(H)); None here."""
        return None

    def jacobian(self, dp, dh):
        """Full Jacobian (see :func:`~ehl_dataset.discretisation.reynolds.full_jacobian`)."""
        return full_jacobian(dp, dh, self.kmat, self.rows)

    def jacobian_diagonal(self, dp, dh):
        """Diagonal of :meth:`jacobian` (see :func:`~ehl_dataset.discretisation.reynolds.jacobian_diagonal`)."""
        return jacobian_diagonal(dp, dh, self.kmat, self.rows)

    def newton_matrix(self, dp, dh, d_a, d_b, load_row):
        """Semi-smooth Newton matrix (see :func:`~ehl_dataset.discretisation.reynolds.newton_matrix`)."""
        return newton_matrix(dp, dh, self.kmat, self.rows, d_a, d_b, load_row)


class NewtonSystem:
    """The semi-smooth Newton matrix S of one iteration of :func:`newton_solve`, held in its banded parts.

    Rows r < M (M = N − 2 interior nodes): d_a[r] e_r − d_b[r] J_r with J = ∂R/∂P + (∂R/∂H)·K (the full Jacobian)
    and, for a problem whose cavitation condition acts on P − s(H), minus ``coupling``[r]·∂H_i/∂(P, H0); the last
    row is the load row. :meth:`dense` forms S (:meth:`ReynoldsProblem.newton_matrix`), :meth:`bands` its local
    parts (:func:`~ehl_dataset.discretisation.steady_band.newton_bands`), :meth:`matvec` S v without forming it
    (one product with K).

    Parameters
    ----------
    problem : ReynoldsProblem
        The problem [-].
    dp, dh : numpy.ndarray
        Banded ∂R/∂P and ∂R/∂H, (N, 4) [-].
    d_a, d_b : numpy.ndarray
        Fischer–Burmeister partials of the interior rows, M entries [-].
    load_row : numpy.ndarray
        Derivative of the relative load error, M + 1 entries (0 for H0) [-].
    coupling : numpy.ndarray or None
        d_a·∂s/∂H per interior row for a cavitation offset s(H), else None [-].
    """

    def __init__(self, problem: "ReynoldsProblem", dp, dh, d_a, d_b, load_row, coupling=None):
        self.problem = problem
        self.dp, self.dh, self.d_a, self.d_b = dp, dh, d_a, d_b
        self.load_row = load_row
        self.coupling = coupling
        self.size = load_row.size
        self._dense = None
        self._bands = None

    def dense(self) -> np.ndarray:
        """S as a dense (M + 1) × (M + 1) matrix (formed once)."""
        if self._dense is None:
            problem = self.problem
            system = problem.newton_matrix(self.dp, self.dh, self.d_a, self.d_b, self.load_row)
            if self.coupling is not None:  # a = P_i − s(H_i): dH_i = K_i· dP + dH0
                system[:-1, :-1] -= self.coupling[:, None] * problem.kmat[1:-1, 1:-1]
                system[:-1, -1] -= self.coupling
            self._dense = system
        return self._dense

    def bands(self) -> tuple[np.ndarray, np.ndarray]:
        """(lb, eb), the local parts of the rows (:func:`~ehl_dataset.discretisation.steady_band.newton_bands`)."""
        if self._bands is None:
            lb, eb = newton_bands(self.dp, self.dh, self.problem.rows, self.d_a, self.d_b)
            if self.coupling is not None:
                eb[:, 2] -= self.coupling
            self._bands = (lb, eb)
        return self._bands

    def matvec(self, v: np.ndarray) -> np.ndarray:
        """S v (``v``: M + 1 entries, ΔP then ΔH0)."""
        lb, eb = self.bands()
        p = np.zeros(self.size + 1)
        p[1:-1] = v[:-1]
        out = np.empty(self.size)
        out[:-1] = band_matvec(lb, eb, v, self.problem.kmat @ p)
        out[-1] = self.load_row @ v
        return out


class LinearSolver:
    """Solves the Newton systems S δ = b of one problem.

    Three paths, chosen by the module switches. With :data:`BANDED_PRECONDITIONER` (the default) a
    :class:`NewtonSystem` of at least ``problem.banded_min_unknowns`` unknowns (:data:`INEXACT_BANDED_MIN_UNKNOWNS`
    or :data:`BANDED_MIN_UNKNOWNS`) is solved by GMRES
    (:func:`~ehl_dataset.solvers.krylov.gmres`) preconditioned with the banded LU of S in deflection variables
    (:class:`~ehl_dataset.solvers.krylov.SteadyBandedPreconditioner`, formed afresh for every system: O(N·w²)), its
    products with S formed without the dense matrix (:meth:`NewtonSystem.matvec`), to the relative residual
    :data:`KRYLOV_TOLERANCE` (with ``inexact``, the default: to the forcing term of an inexact Newton iteration,
    :func:`forcing_term`); if GMRES does not get there within :data:`BANDED_KRYLOV_ITERATIONS` (or the band is
    singular) the dense S is factorised instead (counted in ``fallbacks``). Every other system (smaller ones, the
    switch off, a dense matrix given) is solved with LAPACK's LU (``dgetrf``); with :data:`REUSE_FACTORISATION` a
    system of at least :data:`REUSE_MIN_UNKNOWNS` unknowns is first solved by GMRES right-preconditioned with the
    factorisation kept from an earlier Newton iteration of the same problem, and factorised afresh only if that would
    take more than :data:`KRYLOV_ITERATIONS`. Every correction is that of an exact linear solve to within the Krylov
    tolerance or the forcing term, so the Newton iteration keeps its quadratic convergence. Counters:
    ``factorisations`` (dense LU), ``krylov_solves`` and ``krylov_iterations`` (with a reused LU),
    ``banded_solves`` and ``banded_iterations`` (GMRES with the banded preconditioner), ``fallbacks``.

    Parameters
    ----------
    reuse : bool or None
        Reuse factorisations (False: one dense LU per system, the dense path: no banded preconditioner either); None
        takes :data:`REUSE_FACTORISATION` [-].
    inexact : bool or None
        Solve the banded-preconditioned systems only to the forcing term of an inexact Newton iteration
        (:func:`forcing_term`); None takes :data:`INEXACT_NEWTON` [-].
    """

    def __init__(self, reuse: bool | None = None, inexact: bool | None = None):
        self.reuse = REUSE_FACTORISATION if reuse is None else bool(reuse)
        self.inexact = INEXACT_NEWTON if inexact is None else bool(inexact)
        self.lu = None
        self.factorisations = 0
        self.krylov_solves = 0
        self.krylov_iterations = 0
        self.banded_solves = 0
        self.banded_iterations = 0
        self.fallbacks = 0

    def counts(self) -> dict:
        """The counters as a dict of ints."""
        return {"factorisations": self.factorisations, "krylov_solves": self.krylov_solves,
                "krylov_iterations": self.krylov_iterations, "banded_solves": self.banded_solves,
                "banded_iterations": self.banded_iterations, "fallbacks": self.fallbacks}

    def solve(self, system, rhs: np.ndarray) -> np.ndarray:
        """δ with S δ = b (``system`` S: a :class:`NewtonSystem` or a dense matrix, ``rhs`` b); raises
        ``numpy.linalg.LinAlgError`` or ``ValueError`` when S is singular or not finite."""
        if isinstance(system, NewtonSystem):
            if (self.reuse and BANDED_PRECONDITIONER and system.size >= system.problem.banded_min_unknowns
                    and np.all(np.isfinite(rhs))):
                delta = self._banded(system, rhs)
                if delta is not None:
                    return delta
                self.fallbacks += 1
            system = system.dense()
        if self.lu is not None and self.lu[0].shape == system.shape:
            lu = self.lu
            delta, its, relative = gmres(system.dot, lambda r: scipy.linalg.lu_solve(lu, r, check_finite=False), rhs,
                                         KRYLOV_TOLERANCE, KRYLOV_ITERATIONS, give_up_after=3)
            self.krylov_iterations += its
            if relative <= KRYLOV_TOLERANCE and np.all(np.isfinite(delta)):
                self.krylov_solves += 1
                return delta
        if not np.all(np.isfinite(system)):
            raise ValueError("Newton matrix must not contain infs or NaNs")
        # LAPACK's LU directly (what scipy.linalg.lu_factor calls, without its per-call checks: on the small systems
        # of a continuation grid they cost more than the factorisation); ill-conditioning is judged by the residuals
        factors, pivots, info = scipy.linalg.lapack.dgetrf(system)
        if info < 0:
            raise ValueError(f"dgetrf: illegal argument {-info}")
        if info > 0 or np.any(factors.diagonal() == 0.0):
            raise np.linalg.LinAlgError("singular Newton matrix")
        lu = (factors, pivots)
        self.factorisations += 1
        self.lu = lu if self.reuse and system.shape[0] >= REUSE_MIN_UNKNOWNS else None
        return scipy.linalg.lapack.dgetrs(factors, pivots, rhs)[0]

    def _banded(self, system: NewtonSystem, rhs: np.ndarray) -> np.ndarray | None:
        """GMRES with the banded preconditioner; None when it does not reach :data:`KRYLOV_TOLERANCE` (or the forcing
        term, :func:`forcing_term`)."""
        problem = system.problem
        lb, eb = system.bands()
        if not (np.all(np.isfinite(lb)) and np.all(np.isfinite(eb))):
            return None
        grid = SteadyGridBand.of(problem.kmat, problem.weights, system.load_row[:-1], *problem.preconditioner_widths)
        preconditioner = SteadyBandedPreconditioner(lb, eb, grid)
        if preconditioner.singular:
            return None
        tolerance = KRYLOV_TOLERANCE
        if self.inexact:
            tolerance = forcing_term(rhs)
        delta, its, relative = preconditioner.solve(lb, eb, system.load_row, rhs, tolerance,
                                                    BANDED_KRYLOV_ITERATIONS, 5)
        self.banded_iterations += its
        if relative <= tolerance and np.all(np.isfinite(delta)):
            self.banded_solves += 1
            return delta
        return None


@dataclass
class NewtonOutcome:
    """Result of :func:`newton_solve`: ``p``, ``h0``, ``h`` (dimensionless), ``converged``, ``iterations`` and the
    final norms ``residual`` (max relative Reynolds residual on pressurised nodes), ``load`` (relative load
    error), ``step`` (last max |ΔP|), ``complementarity`` (max positive residual on cavitated nodes)."""

    p: np.ndarray
    h0: float
    h: np.ndarray
    converged: bool
    iterations: int
    residual: float
    load: float
    step: float
    complementarity: float
    message: str = ""


def _complementarity(problem: ReynoldsProblem, p, res, kappa):
    """Fischer–Burmeister function φ(a, b) = a + b − √(a² + b²) of a = P_i, b = −κ_i R_i and its partials.

    κ_i = 1/|∂R_i/∂P_i| (Jacobi scaling) makes b the local Newton pressure correction, comparable with P.

    φ = 0 ⇔ a ≥ 0, b ≥ 0, a·b = 0: either the node is pressurised and satisfies Reynolds, or it is cavitated
    (P = 0) and the flow would pull the pressure below zero there. Ψ = ½|φ|² is continuously differentiable, so the
    Armijo line search on it is well defined (semi-smooth Newton; De Luca, Facchinei & Kanzow 1996).
    """
    phi, d_a, d_b = _fb(p[1:-1], -res[1:-1] * kappa)
    return phi, d_a, d_b * kappa


def _fb(a, b, smoothing=0.0):
    """Fischer–Burmeister φ(a, b) = a + b − √(a² + b² + 2s²) and its partials ∂φ/∂a, ∂φ/∂b (a generalised
    gradient at a = b = 0 when s = 0). With s > 0 (Kanzow 1996) φ = 0 ⇔ a > 0, b > 0, a·b = s²: a smooth
    approximation of the complementarity, whose Newton iteration cannot cycle between active sets."""
    s2 = 2.0 * np.asarray(smoothing) ** 2
    root = np.sqrt(a * a + b * b + s2)
    degenerate = root < 1e-14
    safe = np.where(degenerate, 1.0, root)
    d_a = np.where(degenerate, 1.0 - 1.0 / math.sqrt(2.0), 1.0 - a / safe)
    d_b = np.where(degenerate, 1.0 - 1.0 / math.sqrt(2.0), 1.0 - b / safe)
    # a + b − root cancels catastrophically when one argument is huge (e.g. a wild residual): for a + b > 0 use
    # the equal form (2ab − 2s²)/(a + b + root)
    total = a + b
    positive = total > 0.0
    phi = np.where(positive, (2.0 * a * b - s2) / np.where(positive, total + root, 1.0), total - root)
    return phi, d_a, d_b


def newton_solve(problem: ReynoldsProblem, p0: np.ndarray, h00: float, *, homotopy: float = 1.0,
                 tol_residual: float = 1e-6, tol_load: float = 1e-6, tol_step: float = 1e-6,
                 max_iterations: int = 60, max_pressure_step: float = 0.5,
                 pseudo_dt: float = 0.0, m_ref: float | None = None, monotone: bool = True,
                 freeze_scaling: bool = False) -> NewtonOutcome:
    """Solve the discrete problem from the initial guess (``p0``, ``h00``).

    Converged when the Reynolds residual on pressurised nodes (relative to the Couette flux ρ̄H at the contact
    centre), the complementarity violation on the other nodes, the load error and the last pressure step are all
    below tolerance. Steps are limited to ``max_pressure_step`` (in p_h), backtracked on the Fischer–Burmeister
    merit and kept where the film stays open (smooth runs). ``m_ref`` overrides the flux scale (rough runs,
    where the film at the centre may be closed); ``monotone=False`` accepts a damped step (ω < 0.3) even without
    a decrease of the merit, which lets the iteration leave the kinks of the complementarity function;
    ``freeze_scaling`` keeps the Jacobi scaling κ of the first iteration, so that the function whose root is sought
    (and the merit) stays the same from one iteration to the next (a κ that follows the iterate can make the
    iteration cycle where the local derivative changes a lot, e.g. at closed-film nodes). With ``pseudo_dt`` > 0 the Newton iteration is globalised by
    pseudo-transient continuation (Kelley & Keyes 1998): the squeeze term w_i ∂m_i/∂T of the transient Reynolds
    equation with time step ΔT_k = pseudo_dt·r_0/r_k (switched evolution relaxation) is added to the Jacobian only,
    so the iterates follow a damped, physical squeeze-film evolution early on and become pure Newton steps
    (quadratic convergence) as the residual falls; the converged solution is the steady one. Never raises for non-convergence: the outcome says
    ``converged=False`` with the norms.
    """
    n = problem.x.size
    p = np.asarray(p0, dtype=float).copy()
    p[0] = p[-1] = 0.0
    h0 = float(h00)
    centre = int(np.argmin(np.abs(problem.x)))
    h = problem.film(p, h0)
    if not problem.film_may_close and np.any(h <= 0.0):
        return NewtonOutcome(p, h0, h, False, 0, math.inf, math.inf, math.inf, math.inf, "initial film not open")
    res, dp, dh, mm = problem.residual(p, h, homotopy)
    m_ref = max(abs(float(mm[0][centre])), 1e-300) if m_ref is None else float(m_ref)
    r_start = None
    step_norm = math.inf
    message = "iteration limit reached"
    load_row = np.zeros(n - 1)
    load_row[:-1] = problem.weights[1:-1] / (0.5 * math.pi)
    compiled = problem.compiled_arguments(homotopy)
    kappa = np.empty(0)
    for iteration in range(1, max_iterations + 1):
        if compiled is not None:
            shift = None
            load_err, kappa, phi, d_a, d_b, r_free, r_cav = newton_kernels.iteration_state(
                p, res, dp, dh, problem.kmat, problem.rows, problem.weights, m_ref, kappa,
                iteration == 1 or not freeze_scaling)
        else:
            load_err = problem.load(p)
            if iteration == 1 or not freeze_scaling:
                diag = np.abs(problem.jacobian_diagonal(dp, dh))
                kappa = 1.0 / np.maximum(diag, 1e-12 * max(float(diag.max()), 1e-300))
            shift = problem.cavitation_offset(h)
            p_cav = p if shift is None else p - shift[0]
            phi, d_a, d_b, r_free, r_cav = newton_kernels.complementarity(p_cav[1:-1], res, kappa, m_ref)
        # the step test is waived when the equations hold 1000× below tolerance: a nearly singular Jacobian
        # can keep the step from settling although the residual vanishes
        waiver = 1e-3
        if (r_free <= tol_residual and r_cav <= tol_residual and abs(load_err) <= tol_load
                and (step_norm <= tol_step or max(r_free, r_cav) <= waiver * tol_residual)):
            return NewtonOutcome(p, h0, h, True, iteration - 1, r_free, load_err, step_norm, r_cav, "converged")
        if pseudo_dt > 0.0:
            r_now = max(r_free, r_cav, abs(load_err), 1e-300)
            r_start = r_now if r_start is None else r_start
            dt = min(pseudo_dt * r_start / r_now, 1e12)
            sq = problem.weights / dt
            dp = dp.copy()
            dh = dh.copy()
            dp[:, 2] -= sq * mm[1]
            dh[:, 2] -= sq * mm[2]
        # dφ/dx = d_a e_i − d_b J_i  (b = −κ R), and the load row
        system = NewtonSystem(problem, dp, dh, d_a, d_b, load_row,
                              None if shift is None else d_a * shift[1][1:-1])
        rhs = -np.concatenate([phi, [load_err]])
        try:
            delta = problem.linear.solve(system, rhs)
        except (np.linalg.LinAlgError, ValueError) as err:
            message = f"linear solve failed: {err}"
            break
        merit0 = float(phi @ phi) + load_err**2
        if compiled is not None:
            accepted, omega, p_new, h0_new, h_new, res_new, dp_new, dh_new, *m_new = newton_kernels.line_search(
                p, h0, delta, merit0, max_pressure_step, kappa, m_ref, pseudo_dt > 0.0, monotone, *compiled)
            h0_new, m_new = float(h0_new), tuple(m_new)
            trials = ()
        else:
            d_p = np.zeros(n)
            d_p[1:-1] = delta[:-1]
            d_h0 = float(delta[-1])
            largest = float(np.max(np.abs(d_p)))
            omega = min(1.0, max_pressure_step / largest) if largest > 0 else 1.0
            accepted = False
            trials = range(30)
        for _ in trials:
            p_new = p + omega * d_p
            h0_new = h0 + omega * d_h0
            h_new = problem.film(p_new, h0_new)
            if problem.film_may_close or np.all(h_new > 0.0):
                res_new, dp_new, dh_new, m_new = problem.residual(p_new, h_new, homotopy)
                if pseudo_dt > 0.0 and np.all(np.isfinite(res_new)):
                    accepted = True
                    break
                if np.all(np.isfinite(res_new)):
                    shift_new = problem.cavitation_offset(h_new)
                    phi_new = newton_kernels.complementarity(
                        (p_new if shift_new is None else p_new - shift_new[0])[1:-1], res_new, kappa, m_ref)[0]
                    merit1 = float(phi_new @ phi_new) + problem.load(p_new) ** 2
                    if merit1 <= (1.0 - 1e-4 * omega) * merit0 or (not monotone and omega < 0.3):
                        accepted = True
                        break
            omega *= 0.5
        if not accepted:
            message = "line search failed (no decrease of the residual with an open film)"
            break
        step_norm = float(np.max(np.abs(p_new - p)))
        if LOG.isEnabledFor(logging.DEBUG):
            j = int(np.argmax(np.abs(p_new - p)))
            LOG.debug("it %d: r %.2e %.2e merit %.3e omega %.3g step %.3e load %.1e at x=%.4f p=%.4g->%.4g h=%.3e "
                      "phi_max_at=%.4f", iteration, r_free, r_cav, merit0, omega, step_norm, load_err, problem.x[j],
                      p[j], p_new[j], h[j], problem.x[1 + int(np.argmax(np.abs(phi)))])
        p, h0, h, res, dp, dh, mm = p_new, h0_new, h_new, res_new, dp_new, dh_new, m_new
    shift = problem.cavitation_offset(h)
    p_cav = p if shift is None else p - shift[0]
    r_free, r_cav = newton_kernels.complementarity(p_cav[1:-1], res, kappa, m_ref)[3:]
    return NewtonOutcome(p, h0, h, False, max_iterations, r_free, problem.load(p), step_norm, r_cav, message)
