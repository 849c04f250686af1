"""ISO 6336 reference values of a helical gear pair (SI units; stiffness in N/m² = N/(m·m)).

These are the standard's *nominal* values, computed alongside the load-distribution model for comparison:

- ISO 6336-2:2006 (pitting): zone factor Z_H, elasticity factor Z_E, contact ratio factor Z_ε, helix angle factor
  Z_β and the nominal contact stress at the pitch point σ_H0 = Z_H Z_E Z_ε Z_β √(F_t (u + 1)/(d1 b u)).
- ISO 6336-1:2006 method B (stiffness): theoretical single stiffness c'_th = 1/q'_min from the series in z_n and x,
  single stiffness c' = c'_th C_M C_R C_B cos β (line load ≥ 100 N/mm), mesh stiffness c_γα = c'(0.75 ε_α + 0.25),
  c_γβ = 0.85 c_γα.
- ISO 6336-3:2006 method B (tooth root): tooth form factor Y_F from the 30° tangent to the generated root fillet with
  the load at the outer point of single tooth contact of the virtual spur gear, stress correction factor Y_S,
  helix angle factor Y_β, nominal root stress σ_F0 = F_t/(b m_n) Y_F Y_S Y_β (Y_B = Y_DT = 1).

1 N/(mm·µm) = 1e9 N/m². Units in ISO 6336 are mm, N, N/mm², µm; here everything is converted to SI.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ehl_dataset.validation import InputError, check_range

from .geometry import GearPair, _gear_index, involute

STIFFNESS_UNIT = 1e9  # N/m² per N/(mm·µm)

# ISO 6336-1:2006 Table 9: coefficients of q'_min [mm·µm/N] (method B, solid spur gears, ISO basic rack)
_Q_COEFFICIENTS = (0.04723, 0.15551, 0.25791, -0.00635, -0.11654, -0.00193, -0.24188, 0.00529, 0.00182)


# ---------------------------------------------------------------------- common
def virtual_teeth(pair: GearPair) -> tuple[float, float]:
    """Virtual numbers of teeth z_n = z / (cos² β_b cos β) (ISO 6336-1/-3).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].

    Returns
    -------
    tuple of float
        (z_n1, z_n2) [-].
    """
    c = np.cos(pair.base_helix_angle) ** 2 * np.cos(pair.helix_angle)
    return (pair.z1 / c, pair.z2 / c)


def nominal_tangential_load(pair: GearPair, torque1: float) -> float:
    """Nominal tangential load F_t = 2 T1 / d1 on the reference circle.

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    torque1 : float
        Pinion (gear 1) torque T1 [N·m].

    Returns
    -------
    float
        F_t [N].
    """
    check_range("torque1", torque1, 0.0, 1e9, low_inclusive=False, unit="N·m")
    return 2.0 * torque1 / (2.0 * pair.reference_radii[0])


# ---------------------------------------------------------------------- ISO 6336-2: contact
def zone_factor(pair: GearPair) -> float:
    """Zone factor Z_H = √(2 cos β_b cos α_wt / (cos² α_t sin α_wt)) (ISO 6336-2:2006 Eq. 10).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].

    Returns
    -------
    float
        Z_H [-].
    """
    awt, at = pair.working_pressure_angle, pair.transverse_pressure_angle
    return np.sqrt(2.0 * np.cos(pair.base_helix_angle) * np.cos(awt) / (np.cos(at) ** 2 * np.sin(awt)))


def elasticity_factor(e1: float = 206e9, nu1: float = 0.3, e2: float = 206e9, nu2: float = 0.3) -> float:
    """Elasticity factor Z_E = √(1 / (π ((1 − ν1²)/E1 + (1 − ν2²)/E2))) (ISO 6336-2:2006 Eq. 23).

    Parameters
    ----------
    e1 : float
        Young's modulus of gear 1 [Pa].
    nu1 : float
        Poisson's ratio of gear 1 [-].
    e2 : float
        Young's modulus of gear 2 [Pa].
    nu2 : float
        Poisson's ratio of gear 2 [-].

    Returns
    -------
    float
        Z_E [√Pa].
    """
    for name, value in (("e1", e1), ("e2", e2)):
        check_range(name, value, 0.0, 1e13, low_inclusive=False, unit="Pa")
    for name, value in (("nu1", nu1), ("nu2", nu2)):
        check_range(name, value, 0.0, 0.5, high_inclusive=False)
    return math.sqrt(1.0 / (math.pi * ((1.0 - nu1**2) / e1 + (1.0 - nu2**2) / e2)))


def contact_ratio_factor(eps_alpha: float, eps_beta: float) -> float:
    """Contact ratio factor Z_ε (ISO 6336-2:2006 Eq. 28–30).

    Z_ε = √((4 − ε_α)/3 (1 − ε_β) + ε_β/ε_α) for ε_β < 1, else √(1/ε_α).

    Parameters
    ----------
    eps_alpha : float
        Transverse contact ratio ε_α [-].
    eps_beta : float
        Overlap ratio ε_β [-].

    Returns
    -------
    float
        Z_ε [-].
    """
    eps_alpha = np.asarray(eps_alpha, dtype=float)
    eps_beta = np.asarray(eps_beta, dtype=float)
    low = np.sqrt((4.0 - eps_alpha) / 3.0 * (1.0 - eps_beta) + eps_beta / eps_alpha)
    return np.where(eps_beta < 1.0, low, np.sqrt(1.0 / eps_alpha))[()]


def helix_angle_factor_contact(helix_angle: float) -> float:
    """Helix angle factor Z_β = 1/√cos β (ISO 6336-2:2006 Eq. 32).

    Parameters
    ----------
    helix_angle : float
        Helix angle β [rad].

    Returns
    -------
    float
        Z_β [-].
    """
    return 1.0 / np.sqrt(np.cos(helix_angle))


def nominal_contact_stress(pair: GearPair, torque1: float, e: float = 206e9, nu: float = 0.3) -> float:
    """Nominal contact stress σ_H0 = Z_H Z_E Z_ε Z_β √(F_t (u + 1) / (d1 b u)) (ISO 6336-2:2006 Eq. 2, external gears).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    torque1 : float
        Pinion (gear 1) torque T1 [N·m].
    e : float
        Young's modulus of both gears [Pa].
    nu : float
        Poisson's ratio of both gears [-].

    Returns
    -------
    float
        σ_H0 [Pa].
    """
    ft = nominal_tangential_load(pair, torque1)
    u = pair.gear_ratio
    d1 = 2.0 * pair.reference_radii[0]
    z = (zone_factor(pair) * elasticity_factor(e, nu, e, nu)
         * contact_ratio_factor(pair.contact_ratio, pair.overlap_ratio) * helix_angle_factor_contact(pair.helix_angle))
    return z * np.sqrt(ft * (u + 1.0) / (d1 * pair.face_width * u))


# ---------------------------------------------------------------------- ISO 6336-1: stiffness
def theoretical_single_stiffness(pair: GearPair) -> float:
    """Theoretical single stiffness c'_th = 1/q'_min (ISO 6336-1:2006 method B, Eq. 96–97 and Table 9).

    q'_min = C1 + C2/z_n1 + C3/z_n2 + C4 x1 + C5 x1/z_n1 + C6 x2 + C7 x2/z_n2 + C8 x1² + C9 x2², in mm·µm/N.

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].

    Returns
    -------
    float
        c'_th [N/m²].
    """
    c1, c2, c3, c4, c5, c6, c7, c8, c9 = _Q_COEFFICIENTS
    zn1, zn2 = virtual_teeth(pair)
    x1, x2 = pair.x1, pair.x2
    q = c1 + c2 / zn1 + c3 / zn2 + c4 * x1 + c5 * x1 / zn1 + c6 * x2 + c7 * x2 / zn2 + c8 * x1**2 + c9 * x2**2
    return STIFFNESS_UNIT / q


def basic_rack_factor(pair: GearPair) -> float:
    """Basic rack factor C_B = (1 + 0.5 (1.2 − h_fP/m_n)) · (1 − 0.02 (20° − α_n)).

    ISO 6336-1:2006 Eq. 98; α_n in degrees.

    Both gears are generated by the same basic rack here, so C_B = C_B1 = C_B2.

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].

    Returns
    -------
    float
        C_B [-].
    """
    return (1.0 + 0.5 * (1.2 - pair.dedendum_coefficient)) * (1.0 - 0.02 * (20.0 - np.degrees(
        pair.normal_pressure_angle)))


def single_stiffness(pair: GearPair, c_m: float = 0.8, c_r: float = 1.0, c_b: float | None = None,
                     line_load: float | None = None) -> float:
    """Single stiffness c' = c'_th C_M C_R C_B cos β (ISO 6336-1:2006 Eq. 94).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    c_m : float
        C_M, theoretical to measured (0.8 for solid discs) [-].
    c_r : float
        Gear blank factor C_R (1 for solid blanks) [-].
    c_b : float, optional
        Basic rack factor; None: :func:`basic_rack_factor` [-].
    line_load : float, optional
        F_t K_A / b; below 100 N/mm the standard multiplies by (line load / 100 N/mm)^0.25 [N/m].

    Returns
    -------
    float
        c' [N/m²].
    """
    check_range("c_m", c_m, 0.0, 2.0, low_inclusive=False)
    check_range("c_r", c_r, 0.0, 2.0, low_inclusive=False)
    cb = basic_rack_factor(pair) if c_b is None else check_range("c_b", c_b, 0.0, 2.0, low_inclusive=False)
    c = theoretical_single_stiffness(pair) * c_m * c_r * cb * np.cos(pair.helix_angle)
    if line_load is not None:
        check_range("line_load", line_load, 0.0, 1e9, low_inclusive=False, unit="N/m")
        c = c * min(1.0, (line_load / 100e3) ** 0.25)
    return c


def mesh_stiffness(pair: GearPair, **single_kwargs) -> tuple[float, float]:
    """Mesh stiffnesses c_γα = c'(0.75 ε_α + 0.25) and c_γβ = 0.85 c_γα (ISO 6336-1:2006 Eq. 99–100).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    **single_kwargs
        Arguments of :func:`single_stiffness` [-].

    Returns
    -------
    tuple of float
        (c_γα, c_γβ) [N/m²].
    """
    c_ga = single_stiffness(pair, **single_kwargs) * (0.75 * pair.contact_ratio + 0.25)
    return c_ga, 0.85 * c_ga


# ---------------------------------------------------------------------- ISO 6336-3: tooth root
@dataclass(frozen=True)
class RootSection:
    """Critical root section by the 30° tangent (ISO 6336-3:2006 method B), SI.

    Parameters
    ----------
    s_fn : float
        Chord at the critical section [m].
    h_fe : float
        Bending moment arm for load at the outer point of single tooth contact [m].
    rho_f : float
        Root fillet radius at the critical section [m].
    alpha_fen : float
        Load direction angle [rad].
    theta : float
        Auxiliary angle of the iteration [rad].
    d_en : float
        Diameter of the outer point of single contact of the virtual spur gear [m].
    z_n : float
        Virtual number of teeth [-].
    """

    s_fn: float
    h_fe: float
    rho_f: float
    alpha_fen: float
    theta: float
    d_en: float
    z_n: float


def root_section(pair: GearPair, gear: int, protuberance: float = 0.0) -> RootSection:
    """30°-tangent root section of gear 1 or 2 generated by the pair's basic rack (ISO 6336-3:2006 Eq. 5–24).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    gear : int
        1 or 2 [-].
    protuberance : float
        Residual undercut s_pr of a protuberance tool (0 for a standard hob) [m].

    Returns
    -------
    RootSection
        The section.
    """
    i = _gear_index(gear)
    mn = float(pair.normal_module)
    an = float(pair.normal_pressure_angle)
    z = float(pair.teeth[i])
    zn = float(virtual_teeth(pair)[i])
    x = float((pair.x1, pair.x2)[i])
    hfp = float(pair.dedendum_coefficient) * mn
    rho_fp = float(pair.root_fillet_coefficient) * mn
    d = 2.0 * float(pair.reference_radii[i])
    da = 2.0 * float(pair.tip_radii[i])
    beta = float(pair.helix_angle)
    beta_b = float(pair.base_helix_angle)

    e = math.pi / 4.0 * mn - hfp * math.tan(an) + protuberance / math.cos(an) - (1.0 - math.sin(an)) * rho_fp / math.cos(an)
    g = rho_fp / mn - hfp / mn + x
    h = 2.0 / zn * (math.pi / 2.0 - e / mn) - math.pi / 3.0
    theta = math.pi / 6.0
    for _ in range(100):
        new = 2.0 * g / zn * math.tan(theta) - h
        if abs(new - theta) < 1e-14:
            theta = new
            break
        theta = new
    else:  # pragma: no cover - the fixed point iteration contracts for all practical gears
        raise InputError("root_section", gear, "a gear for which the 30° tangent iteration converges")
    s_fn = mn * (zn * math.sin(math.pi / 3.0 - theta) + math.sqrt(3.0) * (g / math.cos(theta) - rho_fp / mn))
    rho_f = rho_fp + 2.0 * mn * g**2 / (math.cos(theta) * (zn * math.cos(theta) ** 2 - 2.0 * g))

    # virtual spur gear and the outer point of single pair tooth contact
    dn = mn * zn
    dbn = dn * math.cos(an)
    dan = dn + da - d
    eps_an = float(pair.contact_ratio) / math.cos(beta_b) ** 2
    pbn_term = math.pi * d * math.cos(beta) * math.cos(an) / z * (eps_an - 1.0)
    den = 2.0 * math.sqrt((math.sqrt((dan / 2.0) ** 2 - (dbn / 2.0) ** 2) - pbn_term) ** 2 + (dbn / 2.0) ** 2)
    alpha_en = math.acos(dbn / den)
    gamma_e = (0.5 * math.pi + 2.0 * x * math.tan(an)) / zn + float(involute(an)) - float(involute(alpha_en))
    alpha_fen = alpha_en - gamma_e
    h_fe = 0.5 * mn * ((math.cos(gamma_e) - math.sin(gamma_e) * math.tan(alpha_fen)) * den / mn
                       - zn * math.cos(math.pi / 3.0 - theta) - g / math.cos(theta) + rho_fp / mn)
    return RootSection(s_fn, h_fe, rho_f, alpha_fen, theta, den, zn)


def tooth_form_factor(pair: GearPair, gear: int, section: RootSection | None = None) -> float:
    """Tooth form factor Y_F = (6 h_Fe/m_n cos α_Fen) / ((s_Fn/m_n)² cos α_n) (ISO 6336-3:2006 Eq. 5, method B).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    gear : int
        1 or 2 [-].
    section : RootSection, optional
        Precomputed :func:`root_section` [-].

    Returns
    -------
    float
        Y_F [-].
    """
    s = section or root_section(pair, gear)
    mn = float(pair.normal_module)
    return 6.0 * s.h_fe / mn * math.cos(s.alpha_fen) / ((s.s_fn / mn) ** 2 * math.cos(float(pair.normal_pressure_angle)))


def stress_correction_factor(pair: GearPair, gear: int, section: RootSection | None = None) -> float:
    """Stress correction factor Y_S = (1.2 + 0.13 L) q_s^(1/(1.21 + 2.3/L)), L = s_Fn/h_Fe, q_s = s_Fn/(2 ρ_F).

    ISO 6336-3:2006 Eq. 25–27.

    The standard states the range 1 ≤ q_s < 8; outside it the value is extrapolated (no error is raised).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    gear : int
        1 or 2 [-].
    section : RootSection, optional
        Precomputed :func:`root_section` [-].

    Returns
    -------
    float
        Y_S [-].
    """
    s = section or root_section(pair, gear)
    el = s.s_fn / s.h_fe
    qs = s.s_fn / (2.0 * s.rho_f)
    return (1.2 + 0.13 * el) * qs ** (1.0 / (1.21 + 2.3 / el))


def helix_angle_factor_bending(overlap_ratio: float, helix_angle: float) -> float:
    """Helix angle factor Y_β = 1 − ε_β β/120° (ISO 6336-3:2006 Eq. 33).

    ε_β is limited to 1 and β to 30° in the formula.

    Parameters
    ----------
    overlap_ratio : float
        ε_β [-].
    helix_angle : float
        β [rad].

    Returns
    -------
    float
        Y_β [-].
    """
    eps = np.minimum(np.asarray(overlap_ratio, dtype=float), 1.0)
    beta_deg = np.minimum(np.degrees(helix_angle), 30.0)
    return (1.0 - eps * beta_deg / 120.0)[()]


def nominal_root_stress(pair: GearPair, torque1: float, gear: int) -> float:
    """Nominal root stress σ_F0 = F_t/(b m_n) Y_F Y_S Y_β (ISO 6336-3:2006 Eq. 3, method B, Y_B = Y_DT = 1).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    torque1 : float
        Pinion (gear 1) torque T1 [N·m].
    gear : int
        1 or 2 [-].

    Returns
    -------
    float
        σ_F0 [Pa].
    """
    s = root_section(pair, gear)
    ft = nominal_tangential_load(pair, torque1)
    return (ft / (pair.face_width * pair.normal_module) * tooth_form_factor(pair, gear, s)
            * stress_correction_factor(pair, gear, s) * helix_angle_factor_bending(pair.overlap_ratio,
                                                                                    pair.helix_angle))


def reference_values(pair: GearPair, torque1: float, e: float = 206e9, nu: float = 0.3, c_m: float = 0.8,
                     c_r: float = 1.0) -> dict:
    """All ISO 6336 reference values of a scalar pair at a pinion torque, SI with unit suffixes in the keys.

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    torque1 : float
        Pinion (gear 1) torque T1 [N·m].
    e : float
        Young's modulus of both gears [Pa].
    nu : float
        Poisson's ratio of both gears [-].
    c_m : float
        Correction factor C_M of the single stiffness [-].
    c_r : float
        Gear blank factor C_R [-].

    Returns
    -------
    dict
        Z and Y factors, stresses [Pa], stiffnesses [N/m²] and virtual teeth.
    """
    ft = nominal_tangential_load(pair, torque1)
    c_ga, c_gb = mesh_stiffness(pair, c_m=c_m, c_r=c_r, line_load=ft / pair.face_width)
    out = {
        "tangential_load_n": float(ft),
        "z_h": float(zone_factor(pair)),
        "z_e_sqrt_pa": float(elasticity_factor(e, nu, e, nu)),
        "z_eps": float(contact_ratio_factor(pair.contact_ratio, pair.overlap_ratio)),
        "z_beta": float(helix_angle_factor_contact(pair.helix_angle)),
        "sigma_h0_pa": float(nominal_contact_stress(pair, torque1, e, nu)),
        "c_th_n_per_m2": float(theoretical_single_stiffness(pair)),
        "c_single_n_per_m2": float(single_stiffness(pair, c_m=c_m, c_r=c_r, line_load=ft / pair.face_width)),
        "c_gamma_alpha_n_per_m2": float(c_ga),
        "c_gamma_beta_n_per_m2": float(c_gb),
        "y_beta": float(helix_angle_factor_bending(pair.overlap_ratio, pair.helix_angle)),
    }
    for gear in (1, 2):
        s = root_section(pair, gear)
        out[f"y_f{gear}"] = float(tooth_form_factor(pair, gear, s))
        out[f"y_s{gear}"] = float(stress_correction_factor(pair, gear, s))
        out[f"sigma_f0_{gear}_pa"] = float(nominal_root_stress(pair, torque1, gear))
    return out
