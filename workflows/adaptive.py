"""Adaptive sampling of contact conditions for the learned friction surrogate (``gearloss lubricant fit
--adaptive``).

Instead of a factorial grid, the training solves are chosen where the learned model is least sure:

1. a space-filling start: ``initial`` points of a scrambled Sobol' sequence over the factorial's box
   (:mod:`surrogate.sampling`);
2. rounds: the ensemble of :mod:`surrogate.mlp` is fitted on every solve so far; ``pool`` candidate points (a fresh
   seeded uniform sample of the box each round) are scored by the members' disagreement s(x) (the standard deviation
   of their ln μ), and the ``batch`` candidates with the largest s(x) are solved next — as one batch, by the
   executors of stage 1 (local processes or Dask), all points of a batch in parallel;
3. it stops when the budget of solves is spent, or when the fitted model's error on the off-grid validation set
   (:mod:`surrogate.offgrid`) meets the targets (median and 90th percentile of |Δμ/μ|).

Every batch is its own HDF5 store, ``DIR/adaptive/batch_NNN.h5`` (the route of the factorial: same solver, level,
effect plan, contact model and lubricant), so a run stopped at any moment continues where it stopped: a finished
batch is read back, an unfinished one is continued with its own points, and only then are new batches chosen.
Choices depend only on the solved data and the seeds, so a continued run makes the same choices as an uninterrupted
one.
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd

from ehl_dataset.validation import InputError, check_range

ADAPTIVE_DIR = "adaptive"
INITIAL_POINTS = 128
BATCH_POINTS = 64
POOL_FACTOR = 40
"""Candidates scored per chosen point in each round."""


@dataclass
class AdaptiveResult:
    """The solves of an adaptive run, the rounds and why it stopped.

    Parameters
    ----------
    table : pandas.DataFrame
        Every training solve (columns of the dataset store, SI) [-].
    rounds : list of dict
        One entry per round: points solved and the model's errors [-].
    stopped : str
        Why the run stopped (budget reached or targets met) [-].
    solves : int
        Training solves in all [-].
    wall_time_s : float
        Wall time of the run [s].
    batch_files : list of str
        The store of each batch [-].
    """

    table: pd.DataFrame
    rounds: list[dict[str, Any]] = field(default_factory=list)
    stopped: str = ""
    solves: int = 0
    wall_time_s: float = 0.0
    batch_files: list[str] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (without the table).

        Returns
        -------
        dict
            ``solves``, ``stopped``, ``rounds``, ``wall_time_s`` [s], ``batch_files``.
        """
        return {"solves": self.solves, "stopped": self.stopped, "rounds": self.rounds,
                "wall_time_s": self.wall_time_s, "batch_files": self.batch_files}


def choose_batch(ensemble, box, *, batch: int, pool: int, seed: int, lubricant, e_reduced: float,
                 sr_floor: float) -> tuple[np.ndarray, np.ndarray]:
    """The ``batch`` points of a seeded uniform candidate pool where the members disagree most.

    Parameters
    ----------
    ensemble : MlpEnsemble
        The current learned model [-].
    box : SampleBox
        The box candidates are drawn from [-].
    batch : int
        Points to choose [-].
    pool : int
        Candidates to score [-].
    seed : int
        Seed of the pool [-].
    lubricant : Lubricant
        The lubricant (features need η0(T), α1(T)) [-].
    e_reduced : float
        Reduced modulus [Pa].
    sr_floor : float
        |SR| floor of the evaluation [-].

    Returns
    -------
    tuple of numpy.ndarray
        (chosen points, dtype ``POINT_DTYPE`` [SI]; their disagreement s [-]).
    """
    from surrogate.features import compute_features
    from surrogate.mlp import feature_matrix
    from surrogate.sampling import unit_sample

    candidates = box.from_unit(unit_sample(pool, "random", seed))
    feats = compute_features(candidates["p_h"], candidates["r_eq"], candidates["u_r"],
                             np.maximum(np.abs(candidates["sr"]), sr_floor), candidates["temperature"],
                             candidates["rq1"], candidates["rq2"], lubricant, e_reduced)
    _, spread = ensemble.predict(feature_matrix(feats))
    order = np.argsort(-spread, kind="stable")[:batch]
    return candidates[order], spread[order]


def _read(path: Path) -> pd.DataFrame:
    from ehl_dataset.dataset.store import read_table

    return read_table(path, status=None)


def run_adaptive(out_dir: str | Path, factorial, lubricant, *, level: str, effects: str, model: str,
                 budget: int, initial: int = INITIAL_POINTS, batch: int = BATCH_POINTS, seed: int = 0,
                 offgrid_table: pd.DataFrame | None = None, target_median: float | None = None,
                 target_p90: float | None = None, workers: int = 1, scheduler: str | None = None,
                 progress: str = "auto", time_limit_s: float | None = None, e_reduced: float | None = None,
                 log=None, solver=None, roughness=None) -> AdaptiveResult:
    """Adaptive sampling of ``factorial``'s box (module docstring); returns every solve and the rounds.

    Parameters
    ----------
    out_dir : str or Path
        Run directory; batches go to ``out_dir/adaptive/`` [-].
    factorial : Factorial
        The factorial whose box and route (level, effects, model) are used [-].
    lubricant : Lubricant
        The lubricant [-].
    level, effects, model : str
        The route of stage 1 [-].
    budget : int
        Largest number of training solves [-].
    initial : int
        Points of the Sobol' start [-].
    batch : int
        Points per adaptive batch [-].
    seed : int
        Seed of the Sobol' start and of the candidate pools [-].
    offgrid_table : pandas.DataFrame, optional
        Solved off-grid validation sample; with a target, the run stops once the model meets it [SI].
    target_median, target_p90 : float, optional
        Targets of the off-grid relative error of μ (median, 90th percentile) [-].
    workers : int
        Local worker processes [-].
    scheduler : str, optional
        Dask scheduler address or ``dask-local`` [-].
    progress : str
        Progress mode of the runner [-].
    time_limit_s : float, optional
        Wall-time budget per solve [s].
    e_reduced : float, optional
        Reduced modulus (default steel on steel) [Pa].
    log : callable, optional
        Called with one line per round [-].
    solver : str or callable, optional
        Solve function (``"module:function"`` or a callable); None: the EHL solver [-].
    roughness : RoughnessChoice, optional
        Roughness profile of every batch's rough solves, recorded in each batch store
        (:func:`ehl_dataset.dataset.roughness_choice.choose_roughness`); None: the default profile [-].

    Returns
    -------
    AdaptiveResult
        Every solve (``table``), the rounds, the stop reason.
    """
    from ehl_dataset.model.materials import STEEL, reduced_modulus
    from surrogate.learned_fit import fit_learned
    from surrogate.sampling import SampleBox, sample_description, unit_sample

    from .sample_runs import run_sample

    for name, value, low in (("budget", budget, 1), ("initial", initial, 20), ("batch", batch, 1)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
            raise InputError(name, value, f"an integer >= {low}")
    if initial > budget:
        raise InputError("budget", budget, f">= the {initial} points of the space-filling start")
    for name, value in (("target_median", target_median), ("target_p90", target_p90)):
        if value is not None:
            check_range(name, value, 0.0, 10.0, low_inclusive=False)
    e_reduced = reduced_modulus(STEEL, STEEL) if e_reduced is None else e_reduced
    started = time.perf_counter()
    box = SampleBox.of_factorial(factorial)
    folder = Path(out_dir) / ADAPTIVE_DIR
    folder.mkdir(parents=True, exist_ok=True)
    route = {"lubricant": lubricant, "level": level, "effects": effects, "model": model, "workers": workers,
             "scheduler": scheduler, "progress": progress, "time_limit_s": time_limit_s, "solver": solver,
             "roughness": roughness}
    result = AdaptiveResult(table=pd.DataFrame())
    tables: list[pd.DataFrame] = []
    say = log or (lambda line: None)

    def solve(index: int, points: np.ndarray, kind: str) -> pd.DataFrame:
        path = folder / f"batch_{index:03d}.h5"
        desc = sample_description(factorial, points, name=f"{factorial.name}-adaptive-{index:03d}", kind=kind,
                                  seed=seed, purpose="adaptive training sample of a learned friction surrogate")
        run_sample(path, points, desc, **route)
        result.batch_files.append(path.name)
        return _read(path)

    def stored_points(index: int) -> np.ndarray | None:
        """The points of an existing batch file (a continued run solves exactly those)."""
        path = folder / f"batch_{index:03d}.h5"
        if not path.exists():
            return None
        from ehl_dataset.dataset.store import DatasetStore

        with DatasetStore.open(path) as store:
            return store.points()

    index = 0
    points = stored_points(0)
    points = box.from_unit(unit_sample(initial, "sobol", seed)) if points is None else points
    tables.append(solve(0, points, "sobol"))
    while True:
        table = pd.concat(tables, ignore_index=True)
        solves = len(table)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            calibration = np.arange(solves) < len(tables[0])  # the space-filling start (surrogate.mlp)
            fit = fit_learned(table, lubricant, e_reduced, seed=seed, calibration=calibration)
        entry: dict[str, Any] = {"round": index, "solves": solves,
                                 "oof_median_rel_err_mu": fit.cv["overall"]["median_rel_err_mu"],
                                 "wall_time_s": time.perf_counter() - started}
        met = False
        if offgrid_table is not None:
            from surrogate.coefficients import coefficients_payload, validate_coefficients
            from surrogate.evaluate import FrictionSurrogate
            from surrogate.offgrid import offgrid_errors

            surrogate = FrictionSurrogate(validate_coefficients(coefficients_payload(fit)))
            overall = offgrid_errors(surrogate, offgrid_table)["overall"]
            entry.update(offgrid_median_rel_err_mu=overall["median_rel_err_mu"],
                         offgrid_p90_rel_err_mu=overall["p90_rel_err_mu"])
            targets = [(target_median, overall["median_rel_err_mu"]), (target_p90, overall["p90_rel_err_mu"])]
            met = any(t is not None for t, _ in targets) and all(t is None or v <= t for t, v in targets)
        result.rounds.append(entry)
        say(_round_line(entry))
        if met:
            result.stopped = "off-grid target met"
            break
        if solves >= budget:
            result.stopped = "budget spent"
            break
        index += 1
        size = min(batch, budget - solves)
        points = stored_points(index)
        if points is None:
            points, _ = choose_batch(fit.ensemble, box, batch=size, pool=POOL_FACTOR * size, seed=seed + index,
                                     lubricant=lubricant, e_reduced=e_reduced, sr_floor=fit.sr_floor)
        tables.append(solve(index, points, "adaptive"))
    result.table = pd.concat(tables, ignore_index=True)
    result.solves = len(result.table)
    result.wall_time_s = time.perf_counter() - started
    return result


def _round_line(entry: dict[str, Any]) -> str:
    text = (f"adaptive round {entry['round']}: {entry['solves']} solves, out-of-fold median |rel err mu| "
            f"{entry['oof_median_rel_err_mu']:.2%}")
    if "offgrid_median_rel_err_mu" in entry:
        text += (f"; off-grid median {entry['offgrid_median_rel_err_mu']:.2%}, 90th percentile "
                 f"{entry['offgrid_p90_rel_err_mu']:.2%}")
    return text + f" ({entry['wall_time_s']:.0f} s)"
