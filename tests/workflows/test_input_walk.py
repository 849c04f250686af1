"""The walk of ``gearloss contact solve``'s arguments down to the solver stays short: inputs are resolved once.

The walk is traced with :func:`sys.settrace`: every call of the package's functions from the command's handler
(``workflows.cli_contact._solve``) until the solver entry (``solve_steady``, ``solve_homogenised`` or
``solve_deterministic_contact``) is a stop, down to three calls below the handler (deeper calls are the physics of a
step, e.g. the planner's film formulas, not the handling of the inputs); code run by the first import of a module is
not part of the walk. A *return* is a stop in a file the walk had
already left. Inputs checked at every layer show up as returns (the command line, the case, the solver entry and the
planner each calling the same checks and lookups); resolved once, the walk goes down the layers and comes back only
for the resolution steps.

``python tests/workflows/test_input_walk.py`` prints the walk of the smooth and the rough case.
"""

from __future__ import annotations

import inspect
import os
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PACKAGES = ("ehl_dataset", "workflows", "surrogate", "efficiency")
SOLVERS = frozenset({"solve_steady", "solve_homogenised", "solve_deterministic_contact"})
DEPTH = 3
"""Calls below the handler that count as stops."""
CONTACT = ["contact", "solve", "--p-h-gpa", "1", "--r-eq-mm", "10", "--u-r", "5", "--sr", "0.3", "--temp-c", "90",
           "--level", "fast"]
ROUGH = ["--rq1-um", "0.2", "--rq2-um", "0.2"]
MAX_RETURNS = 10
"""The acceptance limit of the walk's returns to a file already left."""


class _SolverReached(BaseException):
    """Stops the command at the solver's entry (not an Exception: no handler of the command catches it)."""


def _package_file(filename: str) -> str | None:
    path = os.path.abspath(filename)
    root = str(ROOT) + os.sep
    if not path.startswith(root):
        return None
    relative = path[len(root):]
    return relative if relative.split(os.sep)[0] in PACKAGES else None


def _importing(frame, handler) -> bool:
    """Whether ``frame`` runs as part of an import started below the handler (a module or class body on the way
    up): the first use of a module, not the walk."""
    frame = frame.f_back
    while frame is not None and frame is not handler:
        if frame.f_code.co_name == "<module>" or not frame.f_code.co_flags & inspect.CO_OPTIMIZED:
            return True
        frame = frame.f_back
    return False


def walk(argv: list[str]) -> list[tuple[str, str]]:
    """The stops (file, function) of the command ``argv`` from its handler to the solver's entry."""
    from workflows.cli import main

    stops: list[tuple[str, str]] = []
    stack: list = []

    def tracer(frame, event, arg):
        if event == "return":
            if stack and stack[-1] is frame:
                stack.pop()
            return None
        if event != "call":
            return None
        name = frame.f_code.co_name
        path = _package_file(frame.f_code.co_filename)
        if path is None or not frame.f_code.co_flags & inspect.CO_OPTIMIZED:
            return None
        if name in SOLVERS and path.startswith(os.path.join("ehl_dataset", "solvers")):
            raise _SolverReached
        if name == "_solve" and path.endswith("cli_contact.py"):
            stack.clear()
            stops.append((path, name))
            stack.append(frame)
            return tracer
        if not stack or _importing(frame, stack[0]):
            return None
        if len(stack) <= DEPTH:
            stops.append((path, name))
        stack.append(frame)
        return tracer

    sys.settrace(tracer)
    try:
        main(argv)
    except _SolverReached:
        pass
    finally:
        sys.settrace(None)
    return stops


def returns(stops: list[tuple[str, str]]) -> int:
    """How often the walk comes back to a file it had already left."""
    files = [path for path, _ in stops]
    left, count = set(), 0
    for before, after in zip(files, files[1:]):
        if after == before:
            continue
        left.add(before)
        count += after in left
    return count


@pytest.mark.parametrize("extra", [[], ROUGH], ids=["smooth", "rough"])
def test_contact_solve_reaches_the_solver_with_few_returns(extra):
    """Acceptance: at most 10 returns to a file already left; the walk reaches the solver; the case is converted and
    range-checked once, the lubricant's temperature checked once, the inputs resolved once and the plan made once."""
    stops = walk(CONTACT + extra + ["--json"])
    assert stops and stops[0][1] == "_solve"
    assert returns(stops) <= MAX_RETURNS, stops
    names = [name for _, name in stops]
    assert names.count("check_temperature") == 1 and names.count("from_engineering") == 1
    assert names.count("resolve_contact") == 1 and names.count("plan_effects") == 1


if __name__ == "__main__":
    for label, extra in (("smooth", []), ("rough", ROUGH)):
        found = walk(CONTACT + extra + ["--json"])
        print(f"{label}: {len(found)} stops in {len({p for p, _ in found})} files, {returns(found)} returns")
        for path, function in found:
            print(f"    {path}: {function}")
