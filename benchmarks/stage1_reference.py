"""Record the solved values of a seeded sample of paper-factorial contacts (the stage-1 regression reference).

    python benchmarks/stage1_reference.py [--n-smooth 24] [--n-rough 6] [--seed 45]
        [--out tests/ehl_dataset/data/stage1_reference.json]

Smooth surfaces at ``standard`` (``model="smooth"``, the planner's effects, thermal correction where it asks for it)
and rough contacts at ``standard`` with the default model (``model="auto"``, the paper factorial's isothermal
effects), both drawn without replacement from the axes of ``data/factorials/paper2009.toml``. The file records the
solver version that produced the values; ``tests/ehl_dataset/test_stage1_reference.py`` re-solves the contacts and
compares.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from ehl_dataset.dataset.factorial import load_factorial
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solver import SOLVER_VERSION, solve_contact

OUTPUTS = ("mu", "h_min", "h_central", "p_max")


def sample_points(n_smooth: int, n_rough: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    """(smooth, rough) SI point rows (p_h, r_eq, u_r, sr, T, rq1, rq2) of the paper factorial, seeded; smooth rows
    have rq1 = rq2 = 0."""
    points = load_factorial("paper2009").points()
    table = np.column_stack([points[name] for name in points.dtype.names])
    rng = np.random.default_rng(seed)
    picks = rng.choice(table.shape[0], n_smooth + n_rough, replace=False)
    smooth = table[picks[:n_smooth]].copy()
    smooth[:, 5:] = 0.0
    return smooth, table[picks[n_smooth:]]


def solve_rows(rows: np.ndarray, model: str, effects: str) -> list[dict]:
    lub = load_lubricant("atf")
    out = []
    for row in rows:
        res = solve_contact(ContactCase(*row), lub, "standard", effects, model=model)
        out.append({"point": [float(v) for v in row], "converged": bool(res.converged),
                    **{k: float(getattr(res, k)) for k in OUTPUTS}})
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n-smooth", type=int, default=24)
    parser.add_argument("--n-rough", type=int, default=6)
    parser.add_argument("--seed", type=int, default=45)
    parser.add_argument("--out", default="tests/ehl_dataset/data/stage1_reference.json")
    args = parser.parse_args(argv)
    smooth, rough = sample_points(args.n_smooth, args.n_rough, args.seed)
    report = {"command": ("python benchmarks/stage1_reference.py " + " ".join(argv or sys.argv[1:])).strip(),
              "solver_version": SOLVER_VERSION, "level": "standard", "lubricant": "atf",
              "point_columns": ["p_h_pa", "r_eq_m", "u_r_m_s", "sr", "temperature_k", "rq1_m", "rq2_m"],
              "smooth": {"model": "smooth", "effects": "auto", "cases": solve_rows(smooth, "smooth", "auto")},
              "rough": {"model": "auto", "effects": "isothermal", "cases": solve_rows(rough, "auto", "isothermal")}}
    Path(args.out).write_text(json.dumps(report, indent=1) + "\n")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
