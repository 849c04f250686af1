"""A dataset run on a chosen roughness profile: the choice reaches every worker (resolved and hash-checked there),
every rough solve uses it, the file records it, and a resume on another profile is refused naming both.

The physics anchor is the solver itself: a stored row must equal ``solve_contact`` of the same point with the same
profile (one BLAS thread in both, so to rounding), and a smooth row must not depend on the profile at all (a smooth
contact reads no roughness). The rough point (1.0 GPa, r_eq 10 mm, u_r 2 m/s, SR 0.3, 90 °C, Rq 0.3/0.3 µm, ATF,
``fast``; λ̄ 0.18) runs the asperity closure on the film law, whose heights and spectrum come from the profile: 0.01824
on the default flank-like profile against 0.01856 on baseline_synthetic (``gearloss contact solve --p-h-gpa 1.0 --r-eq-mm 10 --u-r 2
--sr 0.3 --temp-c 90 --rq1-um 0.3 --rq2-um 0.3 --level fast --roughness NAME``).
"""

import hashlib
import shutil

import numpy as np
import pytest

from ehl_dataset.data_files import data_path
from ehl_dataset.dataset import roughness_choice
from ehl_dataset.dataset.factorial import canonical_json, factorial_from_dict
from ehl_dataset.dataset.roughness_choice import RoughnessChoice, choose_roughness
from ehl_dataset.dataset.runner import (DEFAULT_SOLVER, PointTask, compute_point, resume_run, run_factorial,
                                        solver_config)
from ehl_dataset.dataset.store import FAILED, DatasetStore, read_metadata, read_table
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import DEFAULT_PROFILE, PROFILES, load_profile, named_profile
from ehl_dataset.solver import solve_contact
from ehl_dataset.validation import InputError
from workflows.cli import main

ROUGH = (1.0e9, 10.0e-3, 2.0, 0.3, 363.15, 0.3e-6, 0.3e-6)
SMOOTH = ROUGH[:5] + (0.0, 0.0)
FLANK = {"name": "baseline_synthetic", "sha256": PROFILES["baseline_synthetic"].sha256}


def two_point_plan():
    """The rough film-law point and the same contact smooth (module docstring)."""
    return factorial_from_dict({"name": "two", "level": "fast", "effects": "auto", "axes": {
        "p_h_gpa": [1.0], "r_eq_mm": [10.0], "u_r_m_s": [2.0], "sr": [0.3], "temp_c": [90.0],
        "roughness_um": [[0.3, 0.3], [0.0, 0.0]]}})


def mu_by_rq(path) -> dict[float, float]:
    table = read_table(path)
    assert table["converged"].all()
    return {float(rq): float(mu) for rq, mu in zip(table["rq1"], table["mu"])}


def reference_mu(point, profile=None) -> float:
    result = solve_contact(ContactCase(*point), "atf", level="fast", effects="auto", roughness=profile)
    assert result.converged
    return result.mu


@pytest.fixture(scope="module")
def default_run(tmp_path_factory):
    path = tmp_path_factory.mktemp("default") / "default.h5"
    assert run_factorial(path, two_point_plan(), workers=0, progress="none").ok == 2
    return path


def test_a_run_on_baseline_synthetic_records_it_and_every_solve_in_a_worker_uses_it(tmp_path, default_run):
    """Computed by a worker process (no warm-up in the coordinator); the record is the registry name and the
    sha256 of the shipped file's bytes (hashed here independently)."""
    path = tmp_path / "flank.h5"
    summary = run_factorial(path, two_point_plan(), workers=1, warm_up=False, progress="none",
                            roughness=choose_roughness("baseline_synthetic"))
    assert summary.ok == 2 and summary.executor["executor"] == "local"
    digest = hashlib.sha256(data_path("roughness", PROFILES["baseline_synthetic"].file).read_bytes()).hexdigest()
    assert read_metadata(path)["roughness"] == {"name": "baseline_synthetic", "sha256": digest}
    flank, default = mu_by_rq(path), mu_by_rq(default_run)
    assert flank[ROUGH[5]] == pytest.approx(reference_mu(ROUGH, named_profile("baseline_synthetic")), rel=1e-12)
    assert default[ROUGH[5]] == pytest.approx(reference_mu(ROUGH), rel=1e-12)
    assert abs(flank[ROUGH[5]] / default[ROUGH[5]] - 1.0) > 1e-3  # 0.01856 against 0.01824: far above the 1e-6 tolerance
    assert flank[0.0] == default[0.0]  # a smooth contact reads no profile
    assert read_metadata(default_run)["roughness"] == {"name": DEFAULT_PROFILE,
                                                        "sha256": PROFILES[DEFAULT_PROFILE].sha256}


def test_naming_the_default_profile_solves_and_records_exactly_as_naming_none(tmp_path, default_run):
    path = tmp_path / "named_default.h5"
    run_factorial(path, two_point_plan(), workers=0, progress="none", roughness=choose_roughness(DEFAULT_PROFILE))
    assert mu_by_rq(path) == mu_by_rq(default_run)
    assert read_metadata(path)["roughness"] == read_metadata(default_run)["roughness"]
    assert read_metadata(path)["solver"] == read_metadata(default_run)["solver"]


def test_resume_takes_the_recorded_profile_and_refuses_another_naming_both(tmp_path):
    """A file recording baseline_synthetic with its rows pending: a resume without an option solves them on baseline_synthetic;
    a resume or run on another profile is one error naming both profiles and the option that continues it."""
    plan = two_point_plan()
    path = tmp_path / "pending.h5"
    with DatasetStore.create(path, plan.points(), factorial=plan.to_dict(),
                             solver=solver_config(DEFAULT_SOLVER, "fast", "auto"),
                             lubricant=load_lubricant("atf").to_json_dict(), roughness=FLANK):
        pass
    for attempt in (lambda: resume_run(path, workers=0, progress="none",
                                       roughness=choose_roughness(DEFAULT_PROFILE)),
                    lambda: run_factorial(path, plan, workers=0, progress="none")):
        with pytest.raises(InputError) as err:
            attempt()
        message = str(err.value)
        assert "baseline_synthetic" in message and DEFAULT_PROFILE in message
        assert "continue it with --roughness baseline_synthetic" in message
    assert read_table(path, status=None)["status"].tolist() == ["pending"] * 2  # the refused calls computed nothing
    assert resume_run(path, workers=0, progress="none").ok == 2
    assert mu_by_rq(path)[ROUGH[5]] == pytest.approx(reference_mu(ROUGH, named_profile("baseline_synthetic")), rel=1e-12)


def test_a_file_that_records_no_profile_is_not_continued_on_another(tmp_path):
    plan = two_point_plan()
    path = tmp_path / "bare.h5"
    with DatasetStore.create(path, plan.points(), factorial=plan.to_dict(),
                             solver=solver_config(DEFAULT_SOLVER, "fast", "auto"),
                             lubricant=load_lubricant("atf").to_json_dict()):
        pass
    with pytest.raises(InputError, match="records no roughness profile"):
        resume_run(path, workers=0, progress="none", roughness=choose_roughness("baseline_synthetic"))


def test_unknown_name_is_one_error_listing_the_registered_ones(tmp_path, capsys):
    with pytest.raises(InputError, match="baseline_synthetic"):
        choose_roughness("shaved")
    out = tmp_path / "never.h5"
    assert main(["dataset", "run", "--factorial", "smoke", "--out", str(out), "--roughness", "shaved"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--roughness=shaved" in err
    assert "baseline_synthetic" in err and "baseline_synthetic" in err
    assert not out.exists()


@pytest.fixture()
def user_trace(tmp_path):
    """A user's two-column file (µm): the flank-like profile's data under another name."""
    trace = tmp_path / "my_trace.txt"
    shutil.copy(data_path("roughness", PROFILES["baseline_synthetic"].file), trace)
    return trace


def test_a_user_file_is_recorded_by_name_and_hash_and_solved_on(tmp_path, user_trace, capsys):
    choice = choose_roughness(path=user_trace)
    digest = hashlib.sha256(user_trace.read_bytes()).hexdigest()
    assert choice.record == {"name": "my_trace.txt", "sha256": digest}
    path = tmp_path / "user.h5"
    assert run_factorial(path, two_point_plan(), workers=0, progress="none", roughness=choice).ok == 2
    meta = read_metadata(path)
    assert meta["roughness"] == choice.record and meta["solver"]["roughness_unit"] == "um"
    assert mu_by_rq(path)[ROUGH[5]] == pytest.approx(reference_mu(ROUGH, load_profile(user_trace)), rel=1e-12)
    # a resume needs the file again (its path is not recorded), with the same unit
    with pytest.raises(InputError, match="--roughness-file my_trace.txt"):
        resume_run(path, workers=0, progress="none")
    with pytest.raises(InputError, match="roughness_unit"):
        resume_run(path, workers=0, progress="none", roughness=choose_roughness(path=user_trace, unit="mm"))
    assert resume_run(path, workers=0, progress="none", roughness=choice).computed == 0
    assert main(["dataset", "resume", str(path), "--workers", "0", "--progress", "none"]) == 2
    assert "--roughness-file" in capsys.readouterr().err


def test_a_worker_refuses_a_profile_file_that_is_not_the_one_chosen(tmp_path, user_trace):
    """The hash check where the profile is resolved: after the file changed, the point fails with the reason
    instead of being solved on another profile."""
    choice = choose_roughness(path=user_trace)
    user_trace.write_text(user_trace.read_text().replace("\n", "\n# changed\n", 1))
    roughness_choice._RESOLVED.clear()  # a fresh worker process
    task = PointTask(0, ROUGH, canonical_json(load_lubricant("atf").to_json_dict()), "fast", "auto",
                     roughness=choice)
    result = compute_point(task)
    assert result["status"] == FAILED and "sha256" in result["error"] and "changed" in result["error"]
    wrong = RoughnessChoice("baseline_synthetic", "0" * 64)
    assert "sha256" in compute_point(PointTask(0, ROUGH, task.lubricant_json, "fast", "auto",
                                               roughness=wrong))["error"]


def test_a_solver_without_a_roughness_keyword_is_refused_before_anything_runs(tmp_path):
    def bare_solve(case, lubricant, level="fast", effects="auto"):
        raise AssertionError("not called")

    with pytest.raises(InputError, match="does not accept it"):
        run_factorial(tmp_path / "x.h5", two_point_plan(), workers=0, progress="none", solver=bare_solve,
                      roughness=choose_roughness("baseline_synthetic"))
    assert not (tmp_path / "x.h5").exists()


@pytest.mark.slow
def test_dask_workers_resolve_the_profile_themselves(tmp_path):
    """Dask workers are fresh processes (nothing inherited from the coordinator): they get the choice, resolve it
    and solve on it."""
    pytest.importorskip("distributed")
    path = tmp_path / "dask.h5"
    summary = run_factorial(path, two_point_plan(), workers=1, scheduler="dask-local", progress="none",
                            roughness=choose_roughness("baseline_synthetic"))
    assert summary.ok == 2 and summary.executor["executor"] == "dask"
    assert read_metadata(path)["roughness"] == FLANK
    assert mu_by_rq(path)[ROUGH[5]] == pytest.approx(reference_mu(ROUGH, named_profile("baseline_synthetic")), rel=1e-12)
    assert np.isfinite(mu_by_rq(path)[0.0])
