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
from efficiency.loss_factor import wimmer_loss_factor
from efficiency.mesh_cycle import MeshOptions, evaluate_mesh
from efficiency.power_loss import contact_conditions, mesh_power_loss
from ehl_dataset.validation import InputError

# FZG type C gears (DIN ISO 14635-1): z1, z2, m_n [mm], β [deg], b [mm], x1, x2; a = 91.5 mm.
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
    """(power-loss result, H = P/(μ P_in)) of the elastic load distribution; ``positions`` None = the default rule."""
    mesh = evaluate_mesh(pair, torque, speed, options=MeshOptions(positions=positions, slices=30, outputs=frozenset()))
    result = mesh_power_loss(mesh, ConstantFriction(mu), 353.15, 0.4e-6, 0.4e-6)
    return result, (result.power_loss / (mu * result.input_power) if mu > 0 else 0.0)


def test_spur_rigid_uniform_sharing_reproduces_ohlendorf_exactly():
    """FZG C (spur): equal sharing in double contact is Ohlendorf's assumption, so the rigid-uniform load sharing
    gives his H_V; at the default (breakpoint-aligned) number of positions within 0.05 %."""
    pair = fzg("C")
    prefactor, ohlendorf, _ = loss_factor_brackets(pair)
    mesh = evaluate_mesh(pair, 300.0, 100.0, options=MeshOptions(outputs=frozenset(), load_sharing="rigid-uniform"))
    assert mesh.loss_factor == pytest.approx(prefactor * ohlendorf, rel=5e-4)


def test_spur_elastic_sharing_lies_below_ohlendorf():
    """FZG C: with elastic sharing the pair entering or leaving contact (tip of one gear: the most compliant
    position) carries less than half the load in the double-contact zones, where sliding is largest, so H < H_V.
    Measured −1.6 % at convergence (400 positions: 0.19193 against 0.19498), outside the 1 % the issue asked for:
    the difference is the physics of stiffness sharing, not sampling (rigid-uniform gives H_V to 0.02 %)."""
    pair = fzg("C")
    prefactor, ohlendorf, _ = loss_factor_brackets(pair)
    _, h_v = loss_factor(pair, positions=None)
    assert 0.97 * prefactor * ohlendorf < h_v < prefactor * ohlendorf


@pytest.mark.xfail(strict=True, reason="acceptance 'spur elastic H within 1 % of H_V' not met: "
                   "elastic sharing gives −1.6 % (see test above)")
def test_spur_elastic_loss_factor_within_one_percent_of_ohlendorf():
    pair = fzg("C")
    prefactor, ohlendorf, _ = loss_factor_brackets(pair)
    _, h_v = loss_factor(pair, positions=None)
    assert h_v == pytest.approx(prefactor * ohlendorf, rel=0.01)


def test_helical_stiffness_weighted_sharing_lies_below_wimmer():
    """FZG H501: independent slices (load ∝ local stiffness, tip and root of the path softer) give less load where
    sliding is largest, so H < Wimmer's rigid-uniform H_VL; measured −4.5 %."""
    pair = fzg("H501")
    mesh = evaluate_mesh(pair, 300.0, 100.0, options=MeshOptions(outputs=frozenset(),
                                                                   load_sharing="independent-slices"))
    assert mesh.loss_factor < 0.97 * wimmer_loss_factor(pair)


@pytest.mark.xfail(strict=True, reason="acceptance 'helical elastic H <= H_VL' not met: with the face "
                   "coupling of tooth and gear body (0.6 tooth depth) H501 gives +2.2 % over H_VL; a 3-D FE of the "
                   "teeth on their gear body gives +1.6 % (docs/validation/gear.md §3)")
def test_helical_elastic_loss_factor_at_most_wimmer():
    pair = fzg("H501")
    _, h_v = loss_factor(pair, positions=None)
    assert h_v <= wimmer_loss_factor(pair)


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
    """p_h from each point inverts the Hertz relation W' = 2π r_eq p_h²/E' (docs/explanation/ehl-model.md)."""
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


class _BandedFriction:
    """μ = 0.05 with the interval [μ e^-h, μ e^+h] at every point (a stand-in for a surrogate with intervals)."""

    has_interval = True

    def __init__(self, half_width):
        self.half_width = half_width
        self.alpha = None

    def __call__(self, p_h, *args):
        return np.full(np.shape(p_h), 0.05)

    def mu_interval(self, p_h, *args, alpha=0.1):
        self.alpha = alpha
        mu = self(p_h)
        return mu, mu * math.exp(-self.half_width), mu * math.exp(self.half_width)


def test_power_loss_band_is_the_fully_correlated_sum_of_the_mu_intervals():
    """P is linear in μ, so with every point at the same end of its interval (fully correlated errors) the band is
    exactly P·e^(±h) for a uniform half width h of ln μ; η's band follows from P's; 90 % intervals by default."""
    pair = fzg("H501")
    mesh = evaluate_mesh(pair, 300.0, 100.0, options=MeshOptions(positions=12, slices=20, outputs=frozenset()))
    friction = _BandedFriction(0.2)
    result = mesh_power_loss(mesh, friction, 353.15, 0.4e-6, 0.4e-6)
    plain = mesh_power_loss(mesh, ConstantFriction(0.05), 353.15, 0.4e-6, 0.4e-6)
    assert result.power_loss == pytest.approx(plain.power_loss, rel=1e-14)
    low, high = result.power_loss_band
    assert low == pytest.approx(plain.power_loss * math.exp(-0.2), rel=1e-12)
    assert high == pytest.approx(plain.power_loss * math.exp(0.2), rel=1e-12)
    eta_low, eta_high = result.efficiency_band
    assert eta_low == pytest.approx(1 - high / result.input_power, rel=1e-14) and eta_low < result.efficiency < eta_high
    assert friction.alpha == pytest.approx(0.10) and result.band_coverage == pytest.approx(0.90)
    assert plain.power_loss_band is None and plain.efficiency_band is None


@pytest.mark.parametrize("name", ["atf_quick", "atf_quick_learned"])
def test_band_of_a_shipped_coefficient_file_is_a_weighted_mean_of_its_mu_intervals(name):
    """P_high/P = Σ μ_high W|u_s| / Σ μ W|u_s| is a weighted mean of μ_high/μ over the loaded points (weights
    μ W|u_s| ≥ 0), so it lies between their smallest and largest ratio; likewise for P_low. Both shipped quick files
    (Eq. 9 format 2 and the learned form) give a band around P."""
    from efficiency.friction import friction_from_spec

    friction = friction_from_spec(name)
    mesh = evaluate_mesh(fzg("H501"), 300.0, 100.0,
                         options=MeshOptions(positions=12, slices=20, outputs=frozenset()))
    with pytest.warns(UserWarning):  # the lightly loaded ends of the contact lines lie below the fitted p_h
        result = mesh_power_loss(mesh, friction, 353.15, 0.4e-6, 0.4e-6)
    cond = contact_conditions(mesh)
    loaded = cond["loaded"]
    n = int(loaded.sum())
    mu, low, high = friction.mu_interval(cond["p_h"][loaded], cond["r_eq"][loaded], cond["u_r"][loaded],
                                         cond["sr"][loaded], np.full(n, 353.15), np.full(n, 0.4e-6),
                                         np.full(n, 0.4e-6), warn=False)
    p_low, p_high = result.power_loss_band
    assert p_low < result.power_loss < p_high
    for bound, p_bound in ((low, p_low), (high, p_high)):
        ratio = bound / mu
        assert ratio.min() * (1 - 1e-12) <= p_bound / result.power_loss <= ratio.max() * (1 + 1e-12)
