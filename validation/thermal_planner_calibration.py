"""Calibration of the planner's thermal switch (docs/explanation/planner.md): on random smooth points of the paper's factorial
(data/factorials/paper2009.toml axes, ATF), the thermal estimate at the Hertz centre that the planner decides from
(``thermal_change``) against the measured change of μ when the steady solver applies the thermal correction,
(μ_isothermal − μ_thermal)/μ_isothermal, at the fast and standard levels.

Run: ``python validation/thermal_planner_calibration.py [--points 60] [--seed 17]``; writes
validation/results/thermal_planner_calibration.json.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))  # _common.py, shared with the speed benchmarks
from _common import emit_json, machine_info  # noqa: E402

AXES = {"p_h_gpa": [0.5, 1.0, 1.5, 2.0, 2.5], "r_eq_mm": [5.0, 10.0, 20.0, 40.0, 80.0],
        "u_r": [1.0, 2.0, 5.0, 10.0, 15.0, 20.0], "sr": [0.05, 0.1, 0.2, 0.4, 0.7, 1.0],
        "temp_c": [25.0, 50.0, 75.0, 100.0]}
"""The paper's axes (paper2009.toml) without SR = 0 (no sliding: exactly no thermal effect) and roughness (smooth)."""


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=60)
    parser.add_argument("--seed", type=int, default=17)
    parser.add_argument("--low-speed", action="store_true",
                        help="draw u_r from 0.1-2 m/s and SR from 0.01-0.2 (the region of small changes)")
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "thermal_planner_calibration.json"))
    args = parser.parse_args(argv)

    from ehl_dataset.model.contact import ContactCase
    from ehl_dataset.model.effects import Effects
    from ehl_dataset.model.lubricant import load_lubricant
    from ehl_dataset.solver import solve_contact
    from ehl_dataset.solvers.planner import dimensionless_numbers

    lub = load_lubricant("atf")
    rng = np.random.default_rng(args.seed)
    rows = []
    for i in range(args.points):
        point = {k: float(rng.choice(v)) for k, v in AXES.items()}
        if args.low_speed:
            point["u_r"] = float(np.exp(rng.uniform(np.log(0.1), np.log(2.0))))
            point["sr"] = float(np.exp(rng.uniform(np.log(0.01), np.log(0.2))))
        case = ContactCase.from_engineering(point["p_h_gpa"], point["r_eq_mm"], point["u_r"], point["sr"],
                                            point["temp_c"], 0.0, 0.0)
        nums = dimensionless_numbers(case, lub)
        row = {**point, "predicted": nums["thermal_change"], "flash_rise_k": nums["flash_rise_k"],
               "film_centre_rise_k": nums["film_centre_rise_k"], "nahme_number": nums["nahme_number"]}
        for level in ("fast", "standard"):
            started = time.perf_counter()
            iso = solve_contact(case, lub, level, Effects(False, False, True, True, "forced"))
            hot = solve_contact(case, lub, level, Effects(False, False, True, True, "forced", thermal=True))
            row[level] = {"mu_isothermal": iso.mu, "mu_thermal": hot.mu, "converged": iso.converged and hot.converged,
                          "measured": (iso.mu - hot.mu) / iso.mu, "time_s": time.perf_counter() - started,
                          "thermal": hot.extra.get("thermal", {})}
        rows.append(row)
        print(i, {k: round(v, 3) for k, v in point.items()}, f"pred {row['predicted']:.4f}",
              f"fast {row['fast']['measured']:.4f} std {row['standard']['measured']:.4f}", file=sys.stderr)
    ratio = {lvl: [r[lvl]["measured"] / r["predicted"] for r in rows if r["predicted"] > 1e-4] for lvl in
             ("fast", "standard")}
    report = {"benchmark": "thermal planner calibration: predicted (centre estimate) vs measured change of mu",
              "lubricant": "atf", "seed": args.seed, "low_speed": args.low_speed, "machine": machine_info(),
              "ratio_measured_over_predicted": {lvl: {"max": max(v), "median": float(np.median(v)), "min": min(v)}
                                                for lvl, v in ratio.items() if v},
              "rows": rows}
    emit_json(report, args.out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
