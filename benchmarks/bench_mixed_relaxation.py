"""Benchmark: the semi-system relaxation solver for transient mixed EHL (ehl_dataset.ehl_mixed_relaxation).

    python benchmarks/bench_mixed_relaxation.py --sample compare --level fast   # λ̄ ≈ 1–3 corners, vs the Newton solver
    python benchmarks/bench_mixed_relaxation.py --sample hard --level fast      # the brief's failing cases
    python benchmarks/bench_mixed_relaxation.py --sample corners --level fast   # the 64 corners (slow)
    python benchmarks/bench_mixed_relaxation.py --sample sweep --level fast     # λ̄ → 0 by Rq 0.05 … 10 µm

Per case: converged, μ, μ_std, h_min, asperity share, λ̄, max load error, sweeps, wall time; for ``compare`` also
the transient Newton solver's (ehl_dataset.solver.solve_contact, effects=full) result and the relative μ
difference. Writes benchmarks/results/mixed_relaxation_<sample>_<level>.json with the machine noted.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from ehl_dataset.contact import ContactCase
from ehl_dataset.effects import Effects
from ehl_dataset.ehl_mixed_relaxation import solve_mixed_relaxation
from ehl_dataset.lubricant import load_lubricant

# _common.py sits next to this file. Run as a script (`python benchmarks/bench_mixed_relaxation.py` or, inside
# benchmarks/, `python bench_mixed_relaxation.py`) Python already puts this directory first on sys.path; adding it
# explicitly also covers loading this file as a module (runpy, tests), where sys.path[0] is the caller's directory.
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import RESULTS_DIR, machine_info, summarize_rows, write_report  # noqa: E402

# (p_h GPa, r_eq mm, u_r m/s, SR, T °C, Rq1 µm, Rq2 µm, lubricant)
COMPARE = [(0.5, 5, 20, 1, 25, 1.0, 1.0, "atf"), (0.5, 80, 20, 1, 25, 1.0, 1.0, "atf"),
           (2.5, 5, 20, 0, 25, 1.0, 1.0, "atf"), (0.5, 5, 20, 1, 100, 0.05, 0.05, "atf")]
HARD = [(0.167, 10, 5, 0.327, 90, 0.4, 0.4, "gear_oil_75w90"), (1.2, 10, 3.06, 0.39, 90, 0.4, 0.4, "gear_oil_75w90"),
        (2.5, 5, 1, 1, 100, 1.0, 1.0, "atf"), (0.5, 5, 1, 1, 100, 1.0, 1.0, "atf")]


# λ̄ → 0 at fixed conditions (0.5 GPa, 5 mm, 1 m/s, SR 1, 100 °C): Rq 0.05 … 10 µm, λ̄ ≈ 0.54 … 0.0027
SWEEP = [(0.5, 5, 1, 1, 100, rq, rq, "atf") for rq in (0.05, 0.2, 1.0, 3.0, 10.0)]


def corner_cases():
    import itertools

    return [(p, r, u, s, t, q, q, "atf") for p, r, u, s, t, q in itertools.product(
        [0.5, 2.5], [5, 80], [1, 20], [0, 1], [25, 100], [0.05, 1.0])]


def _row(res, lub_mu_d):
    return {"converged": bool(res.converged), "mu": res.mu, "mu_std": res.mu_std, "h_min_m": res.h_min,
            "lambda_bar": res.lambda_bar, "asperity_load_share": res.asperity_load_share,
            "p_max_pa": res.p_max, "max_load_error": res.extra.get("max_load_error"),
            "n_nodes": res.extra.get("n_nodes"), "n_steps": res.extra.get("n_steps"),
            "iterations": res.iterations, "mu_in_0_mu_d": bool(0.0 <= res.mu <= lub_mu_d),
            "message": res.message[:300], "wall_time_s": res.wall_time}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--level", default="fast")
    parser.add_argument("--sample", choices=["compare", "hard", "corners", "sweep"], default="compare")
    parser.add_argument("--out", default=None)
    parser.add_argument("--shard", default="0/1", help="k/n: run every n-th case starting at k (parallel runs)")
    args = parser.parse_args(argv)
    cases = {"compare": COMPARE, "hard": HARD, "corners": corner_cases(), "sweep": SWEEP}[args.sample]
    k, n = (int(v) for v in args.shard.split("/"))
    cases = cases[k::n]
    rows = []
    for spec in cases:
        lub = load_lubricant(spec[7])
        case = ContactCase.from_engineering(*spec[:7])
        row = {"case": list(spec)}
        try:
            row["relaxation"] = _row(solve_mixed_relaxation(case, lub, args.level), lub.mu_d)
        except Exception as err:  # recorded, the sweep goes on
            row["relaxation"] = {"converged": False, "error": f"{type(err).__name__}: {err}"}
        if args.sample == "compare":
            from ehl_dataset.solver import solve_contact

            newton = solve_contact(case, lub, args.level, Effects.full())
            row["newton"] = _row(newton, lub.mu_d)
            if newton.converged and row["relaxation"].get("converged"):
                row["mu_relative_difference"] = row["relaxation"]["mu"] / newton.mu - 1.0
        rows.append(row)
        print(json.dumps(row, default=float), flush=True)
    summary = _summary(rows)
    report = {"benchmark": "mixed_relaxation", "level": args.level, "sample": args.sample, "summary": summary,
              "rows": rows, "machine": machine_info()}
    name = f"mixed_relaxation_{args.sample}_{args.level}" + (f"_shard{k}of{n}" if n > 1 else "") + ".json"
    write_report(args.out or RESULTS_DIR / name, report)
    print(json.dumps(summary, indent=2, default=float))
    return 0


def _summary(rows) -> dict:
    """Case count, converged count, median and mean wall time [s] of the relaxation solves (a solve that raised
    has no time and counts 0 s)."""
    stats = summarize_rows([r["relaxation"] for r in rows], wall_time_s=lambda r: r.get("wall_time_s", 0.0))
    return {key: stats[key] for key in ("n_cases", "converged", "median_time_s", "mean_time_s")}


if __name__ == "__main__":
    sys.exit(main())
