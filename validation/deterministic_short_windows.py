"""Does the standard error of a 1.5-pass paired difference tell the truth? (docs/explanation/mixed-regime.md, "Standard
error of the short runs").

The validation estimator (validation/deterministic_validation.py) takes each spacing other than the long run's from a
short run: its mean difference to the neighbouring spacing over 1.5 passes, with the autocorrelation-corrected
standard error of that difference (ehl_dataset.solvers.time_average: Sokal's window, which needs a series ≫ its
correlation time). Here the case's coarse spacing is run for ``--passes`` passes on the same roughness layout as
the long run (and the middle spacing too where the long run is shorter than that), so the paired difference
μ_coarse − μ_middle is known over many 1.5-pass windows. Two figures result:

- the within-window estimate: the median over the 1.5-pass windows of the standard error each window reports;
- the truth it estimates: the spread (standard deviation) of the windows' means, and the standard error of the
  whole difference (Sokal and batch means over the full run, which agree when the run is long enough).

Their ratio says by how much the short windows' standard errors are too small (or large). The same is done for μ of
the long run itself (1.5-pass windows against its full record).

    python validation/deterministic_short_windows.py B --passes 20
    python validation/deterministic_short_windows.py A --passes 20

Rows go to validation/results/deterministic_short_windows.json (one per case and model version); the coarse run's
series to validation/results/deterministic_short_windows/<case>_beta<n>.json, reused when present.
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import deterministic_validation as validation  # noqa: E402
from ehl_dataset.model.contact import ContactCase  # noqa: E402
from ehl_dataset.model.effects import Effects  # noqa: E402
from ehl_dataset.model.lubricant import load_lubricant  # noqa: E402
from ehl_dataset.solvers.deterministic import MODEL_VERSION, solve_deterministic  # noqa: E402
from ehl_dataset.solvers.time_average import time_mean  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"
OUT = RESULTS / "deterministic_short_windows.json"
SERIES = RESULTS / "deterministic_short_windows"
WINDOW = validation.SHORT_AVERAGE_PASSES


def paired_run(name: str, n: int, passes: float) -> dict:
    """Case ``name`` at β/``n`` averaged over ``passes`` passes on the validation layout (a short run's options
    otherwise); cached in :data:`SERIES`."""
    path = SERIES / f"{name}_beta{n}.json"
    if path.exists():
        done = json.loads(path.read_text())
        if done["window_passes"] >= passes and done["solver_version"] == MODEL_VERSION:
            return done
    case = ContactCase.from_engineering(*validation.CASES[name])
    state = load_lubricant(validation.LUBRICANT).state(case.temperature)
    layout = validation.layout_passes(name)
    options = validation.options_for(n, False, layout, layout, passes)
    start = time.perf_counter()
    result = solve_deterministic(case, state, Effects.full(), options, roughness=validation.profile_for(name))
    record = {"case": name, "points_per_beta": n, "inputs": validation.CASES[name], "solver_version": MODEL_VERSION,
              "window_passes": passes, "converged": result.converged, "mu": result.mu,
              "wall_time_s": time.perf_counter() - start,
              "extra": {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in result.extra.items()
                        if k in ("t_series_s", "mu_series", "average_from_step", "n_steps", "courant", "dx_m")}}
    SERIES.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(record))
    return record


def window_statistics(t: np.ndarray, y: np.ndarray, pass_time: float) -> dict:
    """The 1.5-pass windows of series ``y`` (times ``t`` [s], one pass ``pass_time`` [s]): the median standard
    error they report, the spread of their means, and the whole series' Sokal and batch-means standard errors."""
    edges = np.arange(t[0], t[-1] + 1e-12 * pass_time, WINDOW * pass_time)
    reported, means = [], []
    for lo, hi in zip(edges[:-1], edges[1:]):
        sel = (t > lo) & (t <= hi)
        if np.count_nonzero(sel) > 2:
            window = time_mean(y[sel])
            reported.append(window.standard_error)
            means.append(window.mean)
    whole = time_mean(y)
    batches = 10
    k = y.size // batches
    batch_means = y[:k * batches].reshape(batches, k).mean(axis=1)
    return {"windows": len(means), "window_se_reported_median": float(np.median(reported)),
            "window_mean_spread": float(np.std(means, ddof=1)),
            "ratio_reported_to_spread": float(np.median(reported) / np.std(means, ddof=1)),
            "whole_mean": whole.mean, "whole_se_sokal": whole.standard_error, "whole_reliable": whole.reliable,
            "whole_se_batch_means": float(batch_means.std(ddof=1) / math.sqrt(batches)),
            "whole_passes": float((t[-1] - t[0]) / pass_time),
            "whole_correlation_passes": float(whole.inefficiency * (t[-1] - t[0]) / pass_time / y.size),
            "window_se_implied_by_whole": whole.standard_error * math.sqrt((t[-1] - t[0]) / (WINDOW * pass_time))}


def pass_time_s(name: str) -> float:
    """One pass [s] of case ``name``: the domain length at u_r."""
    case = ContactCase.from_engineering(*validation.CASES[name])
    domain = validation.DeterministicOptions().domain
    return (domain[1] - domain[0]) * case.half_width / case.u_r


def paired_series(run: dict, long_run: dict) -> tuple[np.ndarray, np.ndarray]:
    """(times [s], μ_run − μ_long) over ``run``'s averaging window on the long run's time grid (finite values only)."""
    extra = run["extra"]
    t_r, y_r = np.asarray(extra["t_series_s"]), np.asarray(extra["mu_series"])
    t_b, y_b = np.asarray(long_run["extra"]["t_series_s"]), np.asarray(long_run["extra"]["mu_series"])
    start, end = t_r[extra["average_from_step"]], min(t_r[-1], t_b[-1])
    inside = (t_b > start) & (t_b <= end)
    difference = validation._on_grid(t_r, y_r, t_b[inside]) - y_b[inside]
    keep = np.isfinite(difference)
    return t_b[inside][keep], difference[keep]


def analyse(name: str, passes: float, spacing: int | None = None) -> dict:
    """The row of case ``name``: its run at β/``spacing`` (default: the coarse spacing) over ``passes`` passes paired
    with the middle spacing's long run."""
    coarse, middle, _ = validation.spacings(name)
    coarse = coarse if spacing is None else spacing
    long_run = json.loads(validation.run_path(name, middle).read_text())
    if validation.averaging_passes(long_run) < passes:  # a long run met its target sooner: run the middle too
        long_run = paired_run(name, middle, passes)
    run = paired_run(name, coarse, passes)
    grid, difference = paired_series(run, long_run)
    start = long_run["extra"]["average_from_step"]
    long_t = np.asarray(long_run["extra"]["t_series_s"])[start:]
    long_mu = np.asarray(long_run["extra"]["mu_series"])[start:]
    return {"case": name, "coarse": f"beta/{coarse}", "paired_spacing": coarse, "long": f"beta/{middle}",
            "model_version": MODEL_VERSION,
            "long_run_version": long_run["solver_version"], "coarse_wall_time_s": run["wall_time_s"],
            "middle_passes": float(validation.averaging_passes(long_run)),
            "window_passes": WINDOW,
            "paired_difference": window_statistics(grid, difference, pass_time_s(name)),
            "long_run_mu": window_statistics(long_t, long_mu, pass_time_s(name))}


def difference_series(name: str, spacing: int | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray, str]:
    """(time [passes], μ_n − μ_middle, μ_middle − its mean, label) of case ``name``'s cached paired runs (n: the
    coarse spacing, or ``spacing``)."""
    coarse, middle, _ = validation.spacings(name)
    coarse = coarse if spacing is None else spacing
    long_run = json.loads(validation.run_path(name, middle).read_text())
    cached_middle = SERIES / f"{name}_beta{middle}.json"
    if cached_middle.exists():
        long_run = json.loads(cached_middle.read_text())
    run = json.loads((SERIES / f"{name}_beta{coarse}.json").read_text())
    grid, difference = paired_series(run, long_run)
    t_b, y_b = np.asarray(long_run["extra"]["t_series_s"]), np.asarray(long_run["extra"]["mu_series"])
    middle_mu = y_b[np.isin(t_b, grid)]
    return ((grid - grid[0]) / pass_time_s(name), difference, middle_mu - middle_mu.mean(),
            f"{name}: μ(β/{coarse}) − μ(β/{middle})")


def plot(names: list[str], path: Path) -> None:
    """The paired differences of ``names`` against time, with the middle spacing's μ about its mean."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(len(names), 1, figsize=(10, 1.9 * len(names)), sharex=True, squeeze=False)
    for ax, name in zip(axes[:, 0], names):
        t, d, mu, label = difference_series(name)
        ax.plot(t, mu, lw=0.5, color="tab:orange", alpha=0.6, label="μ middle − its mean")
        ax.plot(t, d, lw=0.6, color="tab:blue", label=label)
        for k in np.arange(WINDOW, t[-1], WINDOW):
            ax.axvline(k, color="0.85", lw=0.5, zorder=0)
        ax.legend(loc="upper right", fontsize=7, frameon=False)
        ax.set_ylabel("Δμ")
    axes[-1, 0].set_xlabel("time [passes] (grey: the 1.5-pass windows)")
    fig.suptitle(f"Paired differences between spacings: `python validation/deterministic_short_windows.py "
                 f"{' '.join(names)} --figure`, {MODEL_VERSION}", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


FIGURE = Path(__file__).resolve().parents[1] / "docs" / "figures" / "deterministic_short_windows.png"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("cases", nargs="+")
    parser.add_argument("--passes", type=float, default=20.0, help="averaging passes of the paired run")
    parser.add_argument("--spacing", type=int, default=None,
                        help="points per β of the run paired with the long run (default: the case's coarse spacing; "
                             "its fine one checks whether the factor holds at the finer pair)")
    parser.add_argument("--figure", action="store_true",
                        help=f"only plot the cached runs of the cases to {FIGURE.relative_to(FIGURE.parents[2])}")
    args = parser.parse_args(argv)
    if args.figure:
        plot(args.cases, FIGURE)
        return 0
    for name in args.cases:
        flags = f" --spacing {args.spacing}" if args.spacing else ""
        row = {"command": f"python validation/deterministic_short_windows.py {name} --passes {args.passes:g}{flags}",
               **analyse(name, args.passes, args.spacing)}
        print(json.dumps(row), flush=True)
        kept = json.loads(OUT.read_text())["rows"] if OUT.exists() else []
        key = (name, MODEL_VERSION, row["coarse"])
        kept = [r for r in kept if (r["case"], r["model_version"], r["coarse"]) != key]
        OUT.write_text(json.dumps({"machine": platform.platform(), "rows": kept + [row]}, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
