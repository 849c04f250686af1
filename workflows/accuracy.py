"""What accuracy costs in time: each EHL accuracy level against the reference level on a fixed case set.

For every case of :data:`ACCURACY_CASES` (16 points of the paper's factorial, including its hardest corners)
the study solves the reference (``reference`` level, ``effects="full"`` by default: the most complete model) and each
level as a user runs it (``effects="auto"``: the planner's approximations are part of the level's error), and records

    err_mu = |μ − μ_ref|/μ_ref,   err_h = |h_min − h_min,ref|/h_min,ref   (NaN where h_min,ref ≤ 0, asperity contact),

the wall time per case (``time.perf_counter`` around :func:`ehl_dataset.solver.solve_contact`, numba compiled before),
and whether each solve converged. :func:`write_report` writes ``<stem>.md`` (Markdown tables) and ``<stem>.png``
(error versus time, log axes); :func:`convergence_study` measures μ and h_min under refinement of the level's grid
spacing with the observed order of convergence (steady solves; the deterministic rough model's grid convergence is
its validation, docs/validation/deterministic-reference.md).

Rough cases solved at the ``reference`` level, or with every effect (``effects="full"``), run the deterministic
transient model: minutes to hours per case. The accuracy of the mixed regime's models is measured against its
twelve-case reference set by :mod:`workflows.accuracy_mixed` (``gearloss accuracy --mixed``).
"""

from __future__ import annotations

import dataclasses
import json
import math
import platform
import subprocess
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Callable, Sequence

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.validation import InputError

CaseSpec = tuple[str, float, float, float, float, float, float, float]

ACCURACY_CASES: tuple[CaseSpec, ...] = (
    # name, p_h [GPa], r_eq [mm], u_r [m/s], SR, T [°C], Rq1 [µm], Rq2 [µm]         (λ̄ with the ATF)
    ("corner-hard-sr1", 2.5, 5.0, 1.0, 1.0, 100.0, 1.0, 1.0),      # 0.018: hardest corner
    ("corner-hard-sr0", 2.5, 5.0, 1.0, 0.0, 100.0, 1.0, 1.0),      # 0.018, pure rolling
    ("corner-big-heavy", 2.5, 80.0, 1.0, 1.0, 100.0, 0.4, 1.0),    # 0.054, a = 3.5 mm, M ≈ 1050
    ("corner-smooth-heavy", 2.5, 5.0, 1.0, 0.0, 100.0, 0.05, 0.05),  # 0.36, smoothest at the hard corner
    ("thin-light", 0.5, 10.0, 1.0, 0.05, 100.0, 0.7, 0.7),         # 0.047
    ("big-hot", 1.5, 80.0, 5.0, 0.2, 100.0, 1.0, 1.0),             # 0.14
    ("gear-typical", 1.0, 20.0, 5.0, 0.2, 90.0, 0.4, 0.4),         # 0.31
    ("mid-unequal", 1.5, 10.0, 10.0, 0.4, 75.0, 0.2, 0.5),         # 0.52
    ("heavy-slide", 2.0, 40.0, 2.0, 0.7, 50.0, 0.3, 0.3),          # 0.54
    ("near-one", 1.0, 10.0, 20.0, 0.05, 75.0, 0.2, 0.5),           # 0.94
    ("mixed-1.6", 1.0, 20.0, 10.0, 0.4, 50.0, 0.3, 0.3),           # 1.6
    ("mixed-2.2", 2.0, 20.0, 10.0, 0.2, 25.0, 0.4, 0.4),           # 2.2
    ("corner-fast-cold", 2.5, 20.0, 20.0, 1.0, 25.0, 0.5, 0.5),    # 2.7
    ("threshold-3.0", 1.0, 40.0, 10.0, 0.1, 50.0, 0.2, 0.2),       # 3.0 (planner threshold)
    ("full-film-9", 1.0, 5.0, 15.0, 0.1, 25.0, 0.1, 0.1),          # 9.1
    ("corner-thick", 0.5, 80.0, 20.0, 1.0, 25.0, 0.05, 0.05),      # 62: thickest corner
)
"""The fixed case set (engineering units). Levels on each axis of the paper's factorial appear at both ends."""

DEFAULT_LEVELS = ("fast", "standard")
DEFAULT_STEM = "accuracy_levels_rough"
"""File name stem of the report; docs/validation/index.md is the hand-written summary of all accuracy results."""


def case_from_spec(spec: CaseSpec) -> ContactCase:
    """The contact case of one row of :data:`ACCURACY_CASES`.

    Parameters
    ----------
    spec : tuple
        name, p_h in GPa, r_eq in mm, u_r in m/s, SR, T in °C, Rq1 and Rq2 in µm [-].

    Returns
    -------
    ContactCase
        The case in SI.
    """
    return ContactCase.from_engineering(*spec[1:])


@dataclass
class CaseRun:
    """One solve of the study (SI units; ``wall_time_s`` measured around the call).

    Parameters
    ----------
    case : str
        Case name [-].
    level : str
        Accuracy level [-].
    effects_mode : str
        Effect plan [-].
    mu : float
        Friction coefficient [-].
    h_min_m : float
        Minimum film thickness [m].
    wall_time_s : float
        Wall time of the solve [s].
    converged : bool
        Whether the solve converged [-].
    lambda_bar : float
        Film parameter λ̄ of the solve [-].
    roughness : bool
        Whether the plan simulated roughness [-].
    message : str
        The solver's message [-].
    mu_error : float
        |μ − μ_ref|/μ_ref [-].
    h_min_error : float
        |h_min − h_min,ref|/h_min,ref [-].
    mu_sem : float
        Standard error of a time-averaged μ (NaN for steady solves) [-].
    """

    case: str
    level: str
    effects_mode: str
    mu: float
    h_min_m: float
    wall_time_s: float
    converged: bool
    lambda_bar: float
    roughness: bool
    message: str = ""
    mu_error: float = math.nan
    h_min_error: float = math.nan
    mu_sem: float = math.nan
    """Standard error of a rough run's time-averaged μ (0 for steady solves; NaN in studies made before it)."""


@dataclass
class AccuracyStudy:
    """All runs of a study plus provenance (solver commit, machine).

    Parameters
    ----------
    runs : list of CaseRun
        Every solve, reference runs included [-].
    reference_level : str
        Level of the reference solves [-].
    levels : tuple of str
        The levels compared [-].
    cases : tuple of tuple
        The cases (rows of :data:`ACCURACY_CASES`) [-].
    provenance : dict
        Machine and code version (:func:`provenance`) [-].
    """

    runs: list[CaseRun]
    reference_level: str
    levels: tuple[str, ...]
    cases: tuple[CaseSpec, ...]
    provenance: dict[str, Any] = field(default_factory=dict)

    def for_level(self, level: str) -> list[CaseRun]:
        """The runs at one level, in case order.

        Parameters
        ----------
        level : str
            Level name [-].

        Returns
        -------
        list of CaseRun
            The runs.
        """
        return [r for r in self.runs if r.level == level]

    def summary(self) -> dict[str, dict[str, float]]:
        """Per level: median and max relative errors of μ and h_min, mean and median wall time, converged count.

        Returns
        -------
        dict
            {level: {statistic: value}}, errors as fractions [-] and times in seconds.
        """
        out = {}
        groups = [(level, [r for r in self.runs if r.level == level and r.effects_mode != "reference"])
                  for level in self.levels]
        groups.append((f"{self.reference_level} (reference)",
                       [r for r in self.runs if r.effects_mode == "reference"]))
        for label, runs in groups:
            mu_err = np.array([r.mu_error for r in runs], dtype=float)
            h_err = np.array([r.h_min_error for r in runs], dtype=float)
            times = np.array([r.wall_time_s for r in runs], dtype=float)
            out[label] = {
                "n_cases": len(runs),
                "converged": int(sum(r.converged for r in runs)),
                "mu_error_median": _nanstat(np.nanmedian, mu_err),
                "mu_error_max": _nanstat(np.nanmax, mu_err),
                "h_min_error_median": _nanstat(np.nanmedian, h_err),
                "h_min_error_max": _nanstat(np.nanmax, h_err),
                "wall_time_mean_s": float(times.mean()) if times.size else math.nan,
                "wall_time_median_s": float(np.median(times)) if times.size else math.nan,
            }
        return out


def _nanstat(fn, values: np.ndarray) -> float:
    finite = values[np.isfinite(values)]
    return float(fn(finite)) if finite.size else math.nan


def provenance() -> dict[str, Any]:
    """Machine and code version: platform, CPU count, Python/NumPy versions, git commit of the checkout."""
    import os
    import sys

    commit = "unknown"
    dirty = None
    try:
        root = Path(__file__).resolve().parent.parent
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=root, capture_output=True, text=True,
                                timeout=10).stdout.strip() or "unknown"
        status = subprocess.run(["git", "status", "--porcelain", "--", "ehl_dataset"], cwd=root,
                                capture_output=True, text=True, timeout=10).stdout
        dirty = bool(status.strip())
    except (OSError, subprocess.SubprocessError):
        pass
    try:
        from importlib.metadata import version

        package_version = version("gearloss")
    except Exception:  # pragma: no cover - not installed
        package_version = "unknown"
    return {
        "platform": platform.platform(),
        "processor": platform.processor() or platform.machine(),
        "cpu_count": os.cpu_count(),
        "python": sys.version.split()[0],
        "numpy": np.__version__,
        "gearloss": package_version,
        "solver_version": _solver_version(),
        "git_commit": commit,
        "solver_files_modified": dirty,
        "date_utc": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
    }


def _solver_version() -> str:
    from ehl_dataset.solver import SOLVER_VERSION

    return SOLVER_VERSION


def _default_solver():
    from ehl_dataset.solver import solve_contact

    return solve_contact


def effects_argument(effects):
    """``"auto"``/``"full"``/an Effects pass through; ``"smooth"`` is the steady smooth plan (roughness ignored)."""
    if effects == "smooth":
        from ehl_dataset.model.effects import Effects

        return Effects.smooth_steady(forced="accuracy study: steady smooth physics")
    return effects


def _solve(solve: Callable, case: ContactCase, lubricant, level, effects, name: str, label: str,
           mode: str) -> CaseRun:
    effects = effects_argument(effects)
    start = time.perf_counter()
    try:
        result = solve(case, lubricant, level, effects)
    except InputError:
        raise
    except Exception as err:  # a failed solve is a data point of the study, not a crash of it
        return CaseRun(name, label, mode, math.nan, math.nan, time.perf_counter() - start, False, math.nan, False,
                       f"{type(err).__name__}: {err}")
    elapsed = time.perf_counter() - start
    return CaseRun(name, label, mode, float(result.mu), float(result.h_min), elapsed, bool(result.converged),
                   float(result.lambda_bar), bool(result.effects.get("roughness", False)), result.message or "",
                   mu_sem=float(getattr(result, "mu_sem", math.nan)))


def relative_error(value: float, reference: float) -> float:
    """Relative error |value − reference|/|reference|.

    Parameters
    ----------
    value : float
        The value [-].
    reference : float
        The reference, in the unit of ``value`` [-].

    Returns
    -------
    float
        The error; NaN if the reference is not a positive finite number [-].
    """
    if not (math.isfinite(reference) and reference > 0.0) or not math.isfinite(value):
        return math.nan
    return abs(value - reference) / reference


def run_study(cases: Sequence[CaseSpec] = ACCURACY_CASES, levels: Sequence[str] = DEFAULT_LEVELS,
              reference: str = "reference", lubricant="atf", reference_effects: str = "full",
              level_effects: str = "auto", solve: Callable | None = None,
              progress: Callable[[str], None] | None = None, checkpoint: str | Path | None = None) -> AccuracyStudy:
    """Solve every case at the reference and at each level; errors relative to the reference (module docstring).

    Parameters
    ----------
    cases : sequence of tuple
        Cases as rows of :data:`ACCURACY_CASES`: name, p_h in GPa, r_eq in mm, u_r in m/s, SR, T in °C, Rq1 and Rq2
        in µm [-].
    levels : sequence of str
        Accuracy levels compared with the reference [-].
    reference : str
        Level of the reference solves [-].
    lubricant : str or Lubricant
        The lubricant [-].
    reference_effects : str
        Effect plan of the reference solves [-].
    level_effects : str
        Effect plan of the level solves [-].
    solve : callable, optional
        Solve function with the signature of :func:`ehl_dataset.solver.solve_contact`; None: that function [-].
    progress : callable, optional
        Called with a one-line message after every solve [-].
    checkpoint : str or Path, optional
        JSON file the runs so far are written to after every case, so that a long study can be stopped [-].

    Returns
    -------
    AccuracyStudy
        Every run with its errors, and the provenance.
    """
    from ehl_dataset.model.lubricant import Lubricant, load_lubricant

    if not cases:
        raise InputError("cases", 0, "at least one case")
    lub = lubricant if isinstance(lubricant, Lubricant) else load_lubricant(lubricant)
    solve = solve or _default_solver()
    specs = tuple(cases)
    # compile numba kernels outside the timings
    _solve(solve, case_from_spec(specs[0]), lub, levels[0] if levels else reference, level_effects, "warm-up",
           "warm-up", "warm-up")
    runs: list[CaseRun] = []
    for spec in specs:
        name, case = spec[0], case_from_spec(spec)
        ref = _solve(solve, case, lub, reference, reference_effects, name, reference, "reference")
        runs.append(ref)
        if progress:
            progress(f"{name}: reference mu={ref.mu:.4g} h_min={ref.h_min_m:.3g} m in {ref.wall_time_s:.2f} s")
        for level in levels:
            run = _solve(solve, case, lub, level, level_effects, name, level, level_effects)
            run.mu_error = relative_error(run.mu, ref.mu) if ref.converged else math.nan
            run.h_min_error = relative_error(run.h_min_m, ref.h_min_m) if ref.converged else math.nan
            runs.append(run)
            if progress:
                progress(f"{name}: {level} mu={run.mu:.4g} err={run.mu_error:.2%} in {run.wall_time_s:.2f} s")
        if checkpoint is not None:
            Path(checkpoint).write_text(json.dumps({"reference_level": reference, "levels": list(levels),
                                                    "provenance": {}, "runs": [dataclasses.asdict(r) for r in runs]},
                                                   default=float), encoding="utf-8")
    prov = provenance()
    prov.update(reference_effects=str(reference_effects), level_effects=str(level_effects))
    return AccuracyStudy(runs, reference, tuple(levels), specs, prov)


# ---------------------------------------------------------------------------------------------------------------
# Convergence under refinement
# ---------------------------------------------------------------------------------------------------------------
REFINEMENTS: dict[str, tuple[str, ...]] = {
    "grid": ("dx_fine", "dx_coarse", "inlet_resolution"),
}
"""Which :class:`~ehl_dataset.solvers.levels.AccuracyLevel` fields each refinement divides by the factor."""


def refined_level(base, kind: str, factor: float):
    """Copy of level ``base`` with the fields of refinement ``kind`` divided by ``factor``.

    Parameters
    ----------
    base : str or AccuracyLevel
        The level [-].
    kind : str
        The refinement, a key of :data:`REFINEMENTS` [-].
    factor : float
        Refinement factor (> 1 finer) [-].

    Returns
    -------
    AccuracyLevel
        The refined level.
    """
    from ehl_dataset.solvers.levels import get_level

    lvl = get_level(base)
    if kind not in REFINEMENTS:
        raise InputError("refinement", kind, f"one of {sorted(REFINEMENTS)}")
    changes = {name: getattr(lvl, name) / factor for name in REFINEMENTS[kind]}
    return dataclasses.replace(lvl, **changes)


def observed_order(values: Sequence[float], ratio: float = 2.0) -> float:
    """Observed order p = log(|f1 − f2|/|f2 − f3|)/log(ratio) from the last three values of a refinement sequence.

    Parameters
    ----------
    values : sequence of float
        Values at successive refinements with a constant ratio [-].
    ratio : float
        Refinement ratio [-].

    Returns
    -------
    float
        p, NaN if undefined [-].
    """
    if len(values) < 3:
        return math.nan
    f1, f2, f3 = values[-3:]
    d1, d2 = abs(f1 - f2), abs(f2 - f3)
    if not (d1 > 0 and d2 > 0 and math.isfinite(d1) and math.isfinite(d2)):
        return math.nan
    return math.log(d1 / d2) / math.log(ratio)


def convergence_study(spec: CaseSpec, kind: str = "grid", base_level: str = "standard", factors=(0.5, 1.0, 2.0, 4.0),
                      lubricant="atf", effects="auto", solve: Callable | None = None) -> dict[str, Any]:
    """μ and h_min of one case as one aspect of the level is refined by each factor (relative to ``base_level``).

    A plan with the transient rough solve (every effect on a rough case, or the reference level's rough model) is
    refused: the deterministic model's grid is its own rule, not the level's fields (its convergence:
    docs/validation/deterministic-reference.md).

    Parameters
    ----------
    spec : tuple
        The case, a row of :data:`ACCURACY_CASES` [-].
    kind : str
        The refinement, a key of :data:`REFINEMENTS` [-].
    base_level : str
        Level refined [-].
    factors : sequence of float
        Refinement factors (> 1 finer) [-].
    lubricant : str or Lubricant
        The lubricant [-].
    effects : str or Effects
        Effect plan [-].
    solve : callable, optional
        Solve function; None: :func:`ehl_dataset.solver.solve_contact` [-].

    Returns
    -------
    dict
        The table rows (factor, μ, its standard error, h_min [m], wall time [s]) and the observed orders of μ and
        h_min from the three finest runs.
    """
    from ehl_dataset.model.lubricant import Lubricant, load_lubricant
    from ehl_dataset.solvers.planner import resolve_effects

    lub = lubricant if isinstance(lubricant, Lubricant) else load_lubricant(lubricant)
    solve = solve or _default_solver()
    case = case_from_spec(spec)
    plan = resolve_effects(effects_argument(effects), case, lub, base_level)
    if plan.roughness and plan.transient and case.s_c > 0.0:
        raise InputError("effects", str(effects), f"a plan without the transient rough solve for {spec[0]} at "
                         f"{base_level} (the deterministic model's spacing is not the level's: its grid "
                         "convergence is validation/deterministic_validation.py)")
    rows = []
    for factor in factors:
        lvl = refined_level(base_level, kind, factor)
        run = _solve(solve, case, lub, lvl, effects, spec[0], f"{base_level}x{factor:g}", str(effects))
        rows.append({"factor": factor, "mu": run.mu, "mu_sem": run.mu_sem, "h_min_m": run.h_min_m,
                     "wall_time_s": run.wall_time_s,
                     "converged": run.converged, "roughness": run.roughness})
    ratios = [factors[i + 1] / factors[i] for i in range(len(factors) - 1)]
    ratio = ratios[-1] if ratios and np.allclose(ratios, ratios[-1]) else math.nan
    return {
        "case": spec[0], "kind": kind, "base_level": base_level, "effects": str(effects), "rows": rows,
        "order_mu": observed_order([r["mu"] for r in rows], ratio),
        "order_h_min": observed_order([r["h_min_m"] for r in rows], ratio),
    }


# ---------------------------------------------------------------------------------------------------------------
# Report
# ---------------------------------------------------------------------------------------------------------------
def _fmt_err(value: float) -> str:
    return "n/a" if not math.isfinite(value) else f"{100 * value:.2g} %"


def _fmt_mu(mu: float, sem: float | None, digits: int = 4) -> str:
    """μ, with "± standard error of its time average" where one was recorded and is not zero."""
    text = f"{mu:.{digits}g}"
    return text + (f" ± {sem:.2g}" if sem is not None and math.isfinite(sem) and sem > 0.0 else "")


def markdown_report(study: AccuracyStudy, convergence: Sequence[dict] = (), png_name: str = f"{DEFAULT_STEM}.png",
                    reference_effects: str = "full", level_effects: str = "auto") -> str:
    """The Markdown page: provenance, summary per level, per-case table, convergence tables."""
    prov = study.provenance
    title = "# EHL solver: accuracy versus time"
    if level_effects == "smooth":
        title += " (steady smooth physics for every case)"
    lines = [
        title,
        "",
        "Generated by `gearloss accuracy` (`workflows/accuracy.py`) from its fixed set of 16 points of the paper's"
        " factorial (`ACCURACY_CASES`) including its hardest corners; do not edit by hand. Regenerate with:",
        "",
        f"    {prov.get('command', 'gearloss accuracy')}",
        "",
        f"Reference: level `{study.reference_level}` with `effects={reference_effects}`; the levels run with"
        f" `effects={level_effects}`" + (" (the planner's savings are part of their error)" if level_effects == "auto"
                                        else "") + ". Errors are |x − x_ref|/x_ref; h_min errors are n/a where the"
        " reference film is zero (asperity contact). Wall time per case measured around `solve_contact` on one core.",
        "",
        f"Solver commit `{prov.get('git_commit')}`"
        + (" (with uncommitted solver changes)" if prov.get("solver_files_modified") else "")
        + f", gearloss {prov.get('gearloss')}, {prov.get('date_utc')}; machine: {prov.get('platform')},"
          f" {prov.get('cpu_count')} CPUs, Python {prov.get('python')}, NumPy {prov.get('numpy')}.",
        "",
        *[f"- {note}" for note in prov.get("notes", [])],
        *([""] if prov.get("notes") else []),
        "## Summary",
        "",
        "| level | cases | converged | median err μ | max err μ | median err h_min | max err h_min |"
        " mean time/case [s] | median time/case [s] |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for level, row in study.summary().items():
        is_ref = level.endswith("(reference)")
        lines.append(
            f"| {level} | {row['n_cases']} | {row['converged']} | "
            f"{'—' if is_ref else _fmt_err(row['mu_error_median'])} | {'—' if is_ref else _fmt_err(row['mu_error_max'])} | "
            f"{'—' if is_ref else _fmt_err(row['h_min_error_median'])} | "
            f"{'—' if is_ref else _fmt_err(row['h_min_error_max'])} | "
            f"{row['wall_time_mean_s']:.3g} | {row['wall_time_median_s']:.3g} |")
    lines += ["", f"![error versus time]({png_name})", "",
              f"*Made by `{prov.get('command', 'gearloss accuracy')}` (gearloss {prov.get('gearloss')}, EHL solver "
              f"{prov.get('solver_version', 'unknown')}).*", "", "## Per case", "",
              "| case | p_h [GPa] | r_eq [mm] | u_r [m/s] | SR | T [°C] | Rq1/Rq2 [µm] | λ̄ | level | plan | μ |"
              " h_min [nm] | err μ | err h_min | time [s] | converged |",
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for spec in study.cases:
        name = spec[0]
        for run in (r for r in study.runs if r.case == name):
            plan = "rough" if run.roughness else "smooth steady"
            lines.append(
                f"| {name} | {spec[1]:g} | {spec[2]:g} | {spec[3]:g} | {spec[4]:g} | {spec[5]:g} | "
                f"{spec[6]:g}/{spec[7]:g} | {run.lambda_bar:.3g} | {run.level}"
                f"{' (ref)' if run.effects_mode == 'reference' else ''} | {plan} | {_fmt_mu(run.mu, run.mu_sem)} | "
                f"{run.h_min_m * 1e9:.4g} | {_fmt_err(run.mu_error)} | {_fmt_err(run.h_min_error)} | "
                f"{run.wall_time_s:.3g} | {'yes' if run.converged else 'NO'} |")
    failures = [r for r in study.runs if not r.converged]
    if failures:
        lines += ["", "Not converged (listed in the table with their values; errors against a non-converged"
                      " reference are n/a):", ""]
        lines += [f"- {r.case} at {r.level}: {r.message or 'converged=False'}" for r in failures]
    if convergence:
        lines += ["", "## Convergence under refinement", "",
                  "Factor > 1 is finer (grid spacing and time step divided by it, averaging window multiplied)."
                  " Observed order p = log(|f1 − f2|/|f2 − f3|)/log 2 from the three finest runs. ± is the standard"
                  " error of a rough run's time-averaged μ (sampling, not discretisation): differences within about"
                  " two combined standard errors are not resolved.", ""]
        for study_c in convergence:
            lines += [f"### {study_c['case']}: {study_c['kind']} (base `{study_c['base_level']}`, effects"
                      f" `{study_c['effects']}`)", "",
                      "| factor | μ | h_min [nm] | time [s] | converged |", "|---|---|---|---|---|"]
            for row in study_c["rows"]:
                lines.append(f"| {row['factor']:g} | {_fmt_mu(row['mu'], row.get('mu_sem'), 6)} | {row['h_min_m'] * 1e9:.5g} | "
                             f"{row['wall_time_s']:.3g} | {'yes' if row['converged'] else 'NO'} |")
            lines += ["", f"Observed order: μ {study_c['order_mu']:.2f}, h_min {study_c['order_h_min']:.2f}.", ""]
    return "\n".join(lines) + "\n"


def plot_error_vs_time(study: AccuracyStudy, path: Path, floor: float = 1e-6) -> Path:
    """Scatter of relative error (μ and h_min) versus wall time per case, one colour per level, log axes.
    Errors below ``floor`` (e.g. exactly 0) are drawn at the floor."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), constrained_layout=True)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    ref_times = [r.wall_time_s for r in study.runs if r.effects_mode == "reference"]
    for ax, key, label in ((axes[0], "mu_error", "relative error of μ"),
                           (axes[1], "h_min_error", "relative error of h_min")):
        plotted = False
        for k, level in enumerate(study.levels):
            runs = [r for r in study.for_level(level) if r.effects_mode != "reference"]
            t = np.array([r.wall_time_s for r in runs])
            e = np.array([getattr(r, key) for r in runs], dtype=float)
            ok = np.isfinite(e)
            colour = colours[k % len(colours)]
            ax.scatter(t[ok], np.maximum(e[ok], floor), s=22, color=colour, alpha=0.75, label=f"{level} (cases)")
            plotted |= bool(ok.any())
            if ok.any():
                ax.scatter([np.median(t[ok])], [max(np.median(e[ok]), floor)], s=140, marker="*", color=colour,
                           edgecolor="black", zorder=5, label=f"{level} median")
        if ref_times:
            ax.axvline(float(np.median(ref_times)), color="grey", ls="--", lw=1,
                       label=f"{study.reference_level} median time")
        ax.set_xscale("log")
        if plotted:
            ax.set_yscale("log")
        else:  # e.g. every reference film is zero (asperity contact): no relative error is defined
            ax.text(0.5, 0.5, "no finite errors", transform=ax.transAxes, ha="center", va="center")
        ax.set_xlabel("wall time per case [s]")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    commit = study.provenance.get("git_commit", "?")
    fig.suptitle(f"EHL accuracy levels vs '{study.reference_level}' ({len(study.cases)} cases, solver {commit})",
                 fontsize=10)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def write_report(study: AccuracyStudy, out_dir: str | Path, convergence: Sequence[dict] = (),
                 stem: str = DEFAULT_STEM) -> dict[str, Path]:
    """Write ``<stem>.md``, ``<stem>.png`` and ``<stem>.json`` (raw runs) into ``out_dir``.

    Parameters
    ----------
    study : AccuracyStudy
        The study [-].
    out_dir : str or Path
        Output directory [-].
    convergence : sequence of dict
        Results of :func:`convergence_study` [-].
    stem : str
        File name stem [-].

    Returns
    -------
    dict of str to Path
        The files written, keyed ``markdown``, ``plot``, ``json``.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    png = plot_error_vs_time(study, out / f"{stem}.png")
    md = out / f"{stem}.md"
    md.write_text(markdown_report(study, convergence, png.name, study.provenance.get("reference_effects", "full"),
                                  study.provenance.get("level_effects", "auto")), encoding="utf-8")
    raw = out / f"{stem}.json"
    raw.write_text(json.dumps({"provenance": study.provenance, "reference_level": study.reference_level,
                               "levels": list(study.levels), "summary": study.summary(),
                               "runs": [dataclasses.asdict(r) for r in study.runs],
                               "convergence": list(convergence)}, indent=1, default=float), encoding="utf-8")
    return {"markdown": md, "plot": png, "json": raw}


def load_study(path: str | Path) -> tuple[AccuracyStudy, list[dict]]:
    """Read a study and its convergence records back from the ``<stem>.json`` written by :func:`write_report`.

    Re-renders the report without solving again.

    Parameters
    ----------
    path : str or Path
        The JSON file [-].

    Returns
    -------
    tuple
        (AccuracyStudy, list of convergence records).
    """
    data = json.loads(Path(path).read_text(encoding="utf-8"))
    runs = [CaseRun(**row) for row in data["runs"]]
    names = []
    for run in runs:
        if run.case not in names:
            names.append(run.case)
    by_name = {spec[0]: spec for spec in ACCURACY_CASES}
    cases = tuple(by_name[name] for name in names)
    study = AccuracyStudy(runs, data["reference_level"], tuple(data["levels"]), cases, data["provenance"])
    return study, list(data.get("convergence", []))


def merge_studies(studies: Sequence[AccuracyStudy], notes: Sequence[str] = ()) -> AccuracyStudy:
    """One study from several runs of the same levels and reference on disjoint case subsets (e.g. parallel processes).

    Cases in the order of :data:`ACCURACY_CASES`, provenance of the first plus ``notes``.

    Parameters
    ----------
    studies : sequence of AccuracyStudy
        The partial studies [-].
    notes : sequence of str
        Notes added to the provenance [-].

    Returns
    -------
    AccuracyStudy
        The merged study.
    """
    if not studies:
        raise InputError("studies", 0, "at least one study")
    first = studies[0]
    for other in studies[1:]:
        if other.levels != first.levels or other.reference_level != first.reference_level:
            raise InputError("studies", other.levels, f"the same levels {first.levels} and reference")
    order = {spec[0]: i for i, spec in enumerate(ACCURACY_CASES)}
    cases = sorted({spec for study in studies for spec in study.cases}, key=lambda spec: order.get(spec[0], 1e9))
    runs = sorted((run for study in studies for run in study.runs), key=lambda run: order.get(run.case, 1e9))
    prov = dict(first.provenance)
    prov["notes"] = list(prov.get("notes", [])) + list(notes)
    return AccuracyStudy(runs, first.reference_level, first.levels, tuple(cases), prov)
