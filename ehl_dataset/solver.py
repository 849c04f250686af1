"""Public entry of the EHL line-contact solver: :func:`solve_contact`.

    result = solve_contact(case, lubricant, level="standard", effects="auto")

* ``case`` — :class:`~ehl_dataset.model.contact.ContactCase` (SI).
* ``lubricant`` — :class:`~ehl_dataset.model.lubricant.Lubricant` (or a shipped name / TOML path).
* ``level`` — accuracy level name (:mod:`ehl_dataset.solvers.levels`).
* ``effects`` — ``"auto"`` (ask :func:`ehl_dataset.solvers.planner.plan_effects`), ``"isothermal"`` (the same
  plan without the thermal correction), ``"full"`` or an :class:`~ehl_dataset.model.effects.Effects` used as given.

Smooth cases (no roughness effect, or S_c = 0) go to the steady solver (:mod:`ehl_dataset.solvers.steady`: a smooth
contact under constant load and speed has a steady solution, which is what a transient run would settle to, so the
````transient`` flag changes nothing for smooth surfaces); rough surfaces with the ``roughness`` effect go where the
plan's ``model`` decision sends them (:data:`MODELS`): the steady film-law homogenised model
(:mod:`ehl_dataset.solvers.homogenised`) at ``fast`` and ``standard``, and the deterministic mixed reference
(:mod:`ehl_dataset.solvers.deterministic`) at ``reference`` and wherever the effects are forced with ``transient``
on (``effects="full"``): it is the package's one transient rough solver. ``model="homogenised"`` and
``model="deterministic"`` ask for those models whatever the plan; the result's effects then record what that model
simulates, with the planner's choice kept in the reasons (:func:`~ehl_dataset.solvers.planner.with_model`).

Every dataset file records ``ehl_dataset.solver:solve_contact`` and imports it on resume, and the store compares
:data:`SOLVER_VERSION` with the recorded one: both stay here whatever moves behind them.

The returned :class:`~ehl_dataset.solvers.result.ContactResult` always says whether the solve converged; a
non-converged result carries its residuals and a message.
"""

from __future__ import annotations

from threadpoolctl import threadpool_limits

from .model.contact import ContactCase
from .model.effects import Effects
from .model.lubricant import Lubricant, load_lubricant
from .model.roughness import RoughnessProfile
from .solvers.deterministic import DeterministicOptions, deterministic_options
from .solvers.wide_contact import solve_deterministic_contact
from .solvers.homogenised import HomogenisedOptions, solve_homogenised
from .solvers.levels import AccuracyLevel, get_level
from .solvers.planner import resolve_effects, with_model, without_thermal
from .solvers.result import ContactResult
from .solvers.steady import solve_steady
from .validation import InputError, check_time_limit

SOLVER_VERSION = "ehl-2026.11-15"
"""Version of the numerics behind :func:`solve_contact`. The dataset store records it and refuses to resume a file
computed with another version: bump it with every change that can alter a solved value. The deterministic model's
numerics carry their own version (:data:`ehl_dataset.solvers.deterministic.MODEL_VERSION`, recorded in the files that
use it: ``model="deterministic"`` or the ``reference`` level), so a change of that model alone bumps only it
(det-2026.11-9: Courant 0.25; det-2026.11-11: the cancellation-free logarithmic face mean)."""

MODELS = ("auto", "smooth", "homogenised", "deterministic")
"""Contact models :func:`solve_contact` can be asked for: ``auto`` (the effect plan decides: steady smooth; for rough
surfaces the steady homogenised model with the film-law closure where the contact is at least the planner's
``a_over_beta_homogenised`` correlation lengths wide, else the level's ``rough_model``: the same film-law model at
``fast`` and ``standard`` (outside its validated range, recorded), the deterministic solver at ``reference``; forced
effects with ``transient`` on run the deterministic solver at the level's grid rule too), ``smooth``
(steady smooth surfaces whatever the roughness), ``homogenised``
(the steady two-scale mixed model, :mod:`ehl_dataset.solvers.homogenised`, with the closure of ``homogenised``;
errors against the reference in docs/homogenised_model.md), ``deterministic`` (the deterministic mixed reference
solver, :mod:`ehl_dataset.solvers.deterministic`, for rough surfaces).

Version history of what can change a solved value: ehl-2026.11-8 added the thermal correction of the traction;
ehl-2026.11-9 makes ``auto`` solve wide rough contacts (a/β ≥ 15 at ``fast`` and ``standard``) by the film-law
homogenised model instead of the transient solver; ehl-2026.11-10 makes ``auto`` at ``reference`` solve rough
contacts by the deterministic solver (the accuracy reference) instead of the transient solver; ehl-2026.11-11 makes
``auto`` at ``fast`` and ``standard`` solve narrow rough contacts (a/β < 15) by the film-law homogenised model too,
instead of the transient solver (docs/narrow_contacts.md); ehl-2026.11-12 keeps the film law for narrow contacts
within its measured range (λ̄ > 1 or X_h ≥ 150) whatever the level's rough model, and its deterministic model
det-2026.11-10 accepts a Newton solve stalled at the round-off floor instead of splitting the step; ehl-2026.11-13
gives the film law on narrow contacts a micro-EHL pressure-fluctuation closure (film-law-2026.11-2,
:mod:`ehl_dataset.model.micro_pressure`) and widens its measured range to the unsaturated narrow contacts with
λ̄ ≥ 0.1 and roughness parameter α ≤ 2.5 (docs/narrow_contacts.md); ehl-2026.11-14 makes the closure's c a function
of the inlet length in correlation lengths on every contact, narrow and wide, instead of a constant below a/β 15 and
none above (film-law-2026.11-3; the wide unsaturated contacts resolved whole were 40 % above the film law without
it), and extends the closure's measured range to wide contacts; ehl-2026.11-15 deletes the transient mixed solver
(its grid-dependent μ, recorded in docs/transient_solver_record.md) and sends forced effects with ``transient`` on
(``effects="full"``) on rough contacts to the deterministic solver at the level's grid rule."""

__all__ = ["solve_contact", "checked_inputs", "SOLVER_VERSION", "MODELS"]


def checked_inputs(case, lubricant) -> Lubricant:
    """The lubricant of a solve (a shipped name or TOML path is loaded) after checking that ``case`` is a
    :class:`ContactCase`; InputError otherwise."""
    if not isinstance(case, ContactCase):
        raise InputError("case", type(case).__name__, "a ContactCase")
    if isinstance(lubricant, str):
        lubricant = load_lubricant(lubricant)
    if not isinstance(lubricant, Lubricant):
        raise InputError("lubricant", type(lubricant).__name__, "a Lubricant, a shipped name or a TOML path")
    return lubricant


def solve_contact(case: ContactCase, lubricant: Lubricant | str, level: str | AccuracyLevel = "standard",
                  effects: str | Effects = "auto", roughness=None, time_limit_s: float | None = None,
                  model: str = "auto",
                  deterministic: DeterministicOptions | None = None,
                  homogenised: HomogenisedOptions | None = None, checkpoint=None) -> ContactResult:
    """Solve one line contact; see the module docstring. Bad input raises :class:`InputError`.

    ``time_limit_s``: wall-time budget [s] of a deterministic (rough, transient) solve; when it runs out the result is returned
    ``converged=False`` with a message naming the step reached (a sweep is not held up by one pathological point;
    the resumable pipeline can retry it). None: no limit. Steady smooth solves ignore it (they take < 1 s).

    ``roughness``: a :class:`~ehl_dataset.model.roughness.RoughnessProfile` (e.g. a measured trace from
    :func:`~ehl_dataset.model.roughness.load_profile`) whose shape both surfaces take in rough runs, scaled to the
    case's Rq1 and Rq2; None uses the shipped synthetic baseline profile.

    ``model``: one of :data:`MODELS`. ``deterministic``: the options of the deterministic model (None: those of the
    level, :func:`~ehl_dataset.solvers.deterministic.deterministic_options`). ``homogenised``: the closure options of
    the homogenised model (None: :class:`~ehl_dataset.solvers.homogenised.HomogenisedOptions` defaults). Smooth
    surfaces (S_c = 0) asked for either mixed model get the steady smooth solve, with the reason recorded.

    ``checkpoint``: for a resolved deterministic run only, where it saves its state and continues from it (e.g.
    :class:`ehl_dataset.dataset.checkpoint.FileCheckpoint`; runs of hours at ``reference``); any other route
    refuses it.
    """
    lubricant = checked_inputs(case, lubricant)
    if roughness is not None and not isinstance(roughness, RoughnessProfile):
        raise InputError("roughness", type(roughness).__name__, "a RoughnessProfile or None")
    if model not in MODELS:
        raise InputError("model", model, f"one of {list(MODELS)}")
    if deterministic is not None and not isinstance(deterministic, DeterministicOptions):
        raise InputError("deterministic", type(deterministic).__name__, "a DeterministicOptions or None")
    if homogenised is not None and not isinstance(homogenised, HomogenisedOptions):
        raise InputError("homogenised", type(homogenised).__name__, "a HomogenisedOptions or None")
    time_limit_s = check_time_limit(time_limit_s)
    state = lubricant.state(case.temperature)
    lvl = get_level(level)
    if model == "smooth":
        effects = Effects.smooth_steady(forced="model=smooth")
    plan = resolve_effects(effects, case, lubricant, lvl.name,
                           roughness.correlation_length if roughness is not None else None)
    if model in ("homogenised", "deterministic"):
        plan = with_model(plan, model, case.s_c > 0.0)
    # one BLAS thread per solve: the dense solves are small, and workers run one case per core
    with threadpool_limits(limits=1):
        # a rough plan with the transient on (the reference level's rough model, or forced effects) runs the
        # package's one transient rough solver: the deterministic model
        deterministic_route = model == "deterministic" or (plan.roughness and plan.transient and case.s_c > 0.0
                                                           and model == "auto")
        if checkpoint is not None and not deterministic_route:
            raise InputError("checkpoint", str(getattr(checkpoint, "path", checkpoint)),
                             "None unless the deterministic model solves the contact (model='deterministic', the "
                             "reference level's plan for a rough contact, or effects='full' on a rough contact)")
        if model == "homogenised":
            options = homogenised or HomogenisedOptions()
            # the film-law closure has the smooth solver's thermal correction; the flow-factor closures have none
            return solve_homogenised(case, state, lvl, plan if options.closure == "film_law"
                                     else _isothermal(plan, "homogenised"), roughness, options)
        if deterministic_route:
            return solve_deterministic_contact(case, state, _isothermal(plan, "deterministic"),
                                               deterministic or deterministic_options(lvl.name), roughness,
                                               time_limit_s, lvl.name, checkpoint)
        if plan.roughness and case.s_c > 0.0:  # the planner's homogenised choice
            return solve_homogenised(case, state, lvl, plan, roughness, HomogenisedOptions(closure="film_law"))
        return solve_steady(case, state, lvl, plan)


def _isothermal(plan: Effects, solver: str) -> Effects:
    """The plan a solver without a thermal model runs: ``thermal`` off, with the reason, if it was asked for."""
    if not plan.thermal:
        return plan
    return without_thermal(plan, f"thermal correction requested but the {solver} solver has no thermal model: "
                                 f"isothermal traction")
