"""Shared fixtures of the EHL tests."""

import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCRIPT_FOLDERS = (ROOT / "validation", ROOT / "benchmarks")


@pytest.fixture(scope="session")
def load_benchmark():
    """``load_benchmark(name)``: the module validation/<name>.py or benchmarks/<name>.py (scripts the tests check,
    not a package)."""
    def load(name: str):
        path = next(folder / f"{name}.py" for folder in SCRIPT_FOLDERS if (folder / f"{name}.py").exists())
        spec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module
    return load
