"""How many averaging passes each spacing of a validation case needs for a standard error of μ ≤ 1.5 % at its finest
spacing, and what that costs: the optimal multilevel allocation (Giles, Oper. Res. 56 (2008) 607, Eq. 3.1–3.2) from
the variances and costs the recorded runs measured.

The validation estimator (validation/deterministic_validation.py) writes μ at the finest spacing L as the long run's
mean at the middle spacing m plus the paired differences up the chain,

    μ̂_L = ⟨μ_m⟩ + Σ_l ⟨μ_l − μ_(l−1)⟩,    Var μ̂_L = Σ_l V_l / N_l,

with V_l the per-pass variance of level l (standard error² × averaging passes of the recorded run, the
autocorrelation-corrected standard error of ehl_dataset.solvers.time_average) and N_l its averaging passes. Level l's
run costs c_l per pass (wall time over all passes of its recorded run, start-up included); a difference's coarser
partner runs at least as long anyway (N falls up the chain), so level l costs N_l·c_l. The least total cost for
Var μ̂_L ≤ ε², ε = 1.5 %·μ_L, takes

    N_l = √(V_l / c_l) · Σ_k √(V_k c_k) / ε²,     cost = (Σ_k √(V_k c_k))² / ε²   (+ each run's start-up).

The variances of the short runs come from 1.5-pass windows, whose own standard errors are too small where contact
episodes drive the differences (docs/explanation/mixed-regime.md, "Standard error of the short runs"); with ``--scaled``
they are multiplied by the case's measured factor (``short_window_factor`` of the validation script), as the
validation's scaled figures are. A plan is an estimate to be checked by the runs it asks for. The base run's passes are checked against what the case's profile holds (``plan_surfaces``: two disjoint
stretches of 2·(domain) + 2·u_r·t each, the gap between them).

    python validation/deterministic_sampling_plan.py [--target 0.0135] [--scaled] [--out FILE]
                                  # every case -> validation/results/deterministic_sampling_plan.json and a table

The plan behind ``WINDOWS`` of validation/deterministic_validation.py (from the runs recorded before it, target
1.35 %): validation/results/deterministic_sampling_plan.json; with the measured factors (`--scaled`, target
1.5 %): ..._scaled.json (A ≈ 9 h on a longer profile, B ≈ 430 h, C 2.6 h, D 0.7 h).
"""

from __future__ import annotations

import json
import math
import platform
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import deterministic_validation as validation  # noqa: E402
from ehl_dataset.model.contact import ContactCase  # noqa: E402
from ehl_dataset.model.roughness import plan_surfaces  # noqa: E402
from ehl_dataset.solvers.deterministic import DeterministicOptions  # noqa: E402
from ehl_dataset.solvers.time_average import time_mean  # noqa: E402

OUT = validation.ROOT / "validation" / "results" / "deterministic_sampling_plan.json"


def optimal_passes(variances: np.ndarray, costs: np.ndarray, target_sem: float) -> tuple[np.ndarray, float]:
    """Giles' allocation: averaging passes N_l minimising Σ N_l c_l subject to Σ V_l/N_l = ``target_sem``² (V_l per-pass
    variances, c_l costs per pass [s]); returns (N_l, Σ N_l c_l [s])."""
    v, c = np.asarray(variances, float), np.asarray(costs, float)
    total = float(np.sum(np.sqrt(v * c)))
    passes = np.sqrt(v / c) * total / target_sem**2
    return passes, float(np.sum(passes * c))


def profile_capacity_passes(name: str) -> float:
    """Largest run length [passes] whose two surfaces read disjoint stretches of case ``name``'s profile
    (bisection on ``plan_surfaces(...).independent``; the domain, not the spacing, sets it)."""
    case = ContactCase.from_engineering(*validation.CASES[name])
    domain = DeterministicOptions().domain
    a = case.half_width
    x = np.linspace(domain[0] * a, domain[1] * a, 64)
    t_pass = (domain[1] - domain[0]) * a / case.u_r
    profile = validation.profile_for(name)
    lo, hi = 0.0, 1e5
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if plan_surfaces(case, x, mid * t_pass, profile).independent:
            lo = mid
        else:
            hi = mid
    return lo


def run_passes(run: dict) -> tuple[float, float]:
    """(averaging passes, all passes) of a recorded run."""
    per_pass = validation.steps_per_pass(run["inputs"], run["extra"])
    return validation.averaging_passes(run), run["extra"]["n_steps"] / per_pass


def plan_case(name: str, target: float = validation.SEM_TARGET, scaled: bool = False) -> dict | None:
    """The measured variances and costs of case ``name``'s levels and the allocation that meets ``target`` (relative
    standard error of μ at the finest spacing); None while the case's runs are incomplete."""
    row = validation.summarise_case(name)
    if row is None:
        return None
    coarse, middle, fine = validation.spacings(name)
    chain = (coarse, middle, fine) + validation.EXTRA_SPACINGS.get(name, ())
    runs = {n: json.loads(validation.run_path(name, n).read_text()) for n in chain}
    up = chain[chain.index(middle):]  # the long run and the spacings chained above it
    levels, variances, costs, passes_now, startup = [], [], [], [], []
    factor, _, measured_passes = validation.short_window_factor(name)
    base = runs[middle]
    mean = time_mean(np.asarray(base["extra"]["mu_series"])[base["extra"]["average_from_step"]:])
    for k, n in enumerate(up):
        averaging, total = run_passes(runs[n])
        if k == 0:
            se = mean.standard_error
            levels.append(f"beta/{n}")
        else:
            se = validation.paired_difference(runs[n], runs[up[k - 1]], "mu_series")[1]
            if scaled and factor is not None and averaging < measured_passes:
                se *= factor
            levels.append(f"beta/{n} - beta/{up[k - 1]}")
        variances.append(se**2 * averaging)
        costs.append(runs[n]["wall_time_s"] / total)
        passes_now.append(averaging)
        startup.append(total - averaging)
    mu_fine = row["mu"][f"beta/{up[-1]}"]
    eps = target * mu_fine
    passes, cost = optimal_passes(np.array(variances), np.array(costs), eps)
    passes = np.maximum(passes, validation.SHORT_AVERAGE_PASSES)  # a window never shorter than the validation's
    cost = float(np.sum((passes + np.array(startup)) * np.array(costs)))
    sem_now = math.sqrt(sum(v / p for v, p in zip(variances, passes_now))) / mu_fine
    capacity = profile_capacity_passes(name)
    return {"case": name, "mu_fine": mu_fine, "finest": f"beta/{up[-1]}", "target_relative_sem": target,
            "relative_sem_now": sem_now, "levels": levels, "scaled": scaled, "short_window_factor": factor,
            "per_pass_variance": variances, "cost_per_pass_s": costs, "startup_passes": startup,
            "averaging_passes_now": passes_now, "averaging_passes_planned": passes.tolist(),
            "relative_sem_planned": math.sqrt(sum(v / p for v, p in zip(variances, passes))) / mu_fine,
            "wall_time_now_s": float(sum(runs[n]["wall_time_s"] for n in up)),
            "wall_time_planned_s": cost,
            "profile_points": validation.profile_points(name),
            "profile_capacity_passes": capacity,
            "longer_profile_needed": bool(passes[0] + startup[0] > capacity)}


def main(argv=None) -> int:
    import argparse
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--target", type=float, default=validation.SEM_TARGET,
                        help="relative standard error of μ at the finest spacing to plan for (default 0.015)")
    parser.add_argument("--out", type=Path, default=OUT, help="results file (JSON)")
    parser.add_argument("--scaled", action="store_true",
                        help="scale the short windows' standard errors by the measured factors")
    args = parser.parse_args(argv)
    rows = [r for r in (plan_case(name, args.target, args.scaled) for name in validation.CASES) if r is not None]
    command = "python validation/deterministic_sampling_plan.py" + (
        f" --target {args.target:g}" if args.target != validation.SEM_TARGET else "") + (
        " --scaled" if args.scaled else "") + (
        f" --out {args.out}" if args.out != OUT else "")
    args.out.write_text(json.dumps({"command": command, "machine": platform.platform(), "rows": rows},
                                   indent=1) + "\n")
    print("| case | sem of μ fine now | passes now (base, differences up) | passes planned | core-hours, every run of the plan | "
          "profile holds [passes] |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        now = ", ".join(f"{p:.1f}" for p in r["averaging_passes_now"])
        planned = ", ".join(f"{p:.1f}" for p in r["averaging_passes_planned"])
        print(f"| {r['case']} | {100 * r['relative_sem_now']:.2f} % | {now} | {planned} | "
              f"{r['wall_time_planned_s'] / 3600:.2f} | {r['profile_capacity_passes']:.0f}"
              f"{' (longer profile needed)' if r['longer_profile_needed'] else ''} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
