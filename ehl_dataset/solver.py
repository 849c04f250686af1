"""Public entry of the EHL line-contact solver: :func:`solve_contact`.

    result = solve_contact(case, lubricant, level="standard", effects="auto")

* ``case`` — :class:`~ehl_dataset.model.contact.ContactCase` (SI).
* ``lubricant`` — :class:`~ehl_dataset.model.lubricant.Lubricant` (or a shipped name / TOML path).
* ``level`` — accuracy level name (:mod:`ehl_dataset.solvers.levels`).
* ``effects`` — ``"auto"`` (ask :func:`ehl_dataset.solvers.planner.plan_effects`), ``"isothermal"`` (the same
  plan without the thermal correction), ``"full"``, ``"smooth"`` (steady smooth surfaces) or an
  :class:`~ehl_dataset.model.effects.Effects` used as given.

Smooth cases (no roughness effect, or S_c = 0) go to the steady solver (:mod:`ehl_dataset.solvers.steady`: a smooth
contact under constant load and speed has a steady solution, which is what a transient run would settle to, so the
``transient`` flag changes nothing for smooth surfaces); rough surfaces with the ``roughness`` effect go where the
plan's ``model`` decision sends them (:data:`MODELS`): the steady film-law homogenised model with the asperity-load
closure (:mod:`ehl_dataset.solvers.homogenised`) at ``fast`` and ``standard``, and the deterministic mixed reference
(:mod:`ehl_dataset.solvers.deterministic`) at ``reference`` and wherever the effects are forced with ``transient``
on (``effects="full"``): it is the package's one transient rough solver. ``model="homogenised"`` and
``model="deterministic"`` ask for those models whatever the plan; the result's effects then record what that model
simulates, with the planner's choice kept in the reasons (:func:`~ehl_dataset.solvers.planner.with_model`).

The inputs are checked and resolved once, at this boundary: :func:`~ehl_dataset.solvers.problem.resolve_contact`
builds a :class:`~ehl_dataset.solvers.problem.ContactProblem` (lubricant state, level of the registry, effect plan,
route and options) and :func:`solve_problem` runs it without checking again; a caller that solves many variants of
one problem may resolve once and call :func:`solve_problem` itself.

Every dataset file records ``ehl_dataset.solver:solve_contact`` and imports it on resume, and the store compares
:data:`SOLVER_VERSION` with the recorded one: both stay here whatever moves behind them.

The returned :class:`~ehl_dataset.solvers.result.ContactResult` always says whether the solve converged; a
non-converged result carries its residuals and a message.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from . import names
from .lazy import lazy_exports
from .model.contact import ContactCase
from .model.effects import Effects
from .model.lubricant import Lubricant
from .solvers.levels import AccuracyLevel
from .solvers.problem import ContactProblem, resolve_contact
from .solvers.result import ContactResult
from .solvers.threads import one_blas_thread
from .solvers.steady import solve_steady

if TYPE_CHECKING:
    from .solvers.deterministic import DeterministicOptions
    from .solvers.homogenised import HomogenisedOptions

# the mixed-model solvers (and their scipy.fft, scipy.interpolate, scipy.special imports) load on first use: a smooth
# solve does not need them
_LAZY = {"solve_homogenised": "ehl_dataset.solvers.homogenised",
         "HomogenisedOptions": "ehl_dataset.solvers.homogenised",
         "solve_deterministic_contact": "ehl_dataset.solvers.wide_contact",
         "DeterministicOptions": "ehl_dataset.solvers.deterministic"}
__getattr__, __dir__ = lazy_exports(__name__, _LAZY, globals())


def _entry(name: str):
    """The module attribute ``name``, imported on first use (a value set on the module, e.g. a test's stand-in,
    wins)."""
    return globals()[name] if name in globals() else __getattr__(name)

SOLVER_VERSION = "ehl-2026.11-17"
"""Version of the numerics behind :func:`solve_contact`. The dataset store records it and refuses to resume a file
computed with another version: bump it with every change that can alter a solved value. The deterministic model's
numerics carry their own version (:data:`ehl_dataset.solvers.deterministic.MODEL_VERSION`, recorded in the files that
use it: ``model="deterministic"`` or the ``reference`` level), so a change of that model alone bumps only it. What
each version changed is listed in CHANGELOG.md, "Solver versions"."""

MODELS = names.MODELS
"""Contact models :func:`solve_contact` can be asked for: ``auto`` (the effect plan decides: steady smooth for smooth
surfaces; for rough ones at ``fast`` and ``standard`` the steady film-law homogenised model with the asperity-load
closure (flagged where it is outside its validated range), at ``reference`` the deterministic solver; forced effects
with ``transient`` on run the deterministic solver at the level's grid rule), ``smooth`` (steady smooth surfaces
whatever the roughness), ``homogenised`` (the steady two-scale mixed model, :mod:`ehl_dataset.solvers.homogenised`,
with the closure of ``homogenised``; errors against the reference in docs/explanation/mixed-regime.md),
``deterministic`` (the deterministic mixed reference solver, :mod:`ehl_dataset.solvers.deterministic`, for rough
surfaces). What each solver version changed: CHANGELOG.md, "Solver versions"."""

__all__ = ["solve_contact", "solve_problem", "resolve_contact", "SOLVER_VERSION", "MODELS"]


def solve_contact(case: ContactCase, lubricant: Lubricant | str, level: str | AccuracyLevel = "standard",
                  effects: str | Effects = "auto", roughness=None, time_limit_s: float | None = None,
                  model: str = "auto",
                  deterministic: DeterministicOptions | None = None,
                  homogenised: HomogenisedOptions | None = None, checkpoint=None) -> ContactResult:
    """Solve one line contact: resolve the inputs once (:func:`~ehl_dataset.solvers.problem.resolve_contact`), then
    run the solver the resolution chose (:func:`solve_problem`); see the module docstring.

    Parameters
    ----------
    case : ContactCase
        Operating conditions [SI].
    lubricant : Lubricant or str
        The lubricant, or a shipped name or TOML path [-].
    level : str or AccuracyLevel
        Accuracy level (:data:`ehl_dataset.names.LEVELS`) [-].
    effects : str or Effects
        ``"auto"``, ``"isothermal"``, ``"full"``, ``"smooth"`` or an :class:`Effects` used as given [-].
    roughness : RoughnessProfile or None
        A profile (e.g. a measured trace from :func:`~ehl_dataset.model.roughness.load_profile`) whose shape both
        surfaces take in rough runs, scaled to the case's Rq1 and Rq2; None uses the default profile
        (:func:`~ehl_dataset.model.roughness.default_profile`) [m].
    time_limit_s : float or None
        Wall-time budget of a deterministic (rough, transient) solve; when it runs out the result is returned
        ``converged=False`` with a message naming the step reached. None: no limit. Steady solves ignore it [s].
    model : str
        One of :data:`MODELS` [-].
    deterministic : DeterministicOptions or None
        Options of the deterministic model (None: those of the level,
        :func:`~ehl_dataset.solvers.deterministic.deterministic_options`) [-].
    homogenised : HomogenisedOptions or None
        Closure options of the homogenised model (None: the defaults). On the planner's route (``model="auto"``)
        the planner's closure is used unless these name ``film_law`` or ``asperity``; the other options apply as
        given. Smooth surfaces (S_c = 0) asked for either
        mixed model get the steady smooth solve, with the reason recorded [-].
    checkpoint : object or None
        For a resolved deterministic run only, where it saves its state and continues from it (e.g.
        :class:`ehl_dataset.dataset.checkpoint.FileCheckpoint`; runs of hours at ``reference``); any other route
        refuses it [-].

    Returns
    -------
    ContactResult
        The result; it says whether the solve converged. Bad input raises
        :class:`~ehl_dataset.validation.InputError`.
    """
    return solve_problem(resolve_contact(case, lubricant, level, effects, roughness, time_limit_s, model,
                                         deterministic, homogenised, checkpoint))


def solve_problem(problem: ContactProblem) -> ContactResult:
    """Run the solver a resolved problem's route names; nothing is checked again.

    Parameters
    ----------
    problem : ContactProblem
        Inputs resolved by :func:`~ehl_dataset.solvers.problem.resolve_contact` [-].

    Returns
    -------
    ContactResult
        The result of the steady smooth solver, the homogenised model or the deterministic model.
    """
    p = problem
    # one BLAS thread per solve: the dense solves are small, and workers run one case per core
    with one_blas_thread():
        if p.route in ("homogenised", "film_law"):
            return _entry("solve_homogenised")(p.case, p.state, p.steady_level, p.plan, p.roughness, p.homogenised)
        if p.route == "deterministic":
            return _entry("solve_deterministic_contact")(p.case, p.state, p.plan, p.deterministic, p.roughness,
                                                         p.time_limit_s, p.level.name, p.checkpoint)
        return solve_steady(p.case, p.state, p.steady_level, p.plan)
