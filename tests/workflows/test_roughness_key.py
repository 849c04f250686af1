"""The roughness record travels from a dataset to its coefficient file (``roughness`` key) and is shown by
``surrogate predict --json`` and ``gear evaluate --json``; files without it say "not recorded"."""

import json
import warnings

import h5py
import pytest

from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.materials import STEEL, reduced_modulus
from ehl_dataset.model.roughness import PROFILES
from ehl_dataset.validation import InputError
from surrogate.synthetic import SMALL_LEVELS, eq9_table, factorial_inputs, reference_coefficients, write_hdf5
from workflows.cli import main

FLANK = {"name": "flank_ground", "sha256": PROFILES["flank_ground"].sha256}
PREDICT = ["--p-h-gpa", "1.0", "--r-eq-mm", "20", "--u-r", "5", "--sr", "0.2", "--temp-c",
           "75", "--rq1-um", "0.2", "--rq2-um", "0.2", "--json"]
DESIGN_D = ["--teeth", "32", "--pressure-angle-deg", "30", "--helix-angle-deg", "19", "--working-depth", "2.068",
            "--positions", "12", "--slices", "12"]


@pytest.fixture(scope="module")
def datasets(tmp_path_factory):
    """The same synthetic Eq. 9 table in two stores: one recording the flank-like profile (as a run with it would),
    one recording none (as files written before the record)."""
    atf = load_lubricant("atf")
    e = reduced_modulus(STEEL, STEEL)
    table = eq9_table(factorial_inputs(SMALL_LEVELS), reference_coefficients(atf, e), atf, e, seed=3)
    folder = tmp_path_factory.mktemp("roughness_key")
    recorded = write_hdf5(table, folder / "recorded.h5", atf)
    with h5py.File(recorded, "r+") as h5:
        h5.attrs["roughness"] = json.dumps(FLANK)
    bare = write_hdf5(table, folder / "bare.h5", atf)
    return recorded, bare


@pytest.fixture(scope="module")
def fitted(datasets, tmp_path_factory):
    folder = tmp_path_factory.mktemp("roughness_key_fit")
    paths = []
    for dataset, name in zip(datasets, ("recorded.json", "bare.json")):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            assert main(["surrogate", "fit", str(dataset), "--out", str(folder / name), "--json"]) == 0
        paths.append(folder / name)
    return paths


def test_the_fit_copies_the_datasets_record(fitted, capsys):
    capsys.readouterr()
    recorded, bare = (json.loads(p.read_text()) for p in fitted)
    assert recorded["roughness"] == FLANK
    assert "roughness" not in bare


def test_predict_json_shows_the_record_or_null(fitted, capsys):
    capsys.readouterr()
    main(["surrogate", "predict", str(fitted[0]), *PREDICT])
    assert json.loads(capsys.readouterr().out)["roughness"] == FLANK
    main(["surrogate", "predict", str(fitted[1]), *PREDICT])
    assert json.loads(capsys.readouterr().out)["roughness"] is None
    main(["surrogate", "predict", "atf", *PREDICT])  # shipped, fitted on the default profile
    assert json.loads(capsys.readouterr().out)["roughness"] == FLANK


def test_gear_evaluate_shows_the_coefficient_files_record(fitted, capsys):
    capsys.readouterr()
    main(["gear", "evaluate", *DESIGN_D, "--friction", str(fitted[0]), "--json"])
    assert json.loads(capsys.readouterr().out)["friction_roughness"] == FLANK
    main(["gear", "evaluate", *DESIGN_D, "--friction", str(fitted[1]), "--json"])
    assert json.loads(capsys.readouterr().out)["friction_roughness"] is None


def test_training_files_of_different_profiles_are_not_mixed(datasets, tmp_path):
    """An adaptive design's files must share their profile; a file that records none makes the mix unrecorded."""
    from workflows.surrogate_stage import load_rows

    other = tmp_path / "other.h5"
    other.write_bytes(datasets[0].read_bytes())
    with h5py.File(other, "r+") as h5:
        h5.attrs["roughness"] = json.dumps({"name": "baseline_synthetic",
                                            "sha256": PROFILES["baseline_synthetic"].sha256})
    with pytest.raises(InputError, match="roughness profile"):
        load_rows([datasets[0], other])
    assert load_rows([datasets[0], datasets[0]])[1].roughness == FLANK
    assert load_rows([datasets[0], datasets[1]])[1].roughness is None


def test_a_malformed_record_is_refused():
    from surrogate.coefficients import coefficients_payload

    with pytest.raises(InputError, match="roughness"):
        coefficients_payload(None, roughness={"name": "flank_ground", "sha256": "not a hash"})
