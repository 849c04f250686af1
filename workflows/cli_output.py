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
