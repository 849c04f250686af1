"""Stage 2 of the pipeline and of ``gearloss lubricant fit`` in both forms: the off-grid validation sample, the
adaptive training design, and the fit written to a coefficient file with its off-grid errors.

* :func:`offgrid_stage` solves the off-grid validation sample of a factorial (``OUT/offgrid.h5``, seeded uniform
  points in the factorial's ranges, :func:`workflows.sample_runs.offgrid_points`) by the factorial's route;
* :func:`adaptive_stage` runs :func:`workflows.adaptive.run_adaptive` (``OUT/adaptive/batch_NNN.h5``);
* :func:`fit_and_write` fits the chosen form (``eq9``: paper Eq. 9 with statsmodels; ``learned``: the ensemble of
  :mod:`surrogate.mlp`) on one or more dataset files and writes the coefficient file with the ``offgrid`` table.

The functions return plain dictionaries (artefact path, wall time, details); :mod:`workflows.pipeline` wraps them in
its stage results.
"""

from __future__ import annotations

import operator
import time
import warnings
from pathlib import Path
from typing import Any

import pandas as pd

from ehl_dataset.validation import InputError

from .sample_runs import OFFGRID_POINTS, OFFGRID_SEED, offgrid_points, run_sample

FORMS = ("eq9", "learned")
OFFGRID_FILE = "offgrid.h5"


CALIBRATION_ROWS = 9
"""Held-out rows a split-conformal 90 % factor needs: the ⌈(n + 1)·0.9⌉-th smallest of n scores exists from n = 9 on
(:func:`surrogate.mlp.conformal_quantile`; the split-conformal rank of Lei et al., *J. Am. Stat. Assoc.* 113, 2018)."""


def smallest_offgrid_sample(form: str) -> int:
    """The smallest off-grid sample whose even rows can calibrate the interval of ``form``: :data:`CALIBRATION_ROWS`
    even rows per interval, one interval per λ̄ branch for ``eq9`` (35 points), one for ``learned`` (17 points).
    It is necessary, not sufficient: the sample's split between the branches and its failed or excluded solves are
    known only once it is solved (:func:`validate_offgrid` then records the errors without calibrating).

    Parameters
    ----------
    form : str
        ``eq9`` or ``learned`` [-].

    Returns
    -------
    int
        Points [-].
    """
    even_rows = CALIBRATION_ROWS * (2 if check_form(form) == "eq9" else 1)
    return 2 * even_rows - 1


def check_offgrid_points(n: int, form: str, name: str = "offgrid_points") -> int:
    """``n`` if it is 0 (no off-grid sample) or a sample :func:`smallest_offgrid_sample` can calibrate, up to
    100,000; else one :class:`InputError` naming ``name``, the value and the accepted values, before anything is
    solved.

    Parameters
    ----------
    n : int
        Points of the off-grid sample [-].
    form : str
        ``eq9`` or ``learned`` [-].
    name : str
        The name of the option in the message (``--offgrid-points`` on the command line) [-].

    Returns
    -------
    int
        ``n`` [-].
    """
    smallest = smallest_offgrid_sample(form)
    try:
        n = operator.index(n)
    except TypeError:
        raise InputError(name, n, "an integer") from None
    if n != 0 and not smallest <= n <= 100000:
        branches = "on each of the two λ̄ branches" if form == "eq9" else "for the ensemble"
        raise InputError(name, n, f"0 (no off-grid sample) or {smallest} to 100000 with form {form}",
                         f"the even rows of the sample calibrate the 90 % interval: {CALIBRATION_ROWS} needed "
                         f"{branches}")
    return n


def check_form(form: str) -> str:
    """``form`` if it is one of :data:`FORMS`, else :class:`InputError`."""
    if form not in FORMS:
        raise InputError("form", form, f"one of {list(FORMS)}")
    return form


def coefficients_path(base: Path, form: str, adaptive: bool = False) -> Path:
    """The coefficient file of a run: ``<lubricant>_<factorial>[_adaptive][_learned].json`` beside ``base``.

    Parameters
    ----------
    base : Path
        The run's coefficient file of the default form (``<lubricant>_<factorial>.json``) [-].
    form : str
        Surrogate form, ``eq9`` or ``learned`` [-].
    adaptive : bool
        Whether the training design was adaptive [-].

    Returns
    -------
    Path
        The file.
    """
    stem = base.stem + ("_adaptive" if adaptive else "") + ("_learned" if form == "learned" else "")
    return base.with_name(stem + ".json")


def offgrid_stage(out_dir: str | Path, factorial, lubricant, *, level: str, effects: str, model: str,
                  n: int = OFFGRID_POINTS, seed: int = OFFGRID_SEED, workers: int = 1, scheduler: str | None = None,
                  progress: str = "auto", time_limit_s: float | None = None, roughness=None) -> dict[str, Any]:
    """Solve the off-grid validation sample of ``factorial`` into ``out_dir/offgrid.h5`` (resumable).

    Parameters
    ----------
    out_dir : str or Path
        Run directory [-].
    factorial : Factorial
        The factorial whose ranges the sample fills [-].
    lubricant : Lubricant
        The lubricant [-].
    level, effects, model : str
        The route of the factorial [-].
    n : int
        Points of the sample [-].
    seed : int
        Seed [-].
    workers : int
        Local worker processes [-].
    scheduler : str, optional
        Dask scheduler [-].
    progress : str
        Progress mode [-].
    time_limit_s : float, optional
        Wall-time budget per solve [s].
    roughness : RoughnessChoice, optional
        Roughness profile of the route (:func:`ehl_dataset.dataset.roughness_choice.choose_roughness`); None: the
        default profile [-].

    Returns
    -------
    dict
        ``artefact`` (the store), ``wall_time_s``, ``details`` (counts, seed, interrupted).
    """
    started = time.perf_counter()
    points, description = offgrid_points(factorial, n, seed)
    path = Path(out_dir) / OFFGRID_FILE
    summary = run_sample(path, points, description, lubricant=lubricant, level=level, effects=effects, model=model,
                         workers=workers, scheduler=scheduler, progress=progress, time_limit_s=time_limit_s,
                         roughness=roughness)
    details = {"n_points": summary.n_points, "seed": seed, "computed": summary.computed, "ok": summary.ok,
               "failed": summary.failed, "pending": summary.pending, "non_converged": summary.non_converged,
               "interrupted": summary.interrupted}
    return {"artefact": str(path), "wall_time_s": time.perf_counter() - started, "details": details}


def adaptive_stage(out_dir: str | Path, factorial, lubricant, *, level: str, effects: str, model: str, budget: int,
                   offgrid_path: str | Path | None = None, target_median: float | None = None,
                   target_p90: float | None = None, initial: int | None = None, batch: int | None = None,
                   workers: int = 1, scheduler: str | None = None,
                   progress: str = "auto", time_limit_s: float | None = None, log=None,
                   roughness=None) -> dict[str, Any]:
    """Adaptive training design (:func:`workflows.adaptive.run_adaptive`) with the off-grid set as stop test.

    Parameters
    ----------
    out_dir : str or Path
        Run directory [-].
    factorial : Factorial
        Box and route [-].
    lubricant : Lubricant
        The lubricant [-].
    level, effects, model : str
        The route [-].
    budget : int
        Largest number of training solves [-].
    offgrid_path : str or Path, optional
        Solved off-grid sample [-].
    target_median, target_p90 : float, optional
        Off-grid targets of |Δμ/μ| [-].
    initial, batch : int, optional
        Points of the Sobol' start and of each batch; None: :data:`workflows.adaptive.INITIAL_POINTS`,
        :data:`workflows.adaptive.BATCH_POINTS` [-].
    workers : int
        Local worker processes [-].
    scheduler : str, optional
        Dask scheduler [-].
    progress : str
        Progress mode of each batch [-].
    time_limit_s : float, optional
        Wall-time budget per solve [s].
    log : callable, optional
        Receives one line per round [-].
    roughness : RoughnessChoice, optional
        Roughness profile of the route; None: the default profile [-].

    Returns
    -------
    dict
        ``artefacts`` (batch files), ``wall_time_s``, ``details`` (solves, rounds, stop reason).
    """
    from .adaptive import run_adaptive

    offgrid_table = None
    if offgrid_path is not None:
        from surrogate.dataset_io import load_dataset

        offgrid_table = load_dataset(offgrid_path).table
    from .adaptive import BATCH_POINTS, INITIAL_POINTS

    sizes = {"initial": INITIAL_POINTS if initial is None else int(initial),
             "batch": BATCH_POINTS if batch is None else int(batch)}
    result = run_adaptive(out_dir, factorial, lubricant, level=level, effects=effects, model=model, budget=budget,
                          **sizes,
                          offgrid_table=offgrid_table, target_median=target_median, target_p90=target_p90,
                          workers=workers, scheduler=scheduler, progress=progress, time_limit_s=time_limit_s,
                          log=log, roughness=roughness)
    folder = Path(out_dir) / "adaptive"
    return {"artefacts": [str(folder / name) for name in result.batch_files], "wall_time_s": result.wall_time_s,
            "details": result.to_dict()}


SPACE_FILLING_KINDS = ("sample:sobol", "sample:random", "sample:lhs")
"""Sample kinds (recorded in a sample's store) drawn uniformly over the box, like the off-grid sample."""


def load_rows(paths) -> tuple[pd.DataFrame, Any, Any]:
    """Every row of one or more dataset files (same lubricant, E' and recorded roughness profile), the first file's
    :class:`Dataset` (its table replaced by all rows; its roughness None unless every file records it), and the
    calibration mask of the learned form's interval: None for one file; for several
    (an adaptive design) the rows of the space-filling files (:data:`SPACE_FILLING_KINDS`), not those chosen where
    the ensemble disagreed (:func:`surrogate.mlp.fit_mlp_ensemble`)."""
    import numpy as np

    from ehl_dataset.dataset.store import read_metadata
    from surrogate.dataset_io import load_dataset

    paths = [paths] if isinstance(paths, (str, Path)) else list(paths)
    datasets = [load_dataset(p) for p in paths]
    calibration = None
    if len(paths) > 1:
        kinds = [(read_metadata(p).get("factorial") or {}).get("kind") for p in paths]
        calibration = np.concatenate([np.full(len(d.table), k in SPACE_FILLING_KINDS) for d, k in zip(datasets, kinds)])
        if not calibration.any():
            calibration = None
    first = datasets[0]
    for other, path in zip(datasets[1:], paths[1:]):
        if other.lubricant.to_json_dict() != first.lubricant.to_json_dict() or other.e_reduced != first.e_reduced:
            raise InputError("dataset", str(path), f"a dataset of the lubricant and E' of {paths[0]}")
    table = pd.concat([d.table for d in datasets], ignore_index=True) if len(datasets) > 1 else first.table
    for other, path in zip(datasets[1:], paths[1:]):
        if other.roughness != first.roughness and other.roughness is not None and first.roughness is not None:
            raise InputError("dataset", str(path), f"a dataset of the roughness profile of {paths[0]} "
                             f"({first.roughness['name']})", f"it records {other.roughness['name']}")
    if any(d.roughness is None for d in datasets):
        first.roughness = None  # one file records none: the mix is not recorded
    if len(datasets) > 1:
        first.source["files"] = [{"path": Path(p).name, "sha256": d.source["sha256"], "n_points": len(d.table)}
                                 for p, d in zip(paths, datasets)]
        first.table = table
        first.source["n_points"] = int(len(table))
    return table, first, calibration


BOX_KEYS = {"p_h": "p_h_pa", "r_eq": "r_eq_m", "u_r": "u_r_m_s", "sr": "sr_abs", "temperature": "temperature_k",
            "rq1": "rq1_m", "rq2": "rq2_m"}
"""Inputs of a sample's box → the fitted-range entries of a coefficient file."""


def sample_box(paths) -> dict[str, list[float]] | None:
    """The box a sampled training design fills (the union of its files' boxes), or None when any file is not a
    sample (a factorial: its fitted ranges are its levels' ranges already)."""
    from ehl_dataset.dataset.store import read_metadata

    paths = [paths] if isinstance(paths, (str, Path)) else list(paths)
    boxes = [(read_metadata(p).get("factorial") or {}).get("box") for p in paths]
    if not boxes or any(not isinstance(b, dict) for b in boxes):
        return None
    return {key: [min(b[name][0] for b in boxes), max(b[name][1] for b in boxes)] for name, key in BOX_KEYS.items()}


def widen_to_box(fit, box: dict[str, list[float]] | None):
    """Set the fitted ranges of ``fit`` to the box of its sampled design: a random or adaptive design covers its box,
    but its extreme points lie strictly inside it, and clipping gear contacts to the points' hull would throw away
    the design's edges (the fitted λ̄ range stays that of the rows)."""
    if box is None:
        return fit
    for key, pair in box.items():
        fit.input_ranges[key] = [float(pair[0]), float(pair[1])]
    fit.sr_floor = float(box["sr_abs"][0])
    return fit


def fit_form(form: str, table: pd.DataFrame, data, *, allow_unstable: bool = False, blend_half_width: float = 0.1,
             calibration=None):
    """The fit of ``form`` on ``table`` (``eq9``: :func:`surrogate.fit.fit_surrogate`; ``learned``:
    :func:`surrogate.learned_fit.fit_learned`, its interval calibrated on the rows of ``calibration``)."""
    if check_form(form) == "learned":
        from surrogate.learned_fit import fit_learned

        return fit_learned(table, data.lubricant, data.e_reduced, calibration=calibration)
    from surrogate.fit import fit_surrogate

    return fit_surrogate(table, data.lubricant, data.e_reduced, allow_unstable=allow_unstable,
                         blend_half_width=blend_half_width)


def offgrid_of(surrogate, offgrid_path: str | Path, coverage_rows=None) -> dict[str, Any]:
    """The ``offgrid`` table of ``surrogate`` (a :class:`~surrogate.evaluate.FrictionSurrogate`) on the solved sample
    at ``offgrid_path``; the coverage counts the rows of ``coverage_rows`` (None: all)."""
    from surrogate.dataset_io import load_dataset
    from surrogate.offgrid import offgrid_errors, offgrid_report

    sample = load_dataset(offgrid_path)
    errors = offgrid_errors(surrogate, sample.table, coverage_rows=coverage_rows)
    described = {"file": Path(offgrid_path).name, "sha256": sample.source["sha256"],
                 "n_points": sample.source.get("n_points"), "level": sample.source.get("accuracy_level"),
                 "effects": sample.source.get("effects"), "solver_version": sample.source.get("solver_version")}
    from ehl_dataset.dataset.store import read_metadata

    plan = read_metadata(offgrid_path).get("factorial") or {}
    described.update({k: plan.get(k) for k in ("kind", "seed", "within_factorial", "box")})
    return offgrid_report(errors, described)


def calibrated_interval(surrogate, offgrid_path: str | Path) -> tuple[dict[str, Any], Any]:
    """A learned file's interval recalibrated on the even rows of the off-grid sample
    (:func:`surrogate.mlp.recalibrate`; :func:`surrogate.offgrid.calibration_rows`): the new ``learned.interval``
    table and the mask of the rows left to measure its coverage."""
    from surrogate.dataset_io import load_dataset
    from surrogate.fit import prepare_table
    from surrogate.mlp import feature_matrix, recalibrate
    from surrogate.offgrid import calibration_rows

    table = load_dataset(offgrid_path).table
    calibrate = calibration_rows(len(table))
    prepared = prepare_table(table, surrogate.lubricant, surrogate.e_reduced)
    rows = calibrate[prepared.kept_rows]
    features = {k: v[rows] for k, v in prepared.features.items()}
    ensemble = recalibrate(surrogate.coefficients.learned, feature_matrix(features), prepared.ln_mu[rows])
    interval = dict(surrogate.coefficients.document["learned"]["interval"])
    interval.update(ensemble.to_dict()["interval"])
    interval["method"] = ("split conformal with normalised score |r|/(s + s0) on the even rows of the off-grid "
                          "sample (cross-validation+ quantiles of the training rows in cv_plus_score_quantiles)")
    interval["calibration_rows"] = int(rows.sum())
    interval["cv_plus_score_quantiles"] = surrogate.coefficients.document["learned"]["interval"]["score_quantiles"]
    return interval, ~calibrate


def fit_details(fit) -> dict[str, Any]:
    """The numbers a fit stage reports, for either form."""
    cv = fit.cv["overall"]
    details = {"n_input_rows": fit.n_input_rows, "n_used": fit.n_used, "exclusions": fit.exclusions,
               "cv_rmse_ln_mu": cv["rmse_ln_mu"], "cv_mean_rel_err_mu": cv["mean_rel_err_mu"],
               "cv_median_rel_err_mu": cv["median_rel_err_mu"]}
    if hasattr(fit, "branches"):
        details.update(form="eq9", stable=fit.stable,
                       branches={b: {"n_obs": f.n_obs, "adj_r2": f.adj_r2, "resid_std_error": f.resid_std_error}
                                 for b, f in fit.branches.items()})
    else:
        details.update(form="learned", stable=True, members=fit.ensemble.members,
                       interval_q90=fit.ensemble.score_quantiles.get(0.9))
    return details


def fit_and_write(dataset_paths, coefficients_file: str | Path, *, form: str = "eq9", allow_unstable: bool = False,
                  blend_half_width: float = 0.1, offgrid_path: str | Path | None = None) -> tuple[str, dict, list]:
    """Fit ``form`` on the dataset file(s), validate it off the grid, write the coefficient file.

    Parameters
    ----------
    dataset_paths : str, Path or list
        Dataset file(s) of the training rows [-].
    coefficients_file : str or Path
        The coefficient file to write [-].
    form : str
        ``eq9`` or ``learned`` [-].
    allow_unstable : bool
        Keep an Eq. 9 fit flagged unstable [-].
    blend_half_width : float
        Eq. 9's λ̄ blend half width [-].
    offgrid_path : str or Path, optional
        Solved off-grid sample whose errors the file records [-].

    Returns
    -------
    tuple
        (path written, details, warnings caught).
    """
    from surrogate.coefficients import summary_path, write_coefficients

    table, data, calibration = load_rows(dataset_paths)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        fit = widen_to_box(fit_form(form, table, data, allow_unstable=allow_unstable,
                                    blend_half_width=blend_half_width, calibration=calibration),
                           sample_box(dataset_paths))
    path = write_coefficients(fit, coefficients_file, source=data.source, roughness=data.roughness)
    details = fit_details(fit) | {"lubricant": data.lubricant.name, "summary": str(summary_path(path))}
    if offgrid_path is not None:
        details["offgrid"] = validate_offgrid(path, offgrid_path)
    return str(path), details, [str(w.message) for w in caught]


def validate_offgrid(coefficients_file: str | Path, offgrid_path: str | Path) -> dict[str, Any]:
    """Measure a written coefficient file on the solved off-grid sample and record the result in the file.

    A learned file's interval is first recalibrated on the even rows of the sample (:func:`calibrated_interval`), an
    Eq. 9 file's gets split-conformal factors from them (:func:`surrogate.offgrid.eq9_interval_calibration`); the
    coverage is then counted on the odd rows only. The errors of μ are measured on all rows (the sample takes no
    part in the fit).

    Parameters
    ----------
    coefficients_file : str or Path
        The coefficient file [-].
    offgrid_path : str or Path
        The solved off-grid sample [-].

    Returns
    -------
    dict
        The ``offgrid`` table recorded.
    """
    from surrogate.coefficients import record_offgrid, validate_coefficients
    from surrogate.evaluate import FrictionSurrogate

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        surrogate = FrictionSurrogate.load(coefficients_file)
        interval, coverage_rows, calibration, not_calibrated = None, None, None, None
        try:
            if surrogate.form == "eq9" and surrogate.coefficients.covariance is not None:
                from surrogate.dataset_io import load_dataset
                from surrogate.offgrid import eq9_interval_calibration

                calibration, coverage_rows = eq9_interval_calibration(surrogate, load_dataset(offgrid_path).table)
                doc = {**surrogate.coefficients.document, "interval_calibration": calibration}
            if surrogate.form == "learned":
                interval, coverage_rows = calibrated_interval(surrogate, offgrid_path)
                doc = dict(surrogate.coefficients.document)
                doc["learned"] = {**doc["learned"], "interval": interval}
        except InputError as err:
            if not too_few_calibration_rows(err):
                raise
            interval, coverage_rows, calibration = None, None, None
            not_calibrated = (f"not calibrated on this sample: {err}; the interval is the fit's own and its coverage "
                              "is counted on all rows")
        if interval is not None or calibration is not None:
            surrogate = FrictionSurrogate(validate_coefficients(
                {**doc, "content_sha256": _rehash(doc)}, str(coefficients_file)))
        offgrid = offgrid_of(surrogate, offgrid_path, coverage_rows)
    if not_calibrated is not None:
        offgrid["interval_calibration"] = not_calibrated
        warnings.warn(f"off-grid sample {Path(offgrid_path).name}: interval {not_calibrated}", stacklevel=2)
    record_offgrid(coefficients_file, offgrid, learned_interval=interval, interval_calibration=calibration)
    return offgrid


def too_few_calibration_rows(err: InputError) -> bool:
    """Whether ``err`` says that a sample has too few usable held-out rows to calibrate a 90 % interval
    (:func:`surrogate.intervals.calibrate_scores`, :func:`surrogate.mlp.recalibrate`).

    Parameters
    ----------
    err : InputError
        The error [-].

    Returns
    -------
    bool
        True for that shortfall, False for any other error [-].
    """
    from surrogate.intervals import TOO_FEW_CALIBRATION_ROWS

    return err.parameter.startswith("calibration rows") and err.accepted == TOO_FEW_CALIBRATION_ROWS


def _rehash(doc: dict) -> str:
    from surrogate.coefficients import content_hash

    return content_hash(doc)
