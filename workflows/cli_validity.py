"""The validity verdict of a command's result: ``"valid"`` and ``"validity"`` in the output, the exit code, and
``--strict`` (refuse instead of flag).

A command collects its checks (:mod:`efficiency.validity`, :mod:`surrogate.validity`: each ``{check, valid, value,
limit, unit, reason}``) and calls :func:`finish`, which adds ``valid`` (all checks pass) and ``validity`` (the
checks) to the payload, prints it and returns 0, or 1 when a check fails or the computation did not converge
(:mod:`workflows.exit_codes`). With ``--strict`` a result outside the validity is not printed: the command is
refused (exit 2) with one line naming the option that put it there.
"""

from __future__ import annotations

from typing import Callable

from ehl_dataset.validation import InputError

from . import exit_codes
from .cli_output import emit


def add_validity_options(parser, *, clip: bool = True) -> None:
    """``--strict`` (and, for commands that evaluate a fitted surrogate, ``--no-clip``)."""
    group = parser.add_argument_group("validity")
    group.add_argument("--strict", action="store_true",
                       help="refuse (exit 2) a result outside the model's validity instead of printing it flagged "
                            "\"valid\": false (exit 1)")
    if clip:
        group.add_argument("--no-clip", action="store_true",
                           help="evaluate a coefficient file's regression outside its fitted ranges (extrapolate) "
                                "instead of clipping its inputs to them; such a result is flagged not valid")


def finish(payload: dict, checks: list[dict], args, human: Callable[[dict], str], *, converged: bool = True,
           options: dict[str, str] | None = None) -> int:
    """Add the verdict to ``payload``, print it (``--json`` or ``human``) and return the exit code; with
    ``args.strict`` raise :class:`InputError` instead when a check fails. ``options``: check name → the option
    to name in that refusal (e.g. ``{"contact_pressure": "torque-nm"}``)."""
    failed = [c for c in checks if not c["valid"]]
    payload["valid"] = not failed
    payload["validity"] = checks
    if failed and getattr(args, "strict", False):
        first = failed[0]
        option = (options or {}).get(first["check"], "input")
        dest = option.replace("-", "_")
        raise InputError(option, getattr(args, dest, None),
                         "a value inside the model's validity (--strict)", first["reason"])
    emit(payload, args.json, lambda p: _with_verdict(human(p), failed))
    return exit_codes.OK if (converged and not failed) else exit_codes.NOT_VALID


def _with_verdict(text: str, failed: list[dict]) -> str:
    if not failed:
        return text
    lines = [text] + [f"NOT VALID: {c['reason']}" for c in failed]
    lines.append("valid: no (exit 1; --strict refuses such a result)")
    return "\n".join(lines)
