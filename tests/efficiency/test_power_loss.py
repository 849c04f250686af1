"""Mesh power loss (paper Eq. 10–11) against the gear loss factor H_V of closed-form load sharing.

For a constant μ the mean loss is P = μ T_in ω_in H_V. Ohlendorf's H_V for ideal spur load sharing (a single pair
carries all the load, two pairs share it equally) is

    H_V = π (u + 1)/(z1 u cos β_b) · (1 − ε_α + ε1² + ε2²)

(Ohlendorf 1958, as used by Fernandes, Marques, Martins & Seabra, Mech. Sci. 6 (2015) 81–88), ε1, ε2 the
recess/approach contact ratios. For a helical pair whose load intensity is uniform over the zone of action the same
integral gives the bracket (ε1² + ε2²)/ε_α instead: an elastic helical load distribution lies between the two.
"""

import math

import numpy as np
import pytest

from efficiency.friction import ConstantFriction
from efficiency.geometry import GearPair
from efficiency.mesh_cycle import MeshOptions, evaluate_mesh
from efficiency.power_loss import contact_conditions, mesh_power_loss
from ehl_dataset.validation import InputError

# FZG gears (shared/reference/gear_cases.md): z1, z2, m_n [mm], β [deg], b [mm], x1, x2; a = 91.5 mm.
FZG = {"C": (16, 24, 4.5, 0.0, 14, 0.1817, 0.1715), "H501": (20, 30, 3.5, 15.0, 23, 0.1809, 0.0891)}


def fzg(name):
    z1, z2, m, beta, b, x1, x2 = FZG[name]
    return GearPair(z1, z2, m * 1e-3, math.radians(20), math.radians(beta), b * 1e-3, x1, x2, center_distance=0.0915)


def loss_factor_brackets(pair):
    """Ohlendorf's bracket and the uniform-intensity bracket, and the prefactor π(u+1)/(z1 u cos β_b)."""
    z1, z2 = pair.teeth
    u = z2 / z1
    pitch = pair.transverse_base_pitch
    e1 = (pair.contact_end - pair.pitch_point) / pitch
    e2 = (pair.pitch_point - pair.contact_start) / pitch
    eps = pair.contact_ratio
    prefactor = math.pi * (u + 1) / (z1 * u * math.cos(pair.base_helix_angle))
    return prefactor, 1 - eps + e1**2 + e2**2, (e1**2 + e2**2) / eps


def loss_factor(pair, mu=0.05, speed=100.0, torque=300.0, positions=48):
    mesh = evaluate_mesh(pair, torque, speed, options=MeshOptions(positions=positions, slices=30, outputs=frozenset()))
    result = mesh_power_loss(mesh, ConstantFriction(mu), 353.15, 0.4e-6, 0.4e-6)
    return result, (result.power_loss / (mu * result.input_power) if mu > 0 else 0.0)


def test_spur_loss_factor_matches_ohlendorf():
    """FZG C (spur): the elastic load sharing gives Ohlendorf's H_V within 1 % (ideal sharing is its limit)."""
    pair = fzg("C")
    prefactor, ohlendorf, _ = loss_factor_brackets(pair)
    _, h_v = loss_factor(pair)
    assert h_v == pytest.approx(prefactor * ohlendorf, rel=0.01)


def test_helical_loss_factor_between_ideal_spur_and_uniform_intensity():
    """FZG H501 (ε_β = 0.54): H_V lies between Ohlendorf's spur-sharing value and the uniform-intensity value."""
    pair = fzg("H501")
    prefactor, ohlendorf, uniform = loss_factor_brackets(pair)
    _, h_v = loss_factor(pair)
    assert prefactor * ohlendorf < h_v <= prefactor * uniform * 1.01


def test_constant_mu_efficiency_is_speed_independent_and_loss_linear_in_mu():
    """Quasi-static mesh: every sliding velocity scales with ω, so P ∝ ω and η does not depend on speed."""
    pair = fzg("C")
    slow, _ = loss_factor(pair, mu=0.05, speed=50.0)
    fast, _ = loss_factor(pair, mu=0.05, speed=400.0)
    assert fast.power_loss == pytest.approx(8.0 * slow.power_loss, rel=1e-12)
    assert fast.efficiency == pytest.approx(slow.efficiency, rel=1e-12)
    double, _ = loss_factor(pair, mu=0.10, speed=50.0)
    assert double.power_loss == pytest.approx(2.0 * slow.power_loss, rel=1e-12)
    zero, _ = loss_factor(pair, mu=0.0, speed=50.0)
    assert zero.power_loss == 0.0 and zero.efficiency == 1.0


def test_contact_conditions_recover_the_load_per_length():
    """p_h from each point inverts the Hertz relation W' = 2π r_eq p_h²/E' (docs/ehl_solver.md)."""
    pair = fzg("H501")
    mesh = evaluate_mesh(pair, 300.0, 100.0, options=MeshOptions(positions=12, slices=20, outputs=frozenset()))
    cond = contact_conditions(mesh)
    loaded = cond["loaded"]
    e_red = 206e9 / (1 - 0.09)
    w_back = 2 * math.pi * cond["r_eq"][loaded] * cond["p_h"][loaded] ** 2 / e_red
    np.testing.assert_allclose(w_back, mesh.load_per_length[loaded], rtol=1e-12)
    assert np.all(cond["sr"][loaded] >= 0)


def test_bad_friction_output_and_inputs_are_rejected():
    pair = fzg("C")
    mesh = evaluate_mesh(pair, 300.0, 100.0, options=MeshOptions(positions=6, slices=10, outputs=frozenset()))
    with pytest.raises(InputError, match="friction model output"):
        mesh_power_loss(mesh, lambda *a: np.full(np.shape(a[0]), np.nan), 353.15, 0.4e-6, 0.4e-6)
    with pytest.raises(InputError, match="rq1"):
        mesh_power_loss(mesh, ConstantFriction(0.05), 353.15, -1e-6, 0.4e-6)
