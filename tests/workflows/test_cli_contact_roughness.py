"""``gearloss contact solve --roughness NAME``: a registered profile by name, recorded in the result with its file
hash; an unknown name is one error listing the registered ones; a user's file is recorded by its name and hash."""

import hashlib
import json

import numpy as np

from ehl_dataset.data_files import data_path
from ehl_dataset.model.roughness import DEFAULT_PROFILE, PROFILES
from workflows.cli import main

# lightly rough, full film: λ̄ well above 3 at the fast level
BASE = ["contact", "solve", "--p-h-gpa", "1.2", "--r-eq-mm", "20", "--u-r", "5", "--sr", "0.3", "--temp-c", "90",
        "--level", "fast", "--rq1-um", "0.02", "--rq2-um", "0.02", "--json"]


def _json(capsys):
    return json.loads(capsys.readouterr().out)


def test_a_registered_name_is_solved_with_and_recorded(capsys):
    """The homogenised film-law model reads the profile (its record names the shipped file), and the result
    carries the registry name and the sha256 of the file's bytes (hashed here independently)."""
    assert main([*BASE, "--roughness", "flank_ground", "--model", "homogenised", "--closure", "film_law"]) == 0
    out = _json(capsys)
    digest = hashlib.sha256(data_path("roughness", PROFILES["flank_ground"].file).read_bytes()).hexdigest()
    assert out["roughness_name"] == "flank_ground" and out["roughness_sha256"] == digest
    assert "flank_ground" in out["roughness_profile"]  # what the solver itself records of the profile it used


def test_the_default_profile_is_recorded_and_smooth_surfaces_record_none(capsys):
    assert main(BASE) == 0
    out = _json(capsys)
    assert out["roughness_name"] == DEFAULT_PROFILE and out["roughness_sha256"] == PROFILES[DEFAULT_PROFILE].sha256
    smooth = [a for a in BASE if a not in ("--rq1-um", "--rq2-um", "0.02")]
    assert main(smooth) == 0
    out = _json(capsys)
    assert out["roughness_name"] is None and out["roughness_sha256"] is None


def test_an_unknown_name_is_one_error_listing_the_registered_names(capsys):
    assert main([*BASE, "--roughness", "shaved"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--roughness=shaved" in err
    assert all(name in err for name in PROFILES)


def test_a_user_file_is_recorded_by_its_name_and_hash(tmp_path, capsys):
    x = np.arange(256) * 0.5
    z = 0.1 * np.sin(2 * np.pi * x / 8.0) + 0.05 * np.sin(2 * np.pi * x / 3.0)
    trace = tmp_path / "ground_flank.txt"
    trace.write_text("\n".join(f"{a:.2f} {b:.5f}" for a, b in zip(x, z)) + "\n")
    assert main([*BASE, "--roughness-file", str(trace)]) == 0
    out = _json(capsys)
    assert out["roughness_name"] == "ground_flank.txt"
    assert out["roughness_sha256"] == hashlib.sha256(trace.read_bytes()).hexdigest()


def test_name_and_file_exclude_each_other_and_the_help_lists_every_name(tmp_path, capsys):
    assert main([*BASE, "--roughness", "flank_ground", "--roughness-file", str(tmp_path / "t.txt")]) == 2
    assert "not allowed with" in capsys.readouterr().err
    assert main(["contact", "solve", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert all(name in text for name in PROFILES)


def test_the_spectral_pressure_spread_reaches_the_planner_route(capsys):
    """``--fluctuations spectral`` on the planner's route (model auto) at λ̄ 0.3 on the flank-like profile:
    the result records the form, and its σ_p is E'Δq_f/4, below the inlet form's c(L_in/β)·E'Δq/4 there
    (docs/explanation/mixed-regime.md: the flank profile's slope sits in wavelengths that pass the conjunction)."""
    rough = [a if a != "0.02" else "0.33" for a in BASE]
    records = {}
    for form in ("inlet", "spectral"):
        assert main([*rough, "--roughness", "flank_ground", "--effects", "isothermal", "--fluctuations", form]) == 0
        out = _json(capsys)
        assert out["closure"] == "asperity"  # the planner's closure, the film law with the asperity load
        records[form] = out["micro_pressure"]
    assert records["inlet"]["form"] == "inlet" and records["spectral"]["form"] == "spectral"
    assert 0.0 < records["spectral"]["std_pa"] < records["inlet"]["std_pa"]
