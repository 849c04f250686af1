"""Result of one EHL contact solve (SI units). The dataset store writes :meth:`ContactResult.to_record`."""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

RECORD_UNITS: dict[str, str] = {
    "mu": "1",
    "mu_std": "1",
    "mu_sem": "1",
    "h_min": "m",
    "h_central": "m",
    "lambda_bar": "1",
    "asperity_load_share": "1",
    "p_max": "Pa",
    "iterations": "1",
    "converged": "bool",
    "wall_time": "s",
    "effects": "json",
    "level": "name",
    "dx": "m",
    "n_nodes": "1",
    "n_steps": "1",
}
"""Scalar outputs stored per factorial point and their units (also the HDF5 column names)."""


@dataclass
class ContactResult:
    """Outcome of an EHL line-contact solve; ``residuals`` make non-convergence visible.

    Parameters
    ----------
    mu : float
        Friction coefficient, the time average for transient runs [-].
    h_min : float
        Minimum film thickness [m].
    h_central : float
        Film thickness at x = 0 [m].
    p_max : float
        Largest pressure [Pa].
    converged : bool
        Whether the solve met its tolerances [-].
    iterations : int
        Iterations of the solver [-].
    wall_time : float
        Wall time of the solve [s].
    level : str
        Accuracy level name [-].
    effects : dict
        The plan that was simulated (:meth:`Effects.to_dict`) [-].
    mu_std : float
        Standard deviation of μ over the averaging window (0 for steady runs) [-].
    mu_sem : float
        Standard error of the time average of μ, autocorrelation-corrected (:mod:`ehl_dataset.solvers.time_average`;
        0 for steady runs) [-].
    lambda_bar : float
        Dowson–Higginson film over composite roughness (inf for smooth surfaces) [-].
    asperity_load_share : float
        Fraction of the load carried where asperities touch [-].
    residuals : dict of str to float
        Final residual norms (and ``history`` where kept) [-].
    message : str
        The solver's message (why it stopped, what did not converge) [-].
    x : ndarray, optional
        Nodes of the profiles [m].
    pressure : ndarray, optional
        Pressure at the nodes, at the last step [Pa].
    film : ndarray, optional
        Film thickness at the nodes, at the last step [m].
    extra : dict
        Model-specific records (grid, time steps, thermal correction, ...) [-].
    """

    mu: float
    h_min: float
    h_central: float
    p_max: float
    converged: bool
    iterations: int
    wall_time: float
    level: str
    effects: dict[str, Any]
    mu_std: float = 0.0
    mu_sem: float = 0.0
    lambda_bar: float = math.inf
    asperity_load_share: float = 0.0
    residuals: dict[str, float] = field(default_factory=dict)
    message: str = ""
    x: np.ndarray | None = field(default=None, repr=False)
    pressure: np.ndarray | None = field(default=None, repr=False)
    film: np.ndarray | None = field(default=None, repr=False)
    extra: dict[str, Any] = field(default_factory=dict)

    def to_record(self) -> dict[str, Any]:
        """Flat dict of the scalar outputs named as in :data:`RECORD_UNITS` (effects as a JSON string).

        Returns
        -------
        dict
            Output name to value, in the units of :data:`RECORD_UNITS`.
        """
        return {
            "mu": float(self.mu),
            "mu_std": float(self.mu_std),
            "mu_sem": float(self.mu_sem),
            "h_min": float(self.h_min),
            "h_central": float(self.h_central),
            "lambda_bar": float(self.lambda_bar),
            "asperity_load_share": float(self.asperity_load_share),
            "p_max": float(self.p_max),
            "iterations": int(self.iterations),
            "converged": bool(self.converged),
            "wall_time": float(self.wall_time),
            "effects": json.dumps(self.effects, sort_keys=True),
            "level": str(self.level),
            **self.grid_record(),
        }

    def to_dict(self) -> dict[str, Any]:
        """The result as one JSON-ready mapping in SI units, keys named with their unit: the schema of a contact
        result wherever one is printed or written (the ``contact solve`` command's JSON, studies, reports).

        Returns
        -------
        dict
            ``mu``, ``mu_std``, ``mu_sem`` [-]; ``h_min_m``, ``h_central_m`` [m]; ``p_max_pa`` [Pa]; ``lambda_bar``
            [-] (None for smooth surfaces, λ̄ = ∞); ``asperity_load_share`` [-]; ``converged``, ``iterations``,
            ``wall_time_s`` [s], ``level``, ``effects`` (the plan and its reasons), ``residuals``, ``message``;
            from the solver's record: ``model`` (``smooth`` unless a mixed model ran), ``closure``, ``route``,
            ``roughness_profile``, ``dx_m`` [m], ``n_nodes``, ``n_steps``, ``thermal``, ``micro_pressure`` (the
            film-law closures' pressure spread: ``form``, ``coefficient`` c, ``slope_rms`` Δq, ``std_pa`` σ_p [Pa])
            (None where not recorded).
        """
        extra = self.extra
        return {
            "mu": self.mu,
            "mu_std": self.mu_std,
            "mu_sem": self.mu_sem,
            "h_min_m": self.h_min,
            "h_central_m": self.h_central,
            "p_max_pa": self.p_max,
            "lambda_bar": self.lambda_bar if math.isfinite(self.lambda_bar) else None,
            "asperity_load_share": self.asperity_load_share,
            "converged": self.converged,
            "iterations": self.iterations,
            "wall_time_s": self.wall_time,
            "level": self.level,
            "effects": self.effects,
            "residuals": self.residuals,
            "message": self.message,
            "roughness_profile": extra.get("roughness_profile"),
            "model": extra.get("model", "smooth"),
            "closure": extra.get("closure"),
            "route": extra.get("route"),
            "dx_m": extra.get("dx_m"),
            "n_nodes": extra.get("n_nodes"),
            "n_steps": extra.get("n_steps"),
            "thermal": extra.get("thermal"),
            "micro_pressure": extra.get("micro_pressure"),
        }

    def grid_record(self) -> dict[str, Any]:
        """The discretisation a solve used, from ``extra``.

        Returns
        -------
        dict
            ``dx`` the uniform grid spacing of the deterministic model (NaN for the steady solvers' graded grids) [m],
            ``n_nodes`` the grid nodes (-1: not recorded), ``n_steps`` the time steps (0 for a steady solve, -1: not
            recorded).
        """
        steps = self.extra.get("n_steps")
        if steps is None:
            steps = -1 if self.effects.get("transient") else 0
        return {"dx": float(self.extra.get("dx_m", math.nan)), "n_nodes": int(self.extra.get("n_nodes", -1)),
                "n_steps": int(steps)}
