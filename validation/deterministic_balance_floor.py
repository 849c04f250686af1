"""How far double precision lets the global lubricant balance of a deterministic run go below its 1e-10 target
(docs/explanation/mixed-regime.md, "Mass balance").

Runs the start of a validation run (its own options, layout and roughness) and, at every Newton solve that ends
converged with the global balance |Σ mass rows|/(ρ̄H)_ref above the target, moves each group of unknowns (the fluid
pressures, the fill fractions, the contact pressures, the film offset H_0) by one unit in its last place (random signs)
and records how much the balance moves. Where one ulp of a group moves it by a sizeable fraction of the target, no
state that double precision can hold balances better: the excess is the representation floor, not a lubricant loss.
It also records the sum of the rows telescoped (interior face fluxes cancel exactly; ``math.fsum`` over the
boundary fluxes and the time terms), which shows whether rounding in the summation itself contributes.

    python validation/deterministic_balance_floor.py L 16 --seconds 70
    python validation/deterministic_balance_floor.py H 32 --seconds 60

A diagnosis tool: the solver's ``newton`` is wrapped to observe its ends; the numerics are unchanged. Rows are
written to validation/results/deterministic_balance_floor.json (one entry per run and model version, replaced when
run again).
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import deterministic_validation as validation  # noqa: E402

from ehl_dataset.discretisation.mixed_system import _face_partials_of  # noqa: E402
from ehl_dataset.model.contact import ContactCase  # noqa: E402
from ehl_dataset.model.effects import Effects  # noqa: E402
from ehl_dataset.model.lubricant import load_lubricant  # noqa: E402
from ehl_dataset.solvers import deterministic  # noqa: E402

OUT = Path(__file__).resolve().parent / "results" / "deterministic_balance_floor.json"
TARGET = 1e-10
ROW_KINDS = ("mass", "cavitation", "contact")
GROUPS = {"fluid pressure": slice(0, -1, 3), "fill fraction": slice(1, -1, 3), "contact pressure": slice(2, -1, 3),
          "film offset H0": slice(-1, None)}


def telescoped_balance(problem, z, gap, storage) -> float:
    """Σ of the mass rows with the interior face fluxes cancelled exactly: −q_inlet − outflow − Σ time terms
    (``math.fsum``), relative to the reference flux (the same quantity as ``mass_balance_error``, summed without
    the interior fluxes' rounding)."""
    pf = problem.unpack(z)[0]
    h = problem.film(z, gap)
    eps, eps_p, eps_h, _, _ = problem.fluid(pf, h)
    hp, floor = problem.conducting_film(h)
    cube, cube_h = hp**3, np.where(h > floor, 3.0 * hp**2, 0.0)
    content = problem.content(z, h)
    time_terms = storage[0] * content + storage[1]
    if problem.periodic:
        return -math.fsum(time_terms) / problem.m_ref
    conductance = _face_partials_of(0, 1, eps, eps_p, eps_h, cube, cube_h, problem.mean)[0]
    q_inlet = conductance * (pf[1] - pf[0]) / problem.dx - content[0]
    return math.fsum([-q_inlet, -content[-1], *(-time_terms[1:])]) / problem.m_ref


def observe(rows: list, seed: int = 0) -> None:
    """Wrap ``MixedProblem.newton`` so that every converged solve above the target appends its sensitivities."""
    newton = deterministic.MixedProblem.newton
    rng = np.random.default_rng(seed)

    def _newton(self, z, gap, storage, tol, max_iterations, *args, **kwargs):
        out = newton(self, z, gap, storage, tol, max_iterations, *args, **kwargs)
        z_out, converged = out[0], out[1]
        scale = self.row_scale()

        def balance(state):
            scaled = self.evaluate(state, gap, storage)[0] * scale
            return float(np.sum(scaled[self.mass_rows])), float(np.max(np.abs(scaled[:-1]))), scaled

        total, largest_row, scaled = balance(z_out)
        if converged and abs(total) > TARGET:
            where = int(np.argmax(np.abs(scaled[:-1])))
            row = {"balance": total, "largest_row": largest_row, "largest_row_kind": ROW_KINDS[where % 3],
                   "largest_row_x_over_a": float(self.x[where // 3]),
                   "telescoped": telescoped_balance(self, z_out, gap, storage), "n_nodes": int(self.n),
                   "film_offset": float(z_out[-1])}
            for name, part in GROUPS.items():
                moved = z_out.copy()
                values = moved[part]
                moved[part] = values + np.spacing(np.abs(values)) * rng.choice((-1.0, 1.0), size=values.size)
                row[f"one_ulp_{name}"] = balance(moved)[0] - total
            rows.append(row)
        return out

    deterministic.MixedProblem.newton = _newton


def analyse(name: str, n: int, seconds: float) -> dict:
    rows: list[dict] = []
    observe(rows)
    long = n == validation.spacings(name)[1]
    case = ContactCase.from_engineering(*validation.CASES[name])
    state = load_lubricant(validation.LUBRICANT).state(case.temperature)
    cap = validation.long_max_passes(name) if long else validation.MAX_PASSES
    options = validation.options_for(n, long, cap, validation.layout_passes(name))
    result = deterministic.solve_deterministic(case, state, Effects.full(), options,
                                               roughness=validation.profile_for(name), time_limit_s=seconds)
    mass = np.asarray(result.extra["mass_error_series"])
    summary = {"run": f"{name} beta/{n}", "model_version": deterministic.MODEL_VERSION, "seconds": seconds,
               "steps": int(mass.size), "steps_over_target": int(np.sum(mass > TARGET)),
               "solves_over_target": len(rows)}
    if rows:
        for key in ("balance", "telescoped", "largest_row", *(f"one_ulp_{g}" for g in GROUPS)):
            summary[f"median_abs_{key}"] = float(np.median([abs(r[key]) for r in rows]))
    return {**summary, "rows": rows}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("case")
    parser.add_argument("points_per_beta", type=int)
    parser.add_argument("--seconds", type=float, default=60.0, help="wall time of the run's start [s]")
    args = parser.parse_args(argv)
    entry = analyse(args.case, args.points_per_beta, args.seconds)
    entry["command"] = (f"python validation/deterministic_balance_floor.py {args.case} {args.points_per_beta} "
                        f"--seconds {args.seconds:g}")
    print(json.dumps({k: v for k, v in entry.items() if k != "rows"}, indent=1), flush=True)
    kept = json.loads(OUT.read_text()) if OUT.exists() else {}
    runs = [r for r in kept.get("runs", [])
            if (r.get("run"), r.get("model_version")) != (entry["run"], entry["model_version"])]
    OUT.write_text(json.dumps({"machine": platform.platform(), "runs": runs + [entry]}, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
