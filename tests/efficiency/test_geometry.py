"""Helical gear pair geometry (efficiency.geometry) against published gears, closed forms and exact identities."""

import math
import tomllib

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ehl_dataset.data_files import data_path
from ehl_dataset.validation import InputError
from efficiency.design_io import load_study
from efficiency.geometry import GearPair, involute, inverse_involute

CASES = tomllib.loads(data_path("reference", "gear_geometry_cases.toml").read_text())
rad = math.radians


def fzg_pair(name: str, **kwargs) -> GearPair:
    case = CASES["fzg"][name]
    return GearPair(z1=case["z"][0], z2=case["z"][1], normal_module=case["normal_module_mm"] * 1e-3,
                    normal_pressure_angle=rad(CASES["fzg"]["normal_pressure_angle_deg"]),
                    helix_angle=rad(case["helix_angle_deg"]), face_width=case["face_width_mm"] * 1e-3,
                    x1=case["x"][0], x2=case["x"][1], **kwargs)


def test_inverse_involute_round_trip():
    """inv⁻¹(inv α) = α to machine precision for pressure angles 3–60° (below, tan α − α itself loses digits)."""
    alpha = np.linspace(rad(3.0), rad(60.0), 200)
    assert np.allclose(inverse_involute(involute(alpha)), alpha, rtol=1e-13, atol=1e-15)
    assert inverse_involute(0.0) == 0.0
    with pytest.raises(InputError, match="involute"):
        inverse_involute(-0.1)


@pytest.mark.parametrize("name", ["A", "B", "C", "D"])
def test_paper_table1_module_tip_and_root_diameters(name):
    """Li & Kahraman 2009 Table 1: m (4 decimals), d_o and root diameter (2 decimals) of designs A–D from the
    parametrisation (m_n = a cos Ψ/N, addendum (Λ_wd − 0.25)/2 m_n, dedendum addendum + 0.25 m_n)."""
    study = load_study("paper2009")
    published = study.designs[name]
    pair = study.design(name)
    assert abs(pair.normal_module - published.normal_module) * 1e3 <= 0.00005
    assert abs(2 * pair.tip_radii[0] - published.tip_diameter) * 1e3 <= 0.005
    assert abs(2 * pair.root_radii[0] - published.root_diameter) * 1e3 <= 0.005
    assert 2 * pair.tip_radii[0] == 2 * pair.tip_radii[1]  # identical gears
    assert pair.center_distance == pytest.approx(0.0915, abs=1e-15)
    assert pair.standard_center_distance == pytest.approx(0.0915, rel=1e-14)


@pytest.mark.parametrize("name", ["C", "H501", "H701"])
def test_fzg_gears_to_the_printed_digits(name):
    """FZG C, H501, H701 (GEARpie; Fernandes et al., Mech. Sci. 6 (2015) 81–88): zero-backlash centre distance
    91.5 mm, tip diameters with the addendum reduction k, ε_α, ε_β and p_bt to the printed digits."""
    case = CASES["fzg"][name]
    pair = fzg_pair(name)
    assert pair.center_distance * 1e3 == pytest.approx(91.5, abs=5e-4)  # x printed with 4 decimals
    for i in range(2):
        assert abs(2 * pair.tip_radii[i] * 1e3 - case["tip_diameter_mm"][i]) <= 0.5e-4
    assert abs(pair.contact_ratio - case["contact_ratio"]) <= 0.5e-5
    assert abs(pair.overlap_ratio - case["overlap_ratio"]) <= 0.5e-5
    assert abs(pair.transverse_base_pitch * 1e3 - case["transverse_base_pitch_mm"]) <= 0.5e-5
    if "working_pressure_angle_deg" in case:
        assert abs(math.degrees(pair.working_pressure_angle) - case["working_pressure_angle_deg"]) <= 0.5e-4
    if "base_helix_angle_deg" in case:
        assert abs(math.degrees(pair.base_helix_angle) - case["base_helix_angle_deg"]) <= 0.5e-4


def test_tip_reduction_restores_the_basic_rack_clearance():
    """ISO 21771: with k = x1 + x2 − y at the zero-backlash centre distance the tip-to-root clearance is exactly the
    basic rack's (h_fP − h_aP) m_n = 0.25 m_n; without it the shifted FZG C gears have less."""
    pair = fzg_pair("C")
    assert pair.tip_reduction_coefficient > 0
    for c in pair.root_clearances:
        assert c == pytest.approx(0.25 * pair.normal_module, rel=1e-12)
    full = fzg_pair("C", tip_reduction=False)
    assert all(c < 0.25 * full.normal_module for c in full.root_clearances)


def _path_of_contact_cartesian(pair: GearPair) -> float:
    """Independent construction: gear centres at (0,0) and (a,0); intersect the line of action through the pitch
    point (inclined at α_wt) with the two tip circles; the path of contact is the distance between them."""
    a = float(pair.center_distance)
    awt = float(pair.working_pressure_angle)
    rw1 = float(pair.working_pitch_radii[0])
    pitch = np.array([rw1, 0.0])
    direction = np.array([math.sin(awt), math.cos(awt)])  # perpendicular to the base-circle radius at T1

    def hit(center, radius):
        # |pitch + t d − center|² = radius² → the root nearer to the pitch point on the far side of the centre
        rel = pitch - center
        b = rel @ direction
        c = rel @ rel - radius**2
        return [-b + s * math.sqrt(b * b - c) for s in (1.0, -1.0)]

    t1 = hit(np.array([0.0, 0.0]), float(pair.tip_radii[0]))
    t2 = hit(np.array([a, 0.0]), float(pair.tip_radii[1]))
    # contact ends where gear 1's tip crosses the line on the side of T2, starts at gear 2's tip on the T1 side
    tangent1 = -rw1 * math.sin(awt)  # parameter of T1 along the line
    end = min(t for t in t1 if t > tangent1)
    start = max(t for t in t2 if t < -tangent1 * pair.z2 / pair.z1)
    return abs(end - start)


@pytest.mark.parametrize("name", ["C", "H501", "H701"])
def test_path_of_contact_equals_tip_circle_intersections(name):
    """g_α from the closed form √(r_a1² − r_b1²) + √(r_a2² − r_b2²) − a sin α_wt equals the distance between the
    intersections of the tip circles with the line of action (Cartesian construction)."""
    pair = fzg_pair(name)
    assert pair.path_of_contact == pytest.approx(_path_of_contact_cartesian(pair), rel=1e-12)
    assert pair.contact_ratio == pytest.approx(pair.path_of_contact / pair.transverse_base_pitch, rel=1e-15)


def test_standard_spur_contact_ratio_textbook_value():
    """20/20 teeth, 20°, h_a = 1 m (standard spur): ε_α = 1.557 (e.g. Niemann/Winter, Maschinenelemente II,
    ε_α for z1 = z2 = 20), and spur limits ε_β = 0, β_b = 0, m_t = m_n."""
    pair = GearPair(20, 20, 3e-3, rad(20.0), 0.0, 0.03)
    assert pair.contact_ratio == pytest.approx(1.557, abs=5e-4)
    assert pair.overlap_ratio == 0.0 and pair.base_helix_angle == 0.0
    assert pair.transverse_module == pair.normal_module


@given(beta=st.floats(0.0, 0.7), alpha=st.floats(0.25, 0.6))
@settings(max_examples=40, deadline=None)
def test_helical_identities(beta, alpha):
    """sin β_b = sin β cos α_n, p_bn = p_bt cos β_b, tan α_t = tan α_n / cos β (ISO 21771 §4)."""
    pair = GearPair(23, 41, 2e-3, alpha, beta, 0.02)
    assert math.sin(pair.base_helix_angle) == pytest.approx(math.sin(beta) * math.cos(alpha), rel=1e-12, abs=1e-15)
    assert pair.normal_base_pitch == pytest.approx(pair.transverse_base_pitch * math.cos(pair.base_helix_angle),
                                                   rel=1e-12)
    assert pair.transverse_base_pitch == pytest.approx(2 * math.pi * pair.base_radii[0] / 23, rel=1e-12)


@given(x1=st.floats(-0.4, 0.8), x2=st.floats(-0.4, 0.8), beta=st.floats(0.0, 0.6))
@settings(max_examples=40, deadline=None)
def test_zero_backlash_centre_distance_has_zero_backlash(x1, x2, beta):
    """The centre distance from inv α_wt = inv α_t + 2 tan α_n (x1 + x2)/(z1 + z2) makes the transverse tooth
    thicknesses on the operating pitch circles add up to the operating circular pitch (zero backlash)."""
    pair = GearPair(19, 37, 2.5e-3, rad(20.0), beta, 0.02, x1, x2)
    assert abs(pair.circumferential_backlash) < 1e-12


def test_backlash_from_thickness_allowances_and_centre_distance():
    """Normal backlash at the zero-backlash centre distance j_bn = (A_sn1 + A_sn2) cos α_n (ISO 21771-2 relation
    for thinned teeth); increasing a by Δa adds j_wt ≈ 2 Δa tan α_wt (first order)."""
    allow = (30e-6, 50e-6)
    pair = GearPair(25, 40, 3e-3, rad(20.0), rad(18.0), 0.03, 0.2, -0.1, thickness_allowance1=allow[0],
                    thickness_allowance2=allow[1], center_distance=None)
    assert pair.normal_backlash == pytest.approx(sum(allow) * math.cos(rad(20.0)), rel=1e-9)
    nominal = GearPair(25, 40, 3e-3, rad(20.0), rad(18.0), 0.03, 0.2, -0.1)
    da = 1e-6
    moved = GearPair(25, 40, 3e-3, rad(20.0), rad(18.0), 0.03, 0.2, -0.1, center_distance=nominal.center_distance + da)
    assert moved.circumferential_backlash == pytest.approx(2 * da * math.tan(nominal.working_pressure_angle), rel=1e-4)


def test_undercut_limit_of_the_20_degree_rack():
    """ISO 21771 undercut limit h_FfP − x m_n = r sin² α_t: with h_fP = 1.25, ρ_fP = 0.38 (h_FfP = 1.0 m_n) a
    standard 20° spur gear is undercut up to z = 17 (z_min = 2 h_FfP/sin² α = 17.1), not from 18; at the limiting
    shift x_min = h_FfP/m_n − z sin² α_t / 2 the form point sits exactly on the base circle."""
    def gear(z, x=0.0):
        return GearPair(z, 40, 2e-3, rad(20.0), 0.0, 0.02, x, 0.0)

    assert gear(17).undercut[0] and not gear(18).undercut[0]
    z = 12
    h_ffp = 1.25 - 0.38 * (1 - math.sin(rad(20.0)))
    x_min = h_ffp - z * math.sin(rad(20.0)) ** 2 / 2
    pair = gear(z, x_min)
    assert abs(pair.form_roll_distances[0]) < 1e-15
    assert pair.form_radii[0] == pytest.approx(pair.base_radii[0], rel=1e-12)


def test_tip_thickness_and_pointed_tip():
    """Tip thickness from s_y = d_y (s_t/d + inv α_t − inv α_y): equals s_t on the reference circle, vanishes at
    the pointed-tip radius where inv α_y = s_t/d + inv α_t, and s_an = s_at cos β_a."""
    pair = GearPair(30, 30, 2e-3, rad(20.0), rad(20.0), 0.02)
    r = pair.reference_radii[0]
    assert pair.transverse_thickness_at(r, 1) == pytest.approx(pair.transverse_thicknesses[0], rel=1e-12)
    inv_pointed = pair.transverse_thicknesses[0] / (2 * r) + involute(pair.transverse_pressure_angle)
    r_pointed = pair.base_radii[0] / math.cos(inverse_involute(inv_pointed))
    assert abs(pair.transverse_thickness_at(r_pointed, 1)) < 1e-15
    beta_a = math.atan(math.tan(pair.helix_angle) * pair.tip_radii[0] / r)
    assert pair.tip_normal_thicknesses[0] == pytest.approx(pair.tip_transverse_thicknesses[0] * math.cos(beta_a))


def test_vectorised_pairs_match_scalar_pairs():
    """Array inputs evaluate element-wise exactly like scalar pairs (used by the feasibility sweep)."""
    teeth = np.array([20, 33, 53])
    phi = np.radians([15.0, 22.5, 30.0])
    psi = np.radians([15.0, 21.0, 30.0])
    wd = np.array([1.85, 2.722, 3.376])
    many = GearPair.from_paper(teeth, phi, psi, wd, thickness_allowance=np.array([0.0, 2e-5, 5e-5]))
    for i in range(3):
        one = GearPair.from_paper(int(teeth[i]), phi[i], psi[i], wd[i], thickness_allowance=[0.0, 2e-5, 5e-5][i])
        for name in ("contact_ratio", "overlap_ratio", "normal_backlash", "path_of_contact"):
            assert getattr(many, name)[i] == pytest.approx(getattr(one, name), rel=1e-13, abs=1e-18)
        for name in ("tip_radii", "sap_radii", "form_radii", "tip_normal_thicknesses", "root_clearances"):
            assert getattr(many, name)[0][i] == pytest.approx(getattr(one, name)[0], rel=1e-13)


@pytest.mark.parametrize("field, value", [
    ("normal_module", -2e-3), ("normal_module", float("nan")), ("helix_angle", rad(50.0)),
    ("normal_pressure_angle", 0.0), ("face_width", 0.0), ("z1", 3), ("x1", 5.0), ("thickness_allowance1", -0.02)])
def test_bad_input_names_the_parameter(field, value):
    kwargs = dict(z1=20, z2=30, normal_module=2e-3, normal_pressure_angle=rad(20.0), helix_angle=rad(15.0),
                  face_width=0.02)
    kwargs[field] = value
    with pytest.raises(InputError, match=field):
        GearPair(**kwargs)


def test_centre_distance_inside_the_base_circles_is_rejected():
    with pytest.raises(InputError, match="center_distance"):
        GearPair(20, 30, 2e-3, rad(20.0), 0.0, 0.02, center_distance=0.045)
    with pytest.raises(InputError, match="teeth"):
        GearPair(20.5, 30, 2e-3, rad(20.0), 0.0, 0.02)
