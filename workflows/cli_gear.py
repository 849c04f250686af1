"""``gearloss gear ...``: the gear-pair sub-commands.

The group is assembled from small modules so that each piece of the gear model owns its own sub-commands:
``cli_gear_geometry`` (``geometry``) and ``cli_gear_evaluate`` (``evaluate``, and later ``sweep``,
``modifications``). Each exposes ``register(gear_subparsers)``.
"""

from __future__ import annotations

from . import cli_gear_evaluate, cli_gear_geometry, cli_gear_studies

PARTS = (cli_gear_geometry, cli_gear_evaluate, cli_gear_studies)


def register(subparsers) -> None:
    parser = subparsers.add_parser("gear", help="helical gear pair: geometry, evaluation, studies")
    gear_subparsers = parser.add_subparsers(dest="gear_command", metavar="COMMAND")
    parser.set_defaults(handler=lambda args: parser.print_help() or 2)
    for module in PARTS:
        module.register(gear_subparsers)
