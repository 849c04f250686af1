"""``gearloss --version`` reports the solver's own constants without loading the solver: the version line is read
from the source of ehl_dataset.solver, and the process that prints it imports neither numpy, scipy, numba nor h5py.
``gearloss --help`` and a command's ``--help`` build the parser without them too (the options' defaults and choices
live in modules without numerics)."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from ehl_dataset.names import MODELS
from ehl_dataset.solver import SOLVER_VERSION
from workflows.cli_version import solver_constants, version_text


def test_version_line_names_the_solver_version_and_models():
    assert solver_constants() == {"SOLVER_VERSION": SOLVER_VERSION, "MODELS": tuple(MODELS)}
    assert f"EHL solver {SOLVER_VERSION};" in version_text()


NUMERICS = ("numpy", "scipy", "numba", "h5py", "pandas", "statsmodels")


def numerics_loaded_by(argv: list[str]) -> tuple[str, list[str]]:
    """(the output of ``gearloss argv``, the packages of :data:`NUMERICS` it imported), in a fresh interpreter."""
    code = ("import json, sys\nfrom workflows.cli import main\nmain(sys.argv[1:])\n"
            f"print(json.dumps(sorted({{m.split('.')[0] for m in sys.modules}} & set({list(NUMERICS)!r}))))")
    out = subprocess.run([sys.executable, "-c", code, *argv], check=True, capture_output=True, text=True).stdout
    lines = out.strip().splitlines()
    return "\n".join(lines[:-1]), json.loads(lines[-1])


def test_version_imports_no_numerics():
    out, loaded = numerics_loaded_by(["--version"])
    assert out.startswith("gearloss ") and loaded == []


@pytest.mark.parametrize("argv", [["--help"], ["contact", "solve", "--help"], ["dataset", "run", "--help"]])
def test_help_imports_no_numerics(argv):
    out, loaded = numerics_loaded_by(argv)
    assert "usage: gearloss" in out and loaded == []


def test_a_reader_that_closes_the_pipe_early_gets_no_traceback():
    """`gearloss ... | true`: the reader is gone before the command writes (EPIPE); the command stops without a
    traceback, exit 0."""
    import subprocess
    import sys

    code = "import sys; from workflows.cli import main; sys.exit(main())"
    run = subprocess.run(["bash", "-c", f"set -o pipefail; {sys.executable} -c '{code}' contact solve --p-h-gpa 1 "
                          "--r-eq-mm 20 --u-r 5 --sr 0.2 --temp-c 90 --level fast | true"],
                         capture_output=True, text=True)
    assert "Traceback" not in run.stderr and "BrokenPipe" not in run.stderr, run.stderr
    assert run.returncode == 0
