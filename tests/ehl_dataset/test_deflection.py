"""Elastic deflection of a line contact with exact cell integrals of the log kernel (paper Eq. 4)."""

import math

import numpy as np
import pytest

from ehl_dataset.discretisation.deflection import deflection_fft, influence_matrix, uniform_kernel

# Dimensionless Hertz line contact: for P = √(1 − X²) on |X| ≤ 1,
#   −(1/π) ∫ ln|X − X'| P(X') dX' = ln2/2 + 1/4 − X²/2   for |X| ≤ 1
# (Johnson, Contact Mechanics, 1985, Eq. 2.47 with the constant evaluated at X = 0), so the loaded gap
# X²/2 + V is flat, H = ln2/2 + 1/4, inside the contact.
HERTZ_GAP = 0.5 * math.log(2.0) + 0.25


def _hertz_gap_error(n):
    x = np.linspace(-2.5, 1.5, n)
    p = np.sqrt(np.clip(1.0 - x**2, 0.0, None))
    gap = 0.5 * x**2 + influence_matrix(x) @ p
    inside = np.abs(x) <= 0.5
    return float(np.max(np.abs(gap[inside] - HERTZ_GAP)))


def test_hertz_pressure_gives_flat_gap():
    """Limit case: the Hertz pressure produces a constant gap ln2/2 + 1/4 inside the contact (Johnson 1985)."""
    assert _hertz_gap_error(801) < 2e-5


def test_deflection_converges_under_refinement():
    """The piecewise-linear pressure on a uniform grid: the error of the Hertz gap falls by ≥ 2.8× per halving of
    the spacing (observed order ≥ 1.5; the √ singularity of p' at the contact edges limits it below 2)."""
    errors = [_hertz_gap_error(n) for n in (161, 321, 641)]  # x = ±1 on the grid
    assert errors[0] / errors[1] > 2.8 and errors[1] / errors[2] > 2.8


def test_fft_equals_dense_product_on_uniform_grid():
    """DC-FFT convolution (Liu, Wang & Liu 2000) reproduces the dense exact-integral product to round-off."""
    rng = np.random.default_rng(1)
    x = np.linspace(-2.5, 1.5, 257)
    p = rng.random(x.size)
    p[0] = p[-1] = 0.0
    dense = influence_matrix(x) @ p
    fft = deflection_fft(p, uniform_kernel(x.size, x[1] - x[0]))
    assert np.max(np.abs(fft - dense)) < 1e-12 * np.max(np.abs(dense))


def test_influence_matrix_symmetry_on_uniform_grid():
    """On a uniform grid the kernel depends on |x_i − x_j| only (Toeplitz and symmetric)."""
    x = np.linspace(0.0, 1.0, 33)
    k = influence_matrix(x)
    interior = k[1:-1, 1:-1]
    assert np.allclose(interior, interior.T, rtol=1e-12, atol=1e-15)


def test_si_scale_matches_point_load_far_field():
    """The SI scale of :func:`influence_matrix` (4/E'): the deflection difference between two far points equals the line-load (Flamant) result
    ΔV = −(4 W'/(πE')) ln(r1/r2) for a narrow pressure strip of total load W' (Johnson 1985, Eq. 2.19b)."""
    e_red, load = 2.26e11, 1e5
    x = np.linspace(-1e-4, 1e-4, 4001)
    p = np.sqrt(np.clip(1 - (x / 2e-6) ** 2, 0, None))  # strip half width 2 µm ≪ distances 50, 100 µm
    p *= load / np.trapezoid(p, x)
    x_far = np.array([5e-5, 1e-4])
    from ehl_dataset.discretisation.deflection import _hat_weights

    v_far = -(4.0 / e_red) / np.pi * _hat_weights(x_far, x) @ p  # the kernel of influence_matrix off the grid
    k_on_grid = influence_matrix(x[::400], scale=4.0 / e_red)
    assert np.allclose(k_on_grid, -(4.0 / e_red) / np.pi * _hat_weights(x[::400], x[::400]))
    expected = -(4.0 * load / (np.pi * e_red)) * math.log(x_far[0] / x_far[1])
    # finite strip width b: relative correction O((b/r)²) ≈ 2e-3 at r = 50 µm
    assert v_far[0] - v_far[1] == pytest.approx(expected, rel=3e-3)


def test_bad_grid_rejected():
    with pytest.raises(ValueError):
        influence_matrix(np.array([0.0, 0.0, 1.0]))
