"""The ``gearloss`` command line: one console script with sub-command groups.

Each group lives in its own module (``cli_contact``, ``cli_dataset``, ``cli_surrogate``, ``cli_gear``, ...) that
exposes ``register(subparsers)``; heavy imports happen inside the handlers so ``gearloss --help`` stays fast.
Output goes through :func:`workflows.cli_output.emit`.
Bad input raises :class:`ehl_dataset.validation.InputError`, which is printed as one line with exit status 2.
"""

from __future__ import annotations

import argparse
import sys

from ehl_dataset.validation import InputError, SolverError

from . import cli_accuracy, cli_contact, cli_dataset, cli_gear, cli_pipeline, cli_surrogate

GROUP_MODULES = (cli_contact, cli_dataset, cli_surrogate, cli_gear, cli_pipeline, cli_accuracy)
"""The command groups, in the order of ``gearloss --help``; each module adds its sub-commands (``register``)."""


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="gearloss", description=__doc__.splitlines()[0])
    subparsers = parser.add_subparsers(dest="group", metavar="GROUP")
    for module in GROUP_MODULES:
        module.register(subparsers)
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
