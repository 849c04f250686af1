"""The ``gearloss`` command line: one console script with sub-command groups.

Each group lives in its own module (``cli_contact``, ``cli_dataset``, ``cli_surrogate``, ``cli_gear``, ...) that
exposes ``register(subparsers)``; heavy imports happen inside the handlers so ``gearloss --help`` stays fast.
Bad input raises :class:`ehl_dataset.validation.InputError`, which is printed as one line with exit status 2.
"""

from __future__ import annotations

import argparse
import importlib
import json
import sys
from typing import Any, Callable

from ehl_dataset.validation import InputError, SolverError

GROUP_MODULES = ["cli_contact", "cli_dataset", "cli_surrogate", "cli_gear", "cli_pipeline", "cli_accuracy"]


def emit(payload: dict[str, Any], as_json: bool, human: Callable[[dict[str, Any]], str]) -> None:
    """Print ``payload`` as a single JSON object (``--json``) or as human-readable text."""
    if as_json:
        print(json.dumps(payload, default=_json_default, allow_nan=True))
    else:
        print(human(payload))


def _json_default(value: Any):
    try:
        import numpy as np

        if isinstance(value, np.generic):
            return value.item()
        if isinstance(value, np.ndarray):
            return value.tolist()
    except ImportError:  # pragma: no cover
        pass
    raise TypeError(f"not JSON serialisable: {type(value).__name__}")


def register_modules(subparsers, names) -> None:
    """Let each ``workflows.<name>`` module add its sub-commands (``register(subparsers)``); a module that is not
    there is skipped, an import error inside one is raised."""
    for name in names:
        try:
            module = importlib.import_module(f"workflows.{name}")
        except ModuleNotFoundError as err:
            if err.name == f"workflows.{name}":
                continue
            raise
        module.register(subparsers)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="gearloss", description=__doc__.splitlines()[0])
    register_modules(parser.add_subparsers(dest="group", metavar="GROUP"), GROUP_MODULES)
    return parser


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    handler = getattr(args, "handler", None)
    if handler is None:
        parser.print_help()
        return 2
    try:
        return int(handler(args) or 0)
    except InputError as err:
        print(f"gearloss: error: {err}", file=sys.stderr)
        return 2
    except SolverError as err:
        print(f"gearloss: solver error: {err}", file=sys.stderr)
        return 3
    except FileNotFoundError as err:
        print(f"gearloss: error: file not found: {err.filename or err}", file=sys.stderr)
        return 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
