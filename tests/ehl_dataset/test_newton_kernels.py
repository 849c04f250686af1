"""The compiled per-iteration arithmetic of the steady Newton solve equals its array form (the same formulas:
paper Eq. 1–6, Fischer–Burmeister complementarity) to round-off, for every viscosity–pressure law, below p = 0, where
the viscosity exponent is clipped, with and without compressibility and shear thinning."""

from dataclasses import replace

import numpy as np
import pytest

from ehl_dataset.discretisation.deflection import influence_matrix
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import ViscosityPressureLaw, load_lubricant
from ehl_dataset.solvers import newton, newton_kernels, steady
from ehl_dataset.solvers.levels import get_level
from ehl_dataset.solvers.newton import ReynoldsProblem


def _state(kind: str):
    state = load_lubricant("atf").state(363.15)
    if kind == "two_slope":
        return state
    law = state.law
    if kind == "barus":
        return replace(state, law=ViscosityPressureLaw("barus", law.eta0, law.alpha1))
    return replace(state, law=ViscosityPressureLaw("roelands", law.eta0, law.alpha1, z=0.6))


def _problem(kind: str, compressible: bool, shear: float) -> ReynoldsProblem:
    case = ContactCase.from_engineering(1.0, 20, 5, 0.2, 90)
    state = _state(kind)
    scales = steady.ContactScales.of(case, state)
    x = steady.steady_grid(get_level("fast"), h_c=steady.moes_h_c(case, state, scales))
    return ReynoldsProblem(x=x, kmat=influence_matrix(x), gap=0.5 * x**2, lam=scales.lam, p_h=case.p_h,
                           state=state, compressible=compressible, shear=shear)


def _pressures(x: np.ndarray) -> np.ndarray:
    """A Hertz-like pressure with negative values (wild iterates), the two-slope transition (0.4–0.6 GPa at
    p_h = 1 GPa) and values high enough to clip the viscosity exponent at 600."""
    p = np.sqrt(np.clip(1.0 - x**2, 0.0, None)) + 0.05 * np.sin(40.0 * x)
    p[::37] = 1e4  # ln(η/η0) > 600 at 10 TPa for every law here
    return p


@pytest.mark.parametrize("kind", ["two_slope", "barus", "roelands"])
@pytest.mark.parametrize("compressible", [True, False])
@pytest.mark.parametrize("shear", [0.0, 3.0])
def test_compiled_residual_equals_the_array_form(kind, compressible, shear):
    problem = _problem(kind, compressible, shear)
    assert problem.law is not None and problem.law[0] == newton_kernels.LAW_CODES[kind]
    p = _pressures(problem.x)
    assert (p < 0).any() and (p * problem.p_h > 6e8).any()
    h = problem.film(np.clip(p, 0.0, 3.0), 0.3)
    compiled = [problem.rheology(p, 0.7), problem.fluid(p, h, 0.7), problem.residual(p, h, 0.7)]
    assert np.any(compiled[0][0] == newton.EXPONENT_CAP) and np.any(compiled[0][1] == 0.0)
    problem.law = None  # the array form
    arrays = [problem.rheology(p, 0.7), problem.fluid(p, h, 0.7), problem.residual(p, h, 0.7)]
    flat = lambda parts: [np.asarray(a) for part in parts for a in (part if isinstance(part, tuple) else (part,))]
    for got, want in zip(flat(compiled[0] + compiled[1] + compiled[2][:3] + compiled[2][3]),
                         flat(arrays[0] + arrays[1] + arrays[2][:3] + arrays[2][3])):
        assert got.shape == want.shape
        assert np.allclose(got, want, rtol=1e-13, atol=1e-300 + 1e-13 * np.abs(want).max())


def test_compiled_complementarity_equals_the_array_form():
    problem = _problem("two_slope", True, 3.0)
    rng = np.random.default_rng(5)
    p = _pressures(problem.x)
    p[1:-1:5] = 0.0  # cavitated nodes with a = 0
    res = rng.standard_normal(problem.x.size) * 1e-2
    res[3] = 1e30  # a wild residual: the cancellation-free form
    kappa = rng.uniform(0.5, 2.0, problem.x.size - 2)
    phi, d_a, d_b, r_free, r_cav = newton_kernels.complementarity(p[1:-1], res, kappa, 0.25)
    want_phi, want_a, want_b = newton._complementarity(problem, p, res, kappa)
    assert np.allclose(phi, want_phi, rtol=1e-14, atol=1e-300)
    assert np.allclose(d_a, want_a, rtol=1e-14, atol=1e-300)
    assert np.allclose(d_b, want_b, rtol=1e-14, atol=1e-300)
    a, b = p[1:-1], -res[1:-1] * kappa
    pressurised = (a > b) & (a >= 0.0)
    assert pressurised.any() and (~pressurised).any()
    assert r_free == np.max(np.abs(res[1:-1][pressurised])) / 0.25
    assert r_cav == np.max(np.abs(want_phi[~pressurised]))


def test_an_unknown_state_takes_the_array_form():
    class Custom:  # a state of another kind: its own methods are evaluated
        law = None

    assert newton_kernels.law_parameters(Custom()) is None
    assert newton_kernels.law_parameters(_state("roelands"))[0] == newton_kernels.LAW_CODES["roelands"]


@pytest.mark.parametrize("conditions", [(2.0, 60, 15, 0.1, 75), (0.5, 5, 20, 0.7, 50)])
def test_compiled_newton_iteration_takes_the_array_forms_iterates(monkeypatch, conditions):
    """The compiled state and line search (newton_kernels.iteration_state, line_search) are the array form's
    arithmetic: the same Newton iterations and the same converged solution (to round-off) for a heavy contact and a
    light one (a load continuation with pseudo-transient steps) on the `standard` steady solve."""
    from ehl_dataset.solver import solve_contact

    case = ContactCase.from_engineering(*conditions)
    lubricant = load_lubricant("atf")
    steady._STEADY_CACHE.clear()
    compiled = solve_contact(case, lubricant, "standard", model="smooth")
    monkeypatch.setattr(ReynoldsProblem, "compiled_arguments", lambda self, homotopy: None)
    steady._STEADY_CACHE.clear()
    arrays = solve_contact(case, lubricant, "standard", model="smooth")
    steady._STEADY_CACHE.clear()
    assert compiled.converged and arrays.converged
    assert compiled.iterations == arrays.iterations
    assert compiled.extra["continuation"]["coarse"] == arrays.extra["continuation"]["coarse"]
    assert np.allclose(compiled.pressure, arrays.pressure, rtol=0.0, atol=1e-12 * case.p_h)
    for key in ("mu", "h_min", "h_central"):
        assert getattr(compiled, key) == pytest.approx(getattr(arrays, key), rel=1e-12), key


def test_a_problem_that_changes_its_equations_takes_the_array_form():
    class ShiftedFilm(ReynoldsProblem):  # a subclass with its own film equation: the kernels would not see it
        def film(self, p, h0):
            return super().film(p, h0) + 1e-3

    problem = _problem("two_slope", True, 0.0)
    assert problem.compiled_arguments(1.0) is not None
    problem.film_may_close = True
    assert problem.compiled_arguments(1.0) is None
    shifted = ShiftedFilm(x=problem.x, kmat=problem.kmat, gap=problem.gap, lam=problem.lam, p_h=problem.p_h,
                          state=problem.state, shear=problem.shear)
    assert shifted.law is not None and shifted.compiled_arguments(1.0) is None
