"""Output of the ``gearloss`` commands: one JSON object (``--json``, SI units) or human-readable text."""

from __future__ import annotations

import json
from typing import Any, Callable


def emit(payload: dict[str, Any], as_json: bool, human: Callable[[dict[str, Any]], str]) -> None:
    """Print ``payload`` as a single JSON object (``--json``) or as human-readable text."""
    if as_json:
        print(json.dumps(payload, default=_json_default, allow_nan=True))
    else:
        print(human(payload))


def _json_default(value: Any):
    import numpy as np  # here, not at the top: ``gearloss --help`` stays fast

    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"not JSON serialisable: {type(value).__name__}")


def fail(code: int, message: str, as_json: bool, *, prog: str = "gearloss", **fields) -> int:
    """Report an error: one line on stderr (``PROG: error: MESSAGE`` for bad input, ``PROG: MESSAGE`` otherwise)
    and, with ``--json``, the JSON object of :func:`workflows.exit_codes.error_payload` on stdout. Returns ``code``
    (the exit status, :mod:`workflows.exit_codes`)."""
    import sys

    from .exit_codes import BAD_INPUT, error_payload

    print(f"{prog}: {'error: ' if code == BAD_INPUT else ''}{message}", file=sys.stderr, flush=True)
    if as_json:
        print(json.dumps(error_payload(code, message, **fields), default=_safe_default), flush=True)
    return code


def _safe_default(value: Any):
    if hasattr(value, "as_json"):
        return value.as_json()
    try:
        return _json_default(value)
    except TypeError:
        return repr(value)
