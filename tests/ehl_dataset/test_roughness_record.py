"""Which roughness profile a dataset used: recorded in the store (name and sha256 of the shipped file), shown by
``dataset info``, checked on resume; files written before the record load as before and say "not recorded"."""

import hashlib
import shutil
from pathlib import Path

import pytest

from ehl_dataset.data_files import data_path
from ehl_dataset.dataset.factorial import factorial_from_dict
from ehl_dataset.dataset.roughness_choice import choose_roughness
from ehl_dataset.dataset.runner import DEFAULT_SOLVER, dataset_roughness, resume_run, run_factorial, solver_config
from ehl_dataset.dataset.store import DatasetStore, read_metadata, summarize
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import DEFAULT_PROFILE, PROFILES
from ehl_dataset.model.roughness_identity import describe_roughness, roughness_identity
from ehl_dataset.validation import InputError
from workflows.cli import main

OLD_FILE = Path(__file__).parent / "data" / "smoke_partial_v7.h5"


def sha256_of(path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def one_point_plan():
    """One lightly rough full-film point (λ̄ ≫ 3 at 20 m/s): the steady solve, a fraction of a second."""
    return factorial_from_dict({"name": "one", "level": "fast", "effects": "auto", "axes": {
        "p_h_gpa": [0.5], "r_eq_mm": [20.0], "u_r_m_s": [20.0], "sr": [0.3], "temp_c": [75.0],
        "roughness_um": [[0.05, 0.05]]}})


def test_the_default_solver_records_the_default_profile_by_its_file_hash():
    """The record is the registry name and the sha256 of the shipped file's bytes (hashed here independently);
    a solve function the runner does not know records nothing."""
    record = dataset_roughness(DEFAULT_SOLVER)
    entry = PROFILES[DEFAULT_PROFILE]
    assert record == {"name": DEFAULT_PROFILE, "sha256": sha256_of(data_path("roughness", entry.file))}
    assert record["sha256"] == entry.sha256
    assert dataset_roughness(lambda case, lubricant, level="fast", effects="auto": None) is None


def test_a_user_file_is_recorded_by_its_name_and_bytes(tmp_path):
    trace = tmp_path / "sub" / "flank trace.txt"
    trace.parent.mkdir()
    trace.write_text("# x z\n" + "\n".join(f"{i * 0.5:.1f} {(-1) ** i * 0.1 * (i % 7):.3f}" for i in range(64)))
    record = roughness_identity(path=trace)
    assert record == {"name": "flank trace.txt", "sha256": sha256_of(trace)}  # no directory: no machine path
    assert describe_roughness(record) == f"flank trace.txt (sha256 {record['sha256'][:12]}...)"
    assert describe_roughness(None) == "not recorded"


def test_a_run_records_its_profile_and_dataset_info_prints_it(tmp_path, capsys):
    path = tmp_path / "one.h5"
    summary = run_factorial(path, one_point_plan(), workers=0, progress="none")
    assert summary.ok == 1
    expected = {"name": DEFAULT_PROFILE, "sha256": PROFILES[DEFAULT_PROFILE].sha256}
    assert read_metadata(path)["roughness"] == expected
    assert summarize(path)["roughness"] == expected
    assert main(["dataset", "info", str(path)]) == 0
    assert f"roughness  {DEFAULT_PROFILE} (sha256 {expected['sha256']})" in capsys.readouterr().out
    assert main(["dataset", "info", str(path), "--json"]) == 0
    assert '"roughness": {' in capsys.readouterr().out


def test_a_file_without_the_record_loads_and_says_not_recorded(tmp_path, capsys):
    """An old file (no roughness attribute) reads as before: roughness None, 'not recorded' in dataset info."""
    path = tmp_path / "old.h5"
    shutil.copy(OLD_FILE, path)
    assert read_metadata(path)["roughness"] is None
    assert main(["dataset", "info", str(path)]) == 0
    assert "roughness  not recorded" in capsys.readouterr().out


def test_resume_refuses_another_profile_and_continues_a_file_that_records_none(tmp_path):
    """A file that records a profile is not continued on another one (e.g. the default, after it changed: a resume
    without a profile option takes the recorded one, so the refusal is of an explicit choice); a file that records
    none is continued as before."""
    plan = one_point_plan()
    other = {"name": "baseline_synthetic", "sha256": PROFILES["baseline_synthetic"].sha256}
    config = solver_config(DEFAULT_SOLVER, "fast", "auto")
    lubricant = load_lubricant("atf").to_json_dict()
    path = tmp_path / "other.h5"
    with DatasetStore.create(path, plan.points(), factorial=plan.to_dict(), solver=config, lubricant=lubricant,
                             roughness=other) as store:
        assert store.roughness == other
        with pytest.raises(InputError, match="roughness") as err:
            store.check_compatible(roughness=dataset_roughness(DEFAULT_SOLVER))
        assert "baseline_synthetic" in str(err.value) and DEFAULT_PROFILE in str(err.value)
        store.check_compatible(roughness=other)
    with pytest.raises(InputError, match="roughness"):
        resume_run(path, workers=0, progress="none", roughness=choose_roughness(DEFAULT_PROFILE))
    bare = tmp_path / "bare.h5"
    with DatasetStore.create(bare, plan.points(), factorial=plan.to_dict(), solver=config,
                             lubricant=lubricant) as store:
        assert store.roughness is None
        store.check_compatible(roughness=dataset_roughness(DEFAULT_SOLVER))


def test_a_malformed_record_is_refused_naming_it(tmp_path):
    plan = one_point_plan()
    with pytest.raises(InputError, match="roughness"):
        DatasetStore.create(tmp_path / "bad.h5", plan.points(), factorial=plan.to_dict(), solver={}, lubricant={},
                            roughness={"name": "baseline_synthetic", "sha256": "abc"})
