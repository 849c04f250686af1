"""Flow-factor, shear-stress-factor and traction closures of the averaged (homogenised) Reynolds equation.

All closures describe the same averaged line-contact flux (per unit width, SI units)

    q̄ = −C_p/(12η) ∂p̄/∂x + u_m h_T + ((u1 − u2)/2) S_φ,        u_m = (u1 + u2)/2,

with the pressure-flow *conductance* C_p [m³] (Patir & Cheng: C_p = φ_x h̄³ with the nominal film h̄; Wilson &
Marsault: C_p = φ_x h_T³), the mean gap h_T [m] (lubricant volume per area) and the shear-flow length S_φ = σ φ_s
[m]. The macro solver's unknown is the nominal separation d (the table's d, which includes the macro elastic
deflection), so every quantity comes with its derivative with respect to d.

Closures
--------
* :func:`transverse_flow_factors` — the paper's 1-D model (transverse roughness, no side leakage), exact for a
  periodic cell in which the gap is steady in the frame of the roughness (derivation in
  docs/explanation/mixed-regime.md):

      C_p = 1/⟨g⁻³⟩,    h_T = ⟨g⟩,    S_φ = (2w − 1)(⟨g⟩ − ⟨g⁻²⟩/⟨g⁻³⟩),

  all moments of the floored gap max(g, h_b) from the dry-contact table. w is the weight of surface 1 in the
  speed c = w u1 + (1 − w) u2 at which the composite roughness is carried (``transport``): w = Rq1²/σ²
  ("variance", default: exact when either surface is smooth, symmetric, Patir & Cheng's variance-ratio
  superposition φ_s = V_r1 Φ_s − V_r2 Φ_s), w = ½ ("mean": roughness at the mean speed, no shear flow), 1 or 0,
  or any number in [0, 1].
* :func:`isotropic_flow_factors` — isotropic roughness (γ = 1, with side leakage): Patir & Cheng (1978, 1979)
  above a mean-gap ratio H_T = h_T/σ of 3.5, Wilson & Marsault (1998) percolation factors below 2.5, C¹ blend
  (cubic smoothstep) of C_p and of S_φ in between. The Patir–Cheng factors are functions of the nominal
  separation H of rigid Gaussian surfaces; they are evaluated at the H whose rigid Gaussian mean gap equals h_T.
* :func:`lubricated_shear_stress`, :func:`traction` — traction = Eyring shear over the lubricated fraction
  (cell average of τ0 asinh(η u_s/(τ0 g)) over the open gaps) + μ_d p_a.

The raw published formulas are public (``pc_*``, ``wm_*``), each returning (value, derivative).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import erf

from ..validation import InputError, check_range

# ---------------------------------------------------------------------------------------------------------------
# Published closures (γ = 1), each f(H) → (value, df/dH)
# ---------------------------------------------------------------------------------------------------------------
PC_PRESSURE = (0.90, 0.56)
"""Patir & Cheng (1978) φ_x = 1 − C e^{−rH} for γ = 1 (valid H > 0.5): (C, r)."""
PC_SHEAR_FLOW = (1.899, 0.98, 0.92, 0.05, 1.126)
"""Patir & Cheng (1979) Φ_s = A1 H^α1 exp(−α2 H + α3 H²) (H ≤ 5), A2 e^{−H/4} (H > 5), γ = 1: (A1, α1, α2, α3, A2)."""
PC_SHEAR_STRESS = (11.1, 2.31, 2.38, 0.11)
"""Patir & Cheng (1979) Φ_fs = A3 H^α4 exp(−α5 H + α6 H²) for H < 7 (0 beyond), γ = 1: (A3, α4, α5, α6)."""
PC_PRESSURE_STRESS = (1.40, 0.66)
"""Patir & Cheng (1979) φ_fp = 1 − D e^{−sH}, γ = 1: (D, s)."""
WM_HC = 3.0 * (1.0 - (0.47476 + 1.0) ** -0.25007)
"""Wilson & Marsault (1998) percolation threshold of the mean-gap ratio H_T for γ = 1 (0.2777)."""
WM_A2 = 0.051375 * math.log(9.0) ** 3 - 0.0071901 * math.log(9.0) ** 4
WM_A3 = 1.0019
WM_SHEAR_POLY = {(0, 0): 0.1403, (1, 0): 0.7448, (0, 1): 0.1098, (2, 0): -0.2744, (0, 2): -0.1042,
                 (3, 0): 0.03141, (0, 3): 0.02828, (4, 0): -0.0005932, (0, 4): -0.003105, (5, 0): -0.00007039,
                 (0, 5): 0.0001203, (1, 1): -0.203, (2, 1): 0.05916, (1, 2): 0.02689, (3, 1): -0.004833,
                 (1, 3): -0.001413, (4, 1): 0.0001006, (1, 4): 0.00002183, (2, 2): -0.005968, (3, 2): 0.0002656,
                 (2, 3): 0.0001916}
"""Wilson & Marsault (1998) shear flow factor Φ_s(H_T, γ) for γ ≥ 1: polynomial Σ p_ij H_T^i γ^j fitted to their
Fig. 4 (foam-extend flowFactorsWilsonMarsault.C; a fit of digitised data, medium confidence)."""
DEFAULT_BLEND = (2.5, 3.5)
"""Mean-gap ratios H_T between which the isotropic closure passes from Wilson–Marsault to Patir–Cheng."""


def pc_pressure_flow_factor(H):
    """Patir & Cheng (1978) pressure flow factor φ_x(H) = 1 − 0.90 e^{−0.56H} (γ = 1) and dφ_x/dH.

    Parameters
    ----------
    H : array_like
        Nominal separation over the composite RMS roughness, h/σ [-].

    Returns
    -------
    tuple of ndarray
        (φ_x, its derivative with respect to the argument) [-].
    """
    c, r = PC_PRESSURE
    e = c * np.exp(-r * np.asarray(H, dtype=float))
    return 1.0 - e, r * e


def pc_shear_flow_factor(H):
    """Patir & Cheng (1979) shear flow factor Φ_s(H) (γ = 1, one rough surface of variance ratio 1) and dΦ_s/dH.

    The published branches A1 H^α1 e^{−α2H+α3H²} (H ≤ 5) and A2 e^{−H/4} (H > 5) differ by 0.06 % at H = 5 and
    their slopes by 10 %; they are blended over 4.75 ≤ H ≤ 5.25 (cubic smoothstep) to make Φ_s C¹. H ≤ 0 gives 0.

    Parameters
    ----------
    H : array_like
        Nominal separation over the composite RMS roughness, h/σ [-].

    Returns
    -------
    tuple of ndarray
        (Φ_s, its derivative with respect to the argument) [-].
    """
    a1, al1, al2, al3, a2 = PC_SHEAR_FLOW
    H = np.asarray(H, dtype=float)
    hp = np.maximum(H, 1e-300)
    low = np.where(H > 0, a1 * hp**al1 * np.exp(-al2 * hp + al3 * hp * hp), 0.0)
    d_low = np.where(H > 0, low * (al1 / hp - al2 + 2 * al3 * hp), 0.0)
    high = a2 * np.exp(-0.25 * H)
    weight, d_weight = _smoothstep(H, 4.75, 5.25)
    return (1 - weight) * low + weight * high, (1 - weight) * d_low - weight * 0.25 * high + d_weight * (high - low)


def pc_couette_stress_factor(H):
    """Patir & Cheng (1979) shear stress factor φ_f(H) of Gaussian heights truncated at ±3σ.

    Density (35/96)(1 − x²/9)³: φ_f = E(h/h_local) with local gaps cut off at 0.01σ for H ≤ 3; 1 for H ≥ 30. The
    derivative is a centred difference of the closed form.

    Parameters
    ----------
    H : array_like
        Nominal separation over the composite RMS roughness, h/σ [-].

    Returns
    -------
    tuple of ndarray
        (φ_f, its derivative with respect to the argument) [-].
    """
    def closed(Hv):
        z = np.asarray(Hv, dtype=float) / 3.0
        zc = np.minimum(z, 1.0)
        poly = -55 + zc * (132 + zc * (345 + zc * (-160 + zc * (-405 + zc * (60 + 147 * zc)))))
        low = 35 / 32 * zc * ((1 - zc * zc) ** 3 * np.log(300 * (1 + zc)) + poly / 60.0)
        zh = np.maximum(z, 1.0 + 1e-12)
        high = 35 / 32 * zh * ((1 - zh * zh) ** 3 * np.log((zh + 1) / (zh - 1)) + zh / 15 * (66 + zh * zh *
                                                                                                (30 * zh * zh - 80)))
        out = np.where(z <= 1.0, low, high)
        return np.where(z >= 10.0, 1.0, out)
    H = np.asarray(H, dtype=float)
    step = 1e-5 * np.maximum(1.0, np.abs(H))
    return closed(H), (closed(H + step) - closed(H - step)) / (2 * step)


def pc_shear_stress_factor(H):
    """Patir & Cheng (1979) Φ_fs(H) = 11.1 H^2.31 exp(−2.38H + 0.11H²) for 0 < H < 7, 0 beyond (γ = 1).

    The published form drops from 0.0127 to 0 at H = 7.

    Parameters
    ----------
    H : array_like
        Nominal separation over the composite RMS roughness, h/σ [-].

    Returns
    -------
    tuple of ndarray
        (Φ_fs, its derivative with respect to the argument) [-].
    """
    a3, a4, a5, a6 = PC_SHEAR_STRESS
    H = np.asarray(H, dtype=float)
    inside = (H > 0) & (H < 7.0)
    hp = np.where(inside, H, 1.0)  # evaluated only where the fit holds (beyond, exp(0.11H²) overflows)
    v = a3 * hp**a4 * np.exp(-a5 * hp + a6 * hp * hp)
    return np.where(inside, v, 0.0), np.where(inside, v * (a4 / hp - a5 + 2 * a6 * hp), 0.0)


def pc_pressure_stress_factor(H):
    """Patir & Cheng (1979) φ_fp(H) = 1 − 1.40 e^{−0.66H} (γ = 1) and its derivative.

    Parameters
    ----------
    H : array_like
        Nominal separation over the composite RMS roughness, h/σ [-].

    Returns
    -------
    tuple of ndarray
        (φ_fp, its derivative with respect to the argument) [-].
    """
    dd, s = PC_PRESSURE_STRESS
    e = dd * np.exp(-s * np.asarray(H, dtype=float))
    return 1.0 - e, s * e


def wm_pressure_conductance(H_T):
    """Wilson & Marsault (1998) normalised pressure-flow conductance φ_x H_T³ and its derivative.

    φ_x H_T³ = a2 (H_T − H_c)² + a3 (H_T − H_c)³ for H_T ≥ H_c, else 0 (γ = 1: H_c = 0.2777, a2 = 0.3774,
    a3 = 1.0019).

    Parameters
    ----------
    H_T : array_like
        Mean gap over the composite RMS roughness, h_T/σ [-].

    Returns
    -------
    tuple of ndarray
        (φ_x H_T³, its derivative with respect to the argument) [-].
    """
    x = np.maximum(np.asarray(H_T, dtype=float) - WM_HC, 0.0)
    return WM_A2 * x**2 + WM_A3 * x**3, 2 * WM_A2 * x + 3 * WM_A3 * x**2


def wm_shear_flow_factor(H_T, gamma: float = 1.0):
    """Wilson & Marsault (1998) shear flow factor Φ_s(H_T) for γ ≥ 1 and its derivative.

    A polynomial fit of their Fig. 4, continued by Patir & Cheng's A2 e^{−H_T/4} above H_T = 5 with A2 matching the
    polynomial there; without the cap Φ_s ≤ H_T (applied by the caller).

    Parameters
    ----------
    H_T : array_like
        Mean gap over the composite RMS roughness, h_T/σ [-].
    gamma : float
        Peklenik surface pattern parameter γ, ≥ 1 [-].

    Returns
    -------
    tuple of ndarray
        (Φ_s, its derivative with respect to the argument) [-].
    """
    if gamma < 1.0:
        raise InputError("gamma", gamma, ">= 1 (the fit's γ ≥ 1 branch)")
    H = np.asarray(H_T, dtype=float)

    def poly(h):
        v = np.zeros_like(h)
        dv = np.zeros_like(h)
        for (i, j), c in WM_SHEAR_POLY.items():
            v = v + c * h**i * gamma**j
            if i:
                dv = dv + c * i * h ** (i - 1) * gamma**j
        return v, dv

    v, dv = poly(np.minimum(H, 5.0))
    a2 = float(poly(np.array(5.0))[0]) * math.exp(1.25)
    high = a2 * np.exp(-0.25 * H)
    return np.where(H > 5.0, high, v), np.where(H > 5.0, -0.25 * high, dv)


def gaussian_mean_gap_ratio(H):
    """Mean gap of rigid Gaussian surfaces at nominal separation ratio H (Patir & Cheng 1978).

    H_T = (H/2)(1 + erf(H/√2)) + e^{−H²/2}/√(2π), and dH_T/dH = (1 + erf(H/√2))/2.

    Parameters
    ----------
    H : array_like
        Nominal separation over the composite RMS roughness, h/σ [-].

    Returns
    -------
    tuple of ndarray
        (H_T, its derivative with respect to the argument) [-].
    """
    H = np.asarray(H, dtype=float)
    return 0.5 * H * (1 + erf(H / math.sqrt(2))) + np.exp(-0.5 * H * H) / math.sqrt(2 * math.pi), \
        0.5 * (1 + erf(H / math.sqrt(2)))


def nominal_ratio_from_mean_gap(H_T):
    """Inverse of :func:`gaussian_mean_gap_ratio` (Newton, H_T > 0) and dH/dH_T.

    Parameters
    ----------
    H_T : array_like
        Mean gap over the composite RMS roughness, h_T/σ [-].

    Returns
    -------
    tuple of ndarray
        (H, its derivative with respect to the argument) [-].
    """
    H_T = np.asarray(H_T, dtype=float)
    if np.any(H_T <= 0):
        raise InputError("H_T", "array" if H_T.ndim else float(H_T), "mean-gap ratios > 0")
    H = np.where(H_T > 1.5, H_T, H_T - 1.0)
    for _ in range(60):
        f, fp = gaussian_mean_gap_ratio(H)
        step = (f - H_T) / fp
        H = H - np.clip(step, -2.0, 2.0)
        if np.all(np.abs(step) < 1e-13 * np.maximum(1.0, np.abs(H))):
            break
    return H, 1.0 / gaussian_mean_gap_ratio(H)[1]


def _smoothstep(x, lo, hi):
    """C¹ weight 0 → 1 between lo and hi (3t² − 2t³) and its derivative."""
    t = np.clip((x - lo) / (hi - lo), 0.0, 1.0)
    return t * t * (3 - 2 * t), np.where((t > 0) & (t < 1), 6 * t * (1 - t) / (hi - lo), 0.0)


def _smooth_min(a, da, b, db, width):
    """C¹ minimum of a and b (quadratic smoothing over |a − b| < width) with its derivative (chain rule)."""
    h = np.clip(0.5 + 0.5 * (b - a) / width, 0.0, 1.0)
    value = b + (a - b) * h - width * h * (1 - h)
    dh = np.where((h > 0) & (h < 1), 0.5 / width, 0.0) * (db - da)
    slope = db + (da - db) * h + (a - b) * dh - width * (1 - 2 * h) * dh
    return value, slope


# ---------------------------------------------------------------------------------------------------------------
# Flow factors of the homogenised model
# ---------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class FlowFactors:
    """Averaged-Reynolds coefficients at separations d (arrays of d's shape), with derivatives with respect to d.

    The flux is q̄ = −C_p/(12η) ∂p̄/∂x + u_m h_T + ((u1 − u2)/2) S_φ. Shear-stress factors are referred to h_T (mean
    shear stress on surface 1 and 2, Newtonian): τ̄₁ = (η(u2 − u1)/h_T)(φ_f − φ_fs) − φ_fp (h_T/2) ∂p̄/∂x and
    τ̄₂ = −(η(u2 − u1)/h_T)(φ_f + φ_fs) − φ_fp (h_T/2) ∂p̄/∂x.

    Parameters
    ----------
    mean_gap : ndarray
        Mean gap h_T, the lubricant volume per area [m].
    d_mean_gap : ndarray
        dh_T/dd [-].
    conductance : ndarray
        Pressure-flow conductance C_p [m³].
    d_conductance : ndarray
        dC_p/dd [m²].
    shear_flow : ndarray
        Shear flow S_φ = σφ_s, transport weight included [m].
    d_shear_flow : ndarray
        dS_φ/dd [-].
    phi_f : ndarray
        Couette stress factor φ_f [-].
    phi_fs : ndarray
        Shear stress factor φ_fs [-].
    phi_fp : ndarray
        Pressure stress factor φ_fp [-].
    lubricated_fraction : ndarray
        1 − contact fraction [-].
    sigma : float
        Composite RMS roughness σ [m].
    model : str
        Name of the closure [-].
    """

    mean_gap: np.ndarray
    d_mean_gap: np.ndarray
    conductance: np.ndarray
    d_conductance: np.ndarray
    shear_flow: np.ndarray
    d_shear_flow: np.ndarray
    phi_f: np.ndarray
    phi_fs: np.ndarray
    phi_fp: np.ndarray
    lubricated_fraction: np.ndarray
    sigma: float
    model: str

    @property
    def phi_x(self):
        """Pressure flow factor referred to the mean gap, C_p/h_T³ (Patir & Cheng's nominal φ_x is C_p/h̄³)."""
        return self.conductance / self.mean_gap**3

    @property
    def phi_s(self):
        """Shear flow factor φ_s = S_φ/σ (transport weight included)."""
        return self.shear_flow / self.sigma

    def flux(self, dpdx, eta, u1: float, u2: float):
        """Averaged flux q̄ for a mean pressure gradient.

        Parameters
        ----------
        dpdx : array_like
            Mean pressure gradient [Pa/m].
        eta : array_like
            Viscosity [Pa s].
        u1 : float
            Velocity of surface 1 [m/s].
        u2 : float
            Velocity of surface 2 [m/s].

        Returns
        -------
        ndarray
            q̄ [m²/s].
        """
        return -self.conductance * np.asarray(dpdx) / (12.0 * np.asarray(eta)) + 0.5 * (u1 + u2) * self.mean_gap \
            + 0.5 * (u1 - u2) * self.shear_flow

    def shear_stresses(self, dpdx, eta, u1: float, u2: float):
        """Newtonian mean shear stresses on surfaces 1 and 2 over the whole cell.

        Parameters
        ----------
        dpdx : array_like
            Mean pressure gradient [Pa/m].
        eta : array_like
            Viscosity [Pa s].
        u1 : float
            Velocity of surface 1 [m/s].
        u2 : float
            Velocity of surface 2 [m/s].

        Returns
        -------
        tuple of ndarray
            (τ̄₁, τ̄₂) [Pa].
        """
        couette = np.asarray(eta) * (u2 - u1) / self.mean_gap
        poiseuille = self.phi_fp * 0.5 * self.mean_gap * np.asarray(dpdx)
        return couette * (self.phi_f - self.phi_fs) - poiseuille, -couette * (self.phi_f + self.phi_fs) - poiseuille


def transport_weight(transport, rq1: float, rq2: float) -> float:
    """Weight w of surface 1 in the roughness transport speed c = w u1 + (1 − w) u2 (see module doc)."""
    if isinstance(transport, str):
        if transport == "variance":
            return rq1**2 / (rq1**2 + rq2**2)
        if transport == "mean":
            return 0.5
        if transport == "surface1":
            return 1.0
        if transport == "surface2":
            return 0.0
        raise InputError("transport", transport, "'variance', 'mean', 'surface1', 'surface2' or a number in [0, 1]")
    return check_range("transport", transport, 0.0, 1.0)


def transverse_flow_factors(table, d, h_b: float = 1e-9, transport="variance") -> FlowFactors:
    """The exact 1-D closure (transverse roughness, no side leakage) from a dry-contact table.

    C_p = 1/M₋₃, h_T = M₁, S_φ = (2w − 1)(M₁ − M₋₂/M₋₃) with M_k = ⟨max(g, h_b)^k⟩; shear-stress factors
    φ_f = h_T ⟨g⁻¹⟩_lub (open gaps only: contact spots carry μ_d p instead), φ_fp = M₋₂/(h_T M₋₃),
    φ_fs = 3(2w − 1) h_T (M₋₁ − M₋₂²/M₋₃).

    Parameters
    ----------
    table : DryContactTable
        Dry-contact table of the roughness pair [-].
    d : array_like
        Separations [m].
    h_b : float
        Film-breakdown floor: the cell's gap is max(g, h_b), needed because any contact blocks a 1-D cell
        (⟨g⁻³⟩ = ∞ for h_b = 0) [m].
    transport : str
        Roughness transport weight (module docstring): ``variance``, ``mean``, ``surface1`` or ``surface2`` [-].

    Returns
    -------
    FlowFactors
        The coefficients at ``d``.
    """
    check_range("h_b", h_b, 0.0, 1e-3, low_inclusive=False, unit="m")
    w = transport_weight(transport, table.meta["rq1_m"], table.meta["rq2_m"])
    m1, dm1 = table.gap_moment(d, 1, h_b), table.d_gap_moment(d, 1, h_b)
    m1i, dm1i = table.gap_moment(d, -1, h_b), table.d_gap_moment(d, -1, h_b)
    m2, dm2 = table.gap_moment(d, -2, h_b), table.d_gap_moment(d, -2, h_b)
    m3, dm3 = table.gap_moment(d, -3, h_b), table.d_gap_moment(d, -3, h_b)
    m1, dm1, m1i, dm1i, m2, dm2, m3, dm3 = (np.asarray(v, dtype=float) for v in (m1, dm1, m1i, dm1i, m2, dm2, m3,
                                                                                    dm3))
    conductance = 1.0 / m3
    d_conductance = -dm3 / m3**2
    ratio = m2 / m3
    d_ratio = (dm2 * m3 - m2 * dm3) / m3**2
    carried = m1 - ratio
    cf = np.asarray(table.contact_fraction(d), dtype=float)
    lub_inverse = np.maximum(m1i - cf / h_b, 0.0)
    return FlowFactors(mean_gap=m1, d_mean_gap=dm1, conductance=conductance, d_conductance=d_conductance,
                       shear_flow=(2 * w - 1) * carried, d_shear_flow=(2 * w - 1) * (dm1 - d_ratio),
                       phi_f=m1 * lub_inverse, phi_fs=3 * (2 * w - 1) * m1 * np.maximum(m1i - m2 * ratio, 0.0),
                       phi_fp=ratio / m1, lubricated_fraction=1.0 - cf, sigma=table.sigma, model="transverse-1d")


def isotropic_flow_factors(table, d, transport="variance", blend=DEFAULT_BLEND) -> FlowFactors:
    """Isotropic (γ = 1) closure with side leakage at separations ``d``.

    Patir & Cheng above H_T = blend[1], Wilson & Marsault below blend[0], cubic-smoothstep blend of C_p and S_φ in
    between (module docstring). H_T = h_T/σ with h_T = ⟨g⟩ from the dry-contact table (elastic–plastic asperities);
    the Patir–Cheng factors are taken at the nominal H of rigid Gaussian surfaces with the same mean gap. Below the
    percolation threshold H_T < H_c = 0.278 the pressure flow vanishes (C_p = 0).

    Parameters
    ----------
    table : DryContactTable
        Dry-contact table of the roughness pair [-].
    d : array_like
        Separations [m].
    transport : str
        Roughness transport weight (module docstring) [-].
    blend : tuple of float
        H_T range of the blend between the two closures [-].

    Returns
    -------
    FlowFactors
        The coefficients at ``d``.
    """
    lo, hi = (float(v) for v in blend)
    if not 0.5 <= lo < hi <= 10.0:
        raise InputError("blend", blend, "two mean-gap ratios 0.5 <= lo < hi <= 10")
    w = transport_weight(transport, table.meta["rq1_m"], table.meta["rq2_m"])
    sigma = table.sigma
    h_t = np.asarray(table.mean_gap(d), dtype=float)
    dh_t = np.asarray(table.d_mean_gap(d), dtype=float)
    h_t = np.maximum(h_t, 1e-12 * sigma)
    ratio_t = h_t / sigma
    # Wilson & Marsault: C_p = σ³ ψ(H_T); Φ_s capped at H_T (all lubricant carried by the rough surface)
    psi, dpsi = wm_pressure_conductance(ratio_t)
    wm_s, dwm_s = wm_shear_flow_factor(ratio_t)
    wm_s, dwm_s = _smooth_min(wm_s, dwm_s, ratio_t, np.ones_like(ratio_t), 0.05)
    # Patir & Cheng at the equivalent nominal H (only where it contributes)
    H, dH = nominal_ratio_from_mean_gap(np.maximum(ratio_t, lo))
    phx, dphx = pc_pressure_flow_factor(H)
    pc_c = phx * H**3
    dpc_c = (dphx * H**3 + 3 * phx * H**2) * dH
    pcs, dpcs = pc_shear_flow_factor(H)
    dpcs = dpcs * dH
    weight, dweight = _smoothstep(ratio_t, lo, hi)
    cond = (1 - weight) * psi + weight * pc_c
    dcond = (1 - weight) * dpsi + weight * dpc_c + dweight * (pc_c - psi)
    shear = (1 - weight) * wm_s + weight * pcs
    dshear = (1 - weight) * dwm_s + weight * dpcs + dweight * (pcs - wm_s)
    h_stress = np.maximum(nominal_ratio_from_mean_gap(ratio_t)[0], 0.5)  # PC stress factors: valid H ≥ 0.5
    phif, _ = pc_couette_stress_factor(h_stress)
    phifs, _ = pc_shear_stress_factor(h_stress)
    phifp, _ = pc_pressure_stress_factor(h_stress)
    scale = h_stress / ratio_t  # PC factors are referred to the nominal h; FlowFactors refers them to h_T
    cf = np.asarray(table.contact_fraction(d), dtype=float)
    return FlowFactors(mean_gap=h_t, d_mean_gap=dh_t, conductance=sigma**3 * cond,
                       d_conductance=sigma**2 * dcond * dh_t, shear_flow=(2 * w - 1) * sigma * shear,
                       d_shear_flow=(2 * w - 1) * dshear * dh_t, phi_f=phif / scale,
                       phi_fs=(2 * w - 1) * phifs / scale, phi_fp=phifp * scale,
                       lubricated_fraction=1.0 - cf, sigma=sigma, model="isotropic-pc-wm")


# ---------------------------------------------------------------------------------------------------------------
# Traction
# ---------------------------------------------------------------------------------------------------------------
def lubricated_shear_stress(table, d, eta, u_s: float, tau0: float, h_b: float = 1e-9):
    """Mean Couette (Eyring) shear stress over the nominal area carried by the lubricant.

    The cell average of τ0 asinh(η u_s/(τ0 g)) over the open gaps (g > 0, floored at h_b), i.e. already weighted by
    the lubricated fraction (:meth:`DryContactTable.open_gap_expectation`).

    Parameters
    ----------
    table : DryContactTable
        Dry-contact table [-].
    d : array_like
        Separations [m].
    eta : float or array_like
        Viscosity, scalar or one per d [Pa s].
    u_s : float
        Sliding velocity u1 − u2 [m/s].
    tau0 : float
        Eyring stress; ``math.inf``: Newtonian η u_s/g [Pa].
    h_b : float
        Gap floor [m].

    Returns
    -------
    ndarray
        Mean shear stress [Pa].
    """
    d_arr = np.asarray(d, dtype=float)
    eta_rows = np.broadcast_to(np.asarray(eta, dtype=float), d_arr.shape).reshape(-1)[:, None]
    out = np.asarray(table.open_gap_expectation(d_arr.reshape(-1),
                                                lambda g: eyring_shear(g, eta_rows, u_s, tau0), h_b))
    return out.reshape(d_arr.shape) if d_arr.ndim else float(out[0])


def eyring_shear(g, eta, u_s: float, tau0: float):
    """Couette shear stress at gap g: τ0 asinh(η u_s/(τ0 g)) (Eyring), or η u_s/g for τ0 = ∞.

    Parameters
    ----------
    g : array_like
        Gap [m].
    eta : array_like
        Viscosity [Pa s].
    u_s : float
        Sliding velocity [m/s].
    tau0 : float
        Eyring stress [Pa].

    Returns
    -------
    ndarray
        τ [Pa].
    """
    if math.isinf(tau0):
        return np.asarray(eta) * u_s / g
    return tau0 * np.arcsinh(np.asarray(eta) * u_s / (tau0 * g))


def traction(table, d, eta, u_s: float, tau0: float, mu_dry: float, h_b: float = 1e-9):
    """Mean surface traction of the homogenised model: Eyring shear over the lubricated fraction plus asperity friction.

    (:func:`lubricated_shear_stress`) + sign(u_s) μ_d p_a(d): the asperity friction opposes sliding; the rolling
    (Poiseuille) part is the macro solver's ±(h/2)∂p/∂x.

    Parameters
    ----------
    table : DryContactTable
        Dry-contact table [-].
    d : array_like
        Separations [m].
    eta : float or array_like
        Viscosity [Pa s].
    u_s : float
        Sliding velocity u1 − u2 [m/s].
    tau0 : float
        Eyring stress [Pa].
    mu_dry : float
        Boundary friction coefficient μ_d [-].
    h_b : float
        Gap floor [m].

    Returns
    -------
    ndarray
        Mean traction [Pa].
    """
    check_range("mu_dry", mu_dry, 0.0, 2.0)
    shear = lubricated_shear_stress(table, d, eta, u_s, tau0, h_b)
    return shear + math.copysign(1.0, u_s) * (u_s != 0) * mu_dry * np.asarray(table.asperity_pressure(d))
