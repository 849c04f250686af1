"""Tooth and contact compliance of an involute gear pair for the slice load-distribution model, SI units.

One transverse slice of a tooth is a cantilever of unit width loaded along its transverse line of action at the
contact radius. Its compliance per unit face width, ``c_t(ρ)`` [m²/N] (deflection along the line of action per
load per unit face width), is the sum of

- bending, shear and axial compression of the tooth as a beam of variable thickness clamped at the root circle
  (strain energy / potential energy method: Yang & Lin, J. Mech. Trans. Autom. Des. 109 (1987) 189; Tian,
  MSc thesis, U. Saskatchewan 2004; Chen & Shao, Eng. Fail. Anal. 18 (2011) 2149):
      c_b = ∫ [cos α1 (x_c − x) − y_c sin α1]² / (E' I(x)) dx,   I = (2y)³/12,
      c_s = ∫ 1.2 cos² α1 / (G A(x)) dx,   c_a = ∫ sin² α1 / (E' A(x)) dx,   A = 2y,
  with the involute half thickness y(r) above the base circle, constant (= y(r_b)) between the root circle and
  the base circle (the usual straight-flank approximation of the fillet zone), α1 the angle between the load line
  and the normal to the tooth centreline, and (x_c, y_c) the load point. Plane strain E' = E/(1 − ν²) (wide face),
  G = E / (2(1 + ν));
- the fillet-foundation (gear body) deflection of Sainsot, Velex & Duverger, J. Mech. Des. 126 (2004) 748:
      c_f = cos² α1 / E · [L* (u_f/S_f)² + M* (u_f/S_f) + P* (1 + Q* tan² α1)],
  with L*, M*, P*, Q* their polynomial fits in h_f = r_f / r_int and θ_f (half tooth angle at the root circle),
  u_f the distance from the root circle to where the load line crosses the tooth centreline, S_f the tooth
  thickness at the root circle, r_int the bore (hub) radius.

The Hertzian contact compliance (normal approach per load per unit length of contact line) is either
- Weber's (1949) line-contact approach between the tooth centre lines (default; the half-plane solution under a
  Hertz pressure, Johnson, *Contact Mechanics* (1985) §5.6): for each body the surface point moves towards a point
  at depth d by (w (1 − ν²)/(π E)) [2 ln(2d/a) − ν/(1 − ν)], with a = √(8 w R/(π E')) the Hertz half width and d
  the distance from the contact point to the tooth centre line along the load line. It depends (logarithmically)
  on the local load, so the load distribution iterates on it (secant compliance);
- or the load-independent value of Yang & Lin (1987), ``c_H = 4 / (π E')`` (a contact stiffness π E' L / 4 for
  a contact of length L), which is stiffer by a factor of about 2–3 for gear teeth.
E' = 2/[(1 − ν1²)/E1 + (1 − ν2²)/E2].

Coupling along the face: a load on one slice also deflects its neighbours. The influence function is the
exponential kernel κ(d) = exp(−|d|/ℓ)/(2ℓ) (the Green's function of (1 − ℓ² d²/dz²), the form used for
face-width coupling in thin-slice models), reflected at the free faces z = 0 and z = b (images), so a uniform
line load gives exactly the uniform slice deflection and a load at a face end deflects twice as much as the same
load at mid-face. The length ℓ is a model parameter: default one whole tooth depth (a concentrated load is carried
by an effective face width 2ℓ), a representative value (see docs/explanation/gear-model.md for the sensitivity).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ehl_dataset.model.materials import STEEL, Material, reduced_modulus
from ehl_dataset.validation import check_range

# Sainsot, Velex & Duverger 2004, Table 1: X* = A/θ_f² + B h_f² + C h_f/θ_f + D/θ_f + E h_f + F for L*, M*, P*, Q*.
_SAINSOT = np.array([
    [-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045],
    [60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086],
    [-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236],
    [-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904],
])
_GAUSS_T, _GAUSS_W = np.polynomial.legendre.leggauss(16)

DEFAULT_HUB_RATIO = 2.0
"""Default h_f = r_f / r_int (root radius over bore radius) for the foundation term: a solid gear on a shaft of
half the root radius (representative; the paper does not give the bore)."""


def _half_thickness(pair, gear: int, radius):
    """Half transverse tooth thickness y(r) [m]: involute above r_b, constant y(r_b) below (fillet zone)."""
    rb = float(pair.base_radii[gear - 1])
    return 0.5 * pair.transverse_thickness_at(np.maximum(radius, rb), gear)


def _load_point(pair, gear: int, rho):
    """Load point (x_c, y_c) in tooth coordinates and load angle α1 for contact at roll ``rho`` of ``gear``."""
    rb = float(pair.base_radii[gear - 1])
    rho = np.asarray(rho, dtype=float)
    r_c = np.sqrt(rb**2 + rho**2)
    alpha_c = np.arctan2(rho, rb)
    theta_c = _half_thickness(pair, gear, r_c) / r_c
    alpha1 = alpha_c - theta_c
    return r_c * np.cos(theta_c), r_c * np.sin(theta_c), alpha1, r_c


def tooth_compliance(pair, gear: int, rho, material: Material = STEEL, hub_ratio: float = DEFAULT_HUB_RATIO):
    """Compliance components of one tooth slice of ``gear`` loaded at roll distance ``rho`` from its own base-circle
    tangent point, per unit face width along the transverse line of action (models in the module docstring).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    gear : int
        1 or 2 [-].
    rho : array_like
        Roll distance of the load from the gear's base-circle tangent point [m].
    material : Material
        The gear's material [-].
    hub_ratio : float
        h_f = r_f / r_int, root radius over bore radius, of the foundation term [-].

    Returns
    -------
    dict of str to ndarray
        ``bending``, ``shear``, ``axial``, ``foundation`` and ``total`` compliance, shaped like ``rho`` [m²/N].
    """
    check_range("hub_ratio", hub_ratio, 1.0, 10.0, low_inclusive=False)
    e = material.youngs_modulus
    nu = material.poisson_ratio
    e_plane = e / (1.0 - nu**2)
    shear_modulus = e / (2.0 * (1.0 + nu))
    rb = float(pair.base_radii[gear - 1])
    rf = float(pair.root_radii[gear - 1])
    x_c, y_c, alpha1, r_c = _load_point(pair, gear, rho)
    cos1, sin1 = np.cos(alpha1), np.sin(alpha1)

    bending = np.zeros_like(x_c)
    shear = np.zeros_like(x_c)
    axial = np.zeros_like(x_c)
    # Two Gauss segments (the thickness law has a kink at the base circle): [r_f, min(r_b, r_c)], [max(r_f, r_b), r_c].
    for low, high in ((np.full_like(r_c, rf), np.minimum(rb, r_c)), (np.maximum(rf, rb) + 0 * r_c, r_c)):
        span = np.maximum(high - low, 0.0)
        r = low[..., None] + 0.5 * span[..., None] * (_GAUSS_T + 1.0)
        w = 0.5 * span[..., None] * _GAUSS_W
        y = _half_thickness(pair, gear, r)
        x = r * np.cos(y / r)
        area = 2.0 * y
        inertia = area**3 / 12.0
        arm = cos1[..., None] * (x_c[..., None] - x) - y_c[..., None] * sin1[..., None]
        bending = bending + np.sum(w * arm**2 / (e_plane * inertia), axis=-1)
        shear = shear + np.sum(w * 1.2 * cos1[..., None] ** 2 / (shear_modulus * area), axis=-1)
        axial = axial + np.sum(w * sin1[..., None] ** 2 / (e_plane * area), axis=-1)

    y_f = _half_thickness(pair, gear, rf)
    theta_f = float(y_f / rf)
    s_f = 2.0 * float(y_f)
    basis = np.array([1 / theta_f**2, hub_ratio**2, hub_ratio / theta_f, 1 / theta_f, hub_ratio, 1.0])
    l_star, m_star, p_star, q_star = _SAINSOT @ basis
    u_f = x_c - y_c * np.tan(alpha1) - rf
    ratio = u_f / s_f
    foundation = cos1**2 / e * (l_star * ratio**2 + m_star * ratio + p_star * (1.0 + q_star * np.tan(alpha1) ** 2))
    total = bending + shear + axial + foundation
    return {"bending": bending, "shear": shear, "axial": axial, "foundation": foundation, "total": total}


def root_bending_arm(pair, gear: int, rho):
    """Lever arm of a unit load at roll ``rho`` about the root section (at the root circle) of ``gear`` [m]:
    h = cos α1 (x_c − r_f) − y_c sin α1 (bending moment per unit load; used to scale root stress with load height).
    """
    rf = float(pair.root_radii[gear - 1])
    x_c, y_c, alpha1, _ = _load_point(pair, gear, rho)
    return np.cos(alpha1) * (x_c - rf) - y_c * np.sin(alpha1)


def centreline_depth(pair, gear: int, rho):
    """Distance from the contact point at roll ``rho`` of ``gear`` to its tooth centre line along the load line,
    y_c / cos α1 [m] (the depth d of Weber's contact approach)."""
    _, y_c, alpha1, _ = _load_point(pair, gear, rho)
    return y_c / np.cos(alpha1)


def weber_contact_compliance(load_per_length, r_eq, depth1, depth2, material1: Material = STEEL,
                             material2: Material = STEEL):
    """Secant Hertzian contact compliance δ/w of a line contact (Weber 1949; Johnson 1985 §5.6).

    δ = Σ_i (w (1 − ν_i²)/(π E_i)) (2 ln(2 d_i/a) − ν_i/(1 − ν_i)), a = √(8 w R/(π E')). The logarithm's argument
    is limited below by e (a ≤ 2d/e), where the half-plane assumption fails anyway.

    Parameters
    ----------
    load_per_length : array_like
        Load per unit contact length w, > 0 [N/m].
    r_eq : array_like
        Equivalent radius of curvature R [m].
    depth1 : array_like
        Depth d_1 of the reference point in gear 1 [m].
    depth2 : array_like
        Depth d_2 of the reference point in gear 2 [m].
    material1 : Material
        Material of gear 1 [-].
    material2 : Material
        Material of gear 2 [-].

    Returns
    -------
    ndarray
        δ/w [m²/N].
    """
    e_red = reduced_modulus(material1, material2)
    a = np.sqrt(8.0 * np.asarray(load_per_length, float) * r_eq / (math.pi * e_red))
    out = 0.0
    for mat, d in ((material1, depth1), (material2, depth2)):
        nu = mat.poisson_ratio
        log_term = np.log(np.maximum(2.0 * d / a, math.e))
        out = out + (1.0 - nu**2) / (math.pi * mat.youngs_modulus) * (2.0 * log_term - nu / (1.0 - nu))
    return out


def weber_log_terms(r_eq, depth1, depth2, material1: Material = STEEL, material2: Material = STEEL):
    """Load-independent parts of Weber's compliance for :func:`weber_secant`: (L1, L2, k1, k2, q1, q2).

    ln(2 d_i / a) = L_i − ½ ln w with L_i = ln(2 d_i) − ½ ln(8 R/(π E')); k_i = (1 − ν_i²)/(π E_i);
    q_i = ν_i/(1 − ν_i).
    """
    e_red = reduced_modulus(material1, material2)
    half_log = 0.5 * np.log(8.0 * np.asarray(r_eq, float) / (math.pi * e_red))
    terms = []
    for d in (depth1, depth2):
        terms.append(np.log(2.0 * np.asarray(d, float)) - half_log)
    ks = [(1.0 - m.poisson_ratio**2) / (math.pi * m.youngs_modulus) for m in (material1, material2)]
    qs = [m.poisson_ratio / (1.0 - m.poisson_ratio) for m in (material1, material2)]
    return terms[0], terms[1], ks[0], ks[1], qs[0], qs[1]


@njit(cache=True)
def weber_secant(w, l1, l2, k1, k2, q1, q2):
    """Weber's secant compliance [m²/N] from the precomputed :func:`weber_log_terms` (same value as
    :func:`weber_contact_compliance`, cheap enough for the inner iteration)."""
    out = np.empty(w.size)
    for i in range(w.size):
        half = 0.5 * np.log(w[i])
        out[i] = (k1 * (2.0 * max(l1[i] - half, 1.0) - q1) + k2 * (2.0 * max(l2[i] - half, 1.0) - q2))
    return out


def contact_compliance(material1: Material = STEEL, material2: Material = STEEL) -> float:
    """Load-independent Hertzian line-contact compliance per unit contact length, 4/(π E') (Yang & Lin 1987).

    Parameters
    ----------
    material1 : Material
        Material of gear 1 [-].
    material2 : Material
        Material of gear 2 [-].

    Returns
    -------
    float
        Compliance [m²/N].
    """
    return 4.0 / (math.pi * reduced_modulus(material1, material2))


def face_coupling(z, face_width: float, length: float) -> np.ndarray:
    """Slice-to-slice influence matrix G (S × S, dimensionless, symmetric positive definite).

    G_ij = ∫_{cell j} κ_N(z_i, z') dz' with κ the exponential kernel exp(−|d|/ℓ)/(2ℓ) and its images reflected at
    z = 0 and z = b (n image generations with exp(−2nb/ℓ) < 1e−17, i.e. the exact Neumann Green's function). A slice
    load F_j spread over its cell gives the deflection w_i = c Σ_j G_ij F_j / Δz for a slice compliance c per unit
    face width; Σ_j G_ij = 1.

    Parameters
    ----------
    z : array_like
        (S,) slice centres, uniformly spaced between 0 and b [m].
    face_width : float
        Face width b [m].
    length : float
        Coupling length ℓ [m].

    Returns
    -------
    ndarray
        G, shape (S, S) [-].
    """
    z = np.asarray(z, dtype=float)
    check_range("coupling_length", length, 0.0, 10.0, low_inclusive=False, unit="m")
    slices = z.size
    dz = face_width / slices
    lo = z - 0.5 * dz
    hi = z + 0.5 * dz

    def primitive(t):
        return 0.5 * np.sign(t) * (1.0 - np.exp(-np.abs(t) / length))

    g = np.zeros((slices, slices))
    zi = z[:, None]
    generations = int(math.ceil(20.0 * length / face_width)) + 1
    for n in range(-generations, generations + 1):
        shift = 2.0 * n * face_width
        # direct images z' + 2nb over [lo, hi] + shift
        g += primitive(hi[None, :] + shift - zi) - primitive(lo[None, :] + shift - zi)
        # mirrored images −z' + 2nb over [−hi, −lo] + shift
        g += primitive(-lo[None, :] + shift - zi) - primitive(-hi[None, :] + shift - zi)
    return 0.5 * (g + g.T)


def whole_depth(pair, gear: int = 1) -> float:
    """Tooth depth r_a − r_f of ``gear`` (the default face-coupling length).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    gear : int
        1 or 2 [-].

    Returns
    -------
    float
        r_a − r_f [m].
    """
    return float(pair.tip_radii[gear - 1] - pair.root_radii[gear - 1])
