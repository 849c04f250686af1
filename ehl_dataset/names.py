"""The names a user chooses among (accuracy levels, effect plans, contact models, closures), defined once.

The command line imports these tuples as argparse ``choices`` and the solver, the planner, the factorial reader and
the registries check against them, so a name added here is accepted everywhere at once. The module imports nothing
(building the command-line parser must not load the solver).
"""

from __future__ import annotations

LEVELS: tuple[str, ...] = ("fast", "standard", "reference")
"""Accuracy levels of the EHL solver, cheapest first; each is one entry of the level registry
:data:`ehl_dataset.solvers.levels.LEVELS` (steady grid, planner thresholds, deterministic grid rule)."""

DEFAULT_LEVEL = "standard"
"""The level :func:`ehl_dataset.solver.solve_contact` uses when none is given."""

EFFECT_PLANS: tuple[str, ...] = ("auto", "isothermal", "full")
"""Named effect plans: ``auto`` (the planner's), ``isothermal`` (the planner's without the thermal correction of the
traction: the isothermal data the paper's Eq. 9 was fitted to), ``full`` (every effect the solvers model)."""

CONTACT_EFFECT_PLANS: tuple[str, ...] = (*EFFECT_PLANS, "smooth")
"""The plans of one contact solve: :data:`EFFECT_PLANS` and ``smooth`` (the steady smooth solve, isothermal)."""

MODELS: tuple[str, ...] = ("auto", "smooth", "homogenised", "deterministic")
"""Contact models :func:`ehl_dataset.solver.solve_contact` can be asked for (``auto``: the effect plan decides)."""

ROUGH_MODELS: tuple[str, ...] = ("homogenised", "deterministic")
"""Models a level may send the rough contacts outside the film law's measured range to."""

CLOSURES: tuple[str, ...] = ("transverse", "isotropic", "film_law", "asperity")
"""Closures of the homogenised model: the flow factors ``transverse`` (1-D roughness, no side leakage) and
``isotropic`` (side leakage), ``film_law`` (smooth pressure, the measured film law, the dry-contact traction), or
``asperity`` (the film law with the load the surviving roughness carries: amplitude reduction, dry-contact table,
load balance)."""

FLUCTUATIONS: tuple[str, ...] = ("inlet", "spectral")
"""Forms of the film-law closures' micro-EHL pressure spread σ_p: ``inlet`` (c(L_in/β)·E'Δq/4, calibrated on the
baseline profile) or ``spectral`` (E'Δq_f/4, Δq_f the slope of the part of the profile's spectrum that the
conjunction flattens; no fitted constant)."""

DEFAULT_FLUCTUATIONS = "spectral"
"""The pressure-spread form of the film-law closures when none is given."""

DEFAULT_CLOSURE = "transverse"
"""The closure of ``model="homogenised"`` when none is given."""
