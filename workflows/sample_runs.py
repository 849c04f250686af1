"""Solving a sample of contact conditions (not a factorial grid) into a resumable HDF5 store, by the route of a
factorial: the same solver, level, effect plan, contact model and lubricant, the same executors (local processes
or Dask) and the same store (:mod:`ehl_dataset.dataset.store`), so a run stopped by a signal continues where it
stopped when called again with the same arguments.

Used for the off-grid validation set of a fit (:func:`offgrid_points`) and for the batches of adaptive sampling
(:mod:`workflows.adaptive`).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ehl_dataset.validation import InputError

from .offgrid_defaults import OFFGRID_POINTS, OFFGRID_SEED


def offgrid_points(factorial, n: int = OFFGRID_POINTS, seed: int = OFFGRID_SEED):
    """The off-grid validation sample of ``factorial``: ``n`` independent uniform points of its box.

    Drawn by :func:`surrogate.sampling.sample_points` (kind ``random``).

    Parameters
    ----------
    factorial : Factorial
        The factorial whose box the sample fills [-].
    n : int
        Number of points [-].
    seed : int
        Seed [-].

    Returns
    -------
    tuple
        (points, a structured array of dtype ``POINT_DTYPE`` in SI; the description its store records).
    """
    from surrogate.sampling import sample_description, sample_points

    points = sample_points(factorial, n, kind="random", seed=seed)
    desc = sample_description(factorial, points, name=f"{factorial.name}-offgrid", kind="random", seed=seed,
                              purpose="off-grid validation of a friction surrogate fitted on this factorial's ranges")
    return points, desc


def run_sample(path: str | Path, points: np.ndarray, description: dict, *, lubricant, level: str, effects: str,
               model: str, workers: int = 1, scheduler: str | None = None, progress: str = "auto",
               time_limit_s: float | None = None, solver=None, roughness=None, **options):
    """Compute ``points`` into the store ``path``: created, or continued when it records the same points, solver,
    lubricant and roughness profile; anything else is refused with :class:`InputError`.

    Parameters
    ----------
    path : str or Path
        The HDF5 store [-].
    points : ndarray
        Structured array of dtype :data:`ehl_dataset.dataset.factorial.POINT_DTYPE` [SI].
    description : dict
        The plan the store records (:func:`surrogate.sampling.sample_description`) [-].
    lubricant : Lubricant
        The lubricant [-].
    level : str
        Accuracy level of the route of the factorial whose ranges the sample fills [-].
    effects : str
        Effect plan of that route [-].
    model : str
        Contact model of that route [-].
    workers : int
        Worker processes [-].
    scheduler : str, optional
        Address of a Dask scheduler; None: local processes [-].
    progress : str
        Progress display: ``auto``, ``bar``, ``log`` or ``none`` [-].
    time_limit_s : float, optional
        Wall-time budget per point [s].
    solver : str or callable, optional
        The solve function (``"module:function"`` or a callable); None: the EHL solver [-].
    roughness : RoughnessChoice, optional
        Roughness profile of the rough points (:func:`ehl_dataset.dataset.roughness_choice.choose_roughness`),
        recorded in the store; None: the default profile [-].
    **options
        Execution options of :func:`ehl_dataset.dataset.runner.execute` [-].

    Returns
    -------
    RunSummary
        The runner's summary.
    """
    from ehl_dataset.dataset.factorial import canonical_json
    from ehl_dataset.dataset.runner import (DEFAULT_SOLVER, check_recorded_roughness, check_time_limit,
                                            dataset_roughness, execute, solver_config)
    from ehl_dataset.dataset.store import DatasetStore

    solver = DEFAULT_SOLVER if solver is None else solver
    time_limit_s = check_time_limit(time_limit_s, solver)
    config = solver_config(solver, level, effects, model, roughness)
    lubricant_dict = json.loads(canonical_json(lubricant.to_json_dict()))
    t_lo, t_hi = lubricant.t_min, lubricant.t_max
    bad = (points["temperature"] < t_lo) | (points["temperature"] > t_hi)
    if bad.any():
        raise InputError("sample temperature", float(points["temperature"][bad][0]),
                         f"[{t_lo:g}, {t_hi:g}] K, the data range of lubricant {lubricant.name!r}")
    path = Path(path)
    if path.exists():
        store = DatasetStore.open(path, "r+")
        try:
            check_recorded_roughness(store, solver, roughness)
            store.check_compatible(factorial_sha256=description["points_sha256"], solver=config,
                                   lubricant=lubricant_dict, roughness=dataset_roughness(solver, roughness))
        except BaseException:
            store.close()
            raise
        kind = "continue"
    else:
        store = DatasetStore.create(path, points, factorial=description, solver=config, lubricant=lubricant_dict,
                                    roughness=dataset_roughness(solver, roughness))
        kind = "run"
    with store:
        return execute(store, solver=solver, workers=workers, scheduler=scheduler, kind=kind, progress=progress,
                       time_limit_s=time_limit_s, roughness=roughness, **options)
