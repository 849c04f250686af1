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
plan's ``model`` decision sends them (:data:`MODELS`): the steady film-law homogenised model
(:mod:`ehl_dataset.solvers.homogenised`) at ``fast`` and ``standard``, and the deterministic mixed reference
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
"""Contact models :func:`solve_contact` can be asked for: ``auto`` (the effect plan decides: steady smooth; for rough
surfaces the steady homogenised model with the film-law closure where the contact is at least the planner's
``a_over_beta_homogenised`` correlation lengths wide, else the level's ``rough_model``: the same film-law model at
``fast`` and ``standard`` (outside its validated range, recorded; the asperity-load closure on point-like
contacts, a/β below the planner's ``a_over_beta_point_contact``), the deterministic solver at ``reference``; forced
effects with ``transient`` on run the deterministic solver at the level's grid rule too), ``smooth``
(steady smooth surfaces whatever the roughness), ``homogenised``
(the steady two-scale mixed model, :mod:`ehl_dataset.solvers.homogenised`, with the closure of ``homogenised``;
errors against the reference in docs/explanation/mixed-regime.md), ``deterministic`` (the deterministic mixed reference
solver, :mod:`ehl_dataset.solvers.deterministic`, for rough surfaces).

Version history of what can change a solved value: ehl-2026.11-8 added the thermal correction of the traction;
ehl-2026.11-9 makes ``auto`` solve wide rough contacts (a/β ≥ 15 at ``fast`` and ``standard``) by the film-law
homogenised model instead of the transient solver; ehl-2026.11-10 makes ``auto`` at ``reference`` solve rough
contacts by the deterministic solver (the accuracy reference) instead of the transient solver; ehl-2026.11-11 makes
``auto`` at ``fast`` and ``standard`` solve narrow rough contacts (a/β < 15) by the film-law homogenised model too,
instead of the transient solver (docs/explanation/mixed-regime.md); ehl-2026.11-12 keeps the film law for narrow
contacts
within its measured range (λ̄ > 1 or X_h ≥ 150) whatever the level's rough model, and its deterministic model
det-2026.11-10 accepts a Newton solve stalled at the round-off floor instead of splitting the step; ehl-2026.11-13
gives the film law on narrow contacts a micro-EHL pressure-fluctuation closure (film-law-2026.11-2,
:mod:`ehl_dataset.model.micro_pressure`) and widens its measured range to the unsaturated narrow contacts with
λ̄ ≥ 0.1 and roughness parameter α ≤ 2.5 (docs/explanation/mixed-regime.md); ehl-2026.11-14 makes the closure's c a
function
of the inlet length in correlation lengths on every contact, narrow and wide, instead of a constant below a/β 15 and
none above (film-law-2026.11-3; the wide unsaturated contacts resolved whole were 40 % above the film law without
it), and extends the closure's measured range to wide contacts; ehl-2026.11-15 deletes the transient mixed solver
(its grid-dependent μ) and sends forced effects with ``transient`` on
(``effects="full"``) on rough contacts to the deterministic solver at the level's grid rule; ehl-2026.11-16 makes
``auto`` at ``fast`` and ``standard`` solve point-like rough contacts (a/β < 1.8) by the asperity-load closure, and the
film law's rolling term there take a film without steps at the zone edges (film-law-2026.11-4); no contact of the
paper factorial (a/β ≥ 2.95) changes."""

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
        surfaces take in rough runs, scaled to the case's Rq1 and Rq2; None uses the shipped synthetic baseline [m].
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
