"""Mechanical (sliding friction) power loss of a gear mesh over one cycle (Li & Kahraman 2009, Eq. 10–11).

Given a loaded mesh cycle (:func:`efficiency.mesh_cycle.evaluate_mesh`), every loaded contact point q at mesh
position φ_m is a line contact with normal load W_q [N], load per unit length w'_q [N/m], normal equivalent radius
r_eq,q [m], rolling velocity u_r,q and sliding velocity u_s,q [m/s]. Its Hertz pressure is
p_h = √(w' E'/(2π r_eq)) (the inverse of W' = 2π r_eq p_h²/E', DESIGN §3) and its slide-to-roll ratio
SR = |u_s|/u_r. A friction model gives μ_q; then

    F_f = μ W                                   (Eq. 10)
    P(φ_m) = Σ_q μ_q W_q |u_s,q|,  η(φ_m) = 1 − P(φ_m)/(T_in ω_in)      (Eq. 11a,b)
    P = mean_m P(φ_m),  η = 1 − P/(T_in ω_in).

Friction models are callables ``mu(p_h, r_eq, u_r, sr, temperature, rq1, rq2) -> array`` in SI units (the
signature of :class:`surrogate.evaluate.FrictionSurrogate`); :class:`ConstantFriction`,
:class:`PublishedFriction` and :class:`EhlFriction` (the EHL solver at every point: slow, for accuracy checks)
adapt the other options.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Protocol

import numpy as np

from ehl_dataset.model.materials import STEEL, Material, reduced_modulus
from ehl_dataset.validation import InputError, check_range


class FrictionModel(Protocol):
    def __call__(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2) -> np.ndarray: ...


@dataclass(frozen=True)
class ConstantFriction:
    """A constant friction coefficient μ [-] at every contact point."""

    mu: float

    def __post_init__(self):
        check_range("mu", self.mu, 0.0, 1.0)

    def __call__(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2):
        return np.full(np.shape(p_h), self.mu)


@dataclass(frozen=True)
class PublishedFriction:
    """A published friction formula (``xu2007``, ``benedict_kelley``, ``iso14179``) from :mod:`surrogate.published`."""

    name: str
    lubricant: Any
    e_reduced: float = reduced_modulus(STEEL, STEEL)

    def __call__(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2):
        from surrogate.published import published_mu

        return published_mu(self.name, p_h, r_eq, u_r, sr, temperature, rq1, rq2, self.lubricant, self.e_reduced)


def _significant(values: np.ndarray, digits: int) -> np.ndarray:
    """``values`` rounded to ``digits`` significant digits (zeros stay zero)."""
    magnitude = np.where(values != 0.0, np.floor(np.log10(np.abs(np.where(values != 0.0, values, 1.0)))), 0.0)
    scale = 10.0 ** (digits - 1 - magnitude)
    return np.round(values * scale) / scale


@dataclass(frozen=True)
class EhlFriction:
    """The EHL solver itself at every contact point (slow: one solve per distinct loaded point; for accuracy checks).

    Points whose inputs agree to 10 significant digits (e.g. the slices of a spur gear with a uniform load across
    the face, equal up to round-off) are solved once, at the first of them. Points whose solve does not converge
    raise :class:`ehl_dataset.validation.SolverError` (no silent numbers); so does a rough point that needs the
    transient mixed solver while it is unavailable.
    After a call, ``last_stats()`` gives the number of solves and their time.
    """

    lubricant: Any
    level: str = "fast"
    effects: str = "auto"
    _stats: dict = field(default_factory=dict, compare=False, repr=False)

    def __call__(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2):
        from ehl_dataset.model.contact import ContactCase
        from ehl_dataset.solver import solve_contact
        from ehl_dataset.validation import SolverError

        started = time.perf_counter()
        arrays = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (p_h, r_eq, u_r, sr, temperature,
                                                                              rq1, rq2)))
        shape = arrays[0].shape
        rows = np.stack([a.reshape(-1) for a in arrays], axis=1)
        if rows.size:  # group points equal to 10 significant digits (round-off of the load distribution)
            _, first, inverse = np.unique(_significant(rows, 10), axis=0, return_index=True, return_inverse=True)
            unique = rows[first]
        else:
            unique, inverse = rows, np.zeros(0, int)
        mu_unique = np.empty(len(unique))
        iterations = 0
        for k, values in enumerate(unique):
            result = solve_contact(ContactCase(*(float(v) for v in values)), self.lubricant, self.level, self.effects)
            if not result.converged:
                index = np.unravel_index(int(np.flatnonzero(inverse.reshape(-1) == k)[0]), shape) if shape else ()
                raise SolverError(f"EHL solve did not converge at contact point {tuple(int(i) for i in index)} "
                                  f"(p_h {values[0] / 1e9:.3g} GPa, r_eq {values[1] * 1e3:.3g} mm, u_r "
                                  f"{values[2]:.3g} m/s, SR {values[3]:.3g}, level {self.level}): {result.message}")
            mu_unique[k] = result.mu
            iterations += int(getattr(result, "iterations", 0) or 0)
        self._stats.clear()
        self._stats.update(ehl_solves=len(unique), ehl_points=int(rows.shape[0]), ehl_iterations=iterations,
                           ehl_time_s=time.perf_counter() - started)
        return mu_unique[inverse.reshape(-1)].reshape(shape)

    def last_stats(self) -> dict:
        """``ehl_solves`` (distinct points solved), ``ehl_points``, ``ehl_iterations``, ``ehl_time_s`` of the last
        call."""
        return dict(self._stats)


@dataclass(frozen=True)
class PowerLossResult:
    """Friction power loss over a mesh cycle.

    power_loss : mean mechanical power loss P [W]; power_loss_instant : (M,) P(φ_m) [W]
    efficiency : mechanical efficiency η = 1 − P/(T_in ω_in) [-]; efficiency_instant : (M,) η(φ_m)
    input_power : T_in ω_in [W]
    mu : friction coefficient per contact point (shape of the mesh point arrays; NaN where not loaded)
    p_h : Hertz pressure per point [Pa] (0 where not loaded); sr : |u_s|/u_r per point [-]
    friction_model : a description of the model used; wall_time_s : evaluation time [s]
    """

    power_loss: float
    power_loss_instant: np.ndarray
    efficiency: float
    efficiency_instant: np.ndarray
    input_power: float
    mu: np.ndarray
    p_h: np.ndarray
    sr: np.ndarray
    friction_model: str
    wall_time_s: float
    extra: dict = field(default_factory=dict)


def contact_conditions(mesh, material1: Material = STEEL, material2: Material = STEEL) -> dict[str, np.ndarray]:
    """Hertz pressure p_h [Pa], r_eq [m], u_r [m/s] and SR = |u_s|/u_r [-] at every point of a mesh cycle.

    Points that carry no load get p_h = 0 (they dissipate nothing).
    """
    kin = mesh.kinematics
    e_red = reduced_modulus(material1, material2)
    loaded = mesh.loads > 0.0
    p_h = np.zeros(mesh.loads.shape)
    p_h[loaded] = np.sqrt(mesh.load_per_length[loaded] * e_red / (2.0 * math.pi * kin.r_eq_normal[loaded]))
    with np.errstate(divide="ignore", invalid="ignore"):
        sr = np.where(kin.u_r > 0.0, np.abs(kin.u_s) / kin.u_r, 0.0)
    return {"p_h": p_h, "r_eq": kin.r_eq_normal, "u_r": kin.u_r, "sr": sr, "loaded": loaded}


def mesh_power_loss(mesh, friction: FrictionModel | Callable, temperature: float, rq1: float, rq2: float,
                    material1: Material = STEEL, material2: Material = STEEL) -> PowerLossResult:
    """Mechanical power loss (paper Eq. 10–11) of a loaded mesh cycle with a friction model.

    ``temperature`` [K] oil inlet temperature; ``rq1``, ``rq2`` [m] RMS roughness of the two flanks. The friction
    model is called once, vectorised over all loaded points of all mesh positions.
    """
    started = time.perf_counter()
    check_range("temperature", temperature, 0.0, 1000.0, low_inclusive=False, unit="K")
    check_range("rq1", rq1, 0.0, 1e-4, unit="m")
    check_range("rq2", rq2, 0.0, 1e-4, unit="m")
    kin = mesh.kinematics
    if kin.omega1 <= 0.0:
        raise InputError("speed", kin.omega1, "> 0 rad/s for a power loss")
    cond = contact_conditions(mesh, material1, material2)
    loaded = cond["loaded"]
    if hasattr(friction, "for_mesh"):  # mesh-aware models (e.g. EHL on a grid in roll distance) bind to the mesh
        friction = friction.for_mesh(mesh, loaded, material1, material2)
    mu = np.full(mesh.loads.shape, np.nan)
    n = int(loaded.sum())
    mu_loaded = np.asarray(friction(cond["p_h"][loaded], cond["r_eq"][loaded], cond["u_r"][loaded],
                                    cond["sr"][loaded], np.full(n, temperature), np.full(n, rq1),
                                    np.full(n, rq2)), dtype=float)
    if mu_loaded.shape != (n,) or not np.all(np.isfinite(mu_loaded)) or np.any(mu_loaded < 0.0):
        raise InputError("friction model output", f"{mu_loaded!r:.80}", "finite μ ≥ 0 at every loaded point")
    mu[loaded] = mu_loaded
    dissipation = np.where(loaded, np.nan_to_num(mu) * mesh.loads * np.abs(kin.u_s), 0.0)
    instant = dissipation.sum(axis=(1, 2))
    input_power = mesh.torque * kin.omega1
    power = float(instant.mean())
    return PowerLossResult(
        power_loss=power, power_loss_instant=instant, efficiency=1.0 - power / input_power,
        efficiency_instant=1.0 - instant / input_power, input_power=input_power, mu=mu, p_h=cond["p_h"],
        sr=cond["sr"], friction_model=_describe(friction), wall_time_s=time.perf_counter() - started,
        extra=dict(friction.last_stats()) if hasattr(friction, "last_stats") else {},
    )


def _describe(friction) -> str:
    if isinstance(friction, ConstantFriction):
        return f"constant mu={friction.mu:g}"
    if isinstance(friction, PublishedFriction):
        return f"published {friction.name}"
    if isinstance(friction, EhlFriction):
        return f"EHL solver level={friction.level} effects={friction.effects}"
    if hasattr(friction, "describe"):
        return str(friction.describe())
    return type(friction).__name__
