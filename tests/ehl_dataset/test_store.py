"""The HDF5 dataset store: layout, units, round trip, resumability checks, crash-safe writes, clear errors."""

import json
import math

import h5py
import numpy as np
import pytest

from ehl_dataset.dataset.factorial import POINT_FIELDS, POINT_UNITS, factorial_from_dict
from ehl_dataset.model.lubricant import load_lubricant, lubricant_from_dict
from ehl_dataset.solvers.result import RECORD_UNITS, ContactResult
from ehl_dataset.dataset.store import (EFFECTS_WIDTH, ERROR_WIDTH, FAILED, FORMAT_VERSION, OK, TABLE_COLUMNS, DatasetStore,
                               encode_effects, read_metadata, read_table, summarize)
from ehl_dataset.validation import InputError

CONTRACT_COLUMNS = ["point", "p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2", "mu", "mu_std", "h_min",
                    "h_central", "lambda_bar", "asperity_load_share", "p_max", "iterations", "converged",
                    "wall_time", "effects", "level", "status", "error"]
SOLVER = {"function": "ehl_dataset.solver:solve_contact", "version": "1", "level": "fast", "effects": "auto",
          "level_definition": None}


@pytest.fixture()
def plan():
    return factorial_from_dict({"name": "t", "axes": {
        "p_h_gpa": [0.5, 1.5], "r_eq_mm": [10.0], "u_r_m_s": [2.0, 10.0], "sr": [0.2], "temp_c": [60.0],
        "roughness_um": [[0.1, 0.1], [0.2, 0.5], [0.4, 1.0]]}})


@pytest.fixture()
def lubricant():
    return load_lubricant("atf")


def make_store(path, plan, lubricant, **solver_changes):
    return DatasetStore.create(path, plan.points(), factorial=plan.to_dict(), solver={**SOLVER, **solver_changes},
                               lubricant=lubricant.to_json_dict())


def record_of(i):
    """A ContactResult record with distinguishable values per point (the store must not alter them)."""
    return ContactResult(mu=0.01 + i * 1e-3, h_min=1e-7 * (i + 1), h_central=1.3e-7 * (i + 1), p_max=1e9 + i,
                         converged=True, iterations=10 + i, wall_time=0.1 * i, level="fast",
                         effects={"roughness": i % 2 == 0, "mode": "auto", "reasons": {"lambda_bar": 0.5 * i}},
                         mu_std=1e-4 * i, lambda_bar=0.5 * i, asperity_load_share=0.01 * i).to_record()


def test_new_file_layout_units_and_provenance(tmp_path, plan, lubricant):
    path = tmp_path / "run.h5"
    make_store(path, plan, lubricant).close()
    with h5py.File(path, "r") as h5:
        assert h5.attrs["format"] == "gearloss-ehl-dataset" and h5.attrs["format_version"] == FORMAT_VERSION
        assert h5.attrs["n_points"] == plan.size == 12
        points = h5["points"]
        for name in POINT_FIELDS:
            assert points[name].attrs["units"] == POINT_UNITS[name]
            np.testing.assert_array_equal(points[name][...], plan.points()[name])
        for name, unit in RECORD_UNITS.items():
            assert points[name].attrs["units"] == unit
        assert np.isnan(points["mu"][...]).all() and (points["status"][...] == 0).all()
        assert points["mu"].dims[0][0].name == "/points/point"  # dimension scale attached
    meta = read_metadata(path)
    assert meta["counts"] == {"pending": 12, "ok": 0, "failed": 0}
    assert meta["factorial"]["points_sha256"] == plan.points_hash() == meta["factorial_sha256"]
    assert meta["solver"] == SOLVER
    assert meta["package_version"] and meta["created"].endswith("+00:00")
    # the lubricant definition rebuilds an identical lubricant (same viscosity at the factorial temperature)
    rebuilt = lubricant_from_dict(meta["lubricant"])
    assert rebuilt.dynamic_viscosity(333.15) == lubricant.dynamic_viscosity(333.15)


def test_results_round_trip_bit_for_bit_and_table_has_the_contract_columns(tmp_path, plan, lubricant):
    path = tmp_path / "run.h5"
    with make_store(path, plan, lubricant) as store:
        for i in (0, 1, 2, 5, 7, 11):  # non-contiguous rows are written as separate runs
            store.record(i, status=OK, record=record_of(i), worker="host:1", worker_time=0.5)
        store.record(3, status=FAILED, error="SolverError: no convergence at 2.5 GPa")
        assert store.flush() == 7
    table = read_table(path, status=None)
    assert list(table.columns) == list(TABLE_COLUMNS) and list(table.columns[:22]) == CONTRACT_COLUMNS
    ok = read_table(path)
    assert list(ok["point"]) == [0, 1, 2, 5, 7, 11]
    for row in ok.itertuples():
        expected = record_of(row.point)
        for name in ("mu", "mu_std", "h_min", "h_central", "lambda_bar", "asperity_load_share", "p_max",
                     "wall_time", "iterations", "converged", "level"):
            assert getattr(row, name) == expected[name], name
        assert json.loads(row.effects) == json.loads(expected["effects"])
        assert row.attempts == 1 and row.worker == "host:1"
    failed = read_table(path, status="failed")
    assert list(failed["point"]) == [3] and failed["error"][0].startswith("SolverError")
    assert math.isnan(failed["mu"][0])
    assert len(read_table(path, status="pending")) == 5
    with pytest.raises(InputError, match="status"):
        read_table(path, status="done")


def test_attempts_accumulate_and_only_non_ok_rows_are_pending(tmp_path, plan, lubricant):
    path = tmp_path / "run.h5"
    with make_store(path, plan, lubricant) as store:
        store.record(4, status=FAILED, error="x")
    with DatasetStore.open(path, "r+") as store:
        assert 4 in store.pending_indices() and store.pending_indices().size == 12
        store.record(4, status=OK, record=record_of(4), attempts=2)
    with DatasetStore.open(path, "r") as store:
        assert store.column("attempts")[4] == 3
        assert 4 not in store.pending_indices() and store.pending_indices().size == 11


def test_buffered_rows_reach_the_disk_only_on_flush_and_readers_see_a_live_run(tmp_path, plan, lubricant):
    path = tmp_path / "run.h5"
    with make_store(path, plan, lubricant) as store:
        store.record(0, status=OK, record=record_of(0))
        assert store.buffered == 1
        assert read_metadata(path)["counts"]["ok"] == 0  # a reader (no file lock) while the writer is open
        store.flush()
        assert read_metadata(path)["counts"]["ok"] == 1


def test_writes_after_creation_touch_raw_data_only(tmp_path, plan, lubricant):
    """Crash safety by construction: recording and flushing rows neither grows the file nor moves any dataset,
    so a writer killed mid-run cannot leave HDF5 metadata half-written (only the sessions attribute changes)."""
    path = tmp_path / "run.h5"
    make_store(path, plan, lubricant).close()
    with h5py.File(path, "r") as h5:
        offsets = {name: h5["points"][name].id.get_offset() for name in h5["points"]}
    size = path.stat().st_size
    with DatasetStore.open(path, "r+") as store:
        for i in range(plan.size):
            store.record(i, status=OK if i % 3 else FAILED, record=record_of(i), error="e" * 2000)
        store.flush()
    assert path.stat().st_size == size
    with h5py.File(path, "r") as h5:
        assert {name: h5["points"][name].id.get_offset() for name in h5["points"]} == offsets
        assert all(h5["points"][name].chunks is None for name in h5["points"])


def test_resume_compatibility_is_checked_field_by_field(tmp_path, plan, lubricant):
    path = tmp_path / "run.h5"
    make_store(path, plan, lubricant).close()
    with DatasetStore.open(path, "r+") as store:
        store.check_compatible(factorial_sha256=plan.points_hash(), solver=dict(SOLVER),
                               lubricant=lubricant.to_json_dict())
        other = factorial_from_dict({**plan.to_dict(), "points_sha256": None,
                                     "axes": {**plan.to_dict()["axes"], "sr": [0.3]}})
        with pytest.raises(InputError, match="factorial"):
            store.check_compatible(factorial_sha256=other.points_hash())
        with pytest.raises(InputError, match=r"solver\.version.*'1' as recorded"):
            store.check_compatible(solver={**SOLVER, "version": "2"})
        with pytest.raises(InputError, match=r"solver\.level"):
            store.check_compatible(solver={**SOLVER, "level": "standard"})
        with pytest.raises(InputError, match="lubricant"):
            store.check_compatible(lubricant=load_lubricant("gear_oil_75w90").to_json_dict())
        changed = json.loads(json.dumps(lubricant.to_json_dict()))
        changed["traction"]["eyring_stress_mpa"] = 5.5
        with pytest.raises(InputError, match="lubricant"):
            store.check_compatible(lubricant=changed)


def test_existing_file_is_not_overwritten_by_accident(tmp_path, plan, lubricant):
    path = tmp_path / "run.h5"
    make_store(path, plan, lubricant).close()
    with pytest.raises(InputError, match="exists"):
        make_store(path, plan, lubricant)


def test_truncated_foreign_and_non_hdf5_files_give_one_clear_error(tmp_path, plan, lubricant):
    path = tmp_path / "run.h5"
    make_store(path, plan, lubricant).close()
    truncated = tmp_path / "truncated.h5"
    truncated.write_bytes(path.read_bytes()[: path.stat().st_size // 2])
    with pytest.raises(InputError, match="truncated.h5.*truncated"):
        read_table(truncated)
    foreign = tmp_path / "foreign.h5"
    with h5py.File(foreign, "w") as h5:
        h5["x"] = np.arange(3)
    with pytest.raises(InputError, match="foreign.h5.*foreign HDF5"):
        read_metadata(foreign)
    text = tmp_path / "notes.h5"
    text.write_text("not hdf5")
    with pytest.raises(InputError, match="notes.h5.*not a readable HDF5"):
        read_table(text)
    with pytest.raises(FileNotFoundError):
        read_table(tmp_path / "missing.h5")


@pytest.mark.parametrize("reader, failing_key", [
    (read_table, "sessions"),  # met while the file is validated on opening
    (read_metadata, "sessions"),
    (read_metadata, "package_version"),  # met after the file was opened and validated
    (summarize, "package_version"),  # `gearloss dataset info` on a live run
])
def test_a_read_error_inside_the_file_is_one_clear_error(tmp_path, plan, lubricant, monkeypatch, reader, failing_key):
    """A reader without a lock can meet a half-written attribute while the run's writer flushes (the h5py OSError
    'len not positive after adjustment for EOA' seen in CI): it gets the store's InputError naming the file, which a
    caller polling a live run catches and retries, not a raw h5py error."""
    path = tmp_path / "run.h5"
    make_store(path, plan, lubricant).close()
    original = h5py.AttributeManager.__getitem__

    def failing(self, name):
        if name == failing_key:
            raise OSError("Can't synchronously read data (len not positive after adjustment for EOA)")
        return original(self, name)

    monkeypatch.setattr(h5py.AttributeManager, "__getitem__", failing)
    with pytest.raises(InputError, match=r"run\.h5.*could not be read.*EOA"):
        reader(path)


@pytest.mark.parametrize("damage, message", [
    (lambda h5: h5.attrs.__setitem__("format_version", 99), "format_version 99"),
    (lambda h5: h5["points"].__delitem__("mu"), "points/mu"),
    (lambda h5: h5.attrs.__setitem__("solver", "{not json"), "'solver'"),
    (lambda h5: h5.attrs.__setitem__("format", "something-else"), "something-else"),
])
def test_damaged_files_name_what_is_wrong(tmp_path, plan, lubricant, damage, message):
    path = tmp_path / "run.h5"
    make_store(path, plan, lubricant).close()
    with h5py.File(path, "r+") as h5:
        damage(h5)
    with pytest.raises(InputError, match=message):
        read_metadata(path)


def test_long_texts_fit_their_columns(tmp_path, plan, lubricant):
    n = EFFECTS_WIDTH // 30  # ~37 bytes per reason at full precision, ~23 rounded
    plan_json = {"roughness": True, "transient": True, "mode": "auto",
                 "reasons": {f"criterion_{i:03d}": 1.0 / 3.0 for i in range(n)}}
    assert len(json.dumps(plan_json)) > EFFECTS_WIDTH
    rounded = json.loads(encode_effects(plan_json))
    assert rounded["reasons"]["criterion_000"] == 0.3333 and len(rounded["reasons"]) == n
    plan_json["reasons"] = {f"criterion_{i:03d}": 1.0 / 3.0 for i in range(3 * n)}
    raw = encode_effects(plan_json)
    assert len(raw) <= EFFECTS_WIDTH
    decoded = json.loads(raw)
    assert decoded["roughness"] is True and decoded["transient"] is True and "omitted" in decoded["reasons"]
    path = tmp_path / "run.h5"
    with make_store(path, plan, lubricant) as store:
        store.record(0, status=FAILED, error="start " + "é" * 1000 + " end")
    error = read_table(path, status="failed")["error"][0]
    assert len(error.encode()) <= ERROR_WIDTH and error.startswith("start") and error.endswith("end")


def test_a_compressed_copy_is_readable_but_not_resumable(tmp_path, plan, lubricant):
    """Archiving with gzip (as h5repack would) keeps the file readable; the writer refuses chunked layouts."""
    path, packed = tmp_path / "run.h5", tmp_path / "packed.h5"
    with make_store(path, plan, lubricant) as store:
        store.record(2, status=OK, record=record_of(2))
    with h5py.File(path, "r") as src, h5py.File(packed, "w") as dst:
        for key, value in src.attrs.items():
            dst.attrs[key] = value
        group = dst.create_group("points")
        for name, data in src["points"].items():
            group.create_dataset(name, data=data[...], dtype=data.dtype, compression="gzip", shuffle=True)
    assert read_table(packed).equals(read_table(path))
    with pytest.raises(InputError, match="chunked"):
        DatasetStore.open(packed, "r+")


def test_files_without_the_later_warnings_column_are_read_and_resumed(tmp_path, plan, lubricant):
    """'warnings' was added within format version 1: older files read it as "" and take new rows without it."""
    path = tmp_path / "run.h5"
    make_store(path, plan, lubricant).close()
    with h5py.File(path, "r+") as h5:
        del h5["points/warnings"]
    with DatasetStore.open(path, "r+") as store:
        store.record(1, status=OK, record=record_of(1), warnings="RuntimeWarning x1 (a.py:1)")
    table = read_table(path)
    assert list(table["point"]) == [1] and table["warnings"][0] == "" and table["mu"][0] == record_of(1)["mu"]


def test_a_deterministic_file_is_not_resumed_under_other_deterministic_numerics(tmp_path, plan, lubricant):
    """The deterministic model's numerics carry their own version (det-YYYY.MM-n); the solver configuration of a
    deterministic run records it, and a file made under another one is refused rather than mixed."""
    from ehl_dataset.dataset.runner import solver_config
    from ehl_dataset.solvers.deterministic import MODEL_VERSION

    config = solver_config("ehl_dataset.solver:solve_contact", "fast", "auto", model="deterministic")
    assert config["model_version"] == MODEL_VERSION
    assert "model_version" not in solver_config("ehl_dataset.solver:solve_contact", "fast", "auto")
    # the reference level's planner sends every rough contact to the deterministic model
    assert solver_config("ehl_dataset.solver:solve_contact", "reference", "auto")["model_version"] == MODEL_VERSION
    path = tmp_path / "det.h5"
    make_store(path, plan, lubricant, **{**config, "model_version": "det-2026.11-1"}).close()
    with DatasetStore.open(path, "r+") as store:
        with pytest.raises(InputError, match=r"solver\.model_version.*det-2026\.11-1"):
            store.check_compatible(solver=config)
    from ehl_dataset.solvers.wide_contact import WIDE_MODEL_VERSION

    assert config["wide_model_version"] == WIDE_MODEL_VERSION
    path = tmp_path / "wide.h5"
    make_store(path, plan, lubricant, **{**config, "wide_model_version": "wide-2026.10-1"}).close()
    with DatasetStore.open(path, "r+") as store:
        with pytest.raises(InputError, match=r"solver\.wide_model_version.*wide-2026\.10-1"):
            store.check_compatible(solver=config)
