"""``gearloss --version`` reports the solver's own constants without loading the solver: the version line is read
from the source of ehl_dataset.solver, and the process that prints it imports neither numpy, scipy, numba nor h5py."""

from __future__ import annotations

import json
import subprocess
import sys

from ehl_dataset.names import MODELS
from ehl_dataset.solver import SOLVER_VERSION
from workflows.cli_version import solver_constants, version_text


def test_version_line_names_the_solver_version_and_models():
    assert solver_constants() == {"SOLVER_VERSION": SOLVER_VERSION, "MODELS": tuple(MODELS)}
    assert f"EHL solver {SOLVER_VERSION};" in version_text()


def test_version_imports_no_numerics():
    code = ("import json, sys\nfrom workflows.cli import main\nmain(['--version'])\n"
            "print(json.dumps(sorted({m.split('.')[0] for m in sys.modules} & "
            "{'numpy', 'scipy', 'numba', 'h5py', 'pandas', 'statsmodels'})))")
    out = subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True).stdout
    lines = out.strip().splitlines()
    assert lines[0].startswith("gearloss ") and json.loads(lines[-1]) == []
