"""One contact solve with every input resolved once: :class:`ContactProblem` and :func:`resolve_contact`.

:func:`resolve_contact` is the boundary of the EHL stage: it checks the types, loads a lubricant given by name, takes
the lubricant's state at the case's temperature (the temperature's one check against the lubricant's data), looks the
level up in the registry (:data:`ehl_dataset.solvers.levels.REGISTRY`), asks the planner for the effect plan and
decides which solver runs it (the ``route``) with which options. The solvers behind
:func:`ehl_dataset.solver.solve_problem` accept the resolved problem and check nothing again (as scikit-learn's
``check_input=False`` paths); :func:`ehl_dataset.solver.solve_contact` resolves and solves.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

from ..model.contact import ContactCase
from ..model.effects import Effects
from ..model.lubricant import Lubricant, LubricantState, load_lubricant
from ..model.roughness import RoughnessProfile
from ..names import CONTACT_EFFECT_PLANS, MODELS
from ..validation import InputError, check_time_limit
from .levels import AccuracyLevel, Level, level_settings
from .planner import planned_closure, resolve_effects, with_model, without_thermal

if TYPE_CHECKING:  # imported where a route needs them: a smooth solve does not load the mixed models
    from .deterministic import DeterministicOptions
    from .homogenised import HomogenisedOptions

ROUTES = ("steady", "film_law", "homogenised", "deterministic")
"""Which solver a resolved problem runs: the steady smooth solver, the planner's film-law homogenised model, the
homogenised model asked for with ``model="homogenised"`` (its closure from the options), the deterministic model."""


@dataclass(frozen=True)
class ContactProblem:
    """A line-contact solve with its inputs resolved and checked (SI): what the solvers accept.

    Parameters
    ----------
    case : ContactCase
        Operating conditions (range-checked when built) [SI].
    lubricant : Lubricant
        The lubricant [-].
    state : LubricantState
        Its properties at the case's temperature (checked against its data) [SI].
    level : Level
        Accuracy level: steady grid, planner thresholds, deterministic grid rule [-].
    plan : Effects
        The effect plan the solver runs (the thermal correction off, with the reason, for a solver without a
        thermal model) [-].
    model : str
        The contact model asked for (:data:`ehl_dataset.names.MODELS`) [-].
    route : str
        The solver that runs (:data:`ROUTES`) [-].
    roughness : RoughnessProfile or None
        Shape of both surfaces in rough runs (None: the default profile) [m].
    homogenised : HomogenisedOptions or None
        Options of the homogenised routes (None on the others) [-].
    deterministic : DeterministicOptions or None
        Options of the deterministic route (None on the others) [-].
    time_limit_s : float or None
        Wall-time budget of a deterministic solve [s].
    checkpoint : object or None
        Where a deterministic run saves its state (only on that route) [-].
    """

    case: ContactCase
    lubricant: Lubricant
    state: LubricantState
    level: Level
    plan: Effects
    model: str
    route: str
    roughness: RoughnessProfile | None = None
    homogenised: HomogenisedOptions | None = None
    deterministic: DeterministicOptions | None = None
    time_limit_s: float | None = None
    checkpoint: Any = None

    @property
    def steady_level(self) -> AccuracyLevel:
        """Grid and stopping rules of the steady solves at the problem's level."""
        return self.level.steady


def resolve_lubricant(lubricant: Lubricant | str) -> Lubricant:
    """A lubricant given as an object, a shipped name or a TOML path, loaded once.

    Parameters
    ----------
    lubricant : Lubricant or str
        The lubricant, or the shipped name or TOML file to load it from [-].

    Returns
    -------
    Lubricant
        The lubricant; anything else raises :class:`~ehl_dataset.validation.InputError`.
    """
    if isinstance(lubricant, str):
        lubricant = load_lubricant(lubricant)
    if not isinstance(lubricant, Lubricant):
        raise InputError("lubricant", type(lubricant).__name__, "a Lubricant, a shipped name or a TOML path")
    return lubricant


def resolve_contact(case: ContactCase, lubricant: Lubricant | str, level: str | AccuracyLevel | Level = "standard",
                    effects: str | Effects = "auto", roughness: RoughnessProfile | None = None,
                    time_limit_s: float | None = None, model: str = "auto",
                    deterministic: DeterministicOptions | None = None, homogenised: HomogenisedOptions | None = None,
                    checkpoint=None) -> ContactProblem:
    """Check and resolve the inputs of one contact solve, once.

    Parameters
    ----------
    case : ContactCase
        Operating conditions [SI].
    lubricant : Lubricant or str
        The lubricant, or a shipped name or TOML path [-].
    level : str or AccuracyLevel or Level
        Accuracy level (:data:`ehl_dataset.names.LEVELS`) [-].
    effects : str or Effects
        ``"auto"`` (the planner), ``"isothermal"`` (the planner's plan without the thermal correction), ``"full"``,
        ``"smooth"`` (steady smooth surfaces, isothermal; :data:`ehl_dataset.names.CONTACT_EFFECT_PLANS`) or an
        :class:`~ehl_dataset.model.effects.Effects` used as given [-].
    roughness : RoughnessProfile or None
        Shape of both surfaces in rough runs, scaled to the case's Rq1 and Rq2 (None: the default profile) [m].
    time_limit_s : float or None
        Wall-time budget of a deterministic solve (None: no limit) [s].
    model : str
        Contact model (:data:`ehl_dataset.names.MODELS`) [-].
    deterministic : DeterministicOptions or None
        Options of the deterministic model (None: the level's) [-].
    homogenised : HomogenisedOptions or None
        Options of ``model="homogenised"`` (None: the defaults); their ``fluctuations`` also apply to the planner's
        film-law route [-].
    checkpoint : object or None
        Where a deterministic run saves its state; refused on any other route [-].

    Returns
    -------
    ContactProblem
        The resolved problem. Bad input raises :class:`~ehl_dataset.validation.InputError`.
    """
    if not isinstance(case, ContactCase):
        raise InputError("case", type(case).__name__, "a ContactCase")
    lubricant = resolve_lubricant(lubricant)
    if roughness is not None and not isinstance(roughness, RoughnessProfile):
        raise InputError("roughness", type(roughness).__name__, "a RoughnessProfile or None")
    if model not in MODELS:
        raise InputError("model", model, f"one of {list(MODELS)}")
    if deterministic is not None:
        from .deterministic import DeterministicOptions

        if not isinstance(deterministic, DeterministicOptions):
            raise InputError("deterministic", type(deterministic).__name__, "a DeterministicOptions or None")
    if homogenised is not None:
        from .homogenised import HomogenisedOptions

        if not isinstance(homogenised, HomogenisedOptions):
            raise InputError("homogenised", type(homogenised).__name__, "a HomogenisedOptions or None")
    time_limit_s = check_time_limit(time_limit_s)
    state = lubricant.state(case.temperature)
    settings = level_settings(level)
    if isinstance(level, AccuracyLevel):  # a level's steady part with changed numerics (e.g. a refinement study)
        settings = replace(settings, steady=level)
    if model == "smooth":
        effects = Effects.smooth_steady(forced="model=smooth")
    elif isinstance(effects, str) and effects == "smooth":
        effects = Effects.smooth_steady(forced="effects=smooth")
    elif not isinstance(effects, (str, Effects)) or (isinstance(effects, str) and effects not in CONTACT_EFFECT_PLANS):
        raise InputError("effects", effects, f"one of {list(CONTACT_EFFECT_PLANS)} or an Effects instance")
    plan = resolve_effects(effects, case, state, settings,
                           roughness.correlation_length if roughness is not None else None)
    rough = case.s_c > 0.0
    if model in ("homogenised", "deterministic"):
        plan = with_model(plan, model, rough)
    # a rough plan with the transient on (the reference level's rough model, or forced effects) runs the
    # package's one transient rough solver: the deterministic model
    if model == "deterministic" or (plan.roughness and plan.transient and rough and model == "auto"):
        route = "deterministic"
    elif model == "homogenised":
        route = "homogenised"
    elif plan.roughness and rough:  # the planner's homogenised choice
        route = "film_law"
    else:
        route = "steady"
    if checkpoint is not None and route != "deterministic":
        raise InputError("checkpoint", str(getattr(checkpoint, "path", checkpoint)),
                         "None unless the deterministic model solves the contact (model='deterministic', the "
                         "reference level's plan for a rough contact, or effects='full' on a rough contact)")
    options_h = options_d = None
    if route == "homogenised":
        from .homogenised import HomogenisedOptions

        options_h = homogenised or HomogenisedOptions()
        # the film-law closure (and the asperity closure built on it) has the smooth solver's thermal correction;
        # the flow-factor closures have none
        if options_h.closure not in ("film_law", "asperity"):
            plan = _isothermal(plan, "homogenised")
    elif route == "film_law":
        from .homogenised import HomogenisedOptions

        # the planner's closure unless the options name one of the two this route runs (film_law, asperity)
        if homogenised is None:
            options_h = HomogenisedOptions(closure=planned_closure(plan))
        elif homogenised.closure in ("film_law", "asperity"):
            options_h = homogenised
        else:
            options_h = replace(homogenised, closure=planned_closure(plan))
    elif route == "deterministic":
        from .deterministic import deterministic_options

        plan = _isothermal(plan, "deterministic")
        options_d = deterministic or deterministic_options(settings)
    return ContactProblem(case, lubricant, state, settings, plan, model, route, roughness, options_h, options_d,
                          time_limit_s, checkpoint)


def _isothermal(plan: Effects, solver: str) -> Effects:
    """The plan a solver without a thermal model runs: ``thermal`` off, with the reason, if it was asked for."""
    if not plan.thermal:
        return plan
    return without_thermal(plan, f"thermal correction requested but the {solver} solver has no thermal model: "
                                 f"isothermal traction")
