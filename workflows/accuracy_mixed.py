"""What accuracy costs in time in the mixed regime: every contact model and level against the deterministic reference.

The reference is the validation set of the deterministic mixed-EHL solver (``data/reference/
deterministic_validation.json``, made by ``python validation/deterministic_validation.py --summarise``: each case
solved at three grid spacings, μ Richardson-extrapolated, with its uncertainty; docs/validation/deterministic-reference.md). Each
model of :data:`MIXED_MODELS` solves every reference case through :func:`ehl_dataset.solver.solve_contact` on the
roughness the reference was computed with (the shipped ``baseline_synthetic`` profile, whatever the package's default),
and the study records

    err_mu = |μ − μ_ref|/μ_ref,   err_hc = |h_c − h_c,ref|/h_c,ref,   Δshare = share − share_ref,

with the central film h_c (the film at x = 0: the time-mean film of the deterministic runs, the mean gap of the
homogenised model) because the minimum of a rough film is a contact spot (h_b) in every model that has asperity
contact. The wall time per case is measured around the call on one core. Runs are checkpointed to JSON after each
solve (a study of the slow models can be stopped and resumed); the report is Markdown plus a PNG of error against
time (:func:`write_mixed_report`). When the reference is recomputed, :func:`rescore_study` measures the runs of an
earlier report against it without solving again (the runs keep the solver version, commit and machine they were made
with; the report names both).
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, Sequence

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.validation import InputError

from .accuracy import provenance, relative_error

REFERENCE_FILE = Path(__file__).resolve().parents[1] / "data" / "reference" / "deterministic_validation.json"
DEFAULT_STEM = "accuracy_mixed"


def _shown_path(path: str | Path) -> str:
    """``path`` relative to the repository root when it lies inside it, else its file name (a report records no
    machine path)."""
    resolved = Path(path).resolve()
    try:
        return str(resolved.relative_to(REFERENCE_FILE.parents[2]))
    except ValueError:
        return resolved.name

MIXED_MODELS: dict[str, dict[str, Any]] = {
    "smooth-standard": {"model": "smooth", "level": "standard"},
    "homogenised-transverse-standard": {"model": "homogenised", "level": "standard", "closure": "transverse"},
    "homogenised-isotropic-standard": {"model": "homogenised", "level": "standard", "closure": "isotropic"},
    "homogenised-film_law-standard": {"model": "homogenised", "level": "standard", "closure": "film_law",
                                      "effects": "isothermal"},
    "homogenised-asperity-standard": {"model": "homogenised", "level": "standard", "closure": "asperity",
                                      "effects": "isothermal"},
    "deterministic-fast": {"model": "deterministic", "level": "fast"},
    "deterministic-standard": {"model": "deterministic", "level": "standard"},
}
"""The models measured, each a :func:`~ehl_dataset.solver.solve_contact` call: the steady smooth solve (what the
mixed regime costs if roughness is ignored), the homogenised model with each closure (the film-law one isothermal,
like the reference and the other rough models; ``asperity`` is the film law with the load of the surviving
roughness, :mod:`ehl_dataset.solvers.asperity_model`) and the deterministic solver at its ``fast`` and ``standard`` grid
rules (the reference itself is its three-spacing extrapolation)."""
CHEAP_MODELS = ("smooth-standard", "homogenised-transverse-standard", "homogenised-isotropic-standard")


@dataclass
class MixedRun:
    """One solve of the study (SI units)."""

    case: str
    model: str
    mu: float
    mu_sem: float
    h_central_m: float
    asperity_load_share: float
    wall_time_s: float
    converged: bool
    message: str
    mu_error: float = math.nan
    h_central_error: float = math.nan
    share_difference: float = math.nan


def load_reference(path: str | Path = REFERENCE_FILE) -> list[dict]:
    """The reference cases (the ``cases`` list of the validation file); InputError if missing or malformed."""
    path = Path(path)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        cases = data["cases"]
        missing = [key for row in cases for key in ("case", "inputs", "mu_extrapolated") if key not in row]
        if missing:
            raise KeyError(missing[0])
    except FileNotFoundError:
        raise InputError("reference", str(path), "an existing file made by validation/deterministic_validation.py "
                                                 "--summarise") from None
    except (ValueError, KeyError, TypeError) as err:
        raise InputError("reference", str(path), f"a deterministic validation file ({type(err).__name__}: {err})") \
            from None
    if not cases:
        raise InputError("reference", str(path), "at least one reference case")
    return cases


def reference_case(row: dict) -> ContactCase:
    i = row["inputs"]
    return ContactCase.from_engineering(i["p_h_gpa"], i["r_eq_mm"], i["u_r_m_s"], i["sr"], i["temp_c"], i["rq1_um"],
                                        i["rq2_um"])


def solve_model(case: ContactCase, lubricant, name: str, solve: Callable | None = None):
    """Solve ``case`` with the model ``name`` of :data:`MIXED_MODELS`; returns the ContactResult."""
    from ehl_dataset.solver import solve_contact
    from ehl_dataset.solvers.homogenised import HomogenisedOptions

    if name not in MIXED_MODELS:
        raise InputError("model", name, f"one of {list(MIXED_MODELS)}")
    from ehl_dataset.model.roughness import baseline_profile

    spec = MIXED_MODELS[name]
    # the reference cases were computed on the shipped baseline profile, not on the package's default roughness
    kwargs = {"model": spec["model"], "roughness": baseline_profile()}
    if "closure" in spec:
        kwargs["homogenised"] = HomogenisedOptions(closure=spec["closure"])
    return (solve or solve_contact)(case, lubricant, spec["level"], spec.get("effects", "auto"), **kwargs)


def _run(case: ContactCase, lubricant, row: dict, name: str, solve: Callable | None) -> MixedRun:
    start = time.perf_counter()
    try:
        result = solve_model(case, lubricant, name, solve)
    except InputError:
        raise
    except Exception as err:  # a failed solve is a data point of the study
        return MixedRun(row["case"], name, math.nan, math.nan, math.nan, math.nan, time.perf_counter() - start, False,
                        f"{type(err).__name__}: {err}")
    elapsed = time.perf_counter() - start
    return MixedRun(row["case"], name, float(result.mu), float(result.mu_sem or 0.0), float(result.h_central),
                    float(result.asperity_load_share), elapsed, bool(result.converged), result.message or "")


def _measure(run: MixedRun, row: dict) -> MixedRun:
    """Set the errors of ``run`` against the reference ``row`` (also for a run resumed from a checkpoint: the
    reference may have been recomputed since)."""
    if not math.isfinite(run.mu):
        return run
    run.mu_error = relative_error(run.mu, row["mu_extrapolated"])
    if row.get("h_central_m"):
        run.h_central_error = relative_error(run.h_central_m, row["h_central_m"])
    share_ref = row.get("asperity_load_share_extrapolated")
    if share_ref is not None and math.isfinite(run.asperity_load_share):
        run.share_difference = run.asperity_load_share - share_ref
    return run


def run_mixed_study(models: Sequence[str] = CHEAP_MODELS, reference: str | Path = REFERENCE_FILE,
                    lubricant: str = "atf", checkpoint: str | Path | None = None, solve: Callable | None = None,
                    progress: Callable[[str], None] | None = None) -> dict:
    """Solve every reference case with every model; resume from ``checkpoint`` (runs of the same case and model
    already there are kept when the solver version matches, and for the deterministic models the deterministic
    model's version too) and rewrite it after each solve."""
    from ehl_dataset.model.lubricant import load_lubricant
    from ehl_dataset.solver import SOLVER_VERSION
    from ehl_dataset.solvers.deterministic import MODEL_VERSION

    for name in models:
        if name not in MIXED_MODELS:
            raise InputError("models", name, f"names from {list(MIXED_MODELS)}")
    cases = load_reference(reference)
    lub = load_lubricant(lubricant)
    done: dict[tuple[str, str], MixedRun] = {}
    if checkpoint is not None and Path(checkpoint).exists():
        old = json.loads(Path(checkpoint).read_text(encoding="utf-8"))
        same_deterministic = old.get("deterministic_model_version") == MODEL_VERSION
        if old.get("solver_version") == SOLVER_VERSION:
            done = {(r["case"], r["model"]): MixedRun(**r) for r in old.get("runs", [])
                    if same_deterministic or not r["model"].startswith("deterministic")}
    runs: list[MixedRun] = []
    for row in cases:
        case = reference_case(row)
        for name in models:
            run = _measure(done.get((row["case"], name)) or _run(case, lub, row, name, solve), row)
            done[(row["case"], name)] = run
            runs.append(run)
            if progress:
                progress(f"{row['case']}: {name} mu={run.mu:.4g} (ref {row['mu_extrapolated']:.4g}, "
                         f"err {run.mu_error:.1%}) in {run.wall_time_s:.3g} s")
            if checkpoint is not None:
                Path(checkpoint).write_text(json.dumps(
                    {"solver_version": SOLVER_VERSION, "deterministic_model_version": MODEL_VERSION,
                     "runs": [dataclasses.asdict(r) for r in done.values()]},
                    default=float), encoding="utf-8")
    return {"runs": runs, "cases": cases, "models": list(models),
            "provenance": {**provenance(), "deterministic_model_version": MODEL_VERSION,
                           "reference_sha256": reference_fingerprint(reference)},
            "reference_file": _shown_path(reference)}


def reference_fingerprint(path: str | Path) -> str:
    """First 12 hex digits of the SHA-256 of the reference file: which reference a report was measured against."""
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()[:12]


def rescore_study(report: str | Path, reference: str | Path = REFERENCE_FILE,
                  models: list[str] | tuple[str, ...] | None = None) -> dict:
    """The runs of an earlier report (the ``<stem>.json`` of :func:`write_mixed_report`) measured against
    ``reference`` without solving again, for a recomputed reference. The runs keep their provenance (solver version,
    commit, machine, date, command); the study's ``rescored`` records the re-measurement's. InputError if the report
    is missing or corrupt, holds a case the reference does not, or was solved at other inputs than the reference's
    (checked where the report records them, ``reference_inputs``). ``models``: only these of the report's models
    (None: all of them); InputError naming the report's models for one it does not hold."""
    path = Path(report)
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
        runs = [MixedRun(**{**r, "mu_error": math.nan, "h_central_error": math.nan, "share_difference": math.nan})
                for r in data["runs"]]
        data_models, runs_provenance, runs_command = list(data["models"]), dict(data["provenance"]), str(data["command"])
    except FileNotFoundError:
        raise InputError("report", str(path), "an existing <stem>.json written by gearloss accuracy --mixed") from None
    except (ValueError, KeyError, TypeError) as err:
        raise InputError("report", str(path), f"a report JSON of gearloss accuracy --mixed ({type(err).__name__}: "
                                              f"{err})") from None
    if models is not None:
        missing = [m for m in models if m not in data_models]
        if missing or not models:
            raise InputError("models", " ".join(models) or "<none>", f"models of the report {path}: "
                                                                      f"{' '.join(data_models)}")
        runs = [run for run in runs if run.model in models]
    models = list(models) if models is not None else data_models
    by_name = {row["case"]: row for row in load_reference(reference)}
    solved_at = data.get("reference_inputs", {})
    for run in runs:
        if run.case not in by_name:
            raise InputError("report", str(path), f"runs of the reference's cases {sorted(by_name)} (case "
                                                  f"{run.case!r} is not in {reference})")
        if run.case in solved_at and solved_at[run.case] != by_name[run.case]["inputs"]:
            raise InputError("report", str(path), f"runs solved at the reference's inputs (case {run.case}: "
                                                  f"{solved_at[run.case]} against {by_name[run.case]['inputs']})")
    names = {run.case for run in runs}
    cases = [row for name, row in by_name.items() if name in names]
    runs = [_measure(run, by_name[run.case]) for run in runs]
    rescored = {**provenance(), "report": _shown_path(path), "reference_sha256": reference_fingerprint(reference),
                "cases_without_runs": sorted(set(by_name) - names)}
    return {"runs": runs, "cases": cases, "models": models, "provenance": runs_provenance,
            "runs_command": runs_command, "reference_file": _shown_path(reference), "rescored": rescored}


def summary(study: dict) -> dict[str, dict[str, float]]:
    """Per model: cases, converged, median / 90th percentile / max of err_mu, median err_hc, median |Δshare|, mean
    and median wall time."""
    out = {}
    for name in study["models"]:
        runs = [r for r in study["runs"] if r.model == name]
        err = np.array([r.mu_error for r in runs], dtype=float)
        hc = np.array([r.h_central_error for r in runs], dtype=float)
        share = np.abs(np.array([r.share_difference for r in runs], dtype=float))
        times = np.array([r.wall_time_s for r in runs], dtype=float)

        def stat(fn, v):
            v = v[np.isfinite(v)]
            return float(fn(v)) if v.size else math.nan

        out[name] = {"n_cases": len(runs), "converged": int(sum(r.converged for r in runs)),
                     "mu_error_median": stat(np.median, err), "mu_error_p90": stat(lambda v: np.percentile(v, 90), err),
                     "mu_error_max": stat(np.max, err), "h_central_error_median": stat(np.median, hc),
                     "share_difference_median": stat(np.median, share),
                     "wall_time_mean_s": stat(np.mean, times), "wall_time_median_s": stat(np.median, times)}
    return out


def _pct(v: float) -> str:
    return "n/a" if not math.isfinite(v) else f"{100 * v:.3g} %"


def markdown_mixed(study: dict, command: str, png_name: str) -> str:
    """The report: ``command`` made it (for a rescored study, :func:`rescore_study`, the command that rescored it;
    the runs' own command is ``study["runs_command"]``)."""
    prov = study["provenance"]
    rescored = study.get("rescored")
    runs_command = study.get("runs_command", command)
    regenerate = [f"    {runs_command}"]
    if rescored:
        regenerate += ["", "then, against a recomputed reference, without solving again:", "", f"    {command}"]
    lines = ["# Mixed regime: accuracy versus time against the deterministic reference", "",
             "Generated by `gearloss accuracy --mixed` (`workflows/accuracy_mixed.py`); do not edit by hand. "
             "Regenerate with:", "", *regenerate, "",
             f"Reference: `{Path(study['reference_file']).name}` (the deterministic solver's validation set, μ "
             "Richardson-extrapolated from its three finest grid spacings; docs/validation/deterministic-reference.md). err μ = |μ − μ_ref|/"
             "μ_ref; err h_c is that of the central film, against the reference's time mean of the film at x = 0 over its "
             "longest averaging window (± its standard error: windows of 1.5 passes scatter by 1–10 % where λ̄ > 0.25 and a/β > 5, 14–29 % on A, B, C (measured), "
             "validation/deterministic_film_sampling.py); Δshare the difference of the asperity load share. Wall time "
             "per case on one core, around `solve_contact`.", "",
             f"EHL solver {prov.get('solver_version')} (deterministic model "
             f"{prov.get('deterministic_model_version', 'not recorded')}), commit `{prov.get('git_commit')}`"
             + (" (with uncommitted solver changes)" if prov.get("solver_files_modified") else "")
             + f", {prov.get('date_utc')}; {prov.get('platform')}, {prov.get('cpu_count')} CPUs"
             + (f"; reference `{prov['reference_sha256']}` (first digits of its SHA-256)." if prov.get("reference_sha256")
                else "."), ""]
    if rescored:
        lines += [f"Errors re-measured against the reference `{rescored['reference_sha256']}` on "
                  f"{rescored.get('date_utc')} (commit `{rescored.get('git_commit')}`, EHL solver "
                  f"{rescored.get('solver_version')}) from the runs of `{Path(rescored['report']).name}`: the μ, "
                  "films, shares and times are those of the runs, made with the versions above"
                  + (f"; reference cases without runs: {', '.join(rescored['cases_without_runs'])}"
                     if rescored.get("cases_without_runs") else "") + ".", ""]
    lines += ["## Summary", "",
             "| model | cases | converged | median err μ | 90th pct err μ | max err μ | median err h_c | "
             "median \\|Δshare\\| | mean time [s] | median time [s] |", "|---|---|---|---|---|---|---|---|---|---|"]
    for name, row in summary(study).items():
        lines.append(f"| {name} | {row['n_cases']} | {row['converged']} | {_pct(row['mu_error_median'])} | "
                     f"{_pct(row['mu_error_p90'])} | {_pct(row['mu_error_max'])} | "
                     f"{_pct(row['h_central_error_median'])} | {row['share_difference_median']:.3f} | "
                     f"{row['wall_time_mean_s']:.3g} | {row['wall_time_median_s']:.3g} |")
    made = f"*Made by `{runs_command}` (gearloss {prov.get('gearloss')}, EHL solver {prov.get('solver_version')})" + (
        f", errors re-measured by `{command}` ({rescored.get('date_utc')}).*" if rescored else ".*")
    lines += ["", f"![error versus time]({png_name})", "", made,
              "", "## Per case", "",
              "| case | λ̄ | a/β | μ_ref ± | h_c,ref ± [nm] | share_ref | model | μ | err μ | h_c [nm] | err h_c | share | "
              "time [s] | converged |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    from ehl_dataset.model.roughness import baseline_profile

    beta = baseline_profile().correlation_length
    for row in study["cases"]:
        for run in (r for r in study["runs"] if r.case == row["case"]):
            hc_ref = row.get("h_central_m")
            hc_sem = row.get("h_central_sem_m", math.nan)
            hc_text = "n/a" if not hc_ref else f"{hc_ref * 1e9:.0f}" + (
                f" ± {hc_sem * 1e9:.0f}" if hc_sem is not None and math.isfinite(hc_sem) else "")
            lines.append(
                f"| {row['case']} | {row['lambda_bar']:.3g} | {row['half_width_m'] / beta:.1f} | "
                f"{row['mu_extrapolated']:.4f} ± {row['mu_uncertainty']:.4f} | "
                f"{hc_text} | "
                f"{row.get('asperity_load_share_extrapolated', math.nan):.3f} | {run.model} | {run.mu:.4f} | "
                f"{_pct(run.mu_error)} | {run.h_central_m * 1e9:.0f} | {_pct(run.h_central_error)} | "
                f"{run.asperity_load_share:.3f} | {run.wall_time_s:.3g} | {'yes' if run.converged else 'NO'} |")
    failures = [r for r in study["runs"] if not r.converged]
    if failures:
        lines += ["", "Not converged:", ""] + [f"- {r.case}, {r.model}: {r.message}" for r in failures]
    return "\n".join(lines) + "\n"


def plot_mixed(study: dict, path: Path, floor: float = 1e-4) -> Path:
    """Relative error of μ against wall time per case (labelled), one colour per model (median as a star), log
    axes."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.5, 4.8), constrained_layout=True)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for k, name in enumerate(study["models"]):
        runs = [r for r in study["runs"] if r.model == name and math.isfinite(r.mu_error)]
        if not runs:
            continue
        t = np.array([r.wall_time_s for r in runs])
        e = np.maximum(np.array([r.mu_error for r in runs]), floor)
        c = colours[k % len(colours)]
        ax.scatter(t, e, s=22, color=c, alpha=0.7)
        for r, ti, ei in zip(runs, t, e):
            ax.annotate(r.case, (ti, ei), fontsize=6, color=c, xytext=(3, 2), textcoords="offset points")
        ax.scatter([np.median(t)], [np.median(e)], s=150, marker="*", color=c, edgecolor="black", zorder=5,
                   label=f"{name} (median)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.axhline(0.10, color="grey", ls=":", lw=1)
    ax.set_xlabel("wall time per case [s]")
    ax.set_ylabel("relative error of μ against the reference")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    prov = study["provenance"]
    rescored = study.get("rescored")
    ax.set_title(f"mixed regime, {len(study['cases'])} reference cases (EHL solver {prov.get('solver_version')}, "
                 f"commit {prov.get('git_commit')})"
                 + (f"\nerrors re-measured against reference {rescored['reference_sha256']}, "
                    f"{rescored.get('date_utc')}" if rescored else ""), fontsize=9)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def write_mixed_report(study: dict, out_dir: str | Path, command: str, stem: str = DEFAULT_STEM) -> dict[str, Path]:
    """Write ``<stem>.md``, ``<stem>.png`` and ``<stem>.json`` into ``out_dir``."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    png = plot_mixed(study, out / f"{stem}.png")
    md = out / f"{stem}.md"
    md.write_text(markdown_mixed(study, command, png.name), encoding="utf-8")
    raw = out / f"{stem}.json"
    payload = {"provenance": study["provenance"], "command": study.get("runs_command", command),
               "models": study["models"], "reference_file": study["reference_file"],
               "reference_inputs": {row["case"]: row["inputs"] for row in study["cases"]}, "summary": summary(study),
               "runs": [dataclasses.asdict(r) for r in study["runs"]]}
    if study.get("rescored"):
        payload["rescored"] = {**study["rescored"], "command": command}
    raw.write_text(json.dumps(payload, indent=1, default=float), encoding="utf-8")
    return {"markdown": md, "plot": png, "json": raw}
