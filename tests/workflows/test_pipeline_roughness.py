"""``--roughness`` on the pipeline and ``lubricant fit``: the run directory carries the profile, the dataset, the
off-grid sample, every adaptive batch and the coefficient file record it, the samples are solved on it, and a run
directory of another profile is not resumed."""

import json
import warnings

import pytest

from ehl_dataset.dataset.factorial import factorial_from_dict, load_factorial
from ehl_dataset.dataset.roughness_choice import choose_roughness
from ehl_dataset.dataset.store import read_metadata, read_table
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import DEFAULT_PROFILE, PROFILES, named_profile
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers.result import ContactResult
from workflows.adaptive import run_adaptive
from workflows.cli import main
from workflows.pipeline import check_inputs, default_out_dir
from workflows.surrogate_stage import offgrid_stage

FLANK = {"name": "baseline_synthetic", "sha256": PROFILES["baseline_synthetic"].sha256}


def test_the_default_directory_names_a_chosen_profile(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert default_out_dir("quick", "fast", "auto", None, "isothermal", "baseline_synthetic") == \
        "gearloss_quick_fast_isothermal_baseline_synthetic"
    assert default_out_dir("quick", "fast", roughness_name="my trace.txt") == "gearloss_quick_fast_my_trace"
    flank = check_inputs("quick", design=None, roughness=choose_roughness("baseline_synthetic"))
    assert flank.out_dir.name == "gearloss_quick_fast_isothermal_baseline_synthetic"
    assert flank.roughness.name == "baseline_synthetic"
    named_default = check_inputs("quick", design=None, roughness=choose_roughness(DEFAULT_PROFILE))
    assert named_default.out_dir == check_inputs("quick", design=None).out_dir  # the default adds nothing


def test_lubricant_fit_records_the_profile_in_dataset_and_coefficients_and_refuses_another(tmp_path, capsys):
    """The smoke factorial (smooth solves, seconds): what is checked is the record and the refusal."""
    out = tmp_path / "run"
    argv = ["lubricant", "fit", "atf", "--factorial", "smoke", "--out-dir", str(out), "--workers", "1",
            "--progress", "none", "--json"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        assert main([*argv, "--roughness", "baseline_synthetic"]) == 0
    payload = json.loads(capsys.readouterr().out)
    assert payload["stages"]["dataset"]["roughness"] == FLANK
    assert read_metadata(out / "dataset.h5")["roughness"] == FLANK
    assert json.loads((out / "atf_smoke.json").read_text())["roughness"] == FLANK
    assert main([*argv, "--roughness", DEFAULT_PROFILE]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1
    assert "--roughness" in err and "baseline_synthetic" in err and DEFAULT_PROFILE in err


def test_the_offgrid_sample_is_solved_on_the_runs_profile(tmp_path):
    plan = factorial_from_dict({"name": "narrow", "level": "fast", "effects": "auto", "axes": {
        "p_h_gpa": [1.0], "r_eq_mm": [10.0], "u_r_m_s": [2.0], "sr": [0.3], "temp_c": [90.0],
        "roughness_um": [[0.2, 0.2], [0.4, 0.4]]}})
    solved = offgrid_stage(tmp_path, plan, load_lubricant("atf"), level="fast", effects="auto", model="auto", n=2,
                           workers=0, progress="none", roughness=choose_roughness("baseline_synthetic"))
    assert solved["details"]["ok"] == 2
    assert read_metadata(solved["artefact"])["roughness"] == FLANK
    profile = named_profile("baseline_synthetic")
    for row in read_table(solved["artefact"]).itertuples():
        case = ContactCase(row.p_h, row.r_eq, row.u_r, row.sr, row.temperature, row.rq1, row.rq2)
        expected = solve_contact(case, "atf", level="fast", effects="auto", roughness=profile).mu
        assert row.mu == pytest.approx(expected, rel=1e-12)


def flank_only_solve(case, lubricant, level="fast", effects="auto", roughness=None):
    """A stand-in that solves only on the flank-like profile (a point solved on any other fails): μ from a smooth
    function of the inputs, λ̄ from Rq (the adaptive workflow, not the physics, is under test)."""
    if roughness is None or roughness.name != "baseline_synthetic":
        raise AssertionError(f"solved on {getattr(roughness, 'name', 'the default profile')}")
    mu = 0.02 + 0.01 * abs(case.sr) / (1.0 + case.u_r / 10.0)
    h = 2e-7 * (case.u_r / 10.0) ** 0.7
    return ContactResult(mu=mu, h_min=h, h_central=4.0 / 3.0 * h, p_max=case.p_h, converged=True, iterations=1,
                         wall_time=1e-3, level=level, effects={"mode": effects, "reasons": {}},
                         lambda_bar=h / case.s_c, asperity_load_share=0.0)


def test_every_adaptive_batch_is_solved_on_and_records_the_profile(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        result = run_adaptive(tmp_path, load_factorial("quick"), load_lubricant("atf"), level="fast",
                              effects="isothermal", model="auto", budget=24, initial=20, batch=4, workers=0,
                              progress="none", solver=flank_only_solve, roughness=choose_roughness("baseline_synthetic"))
    assert result.solves == 24 and len(result.batch_files) == 2
    for name in result.batch_files:
        path = tmp_path / "adaptive" / name
        assert read_metadata(path)["roughness"] == FLANK
        assert read_metadata(path)["counts"]["failed"] == 0
