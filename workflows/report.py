"""The figures gear engineers expect, computed and drawn (``gearloss report ...``, docs/how-to/studies-and-reports.md).

* :func:`efficiency_map` — η and P of one design over input torque × speed, cells outside the models' validity
  hatched (:mod:`efficiency.validity`); with a friction model that has prediction intervals, the 90 % band of P and
  η of every cell (:mod:`efficiency.power_loss`: fully correlated over the mesh) and a panel of its width;
* :func:`mesh_cycle_loss` — the instantaneous friction power loss P(φ) over one mesh cycle and the cycle-mean loss
  along the line of action (with μ and SR there), for the fitted coefficients and published formulas;
* :func:`study_sweep` and :func:`study_modifications` — the paper's design sweep (Fig. 3–5) and modification study
  (Fig. 6) with the project's fitted coefficients, the published formulas drawn for comparison.

Each ``*_figure`` function writes one PNG (matplotlib, Agg) whose footer names the command that made it and the
package and EHL solver versions (:func:`provenance`); the compute functions return plain tables (SI units).
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

FIG3_LINE = {"normal_pressure_angle_deg": 22.5, "helix_angle_deg": 20.0, "working_depth": 2.286}
"""Paper Fig. 3a-c: the designs along N (and so m, d_o) with these fixed."""
FIG4_LINES = {
    "normal_pressure_angle_deg": {"teeth": 30, "helix_angle_deg": 20.0, "working_depth": 2.286},
    "helix_angle_deg": {"teeth": 30, "normal_pressure_angle_deg": 22.5, "working_depth": 2.286},
    "working_depth": {"teeth": 30, "normal_pressure_angle_deg": 22.5, "helix_angle_deg": 20.0},
}
"""Paper Fig. 4a-c: the "sole influence" lines of Φ, Ψ, Λ_wd."""
STYLES = ("-", "--", ":", "-.")


def provenance(command: str, note: str = "") -> str:
    """The footer of every figure: the command, the package and EHL solver versions, and ``note``.

    Parameters
    ----------
    command : str
        The command that made the figure [-].
    note : str
        Extra text, e.g. the solver version of a coefficient file's data [-].

    Returns
    -------
    str
        The footer.
    """
    return f"{command}\n{versions()}" + (f"; {note}" if note else "")


def versions() -> str:
    from ehl_dataset.dataset.store import package_version
    from ehl_dataset.solver import SOLVER_VERSION

    return f"gearloss {package_version()}, EHL solver {SOLVER_VERSION}"


def coefficients_note(frictions: dict[str, Any]) -> str:
    """Which EHL solver version and level computed the data of each coefficient file among ``frictions``."""
    notes = []
    for name, friction in frictions.items():
        source = getattr(getattr(friction, "coefficients", None), "document", {}).get("source", {})
        if source:
            notes.append(f"{name} fitted on {source.get('factorial', '?')} data of EHL solver "
                         f"{source.get('solver_version', '?')} at the {source.get('accuracy_level', '?')} level")
    return "; ".join(notes)


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path, command: str, note: str = "") -> str:
    fig.text(0.005, 0.003, provenance(command, note), fontsize=7, color="0.35", ha="left", va="bottom",
             family="monospace")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110, metadata={"Description": command, "Software": versions(), "Comment": note})
    _pyplot().close(fig)
    return str(path)


def _evaluate(pair, friction, point, options) -> dict:
    """:func:`efficiency.studies.evaluate_design` with its errors kept in the row (NaN outputs, not valid)."""
    from ehl_dataset.validation import InputError, SolverError
    from efficiency.studies import evaluate_design

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            return evaluate_design(pair, friction, point, options)
        except (InputError, SolverError) as err:
            return {"power_loss_w": math.nan, "efficiency": math.nan, "converged": False, "valid": False,
                    "not_valid_because": f"{type(err).__name__}: {err}"}


# ---------------------------------------------------------------------- efficiency map
NO_BAND_NOTE = "no band: the friction model has no prediction interval"
"""The efficiency map's note for a friction model without μ intervals (a format-1 file, a published formula)."""


@dataclass
class EfficiencyMap:
    """η and P over torque × speed.

    Parameters
    ----------
    design : str
        Design name [-].
    friction : str
        Friction model name [-].
    torque_nm : ndarray
        (T,) input torques [N·m].
    speed_rpm : ndarray
        (N,) input speeds [rpm].
    efficiency : ndarray
        (T, N) mechanical efficiency η [-].
    power_loss_w : ndarray
        (T, N) friction power loss [W].
    valid : ndarray of bool
        (T, N) whether each cell lies inside the models' validity [-].
    converged : ndarray of bool
        (T, N) whether each load distribution converged [-].
    reasons : list of str
        The distinct reasons of the cells that are not valid [-].
    wall_time_s : float
        Evaluation time [s].
    power_loss_low_w : ndarray or None
        (T, N) lower end of the band of P from the friction model's μ prediction intervals
        (:mod:`efficiency.power_loss`: every contact point at the same end of its interval); None when the model
        has no interval [W].
    power_loss_high_w : ndarray or None
        (T, N) upper end of that band [W].
    band_coverage : float or None
        Nominal coverage of the μ intervals behind the band (0.9); None without a band [-].
    """

    design: str
    friction: str
    torque_nm: np.ndarray
    speed_rpm: np.ndarray
    efficiency: np.ndarray
    power_loss_w: np.ndarray
    valid: np.ndarray
    converged: np.ndarray
    reasons: list[str] = field(default_factory=list)
    wall_time_s: float = 0.0
    power_loss_low_w: np.ndarray | None = None
    power_loss_high_w: np.ndarray | None = None
    band_coverage: float | None = None

    @property
    def has_band(self) -> bool:
        """Whether the map carries a band of P and η (a friction model with prediction intervals) [-]."""
        return self.power_loss_low_w is not None

    @property
    def input_power_w(self) -> np.ndarray:
        """(T, N) input power T ω of every cell [W]."""
        return self.torque_nm[:, None] * self.speed_rpm[None, :] * (math.pi / 30.0)

    @property
    def efficiency_low(self) -> np.ndarray | None:
        """(T, N) lower end of the band of η, 1 − P_high/(T ω); None without a band [-]."""
        return None if self.power_loss_high_w is None else 1.0 - self.power_loss_high_w / self.input_power_w

    @property
    def efficiency_high(self) -> np.ndarray | None:
        """(T, N) upper end of the band of η, 1 − P_low/(T ω); None without a band [-]."""
        return None if self.power_loss_low_w is None else 1.0 - self.power_loss_low_w / self.input_power_w

    @property
    def band_note(self) -> str:
        """What the band is, or why there is none (the figure's legend and the JSON's ``band_note``) [-]."""
        if not self.has_band:
            return NO_BAND_NOTE
        return (f"{self.band_coverage * 100:.0f} % prediction band of the friction surrogate, fully correlated over "
                "the mesh (every contact point at the same end of its μ interval)")

    def to_dict(self) -> dict[str, Any]:
        """The map as a JSON-ready dict (arrays as arrays; ``friction_model``, ``not_valid_reasons`` as named there).

        Returns
        -------
        dict
            The fields, units in the key names; ``power_loss_low_w``, ``power_loss_high_w``, ``efficiency_low``,
            ``efficiency_high`` per cell (None without a band), ``band_coverage`` and ``band_note``.
        """
        return {"design": self.design, "friction_model": self.friction, "torque_nm": self.torque_nm,
                "speed_rpm": self.speed_rpm, "efficiency": self.efficiency, "power_loss_w": self.power_loss_w,
                "power_loss_low_w": self.power_loss_low_w, "power_loss_high_w": self.power_loss_high_w,
                "efficiency_low": self.efficiency_low, "efficiency_high": self.efficiency_high,
                "band_coverage": self.band_coverage, "band_note": self.band_note,
                "valid": self.valid, "converged": self.converged, "not_valid_reasons": self.reasons,
                "wall_time_s": self.wall_time_s}

    def to_table(self):
        """One row per cell (torque-major), SI columns: the table ``report efficiency-map --table`` writes.

        Returns
        -------
        pandas.DataFrame
            ``torque_nm``, ``speed_rpm``, ``input_power_w``, ``power_loss_w``, ``power_loss_low_w``,
            ``power_loss_high_w``, ``efficiency``, ``efficiency_low``, ``efficiency_high`` (the band columns NaN
            without a band), ``valid``, ``converged``.
        """
        import pandas as pd

        torque, speed = np.meshgrid(self.torque_nm, self.speed_rpm, indexing="ij")
        nan = np.full(self.power_loss_w.shape, np.nan)
        columns = {"torque_nm": torque, "speed_rpm": speed, "input_power_w": self.input_power_w,
                   "power_loss_w": self.power_loss_w,
                   "power_loss_low_w": nan if self.power_loss_low_w is None else self.power_loss_low_w,
                   "power_loss_high_w": nan if self.power_loss_high_w is None else self.power_loss_high_w,
                   "efficiency": self.efficiency,
                   "efficiency_low": nan if self.efficiency_low is None else self.efficiency_low,
                   "efficiency_high": nan if self.efficiency_high is None else self.efficiency_high,
                   "valid": self.valid, "converged": self.converged}
        return pd.DataFrame({k: np.ravel(v) for k, v in columns.items()})


def efficiency_map(pair, friction, torques_nm, speeds_rpm, point, options, *, design: str = "",
                   friction_name: str = "") -> EfficiencyMap:
    """Evaluate ``pair`` at every torque × speed, the other conditions those of the study point ``point``.

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    friction : callable
        Friction model [-].
    torques_nm : array_like
        Input torques [N·m].
    speeds_rpm : array_like
        Input speeds [rpm].
    point : StudyPoint
        The other operating conditions (oil temperature, roughness, modifications) [-].
    options : MeshOptions
        Mesh resolution and models [-].
    design : str
        Design name shown in the figure [-].
    friction_name : str
        Friction model name shown in the figure [-].

    Returns
    -------
    EfficiencyMap
        η and P on the torque × speed grid with the validity of each cell and, for a friction model with
        prediction intervals (``has_interval``), the band of P of every cell (:mod:`efficiency.power_loss`: the
        90 % μ intervals taken fully correlated over the mesh).
    """
    from efficiency.power_loss import BAND_COVERAGE
    from efficiency.studies import StudyPoint

    started = time.perf_counter()
    torques, speeds = np.asarray(torques_nm, dtype=float), np.asarray(speeds_rpm, dtype=float)
    shape = (len(torques), len(speeds))
    eff, loss = np.full(shape, np.nan), np.full(shape, np.nan)
    low, high = np.full(shape, np.nan), np.full(shape, np.nan)
    valid, converged = np.zeros(shape, dtype=bool), np.zeros(shape, dtype=bool)
    reasons: dict[str, None] = {}
    for i, torque in enumerate(torques):
        for j, speed in enumerate(speeds):
            here = StudyPoint(float(torque), float(speed) * math.pi / 30.0, point.oil_temperature, point.rq1,
                              point.rq2, point.modifications)
            row = _evaluate(pair, friction, here, options)
            eff[i, j], loss[i, j] = row["efficiency"], row["power_loss_w"]
            low[i, j], high[i, j] = row.get("power_loss_low_w", math.nan), row.get("power_loss_high_w", math.nan)
            valid[i, j], converged[i, j] = bool(row["valid"]), bool(row["converged"])
            for reason in filter(None, str(row.get("not_valid_because", "")).split(" | ")):
                reasons[_reason_kind(reason)] = None
    band = bool(getattr(friction, "has_interval", False))
    return EfficiencyMap(design, friction_name, torques, speeds, eff, loss, valid, converged, list(reasons),
                         time.perf_counter() - started, power_loss_low_w=low if band else None,
                         power_loss_high_w=high if band else None, band_coverage=BAND_COVERAGE if band else None)


def _reason_kind(reason: str) -> str:
    """A reason without its numbers (``surrogate inputs clipped ...; they carry 20.1 % ...`` → its first words)."""
    for key, text in (("contact pressure", "σ_c above 0.6 × flank hardness"),
                      ("root stress", "σ_b above the static bending strength"),
                      ("normal approach", "deflection above 5 % of m_n"),
                      ("surrogate inputs", "more than 10 % of the loss at inputs clipped to the fitted ranges")):
        if key in reason:
            return text
    return reason.split(":")[0]


def efficiency_map_figure(result: EfficiencyMap, path, command: str, study_point: tuple[float, float] | None,
                          note: str = "") -> str:
    """Draw η and P over torque × speed (contours, cells outside the validity marked) and, for a map with a band,
    the band's width, and save the figure.

    The third panel (maps with a band only) fills the width of the band of η, η_high − η_low, in percentage points,
    with contour lines of the relative width of the band of P, (P_high − P_low)/P in per cent; its legend says what
    the band is (:attr:`EfficiencyMap.band_note`). A map without a band says so in its title.

    Parameters
    ----------
    result : EfficiencyMap
        The map [-].
    path : str or Path
        The PNG to write [-].
    command : str
        The command that made the figure, printed in its footer (:func:`provenance`) [-].
    study_point : tuple of float, optional
        (torque in N·m, speed in rpm) of the study's operating point, marked on the map [-].
    note : str
        Extra footer text [-].

    Returns
    -------
    str
        The path written.
    """
    import textwrap

    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    plt = _pyplot()
    panels = [(result.efficiency * 100, "mechanical efficiency η [%]", "%.2f", "viridis"),
              (result.power_loss_w / 1e3, "friction power loss P [kW]", "%.2f", "viridis")]
    if result.has_band:
        width = f"width of the {result.band_coverage * 100:.0f} % band of η [percentage points]"
        panels.append(((result.efficiency_high - result.efficiency_low) * 100, width, "%.3f", "magma_r"))
    fig, axes = plt.subplots(1, len(panels), figsize=(6.5 * len(panels), 6.3 if result.has_band else 5.4))
    t, n = result.torque_nm, result.speed_rpm
    contoured = len(t) > 1 and len(n) > 1
    for ax, (values, label, fmt, cmap) in zip(axes, panels):
        finite = np.isfinite(values)
        if finite.sum() >= 4 and contoured:
            filled = ax.contourf(n, t, np.ma.masked_invalid(values), levels=14, cmap=cmap)
            if label.startswith("width"):
                _relative_band_lines(ax, result)
            else:
                lines = ax.contour(n, t, np.ma.masked_invalid(values), levels=filled.levels[::2], colors="white",
                                   linewidths=0.6)
                ax.clabel(lines, fmt=fmt, fontsize=7)
            fig.colorbar(filled, ax=ax, label=label)
        else:
            mesh = ax.pcolormesh(_cell_edges(n), _cell_edges(t), np.ma.masked_invalid(values), shading="flat",
                                 cmap=cmap)
            fig.colorbar(mesh, ax=ax, label=label)
            if label.startswith("width"):
                _relative_band_labels(ax, result)
        bad = ~result.valid
        if bad.any():
            if contoured:
                ax.contourf(n, t, bad.astype(float), levels=[0.5, 1.5], colors="none", hatches=["///"])
            grid_n, grid_t = np.meshgrid(n, t)
            ax.plot(grid_n[bad], grid_t[bad], "x", color="0.15", ms=4, label="outside validity (x, hatched)")
        ax.scatter(*np.meshgrid(n, t), s=3, color="k", alpha=0.3)
        if study_point is not None:
            ax.plot(study_point[1], study_point[0], "r*", ms=12, label="study operating point")
        ax.set_xlabel("input speed [rpm]")
        ax.set_ylabel("input torque [N·m]")
        ax.set_title(label, fontsize=10)
        handles, labels = ax.get_legend_handles_labels()
        if label.startswith("width"):
            relative = _relative_band(result)
            handles += [Patch(facecolor=plt.get_cmap(cmap)(0.6), label=textwrap.fill(result.band_note, 70)),
                        Line2D([], [], color="0.5", lw=0.8, label=f"{'lines' if contoured else 'cell labels'}: "
                               f"(P_high − P_low)/P [%], {_finite_range(relative, '%.1f')} % over the map")]
            ax.legend(handles=handles, loc="upper center", bbox_to_anchor=(0.5, -0.13), fontsize=7.5, ncol=1)
        else:
            ax.legend(handles=handles, labels=labels, loc="upper right", fontsize=8)
    hatched = "; ".join(result.reasons) if result.reasons else "every cell inside the validity"
    band = "" if result.has_band else f"\n{result.band_note}"
    fig.suptitle(f"Efficiency map of design {result.design}, friction: {result.friction}\nhatched: {hatched}{band}",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    return _save(fig, path, command, note)


def _cell_edges(centres: np.ndarray) -> np.ndarray:
    """Edges of the cells around sorted ``centres`` (midpoints; ±5 % around a single value) for pcolormesh."""
    centres = np.asarray(centres, dtype=float)
    if centres.size == 1:
        half = 0.05 * abs(centres[0]) or 0.5
        return np.array([centres[0] - half, centres[0] + half])
    mid = 0.5 * (centres[1:] + centres[:-1])
    return np.concatenate([[2 * centres[0] - mid[0]], mid, [2 * centres[-1] - mid[-1]]])


def _finite_range(values: np.ndarray, fmt: str) -> str:
    """``min–max`` of the finite values, each formatted with ``fmt``; ``n/a`` when there are none."""
    finite = np.asarray(values)[np.isfinite(values)]
    return f"{fmt % finite.min()}–{fmt % finite.max()}" if finite.size else "n/a"


def _relative_band(result: EfficiencyMap) -> np.ndarray:
    """(P_high − P_low)/P of every cell [%]."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return (result.power_loss_high_w - result.power_loss_low_w) / result.power_loss_w * 100


def _relative_band_lines(ax, result: EfficiencyMap) -> None:
    """Labelled contour lines of (P_high − P_low)/P [%] on the band panel."""
    relative = np.ma.masked_invalid(_relative_band(result))
    if relative.count() < 4 or float(relative.max() - relative.min()) <= 0.0:
        return
    lines = ax.contour(result.speed_rpm, result.torque_nm, relative, levels=6, colors="white", linewidths=0.8)
    ax.clabel(lines, fmt="%.1f %%", fontsize=7)


def _relative_band_labels(ax, result: EfficiencyMap) -> None:
    """(P_high − P_low)/P [%] written into every cell of a band panel drawn as cells (one torque or one speed)."""
    relative = _relative_band(result)
    for i, torque in enumerate(result.torque_nm):
        for j, speed in enumerate(result.speed_rpm):
            if np.isfinite(relative[i, j]):
                ax.annotate(f"{relative[i, j]:.1f} %", (speed, torque), xytext=(0, 10), textcoords="offset points",
                            ha="center", va="bottom", fontsize=7,
                            bbox={"boxstyle": "round,pad=0.2", "facecolor": "white", "alpha": 0.7, "lw": 0})


# ---------------------------------------------------------------------- mesh cycle and line of action
@dataclass
class MeshCycleLoss:
    """Per friction model: P(φ) over the cycle, and the cycle-mean loss, load-weighted μ and SR in bins of roll distance
    along the line of action (from T1); the pitch point and the active path of contact.

    Parameters
    ----------
    design : str
        Design name [-].
    mesh_angle_rad : ndarray
        (M,) mesh angles [rad].
    roll_bins_m : ndarray
        Bin edges of roll distance from T1 [m].
    pitch_roll_m : float
        Roll distance of the pitch point [m].
    contact_start_m : float
        Start of the active path of contact [m].
    contact_end_m : float
        End of the active path of contact [m].
    models : dict of str to dict
        Per model: ``power_loss_w`` [W], ``power_loss_band_w`` (the 90 % band of P of a surrogate with prediction
        intervals, else None) [W], ``efficiency``, ``power_loss_instant_w`` [W], ``loss_per_length_w_per_m``
        [W/m], ``mu_load_weighted`` and ``sr_load_weighted`` per bin [-].
    torque_nm : float
        Input torque [N·m].
    speed_rpm : float
        Input speed [rpm].
    """

    design: str
    mesh_angle_rad: np.ndarray
    roll_bins_m: np.ndarray
    pitch_roll_m: float
    contact_start_m: float
    contact_end_m: float
    models: dict[str, dict[str, Any]]
    torque_nm: float = 0.0
    speed_rpm: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        """The result as a JSON-ready dict (``roll_bin_edges_m`` for the bin edges).

        Returns
        -------
        dict
            The fields, units in the key names.
        """
        return {"design": self.design, "torque_nm": self.torque_nm, "speed_rpm": self.speed_rpm,
                "mesh_angle_rad": self.mesh_angle_rad, "roll_bin_edges_m": self.roll_bins_m,
                "pitch_roll_m": self.pitch_roll_m, "contact_start_m": self.contact_start_m,
                "contact_end_m": self.contact_end_m, "models": self.models}


def mesh_cycle_loss(pair, frictions: dict[str, Any], point, options, *, design: str = "", bins: int = 40,
                    ) -> MeshCycleLoss:
    """P(φ) over the cycle and the loss along the line of action of ``pair`` at ``point`` for each friction model.

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    frictions : dict of str to callable
        Friction models by name [-].
    point : StudyPoint
        The operating point [-].
    options : MeshOptions
        Mesh resolution and models [-].
    design : str
        Design name [-].
    bins : int
        Bins of roll distance along the line of action [-].

    Returns
    -------
    MeshCycleLoss
        Per model: P(φ) and the binned loss, μ and SR.
    """
    from efficiency.mesh_cycle import evaluate_mesh
    from efficiency.power_loss import mesh_power_loss

    mesh = evaluate_mesh(pair, point.input_torque, point.input_speed, point.modifications, options)
    kin = mesh.kinematics
    edges = np.linspace(kin.contact_start, kin.contact_end, bins + 1)
    width = np.diff(edges)
    loaded = mesh.loads > 0
    roll = np.broadcast_to(kin.roll, mesh.loads.shape)
    which = np.clip(np.searchsorted(edges, roll, side="right") - 1, 0, bins - 1)
    sliding = np.abs(np.broadcast_to(kin.u_s, mesh.loads.shape))
    pitch = float(np.interp(0.0, *_sorted_pair(kin.u_s[loaded], roll[loaded])))
    models = {}
    m = mesh.loads.shape[0]
    for name, friction in frictions.items():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            loss = mesh_power_loss(mesh, friction, point.oil_temperature, point.rq1, point.rq2)
        dissipation = np.where(loaded, np.nan_to_num(loss.mu) * mesh.loads * sliding, 0.0)
        per_bin = np.bincount(which[loaded], weights=dissipation[loaded], minlength=bins) / m
        load_bin = np.bincount(which[loaded], weights=mesh.loads[loaded], minlength=bins)
        mu_bin = np.bincount(which[loaded], weights=(np.nan_to_num(loss.mu) * mesh.loads)[loaded], minlength=bins)
        sr_bin = np.bincount(which[loaded], weights=(loss.sr * mesh.loads)[loaded], minlength=bins)
        with np.errstate(invalid="ignore", divide="ignore"):
            models[name] = {"power_loss_w": loss.power_loss, "efficiency": loss.efficiency,
                            "power_loss_band_w": loss.power_loss_band,
                            "power_loss_instant_w": loss.power_loss_instant,
                            "loss_per_length_w_per_m": per_bin / width,
                            "mu_load_weighted": mu_bin / load_bin, "sr_load_weighted": sr_bin / load_bin}
    return MeshCycleLoss(design, kin.mesh_angle, edges, pitch, float(kin.contact_start), float(kin.contact_end),
                         models, point.input_torque, point.input_speed * 30.0 / math.pi)


def _sorted_pair(x, y):
    order = np.argsort(x)
    return np.asarray(x)[order], np.asarray(y)[order]


def mesh_cycle_figure(result: MeshCycleLoss, path, command: str, note: str = "") -> str:
    """Draw P(φ) and the loss, μ and SR along the line of action for every model and save the figure.

    Parameters
    ----------
    result : MeshCycleLoss
        The result [-].
    path : str or Path
        The PNG to write [-].
    command : str
        The command that made the figure, printed in its footer [-].
    note : str
        Extra footer text [-].

    Returns
    -------
    str
        The path written.
    """
    plt = _pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    centres = 0.5 * (result.roll_bins_m[1:] + result.roll_bins_m[:-1])
    x_mm = (centres - result.pitch_roll_m) * 1e3
    phi = result.mesh_angle_rad * 1e3
    for k, (name, model) in enumerate(result.models.items()):
        style = STYLES[k % len(STYLES)]
        axes[0].plot(phi, model["power_loss_instant_w"] / 1e3, style, color=f"C{k}", marker="o", ms=3,
                     label=f"{name}: mean P {model['power_loss_w'] / 1e3:.3f} kW"
                     + (" (90 % band {:.3f}-{:.3f})".format(*(v / 1e3 for v in model["power_loss_band_w"]))
                        if model.get("power_loss_band_w") else ""))
        axes[0].axhline(model["power_loss_w"] / 1e3, color=f"C{k}", lw=0.8, ls=":")
        axes[1].plot(x_mm, model["loss_per_length_w_per_m"] * 1e-3, style, color=f"C{k}", label=name)
        axes[2].plot(x_mm, model["mu_load_weighted"], style, color=f"C{k}", label=f"μ {name}")
    first = next(iter(result.models.values()))
    twin = axes[2].twinx()
    twin.plot(x_mm, first["sr_load_weighted"], color="0.4", lw=1, label="SR")
    twin.set_ylabel("slide-to-roll ratio SR [-]", color="0.4")
    axes[0].set_xlabel("mesh angle φ of gear 1 [mrad]")
    axes[0].set_ylabel("instantaneous power loss P(φ) [kW]")
    axes[0].set_title("loss over one mesh cycle (Eq. 11a)")
    for ax in axes[1:]:
        ax.axvline(0.0, color="k", lw=0.8, ls="--")
        ax.set_xlim((result.contact_start_m - result.pitch_roll_m) * 1e3,
                    (result.contact_end_m - result.pitch_roll_m) * 1e3)
        ax.text(0.02, 0.02, "approach", transform=ax.transAxes, fontsize=8, color="0.3")
        ax.text(0.98, 0.02, "recess", transform=ax.transAxes, fontsize=8, color="0.3", ha="right")
        ax.set_xlabel("distance from the pitch point along the path of contact [mm]")
    axes[1].set_ylabel("cycle-mean loss per unit length of the path [W/mm]")
    axes[1].set_title("where the loss is made")
    axes[2].set_ylabel("load-weighted μ [-]")
    axes[2].set_title("friction and sliding along the line of action")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper left")
    fig.suptitle(f"Design {result.design} at {result.torque_nm:.0f} N·m, {result.speed_rpm:.0f} rpm: friction power "
                 f"loss over the mesh cycle and along the line of action", fontsize=10)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    return _save(fig, path, command, note)


# ---------------------------------------------------------------------- the paper's studies
def study_sweep(study, frictions: dict[str, Any], point, options, *, stride: int = 1, limit: int | None = None):
    """The paper's design sweep for every friction model: the scatter table, the trend lines and the Table 1 designs.

    Parameters
    ----------
    study : PaperStudy
        The study [-].
    frictions : dict of str to callable
        Friction models by name; the first one gives the scatter table [-].
    point : StudyPoint
        The operating point [-].
    options : MeshOptions
        Mesh resolution and models [-].
    stride : int
        Keep every stride-th feasible design in the scatter [-].
    limit : int, optional
        Keep the first ``limit`` designs after the stride [-].

    Returns
    -------
    tuple
        (table, lines {model: {column: table}}, designs {model: {name: row}}).
    """
    from efficiency.studies import design_sweep, evaluate_design, trend_line

    names = list(frictions)
    table = design_sweep(study.space, frictions[names[0]], point, study.limits, options, stride=stride, limit=limit)
    lines, designs = {}, {}
    for name, friction in frictions.items():
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            lines[name] = {"teeth": trend_line(design_sweep(study.space, friction, point, study.limits, options,
                                                            where=FIG3_LINE), "teeth", {})}
            for column, fixed in FIG4_LINES.items():
                lines[name][column] = trend_line(design_sweep(study.space, friction, point, study.limits, options,
                                                              where=fixed), column, {})
            designs[name] = {d: evaluate_design(study.design(d), friction, point, options) for d in study.designs}
    return table, lines, designs


def sweep_figures(table, lines, designs, study, out_dir, command: str, point_text: str, note: str = "") -> list[str]:
    """Draw the sweep figures (P against the design parameters, as the paper's Fig. 3–5) into ``out_dir``.

    Parameters
    ----------
    table : pandas.DataFrame
        The scatter table of :func:`study_sweep` [-].
    lines : dict
        The trend lines of :func:`study_sweep` [-].
    designs : dict
        The Table 1 designs of :func:`study_sweep` [-].
    study : PaperStudy
        The study [-].
    out_dir : str or Path
        Output directory [-].
    command : str
        The command that made the figures, printed in their footer [-].
    point_text : str
        The operating point, printed in the titles [-].
    note : str
        Extra footer text [-].

    Returns
    -------
    list of str
        The paths written.
    """
    plt = _pyplot()
    names = list(lines)
    ok = table[table["converged"].astype(bool)]
    inside = ok[ok["valid"].fillna(False).astype(bool)]
    outside = ok[~ok["valid"].fillna(False).astype(bool)]
    written = []

    def scatter(ax, x, scale):
        if len(outside):
            ax.scatter(outside[x] * scale, outside["power_loss_w"] / 1e3, s=2, alpha=0.25, color="C3",
                       rasterized=True, label=f"{len(outside)} feasible designs outside the validity ({names[0]})")
        ax.scatter(inside[x] * scale, inside["power_loss_w"] / 1e3, s=2, alpha=0.5, color="0.3", rasterized=True,
                   label=f"{len(inside)} feasible designs inside the validity ({names[0]})")

    fig, axes = plt.subplots(2, 3, figsize=(14, 8), sharey=True)
    panels = [(axes[0, 0], "teeth", "teeth", 1.0, "N"), (axes[0, 1], "teeth", "normal_module_m", 1e3, "m_n [mm]"),
              (axes[0, 2], "teeth", "tip_diameter_m", 1e3, "d_o [mm]"),
              (axes[1, 0], "normal_pressure_angle_deg", "normal_pressure_angle_deg", 1.0, "Φ [deg]"),
              (axes[1, 1], "helix_angle_deg", "helix_angle_deg", 1.0, "Ψ [deg]"),
              (axes[1, 2], "working_depth", "working_depth", 1.0, "Λ_wd")]
    for ax, line_key, column, scale, label in panels:
        scatter(ax, column, scale)
        for k, name in enumerate(names):
            line = lines[name][line_key]
            line = line[line["converged"].astype(bool)]
            ax.plot(line[column] * scale, line["power_loss_w"] / 1e3, STYLES[k % len(STYLES)], color=f"C{k}",
                    marker="o", ms=3, label=f"sole influence, {name}")
        ax.set_xlabel(label)
        ax.set_ylabel("P [kW]")
        ax.grid(alpha=0.3)
    axes[0, 0].legend(loc="upper right", fontsize=7)
    fig.suptitle(f"Power loss of the feasible designs at {point_text} (cf. Li & Kahraman 2009, Fig. 3a-c and "
                 f"4a-c)\nlines: Φ 22.5°, Ψ 20°, Λ_wd 2.286 for N, m, d_o; N = 30 with the other two fixed for Φ, Ψ, "
                 f"Λ_wd; friction {names[0]} (scatter and solid line), others for comparison", fontsize=9)
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    written.append(_save(fig, Path(out_dir) / "sweep_power_loss.png", command, note))

    fig, axes = plt.subplots(1, 3, figsize=(14, 4.8), sharey=True)
    for ax, column, scale, label, limit_key, limit_scale in (
            (axes[0], "te_pp_m", 1e6, "peak-to-peak TE [µm]", "max_transmission_error_m", 1e6),
            (axes[1], "sigma_c_pa", 1e-9, "max σ_c [GPa]", "max_contact_stress_pa", 1e-9),
            (axes[2], "sigma_b_pa", 1e-6, "max σ_b [MPa]", "max_root_stress_pa", 1e-6)):
        scatter(ax, column, scale)
        limit = (study.search_limits or {}).get(limit_key)
        if limit is not None:
            ax.axvline(limit * limit_scale, color="C0", ls="--", lw=1, label="design-D search limit")
        ax.axhline((study.search_limits or {}).get("max_power_loss_w", np.nan) / 1e3, color="C0", ls=":", lw=1)
        for k, name in enumerate(names):
            for design, row in designs[name].items():
                ax.plot(row[column] * scale, row["power_loss_w"] / 1e3, "s", ms=7, mfc="none", color=f"C{k}",
                        label=name if design == "A" else None)
                ax.annotate(design, (row[column] * scale, row["power_loss_w"] / 1e3), xytext=(4, 4),
                            textcoords="offset points", color=f"C{k}", fontsize=9, weight="bold")
        ax.set_xlabel(label)
        ax.set_ylabel("P [kW]")
        ax.grid(alpha=0.3)
    axes[0].legend(loc="upper right", fontsize=7)
    fig.suptitle(f"P against TE, σ_c, σ_b (cf. Li & Kahraman 2009, Fig. 5); Table 1 designs A-D for each friction "
                 f"model; {point_text}", fontsize=9)
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    written.append(_save(fig, Path(out_dir) / "sweep_tradeoffs.png", command, note))
    return written


def study_modifications(pair, frictions: dict[str, Any], profile_crowns, lead_crowns, torques, point, options):
    """:func:`efficiency.studies.modification_study` for every friction model.

    Parameters
    ----------
    pair : GearPair
        A scalar pair [-].
    frictions : dict of str to callable
        Friction models by name [-].
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

    Returns
    -------
    dict of str to pandas.DataFrame
        {model: table}.
    """
    from efficiency.studies import modification_study

    return {name: modification_study(pair, friction, profile_crowns, lead_crowns, torques, point, options)
            for name, friction in frictions.items()}


def modifications_figure(tables: dict, design: str, path, command: str, note: str = "") -> str:
    """Draw P, TE, σ_c and σ_b against the profile crown (middle lead crown) per torque, as paper Fig. 6.

    Parameters
    ----------
    tables : dict of str to pandas.DataFrame
        :func:`study_modifications` [-].
    design : str
        Design name [-].
    path : str or Path
        The PNG to write [-].
    command : str
        The command that made the figure, printed in its footer [-].
    note : str
        Extra footer text [-].

    Returns
    -------
    str
        The path written.
    """
    plt = _pyplot()
    names = list(tables)
    first = tables[names[0]]
    fig, axes = plt.subplots(1, 4, figsize=(17, 4.8))
    leads = sorted(set(np.round(first["lead_crown_m"], 9)))
    lead = leads[len(leads) // 2]
    torques = sorted(set(first["torque_nm"]))
    for k, torque in enumerate(torques):
        for j, name in enumerate(names):
            rows = tables[name]
            rows = rows[(rows["torque_nm"] == torque) & np.isclose(rows["lead_crown_m"], lead)]
            rows = rows.sort_values("profile_crown_m")
            axes[0].plot(rows["profile_crown_m"] * 1e6, rows["power_loss_w"] / 1e3, STYLES[j % len(STYLES)],
                         color=f"C{k}", marker="o" if j == 0 else None, ms=3, label=f"T = {torque:.0f} N·m, {name}")
            bad = rows[~rows["valid"].fillna(False).astype(bool)]
            if j == 0 and len(bad):
                axes[0].plot(bad["profile_crown_m"] * 1e6, bad["power_loss_w"] / 1e3, "x", color="C3", ms=7)
        for ax, (column, scale) in zip(axes[1:], (("te_pp_m", 1e6), ("sigma_c_pa", 1e-9), ("sigma_b_pa", 1e-6))):
            for style, shown in zip(STYLES, (leads[0], lead, leads[-1])):
                rows = first[(first["torque_nm"] == torque) & np.isclose(first["lead_crown_m"], shown)]
                rows = rows.sort_values("profile_crown_m")
                ax.plot(rows["profile_crown_m"] * 1e6, rows[column] * scale, style, color=f"C{k}", marker="o", ms=3,
                        label=f"T = {torque:.0f} N·m, M_L = {shown * 1e6:.0f} µm")
    axes[0].plot([], [], "x", color="C3", label=f"outside validity ({names[0]})")
    for ax, label in zip(axes, (f"P [kW] (M_L = {lead * 1e6:.0f} µm)", "peak-to-peak TE [µm]", "max σ_c [GPa]",
                                "max σ_b [MPa]")):
        ax.set_xlabel("profile crown M_P [µm]")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=6)
    axes[1].legend(fontsize=6)
    fig.suptitle(f"Design {design}: tooth modifications (cf. Li & Kahraman 2009, Fig. 6); P with friction "
                 f"{names[0]} (solid) and {', '.join(names[1:]) or '-'} (dashed); TE and stresses do not depend on "
                 f"friction", fontsize=9)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    return _save(fig, path, command, note)
