"""What the friction model costs in accuracy and time inside the gear loss (DESIGN §6, "for accuracy checks").

The mesh power loss P = mean_m Σ_q μ_q W_q |u_s,q| (Li & Kahraman 2009, Eq. 11) needs μ at every loaded contact
point of a mesh cycle. The most faithful model runs the EHL solver at every point
(:class:`efficiency.power_loss.EhlFriction`); this module

* makes that affordable with :class:`EhlGridFriction`: along the path of contact the radii, the rolling and the
  sliding velocities are functions of the roll distance s alone (ρ1 = s, ρ2 = T1T2 − s, u_s linear in s), so with a
  fixed oil temperature and roughness μ of a gear mesh is a function μ(s, p_h) of two variables. It is smooth on
  each side of the pitch point (where u_s changes sign and μ has a kink), so the EHL solver runs on a small
  Chebyshev–Lobatto grid in (s, p_h) on the approach side and on the recess side, with the pitch point a node of
  both, and μ at the loaded points follows from tensor-product barycentric interpolation (Berrut & Trefethen,
  SIAM Review 46 (2004) 501–517). The cost no longer grows with the mesh resolution;
* compares friction models on one loaded mesh (:func:`compare_friction_models`): P, η, the load-weighted mean μ,
  the error in P against a reference model and the wall time of each;
* checks the pitch-point region (SR → 0, :func:`pitch_point_behaviour`): every model must return a finite μ there,
  and its contribution to P vanishes with |u_s|.

Friction models by name (:func:`friction_from_name`): ``ehl:LEVEL[:EFFECTS]`` the EHL solver at every point,
``ehl-grid:LEVEL[:EFFECTS][:NSxNP]`` the grid above, anything else as ``gear sweep --friction``
(:func:`efficiency.studies.friction_from_spec`: ``constant:MU``, ``xu2007``, ``benedict_kelley``, ``iso14179`` or a
coefficient file).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Mapping

import numpy as np

from ehl_dataset.model.materials import STEEL, Material
from ehl_dataset.validation import InputError, SolverError, check_range

from .power_loss import EhlFriction, contact_conditions, mesh_power_loss

EHL_EFFECTS = ("auto", "full")


# ---------------------------------------------------------------------- Chebyshev–Lobatto interpolation
def lobatto_nodes(low: float, high: float, n: int) -> np.ndarray:
    """n Chebyshev–Lobatto (second kind) points on [low, high], both ends included, ascending."""
    if n == 1 or high == low:
        return np.array([0.5 * (low + high)]) if n == 1 else np.full(n, low)
    theta = np.linspace(math.pi, 0.0, n)
    return 0.5 * (low + high) + 0.5 * (high - low) * np.cos(theta)


def barycentric_matrix(nodes: np.ndarray, x: np.ndarray) -> np.ndarray:
    """(len(x), n) matrix B with f(x) ≈ B @ f(nodes): barycentric Lagrange interpolation on Chebyshev–Lobatto
    nodes (weights (−1)^j, halved at both ends; Berrut & Trefethen 2004, Eq. 5.4). Exact at the nodes."""
    n = len(nodes)
    x = np.asarray(x, dtype=float)
    if n == 1:
        return np.ones((x.size, 1))
    weights = (-1.0) ** np.arange(n)
    weights[0] *= 0.5
    weights[-1] *= 0.5
    diff = x.reshape(-1, 1) - nodes.reshape(1, -1)
    exact = diff == 0.0
    with np.errstate(divide="ignore", invalid="ignore"):
        terms = weights / diff
        terms = terms / terms.sum(axis=1, keepdims=True)
    hit = exact.any(axis=1)
    terms[hit] = exact[hit].astype(float)
    return terms


# ---------------------------------------------------------------------- the EHL solver on a grid
SR_FLOOR = 1e-3
"""Below this slide-to-roll ratio :class:`EhlGridFriction` interpolates linearly in SR towards the pitch point."""


@dataclass(frozen=True)
class EhlGridFriction:
    """EHL friction on a small grid per side of the pitch point, interpolated (DESIGN §6, accuracy checks).

    Along the path of contact, r_eq, u_r and SR are functions of the roll distance s; with one oil temperature and
    roughness μ = μ(s, p_h). On each side of the pitch point SR grows monotonically with |s − s_p|, and μ is close
    to linear in ln SR (Eyring traction, τ ≈ τ0 ln(2 η u_s/(τ0 h))), but varies non-monotonically with p_h (light
    hydrodynamic loads, the piezo-viscous rise, Eyring saturation). The grid is the tensor product of
    ``roll_nodes`` Chebyshev–Lobatto nodes in ln SR over the loaded range of the side (SR ≥ :data:`SR_FLOOR`) and
    ``load_nodes`` nodes in p_h over the loaded range of p_h; points with SR < SR_FLOOR interpolate linearly in SR
    between the pitch point (SR = 0, a column of ``load_nodes`` extra solves) and the grid's first column.
    Cost: 2·roll_nodes·load_nodes (+ load_nodes) EHL solves per mesh, whatever its resolution. Measured on
    design D (docs/gear_friction_accuracy.md): 5 × 9 nodes, error in P ≈ 0.1 %.

    It needs the mesh (it works in roll distance): :func:`efficiency.power_loss.mesh_power_loss` binds it through
    :meth:`for_mesh`. Oil temperature and roughness must be the same at every point (they are in a gear mesh).
    """

    lubricant: Any
    level: str = "fast"
    effects: str = "auto"
    roll_nodes: int = 5
    load_nodes: int = 9

    def __post_init__(self):
        check_range("roll_nodes", self.roll_nodes, 2, 64)
        check_range("load_nodes", self.load_nodes, 2, 64)
        if self.effects not in EHL_EFFECTS:
            raise InputError("effects", self.effects, f"one of {list(EHL_EFFECTS)}")

    def describe(self) -> str:
        return (f"EHL solver level={self.level} effects={self.effects} on a grid of {self.roll_nodes} (ln SR) x "
                f"{self.load_nodes} (p_h) nodes per side of the pitch point")

    def __call__(self, *args):
        raise InputError("friction", "ehl-grid", "a mesh: use it through efficiency.power_loss.mesh_power_loss "
                                                 "(it interpolates along the path of contact)")

    def for_mesh(self, mesh, loaded: np.ndarray, material1: Material = STEEL,
                 material2: Material = STEEL) -> "_BoundGrid":
        return _BoundGrid(self, mesh, np.asarray(loaded, dtype=bool))


@dataclass
class _BoundGrid:
    """:class:`EhlGridFriction` bound to one mesh (knows the roll distance of each loaded point)."""

    model: EhlGridFriction
    mesh: Any
    loaded: np.ndarray
    stats: dict = field(default_factory=dict)
    grid: dict = field(default_factory=dict)

    def describe(self) -> str:
        return self.model.describe()

    def last_stats(self) -> dict:
        return dict(self.stats)

    def __call__(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2) -> np.ndarray:
        started = time.perf_counter()
        s = self.mesh.kinematics.roll[self.loaded]
        p_h = np.asarray(p_h, dtype=float)
        sr = np.asarray(sr, dtype=float)
        if p_h.shape != s.shape or sr.shape != s.shape:
            raise InputError("friction input", p_h.shape, f"the {s.shape} loaded points of the bound mesh")
        scalars = {}
        for name, values in (("temperature", temperature), ("rq1", rq1), ("rq2", rq2)):
            values = np.asarray(values, dtype=float)
            if values.size and np.ptp(values) > 0.0:
                raise InputError(name, f"{values.min():g}..{values.max():g}", "one value for every point of a mesh")
            scalars[name] = float(values.reshape(-1)[0]) if values.size else 0.0
        if s.size == 0:
            return np.zeros(0)
        path = PathOfContact.of(self.mesh.kinematics)
        p_nodes = lobatto_nodes(float(p_h.min()), float(p_h.max()), self.model.load_nodes)
        sides = [mask for mask in (s <= path.pitch, s > path.pitch) if mask.any()]
        need_pitch = bool(np.any(sr < SR_FLOOR))
        sr_nodes = []
        for side in sides:
            sr_lo = max(float(sr[side].min()), SR_FLOOR)
            sr_hi = max(float(sr[side].max()), sr_lo)
            n = self.model.roll_nodes if sr_hi > sr_lo else 1
            nodes = np.exp(lobatto_nodes(math.log(sr_lo), math.log(sr_hi), n))
            nodes[0], nodes[-1] = sr_lo, sr_hi  # exact ends (exp∘log rounds)
            sr_nodes.append(nodes)
        # all nodes in one solver call (duplicates, e.g. the pitch column, are solved once)
        node_s, node_p = [], []
        for side, nodes in zip(sides, sr_nodes):
            sign = 1.0 if np.all(s[side] > path.pitch) else -1.0
            ss, pp = np.meshgrid(path.roll_at(nodes, sign), p_nodes, indexing="ij")
            node_s.append(ss.reshape(-1))
            node_p.append(pp.reshape(-1))
        if need_pitch:
            node_s.append(np.full(p_nodes.size, path.pitch))
            node_p.append(p_nodes)
        ss, pp = np.concatenate(node_s), np.concatenate(node_p)
        solver = EhlFriction(self.model.lubricant, self.model.level, self.model.effects)
        try:
            mu_all = solver(pp, path.r_eq(ss), path.u_r(ss), path.sr(ss), scalars["temperature"], scalars["rq1"],
                            scalars["rq2"])
        except SolverError as err:  # the "contact point" index there is a grid node, not a mesh point
            raise SolverError(f"EHL grid node of {self.model.describe()}: {err}") from None
        mu = np.empty(s.shape)
        grids, start = [], 0
        pitch_column = mu_all[-p_nodes.size:] if need_pitch else None
        for side, nodes in zip(sides, sr_nodes):
            table = mu_all[start:start + nodes.size * p_nodes.size].reshape(nodes.size, p_nodes.size)
            start += table.size
            q = np.log(np.maximum(sr[side], nodes[0]))
            values = np.einsum("qi,ij,qj->q", barycentric_matrix(np.log(nodes), q), table,
                               barycentric_matrix(p_nodes, p_h[side]))
            low = sr[side] < SR_FLOOR
            if low.any():  # linear in SR between the pitch point and the first column
                b_p = barycentric_matrix(p_nodes, p_h[side][low])
                at_pitch, at_first = b_p @ pitch_column, b_p @ table[0]
                frac = sr[side][low] / SR_FLOOR
                values[low] = at_pitch + frac * (at_first - at_pitch)
            mu[side] = values
            grids.append({"sr": nodes, "p_h_pa": p_nodes, "mu": table})
        self.grid = {"pitch_roll_m": path.pitch, "sides": grids, "pitch_mu": pitch_column}
        self.stats = {"ehl_solves": solver.last_stats()["ehl_solves"], "ehl_points": int(s.size),
                      "ehl_time_s": time.perf_counter() - started}
        if not np.all(np.isfinite(mu)):
            raise SolverError("EHL grid interpolation gave a non-finite μ")
        # a polynomial may undershoot where μ is small; a friction coefficient cannot be negative
        return np.maximum(mu, 0.0)


@dataclass(frozen=True)
class PathOfContact:
    """Kinematics along the path of contact as functions of the roll distance s [m] (from the mesh's own
    in-contact points; ρ1n, ρ2n, u_r and u_s are linear in s, so linear interpolation and fits are exact).

    u_s = k (s − s_p), u_r = u_p + m (s − s_p); ``pitch`` s_p where u_s = 0."""

    s: np.ndarray
    rho1: np.ndarray
    rho2: np.ndarray
    pitch: float
    k: float
    u_p: float
    m: float

    @classmethod
    def of(cls, kin) -> "PathOfContact":
        ic = kin.in_contact
        order = np.argsort(kin.roll[ic])
        s = kin.roll[ic][order]
        k, b = np.polyfit(s, kin.u_s[ic][order], 1)
        m, c = np.polyfit(s, kin.u_r[ic][order], 1)
        pitch = -b / k if k != 0.0 else math.inf
        return cls(s, kin.rho1_normal[ic][order], kin.rho2_normal[ic][order], float(pitch), float(k),
                   float(m * pitch + c), float(m))

    def r_eq(self, s):
        r1, r2 = np.interp(s, self.s, self.rho1), np.interp(s, self.s, self.rho2)
        return r1 * r2 / (r1 + r2)

    def u_r(self, s):
        return self.u_p + self.m * (np.asarray(s) - self.pitch)

    def sr(self, s):
        return np.abs(self.k * (np.asarray(s) - self.pitch)) / self.u_r(s)

    def roll_at(self, sr, side: float) -> np.ndarray:
        """s at slide-to-roll ratio ``sr`` on the recess (side = +1, s > s_p) or approach (−1) side: from
        SR (u_p + m t) = ±k t, t = s − s_p."""
        sr = np.asarray(sr, dtype=float)
        t = sr * self.u_p / (side * abs(self.k) - sr * self.m)
        return self.pitch + t


# ---------------------------------------------------------------------- friction models by name
def friction_from_name(spec: str, lubricant="atf") -> Callable:
    """A friction model from a short name: ``ehl:LEVEL[:EFFECTS]`` (:class:`EhlFriction`), ``ehl-grid:LEVEL
    [:EFFECTS][:NSxNP]`` (:class:`EhlGridFriction`, NS roll × NP load nodes), else
    :func:`efficiency.studies.friction_from_spec` (``constant:MU``, ``xu2007``, ``benedict_kelley``, ``iso14179``,
    a coefficient file). ``lubricant`` (name, file or Lubricant) is used by the EHL and published models."""
    from ehl_dataset.solvers.levels import LEVELS
    from ehl_dataset.model.lubricant import Lubricant, load_lubricant

    accepted = ("ehl:LEVEL[:auto|full], ehl-grid:LEVEL[:auto|full][:NSxNP], constant:MU, xu2007, "
                "benedict_kelley, iso14179 or a coefficient file")
    if not isinstance(spec, str) or not spec.strip():
        raise InputError("friction", spec, accepted)
    text = spec.strip()
    head, _, rest = text.partition(":")
    if head.lower() not in ("ehl", "ehl-grid"):
        from .studies import friction_from_spec

        return friction_from_spec(text, lubricant)
    parts = [p for p in rest.split(":") if p] if rest else []
    level = parts.pop(0) if parts else "fast"
    if level not in LEVELS:
        raise InputError("friction", spec, f"an EHL level of {sorted(LEVELS)} after '{head}:'")
    effects = "auto"
    if parts and parts[0] in EHL_EFFECTS:
        effects = parts.pop(0)
    lub = lubricant if isinstance(lubricant, Lubricant) else load_lubricant(lubricant)
    if head.lower() == "ehl":
        if parts:
            raise InputError("friction", spec, accepted)
        return EhlFriction(lub, level, effects)
    nodes = {}
    if parts:
        try:
            ns, np_ = (int(v) for v in parts.pop(0).lower().split("x"))
        except ValueError:
            raise InputError("friction", spec,
                             "ehl-grid:LEVEL[:EFFECTS][:NSxNP] with integers NS ≥ 2, NP ≥ 1") from None
        nodes = {"roll_nodes": ns, "load_nodes": np_}
    if parts:
        raise InputError("friction", spec, accepted)
    return EhlGridFriction(lub, level, effects, **nodes)


def describe_model(friction) -> str:
    """One line naming a friction model (the power-loss result's description)."""
    if hasattr(friction, "describe"):
        return str(friction.describe())
    from .studies import describe_friction

    if isinstance(friction, EhlFriction):
        return f"EHL solver level={friction.level} effects={friction.effects}"
    return describe_friction(friction)


# ---------------------------------------------------------------------- comparison on one mesh
@dataclass(frozen=True)
class FrictionModelRow:
    """One friction model on one loaded mesh: mean power loss P [W], η [-], load-weighted mean μ over the cycle,
    ``rel_error`` (P − P_ref)/P_ref against the reference model (NaN for the reference itself or when it failed),
    ``wall_time_s`` of the loss evaluation (friction model included), EHL solves if any, and ``error`` (empty
    unless the model raised, e.g. a rough point while the transient solver is missing)."""

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
        return dict(self.__dict__)


def load_weighted_mu(result, mesh) -> float:
    """Σ μ W / Σ W over the loaded points of the cycle."""
    loaded = mesh.loads > 0.0
    return float(np.sum(result.mu[loaded] * mesh.loads[loaded]) / np.sum(mesh.loads[loaded]))


def compare_friction_models(mesh, models: Mapping[str, Callable], temperature: float, rq1: float, rq2: float,
                            reference: str, material1: Material = STEEL, material2: Material = STEEL
                            ) -> list[FrictionModelRow]:
    """P with each model on the same loaded mesh, its error against ``models[reference]`` and its wall time.

    ``temperature`` [K], ``rq1``, ``rq2`` [m]. A model that raises :class:`SolverError` or :class:`InputError`
    gets a row with NaN numbers and the message (never a silent number).
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
            rows.append(FrictionModelRow(name, describe_model(models[name]), math.nan, math.nan, math.nan, math.nan,
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
    """μ of a pointwise friction model as SR → 0 at fixed p_h [Pa], r_eq [m], u_r [m/s], temperature [K],
    roughness [m], and the friction power per unit normal load μ |u_s| = μ SR u_r [W/N] that it implies.

    Returns ``sr``, ``mu``, ``power_per_load_w_per_n`` (arrays over ``sr_values``) and ``finite`` (μ finite and
    ≥ 0 everywhere)."""
    sr = np.asarray(sr_values, dtype=float)
    n = sr.size
    mu = np.asarray(friction(np.full(n, p_h), np.full(n, r_eq), np.full(n, u_r), sr, np.full(n, temperature),
                             np.full(n, rq1), np.full(n, rq2)), dtype=float)
    return {"sr": sr, "mu": mu, "power_per_load_w_per_n": mu * sr * u_r,
            "finite": bool(np.all(np.isfinite(mu)) and np.all(mu >= 0.0))}


def pitch_region_share(result, mesh, sr_max: float = 0.02) -> float:
    """Share of the cycle's friction energy dissipated at points with SR ≤ ``sr_max`` (the pitch-point region)."""
    loaded = mesh.loads > 0.0
    dissipation = np.where(loaded, np.nan_to_num(result.mu) * mesh.loads * np.abs(mesh.kinematics.u_s), 0.0)
    total = dissipation.sum()
    near = dissipation[loaded & (result.sr <= sr_max)].sum()
    return float(near / total) if total > 0.0 else 0.0
