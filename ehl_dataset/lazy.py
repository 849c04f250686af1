"""Lazy re-exports of a package's public names (PEP 562): the package's ``__init__`` maps each name to the module
that defines it, and the module is imported on first use, so importing one light sub-module does not load the
whole package (numba, h5py, statsmodels)."""

from __future__ import annotations

import importlib
from typing import Callable


def lazy_exports(package: str, names: dict[str, str], namespace: dict) -> tuple[Callable, Callable]:
    """``(__getattr__, __dir__)`` for the package ``package`` whose public ``names`` map to the modules that define
    them; ``namespace`` is the package's ``globals()`` (a name, once imported, is cached there)."""

    def __getattr__(name):
        if name in names:
            value = getattr(importlib.import_module(names[name]), name)
            namespace[name] = value
            return value
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__():
        return sorted(set(namespace) | set(names))

    return __getattr__, __dir__
