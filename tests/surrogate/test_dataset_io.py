"""Reading datasets for fitting: HDF5 store (lubricant and provenance from the file) or CSV (lubricant given)."""

import pytest

from ehl_dataset.validation import InputError
from surrogate.dataset_io import load_dataset
from surrogate.synthetic import write_hdf5


def test_hdf5_and_csv_give_the_same_table(eq9_data, atf, tmp_path):
    h5 = write_hdf5(eq9_data.iloc[:200], tmp_path / "d.h5", atf)
    csv = tmp_path / "d.csv"
    eq9_data.iloc[:200].to_csv(csv, index=False)
    a, b = load_dataset(h5), load_dataset(csv, "atf")
    assert a.lubricant == b.lubricant and a.e_reduced == b.e_reduced
    for column in ("p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2", "mu"):
        assert a.table[column].to_numpy() == pytest.approx(b.table[column].to_numpy(), rel=1e-15)
    assert a.source["accuracy_level"] == "synthetic" and a.source["n_points"] == 200
    assert len(a.source["sha256"]) == 64 and a.source["sha256"] != b.source["sha256"]


def test_bad_dataset_arguments_are_clear_errors(eq9_data, atf, tmp_path):
    with pytest.raises(InputError, match="dataset"):
        load_dataset(tmp_path / "missing.h5")
    other = tmp_path / "table.parquet"
    other.write_text("x")
    with pytest.raises(InputError, match=r"\.csv"):
        load_dataset(other)
    h5 = write_hdf5(eq9_data.iloc[:20], tmp_path / "small.h5", atf)
    with pytest.raises(InputError, match="lubricant"):
        load_dataset(h5, "atf")
    broken = tmp_path / "broken.h5"
    broken.write_bytes(b"not an hdf5 file")
    with pytest.raises(InputError):
        load_dataset(broken)
