"""Kinematics of the helical mesh on the plane of action (efficiency.kinematics)."""

import math

import numpy as np
import pytest

from ehl_dataset.validation import InputError
from efficiency.geometry import GearPair
from efficiency.kinematics import mesh_kinematics

DEG = math.pi / 180.0


def fzg_h501():
    """FZG H501 helical pair (gear_cases.md: Fernandes et al. 2015 / GEARpie), ratio 1.5."""
    return GearPair(20, 30, 3.5e-3, 20 * DEG, 15 * DEG, 0.023, x1=0.1809, x2=0.0891)


def design_d():
    """The paper's design D (Li & Kahraman 2009, Table 1): N = 32, Φ = 30°, Ψ = 19°, Λ_wd = 2.068."""
    return GearPair.from_paper(32, 30 * DEG, 19 * DEG, 2.068)


def test_sliding_vanishes_at_the_pitch_point_and_is_linear_in_roll_angle():
    """u_s = ω1 ρ1 − ω2 ρ2 = (ω1 + ω2) s − ω2 T1T2 is linear in s (hence in the roll angle s/r_b1) and vanishes
    at the pitch point s = r_b1 tan α_wt (involute kinematics: pure rolling at the pitch point)."""
    pair = fzg_h501()
    omega1 = 2 * math.pi * 3000 / 60
    kin = mesh_kinematics(pair, positions=16, slices=12, speed_rad_s=omega1)
    s = kin.roll[kin.in_contact]
    u_s = kin.u_s[kin.in_contact]
    slope, intercept = np.polyfit(s, u_s, 1)
    assert np.max(np.abs(u_s - (slope * s + intercept))) < 1e-9 * np.max(np.abs(u_s))
    assert slope == pytest.approx(kin.omega1 + kin.omega2, rel=1e-12)
    assert -intercept / slope == pytest.approx(float(pair.pitch_point), rel=1e-12)
    # the ratio: ω2 = ω1 z1/z2 for base radii in the ratio of the tooth numbers
    assert kin.omega2 == pytest.approx(omega1 * 20 / 30, rel=1e-12)
    # rolling velocity and radii
    assert np.allclose(kin.rho1 + kin.rho2, float(pair.line_of_action_length), rtol=0, atol=1e-15)
    assert np.allclose(kin.u_r, 0.5 * (omega1 * kin.rho1 + kin.omega2 * kin.rho2), rtol=1e-14)
    cos_b = math.cos(float(pair.base_helix_angle))
    assert np.allclose(kin.rho1_normal * cos_b, kin.rho1, rtol=1e-14)


def test_contact_lines_are_inclined_at_the_base_helix_angle():
    """Along a contact line the roll distance advances by Δz tan ψ_b per slice (Litvin & Fuentes §14)."""
    pair = design_d()
    kin = mesh_kinematics(pair, positions=4, slices=25)
    steps = np.diff(kin.roll, axis=2)
    assert np.allclose(steps, kin.slice_width * math.tan(float(pair.base_helix_angle)), rtol=1e-12)


@pytest.mark.parametrize("positions", [24, 97])
@pytest.mark.parametrize("pair_factory", [fzg_h501, design_d])
def test_contact_ratios_from_the_kinematics_equal_the_closed_forms(pair_factory, positions):
    """Averaged over a mesh cycle, the number of tooth pairs in contact in one transverse slice is ε_α = g_α/p_bt
    and the number of pairs touching anywhere on the face is ε_γ = ε_α + ε_β (ISO 21771). With M equally spaced
    positions each count can differ from its limit by at most 1/M."""
    pair = pair_factory()
    kin = mesh_kinematics(pair, positions=positions, slices=40)
    per_slice = kin.contact_count_per_slice().mean(axis=0)
    assert np.all(np.abs(per_slice - float(pair.contact_ratio)) <= 1.0 / positions + 1e-12)
    pairs = kin.pairs_in_contact().mean()
    # the slice centres sample the face: the face extent is (S − 1)/S b, i.e. ε_β (1 − 1/S)
    expected = float(pair.contact_ratio) + float(pair.overlap_ratio) * (1 - 1 / 40)
    assert abs(pairs - expected) <= 1.0 / positions + 1e-12


def test_spur_pair_has_straight_contact_lines():
    """Ψ = 0: every slice of a tooth pair touches at the same roll distance (FZG type C spur gears)."""
    pair = GearPair(16, 24, 4.5e-3, 20 * DEG, 0.0, 0.014, x1=0.1817, x2=0.1715)
    kin = mesh_kinematics(pair, positions=8, slices=5)
    assert np.all(kin.roll == kin.roll[..., :1])
    assert kin.contact_count_per_slice().mean() == pytest.approx(float(pair.contact_ratio), abs=1 / 8)


@pytest.mark.parametrize("name,value", [("positions", 0), ("slices", -3), ("speed_rad_s", float("nan"))])
def test_bad_resolution_is_reported_by_name(name, value):
    kwargs = {"positions": 8, "slices": 8, "speed_rad_s": 1.0, name: value}
    with pytest.raises(InputError, match=name):
        mesh_kinematics(design_d(), **kwargs)
