"""The validation set of the deterministic mixed-EHL solver: rough cases across the paper's factorial, each
solved at three grid spacings (β/8, β/16, β/32; β/16, β/32, β/64 where asperities carry a large share of the load,
see ``SPACINGS``), the grid-converged μ and asperity share with their uncertainty.

Estimator (multilevel, Giles, Oper. Res. 56 (2008) 607): the three runs of a case read the same roughness at the same
times, so their differences are paired and vary little. The β/16 run carries the long averaging window (standard
error of μ ≤ 1.5 %); the β/8 and β/32 runs last only the start-up and a short window, and enter through their mean
difference to β/16 over that window (written for β/8, β/16, β/32; the same with the case's own spacings):

    μ̂_16 = ⟨μ_16⟩_long,   μ̂_32 = μ̂_16 + ⟨μ_32 − μ_16⟩_short,   μ̂_8 = μ̂_16 + ⟨μ_8 − μ_16⟩_short,

each mean with its autocorrelation-corrected standard error (ehl_dataset.solvers.time_average). Richardson
extrapolation (spacing ratio 2) gives the observed order p = log2((μ̂_8 − μ̂_16)/(μ̂_16 − μ̂_32)) and
μ_∞ = μ̂_32 + (μ̂_32 − μ̂_16)/(2^p − 1); its uncertainty combines the standard error and Roache's grid convergence
index with safety factor 1.25 (or |μ̂_32 − μ̂_16| when no order can be observed).

    python validation/deterministic_validation.py --case A          # run (resumable) one case, all spacings
    python validation/deterministic_validation.py --all             # all cases, cheapest first
    python validation/deterministic_validation.py --summarise       # data/reference + docs table from the runs
    python validation/deterministic_validation.py --case G --spacing 32 [--max-passes 12]
                                                     # one spacing only (spacings can run in parallel processes)

Runs are cached as validation/results/deterministic/<case>_beta<n>.json (the series and the run's record). A run
saves its state every 10 min under validation/results/deterministic/checkpoints/ (git-ignored): started again after
a stop (restart, end of a session), the same command continues it where it was saved, to the same result.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from ehl_dataset.dataset.checkpoint import FileCheckpoint
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import BASELINE_POINTS, baseline_profile, long_baseline_profile
from ehl_dataset.solvers.deterministic import (MODEL_VERSION, STRICT_ROUND_OFF_SINCE, DeterministicOptions,
                                               model_version_key, solve_deterministic)
from ehl_dataset.solvers.time_average import RELIABLE_LENGTH, time_mean

ROOT = Path(__file__).resolve().parents[1]
RUNS = ROOT / "validation" / "results" / "deterministic"
CHECKPOINTS = RUNS / "checkpoints"
REFERENCE = ROOT / "data" / "reference" / "deterministic_validation.json"
REPORT = ROOT / "docs" / "validation" / "deterministic_validation.md"
FILM_SAMPLING = ROOT / "validation" / "results" / "deterministic_film_sampling.json"

CASES = {
    # name: (p_h GPa, r_eq mm, u_r m/s, SR, T °C, Rq1 µm, Rq2 µm)
    "A": (0.5, 5, 5, 0.3, 90, 0.3, 0.3),
    "B": (0.5, 5, 1, 0.05, 100, 0.5, 0.5),
    "C": (0.5, 5, 2, 0.7, 25, 1.0, 1.0),
    "D": (1.0, 5, 2, 0.5, 100, 0.5, 0.5),
    "E": (1.0, 5, 10, 0.1, 25, 0.3, 0.3),
    "F": (1.0, 5, 20, 0.7, 100, 0.05, 0.05),
    "G": (0.5, 10, 10, 0.2, 100, 0.4, 0.4),
    "H": (1.5, 5, 1, 1.0, 100, 0.4, 0.4),
    "I": (1.5, 5, 5, 0.2, 75, 0.2, 0.5),
    "J": (1.0, 10, 2, 0.4, 50, 0.3, 0.3),
    "K": (2.0, 5, 15, 0.05, 25, 0.7, 0.7),
    "L": (2.5, 5, 5, 0.1, 100, 0.4, 0.4),
}
POINTS_PER_BETA = (8, 16, 32)
CONTACT_SPACINGS = (16, 32, 64)
SPACINGS = {"A": CONTACT_SPACINGS, "B": CONTACT_SPACINGS, "C": CONTACT_SPACINGS}
"""Points per correlation length of each case (default POINTS_PER_BETA; the middle one carries the long run).
A, B and C: μ moves by 7–14 % between β/16 and β/32 under det-2026.11-6 (benchmarks/results/
deterministic_convergence_<case>.json), so their finest pair has to be β/32–β/64. D (λ̄ 0.07) was given the contact
spacings too, expected to be contact-dominated like B; under det-2026.11-11 its asperity share is 0.0013 at β/16 and
0.0063 at β/32 (short runs; B: 0.13 at β/32, 0.53 at β/64), a film-dominated case like H (λ̄ 0.05, share 0.007, fine
step +1.0 % at β/8/16/32), so it takes the default spacings."""
EXTRA_SPACINGS = {"B": (128, 256), "C": (128,)}
"""Finer short runs beyond a case's three spacings (``python validation/deterministic_extra_spacing.py CASE N``),
chained onto them by paired differences: the extrapolation then takes the three finest spacings. B and C were not
grid-converged at β/64 (docs/explanation/mixed-regime.md)."""
MAX_PASSES = 40.0
LAYOUT_PASSES = 100.0
"""Run length [passes] every run's roughness is laid out for, whatever its own cap: the paired differences need
the same roughness at the same times at every spacing (DeterministicOptions.layout_passes). Case G's short runs
were once laid out for their default cap of 40 passes against 100 for the long run, and their paired differences
were −17 %/−18 % where a shared layout gives +0.1 % (docs/explanation/mixed-regime.md)."""
LONG_RUNS = {"A": 200.0, "C": 120.0, "D": 100.0, "G": 300.0}
"""Cases whose long run needs more than :data:`MAX_PASSES` passes for the standard-error target: the cap of the
long run [passes] and the layout of all their runs (a layout of at least the cap, so that no surface reads its own
roughness twice; checked by ``SurfacePair.independent``; G's 300 passes take 81 % of its long profile,
:data:`PROFILE_POINTS`). Narrow
contacts (a/β 2.9–5.9) hold few asperities at a time and their μ fluctuates slowly: at the default caps A reached
3.1 % after 38.5 averaging passes, C 2.4 % after 38.5, G 1.9 % after 98.5 (det-2026.11-10 to -13), so the target
of 1.5 % takes about (sem/1.5 %)² times as long. B (9.5 % after 38.5 passes) would need about 1,500 passes, four
times what the profile holds, and is left at the default. D's entry only raises its cap to its layout's
100 passes for the window of :data:`WINDOWS`: its roughness is laid out as before."""
PROFILE_POINTS = {"G": 2**18}
"""Cases whose runs read a longer realisation of the baseline's random process (``long_baseline_profile``: same
generator, seed, β and Rq, 2^18 samples = 262 mm) instead of the shipped 131 mm baseline. G's long run reached 1.7 %
at the cap of a 175-pass layout, which took 95 % of the baseline: the target needs about 215–270 passes
(1.9 % after 98.5 passes, 1.7 % after 175). The baseline is itself synthetic, so a longer realisation of the same
process is the same roughness statistically; the case's reference changes by its sampling error."""
WINDOWS = {"A": {16: 5.0, 64: 20.0},
           "C": {16: 2.5, 32: 103.0, 64: 10.5, 128: 2.5},
           "D": {8: 2.5, 16: 40.0, 32: 3.2},
           "F": {8: 2.0, 16: 2.0, 32: 2.0},
           "G": {8: 5.5, 16: 290.0, 32: 5.5},
           "H": {16: 4.6},
           "J": {8: 3.5, 16: 3.5, 32: 3.5},
           "K": {8: 3.0, 16: 3.0, 32: 3.0},
           "L": {8: 5.5, 16: 5.5, 32: 5.5}}
"""Averaging windows [passes] longer than the default (the long run until its own standard error is ≤ 1.5 %, a short
run :data:`SHORT_AVERAGE_PASSES`), per case and spacing, for two reasons:

- reliability: every window at least 20 correlation times of μ measured on the case's long run
  (:func:`long_run_correlation_passes`; the reliability test of ehl_dataset.solvers.time_average), rounded up to
  0.5 pass (the summary also takes the measured difference's correlation time where longer: B's, 0.84 passes).
  Necessary, not sufficient: A's contact episodes are rarer than one per 5 passes, and its 5-pass windows still
  report standard errors ≈ 5× too small (:func:`short_window_factor`). A's fine step (β/32 → β/64) over 5 passes
  is +3.3 %, all of it from contact episodes in 3 of its 9 half-pass windows, so its β/64 window is 20 passes. A 1.5-pass paired difference cannot see correlations on that scale, and its standard error is then
  too small: measured by ``python validation/deterministic_short_windows.py`` (B: 11×; G: 1.6×). A long run shorter
  than its short runs' window is extended with them (F, J, K, L), since a paired difference needs it.
- the standard error of μ at the finest spacing: where the default left it above 1.5 % (C 2.1 %, D 1.9 %, G 1.51 %,
  H 1.53 %), the multilevel allocation of ``python validation/deterministic_sampling_plan.py`` for 1.35 % (a
  margin for variances measured on short windows; its results file has the inputs).

A's long run would need ≈ 346 passes for the second reason, more than its 200-pass layout, so all its runs would
have to be redone (≈ 2.4 h); B needs a longer profile and ≈ 12 passes at every spacing up to β/256 for the first
(≈ 15 h, docs/explanation/mixed-regime.md "Open"). Both are left at their windows."""
SHORT_AVERAGE_PASSES = 1.5
LONG_TARGET = 0.015
SAFETY = 1.25
LUBRICANT = "atf"


SAME_NUMERICS = {"det-2026.11-9": "det-2026.11-10", "det-2026.11-11": "det-2026.11-10",
                 "det-2026.11-12": "det-2026.11-10", "det-2026.11-13": "det-2026.11-10",
                 "det-2026.11-14": "det-2026.11-10", "det-2026.11-15": "det-2026.11-10",
                 "det-2026.11-16": "det-2026.11-10", "det-2026.11-17": "det-2026.11-10",
                 "det-2026.11-18": "det-2026.11-10", "det-2026.11-19": "det-2026.11-10",
                 "det-2026.11-20": "det-2026.11-10", "det-2026.11-21": "det-2026.11-10"}
"""Model versions whose runs may be paired with runs of the version they map to. det-2026.11-10 changed only the
Newton stop at the round-off floor (a step that stalls there is accepted instead of split); rerun under it, the short
runs A β/16, B β/16, G β/8 and I β/8 reproduce det-2026.11-9's μ within 1e-12 (relative) and C β/16 within 8e-5
(`python validation/deterministic_rerun_check.py A:16 B:16 C:16 G:8 I:8`,
validation/results/deterministic_rerun_check_det-2026.11-10.json). det-2026.11-11 evaluates the logarithmic face mean
without cancellation; rerun under it, the same runs reproduce the recorded μ within 3e-8 (C β/16 within 8.7e-5, as
under det-10) while B β/16's round-off stops fall from 1,037 to 54 and its largest mass-balance error from 3.2e-10 to
1.0e-10 (validation/results/deterministic_rerun_check_det-2026.11-11.json). det-2026.11-12 changed only the grid
rule of runs without ``dx_m`` (every validation run gives it). det-2026.11-13 changed the logarithmic face mean only
where neighbouring fluid factors differ by more than 1e16, where det-11 and -12 returned NaN partials: a state with
such a face fails every Newton solve that starts from it, so a run under det-11/-12 that converged never accepted
one, and its steps solve det-13's equations too. det-2026.11-14 changed only when the preconditioner is refactored
(before a solve that follows one of ``REFACTOR_ITERATIONS`` GMRES iterations, instead of repeating that solve): rerun
under it, A β/16, B β/16, I β/8 and L β/8 reproduce their recorded μ within 4e-13 (relative), D β/8 within 1.3e-6 and
H β/8 within 6.9e-6 (`python validation/deterministic_rerun_check.py A:16 B:16 I:8 D:8 H:8 L:8`,
validation/results/deterministic_rerun_check_det-2026.11-14.json). det-2026.11-15 changed only the round-off stop
on a small correction (below 1e-15 p_h instead of 1e-12: a step iterates on until its global balance meets the
tolerance); rerun under it with ``--replace`` (the reruns are the records now), the runs listed in
validation/results/deterministic_rerun_check_det-2026.11-15.json reproduce their recorded μ within the figures given
there and in docs/explanation/mixed-regime.md, "Mass balance". det-2026.11-16 computes the deflection of grids of at most
320 nodes by a dense product instead of the FFT pair (the same operator) and the periodic preconditioner's
convolution by ``np.convolve``: rerun under it, B β/16, E β/8, G β/8 and I β/8 reproduce their recorded μ within
7e-13 (relative) and D β/8 within 1.1e-6, every step balanced to 1e-10 (`python
validation/deterministic_rerun_check.py B:16 D:8 E:8 G:8 I:8`,
validation/results/deterministic_rerun_check_det-2026.11-16.json). det-2026.11-17 also stops a Newton solve stalled above 10× the
tolerance where its norm is within the round-off floor it measures: rerun under it, B β/16, D β/8, H β/8 and L β/8
reproduce their recorded μ within 5.8e-6 (relative; the same sub-step counts), every step balanced to 1e-10 (`python
validation/deterministic_rerun_check.py B:16 D:8 H:8 L:8`,
validation/results/deterministic_rerun_check_det-2026.11-17.json); det-17 continues det-16's saved states
(``CONTINUES``, recorded in a run's ``continued_from``). det-2026.11-18 adds a last attempt (watchdog steps) only at a
step that fails at every split, so a run det-17 completes is step for step the same. det-2026.11-19 changed only the
global balance of periodic windows (which the validation runs do not use): its whole-contact runs are det-18's.
det-2026.11-20 carries the film offset relative to the steady start's and lets the line search measure the global
balance where only it misses the tolerance: rerun under it, B β/16, D β/8, H β/8 and L β/8 reproduce their recorded μ
within 2.2e-6 (relative), every step balanced to 1e-10 (`python validation/deterministic_rerun_check.py B:16 D:8 H:8
L:8`, validation/results/deterministic_rerun_check_det-2026.11-20.json). det-2026.11-21 lets a solve that stalls with only
the global balance above the tolerance go on for up to three iterations: the same four runs give det-20's μ (same file
name with det-2026.11-21)."""


def numerics(version: str) -> str:
    """The model version whose numerics a run of ``version`` shares (:data:`SAME_NUMERICS`)."""
    return SAME_NUMERICS.get(version, version)


def run_case_specs(script: str, specs: list[str], analyse, out: Path, flags: str = "") -> int:
    """Run ``analyse(name, points_per_beta)`` for every ``CASE:N`` of ``specs``; print each row as JSON and write
    it at once, with its command (``python validation/<script> [flags] <spec>``) and the machine, to ``out``, whose
    rows of other runs are kept (a row of the same run is replaced): a run that stops keeps the finished rows."""
    import platform
    for spec in specs:
        name, n = spec.split(":")
        row = analyse(name, int(n))
        print(json.dumps(row), flush=True)
        command = " ".join(part for part in (f"python validation/{script}", flags, spec) if part)
        kept = json.loads(out.read_text()) if out.exists() else {}
        rows = [r for r in kept.get("rows", []) if r.get("run") != row.get("run")]
        out.write_text(json.dumps({"machine": platform.platform(), "rows": rows + [{"command": command, **row}]},
                                  indent=1) + "\n")
    return 0


def spacings(name: str) -> tuple[int, int, int]:
    return SPACINGS.get(name, POINTS_PER_BETA)


def layout_passes(name: str) -> float:
    """Run length [passes] case ``name``'s roughness is laid out for (:data:`LAYOUT_PASSES`, :data:`LONG_RUNS`)."""
    return LONG_RUNS.get(name, LAYOUT_PASSES)


def profile_points(name: str) -> int:
    """Samples of the roughness profile case ``name``'s runs read (:data:`PROFILE_POINTS`, else the baseline's)."""
    return PROFILE_POINTS.get(name, BASELINE_POINTS)


def profile_for(name: str):
    """The roughness profile case ``name``'s runs read: the shipped baseline, or its process over
    :func:`profile_points` samples."""
    n = profile_points(name)
    return baseline_profile() if n == BASELINE_POINTS else long_baseline_profile(n)


def long_max_passes(name: str) -> float:
    """Cap [passes] of case ``name``'s long run (:data:`MAX_PASSES`, :data:`LONG_RUNS`)."""
    return LONG_RUNS.get(name, MAX_PASSES)


def window_passes(name: str, n: int) -> float | None:
    """The averaging window [passes] case ``name``'s run at β/``n`` must reach (:data:`WINDOWS`), None for the
    default."""
    return WINDOWS.get(name, {}).get(n)


def options_for(n: int, long: bool, max_passes: float = MAX_PASSES,
                layout: float = LAYOUT_PASSES, window: float | None = None) -> DeterministicOptions:
    """The run's options at β/``n``: the long run averages until its standard error is ≤ 1.5 % (and for at least
    ``window`` passes), a short run for ``window`` passes (default :data:`SHORT_AVERAGE_PASSES`)."""
    beta = baseline_profile().correlation_length
    if long:
        return DeterministicOptions(dx_m=beta / n, max_passes=max_passes, mu_sem_target=LONG_TARGET,
                                    layout_passes=layout,
                                    **({} if window is None else {"min_average_passes": window}))
    # short runs: stop at the minimum window (a target of 100 % is met at once)
    return DeterministicOptions(dx_m=beta / n, max_passes=min(max_passes, layout), mu_sem_target=1.0,
                                min_average_passes=SHORT_AVERAGE_PASSES if window is None else window,
                                layout_passes=layout)


def run_path(name: str, n: int) -> Path:
    return RUNS / f"{name}_beta{n}.json"


def checkpoint_path(name: str, n: int, long: bool) -> Path:
    """Where a run of case ``name`` at β/``n`` keeps its state while it runs (git-ignored; removed once the run's
    record is written): a run stopped by a restart or a session's end continues from it when started again."""
    return CHECKPOINTS / f"{name}_beta{n}_{'long' if long else 'short'}.pickle"


def solve_and_record(name: str, n: int, long: bool, max_passes: float | None = None,
                     out: Path | None = None) -> dict:
    """Solve case ``name`` at β/``n`` (the long run's options if ``long``, else the short run's) and return the run's
    record as the validation set stores it (inputs, version, μ and its standard error, share, films, series). The
    run saves its state every 10 min (:func:`checkpoint_path`) and continues from a saved state; with ``out`` the
    record is written there and the saved state removed (a Newton failure's state stays in ``<checkpoint>.failed``
    for replay: ``FileCheckpoint.save_failure``). ``max_passes`` None: the case's cap
    (:func:`long_max_passes`)."""
    case = ContactCase.from_engineering(*CASES[name])
    state = load_lubricant(LUBRICANT).state(case.temperature)
    checkpoint = FileCheckpoint(checkpoint_path(name, n, long))
    cap = long_max_passes(name) if max_passes is None else max_passes
    options = options_for(n, long, cap, layout_passes(name), window_passes(name, n))
    result = solve_deterministic(case, state, Effects.full(), options,
                                 roughness=profile_for(name), checkpoint=checkpoint)
    extra = {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in result.extra.items()}
    record = {"case": name, "inputs": CASES[name], "points_per_beta": n, "solver_version": MODEL_VERSION,
              "layout_passes": layout_passes(name), "profile_points": profile_points(name),
              "window_passes": options.min_average_passes,
              "mu": result.mu, "mu_sem": result.mu_sem, "asperity_load_share": result.asperity_load_share,
              "h_min_m": result.h_min, "h_central_m": result.h_central, "converged": result.converged,
              "message": result.message, "wall_time_s": result.wall_time, "lambda_bar": result.lambda_bar,
              "residuals": result.residuals, "extra": extra}
    if out is not None:
        out.write_text(json.dumps(record))
        checkpoint.remove()
    return record


def run_case(name: str, only: int | None = None, max_passes: float | None = None) -> None:
    """Run the case's spacings not yet on record under this model version (``only``: that spacing alone); the
    long run stops at ``max_passes`` passes if its standard-error target is not met by then (recorded in its
    message)."""
    RUNS.mkdir(parents=True, exist_ok=True)
    coarse, middle, fine = spacings(name)
    for n in (middle, coarse, fine):
        if only is not None and n != only:
            continue
        path = run_path(name, n)
        if path.exists():
            done = json.loads(path.read_text())
            same_layout = (done.get("layout_passes", LAYOUT_PASSES) == layout_passes(name)  # before the key: 100
                           and done.get("profile_points", BASELINE_POINTS) == profile_points(name))
            long_enough = averaging_passes(done) >= (window_passes(name, n) or 0.0) - 1e-9
            if numerics(done.get("solver_version", "")) == numerics(MODEL_VERSION) and same_layout and long_enough:
                continue
        start = time.time()
        record = solve_and_record(name, n, n == middle, max_passes, out=path)
        print(f"{name} beta/{n}: mu {record['mu']:.5f} +- {record['mu_sem']:.5f} share "
              f"{record['asperity_load_share']:.4f} {record['message']} {time.time() - start:.0f} s", flush=True)


def _on_grid(t_fine, y_fine, t_grid):
    """Mean of a finer (or equal) series over each interval (t_grid[k-1], t_grid[k]]."""
    edges = np.concatenate([[t_grid[0] - (t_grid[1] - t_grid[0])], t_grid])
    index = np.searchsorted(edges, t_fine, side="left") - 1
    out = np.full(t_grid.size, np.nan)
    for k in range(t_grid.size):
        sel = index == k
        if sel.any():
            out[k] = float(np.mean(y_fine[sel]))
    return out


def paired_difference(run: dict, base: dict, key: str) -> tuple[float, float]:
    """Mean and standard error of (run − base) of series ``key`` over the run's averaging window, both series on
    the coarser of the two time grids."""
    t_r, y_r = np.asarray(run["extra"]["t_series_s"]), np.asarray(run["extra"][key])
    t_b, y_b = np.asarray(base["extra"]["t_series_s"]), np.asarray(base["extra"][key])
    t_start = t_r[run["extra"]["average_from_step"]]
    t_end = t_r[-1]
    coarse_r = (t_r[1] - t_r[0]) >= (t_b[1] - t_b[0])
    if coarse_r:
        grid = t_r[(t_r > t_start) & (t_r <= t_end)]
        a, b = y_r[(t_r > t_start) & (t_r <= t_end)], _on_grid(t_b, y_b, grid)
    else:
        grid = t_b[(t_b > t_start) & (t_b <= t_end)]
        a, b = _on_grid(t_r, y_r, grid), y_b[(t_b > t_start) & (t_b <= t_end)]
    keep = np.isfinite(a) & np.isfinite(b)
    diff = time_mean(a[keep] - b[keep])
    return diff.mean, diff.standard_error


def steps_per_pass(inputs, extra: dict) -> float:
    """Time steps per pass (the domain length at u_r) of a run of the case ``inputs`` with the recorded ``extra``
    (its Courant number and spacing)."""
    domain = DeterministicOptions().domain
    return (domain[1] - domain[0]) * ContactCase.from_engineering(*inputs).half_width / (extra["courant"]
                                                                                           * extra["dx_m"])


def averaging_passes(run: dict) -> float:
    """Length [passes] of a run's averaging window."""
    extra = run["extra"]
    return (extra["n_steps"] - extra["average_from_step"]) / steps_per_pass(run["inputs"], extra)


def central_film(name: str, fine: dict, middle: dict) -> dict:
    """The reference's central film h_c: the time mean of the film at x = 0 over the longest averaging window
    available, the validation's long (middle-spacing) run or the long run of validation/deterministic_film_sampling.py,
    with its standard error σ_W·√(W/P) (σ_W the measured spread of the means of windows W = 1.5 passes long, P the
    chosen run's window). The grid moves h_c by ≤ 1.2 % between the spacings at a common window; the window length
    moves it by up to 30 % (A, B, C: the 1.5-pass fine runs against the 40-pass middle runs), so the window decides.
    Without a sampling run: the longer of the fine and middle runs, no standard error."""
    out = {"h_central_m_fine": fine["h_central_m"], "h_central_m_middle": middle["h_central_m"]}
    sampling = {r["case"]: r for r in json.loads(FILM_SAMPLING.read_text())["rows"]} if FILM_SAMPLING.exists() else {}
    row = sampling.get(name)
    candidates = [(averaging_passes(run), run["h_central_m"], f"beta/{run['points_per_beta']} run")
                  for run in (fine, middle)]
    if row is not None:
        candidates.append((row["average_passes"], row["h_central_long_m"],
                           f"film-sampling run at beta/{row['points_per_beta']}"))
    passes, value, source = max(candidates, key=lambda c: c[0])
    chosen = {"h_central_m": value, "h_central_passes": passes, "h_central_source": f"{source} ({passes:.1f} passes)",
              **out}
    if row is None:
        return {**chosen, "h_central_sem_m": math.nan}
    return {**chosen, "h_central_sem_m": row["h_central_window_std_m"] * math.sqrt(row["validation_window_passes"]
                                                                                    / passes),
            "h_central_window_std_m": row["h_central_window_std_m"]}


BALANCE_TARGET = 1e-10
"""The conservation target: lubricant mass and load balanced to ≤ 1e-10 (relative) at every step."""


def balance_record(runs: dict[int, dict], chain: tuple[int, ...]) -> dict:
    """Per spacing of ``chain``: the largest per-step global mass-balance error (relative to the central film's
    flux, ``extra["mass_error_series"]``), the number of steps above :data:`BALANCE_TARGET` and of all steps, and the
    largest load-balance error (``residuals["max_load_error"]``)."""
    out = {"mass_error_max": {}, "mass_error_steps_over_target": {}, "steps": {}, "load_error_max": {}}
    for n in chain:
        errors = np.abs(np.asarray(runs[n]["extra"]["mass_error_series"], dtype=float))
        key = f"beta/{n}"
        out["mass_error_max"][key] = float(errors.max())
        out["mass_error_steps_over_target"][key] = int(np.count_nonzero(errors > BALANCE_TARGET))
        out["steps"][key] = int(errors.size)
        out["load_error_max"][key] = float(runs[n]["residuals"]["max_load_error"])
    return out


def summarise_case(name: str) -> dict | None:
    """The reference entry of case ``name``: μ and the asperity share at each spacing (the long run's time mean at
    the middle spacing, the other spacings by paired differences, :data:`EXTRA_SPACINGS` chained onto the finest),
    Richardson-extrapolated from the three finest; None until every run is on record and converged."""
    coarse, middle, fine = spacings(name)
    chain = (coarse, middle, fine) + EXTRA_SPACINGS.get(name, ())
    runs = {n: json.loads(run_path(name, n).read_text()) for n in chain if run_path(name, n).exists()}
    if set(runs) != set(chain) or not all(r["converged"] for r in runs.values()):
        return None
    if len({numerics(r["solver_version"]) for r in runs.values()}) != 1:
        return None  # the three spacings must share one model version (a rerun in progress mixes them)
    layouts = {(r.get("layout_passes", LAYOUT_PASSES), r.get("profile_points", BASELINE_POINTS))
               for r in runs.values()}
    if len(layouts) > 1:
        print(f"{name}: runs laid out differently {sorted(layouts)} (passes, profile samples) are not paired; rerun "
              f"the short runs", file=sys.stderr)
        return None
    base = runs[middle]
    levels = chain[-3:]  # the spacings of the extrapolation
    out = {"case": name, "inputs": dict(zip(("p_h_gpa", "r_eq_mm", "u_r_m_s", "sr", "temp_c", "rq1_um", "rq2_um"),
                                            CASES[name])),
           "lambda_bar": base["lambda_bar"],
           "solver_version": max((r["solver_version"] for r in runs.values()), key=version_key),
           "run_versions": {f"beta/{n}": runs[n]["solver_version"] for n in chain},
           "half_width_m": ContactCase.from_engineering(*CASES[name]).half_width,
           "points_per_beta": list(levels),
           "long_run_points_per_beta": middle,
           "wall_time_s": {f"beta/{n}": runs[n]["wall_time_s"] for n in chain},
           "n_nodes": {f"beta/{n}": runs[n]["extra"]["n_nodes"] for n in chain},
           "smooth_mu": base["extra"]["smooth_mu"],
           **balance_record(runs, chain),
           **central_film(name, runs[fine], base)}
    low, mid, high = levels
    factor, correlation_d, measured_passes = short_window_factor(name)
    mu_factor = long_run_factor(name)
    correlation = max(long_run_correlation_passes(base), correlation_d or 0.0)

    def scaled(se: float, n: int) -> float:
        short = averaging_passes(runs[n]) < (measured_passes or 0.0)
        return se * (factor if factor is not None and short else 1.0)

    for key, series in (("mu", "mu_series"), ("asperity_load_share", "share_series")):
        long_mean = time_mean(np.asarray(base["extra"][series])[base["extra"]["average_from_step"]:])
        values, errors = {middle: long_mean.mean}, {middle: long_mean.standard_error}
        errors_scaled = dict(errors)
        if mu_factor is not None and averaging_passes(base) < (measured_passes or 0.0):
            errors_scaled[middle] = long_mean.standard_error * mu_factor
        for n in (coarse, fine):
            d, se = paired_difference(runs[n], base, series)
            values[n] = long_mean.mean + d
            errors[n] = math.hypot(long_mean.standard_error, se)
            errors_scaled[n] = math.hypot(errors_scaled[middle], scaled(se, n))
        for previous, n in zip(chain[2:], chain[3:]):
            d, se = paired_difference(runs[n], runs[previous], series)
            values[n] = values[previous] + d
            errors[n] = math.hypot(errors[previous], se)
            errors_scaled[n] = math.hypot(errors_scaled[previous], scaled(se, n))
        if key == "mu":
            out["mu_sem_scaled"] = {f"beta/{n}": errors_scaled[n] for n in chain}
        e_coarse = values[low] - values[mid]
        e_fine = values[mid] - values[high]
        order = math.nan
        if e_coarse * e_fine > 0 and abs(e_coarse) > abs(e_fine):
            order = math.log2(e_coarse / e_fine)
        if math.isfinite(order) and order > 0.5:
            correction = (values[high] - values[mid]) / (2.0**order - 1.0)
            extrapolated = values[high] + correction
            grid_uncertainty = SAFETY * abs(correction)
        else:
            extrapolated = values[high]
            grid_uncertainty = abs(values[high] - values[mid])
        out[key] = {f"beta/{n}": values[n] for n in chain}
        out[key + "_sem"] = {f"beta/{n}": errors[n] for n in chain}
        out[key + "_observed_order"] = order
        out[key + "_extrapolated"] = extrapolated
        # μ's uncertainty takes the short windows' standard errors scaled by the measured factor (short_window_factor)
        out[key + "_uncertainty"] = math.hypot(grid_uncertainty, (errors_scaled if key == "mu" else errors)[high])
        if key == "mu":
            out["mu_uncertainty_unscaled"] = math.hypot(grid_uncertainty, errors[high])
        out[key + "_fine_step"] = values[high] - values[mid]
        out[key + "_fine_step_sem"] = paired_difference(runs[high], runs[mid], series)[1]
        if key == "mu":
            out["mu_fine_step_sem_scaled"] = scaled(out["mu_fine_step_sem"], high)
    out["mu_fine_step_relative"] = out["mu_fine_step"] / out["mu"][f"beta/{high}"]
    out["mu_relative_sem_finest"] = {f"beta/{n}": out["mu_sem"][f"beta/{n}"] / out["mu"][f"beta/{n}"]
                                     for n in (mid, high)}
    out["window_passes"] = {f"beta/{n}": averaging_passes(runs[n]) for n in chain}
    out["long_run_correlation_passes"] = long_run_correlation_passes(base)
    out["difference_correlation_passes"] = correlation_d
    out["short_window_se_factor"] = factor
    out["long_run_se_factor"] = mu_factor
    out["mu_relative_sem_finest_scaled"] = {f"beta/{n}": out["mu_sem_scaled"][f"beta/{n}"] / out["mu"][f"beta/{n}"]
                                            for n in (mid, high)}
    out["reliable_window_passes"] = RELIABLE_LENGTH * correlation
    out["window_reliable"] = {k: bool(w >= RELIABLE_LENGTH * correlation) for k, w in out["window_passes"].items()}
    return out


SHORT_WINDOWS = ROOT / "validation" / "results" / "deterministic_short_windows.json"


def _short_window_row(name: str) -> dict | None:
    """Case ``name``'s row of :data:`SHORT_WINDOWS` (validation/deterministic_short_windows.py): of the finest pair
    measured (the one nearest the fine steps), newest model version; None where not measured."""
    if not SHORT_WINDOWS.exists():
        return None
    rows = [r for r in json.loads(SHORT_WINDOWS.read_text())["rows"] if r["case"] == name]
    if not rows:
        return None
    finest = max(int(r["coarse"].split("/")[1]) for r in rows)
    rows = [r for r in rows if int(r["coarse"].split("/")[1]) == finest]
    return max(rows, key=lambda r: version_key(r["model_version"]))


def short_window_factor(name: str) -> tuple[float | None, float | None, float | None]:
    """(factor, correlation time [passes], length [passes]) of case ``name``'s paired differences, measured by
    ``python validation/deterministic_short_windows.py`` on a long run of its coarse spacing (or a finer one, preferred
    where measured) paired with the middle one: how many times the spread of 1.5-pass window means exceeds the
    standard error such a window reports (the median over the windows; never below 1), the correlation time of the
    whole difference series, and its length (over which its Sokal standard error agrees with batch means).
    (None, None, None) where not measured.

    The validation multiplies the standard error of every paired window shorter than that length by the factor, on
    the assumption that the case's finer differences fluctuate alike (on G the fine pair's factor is 1.62 against
    1.56 at the coarse one). For longer windows the factor measured at 1.5 passes is conservative on B, C, D and G (it
    falls to 0.6–2.3 at 2.5–5 passes) and about right on A (4–6 from 1 to 5 passes: its contact episodes are rarer
    than one per window, so windows of 20 correlation times are not enough there)."""
    row = _short_window_row(name)
    if row is None:
        return None, None, None
    diff = row["paired_difference"]
    return (max(1.0, 1.0 / diff["ratio_reported_to_spread"]), diff.get("whole_correlation_passes"),
            diff["whole_passes"])


def long_run_factor(name: str) -> float | None:
    """How many times the spread of 1.5-pass window means of μ exceeds the standard error such a window reports,
    measured on case ``name``'s middle spacing over ≥ 20 passes (``long_run_mu`` of
    validation/deterministic_short_windows.py; never below 1), None where not measured. Applied to a long run that
    is itself shorter than that measurement (E, I: 1.5 passes)."""
    row = _short_window_row(name)
    return None if row is None else max(1.0, 1.0 / row["long_run_mu"]["ratio_reported_to_spread"])


def long_run_correlation_passes(run: dict) -> float:
    """The correlation time [passes] of μ measured on a long run (its statistical inefficiency g over the averaging
    window, in passes). A paired difference's own window underestimates it: the difference is driven by the same
    asperity passages, and a window of a few correlation times cannot see them (benchmarks/
    deterministic_short_windows.py: on case B the 1.5-pass windows report standard errors 11× smaller than the spread
    of their means). A window counts as reliable when it is at least RELIABLE_LENGTH (20) of these long."""
    series = np.asarray(run["extra"]["mu_series"])[run["extra"]["average_from_step"]:]
    return time_mean(series).inefficiency * averaging_passes(run) / series.size


OLDEST_ACCEPTED = "det-2026.11-7"
"""Runs made under older deterministic numerics (before the limited Couette flux and the round-off stop) do not enter
the reference set."""


version_key = model_version_key


def _order_text(order: float) -> str:
    """The observed order, or "n/o" where none is observable (steps that do not shrink or change sign: the
    extrapolated μ is then the finest one, with the fine step as its grid uncertainty)."""
    return f"{order:.1f}" if math.isfinite(order) else "n/o"


GRID_TARGET, SHARE_TARGET, SEM_TARGET = 0.05, 0.03, LONG_TARGET
"""The grid targets: μ at the two finest spacings within 5 % and the asperity share within 0.03, with the
standard error of μ ≤ 1.5 %."""


def acceptance_lines(rows: list[dict]) -> list[str]:
    """One line per grid target: how many cases meet it and which do not (the standard error rounded to
    0.1 % as in the table)."""
    def sem(r):
        long_n = r.get("long_run_points_per_beta", r["points_per_beta"][1])
        return round(100 * r["mu_sem"][f"beta/{long_n}"] / r["mu"][f"beta/{long_n}"], 1) / 100

    def sem_finest(r):
        return round(100 * max(r["mu_relative_sem_finest"].values()), 1) / 100

    checks = (("μ fine step ≤ 5 %", lambda r: abs(r["mu_fine_step_relative"]) <= GRID_TARGET,
               lambda r: f"{100 * r['mu_fine_step_relative']:+.1f} %"),
              ("asperity share fine step ≤ 0.03", lambda r: abs(r["asperity_load_share_fine_step"]) <= SHARE_TARGET,
               lambda r: f"{r['asperity_load_share_fine_step']:+.3f}"),
              ("standard error of μ (long run) ≤ 1.5 %", lambda r: sem(r) <= SEM_TARGET,
               lambda r: f"{100 * sem(r):.1f} %"),
              ("standard error of μ at the two finest spacings (long run and paired differences combined) ≤ 1.5 %",
               lambda r: "mu_relative_sem_finest" in r and sem_finest(r) <= SEM_TARGET,
               lambda r: f"{100 * sem_finest(r):.1f} %" if "mu_relative_sem_finest" in r else "not recorded"))
    def sem_scaled(r):
        return round(100 * max(r["mu_relative_sem_finest_scaled"].values()), 1) / 100

    def step_bound(r):
        return (abs(r["mu_fine_step"]) + 2 * r["mu_fine_step_sem_scaled"]) / abs(r["mu"][f"beta/{r['points_per_beta'][2]}"])

    measured = [r for r in rows if r.get("short_window_se_factor") is not None]
    checks += (("the same with the short windows' standard errors scaled by the factor measured on the case (cases "
                "measured: " + (", ".join(f"{r['case']} ×{r['short_window_se_factor']:.1f}" for r in measured) or "none")
                + "; a long run shorter than the measurement, E's and I's, scaled by μ's factor; the others "
                  "unscaled)",
                lambda r: "mu_relative_sem_finest_scaled" in r and sem_scaled(r) <= SEM_TARGET,
                lambda r: f"{100 * sem_scaled(r):.1f} %" if "mu_relative_sem_finest_scaled" in r else "not recorded"),
               ("μ fine step ≤ 5 % at two standard errors (|step| + 2 × its scaled standard error)",
                lambda r: "mu_fine_step_sem_scaled" in r and step_bound(r) <= GRID_TARGET,
                lambda r: f"{100 * step_bound(r):.1f} %" if "mu_fine_step_sem_scaled" in r else "not recorded"))
    lines = ["Grid targets on this set:", ""]
    short = [r for r in rows if "window_reliable" in r and not all(r["window_reliable"].values())]
    for text, met, value in checks:
        failing = [r for r in rows if not met(r)]
        lines.append(f"- {text}: met on {len(rows) - len(failing)} of {len(rows)} cases"
                     + ("" if not failing else "; not on " + ", ".join(f"{r['case']} ({value(r)})"
                                                                    for r in failing)))
    lines.append(f"- windows of at least 20 correlation times (of μ on the long run, or of the measured paired "
                 f"difference where that is longer; the standard error's reliability test, "
                 f"ehl_dataset.solvers.time_average): every run on {len(rows) - len(short)} of {len(rows)} cases"
                 + ("" if not short else "; not on " + ", ".join(
                     f"{r['case']} ({', '.join(k for k, ok in r['window_reliable'].items() if not ok)}: "
                     f"{r['reliable_window_passes']:.1f} passes needed)" for r in short))
                 + ". A short window's own standard error is too small where it cannot see the difference's "
                   "correlations (docs/validation/deterministic-reference.md, \"Standard errors of short windows\")")
    return lines + balance_lines(rows)


def balance_lines(rows: list[dict]) -> list[str]:
    """The conservation target over every step of every run of the set (cases whose entry predates the balance
    record are counted as not recorded)."""
    recorded = [r for r in rows if "mass_error_max" in r]

    def where(r, key):
        steps = (f", {sum(r['mass_error_steps_over_target'].values()):,} of {sum(r['steps'].values()):,} steps"
                 if key == "mass_error_max" else "")
        return f"{r['case']} ({max(r[key].values()):.1e}{steps})"

    lines = []
    for text, key in (("load", "load_error_max"), ("lubricant mass", "mass_error_max")):
        failing = [r for r in recorded if max(r[key].values()) > BALANCE_TARGET]
        worst = max((max(r[key].values()) for r in recorded), default=math.nan)
        line = (f"- {text} balance ≤ 1e-10 (relative) at every step of every run: met on "
                f"{len(recorded) - len(failing)} of {len(recorded)} cases (largest {worst:.1e})")
        if failing:
            line += "; not on " + ", ".join(where(r, key) for r in failing)
        if len(recorded) < len(rows):
            line += f"; {len(rows) - len(recorded)} cases not recorded"
        lines.append(line)
    lines.append(stop_rule_line(recorded))
    return lines


STOP_RULE_VERSION = STRICT_ROUND_OFF_SINCE
"""The first model version whose Newton solve takes a round-off stop on a small correction only below 1e-15 p_h
(``ROUND_OFF_STEP``; 1e-12 before, which accepted steps a further iteration would have balanced)."""


def stop_rule_line(recorded: list[dict]) -> str:
    """The mass balance over the runs made under :data:`STOP_RULE_VERSION` or later, apart from the older runs."""
    new, old = [], []
    for r in recorded:
        for spacing, version in r["run_versions"].items():
            item = (r["case"], spacing, r["mass_error_steps_over_target"][spacing], r["steps"][spacing],
                    r["mass_error_max"][spacing])
            (new if version_key(version) >= version_key(STOP_RULE_VERSION) else old).append(item)
    over = [i for i in new if i[2]]
    line = (f"- the runs made under {STOP_RULE_VERSION} or later (its strict round-off stop, "
            f"docs/explanation/mixed-regime.md): {len(new)} of {len(new) + len(old)} runs, {sum(i[2] for i in new):,} of "
            f"{sum(i[3] for i in new):,} steps above 1e-10")
    if over:
        line += " (" + ", ".join(f"{c} {s}: {k:,}, largest {e:.1e}" for c, s, k, _, e in over) + ")"
    return line + (f"; the other {sum(i[2] for i in old):,} steps above it are in the {len(old)} older runs"
                   if old else "")


def summarise() -> None:
    """Write the reference data and the docs table. Each case enters with its three runs if they share one model
    version (not older than OLDEST_ACCEPTED), else keeps its entry of the existing reference file; the newer of the
    two wins, so that a version bump never empties the reference set that ``gearloss accuracy --mixed`` reads. The
    table and the data name each case's version."""
    previous = {}
    if REFERENCE.exists():
        previous = {r["case"]: r for r in json.loads(REFERENCE.read_text()).get("cases", [])}
    rows = []
    for name in CASES:
        row = summarise_case(name)
        if row is not None and version_key(row["solver_version"]) < version_key(OLDEST_ACCEPTED):
            row = None
        kept = previous.get(name)
        if row is None or (kept is not None and version_key(kept["solver_version"]) > version_key(
                row["solver_version"])):
            row = kept
        if row is not None:
            rows.append(row)
    REFERENCE.parent.mkdir(parents=True, exist_ok=True)
    REFERENCE.write_text(json.dumps({"description": "Grid-converged mu of the deterministic mixed-EHL solver "
                                                    "(validation/deterministic_validation.py)",
                                     "lubricant": LUBRICANT, "cases": rows}, indent=1, default=float) + "\n")
    lines = ["# Validation set of the deterministic solver", "",
             f"Made by `python validation/deterministic_validation.py --summarise` (deterministic model versions: "
             f"{', '.join(sorted({r['solver_version'] for r in rows})) or '-'}, per case in the data); the data: "
             f"`data/reference/deterministic_validation.json`.",
             "", "| case | p_h GPa | r_eq mm | u_r m/s | SR | T °C | Rq µm | λ̄ | a/β | spacings β/n | μ coarse | "
             "μ middle | μ fine | fine step | ± (paired) | order | μ extrapolated | ± | sem of μ (long run) | "
             "sem of μ fine | share fine | share fine step | smooth μ | averaging passes per spacing | "
             "time per spacing, coarsest first [s] |",
             "|---|" + "---|" * 24]
    beta = baseline_profile().correlation_length
    for r in rows:
        i = r["inputs"]
        coarse, middle, fine = r["points_per_beta"]
        long_n = r.get("long_run_points_per_beta", middle)
        chain = sorted(int(k.split("/")[1]) for k in r["wall_time_s"])
        times = " / ".join(f"{r['wall_time_s'][f'beta/{n}']:.0f}" for n in chain)
        windows = (" / ".join(f"{r['window_passes'][f'beta/{n}']:.1f}"
                              + ("" if r.get("window_reliable", {}).get(f"beta/{n}", True) else "*") for n in chain)
                   if "window_passes" in r else "-")
        spacing_text = f"{coarse}/{middle}/{fine}" + (f" (long run {long_n})" if long_n != middle else "")
        lines.append(
            f"| {r['case']} | {i['p_h_gpa']} | {i['r_eq_mm']} | {i['u_r_m_s']} | {i['sr']} | {i['temp_c']} | "
            f"{i['rq1_um']}/{i['rq2_um']} | {r['lambda_bar']:.3f} | {r['half_width_m'] / beta:.1f} | "
            f"{spacing_text} | {r['mu'][f'beta/{coarse}']:.4f} | {r['mu'][f'beta/{middle}']:.4f} | "
            f"{r['mu'][f'beta/{fine}']:.4f} | {100 * r['mu_fine_step_relative']:+.1f} % | "
            f"{100 * r['mu_fine_step_sem'] / r['mu'][f'beta/{fine}']:.1f} % | "
            f"{_order_text(r['mu_observed_order'])} | {r['mu_extrapolated']:.4f} | {r['mu_uncertainty']:.4f} | "
            f"{100 * r['mu_sem'][f'beta/{long_n}'] / r['mu'][f'beta/{long_n}']:.1f} % | "
            f"{100 * r['mu_sem'][f'beta/{fine}'] / r['mu'][f'beta/{fine}']:.1f} % | "
            f"{r['asperity_load_share'][f'beta/{fine}']:.3f} | "
            f"{r['asperity_load_share_fine_step']:+.3f} | {r['smooth_mu']:.4f} | {windows} | {times} |")
    lines += ["", "μ coarse / middle / fine: the three finest spacings (paired with the long run at the middle one, or at "
              "the one named); fine step: (μ fine − μ middle)/μ fine (target ≤ 5 %), ± its standard error from the two runs' "
              "paired difference over their common window (relative to μ fine); order: the observed order of "
              "convergence p = log2(Δ_coarse/Δ_fine), n/o where none is observable (the steps do not shrink or change "
              "sign); with n/o or p ≤ 0.5 μ extrapolated is μ fine and ± the fine step combined with the standard error, else "
              "Richardson's value with Roache's GCI (safety 1.25) combined with it; sem of μ: "
              "the long run's standard error (target ≤ 1.5 %); sem of μ fine: the standard error of μ at the finest "
              "spacing, the long run's and the paired differences' combined (target ≤ 1.5 %; the windows that reach it: "
              "`python validation/deterministic_sampling_plan.py`); averaging passes: each run's window, coarsest "
              "first, * where shorter than 20 correlation times of the long run (its standard error is then not "
              "reliable); share fine step: the asperity load share's change "
              "between the two finest spacings (target ≤ 0.03)."]
    lines += ["", *acceptance_lines(rows)]
    REPORT.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", action="append", default=[], help="case name (repeatable)")
    parser.add_argument("--all", action="store_true", help="every case, cheapest first")
    parser.add_argument("--summarise", action="store_true", help="write the reference data and the docs table")
    parser.add_argument("--spacing", type=int, default=None, help="run only this spacing (points per beta)")
    parser.add_argument("--max-passes", type=float, default=None,
                        help="cap of the long run's passes (default: the case's, see LONG_RUNS)")
    args = parser.parse_args(argv)
    names = list(CASES) if args.all else args.case
    if args.all:
        names.sort(key=lambda k: CASES[k][0] * CASES[k][1])
    for name in names:
        run_case(name, args.spacing, args.max_passes)
    if args.summarise:
        summarise()
    return 0


if __name__ == "__main__":
    sys.exit(main())
