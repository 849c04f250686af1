"""Point-like rough contacts (a Hertz half width of the order of the roughness correlation length β) at light load:
the smooth model, the film-law model and the asperity closure against the deterministic reference.

The contacts are those of a gear's contact-line ends (the paper's design D at 10 m/s, 90 °C, Rq 0.4/0.4 µm, the
baseline roughness): r_eq 12.4 mm, p_h 37, 74 and 222 MPa (a/β ≈ 0.54, 1.1, 3.2), SR 0.054 and 0.3. The deterministic
reference runs the whole contact on the paper's domain (−2.5a, 1.5a), like the steady solver, with a spacing of
min(a, β)/``--nodes`` (its default grid rule, β/8 at ``fast``, puts about 8 nodes across a contact of a/β 0.5), the
averaging of the ``fast`` level extended to ``--passes`` passes and a 3 % standard-error target. Writes
validation/results/narrow_point_contacts.json.

    python validation/narrow_point_contacts.py
    python validation/narrow_point_contacts.py --cases 37:0.054 --nodes 32   # the grid check
    python validation/narrow_point_contacts.py --cheap-only                  # steady models only, domain study
    python validation/narrow_point_contacts.py --factorial-check             # the continuous film on the factorial

The film law is recorded as the model runs it (on these contacts with the film continuous at the zone edges) and
with the film steps of film-law-2026.11-3 (``film_law_with_film_steps``).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time
from pathlib import Path

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solver import SOLVER_VERSION, solve_contact
from ehl_dataset.solvers.deterministic import deterministic_options
from ehl_dataset.solvers.film_law_model import solve_film_law
from ehl_dataset.solvers.homogenised import HomogenisedOptions
from ehl_dataset.solvers.planner import plan_effects
from ehl_dataset.solvers.problem import resolve_contact

R_EQ_M, U_R_M_S, TEMPERATURE_K, RQ_M = 0.0124162, 9.987, 363.15, 4e-7
P_H_PA = {"37": 36856271.7, "74": 74e6, "222": 222e6}
DEFAULT_CASES = ["37:0.054", "37:0.3", "74:0.054", "74:0.3", "222:0.054", "222:0.3"]
OUT = Path(__file__).resolve().parent / "results" / "narrow_point_contacts.json"


def run_case(key: str, sr: float, nodes: float, passes: float, level: str, deterministic: bool = True) -> dict:
    """All models on one contact; the deterministic run's μ, its standard error and asperity share (not run with
    ``deterministic`` False)."""
    lub = load_lubricant("atf")
    case = ContactCase(P_H_PA[key], R_EQ_M, U_R_M_S, sr, TEMPERATURE_K, RQ_M, RQ_M)
    profile = baseline_profile()  # the contacts' baseline roughness (module docstring), not the package's default
    beta = profile.correlation_length
    plan = plan_effects(case, lub, level, beta)
    nums = plan.reasons["numbers"]
    row = {"p_h_pa": case.p_h, "sr": sr, "a_m": case.half_width, "a_over_beta": case.half_width / beta,
           "lambda_bar": nums["lambda_bar"], "roughness_parameter": nums["roughness_parameter"],
           "planner_model_decision": plan.reasons["decisions"]["model"], "planner_roughness": plan.roughness}
    for name, kwargs in (("smooth", {"model": "smooth"}),
                         ("auto", {"model": "auto"}),
                         ("film_law", {"model": "homogenised", "homogenised": HomogenisedOptions(closure="film_law")}),
                         ("asperity", {"model": "homogenised", "homogenised": HomogenisedOptions(closure="asperity")})):
        result = solve_contact(case, lub, level, "isothermal", roughness=profile, **kwargs)
        row[name] = {"mu": result.mu, "asperity_load_share": result.asperity_load_share,
                     "h_central_m": result.h_central, "converged": result.converged,
                     **{k: result.extra[k] for k in ("mu_couette", "mu_poiseuille", "mu_outside_zone",
                                                     "fed_central_film_m", "smooth_central_film_m")
                        if k in result.extra}}
    problem = resolve_contact(case, lub, level, "isothermal", model="homogenised", roughness=profile,
                              homogenised=HomogenisedOptions(closure="film_law"))
    steps = solve_film_law(problem.case, problem.state, problem.steady_level, problem.plan, profile,
                           problem.homogenised.boundary_film_m, continuous_film=False)
    row["film_law_with_film_steps"] = {"mu": steps.mu, **{k: steps.extra[k] for k in (
        "mu_couette", "mu_poiseuille", "mu_outside_zone")}}
    if not deterministic:
        return row
    dx = min(case.half_width, beta) / nodes
    options = deterministic_options("fast", dx_m=dx, max_passes=passes, layout_passes=max(passes, 40.0),
                                    mu_sem_target=0.03, wide="resolve")
    cpu = time.process_time()
    result = solve_contact(case, lub, "fast", "isothermal", model="deterministic", deterministic=options,
                           roughness=profile)
    extra = result.extra
    row["deterministic"] = {
        "mu": result.mu, "mu_sem": result.mu_sem, "mu_std": result.mu_std, "asperity_load_share": result.asperity_load_share,
        "asperity_load_share_sem": extra.get("asperity_load_share_sem"), "h_central_m": result.h_central,
        "h_min_m": result.h_min, "converged": result.converged, "message": result.message, "dx_m": dx,
        "nodes_per_min_a_beta": nodes, "max_passes": passes, "n_nodes": extra.get("n_nodes"),
        "n_steps": extra.get("n_steps"), "model_version": extra.get("model_version"),
        "cpu_s": time.process_time() - cpu}
    return row


def domain_study(level: str) -> list[dict]:
    """The smooth model on the lightest contact (37 MPa, SR 0.054) with the inlet end of the domain moved from the
    paper's −2.5a upstream: how much the paper's domain starves a contact this light."""
    from ehl_dataset.model.film_formulas import moes_central_film
    from ehl_dataset.solvers.levels import level_settings

    lub = load_lubricant("atf")
    case = ContactCase(P_H_PA["37"], R_EQ_M, U_R_M_S, 0.054, TEMPERATURE_K, RQ_M, RQ_M)
    state = lub.state(case.temperature)
    moes = float(moes_central_film(state.eta0, case.u_r, state.alpha1, case.e_reduced, case.r_eq,
                                   case.load_per_length))
    rows = []
    for x_start in (-2.5, -5.0, -10.0, -20.0, -40.0):
        steady = level_settings(level).steady.with_domain(x_start, 1.5)
        result = solve_contact(case, lub, steady, "smooth")
        rows.append({"x_start_over_a": x_start, "mu": result.mu, "h_central_m": result.h_central,
                     "converged": result.converged, "moes_central_film_m": moes})
    return rows


def factorial_check() -> dict:
    """The film law at ``fast`` with the smooth film outside the zone (as on the factorial) and with the continuous
    film, on the factorial points that have a deterministic reference at ``fast`` (benchmarks/results/
    ehl_mixed_{random200,corners}_fast_deterministic.json; SR > 0, rough): how much the continuous film would move μ
    there, and the errors against the reference with and without it."""
    import numpy as np

    lub = load_lubricant("atf")
    profile = baseline_profile()
    root = Path(__file__).resolve().parents[1]
    points = []
    for name in ("random200", "corners"):
        data = json.loads((root / "benchmarks" / "results" / f"ehl_mixed_{name}_fast_deterministic.json").read_text())
        for row in data["rows"]:
            p_h, r_eq, u_r, sr, temp_c, rq1, rq2 = row["case"]
            if not row.get("converged") or row.get("mu") is None or sr == 0 or rq1 + rq2 == 0:
                continue
            case = ContactCase.from_engineering(p_h, r_eq, u_r, sr, temp_c, rq1, rq2)
            # the baseline profile the deterministic reference was computed on, not the package's default
            problem = resolve_contact(case, lub, "fast", "isothermal", model="homogenised", roughness=profile,
                                      homogenised=HomogenisedOptions(closure="film_law"))
            args = (problem.case, problem.state, problem.steady_level, problem.plan, profile,
                    problem.homogenised.boundary_film_m)
            steps = solve_film_law(*args, continuous_film=False)
            joined = solve_film_law(*args, continuous_film=True)
            points.append({"sample": name, "case": row["case"], "a_over_beta": steps.extra["a_over_beta"],
                           "deterministic": row["mu"], "smooth_film_outside": steps.mu, "continuous_film": joined.mu})
    a = np.array([[p["smooth_film_outside"], p["continuous_film"], p["deterministic"], p["a_over_beta"]]
                  for p in points])
    change = np.abs(a[:, 1] / a[:, 0] - 1.0)
    summary = {}
    for label, mask in (("narrow", a[:, 3] < 15.0), ("wide", a[:, 3] >= 15.0), ("all", a[:, 3] > 0.0)):
        summary[label] = {"points": int(mask.sum()), "change_median": float(np.median(change[mask])),
                          "change_max": float(change[mask].max()),
                          "error_median_smooth_film": float(np.median(np.abs(a[mask, 0] / a[mask, 2] - 1.0))),
                          "error_median_continuous_film": float(np.median(np.abs(a[mask, 1] / a[mask, 2] - 1.0))),
                          "error_p90_smooth_film": float(np.percentile(np.abs(a[mask, 0] / a[mask, 2] - 1.0), 90)),
                          "error_p90_continuous_film": float(np.percentile(np.abs(a[mask, 1] / a[mask, 2] - 1.0),
                                                                            90))}
    worst = points[int(np.argmax(change))]
    return {"summary": summary, "largest_change": {**worst, "relative_change": float(change.max())},
            "smallest_a_over_beta": float(a[:, 3].min())}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", nargs="+", default=DEFAULT_CASES, help="P:SR, P one of 37, 74, 222 (MPa)")
    parser.add_argument("--nodes", type=float, default=16.0, help="deterministic spacing min(a, beta)/NODES")
    parser.add_argument("--passes", type=float, default=30.0, help="longest averaging window [passes]")
    parser.add_argument("--level", default="standard", help="level of the steady models")
    parser.add_argument("--out", type=Path, default=OUT)
    parser.add_argument("--factorial-check", action="store_true",
                        help="only the film law with and without the continuous film on the factorial points that "
                             "have a deterministic reference (a few minutes)")
    parser.add_argument("--cheap-only", action="store_true",
                        help="recompute the steady models only, keeping each case's recorded deterministic run")
    args = parser.parse_args(argv)
    record = json.loads(args.out.read_text()) if args.out.exists() else {"runs": {}}
    record.update({"solver_version": SOLVER_VERSION, "machine": platform.machine(), "cpus": os.cpu_count(),
                   "command": "python validation/narrow_point_contacts.py"})
    if args.factorial_check:
        record["factorial_check"] = factorial_check()
        print(json.dumps(record["factorial_check"]["summary"], indent=1))
        args.out.write_text(json.dumps(record, indent=1, default=float) + "\n")
        return 0
    if args.cheap_only:
        record["smooth_domain_study"] = domain_study(args.level)
        for row in record["smooth_domain_study"]:
            print(f"domain from {row['x_start_over_a']:g} a: smooth mu {row['mu']:.5f}, h_c "
                  f"{row['h_central_m'] * 1e6:.3f} um (Moes {row['moes_central_film_m'] * 1e6:.2f} um)")
    for spec in args.cases:
        key, sr = spec.split(":")
        name = f"{key}MPa_sr{sr}_n{args.nodes:g}"
        row = run_case(key, float(sr), args.nodes, args.passes, args.level, deterministic=not args.cheap_only)
        if args.cheap_only:
            row["deterministic"] = record["runs"][name]["deterministic"]
        record["runs"][name] = row
        det = row["deterministic"]
        print(f"{spec}: a/beta {row['a_over_beta']:.2f} alpha {row['roughness_parameter']:.3g} lambda "
              f"{row['lambda_bar']:.3g} | smooth {row['smooth']['mu']:.5f} auto {row['auto']['mu']:.5f} film law "
              f"{row['film_law']['mu']:.5f} (with the film steps {row['film_law_with_film_steps']['mu']:.5f}) "
              f"asperity {row['asperity']['mu']:.5f} "
              f"(share {row['asperity']['asperity_load_share']:.2f}) | deterministic {det['mu']:.5f} "
              f"± {det['mu_sem'] or float('nan'):.5f} share {det['asperity_load_share']:.2f} ({det['cpu_s']:.0f} s)",
              flush=True)
        args.out.parent.mkdir(parents=True, exist_ok=True)
        args.out.write_text(json.dumps(record, indent=1, default=float) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
