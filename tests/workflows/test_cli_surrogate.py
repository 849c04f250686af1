"""``gearloss surrogate fit|predict|compare`` in process (plus one real subprocess call)."""

import json
import subprocess
import sys
import warnings

import numpy as np
import pytest

from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.materials import STEEL, reduced_modulus
from surrogate.synthetic import SMALL_LEVELS, eq9_table, factorial_inputs, reference_coefficients, write_hdf5
from workflows.cli import main

PREDICT = ["--p-h-gpa", "1.0", "--r-eq-mm", "20", "--u-r", "5", "--sr", "0.2", "--temp-c", "75", "--rq1-um", "0.2",
           "--rq2-um", "0.2"]


@pytest.fixture(scope="module")
def dataset(tmp_path_factory):
    atf = load_lubricant("atf")
    e = reduced_modulus(STEEL, STEEL)
    table = eq9_table(factorial_inputs(SMALL_LEVELS), reference_coefficients(atf, e), atf, e, seed=3)
    table.loc[7, "mu"] = np.nan  # one failed point
    folder = tmp_path_factory.mktemp("cli_surrogate")
    return write_hdf5(table, folder / "synthetic.h5", atf), table


@pytest.fixture(scope="module")
def fitted(dataset, tmp_path_factory):
    path = tmp_path_factory.mktemp("coef") / "syn.json"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert main(["surrogate", "fit", str(dataset[0]), "--out", str(path), "--json"]) == 0
    return path


def _json(capsys):
    return json.loads(capsys.readouterr().out)


def test_fit_writes_a_file_and_reports_exclusions(dataset, tmp_path, capsys):
    path = tmp_path / "c.json"
    assert main(["surrogate", "fit", str(dataset[0]), "--out", str(path), "--json"]) == 0
    out = _json(capsys)
    table = dataset[1]
    assert out["exclusions"]["failed"] == 1
    assert out["exclusions"]["sr_zero"] == int((table["sr"] == 0).sum()) - int(table.loc[7, "sr"] == 0)
    assert out["n_used"] == len(table) - sum(out["exclusions"].values())
    assert path.is_file() and path.with_name("c.summary.txt").is_file()
    assert 0.9 < out["branches"]["mixed"]["adj_r2"] <= 1.0
    doc = json.loads(path.read_text())
    assert doc["source"]["accuracy_level"] == "synthetic" and len(doc["source"]["sha256"]) == 64


def test_predict_matches_the_library_and_flags_inputs_outside_the_fitted_ranges(fitted, capsys):
    """Inside the fitted ranges: the library's μ, valid, exit 0. Outside (u_r 40 m/s, fitted up to 20): the policy
    of gear evaluate: μ of the surrogate with its inputs clipped, the clipped input counted,
    valid false and exit 1; --no-clip gives the raw regression, flagged the same way."""
    from surrogate.evaluate import FrictionSurrogate

    assert main(["surrogate", "predict", str(fitted), *PREDICT, "--json"]) == 0
    out = _json(capsys)
    expected = FrictionSurrogate.load(fitted).mu(1e9, 0.02, 5.0, 0.2, 348.15, 0.2e-6, 0.2e-6)
    assert out["mu"] == pytest.approx(float(expected), rel=1e-12)
    assert out["valid"] is True and not any(out["clipped_inputs"].values())
    args = [str(fitted), *PREDICT]
    args[args.index("--u-r") + 1] = "40"
    assert main(["surrogate", "predict", *args, "--json"]) == 1
    out = _json(capsys)
    clipped = FrictionSurrogate.load(fitted, clip_to_fitted_ranges=True).mu(1e9, 0.02, 40.0, 0.2, 348.15, 0.2e-6,
                                                                             0.2e-6, warn=False)
    assert out["mu"] == pytest.approx(float(clipped), rel=1e-12)
    assert out["valid"] is False and out["clipped_inputs"]["u_r"] == 1
    assert out["note"].startswith("surrogate inputs clipped to the fitted ranges: u_r 1 of 1 point")
    assert main(["surrogate", "predict", *args, "--no-clip", "--json"]) == 1
    raw = _json(capsys)
    expected = FrictionSurrogate.load(fitted).mu(1e9, 0.02, 40.0, 0.2, 348.15, 0.2e-6, 0.2e-6, warn=False)
    assert raw["mu"] == pytest.approx(float(expected), rel=1e-12) and raw["extrapolated_inputs"]["u_r"] == 1


def test_bad_input_and_tampered_file_exit_2_with_one_line(fitted, tmp_path, capsys):
    args = [str(fitted), *PREDICT]
    args[args.index("--temp-c") + 1] = "nan"
    assert main(["surrogate", "predict", *args]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "invalid --temp-c=nan" in err
    doc = json.loads(fitted.read_text())
    doc["branches"]["mixed"]["params"][0] += 0.1
    bad = tmp_path / "tampered.json"
    bad.write_text(json.dumps(doc))
    assert main(["surrogate", "predict", str(bad), *PREDICT]) == 2
    assert "content_sha256" in capsys.readouterr().err


def test_compare_table_has_every_model(dataset, capsys):
    assert main(["surrogate", "compare", str(dataset[0]), "--k-folds", "3", "--json"]) == 0
    out = _json(capsys)
    models = {row["model"]: row for row in out["models"]}
    assert set(models) == {"li_kahraman_2009_eq9", "li_kahraman_2009_eq9_hard_switch", "hist_gradient_boosting", "xu_2007", "benedict_kelley_1961",
                           "iso_tr_14179_2"}
    # the data follow Eq. 9 exactly with σ = 0.05 noise: its CV error must be the noise level
    assert models["li_kahraman_2009_eq9_hard_switch"]["metrics"]["rmse_ln_mu"] == pytest.approx(0.05, rel=0.15)
    assert models["li_kahraman_2009_eq9"]["metrics"]["rmse_ln_mu"] == pytest.approx(0.05, rel=0.15)


def test_predict_as_a_real_subprocess(fitted):
    run = subprocess.run([sys.executable, "-m", "workflows.cli", "surrogate", "predict", str(fitted), *PREDICT,
                          "--json"], capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert 0 < json.loads(run.stdout)["mu"] < 0.2
