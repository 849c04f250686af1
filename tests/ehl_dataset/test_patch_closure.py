"""The closure of the unified Reynolds equation across asperity-contact patches (ehl_dataset.discretisation.reynolds
``reroute_patch_fluxes``, used by the transient mixed solver): a conservation law and exact Newton derivatives."""

import numpy as np
import pytest

from ehl_dataset.discretisation.deflection import influence_matrix
from ehl_dataset.discretisation.reynolds import face_flux
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solvers.newton import ReynoldsProblem


def _problem(compressible: bool, couette_faces: bool = False):
    """A 61-node rough-looking state with two closed patches (nodes 20–23 and 35), squeeze on, exact numbers
    chosen so that every branch (closed, faded, open film) is present."""
    rng = np.random.default_rng(3)
    x = np.linspace(-2.5, 1.5, 61)
    state = load_lubricant("atf").state(348.15)
    problem = ReynoldsProblem(x=x, kmat=influence_matrix(x), gap=0.5 * x**2 + 0.002 * rng.standard_normal(61),
                              lam=1e-3, p_h=1e9, state=state, compressible=compressible, shear=1e-4)
    problem.h_closed = 1e-4
    problem.p_cap = 6.8
    closed = np.zeros(61, dtype=bool)
    closed[20:24] = True
    closed[35] = True
    problem.closed = closed
    problem.closure = "patch"
    problem.contact_faces_couette = couette_faces
    problem.squeeze = problem.weights / 0.05
    problem.m_old = 0.01 + 0.02 * rng.random(61)
    p = np.clip(np.sqrt(np.clip(1 - x**2, 0, None)) + 0.1 * rng.standard_normal(61), 0.0, None)
    p[0] = p[-1] = 0.0
    return problem, p, -0.02


def test_patches_are_found_with_open_nodes_on_both_sides():
    problem, _, _ = _problem(True)
    starts, ends = problem.patches()
    assert starts.tolist() == [20, 35] and ends.tolist() == [23, 35]
    pois = problem.face_poiseuille()
    assert pois.sum() == pois.size  # the unified equation everywhere by default
    problem.contact_faces_couette = True
    pois = problem.face_poiseuille()
    assert np.nonzero(pois == 0.0)[0].tolist() == [19, 20, 21, 22, 23, 34, 35]


@pytest.mark.parametrize("couette_faces", [False, True])
@pytest.mark.parametrize("compressible", [True, False])
def test_global_mass_balance_telescopes_across_patches(compressible, couette_faces):
    """Conservation law: summed over the open (Reynolds) rows, the residuals equal the boundary flux difference
    minus the storage change of every interior node, closed ones included — so at a solution (open rows zero)
    what enters the domain either stays in it or leaves it; nothing is created or lost at a contact."""
    problem, p, h0 = _problem(compressible, couette_faces)
    h = problem.film(p, h0)
    res, _, _, (m, m_p, m_h), links = problem.residual(p, h)
    assert links is not None
    eps, eps_p, eps_h, *_ = problem.fluid(p, h)
    order, pois = problem.face_order(), problem.face_poiseuille()
    q_first = face_flux(problem.x, p, eps, eps_p, eps_h, m, m_p, m_h, 0, order[0], pois[0])[0]
    n = problem.x.size
    q_last = face_flux(problem.x, p, eps, eps_p, eps_h, m, m_p, m_h, n - 2, order[n - 2], pois[n - 2])[0]
    open_rows = ~problem.closed[1:-1]
    storage = problem.squeeze[1:-1] * (m[1:-1] - problem.m_old[1:-1])
    expected = q_last - q_first - storage.sum()
    assert res[1:-1][open_rows].sum() == pytest.approx(expected, rel=1e-12, abs=1e-12 * np.abs(res).max())


@pytest.mark.parametrize("couette_faces", [False, True])
def test_newton_jacobian_of_open_rows_matches_finite_differences(couette_faces):
    """The rerouted fluxes' out-of-band derivatives (reynolds.add_links) make the Jacobian of the open rows exact
    (incompressible, so that the storage of closed nodes, ρ̄H_c, has no pressure derivative)."""
    problem, p, h0 = _problem(False, couette_faces)
    h = problem.film(p, h0)
    res, dp, dh, _, links = problem.residual(p, h)
    jac = problem.jacobian(dp, dh, links)
    open_rows = np.nonzero(~problem.closed[1:-1])[0]
    step = 1e-7
    for col in (15, 19, 20, 24, 30, 34, 36, 40):
        pp = p.copy()
        pp[col + 1] += step
        res_plus = problem.residual(pp, problem.film(pp, h0))[0]
        pm = p.copy()
        pm[col + 1] -= step
        res_minus = problem.residual(pm, problem.film(pm, h0))[0]
        fd = (res_plus - res_minus)[1:-1] / (2 * step)
        scale = np.abs(jac[open_rows]).max()
        assert np.max(np.abs(fd[open_rows] - jac[open_rows, col])) <= 1e-6 * scale, col


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
