"""Grid convergence of the deterministic mixed-EHL solver on one case: the same roughness over the same time window
at several spacings β/n (paired runs), μ and asperity share per spacing, their steps and the observed order.

    python validation/deterministic_convergence.py --case A --spacings 16 32 64 --passes 11
    python validation/deterministic_convergence.py --case B --spacings 16 32 --face-mean harmonic   # another face

Cases are those of validation/deterministic_validation.py. The window is [start-up end, end of run]; every run of a
case uses the same layout of the roughness (it is laid out for 40 passes whatever the spacing), so the differences
between spacings are not sampling noise. Writes validation/results/deterministic_convergence_<case>.json.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solvers.deterministic import MODEL_VERSION, DeterministicOptions, solve_deterministic

sys.path.insert(0, str(Path(__file__).resolve().parent))
from deterministic_validation import CASES, LUBRICANT, MAX_PASSES  # noqa: E402

RESULTS = Path(__file__).resolve().parent / "results"


def run(name: str, spacings: list[int], passes: float, face_mean: str | None = None) -> dict:
    lubricant = load_lubricant(LUBRICANT)
    case = ContactCase.from_engineering(*CASES[name])
    state = lubricant.state(case.temperature)
    beta = baseline_profile().correlation_length
    default_face = DeterministicOptions().face_mean
    face = face_mean or default_face
    suffix = "" if face == default_face else f"_{face}"
    path = RESULTS / f"deterministic_convergence_{name}{suffix}.json"
    record = json.loads(path.read_text()) if path.exists() else {}
    if record.get("model_version") != MODEL_VERSION or record.get("passes") != passes:
        record = {"case": name, "inputs": CASES[name], "model_version": MODEL_VERSION, "passes": passes,
                  "face_mean": face, "runs": {}}
    for n in spacings:
        if str(n) in record["runs"]:
            continue
        options = DeterministicOptions(dx_m=beta / n, max_passes=MAX_PASSES, mu_sem_target=1.0,
                                       min_average_passes=passes - 1.5, face_mean=face)
        start = time.time()
        # the validation cases' roughness (spacings in its β), not the package's default profile
        result = solve_deterministic(case, state, Effects.full(), options, roughness=baseline_profile())
        e = result.extra
        window = slice(e["average_from_step"], None)
        record["runs"][str(n)] = {
            "dx_m": e["dx_m"], "n_nodes": e["n_nodes"], "n_steps": e["n_steps"], "converged": result.converged,
            "mu": float(np.mean(e["mu_series"][window])), "asperity_load_share": float(np.mean(e["share_series"][window])),
            "h_min_m": result.h_min, "h_min_local_m": e["h_min_local_m"], "wall_time_s": time.time() - start,
            "newton_iterations": e["newton_iterations"], "gmres_iterations": e["gmres_iterations"],
            "substep_steps": e["substep_steps"], "max_mass_error": result.residuals["max_mass_error"],
            "round_off_stops": e.get("round_off_stops"), "message": result.message}
        path.write_text(json.dumps(record, indent=1))
        print(name, f"beta/{n}", record["runs"][str(n)], flush=True)
    keys = sorted(record["runs"], key=int)
    for quantity in ("mu", "asperity_load_share"):
        values = [record["runs"][k][quantity] for k in keys]
        steps = [b - a for a, b in zip(values, values[1:])]
        orders = [math.log2(s1 / s2) if s1 * s2 > 0 and abs(s2) > 0 else math.nan for s1, s2 in zip(steps, steps[1:])]
        record[quantity + "_steps"] = steps
        record[quantity + "_observed_orders"] = orders
    path.write_text(json.dumps(record, indent=1))
    return record


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--case", required=True, choices=sorted(CASES))
    parser.add_argument("--spacings", type=int, nargs="+", default=[16, 32, 64])
    parser.add_argument("--passes", type=float, default=11.0, help="run length in passes (start-up 1.5 included)")
    parser.add_argument("--face-mean", default=None, help="face conductance (default: the model's; another one "
                        "writes deterministic_convergence_<case>_<face>.json)")
    args = parser.parse_args(argv)
    record = run(args.case, args.spacings, args.passes, args.face_mean)
    print(json.dumps({k: v for k, v in record.items() if k != "runs"}, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
