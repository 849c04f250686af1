"""Input validation shared by all stages: one clear error naming the parameter, the value and the accepted range."""

from __future__ import annotations

import math
import numbers
from typing import Any


class InputError(ValueError):
    """Bad user input. ``str(err)`` is a single line: parameter, value, accepted range."""

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
    """Return ``float(value)`` or raise :class:`InputError` if it is not a finite number."""
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
    """Check ``low <= value <= high`` (bounds inclusive or not) and return the value as float."""
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
