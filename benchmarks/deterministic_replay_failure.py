"""Replay the step a validation run failed, from the state it kept (``<checkpoint>.failed``), and say how each Newton
solve of that step ended: iterations, final scaled norm, the row that limits it (kind: 0 mass, 1 cavitation, 2
contact; node and x/a) and the round-off floor measured there (docs/deterministic_solver.md, "Robustness" item 9).

    python benchmarks/deterministic_replay_failure.py B 256
    python benchmarks/deterministic_replay_failure.py B 256 --state path/to/copy.failed

The kept state is copied to a scratch file first, so the run's own files are left as they are. A diagnosis tool:
it changes no numerics (the solver's methods are wrapped to observe them).
"""

from __future__ import annotations

import argparse
import shutil
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import deterministic_validation as validation  # noqa: E402

from ehl_dataset.dataset.checkpoint import FileCheckpoint  # noqa: E402
from ehl_dataset.model.contact import ContactCase  # noqa: E402
from ehl_dataset.model.effects import Effects  # noqa: E402
from ehl_dataset.model.lubricant import load_lubricant  # noqa: E402
from ehl_dataset.solvers import deterministic  # noqa: E402

ROW_KINDS = ("mass", "cavitation", "contact")


def observe(problem_class, report):
    """Wrap ``newton`` and ``_direction`` of ``problem_class`` so that every Newton solve reports its end."""
    newton, direction = problem_class.newton, problem_class._direction
    last = {}

    def _direction(self, jac, dfilm, scaled, scale, tol):
        last["row"] = int(np.argmax(np.abs(scaled[:-1])))
        return direction(self, jac, dfilm, scaled, scale, tol)

    def _newton(self, z, gap, storage, tol, max_iterations, *args, **kwargs):
        last.clear()
        z_out, converged, iterations, norm = newton(self, z, gap, storage, tol, max_iterations, *args, **kwargs)
        row = last.get("row", -1)
        report({"converged": bool(converged), "iterations": int(iterations), "norm": float(norm),
                "row_kind": ROW_KINDS[row % 3] if row >= 0 else "-", "node": row // 3,
                "x_over_a": float(self.x[row // 3]) if row >= 0 else float("nan"),
                "floor": self.round_off_floor(z_out, gap, storage),
                "step_weight": float(storage[0][0]) if storage[0] is not None else 0.0})
        return z_out, converged, iterations, norm

    problem_class.newton, problem_class._direction = _newton, _direction


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("case")
    parser.add_argument("points_per_beta", type=int)
    parser.add_argument("--state", default=None, help="the kept state (default: the run's <checkpoint>.failed)")
    parser.add_argument("--long", action="store_true", help="the case's long run (default: a short run)")
    args = parser.parse_args(argv)
    kept = Path(args.state) if args.state else FileCheckpoint(
        validation.checkpoint_path(args.case, args.points_per_beta, args.long)).failure_path
    if not kept.exists():
        print(f"no kept state at {kept}", file=sys.stderr)
        return 2
    scratch = Path(tempfile.mkdtemp()) / "replay.pickle"
    shutil.copy(kept, scratch)
    print(f"replaying step {FileCheckpoint(scratch).load()['k'] + 1} of {args.case} beta/{args.points_per_beta}",
          flush=True)

    def report(row):
        if not row["converged"] or row["norm"] > deterministic.ROUND_OFF_MARGIN * 1e-10:
            print("newton {converged!s:5} {iterations:3d} its  norm {norm:.2e}  floor {floor:.2e}  "
                  "{row_kind} row at node {node} (x/a {x_over_a:+.3f})  w/dT {step_weight:.3g}".format(**row),
                  flush=True)

    observe(deterministic.MixedProblem, report)
    case = ContactCase.from_engineering(*validation.CASES[args.case])
    state = load_lubricant(validation.LUBRICANT).state(case.temperature)
    cap = validation.long_max_passes(args.case) if args.long else validation.MAX_PASSES
    options = validation.options_for(args.points_per_beta, args.long, cap, validation.layout_passes(args.case))
    saved = FileCheckpoint(scratch).load()
    result = deterministic.solve_deterministic(case, state, Effects.full(), options,
                                               roughness=validation.profile_for(args.case),
                                               checkpoint=FileCheckpoint(scratch, every_s=float("inf")),
                                               time_limit_s=saved["elapsed_s"] + 600.0)
    print(result.message)
    shutil.rmtree(scratch.parent, ignore_errors=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
