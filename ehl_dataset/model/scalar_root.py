"""One scalar root in a sign-changing bracket by Brent's method, without importing :mod:`scipy.optimize`.

The planner's thermal estimate (:func:`ehl_dataset.model.thermal.centre_estimate`) solves one such root per contact;
importing :mod:`scipy.optimize` for it costs about a fifth of a cold ``gearloss contact solve``. The iteration is
Brent's (R. P. Brent, *Algorithms for Minimization without Derivatives*, Prentice-Hall 1973, ch. 4): inverse
quadratic (or, after the bracket flips, linear) interpolation, accepted only when the step is short compared with
the previous one and the bisection step, else bisection; a step never shorter than the tolerance. The step rules
and the stopping test |b − c|/2 < (xtol + rtol |b|)/2 are those of :func:`scipy.optimize.brentq`, so both return
the same root for the same bracket and tolerances (``tests/ehl_dataset/test_scalar_root.py``).
"""

from __future__ import annotations

import math
from typing import Callable, NamedTuple

from ..validation import InputError, SolverError

__all__ = ["BracketedRoot", "brent_root"]


class BracketedRoot(NamedTuple):
    """Result of :func:`brent_root`.

    Parameters
    ----------
    root : float
        The last estimate of the root [-].
    converged : bool
        True when the bracket shrank below the tolerance or f vanished [-].
    iterations : int
        Interpolation or bisection steps taken [-].
    function_calls : int
        Evaluations of f [-].
    """

    root: float
    converged: bool
    iterations: int
    function_calls: int


def brent_root(f: Callable[[float], float], a: float, b: float, xtol: float = 2e-12, rtol: float = 8.9e-16,
               max_iterations: int = 100) -> BracketedRoot:
    """The root of ``f`` in the bracket [a, b] (f(a) and f(b) of opposite signs) by Brent's method.

    Parameters
    ----------
    f : callable
        Continuous function of one float, returning a float [-].
    a : float
        One end of the bracket [-].
    b : float
        The other end of the bracket [-].
    xtol : float
        Absolute tolerance of the root, > 0 [-].
    rtol : float
        Relative tolerance of the root, ≥ 4 machine epsilons [-].
    max_iterations : int
        Steps allowed before giving up (the result then says ``converged=False``) [-].

    Returns
    -------
    BracketedRoot
        The root, whether it converged, the steps and function calls. f(a) and f(b) of the same sign raise
        :class:`~ehl_dataset.validation.InputError`, a NaN value of f :class:`~ehl_dataset.validation.SolverError`.
    """
    if not xtol > 0.0:
        raise InputError("xtol", xtol, "> 0")
    if not rtol >= 4.0 * 2.220446049250313e-16:
        raise InputError("rtol", rtol, ">= 4 machine epsilons (8.9e-16)")

    def value(x: float) -> float:
        y = float(f(x))
        if math.isnan(y):
            raise SolverError(f"brent_root: f({x!r}) is NaN; the root cannot be bracketed further")
        return y

    # b: the current estimate; c: the other end of the bracket ("contrapoint"); a: the previous estimate
    f_a, f_b = value(a), value(b)
    calls = 2
    if f_a * f_b > 0.0:
        raise InputError("bracket", f"[{a!r}, {b!r}] with f = {f_a!r}, {f_b!r}", "an interval where f changes sign")
    if f_a == 0.0:
        return BracketedRoot(a, True, 0, calls)
    if f_b == 0.0:
        return BracketedRoot(b, True, 0, calls)
    c = f_c = 0.0
    step_before = step = 0.0
    for iteration in range(1, max_iterations + 1):
        if f_a * f_b < 0.0:  # the previous estimate and the current one bracket the root: restart the bracket
            c, f_c = a, f_a
            step_before = step = b - a
        if abs(f_c) < abs(f_b):  # keep the best estimate in b
            a, b, c = b, c, b
            f_a, f_b, f_c = f_b, f_c, f_b
        tolerance = (xtol + rtol * abs(b)) / 2.0
        half = (c - b) / 2.0
        if f_b == 0.0 or abs(half) < tolerance:
            return BracketedRoot(b, True, iteration, calls)
        if abs(step_before) > tolerance and abs(f_b) < abs(f_a):
            if a == c:  # two points: secant
                trial = -f_b * (b - a) / (f_b - f_a)
            else:  # three points: inverse quadratic interpolation
                slope_a = (f_a - f_b) / (a - b)
                slope_c = (f_c - f_b) / (c - b)
                trial = -f_b * (f_c * slope_c - f_a * slope_a) / (slope_c * slope_a * (f_c - f_a))
            if 2.0 * abs(trial) < min(abs(step_before), 3.0 * abs(half) - tolerance):
                step_before, step = step, trial
            else:
                step_before = step = half
        else:
            step_before = step = half
        a, f_a = b, f_b
        b += step if abs(step) > tolerance else (tolerance if half > 0.0 else -tolerance)
        f_b = value(b)
        calls += 1
    return BracketedRoot(b, False, max_iterations, calls)
