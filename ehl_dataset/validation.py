"""Input validation shared by all stages: one clear error naming the parameter, the value and the accepted range."""

from __future__ import annotations

import math
import numbers
from typing import Any


class InputError(ValueError):
    """Bad user input; ``str(err)`` is a single line naming the parameter, the value and the accepted range.

    Parameters
    ----------
    parameter : str
        Name of the bad parameter [-].
    value : object
        The value given [-].
    accepted : str
        The accepted range or choices, with the unit [-].
    detail : str
        Further detail, e.g. the index of the first bad element [-].
    """

    def __init__(self, parameter: str, value: Any, accepted: str, detail: str = ""):
        self.parameter = parameter
        self.value = value
        self.accepted = accepted
        message = f"invalid {parameter}={value!r}: accepted {accepted}"
        if detail:
            message += f" ({detail})"
        super().__init__(message)


class SolverError(RuntimeError):
    """A numerical problem that cannot be solved (as opposed to bad input)."""


def check_finite(name: str, value: float) -> float:
    """Check that a value is a finite number.

    Parameters
    ----------
    name : str
        Parameter name for the error message [-].
    value : float
        The value [-].

    Returns
    -------
    float
        ``float(value)``.

    Raises
    ------
    InputError
        When it is not a finite number.
    """
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InputError(name, value, "a finite number") from None
    if not math.isfinite(number):
        raise InputError(name, value, "a finite number")
    return number


def check_range(
    name: str,
    value: float,
    low: float = -math.inf,
    high: float = math.inf,
    *,
    low_inclusive: bool = True,
    high_inclusive: bool = True,
    unit: str = "",
) -> float:
    """Check ``low <= value <= high`` (bounds inclusive or not) and return the value as float.

    Parameters
    ----------
    name : str
        Parameter name for the error message [-].
    value : float
        The value, in ``unit`` [-].
    low : float
        Lower bound, in ``unit`` [-].
    high : float
        Upper bound, in ``unit`` [-].
    low_inclusive : bool
        Whether ``low`` itself is accepted [-].
    high_inclusive : bool
        Whether ``high`` itself is accepted [-].
    unit : str
        Unit named in the error message [-].

    Returns
    -------
    float
        The value.

    Raises
    ------
    InputError
        Naming the parameter, the value and the accepted range.
    """
    number = check_finite(name, value)
    too_low = number < low if low_inclusive else number <= low
    too_high = number > high if high_inclusive else number >= high
    if too_low or too_high:
        left = "[" if low_inclusive else "("
        right = "]" if high_inclusive else ")"
        suffix = f" {unit}" if unit else ""
        raise InputError(name, value, f"{left}{low:g}, {high:g}{right}{suffix}")
    return number


def check_time_limit(value) -> float | None:
    """A wall-time budget [s]: None (no limit) or a finite number > 0 (not a bool), returned as float."""
    if value is None:
        return None
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(value) or value <= 0:
        raise InputError("time_limit_s", value, "a positive number of seconds, or None")
    return float(value)
