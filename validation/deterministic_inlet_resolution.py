"""How fine the deterministic model's uniform grid must be at the smooth EHL inlet: the smooth solution on that grid
(the steady start every rough run begins from) against the steady solver's ``reference`` level, with the spacing
min(β/8, f·L_in) for f = 0.1, 0.2, 0.3, 0.5 (L_in = a·H_c^(2/3), the inlet length scale of the grid rule;
``ehl_dataset.solvers.deterministic.grid_spacing``) on the validation cases' conditions and six heavily loaded,
slow, hot corners of the paper's factorial, where L_in is shortest.

    python validation/deterministic_inlet_resolution.py      # ≈ 3 min; writes validation/results/deterministic_inlet_resolution.json

Each row: the conditions, a and L_in [µm], and per factor f the spacing in % of β, the relative error of μ and of
the central film h_c [%] and the solve time [s]. This is what the level-dependent inlet term of the grid rule
(``DeterministicOptions.inlet_resolution``, :data:`~ehl_dataset.solvers.levels.REGISTRY`) rests on.
"""

from __future__ import annotations

import json
import platform
import sys
import time
from pathlib import Path

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solver import SOLVER_VERSION
from ehl_dataset.solvers.deterministic import MODEL_VERSION, DeterministicOptions, solve_deterministic
from ehl_dataset.solvers.levels import get_level
from ehl_dataset.solvers.steady import ContactScales, moes_h_c, solve_steady

sys.path.insert(0, str(Path(__file__).resolve().parent))
from deterministic_validation import CASES  # noqa: E402

OUT = Path(__file__).resolve().parent / "results" / "deterministic_inlet_resolution.json"
FACTORS = (0.1, 0.2, 0.3, 0.5)
CORNERS = {  # p_h GPa, r_eq mm, u_r m/s, SR, T °C: the shortest inlets of the factorial
    "2.5/5/1/0.5/100": (2.5, 5, 1, 0.5, 100), "2.5/5/1/0.05/25": (2.5, 5, 1, 0.05, 25),
    "2.0/5/2/1.0/100": (2.0, 5, 2, 1.0, 100), "2.5/10/1/0.3/100": (2.5, 10, 1, 0.3, 100),
    "1.5/5/1/1.0/100": (1.5, 5, 1, 1.0, 100), "2.5/5/5/0.1/100": (2.5, 5, 5, 0.1, 100),
}


def measure(name: str, conditions, lubricant, beta: float) -> dict:
    case = ContactCase.from_engineering(*conditions[:5], 0.0, 0.0)
    state = lubricant.state(case.temperature)
    plan = Effects(False, False, True, True, "forced", {})
    reference = solve_steady(case, state, get_level("reference"), plan)
    scales = ContactScales.of(case, state, True)
    inlet = scales.a * moes_h_c(case, state, scales) ** (2.0 / 3.0)
    row = {"case": name, "conditions": list(conditions[:5]), "a_um": scales.a * 1e6, "inlet_length_um": inlet * 1e6,
           "reference_mu": reference.mu, "reference_h_central_m": reference.h_central, "factors": {}}
    for factor in FACTORS:
        dx = min(beta / 8.0, factor * inlet)
        start = time.perf_counter()
        result = solve_deterministic(case, state, plan, DeterministicOptions(dx_m=dx))
        row["factors"][str(factor)] = {
            "dx_percent_of_beta": 100.0 * dx / beta,
            "mu_error_percent": 100.0 * (result.mu / reference.mu - 1.0),
            "h_central_error_percent": 100.0 * (result.h_central / reference.h_central - 1.0),
            "wall_time_s": time.perf_counter() - start}
    return row


def main() -> int:
    lubricant = load_lubricant("atf")
    beta = baseline_profile().correlation_length
    rows = []
    for name, conditions in [*CASES.items(), *CORNERS.items()]:
        rows.append(measure(name, conditions, lubricant, beta))
        print(json.dumps(rows[-1]), flush=True)
    worst = {str(f): {"mu_error_percent": max(abs(r["factors"][str(f)]["mu_error_percent"]) for r in rows),
                      "h_central_error_percent": max(abs(r["factors"][str(f)]["h_central_error_percent"])
                                                     for r in rows)} for f in FACTORS}
    OUT.write_text(json.dumps({"benchmark": "deterministic_inlet_resolution",
                               "command": "python validation/deterministic_inlet_resolution.py",
                               "model_version": MODEL_VERSION, "solver_version": SOLVER_VERSION,
                               "machine": platform.platform(), "worst": worst, "rows": rows}, indent=1) + "\n")
    print(json.dumps(worst))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
