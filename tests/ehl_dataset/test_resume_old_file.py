"""A dataset file written by an earlier version of the code resumes with this one.

``data/smoke_partial_v7.h5`` is the smoke factorial computed by solver version ehl-2026.11-7 before the package was
regrouped into layers (commit b399435), with rows 6, 7, 8 and 12 left pending as an interrupted run leaves them
(``python benchmarks/behaviour_snapshot.py partial``). The file records ``ehl_dataset.solver:solve_contact``, which
the resume imports; the resumed rows must equal those of the uninterrupted run recorded before the change
(``benchmarks/results/behaviour_before.json``).
"""

import json
import shutil
from pathlib import Path

import numpy as np

from ehl_dataset.dataset.runner import resume_run
from ehl_dataset.dataset.store import read_metadata, read_table

REPO = Path(__file__).resolve().parents[2]
OLD_FILE = Path(__file__).parent / "data" / "smoke_partial_v7.h5"
BEFORE = REPO / "benchmarks" / "results" / "behaviour_before.json"
PENDING = [6, 7, 8, 12]


def test_a_file_written_before_the_regrouping_resumes_with_the_same_results(tmp_path):
    path = tmp_path / "smoke.h5"
    shutil.copy(OLD_FILE, path)
    assert read_metadata(path)["solver"]["function"] == "ehl_dataset.solver:solve_contact"
    assert sorted(read_table(path, status="pending")["point"]) == PENDING
    summary = resume_run(path, workers=0, progress="none")
    assert summary.computed == len(PENDING) and summary.pending == 0 and summary.failed == 0
    table = read_table(path).set_index("point")
    expected = json.loads(BEFORE.read_text())["dataset_file"]["columns"]
    for column in ("mu", "mu_std", "mu_sem", "h_min", "h_central", "asperity_load_share", "p_max", "iterations",
                   "converged", "effects"):
        for i in range(16):
            value = table.loc[i, column]
            if isinstance(value, (float, np.floating)):
                assert value == float(expected[column][i]), (column, i)
            else:
                assert value == expected[column][i], (column, i)
