"""EHL solver numerics: published numerical case, Hertz limit, load balance, grid convergence."""

import math
from dataclasses import replace

import numpy as np
import pytest

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.materials import Material
from ehl_dataset.solver import solve_contact
from ehl_dataset.solvers.levels import REGISTRY, get_level
from ehl_dataset.solvers.newton import _fb

NEWTONIAN = Effects(roughness=False, transient=False, shear_thinning=False, compressibility=True, mode="forced")


def _huang_case():
    """Huang textbook line contact (Huang 2013, Ch. 3; docs/explanation/ehl-model.md): E' = 2.21e11 Pa, w' = 5e4 N/m, R = 20 mm, u_m = 1.5 m/s."""
    e_red, load, radius = 2.21e11, 5e4, 0.02
    material = Material(e_red * (1 - 0.3**2), 0.3)
    p_h = math.sqrt(load * e_red / (2 * math.pi * radius))
    case = ContactCase(p_h, radius, 1.5, 0.0, 313.15, material1=material, material2=material)
    assert case.e_reduced == pytest.approx(e_red) and case.load_per_length == pytest.approx(load)
    return case


def _dimensionless(result, case):
    scale = case.r_eq / case.half_width**2
    return result.h_min * scale, result.h_central * scale


def test_huang_case_on_long_inlet_matches_fine_grid_newton():
    """On −3b…1.5b a fine-grid Newton solution of the Huang case gives H_min = 0.512, H(0) = 0.613 (docs/explanation/ehl-model.md).
    Measured: 0.5119, 0.6131 (standard level); 1 % tolerance = grid error at this level (< 0.2 % from standard to
    reference) plus the 3-digit rounding of the reference values."""
    case = _huang_case()
    result = solve_contact(case, load_lubricant("validation_roelands_huang"),
                           get_level("standard").with_domain(-3.0, 1.5), NEWTONIAN)
    assert result.converged
    h_min, h_0 = _dimensionless(result, case)
    assert h_min == pytest.approx(0.512, rel=0.01)
    assert h_0 == pytest.approx(0.613, rel=0.01)


@pytest.mark.xfail(strict=True, reason="converged solutions on Huang's domain −2b…1.5b give H_min = 0.443, "
                   "H(0) = 0.515 (grid-independent to 0.1 %), 14 % and 12 % below the book's 101-node values; "
                   "see docs/explanation/ehl-model.md")
def test_huang_case_on_published_domain():
    """Huang (2013) on −2b…1.5b with 101 nodes: H_min ≈ 0.514, H(0) ≈ 0.584 (Huang 2013), 3 % tolerance."""
    case = _huang_case()
    result = solve_contact(case, load_lubricant("validation_roelands_huang"),
                           get_level("standard").with_domain(-2.0, 1.5), NEWTONIAN)
    h_min, h_0 = _dimensionless(result, case)
    assert h_min == pytest.approx(0.514, rel=0.03) and h_0 == pytest.approx(0.584, rel=0.03)


def test_shorter_inlet_starves_the_film():
    """Limit: shortening the inlet (−3b → −2b) can only starve the contact, never thicken the film."""
    case = _huang_case()
    lub = load_lubricant("validation_roelands_huang")
    long_ = solve_contact(case, lub, get_level("fast").with_domain(-3.0, 1.5), NEWTONIAN)
    short = solve_contact(case, lub, get_level("fast").with_domain(-2.0, 1.5), NEWTONIAN)
    assert short.h_central < long_.h_central and short.h_min < long_.h_min


def _hertz_deviation(point):
    case = ContactCase.from_engineering(*point, 0.0, 40.0)
    result = solve_contact(case, load_lubricant("validation_barus"), "standard", NEWTONIAN)
    assert result.converged
    x = result.x / case.half_width
    inside = np.abs(x) <= 0.7  # away from the inlet and the outlet spike
    hertz = case.p_h * np.sqrt(1.0 - x[inside] ** 2)
    load = float(np.sum(0.5 * (result.pressure[1:] + result.pressure[:-1]) * np.diff(result.x)))
    return float(np.max(np.abs(result.pressure[inside] - hertz))) / case.p_h, load / case.load_per_length


def test_pressure_tends_to_hertz_at_high_load_and_load_balances():
    """Hertz limit (docs/explanation/ehl-model.md, "Validation"): as the Moes load parameter grows (M = 26 → 231 → 729) the pressure over
    |x| ≤ 0.7a approaches the Hertz ellipse monotonically (max deviation 1.7 % → 0.10 % → 0.011 % of p_h measured),
    and ∫p dx = W' to 1e−4 relative or better."""
    deviations = []
    for point in [(1.0, 20, 5), (2.5, 40, 5), (2.5, 80, 1)]:
        deviation, load_ratio = _hertz_deviation(point)
        deviations.append(deviation)
        assert load_ratio == pytest.approx(1.0, abs=1e-4)
    assert deviations[0] > deviations[1] > deviations[2]
    assert deviations[2] < 1e-3


def test_grid_convergence_is_second_order():
    """Grid convergence: halving both spacings of the clustered grid three times, the changes of h_c,
    h_min and μ shrink by ≈ 4 per halving. Observed orders (measured): h_c 1.97/1.99, h_min 2.4/1.8, μ 2.01/2.01
    at p_h = 2 GPa (M ≈ 60, ATF with Eyring shear); asserted 1.5–2.6 (second-order finite volumes, linear-upwind
    Couette flux, exact log-kernel deflection of a piecewise-linear pressure)."""
    case = ContactCase.from_engineering(2.0, 10, 2, 0.5, 75)
    lub = load_lubricant("atf")
    base = get_level("standard")
    values = []
    for factor in (4.0, 2.0, 1.0, 0.5):
        level = replace(base, name=f"x{factor}", dx_fine=base.dx_fine * factor, dx_coarse=base.dx_coarse * factor,
                        inlet_resolution=base.inlet_resolution * factor,
                        tol_residual=1e-9, tol_load=1e-10, tol_step=1e-9)
        refined = replace(REGISTRY["standard"], steady=level)  # the standard level's planner and deterministic rule
        result = solve_contact(case, lub, refined, Effects(False, False, True, True, "forced"))
        assert result.converged
        values.append([result.h_central, result.h_min, result.mu])
    values = np.array(values)
    diffs = np.abs(np.diff(values, axis=0))
    orders = np.log2(diffs[:-1] / diffs[1:])
    assert np.all((orders > 1.5) & (orders < 2.6)), orders
    # the standard level (factor 1) is within 1 % of the Richardson extrapolation
    extrapolated = values[3] + (values[3] - values[2]) / 3.0
    assert np.all(np.abs(values[2] / extrapolated - 1.0) < 0.01)


def test_fischer_burmeister_zero_set_and_no_cancellation():
    """φ(a, b) = 0 ⇔ a ≥ 0, b ≥ 0, ab = 0 (Fischer 1992); with a huge b the value must still be a (the limit
    φ → a as b → ∞), not the 0 that a + b − √(a² + b²) gives in floating point. Smoothed: φ_s = 0 ⇔ ab = s²."""
    a = np.array([0.0, 2.0, 0.0, -1.0, 1.0, -1.37])
    b = np.array([3.0, 0.0, 0.0, 0.0, -1.0, 1.6e20])
    phi = _fb(a, b)[0]
    assert phi[:3] == pytest.approx([0.0, 0.0, 0.0], abs=1e-15)
    assert phi[3] == pytest.approx(-2.0)  # a + b − |a| with b = 0, a < 0
    assert phi[4] == pytest.approx(-math.sqrt(2.0))
    assert phi[5] == pytest.approx(-1.37, rel=1e-12)
    s = 1e-3
    assert _fb(np.array([0.5]), np.array([s * s / 0.5]), s)[0][0] == pytest.approx(0.0, abs=1e-15)
