"""The cost-saving parts of the steady smooth solve give the numbers of the direct computation they replace.

* the influence matrix of a grid (numba, one logarithm per node pair, cached per grid) equals the element-wise exact
  integration of the hat functions (:func:`ehl_dataset.discretisation.deflection._hat_weights`) to round-off, and a
  second request returns the same read-only array;
* the reused-factorisation linear solve of the Newton systems (GMRES preconditioned by an older LU) solves to its
  stated relative residual, and falls back to a fresh factorisation when the matrix has moved;
* the temperature table built in one array evaluation equals the row-by-row evaluation of the lubricant's laws;
* a steady solution reused from the per-process cache (another roughness pair of the same contact, as a factorial
  asks for it) gives the same result, bit for bit, as a solve from scratch.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from ehl_dataset.discretisation.deflection import _hat_weights, influence_matrix
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.thermal import THERMAL_RISES_K
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers import steady
from ehl_dataset.solvers.newton import KRYLOV_TOLERANCE, REUSE_MIN_UNKNOWNS, LinearSolver
from ehl_dataset.solvers.levels import get_level


def test_influence_matrix_equals_exact_hat_integration_and_is_cached():
    x = steady.steady_grid(get_level("fast"))
    k = influence_matrix(x)
    reference = -(1.0 / np.pi) * _hat_weights(x, x)
    # both forms difference antiderivatives of size ~span² ln(span) and divide by the element length: their round-off
    # is of the order eps·span²(1 + ln span)/dx_min
    span, dx_min = x[-1] - x[0], np.min(np.diff(x))
    assert np.max(np.abs(k - reference)) <= np.finfo(float).eps * span**2 * (1.0 + np.log(span)) / dx_min
    assert influence_matrix(x.copy()) is k
    assert not k.flags.writeable


def test_reused_factorisation_solves_to_its_tolerance_and_refactorises_when_needed():
    rng = np.random.default_rng(3)
    n = REUSE_MIN_UNKNOWNS + 20
    base = np.eye(n) * 4.0 + rng.standard_normal((n, n)) / np.sqrt(n)
    b = rng.standard_normal(n)
    solver = LinearSolver(reuse=True)
    solver.solve(base, b)
    assert solver.factorisations == 1
    near = base + 1e-3 * rng.standard_normal((n, n)) / np.sqrt(n)   # a later Newton matrix, close to the first
    x = solver.solve(near, b)
    assert solver.factorisations == 1 and solver.krylov_solves == 1
    assert np.linalg.norm(near @ x - b) <= 10 * KRYLOV_TOLERANCE * np.linalg.norm(b)
    far = np.eye(n) + 3.0 * rng.standard_normal((n, n)) / np.sqrt(n)  # moved: GMRES gives up, fresh LU
    x = solver.solve(far, b)
    assert solver.factorisations == 2
    assert np.linalg.norm(far @ x - b) <= 1e-10 * np.linalg.norm(b)
    dense = LinearSolver(reuse=False)
    dense.solve(base, b)
    dense.solve(near, b)
    assert dense.factorisations == 2 and dense.krylov_solves == 0


@pytest.mark.parametrize("name", ["atf", "gear_oil_75w90", "validation_roelands_huang"])
def test_temperature_table_in_one_evaluation_equals_row_by_row(name):
    lub = load_lubricant(name)
    state = lub.state(max(lub.t_min, 330.0))
    p = np.linspace(-1e8, 2.5e9, 57)
    rows = np.vstack([np.log(state.viscosity(p)) if r == 0.0 else lub.log_viscosity(p, state.temperature + r)
                      for r in THERMAL_RISES_K])
    assert np.allclose(state.temperature_table(p).log_eta, rows, rtol=1e-14, atol=1e-14)


def test_reused_steady_solution_equals_a_solve_from_scratch():
    lub = load_lubricant("atf")
    smooth = ContactCase.from_engineering(1.0, 20, 5, 0.2, 90)
    rough = [dataclasses.replace(smooth, rq1=q * 1e-6, rq2=q * 1e-6) for q in (0.2, 0.4)]
    steady._STEADY_CACHE.clear()
    fresh = [solve_contact(case, lub, "fast", "isothermal") for case in rough]   # the second reuses the first's
    steady._STEADY_CACHE.clear()
    alone = solve_contact(rough[1], lub, "fast", "isothermal")                    # the same contact from scratch
    for key in ("mu", "h_min", "h_central", "p_max"):
        assert getattr(fresh[1], key) == getattr(alone, key), key
    steady._STEADY_CACHE.clear()
    first = solve_contact(smooth, lub, "fast")
    second = solve_contact(smooth, lub, "fast")
    assert second.extra["continuation"]["reused"] and "reused" not in first.extra["continuation"]
    assert second.mu == first.mu and np.array_equal(second.pressure, first.pressure)


def test_neighbour_warm_start_converges_to_the_cold_solution():
    """Temperatures of one contact solved in a row (a factorial's fast axis) with neighbour warm starts: each after
    the first starts from its predecessor and reaches the cold-start solution within the level's Newton tolerances
    (relative 10 × tol_step on the outputs, as tests/ehl_dataset/test_stage1_reference.py)."""
    lub = load_lubricant("atf")
    lvl = get_level("standard")
    cases = [ContactCase.from_engineering(1.0, 10, 20, 0.1, t) for t in (50, 75, 100)]
    cold = []
    for case in cases:
        steady._STEADY_CACHE.clear()
        cold.append(solve_contact(case, lub, "standard", model="smooth"))
    steady._STEADY_CACHE.clear()
    with steady.neighbour_warm_starts():
        warm = [solve_contact(case, lub, "standard", model="smooth") for case in cases]
    started = [w.extra["continuation"].get("warm_start") for w in warm]
    assert started[0] is None and all(s is not None and s["converged"] for s in started[1:])
    for w, c in zip(warm, cold):
        assert w.converged and c.converged
        for key in ("mu", "h_min", "h_central", "p_max"):
            assert getattr(w, key) == pytest.approx(getattr(c, key), rel=10 * lvl.tol_step), key
    assert sum(w.iterations for w in warm[1:]) < sum(c.iterations for c in cold[1:])


def test_a_light_load_continuation_takes_a_grid_with_enough_nodes(monkeypatch):
    """75W90 at 0.5 GPa, 10 mm, 20 m/s, SR 0.7, 50 °C (λ̄ 3.7: a six-stage load continuation) at `fast`: the grid
    COARSENING times coarser than the level's has 37 nodes, on which that continuation stalls (and the level's grid
    from scratch does not converge either); the solve takes the FALLBACK_COARSENING grid instead and converges to the
    solution it gives when that is the only continuation grid, and within 0.1 % of μ at `standard`."""
    lub = load_lubricant("gear_oil_75w90")
    case = ContactCase(5e8, 0.01, 20.0, 0.7, 323.15, 0.0, 0.0)
    assert steady.steady_grid(get_level("fast"), steady.COARSENING,
                              h_c=10.0).size < steady.COARSE_MIN_NODES  # h_c large: the level's own spacing
    steady._STEADY_CACHE.clear()
    result = solve_contact(case, lub, "fast", "auto", model="smooth")
    route = result.extra["continuation"]
    assert result.converged and route["coarse"]["nodes"] >= steady.COARSE_MIN_NODES and "fine_from_scratch" not in route
    steady._STEADY_CACHE.clear()
    monkeypatch.setattr(steady, "COARSENING", steady.FALLBACK_COARSENING)
    alone = solve_contact(case, lub, "fast", "auto", model="smooth")
    assert result.mu == alone.mu
    steady._STEADY_CACHE.clear()
    assert result.mu == pytest.approx(solve_contact(case, lub, "standard", "auto", model="smooth").mu, rel=1e-3)
