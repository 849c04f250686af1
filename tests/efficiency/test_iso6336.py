"""ISO 6336 reference values (efficiency.iso6336) against ISO/TR 6336-30 example 1, closed-form limits and an
independent numerical construction of the generated root fillet (30° tangent)."""

import math
import tomllib

import numpy as np
import pytest
from scipy.optimize import brentq

from ehl_dataset.data_files import data_path
from ehl_dataset.validation import InputError
from efficiency import iso6336
from efficiency.design_io import paper_design
from efficiency.geometry import GearPair, involute

EX1 = tomllib.loads(data_path("reference", "gear_geometry_cases.toml").read_text())["iso_tr_6336_30_example1"]
rad = math.radians


@pytest.fixture(scope="module")
def example1() -> GearPair:
    return GearPair(z1=EX1["z"][0], z2=EX1["z"][1], normal_module=EX1["normal_module_mm"] * 1e-3,
                    normal_pressure_angle=rad(EX1["normal_pressure_angle_deg"]), helix_angle=rad(EX1["helix_angle_deg"]),
                    face_width=EX1["face_width_mm"] * 1e-3, x1=EX1["x"][0], x2=EX1["x"][1],
                    addendum_coefficient=EX1["addendum_coefficient"], dedendum_coefficient=EX1["dedendum_coefficient"],
                    root_fillet_coefficient=EX1["root_fillet_coefficient"],
                    center_distance=EX1["center_distance_mm"] * 1e-3, tip_reduction=False)


def test_tr6336_30_example1_contact_and_stiffness(example1):
    """ISO/TR 6336-30 example 1 (gear_cases.md): Z_H, Z_E, Z_β, σ_H0, c'_th, c', c_γα, c_γβ within 0.1 %, Z_ε to the
    printed 3 digits, F_t and z_n to the printed digits. C_M = 0.8, C_R = 1, C_B = 0.9 (h_fP = 1.4 m_n)."""
    pair, torque = example1, EX1["torque1_nm"]
    e = EX1["young_modulus_gpa"] * 1e9
    nu = EX1["poisson_ratio"]
    assert iso6336.nominal_tangential_load(pair, torque) == pytest.approx(EX1["tangential_load_n"], abs=0.5)
    zn = iso6336.virtual_teeth(pair)
    assert [round(float(z), 3) for z in zn] == EX1["virtual_teeth"]
    assert float(iso6336.basic_rack_factor(pair)) == pytest.approx(EX1["c_b"], rel=1e-12)
    assert iso6336.zone_factor(pair) == pytest.approx(EX1["z_h"], rel=1e-3)
    assert iso6336.elasticity_factor(e, nu, e, nu) / 1e3 == pytest.approx(EX1["z_e_sqrt_mpa"], rel=1e-3)
    assert round(float(iso6336.contact_ratio_factor(pair.contact_ratio, pair.overlap_ratio)), 3) == EX1["z_eps"]
    assert iso6336.helix_angle_factor_contact(pair.helix_angle) == pytest.approx(EX1["z_beta"], rel=1e-3)
    assert iso6336.nominal_contact_stress(pair, torque, e, nu) / 1e6 == pytest.approx(EX1["sigma_h0_mpa"], rel=1e-3)
    unit = iso6336.STIFFNESS_UNIT
    assert iso6336.theoretical_single_stiffness(pair) / unit == pytest.approx(EX1["c_th_n_per_mm_um"], rel=1e-3)
    c_single = iso6336.single_stiffness(pair, c_m=EX1["c_m"], c_r=EX1["c_r"])
    assert c_single / unit == pytest.approx(EX1["c_single_n_per_mm_um"], rel=1e-3)
    c_ga, c_gb = iso6336.mesh_stiffness(pair, c_m=EX1["c_m"], c_r=EX1["c_r"])
    assert c_ga / unit == pytest.approx(EX1["c_gamma_alpha_n_per_mm_um"], rel=1e-3)
    assert c_gb / unit == pytest.approx(EX1["c_gamma_beta_n_per_mm_um"], rel=1e-3)


def test_zone_factor_of_standard_spur_gears():
    """Z_H = √(2/(cos α sin α)) = 2.495 for unshifted 20° spur gears (ISO 6336-2 Fig. 3 at β = 0, x = 0)."""
    pair = GearPair(30, 45, 3e-3, rad(20.0), 0.0, 0.03)
    assert iso6336.zone_factor(pair) == pytest.approx(math.sqrt(2 / (math.cos(rad(20)) * math.sin(rad(20)))),
                                                      rel=1e-12)
    assert float(iso6336.zone_factor(pair)) == pytest.approx(2.495, abs=5e-4)


def test_contact_ratio_factor_branches_are_continuous():
    """Z_ε: spur limit √((4 − ε_α)/3); both branches equal √(1/ε_α) at ε_β = 1 (ISO 6336-2 Eq. 28–30)."""
    assert iso6336.contact_ratio_factor(1.6, 0.0) == pytest.approx(math.sqrt((4 - 1.6) / 3))
    below = iso6336.contact_ratio_factor(1.6, 1.0 - 1e-12)
    assert below == pytest.approx(iso6336.contact_ratio_factor(1.6, 1.0), rel=1e-9)
    assert iso6336.contact_ratio_factor(1.6, 2.0) == pytest.approx(math.sqrt(1 / 1.6))


def test_helix_angle_factor_bending_limits():
    """Y_β = 1 − ε_β β/120° (ISO 6336-3 Eq. 33): 1 for spur gears, 0.75 floor at ε_β ≥ 1 and β ≥ 30°."""
    assert iso6336.helix_angle_factor_bending(0.0, 0.0) == 1.0
    assert iso6336.helix_angle_factor_bending(1.5, rad(35.0)) == pytest.approx(0.75)
    assert iso6336.helix_angle_factor_bending(0.5, rad(15.0)) == pytest.approx(1 - 0.5 * 15 / 120)


def test_low_line_load_reduces_the_single_stiffness():
    """ISO 6336-1: below F_t K_A/b = 100 N/mm, c' is multiplied by (line load/100)^0.25."""
    pair = GearPair(30, 45, 3e-3, rad(20.0), 0.0, 0.03)
    full = iso6336.single_stiffness(pair)
    assert iso6336.single_stiffness(pair, line_load=200e3) == pytest.approx(full)
    assert iso6336.single_stiffness(pair, line_load=25e3) == pytest.approx(full * 0.25**0.25)


# ---------------------------------------------------------------------- independent root-fillet construction
def _numerical_root_section(pair: GearPair, gear: int):
    """30° tangent section of the virtual spur gear found on the fillet generated by the rack tip circle.

    Gear frame: space centre line on +y; the rack (reference line at r + x m, tip line h_fP below it, tip radius
    ρ centred at half-width E from the rack tooth centre line) rolls on the pitch circle r = z_n m/2. The tip
    circle centre in gear coordinates is T(φ) = Rot(φ)(E + rφ, r + x m − h_fP + ρ); the fillet is its offset by ρ
    towards the gear. The 30° tangent point is where the fillet tangent makes 30° with the centre line of the
    adjacent tooth. Returns s_Fn, ρ_F and the height of the section along the tooth centre line.
    """
    i = gear - 1
    m = float(pair.normal_module)
    alpha = float(pair.normal_pressure_angle)
    zn = float(iso6336.virtual_teeth(pair)[i])
    x = (pair.x1, pair.x2)[i]
    hfp = pair.dedendum_coefficient * m
    rho = pair.root_fillet_coefficient * m
    r = zn * m / 2
    e = math.pi / 4 * m - hfp * math.tan(alpha) - rho * (1 - math.sin(alpha)) / math.cos(alpha)
    yc = r + x * m - hfp + rho

    def fillet(phi):
        c, s = np.cos(phi), np.sin(phi)
        px, py = e + r * phi, yc
        tx, ty = c * px - s * py, s * px + c * py
        dpx = r
        vx = -s * px - c * py + c * dpx
        vy = c * px - s * py + s * dpx
        norm = np.hypot(vx, vy)
        nx, ny = -vy / norm, vx / norm
        return tx - rho * nx, ty - rho * ny

    half_pitch = math.pi / zn
    u = np.array([math.sin(half_pitch), math.cos(half_pitch)])  # centre line of the tooth on the +x side
    w = np.array([u[1], -u[0]])  # perpendicular to it, pointing into the space

    def tangent_angle(phi, h=1e-7):
        x1, y1 = fillet(phi - h)
        x2, y2 = fillet(phi + h)
        d = np.array([x2 - x1, y2 - y1])
        return math.atan2(abs(d @ w), abs(d @ u))  # angle between tangent and the tooth centre line

    phis = np.linspace(-0.02, 0.6, 3000)
    angles = np.array([tangent_angle(p) for p in phis]) - math.radians(30.0)
    k = np.nonzero(np.sign(angles[:-1]) != np.sign(angles[1:]))[0][0]
    phi30 = brentq(lambda p: tangent_angle(p) - math.radians(30.0), phis[k], phis[k + 1], xtol=1e-14)
    fx, fy = fillet(phi30)
    point = np.array([fx, fy])
    s_fn = 2 * abs(point @ w)
    height = point @ u
    h = 1e-5
    (xa, ya), (xb, yb), (xc, yc2) = fillet(phi30 - h), fillet(phi30), fillet(phi30 + h)
    dx, dy = (xc - xa) / (2 * h), (yc2 - ya) / (2 * h)
    ddx, ddy = (xc - 2 * xb + xa) / h**2, (yc2 - 2 * yb + ya) / h**2
    rho_f = (dx * dx + dy * dy) ** 1.5 / abs(dx * ddy - dy * ddx)
    return s_fn, rho_f, height


def _numerical_bending_arm(pair: GearPair, gear: int, section_height: float, d_en: float):
    """Load on the involute at d_en along its normal (tangent to the base circle); returns the distance from where
    that line crosses the tooth centre line down to the critical section, and the load angle to the normal of the
    centre line."""
    i = gear - 1
    m = float(pair.normal_module)
    alpha = float(pair.normal_pressure_angle)
    zn = float(iso6336.virtual_teeth(pair)[i])
    x = (pair.x1, pair.x2)[i]
    r = zn * m / 2
    rb = r * math.cos(alpha)
    s = m * (math.pi / 2 + 2 * x * math.tan(alpha))
    ry = d_en / 2
    ay = math.acos(rb / ry)
    psi = s / (2 * r) + float(involute(alpha)) - float(involute(ay))  # half tooth angle at r_y
    p = ry * np.array([math.sin(psi), math.cos(psi)])  # tooth-local frame, centre line = +y
    b = rb * np.array([math.sin(psi - ay), math.cos(psi - ay)])  # tangent point on the base circle
    d = b - p
    t = -p[0] / d[0]
    y_cross = p[1] + t * d[1]
    return y_cross - section_height, math.atan2(abs(d[1]), abs(d[0]))


@pytest.mark.parametrize("case", ["example1_pinion", "example1_wheel", "design_D", "spur_z25"])
def test_root_section_matches_the_generated_fillet(case, example1):
    """ISO 6336-3 method B closed forms (θ iteration, s_Fn, ρ_F, h_Fe, α_Fen) equal a direct numerical
    construction of the trochoidal fillet generated by the rack tip radius and of the load line at d_en."""
    pair, gear = {
        "example1_pinion": (example1, 1),
        "example1_wheel": (example1, 2),
        "design_D": (paper_design(32, 30.0, 19.0, 2.068), 1),
        "spur_z25": (GearPair(25, 50, 3e-3, rad(20.0), 0.0, 0.03, 0.2, 0.0), 1),
    }[case]
    section = iso6336.root_section(pair, gear)
    s_fn, rho_f, height = _numerical_root_section(pair, gear)
    assert section.s_fn == pytest.approx(s_fn, rel=1e-6)
    assert section.rho_f == pytest.approx(rho_f, rel=1e-3)
    h_fe, alpha_fen = _numerical_bending_arm(pair, gear, height, section.d_en)
    assert section.h_fe == pytest.approx(h_fe, rel=1e-6)
    assert section.alpha_fen == pytest.approx(alpha_fen, rel=1e-9)


def test_nominal_root_stress_is_the_product_of_its_factors(example1):
    """σ_F0 = F_t/(b m_n) Y_F Y_S Y_β (ISO 6336-3 Eq. 3) and Y_S from L = s_Fn/h_Fe, q_s = s_Fn/(2ρ_F)."""
    pair = example1
    s = iso6336.root_section(pair, 1)
    el, qs = s.s_fn / s.h_fe, s.s_fn / (2 * s.rho_f)
    ys = (1.2 + 0.13 * el) * qs ** (1 / (1.21 + 2.3 / el))
    assert iso6336.stress_correction_factor(pair, 1) == pytest.approx(ys, rel=1e-14)
    ft = iso6336.nominal_tangential_load(pair, 9000.0)
    expected = (ft / (pair.face_width * pair.normal_module) * iso6336.tooth_form_factor(pair, 1) * ys
                * iso6336.helix_angle_factor_bending(pair.overlap_ratio, pair.helix_angle))
    assert iso6336.nominal_root_stress(pair, 9000.0, 1) == pytest.approx(expected, rel=1e-14)


def test_bad_inputs_name_the_parameter(example1):
    with pytest.raises(InputError, match="torque1"):
        iso6336.nominal_tangential_load(example1, -5.0)
    with pytest.raises(InputError, match="nu1"):
        iso6336.elasticity_factor(206e9, 0.6)
    with pytest.raises(InputError, match="gear"):
        iso6336.root_section(example1, 3)
