"""The face flux of the finite-volume Reynolds discretisation (ehl_dataset.discretisation.reynolds.face_flux):
exact Newton derivatives for the arithmetic and harmonic face means of ε. (The patch-closure tests of the transient
mixed solver went with it at ehl-2026.11-15.)"""

import numpy as np
import pytest

from ehl_dataset.discretisation.deflection import influence_matrix
from ehl_dataset.discretisation.reynolds import face_flux
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solvers.newton import ReynoldsProblem


def _problem(compressible: bool):
    """A 61-node open-film state with a rough-looking gap and the squeeze term on."""
    rng = np.random.default_rng(3)
    x = np.linspace(-2.5, 1.5, 61)
    state = load_lubricant("atf").state(348.15)
    problem = ReynoldsProblem(x=x, kmat=influence_matrix(x), gap=0.5 * x**2 + 0.002 * rng.standard_normal(61),
                              lam=1e-3, p_h=1e9, state=state, compressible=compressible, shear=1e-4)
    problem.squeeze = problem.weights / 0.05
    problem.m_old = 0.01 + 0.02 * rng.random(61)
    p = np.clip(np.sqrt(np.clip(1 - x**2, 0, None)) + 0.1 * rng.standard_normal(61), 0.0, None)
    p[0] = p[-1] = 0.0
    return problem, p, 0.02


@pytest.mark.parametrize("compressible", [True, False])
def test_global_mass_balance_telescopes(compressible):
    """Conservation law: summed over the interior rows, the residuals equal the boundary flux difference minus the
    storage change of every interior node, so at a solution what enters the domain stays in it or leaves it."""
    problem, p, h0 = _problem(compressible)
    h = problem.film(p, h0)
    res, _, _, (m, m_p, m_h) = problem.residual(p, h)
    eps, eps_p, eps_h, *_ = problem.fluid(p, h)
    order, pois = problem.face_order(), problem.face_poiseuille()
    n = problem.x.size
    q_first = face_flux(problem.x, p, eps, eps_p, eps_h, m, m_p, m_h, 0, order[0], pois[0])[0]
    q_last = face_flux(problem.x, p, eps, eps_p, eps_h, m, m_p, m_h, n - 2, order[n - 2], pois[n - 2])[0]
    storage = problem.squeeze[1:-1] * (m[1:-1] - problem.m_old[1:-1])
    expected = q_last - q_first - storage.sum()
    assert res[1:-1].sum() == pytest.approx(expected, rel=1e-12, abs=1e-12 * np.abs(res).max())


@pytest.mark.parametrize("harmonic", [False, True])
def test_face_flux_derivatives_match_finite_differences(harmonic):
    """The face flux's partial derivatives (arithmetic and harmonic face means of ε) equal central differences."""
    problem, p, h0 = _problem(False)
    h = problem.film(p, h0)
    k = 28
    eps, eps_p, eps_h, m, m_p, m_h = problem.fluid(p, h)
    exact = face_flux(problem.x, p, eps, eps_p, eps_h, m, m_p, m_h, k, 1.0, 1.0, harmonic)
    step = 1e-7
    for o, node in enumerate((k - 1, k, k + 1)):
        values = []
        for sign in (1.0, -1.0):
            pp = p.copy()
            pp[node] += sign * step
            f = problem.fluid(pp, h)
            values.append(face_flux(problem.x, pp, *f, k, 1.0, 1.0, harmonic)[0])
        fd = (values[0] - values[1]) / (2 * step)
        assert fd == pytest.approx(exact[1 + o], rel=1e-5, abs=1e-9 * abs(exact[2]))
