"""The argument parser of every ``gearloss`` command: defaults shown in ``--help`` and usage errors as one line (no
9-line usage block).

:class:`GearlossParser` is the parser class of the top level; ``add_subparsers`` creates every sub-command parser
of the same class, so each gets :class:`HelpFormatter` and the one-line :meth:`GearlossParser.error`.
"""

from __future__ import annotations

import argparse
import re

from ehl_dataset.names import EFFECT_PLANS, MODELS


class UsageError(Exception):
    """A command line argparse cannot parse (unknown option, a word for a number, a missing required option):
    ``option`` as typed, ``value`` and ``accepted`` when the message says them, ``prog`` the command."""

    def __init__(self, message: str, prog: str, option: str | None = None, value=None, accepted: str | None = None):
        self.prog, self.option, self.value, self.accepted = prog, option, value, accepted
        super().__init__(message)


class HelpFormatter(argparse.RawDescriptionHelpFormatter):
    """Descriptions as written (line breaks kept); every option's default appended unless its help already names
    one."""

    def _get_help_string(self, action):
        text = str(action.help) if action.help is not None else ""
        default = action.default
        if (action.option_strings and "default" not in text.lower() and default not in (None, False, True)
                and default is not argparse.SUPPRESS and text != argparse.SUPPRESS):
            shown = ",".join(str(v) for v in default) if isinstance(default, (list, tuple)) else default
            text += f" (default: {str(shown).replace('%', '%%')})"
        return text


_UNIT = re.compile(r"\[([^\]\[]+)\]")


class GearlossParser(argparse.ArgumentParser):
    """``argparse.ArgumentParser`` with :class:`HelpFormatter` and one-line usage errors (:class:`UsageError`)."""

    def __init__(self, *args, **kwargs):
        kwargs.setdefault("formatter_class", HelpFormatter)
        super().__init__(*args, **kwargs)

    def error(self, message: str):  # noqa: D401 - argparse's hook
        raise usage_error(self, message)


def usage_error(parser: argparse.ArgumentParser, message: str) -> UsageError:
    """A :class:`UsageError` in the project's form ("invalid --option='value': accepted ...") where argparse's
    message says which option and value; otherwise argparse's message."""
    match = re.match(r"argument (\S+?)(?:/\S+)?: invalid (\w+) value: '(.*)'$", message)
    if match:
        option, kind, value = match.groups()
        action = parser._option_string_actions.get(option)
        unit = _UNIT.search(str(action.help)) if action is not None and action.help else None
        accepted = {"float": "a number", "int": "a whole number"}.get(kind, f"a {kind} value")
        if unit and kind in ("float", "int"):
            accepted += f" [{unit.group(1)}]"
        return UsageError(f"invalid {option}={value!r}: accepted {accepted}", parser.prog, option, value, accepted)
    match = re.match(r"argument (\S+?)(?:/\S+)?: invalid choice: '(.*)' \(choose from (.*)\)$", message)
    if match:
        option, value, choices = match.groups()
        accepted = "one of " + choices.replace("'", "")
        return UsageError(f"invalid {option}={value!r}: accepted {accepted}", parser.prog, option, value, accepted)
    return UsageError(f"{message} (see '{parser.prog} --help')", parser.prog)


ACCURACY_EPILOG = """\
accuracy: at fast and standard every rough contact is solved by the steady film-law model (the two levels agree
within 0.1 % in median, docs/validation/accuracy_random_levels.md); below λ̄ 1, with its pressure-fluctuation closure where the
traction is unsaturated, it is within a median 5.3 % of the deterministic model, except below λ̄ 0.1 or at a roughness parameter above
2.5, where it is 23-78 % low: --level reference runs the deterministic model (docs/explanation/mixed-regime.md)"""
"""The accuracy paragraph of the epilogs of the commands that run a factorial (pipeline, lubricant fit)."""

EFFECTS_CHOICES = EFFECT_PLANS
"""The ``--effects`` values of the dataset, pipeline and lubricant-fit commands:
:data:`ehl_dataset.names.EFFECT_PLANS`."""

EFFECTS_HELP = ("effect plan of stage 1: auto (the planner's), isothermal (the planner's without the thermal correction "
                "of the traction: isothermal data, as the paper's Eq. 9 was fitted to), full (every effect)")


def model_help(extra: str) -> str:
    """Help of a ``--model`` option: the names of :data:`ehl_dataset.names.MODELS` and ``extra``."""
    return f"contact model, one of {', '.join(MODELS)} (ehl_dataset.names.MODELS); {extra}"
