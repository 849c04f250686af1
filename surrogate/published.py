"""Published gear friction formulas as alternative friction models (SI in, μ out; units converted inside).

Every function takes the contact inputs of the surrogate (SI arrays) plus the oil's dynamic viscosity η0 [Pa·s]
at the inlet temperature, and converts to the units in which the formula was published. The mapping from a
line contact to each formula's inputs is documented per function; tests pin the units (tests/surrogate).

Roughness: the formulas were regressed on arithmetic-mean roughness Ra (Benedict & Kelley, ISO/TR 14179-2) or an
unspecified "surface roughness" (Xu et al.); our data carry RMS roughness Rq. For a Gaussian height distribution
Ra = √(2/π) Rq ≈ 0.798 Rq (:data:`RA_PER_RQ`), used where the formula asks for Ra.
"""

from __future__ import annotations

import math

import numpy as np

from ehl_dataset.validation import InputError

RA_PER_RQ = math.sqrt(2.0 / math.pi)
"""Ra/Rq of a Gaussian surface."""

XU_2007_COEFFICIENTS = (-8.916465, 1.03303, 1.036077, -0.354068, 2.812084, -0.100601, 0.752755, -0.390958, 0.620305)
"""b1..b9 of Xu, Kahraman, Anderson & Maddock, J. Mech. Des. 129 (2007) 58–68 (75W90 gear oil)."""

BK_CONSTANT_IMPERIAL = 3.17e8
"""Benedict & Kelley (1961) log-argument constant for W [lb/in], η0 [cP], V_s, V_t [in/s]."""
LBF_PER_IN_PER_N_PER_M = 1.0 / 175.126835
"""1 N/m in lbf/in."""
IN_PER_M = 1.0 / 0.0254
BK_CONSTANT_SI = BK_CONSTANT_IMPERIAL * LBF_PER_IN_PER_N_PER_M / IN_PER_M**3
"""The same constant for W' [N/m], η0 [cP], V_s, V_t [m/s]: 3.17e8 · 0.0057101 / 39.37³ = 29.66."""


def _arrays(**values):
    out = {}
    for name, value in values.items():
        arr = np.asarray(value, dtype=float)
        if not np.all(np.isfinite(arr)):
            raise InputError(name, value, "finite numbers")
        out[name] = arr
    return out


def xu_2007_mu(p_h, r_eq, u_r, sr, eta0, rq1, rq2, coefficients=XU_2007_COEFFICIENTS):
    """Xu et al. (2007) EHL-regressed friction coefficient of a 75W90 gear oil.

    μ = e^f · P_h^b2 · |SR|^b3 · V_e^b6 · ν0^b7 · R^b8,  f = b1 + b4 |SR| P_h log10 ν0 + b5 e^(−|SR| P_h log10 ν0)
    + b9 e^S, in the published units: P_h [GPa], V_e [m/s], ν0 absolute (dynamic) viscosity at the inlet [mPa·s],
    R effective radius [m], S roughness [µm].

    Mapping: P_h = p_h, R = r_eq, V_e = u_r = (u1 + u2)/2 (the entraining velocity as used in public
    implementations; reading V_e as u1 + u2 would lower μ by 2^−0.1, i.e. 6.7 %), S = (Rq1 + Rq2)/2.
    At SR = 0 the formula gives μ = 0 (|SR|^1.04).

    Parameters
    ----------
    p_h : array_like
        Hertz pressure [Pa].
    r_eq : array_like
        Equivalent radius of curvature [m].
    u_r : array_like
        Rolling (entraining) velocity [m/s].
    sr : array_like
        Slide-to-roll ratio [-].
    eta0 : array_like
        Dynamic viscosity at the inlet temperature and ambient pressure [Pa s].
    rq1 : array_like
        RMS roughness of surface 1 [m].
    rq2 : array_like
        RMS roughness of surface 2 [m].
    coefficients : sequence of float
        b1 … b9 of the published regression [-].

    Returns
    -------
    ndarray
        μ [-].
    """
    a = _arrays(p_h=p_h, r_eq=r_eq, u_r=u_r, sr=sr, eta0=eta0, rq1=rq1, rq2=rq2)
    b1, b2, b3, b4, b5, b6, b7, b8, b9 = coefficients
    p_gpa = a["p_h"] * 1e-9
    nu_mpas = a["eta0"] * 1e3
    s_um = 0.5 * (a["rq1"] + a["rq2"]) * 1e6
    sr_abs = np.abs(a["sr"])
    group = sr_abs * p_gpa * np.log10(nu_mpas)
    f = b1 + b4 * group + b5 * np.exp(-group) + b9 * np.exp(s_um)
    return np.exp(f) * p_gpa**b2 * sr_abs**b3 * a["u_r"] ** b6 * nu_mpas**b7 * a["r_eq"] ** b8


def benedict_kelley_mu(w_prime, u_r, sr, eta0, rq1, rq2, mu_cap: float = 0.1):
    """Benedict & Kelley (1961) gear friction coefficient, capped near the pitch point.

    μ = 0.0127 C_R log10[3.17e8 W/(η0 V_s V_t²)] with W [lb/in], η0 [cP], V_s = |u1 − u2| and V_t = u1 + u2 [in/s]
    (Trans. ASLE 4 (1961) 59–70, as used by Anderson & Loewenthal, NASA TM-81426), i.e. in SI
    μ = 0.0127 C_R log10[29.66 W'/(η0[cP] V_s V_t²)] with W' [N/m], V [m/s] (:data:`BK_CONSTANT_SI`).
    Roughness factor C_R = 50/(50 − S), S = (Ra1 + Ra2)/2 in µin (Ra from Rq by :data:`RA_PER_RQ`); S ≥ 50 µin
    (1.27 µm) is outside the formula and raises.

    The log diverges as V_s → 0 at the pitch point; the result is clipped to [0, ``mu_cap``] (default 0.1, a
    boundary friction level), so μ is finite at SR = 0.

    Parameters
    ----------
    w_prime : array_like
        Normal load per unit contact length W' [N/m].
    u_r : array_like
        Rolling velocity [m/s].
    sr : array_like
        Slide-to-roll ratio [-].
    eta0 : array_like
        Dynamic viscosity at the inlet temperature [Pa s].
    rq1 : array_like
        RMS roughness of surface 1 [m].
    rq2 : array_like
        RMS roughness of surface 2 [m].
    mu_cap : float
        Upper clip of μ near the pitch point [-].

    Returns
    -------
    ndarray
        μ, between 0 and ``mu_cap`` [-].
    """
    a = _arrays(w_prime=w_prime, u_r=u_r, sr=sr, eta0=eta0, rq1=rq1, rq2=rq2)
    s_uin = 0.5 * (a["rq1"] + a["rq2"]) * RA_PER_RQ * 1e6 / 0.0254
    if np.any(s_uin >= 50.0):
        raise InputError("roughness", float(np.max(s_uin)), "mean Ra below 50 µin (1.27 µm) for Benedict & Kelley")
    c_r = 50.0 / (50.0 - s_uin)
    v_s = np.abs(a["sr"]) * a["u_r"]
    v_t = 2.0 * a["u_r"]
    with np.errstate(divide="ignore"):
        argument = BK_CONSTANT_SI * a["w_prime"] / (a["eta0"] * 1e3 * v_s * v_t**2)
        mu = 0.0127 * c_r * np.log10(argument)
    return np.clip(np.where(v_s > 0, mu, mu_cap), 0.0, mu_cap)


def iso_14179_2_mu(w_prime, r_eq, u_r, eta0, rq1, rq2, x_l: float = 1.0):
    """ISO/TR 14179-2 (2001) mean tooth friction coefficient μ_mz (Schlenk's formula).

    μ_mz = 0.048 (F_bt/b / (v_Σc ρ_redC))^0.2 η_oil^−0.05 Ra^0.25 X_L with F_bt/b [N/mm], v_Σc sum velocity [m/s],
    ρ_redC equivalent radius [mm], η_oil [mPa·s] at oil temperature, Ra = (Ra1 + Ra2)/2 [µm], X_L lubricant factor
    (1.0 mineral oil).

    Mapping to one line contact: F_bt/b → W' (normal load per length, N/mm; the standard uses the transverse
    tangential load at the pitch point, cos α_t cos β_b smaller, i.e. ≈1–2 % in μ), v_Σc = 2 u_r, ρ_redC = r_eq,
    Ra = √(2/π) Rq. The standard intends a mesh-averaged value; here it is applied point by point. Independent of
    SR, so finite at the pitch point.

    Provenance of the form and units: checked against an independent public implementation of Schlenk's formula
    (Fernandes' GEARpie, ``CLASSES/CONTACT.py``), which also uses the normal load per unit contact length [N/mm],
    the sum velocity [m/s], the equivalent radius at the pitch point [mm], η [mPa·s] and Ra [µm].

    Parameters
    ----------
    w_prime : array_like
        Normal load per unit contact length W' [N/m].
    r_eq : array_like
        Equivalent radius of curvature [m].
    u_r : array_like
        Rolling velocity [m/s].
    eta0 : array_like
        Dynamic viscosity at the oil temperature [Pa s].
    rq1 : array_like
        RMS roughness of surface 1 [m].
    rq2 : array_like
        RMS roughness of surface 2 [m].
    x_l : float
        Lubricant factor X_L (1.0 mineral oil) [-].

    Returns
    -------
    ndarray
        μ_mz [-].
    """
    a = _arrays(w_prime=w_prime, r_eq=r_eq, u_r=u_r, eta0=eta0, rq1=rq1, rq2=rq2)
    if not x_l > 0:
        raise InputError("x_l", x_l, "(0, inf)")
    load_n_mm = a["w_prime"] * 1e-3
    v_sum = 2.0 * a["u_r"]
    rho_mm = a["r_eq"] * 1e3
    ra_um = 0.5 * (a["rq1"] + a["rq2"]) * RA_PER_RQ * 1e6
    return 0.048 * (load_n_mm / (v_sum * rho_mm)) ** 0.2 * (a["eta0"] * 1e3) ** -0.05 * ra_um**0.25 * x_l


PUBLISHED_MODELS = ("xu_2007", "benedict_kelley_1961", "iso_tr_14179_2")
ALIASES = {"xu2007": "xu_2007", "benedict_kelley": "benedict_kelley_1961", "iso14179": "iso_tr_14179_2"}
"""Short names accepted by :func:`published_mu` (used by :mod:`efficiency.power_loss`)."""


def published_mu(name: str, p_h, r_eq, u_r, sr, temperature, rq1, rq2, lubricant, e_reduced: float,
                 x_l: float = 1.0):
    """μ of a published friction formula for the surrogate's inputs (SI), with η0 from ``lubricant`` at ``temperature``.

    Parameters
    ----------
    name : str
        ``xu_2007``, ``benedict_kelley_1961`` or ``iso_14179_2`` (or one of their short aliases) [-].
    p_h : array_like
        Hertz pressure [Pa].
    r_eq : array_like
        Equivalent radius of curvature [m].
    u_r : array_like
        Rolling velocity [m/s].
    sr : array_like
        Slide-to-roll ratio [-].
    temperature : array_like
        Oil inlet temperature [K].
    rq1 : array_like
        RMS roughness of surface 1 [m].
    rq2 : array_like
        RMS roughness of surface 2 [m].
    lubricant : Lubricant
        Supplies η0 at ``temperature`` and the boundary friction μ_d that caps Benedict & Kelley [-].
    e_reduced : float
        Reduced modulus E' (for the load per length W') [Pa].
    x_l : float
        Lubricant factor X_L of ISO/TR 14179-2 (1.0: the formula as printed; ignored by the others) [-].

    Returns
    -------
    ndarray
        μ [-].

    Raises
    ------
    InputError
        For an unknown ``name``.
    """
    from .features import load_per_length, lubricant_properties

    name = ALIASES.get(name, name)
    if name not in PUBLISHED_MODELS:
        raise InputError("model", name, f"one of {list(PUBLISHED_MODELS) + list(ALIASES)}")
    eta0, _ = lubricant_properties(lubricant, temperature)
    w_prime = load_per_length(p_h, r_eq, e_reduced)
    if name == "xu_2007":
        return xu_2007_mu(p_h, r_eq, u_r, sr, eta0, rq1, rq2)
    if name == "benedict_kelley_1961":
        return benedict_kelley_mu(w_prime, u_r, sr, eta0, rq1, rq2, mu_cap=lubricant.mu_d)
    return iso_14179_2_mu(w_prime, r_eq, u_r, eta0, rq1, rq2, x_l=x_l)
