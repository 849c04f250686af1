"""A user's measured roughness profile through ``solve_contact`` and ``gearloss contact solve`` (the
loader's profile must reach the rough solvers: the deterministic transient model and the
production film-law model)."""

import json

import numpy as np
import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import (BASELINE_NAME, DEFAULT_PROFILE, baseline_profile, default_profile,
                                         generate_profile, load_profile, named_profile)
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers.deterministic import DeterministicOptions
from ehl_dataset.validation import InputError
from workflows.cli import main

LUB = load_lubricant("atf")
# a light, fast rough case near λ̄ = 1.3 (1 GPa, 5 mm, 5 m/s, SR 0.5, 25 °C, Rq 0.3 µm)
CASE = ContactCase.from_engineering(1.0, 5, 5, 0.5, 25, 0.3, 0.3)
# a short, coarse deterministic run (one pass, 4 points per correlation length): what reaches the solver is the
# point here, not a converged mu
SHORT = DeterministicOptions(points_per_beta=4.0, points_per_ell=0.3, inlet_resolution=0.5, ramp_passes=0.25,
                             startup_passes=0.25, min_average_passes=0.5, max_passes=1.0, mu_sem_target=0.0)


def _deterministic(roughness=None):
    return solve_contact(CASE, LUB, "fast", Effects.full(), roughness=roughness, model="deterministic",
                         deterministic=SHORT)


def _write(path, profile):
    x_um = np.arange(profile.z.size) * profile.spacing * 1e6
    np.savetxt(path, np.column_stack([x_um, profile.z * 1e6]), header="x_um z_um")


def test_shipped_profile_passed_explicitly_gives_the_default_result():
    """Identity: passing the shipped default profile gives the default run bit for bit, on the production route and
    on the deterministic one (which the baseline profile's β keeps short here: a named profile passed explicitly
    equals it passed by name)."""
    default = solve_contact(CASE, LUB, "fast")
    explicit = solve_contact(CASE, LUB, "fast", roughness=default_profile())
    assert explicit.mu == default.mu and explicit.extra["roughness_profile"] == default.extra["roughness_profile"]
    assert default.extra["roughness_name"] == DEFAULT_PROFILE
    by_name = _deterministic(named_profile(BASELINE_NAME))
    explicit = _deterministic(baseline_profile())
    assert explicit.mu == by_name.mu and explicit.asperity_load_share == by_name.asperity_load_share
    assert "baseline" in by_name.extra["roughness_profile"]


def test_a_measured_profile_file_reaches_the_solver_and_is_recorded(tmp_path, capsys):
    """Another surface (same Rq, correlation length 5 µm instead of 15 µm, another seed), written as a two-column
    µm text file with a tilt that the loader must remove, changes the result and is named in it; the CLI gives the
    same μ as the library call (the production route: the film-law model, whose planner reads the correlation
    length)."""
    other = generate_profile(8192, 0.5e-6, 5e-6, 0.5e-6, seed=7)  # a 4 mm trace: 820 β
    tilted = other.z + 2e-3 * np.arange(other.z.size) * other.spacing  # a form error of 2 µm per mm
    path = tmp_path / "my_trace.txt"
    _write(path, type(other)(tilted, other.spacing, "tilted"))
    profile = load_profile(path)
    assert abs(np.polyfit(np.arange(profile.z.size), profile.z, 1)[0]) < 1e-12  # detrended
    res = _deterministic(profile)
    base = _deterministic(baseline_profile())
    assert res.converged, res.message
    assert "my_trace.txt" in res.extra["roughness_profile"]
    assert res.extra["roughness_correlation_length_m"] == pytest.approx(5e-6, rel=0.3)
    assert res.mu != base.mu
    production = solve_contact(CASE, LUB, "fast", "auto", roughness=profile)
    assert production.converged and production.effects["roughness"]
    # too short for the default 8 windows of 512 β: one window of 256 β (dry_contact.windows_that_fit)
    assert production.extra["roughness_windows"] == {"n_windows": 1, "window_correlation_lengths": 256.0}
    assert production.mu != solve_contact(CASE, LUB, "fast", "auto").mu
    code = main(["contact", "solve", "--p-h-gpa", "1", "--r-eq-mm", "5", "--u-r", "5", "--sr", "0.5", "--temp-c",
                 "25", "--rq1-um", "0.3", "--rq2-um", "0.3", "--level", "fast", "--roughness-file", str(path),
                 "--json"])
    out = json.loads(capsys.readouterr().out)
    assert code == 0 and out["mu"] == pytest.approx(production.mu, rel=1e-12)
    assert "my_trace.txt" in out["roughness_profile"]


def test_a_roughness_that_is_not_a_profile_is_refused():
    with pytest.raises(InputError, match="roughness"):
        solve_contact(CASE, LUB, "fast", Effects.full(), roughness=np.zeros(10))


def test_the_film_law_takes_what_a_short_trace_allows_and_names_the_length_it_needs():
    """``windows_that_fit``: the default windows (8 of 512 β) for a long profile (the shipped baseline, unchanged
    results); fewer, then shorter windows for a short measured trace; below two stretches of 64 β one clear error
    naming the samples needed and those given."""
    from dataclasses import replace

    from ehl_dataset.model.dry_contact import DryContactSettings, _samples_needed, windows_that_fit

    assert windows_that_fit(baseline_profile()) == DryContactSettings()
    short = generate_profile(2 * 2 * 520 * 10 + 10, 0.5e-6, 5e-6, 0.5e-6, seed=3)  # about two windows of 512 β
    fitted = windows_that_fit(short)
    assert fitted.window_correlation_lengths == 512.0 and 1 <= fitted.n_windows < 8
    # the most windows that fit: these fit, one more does not
    assert _samples_needed(short, fitted) <= short.z.size
    assert _samples_needed(short, replace(fitted, n_windows=fitted.n_windows + 1)) > short.z.size
    tiny = generate_profile(1000, 0.5e-6, 5e-6, 0.5e-6, seed=3)  # 100 β
    with pytest.raises(InputError, match="roughness profile.*samples.*it has 1000"):
        windows_that_fit(tiny)
