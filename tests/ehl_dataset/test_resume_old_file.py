"""A dataset file written by an earlier solver version is refused on resume, with one clear error.

``data/smoke_partial_v7.h5`` is the smoke factorial computed by solver version ehl-2026.11-7 before the package was
regrouped into layers (commit b399435), with rows 6, 7, 8 and 12 left pending as an interrupted run leaves them
(``python benchmarks/behaviour_snapshot.py partial``). Until version -7 its resume gave the rows of the
uninterrupted run recorded before the regrouping (``benchmarks/results/behaviour_before.json``): the regrouping
changed no result. Version ehl-2026.11-8 (the thermal correction of the traction) can change solved
values, so the store must refuse to continue the file, naming both versions (docs/reference/dataset-format.md).
"""

import shutil
from pathlib import Path

import pytest

from ehl_dataset.dataset.runner import resume_run
from ehl_dataset.dataset.store import read_metadata, read_table
from ehl_dataset.solver import SOLVER_VERSION
from ehl_dataset.validation import InputError

OLD_FILE = Path(__file__).parent / "data" / "smoke_partial_v7.h5"
PENDING = [6, 7, 8, 12]


def test_a_file_of_an_earlier_solver_version_is_refused(tmp_path):
    path = tmp_path / "smoke.h5"
    shutil.copy(OLD_FILE, path)
    assert read_metadata(path)["solver"]["function"] == "ehl_dataset.solver:solve_contact"
    assert read_metadata(path)["solver"]["version"] == "ehl-2026.11-7" != SOLVER_VERSION
    assert sorted(read_table(path, status="pending")["point"]) == PENDING
    with pytest.raises(InputError, match="solver.version") as err:
        resume_run(path, workers=0, progress="none")
    assert "ehl-2026.11-7" in str(err.value) and SOLVER_VERSION in str(err.value)
    assert sorted(read_table(path, status="pending")["point"]) == PENDING   # nothing written
