"""The design studies of Li & Kahraman 2009, §3: the design sweep (Fig. 3–5), the search for a design like D, and
the tooth-modification study (Fig. 6).

Every design of a :class:`~efficiency.feasibility.DesignSpace` that passes the feasibility screen
(:func:`~efficiency.feasibility.feasibility_masks`) is evaluated over one loaded mesh cycle
(:func:`~efficiency.mesh_cycle.evaluate_mesh`) at the study's operating point, and its mechanical power loss follows
from paper Eq. 10–11 (:func:`~efficiency.power_loss.mesh_power_loss`) with any friction model (a coefficient
file's :class:`surrogate.evaluate.FrictionSurrogate`, a published formula, a constant, the EHL solver; built from a
spec string by :func:`efficiency.friction.friction_from_spec`).

Tables are :class:`pandas.DataFrame` objects in SI units, one row per design (or per modification/torque), with the
unit in each column name:

``teeth``, ``normal_pressure_angle_deg``, ``helix_angle_deg``, ``working_depth``   the design (paper notation N, Φ,
                                                   Ψ, Λ_wd; angles in degrees as in the paper's tables)
``normal_module_m``, ``tip_diameter_m`` (d_o), ``root_diameter_m``, ``thickness_allowance_m``   geometry
``eps_alpha``, ``eps_beta``, ``eps_gamma``          transverse (profile, ε_p), overlap (face, ε_f), total contact ratio
``power_loss_w`` (P), ``power_loss_low_w`` and ``power_loss_high_w`` (the 90 % band of P from a friction surrogate's
prediction intervals, every contact point at the same end of its interval: :mod:`efficiency.power_loss`; NaN for a
model without intervals), ``efficiency`` (η = 1 − P/(T ω)), ``te_pp_m`` (peak-to-peak loaded TE), ``sigma_c_pa`` (max
Hertz pressure), ``sigma_b_pa`` (max root stress), ``mu_mean`` (load-weighted mean μ), ``converged``, ``error``
(empty unless the evaluation of this design raised), ``warning`` (the warnings the evaluation emitted, joined by " | ", e.g. a
friction surrogate extrapolating outside its fitted ranges; empty if none), ``wall_time_s``.

A design whose evaluation raises an :class:`~ehl_dataset.validation.InputError` or
:class:`~ehl_dataset.validation.SolverError` is kept in the table with NaN outputs and the message in ``error``;
a design whose load distribution did not converge keeps its numbers with ``converged`` False. Neither is ever
selected by :func:`find_design_like_d`.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, replace
from typing import Callable, Iterable, Mapping

import numpy as np
import pandas as pd

from ehl_dataset.validation import InputError, SolverError, check_range

from .feasibility import DesignSpace, FeasibilityLimits, feasibility_masks
from .geometry import GearPair
from .mesh_cycle import MeshOptions, evaluate_mesh
from .modifications import Modifications
from .power_loss import mesh_power_loss

DESIGN_COLUMNS = ("teeth", "normal_pressure_angle_deg", "helix_angle_deg", "working_depth")
GEOMETRY_COLUMNS = ("normal_module_m", "tip_diameter_m", "root_diameter_m", "thickness_allowance_m", "eps_alpha",
                    "eps_beta", "eps_gamma")
OUTPUT_COLUMNS = ("power_loss_w", "power_loss_low_w", "power_loss_high_w", "efficiency", "te_pp_m", "sigma_c_pa",
                  "sigma_b_pa", "mu_mean", "converged", "valid", "not_valid_because", "error", "warning", "wall_time_s")

SEARCH_CRITERIA = {
    "max_power_loss_w": "power_loss_w",
    "max_root_stress_pa": "sigma_b_pa",
    "max_contact_stress_pa": "sigma_c_pa",
    "max_transmission_error_m": "te_pp_m",
}
"""Keys of the design-D search limits (``PaperStudy.search_limits``, SI) → the table column each one bounds."""

MU_MAX = 1.0
"""Largest friction coefficient accepted from a friction model; anything above is an extrapolation artefact (steel on
steel in lubricated contact stays below the boundary value μ_d ≈ 0.1)."""

PAPER_SEARCH_LIMITS = {"max_power_loss_w": 300.0, "max_root_stress_pa": 235e6, "max_contact_stress_pa": 1.175e9,
                       "max_transmission_error_m": 0.25e-6}
"""Li & Kahraman 2009 §3: "P < 0.3 kW, σ_b < 235 MPa, σ_c < 1.175 GPa, and the peak-to-peak TE < 0.25 µm"."""


@dataclass(frozen=True)
class StudyPoint:
    """Operating point of a study (SI).

    Parameters
    ----------
    input_torque : float
        Input torque on gear 1 [N·m].
    input_speed : float
        Input angular speed [rad/s].
    oil_temperature : float
        Oil inlet temperature [K].
    rq1 : float
        RMS roughness of gear 1's flanks [m].
    rq2 : float
        RMS roughness of gear 2's flanks [m].
    modifications : Modifications
        Flank modifications [-].
    """

    input_torque: float
    input_speed: float
    oil_temperature: float
    rq1: float
    rq2: float
    modifications: Modifications = Modifications()

    def __post_init__(self):
        check_range("input_torque", self.input_torque, 0.0, 1e7, low_inclusive=False, unit="N·m")
        check_range("input_speed", self.input_speed, 0.0, 1e5, low_inclusive=False, unit="rad/s")
        check_range("oil_temperature", self.oil_temperature, 200.0, 600.0, unit="K")
        check_range("rq1", self.rq1, 0.0, 1e-4, unit="m")
        check_range("rq2", self.rq2, 0.0, 1e-4, unit="m")

    @classmethod
    def from_operating_point(cls, op) -> "StudyPoint":
        """The study point of a study file's ``[operating_point]``.

        Parameters
        ----------
        op : OperatingPoint
            The operating point (:class:`efficiency.design_io.OperatingPoint`) [-].

        Returns
        -------
        StudyPoint
            The point, its crowns as :class:`Modifications`.
        """
        return cls(op.input_torque, op.input_speed, op.oil_temperature, op.rq1, op.rq2,
                   Modifications(profile_crown=op.profile_crown, lead_crown=op.lead_crown))


# ---------------------------------------------------------------------- the feasible designs of a space
def feasible_designs(space: DesignSpace, limits: FeasibilityLimits = FeasibilityLimits(), *,
                     where: Mapping[str, float] | None = None, stride: int = 1, limit: int | None = None
                     ) -> pd.DataFrame:
    """The designs of ``space`` that pass the feasibility screen, with their geometry (one row per design).

    Order: Φ, Ψ, N, Λ_wd (C order of :meth:`DesignSpace.grid`).

    Parameters
    ----------
    space : DesignSpace
        The design space [-].
    limits : FeasibilityLimits
        Feasibility limits [-].
    where : Mapping of str to float, optional
        Fixed design columns, e.g. ``{"normal_pressure_angle_deg": 22.5, "helix_angle_deg": 20, "working_depth":
        2.286}`` (the line of paper Fig. 3a) [-].
    stride : int
        Keep every stride-th feasible design [-].
    limit : int, optional
        Keep the first ``limit`` designs after the stride [-].

    Returns
    -------
    pandas.DataFrame
        One row per design.
    """
    check_range("stride", stride, 1, 10**9)
    if limit is not None:
        check_range("limit", limit, 0, 10**9)
    pairs = space.pairs()
    feasible = feasibility_masks(pairs, limits)["feasible"]
    phi, psi, teeth, depth = space.grid()
    columns = {
        "teeth": teeth.astype(int), "normal_pressure_angle_deg": np.degrees(phi), "helix_angle_deg": np.degrees(psi),
        "working_depth": depth, "normal_module_m": np.broadcast_to(pairs.normal_module, phi.shape),
        "tip_diameter_m": np.broadcast_to(pairs.tip_diameters_m[0], phi.shape),
        "root_diameter_m": np.broadcast_to(pairs.root_diameters[0], phi.shape),
        "thickness_allowance_m": np.broadcast_to(pairs.thickness_allowance1, phi.shape),
        "eps_alpha": np.broadcast_to(pairs.contact_ratio, phi.shape),
        "eps_beta": np.broadcast_to(pairs.overlap_ratio, phi.shape),
        "eps_gamma": np.broadcast_to(pairs.total_contact_ratio, phi.shape),
    }
    table = pd.DataFrame({k: np.asarray(v)[feasible] for k, v in columns.items()})
    table["normal_pressure_angle_deg"] = table["normal_pressure_angle_deg"].round(9)
    table["helix_angle_deg"] = table["helix_angle_deg"].round(9)
    for key, value in (where or {}).items():
        if key not in DESIGN_COLUMNS:
            raise InputError("where", key, f"one of {list(DESIGN_COLUMNS)}")
        table = table[np.isclose(table[key].to_numpy(dtype=float), float(value), rtol=0.0, atol=1e-6)]
    table = table.iloc[::stride]
    if limit is not None:
        table = table.iloc[:limit]
    return table.reset_index(drop=True)


def design_pair(row: Mapping, space: DesignSpace) -> GearPair:
    """The scalar :class:`GearPair` of one row of :func:`feasible_designs` (the paper's parametrisation).

    Parameters
    ----------
    row : Mapping
        A row of :func:`feasible_designs` [-].
    space : DesignSpace
        The space it came from [-].

    Returns
    -------
    GearPair
        The design.
    """
    return GearPair.from_paper(int(row["teeth"]), math.radians(float(row["normal_pressure_angle_deg"])),
                               math.radians(float(row["helix_angle_deg"])), float(row["working_depth"]),
                               center_distance=space.center_distance, face_width=space.face_width,
                               root_fillet_coefficient=space.root_fillet_coefficient,
                               thickness_allowance=float(row["thickness_allowance_m"]))


# ---------------------------------------------------------------------- one design
def evaluate_design(pair: GearPair, friction: Callable, point: StudyPoint,
                    options: MeshOptions = MeshOptions()) -> dict:
    """P, η, TE p-p, σ_c, σ_b (SI) of one design at one operating point: the row of a study table.

    ``options.outputs`` is forced to {"te", "stresses"} (the studies need both). Errors are raised, not caught
    (:func:`design_sweep` records them per design).

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    friction : callable
        Friction model μ(p_h, r_eq, u_r, sr, temperature, rq1, rq2) [-].
    point : StudyPoint
        The operating point [-].
    options : MeshOptions
        Mesh resolution and models [-].

    Returns
    -------
    dict
        ``power_loss_w``, ``efficiency``, ``te_pp_m``, ``sigma_c_pa``, ``sigma_b_pa``, ``mu_mean``, ``converged``,
        ``valid`` (inside the validity of the load distribution and of a surrogate's fitted ranges,
        :mod:`efficiency.validity`), ``not_valid_because``, ``error``, ``warning``, ``wall_time_s``.
    """
    started = time.perf_counter()
    if options.outputs != frozenset({"te", "stresses"}):
        options = replace(options, outputs=frozenset({"te", "stresses"}))
    mesh = evaluate_mesh(pair, point.input_torque, point.input_speed, point.modifications, options)
    loss = mesh_power_loss(mesh, friction, point.oil_temperature, point.rq1, point.rq2,
                           options.material1, options.material2)
    mu_max = float(np.nanmax(loss.mu)) if np.any(np.isfinite(loss.mu)) else 0.0
    if mu_max > MU_MAX:
        at = np.unravel_index(int(np.nanargmax(loss.mu)), loss.mu.shape)
        raise SolverError(f"friction model gave mu = {mu_max:.4g} (> {MU_MAX:g}, not physical) at p_h = "
                          f"{loss.p_h[at]:.4g} Pa, SR = {loss.sr[at]:.4g}; a surrogate far outside its fitted ranges?")
    loads = mesh.loads
    mu_mean = float(np.nansum(np.nan_to_num(loss.mu) * loads) / loads.sum()) if loads.sum() > 0 else math.nan
    from .validity import friction_checks, mesh_checks, summarize

    valid, reasons = summarize(mesh_checks(mesh, pair) + friction_checks(
        loss, mesh, friction, point.oil_temperature, point.rq1, point.rq2,
        clip=getattr(friction, "clip_to_fitted_ranges", True)))
    summary = mesh.to_dict()
    return {
        "power_loss_w": loss.power_loss, "efficiency": loss.efficiency,
        "power_loss_low_w": loss.power_loss_band[0] if loss.power_loss_band else math.nan,
        "power_loss_high_w": loss.power_loss_band[1] if loss.power_loss_band else math.nan,
        **{key: summary[key] for key in ("te_pp_m", "sigma_c_pa", "sigma_b_pa")}, "mu_mean": mu_mean,
        "converged": bool(mesh.converged), "valid": valid, "not_valid_because": " | ".join(reasons), "error": "",
        "warning": "", "wall_time_s": time.perf_counter() - started,
    }


def _failed_row(err: Exception, started: float) -> dict:
    row = {name: math.nan for name in OUTPUT_COLUMNS}
    row.update(converged=False, valid=False, not_valid_because="", error=f"{type(err).__name__}: {err}", warning="",
               wall_time_s=time.perf_counter() - started)
    return row


def _evaluate_recording(pair, friction, point, options) -> dict:
    """:func:`evaluate_design` with its errors and warnings recorded in the row instead of raised / printed."""
    started = time.perf_counter()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            row = evaluate_design(pair, friction, point, options)
        except (InputError, SolverError) as err:
            row = _failed_row(err, started)
    row["warning"] = " | ".join(dict.fromkeys(f"{w.category.__name__}: {w.message}" for w in caught))
    return row


# ---------------------------------------------------------------------- the sweep (paper Fig. 3–5)
def design_sweep(space: DesignSpace, friction: Callable, point: StudyPoint,
                 limits: FeasibilityLimits = FeasibilityLimits(), options: MeshOptions = MeshOptions(), *,
                 where: Mapping[str, float] | None = None, stride: int = 1, limit: int | None = None,
                 progress: Callable[[int, int], None] | None = None) -> pd.DataFrame:
    """Evaluate every feasible design of ``space`` at ``point`` with ``friction``: the table of the paper's Fig. 3–5.

    One design's error does not stop the sweep: it is recorded in the row's ``error`` column, and its warnings in
    ``warning`` (module docstring).

    Parameters
    ----------
    space : DesignSpace
        The design space [-].
    friction : callable
        Friction model [-].
    point : StudyPoint
        The operating point [-].
    limits : FeasibilityLimits
        Feasibility limits [-].
    options : MeshOptions
        Mesh resolution and models [-].
    where : Mapping of str to float, optional
        Fixed design columns (:func:`feasible_designs`) [-].
    stride : int
        Keep every stride-th feasible design [-].
    limit : int, optional
        Keep the first ``limit`` designs after the stride [-].
    progress : callable, optional
        ``progress(done, total)``, called after each design [-].

    Returns
    -------
    pandas.DataFrame
        The design columns and the columns of :func:`evaluate_design`.
    """
    designs = feasible_designs(space, limits, where=where, stride=stride, limit=limit)
    rows = []
    total = len(designs)
    for i, record in enumerate(designs.to_dict("records")):
        rows.append(_evaluate_recording(design_pair(record, space), friction, point, options))
        if progress is not None:
            progress(i + 1, total)
    outputs = pd.DataFrame(rows, columns=list(OUTPUT_COLUMNS)) if rows else pd.DataFrame(
        {c: pd.Series(dtype=bool if c == "converged" else object if c in ("error", "warning") else float)
         for c in OUTPUT_COLUMNS})
    return pd.concat([designs, outputs], axis=1)


def no_error(table: pd.DataFrame) -> pd.Series:
    """True for rows whose ``error`` is empty (also when read back from CSV, where empty cells become NaN).

    Parameters
    ----------
    table : pandas.DataFrame
        A study table [-].

    Returns
    -------
    pandas.Series
        Boolean per row.
    """
    errors = table["error"]
    return errors.isna() | (errors.astype(str) == "")


def _check_table(table: pd.DataFrame, columns: Iterable[str]) -> None:
    missing = [c for c in columns if c not in table.columns]
    if missing:
        raise InputError("table", f"columns {list(table.columns)}", f"a study table with the columns {missing}")


def find_design_like_d(table: pd.DataFrame, limits: Mapping[str, float] = PAPER_SEARCH_LIMITS) -> pd.DataFrame:
    """The designs of a sweep table that meet every limit of the paper's design-D search, sorted by P.

    Paper §3: P < 0.3 kW, σ_b < 235 MPa, σ_c < 1.175 GPa, TE p-p < 0.25 µm. Only converged rows without error count.
    :func:`rank_by_limits` gives the same ratio for every row, which shows how near the closest designs come when
    nothing matches.

    Parameters
    ----------
    table : pandas.DataFrame
        A :func:`design_sweep` table [-].
    limits : Mapping of str to float
        Limits keyed as :data:`SEARCH_CRITERIA`, SI (units in the keys) [-].

    Returns
    -------
    pandas.DataFrame
        The matching rows with ``worst_ratio``, the largest value/limit over the criteria (< 1 for every match).
    """
    ranked = rank_by_limits(table, limits)
    return ranked[ranked["worst_ratio"] < 1.0].sort_values("power_loss_w").reset_index(drop=True)


def rank_by_limits(table: pd.DataFrame, limits: Mapping[str, float] = PAPER_SEARCH_LIMITS) -> pd.DataFrame:
    """Every valid (converged, no error) row ranked by how near it comes to meeting all limits.

    Parameters
    ----------
    table : pandas.DataFrame
        A :func:`design_sweep` table [-].
    limits : Mapping of str to float
        Limits keyed as :data:`SEARCH_CRITERIA`, SI [-].

    Returns
    -------
    pandas.DataFrame
        The rows with ``ratio_<column>`` = value / limit per criterion and ``worst_ratio`` = their maximum, sorted
        by ``worst_ratio``.
    """
    unknown = set(limits) - set(SEARCH_CRITERIA)
    if unknown:
        key = sorted(unknown)[0]
        raise InputError("limits", key, f"keys among {sorted(SEARCH_CRITERIA)}")
    if not limits:
        raise InputError("limits", dict(limits), "at least one of " + ", ".join(sorted(SEARCH_CRITERIA)))
    _check_table(table, [SEARCH_CRITERIA[k] for k in limits] + ["converged", "error"])
    valid = table[table["converged"].astype(bool) & no_error(table)].copy()
    ratios = []
    for key, value in limits.items():
        check_range(key, value, 0.0, math.inf, low_inclusive=False)
        name = "ratio_" + SEARCH_CRITERIA[key]
        valid[name] = valid[SEARCH_CRITERIA[key]].to_numpy(dtype=float) / float(value)
        ratios.append(name)
    valid["worst_ratio"] = valid[ratios].max(axis=1)
    return valid.sort_values("worst_ratio", kind="stable").reset_index(drop=True)


def trend_line(table: pd.DataFrame, vary: str, fixed: Mapping[str, float]) -> pd.DataFrame:
    """The rows of ``table`` with the ``fixed`` design values, sorted by ``vary``: the paper's "larger symbols" lines.

    Parameters
    ----------
    table : pandas.DataFrame
        A :func:`design_sweep` table [-].
    vary : str
        The design column that varies along the line [-].
    fixed : Mapping of str to float
        Fixed design values, e.g. Φ = 22.5°, Ψ = 20°, Λ_wd = 2.286 for paper Fig. 3a (column units: degrees) [-].

    Returns
    -------
    pandas.DataFrame
        The line's rows.
    """
    _check_table(table, list(fixed) + [vary])
    mask = np.ones(len(table), dtype=bool)
    for key, value in fixed.items():
        mask &= np.isclose(table[key].to_numpy(dtype=float), float(value), rtol=0.0, atol=1e-6)
    return table[mask].sort_values(vary).reset_index(drop=True)


# ---------------------------------------------------------------------- the modification study (paper Fig. 6)
def modification_study(pair: GearPair, friction: Callable, profile_crowns: Iterable[float],
                       lead_crowns: Iterable[float], torques: Iterable[float], point: StudyPoint,
                       options: MeshOptions = MeshOptions(), *,
                       progress: Callable[[int, int], None] | None = None) -> pd.DataFrame:
    """P, η, TE, σ_c, σ_b of ``pair`` for every profile crown × lead crown × input torque.

    Paper Fig. 6: M_P, M_L = 0–30 µm at T_in = 50, 250, 500 N·m on Design D. The other operating conditions (speed,
    temperature, roughness) come from ``point``; its modifications are replaced.

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    friction : callable
        Friction model [-].
    profile_crowns : iterable of float
        Profile crowns M_P [m].
    lead_crowns : iterable of float
        Lead crowns M_L [m].
    torques : iterable of float
        Input torques [N·m].
    point : StudyPoint
        The other operating conditions [-].
    options : MeshOptions
        Mesh resolution and models [-].
    progress : callable, optional
        ``progress(done, total)`` [-].

    Returns
    -------
    pandas.DataFrame
        ``torque_nm``, ``profile_crown_m``, ``lead_crown_m`` and the output columns of :func:`design_sweep`.
    """
    grid = [(float(t), float(mp), float(ml)) for t in torques for mp in profile_crowns for ml in lead_crowns]
    if not grid:
        raise InputError("modification grid", "empty", "at least one torque, profile crown and lead crown")
    rows = []
    for i, (torque, mp, ml) in enumerate(grid):
        here = StudyPoint(torque, point.input_speed, point.oil_temperature, point.rq1, point.rq2,
                          Modifications(profile_crown=mp, lead_crown=ml))
        row = _evaluate_recording(pair, friction, here, options)
        rows.append({"torque_nm": torque, "profile_crown_m": mp, "lead_crown_m": ml, **row})
        if progress is not None:
            progress(i + 1, len(grid))
    return pd.DataFrame(rows)
