"""Stage 1 of gearloss: the mixed-EHL line-contact solver, the factorial of contact conditions and its HDF5 store.

Layers (each imports only from the ones before it; ``tests/test_architecture.py`` checks it):

* :mod:`ehl_dataset.model` — physical models: contact case, materials, lubricant, roughness, effect plan, film
  formulas, traction;
* :mod:`ehl_dataset.discretisation` — grids, the Reynolds residual and Jacobian, the deflection matrix;
* :mod:`ehl_dataset.solvers` — Newton solver, the steady smooth solve, the homogenised and deterministic mixed
  models, time averaging, accuracy levels, the effect planner, the result record;
* :mod:`ehl_dataset.solver` — the public entry :func:`solve_contact` (recorded in every dataset file);
* :mod:`ehl_dataset.dataset` — factorials, the HDF5 store, the runner and its executors.

:mod:`ehl_dataset.validation` (input checks, ``InputError``/``SolverError``) and :mod:`ehl_dataset.data_files`
(the shipped-data locator) serve every stage of gearloss (docs/explanation/architecture.md).

The names below are re-exported here and imported on first use, so that ``import ehl_dataset.validation`` (which
every stage does) does not load the solver, numba and h5py.
"""

from .lazy import lazy_exports

_LAZY = {
    "solve_contact": "ehl_dataset.solver",
    "solve_problem": "ehl_dataset.solver",
    "resolve_contact": "ehl_dataset.solvers.problem",
    "ContactProblem": "ehl_dataset.solvers.problem",
    "SOLVER_VERSION": "ehl_dataset.solver",
    "ContactCase": "ehl_dataset.model.contact",
    "Material": "ehl_dataset.model.materials",
    "STEEL": "ehl_dataset.model.materials",
    "Lubricant": "ehl_dataset.model.lubricant",
    "load_lubricant": "ehl_dataset.model.lubricant",
    "RoughnessProfile": "ehl_dataset.model.roughness",
    "load_profile": "ehl_dataset.model.roughness",
    "Effects": "ehl_dataset.model.effects",
    "AccuracyLevel": "ehl_dataset.solvers.levels",
    "LEVELS": "ehl_dataset.solvers.levels",
    "get_level": "ehl_dataset.solvers.levels",
    "plan_effects": "ehl_dataset.solvers.planner",
    "ContactResult": "ehl_dataset.solvers.result",
    "DeterministicOptions": "ehl_dataset.solvers.deterministic",
    "Factorial": "ehl_dataset.dataset.factorial",
    "load_factorial": "ehl_dataset.dataset.factorial",
    "run_factorial": "ehl_dataset.dataset.runner",
    "resume_run": "ehl_dataset.dataset.runner",
    "read_table": "ehl_dataset.dataset.store",
    "read_metadata": "ehl_dataset.dataset.store",
    "InputError": "ehl_dataset.validation",
    "SolverError": "ehl_dataset.validation",
}

__all__ = sorted(_LAZY)
__getattr__, __dir__ = lazy_exports(__name__, _LAZY, globals())
