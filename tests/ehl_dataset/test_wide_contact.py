"""The wide-contact route of the deterministic model (ehl_dataset.solvers.wide_contact): the film law that feeds
its windows, the choice of route, and its smooth limit."""

import dataclasses
import json
import math
from functools import partial
from pathlib import Path

import numpy as np
import pytest
from scipy.optimize import curve_fit

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solvers.deterministic import DeterministicOptions, solve_deterministic
from ehl_dataset.solvers.wide_contact import (FILM_LAW_C, FILM_LAW_D, FILM_LAW_K, WideOptions, fed_central_film,
                                              inlet_length, solve_deterministic_contact, takes_windows)
from ehl_dataset.validation import InputError


# the numbers these tests check were measured on the baseline profile; a call may name another one
solve_deterministic = partial(solve_deterministic, roughness=baseline_profile())
solve_deterministic_contact = partial(solve_deterministic_contact, roughness=baseline_profile())


FILM_LAW_DATA = Path(__file__).resolve().parents[2] / "validation" / "results" / "deterministic_film_law.json"
TINY = dict(points_per_beta=4.0, points_per_ell=0.01, wide_windows=3, window_length_beta=4.0)
"""A coarse window layout (3 windows of 4 β at β/4) that keeps a wide run to seconds."""


def test_the_film_law_constants_are_the_fit_of_the_recorded_resolved_runs():
    """FILM_LAW_C, _D, _K are the least-squares fit of Δ/σ = c (L_in/β)^k/(H + d) to the resolved runs recorded by
    ``python validation/deterministic_film_law.py``; a rerun that changes the points must update the constants."""
    data = json.loads(FILM_LAW_DATA.read_text())
    H = np.array([p["H"] for p in data["points"]])
    inlet = np.array([p["inlet_over_beta"] for p in data["points"]])
    excess = np.array([p["excess_over_sigma"] for p in data["points"]])
    (c, d, k), _ = curve_fit(lambda X, c, d, k: c * X[1] ** k / (X[0] + d), (H, inlet), excess, p0=(0.4, 0.4, 0.4))
    assert (c, d, k) == pytest.approx((FILM_LAW_C, FILM_LAW_D, FILM_LAW_K), abs=0.0015)
    predicted = np.array([fed_central_film(p["smooth_film_m"], p["sigma_m"], p["inlet_over_beta"])
                          for p in data["points"]])
    content = np.array([p["content_film_m"] for p in data["points"]])
    assert np.max(np.abs(predicted / content - 1.0)) == pytest.approx(data["fit"]["film_error_max"], abs=2e-3)


def test_the_film_law_predicts_a_resolved_contact_it_was_not_fitted_on():
    """W1 (a/β = 23.6, resolved at β/8 under det-2026.11-6: time-averaged central gap 678 nm) is in no fit; the
    two-variable law predicts its film within 2 % (the one-variable law c/(H + d) missed it by 14 %)."""
    data = json.loads(FILM_LAW_DATA.read_text())
    (w1,) = [p for p in data["fit"]["out_of_sample"] if "W1" in p["source"]]
    case = ContactCase.from_engineering(*w1["inputs"])
    inlet = inlet_length(case, w1["smooth_film_m"]) / baseline_profile().correlation_length
    predicted = fed_central_film(w1["smooth_film_m"], w1["sigma_m"], inlet)
    assert predicted == pytest.approx(678e-9, rel=0.02)


def test_the_film_law_limits():
    """Smooth surfaces: the smooth film. Thick films: the excess falls like c·σ²/h (second order in σ, as any
    perturbation of the mean flux by zero-mean roughness). Thin films: it tends to (c/d)·σ (at L_in = β)."""
    assert fed_central_film(2e-7, 0.0, 2.0) == 2e-7
    h, sigma = 1e-6, 1e-8
    assert fed_central_film(h, sigma, 1.0) - h == pytest.approx(FILM_LAW_C * sigma**2 / h, rel=0.01)
    assert fed_central_film(1e-12, 1e-6, 1.0) == pytest.approx(1e-6 * FILM_LAW_C / FILM_LAW_D, rel=1e-5)
    films = [fed_central_film(2e-7, s, 2.0) for s in np.linspace(0.0, 1e-6, 11)]
    assert np.all(np.diff(films) > 0.0)
    assert fed_central_film(2e-7, 2e-7, 4.0) > fed_central_film(2e-7, 2e-7, 1.0)


@pytest.mark.parametrize("kwargs, parameter", [(dict(smooth_film_m=-1e-9, sigma_m=1e-7, inlet_over_beta=1.0), "smooth_film_m"),
                                               (dict(smooth_film_m=1e-7, sigma_m=math.nan, inlet_over_beta=1.0), "sigma_m"),
                                               (dict(smooth_film_m=1e-7, sigma_m=1e-7, inlet_over_beta=0.0),
                                                "inlet_over_beta")])
def test_the_film_law_refuses_bad_input(kwargs, parameter):
    with pytest.raises(InputError, match=parameter):
        fed_central_film(**kwargs)


def test_bad_route_and_layout_are_refused(wide_case):
    with pytest.raises(InputError, match="wide"):
        DeterministicOptions(wide="sideways")
    case, state = wide_case
    with pytest.raises(InputError, match="wide"):  # the resolving solver does not silently ignore a route
        solve_deterministic(case, state, Effects.full(), DeterministicOptions(wide="windows"))
    with pytest.raises(InputError, match="points"):
        WideOptions(points=0)


@pytest.fixture(scope="module")
def wide_case():
    """W1's load, radius, speed and temperature (a/β = 23.6) with nanometre roughness."""
    case = ContactCase.from_engineering(1.0, 20, 5, 0.2, 75, 0.002, 0.002)
    return case, load_lubricant("atf").state(case.temperature)


@pytest.fixture(scope="module")
def wide_smooth_limit(wide_case):
    case, state = wide_case
    return solve_deterministic_contact(case, state, Effects.full(), DeterministicOptions(**TINY))


def test_a_wide_contact_takes_the_windows_and_records_why(wide_smooth_limit):
    result = wide_smooth_limit
    assert result.converged, result.message
    assert result.extra["route"] == "wide" and len(result.extra["windows"]) == 3
    assert "periodic windows" in result.effects["reasons"]["model"]
    assert result.extra["model_version"].startswith("det-") and result.extra["wide_model_version"].startswith("wide-")


def test_the_wide_route_tends_to_the_smooth_solve_as_the_roughness_vanishes(wide_case, wide_smooth_limit):
    """Rq 2 nm (λ̄ ≈ 100): the windows carry a uniform film at the local pressure; the whole-contact μ is the smooth
    solver's within 1 % (3 Gauss points over the Hertzian zone; the smooth outlet constriction is replaced by the
    law's flat mean film) and the fed central film is the smooth one (the law's excess, 0.6 σ²/h, is 0.03 nm)."""
    case, _ = wide_case
    result = wide_smooth_limit
    assert result.mu == pytest.approx(result.extra["smooth_mu"], rel=0.01)
    assert result.extra["fed_central_film_m"] == pytest.approx(result.extra["smooth_central_film_m"], rel=1e-3)
    weights = np.polynomial.legendre.leggauss(3)[1] * 0.9 * case.half_width
    zone = sum(w * window["shear_stress_pa"] for w, window in zip(weights, result.extra["windows"]))
    assert result.mu == pytest.approx(zone / case.load_per_length + result.extra["mu_outside_zone"], rel=1e-12)


def test_a_narrow_contact_or_a_given_spacing_is_resolved(wide_case):
    """``auto`` resolves contacts up to WIDE_A_OVER_BETA wide, and any run given an explicit spacing (the
    convergence studies); only ``wide="windows"`` forces the windows."""
    case, _ = wide_case
    profile = baseline_profile()
    narrow = ContactCase.from_engineering(0.5, 5, 5, 0.3, 90, 0.3, 0.3)
    assert takes_windows(case, profile, DeterministicOptions())
    assert not takes_windows(narrow, profile, DeterministicOptions())
    assert not takes_windows(case, profile, DeterministicOptions(dx_m=1e-6))
    assert not takes_windows(case, profile, DeterministicOptions(wide="resolve"))
    assert takes_windows(narrow, profile, DeterministicOptions(wide="windows"))


def test_the_command_line_reports_the_route(capsys, monkeypatch):
    """``gearloss contact solve ... --model deterministic --wide windows --json``: the JSON
    names the route and carries the fields of a deterministic run. (The ``fast`` level's layout is shrunk to the
    coarse one above to keep the test to seconds.)"""
    from ehl_dataset.solvers import levels
    from workflows.cli import main

    fast = levels.REGISTRY["fast"]
    monkeypatch.setitem(levels.REGISTRY, "fast", dataclasses.replace(fast, deterministic={**fast.deterministic, **TINY}))

    code = main(["contact", "solve", "--p-h-gpa", "1.0", "--r-eq-mm", "20", "--u-r", "5", "--sr", "0.2", "--temp-c",
                 "75", "--rq1-um", "0.002", "--rq2-um", "0.002", "--model", "deterministic", "--wide", "windows",
                 "--level", "fast", "--json"])
    payload = json.loads(capsys.readouterr().out)
    assert code == 0 and payload["converged"]
    assert payload["route"] == "wide" and payload["model"] == "deterministic"
    for key in ("mu", "mu_sem", "asperity_load_share", "h_min_m", "lambda_bar", "dx_m", "n_nodes", "n_steps",
                "effects", "wall_time_s"):
        assert payload[key] is not None, key


def test_a_film_law_outside_its_fitted_range_is_flagged():
    from ehl_dataset.solvers.wide_contact import FILM_LAW_RANGE, film_law_extrapolation

    data = json.loads(FILM_LAW_DATA.read_text())["fit"]["range"]
    assert FILM_LAW_RANGE["H"][0] <= data["H"][0] and FILM_LAW_RANGE["H"][1] >= data["H"][1]
    assert film_law_extrapolation(1e-7, 1e-7, 2.0) == ""
    assert "inlet_over_beta = 12" in film_law_extrapolation(1e-7, 1e-7, 12.0)
    assert "H = 20" in film_law_extrapolation(2e-6, 1e-7, 2.0)
