"""What the friction model costs in accuracy and time inside the gear loss (docs/validation/gear.md).

The mesh power loss P = mean_m Σ_q μ_q W_q |u_s,q| (Li & Kahraman 2009, Eq. 11) needs μ at every loaded contact
point of a mesh cycle; the friction models are in :mod:`efficiency.friction`. This module

* compares friction models on one loaded mesh (:func:`compare_friction_models`): P, η, the load-weighted mean μ,
  the error in P against a reference model and the wall time of each;
* checks the pitch-point region (SR → 0, :func:`pitch_point_behaviour`): every model must return a finite μ there,
  and its contribution to P vanishes with |u_s|.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import Callable, Mapping

import numpy as np

from ehl_dataset.model.materials import STEEL, Material
from ehl_dataset.validation import InputError, SolverError

from .friction import describe_friction
from .power_loss import mesh_power_loss


# ---------------------------------------------------------------------- comparison on one mesh
@dataclass(frozen=True)
class FrictionModelRow:
    """One friction model on one loaded mesh.

    Parameters
    ----------
    name : str
        Name of the model [-].
    description : str
        One-line description (:func:`efficiency.friction.describe_friction`) [-].
    power_loss_w : float
        Mean power loss P [W].
    efficiency : float
        Mechanical efficiency η [-].
    mu_mean : float
        Load-weighted mean μ over the cycle [-].
    rel_error : float
        (P − P_ref)/P_ref against the reference model; NaN for the reference itself or when it failed [-].
    wall_time_s : float
        Time of the loss evaluation, friction model included [s].
    ehl_solves : int
        EHL solves the model made, if any [-].
    error : str
        Empty unless the model raised [-].
    """

    name: str
    description: str
    power_loss_w: float
    efficiency: float
    mu_mean: float
    rel_error: float
    wall_time_s: float
    ehl_solves: int
    error: str = ""

    def to_dict(self) -> dict:
        """The row as a JSON-serialisable dict (unit-suffixed keys as the fields).

        Returns
        -------
        dict
            Field names to values.
        """
        return dict(self.__dict__)


def load_weighted_mu(result, mesh) -> float:
    """Load-weighted mean friction coefficient Σ μ W / Σ W over the loaded points of the cycle.

    Parameters
    ----------
    result : PowerLossResult
        The power loss with its μ per point [-].
    mesh : MeshCycleResult
        The loaded mesh [-].

    Returns
    -------
    float
        The mean μ [-].
    """
    loaded = mesh.loads > 0.0
    return float(np.sum(result.mu[loaded] * mesh.loads[loaded]) / np.sum(mesh.loads[loaded]))


def compare_friction_models(mesh, models: Mapping[str, Callable], temperature: float, rq1: float, rq2: float,
                            reference: str, material1: Material = STEEL, material2: Material = STEEL
                            ) -> list[FrictionModelRow]:
    """Power loss with each friction model on the same loaded mesh, its error against ``models[reference]`` and its
    wall time.

    A model that raises :class:`SolverError` or :class:`InputError` gets a row with NaN numbers and the message (never
    a silent number).

    Parameters
    ----------
    mesh : MeshCycleResult
        The loaded mesh [-].
    models : Mapping of str to callable
        Friction models by name [-].
    temperature : float
        Oil inlet temperature [K].
    rq1 : float
        RMS roughness of gear 1's flanks [m].
    rq2 : float
        RMS roughness of gear 2's flanks [m].
    reference : str
        Name of the reference model in ``models`` [-].
    material1 : Material
        Material of gear 1 [-].
    material2 : Material
        Material of gear 2 [-].

    Returns
    -------
    list of FrictionModelRow
        One row per model, in the order of ``models``.
    """
    if reference not in models:
        raise InputError("reference", reference, f"one of {list(models)}")
    outcomes = {}
    for name, friction in models.items():
        started = time.perf_counter()
        try:
            result = mesh_power_loss(mesh, friction, temperature, rq1, rq2, material1, material2)
            outcomes[name] = (result, time.perf_counter() - started, "")
        except (SolverError, InputError) as err:
            outcomes[name] = (None, time.perf_counter() - started, f"{type(err).__name__}: {err}")
    ref = outcomes[reference][0]
    rows = []
    for name, (result, wall, error) in outcomes.items():
        if result is None:
            rows.append(FrictionModelRow(name, describe_friction(models[name]), math.nan, math.nan, math.nan, math.nan,
                                         wall, 0, error))
            continue
        rel = (result.power_loss / ref.power_loss - 1.0) if (ref is not None and name != reference) else math.nan
        rows.append(FrictionModelRow(name, result.friction_model, result.power_loss, result.efficiency,
                                     load_weighted_mu(result, mesh), rel, wall,
                                     int(result.extra.get("ehl_solves", 0))))
    return rows


# ---------------------------------------------------------------------- the pitch point
def pitch_point_behaviour(friction: Callable, p_h: float, r_eq: float, u_r: float, temperature: float, rq1: float,
                          rq2: float, sr_values=(0.0, 1e-4, 1e-3, 1e-2, 0.05)) -> dict:
    """μ of a pointwise friction model as SR → 0 at a fixed contact, and the friction power per unit normal load
    μ |u_s| = μ SR u_r that it implies.

    Parameters
    ----------
    friction : callable
        μ(p_h, r_eq, u_r, sr, temperature, rq1, rq2) in SI [-].
    p_h : float
        Hertz pressure [Pa].
    r_eq : float
        Equivalent radius of curvature [m].
    u_r : float
        Rolling velocity [m/s].
    temperature : float
        Oil inlet temperature [K].
    rq1 : float
        RMS roughness of surface 1 [m].
    rq2 : float
        RMS roughness of surface 2 [m].
    sr_values : sequence of float
        Slide-to-roll ratios evaluated [-].

    Returns
    -------
    dict
        ``sr`` [-], ``mu`` [-], ``power_per_load_w_per_n`` [W/N] (arrays over ``sr_values``) and ``finite`` (μ finite
        and ≥ 0 everywhere).
    """
    sr = np.asarray(sr_values, dtype=float)
    n = sr.size
    mu = np.asarray(friction(np.full(n, p_h), np.full(n, r_eq), np.full(n, u_r), sr, np.full(n, temperature),
                             np.full(n, rq1), np.full(n, rq2)), dtype=float)
    return {"sr": sr, "mu": mu, "power_per_load_w_per_n": mu * sr * u_r,
            "finite": bool(np.all(np.isfinite(mu)) and np.all(mu >= 0.0))}


def pitch_region_share(result, mesh, sr_max: float = 0.02) -> float:
    """Share of the cycle's friction energy dissipated at points with SR ≤ ``sr_max`` (the pitch-point region).

    Parameters
    ----------
    result : PowerLossResult
        The power loss with μ and SR per point [-].
    mesh : MeshCycleResult
        The loaded mesh [-].
    sr_max : float
        Largest slide-to-roll ratio of the region [-].

    Returns
    -------
    float
        The share, between 0 and 1 [-].
    """
    loaded = mesh.loads > 0.0
    dissipation = np.where(loaded, np.nan_to_num(result.mu) * mesh.loads * np.abs(mesh.kinematics.u_s), 0.0)
    total = dissipation.sum()
    near = dissipation[loaded & (result.sr <= sr_max)].sum()
    return float(near / total) if total > 0.0 else 0.0
