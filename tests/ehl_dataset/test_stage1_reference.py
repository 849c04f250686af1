"""The solved values of a seeded sample of paper-factorial contacts stay those recorded before the stage-1 speed work
(``tests/ehl_dataset/data/stage1_reference.json``, made by ``python benchmarks/stage1_reference.py`` with
ehl-2026.11-15).

A Newton solve stops when the relative Reynolds residual, the load error and the last pressure step are all below the
level's tolerances (``standard``: 1e-6, :mod:`ehl_dataset.solvers.levels`); two solves of the same discrete problem
that take different linear-algebra paths to it may stop at iterates that differ by that much. The outputs are
compared at a relative 10 × tol_step: a bound the amplification of a 1e-6 pressure step into μ and the film stays
below on these contacts, and far below any change of the discretisation (the ``fast`` level differs from
``standard`` by percents, docs/validation/accuracy_smooth.md).
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers.levels import get_level

DATA = json.loads((Path(__file__).parent / "data" / "stage1_reference.json").read_text())
LEVEL = get_level(DATA["level"])
RELATIVE = 10.0 * LEVEL.tol_step
OUTPUTS = ("mu", "h_min", "h_central", "p_max")


def _check(group: str, index: int) -> None:
    spec = DATA[group]
    row = spec["cases"][index]
    res = solve_contact(ContactCase(*row["point"]), load_lubricant(DATA["lubricant"]), DATA["level"],
                        spec["effects"], model=spec["model"])
    assert res.converged == row["converged"]
    for key in OUTPUTS:
        assert getattr(res, key) == pytest.approx(row[key], rel=RELATIVE), key


@pytest.mark.parametrize("index", range(len(DATA["smooth"]["cases"])))
def test_smooth_values_unchanged(index):
    _check("smooth", index)


@pytest.mark.parametrize("index", range(len(DATA["rough"]["cases"])))
def test_default_model_values_unchanged(index):
    _check("rough", index)
