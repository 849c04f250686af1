"""The end-to-end pipeline: a factorial of mixed-EHL contacts → a fitted friction surrogate → a gear design's loss.

Three stage functions, each returning a :class:`StageResult` (artefact path, wall time, the numbers worth
reporting), and :func:`run_pipeline` that chains them in one process (docs/pipeline.md):

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
``ok`` rows in a branch, rank deficiency, an unstable fit); stage 3 reports the surrogate's extrapolation warnings
and whether the load distribution converged.
"""

from __future__ import annotations

import math
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ehl_dataset.validation import InputError, SolverError

QUICK_FACTORIAL = "quick"
PAPER_FACTORIAL = "paper2009"
DATASET_FILE = "dataset.h5"


@dataclass
class StageResult:
    """One stage: ``name``, the file it wrote (``artefact``), its wall time [s] and the numbers it reports
    (``details``, SI units with the unit in each key)."""

    name: str
    artefact: str | None
    wall_time_s: float
    details: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "artefact": self.artefact, "wall_time_s": self.wall_time_s, **self.details}


@dataclass
class PipelineResult:
    """All stages of one pipeline run, in order, and the total wall time [s]."""

    out_dir: str
    stages: list[StageResult]
    wall_time_s: float

    def stage(self, name: str) -> StageResult:
        for stage in self.stages:
            if stage.name == name:
                return stage
        raise KeyError(name)

    def to_dict(self) -> dict[str, Any]:
        return {"out_dir": self.out_dir, "wall_time_s": self.wall_time_s,
                "stages": {s.name: s.to_dict() for s in self.stages}}


def _factorial(factorial):
    from ehl_dataset.dataset.factorial import Factorial, load_factorial

    return factorial if isinstance(factorial, Factorial) else load_factorial(factorial)


def coefficients_file_name(lubricant_name: str, factorial_name: str) -> str:
    """``<lubricant>_<factorial>.json`` with the factorial name shortened as in the brief: quick → ``atf_quick``."""
    safe = "".join(c if c.isalnum() or c in "-_" else "_" for c in f"{lubricant_name}_{factorial_name}")
    return f"{safe}.json"


# ---------------------------------------------------------------------- stage 1
def dataset_stage(out_dir: str | Path, factorial, *, workers: int = 1, scheduler: str | None = None,
                  lubricant=None, level: str | None = None, progress: str = "auto", overwrite: bool = False,
                  time_limit_s: float | None = None, **runner_options) -> StageResult:
    """Compute ``factorial`` (a :class:`~ehl_dataset.dataset.factorial.Factorial`, a shipped name or a TOML path) into
    ``out_dir/dataset.h5``; continue the file if it holds the same run. ``time_limit_s``: wall-time budget per
    point [s] (None: none; a point that spends it is stored not converged with its message; an execution option, so
    a file continues whatever budget it was started with). ``runner_options`` go to
    :func:`ehl_dataset.dataset.runner.run_factorial` (``window``, ``max_attempts``, ``stream``, ...)."""
    from ehl_dataset.dataset.runner import check_time_limit, run_factorial

    time_limit_s = check_time_limit(time_limit_s)
    started = time.perf_counter()
    plan = _factorial(factorial)
    out = Path(out_dir) / DATASET_FILE
    out.parent.mkdir(parents=True, exist_ok=True)
    resumed = out.exists() and not overwrite
    summary = run_factorial(out, plan, lubricant=lubricant, level=level, workers=workers, scheduler=scheduler,
                            progress=progress, overwrite=overwrite, time_limit_s=time_limit_s, **runner_options)
    details = {"factorial": plan.name, "n_points": summary.n_points, "computed": summary.computed,
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
def fit_stage(dataset_path: str | Path, coefficients_path: str | Path, *, allow_unstable: bool = False,
              blend_half_width: float = 0.1) -> StageResult:
    """Fit paper Eq. 9a/9b on the dataset and write the coefficient file (and its summary beside it).

    Raises :class:`SolverError` ("fit stage: ...") when the rows cannot determine a branch of the regression.
    """
    from surrogate.coefficients import summary_path, write_coefficients
    from surrogate.dataset_io import load_dataset
    from surrogate.fit import fit_surrogate

    started = time.perf_counter()
    data = load_dataset(dataset_path)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            fit = fit_surrogate(data.table, data.lubricant, data.e_reduced, allow_unstable=allow_unstable,
                                blend_half_width=blend_half_width)
        except SolverError as err:
            raise SolverError(f"fit stage ({dataset_path}): {err}") from err
        except (InputError, ValueError, IndexError) as err:
            counts = data.source.get("counts")
            raise SolverError(f"fit stage ({dataset_path}, rows by status {counts}): the data cannot determine "
                              f"the regression: {type(err).__name__}: {err}") from err
    path = write_coefficients(fit, coefficients_path, source=data.source)
    cv = fit.cv["overall"]
    details = {
        "lubricant": data.lubricant.name, "n_input_rows": fit.n_input_rows, "n_used": fit.n_used,
        "exclusions": fit.exclusions, "stable": fit.stable,
        "branches": {b: {"n_obs": f.n_obs, "adj_r2": f.adj_r2, "resid_std_error": f.resid_std_error}
                     for b, f in fit.branches.items()},
        "cv_rmse_ln_mu": cv["rmse_ln_mu"], "cv_mean_rel_err_mu": cv["mean_rel_err_mu"],
        "summary": str(summary_path(path)),
        "warnings": sorted({str(w.message)[:200] for w in caught}),
    }
    return StageResult("fit", str(path), time.perf_counter() - started, details)


# ---------------------------------------------------------------------- stage 3
def design_stage(friction, *, study: str = "paper2009", design: str = "D", options=None,
                 clip_to_fitted_ranges: bool = True) -> StageResult:
    """Evaluate the study's published design (default: Design D of Table 1) at the study's operating point with
    ``friction`` (a coefficient file path / shipped name or any other spec of
    :func:`efficiency.friction.friction_from_spec`, or a friction model). A coefficient file is evaluated with its
    inputs clipped to its fitted ranges (the surrogate's own clipping; the number of clipped contact points per
    input is reported) unless ``clip_to_fitted_ranges`` is False, in which case it extrapolates with warnings."""
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
    pair = paper.design(design)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        row = evaluate_design(pair, friction, point, options or MeshOptions())
    details = {
        "study": paper.name, "design": design, "friction_model": artefact or type(friction).__name__,
        "torque_nm": point.input_torque, "speed_rpm": point.input_speed * 30.0 / math.pi,
        "oil_temperature_k": point.oil_temperature, "rq1_m": point.rq1, "rq2_m": point.rq2,
        "profile_crown_m": point.modifications.profile_crown, "lead_crown_m": point.modifications.lead_crown,
        "input_power_w": point.input_torque * point.input_speed,
        **{k: row[k] for k in ("power_loss_w", "efficiency", "te_pp_m", "sigma_c_pa", "sigma_b_pa", "mu_mean",
                               "converged")},
        "model_time_s": row["wall_time_s"],
        "warnings": sorted({str(w.message)[:300] for w in caught}),
    }
    stats = friction.last_stats() if hasattr(friction, "last_stats") else {}
    if "clipped_inputs" in stats:
        details["clipped_to_fitted_range"] = {"contact_points": stats["surrogate_points"], **stats["clipped_inputs"]}
    return StageResult("design", artefact, time.perf_counter() - started, details)


# ---------------------------------------------------------------------- the chain
def run_pipeline(out_dir: str | Path, factorial=QUICK_FACTORIAL, *, workers: int = 1, scheduler: str | None = None,
                 lubricant=None, level: str | None = None, progress: str = "auto", study: str = "paper2009",
                 design: str = "D", allow_unstable: bool = False, mesh_options=None,
                 clip_to_fitted_ranges: bool = True, time_limit_s: float | None = None,
                 **runner_options) -> PipelineResult:
    """Stages 1–3 in one process: dataset → coefficient file → design evaluation (see the module docstring).
    ``time_limit_s``: stage 1's wall-time budget per point [s] (:func:`dataset_stage`)."""
    started = time.perf_counter()
    plan = _factorial(factorial)
    out = Path(out_dir)
    stages = [dataset_stage(out, plan, workers=workers, scheduler=scheduler, lubricant=lubricant, level=level,
                            progress=progress, time_limit_s=time_limit_s, **runner_options)]
    dataset = stages[0]
    if dataset.details["interrupted"]:
        raise SolverError(f"dataset stage interrupted ({dataset.details['interrupted']}); run the pipeline again "
                          f"to resume {dataset.artefact}")
    from ehl_dataset.dataset.store import read_metadata

    lubricant_name = str(read_metadata(dataset.artefact)["lubricant"].get("name", "lubricant"))
    coefficients = out / coefficients_file_name(lubricant_name, plan.name)
    stages.append(fit_stage(dataset.artefact, coefficients, allow_unstable=allow_unstable))
    stages.append(design_stage(stages[1].artefact, study=study, design=design, options=mesh_options,
                               clip_to_fitted_ranges=clip_to_fitted_ranges))
    return PipelineResult(str(out), stages, time.perf_counter() - started)
