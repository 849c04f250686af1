"""``gearloss --version`` without importing the solver: the package version from the installed metadata and the EHL
solver's :data:`~ehl_dataset.solver.SOLVER_VERSION` and :data:`~ehl_dataset.solver.MODELS` read as literals from the
source of :mod:`ehl_dataset.solver` (where they stay defined: every dataset file records that module), so the
version line does not load numba, scipy or h5py."""

from __future__ import annotations

import ast
import importlib.util
from importlib import metadata
from pathlib import Path

__all__ = ["solver_constants", "version_text"]


def solver_constants() -> dict:
    """``SOLVER_VERSION`` and ``MODELS`` of :mod:`ehl_dataset.solver`, evaluated as literals from its source.

    Returns
    -------
    dict
        ``{"SOLVER_VERSION": str, "MODELS": tuple}``. A name assigned a literal is read from the source, one
        assigned ``module.NAME`` of a sibling module (``ehl_dataset.names``, which imports nothing) from that module;
        anything else is imported from :mod:`ehl_dataset.solver` itself.
    """
    wanted = ("SOLVER_VERSION", "MODELS")
    spec = importlib.util.find_spec("ehl_dataset.solver")
    found: dict = {}
    if spec is not None and spec.origin and spec.origin.endswith(".py"):
        tree = ast.parse(Path(spec.origin).read_text(encoding="utf-8"))
        for node in tree.body:
            target = node.targets[0] if isinstance(node, ast.Assign) and len(node.targets) == 1 else \
                getattr(node, "target", None) if isinstance(node, ast.AnnAssign) else None
            if not (isinstance(target, ast.Name) and target.id in wanted and node.value is not None):
                continue
            value = node.value
            if isinstance(value, ast.Attribute) and isinstance(value.value, ast.Name):
                try:
                    found[target.id] = getattr(importlib.import_module(f"ehl_dataset.{value.value.id}"), value.attr)
                except (ImportError, AttributeError):
                    pass
                continue
            try:
                found[target.id] = ast.literal_eval(value)
            except ValueError:
                pass
    if len(found) < len(wanted):
        from ehl_dataset import solver

        found = {name: getattr(solver, name) for name in wanted}
    return found


def version_text() -> str:
    """``gearloss --version``: the package version and the EHL solver version (the one datasets record).

    Returns
    -------
    str
        ``gearloss <version> (EHL solver <SOLVER_VERSION>; contact models <MODELS>)``.
    """
    try:
        package = metadata.version("gearloss")
    except metadata.PackageNotFoundError:  # an uninstalled source tree
        package = "unknown"
    constants = solver_constants()
    return (f"gearloss {package} (EHL solver {constants['SOLVER_VERSION']}; contact models "
            f"{', '.join(constants['MODELS'])})")
