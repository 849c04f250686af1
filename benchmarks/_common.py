"""Shared helpers of the benchmark scripts in this directory.

Every script: the machine description (:func:`machine_info`; a script adds its own extras such as load averages or
library versions), the median wall time of repeated calls (:func:`median_time`, :func:`repeat_times`) and printing /
writing its JSON (:func:`emit_json`). The mixed EHL benchmark (bench_ehl_mixed.py) also: per-case
result rows → timing summary, shard merging and writing the JSON report.
"""

from __future__ import annotations

import json
import os
import platform
import statistics
import sys
import time
from collections.abc import Callable, Iterable
from pathlib import Path

import numpy as np

RESULTS_DIR = Path(__file__).parent / "results"
"""Default directory of the benchmark JSON reports (benchmarks/results)."""

DATASET_POINTS = 42000
"""Number of operating points of the full data set, for the projected run time."""


def machine_info() -> dict:
    """The machine running this process (a new dict): platform string, processor name (``platform.processor()``, may
    be empty), logical CPU count, Python and NumPy versions."""
    return {"platform": platform.platform(), "processor": platform.processor(), "cpu_count": os.cpu_count(),
            "python": sys.version.split()[0], "numpy": np.__version__}


def repeat_times(fn: Callable[[], object], repeats: int) -> list[float]:
    """Wall times [s] (``time.perf_counter``) of ``repeats`` successive calls ``fn()``, in call order."""
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return times


def median_time(fn: Callable[[], object], repeats: int) -> float:
    """Median wall time [s] of ``repeats`` calls ``fn()`` (:func:`repeat_times`)."""
    return statistics.median(repeat_times(fn, repeats))


def emit_json(report: dict, out: str | Path | None, **dumps_kwargs) -> str:
    """Print ``report`` as JSON (``json.dumps(report, **dumps_kwargs)``) and, if ``out`` is given, also write that
    text plus a newline to ``out``, creating its directory; returns the text."""
    text = json.dumps(report, **dumps_kwargs)
    print(text)
    if out:
        Path(out).parent.mkdir(parents=True, exist_ok=True)
        Path(out).write_text(text + "\n")
    return text


def projected_hours(mean_time_s: float, n_points: int = DATASET_POINTS) -> float:
    """Wall time [h] to solve ``n_points`` points at ``mean_time_s`` [s] each, one process per core of this machine
    (``os.cpu_count()``, 1 if unknown)."""
    return n_points * mean_time_s / (os.cpu_count() or 1) / 3600.0


def _wall_time_s(row: dict) -> float:
    return row["wall_time_s"]


def _is_converged(row: dict) -> bool:
    return bool(row.get("converged"))


def summarize_rows(rows: list[dict], wall_time_s: Callable[[dict], float] = _wall_time_s,
                   converged: Callable[[dict], bool] = _is_converged) -> dict:
    """Timing summary of per-case rows, in this key order:

    ``n_cases``; ``converged`` (count); ``mean_time_s`` and ``median_time_s`` (wall time of all cases [s]);
    ``mean_cpu_time_s`` (CPU time [s], None unless every row has ``cpu_time_s``); ``mean_time_converged_s`` (wall
    time of the converged cases [s], None if none converged); ``projected_42000_points_h_on_cpu_count_cores``
    (:func:`projected_hours` of the mean wall time [h]).

    ``wall_time_s(row)`` and ``converged(row)`` read a row (default: its ``wall_time_s`` key, and the truth of its
    ``converged`` key, False if absent).
    """
    times = [wall_time_s(r) for r in rows]
    ok = [r for r in rows if converged(r)]
    return {"n_cases": len(rows), "converged": len(ok), "mean_time_s": statistics.fmean(times),
            "median_time_s": statistics.median(times),
            "mean_cpu_time_s": (statistics.fmean([r["cpu_time_s"] for r in rows])
                                if all("cpu_time_s" in r for r in rows) else None),
            "mean_time_converged_s": statistics.fmean([wall_time_s(r) for r in ok]) if ok else None,
            "projected_42000_points_h_on_cpu_count_cores": projected_hours(statistics.fmean(times))}


def merge_shards(paths: Iterable[str | Path]) -> list[dict]:
    """The ``rows`` of the shard reports at ``paths`` (JSON written by a ``--shard`` run), concatenated in the given
    order. Only the rows are kept: the summary and the machine are recomputed from them by the caller."""
    return [row for path in paths for row in json.loads(Path(path).read_text())["rows"]]


def write_report(path: str | Path, report: dict) -> Path:
    """Write ``report`` as indented JSON (NumPy scalars as floats) to ``path``, creating its directory; returns the
    path."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(report, indent=2, default=float))
    return path
