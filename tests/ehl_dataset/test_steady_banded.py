"""The banded preconditioner of the steady Newton systems gives the solutions of the dense linear algebra it replaces.

* the band LU solve compiled for the Krylov loop equals LAPACK's ``dgbtrs`` on the same factors;
* the matrix-free product of a Newton system (bands and one product with K) equals the dense Newton matrix times the
  vector, with and without the cavitation-offset coupling of the homogenised model;
* on the uniform part of a grid the banded inverse kernel is the uniform-grid band of
  :func:`~ehl_dataset.discretisation.deflection.inverse_kernel_band` for that spacing;
* a Newton system of a real contact solved by GMRES with the banded preconditioner satisfies S δ = b to the Krylov
  tolerance (the true residual, not GMRES's estimate) and agrees with the dense LU solution;
* a steady solve on the banded path gives the values of the dense path (one LU per Newton iteration) to well below the
  level's Newton tolerances, without falling back to the dense LU.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import lapack

from ehl_dataset.discretisation.deflection import influence_matrix, inverse_kernel_band
from ehl_dataset.discretisation.steady_band import band_lu_solve, inverse_band
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers import newton, steady
from ehl_dataset.solvers.krylov import STEADY_INVERSE_WIDTH
from ehl_dataset.solvers.levels import get_level
from ehl_dataset.solvers.newton import KRYLOV_TOLERANCE, LinearSolver, NewtonSystem, ReynoldsProblem


def test_band_lu_solve_equals_lapack_dgbtrs():
    rng = np.random.default_rng(5)
    m, kl = 60, 5
    ab = np.zeros((3 * kl + 1, m))
    ab[kl:, :] = rng.standard_normal((2 * kl + 1, m))  # rows kl … 3kl of the storage hold the band
    lu, piv, info = lapack.dgbtrf(ab, kl, kl)
    assert info == 0
    b = rng.standard_normal(m)
    reference, _ = lapack.dgbtrs(lu, kl, kl, b, piv)
    assert np.allclose(band_lu_solve(lu, piv, kl, b), reference, rtol=1e-12, atol=1e-12)


def _newton_system(coupling: bool = False):
    """A Newton system of a converging solve of a real contact on the ``standard`` grid (425 nodes)."""
    lub = load_lubricant("atf")
    case = ContactCase.from_engineering(1.0, 20, 5, 0.2, 90)
    state = lub.state(case.temperature)
    scales = steady.ContactScales.of(case, state)
    x = steady.steady_grid(get_level("standard"), h_c=steady.moes_h_c(case, state, scales))
    problem = ReynoldsProblem(x=x, kmat=influence_matrix(x), gap=0.5 * x**2, lam=scales.lam, p_h=case.p_h,
                              state=state, shear=scales.shear)
    p = np.sqrt(np.clip(1.0 - x**2, 0.0, None))
    h0 = steady.moes_h_c(case, state, scales) - float(problem.film(p, 0.0)[np.argmin(np.abs(x))])
    h = problem.film(p, h0)
    res, dp, dh, _ = problem.residual(p, h)
    diag = np.abs(problem.jacobian_diagonal(dp, dh))
    kappa = 1.0 / np.maximum(diag, 1e-12 * diag.max())
    phi, d_a, d_b = newton._complementarity(problem, p, res, kappa)
    load_row = np.zeros(x.size - 1)
    load_row[:-1] = problem.weights[1:-1] / (0.5 * np.pi)
    extra = np.random.default_rng(2).uniform(0.0, 0.1, x.size - 2) if coupling else None
    rhs = -np.concatenate([phi, [problem.load(p)]])
    return problem, NewtonSystem(problem, dp, dh, d_a, d_b, load_row, extra), rhs


@pytest.mark.parametrize("coupling", [False, True])
def test_matrix_free_product_equals_the_dense_newton_matrix(coupling):
    _, system, _ = _newton_system(coupling)
    v = np.random.default_rng(1).standard_normal(system.size)
    dense = system.dense() @ v
    assert np.allclose(system.matvec(v), dense, rtol=1e-12, atol=1e-12 * np.abs(dense).max())


def test_inverse_band_is_the_uniform_band_where_the_grid_is_uniform():
    x = np.linspace(-2.0, 2.0, 201)
    weights = np.full(x.size, x[1] - x[0])
    weights[[0, -1]] *= 0.5
    band = inverse_band(weights, inverse_kernel_band(STEADY_INVERSE_WIDTH, 1.0))
    uniform = inverse_kernel_band(STEADY_INVERSE_WIDTH, x[1] - x[0])
    assert np.allclose(band[100], uniform, rtol=1e-12, atol=0.0)


def test_banded_gmres_solves_a_real_newton_system_to_the_krylov_tolerance():
    _, system, rhs = _newton_system()
    solver = LinearSolver(reuse=True, inexact=False)
    delta = solver.solve(system, rhs)
    assert solver.banded_solves == 1 and solver.fallbacks == 0 and solver.factorisations == 0
    dense = system.dense()
    # GMRES's residual estimate is exact in exact arithmetic; the true residual may exceed it by round-off
    assert np.linalg.norm(dense @ delta - rhs) <= 10 * KRYLOV_TOLERANCE * np.linalg.norm(rhs)
    reference = np.linalg.solve(dense, rhs)
    assert np.allclose(delta, reference, rtol=0.0, atol=1e-7 * np.abs(reference).max())


def test_inexact_newton_solves_to_the_forcing_term_and_no_further():
    """Inexact Newton (Dembo, Eisenstat & Steihaug 1982): the relative residual of the linear solve is the forcing term
    η = min(FORCING_CAP, FORCING_SCALE·‖F‖∞^½) or below, and, since GMRES stops as soon as it gets there, above the
    exact solve's."""
    _, system, rhs = _newton_system()
    forcing = min(newton.FORCING_CAP, max(newton.FORCING_SCALE * np.max(np.abs(rhs)) ** 0.5, KRYLOV_TOLERANCE))
    assert newton.forcing_term(rhs) == forcing
    assert forcing > 100 * KRYLOV_TOLERANCE  # a start far from the solution: the forcing term is loose
    inexact, exact = LinearSolver(reuse=True, inexact=True), LinearSolver(reuse=True, inexact=False)
    delta, reference = inexact.solve(system, rhs), exact.solve(system, rhs)
    dense = system.dense()
    relative = np.linalg.norm(dense @ delta - rhs) / np.linalg.norm(rhs)
    # GMRES's residual estimate equals the true residual up to round-off (far below η here)
    assert KRYLOV_TOLERANCE < relative <= forcing * (1.0 + 1e-6)
    assert inexact.banded_iterations < exact.banded_iterations


def test_steady_solve_on_the_banded_path_equals_the_dense_path(monkeypatch):
    lub = load_lubricant("atf")
    case = ContactCase.from_engineering(2.0, 60, 15, 0.1, 75)
    steady._STEADY_CACHE.clear()
    banded = solve_contact(case, lub, "standard", model="smooth")
    monkeypatch.setattr(newton, "REUSE_FACTORISATION", False)
    steady._STEADY_CACHE.clear()
    dense = solve_contact(case, lub, "standard", model="smooth")
    steady._STEADY_CACHE.clear()
    counts = banded.extra["continuation"]["linear"]
    assert counts["banded_solves"] > 0 and counts["fallbacks"] == 0
    assert dense.extra["continuation"]["linear"]["banded_solves"] == 0
    assert banded.converged and dense.converged and banded.iterations == dense.iterations
    for key in ("mu", "h_min", "h_central", "p_max"):
        assert getattr(banded, key) == pytest.approx(getattr(dense, key), rel=1e-9), key
