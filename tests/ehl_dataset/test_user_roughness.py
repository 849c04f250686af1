"""A user's measured roughness profile through ``solve_contact`` and ``gearloss contact solve`` (issue 3,
deliverable 1: the loader's profile must reach the transient solver)."""

import json

import numpy as np
import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile, generate_profile, load_profile
from ehl_dataset.solver import solve_contact
from ehl_dataset.validation import InputError
from workflows.cli import main

LUB = load_lubricant("atf")
# a light, fast rough case near λ̄ = 1.3 (1 GPa, 5 mm, 5 m/s, SR 0.5, 25 °C, Rq 0.3 µm)
CASE = ContactCase.from_engineering(1.0, 5, 5, 0.5, 25, 0.3, 0.3)


def _write(path, profile):
    x_um = np.arange(profile.z.size) * profile.spacing * 1e6
    np.savetxt(path, np.column_stack([x_um, profile.z * 1e6]), header="x_um z_um")


def test_shipped_profile_passed_explicitly_gives_the_default_result():
    """Identity: passing the shipped baseline gives the default run bit for bit."""
    default = solve_contact(CASE, LUB, "fast", Effects.full())
    explicit = solve_contact(CASE, LUB, "fast", Effects.full(), roughness=baseline_profile())
    assert explicit.mu == default.mu and explicit.asperity_load_share == default.asperity_load_share
    assert explicit.extra["roughness_profile"] == default.extra["roughness_profile"]


def test_a_measured_profile_file_reaches_the_solver_and_is_recorded(tmp_path, capsys):
    """Another surface (same Rq, correlation length 5 µm instead of 15 µm, another seed), written as a two-column
    µm text file with a tilt that the loader must remove, changes the result and is named in it; the CLI gives the
    same μ as the library call."""
    other = generate_profile(8192, 0.5e-6, 5e-6, 0.5e-6, seed=7)
    tilted = other.z + 2e-3 * np.arange(other.z.size) * other.spacing  # a form error of 2 µm per mm
    path = tmp_path / "my_trace.txt"
    _write(path, type(other)(tilted, other.spacing, "tilted"))
    profile = load_profile(path)
    assert abs(np.polyfit(np.arange(profile.z.size), profile.z, 1)[0]) < 1e-12  # detrended
    res = solve_contact(CASE, LUB, "fast", Effects.full(), roughness=profile)
    base = solve_contact(CASE, LUB, "fast", Effects.full())
    assert res.converged, res.message
    assert "my_trace.txt" in res.extra["roughness_profile"]
    assert res.extra["roughness_correlation_length_m"] == pytest.approx(5e-6, rel=0.3)
    assert res.mu != base.mu
    code = main(["contact", "solve", "--p-h-gpa", "1", "--r-eq-mm", "5", "--u-r", "5", "--sr", "0.5", "--temp-c",
                 "25", "--rq1-um", "0.3", "--rq2-um", "0.3", "--level", "fast", "--effects", "full",
                 "--roughness-file", str(path), "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["mu"] == pytest.approx(res.mu, rel=1e-12)
    assert "my_trace.txt" in out["roughness_profile"]


def test_a_roughness_that_is_not_a_profile_is_refused():
    with pytest.raises(InputError, match="roughness"):
        solve_contact(CASE, LUB, "fast", Effects.full(), roughness=np.zeros(10))
