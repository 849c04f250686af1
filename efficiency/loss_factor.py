"""Closed-form and reference gear loss factors H_V = P_VZP / (μ_mz P_in) for a constant friction coefficient, SI.

- Ohlendorf (1958), as given in ISO/TR 14179-2:2001 and by Fernandes, Marques, Martins & Seabra, Mech. Sci. 6
  (2015) 81–88: rigid teeth, a single pair carries all the load, two pairs share it equally (spur gears),

      H_V = π (u + 1)/(z1 u cos β_b) · (1 − ε_α + ε1² + ε2²),

  ε1 = (T1E − T1C)/p_bt and ε2 = (T1C − T1A)/p_bt the recess and approach contact ratios (gear 1 driving).
- Wimmer (2006, TU München thesis; Fernandes et al. 2015): rigid teeth with a uniform load per unit length along
  all contact lines in contact at each instant (F_bn / L(t)); the cycle mean of ∫ (F_bn/L(t)) |v_g| dl over the
  lines, divided by P_in. :func:`wimmer_loss_factor` integrates it exactly along each line (the sliding speed
  is linear in the roll s, so ∫|s − s_C| ds is closed-form) and by the midpoint rule over the cycle. For spur gears
  it equals Ohlendorf's value.
"""

from __future__ import annotations

import math

import numpy as np


def ohlendorf_loss_factor(pair) -> float:
    """Ohlendorf's gear loss factor H_V of a pair (formula in the module docstring).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].

    Returns
    -------
    float
        H_V [-].
    """
    z1, z2 = float(pair.z1), float(pair.z2)
    u = z2 / z1
    p_bt = float(pair.transverse_base_pitch)
    e1 = (float(pair.contact_end) - float(pair.pitch_point)) / p_bt
    e2 = (float(pair.pitch_point) - float(pair.contact_start)) / p_bt
    return math.pi * (u + 1.0) / (z1 * u * math.cos(float(pair.base_helix_angle))) * (
        1.0 - float(pair.contact_ratio) + e1**2 + e2**2)


def wimmer_loss_factor(pair, positions: int = 4000) -> float:
    """Wimmer's H_VL for rigid teeth and uniform load per unit contact-line length (module docstring).

    P_in = T ω1 = F_bn cos β_b r_b1 ω1 and v_g = (ω1 + ω2)|s − s_C| with ω2 = ω1 r_b1/r_b2, so
    H_VL = (1 + r_b1/r_b2)/(r_b1 cos β_b) · mean_φ (Σ_lines ∫|s − s_C| dz / Σ_lines Δz).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    positions : int
        Midpoint samples of the cycle (4000: converged to ≈1e-6) [-].

    Returns
    -------
    float
        H_VL [-].
    """
    start, end = float(pair.contact_start), float(pair.contact_end)
    s_c = float(pair.pitch_point)
    p_bt = float(pair.transverse_base_pitch)
    rb1, rb2 = (float(r) for r in pair.base_radii)
    width = float(pair.face_width)
    tan_b = math.tan(float(pair.base_helix_angle))
    span = width * tan_b  # roll range of one contact line over the face
    k_lines = int(math.ceil(float(pair.total_contact_ratio))) + 1
    phase = (np.arange(positions) + 0.5) * p_bt / positions
    s0 = start - span + phase[:, None] + p_bt * np.arange(k_lines)[None, :]  # roll at z = 0 of each line

    def primitive(s):  # ∫ |s − s_C| ds
        d = s - s_c
        return 0.5 * d * np.abs(d)

    if span > 0.0:
        lo = np.clip(s0, start, end)
        hi = np.clip(s0 + span, start, end)
        length_z = (hi - lo) / tan_b
        moment = (primitive(hi) - primitive(lo)) / tan_b
    else:
        inside = (s0 >= start) & (s0 <= end)
        length_z = np.where(inside, width, 0.0)
        moment = np.where(inside, width * np.abs(s0 - s_c), 0.0)
    mean_distance = moment.sum(axis=1) / length_z.sum(axis=1)
    return float((1.0 + rb1 / rb2) / (rb1 * math.cos(float(pair.base_helix_angle))) * mean_distance.mean())
