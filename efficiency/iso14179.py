"""ISO/TR 14179-2:2001 gear mesh friction: the mean tooth friction coefficient μ_mz and the load-dependent mesh
power loss P_VZP, SI in and out (engineering units only inside the formula, where the standard defines them).

    μ_mz = 0.048 · (F_bt/b / (v_Σc ρ_redC))^0.2 · η_oil^−0.05 · Ra^0.25 · X_L          (Schlenk 1994)
    P_VZP = μ_mz · H_V · P_in,   H_V = Ohlendorf's loss factor (:func:`efficiency.loss_factor.ohlendorf_loss_factor`)

with F_bt = T1/r_b1 the transverse load at the base circle [N], b the face width [mm], v_Σc = 2 v_t sin α_wt the sum
velocity at the pitch point [m/s] (v_t = ω1 r_w1), ρ_redC = ρ_C1 ρ_C2/(ρ_C1 + ρ_C2)/cos β_b the reduced normal radius
of curvature at the pitch point [mm] (ρ_Ci = r_wi sin α_wt), η_oil the dynamic viscosity at the oil temperature
[mPa·s], Ra = (Ra1 + Ra2)/2 the arithmetic mean roughness [µm] and X_L the lubricant factor. The same form, units
and inputs are used by the independent implementation in Fernandes' GEARpie (CLASSES/CONTACT.py) and in
Fernandes, Marques, Martins & Seabra, Tribol. Int. 88 (2015) 309–316.

Roughness: the standard uses Ra. For a Gaussian height distribution Ra = √(2/π) Rq ≈ 0.798 Rq
(:data:`surrogate.published.RA_PER_RQ`); give Ra directly where it was measured.

Lubricant factor X_L by base oil (:data:`LUBRICANT_FACTOR`): mineral 0.846, polyalphaolefin 0.65, ester 0.65,
polyglycol 0.585 — the factors of Fernandes, Marques, Martins & Seabra, Tribol. Int. 88 (2015) 309–316 (fitted
to FZG torque-loss tests, as implemented in GEARpie's LUBRICANT_LIBRARY); "reference" = 1.0 is the standard's
base value for mineral oil, i.e. the formula as printed.

A lubricant for it needs only its viscosity–temperature law and base-oil type: :class:`SimpleOil` from the
kinematic viscosities at 40 and 100 °C (Walther / ASTM D341, log log(ν + 0.7) = A − B log T) and the density at
15 °C with a linear thermal expansion.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ehl_dataset.validation import InputError, check_range

LUBRICANT_FACTOR = {"mineral": 0.846, "pao": 0.65, "ester": 0.65, "polyglycol": 0.585, "reference": 1.0}
"""X_L by base-oil type (module docstring for the sources)."""

WALTHER_C = 0.7
"""ASTM D341 constant [cSt] in log10 log10(ν + 0.7)."""


def lubricant_factor(oil_type: str) -> float:
    """Lubricant factor X_L of ISO/TR 14179-2 for an oil type.

    Parameters
    ----------
    oil_type : str
        A key of :data:`LUBRICANT_FACTOR` [-].

    Returns
    -------
    float
        X_L [-].
    """
    key = str(oil_type).lower()
    if key not in LUBRICANT_FACTOR:
        raise InputError("oil_type", oil_type, " | ".join(LUBRICANT_FACTOR))
    return LUBRICANT_FACTOR[key]


@dataclass(frozen=True)
class SimpleOil:
    """An oil defined by its viscosities at 40 and 100 °C, its density at 15 °C and its thermal expansion.

    ρ = ρ15 (1 + α_T (T − 15 °C)) (GEARpie's law).

    Parameters
    ----------
    nu40 : float
        Kinematic viscosity at 40 °C [m²/s].
    nu100 : float
        Kinematic viscosity at 100 °C [m²/s].
    density15 : float
        Density at 15 °C [kg/m³].
    oil_type : str
        Base-oil type, a key of :data:`LUBRICANT_FACTOR` [-].
    expansion : float
        Thermal expansion coefficient α_T [1/K].
    """

    nu40: float
    nu100: float
    density15: float = 880.0
    oil_type: str = "mineral"
    expansion: float = -6.0e-4

    def __post_init__(self):
        check_range("nu40", self.nu40, 1e-7, 1e-2, unit="m²/s")
        check_range("nu100", self.nu100, 1e-7, 1e-2, unit="m²/s")
        if not self.nu100 < self.nu40:
            raise InputError("nu100", self.nu100, f"< nu40 = {self.nu40:g} m²/s (viscosity falls with temperature)")
        check_range("density15", self.density15, 500.0, 2000.0, unit="kg/m³")
        check_range("expansion", self.expansion, -2e-3, 0.0, unit="1/K")
        lubricant_factor(self.oil_type)

    @classmethod
    def from_walther(cls, a: float, b: float, **kwargs) -> "SimpleOil":
        """An oil from Walther constants, log10 log10(ν + 0.7) = a − b log10 T with ν in cSt and T in K.

        Parameters
        ----------
        a : float
            Walther constant a [-].
        b : float
            Walther constant b [-].
        **kwargs
            Other fields of :class:`SimpleOil` [-].

        Returns
        -------
        SimpleOil
            The oil.
        """
        nus = [(10 ** (10 ** (a - b * math.log10(t))) - WALTHER_C) * 1e-6 for t in (313.15, 373.15)]
        return cls(nu40=nus[0], nu100=nus[1], **kwargs)

    def kinematic_viscosity(self, temperature: float) -> float:
        """Kinematic viscosity on the Walther line through ν40 and ν100.

        Parameters
        ----------
        temperature : float
            Temperature [K].

        Returns
        -------
        float
            ν [m²/s].
        """
        check_range("temperature", temperature, 200.0, 600.0, unit="K")
        t40, t100 = math.log10(313.15), math.log10(373.15)
        y40 = math.log10(math.log10(self.nu40 * 1e6 + WALTHER_C))
        y100 = math.log10(math.log10(self.nu100 * 1e6 + WALTHER_C))
        slope = (y100 - y40) / (t100 - t40)
        y = y40 + slope * (math.log10(temperature) - t40)
        return (10 ** (10**y) - WALTHER_C) * 1e-6

    def density(self, temperature: float) -> float:
        """Density at a temperature.

        Parameters
        ----------
        temperature : float
            Temperature [K].

        Returns
        -------
        float
            ρ [kg/m³].
        """
        return self.density15 * (1.0 + self.expansion * (temperature - 288.15))

    def dynamic_viscosity(self, temperature: float) -> float:
        """Dynamic viscosity η = ν ρ.

        Parameters
        ----------
        temperature : float
            Temperature [K].

        Returns
        -------
        float
            η [Pa·s].
        """
        return self.kinematic_viscosity(temperature) * self.density(temperature)

    @property
    def lubricant_factor(self) -> float:
        return lubricant_factor(self.oil_type)


def iso_14179_2_mesh(pair, torque: float, speed_rad_s: float, eta_oil: float, ra1: float, ra2: float,
                     x_l: float) -> dict:
    """Mean tooth friction coefficient μ_mz, loss factor H_V and mesh power loss P_VZP of ISO/TR 14179-2 for ``pair``.

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    torque : float
        Input torque on gear 1 [N·m].
    speed_rad_s : float
        Angular speed ω1 of gear 1 [rad/s].
    eta_oil : float
        Oil dynamic viscosity at the oil temperature [Pa s].
    ra1 : float
        Arithmetic mean roughness Ra of gear 1 [m].
    ra2 : float
        Arithmetic mean roughness Ra of gear 2 [m].
    x_l : float
        Lubricant factor X_L [-].

    Returns
    -------
    dict
        μ_mz, H_V and P_VZP in SI, with the formula's inputs in its own units (keys with unit suffixes).
    """
    from .loss_factor import ohlendorf_loss_factor

    torque = check_range("torque", torque, 0.0, 1e7, low_inclusive=False, unit="N·m")
    speed = check_range("speed_rad_s", speed_rad_s, 0.0, 1e6, low_inclusive=False, unit="rad/s")
    eta_oil = check_range("eta_oil", eta_oil, 1e-5, 100.0, unit="Pa·s")
    ra1 = check_range("ra1", ra1, 0.0, 1e-4, low_inclusive=False, unit="m")
    ra2 = check_range("ra2", ra2, 0.0, 1e-4, low_inclusive=False, unit="m")
    x_l = check_range("x_l", x_l, 0.0, 5.0, low_inclusive=False)
    rb1 = float(pair.base_radii[0])
    rw1, rw2 = (float(r) for r in pair.working_pitch_radii)
    alpha_wt = float(pair.working_pressure_angle)
    f_bt = torque / rb1
    width_mm = float(pair.face_width) * 1e3
    v_t = speed * rw1
    v_sum = 2.0 * v_t * math.sin(alpha_wt)
    rho1, rho2 = rw1 * math.sin(alpha_wt), rw2 * math.sin(alpha_wt)
    rho_red_mm = rho1 * rho2 / (rho1 + rho2) / math.cos(float(pair.base_helix_angle)) * 1e3
    ra_um = 0.5 * (ra1 + ra2) * 1e6
    eta_mpas = eta_oil * 1e3
    mu = 0.048 * (f_bt / width_mm / (v_sum * rho_red_mm)) ** 0.2 * eta_mpas**-0.05 * ra_um**0.25 * x_l
    h_v = ohlendorf_loss_factor(pair)
    p_in = torque * speed
    return {"mu_mz": mu, "loss_factor_ohlendorf": h_v, "p_vzp_w": mu * h_v * p_in, "input_power_w": p_in,
            "f_bt_n": f_bt, "load_per_width_n_per_mm": f_bt / width_mm, "v_sum_m_per_s": v_sum,
            "rho_red_c_mm": rho_red_mm, "eta_oil_mpas": eta_mpas, "ra_um": ra_um, "x_l": x_l}
