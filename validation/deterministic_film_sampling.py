"""How well does one averaging window of the deterministic validation runs know the central film?

The validation set (validation/deterministic_validation.py) averages each run over a window of 1.5 passes after the
start-up, long enough for μ (standard error ≤ 1.5 %) because the traction averages over the whole contact. The
central film h_c is the time mean of the film at one point, x = 0: the roughness that passes that point in 1.5
passes is a few dozen correlation lengths of each surface, and its long waves are only partly flattened, so the
film's window mean scatters from window to window. The three spacings of a case read the same roughness at the same
times (paired runs), so they agree with each other however large that scatter is: it does not show in the
reference.

This script measures it. For each validation case it runs the deterministic solver at the case's coarsest spacing
with the validation runs' roughness layout (the same surfaces, read for longer), records the film at x = 0 after
every step (``solve_deterministic(observer=...)``), and reports over the averaging window that follows the start-up:

- the long-run mean of the central film, with its autocorrelation-corrected standard error
  (ehl_dataset.solvers.time_average);
- the means of consecutive non-overlapping windows as long as the validation's window, and their standard deviation:
  the sampling uncertainty of the reference's stored h_c (``h_central_window_std_m``).

    python validation/deterministic_film_sampling.py [CASE ...] [--passes 9]

Results are cached per case in validation/results/deterministic_film_sampling/<case>.json and gathered in
validation/results/deterministic_film_sampling.json (read by ``python validation/deterministic_validation.py
--summarise``, which takes the reference's h_c from the longest window and its standard error from this spread).
"""

from __future__ import annotations

import argparse
import json
import platform
import time
from pathlib import Path

import numpy as np

from deterministic_validation import (CASES, LAYOUT_PASSES, RUNS, SHORT_AVERAGE_PASSES, averaging_passes, spacings,
                                      steps_per_pass)
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solvers.deterministic import MODEL_VERSION, DeterministicOptions, solve_deterministic
from ehl_dataset.solvers.time_average import time_mean

ROOT = Path(__file__).resolve().parents[1]
CACHE = ROOT / "validation" / "results" / "deterministic_film_sampling"
OUT = ROOT / "validation" / "results" / "deterministic_film_sampling.json"
REFERENCE = ROOT / "data" / "reference" / "deterministic_validation.json"


def validation_window_passes(name: str) -> float:
    """Length [passes] of the averaging window of the case's finest validation run (the stored h_c's)."""
    return averaging_passes(json.loads((RUNS / f"{name}_beta{max(spacings(name))}.json").read_text()))


def sample_case(name: str, passes: float) -> dict:
    """Long run of case ``name`` at its coarsest spacing; the film at x = 0 after every step (cached)."""
    path = CACHE / f"{name}.json"
    if path.exists():
        record = json.loads(path.read_text())
        if record["average_passes"] >= passes:
            return record
    n = min(spacings(name))
    case = ContactCase.from_engineering(*CASES[name])
    state = load_lubricant("atf").state(case.temperature)
    options = DeterministicOptions(dx_m=baseline_profile().correlation_length / n, mu_sem_target=1.0,
                                   min_average_passes=passes, max_passes=passes + 10.0, layout_passes=LAYOUT_PASSES)
    lo, hi = options.domain
    film_at_centre = []

    def observer(t_s, p_fluid_pa, film_m, fill):
        film_at_centre.append(float(np.interp(0.0, np.linspace(lo, hi, film_m.size), film_m)))

    start = time.perf_counter()
    # the validation runs' baseline profile, not the package's default
    result = solve_deterministic(case, state, Effects.full(), options, roughness=baseline_profile(),
                                 observer=observer)
    extra = result.extra
    per_pass = steps_per_pass(CASES[name], extra)
    series = np.asarray(film_at_centre[extra["average_from_step"]:])
    record = {"case": name, "inputs": list(CASES[name]), "points_per_beta": n, "model_version": MODEL_VERSION,
              "layout_passes": LAYOUT_PASSES, "converged": bool(result.converged), "mu": result.mu,
              "h_central_m": result.h_central, "average_passes": len(series) / per_pass,
              "steps_per_pass": per_pass, "wall_time_s": time.perf_counter() - start,
              "film_at_centre_m": series.tolist()}
    CACHE.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(record))
    return record


def analyse(record: dict, reference: dict) -> dict:
    """Long mean, its standard error, and the spread of window means as long as the validation's window."""
    series = np.asarray(record["film_at_centre_m"])
    window = validation_window_passes(record["case"])
    length = int(round(window * record["steps_per_pass"]))
    count = series.size // length
    means = [float(np.mean(series[i * length:(i + 1) * length])) for i in range(count)]
    long = time_mean(series)
    spread = float(np.std(means, ddof=1)) if count >= 2 else float("nan")
    stored = reference.get("h_central_m_fine", reference["h_central_m"])  # the 1.5-pass window's value
    return {"case": record["case"], "points_per_beta": record["points_per_beta"], "mu": record["mu"],
            "average_passes": record["average_passes"], "validation_window_passes": window,
            "h_central_long_m": long.mean, "h_central_long_sem_m": long.standard_error,
            "h_central_long_reliable": long.reliable, "window_means_m": means,
            "h_central_window_std_m": spread, "h_central_window_std_relative": spread / long.mean,
            "reference_h_central_m": stored, "reference_minus_long_in_window_std": (stored - long.mean) / spread,
            "model_version": record["model_version"], "wall_time_s": record["wall_time_s"]}


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("cases", nargs="*", help="validation cases (default: every case in the reference)")
    parser.add_argument("--passes", type=float, default=6.0 * SHORT_AVERAGE_PASSES,
                        help="averaging passes of the long run (default: six validation windows)")
    args = parser.parse_args(argv)
    reference = {c["case"]: c for c in json.loads(REFERENCE.read_text())["cases"]}
    names = args.cases or sorted(reference)
    for name in names:
        if name not in reference:
            parser.error(f"case {name!r} is not in {REFERENCE.name} (cases: {', '.join(sorted(reference))})")
    for name in names:
        row = analyse(sample_case(name, args.passes), reference[name])
        write_row(row)
        print(f"{name}: h_c long {row['h_central_long_m'] * 1e9:.0f} ± {row['h_central_long_sem_m'] * 1e9:.0f} nm, "
              f"window std {row['h_central_window_std_m'] * 1e9:.0f} nm "
              f"({100 * row['h_central_window_std_relative']:.0f} %), reference {row['reference_h_central_m'] * 1e9:.0f} "
              f"nm, {row['wall_time_s']:.0f} s", flush=True)
    return 0


def write_row(row: dict) -> None:
    """Add (or replace) one case's row in the gathered results file."""
    previous = {r["case"]: r for r in json.loads(OUT.read_text())["rows"]} if OUT.exists() else {}
    previous[row["case"]] = row
    OUT.write_text(json.dumps({"command": "python validation/deterministic_film_sampling.py [CASE ...]",
                               "machine": platform.platform(),
                               "rows": [previous[k] for k in sorted(previous)]}, indent=1) + "\n")


if __name__ == "__main__":
    raise SystemExit(main())
