"""The end-to-end pipeline: a factorial of mixed-EHL contacts → a fitted friction surrogate → a gear design's loss.

Three stage functions, each returning a :class:`StageResult` (artefact path, wall time, the numbers worth
reporting), and :func:`run_pipeline` that chains them in one process (docs/getting-started.md):

1. :func:`dataset_stage` — :func:`ehl_dataset.dataset.runner.run_factorial` into ``OUT/dataset.h5``; an existing file
   of the same factorial, solver and lubricant is continued (only rows that are not ``ok`` are computed).
2. :func:`fit_stage` — :func:`surrogate.fit.fit_surrogate` (paper Eq. 9a/9b) on the ``ok`` rows, written with
   :func:`surrogate.coefficients.write_coefficients` to ``OUT/<lubricant>_<factorial>.json`` (plus the statsmodels
   summary beside it).
3. :func:`design_stage` — the paper's Design D (Table 1) at the study file's operating point (250 N·m, 4000 rpm, ATF
   at 90 °C, Rq 0.4 µm, M_P 15 µm, M_L 12 µm) with that surrogate: P, η, TE p-p, σ_c, σ_b
   (:func:`efficiency.studies.evaluate_design`).

Nothing is hidden: stage 1 reports how many points failed or did not converge; stage 2 raises
:class:`~ehl_dataset.validation.SolverError` naming the stage when the data cannot determine the regression (too few
``ok`` rows in a branch, rank deficiency, an unstable fit); stage 3 reports the surrogate's clipped inputs, whether
the load distribution converged and whether the result lies inside the models' validity (:mod:`efficiency.validity`).

Every input (factorial, level, model, design, output directory) is checked by :func:`check_inputs` before stage 1
starts. Each run writes its own directory, named after its factorial, level and model (:func:`default_out_dir`), so
runs of different factorials never meet in one file. A run stopped by SIGINT/SIGTERM raises
:class:`workflows.exit_codes.Interrupted` with the command that resumes it.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ehl_dataset.validation import InputError, SolverError

from .exit_codes import Interrupted

QUICK_FACTORIAL = "quick"
PAPER_FACTORIAL = "paper2009"
SMOKE_FACTORIAL = "smoke"
DATASET_FILE = "dataset.h5"
SMOKE_LABEL = ("SMOKE RUN: smooth-surface solves (model smooth) of the smoke factorial, to check that every stage "
               "runs; its fit and loss are not a friction model of the lubricant")
"""Printed with, and recorded in, the result of a run whose stage 1 solves smooth surfaces only."""


@dataclass
class StageResult:
    """One stage of a pipeline run.

    Parameters
    ----------
    name : str
        Stage name [-].
    artefact : str or None
        The file it wrote [-].
    wall_time_s : float
        Its wall time [s].
    details : dict
        The numbers it reports, SI units with the unit in each key [-].
    """

    name: str
    artefact: str | None
    wall_time_s: float
    details: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        """The stage as a JSON-serialisable dict.

        Returns
        -------
        dict
            ``name``, ``artefact``, ``wall_time_s`` [s] and the ``details`` entries.
        """
        return {"name": self.name, "artefact": self.artefact, "wall_time_s": self.wall_time_s, **self.details}


@dataclass
class PipelineResult:
    """All stages of one pipeline run, in order, and the total wall time.

    Parameters
    ----------
    out_dir : str
        Output directory [-].
    stages : list of StageResult
        The stages, in order [-].
    wall_time_s : float
        Total wall time [s].
    label : str
        Label of the run [-].
    """

    out_dir: str
    stages: list[StageResult]
    wall_time_s: float
    label: str = ""

    def stage(self, name: str) -> StageResult:
        """The stage called ``name``.

        Parameters
        ----------
        name : str
            ``dataset``, ``fit`` or ``design`` [-].

        Returns
        -------
        StageResult
            The stage.

        Raises
        ------
        KeyError
            When the run has no such stage.
        """
        for stage in self.stages:
            if stage.name == name:
                return stage
        raise KeyError(name)

    def to_dict(self) -> dict[str, Any]:
        """The run as a JSON-serialisable dict.

        Returns
        -------
        dict
            ``out_dir``, ``wall_time_s`` [s], ``label`` and ``stages`` (stage name to :meth:`StageResult.to_dict`).
        """
        return {"out_dir": self.out_dir, "wall_time_s": self.wall_time_s, "label": self.label,
                "stages": {s.name: s.to_dict() for s in self.stages}}


def _factorial(factorial):
    from ehl_dataset.dataset.factorial import Factorial, load_factorial

    return factorial if isinstance(factorial, Factorial) else load_factorial(factorial)


def default_out_dir(factorial_name: str, level: str, model: str = "auto", lubricant_name: str | None = None,
                    effects: str = "auto", roughness_name: str | None = None) -> str:
    """``gearloss_[<lubricant>_]<factorial>_<level>`` (``_<model>`` appended unless auto, ``_<effects>`` unless auto,
    ``_<roughness profile>`` when another than the default is chosen (a profile file by its name without the
    suffix); the lubricant's name when one is chosen instead of the factorial's): one directory per kind of run."""
    parts = ([lubricant_name] if lubricant_name else []) + [factorial_name]
    safe = "_".join(_safe(part) for part in parts)
    return (f"gearloss_{safe}_{level}" + ("" if model == "auto" else f"_{model}")
            + ("" if effects == "auto" else f"_{effects}")
            + ("" if not roughness_name else f"_{_safe(Path(roughness_name).stem)}"))


def _safe(part: str) -> str:
    return "".join(c if c.isalnum() or c in "-_" else "_" for c in part)


@dataclass
class PipelinePlan:
    """The checked inputs of a run (:func:`check_inputs`).

    Parameters
    ----------
    factorial : Factorial
        The factorial [-].
    level : str
        Accuracy level [-].
    model : str
        Contact model [-].
    lubricant_name : str
        Lubricant name [-].
    study : str
        Study of the design stage [-].
    design : str or None
        Design of the design stage; None: no design stage [-].
    out_dir : Path
        Output directory [-].
    resumable : int
        Points already done in an existing dataset file of the same run (0: new run) [-].
    effects : str
        Effect plan of stage 1 [-].
    roughness : RoughnessChoice or None
        Roughness profile of stage 1's rough points and of every sample solved by its route
        (:func:`ehl_dataset.dataset.roughness_choice.choose_roughness`); None: the default profile [-].
    """

    factorial: Any
    level: str
    model: str
    lubricant_name: str
    study: str
    design: str | None
    out_dir: Path
    resumable: int  # points already done in an existing dataset file of the same run (0: new run)
    effects: str = "auto"
    roughness: Any = None

    @property
    def dataset(self) -> Path:
        return self.out_dir / DATASET_FILE

    @property
    def coefficients(self) -> Path:
        return self.out_dir / coefficients_file_name(self.lubricant_name, self.factorial.name)

    @property
    def smoke(self) -> bool:
        return self.model == "smooth"


def check_inputs(factorial=QUICK_FACTORIAL, *, out_dir=None, level: str | None = None, model: str | None = None,
                 lubricant=None, study: str = "paper2009", design: str | None = "D", overwrite: bool = False,
                 workers: int = 1, time_limit_s: float | None = None, effects: str | None = None,
                 roughness=None) -> PipelinePlan:
    """Check everything a run needs before stage 1 computes anything.

    A typo in ``design`` must not cost the stage-1 run.

    Checks the factorial, level, model, effect plan, lubricant (its data range covers the factorial's temperatures),
    the design, workers, time limit, and that ``out_dir`` either holds nothing of this run or the same run, on the
    same roughness profile (then it resumes).

    Parameters
    ----------
    factorial : Factorial or str or Path
        The factorial: an object, a shipped name (``quick``, ``paper2009``, ...) or a TOML path [-].
    out_dir : str or Path, optional
        Output directory; None: :func:`default_out_dir` [-].
    level : str, optional
        Accuracy level of the EHL solves; None: the factorial's [-].
    model : str, optional
        Contact model of the solves (``auto``, ``homogenised``, ``deterministic``); None: the factorial's [-].
    lubricant : str or Path or Lubricant, optional
        Lubricant (shipped name, TOML path or object); None: the factorial's [-].
    study : str
        Study whose design and operating point stage 3 evaluates (shipped name or TOML path) [-].
    design : str, optional
        Design name of ``study`` or a design TOML file; None: no design stage [-].
    overwrite : bool
        Start the run afresh: the directory's dataset and coefficient file are replaced [-].
    workers : int
        Worker processes of stage 1 [-].
    time_limit_s : float, optional
        Wall-time budget per stage-1 point; a point that spends it is stored not converged with its message [s].
    effects : str, optional
        Stage 1's effect plan (one of :data:`ehl_dataset.dataset.factorial.EFFECTS_MODES`; ``isothermal`` gives the
        isothermal data the paper fitted); None: the factorial's [-].
    roughness : RoughnessChoice, optional
        Roughness profile of the rough points (:func:`ehl_dataset.dataset.roughness_choice.choose_roughness`);
        None: the default profile [-].

    Returns
    -------
    PipelinePlan
        The checked inputs.

    Raises
    ------
    InputError
        Naming the first bad input.
    """
    from ehl_dataset.dataset.factorial import EFFECTS_MODES, canonical_json
    from ehl_dataset.dataset.roughness_choice import recorded_option
    from ehl_dataset.dataset.runner import (DEFAULT_SOLVER, check_lubricant_covers, check_model, check_roughness,
                                            check_time_limit, dataset_roughness, recorded_model)
    from ehl_dataset.dataset.store import SOLVER_DEFAULTS, read_metadata
    from ehl_dataset.model.lubricant import load_lubricant
    from ehl_dataset.model.roughness_identity import describe_roughness
    from ehl_dataset.solvers.levels import get_level
    from ehl_dataset.validation import check_range

    check_range("workers", workers, 0, 1024)
    check_time_limit(time_limit_s)
    plan = _factorial(factorial)
    level = get_level(level or plan.level).name
    model = check_model(model or plan.model)
    effects = effects or plan.effects
    if effects not in EFFECTS_MODES:
        raise InputError("effects", effects, f"one of {list(EFFECTS_MODES)}")
    lub = load_lubricant(lubricant or plan.lubricant)
    check_lubricant_covers(plan, lub)
    check_roughness(roughness)
    if design is not None:
        _check_design(study, design)
    chosen = dataset_roughness(DEFAULT_SOLVER, roughness)
    out = Path(out_dir) if out_dir is not None else Path(default_out_dir(
        plan.name, level, model, None if lubricant is None or lub.name == plan.lubricant else lub.name, effects,
        None if roughness is None or roughness.is_default else roughness.name))
    if out.exists() and not out.is_dir():
        raise InputError("out-dir", str(out), "a directory (this path is a file)")
    resumable = 0
    dataset = out / DATASET_FILE
    if dataset.exists() and not overwrite:
        meta = read_metadata(dataset)
        recorded = {**SOLVER_DEFAULTS, **meta["solver"]}
        hint = "another --out-dir, or --overwrite to replace it"
        if meta["factorial_sha256"] != plan.points_hash():
            raise InputError("factorial", plan.name, f"the factorial of the run in {out} "
                             f"({meta['factorial'].get('name')!r})", hint)
        for key, value in (("level", level), ("model", model), ("effects", effects)):
            if str(recorded.get(key)) != value:
                raise InputError(key, value, f"{recorded_model(recorded) if key == 'model' else recorded.get(key)!r}"
                                 f" as recorded in {dataset}", hint)
        if canonical_json(lub.to_json_dict()) != canonical_json(meta["lubricant"]):
            raise InputError("lubricant", lub.name, f"the definition of {meta['lubricant'].get('name')!r} as "
                             f"recorded in {dataset} (compared field by field)", hint)
        if meta["roughness"] is not None and meta["roughness"] != chosen:
            recorded_roughness = meta["roughness"]
            option = ("--roughness" if roughness is None or roughness.registered else "--roughness-file")
            raise InputError(option, describe_roughness(chosen), f"the roughness profile of the run in {out} "
                             f"({describe_roughness(recorded_roughness)})", f"resume it with "
                             f"{recorded_option(recorded_roughness)}; another --out-dir, or --overwrite to replace "
                             "it")
        if roughness is not None and not roughness.registered \
                and recorded.get("roughness_unit") != roughness.unit:
            raise InputError("--roughness-unit", roughness.unit, f"{recorded.get('roughness_unit')!r} as recorded in "
                             f"{dataset}", hint)
        resumable = int(meta["counts"]["ok"])
    return PipelinePlan(plan, level, model, lub.name, study, design, out, resumable, effects, roughness)


def _check_design(study: str, design: str) -> None:
    from efficiency.design_io import load_design, load_study

    paper = load_study(study)
    if design in paper.designs:
        return
    if Path(design).suffix.lower() == ".toml" or Path(design).exists():
        load_design(design)
        return
    raise InputError("design", design, f"a published design of study {paper.name} ({', '.join(paper.designs)}) or "
                                       "a design TOML file")


def coefficients_file_name(lubricant_name: str, factorial_name: str) -> str:
    """``<lubricant>_<factorial>.json`` with the factorial name shortened as in the brief: quick → ``atf_quick``."""
    safe = "".join(c if c.isalnum() or c in "-_" else "_" for c in f"{lubricant_name}_{factorial_name}")
    return f"{safe}.json"


# ---------------------------------------------------------------------- stage 1
def dataset_stage(out_dir: str | Path, factorial, *, workers: int = 1, scheduler: str | None = None,
                  lubricant=None, level: str | None = None, progress: str = "auto", overwrite: bool = False,
                  time_limit_s: float | None = None, model: str | None = None, effects: str | None = None,
                  roughness=None, **runner_options) -> StageResult:
    """Compute ``factorial`` into ``out_dir/dataset.h5``; continue the file if it holds the same run.

    Parameters
    ----------
    out_dir : str or Path
        Output directory [-].
    factorial : Factorial or str or Path
        The factorial: an object, a shipped name (``quick``, ``paper2009``, ...) or a TOML path [-].
    workers : int
        Worker processes of stage 1 [-].
    scheduler : str, optional
        Address of a Dask scheduler to run stage 1 on; None: local processes [-].
    lubricant : str or Path or Lubricant, optional
        Lubricant (shipped name, TOML path or object); None: the factorial's [-].
    level : str, optional
        Accuracy level of the EHL solves; None: the factorial's [-].
    progress : str
        Progress display of stage 1: ``auto``, ``bar``, ``log`` or ``none`` [-].
    overwrite : bool
        Replace an existing dataset file [-].
    time_limit_s : float, optional
        Wall-time budget per point (None: none); a point that spends it is stored not converged with its message.
        An execution option: a file continues whatever budget it was started with [s].
    model : str, optional
        Contact model of the solves (``auto``, ``homogenised``, ``deterministic``); None: the factorial's [-].
    effects : str, optional
        The effect plan; None: the factorial's [-].
    roughness : RoughnessChoice, optional
        Roughness profile of the rough points (:func:`ehl_dataset.dataset.roughness_choice.choose_roughness`);
        None: the default profile [-].
    **runner_options
        Options of :func:`ehl_dataset.dataset.runner.run_factorial` (``window``, ``max_attempts``, ``stream``, ...) [-].

    Returns
    -------
    StageResult
        The dataset file, wall time and row counts.
    """
    from ehl_dataset.dataset.runner import check_time_limit, run_factorial

    time_limit_s = check_time_limit(time_limit_s)
    started = time.perf_counter()
    plan = _factorial(factorial)
    out = Path(out_dir) / DATASET_FILE
    out.parent.mkdir(parents=True, exist_ok=True)
    resumed = out.exists() and not overwrite
    summary = run_factorial(out, plan, lubricant=lubricant, level=level, workers=workers, scheduler=scheduler,
                            progress=progress, overwrite=overwrite, time_limit_s=time_limit_s, model=model,
                            effects=effects, roughness=roughness, **runner_options)
    from ehl_dataset.dataset.store import read_metadata

    meta = read_metadata(out)
    solver = meta["solver"]
    details = {"factorial": plan.name, "level": solver.get("level"), "model": solver.get("model", "auto"),
               "effects": solver.get("effects"), "roughness": meta["roughness"],
               "n_points": summary.n_points, "computed": summary.computed,
               "time_limit_s": time_limit_s,
               "ok": summary.ok, "failed": summary.failed, "pending": summary.pending,
               "non_converged": summary.non_converged, "resumed": resumed, "interrupted": summary.interrupted,
               "points_per_s": summary.points_per_s, "executor": summary.executor}
    if summary.failed:
        details["failures"] = _failure_digest(out)
    return StageResult("dataset", str(out), time.perf_counter() - started, details)


def _failure_digest(path: Path, keep: int = 3) -> dict[str, int]:
    """The most frequent error messages of the failed rows (message → count)."""
    from ehl_dataset.dataset.store import read_table

    failed = read_table(path, status="failed")
    counts = failed["error"].astype(str).str.slice(0, 160).value_counts()
    return {str(k): int(v) for k, v in counts.head(keep).items()}


# ---------------------------------------------------------------------- stage 2
def fit_stage(dataset_path, coefficients_path: str | Path, *, allow_unstable: bool = False,
              blend_half_width: float = 0.1, form: str = "eq9", offgrid_path: str | Path | None = None) -> StageResult:
    """Fit paper Eq. 9a/9b (or the learned form) on the dataset and write the coefficient file (and its summary).

    Parameters
    ----------
    dataset_path : str or Path or list
        The stage-1 dataset, or several dataset files of one lubricant (an adaptive run's batches) [-].
    coefficients_path : str or Path
        The coefficient file to write [-].
    allow_unstable : bool
        Write a fit flagged numerically unstable instead of raising [-].
    blend_half_width : float
        Half width δ of the branch blend band in λ̄ [-].
    form : str
        ``eq9`` (statsmodels OLS of the paper's form) or ``learned`` (:mod:`surrogate.mlp`) [-].
    offgrid_path : str or Path, optional
        A solved off-grid sample whose errors the file records (:mod:`workflows.surrogate_stage`) [-].

    Returns
    -------
    StageResult
        The coefficient file, wall time and fit statistics.

    Raises
    ------
    SolverError
        ("fit stage: ...") when the rows cannot determine a branch of the regression.
    """
    from .surrogate_stage import fit_and_write, load_rows

    started = time.perf_counter()
    where = dataset_path if isinstance(dataset_path, (str, Path)) else Path(list(dataset_path)[0]).parent
    try:
        path, details, caught = fit_and_write(dataset_path, coefficients_path, form=form,
                                              allow_unstable=allow_unstable, blend_half_width=blend_half_width,
                                              offgrid_path=offgrid_path)
    except SolverError as err:
        raise SolverError(f"fit stage ({where}): {err}; {_row_digest(load_rows(dataset_path)[1])}") from err
    except (InputError, ValueError, IndexError) as err:
        raise SolverError(f"fit stage ({where}): the data cannot determine the regression: "
                          f"{type(err).__name__}: {err}; {_row_digest(load_rows(dataset_path)[1])}") from err
    details["warnings"] = sorted({message[:200] for message in caught})
    return StageResult("fit", path, time.perf_counter() - started, details)


def surrogate_stages(run: PipelinePlan, dataset: str | None, lubricant=None, *, form: str = "eq9",
                     offgrid_points: int = 0,
                     adaptive_budget: int | None = None, target_median: float | None = None,
                     target_p90: float | None = None, adaptive_initial: int | None = None,
                     adaptive_batch: int | None = None, allow_unstable: bool = False, workers: int = 1,
                     scheduler: str | None = None, progress: str = "auto", time_limit_s: float | None = None,
                     resume_command: str | None = None) -> list[StageResult]:
    """Stage 2 after the dataset: the fit of ``form`` written to its coefficient file, the off-grid validation
    sample (``offgrid_points`` seeded random contacts in the factorial's ranges, solved by its route into
    ``OUT/offgrid.h5``; 0: none) and its errors recorded in the file; with ``adaptive_budget`` the training rows are
    the adaptive design (:mod:`workflows.adaptive`, up to that many solves, stopping early at the off-grid targets)
    instead of ``dataset``. Smooth-surface runs (the smoke factorial) get no off-grid sample. Every sample is
    solved on the run's roughness profile (``run.roughness``) and records it.

    Parameters
    ----------
    run : PipelinePlan
        The checked run.
    dataset : str, optional
        The stage-1 dataset (None with ``adaptive_budget``) [-].
    lubricant : str or Path or Lubricant, optional
        The lubricant of the run; None: the factorial's [-].
    form : str
        ``eq9`` or ``learned`` [-].
    offgrid_points : int
        Points of the off-grid sample (0: none) [-].
    adaptive_budget : int, optional
        Budget of adaptive training solves; None: train on ``dataset`` [-].
    target_median, target_p90 : float, optional
        Off-grid targets that stop the adaptive design early [-].
    adaptive_initial, adaptive_batch : int, optional
        Points of the adaptive design's Sobol' start and of each batch; None: the defaults of
        :mod:`workflows.adaptive` [-].
    allow_unstable : bool
        Keep an Eq. 9 fit flagged unstable [-].
    workers : int
        Local worker processes [-].
    scheduler : str, optional
        Dask scheduler [-].
    progress : str
        Progress mode [-].
    time_limit_s : float, optional
        Wall-time budget per solve [s].
    resume_command : str, optional
        The command that continues the run (named when a signal stops a solve stage) [-].

    Returns
    -------
    list of StageResult
        ``offgrid`` (when solved), ``adaptive`` (when adaptive), ``fit``.
    """
    import sys

    from ehl_dataset.model.lubricant import Lubricant, load_lubricant

    from .surrogate_stage import adaptive_stage, check_form, coefficients_path, offgrid_stage, validate_offgrid

    check_form(form)
    route = {"level": run.level, "effects": run.effects, "model": run.model, "workers": workers,
             "scheduler": scheduler, "progress": progress, "time_limit_s": time_limit_s,
             "roughness": run.roughness}
    lub = lubricant if isinstance(lubricant, Lubricant) else load_lubricant(lubricant or run.factorial.lubricant)
    stages: list[StageResult] = []

    def solve_offgrid() -> str | None:
        if not offgrid_points or run.smoke:
            return None
        solved = offgrid_stage(run.out_dir, run.factorial, lub, n=offgrid_points, **route)
        stages.append(StageResult("offgrid", solved["artefact"], solved["wall_time_s"], solved["details"]))
        if solved["details"]["interrupted"]:
            raise Interrupted(solved["details"]["interrupted"], f"off-grid sample ({solved['details']['computed']} "
                              f"points computed, {solved['details']['pending']} pending in {solved['artefact']})",
                              resume_command)
        return solved["artefact"]

    out = coefficients_path(run.coefficients, form, adaptive=adaptive_budget is not None)
    if adaptive_budget is not None:  # the off-grid set first: it is the adaptive design's stop test
        offgrid_path = solve_offgrid()
        ran = adaptive_stage(run.out_dir, run.factorial, lub, budget=adaptive_budget, offgrid_path=offgrid_path,
                             target_median=target_median, target_p90=target_p90, initial=adaptive_initial,
                             batch=adaptive_batch,
                             log=lambda line: print(line, file=sys.stderr, flush=True) if progress != "none" else None,
                             **route)
        stages.append(StageResult("adaptive", str(run.out_dir / "adaptive"), ran["wall_time_s"], ran["details"]))
        stages.append(fit_stage(ran["artefacts"], out, allow_unstable=allow_unstable, form=form,
                                offgrid_path=offgrid_path))
        return stages
    fit = fit_stage(dataset, out, allow_unstable=allow_unstable, form=form)  # a fit the data cannot determine
    offgrid_path = solve_offgrid()                                            # stops before the off-grid solves
    if offgrid_path is not None:
        fit.details["offgrid"] = validate_offgrid(fit.artefact, offgrid_path)
    return stages + [fit]


def _row_digest(data) -> str:
    """Which rows the fit could use and why the others were excluded, and what each branch of Eq. 9 needs."""
    from surrogate.fit import branch_masks
    from surrogate.fit import prepare_table
    from surrogate.forms import LI_KAHRAMAN_2009

    try:
        prepared = prepare_table(data.table, data.lubricant, data.e_reduced)
    except (InputError, ValueError) as err:
        return f"rows could not be prepared: {err}"
    excluded = ", ".join(f"{reason.replace('_', ' ')} {n}" for reason, n in prepared.exclusions.items() if n)
    masks = branch_masks(prepared.features["lam"], LI_KAHRAMAN_2009.lambda_threshold)
    usable = ", ".join(f"{b} {int(m.sum())} (needs {len(LI_KAHRAMAN_2009.terms[b])})" for b, m in masks.items())
    return (f"rows: {prepared.n_input_rows} in the file; excluded: {excluded or 'none'}; usable by branch "
            f"(λ̄ ≤ {LI_KAHRAMAN_2009.lambda_threshold:g} mixed, above full_film): {usable}")


# ---------------------------------------------------------------------- stage 3
def design_stage(friction, *, study: str = "paper2009", design: str = "D", options=None,
                 clip_to_fitted_ranges: bool = True) -> StageResult:
    """Evaluate the study's published design at the study's operating point with ``friction``.

    A coefficient file is evaluated with its inputs clipped to its fitted ranges (the surrogate's own clipping; the
    number of clipped contact points per input is reported) unless ``clip_to_fitted_ranges`` is False, in which case
    it extrapolates with warnings.

    Parameters
    ----------
    friction : str or Path or callable
        A coefficient file path or shipped name, any other spec of :func:`efficiency.friction.friction_from_spec`, or
        a friction model [-].
    study : str
        The study (shipped name or TOML path) [-].
    design : str
        Design name of the study (default Design D of Table 1) [-].
    options : MeshOptions, optional
        Mesh resolution and models [-].
    clip_to_fitted_ranges : bool
        Clip a surrogate's inputs to its fitted ranges [-].

    Returns
    -------
    StageResult
        P, η, TE, σ_c, σ_b and the validity of the design.
    """
    from efficiency.design_io import load_study
    from efficiency.friction import friction_from_spec
    from efficiency.mesh_cycle import MeshOptions
    from efficiency.studies import StudyPoint, evaluate_design

    started = time.perf_counter()
    artefact = None
    if isinstance(friction, (str, Path)):
        artefact = str(friction)
        friction = friction_from_spec(artefact, clip_to_fitted_ranges=clip_to_fitted_ranges)
    paper = load_study(study)
    point = StudyPoint.from_operating_point(paper.operating_point)
    if design in paper.designs:
        pair = paper.design(design)
    else:
        from efficiency.design_io import load_design

        pair = load_design(design)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        row = evaluate_design(pair, friction, point, options or MeshOptions())
    details = {
        "study": paper.name, "design": design, "friction_model": artefact or type(friction).__name__,
        "torque_nm": point.input_torque, "speed_rpm": point.input_speed * 30.0 / math.pi,
        "oil_temperature_k": point.oil_temperature, "rq1_m": point.rq1, "rq2_m": point.rq2,
        "profile_crown_m": point.modifications.profile_crown, "lead_crown_m": point.modifications.lead_crown,
        "input_power_w": point.input_torque * point.input_speed,
        **{k: row[k] for k in ("power_loss_w", "power_loss_low_w", "power_loss_high_w", "efficiency", "te_pp_m",
                               "sigma_c_pa", "sigma_b_pa", "mu_mean",
                               "converged", "valid", "not_valid_because")},
        "model_time_s": row["wall_time_s"],
        "warnings": sorted({str(w.message)[:300] for w in caught}),
    }
    stats = friction.last_stats() if hasattr(friction, "last_stats") else {}
    if "clipped_inputs" in stats:
        details["clipped_to_fitted_range"] = {"contact_points": stats["surrogate_points"], **stats["clipped_inputs"]}
    return StageResult("design", artefact, time.perf_counter() - started, details)


# ---------------------------------------------------------------------- the chain
def run_pipeline(out_dir: str | Path | None = None, factorial=QUICK_FACTORIAL, *, workers: int = 1,
                 scheduler: str | None = None, lubricant=None, level: str | None = None, model: str | None = None,
                 progress: str = "auto", study: str = "paper2009", design: str = "D", allow_unstable: bool = False,
                 mesh_options=None, clip_to_fitted_ranges: bool = True, time_limit_s: float | None = None,
                 overwrite: bool = False, resume_command: str | None = None, checked: PipelinePlan | None = None,
                 effects: str | None = None, form: str = "eq9", offgrid_points: int = 0, roughness=None,
                 **runner_options) -> PipelineResult:
    """Stages 1–3 in one process: dataset → coefficient file → design evaluation (module docstring).

    Parameters
    ----------
    out_dir : str or Path, optional
        Output directory; None: :func:`default_out_dir` [-].
    factorial : Factorial or str or Path
        The factorial: an object, a shipped name (``quick``, ``paper2009``, ...) or a TOML path [-].
    workers : int
        Worker processes of stage 1 [-].
    scheduler : str, optional
        Address of a Dask scheduler to run stage 1 on; None: local processes [-].
    lubricant : str or Path or Lubricant, optional
        Lubricant (shipped name, TOML path or object); None: the factorial's [-].
    level : str, optional
        Accuracy level of the EHL solves; None: the factorial's [-].
    model : str, optional
        Contact model of the solves (``auto``, ``homogenised``, ``deterministic``); None: the factorial's [-].
    progress : str
        Progress display of stage 1: ``auto``, ``bar``, ``log`` or ``none`` [-].
    study : str
        Study whose design and operating point stage 3 evaluates (shipped name or TOML path) [-].
    design : str
        Design name of ``study`` (A–D) or a design TOML file [-].
    allow_unstable : bool
        Write a fit flagged numerically unstable instead of raising [-].
    mesh_options : MeshOptions, optional
        Mesh resolution and models of stage 3 [-].
    clip_to_fitted_ranges : bool
        Clip the surrogate's inputs to its fitted ranges in stage 3 (False: extrapolate, with warnings) [-].
    time_limit_s : float, optional
        Wall-time budget per stage-1 point; a point that spends it is stored not converged with its message [s].
    overwrite : bool
        Start the run afresh: the directory's dataset and coefficient file are replaced [-].
    resume_command : str, optional
        The command that continues this run, named in the :class:`~workflows.exit_codes.Interrupted` raised when a
        signal stops stage 1 [-].
    checked : PipelinePlan, optional
        The result of :func:`check_inputs` for these arguments; None: computed here [-].
    effects : str, optional
        Stage 1's effect plan (one of :data:`ehl_dataset.dataset.factorial.EFFECTS_MODES`; ``isothermal`` gives the
        isothermal data the paper fitted); None: the factorial's [-].
    form : str
        Form of the fitted surrogate: ``eq9`` or ``learned`` [-].
    offgrid_points : int
        Points of the off-grid validation sample recorded in the coefficient file (0: none;
        :func:`surrogate_stages`) [-].
    roughness : RoughnessChoice, optional
        Roughness profile of every rough solve (:func:`ehl_dataset.dataset.roughness_choice.choose_roughness`),
        recorded in the dataset and the coefficient file; None: the default profile. Ignored with ``checked``,
        which carries its own [-].
    **runner_options
        Options of :func:`ehl_dataset.dataset.runner.run_factorial` (``window``, ``max_attempts``, ``stream``, ...) [-].

    Returns
    -------
    PipelineResult
        The three stages with their files, wall times and numbers.
    """
    started = time.perf_counter()
    run = checked or check_inputs(factorial, out_dir=out_dir, level=level, model=model, lubricant=lubricant,
                                  study=study, design=design, overwrite=overwrite, workers=workers,
                                  time_limit_s=time_limit_s, effects=effects, roughness=roughness)
    from .surrogate_stage import check_offgrid_points

    check_offgrid_points(offgrid_points, form)  # before stage 1: a sample too small to calibrate is refused now
    out = run.out_dir
    if overwrite:
        for path in (run.dataset, run.coefficients, run.coefficients.with_suffix(".summary.txt")):
            path.unlink(missing_ok=True)
    try:
        stages = [dataset_stage(out, run.factorial, workers=workers, scheduler=scheduler, lubricant=lubricant,
                                level=run.level, model=run.model, progress=progress, time_limit_s=time_limit_s,
                                effects=run.effects, roughness=run.roughness, **runner_options)]
    except InputError as err:  # the store names dataset-run options; the pipeline's are --out-dir / --overwrite
        if "start a new file" in str(err):
            raise InputError(err.parameter, err.value, err.accepted,
                             f"another --out-dir, or --overwrite to replace {run.dataset}") from None
        raise
    dataset = stages[0]
    if dataset.details["interrupted"]:
        raise Interrupted(dataset.details["interrupted"], f"pipeline stage 1 ({dataset.details['computed']} points "
                          f"computed, {dataset.details['pending']} pending in {dataset.artefact})", resume_command)
    stages.extend(surrogate_stages(run, dataset.artefact, lubricant, form=form, offgrid_points=offgrid_points,
                                   allow_unstable=allow_unstable, workers=workers, scheduler=scheduler,
                                   progress=progress, time_limit_s=time_limit_s, resume_command=resume_command))
    stages.append(design_stage(stages[-1].artefact, study=study, design=design, options=mesh_options,
                               clip_to_fitted_ranges=clip_to_fitted_ranges))
    result = PipelineResult(str(out), stages, time.perf_counter() - started)
    if run.smoke:
        result.label = SMOKE_LABEL
    return result


# ---------------------------------------------------------------------- a user's lubricant
def run_lubricant_fit(lubricant, factorial=QUICK_FACTORIAL, *, out_dir=None, workers: int = 1,
                      scheduler: str | None = None, level: str | None = None, model: str | None = None,
                      progress: str = "auto", allow_unstable: bool = False, time_limit_s: float | None = None,
                      overwrite: bool = False, resume_command: str | None = None,
                      checked: PipelinePlan | None = None, effects: str | None = None, form: str = "eq9",
                      offgrid_points: int = 0, adaptive_budget: int | None = None,
                      target_median: float | None = None, target_p90: float | None = None,
                      adaptive_initial: int | None = None, adaptive_batch: int | None = None, roughness=None,
                      **runner_options) -> PipelineResult:
    """Stages 1–2 for ``lubricant``: ``factorial`` → ``OUT/dataset.h5`` → ``OUT/<lubricant>_<factorial>.json``.

    The coefficient file is what ``gearloss gear evaluate --friction FILE`` and
    :func:`efficiency.friction.friction_from_spec` read. Resumable like :func:`run_pipeline` (same directory, same
    factorial, level, model, effects and lubricant definition), on local processes or on a Dask cluster. Every input
    is checked before stage 1, the lubricant's temperature range against the factorial's temperature levels included.

    Parameters
    ----------
    lubricant : str or Path or Lubricant
        The lubricant: a shipped name, a TOML file or an object [-].
    factorial : Factorial or str or Path
        The factorial: an object, a shipped name (``quick``, ``paper2009``, ...) or a TOML path [-].
    out_dir : str or Path, optional
        Output directory; None: ``gearloss_<lubricant>_<factorial>_<level>`` with the model and effects appended
        when not the defaults [-].
    workers : int
        Worker processes of stage 1 [-].
    scheduler : str, optional
        Address of a Dask scheduler to run stage 1 on; None: local processes [-].
    level : str, optional
        Accuracy level of the EHL solves; None: the factorial's [-].
    model : str, optional
        Contact model of the solves (``auto``, ``homogenised``, ``deterministic``); None: the factorial's [-].
    progress : str
        Progress display of stage 1: ``auto``, ``bar``, ``log`` or ``none`` [-].
    allow_unstable : bool
        Write a fit flagged numerically unstable instead of raising [-].
    time_limit_s : float, optional
        Wall-time budget per stage-1 point; a point that spends it is stored not converged with its message [s].
    overwrite : bool
        Start the run afresh: the directory's dataset and coefficient file are replaced [-].
    resume_command : str, optional
        The command that continues this run, named in the :class:`~workflows.exit_codes.Interrupted` raised when a
        signal stops stage 1 [-].
    checked : PipelinePlan, optional
        The result of :func:`check_inputs` for these arguments; None: computed here [-].
    effects : str, optional
        Stage 1's effect plan (one of :data:`ehl_dataset.dataset.factorial.EFFECTS_MODES`; ``isothermal`` gives the
        isothermal data the paper fitted); None: the factorial's [-].
    form : str
        Form of the fitted surrogate: ``eq9`` or ``learned`` [-].
    offgrid_points : int
        Points of the off-grid validation sample recorded in the coefficient file (0: none) [-].
    adaptive_budget : int, optional
        Train on an adaptive design of at most this many solves in the factorial's ranges instead of the factorial
        (:mod:`workflows.adaptive`); None: the factorial [-].
    target_median, target_p90 : float, optional
        Off-grid targets of |Δμ/μ| that stop the adaptive design early [-].
    adaptive_initial, adaptive_batch : int, optional
        Points of the adaptive design's Sobol' start and of each batch; None: the defaults of
        :mod:`workflows.adaptive` [-].
    roughness : RoughnessChoice, optional
        Roughness profile of every rough solve (dataset, off-grid sample, adaptive batches;
        :func:`ehl_dataset.dataset.roughness_choice.choose_roughness`), recorded in each store and the coefficient
        file; None: the default profile. Ignored with ``checked``, which carries its own [-].
    **runner_options
        Options of :func:`ehl_dataset.dataset.runner.run_factorial` (``window``, ``max_attempts``, ``stream``, ...) [-].

    Returns
    -------
    PipelineResult
        The dataset (or adaptive), off-grid and fit stages.
    """
    started = time.perf_counter()
    run = checked or check_inputs(factorial, out_dir=out_dir, level=level, model=model, lubricant=lubricant,
                                  design=None, overwrite=overwrite, workers=workers, time_limit_s=time_limit_s,
                                  effects=effects, roughness=roughness)
    from .surrogate_stage import check_offgrid_points

    check_offgrid_points(offgrid_points, form)  # before any solve: a sample too small to calibrate is refused now
    if overwrite:
        for path in (run.dataset, run.coefficients, run.coefficients.with_suffix(".summary.txt")):
            path.unlink(missing_ok=True)
    stages = []
    if adaptive_budget is None:
        dataset = dataset_stage(run.out_dir, run.factorial, workers=workers, scheduler=scheduler,
                                lubricant=lubricant, level=run.level, model=run.model, progress=progress,
                                time_limit_s=time_limit_s, effects=run.effects, roughness=run.roughness,
                                **runner_options)
        if dataset.details["interrupted"]:
            raise Interrupted(dataset.details["interrupted"], f"lubricant fit stage 1 ({dataset.details['computed']} "
                              f"points computed, {dataset.details['pending']} pending in {dataset.artefact})",
                              resume_command)
        stages.append(dataset)
    stages.extend(surrogate_stages(run, stages[0].artefact if stages else None, lubricant, form=form,
                                   offgrid_points=offgrid_points, adaptive_budget=adaptive_budget,
                                   target_median=target_median, target_p90=target_p90,
                                   adaptive_initial=adaptive_initial, adaptive_batch=adaptive_batch,
                                   allow_unstable=allow_unstable, workers=workers, scheduler=scheduler,
                                   progress=progress, time_limit_s=time_limit_s, resume_command=resume_command))
    result = PipelineResult(str(run.out_dir), stages, time.perf_counter() - started)
    if run.smoke:
        result.label = SMOKE_LABEL
    return result
