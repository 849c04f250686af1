"""Friction models of the gear power loss: μ at every loaded contact point of a mesh cycle, and one constructor.

A friction model is a callable ``mu(p_h, r_eq, u_r, sr, temperature, rq1, rq2) -> array`` in SI units (Hertz
pressure [Pa], equivalent radius [m], rolling velocity [m/s], slide-to-roll ratio [-], oil temperature [K], RMS
roughness of the two flanks [m]), vectorised over the points. :func:`efficiency.power_loss.mesh_power_loss` calls it
once per mesh cycle. The models, cheapest first:

* :class:`ConstantFriction` — one μ everywhere;
* :class:`PublishedFriction` — the published formulas of :mod:`surrogate.published` (Xu et al. 2007, Benedict &
  Kelley 1961, ISO/TR 14179-2);
* a coefficient file — :class:`surrogate.evaluate.FrictionSurrogate`, the fitted Eq. 9 of Li & Kahraman 2009 or the
  learned ensemble of the same inputs (``form`` of the file), with its inputs clipped to the ranges of its fitted data
  (its own clipping; ``last_stats()`` counts the clipped inputs of the last evaluation, per input) and, in a file of
  format 2, a prediction interval (``mu_interval``) from which :func:`efficiency.power_loss.mesh_power_loss` gives
  the band of P;
* :class:`EhlFriction` — the EHL solver at every loaded point (slow; the reference of the accuracy checks);
* :class:`EhlGridFriction` — the EHL solver on a small grid per side of the pitch point, interpolated along the path
  of contact (docs/validation/gear.md).

:func:`friction_from_spec` builds any of them from the short string of the ``--friction`` options
(``gear evaluate``, ``gear sweep``, ``gear modifications``), the pipeline and the studies; :func:`describe_friction`
names one in reports. A model that counts something about its last evaluation (EHL solves, clipped inputs) has
``last_stats()``, which the power-loss result copies into its ``extra``.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Protocol

import numpy as np

from ehl_dataset.model.materials import STEEL, Material, reduced_modulus
from ehl_dataset.names import DEFAULT_FLUCTUATIONS, EFFECT_PLANS, LEVELS
from ehl_dataset.validation import InputError, SolverError, check_range

EHL_EFFECTS = EFFECT_PLANS
"""Effect plans an EHL friction model accepts (:data:`ehl_dataset.names.EFFECT_PLANS`; ``ehl:LEVEL:EFFECTS``;
``isothermal``: the planner's plan without the thermal correction); the Python classes also take an
:class:`ehl_dataset.model.effects.Effects` used as given."""
SR_FLOOR = 1e-3
"""Below this slide-to-roll ratio :class:`EhlGridFriction` interpolates linearly in SR towards the pitch point."""
PUBLISHED_NAMES = {"xu2007": "xu_2007", "xu_2007": "xu_2007", "benedict_kelley": "benedict_kelley_1961",
                   "benedict_kelley_1961": "benedict_kelley_1961", "iso14179": "iso_tr_14179_2",
                   "iso_tr_14179_2": "iso_tr_14179_2"}
"""Spec names of the published formulas → their names in :mod:`surrogate.published`."""
SPEC_FORMS = ("constant:MU, xu2007, benedict_kelley, iso14179[:OIL_TYPE], a coefficient file (shipped name or "
              "path), ehl:LEVEL[:auto|isothermal|full] or ehl-grid:LEVEL[:auto|isothermal|full][:NSxNP]")
"""What :func:`friction_from_spec` accepts (named in its errors)."""


# ---------------------------------------------------------------------- point-wise models
class FrictionModel(Protocol):
    def __call__(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2) -> np.ndarray: ...


@dataclass(frozen=True)
class ConstantFriction:
    """A constant friction coefficient μ at every contact point.

    Parameters
    ----------
    mu : float
        The friction coefficient [-].
    """

    mu: float

    def __post_init__(self):
        check_range("mu", self.mu, 0.0, 1.0)

    def __call__(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2):
        return np.full(np.shape(p_h), self.mu)


@dataclass(frozen=True)
class PublishedFriction:
    """A published friction formula (``xu2007``, ``benedict_kelley``, ``iso14179``) from :mod:`surrogate.published`.

    Parameters
    ----------
    name : str
        The formula [-].
    lubricant : str or Lubricant
        Lubricant for the inlet viscosity [-].
    e_reduced : float
        Reduced modulus E' for the load per length [Pa].
    oil_type : str, optional
        Oil type of ISO/TR 14179-2's lubricant factor X_L (:data:`efficiency.iso14179.LUBRICANT_FACTOR`); None: the
        ``oil_type`` the lubricant file declares, else ``mineral`` [-].
    """

    name: str
    lubricant: Any
    e_reduced: float = reduced_modulus(STEEL, STEEL)
    oil_type: str | None = None

    def __post_init__(self):
        if self.oil_type is not None:
            from .iso14179 import lubricant_factor

            lubricant_factor(self.oil_type)

    @property
    def lubricant_factor(self) -> float:
        """X_L of ISO/TR 14179-2 for this model's oil type."""
        from .iso14179 import lubricant_factor

        declared = (getattr(self.lubricant, "definition", None) or {}).get("oil_type", "mineral")
        return lubricant_factor(self.oil_type if self.oil_type is not None else declared)

    def __call__(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2):
        from surrogate.published import published_mu

        x_l = self.lubricant_factor if self.name == "iso_tr_14179_2" else 1.0
        return published_mu(self.name, p_h, r_eq, u_r, sr, temperature, rq1, rq2, self.lubricant, self.e_reduced,
                             x_l=x_l)


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
    raise :class:`ehl_dataset.validation.SolverError` (no silent numbers).
    After a call, ``last_stats()`` gives the number of solves and their time.

    Parameters
    ----------
    lubricant : str or Lubricant
        The lubricant [-].
    level : str
        Accuracy level of the solves [-].
    effects : str
        Effect plan: ``auto`` or ``full`` [-].
    roughness : RoughnessProfile, optional
        Shape of both flanks' roughness (e.g. ``named_profile("flank_ground")``), scaled to each point's Rq; None:
        the default profile (``roughness.default_profile()``) [-].
    fluctuations : str
        Micro-EHL pressure spread of the film-law closures (:data:`ehl_dataset.names.FLUCTUATIONS`) [-].
    """

    lubricant: Any
    level: str = "fast"
    effects: str = "auto"
    roughness: Any = None
    fluctuations: str = DEFAULT_FLUCTUATIONS
    _stats: dict = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self):
        _check_rough_options(self.roughness, self.fluctuations)

    def __call__(self, p_h, r_eq, u_r, sr, temperature, rq1, rq2):
        from ehl_dataset.model.contact import ContactCase
        from ehl_dataset.solver import solve_contact

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
        from ehl_dataset.solvers.homogenised import HomogenisedOptions

        homogenised = HomogenisedOptions(fluctuations=self.fluctuations)
        for k, values in enumerate(unique):
            result = solve_contact(ContactCase(*(float(v) for v in values)), self.lubricant, self.level, self.effects,
                                   roughness=self.roughness, homogenised=homogenised)
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
        """What the last call did.

        Returns
        -------
        dict
            ``ehl_solves`` (distinct points solved), ``ehl_points``, ``ehl_iterations`` and ``ehl_time_s`` [s].
        """
        return dict(self._stats)


def _check_rough_options(roughness, fluctuations) -> None:
    from ehl_dataset.names import FLUCTUATIONS

    if fluctuations not in FLUCTUATIONS:
        raise InputError("fluctuations", fluctuations, f"one of {list(FLUCTUATIONS)}")
    if roughness is not None and not hasattr(roughness, "correlation_length"):
        raise InputError("roughness", type(roughness).__name__, "None or a RoughnessProfile")


def _check_effects(effects) -> None:
    from ehl_dataset.model.effects import Effects

    if not (isinstance(effects, Effects) or effects in EHL_EFFECTS):
        raise InputError("effects", effects, f"one of {list(EHL_EFFECTS)} or an Effects instance")


def _effects_name(effects) -> str:
    """A plan name for reports: the string, or a forced plan as ``forced(flags on)``."""
    if isinstance(effects, str):
        return effects
    flags = ("roughness", "transient", "shear_thinning", "compressibility", "thermal")
    return f"{effects.mode}({','.join(f for f in flags if getattr(effects, f))})"


# ---------------------------------------------------------------------- Chebyshev–Lobatto interpolation (the grid)
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
@dataclass(frozen=True)
class EhlGridFriction:
    """EHL friction on a small grid per side of the pitch point, interpolated.

    Along the path of contact, r_eq, u_r and SR are functions of the roll distance s; with one oil temperature and
    roughness μ = μ(s, p_h). On each side of the pitch point SR grows monotonically with |s − s_p|, and μ is close
    to linear in ln SR (Eyring traction, τ ≈ τ0 ln(2 η u_s/(τ0 h))), but varies non-monotonically with p_h (light
    hydrodynamic loads, the piezo-viscous rise, Eyring saturation). The grid is the tensor product of
    ``roll_nodes`` Chebyshev–Lobatto nodes in ln SR over the loaded range of the side (SR ≥ :data:`SR_FLOOR`) and
    ``load_nodes`` nodes in p_h over the loaded range of p_h; points with SR < SR_FLOOR interpolate linearly in SR
    between the pitch point (SR = 0, a column of ``load_nodes`` extra solves) and the grid's first column.
    Cost: 2·roll_nodes·load_nodes (+ load_nodes) EHL solves per mesh, whatever its resolution. Measured on
    design D (docs/validation/gear.md): 5 × 9 nodes, error in P ≈ 0.1 %.

    It needs the mesh (it works in roll distance): :func:`efficiency.power_loss.mesh_power_loss` binds it through
    :meth:`for_mesh`. Oil temperature and roughness must be the same at every point (they are in a gear mesh).

    Parameters
    ----------
    lubricant : str or Lubricant
        The lubricant [-].
    level : str
        Accuracy level of the solves [-].
    effects : str or Effects
        Effect plan of the solves [-].
    roll_nodes : int
        Chebyshev–Lobatto nodes in ln SR per side of the pitch point [-].
    load_nodes : int
        Nodes in p_h [-].
    roughness : RoughnessProfile, optional
        Shape of both flanks' roughness; None: the default profile (``roughness.default_profile()``) [-].
    fluctuations : str
        Micro-EHL pressure spread of the film-law closures (:data:`ehl_dataset.names.FLUCTUATIONS`) [-].
    """

    lubricant: Any
    level: str = "fast"
    effects: Any = "auto"
    roll_nodes: int = 5
    load_nodes: int = 9
    roughness: Any = None
    fluctuations: str = DEFAULT_FLUCTUATIONS

    def __post_init__(self):
        check_range("roll_nodes", self.roll_nodes, 2, 64)
        check_range("load_nodes", self.load_nodes, 2, 64)
        _check_effects(self.effects)
        _check_rough_options(self.roughness, self.fluctuations)

    def describe(self) -> str:
        """One line naming the model for reports.

        Returns
        -------
        str
            Level, effects and grid size.
        """
        from ehl_dataset.model.roughness import default_profile

        profile = default_profile() if self.roughness is None else self.roughness
        rough = f" roughness={profile.name or profile.source}"
        return (f"EHL solver level={self.level} effects={_effects_name(self.effects)}{rough} "
                f"fluctuations={self.fluctuations} on a grid of "
                f"{self.roll_nodes} (ln SR) x {self.load_nodes} (p_h) nodes per side of the pitch point")

    def __call__(self, *args):
        raise InputError("friction", "ehl-grid", "a mesh: use it through efficiency.power_loss.mesh_power_loss "
                                                 "(it interpolates along the path of contact)")

    def for_mesh(self, mesh, loaded: np.ndarray, material1: Material = STEEL,
                 material2: Material = STEEL) -> "_BoundGrid":
        """The model bound to one mesh: solves its grid and interpolates at the mesh's loaded points.

        Parameters
        ----------
        mesh : MeshCycleResult
            The loaded mesh [-].
        loaded : ndarray of bool
            Loaded points of the mesh [-].
        material1 : Material
            Material of gear 1 [-].
        material2 : Material
            Material of gear 2 [-].

        Returns
        -------
        callable
            μ(p_h, r_eq, u_r, sr, temperature, rq1, rq2) at the mesh's loaded points.
        """
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
        solver = EhlFriction(self.model.lubricant, self.model.level, self.model.effects, self.model.roughness,
                             self.model.fluctuations)
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
    """Kinematics along the path of contact as functions of the roll distance s (from the mesh's own in-contact points).

    ρ1n, ρ2n, u_r and u_s are linear in s, so linear interpolation and fits are exact: u_s = k (s − s_p),
    u_r = u_p + m (s − s_p), with the pitch point s_p where u_s = 0.

    Parameters
    ----------
    s : ndarray
        Roll distances of the in-contact points, ascending [m].
    rho1 : ndarray
        Normal radius of curvature of gear 1 at ``s`` [m].
    rho2 : ndarray
        Normal radius of curvature of gear 2 at ``s`` [m].
    pitch : float
        Pitch point s_p [m].
    k : float
        Slope of u_s in s [1/s].
    u_p : float
        Rolling velocity at the pitch point [m/s].
    m : float
        Slope of u_r in s [1/s].
    """

    s: np.ndarray
    rho1: np.ndarray
    rho2: np.ndarray
    pitch: float
    k: float
    u_p: float
    m: float

    @classmethod
    def of(cls, kin) -> "PathOfContact":
        """The path of contact of a mesh's kinematics.

        Parameters
        ----------
        kin : MeshKinematics
            The kinematics [-].

        Returns
        -------
        PathOfContact
            The linear fits and interpolation nodes.
        """
        ic = kin.in_contact
        order = np.argsort(kin.roll[ic])
        s = kin.roll[ic][order]
        k, b = np.polyfit(s, kin.u_s[ic][order], 1)
        m, c = np.polyfit(s, kin.u_r[ic][order], 1)
        pitch = -b / k if k != 0.0 else math.inf
        return cls(s, kin.rho1_normal[ic][order], kin.rho2_normal[ic][order], float(pitch), float(k),
                   float(m * pitch + c), float(m))

    def r_eq(self, s):
        """Equivalent normal radius ρ1n ρ2n/(ρ1n + ρ2n) at roll distance ``s``.

        Parameters
        ----------
        s : array_like
            Roll distance [m].

        Returns
        -------
        ndarray
            r_eq [m].
        """
        r1, r2 = np.interp(s, self.s, self.rho1), np.interp(s, self.s, self.rho2)
        return r1 * r2 / (r1 + r2)

    def u_r(self, s):
        """Rolling velocity at roll distance ``s``.

        Parameters
        ----------
        s : array_like
            Roll distance [m].

        Returns
        -------
        ndarray
            u_r [m/s].
        """
        return self.u_p + self.m * (np.asarray(s) - self.pitch)

    def sr(self, s):
        """Slide-to-roll ratio |u_s|/u_r at roll distance ``s``.

        Parameters
        ----------
        s : array_like
            Roll distance [m].

        Returns
        -------
        ndarray
            SR [-].
        """
        return np.abs(self.k * (np.asarray(s) - self.pitch)) / self.u_r(s)

    def roll_at(self, sr, side: float) -> np.ndarray:
        """Roll distance at slide-to-roll ratio ``sr`` on one side of the pitch point.

        From SR (u_p + m t) = ±k t, t = s − s_p.

        Parameters
        ----------
        sr : array_like
            Slide-to-roll ratio [-].
        side : float
            +1 for the recess side (s > s_p), −1 for the approach side [-].

        Returns
        -------
        ndarray
            s [m].
        """
        sr = np.asarray(sr, dtype=float)
        t = sr * self.u_p / (side * abs(self.k) - sr * self.m)
        return self.pitch + t


# ---------------------------------------------------------------------- one constructor from a spec string
def friction_from_spec(spec: str, lubricant="atf", *, clip_to_fitted_ranges: bool = True,
                       oil_type: str | None = None) -> Callable:
    """A friction model from its short specification (the ``--friction`` option).

    * ``constant:0.05`` → :class:`ConstantFriction`;
    * ``xu2007``, ``benedict_kelley``, ``iso14179[:OIL_TYPE]`` → :class:`PublishedFriction` with ``lubricant``
      (name, file or :class:`~ehl_dataset.model.lubricant.Lubricant`) for the inlet viscosity; ISO/TR 14179-2's
      X_L from OIL_TYPE, else ``oil_type``, else the lubricant file's ``oil_type``, else mineral;
    * ``ehl:LEVEL[:EFFECTS]`` → :class:`EhlFriction` (the EHL solver at every point; EFFECTS ``auto`` or ``full``);
    * ``ehl-grid:LEVEL[:EFFECTS][:NSxNP]`` → :class:`EhlGridFriction` (NS roll × NP load nodes per side);
    * anything else is a coefficient file path or shipped coefficient name (``atf``, ``atf_quick``,
      ``atf_quick_learned``; Eq. 9 or learned form) →
      :class:`surrogate.evaluate.FrictionSurrogate` (with its own lubricant), its inputs clipped to the fitted
      ranges unless ``clip_to_fitted_ranges`` is False (gear contacts leave the factorial's ranges; Eq. 9 must not
      extrapolate).

    Parameters
    ----------
    spec : str
        The specification, one of the forms above [-].
    lubricant : str or Path or Lubricant
        Lubricant of the published formulas and the EHL models (shipped name, TOML path or object) [-].
    clip_to_fitted_ranges : bool
        Clip a surrogate's inputs to its fitted ranges [-].
    oil_type : str, optional
        Oil type of ISO/TR 14179-2's lubricant factor X_L [-].

    Returns
    -------
    callable
        μ(p_h, r_eq, u_r, sr, temperature, rq1, rq2) in SI, vectorised.
    """
    if not isinstance(spec, str) or not spec.strip():
        raise InputError("friction", spec, SPEC_FORMS)
    text = spec.strip()
    head, _, rest = text.partition(":")
    if head.lower() in ("ehl", "ehl-grid"):
        return _ehl_from_spec(text, head.lower(), rest, lubricant)
    if text.startswith("constant:"):
        try:
            mu = float(text.split(":", 1)[1])
        except ValueError:
            raise InputError("friction", text, "constant:MU with a number MU in [0, 1]") from None
        return ConstantFriction(mu)
    if text.lower().startswith("iso14179:"):
        return PublishedFriction("iso_tr_14179_2", _lubricant(lubricant), oil_type=text.split(":", 1)[1].strip())
    if text.lower() in PUBLISHED_NAMES:
        return PublishedFriction(PUBLISHED_NAMES[text.lower()], _lubricant(lubricant), oil_type=oil_type)
    from surrogate.evaluate import FrictionSurrogate

    return FrictionSurrogate.load(text, clip_to_fitted_ranges=clip_to_fitted_ranges)


def _lubricant(lubricant):
    from ehl_dataset.model.lubricant import Lubricant, load_lubricant

    return lubricant if isinstance(lubricant, Lubricant) else load_lubricant(lubricant)


def _ehl_from_spec(spec: str, kind: str, rest: str, lubricant) -> Callable:
    """``ehl:LEVEL[:EFFECTS]`` or ``ehl-grid:LEVEL[:EFFECTS][:NSxNP]`` (``rest`` is what follows the first colon)."""
    parts = [p for p in rest.split(":") if p] if rest else []
    level = parts.pop(0) if parts else "fast"
    if level not in LEVELS:
        raise InputError("friction", spec, f"an EHL level of {sorted(LEVELS)} after '{kind}:'")
    effects = "auto"
    if parts and parts[0] in EHL_EFFECTS:
        effects = parts.pop(0)
    lub = _lubricant(lubricant)
    if kind == "ehl":
        if parts:
            raise InputError("friction", spec, SPEC_FORMS)
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
        raise InputError("friction", spec, SPEC_FORMS)
    return EhlGridFriction(lub, level, effects, **nodes)


def describe_friction(friction, short: bool = False) -> str:
    """One line naming a friction model for reports.

    The model's own ``describe()`` if it has one; a published formula with its lubricant, a coefficient-file surrogate
    with its path.

    Parameters
    ----------
    friction : callable
        The friction model [-].
    short : bool
        The form a power-loss result records (:attr:`~efficiency.power_loss.PowerLossResult.friction_model`): without
        the lubricant and the path, a surrogate by its class name [-].

    Returns
    -------
    str
        The description.
    """
    if hasattr(friction, "describe"):
        return str(friction.describe())
    if isinstance(friction, ConstantFriction):
        return f"constant mu={friction.mu:g}"
    if isinstance(friction, PublishedFriction):
        return f"published {friction.name}" + ("" if short else
                                               f" ({getattr(friction.lubricant, 'name', 'lubricant')})")
    if isinstance(friction, EhlFriction):
        return f"EHL solver level={friction.level} effects={_effects_name(friction.effects)}"
    path = getattr(getattr(friction, "coefficients", None), "path", "")
    return f"surrogate {path}" if (path and not short) else type(friction).__name__
