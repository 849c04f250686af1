"""Off-grid samples too small to calibrate the interval: refused before anything is solved when the size alone
says so, recorded without calibration (and saying so) when only the solved sample's split between the λ̄ branches
does."""

import json
import shutil
import warnings

import numpy as np
import pytest

from ehl_dataset.validation import InputError
from surrogate.coefficients import load_coefficients
from surrogate.evaluate import FrictionSurrogate
from surrogate.mlp import conformal_quantile
from surrogate.offgrid import offgrid_lines
from surrogate.synthetic import eq9_table, write_hdf5
from workflows.cli import main
from workflows.surrogate_stage import (CALIBRATION_ROWS, check_offgrid_points, smallest_offgrid_sample,
                                       validate_offgrid)


def test_nine_held_out_rows_are_the_fewest_that_give_a_90_percent_conformal_factor():
    """The split-conformal factor is the ⌈(n + 1)·0.9⌉-th smallest score: it exists from n = 9 on."""
    assert np.isfinite(conformal_quantile(np.arange(CALIBRATION_ROWS, dtype=float), 0.9))
    assert conformal_quantile(np.arange(CALIBRATION_ROWS - 1, dtype=float), 0.9) == np.inf


@pytest.mark.parametrize("form, smallest, intervals", [("eq9", 35, 2), ("learned", 17, 1)])
def test_the_smallest_sample_has_nine_even_rows_per_interval(form, smallest, intervals):
    """The even rows calibrate (one interval per λ̄ branch for Eq. 9, one for the ensemble): 35 points have 18 even
    rows, 34 have 17; 17 points have 9, 16 have 8."""
    assert smallest_offgrid_sample(form) == smallest
    assert (smallest + 1) // 2 == intervals * CALIBRATION_ROWS and smallest // 2 < intervals * CALIBRATION_ROWS
    assert check_offgrid_points(0, form) == 0 and check_offgrid_points(smallest, form) == smallest
    with pytest.raises(InputError, match=rf"offgrid_points=\d+: accepted 0 \(no off-grid sample\) or {smallest} to"):
        check_offgrid_points(smallest - 1, form)
    with pytest.raises(InputError, match="an integer"):
        check_offgrid_points(35.5, form)


@pytest.mark.parametrize("command, extra, smallest", [
    (["lubricant", "fit", "atf", "--factorial", "quick"], [], 35),
    (["lubricant", "fit", "atf", "--factorial", "quick"], ["--form", "learned"], 17),
    (["pipeline", "quick"], [], 35)])
def test_a_small_offgrid_sample_is_refused_before_solving_and_nothing_is_written(tmp_path, capsys, command, extra,
                                                                                 smallest):
    """``gearloss lubricant fit atf --factorial quick --offgrid-points 8``: one line naming the option, the value and
    the smallest accepted size, exit code 2, and no dataset or coefficient file (it used to solve the factorial,
    write the coefficient file and then fail on the calibration); ``gearloss pipeline`` likewise."""
    out = tmp_path / "run"
    code = main([*command, "--level", "fast", "--offgrid-points", "8", "--out-dir", str(out), "--workers", "1",
                 "--progress", "none", *extra])
    assert code == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert "--offgrid-points=8" in err and f"or {smallest} to 100000" in err
    assert not list(out.glob("*.json")) and not list(out.glob("*.h5"))


def test_a_sample_with_a_branch_short_of_calibration_rows_is_recorded_uncalibrated_and_says_so(
        coefficient_file, atf, e_reduced, true_params, tmp_path):
    """40 solved contacts, all in the full-film branch but 4 (λ̄ ≤ 1 on 2 even rows): Eq. 9's mixed interval cannot
    be calibrated. The file keeps its statsmodels interval, records the errors on all 40 rows with the coverage
    counted on all of them, and its off-grid table says why; the file loads and its report prints that line."""
    import pandas as pd

    rng = np.random.default_rng(11)
    n = 40
    inputs = pd.DataFrame({"point": np.arange(n), "p_h": rng.uniform(0.5e9, 1.0e9, n),
                           "r_eq": rng.uniform(20e-3, 80e-3, n), "u_r": rng.uniform(10.0, 20.0, n),
                           "sr": rng.uniform(0.05, 0.5, n), "temperature": np.full(n, 313.15),
                           "rq1": np.full(n, 0.05e-6), "rq2": np.full(n, 0.05e-6)})
    rough = [0, 2, 5, 7]  # two even, two odd rows on the mixed branch
    inputs.loc[rough, ["rq1", "rq2"]] = 1e-6
    inputs.loc[rough, ["p_h", "u_r", "temperature"]] = (2.5e9, 1.0, 373.15)
    table = eq9_table(inputs, true_params, atf, e_reduced, noise_sd=0.05, seed=2)
    lam = table["lambda_bar"].to_numpy()
    assert np.array_equal(np.flatnonzero(lam <= 1.0), rough)
    sample = write_hdf5(table, tmp_path / "offgrid.h5", atf)
    path = tmp_path / "eq9.json"
    shutil.copy(coefficient_file, path)

    with pytest.warns(UserWarning, match="not calibrated"):
        offgrid = validate_offgrid(path, sample)
    doc = json.loads(path.read_text())
    assert "interval_calibration" not in doc  # the statsmodels interval stays
    assert doc["offgrid"]["interval_calibration"].startswith("not calibrated on this sample")
    assert "calibration rows (mixed)=2" in doc["offgrid"]["interval_calibration"]
    assert offgrid["coverage_rows"] == "all" and offgrid["overall"]["n"] == n
    assert offgrid["overall"]["n_coverage"] == n and offgrid["mixed"]["n"] == len(rough)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        loaded = FrictionSurrogate.load(path)
    assert loaded.coefficients.document["offgrid"] == doc["offgrid"]
    assert any("not calibrated" in line for line in offgrid_lines(load_coefficients(path).document["offgrid"]))


def test_a_learned_file_on_a_sample_short_of_calibration_rows_keeps_its_cross_validation_interval(
        eq9_data, atf, e_reduced, true_params, tmp_path):
    """16 solved contacts give 8 even rows, one short of the ensemble's 9: the file keeps its cross-validation+
    interval (its ``learned.interval`` unchanged), the errors and coverage are counted on all 16 rows, and the
    off-grid table says why."""
    from surrogate.coefficients import write_coefficients
    from surrogate.fit import prepare_table
    from surrogate.learned_fit import fit_learned

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fit = fit_learned(eq9_data.sample(300, random_state=3).reset_index(drop=True), atf, e_reduced, members=3,
                          seed=0)
    path = write_coefficients(fit, tmp_path / "learned.json", source={"path": "synthetic"})
    before = json.loads(path.read_text())["learned"]["interval"]
    usable = eq9_data.iloc[prepare_table(eq9_data, atf, e_reduced).kept_rows]  # no SR = 0 rows, which the fit excludes
    rows = usable.sample(16, random_state=8).reset_index(drop=True)
    rows["point"] = np.arange(len(rows))
    sample = write_hdf5(rows, tmp_path / "offgrid.h5", atf)
    with pytest.warns(UserWarning, match="not calibrated"):
        offgrid = validate_offgrid(path, sample)
    doc = json.loads(path.read_text())
    assert doc["learned"]["interval"] == before
    assert "calibration rows=8" in doc["offgrid"]["interval_calibration"]
    assert offgrid["coverage_rows"] == "all" and offgrid["overall"]["n_coverage"] == offgrid["overall"]["n"] == 16
