"""Brent's method of :mod:`ehl_dataset.model.scalar_root` (the planner's flash-temperature root, without importing
:mod:`scipy.optimize` on the cold path).

* roots known in closed form are found within the stated tolerance |x − x*| ≤ xtol + rtol |x*| (Brent 1973, ch. 4:
  the returned point lies within the tolerance of a sign change);
* the step rules are those of :func:`scipy.optimize.brentq`: the same bracket and tolerances give the same root, to
  the last bit, and the same number of steps;
* a bracket without a sign change, a NaN value and a step budget that runs out are reported, not hidden.
"""

from __future__ import annotations

import math

import pytest

from ehl_dataset.model.scalar_root import brent_root
from ehl_dataset.validation import InputError, SolverError

# f, bracket, exact root
CASES = [
    (lambda x: x**3 - 2.0, (0.0, 2.0), 2.0 ** (1.0 / 3.0)),
    (lambda x: math.cos(x) - x, (0.0, 1.0), 0.7390851332151607),   # the Dottie number
    (lambda x: math.exp(x) - 10.0, (-5.0, 5.0), math.log(10.0)),
    (lambda x: (x - 1e-3) * (1.0 + x * x), (-1.0, 3.0), 1e-3),
    (lambda x: math.tanh(50.0 * (x - 0.3)), (0.0, 1.0), 0.3),       # steep: the step rules fall back to bisection
    (lambda x: x - 1e6, (0.0, 1e7), 1e6),
    (lambda x: math.atan(x - 7.0) + 1e-3 * (x - 7.0) ** 3, (-100.0, 50.0), 7.0),
]
TOLERANCES = [(2e-12, 8.881784197001252e-16), (1e-9, 1e-12), (1e-4, 1e-6)]


@pytest.mark.parametrize("xtol, rtol", TOLERANCES)
@pytest.mark.parametrize("index", range(len(CASES)))
def test_known_roots_within_tolerance(index, xtol, rtol):
    f, (a, b), exact = CASES[index]
    found = brent_root(f, a, b, xtol=xtol, rtol=rtol)
    assert found.converged
    assert abs(found.root - exact) <= xtol + rtol * abs(exact) + 4.0 * math.ulp(exact)


@pytest.mark.parametrize("xtol, rtol", TOLERANCES)
@pytest.mark.parametrize("index", range(len(CASES)))
def test_same_root_and_steps_as_scipy_brentq(index, xtol, rtol):
    from scipy.optimize import brentq

    f, (a, b), _ = CASES[index]
    root, info = brentq(f, a, b, xtol=xtol, rtol=rtol, full_output=True)
    found = brent_root(f, a, b, xtol=xtol, rtol=rtol)
    assert found.root == root
    assert (found.iterations, found.function_calls) == (info.iterations, info.function_calls)
    reversed_bracket = brentq(f, b, a, xtol=xtol, rtol=rtol)
    assert brent_root(f, b, a, xtol=xtol, rtol=rtol).root == reversed_bracket


def test_root_at_an_end_of_the_bracket():
    assert brent_root(lambda x: x - 1.0, 1.0, 3.0) == (1.0, True, 0, 2)
    assert brent_root(lambda x: x - 3.0, 1.0, 3.0) == (3.0, True, 0, 2)


def test_bad_bracket_nan_and_exhausted_budget_are_reported():
    with pytest.raises(InputError, match="bracket"):
        brent_root(lambda x: x * x + 1.0, -1.0, 1.0)
    with pytest.raises(InputError, match="xtol"):
        brent_root(lambda x: x, -1.0, 1.0, xtol=0.0)
    with pytest.raises(InputError, match="rtol"):
        brent_root(lambda x: x, -1.0, 1.0, rtol=1e-16)
    with pytest.raises(SolverError, match="NaN"):
        brent_root(lambda x: math.nan if x > 0.2 else x - 0.5, 0.0, 1.0)
    short = brent_root(lambda x: math.tanh(50.0 * (x - 0.3)), 0.0, 1.0, max_iterations=3)
    assert not short.converged and short.iterations == 3
