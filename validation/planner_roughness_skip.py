"""The planner's roughness skip against every effect: μ of the steady smooth solve the planner picks at λ̄ equal to
a level's ``lambda_smooth`` threshold, against the deterministic transient rough solve (``effects="full"``) at that
level's grid rule, on the narrow contact of ``tests/ehl_dataset/test_planner.py::test_roughness_skip_agrees_with_full_model``
(1 GPa, 5 mm, 10 m/s, SR 0.3, 50 °C; Rq1 = Rq2). Both sides isothermal (the deterministic solver has no thermal
model). The test runs ``fast``; ``standard`` (about 2 min) is measured here.

    python validation/planner_roughness_skip.py [--levels fast standard] [--out validation/results/planner_roughness_skip.json]
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))  # _common.py, shared with the speed benchmarks
from _common import emit_json, machine_info  # noqa: E402

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solver import SOLVER_VERSION, solve_contact
from ehl_dataset.solvers.deterministic import MODEL_VERSION
from ehl_dataset.solvers.planner import dimensionless_numbers, thresholds_for

CONTACT = (1.0, 5.0, 10.0, 0.3, 50.0)
"""p_h [GPa], r_eq [mm], u_r [m/s], SR, T [°C] of the contact."""


def measure(level: str, lubricant) -> dict:
    smooth_case = ContactCase.from_engineering(*CONTACT, 0.0, 0.0)
    lam = thresholds_for(level).lambda_smooth
    rq = dimensionless_numbers(smooth_case, lubricant)["h_min_dh_m"] / lam / math.sqrt(2)
    rough_case = ContactCase(smooth_case.p_h, smooth_case.r_eq, smooth_case.u_r, smooth_case.sr,
                             smooth_case.temperature, rq, rq)
    planned = solve_contact(rough_case, lubricant, level, "isothermal")
    start = time.perf_counter()
    # the baseline profile, as the rough side of test_roughness_skip_agrees_with_full_model (not the default)
    full = solve_contact(rough_case, lubricant, level, "full", roughness=baseline_profile())
    wall = time.perf_counter() - start
    return {"level": level, "lambda_bar_threshold": lam, "tolerance": thresholds_for(level).tolerance, "rq_m": rq,
            "planned_roughness": bool(planned.effects["roughness"]), "mu_planned": planned.mu, "mu_full": full.mu,
            "mu_full_sem": full.mu_sem, "full_converged": full.converged, "full_model": full.extra.get("model"),
            "relative_difference": (planned.mu - full.mu) / full.mu, "full_wall_time_s": wall}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--levels", nargs="+", default=["fast", "standard"])
    parser.add_argument("--out", default=str(Path(__file__).resolve().parent / "results" / "planner_roughness_skip.json"))
    args = parser.parse_args()
    lubricant = load_lubricant("atf")
    rows = [measure(level, lubricant) for level in args.levels]
    emit_json({"machine": machine_info(), "solver_version": SOLVER_VERSION, "deterministic_model_version": MODEL_VERSION,
               "contact": dict(zip(("p_h_gpa", "r_eq_mm", "u_r_m_s", "sr", "temp_c"), CONTACT)), "rows": rows},
              args.out)


if __name__ == "__main__":
    main()
