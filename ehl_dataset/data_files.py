"""Locate the data that ships with gearloss (lubricants, roughness, factorials, studies, coefficients, reference).

In a source checkout the data lives in ``<repo>/data``; in an installed wheel it is mapped by the build backend into
``ehl_dataset/shipped_data``. The environment variable ``GEARLOSS_DATA`` overrides both.
"""

from __future__ import annotations

import os
from pathlib import Path

from .validation import InputError

_PACKAGE_DIR = Path(__file__).resolve().parent


def data_root() -> Path:
    """Return the directory that holds the shipped data."""
    override = os.environ.get("GEARLOSS_DATA")
    candidates = [Path(override)] if override else []
    candidates += [_PACKAGE_DIR / "shipped_data", _PACKAGE_DIR.parent / "data"]
    for candidate in candidates:
        if (candidate / "lubricants").is_dir():
            return candidate
    raise FileNotFoundError(f"gearloss data directory not found; looked in {[str(c) for c in candidates]}")


def data_path(*parts: str) -> Path:
    """Path of a shipped data file, e.g. ``data_path("lubricants", "atf.toml")``."""
    return data_root().joinpath(*parts)


def resolve_named_file(kind: str, name_or_path: str | os.PathLike, suffix: str) -> Path:
    """Resolve a user argument that is either a shipped name (``atf``) or a file path (``my_oil.toml``).

    ``kind`` is the data sub-directory (``lubricants``, ``factorials``, ``studies``, ``coefficients``).
    """
    candidate = Path(name_or_path)
    if candidate.suffix and candidate.is_file():
        return candidate
    shipped = data_path(kind, f"{name_or_path}{suffix}")
    if shipped.is_file():
        return shipped
    available = sorted(p.stem for p in data_path(kind).glob(f"*{suffix}"))
    raise InputError(kind.rstrip("s"), str(name_or_path), f"a file path or one of {available}")
