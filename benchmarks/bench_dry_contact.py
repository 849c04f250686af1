"""Cost and accuracy of the dry-contact tables of the homogenised mixed-EHL model (ehl_dataset/model/dry_contact.py).

Writes one JSON object (stdout, and ``--out FILE``) with the machine noted:
- ``tables``: wall time, rows, p_a range of the tables of the given Rq pairs (default settings, shipped baseline);
- ``resolution``: p_a, contact fraction, ⟨g⟩ and ⟨max(g, h_b)^-3⟩ (h_b = 1 nm) at fixed d/σ for β/Δ = 16, 32, 64
  on the same windows, the differences between successive levels and the observed order
  log2(|e16−32| / |e32−64|);
- ``window``: the same quantities for windows of 128, 256, 512, 1024 β at one total length (16, 8, 4, 2
  windows), i.e. the periodic-window (truncation) effect at a constant sample size, with the batch-means
  standard error of p_a;
- ``evaluation``: µs per point of the vectorised interpolation (p_a + dp_a/dd + one moment, 1000 points).

Run: ``python benchmarks/bench_dry_contact.py [--pairs 0.05,0.05 0.4,0.4 1.0,1.0] [--quick]
[--out benchmarks/results/dry_contact.json]``
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import emit_json, machine_info  # noqa: E402

D_OVER_SIGMA = (2.0, 1.0, 0.5, 0.2)
H_B = 1e-9


def point_statistics(profile, rq1, rq2, settings, d_over_sigma=D_OVER_SIGMA):
    """p_a, contact fraction, ⟨g⟩, ⟨max(g, 1 nm)^-3⟩ and the p_a standard error at the given d/σ (warm-started
    from the largest d)."""
    from ehl_dataset.model import dry_contact as dc
    z, spacing = dc.composite_windows(profile, rq1, rq2, settings)
    sigma = math.hypot(rq1, rq2)
    out = []
    p = None
    for ds in d_over_sigma:
        sol = dc.solve_contact(z, spacing, dc.STEEL_E_REDUCED_PA, ds * sigma, hardness=dc.DEFAULT_HARDNESS_PA,
                               p0=p)
        p = sol.pressure
        batch = p.reshape(p.shape[0], 8, -1).mean(axis=2).ravel()
        gap = sol.gap
        out.append({"d_over_sigma": ds, "p_a_pa": float(p.mean()),
                    "p_a_se_pa": float(batch.std(ddof=1) / math.sqrt(batch.size)),
                    "contact_fraction": float((p > 0).mean()), "mean_gap_over_sigma": float(gap.mean() / sigma),
                    "moment_m3_floor_1nm": float(np.mean(np.maximum(gap, H_B) ** -3.0)),
                    "iterations": sol.iterations})
    return out


def observed_order(values):
    """log2(|v1 − v2| / |v2 − v3|) for three successive refinements (None if undefined)."""
    e1, e2 = abs(values[0] - values[1]), abs(values[1] - values[2])
    if e1 == 0 or e2 == 0:
        return None
    return math.log2(e1 / e2)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--pairs", nargs="*", default=["0.05,0.05", "0.4,0.4", "1.0,1.0"],
                        help="Rq1,Rq2 pairs in µm for the table timings and the convergence studies")
    parser.add_argument("--quick", action="store_true", help="timings only (no convergence studies)")
    parser.add_argument("--out", help="also write the JSON here")
    args = parser.parse_args(argv)

    from ehl_dataset.model import dry_contact as dc
    from ehl_dataset.model.roughness import baseline_profile

    profile = baseline_profile()
    pairs = [tuple(float(v) * 1e-6 for v in text.split(",")) for text in args.pairs]
    report = {"machine": machine_info(), "settings": dc.asdict(dc.DryContactSettings()), "tables": []}
    tables = {}
    for rq1, rq2 in pairs:
        start = time.perf_counter()
        table = dc.compute_dry_contact_table(profile, rq1, rq2)
        seconds = time.perf_counter() - start
        tables[(rq1, rq2)] = table
        row = table.summary()
        row["wall_s"] = seconds
        row["max_relative_pressure_se"] = float(np.max(table.tab_pressure_se / table.tab_pressure))
        row["relative_pressure_se_at_p_above_10MPa"] = float(np.max(
            (table.tab_pressure_se / table.tab_pressure)[table.tab_pressure > 1e7], initial=0.0))
        report["tables"].append(row)
        print(f"table {rq1 * 1e6:g}/{rq2 * 1e6:g} um: {seconds:.1f} s, {row['rows']} rows", file=sys.stderr)

    table = next(iter(tables.values()))
    d = np.linspace(*table.d_range, 1000)
    repeats = 50
    start = time.perf_counter()
    for _ in range(repeats):
        table.asperity_pressure(d)
        table.d_asperity_pressure(d)
        table.gap_moment(d, -3, H_B)
    report["evaluation"] = {"us_per_point_for_3_calls": (time.perf_counter() - start) / repeats / d.size * 1e6}

    if not args.quick:
        report["resolution"] = []
        report["window"] = []
        for rq1, rq2 in pairs:
            levels = {}
            for points in (16.0, 32.0, 64.0):
                settings = dc.DryContactSettings(points_per_correlation_length=points)
                start = time.perf_counter()
                levels[points] = point_statistics(profile, rq1, rq2, settings)
                print(f"resolution beta/{points:g} {rq1 * 1e6:g}/{rq2 * 1e6:g}: {time.perf_counter() - start:.1f} s",
                      file=sys.stderr)
            rows = []
            for i, ds in enumerate(D_OVER_SIGMA):
                row = {"d_over_sigma": ds}
                for name in ("p_a_pa", "contact_fraction", "mean_gap_over_sigma", "moment_m3_floor_1nm"):
                    values = [levels[pts][i][name] for pts in (16.0, 32.0, 64.0)]
                    row[name] = values
                    row[name + "_rel_diff_32_64"] = abs(values[1] - values[2]) / max(abs(values[2]), 1e-300)
                    row[name + "_order"] = observed_order(values)
                rows.append(row)
            report["resolution"].append({"rq_um": [rq1 * 1e6, rq2 * 1e6], "points": rows})

            windows = {}
            for length, count in ((128.0, 16), (256.0, 8), (512.0, 4), (1024.0, 2)):
                settings = dc.DryContactSettings(window_correlation_lengths=length, n_windows=count)
                windows[length] = point_statistics(profile, rq1, rq2, settings)
            rows = []
            for i, ds in enumerate(D_OVER_SIGMA):
                row = {"d_over_sigma": ds}
                for name in ("p_a_pa", "p_a_se_pa", "contact_fraction", "moment_m3_floor_1nm"):
                    row[name] = [windows[length][i][name] for length in (128.0, 256.0, 512.0, 1024.0)]
                rows.append(row)
            report["window"].append({"rq_um": [rq1 * 1e6, rq2 * 1e6], "window_beta": [128, 256, 512, 1024],
                                     "n_windows": [16, 8, 4, 2], "points": rows})
    emit_json(report, args.out, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
