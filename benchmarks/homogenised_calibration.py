"""Can one constant calibrate the homogenised model's 1-D transverse closure against the deterministic reference?

The transverse closure's pressure conductance 1/⟨max(g, h_f)⁻³⟩ is dominated by the contact spots of the dry-contact
table, floored at h_f (docs/homogenised_model.md). With h_f = h_b = 5 nm the model entrains a film of several σ and
μ falls below the smooth value; raising the floor h_f (``HomogenisedOptions.flow_floor_sigma``, in units of σ)
weakens the blocking. This script scans h_f/σ on the deterministic cases whose finest two spacings agree within
the grid targets (benchmarks/results/deterministic_convergence_<case>.json, model det-2026.11-6: the finest run's μ
and asperity share) and writes benchmarks/results/homogenised_calibration.json:

    python benchmarks/homogenised_calibration.py [--floors 0.05 0.1 0.2 0.3 0.5]
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solvers.homogenised import HomogenisedOptions, solve_homogenised
from ehl_dataset.solvers.levels import get_level

RESULTS = Path(__file__).resolve().parent / "results"
CASES = ("A", "B", "C", "D")
DEFAULT_FLOORS = (None, 0.05, 0.1, 0.15, 0.2, 0.3, 0.5, 1.0)


def reference(name: str) -> dict:
    """μ and asperity share of the finest run of the case's convergence study."""
    data = json.loads((RESULTS / f"deterministic_convergence_{name}.json").read_text())
    finest = max(data["runs"], key=int)
    run = data["runs"][finest]
    return {"inputs": data["inputs"], "model_version": data["model_version"], "points_per_beta": int(finest),
            "mu": run["mu"], "asperity_load_share": run["asperity_load_share"]}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--floors", nargs="+", type=float, default=None, help="h_f/σ values (default: a scan)")
    args = parser.parse_args(argv)
    floors = args.floors or DEFAULT_FLOORS
    lubricant = load_lubricant("atf")
    rows = []
    for name in CASES:
        ref = reference(name)
        case = ContactCase.from_engineering(*ref["inputs"])
        state = lubricant.state(case.temperature)
        for closure, floor in [("transverse", f) for f in floors] + [("isotropic", None)]:
            start = time.perf_counter()
            r = solve_homogenised(case, state, get_level("standard"), Effects.full(),
                                  options=HomogenisedOptions(closure=closure, flow_floor_sigma=floor))
            inside = np.abs(r.x) < case.half_width
            row = {"case": name, "closure": closure, "flow_floor_sigma": floor, "mu": r.mu,
                   "mu_reference": ref["mu"], "mu_error": r.mu / ref["mu"] - 1.0,
                   "asperity_load_share": r.asperity_load_share, "share_reference": ref["asperity_load_share"],
                   "mean_film_hertz_m": float(np.mean(r.film[inside])), "sigma_m": case.s_c,
                   "converged": r.converged, "wall_time_s": time.perf_counter() - start,
                   "reference_points_per_beta": ref["points_per_beta"], "reference_model": ref["model_version"]}
            rows.append(row)
            print(f"{name} {closure} h_f/sigma {floor}: mu {r.mu:.4f} ({100 * row['mu_error']:+.0f} %) share "
                  f"{r.asperity_load_share:.3f} (ref {ref['asperity_load_share']:.3f}) film "
                  f"{row['mean_film_hertz_m'] * 1e9:.0f} nm", flush=True)
    out = RESULTS / "homogenised_calibration.json"
    out.write_text(json.dumps({"command": "python benchmarks/homogenised_calibration.py", "rows": rows}, indent=1))
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
