"""Is the production transient solver's excess friction in the contact regime a time-step (or grid) artefact?

The deterministic solver's asperity contacts were mostly a time-step artefact: on the roughness sweep of
benchmarks/deterministic_lambda_sweep.py, Courant 0.5 → 0.25 lowered μ by 9–23 % and the asperity share 9×
(docs/deterministic_solver.md, "Time step"). The production transient solver (`standard`: Courant 1 at β/2) runs
+89 % to +133 % above that reference below λ̄ 0.33 (benchmarks/lambda_sweep_models.py). This runs it at the sweep's
low-λ̄ points with the Courant number and the roughness spacing of `standard` refined, everything else unchanged.

    python benchmarks/transient_time_step.py                 # resumable; writes results/transient_time_step.json
    python benchmarks/transient_time_step.py --summary       # the table from the JSON

Same conditions as the sweep (case A: 0.5 GPa / 5 mm / 5 m/s / SR 0.3 / 90 °C, ATF, Rq1 = Rq2).
"""

from __future__ import annotations

import json
import sys
import time
from dataclasses import replace
from pathlib import Path

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solver import SOLVER_VERSION, solve_contact
from ehl_dataset.solvers.levels import LEVELS

from _common import machine_info

ROOT = Path(__file__).resolve().parents[1]
SWEEP = ROOT / "benchmarks" / "results" / "deterministic_lambda_sweep.json"
OUT = ROOT / "benchmarks" / "results" / "transient_time_step.json"
RQ_UM = (0.3, 0.5)
VARIANTS = {  # name: (courant, dx_rough [β])
    "standard": (1.0, 0.5),
    "courant_0.5": (0.5, 0.5),
    "courant_0.25": (0.25, 0.5),
    "courant_0.25_dx_beta4": (0.25, 0.25),
}


def level_for(courant: float, dx_rough: float):
    base = LEVELS["standard"]
    scale = base.courant / courant * base.dx_rough / dx_rough
    return replace(base, courant=courant, dx_rough=dx_rough, max_steps_rough=int(base.max_steps_rough * scale),
                   max_nodes_rough=int(base.max_nodes_rough * base.dx_rough / dx_rough))


def main() -> int:
    record = json.loads(OUT.read_text()) if OUT.exists() else {"machine": machine_info(), "runs": {}}
    sweep = json.loads(SWEEP.read_text())
    record["reference"] = {k: {f: v[f] for f in ("rq_um", "lambda_bar", "mu", "mu_sem", "asperity_load_share")}
                           for k, v in sweep["runs"].items() if v["rq_um"] in RQ_UM}
    record["reference_model_version"] = sweep["model_version"]
    if "--summary" not in sys.argv:
        lubricant = load_lubricant("atf")
        for rq in RQ_UM:
            case = ContactCase.from_engineering(*sweep["conditions"], rq, rq)
            for name, (courant, dx_rough) in VARIANTS.items():
                key = f"{name}/{rq}"
                if key in record["runs"]:
                    continue
                start = time.perf_counter()
                result = solve_contact(case, lubricant, level_for(courant, dx_rough), "full", model="auto")
                record["runs"][key] = {
                    "solver_version": SOLVER_VERSION, "variant": name, "courant": courant,
                    "dx_rough_beta": dx_rough, "rq_um": rq,
                    "lambda_bar": result.lambda_bar, "mu": result.mu, "mu_sem": result.mu_sem,
                    "asperity_load_share": result.asperity_load_share, "converged": result.converged,
                    "message": result.message, "wall_time_s": time.perf_counter() - start,
                    "courant_effective": result.extra.get("courant_effective"),
                    "n_nodes": result.extra.get("n_nodes"), "n_steps": result.extra.get("n_steps")}
                OUT.write_text(json.dumps(record, indent=1, default=float))
                print(key, f"mu {result.mu:.5f} ± {result.mu_sem:.5f} share {result.asperity_load_share:.4f} "
                      f"{time.perf_counter() - start:.0f} s", flush=True)
    OUT.write_text(json.dumps(record, indent=1, default=float))
    print("| Rq [µm] | λ̄ | variant | Courant (effective) | dx [β] | μ | share | vs reference | wall [s] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for run in sorted(record["runs"].values(), key=lambda r: (r["rq_um"], -r["courant"], -r["dx_rough_beta"])):
        ref = next(v for v in record["reference"].values() if v["rq_um"] == run["rq_um"])
        print(f"| {run['rq_um']} | {ref['lambda_bar']:.2f} | {run['variant']} | {run['courant']} "
              f"({run['courant_effective'] or float('nan'):.2f}) | {run['dx_rough_beta']} | {run['mu']:.4f} ± "
              f"{run['mu_sem']:.4f} | {run['asperity_load_share']:.3f} | {100 * (run['mu'] / ref['mu'] - 1):+.0f} % "
              f"| {run['wall_time_s']:.0f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
