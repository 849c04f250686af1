"""The banded preconditioner of the deterministic mixed solver on grids shorter than its band.

A contact narrower than the roughness correlation length (a/β ≈ 0.5) gets about 20 nodes from the grid rule
Δx ≈ β/8, fewer than the 2w + 1 = 25 diagonals of the banded inverse kernel B ≈ K⁻¹ (w = 12). The band is then
only cut at the grid's ends, as it is near the ends of any grid: the preconditioner stays the banded LU of the same
approximation of the Newton matrix.
"""

import dataclasses

import numpy as np
import pytest
import scipy.linalg

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers.deterministic import MixedProblem, deterministic_options
from ehl_dataset.solvers.krylov import BandedPreconditioner, banded_product, gmres
from ehl_dataset.solvers.steady import ContactScales

ATF = load_lubricant("atf")


def _dense_band(stencil: np.ndarray, n: int) -> np.ndarray:
    """The N × N matrix with diagonals s[m + w], m = −w … w (the part of the band inside the grid)."""
    half = (stencil.size - 1) // 2
    column = np.zeros(n)
    row = np.zeros(n)
    column[: min(n, half + 1)] = stencil[half: half + min(n, half + 1)]
    row[: min(n, half + 1)] = stencil[half::-1][: min(n, half + 1)]
    return scipy.linalg.toeplitz(column, row)


@pytest.mark.parametrize("n", [1, 5, 20, 24, 25, 26, 60])
def test_banded_product_is_the_matrix_product_for_grids_shorter_and_longer_than_the_band(n):
    """out = S v with S the banded Toeplitz matrix restricted to the grid, for N below, at and above 2w + 1 = 25
    (an asymmetric stencil, so a reversed or shifted band would show)."""
    rng = np.random.default_rng(n)
    stencil = rng.standard_normal(25)
    values = rng.standard_normal(n)
    expected = _dense_band(stencil, n) @ values
    out = banded_product(values, stencil)
    assert out.shape == (n,)
    assert np.max(np.abs(out - expected)) <= 1e-13 * max(1.0, np.max(np.abs(expected)))


def _problem(n, periodic):
    case = ContactCase.from_engineering(1.0, 10, 5, 0.3, 90)
    state = ATF.state(case.temperature)
    scales = ContactScales.of(case, state)
    x = np.linspace(-1.5, 1.5, n)
    extra = {"mean_pressure": 0.6} if periodic else {}
    problem = MixedProblem(x, scales, state, h_b=5e-9 / scales.film_scale, p_yield=3.0, band=12, **extra)
    return problem, x


@pytest.mark.parametrize("periodic", [False, True])
def test_the_preconditioner_of_a_grid_shorter_than_its_band_solves_the_newton_system(periodic):
    """N = 15 nodes, band 2·12 + 1 = 25: the preconditioner builds, reproduces the load row of J exactly (it
    eliminates ΔH0 with the exact load row Σ w_j (ΔP_f + ΔP_c)_j), and right-preconditioned GMRES reaches 1e-10 on
    the true residual ‖b − J x‖ of the Newton system at a state with pressurised, cavitated and contact nodes."""
    problem, x = _problem(15, periodic)
    assert problem.binv.size > x.size
    n = x.size
    pf = 0.9 * np.sqrt(np.clip(1 - x**2, 0, None))
    th = np.ones(n)
    th[-4:] = np.linspace(0.9, 0.5, 4)
    pf[-4:] = 0.0
    pc = np.zeros(n)
    pc[6:9] = (0.2, 0.5, 0.8)
    z = problem.pack(pf, th, pc, -0.3)
    gap = 0.5 * x**2
    storage = problem.storage(0.05, 0.0, np.full(n, 0.01), None)
    res, _, jac, dfilm = problem.evaluate(z, gap, storage)
    pre = BandedPreconditioner(jac, dfilm, problem.binv, problem.weights, problem.periodic)
    r = np.random.default_rng(5).standard_normal(3 * n + 1)
    out = pre.apply(r)
    assert out.shape == (3 * n + 1,) and np.all(np.isfinite(out))
    if not periodic:  # the periodic load row fixes the mean pressure instead (its own elimination)
        load = problem.jacobian_product(jac, dfilm, out)[-1]
        assert load == pytest.approx(r[-1], rel=1e-12, abs=1e-12 * np.max(np.abs(r)))
    step, its, _ = gmres(lambda v: problem.jacobian_product(jac, dfilm, v), pre.apply, -res, 1e-10, 80)
    true = np.linalg.norm(problem.jacobian_product(jac, dfilm, step) + res) / np.linalg.norm(res)
    assert true < 1e-8
    assert its < 3 * n + 1  # fewer iterations than unknowns: the preconditioner does the work, not GMRES alone


def test_a_contact_narrower_than_the_correlation_length_solves_deterministically_at_fast():
    """a/β ≈ 0.5 (36.9 MPa, R 12.4 mm, 10 m/s, SR 0.054, 90 °C, Rq 0.4 µm each) at ``fast``: the grid rule gives
    20 nodes, fewer than the 25 diagonals of the level's band (building the preconditioner raised ValueError). The
    preconditioner only steers GMRES, so the run gives the friction of a run whose band (2·6 + 1 = 13) fits the grid
    to the Newton tolerance (1e-10; compared at 1e-7 relative), with the load balanced at every step."""
    case = ContactCase(36856271.7, 0.0124162, 9.987, 0.054, 363.15, 4e-7, 4e-7)
    short = dict(ramp_passes=0.2, startup_passes=0.1, min_average_passes=0.2, max_passes=0.4)
    options = dataclasses.replace(deterministic_options("fast"), **short)
    baseline = baseline_profile()  # the β of a/β ≈ 0.5
    wide = solve_contact(case, ATF, level="fast", model="deterministic", deterministic=options, roughness=baseline)
    narrow = solve_contact(case, ATF, level="fast", model="deterministic",
                           deterministic=dataclasses.replace(options, band=6), roughness=baseline)
    assert wide.converged, wide.message
    assert wide.x.size < 2 * options.band + 1 and narrow.x.size == wide.x.size
    assert np.isfinite(wide.mu) and wide.mu > 0.0
    assert wide.mu == pytest.approx(narrow.mu, rel=1e-7)
    assert wide.residuals["max_load_error"] <= 1e-10
