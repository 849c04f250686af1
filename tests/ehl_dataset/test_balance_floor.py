"""The global lubricant balance of the deterministic model's discrete equations (docs/explanation/mixed-regime.md,
"Mass balance"): every interior face flux enters two mass rows with opposite signs, so the sum of the mass rows is
the inlet flux minus the outflow minus the time terms, for any state (a conservation law of the finite-volume
scheme, not a property of the solution). validation/deterministic_balance_floor.py measures the balance's
double-precision floor on that identity."""

import math

import numpy as np
import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solvers.deterministic import MixedProblem
from ehl_dataset.solvers.steady import ContactScales

CASE = ContactCase.from_engineering(1.0, 10, 5, 0.3, 90)
ATF = load_lubricant("atf")


@pytest.fixture(scope="module")
def floor_script(load_benchmark):
    return load_benchmark("deterministic_balance_floor")


def _state(problem, x, periodic):
    n = x.size
    pf = 0.6 + 0.1 * np.sin(2 * math.pi * x / 0.5) if periodic else 0.9 * np.sqrt(np.clip(1 - x**2, 0, None))
    th = np.ones(n)
    if not periodic:
        pf[0] = pf[-1] = 0.0
        th[-12:] = np.linspace(0.9, 0.4, 12)  # a cavitated outlet
        pf[-12:] = 0.0
    pc = np.zeros(n)
    pc[n // 2:n // 2 + 2] = (0.2, 0.4)  # a contact
    return problem.pack(pf, th, pc, 0.05 if periodic else -0.3)


@pytest.mark.parametrize("periodic", [False, True])
@pytest.mark.parametrize("couette_flux", ["minmod", "linear"])
def test_the_mass_rows_sum_to_inlet_flux_minus_outflow_minus_time_terms(floor_script, periodic, couette_flux):
    """Σ mass rows = −q_inlet − outflow − Σ time terms (all of them for a periodic window, which has no boundary),
    to the rounding of the rows' own terms, on a state with pressurised, cavitated and contact nodes and a BDF2
    step."""
    state = ATF.state(CASE.temperature)
    scales = ContactScales.of(CASE, state)
    n = 64
    x = np.arange(n) * (0.5 / n) if periodic else np.linspace(-2.5, 1.5, n)
    problem = MixedProblem(x, scales, state, 5e-9 / scales.film_scale, 3.0, band=6, couette_flux=couette_flux,
                           mean_pressure=0.6 if periodic else None)
    problem.m_ref = 0.01
    z = _state(problem, x, periodic)
    gap = 0.01 * np.cos(6 * math.pi * x / 0.5) + (0.0 if periodic else 0.5 * x**2)
    h = problem.film(z, gap)
    m_now = problem.content(z, h)
    storage = problem.storage(0.25 * problem.dx, 1.0, 0.97 * m_now, 0.95 * m_now)
    res = problem.evaluate(z, gap, storage)[0]
    rows = float(np.sum(res[problem.mass_rows])) / problem.m_ref
    telescoped = floor_script.telescoped_balance(problem, z, gap, storage)
    largest_term = float(np.max(np.abs(storage[0] * m_now))) / problem.m_ref
    assert abs(rows) > 1e3 * 1e-16 * largest_term * n  # a state off balance: the identity is not 0 = 0
    assert abs(rows - telescoped) <= 1e-16 * n * max(largest_term, 1.0) * 10

