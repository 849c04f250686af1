"""Lubricant model: viscosity–temperature, density–temperature, viscosity–pressure and density–pressure laws.

All functions work in SI units (Pa, Pa·s, kg/m³, K). Lubricant files (TOML) use engineering units with the unit in
the key name; :func:`load_lubricant` converts them.

Laws implemented
----------------
* Kinematic viscosity–temperature: Walther / ASTM D341, ``log10 log10(ν + 0.7) = A − B log10 T`` (ν in mm²/s,
  T in K), through two measured points (ν40, ν100). ASTM D341 adds terms below 2 mm²/s; we reject such fits.
* Density–temperature: linear thermal expansion ``ρ(T) = ρ_ref [1 − β (T − T_ref)]``.
* Pressure–viscosity coefficient: log-linear in temperature between two points ``α1(T)``.
* Viscosity–pressure (paper Eq. 5): two-slope law with a C¹ Hermite cubic in ``[p_a, p_b]``; plus Barus
  ``η0 exp(α p)`` and Roelands ``η0 exp{(ln η0 + 9.67)[(1 + p/p0)^z − 1]}``, ``p0 = 1.96e8 Pa``.
* Density–pressure (paper Eq. 6, Dowson–Higginson): ``ρ = ρ0 (1 + γ p)/(1 + λ p)``.
* Eyring shear: reference stress τ0; boundary (dry contact) friction coefficient μ_d.
* Thermal properties (optional ``[thermal]`` table; defaults and the model in :mod:`ehl_dataset.model.thermal`) and
  the temperature–viscosity coefficient β(p) = −∂ln η(p, T)/∂T of the laws above
  (:meth:`LubricantState.viscosity_temperature_coefficient`).
"""

from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Literal

import numpy as np

from ..data_files import resolve_named_file
from ..validation import InputError, check_range
from .thermal import THERMAL_RISES_K, TemperatureTable, ThermalProperties, thermal_properties_from_table

ROELANDS_P0_PA = 1.96e8
"""Roelands reference pressure p0 [Pa]."""
DH_GAMMA_PER_PA = 2.266e-9
"""Dowson–Higginson density constant γ [1/Pa] (paper Eq. 6)."""
DH_LAMBDA_PER_PA = 1.683e-9
"""Dowson–Higginson density constant λ [1/Pa] (paper Eq. 6)."""
CELSIUS_ZERO_K = 273.15
BETA_STEP_K = 1.0
"""Temperature step [K] of the difference quotient β(p) = −∂ln η/∂T (:meth:`LubricantState.viscosity_temperature_coefficient`)."""

PressureLawName = Literal["two_slope", "barus", "roelands"]


# ---------------------------------------------------------------------------------------------------------------
# Pure laws
# ---------------------------------------------------------------------------------------------------------------
def walther_constants(nu1_m2_s: float, t1_k: float, nu2_m2_s: float, t2_k: float) -> tuple[float, float]:
    """Constants (A, B) of ASTM D341 ``log10 log10(ν[mm²/s] + 0.7) = A − B log10 T[K]`` through two points."""
    y1 = math.log10(math.log10(nu1_m2_s * 1e6 + 0.7))
    y2 = math.log10(math.log10(nu2_m2_s * 1e6 + 0.7))
    x1, x2 = math.log10(t1_k), math.log10(t2_k)
    b = (y1 - y2) / (x2 - x1)
    a = y1 + b * x1
    return a, b


def walther_viscosity(temperature_k, a: float, b: float):
    """Kinematic viscosity [m²/s] at ``temperature_k`` from ASTM D341 constants (A, B)."""
    t = np.asarray(temperature_k, dtype=float)
    nu_mm2_s = 10.0 ** (10.0 ** (a - b * np.log10(t))) - 0.7
    return nu_mm2_s * 1e-6


def dowson_higginson_density(p, rho0: float):
    """Density [kg/m³] at pressure ``p`` [Pa], paper Eq. 6: ρ0 (1 + γp)/(1 + λp). Pressures below 0 use p = 0."""
    pp = np.maximum(np.asarray(p, dtype=float), 0.0)
    return rho0 * (1.0 + DH_GAMMA_PER_PA * pp) / (1.0 + DH_LAMBDA_PER_PA * pp)


def dowson_higginson_density_derivative(p, rho0: float):
    """dρ/dp [kg/(m³·Pa)] of :func:`dowson_higginson_density`."""
    pp = np.maximum(np.asarray(p, dtype=float), 0.0)
    return rho0 * (DH_GAMMA_PER_PA - DH_LAMBDA_PER_PA) / (1.0 + DH_LAMBDA_PER_PA * pp) ** 2


def hermite_transition(alpha1: float, alpha2: float, p_t: float, p_a: float, p_b: float) -> np.ndarray:
    """Coefficients c0..c3 of the cubic ``ln(η/η0) = c0 + c1 p + c2 p² + c3 p³`` on [p_a, p_b] (paper Eq. 5).

    The cubic matches value and slope of ``α1 p`` at ``p_a`` and of ``α1 p_t + α2 (p − p_t)`` at ``p_b`` (C¹).
    """
    matrix = np.array(
        [
            [1.0, p_a, p_a**2, p_a**3],
            [0.0, 1.0, 2 * p_a, 3 * p_a**2],
            [1.0, p_b, p_b**2, p_b**3],
            [0.0, 1.0, 2 * p_b, 3 * p_b**2],
        ]
    )
    rhs = np.array([alpha1 * p_a, alpha1, alpha1 * p_t + alpha2 * (p_b - p_t), alpha2])
    # Scale columns by powers of p_b for conditioning (pressures ~1e9 Pa).
    scale = np.array([1.0, p_b, p_b**2, p_b**3])
    return np.linalg.solve(matrix / scale, rhs) / scale


@dataclass(frozen=True)
class ViscosityPressureLaw:
    """Viscosity–pressure law at one temperature: ``η(p) = η0 exp(φ(p))``.

    Attributes (SI): ``eta0`` [Pa·s] ambient viscosity, ``alpha1`` [1/Pa] low-pressure coefficient, and per law:
    two-slope ``alpha2, p_t, p_a, p_b`` [1/Pa, Pa] with cubic coefficients; Roelands ``z`` [-] and ``p0`` [Pa].
    """

    kind: PressureLawName
    eta0: float
    alpha1: float
    alpha2: float = 0.0
    p_t: float = 0.0
    p_a: float = 0.0
    p_b: float = 0.0
    z: float = 0.0
    p0: float = ROELANDS_P0_PA
    cubic: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 0.0)

    def exponent(self, p):
        """φ(p) = ln(η/η0) [-]; negative pressures are treated as 0."""
        pp = np.maximum(np.asarray(p, dtype=float), 0.0)
        if self.kind == "barus":
            return self.alpha1 * pp
        if self.kind == "roelands":
            return (math.log(self.eta0) + 9.67) * ((1.0 + pp / self.p0) ** self.z - 1.0)
        c0, c1, c2, c3 = self.cubic
        low = self.alpha1 * pp
        high = self.alpha1 * self.p_t + self.alpha2 * (pp - self.p_t)
        mid = c0 + pp * (c1 + pp * (c2 + pp * c3))
        return np.where(pp < self.p_a, low, np.where(pp > self.p_b, high, mid))

    def exponent_derivative(self, p):
        """dφ/dp [1/Pa]; zero below p = 0."""
        p_arr = np.asarray(p, dtype=float)
        pp = np.maximum(p_arr, 0.0)
        if self.kind == "barus":
            out = np.full_like(pp, self.alpha1)
        elif self.kind == "roelands":
            out = (math.log(self.eta0) + 9.67) * self.z / self.p0 * (1.0 + pp / self.p0) ** (self.z - 1.0)
        else:
            _, c1, c2, c3 = self.cubic
            mid = c1 + pp * (2 * c2 + 3 * c3 * pp)
            out = np.where(pp < self.p_a, self.alpha1, np.where(pp > self.p_b, self.alpha2, mid))
        return np.where(p_arr < 0.0, 0.0, out)

    def viscosity(self, p):
        """Dynamic viscosity η(p) [Pa·s]."""
        return self.eta0 * np.exp(self.exponent(p))


# ---------------------------------------------------------------------------------------------------------------
# Lubricant definition
# ---------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class LubricantState:
    """Properties of a lubricant at one temperature (SI): what a contact solver needs.

    Parameters
    ----------
    temperature : float
        The temperature [K].
    eta0 : float
        Dynamic viscosity at ambient pressure [Pa s].
    rho0 : float
        Density at ambient pressure [kg/m³].
    alpha1 : float
        Low-pressure viscosity–pressure coefficient, for the dimensionless groups [1/Pa].
    law : ViscosityPressureLaw
        The viscosity–pressure law at this temperature [-].
    tau0 : float
        Eyring stress [Pa].
    mu_d : float
        Boundary friction coefficient [-].
    compressible : bool
        Dowson–Higginson density applies (False: ρ = ρ0) [-].
    thermal : ThermalProperties
        Thermal properties (:mod:`ehl_dataset.model.thermal`) [SI].
    log_viscosity_at : callable, optional
        (p, T) → ln η of the lubricant's laws at any temperature (not range-checked: the thermal correction
        extrapolates); None: β = 0 unless ``thermal.beta_override`` gives it [-].
    log_viscosity_rows : callable, optional
        (p, temperatures) → ln η rows, as :meth:`Lubricant.log_viscosity_rows` [-].
    """

    temperature: float
    eta0: float
    rho0: float
    alpha1: float
    law: ViscosityPressureLaw
    tau0: float
    mu_d: float
    compressible: bool = True
    thermal: ThermalProperties = field(default_factory=ThermalProperties)
    log_viscosity_at: Callable | None = field(default=None, compare=False, repr=False)
    log_viscosity_rows: Callable | None = field(default=None, compare=False, repr=False)

    def viscosity(self, p):
        """Viscosity η(p) at this temperature.

        Parameters
        ----------
        p : array_like
            Pressure [Pa].

        Returns
        -------
        ndarray
            η [Pa·s].
        """
        return self.law.viscosity(p)

    def temperature_table(self, p, rises=THERMAL_RISES_K) -> TemperatureTable:
        """ln η(p, T + ΔT) on the temperature rises ΔT (rows) for the pressures ``p`` (columns).

        The lubricant's own laws (Walther, the temperature dependence of its pressure–viscosity law) extrapolated beyond
        its range where the contact gets hotter, or ln η(p, T) − β ΔT with the lubricant file's constant β
        (``thermal.viscosity_temperature_coefficient_per_k``); β = 0 for a state built without the lubricant.

        Parameters
        ----------
        p : array_like
            Pressures [Pa].
        rises : array_like
            Temperature rises ΔT [K].

        Returns
        -------
        TemperatureTable
            The table.
        """
        p_arr = np.atleast_1d(np.asarray(p, dtype=float))
        rises = np.asarray(rises, dtype=float)
        base = np.log(self.law.viscosity(p_arr))
        if self.thermal.beta_override is not None or self.log_viscosity_at is None:
            beta = self.thermal.beta_override or 0.0
            return TemperatureTable(rises, base[None, :] - beta * rises[:, None])
        if self.log_viscosity_rows is not None:  # one array evaluation of every rise
            table = self.log_viscosity_rows(p_arr, self.temperature + rises)
            table[rises == 0.0] = base
            return TemperatureTable(rises, table)
        rows = [base if r == 0.0 else self.log_viscosity_at(p_arr, self.temperature + r) for r in rises]
        return TemperatureTable(rises, np.vstack(rows))

    def viscosity_temperature_coefficient(self, p):
        """β(p) = −∂ln η(p, T)/∂T at this temperature.

        The lubricant file's constant if it gives one, else the central difference (± :data:`BETA_STEP_K`) of the
        lubricant's ln η(p, T) (it includes the temperature dependence of α).

        Parameters
        ----------
        p : array_like
            Pressure [Pa].

        Returns
        -------
        ndarray
            β [1/K].
        """
        p_arr = np.asarray(p, dtype=float)
        if self.thermal.beta_override is not None:
            return np.full_like(p_arr, self.thermal.beta_override)
        if self.log_viscosity_at is None:
            return np.zeros_like(p_arr)
        t = self.temperature
        return (self.log_viscosity_at(p_arr, t - BETA_STEP_K) - self.log_viscosity_at(p_arr, t + BETA_STEP_K)) / (
            2.0 * BETA_STEP_K)

    def density(self, p):
        """Density ρ(p): Dowson–Higginson (paper Eq. 6), or constant if incompressible.

        Parameters
        ----------
        p : array_like
            Pressure [Pa].

        Returns
        -------
        ndarray
            ρ [kg/m³].
        """
        if not self.compressible:
            return np.full_like(np.asarray(p, dtype=float), self.rho0)
        return dowson_higginson_density(p, self.rho0)

    def density_derivative(self, p):
        """dρ/dp of :meth:`density`.

        Parameters
        ----------
        p : array_like
            Pressure [Pa].

        Returns
        -------
        ndarray
            dρ/dp [kg/(m³·Pa)].
        """
        if not self.compressible:
            return np.zeros_like(np.asarray(p, dtype=float))
        return dowson_higginson_density_derivative(p, self.rho0)


@dataclass(frozen=True)
class Lubricant:
    """A lubricant defined over a temperature range. Build with :func:`load_lubricant` or the constructor.

    Viscosity is either Walther's law (``walther_a``, ``walther_b``) or a fixed ``eta0_fixed`` (isoviscous-in-T
    validation fluids); the viscosity–pressure law is ``pressure_law`` (paper Eq. 5 for ``two_slope``).
    Temperatures outside ``t_min`` … ``t_max`` are rejected.

    Parameters
    ----------
    name : str
        Lubricant name [-].
    t_min : float
        Lowest temperature of the data [K].
    t_max : float
        Highest temperature of the data [K].
    rho_ref : float
        Density at ``t_ref`` and ambient pressure [kg/m³].
    t_ref : float
        Reference temperature of the density [K].
    beta : float
        Thermal expansion coefficient of the density, ρ = ρ_ref (1 − β (T − t_ref)) [1/K].
    alpha_points : tuple of tuple of float
        One or two (T [K], α1 [1/Pa]) points of the low-pressure viscosity–pressure coefficient, log-linear in T [-].
    pressure_law : str
        ``two_slope``, ``barus`` or ``roelands`` [-].
    tau0 : float
        Eyring stress τ0 [Pa].
    mu_d : float
        Boundary (dry-contact) friction coefficient [-].
    walther_a : float, optional
        Walther constant A of log10 log10(ν + 0.7) = A − B log10 T, ν in mm²/s and T in K [-].
    walther_b : float, optional
        Walther constant B [-].
    eta0_fixed : float, optional
        Temperature-independent viscosity at ambient pressure, instead of Walther's law [Pa s].
    alpha2_ratio : float
        α2/α1 of the two-slope law [-].
    p_t : float
        Transition pressure of the two-slope law [Pa].
    p_a : float
        Start of the cubic transition of the two-slope law [Pa].
    p_b : float
        End of the cubic transition of the two-slope law [Pa].
    roelands_z : float, optional
        Roelands pressure index; None: from α1 [-].
    compressible : bool
        Dowson–Higginson density (False: ρ = ρ0) [-].
    sources : dict of str to str
        Source of each property [-].
    definition : dict
        The parsed file, kept for provenance [-].
    thermal : ThermalProperties
        Thermal properties of the thermal correction (:mod:`ehl_dataset.model.thermal`) [SI].
    """

    name: str
    t_min: float
    t_max: float
    rho_ref: float
    t_ref: float
    beta: float
    alpha_points: tuple[tuple[float, float], ...]
    pressure_law: PressureLawName
    tau0: float
    mu_d: float
    walther_a: float | None = None
    walther_b: float | None = None
    eta0_fixed: float | None = None
    alpha2_ratio: float = 1.0
    p_t: float = 0.0
    p_a: float = 0.0
    p_b: float = 0.0
    roelands_z: float | None = None
    compressible: bool = True
    sources: dict[str, str] = field(default_factory=dict)
    definition: dict[str, Any] = field(default_factory=dict, compare=False, repr=False)
    thermal: ThermalProperties = field(default_factory=ThermalProperties)
    _laws: dict = field(default_factory=dict, init=False, compare=False, repr=False)

    def check_temperature(self, temperature_k: float) -> float:
        """Check a temperature against the lubricant's data range.

        Parameters
        ----------
        temperature_k : float or array_like
            Temperature [K].

        Returns
        -------
        float
            The temperature [K].

        Raises
        ------
        InputError
            When it is outside ``t_min`` … ``t_max``.
        """
        return check_range("temperature", temperature_k, self.t_min, self.t_max, unit=f"K for lubricant {self.name}")

    def kinematic_viscosity(self, temperature_k):
        """Kinematic viscosity ν(T) at ambient pressure.

        Parameters
        ----------
        temperature_k : float or array_like
            Temperature [K].

        Returns
        -------
        ndarray
            ν [m²/s].
        """
        if self.eta0_fixed is not None:
            return self.eta0_fixed / self.density_at(temperature_k)
        return walther_viscosity(temperature_k, self.walther_a, self.walther_b)

    def density_at(self, temperature_k):
        """Density ρ(T) at ambient pressure.

        Parameters
        ----------
        temperature_k : float or array_like
            Temperature [K].

        Returns
        -------
        ndarray
            ρ [kg/m³].
        """
        return self.rho_ref * (1.0 - self.beta * (np.asarray(temperature_k, dtype=float) - self.t_ref))

    def dynamic_viscosity(self, temperature_k):
        """Dynamic viscosity η0(T) at ambient pressure.

        Parameters
        ----------
        temperature_k : float or array_like
            Temperature [K].

        Returns
        -------
        ndarray
            η0 [Pa·s].
        """
        if self.eta0_fixed is not None:
            return np.full_like(np.asarray(temperature_k, dtype=float), self.eta0_fixed)
        return self.kinematic_viscosity(temperature_k) * self.density_at(temperature_k)

    def alpha1(self, temperature_k):
        """Low-pressure viscosity–pressure coefficient α1(T), log-linear in T between the data points.

        Parameters
        ----------
        temperature_k : float or array_like
            Temperature [K].

        Returns
        -------
        ndarray
            α1 [1/Pa].
        """
        t = np.asarray(temperature_k, dtype=float)
        if len(self.alpha_points) == 1:
            return np.full_like(t, self.alpha_points[0][1])
        (t1, a1), (t2, a2) = self.alpha_points[:2]
        return np.exp(math.log(a1) + (t - t1) / (t2 - t1) * (math.log(a2) - math.log(a1)))

    def state(self, temperature_k: float) -> LubricantState:
        """All properties at one temperature, validated against the lubricant's range.

        Parameters
        ----------
        temperature_k : float
            Temperature [K].

        Returns
        -------
        LubricantState
            The properties a contact solver needs.
        """
        t = self.check_temperature(temperature_k)
        eta0, alpha1, law = self._pressure_law(t)
        return LubricantState(t, eta0, float(self.density_at(t)), alpha1, law, self.tau0, self.mu_d, self.compressible,
                              self.thermal, self.log_viscosity, self.log_viscosity_rows)

    def log_viscosity(self, p, temperature_k: float):
        """ln η(p, T) of the lubricant's laws, **not** checked against its temperature range (the thermal correction
        extrapolates the laws to the contact temperature).

        Parameters
        ----------
        p : array_like
            Pressures [Pa].
        temperature_k : float
            Temperature [K].

        Returns
        -------
        ndarray
            ln η, η in Pa·s [-].
        """
        return np.log(self._pressure_law(float(temperature_k))[2].viscosity(p))

    def log_viscosity_rows(self, p, temperatures_k) -> np.ndarray:
        """ln η(p, T) of :meth:`log_viscosity` for every temperature (rows) and pressure (columns).

        One array evaluation of the laws (not range-checked).

        Parameters
        ----------
        p : array_like
            1-D pressures [Pa].
        temperatures_k : array_like
            1-D temperatures [K].

        Returns
        -------
        numpy.ndarray
            Shape (len(temperatures_k), len(p)); ln η, η in Pa·s [-].
        """
        t = np.asarray(temperatures_k, dtype=float)[:, None]
        pp = np.maximum(np.atleast_1d(np.asarray(p, dtype=float)), 0.0)[None, :]
        eta0 = np.asarray(self.dynamic_viscosity(t), dtype=float)
        alpha1 = np.asarray(self.alpha1(t), dtype=float) * np.ones_like(t)
        if self.pressure_law == "barus":
            phi = alpha1 * pp
        elif self.pressure_law == "roelands":
            ln_scale = np.log(eta0) + 9.67
            z = self.roelands_z if self.roelands_z is not None else alpha1 * ROELANDS_P0_PA / ln_scale
            phi = ln_scale * ((1.0 + pp / ROELANDS_P0_PA) ** z - 1.0)
        else:  # the Hermite cubic of paper Eq. 5 is linear in α1 when α2 = ratio·α1: one solve for every row
            unit = hermite_transition(1.0, self.alpha2_ratio, self.p_t, self.p_a, self.p_b)
            c0, c1, c2, c3 = (alpha1 * c for c in unit)
            low = alpha1 * pp
            high = alpha1 * self.p_t + self.alpha2_ratio * alpha1 * (pp - self.p_t)
            mid = c0 + pp * (c1 + pp * (c2 + pp * c3))
            phi = np.where(pp < self.p_a, low, np.where(pp > self.p_b, high, mid))
        return np.log(eta0 * np.exp(phi))

    def _pressure_law(self, t: float) -> tuple[float, float, ViscosityPressureLaw]:
        """(η0, α1, viscosity–pressure law) at temperature ``t`` [K] (not range-checked), remembered per temperature:
        the thermal tables ask for the same few hundred temperatures above each factorial temperature."""
        law = self._laws.get(t)
        if law is None:
            if len(self._laws) > 8192:
                self._laws.clear()
            law = self._laws[t] = self._build_pressure_law(t)
        return law

    def _build_pressure_law(self, t: float) -> tuple[float, float, ViscosityPressureLaw]:
        eta0 = float(self.dynamic_viscosity(t))
        alpha1 = float(self.alpha1(t))
        if self.pressure_law == "two_slope":
            alpha2 = self.alpha2_ratio * alpha1
            law = ViscosityPressureLaw(
                "two_slope", eta0, alpha1, alpha2, self.p_t, self.p_a, self.p_b,
                cubic=tuple(hermite_transition(alpha1, alpha2, self.p_t, self.p_a, self.p_b)),
            )
        elif self.pressure_law == "roelands":
            z = self.roelands_z if self.roelands_z is not None else alpha1 * ROELANDS_P0_PA / (math.log(eta0) + 9.67)
            law = ViscosityPressureLaw("roelands", eta0, alpha1, z=z)
        else:
            law = ViscosityPressureLaw("barus", eta0, alpha1)
        return eta0, alpha1, law

    def to_json_dict(self) -> dict[str, Any]:
        """The definition as read from its file (for provenance in HDF5 and coefficient files).

        Returns
        -------
        dict
            The parsed file, or only the name for a lubricant built in code.
        """
        return dict(self.definition) if self.definition else {"name": self.name}


# ---------------------------------------------------------------------------------------------------------------
# TOML loading
# ---------------------------------------------------------------------------------------------------------------
def _get(table: dict, key: str, where: str, *, low: float = -math.inf, high: float = math.inf,
         low_inclusive: bool = True):
    if key not in table:
        raise InputError(f"{where}.{key}", "<missing>", "a required numeric field")
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise InputError(f"{where}.{key}", value, "a number")
    return check_range(f"{where}.{key}", value, low, high, low_inclusive=low_inclusive)


def lubricant_from_dict(data: dict[str, Any], origin: str = "<dict>") -> Lubricant:
    """Build a :class:`Lubricant` from the parsed TOML structure (see ``data/lubricants/atf.toml``).

    Parameters
    ----------
    data : dict
        The parsed TOML structure (engineering units, as the key names say) [-].
    origin : str
        Where it was read from, for messages [-].

    Returns
    -------
    Lubricant
        The lubricant, in SI.

    Raises
    ------
    InputError
        Naming the first missing or bad field.
    """
    if not isinstance(data.get("name"), str):
        raise InputError("name", data.get("name", "<missing>"), f"a string naming the lubricant in {origin}")
    for section in ("temperature_range", "density", "viscosity", "pressure_viscosity", "traction"):
        if not isinstance(data.get(section), dict):
            raise InputError(section, "<missing>", f"a [{section}] table in {origin}")
    tr, de, vi, pv, trc = (data[s] for s in ("temperature_range", "density", "viscosity", "pressure_viscosity",
                                              "traction"))
    t_min = _get(tr, "min_c", "temperature_range", low=-CELSIUS_ZERO_K) + CELSIUS_ZERO_K
    t_max = _get(tr, "max_c", "temperature_range", low=-CELSIUS_ZERO_K) + CELSIUS_ZERO_K
    if t_max <= t_min:
        raise InputError("temperature_range.max_c", tr["max_c"], f"> min_c = {tr['min_c']}")
    rho_ref = _get(de, "rho_ref_kg_m3", "density", low=100.0, high=3000.0)
    t_ref = _get(de, "t_ref_c", "density", low=-CELSIUS_ZERO_K) + CELSIUS_ZERO_K
    beta = _get(de, "expansion_per_k", "density", low=0.0, high=1e-2)
    compressible = bool(de.get("compressible", True))

    model = vi.get("model")
    walther_a = walther_b = eta0_fixed = None
    if model == "walther":
        nu1 = _get(vi, "nu1_mm2_s", "viscosity", low=2.0, high=1e6) * 1e-6
        t1 = _get(vi, "t1_c", "viscosity", low=-CELSIUS_ZERO_K) + CELSIUS_ZERO_K
        nu2 = _get(vi, "nu2_mm2_s", "viscosity", low=2.0, high=1e6) * 1e-6
        t2 = _get(vi, "t2_c", "viscosity", low=-CELSIUS_ZERO_K) + CELSIUS_ZERO_K
        if not (t2 > t1 and nu2 < nu1):
            raise InputError("viscosity", f"nu({t1 - CELSIUS_ZERO_K:g} C)={nu1 * 1e6:g}, "
                             f"nu({t2 - CELSIUS_ZERO_K:g} C)={nu2 * 1e6:g}",
                             "two points with t2_c > t1_c and nu2 < nu1")
        walther_a, walther_b = walther_constants(nu1, t1, nu2, t2)
    elif model == "constant":
        eta0_fixed = _get(vi, "eta0_pa_s", "viscosity", low=0.0, low_inclusive=False)
    else:
        raise InputError("viscosity.model", model if model is not None else "<missing>", "'walther' or 'constant'")

    law = pv.get("model")
    if law not in ("two_slope", "barus", "roelands"):
        raise InputError("pressure_viscosity.model", law if law is not None else "<missing>",
                         "'two_slope', 'barus' or 'roelands'")
    points = pv.get("alpha1_points")
    if not isinstance(points, list) or not 1 <= len(points) <= 2:
        raise InputError("pressure_viscosity.alpha1_points", points if points is not None else "<missing>",
                         "a list of one or two [temperature_c, alpha_per_pa] pairs")
    alpha_points = []
    for i, point in enumerate(points):
        if not (isinstance(point, list) and len(point) == 2):
            raise InputError(f"pressure_viscosity.alpha1_points[{i}]", point, "[temperature_c, alpha_per_pa]")
        t_c = check_range(f"pressure_viscosity.alpha1_points[{i}][0]", point[0], -CELSIUS_ZERO_K)
        alpha = check_range(f"pressure_viscosity.alpha1_points[{i}][1]", point[1], 0.0, 1e-6, low_inclusive=False)
        alpha_points.append((t_c + CELSIUS_ZERO_K, alpha))
    if len(alpha_points) == 2 and alpha_points[0][0] == alpha_points[1][0]:
        raise InputError("pressure_viscosity.alpha1_points", points, "two different temperatures")
    kwargs: dict[str, Any] = {}
    if law == "two_slope":
        kwargs["alpha2_ratio"] = _get(pv, "alpha2_ratio", "pressure_viscosity", low=0.0, high=1.0,
                                      low_inclusive=False)
        p_a = _get(pv, "p_a_gpa", "pressure_viscosity", low=0.0, low_inclusive=False) * 1e9
        p_t = _get(pv, "p_t_gpa", "pressure_viscosity", low=0.0, low_inclusive=False) * 1e9
        p_b = _get(pv, "p_b_gpa", "pressure_viscosity", low=0.0, low_inclusive=False) * 1e9
        if not p_a < p_t < p_b:
            raise InputError("pressure_viscosity.p_a_gpa/p_t_gpa/p_b_gpa", (pv["p_a_gpa"], pv["p_t_gpa"],
                             pv["p_b_gpa"]), "p_a < p_t < p_b")
        kwargs.update(p_a=p_a, p_t=p_t, p_b=p_b)
    elif law == "roelands" and "z" in pv:
        kwargs["roelands_z"] = _get(pv, "z", "pressure_viscosity", low=0.0, high=2.0, low_inclusive=False)

    tau0 = _get(trc, "eyring_stress_mpa", "traction", low=0.0, low_inclusive=False) * 1e6
    mu_d = _get(trc, "boundary_friction", "traction", low=0.0, high=1.0, low_inclusive=False)
    sources = data.get("sources", {})
    if not isinstance(sources, dict):
        raise InputError("sources", sources, "a table of field = 'source or representative'")
    thermal = thermal_properties_from_table(data.get("thermal"), sources.get("thermal"), origin)
    return Lubricant(
        name=data["name"], t_min=t_min, t_max=t_max, rho_ref=rho_ref, t_ref=t_ref, beta=beta,
        alpha_points=tuple(alpha_points), pressure_law=law, tau0=tau0, mu_d=mu_d, walther_a=walther_a,
        walther_b=walther_b, eta0_fixed=eta0_fixed, compressible=compressible, sources=dict(sources),
        definition=data, thermal=thermal, **kwargs,
    )


def load_lubricant(name_or_path: str | Path = "atf") -> Lubricant:
    """Load a lubricant by shipped name (``atf``, ``gear_oil_75w90``, ...) or from a TOML file.

    Parameters
    ----------
    name_or_path : str or Path
        Shipped name (``data/lubricants/NAME.toml``) or path of a lubricant TOML file [-].

    Returns
    -------
    Lubricant
        The validated lubricant.

    Raises
    ------
    InputError
        For a missing or invalid file, naming the first bad field.
    """
    path = resolve_named_file("lubricants", name_or_path, ".toml")
    try:
        with open(path, "rb") as handle:
            data = tomllib.load(handle)
    except tomllib.TOMLDecodeError as err:
        raise InputError("lubricant file", str(path), "a valid TOML file", str(err)) from None
    return lubricant_from_dict(data, origin=str(path))
