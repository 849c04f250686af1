"""The shipped paper-box coefficient files against stage 1 off the factorial's grid.

``data/offgrid_paper2009_seed7.csv``: 200 random contacts in the paper factorial's ranges (seed 7, drawn by
``workflows.sample_runs.offgrid_points``), solved by stage 1 on the factorial's route (``standard``, isothermal,
default model, EHL solver ehl-2026.11-17), which took no part in fitting or calibrating either file; made by
``python validation/surrogate_intervals.py --work-dir DIR atf atf_learned --factorial paper2009`` (its
``DIR/seed7/offgrid.h5``, columns kept: the inputs, μ and the solve's status). Targets: a learned surrogate a median
≤ 3 % and a 90th percentile ≤ 8 % off, and 90 % intervals of both forms covering 85–95 % of the solved μ
(docs/validation/surrogate-off-grid.md).
"""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest

from surrogate.dataset_io import load_dataset
from surrogate.evaluate import FrictionSurrogate
from surrogate.offgrid import offgrid_errors

SAMPLE = Path(__file__).parent / "data" / "offgrid_paper2009_seed7.csv"


@pytest.fixture(scope="module")
def sample():
    return load_dataset(SAMPLE, "atf").table


def _errors(name, table):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return offgrid_errors(FrictionSurrogate.load(name), table)["overall"]


def test_the_independent_sample_is_the_factorial_route_and_inside_the_files_ranges(sample):
    assert len(sample) == 200 and set(sample["status"]) == {"ok"} and sample["converged"].all()
    assert set(sample["level"]) == {"standard"}
    for name in ("atf", "atf_learned"):
        ranges = FrictionSurrogate.load(name).coefficients.document["input_ranges"]
        for column, key in (("p_h", "p_h_pa"), ("r_eq", "r_eq_m"), ("u_r", "u_r_m_s"), ("temperature", "temperature_k"),
                            ("rq1", "rq1_m"), ("rq2", "rq2_m")):
            low, high = ranges[key]
            assert sample[column].between(low * (1 - 1e-9), high * (1 + 1e-9)).all(), (name, column)


def test_shipped_learned_surrogate_meets_the_off_grid_targets_on_an_independent_sample(sample):
    """Measured: median 1.38 %, 90th percentile 4.32 %, coverage 86 % (targets ≤ 3 %, ≤ 8 %, 85–95 %)."""
    errors = _errors("atf_learned", sample)
    assert errors["n"] == 200
    assert errors["median_rel_err_mu"] <= 0.03
    assert errors["p90_rel_err_mu"] <= 0.08
    assert 0.85 <= errors["coverage"] <= 0.95


def test_shipped_eq9_interval_is_calibrated_and_its_error_is_what_its_file_states(sample):
    """Eq. 9 keeps its form: about 11 % off in median, which its own off-grid table (seed 2009) states within a
    couple of points (measured 11.7 % against the file's 11.4 %); its calibrated 90 % interval covers 90.0 % of the
    independent sample."""
    errors = _errors("atf", sample)
    recorded = FrictionSurrogate.load("atf").coefficients.document["offgrid"]["overall"]
    assert 0.85 <= errors["coverage"] <= 0.95
    assert errors["median_rel_err_mu"] == pytest.approx(recorded["median_rel_err_mu"], abs=0.03)
    assert errors["median_rel_err_mu"] > 5 * _errors("atf_learned", sample)["median_rel_err_mu"]
