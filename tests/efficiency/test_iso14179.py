"""ISO/TR 14179-2 μ_mz and P_VZP (efficiency.iso14179) against an independent computation of the standard.

Acceptance case: FZG C (gear_cases.md) at T1 = 200 N·m, n1 = 1500 rpm, mineral ISO VG 32 at 60 °C.
The reference below is computed by hand in the test from the standard's formula (ISO/TR 14179-2:2001, Schlenk)
with inputs taken from the published gear data, not from the package: d_w1 = 2a z1/(z1 + z2) = 73.2 mm,
α_wt = 22.4389° (gear_cases.md), d_b1 = z1 m cos 20°; the oil is GEARpie's "M32" (cfernandesFEUP/GEARpie,
CLASSES/LUBRICANT_LIBRARY.py: Walther m = 9.5259, n = 3.7449 with log10 T[K], c = 0.7 cSt; ρ15 = 902 kg/m³,
α_T = −5.8e-4 1/K; X_L = 0.846), Ra = 0.5 µm on both flanks.
"""

import math

import pytest

from ehl_dataset.validation import InputError
from efficiency.geometry import GearPair
from efficiency.iso14179 import SimpleOil, iso_14179_2_mesh, lubricant_factor

DEG = math.pi / 180


def fzg_c():
    return GearPair(16, 24, 4.5e-3, 20 * DEG, 0.0, 0.014, 0.1817, 0.1715, center_distance=0.0915)


def reference_mu_fzg_c_vg32_60c():
    """The standard's formula evaluated by hand (units of the standard: N/mm, m/s, mm, mPa·s, µm)."""
    t_k = 333.15
    nu_cst = 10 ** (10 ** (9.5259 - 3.7449 * math.log10(t_k))) - 0.7
    rho_g_cm3 = 0.902 * (1 - 5.8e-4 * (60 - 15))
    eta_mpas = nu_cst * rho_g_cm3
    alpha_wt = 22.4389 * DEG
    d_w1, d_w2 = 73.2, 109.8  # mm, 2a z/(z1 + z2)
    r_b1_mm = 16 * 4.5 * math.cos(20 * DEG) / 2
    f_bt = 200e3 / r_b1_mm  # N (N·mm / mm)
    v_t = 1500 * math.pi / 30 * d_w1 / 2e3  # m/s
    v_sum = 2 * v_t * math.sin(alpha_wt)
    rho1, rho2 = d_w1 / 2 * math.sin(alpha_wt), d_w2 / 2 * math.sin(alpha_wt)
    rho_red = rho1 * rho2 / (rho1 + rho2)
    return 0.048 * (f_bt / 14.0 / (v_sum * rho_red)) ** 0.2 * eta_mpas**-0.05 * 0.5**0.25 * 0.846, eta_mpas


def test_mu_mz_fzg_c_matches_an_independent_computation_of_the_standard():
    oil = SimpleOil.from_walther(9.5259, 3.7449, density15=902.0, expansion=-5.8e-4, oil_type="mineral")
    reference, eta_mpas = reference_mu_fzg_c_vg32_60c()
    assert oil.dynamic_viscosity(333.15) * 1e3 == pytest.approx(eta_mpas, rel=1e-9)
    out = iso_14179_2_mesh(fzg_c(), 200.0, 1500 * math.pi / 30, oil.dynamic_viscosity(333.15), 0.5e-6, 0.5e-6,
                           oil.lubricant_factor)
    assert out["mu_mz"] == pytest.approx(reference, rel=0.01)
    # tighter: the only difference is α_wt to the printed digits
    assert out["mu_mz"] == pytest.approx(reference, rel=2e-5)
    assert out["p_vzp_w"] == pytest.approx(out["mu_mz"] * out["loss_factor_ohlendorf"] * 200 * 1500 * math.pi / 30,
                                           rel=1e-12)


def test_vg32_viscosity_is_that_of_an_iso_vg_32_oil():
    """ISO 3448: VG 32 has ν40 within 28.8–35.2 cSt."""
    oil = SimpleOil.from_walther(9.5259, 3.7449, density15=902.0)
    assert 28.8e-6 <= oil.nu40 <= 35.2e-6


def test_walther_line_passes_through_its_two_points():
    oil = SimpleOil(nu40=32e-6, nu100=5.4e-6)
    assert oil.kinematic_viscosity(313.15) == pytest.approx(32e-6, rel=1e-12)
    assert oil.kinematic_viscosity(373.15) == pytest.approx(5.4e-6, rel=1e-12)


def test_mu_scales_with_the_formula_exponents():
    """μ ∝ Ra^0.25, η^−0.05, T^0.2 at fixed speed (F_bt ∝ T), X_L linear."""
    base = iso_14179_2_mesh(fzg_c(), 200.0, 157.0, 0.02, 0.5e-6, 0.5e-6, 1.0)["mu_mz"]
    assert iso_14179_2_mesh(fzg_c(), 200.0, 157.0, 0.02, 8e-6, 8e-6, 1.0)["mu_mz"] == pytest.approx(base * 2.0)
    assert iso_14179_2_mesh(fzg_c(), 200.0, 157.0, 0.02 * 1000, 0.5e-6, 0.5e-6, 1.0)["mu_mz"] == pytest.approx(
        base * 1000**-0.05)
    assert iso_14179_2_mesh(fzg_c(), 200.0 * 32, 157.0, 0.02, 0.5e-6, 0.5e-6, 1.0)["mu_mz"] == pytest.approx(
        base * 2.0)
    assert iso_14179_2_mesh(fzg_c(), 200.0, 157.0, 0.02, 0.5e-6, 0.5e-6, 0.65)["mu_mz"] == pytest.approx(
        base * 0.65)


def test_bad_oil_inputs_name_the_parameter():
    with pytest.raises(InputError, match="oil_type"):
        lubricant_factor("castor")
    with pytest.raises(InputError, match="nu100"):
        SimpleOil(nu40=5e-6, nu100=32e-6)
    with pytest.raises(InputError, match="ra1"):
        iso_14179_2_mesh(fzg_c(), 200.0, 157.0, 0.02, 0.0, 0.5e-6, 1.0)


def test_point_by_point_route_uses_the_oil_types_lubricant_factor():
    """`--friction iso14179` (efficiency.friction.PublishedFriction) multiplies the standard's formula by X_L of the
    oil type (Fernandes et al., Tribol. Int. 88 (2015) 309: mineral 0.846, PAO 0.65; efficiency.iso14179), was 1.0:
    from the spec (iso14179:pao), the oil_type argument (the CLI's --oil-type), the lubricant file's oil_type, else
    mineral."""
    import numpy as np

    from ehl_dataset.model.lubricant import load_lubricant, lubricant_from_dict
    from efficiency.friction import PublishedFriction, friction_from_spec
    from surrogate.published import iso_14179_2_mu

    atf = load_lubricant("atf")
    args = (np.array([1.2e9]), np.array([0.012]), np.array([8.0]), np.array([0.3]), np.array([353.15]),
            np.array([0.4e-6]), np.array([0.4e-6]))
    as_printed = PublishedFriction("iso_tr_14179_2", atf, oil_type="reference")(*args)
    assert friction_from_spec("iso14179", atf)(*args) == pytest.approx(0.846 * as_printed, rel=1e-12)
    assert friction_from_spec("iso14179:pao", atf)(*args) == pytest.approx(0.65 * as_printed, rel=1e-12)
    assert friction_from_spec("iso14179", atf, oil_type="ester")(*args) == pytest.approx(0.65 * as_printed,
                                                                                         rel=1e-12)
    declared = lubricant_from_dict({**atf.definition, "oil_type": "polyglycol"})
    assert friction_from_spec("iso14179", declared)(*args) == pytest.approx(0.585 * as_printed, rel=1e-12)
    w_prime = 2 * math.pi * 0.012 * 1.2e9**2 / 226.4e9
    eta = float(atf.dynamic_viscosity(353.15))
    assert as_printed == pytest.approx(iso_14179_2_mu(w_prime, 0.012, 8.0, eta, 0.4e-6, 0.4e-6), rel=1e-3)
    with pytest.raises(InputError, match="oil_type"):
        friction_from_spec("iso14179:castor", atf)
