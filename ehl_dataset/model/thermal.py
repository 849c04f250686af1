"""Thermal correction of the EHL traction: shear heating of the film and flash temperature of the surfaces.

The Couette (sliding) traction of an isothermal solve, τ = τ0 asinh(η u_s/(τ0 h)), takes the viscosity at the inlet
(bulk) temperature T0. In a sliding contact the film dissipates q = τ |u_s| per unit area; the heat is conducted
across the film into the two surfaces, which carry it away as they move through the contact. The film and the
surfaces get hotter, the viscosity falls and so does τ. This module corrects τ for that, node by node along the
contact, **on the film of the isothermal solve** (the approximation: pressure and film shape stay isothermal; only
the shear stress is corrected; the inlet shear heating that would thin the film, e.g. Gupta et al. 1992, is not
modelled). The structure is that of Olver & Spikes, Proc. IMechE J 212 (1998) 321 and of Evans & Johnson,
Proc. IMechE C 200 (1986) 313: surface temperature from the moving-heat-source (flash temperature) theory of Blok
(1937) and Jaeger (1942), plus the temperature rise across the film from conduction of the heat generated in it
(Crook 1961). The equations below are derived here; the constants they give are checked in
``tests/ehl_dataset/test_thermal.py`` against Blok's published 1.11 and against exact limits.

1. **Viscosity–temperature law.** At the surfaces, η_s = η(p, T0 + ΔT_s) of the lubricant's own laws (Walther and
   the temperature dependence of its pressure–viscosity law, extrapolated beyond the lubricant's range where the
   contact is hotter), tabulated in ΔT (:class:`TemperatureTable`, :data:`THERMAL_RISES_K`); or, if the lubricant
   file gives a constant temperature–viscosity coefficient β, η(p, T0) exp(−β ΔT_s). Across the film the
   exponential law η = η_s exp(−β (T − T_s)), with β the secant of the lubricant's ln η between the wall and the
   film centre temperature (:func:`film_with_secant_beta`; the tangent at the wall for small rises): the
   closed-form film solution needs an exponential law, and the secant keeps β falling with temperature.

2. **Film** (Eyring fluid, conduction across the film only, both walls at the surface temperature T_s, the shear
   stress τ uniform across the film). With θ = β (T − T_s) and the shear rate γ̇ = (τ0/η_s) sinh(τ/τ0) e^θ, the
   energy equation k θ'' = −β τ γ̇ has the closed-form solution (z from the film centre)

       e^θ = cosh²X · sech²(2X z/h),   centre rise ΔT_c = 2 ln cosh X / β,

   and the sliding speed u_s = ∫γ̇ dz gives the traction τ = τ0 asinh(S g(X)), g(X) = 2X/sinh 2X, with S =
   η_s |u_s|/(τ0 h) the isothermal Eyring argument at the wall temperature and X the root of

       X tanh X = A asinh(S g(X)),        A = β |u_s| h τ0 / (8 k).

   The left side rises and the right side falls with X, so the root is unique for every A ≥ 0 (velocity-controlled
   Couette flow has no thermal runaway). Limits: A = 0 (β = 0 or u_s = 0) gives X = 0 and the isothermal τ; for
   small X, X² = β τ u_s h/(8k) = β ΔT_c with Crook's centre rise ΔT_c = τ u_s h/(8k), and g ≈ exp(−β ΔT̄) with
   the mean film rise ΔT̄ = τ u_s h/(12 k): the "mean film temperature" rule of the simplified models. This is the
   analysis of Johnson & Greenwood, Wear 61 (1980) 353, in its conduction-only form (derived here, not copied).

3. **Surfaces** (Blok 1937; Jaeger 1942, high Péclet number u a/(2κ) ≫ 1: heat conducted into each solid only
   normal to its surface). A surface point moving at u_i through the heat flux q_i(x) heats up as

       ΔT_i(x) = 1/(B_i √(π u_i)) ∫_{x_in}^{x} q_i(ξ) (x − ξ)^(−1/2) dξ,     B_i = √(k_i ρ_i c_i),

   and Blok's partition (both surfaces at the same temperature where they meet the film) splits q = τ |u_s| so
   that ΔT_1 = ΔT_2 = ΔT_s:

       ΔT_s(x) = 1/(√π (B_1 √u_1 + B_2 √u_2)) ∫_{x_in}^{x} q(ξ) (x − ξ)^(−1/2) dξ.

   For a Hertzian (semi-elliptic) flux q = q0 √(1 − x²/a²) the maximum is 1.2346 q0 √a/(B_1√u_1 + B_2√u_2) at
   x = 0.652 a, i.e. Blok's maximum flash temperature 1.11 μ w' |u_s| / (√(2a) (B_1√u_1 + B_2√u_2))
   (:data:`BLOK_MAX_COEFFICIENT`).

The coupled problem (T_s depends on τ upstream, τ on T_s) is solved by a damped fixed-point iteration
(:func:`thermal_couette_traction`). The bulk temperature of the surfaces entering the contact is taken equal to
the oil inlet temperature T0.

Property defaults (overridable in a lubricant file's ``[thermal]`` table, with a source): oil conductivity
0.14 W/(m·K) and heat capacity 2000 J/(kg·K) — ambient-pressure values typical of mineral and PAO base oils
(0.13–0.165 W/(m·K), about 2 kJ/(kg·K)); the conductivity rises with pressure (by tens of per cent at 1 GPa), which
the default ignores, so the film rise is on the high side. Steel 46 W/(m·K), 7850 kg/m³, 470 J/(kg·K) (bearing and
gear steels, e.g. AISI 52100), B = 13.0 kW·s^½/(m²·K). All REPRESENTATIVE, like the other property defaults of
the shipped lubricants.
"""

from __future__ import annotations

import math
import threading
from collections import OrderedDict
from dataclasses import asdict, dataclass
from typing import Any

import numba
import numpy as np
from scipy.linalg import solve_triangular

from ..validation import InputError, SolverError, check_range
from .scalar_root import brent_root

OIL_CONDUCTIVITY_W_MK = 0.14
"""Default lubricant thermal conductivity [W/(m·K)] (representative, module docstring)."""
OIL_HEAT_CAPACITY_J_KGK = 2000.0
"""Default lubricant specific heat [J/(kg·K)] (representative)."""
STEEL_CONDUCTIVITY_W_MK = 46.0
"""Default solid thermal conductivity [W/(m·K)] (bearing/gear steel, representative)."""
STEEL_DENSITY_KG_M3 = 7850.0
"""Default solid density [kg/m³]."""
STEEL_HEAT_CAPACITY_J_KGK = 470.0
"""Default solid specific heat [J/(kg·K)]."""

BLOK_MAX_COEFFICIENT = 1.2346
"""max over x of ΔT_s (B_1√u_1 + B_2√u_2)/(q0 √a) for a semi-elliptic flux q0 √(1 − x²/a²): 1.23462 at x = 0.6522 a
(quadrature of the Jaeger integral); × (2/π)·√2 = 1.1116, Blok's 1.11 when written with w' = π a q0/(2 μ |u_s|)
and the contact width 2a."""
BLOK_CENTRE_COEFFICIENT = 0.98623
"""The same at the contact centre x = 0 (the planner's estimate uses the maximum, which is conservative)."""

THERMAL_RISES_K = np.arange(0.0, 402.0, 2.0)
"""Temperature rises [K] at which :class:`TemperatureTable` tabulates ln η (linear interpolation between them: error
in η below 0.1 %; beyond 400 K the last slope is extrapolated)."""

FIXED_POINT_TOLERANCE = 1e-9
"""Tolerance of the coupled solutions: max |ΔT_s − J q| ≤ 1e-9 (1 + max ΔT_s) K (:func:`thermal_couette_traction`),
relative change of τ (:func:`centre_estimate`)."""
FIXED_POINT_MAX_ITERATIONS = 400
NEWTON_STEPS = 100
"""Most safeguarded Newton steps of the film equation (:func:`film_parameter`; it converges in about 5–10)."""


@dataclass(frozen=True)
class ThermalProperties:
    """Thermal properties of a lubricated contact (SI).

    Parameters
    ----------
    oil_conductivity : float
        Thermal conductivity k of the oil [W/(m K)].
    oil_heat_capacity : float
        Specific heat capacity of the oil [J/(kg K)].
    solid_conductivity : float
        Thermal conductivity of both bodies [W/(m K)].
    solid_density : float
        Density of both bodies [kg/m³].
    solid_heat_capacity : float
        Specific heat capacity of both bodies [J/(kg K)].
    beta_override : float, optional
        Constant temperature–viscosity coefficient replacing the one derived from the lubricant's viscosity data;
        None: derived [1/K].
    source : str
        Where the values come from [-].
    """

    oil_conductivity: float = OIL_CONDUCTIVITY_W_MK
    oil_heat_capacity: float = OIL_HEAT_CAPACITY_J_KGK
    solid_conductivity: float = STEEL_CONDUCTIVITY_W_MK
    solid_density: float = STEEL_DENSITY_KG_M3
    solid_heat_capacity: float = STEEL_HEAT_CAPACITY_J_KGK
    beta_override: float | None = None
    source: str = "defaults of ehl_dataset.model.thermal (representative)"

    def __post_init__(self):
        check_range("thermal.oil_conductivity_w_mk", self.oil_conductivity, 0.01, 10.0, unit="W/(m K)")
        check_range("thermal.oil_heat_capacity_j_kgk", self.oil_heat_capacity, 100.0, 1e4, unit="J/(kg K)")
        check_range("thermal.solid_conductivity_w_mk", self.solid_conductivity, 0.1, 1000.0, unit="W/(m K)")
        check_range("thermal.solid_density_kg_m3", self.solid_density, 100.0, 3e4, unit="kg/m3")
        check_range("thermal.solid_heat_capacity_j_kgk", self.solid_heat_capacity, 10.0, 1e4, unit="J/(kg K)")
        if self.beta_override is not None:
            check_range("thermal.viscosity_temperature_coefficient_per_k", self.beta_override, 0.0, 1.0,
                        unit="1/K")

    @property
    def effusivity(self) -> float:
        """Thermal effusivity of the solids B = √(k ρ c) [W·s^½/(m²·K)]."""
        return math.sqrt(self.solid_conductivity * self.solid_density * self.solid_heat_capacity)

    @property
    def solid_diffusivity(self) -> float:
        """κ = k/(ρ c) of the solids [m²/s]."""
        return self.solid_conductivity / (self.solid_density * self.solid_heat_capacity)

    def to_dict(self) -> dict[str, Any]:
        """The properties as a plain dict.

        Returns
        -------
        dict
            Field name to value, SI.
        """
        return asdict(self)


THERMAL_KEYS = {"oil_conductivity_w_mk": "oil_conductivity", "oil_heat_capacity_j_kgk": "oil_heat_capacity",
                "solid_conductivity_w_mk": "solid_conductivity", "solid_density_kg_m3": "solid_density",
                "solid_heat_capacity_j_kgk": "solid_heat_capacity",
                "viscosity_temperature_coefficient_per_k": "beta_override"}
"""Keys of a lubricant file's ``[thermal]`` table → :class:`ThermalProperties` fields (all optional)."""


def thermal_properties_from_table(table: dict | None, source: str | None, origin: str = "<dict>"
                                  ) -> ThermalProperties:
    """:class:`ThermalProperties` from a lubricant file's optional ``[thermal]`` table (defaults for missing keys).

    A table with any value needs ``sources.thermal`` naming where the values come from."""
    if table is None:
        return ThermalProperties()
    if not isinstance(table, dict):
        raise InputError("thermal", table, f"a [thermal] table in {origin}")
    unknown = sorted(set(table) - set(THERMAL_KEYS))
    if unknown:
        raise InputError(f"thermal.{unknown[0]}", table[unknown[0]], f"one of {sorted(THERMAL_KEYS)}")
    if table and not (isinstance(source, str) and source.strip()):
        raise InputError("sources.thermal", source if source is not None else "<missing>",
                         f"a text naming the source of the [thermal] values in {origin}")
    values = {}
    for key, name in THERMAL_KEYS.items():
        if key in table:
            value = table[key]
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise InputError(f"thermal.{key}", value, "a number")
            values[name] = float(value)
    return ThermalProperties(**values, source=source.strip() if table else ThermalProperties.source)


@dataclass(frozen=True)
class TemperatureTable:
    """ln η(p_i, T0 + ΔT_j) on the temperature rises ΔT_j (rows) for the pressures of one contact (columns).

    Built by :meth:`ehl_dataset.model.lubricant.LubricantState.temperature_table`.

    Parameters
    ----------
    rises : ndarray
        Temperature rises ΔT_j, increasing from 0 [K].
    log_eta : ndarray
        ln η (η in Pa·s), shape (len(rises), number of pressures) [-].
    """

    rises: np.ndarray
    log_eta: np.ndarray

    def __post_init__(self):
        if self.rises.ndim != 1 or self.rises.size < 2 or self.rises[0] != 0.0 or np.any(np.diff(self.rises) <= 0):
            raise InputError("rises", self.rises, "increasing temperature rises from 0 K (at least two)")
        if self.log_eta.shape[0] != self.rises.size:
            raise InputError("log_eta", self.log_eta.shape, f"({self.rises.size}, N) rows per rise")

    def at(self, rise) -> tuple[np.ndarray, np.ndarray]:
        """Viscosity and its temperature coefficient at given rises, per column.

        η is interpolated linearly in ln η; β = −∂ln η/∂T is that of the bracketing interval (the last one beyond the
        table; the first one at ΔT = 0).

        Parameters
        ----------
        rise : array_like
            Temperature rise per column [K].

        Returns
        -------
        tuple of ndarray
            (η [Pa·s], β [1/K]).
        """
        rise = np.broadcast_to(np.asarray(rise, dtype=float), self.log_eta.shape[1:])
        j = np.clip(np.searchsorted(self.rises, rise, side="right") - 1, 0, self.rises.size - 2)
        cols = np.arange(self.log_eta.shape[1]) if self.log_eta.ndim > 1 else None
        lo = self.log_eta[j, cols] if cols is not None else self.log_eta[j]
        hi = self.log_eta[j + 1, cols] if cols is not None else self.log_eta[j + 1]
        slope = (hi - lo) / (self.rises[j + 1] - self.rises[j])
        return np.exp(lo + slope * (rise - self.rises[j])), -slope

    def column(self, index: int) -> "TemperatureTable":
        """The table of one pressure (column).

        Parameters
        ----------
        index : int
            Column index [-].

        Returns
        -------
        TemperatureTable
            A one-column table.
        """
        return TemperatureTable(self.rises, self.log_eta[:, index:index + 1])


# ---------------------------------------------------------------------------------------------------------------
# The film: Eyring fluid with an exponential viscosity–temperature law, conduction across the film
# ---------------------------------------------------------------------------------------------------------------
def _g(x):
    """g(X) = 2X/sinh(2X), stable for large X (→ 4X e^(−2X)) and X → 0 (→ 1)."""
    x = np.asarray(x, dtype=float)
    two = 2.0 * x
    with np.errstate(over="ignore", under="ignore", invalid="ignore"):
        big = two * 2.0 * np.exp(-two) / (1.0 - np.exp(-2.0 * two))
        small = two / np.sinh(np.where(two > 0.0, two, 1.0))
    return np.where(two < 1e-8, 1.0 - two**2 / 6.0, np.where(two > 30.0, big, small))


def film_parameter(eta_wall, u_s: float, h, tau0: float, beta, conductivity: float) -> np.ndarray:
    """The root X ≥ 0 of φ(X) = X tanh X − A asinh(S g(X)) = 0 (module docstring, item 2), vectorised.

    φ increases with X from φ(0) = −A asinh S: Newton steps kept inside a bracket that shrinks with the sign of φ (a
    bisection step where Newton leaves it), until the step is below 1e-13 (1 + X).

    Parameters
    ----------
    eta_wall : array_like
        Viscosity at the wall temperature, η(p, T_s) [Pa s].
    u_s : float
        Sliding velocity [m/s].
    h : array_like
        Film thickness [m].
    tau0 : float
        Eyring stress [Pa].
    beta : array_like
        Temperature–viscosity coefficient [1/K].
    conductivity : float
        Thermal conductivity of the oil [W/(m K)].

    Returns
    -------
    ndarray
        X [-].
    """
    eta_wall, h, beta = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (eta_wall, h, beta)))
    shape = eta_wall.shape
    x = _film_parameter_kernel(np.array(eta_wall).ravel(), float(u_s), np.array(h).ravel(), float(tau0),
                               np.array(beta).ravel(), float(conductivity), NEWTON_STEPS)
    return x.reshape(shape)


@numba.njit(cache=True)
def _g_scalar(x):
    """:func:`_g` of one value."""
    two = 2.0 * x
    if two < 1e-8:
        return 1.0 - two * two / 6.0
    if two > 30.0:
        return two * 2.0 * math.exp(-two) / (1.0 - math.exp(-2.0 * two))
    return two / math.sinh(two)


@numba.njit(cache=True)
def _film_newton_step(xi, lo, hi, s, a):
    """One safeguarded Newton step of φ(X) = X tanh X − A asinh(S g(X)) from X = ``xi`` inside the bracket [lo, hi]
    (:func:`film_parameter`). Returns (new X, new lo, new hi, whether the step is below 1e-13 (1 + X))."""
    g = _g_scalar(xi)
    sg = s * g
    phi = xi * math.tanh(xi) - a * math.asinh(sg)
    if phi < 0.0:
        lo = xi
    if phi > 0.0:
        hi = xi
    if xi > 1e-4:
        dg = g * (1.0 / xi - 2.0 / math.tanh(max(2.0 * xi, 1e-300)))
    else:
        dg = -4.0 * xi / 3.0
    dphi = math.tanh(xi) + xi / math.cosh(min(xi, 350.0)) ** 2 - a * s * dg / math.sqrt(1.0 + sg * sg)
    new = xi - phi / dphi if dphi != 0.0 else math.nan
    if not math.isfinite(new) or new < lo or new > hi:
        new = 0.5 * (lo + hi)
    return new, lo, hi, abs(new - xi) <= 1e-13 * (1.0 + xi)


@numba.njit(cache=True)
def _film_newton_start(s, a):
    """Start of the Newton iteration of :func:`film_parameter`: (A asinh S, X0, lo, hi) with the bracket
    [0, 2 A asinh S + 2] and X0 = min(√(A asinh S), its midpoint); X0 is NaN where A asinh S < 0."""
    rhs0 = a * math.asinh(s)
    hi = 2.0 * rhs0 + 2.0
    x = min(math.sqrt(rhs0), 0.5 * hi) if rhs0 >= 0.0 else math.nan
    return rhs0, x, 0.0, hi


@numba.njit(cache=True)
def _film_parameter_lockstep(s, a, steps):
    """The roots X of X tanh X = A asinh(S g(X)) at every node (:func:`film_parameter`): the safeguarded Newton
    iteration of all nodes in lockstep, stopped when every node's step is below 1e-13 (1 + X), as the array form does
    (so that both give the same numbers); 0 where A asinh S is not positive."""
    n = s.size
    rhs0 = np.empty(n)
    lo = np.empty(n)
    hi = np.empty(n)
    x = np.empty(n)
    for i in range(n):
        rhs0[i], x[i], lo[i], hi[i] = _film_newton_start(s[i], a[i])
    for _ in range(steps):
        done = True
        for i in range(n):
            x[i], lo[i], hi[i], small = _film_newton_step(x[i], lo[i], hi[i], s[i], a[i])
            if not small:
                done = False
        if done:
            break
    for i in range(n):
        if not rhs0[i] > 0.0:
            x[i] = 0.0
    return x


@numba.njit(cache=True)
def _film_parameter_recorded(s, a, steps, record):
    """:func:`_film_parameter_lockstep` reusing recorded Newton paths: the same numbers, computed only where needed.

    The Newton path of one node depends on its own S and A only; the lockstep couples the nodes only through the
    number of steps K (the first step after which every node's step is below 1e-13 (1 + X)). ``record`` (from
    :func:`_film_path_record`, for the same ``s`` in every call) keeps for each node the paths of its last two
    values of A (a secant iteration that has converged to round-off often alternates between two): a node whose A
    is one of them takes up its path, stepped further only if K exceeds it. Returns X after K steps, 0 where
    A asinh S ≤ 0."""
    key, rhs0, path, small, lo, hi, length, slot = record
    n = s.size
    for i in range(n):
        if a[i] == key[slot[i], i]:
            continue
        slot[i] = 1 - slot[i]
        if a[i] == key[slot[i], i]:
            continue
        j = slot[i]
        key[j, i] = a[i]
        rhs0[j, i], path[j, 0, i], lo[j, i], hi[j, i] = _film_newton_start(s[i], a[i])
        length[j, i] = 0
    taken = steps
    for k in range(steps):
        done = True
        for i in range(n):
            j = slot[i]
            if length[j, i] <= k:
                path[j, k + 1, i], lo[j, i], hi[j, i], small[j, k, i] = _film_newton_step(path[j, k, i], lo[j, i],
                                                                                          hi[j, i], s[i], a[i])
                length[j, i] = k + 1
            if not small[j, k, i]:
                done = False
        if done:
            taken = k + 1
            break
    x = np.empty(n)
    for i in range(n):
        j = slot[i]
        x[i] = path[j, taken, i] if rhs0[j, i] > 0.0 else 0.0
    return x


@numba.njit(cache=True)
def _film_path_record(n, steps):
    """An empty record of Newton paths for :func:`_film_parameter_recorded`: for two values of A per node (slot 0,
    1) the value (NaN: none), A asinh S, X after k steps, whether step k + 1 was below tolerance, the bracket after
    the recorded steps, their number, and the slot of the node's last call."""
    return (np.full((2, n), np.nan), np.empty((2, n)), np.empty((2, steps + 1, n)),
            np.empty((2, steps, n), dtype=np.bool_), np.empty((2, n)), np.empty((2, n)),
            np.zeros((2, n), dtype=np.int64), np.zeros(n, dtype=np.int64))


@numba.njit(cache=True)
def _film_parameter_kernel(eta_wall, u_s, h, tau0, beta, conductivity, steps):
    """:func:`film_parameter` of flat arrays."""
    s = eta_wall * abs(u_s) / (tau0 * h)
    a = beta * abs(u_s) * h * tau0 / (8.0 * conductivity)
    return _film_parameter_lockstep(s, a, steps)


@numba.njit(cache=True)
def _table_at(rises, log_eta, column, rise):
    """(ln η, β) of :meth:`TemperatureTable.at` for one column and one rise."""
    n = rises.size
    j = np.searchsorted(rises, rise, side="right") - 1
    j = min(max(j, 0), n - 2)
    lo = log_eta[j, column]
    slope = (log_eta[j + 1, column] - lo) / (rises[j + 1] - rises[j])
    return lo + slope * (rise - rises[j]), -slope


@numba.njit(cache=True)
def _secant_film_kernel(rises, log_eta, rise, u_s, h, tau0, conductivity, secant_iterations, steps):
    """:func:`film_with_secant_beta` of node ``i`` = column ``i`` of ``log_eta`` at ``rise[i]`` with film ``h[i]``:
    the secant iteration of all nodes in lockstep, stopped when every β has converged to 1e-10, as the array form.
    The film parameter X of each secant step is that of :func:`_film_parameter_lockstep`, with the Newton paths of
    a node's last two β reused (:func:`_film_parameter_recorded`); a node whose β and X did not change in the last
    secant step keeps its secant: the same numbers as recomputing them."""
    n = rise.size
    log_eta_s = np.empty(n)
    beta = np.empty(n)
    for i in range(n):
        log_eta_s[i], slope_beta = _table_at(rises, log_eta, i, rise[i])
        beta[i] = max(slope_beta, 0.0)
    eta_s = np.exp(log_eta_s)
    log_eta_s = np.log(eta_s)
    s = eta_s * abs(u_s) / (tau0 * h)
    record = _film_path_record(n, steps)
    x = np.full(n, np.nan)
    unchanged = np.zeros(n, dtype=np.bool_)
    for _ in range(secant_iterations):
        x_last = x
        x = _film_parameter_recorded(s, beta * abs(u_s) * h * tau0 / (8.0 * conductivity), steps, record)
        done = True
        for i in range(n):
            if unchanged[i] and x[i] == x_last[i]:
                continue                               # same β and X as in the last step: the same secant again
            centre = 2.0 * (x[i] + math.log1p(math.exp(-2.0 * x[i])) - math.log(2.0)) / beta[i] if beta[i] > 0.0 \
                else 0.0
            secant = beta[i]
            if centre > 1e-6:
                eta_c = math.exp(_table_at(rises, log_eta, i, rise[i] + centre)[0])
                secant = (log_eta_s[i] - math.log(eta_c)) / centre
            secant = max(secant, 0.0)
            if not abs(secant - beta[i]) <= 1e-10 * max(beta[i], 1e-300):
                done = False
            unchanged[i] = secant == beta[i]
            beta[i] = secant
        if done:
            break
    x = _film_parameter_recorded(s, beta * abs(u_s) * h * tau0 / (8.0 * conductivity), steps, record)
    sign = 1.0 if u_s >= 0.0 else -1.0
    tau = np.empty(n)
    for i in range(n):
        tau[i] = sign * tau0 * math.asinh(s[i] * _g_scalar(x[i]))
    return tau, x, beta


@numba.njit(cache=True)
def _film_root_from(s, a, x0, steps):
    """The root X of X tanh X = A asinh(S g(X)) of one node by the Newton steps of :func:`film_parameter`, started
    from ``x0`` where it lies inside the bracket (else from the usual start) and stopped at the first step below
    1e-13 (1 + X); 0 where A asinh S is not positive."""
    rhs0, x, lo, hi = _film_newton_start(s, a)
    if not rhs0 > 0.0:
        return 0.0
    if lo < x0 < hi:
        x = x0
    for _ in range(steps):
        x, lo, hi, small = _film_newton_step(x, lo, hi, s, a)
        if small:
            break
    return x


@numba.njit(cache=True)
def _secant_film_near_kernel(rises, log_eta, rise, u_s, h, tau0, conductivity, live, beta0, x0, secant_iterations,
                             steps):
    """τ [Pa] of :func:`_secant_film_kernel` at the wall rises ``rise`` [K] on the nodes ``live`` (0 elsewhere),
    started from the secant β0 [1/K] and film parameter X0 [-] converged at a nearby rise: each node iterated on its
    own, its secant β until it changes by at most 1e-10 β, its X until the Newton step is below 1e-13 (1 + X). The
    same fixed point as the lockstep kernel, to the tolerance of its secant iteration (not bit for bit)."""
    n = rise.size
    tau = np.zeros(n)
    sign = 1.0 if u_s >= 0.0 else -1.0
    for i in range(n):
        if not live[i]:
            continue
        log_eta_s, slope_beta = _table_at(rises, log_eta, i, rise[i])
        eta_s = math.exp(log_eta_s)
        log_eta_s = math.log(eta_s)
        s = eta_s * abs(u_s) / (tau0 * h[i])
        beta = beta0[i] if beta0[i] >= 0.0 else max(slope_beta, 0.0)
        x = x0[i]
        for _ in range(secant_iterations):
            x = _film_root_from(s, beta * abs(u_s) * h[i] * tau0 / (8.0 * conductivity), x, steps)
            centre = 2.0 * (x + math.log1p(math.exp(-2.0 * x)) - math.log(2.0)) / beta if beta > 0.0 else 0.0
            secant = beta
            if centre > 1e-6:
                eta_c = math.exp(_table_at(rises, log_eta, i, rise[i] + centre)[0])
                secant = (log_eta_s - math.log(eta_c)) / centre
            secant = max(secant, 0.0)
            converged = abs(secant - beta) <= 1e-10 * max(beta, 1e-300)
            beta = secant
            if converged:
                break
        x = _film_root_from(s, beta * abs(u_s) * h[i] * tau0 / (8.0 * conductivity), x, steps)
        tau[i] = sign * tau0 * math.asinh(s * _g_scalar(x))
    return tau


def film_shear_stress(eta_wall, u_s: float, h, tau0: float, beta, conductivity: float):
    """Thermal Couette shear stress (sign of u_s) and film parameter X of a film.

    The walls are at the temperature where η = ``eta_wall`` (module docstring, item 2).

    Parameters
    ----------
    eta_wall : array_like
        Viscosity at the wall temperature [Pa s].
    u_s : float
        Sliding velocity [m/s].
    h : array_like
        Film thickness [m].
    tau0 : float
        Eyring stress [Pa].
    beta : array_like
        Temperature–viscosity coefficient [1/K].
    conductivity : float
        Thermal conductivity of the oil [W/(m K)].

    Returns
    -------
    tuple of ndarray
        (τ [Pa], X [-]).
    """
    x = film_parameter(eta_wall, u_s, h, tau0, beta, conductivity)
    s = np.asarray(eta_wall, dtype=float) * abs(u_s) / (tau0 * np.asarray(h, dtype=float))
    return math.copysign(1.0, u_s) * tau0 * np.arcsinh(s * _g(x)), x


def film_centre_rise(x, beta, tau, u_s: float, h, conductivity: float) -> np.ndarray:
    """Temperature rise of the film centre above the walls: 2 ln cosh X / β; Crook's τ u_s h/(8k) where β = 0.

    Parameters
    ----------
    x : array_like
        Film parameter X [-].
    beta : array_like
        Temperature–viscosity coefficient [1/K].
    tau : array_like
        Shear stress [Pa].
    u_s : float
        Sliding velocity [m/s].
    h : array_like
        Film thickness [m].
    conductivity : float
        Thermal conductivity of the oil [W/(m K)].

    Returns
    -------
    ndarray
        The rise [K].
    """
    x, beta, tau, h = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (x, beta, tau, h)))
    with np.errstate(divide="ignore", invalid="ignore"):
        log_cosh = x + np.log1p(np.exp(-2.0 * x)) - math.log(2.0)
        thermal = 2.0 * log_cosh / beta
    crook = np.abs(tau * u_s) * h / (8.0 * conductivity)
    return np.where(beta > 0.0, thermal, crook)


SECANT_ITERATIONS = 30
"""Iterations of the secant β of :func:`film_with_secant_beta` (it converges to 1e-10 within a few)."""


def film_with_secant_beta(table: TemperatureTable, rise, u_s: float, h, tau0: float, conductivity: float):
    """Film traction at the wall rise ``rise`` [K] with the exponential law across the film fitted as the secant of
    the lubricant's ln η between the wall and the film centre: β = [ln η(T_s) − ln η(T_s + ΔT_c)]/ΔT_c with ΔT_c =
    2 ln cosh X/β (iterated from the tangent β at the wall). For small rises it is the tangent; for a hot film
    it follows β falling with temperature. Returns (τ, X, β)."""
    rise = np.asarray(rise, dtype=float)
    if table.log_eta.ndim == 2 and rise.ndim == 1 and rise.size == table.log_eta.shape[1]:
        h_nodes = np.array(np.broadcast_to(np.asarray(h, dtype=float), rise.shape))
        return _secant_film_kernel(np.asarray(table.rises, dtype=float), np.ascontiguousarray(table.log_eta), rise,
                                   float(u_s), h_nodes, float(tau0), float(conductivity), SECANT_ITERATIONS,
                                   NEWTON_STEPS)
    eta_s, beta = table.at(rise)
    log_eta_s = np.log(eta_s)
    beta = np.maximum(beta, 0.0)
    for _ in range(SECANT_ITERATIONS):
        tau, xpar = film_shear_stress(eta_s, u_s, h, tau0, beta, conductivity)
        with np.errstate(divide="ignore", invalid="ignore"):
            centre = np.where(beta > 0.0, 2.0 * (xpar + np.log1p(np.exp(-2.0 * xpar)) - math.log(2.0)) / beta, 0.0)
        hot = centre > 1e-6
        eta_c, _ = table.at(rise + centre)
        with np.errstate(divide="ignore", invalid="ignore"):
            secant = np.where(hot, (log_eta_s - np.log(eta_c)) / np.where(hot, centre, 1.0), beta)
        secant = np.maximum(secant, 0.0)
        done = np.all(np.abs(secant - beta) <= 1e-10 * np.maximum(beta, 1e-300))
        beta = secant
        if done:
            break
    tau, xpar = film_shear_stress(eta_s, u_s, h, tau0, beta, conductivity)
    return tau, xpar, beta


# ---------------------------------------------------------------------------------------------------------------
# The surfaces: Jaeger's moving heat source at high Péclet number, Blok's partition
# ---------------------------------------------------------------------------------------------------------------
@numba.njit(cache=True)
def _jaeger_kernel(x):
    """The matrix of :func:`jaeger_operator` for increasing nodes ``x`` [m], filled row by row over the segments
    ending at or before x_i (the rest is 0) [m^½]."""
    n = x.size
    out = np.zeros((n, n))
    for i in range(1, n):
        s1 = math.sqrt(max(x[i] - x[0], 0.0))
        for j in range(i):
            s0 = s1                                    # √(x_i − ξ_j), the s1 of segment j − 1
            s1 = math.sqrt(max(x[i] - x[j + 1], 0.0))
            d = (x[j + 1] - x[j]) / (s0 + s1)
            i1 = 2.0 / 3.0 * d * (2.0 * s0 + s1) / (s0 + s1)
            out[i, j] += 2.0 * d - i1
            out[i, j + 1] += i1
    return out


JAEGER_CACHE_SIZE = 8
"""Operators of the most recent distinct grids kept by :func:`jaeger_operator` (the grids of consecutive contacts
at one operating condition repeat) [-]."""
JAEGER_CACHE_BYTES = 64 * 2**20
"""Most memory the kept operators take together; an operator larger than this is computed but not kept [bytes]."""
_jaeger_cache: OrderedDict[bytes, np.ndarray] = OrderedDict()
_jaeger_lock = threading.Lock()


def jaeger_operator(x) -> np.ndarray:
    """Matrix J with (J q)_i = ∫_{x_0}^{x_i} q(ξ) (x_i − ξ)^(−1/2) dξ [m^½] for q piecewise linear on the nodes ``x``
    [m] (increasing, the direction of motion of both surfaces). Exact for piecewise-linear q; lower triangular.

    On a segment [ξ_j, ξ_j+1] ≤ x_i with s0 = √(x_i − ξ_j), s1 = √(x_i − ξ_j+1), d = s0 − s1 = Δ/(s0 + s1):
    ∫ (x_i − ξ)^(−½) dξ = 2d and ∫ (ξ − ξ_j)/Δ (x_i − ξ)^(−½) dξ = (2/3) d (2 s0 + s1)/(s0 + s1).

    The operators of the last :data:`JAEGER_CACHE_SIZE` distinct grids are kept (per process, within
    :data:`JAEGER_CACHE_BYTES`); the returned array is shared with that store and therefore read-only (arithmetic on
    it, e.g. ``jaeger_operator(x) / c``, gives a new array)."""
    x = np.ascontiguousarray(x, dtype=float)
    if x.ndim != 1 or x.size < 2 or not np.all(np.diff(x) > 0.0):
        raise InputError("x", f"{x.shape} nodes", "at least two strictly increasing nodes")
    key = x.tobytes()
    with _jaeger_lock:
        out = _jaeger_cache.get(key)
        if out is not None:
            _jaeger_cache.move_to_end(key)
            return out
    out = _jaeger_kernel(x)
    out.flags.writeable = False
    if out.nbytes <= JAEGER_CACHE_BYTES:
        with _jaeger_lock:
            _jaeger_cache[key] = out
            _jaeger_cache.move_to_end(key)
            while (len(_jaeger_cache) > JAEGER_CACHE_SIZE
                   or sum(v.nbytes for v in _jaeger_cache.values()) > JAEGER_CACHE_BYTES):
                _jaeger_cache.popitem(last=False)
    return out


def blok_denominator(u1: float, u2: float, properties: ThermalProperties) -> float:
    """√π (B_1 √u_1 + B_2 √u_2) [W/(m²·K)·m^½] for two bodies of the same material (Blok's partition)."""
    return math.sqrt(math.pi) * properties.effusivity * (math.sqrt(max(u1, 0.0)) + math.sqrt(max(u2, 0.0)))


def surface_temperature_rise(x, heat_flux, u1: float, u2: float, properties: ThermalProperties,
                             operator: np.ndarray | None = None) -> np.ndarray:
    """Flash temperature rise ΔT_s(x) of both surfaces (Blok's partition) for a heat flux generated on the nodes.

    Parameters
    ----------
    x : ndarray
        Nodes, increasing [m].
    heat_flux : ndarray
        Heat flux q(x) generated at the nodes [W/m²].
    u1 : float
        Velocity of surface 1, ≥ 0 [m/s].
    u2 : float
        Velocity of surface 2, ≥ 0, not both 0 [m/s].
    properties : ThermalProperties
        Thermal properties of the solids [SI].
    operator : ndarray, optional
        Precomputed Jaeger operator of ``x`` (:func:`jaeger_operator`) [-].

    Returns
    -------
    ndarray
        ΔT_s at the nodes [K].
    """
    if not (u1 >= 0.0 and u2 >= 0.0 and u1 + u2 > 0.0):
        raise InputError("surface velocities", (u1, u2), "u1, u2 >= 0 with u1 + u2 > 0 (|SR| <= 2)")
    op = jaeger_operator(x) if operator is None else operator
    return op @ np.asarray(heat_flux, dtype=float) / blok_denominator(u1, u2, properties)


# ---------------------------------------------------------------------------------------------------------------
# The coupled correction along a contact, and the planner's estimate at its centre
# ---------------------------------------------------------------------------------------------------------------
@dataclass
class ThermalTraction:
    """Outcome of :func:`thermal_couette_traction` on the nodes of a solve (SI).

    Parameters
    ----------
    shear_stress : ndarray
        Shear stress τ, 0 outside the liquid nodes [Pa].
    surface_rise : ndarray
        Flash temperature rise ΔT_s of the surfaces [K].
    film_centre_rise : ndarray
        Temperature rise of the film centre above the surfaces [K].
    iterations : int
        Newton iterations [-].
    converged : bool
        Whether the flash-temperature equation converged [-].
    change : float
        Final max |G| / (1 + max ΔT_s) of the flash-temperature equation [-].
    """

    shear_stress: np.ndarray
    surface_rise: np.ndarray
    film_centre_rise: np.ndarray
    iterations: int
    converged: bool
    change: float

    def summary(self) -> dict[str, Any]:
        """The scalar outcome, as recorded with a result.

        Returns
        -------
        dict
            ``max_surface_rise_k``, ``max_film_centre_rise_k``, ``max_film_temperature_rise_k`` [K], ``iterations``,
            ``converged``, ``relative_change``.
        """
        total = self.surface_rise + self.film_centre_rise
        return {"max_surface_rise_k": float(np.max(self.surface_rise, initial=0.0)),
                "max_film_centre_rise_k": float(np.max(self.film_centre_rise, initial=0.0)),
                "max_film_temperature_rise_k": float(np.max(total, initial=0.0)),
                "iterations": int(self.iterations), "converged": bool(self.converged),
                "relative_change": float(self.change)}


def thermal_couette_traction(x, film, table: TemperatureTable, liquid, u1: float, u2: float, tau0: float,
                             properties: ThermalProperties) -> ThermalTraction:
    """Couette shear stress with shear heating and flash temperature (module docstring) on the nodes of an isothermal
    solve.

    Newton's method on G(ΔT_s) = ΔT_s − J q(ΔT_s) = 0 with J the (lower-triangular) flash-temperature operator and
    q = |u_s τ(ΔT_s)|: the Jacobian I − J diag(dq/dΔT_s) is lower triangular (dq/dΔT_s by a forward difference of
    0.01 K, the film at ΔT_s + 0.01 K iterated node by node from the β and X converged at ΔT_s,
    :func:`_secant_film_near_kernel`), steps halved until |G| falls. Stops at max |G| ≤ 1e-9 (1 + max ΔT_s) K.

    Parameters
    ----------
    x : ndarray
        Nodes, increasing [m].
    film : ndarray
        Film thickness h at the nodes [m].
    table : TemperatureTable
        ln η(p, T0 + ΔT) of the nodes' pressures [-].
    liquid : ndarray of bool
        Nodes that carry a sheared liquid film (the heat sources) [-].
    u1 : float
        Velocity of surface 1 [m/s].
    u2 : float
        Velocity of surface 2 [m/s].
    tau0 : float
        Eyring stress [Pa].
    properties : ThermalProperties
        Thermal properties of oil and solids [SI].

    Returns
    -------
    ThermalTraction
        Shear stress, surface and film-centre temperature rises and the convergence record.
    """
    x = np.asarray(x, dtype=float)
    h = np.asarray(film, dtype=float)
    liquid = np.asarray(liquid, dtype=bool)
    u_s = u1 - u2
    k = properties.oil_conductivity
    zeros = np.zeros(x.size)
    if u_s == 0.0 or not liquid.any():
        return ThermalTraction(zeros, zeros.copy(), zeros.copy(), 0, True, 0.0)
    idx = np.flatnonzero(liquid)
    sub = slice(idx[0], idx[-1] + 1)       # heat sources lie from the first to the last liquid node
    xs, hs, live = x[sub], np.where(liquid, h, 1.0)[sub], liquid[sub]
    rises = np.asarray(table.rises, dtype=float)
    log_eta = np.ascontiguousarray(table.log_eta[:, sub], dtype=float)    # once, not per film evaluation
    tab = TemperatureTable(rises, log_eta)
    op = jaeger_operator(xs) / blok_denominator(u1, u2, properties)
    diagonal = np.arange(xs.size)

    def traction(rise):
        tau, xpar, beta_s = film_with_secant_beta(tab, rise, u_s, hs, tau0, k)
        return np.where(live, tau, 0.0), xpar, beta_s

    def residual(rise):
        tau, xpar, beta_s = traction(rise)
        return rise - op @ np.abs(tau * u_s), tau, xpar, beta_s

    rise = np.zeros(xs.size)
    g, tau, xpar, beta_s = residual(rise)
    norm = float(np.max(np.abs(g)))
    iterations, converged, step = 0, False, 0.01
    for iterations in range(1, FIXED_POINT_MAX_ITERATIONS + 1):
        if norm <= FIXED_POINT_TOLERANCE * (1.0 + float(np.max(rise))):
            converged = True
            break
        near = _secant_film_near_kernel(rises, log_eta, rise + step, float(u_s), hs, float(tau0), float(k), live,
                                        beta_s, xpar, SECANT_ITERATIONS, NEWTON_STEPS)
        dq = (np.abs(near * u_s) - np.abs(tau * u_s)) / step
        jacobian = np.multiply(op, dq[None, :])
        np.negative(jacobian, out=jacobian)
        jacobian[diagonal, diagonal] += 1.0                 # I − J diag(dq)
        delta = -solve_triangular(jacobian, g, lower=True, check_finite=False)
        factor = 1.0
        while True:
            trial = np.maximum(rise + factor * delta, 0.0)
            g_new, tau_new, xpar_new, beta_new = residual(trial)
            norm_new = float(np.max(np.abs(g_new)))
            if norm_new < norm or factor < 1e-6:
                break
            factor *= 0.5
        rise, g, tau, xpar, beta_s, norm = trial, g_new, tau_new, xpar_new, beta_new, norm_new
    change = norm / (1.0 + float(np.max(rise)))
    centre = np.where(live, film_centre_rise(xpar, beta_s, tau, u_s, hs, k), 0.0)
    full_tau, full_rise, full_centre = zeros.copy(), zeros.copy(), zeros.copy()
    full_tau[sub], full_centre[sub], full_rise[sub] = tau, centre, rise
    full_rise[idx[-1] + 1:] = rise[-1]     # behind the film: no more heating (cooling not modelled)
    return ThermalTraction(full_tau, full_rise, full_centre, iterations, converged, change)


def centre_estimate(table: TemperatureTable, h_central: float, half_width: float, u1: float, u2: float,
                    tau0: float, properties: ThermalProperties) -> dict[str, float]:
    """The planner's a-priori thermal estimate at the Hertz centre.

    The Couette stress with and without the thermal correction, with the flash temperature of a Hertzian
    (semi-elliptic) heat flux q0 √(1 − x²/a²), q0 = τ_c |u_s|, taken at its maximum (:data:`BLOK_MAX_COEFFICIENT`;
    conservative: it is the downstream peak), the film centre rise, and the Nahme number Na = β τ |u_s| h/k of the film
    at the inlet temperature.

    Parameters
    ----------
    table : TemperatureTable
        ln η(p_h, T0 + ΔT), one column [-].
    h_central : float
        Moes' central film thickness [m].
    half_width : float
        Hertz half width a [m].
    u1 : float
        Velocity of surface 1 [m/s].
    u2 : float
        Velocity of surface 2 [m/s].
    tau0 : float
        Eyring stress [Pa].
    properties : ThermalProperties
        Thermal properties [SI].

    Returns
    -------
    dict of str to float
        ``tau_isothermal_pa``, ``tau_thermal_pa`` [Pa], ``thermal_change`` = 1 − τ_thermal/τ_isothermal [-],
        ``flash_rise_k``, ``film_centre_rise_k`` [K], ``nahme_number`` [-].
    """
    u_s = u1 - u2
    eta_h, beta_h = (float(v[0]) for v in table.at(np.zeros(1)))
    tau_iso = tau0 * math.asinh(eta_h * abs(u_s) / (tau0 * h_central))
    if u_s == 0.0 or tau_iso == 0.0:
        return {"tau_isothermal_pa": tau_iso, "tau_thermal_pa": tau_iso, "thermal_change": 0.0, "flash_rise_k": 0.0,
                "film_centre_rise_k": 0.0, "nahme_number": 0.0}
    coefficient = BLOK_MAX_COEFFICIENT * math.sqrt(half_width) * math.sqrt(math.pi) / blok_denominator(u1, u2,
                                                                                                       properties)
    def film(flash):
        return film_with_secant_beta(table, np.full(1, flash), u_s, h_central, tau0, properties.oil_conductivity)

    def excess(flash):  # decreasing in the flash rise: one root in [0, C |u_s| τ_iso]
        return coefficient * abs(u_s) * abs(float(np.ravel(film(flash)[0])[0])) - flash

    upper = coefficient * abs(u_s) * tau_iso
    flash = upper
    if excess(upper) < 0.0:
        root = brent_root(excess, 0.0, upper, xtol=1e-9 * (1.0 + upper), rtol=1e-12)
        if not root.converged:
            raise SolverError(f"flash temperature of the planner's thermal estimate not converged after "
                              f"{root.iterations} Brent steps (last {root.root!r} K in [0, {upper!r}] K)")
        flash = root.root
    t, xpar, beta_s = film(flash)
    tau = abs(float(np.ravel(t)[0]))
    centre = float(np.ravel(film_centre_rise(xpar, beta_s, tau, u_s, h_central, properties.oil_conductivity))[0])
    return {"tau_isothermal_pa": tau_iso, "tau_thermal_pa": tau, "thermal_change": 1.0 - tau / tau_iso,
            "flash_rise_k": coefficient * tau * abs(u_s), "film_centre_rise_k": centre,
            "nahme_number": max(beta_h, 0.0) * tau_iso * abs(u_s) * h_central / properties.oil_conductivity}
