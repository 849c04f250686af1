"""The accuracy levels of the EHL solver: one registry, :data:`REGISTRY`, keyed by the level names of
:data:`ehl_dataset.names.LEVELS`.

A level is one :class:`Level`: the discretisation and stopping rules of the steady solves (:class:`AccuracyLevel`:
smooth, and the smooth part of the homogenised model), the effect planner's thresholds (:class:`PlannerThresholds`)
and the deterministic rough model's grid rule and averaging target (the fields of
:class:`ehl_dataset.solvers.deterministic.DeterministicOptions` it sets). The accuracy-versus-time study measures
what each level costs. Grid spacings of the steady grid are in units of the Hertz half width a. An unknown level
name is an error (:class:`~ehl_dataset.validation.InputError`); nothing falls back to another level.

Steady smooth grid: nodes are clustered (spacing ``dx_fine``) in two bands around the Hertz inlet (x ≈ −a) and the
outlet constriction/pressure spike (x ≈ +a), growing linearly over ``transition`` to ``dx_coarse`` elsewhere (see
:func:`ehl_dataset.discretisation.grid.clustered_grid`). A uniform grid would need 1,600–3,200 nodes at M > 100; the
clustered grids reach the same film accuracy with a few hundred (docs/explanation/ehl-model.md, "Discretisation and
solver").
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from types import MappingProxyType
from typing import Mapping

from ..names import LEVELS as LEVEL_NAMES, ROUGH_MODELS
from ..validation import InputError


@dataclass(frozen=True)
class AccuracyLevel:
    """Discretisation and tolerances of the steady solves at one accuracy level.

    Lengths are in units of the Hertz half width a. ``inlet_resolution`` caps the fine spacing at a fraction of the
    inlet length scale H_c^(2/3) (H_c = h_c r_eq/a², Moes' estimate): at heavy load the inlet meniscus zone and the
    outlet spike shrink like H_c^(2/3), and a fixed spacing would under-resolve them.

    Parameters
    ----------
    name : str
        Level name (:data:`ehl_dataset.names.LEVELS`) [-].
    x_start : float
        Inlet end of the domain, in units of a [-].
    x_end : float
        Outlet end of the domain, in units of a [-].
    dx_fine : float
        Fine grid spacing, in units of a [-].
    dx_coarse : float
        Coarse grid spacing, in units of a [-].
    inlet_band : tuple of float
        (start, end) of the fine band at the inlet, in units of a [-].
    outlet_band : tuple of float
        (start, end) of the fine band at the outlet, in units of a [-].
    transition : float
        Length over which the spacing grows from fine to coarse, in units of a [-].
    inlet_resolution : float
        Largest fine spacing as a fraction of the inlet length scale H_c^(2/3) [-].
    tol_residual : float
        Largest relative Reynolds residual (scaled by the Couette flux ρ̄H) [-].
    tol_load : float
        Largest relative load-balance error [-].
    tol_step : float
        Largest pressure correction, relative to p_h [-].
    max_iterations : int
        Newton iterations per continuation stage [-].
    """

    name: str
    x_start: float = -2.5
    x_end: float = 1.5
    dx_fine: float = 2.5e-3
    dx_coarse: float = 2.5e-2
    inlet_band: tuple[float, float] = (-1.15, -0.9)
    outlet_band: tuple[float, float] = (0.75, 1.06)
    transition: float = 0.25
    inlet_resolution: float = 0.1
    tol_residual: float = 1e-6
    tol_load: float = 1e-6
    tol_step: float = 1e-6
    max_iterations: int = 60

    def with_domain(self, x_start: float, x_end: float) -> "AccuracyLevel":
        """Copy with another domain, e.g. −2b…1.5b for the Huang case.

        Parameters
        ----------
        x_start : float
            Inlet end, in units of a [-].
        x_end : float
            Outlet end, in units of a [-].

        Returns
        -------
        AccuracyLevel
            The copy.
        """
        if not (x_start < -1.0 and x_end > 1.0):
            raise InputError("domain", (x_start, x_end), "x_start < −1 and x_end > 1 (units of the Hertz half width)")
        return replace(self, x_start=float(x_start), x_end=float(x_end))


WIDE_A_OVER_BETA = 15.0
"""a/β (Hertz half width over the roughness correlation length) from which a rough contact is wide: the planner
solves it by the steady film-law homogenised model (:attr:`PlannerThresholds.a_over_beta_homogenised` at ``fast``
and ``standard``) and ``DeterministicOptions(wide="auto")`` covers it by periodic windows
(:mod:`ehl_dataset.solvers.wide_contact`) instead of resolving the whole contact."""

NARROW_FILM_LAW_EYRING = 150.0
"""X_h from which the film law holds on narrow contacts below λ̄ 1 (ehl-2026.11-12). Against the deterministic
model, narrow rough contacts below λ̄ 1: at X_h ≥ 194 the film law is within 10 % on every point (4 factorial points
at fast; the reference cases I and J, −6.0 % and +6.6 %), at X_h ≤ 111 it is 16–80 % low on 10 of 11 points and on the
reference cases A, C and G (docs/explanation/mixed-regime.md); 150 is the geometric middle of the gap."""

NARROW_CLOSURE_LAMBDA = 0.1
"""λ̄ from which the film law with its pressure-fluctuation closure holds on contacts with an unsaturated traction
(ehl-2026.11-13 on narrow contacts, ehl-2026.11-14 on all). Below it the asperities carry load in the deterministic
model, which the film law, whose fluid carries the whole load, does not model: reference case B (λ̄ 0.054, asperity
share 0.66 at β/128) is −78 % with the closure, the narrow factorial corner at λ̄ 0.027 (share 0.18) −43 %, and the wide corner
at λ̄ 0.062 +162 % (−44 % without). Within the range the lowest λ̄ is 0.14 (+0.5 %); one factorial point at λ̄ 0.085 is
+4 %: validation/results/micro_pressure_closure.json, docs/explanation/mixed-regime.md."""

POINT_CONTACT_A_OVER_BETA = 1.8
"""a/β below which a rough contact is point-like and goes to the asperity-load closure (ehl-2026.11-16). Such a
contact is narrower than the roughness: the composite roughness curves the surfaces far more than r_eq (the
Greenwood–Tripp parameter α = S_c·r_eq/a² is 27–107 on the contacts measured) and a few asperity pairs carry the load.
Against the deterministic model on r_eq 12.4 mm, 10 m/s, 90 °C, Rq 0.4/0.4 µm (gear contact-line ends;
validation/results/narrow_point_contacts.json): at a/β 0.54 and 1.08, SR 0.054 and 0.3, the asperities carry 0.10–0.28
of the load, the film law is 67–124 % low (μ < 0 on one), the smooth model 77–95 % low, the asperity closure −20 % to
+10 % (the reference uncertain by about 20 %). The factorial's narrowest contacts (a/β 2.95, reference case A's size)
are within the film law's range where α ≤ 2.5; 1.8 is the geometric middle of 1.08 and 2.95."""

NARROW_CLOSURE_ROUGHNESS = 2.5
"""Greenwood–Tripp roughness parameter α = S_c·r_eq/a² up to which the closure holds (ehl-2026.11-13). The film law
takes the smooth Hertzian pressure as the mean pressure; where the composite roughness is large against the Hertz
approach a²/r_eq the mean pressure of a rough contact is lower and wider than Hertz's (Greenwood & Tripp 1967;
Johnson, Contact Mechanics, 1985, §13.3). Measured with the closure (ehl-2026.11-14): −2 % at α 1.8 (the largest α
within the range, a factorial point at λ̄ 0.44), 23–43 % low at α 3.6 on all 4 unsaturated points there (reference
case C and three factorial corners); 2.5 is the geometric middle (validation/results/micro_pressure_closure.json)."""


@dataclass(frozen=True)
class PlannerThresholds:
    """Thresholds of the effect planner (:mod:`ehl_dataset.solvers.planner`) at one accuracy level.

    Parameters
    ----------
    lambda_smooth : float
        λ̄ at or above which roughness and the transient are skipped [-].
    eyring_newtonian : float
        Inlet Eyring number X_in at or below which the flow is taken as Newtonian [-].
    tolerance : float
        Relative change of μ and h_min a skipped effect may cause at this level: what the planned-versus-full tests
        assert on cases straddling the thresholds [-].
    thermal_change : float
        Predicted relative reduction of the centre Couette traction at or below which the thermal correction is
        skipped [-].
    a_over_beta_homogenised : float
        a/β at or above which a rough contact is solved by the steady film-law homogenised model, within its
        validated range [-].
    rough_model : str
        Solver of the other narrow rough contacts (:data:`ehl_dataset.names.ROUGH_MODELS`): ``"homogenised"`` (the
        same film-law model, recorded as outside its validated range) or ``"deterministic"`` (the deterministic
        reference solver) [-].
    narrow_film_law_lambda : float
        A narrower rough contact is still within the film law's measured range above this λ̄, and is solved by it [-].
    narrow_film_law_eyring : float
        ... or at or above this Eyring number X_h at the Hertz pressure (an Eyring-saturated traction, τ ≈ τ0 ln(2X)
        linear in the pressure, which the micro-EHL pressure fluctuations leave unchanged in the mean) [-].
    narrow_closure_lambda : float
        The other narrow rough contacts are within the range where the film law's pressure-fluctuation closure was
        calibrated (:mod:`ehl_dataset.model.micro_pressure`) at λ̄ at or above this [-].
    narrow_closure_roughness : float
        ... and a Greenwood–Tripp roughness parameter α = S_c·r_eq/a² at or below this [-].
    a_over_beta_point_contact : float
        A rough contact narrower than this a/β is point-like: the steady homogenised model runs it with the
        asperity-load closure (0: never) [-].
    """

    lambda_smooth: float
    eyring_newtonian: float
    tolerance: float
    thermal_change: float = 0.0
    a_over_beta_homogenised: float = math.inf
    rough_model: str = "homogenised"
    narrow_film_law_lambda: float = math.inf
    narrow_film_law_eyring: float = math.inf
    narrow_closure_lambda: float = math.inf
    narrow_closure_roughness: float = 0.0
    a_over_beta_point_contact: float = 0.0

    def __post_init__(self):
        if self.rough_model not in ROUGH_MODELS:
            raise InputError("rough_model", self.rough_model, f"one of {list(ROUGH_MODELS)}")


@dataclass(frozen=True)
class Level:
    """One accuracy level: what every solver does at it.

    Parameters
    ----------
    steady : AccuracyLevel
        Grid and stopping rules of the steady solves (recorded in dataset files as the level's definition) [-].
    planner : PlannerThresholds
        Thresholds of the effect planner [-].
    deterministic : Mapping[str, float]
        Grid rule and averaging target of the deterministic model: fields of
        :class:`~ehl_dataset.solvers.deterministic.DeterministicOptions` (the others keep their defaults, which are
        the ``reference`` level's rule) [-].
    """

    steady: AccuracyLevel
    planner: PlannerThresholds
    deterministic: Mapping[str, float]

    @property
    def name(self) -> str:
        """The level's name (one of :data:`ehl_dataset.names.LEVELS`)."""
        return self.steady.name


REGISTRY: dict[str, Level] = {
    "fast": Level(
        AccuracyLevel("fast", dx_fine=6e-3, dx_coarse=4e-2, inlet_resolution=0.25, tol_residual=1e-5, tol_load=1e-5,
                      tol_step=1e-5, max_iterations=50),
        PlannerThresholds(lambda_smooth=3.5, eyring_newtonian=0.01, tolerance=0.05, thermal_change=0.04,
                          a_over_beta_homogenised=WIDE_A_OVER_BETA, rough_model="homogenised",
                          narrow_film_law_lambda=1.0, narrow_film_law_eyring=NARROW_FILM_LAW_EYRING,
                          narrow_closure_lambda=NARROW_CLOSURE_LAMBDA, narrow_closure_roughness=NARROW_CLOSURE_ROUGHNESS,
                          a_over_beta_point_contact=POINT_CONTACT_A_OVER_BETA),
        MappingProxyType(dict(points_per_beta=8.0, points_per_ell=0.625, inlet_resolution=0.3, mu_sem_target=0.10,
                              max_passes=6.0))),
    "standard": Level(
        AccuracyLevel("standard"),
        PlannerThresholds(lambda_smooth=5.0, eyring_newtonian=0.003, tolerance=0.02, thermal_change=0.016,
                          a_over_beta_homogenised=WIDE_A_OVER_BETA, rough_model="homogenised",
                          narrow_film_law_lambda=1.0, narrow_film_law_eyring=NARROW_FILM_LAW_EYRING,
                          narrow_closure_lambda=NARROW_CLOSURE_LAMBDA, narrow_closure_roughness=NARROW_CLOSURE_ROUGHNESS,
                          a_over_beta_point_contact=POINT_CONTACT_A_OVER_BETA),
        MappingProxyType(dict(points_per_beta=16.0, points_per_ell=1.25, inlet_resolution=0.2, mu_sem_target=0.03,
                              max_passes=12.0))),
    "reference": Level(
        AccuracyLevel("reference", dx_fine=6e-4, dx_coarse=8e-3, transition=0.2, inlet_resolution=0.03,
                      tol_residual=1e-7, tol_load=1e-9, tol_step=1e-7, max_iterations=80),
        PlannerThresholds(lambda_smooth=math.inf, eyring_newtonian=0.0, tolerance=0.0, thermal_change=0.0,
                          rough_model="deterministic"),
        MappingProxyType(dict(max_passes=40.0))),
}
"""The accuracy levels, keyed by :data:`ehl_dataset.names.LEVELS` (in that order). ``standard`` is the default of
:func:`ehl_dataset.solver.solve_contact`. Planner thresholds: justification and measurements in
docs/explanation/planner.md. Deterministic grid rule (the level names an error budget; what each costs and gives is
measured in docs/explanation/mixed-regime.md): the inlet term (det-2026.11-12; 0.1, the reference level's, at every
level before): on the smooth solution of the uniform grid against the steady solver's reference, over the validation
cases and six slow, hot, heavily loaded factorial corners, 0.3 L_in moves μ by ≤ 0.6 % and h_c by ≤ 3.2 %, 0.2 L_in by ≤
0.6 % and ≤ 1.5 % (validation/results/deterministic_inlet_resolution.json), within the ``fast`` and ``standard``
budgets, where 0.1 L_in made ``fast`` on case H (1.5 GPa, 1 m/s) a β/23 grid and a 1,830 s run."""

if tuple(REGISTRY) != LEVEL_NAMES:  # pragma: no cover - a definition error caught at import
    raise ImportError(f"level registry {tuple(REGISTRY)} differs from ehl_dataset.names.LEVELS {LEVEL_NAMES}")

LEVELS: Mapping[str, AccuracyLevel] = MappingProxyType({name: level.steady for name, level in REGISTRY.items()})
"""The steady part of each level of :data:`REGISTRY`, by name (read-only)."""


def level_settings(level: str | AccuracyLevel | Level) -> Level:
    """The registry entry of a level.

    Parameters
    ----------
    level : str or AccuracyLevel or Level
        A level name (:data:`ehl_dataset.names.LEVELS`), a level's steady part (its name is looked up; a copy made by
        :meth:`AccuracyLevel.with_domain` keeps it) or an entry, returned as is [-].

    Returns
    -------
    Level
        The entry. An unknown name raises :class:`~ehl_dataset.validation.InputError`.
    """
    if isinstance(level, Level):
        return level
    name = level.name if isinstance(level, AccuracyLevel) else level
    try:
        return REGISTRY[name]
    except (KeyError, TypeError):
        raise InputError("level", name, f"one of {sorted(REGISTRY)}") from None


def get_level(name: str | AccuracyLevel | Level) -> AccuracyLevel:
    """The steady part of a level.

    Parameters
    ----------
    name : str or AccuracyLevel or Level
        A level name (:data:`ehl_dataset.names.LEVELS`); an :class:`AccuracyLevel` is returned as is, a
        :class:`Level` gives its steady part [-].

    Returns
    -------
    AccuracyLevel
        The level's grid and stopping rules. An unknown name raises :class:`~ehl_dataset.validation.InputError`.
    """
    if isinstance(name, AccuracyLevel):
        return name
    return level_settings(name).steady
