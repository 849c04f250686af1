"""Mechanical (sliding friction) power loss of a gear mesh over one cycle (Li & Kahraman 2009, Eq. 10–11).

Given a loaded mesh cycle (:func:`efficiency.mesh_cycle.evaluate_mesh`), every loaded contact point q at mesh position
φ_m is a line contact with normal load W_q [N], load per unit length w'_q [N/m], normal equivalent radius r_eq,q [m],
rolling velocity u_r,q and sliding velocity u_s,q [m/s]. Its Hertz pressure is p_h = √(w' E'/(2π r_eq)) (the inverse of
W' = 2π r_eq p_h²/E', docs/explanation/ehl-model.md) and its slide-to-roll ratio SR = |u_s|/u_r. A friction model gives
μ_q; then

    F_f = μ W                                   (Eq. 10)
    P(φ_m) = Σ_q μ_q W_q |u_s,q|,  η(φ_m) = 1 − P(φ_m)/(T_in ω_in)      (Eq. 11a,b)
    P = mean_m P(φ_m),  η = 1 − P/(T_in ω_in).

The friction models (callables ``mu(p_h, r_eq, u_r, sr, temperature, rq1, rq2) -> array`` in SI units) and the
constructor of the ``--friction`` option are in :mod:`efficiency.friction`.

Band of P. A friction model with a prediction interval (a coefficient file of format 2 or of the learned form:
``mu_interval`` and ``has_interval``, :class:`surrogate.evaluate.FrictionSurrogate`) gives [μ_low,q, μ_high,q] at
every contact point; the band of P is

    P_low = mean_m Σ_q μ_low,q W_q |u_s,q|,   P_high = mean_m Σ_q μ_high,q W_q |u_s,q|,

i.e. every contact point at the same end of its interval at once: the errors of a fitted surrogate are taken as fully
correlated across the mesh. That is the honest, conservative choice for a fit's model error, which is systematic
(neighbouring contacts of one mesh have nearly the same conditions, so the fit errs the same way at all of them);
independent errors would shrink the band by about √(number of points) and understate it. η's band follows from P's.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from ehl_dataset.model.materials import STEEL, Material, reduced_modulus
from ehl_dataset.validation import InputError, check_range

from .friction import FrictionModel, describe_friction

BAND_COVERAGE = 0.90
"""Nominal coverage of the μ intervals behind the band of P."""


@dataclass(frozen=True)
class PowerLossResult:
    """Friction power loss over a mesh cycle.

    Parameters
    ----------
    power_loss : float
        Mean mechanical power loss P [W].
    power_loss_instant : ndarray
        (M,) P(φ_m) [W].
    efficiency : float
        Mechanical efficiency η = 1 − P/(T_in ω_in) [-].
    efficiency_instant : ndarray
        (M,) η(φ_m) [-].
    input_power : float
        T_in ω_in [W].
    mu : ndarray
        Friction coefficient per contact point, NaN where not loaded [-].
    p_h : ndarray
        Hertz pressure per point, 0 where not loaded [Pa].
    sr : ndarray
        |u_s|/u_r per point [-].
    friction_model : str
        Description of the friction model used [-].
    wall_time_s : float
        Evaluation time [s].
    power_loss_band : tuple of float or None
        (P_low, P_high) from the friction model's prediction intervals, fully correlated over the mesh (module
        docstring); None when the model gives no interval [W].
    band_coverage : float or None
        Nominal coverage of the μ intervals behind ``power_loss_band`` [-].
    extra : dict
        Records of the friction model (solves, clipped inputs, ...) [-].
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
    power_loss_band: tuple[float, float] | None = None
    band_coverage: float | None = None

    @property
    def efficiency_band(self) -> tuple[float, float] | None:
        """(η_low, η_high) matching ``power_loss_band`` (η_low from P_high), or None [-]."""
        if self.power_loss_band is None:
            return None
        return 1.0 - self.power_loss_band[1] / self.input_power, 1.0 - self.power_loss_band[0] / self.input_power


def contact_conditions(mesh, material1: Material = STEEL, material2: Material = STEEL) -> dict[str, np.ndarray]:
    """Hertz pressure, equivalent radius, rolling velocity and slide-to-roll ratio at every point of a mesh cycle.

    Points that carry no load get p_h = 0 (they dissipate nothing).

    Parameters
    ----------
    mesh : MeshCycleResult
        The loaded mesh [-].
    material1 : Material
        Material of gear 1 [-].
    material2 : Material
        Material of gear 2 [-].

    Returns
    -------
    dict of str to ndarray
        ``p_h`` [Pa], ``r_eq`` [m], ``u_r`` [m/s], ``sr`` = |u_s|/u_r [-] and the boolean ``loaded``, shaped like the
        point arrays.
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
                    material1: Material = STEEL, material2: Material = STEEL,
                    band_coverage: float = BAND_COVERAGE) -> PowerLossResult:
    """Mechanical power loss (paper Eq. 10–11) of a loaded mesh cycle with a friction model.

    The friction model is called once, vectorised over all loaded points of all mesh positions.

    Parameters
    ----------
    mesh : MeshCycleResult
        The loaded mesh (:func:`efficiency.mesh_cycle.evaluate_mesh`) [-].
    friction : FrictionModel or callable
        μ(p_h, r_eq, u_r, sr, temperature, rq1, rq2) in SI (:func:`efficiency.friction.friction_from_spec`) [-].
    temperature : float
        Oil inlet temperature [K].
    rq1 : float
        RMS roughness of gear 1's flanks [m].
    rq2 : float
        RMS roughness of gear 2's flanks [m].
    material1 : Material
        Material of gear 1 [-].
    material2 : Material
        Material of gear 2 [-].
    band_coverage : float
        Nominal coverage of the μ intervals behind the band of P, for a model that has them [-].

    Returns
    -------
    PowerLossResult
        Mean and instantaneous loss and efficiency, μ, p_h and SR per point, and the band of P.
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
    args = (cond["p_h"][loaded], cond["r_eq"][loaded], cond["u_r"][loaded], cond["sr"][loaded],
            np.full(n, temperature), np.full(n, rq1), np.full(n, rq2))
    bounds = None
    if getattr(friction, "has_interval", False) and hasattr(friction, "mu_interval"):
        mu_loaded, low, high = friction.mu_interval(*args, alpha=1.0 - band_coverage)
        bounds = (np.asarray(low, dtype=float), np.asarray(high, dtype=float))
    else:
        mu_loaded = friction(*args)
    mu_loaded = np.asarray(mu_loaded, dtype=float)
    if mu_loaded.shape != (n,) or not np.all(np.isfinite(mu_loaded)) or np.any(mu_loaded < 0.0):
        raise InputError("friction model output", f"{mu_loaded!r:.80}", "finite μ ≥ 0 at every loaded point")
    mu[loaded] = mu_loaded
    work = np.where(loaded, mesh.loads * np.abs(kin.u_s), 0.0)
    instant = (np.nan_to_num(mu) * work).sum(axis=(1, 2))
    input_power = mesh.torque * kin.omega1
    power = float(instant.mean())
    band = None
    if bounds is not None:
        band = tuple(_cycle_mean(work, loaded, values) for values in bounds)
    return PowerLossResult(
        power_loss=power, power_loss_instant=instant, efficiency=1.0 - power / input_power,
        efficiency_instant=1.0 - instant / input_power, input_power=input_power, mu=mu, p_h=cond["p_h"],
        sr=cond["sr"], friction_model=describe_friction(friction, short=True),
        wall_time_s=time.perf_counter() - started,
        extra=dict(friction.last_stats()) if hasattr(friction, "last_stats") else {},
        power_loss_band=band, band_coverage=band_coverage if band is not None else None,
    )


def _cycle_mean(work: np.ndarray, loaded: np.ndarray, mu_loaded: np.ndarray) -> float:
    """mean_m Σ_q μ_q W_q |u_s,q| for μ given at the loaded points."""
    mu = np.zeros(work.shape)
    mu[loaded] = mu_loaded
    return float((mu * work).sum(axis=(1, 2)).mean())
