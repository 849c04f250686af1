"""Amplitude reduction per spectral component (ehl_dataset.model.amplitude_reduction) and the spectral form of the
film-law closures' micro-EHL pressure spread (ehl_dataset.model.micro_pressure.spectral_pressure_std)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from ehl_dataset.model import amplitude_reduction as ar
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.micro_pressure import flattening_pressure_rms, spectral_pressure_std
from ehl_dataset.model.roughness import baseline_profile, named_profile, periodogram
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers.homogenised import HomogenisedOptions
from ehl_dataset.validation import InputError
from workflows.accuracy_mixed import load_reference, reference_case

ROOT = Path(__file__).resolve().parents[2]
CLOSURES = ROOT / "validation" / "results" / "flank_reference_closures.json"


@pytest.fixture(scope="module")
def lub():
    return load_lubricant("atf")


def spectral_slope(profile, rq):
    """Rq·(Σ w_j k_j²)^½ from the periodogram: the r.m.s. slope of the profile scaled to Rq (Parseval)."""
    k, power = periodogram(profile)
    return rq * math.sqrt(float(np.sum(power * k**2) / np.sum(power)))


@pytest.mark.parametrize("name", ["baseline_synthetic", "flank_ground"])
def test_flattened_slope_is_bounded_by_the_whole_slope_and_grows_with_nabla(lub, name):
    """0 ≤ Δq_f ≤ Δq, and Δq_f grows monotonically with the scale of ∇ (F falls with ∇): F → 1 as ∇ → 0 leaves
    nothing flattened, F → 0 as ∇ → ∞ flattens everything (Δq_f → Δq of the composite, the two surfaces'
    slopes added in quadrature)."""
    profile = named_profile(name)
    case = ContactCase.from_engineering(1.0, 10, 5, 0.3, 90, 0.3, 0.2)
    state = lub.state(case.temperature)
    whole = math.hypot(spectral_slope(profile, case.rq1), spectral_slope(profile, case.rq2))
    scales = [1e-9, 0.25, 1.0, 4.0, 1e9]
    slopes = [ar.flattened_slope_rms(profile, case, state, nabla_scale=s) for s in scales]
    assert slopes[0] == pytest.approx(0.0, abs=1e-6 * whole)
    assert slopes[-1] == pytest.approx(whole, rel=1e-6)
    assert all(a < b for a, b in zip(slopes, slopes[1:]))


def test_a_stationary_surface_is_flattened_completely(lub):
    """SR = 2: surface 2 stands still, its complementary wavelength λ·u_m/u_2 is infinite and F = 0 (Hooke 2003),
    so its whole slope is flattened whatever the contact; a smooth moving surface 1 adds nothing."""
    profile = named_profile("flank_ground")
    case = ContactCase.from_engineering(0.5, 5, 5, 2.0, 90, 0.0, 0.4)
    state = lub.state(case.temperature)
    assert ar.flattened_slope_rms(profile, case, state) == pytest.approx(spectral_slope(profile, 0.4e-6), rel=1e-12)


def test_short_wavelengths_pass_the_conjunction(lub):
    """The same contact and Rq: the flank-like profile (self-affine down to λ_s = 2.5 µm) keeps a smaller part of
    its (larger) slope flattened than the baseline (Gaussian ACF, β 15 µm), because its slope sits in short
    wavelengths that pass (F → 1 as λ → 0)."""
    case = ContactCase.from_engineering(0.5, 5, 5, 0.3, 90, 0.33, 0.33)
    state = lub.state(case.temperature)
    ratios = {}
    for name in ("baseline_synthetic", "flank_ground"):
        profile = named_profile(name)
        whole = math.hypot(spectral_slope(profile, case.rq1), spectral_slope(profile, case.rq2))
        ratios[name] = ar.flattened_slope_rms(profile, case, state) / whole
    assert 0.0 < ratios["flank_ground"] < ratios["baseline_synthetic"] < 1.0


def test_spectral_pressure_spread_is_the_flattening_pressure_of_the_flattened_part(lub):
    """σ_p = E'Δq_f/4 (Johnson 1985 §13.1 applied to the flattened part; k = 1)."""
    profile = baseline_profile()
    case = ContactCase.from_engineering(0.5, 5, 5, 0.3, 90, 0.3, 0.3)
    state = lub.state(case.temperature)
    std, slope = spectral_pressure_std(profile, case, state)
    assert slope == ar.flattened_slope_rms(profile, case, state)
    assert std == pytest.approx(flattening_pressure_rms(case.e_reduced, slope), rel=1e-15)


def test_spectral_film_law_meets_the_baseline_reference(lub):
    """The spectral form has no fitted constant; on the grid-converged validation cases of the baseline profile
    (data/reference/deterministic_validation.json) whose asperity share is below 0.01 (the film law carries no
    asperity load) its μ is within the acceptance of the mixed-regime production model, 15 %, of the reference
    (measured: −6 % to +6 %, validation/flank_reference/closure_check.py)."""
    errors = {}
    for row in load_reference():
        if row.get("asperity_load_share_extrapolated", 0.0) >= 0.01:
            continue
        res = solve_contact(reference_case(row), lub, "standard", "isothermal", model="homogenised",
                            homogenised=HomogenisedOptions(closure="film_law", fluctuations="spectral"))
        assert res.converged and res.extra["micro_pressure"]["form"] == "spectral"
        errors[row["case"]] = res.mu / row["mu_extrapolated"] - 1.0
    assert len(errors) >= 8
    assert max(abs(e) for e in errors.values()) <= 0.15, errors


def test_spectral_scale_fitted_freely_is_the_theoretical_one():
    """Fitted freely on the 33 contacts that calibrate the inlet form, the scale k of σ_p = k·E'Δq_f/4 comes out
    within 10 % of the theoretical 1 that the package uses (the committed run of
    validation/flank_reference/closure_check.py)."""
    fit = json.loads(CLOSURES.read_text(encoding="utf-8"))["spectral_scale"]
    assert fit["n"] == 33
    assert abs(fit["k_fitted"] - 1.0) <= 0.1


def test_fluctuation_form_is_checked():
    with pytest.raises(InputError, match="fluctuations"):
        HomogenisedOptions(closure="film_law", fluctuations="gaussian")
