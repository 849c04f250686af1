"""The effect planner (docs/explanation/planner.md): which physical effects one EHL contact solve needs, and why.

:func:`plan_effects` computes the case's dimensionless numbers and switches an effect off only where a measured
threshold says it does not change the result beyond the level's tolerance (the calibration is in
``docs/explanation/planner.md`` and ``tests/ehl_dataset/test_planner.py``):

* **roughness and transient** — film parameter λ̄ = h_min,DH/S_c (Dowson–Higginson minimum film over the
  composite roughness S_c = √(Rq1² + Rq2²), as in the paper). At λ̄ ≥ ``lambda_smooth`` the surfaces no longer touch and
  μ of the rough solve equals that of the steady smooth solve within the level's tolerance: solve the steady smooth
  problem (the saving: one steady solve instead of hundreds of time steps). Moving roughness is what makes a line
  contact transient, so both flags go together. S_c = 0 gives λ̄ = ∞. The ``model`` decision says which solver that
  means: steady smooth; for a rough contact at least ``a_over_beta_homogenised`` roughness correlation lengths wide
  (a/β, β of the roughness profile), the steady homogenised model (the roughness is a
  homogeneous micro-scale there: measured against the deterministic model in docs/explanation/mixed-regime.md, "Film-law
  closure"), so ``transient`` is off; so is a narrower rough contact above λ̄ = 1, with an Eyring-saturated traction
  (X_h ≥ 150, see below), or within the range where the film law's micro-EHL pressure-fluctuation closure was calibrated
  (λ̄ ≥ 0.1 and Greenwood–Tripp roughness parameter α = S_c·r_eq/a² ≤ 2.5), where the film law is measured within 10 %
  in median (docs/explanation/mixed-regime.md); the other narrow rough contacts go to the level's ``rough_model``: the
  same film-law model at ``fast`` and ``standard``, recorded as outside its validated range (no cheap model is within
  those levels' tolerance there), the deterministic solver (the package's transient rough solver) at ``reference``.
  A rough contact narrower than ``a_over_beta_point_contact`` (a/β below 1.8 at ``fast`` and ``standard``) is
  point-like: narrower than the roughness, a few asperity pairs carry part of its load; it goes to the steady
  homogenised model too. Every rough contact the homogenised model runs gets the asperity-load closure on the film law
  (recorded as ``reasons["closure"]``, read by :func:`planned_closure`): where no asperity touches it is the film law
  itself, and against the deterministic reference on both shipped profiles it is within its acceptance where the film
  law alone misses the asperity load (docs/explanation/mixed-regime.md, "The asperity-load closure").
* **shear thinning** — inlet Eyring number X_in = η0·|u_s|/(τ0·h_min,DH): sinh(τ_m/τ0) of the Couette shear where
  the film is formed (the inlet, at ambient viscosity). The Eyring flow factor is √(1 + X²), and only the inlet flow
  shapes the film: in the Hertz zone the Poiseuille flow is negligible whatever its factor. The Eyring number at the
  Hertz pressure, X_h = η(p_h)·|u_s|/(τ0·h_min,DH), does not predict the effect (docs/explanation/planner.md measures
  both); X_h is recorded (it says how deep in the Eyring plateau the traction is), X_in decides. SR = 0 gives X = 0
  (exact).
* **compressibility** — Dowson–Higginson density change ρ(p_h)/ρ0 − 1 (paper Eq. 6) is recorded; compressibility
  costs nothing to simulate and moves h_c by 13–19 % at the factorial's loads (docs/explanation/ehl-model.md), so the
  planner always keeps it (a lubricant file may declare itself incompressible; the solver then uses ρ = ρ0).
* **thermal** — the predicted relative reduction of the Couette traction at the Hertz centre by shear heating of
  the film and the flash temperature of the surfaces (:func:`ehl_dataset.model.thermal.centre_estimate`: η(p_h) and
  β(p_h) of the lubricant, Moes' central film, Blok's maximum flash temperature of a Hertzian heat flux, the
  film's conduction solution). At or below ``thermal_change`` the isothermal traction is kept. u_s = 0 or a
  lubricant whose viscosity does not depend on temperature (β = 0) give exactly 0: skipped at every level. The
  Nahme number Na = β τ |u_s| h_c/k of the film, the flash and film-centre temperature rises and the Péclet numbers
  of the surfaces and of the film are recorded.

Also recorded (they choose no flag but tell the user which regime the case is in): SR, Moes M and L, p_h/p_a for
the two-slope viscosity law (above p_a the high-pressure branch α2 is active), S_c, h_min,DH, the thresholds used and
the level. The ``reference`` level skips only what is exactly absent (S_c = 0, SR = 0), so the accuracy study
measures the planner's approximations as part of each level's error.
"""

from __future__ import annotations

import math
from dataclasses import asdict, replace

from ..model.effects import Effects
from ..model.film_formulas import dimensionless_groups, dowson_higginson_min_film, moes_central_film
from ..model.lubricant import LubricantState, dowson_higginson_density
from ..model.roughness import default_profile
from ..model.thermal import centre_estimate
from ..names import EFFECT_PLANS
from ..validation import InputError
from .levels import PlannerThresholds, level_settings


CLOSURE_MEASURED_LAMBDA = 0.3
"""λ̄ from which the asperity-load closure, the planner's model for rough contacts, is within its measured errors
[-]. On the deterministic references it is within 6.5 % on the baseline profile's 12 validation cases (λ̄ 0.05–3.7,
where its constants were fitted), within 13 % on the baseline's roughness sweep at case A's conditions down to
λ̄ 0.33, and −17 % to +22 % on the flank-like reference's contact-carrying points at λ̄ 0.30–0.32 (their uncertainty
8–29 %); below λ̄ 0.3 the measured errors reach +49 % and +117 % on that sweep (λ̄ 0.2 and 0.12) and +42 % and +45 %
on the flank-like reference (λ̄ 0.064 and 0.10) (docs/explanation/roughness.md,
validation/results/flank_reference_closures.json)."""


def thresholds_for(level) -> PlannerThresholds:
    """The planner's thresholds at one accuracy level.

    Parameters
    ----------
    level : str or AccuracyLevel or Level
        A level name or a level of the registry :data:`ehl_dataset.solvers.levels.REGISTRY` [-].

    Returns
    -------
    PlannerThresholds
        The level's thresholds (docs/explanation/planner.md). An unknown level raises :class:`InputError`.
    """
    return level_settings(level).planner


def dimensionless_numbers(case, lubricant, correlation_length_m: float | None = None) -> dict[str, float]:
    """The numbers the planner decides from.

    Parameters
    ----------
    case : ContactCase
        Operating conditions [SI].
    lubricant : Lubricant or LubricantState
        A lubricant, whose temperature range is checked, or its state at the case's temperature, already checked [-].
    correlation_length_m : float, optional
        Correlation length β of the roughness profile; None: the default profile's [m].

    Returns
    -------
    dict of str to float
        ``lambda_bar``, ``a_over_beta`` (Hertz half width over β), ``h_min_dh_m``, ``s_c_m``, ``sr``,
        ``eyring_inlet`` (X_in), ``eyring_number`` (X_h at the Hertz pressure), ``tau_m_over_tau0`` (asinh X_h),
        ``eta_hertz_pa_s``, ``density_change`` (ρ(p_h)/ρ0 − 1), ``p_h_over_p_a`` (NaN if the law has no p_a),
        ``moes_m``, ``moes_l``, and the thermal estimate at the Hertz centre: ``thermal_change`` (predicted relative
        reduction of the Couette traction), ``flash_rise_k``, ``film_centre_rise_k``, ``nahme_number``,
        ``beta_hertz_per_k`` (β(p_h)), ``surface_peclet`` (u_i a/(2κ) of the slower surface), ``film_peclet``
        (ρ c u_r h_c²/(k a): convection against conduction across the film; the model assumes ≲ 1); units in the
        key names, the others dimensionless.
    """
    state = lubricant if isinstance(lubricant, LubricantState) else lubricant.state(case.temperature)
    e_red = case.e_reduced
    w = case.load_per_length
    h_dh = float(dowson_higginson_min_film(state.eta0, case.u_r, state.alpha1, e_red, case.r_eq, w))
    s_c = case.s_c
    lambda_bar = h_dh / s_c if s_c > 0 else math.inf
    eta_h = float(state.viscosity(case.p_h))
    eyring = eta_h * abs(case.u_s) / (state.tau0 * h_dh)
    u, g, w_dim = (float(v) for v in dimensionless_groups(state.eta0, case.u_r, state.alpha1, e_red, case.r_eq, w))
    # Moes (1992) line-contact parameters with the sum velocity u1 + u2 = 2 u_r: M = W (2U)^-1/2, L = G (2U)^1/4
    moes_m = w_dim * (2 * u) ** -0.5
    moes_l = g * (2 * u) ** 0.25
    density_change = float(dowson_higginson_density(case.p_h, 1.0)) - 1.0 if state.compressible else 0.0
    p_a = getattr(state.law, "p_a", 0.0) if state.law.kind == "two_slope" else 0.0
    h_c = float(moes_central_film(state.eta0, case.u_r, state.alpha1, e_red, case.r_eq, w))
    beta_h = float(state.viscosity_temperature_coefficient(case.p_h))
    thermal = centre_estimate(state.temperature_table(case.p_h), h_c, case.half_width, case.u1, case.u2, state.tau0,
                              state.thermal)
    props = state.thermal
    beta = correlation_length_m if correlation_length_m is not None else default_profile().correlation_length
    return {
        "lambda_bar": lambda_bar,
        "a_over_beta": case.half_width / beta,
        "roughness_parameter": s_c * case.r_eq / case.half_width ** 2,
        "h_min_dh_m": h_dh,
        "s_c_m": s_c,
        "sr": float(case.sr),
        "eyring_inlet": state.eta0 * abs(case.u_s) / (state.tau0 * h_dh),
        "eyring_number": eyring,
        "tau_m_over_tau0": math.asinh(eyring),
        "eta_hertz_pa_s": eta_h,
        "density_change": density_change,
        "p_h_over_p_a": case.p_h / p_a if p_a > 0 else math.nan,
        "moes_m": moes_m,
        "moes_l": moes_l,
        "thermal_change": thermal["thermal_change"],
        "flash_rise_k": thermal["flash_rise_k"],
        "film_centre_rise_k": thermal["film_centre_rise_k"],
        "nahme_number": thermal["nahme_number"],
        "beta_hertz_per_k": beta_h,
        "surface_peclet": min(case.u1, case.u2) * case.half_width / (2.0 * props.solid_diffusivity),
        "film_peclet": state.rho0 * props.oil_heat_capacity * case.u_r * h_c ** 2 / (props.oil_conductivity
                                                                                    * case.half_width),
    }


def narrow_film_law_range(nums: dict, limits: PlannerThresholds) -> tuple[bool, str]:
    """Whether the film law is within its measured range on a rough contact (narrow or wide) with the planner's numbers
    ``nums`` (:func:`dimensionless_numbers`) under ``limits``, and the limit that decides: ``lambda_bar`` (λ̄ above
    ``narrow_film_law_lambda``), ``eyring_number`` (X_h at or above ``narrow_film_law_eyring``), ``closure_range``
    (λ̄ ≥ ``narrow_closure_lambda`` and α ≤ ``narrow_closure_roughness``) — within —, or ``below_closure_lambda``,
    ``above_closure_roughness`` — outside."""
    lam, x_h, alpha = nums["lambda_bar"], nums["eyring_number"], nums["roughness_parameter"]
    if lam > limits.narrow_film_law_lambda:
        return True, "lambda_bar"
    if x_h >= limits.narrow_film_law_eyring:
        return True, "eyring_number"
    if lam < limits.narrow_closure_lambda:
        return False, "below_closure_lambda"
    if alpha > limits.narrow_closure_roughness:
        return False, "above_closure_roughness"
    return True, "closure_range"


def plan_effects(case, lubricant, level="standard", correlation_length_m: float | None = None) -> Effects:
    """Decide which effects to simulate for ``case`` with ``lubricant`` at accuracy ``level``.

    For a rough contact ``reasons`` also holds ``film_law_range``: ``within_measured_range`` (whether the film law
    with its pressure-fluctuation closure is within its measured range) and ``limit``, the limit that decided
    (``lambda_bar``, ``eyring_number``, ``closure_range``, ``below_closure_lambda`` or ``above_closure_roughness``:
    :func:`narrow_film_law_range`), and for one narrower than ``a_over_beta_homogenised`` the same under
    ``narrow_contact``; for every rough contact sent to the homogenised model ``closure`` is ``"asperity"`` and
    ``closure_range`` says whether λ̄ is within the closure's measured range (:data:`CLOSURE_MEASURED_LAMBDA`).

    Parameters
    ----------
    case : ContactCase
        Operating conditions [SI].
    lubricant : Lubricant
        The lubricant; the case's temperature is checked against its data [-].
    level : str or AccuracyLevel or Level
        Accuracy level, whose :class:`PlannerThresholds` apply [-].
    correlation_length_m : float, optional
        Correlation length β of the roughness profile; None: the default profile's [m].

    Returns
    -------
    Effects
        The plan, with ``mode="auto"`` and ``reasons`` holding the numbers, the thresholds and one sentence per
        decision.

    Raises
    ------
    InputError
        For an unknown level or a temperature outside the lubricant's data.
    """
    limits = thresholds_for(level)
    nums = dimensionless_numbers(case, lubricant, correlation_length_m)
    lam = nums["lambda_bar"]
    rough = not lam >= limits.lambda_smooth
    wide = nums["a_over_beta"] >= limits.a_over_beta_homogenised
    x_h = nums["eyring_number"]
    alpha = nums["roughness_parameter"]
    narrow_within, narrow_limit = narrow_film_law_range(nums, limits)
    narrow_valid = not wide and narrow_within
    point = rough and nums["a_over_beta"] < limits.a_over_beta_point_contact
    homogenised = rough and (wide or narrow_valid or point or limits.rough_model == "homogenised")
    a_b = f"a/beta={nums['a_over_beta']:.3g}"
    x_in = nums["eyring_inlet"]
    newtonian = x_in <= limits.eyring_newtonian
    change = nums["thermal_change"]
    thermal = change > limits.thermal_change
    decisions = {
        "roughness": (f"lambda_bar={lam:.3g} < {limits.lambda_smooth:g}: asperities and moving roughness matter"
                      if rough else
                      ("S_c=0: smooth surfaces" if math.isinf(lam) else
                       f"lambda_bar={lam:.3g} >= {limits.lambda_smooth:g}: roughness does not change mu within "
                       f"the level tolerance, steady smooth solve")),
        "transient": (f"{a_b} < {limits.a_over_beta_point_contact:g}: point-like contact, the steady asperity-load "
                      "closure: steady"
                      if point else
                      f"{a_b} >= {limits.a_over_beta_homogenised:g}: the roughness is a homogeneous micro-scale, its "
                      f"ensemble average replaces the time average: steady"
                      if homogenised and wide else
                      f"{a_b} < {limits.a_over_beta_homogenised:g}, but the level's rough model is the steady "
                      f"homogenised one: steady"
                      if homogenised else
                      "moving roughness makes the contact transient" if rough else
                      "smooth surfaces under constant load: steady"),
        "model": (f"homogenised model, asperity-load closure: point-like contact ({a_b} < "
                  f"{limits.a_over_beta_point_contact:g}, roughness parameter alpha={alpha:.3g}: narrower than the "
                  "roughness, a few asperity pairs carry part of the load, which the film law does not model; against "
                  "the deterministic model: docs/explanation/mixed-regime.md)"
                  if point else
                  f"homogenised model, asperity-load closure on the film law ({a_b} >= {limits.a_over_beta_homogenised:g}; against the "
                  "deterministic model's windows on the wide factorial corners: docs/explanation/mixed-regime.md)"
                  + ("" if narrow_within else
                     f"; outside the measured range of its pressure-fluctuation closure (X_h={x_h:.3g} < "
                     f"{limits.narrow_film_law_eyring:g}, "
                     + (f"lambda_bar={lam:.3g} < {limits.narrow_closure_lambda:g}: asperities carry load"
                        if narrow_limit == "below_closure_lambda" else
                        f"roughness parameter alpha={alpha:.3g} > {limits.narrow_closure_roughness:g}")
                     + "; docs/explanation/mixed-regime.md)")
                  if homogenised and wide else
                  f"homogenised model, asperity-load closure on the film law, on a narrow contact within its measured range ({a_b} < "
                  f"{limits.a_over_beta_homogenised:g}, but "
                  + (f"lambda_bar={lam:.3g} > {limits.narrow_film_law_lambda:g}"
                     if narrow_limit == "lambda_bar" else
                     f"Eyring number at p_h X_h={x_h:.3g} >= {limits.narrow_film_law_eyring:g}: Eyring-saturated "
                     "traction"
                     if narrow_limit == "eyring_number" else
                     f"lambda_bar={lam:.3g} >= {limits.narrow_closure_lambda:g} and roughness parameter "
                     f"alpha={alpha:.3g} <= {limits.narrow_closure_roughness:g}: the unsaturated traction with the "
                     "calibrated micro-EHL pressure-fluctuation closure")
                  + ": docs/explanation/mixed-regime.md)"
                  if homogenised and narrow_valid else
                  f"homogenised model, asperity-load closure on the film law, outside its validated range ({a_b} < "
                  f"{limits.a_over_beta_homogenised:g}, X_h={x_h:.3g} < {limits.narrow_film_law_eyring:g}, "
                  + (f"lambda_bar={lam:.3g} < {limits.narrow_closure_lambda:g}: asperities carry load, which the film "
                     "law does not model"
                     if narrow_limit == "below_closure_lambda" else
                     f"roughness parameter alpha={alpha:.3g} > {limits.narrow_closure_roughness:g}: the mean pressure "
                     "is not the Hertzian one the film law takes")
                  + "; docs/explanation/mixed-regime.md); the reference: level reference or model=deterministic"
                  if homogenised else
                  "deterministic mixed solver: the accuracy reference of rough contacts (docs/explanation/mixed-regime.md);"
                  " no thermal model"
                  if rough else "steady smooth solver"),
        "shear_thinning": (f"inlet Eyring number X_in={x_in:.3g} <= {limits.eyring_newtonian:g}: Newtonian "
                           f"flow (factor sqrt(1+X^2)-1={math.sqrt(1 + x_in ** 2) - 1:.2g})"
                           if newtonian else
                           f"inlet Eyring number X_in={x_in:.3g} > {limits.eyring_newtonian:g}: shear thinning in "
                           f"the inlet flow"),
        "compressibility": f"density change {nums['density_change']:.3g} at p_h: always simulated (costs nothing)",
        "thermal": (f"predicted thermal reduction of the traction {change:.3g} > {limits.thermal_change:g} "
                    f"(flash {nums['flash_rise_k']:.3g} K, film centre {nums['film_centre_rise_k']:.3g} K at the "
                    f"Hertz centre): thermal correction of the traction"
                    if thermal else
                    f"predicted thermal reduction of the traction {change:.3g} <= {limits.thermal_change:g}: "
                    f"isothermal traction"),
    }
    level_name = getattr(level, "name", level)
    reasons = {"level": str(level_name), "numbers": _json_safe(nums), "thresholds": _json_safe(asdict(limits)),
               "decisions": decisions}
    if rough:
        reasons["film_law_range"] = {"within_measured_range": bool(narrow_within), "limit": narrow_limit}
    if rough and not wide:
        reasons["narrow_contact"] = {"within_measured_range": bool(narrow_valid), "limit": narrow_limit}
    if homogenised:
        reasons["closure"] = "asperity"
        reasons["closure_range"] = {"within_measured_range": bool(lam >= CLOSURE_MEASURED_LAMBDA),
                                    "limit": "lambda_bar", "lambda_bar_from": CLOSURE_MEASURED_LAMBDA}
        if not lam >= CLOSURE_MEASURED_LAMBDA:
            decisions["model"] += (f"; lambda_bar={lam:.3g} < {CLOSURE_MEASURED_LAMBDA:g}: outside the asperity-load "
                                   "closure's measured range (errors up to +117 % measured there against the "
                                   "deterministic references: docs/explanation/roughness.md)")
    return Effects(roughness=rough, transient=rough and not homogenised, shear_thinning=not newtonian,
                   compressibility=True,
                   mode="auto", reasons=reasons, thermal=thermal)


def planned_closure(plan: Effects) -> str:
    """The closure of the homogenised model that a plan asks for.

    Parameters
    ----------
    plan : Effects
        A plan of :func:`plan_effects` (or any plan; without the planner's ``closure`` reason it is the film law) [-].

    Returns
    -------
    str
        ``"asperity"`` for every rough contact the planner sends to the homogenised model (the film law plus the load
        the surviving roughness carries: it is the film law wherever no asperity touches), else ``"film_law"``.
    """
    return str((plan.reasons or {}).get("closure", "film_law"))


def without_thermal(plan: Effects, why: str) -> Effects:
    """``plan`` with the thermal correction off and ``why`` recorded as its decision (the plan's reasons kept)."""
    reasons = dict(plan.reasons)
    reasons["decisions"] = {**reasons.get("decisions", {}), "thermal": why}
    return replace(plan, thermal=False, reasons=reasons)


def with_model(plan: Effects, model: str, rough: bool) -> Effects:
    """``plan`` as an explicitly requested ``model`` ("homogenised" or "deterministic") runs it, whatever the planner
    chose: roughness on for rough surfaces (``rough``: S_c > 0), the transient on for the deterministic model (it
    time-steps the moving roughness) and off for the homogenised one (steady: the ensemble average replaces the time
    average); smooth surfaces get the steady smooth solve. Each decision that changes, and the model decision, say
    so and keep the planner's own text."""
    roughness = rough
    transient = rough and model == "deterministic"
    reasons = dict(plan.reasons)
    decisions = dict(reasons.get("decisions", {}))
    changed = {"roughness": (plan.roughness, roughness), "transient": (plan.transient, transient)}
    for name, (planned, run) in changed.items():
        if planned != run:
            decisions[name] = (f"model={model} requested: {name} {'on' if run else 'off'}"
                               + (f" (the planner: {decisions[name]})" if name in decisions else ""))
    planner_model = decisions.get("model")
    decisions["model"] = (f"model={model} requested" + ("" if rough else ": smooth surfaces, steady smooth solve")
                          + (f" (the planner: {planner_model})" if planner_model else ""))
    reasons["decisions"] = decisions
    return replace(plan, roughness=roughness, transient=transient, reasons=reasons)


def resolve_effects(effects, case, lubricant, level="standard", correlation_length_m: float | None = None) -> Effects:
    """``"auto"`` → :func:`plan_effects`; ``"isothermal"`` → the same plan with the thermal correction off;
    ``"full"`` → :meth:`Effects.full`; an :class:`Effects` as given. ``correlation_length_m``: β of the roughness
    profile [m] (None: the default profile's)."""
    if isinstance(effects, Effects):
        return effects
    if effects == "auto":
        return plan_effects(case, lubricant, level, correlation_length_m)
    if effects == "isothermal":
        return without_thermal(plan_effects(case, lubricant, level, correlation_length_m),
                               "effects=isothermal: isothermal traction")
    if effects == "full":
        return Effects.full()
    raise InputError("effects", effects, f"one of {list(EFFECT_PLANS)} or an Effects instance")


def _json_safe(values: dict) -> dict:
    """Floats as JSON-safe values: inf → "inf", NaN → None (results are stored as JSON)."""
    out = {}
    for key, value in values.items():
        if isinstance(value, float) and math.isinf(value):
            out[key] = "inf" if value > 0 else "-inf"
        elif isinstance(value, float) and math.isnan(value):
            out[key] = None
        else:
            out[key] = value
    return out
