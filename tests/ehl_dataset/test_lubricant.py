"""Lubricant model: the laws reproduce their defining data points and limits."""

import math

import numpy as np
import pytest

from ehl_dataset.model.lubricant import (
    DH_GAMMA_PER_PA,
    DH_LAMBDA_PER_PA,
    dowson_higginson_density,
    lubricant_from_dict,
    load_lubricant,
)
from ehl_dataset.validation import InputError

C = 273.15


def test_walther_reproduces_the_two_defining_viscosities():
    """ASTM D341 through (40 °C, 30 mm²/s) and (100 °C, 6 mm²/s) returns them (the representative ATF of docs/reference/data.md)."""
    atf = load_lubricant("atf")
    nu = atf.kinematic_viscosity(np.array([40 + C, 100 + C])) * 1e6
    np.testing.assert_allclose(nu, [30.0, 6.0], rtol=1e-10)
    # Viscosity falls monotonically with temperature over the whole range.
    temps = np.linspace(atf.t_min, atf.t_max, 50)
    assert np.all(np.diff(atf.dynamic_viscosity(temps)) < 0)


def test_density_temperature_and_alpha_interpolation():
    atf = load_lubricant("atf")
    assert atf.density_at(15 + C) == pytest.approx(845.0)
    assert atf.density_at(100 + C) == pytest.approx(845.0 * (1 - 6.4e-4 * 85))
    np.testing.assert_allclose(atf.alpha1(np.array([40 + C, 100 + C])), [1.5e-8, 1.1e-8], rtol=1e-12)
    # log-linear: geometric mean at the mid temperature
    assert atf.alpha1(70 + C) == pytest.approx(math.sqrt(1.5e-8 * 1.1e-8), rel=1e-12)


def test_two_slope_law_is_c1_and_matches_paper_eq5_branches():
    state = load_lubricant("atf").state(90 + C)
    law = state.law
    a1, a2, pt = law.alpha1, law.alpha2, law.p_t
    assert a2 == pytest.approx(0.55 * a1)
    # branches of Eq. 5
    assert law.exponent(0.2e9) == pytest.approx(a1 * 0.2e9)
    assert law.exponent(1.0e9) == pytest.approx(a1 * pt + a2 * (1.0e9 - pt))
    # value and slope continuous at p_a and p_b
    for p_j in (law.p_a, law.p_b):
        eps = 1.0
        assert law.exponent(p_j - eps) == pytest.approx(law.exponent(p_j + eps), rel=1e-8)
        assert law.exponent_derivative(p_j - eps) == pytest.approx(law.exponent_derivative(p_j + eps), rel=1e-6)
    # monotone viscosity
    p = np.linspace(0, 2.5e9, 500)
    assert np.all(np.diff(law.viscosity(p)) > 0)


def test_dowson_higginson_density_limits():
    """Eq. 6: ρ(0) = ρ0 and ρ → ρ0 γ/λ (≈ 1.346 ρ0) as p → ∞."""
    assert dowson_higginson_density(0.0, 850.0) == pytest.approx(850.0)
    assert dowson_higginson_density(1e15, 1.0) == pytest.approx(DH_GAMMA_PER_PA / DH_LAMBDA_PER_PA, rel=1e-5)


def test_roelands_law_matches_barus_slope_at_zero_pressure():
    data = _minimal(pressure_viscosity={"model": "roelands", "alpha1_points": [[40.0, 2e-8]]})
    state = lubricant_from_dict(data).state(40 + C)
    assert state.law.exponent_derivative(0.0) == pytest.approx(2e-8, rel=1e-12)


def test_temperature_outside_the_data_is_rejected_with_its_range():
    atf = load_lubricant("atf")
    with pytest.raises(InputError, match="temperature"):
        atf.state(200 + C)


def _minimal(**overrides):
    data = {
        "name": "test",
        "temperature_range": {"min_c": 0.0, "max_c": 150.0},
        "density": {"rho_ref_kg_m3": 850.0, "t_ref_c": 15.0, "expansion_per_k": 6e-4},
        "viscosity": {"model": "constant", "eta0_pa_s": 0.01},
        "pressure_viscosity": {"model": "barus", "alpha1_points": [[40.0, 2e-8]]},
        "traction": {"eyring_stress_mpa": 5.0, "boundary_friction": 0.1},
    }
    data.update(overrides)
    return data


@pytest.mark.parametrize(
    "mutation, field",
    [
        (lambda d: d["density"].pop("rho_ref_kg_m3"), "density.rho_ref_kg_m3"),
        (lambda d: d["viscosity"].update(model="vogel"), "viscosity.model"),
        (lambda d: d["traction"].update(boundary_friction=-1), "traction.boundary_friction"),
        (lambda d: d.pop("traction"), "traction"),
        (lambda d: d["pressure_viscosity"].update(alpha1_points="x"), "pressure_viscosity.alpha1_points"),
    ],
)
def test_malformed_definition_names_the_field(mutation, field):
    data = _minimal()
    mutation(data)
    with pytest.raises(InputError, match=field.replace(".", r"\.")):
        lubricant_from_dict(data)


def test_unknown_lubricant_name_lists_the_shipped_ones():
    with pytest.raises(InputError, match="atf"):
        load_lubricant("no_such_oil")
