"""μ–λ̄ sweeps of the deterministic mixed-EHL reference on the flank-like roughness (``flank_ground``): does the
reference show the measured trends (μ rising as λ̄ falls below ≈ 1; μ falling as the rolling speed rises at λ̄ < 0.5)
once the roughness has the short wavelengths of ground flanks?

Sweeps (ATF; the deterministic model is isothermal):

* ``rqA``: roughness sweep at case A's conditions (0.5 GPa, r_eq 5 mm, u_r 5 m/s, SR 0.3, 90 °C; Eyring-unsaturated,
  X_h ≈ 3.6), Rq1 = Rq2 scaled so that λ̄ goes from ≈ 3 to ≈ 0.1;
* ``rqS``: the same at an Eyring-saturated condition of the same Hertz width: case J's load, speed, sliding and
  temperature at a quarter of its radius (1.0 GPa, 2.5 mm, 2 m/s, SR 0.4, 50 °C; X_h ≈ 1,450, a = 44 µm). J itself
  (a = 177 µm) would cost 16× per run: ≈ 60 h per point at λ_s/16 on one core;
* ``uA``: rolling-speed sweep at case A's load, sliding and temperature with Rq1 = Rq2 = 0.5 µm (λ̄ < 0.5 throughout).

Every point runs at grid spacings Δx = λ_s/4, λ_s/8, λ_s/16 (λ_s = 2.5 µm the profile's short cut-off), all laid out
for the same run length (``LAYOUT_PASSES``) so that the spacings read the same roughness at the same times and their
time-window means are paired. Each run writes one small segment file
validation/results/flank_reference/<point>_ls<n>.json: μ, its standard error, the asperity load share, λ̄, the central
and minimum film, the smooth-surface μ of the same contact (the steady start of the run), residuals, converged flag
and message, wall time, model version, roughness name and sha256, and the means of μ and share over consecutive
quarter-pass time windows. A run saves its state every 10 min in validation/results/flank_reference/checkpoints/
and continues from it when started again (the same result as an uninterrupted run, to the linear solver's
tolerance); the checkpoint is removed when the segment is written.

    python validation/flank_reference/run_sweeps.py --estimate      # cost of every run from a short coarse run
    python validation/flank_reference/run_sweeps.py --run           # the queue, cheapest first (resumable)
    python validation/flank_reference/run_sweeps.py --summary       # table of the segments written so far
    python validation/flank_reference/run_sweeps.py --queue         # remaining runs, estimated cost, cheapest first
    python validation/flank_reference/run_sweeps.py --run --spacings 16 --only rqA   # a part of the queue

A point's finest spacing is not queued when the two before it agree within 1 % of μ and carry no asperity load
(``converged_before``; ``--all-spacings`` queues it anyway, ``--queue`` lists what it leaves out).

Run the queue in the background on one core:

    nohup nice -n 5 env OMP_NUM_THREADS=1 NUMBA_NUM_THREADS=1 \\
        python validation/flank_reference/run_sweeps.py --estimate --run > <log outside the tree> 2>&1 &

The same command resumes it: finished segments are skipped, an interrupted run continues from its checkpoint. A run
that raises writes <run>.error.json (the error) and is tried again on the next start; a run that does not converge
writes its segment with converged false and the solver's message. Checkpoints are portable (a NumPy archive of plain
data, no pickle, without the factorised preconditioner: ``FileCheckpoint(..., portable=True)``), a few hundred kB,
and are committed with the segments, so a run in progress survives a change of machine: commit
validation/results/flank_reference/ while it runs. A run continued from one differs from an uninterrupted run only at
the linear solver's tolerance (tests/ehl_dataset/test_deterministic.py).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

from ehl_dataset.dataset.checkpoint import FileCheckpoint
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import named_profile
from ehl_dataset.solvers.deterministic import MODEL_VERSION, DeterministicOptions, solve_deterministic
from ehl_dataset.solvers.time_average import time_mean

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "results" / "flank_reference"
CHECKPOINTS = RESULTS / "checkpoints"
ESTIMATES = RESULTS / "cost_estimates.json"

PROFILE = "flank_ground"
LUBRICANT = "atf"
CONDITIONS = {"A": (0.5, 5.0, 5.0, 0.3, 90.0), "S": (1.0, 2.5, 2.0, 0.4, 50.0)}
"""p_h [GPa], r_eq [mm], u_r [m/s], SR, T [°C]: validation case A (Eyring-unsaturated, X_h 3.6) and S (saturated,
X_h 1,450; X_h = η(p_h)|u_s|/(τ0 h_min,DH), ehl_dataset.solvers.planner.dimensionless_numbers); both a = 44 µm."""

POINTS = (
    [{"sweep": "rqA", "conditions": CONDITIONS["A"], "rq_um": rq} for rq in (0.033, 0.1, 0.33, 1.0)]
    + [{"sweep": "rqS", "conditions": CONDITIONS["S"], "rq_um": rq} for rq in (0.028, 0.084, 0.28, 0.84)]
    + [{"sweep": "uA", "conditions": (0.5, 5.0, u, 0.3, 90.0), "rq_um": 0.5} for u in (1.0, 2.0, 5.0, 10.0)]
)
"""The sweep points: λ̄ ≈ 3, 1, 0.3, 0.1 (rqA: λ̄ 0.33 at Rq 0.3 µm; rqS: λ̄ 0.28 at Rq 0.3 µm; λ̄ ∝ 1/Rq) and
u_r 1, 2, 5, 10 m/s at Rq 0.5 µm (uA; λ̄ ≈ 0.06–0.32). A gear-typical contact (1.2 GPa, r_eq 20 mm, a ≈ 420 µm) is
not among them: resolved whole it has 2,715 nodes and 86,848 time steps at λ_s/4, ≈ 100 h of one core at the
1.55 ms per node and step of case A's finished λ_s/4 runs (≈ 150 h at λ_s/8); the periodic-window route at this
profile's resolution would be far cheaper."""

SPACINGS = (4, 8, 16)
"""Grid spacings Δx = λ_s/n."""
PASSES = {4: 8.0, 8: 3.0, 16: 2.5}
"""Run length [passes] per spacing: ramp 0.5 + start-up 1 + averaging. The coarse run carries the long window (6.5
passes); the finer runs enter through their paired difference to it over their 1.5 and 1 pass (the multilevel
estimator of validation/deterministic_validation.py)."""
LAYOUT_PASSES = 8.0
"""Run length the roughness is laid out for, the same at every spacing (paired runs)."""
WINDOW_PASSES = 0.25
"""Width [passes] of the time windows whose means a segment records."""
ESTIMATE_S = 60.0
"""Wall time [s] of the short coarse run that measures a point's cost."""


def portable(text: str) -> str:
    """``text`` with this checkout's absolute path replaced by paths relative to the repository (results are
    committed and read on other machines)."""
    return text.replace(str(ROOT.parent) + "/", "")


def point_name(point: dict) -> str:
    p, r, u, sr, t = point["conditions"]
    return f"{point['sweep']}_p{p:g}_r{r:g}_u{u:g}_sr{sr:g}_T{t:g}_rq{point['rq_um']:g}"


def run_name(point: dict, n: int) -> str:
    return f"{point_name(point)}_ls{n}"


def setup(point: dict, n: int, max_passes: float | None = None):
    """(case, lubricant state, options, profile) of one run."""
    p, r, u, sr, t = point["conditions"]
    rq = point["rq_um"]
    case = ContactCase.from_engineering(p, r, u, sr, t, rq, rq)
    state = load_lubricant(LUBRICANT).state(t + 273.15)
    profile = named_profile(PROFILE)
    passes = PASSES[n] if max_passes is None else max_passes
    options = DeterministicOptions(dx_m=profile.resolution_length / n, max_passes=passes,
                                   min_average_passes=max(passes - 1.5, 0.5), mu_sem_target=1.0,
                                   layout_passes=LAYOUT_PASSES, wide="resolve")
    return case, state, options, profile


def window_means(t: np.ndarray, values: np.ndarray, pass_time: float) -> list:
    """Means of ``values`` over consecutive windows of WINDOW_PASSES passes (time ``t`` [s]), from t = 0."""
    if t.size == 0:
        return []
    index = np.floor(t / (WINDOW_PASSES * pass_time)).astype(int)
    out = []
    for k in np.unique(index):
        sel = index == k
        out.append([float(k * WINDOW_PASSES), float(np.mean(values[sel])), int(sel.sum())])
    return out


def segment(point: dict, n: int, result, wall_s: float, case) -> dict:
    """The small record of one finished (or failed) run."""
    e = result.extra
    first = int(e.get("average_from_step", 0))
    t = np.asarray(e.get("t_series_s", []), dtype=float)
    mu = np.asarray(e.get("mu_series", []), dtype=float)
    share = np.asarray(e.get("share_series", []), dtype=float)
    p, r, u, sr, temp = point["conditions"]
    x = result.x if result.x is not None else np.zeros(2)
    pass_time = (float(x[-1] - x[0]) if x.size > 1 else math.nan) / case.u_r
    return {
        "point": point_name(point), "sweep": point["sweep"], "spacing_divisor": n,
        "inputs": {"p_h_gpa": p, "r_eq_mm": r, "u_r_m_s": u, "sr": sr, "temp_c": temp, "rq1_um": point["rq_um"],
                   "rq2_um": point["rq_um"], "lubricant": LUBRICANT},
        "dx_m": e.get("dx_m"), "n_nodes": e.get("n_nodes"), "n_steps": e.get("n_steps"),
        "passes": PASSES[n], "layout_passes": LAYOUT_PASSES,
        "mu": result.mu, "mu_sem": result.mu_sem, "asperity_load_share": result.asperity_load_share,
        "asperity_load_share_sem": e.get("asperity_load_share_sem"), "lambda_bar": result.lambda_bar,
        "h_central_m": result.h_central, "h_min_m": result.h_min, "smooth_mu": e.get("smooth_mu"),
        "smooth_h_min_m": e.get("smooth_h_min_m"), "residuals": result.residuals,
        "converged": bool(result.converged), "message": portable(result.message),
        "time_limited": e.get("time_limited"),
        "wall_time_s": wall_s, "model_version": e.get("model_version", MODEL_VERSION),
        "roughness_name": e.get("roughness_name"), "roughness_sha256": e.get("roughness_sha256"),
        "continued_from": e.get("continued_from"),
        "window_passes": WINDOW_PASSES,
        "mu_windows": window_means(t[first:], mu[first:], pass_time) if mu.size else [],
        "share_windows": window_means(t[first:], share[first:], pass_time) if share.size else [],
    }


def estimate(points=POINTS) -> dict:
    """Cost of each run [s] from a short coarse run: seconds per node-step at λ_s/4, times nodes × steps of each
    spacing (steps per pass ∝ nodes at a fixed Courant number, so a halving of Δx costs ≈ 4× per pass)."""
    record = json.loads(ESTIMATES.read_text()) if ESTIMATES.exists() else {}
    if record.get("model_version") != MODEL_VERSION:
        record = {"model_version": MODEL_VERSION, "estimate_run_s": ESTIMATE_S, "points": {}}
    for point in points:
        name = point_name(point)
        if name in record["points"]:
            continue
        case, state, options, profile = setup(point, SPACINGS[0])
        start = time.perf_counter()
        result = solve_deterministic(case, state, Effects.full(), options, roughness=profile, time_limit_s=ESTIMATE_S)
        wall = time.perf_counter() - start
        e = result.extra
        nodes, steps = e.get("n_nodes"), e.get("n_steps")
        if not nodes or not steps:
            record["points"][name] = {"failed": result.message, "wall_s": wall}
        else:
            per = wall / (nodes * steps)
            steps_per_pass = nodes / options.courant
            runs = {}
            for n in SPACINGS:
                k = n / SPACINGS[0]
                runs[str(n)] = per * (nodes * k) * (steps_per_pass * k) * PASSES[n]
            record["points"][name] = {"s_per_node_step": per, "n_nodes_coarse": nodes, "steps_done": steps,
                                      "estimate_s": runs, "passes": {str(n): PASSES[n] for n in SPACINGS},
                                      "lambda_bar": result.lambda_bar, "short_run_message": result.message}
        RESULTS.mkdir(parents=True, exist_ok=True)
        ESTIMATES.write_text(json.dumps(record, indent=1))
        print(f"estimate {name}: {record['points'][name]}", flush=True)
    return record


COST_SOURCE_FACTOR = 3.0
"""Factor on the 60 s estimate of a run whose point has no finished run yet: the short run measures the roughness
ramp, where asperities have not yet met (on the first two points the finished λ_s/4 runs took 0.34× and ≈ 3× the
estimate: light and contact-dominated)."""


def run_cost(point: dict, n: int, record: dict) -> float:
    """Estimated wall time [s] of a run: from the finished run of the same point at the coarsest spacing done
    (× (n/n0)² for nodes and steps per pass, × the passes ratio), else COST_SOURCE_FACTOR × the 60 s estimate."""
    for n0 in SPACINGS:
        path = RESULTS / f"{run_name(point, n0)}.json"
        if n0 < n and path.exists():
            done = json.loads(path.read_text())
            return done["wall_time_s"] * (n / n0) ** 2 * PASSES[n] / PASSES[n0]
    info = record["points"].get(point_name(point), {})
    base = info.get("estimate_s", {}).get(str(n), math.inf)
    return COST_SOURCE_FACTOR * base * PASSES[n] / info.get("passes", {}).get(str(n), PASSES[n])


CONVERGED_STEP = 0.01
"""A point counts as grid-converged when its last paired step is below this fraction of μ (and below two of its
standard errors or this fraction, whichever is larger) and no asperity load was found: its finest spacing is then
not queued (``--all-spacings`` queues it anyway)."""


def converged_before(point: dict, n: int) -> str:
    """Why the run of ``point`` at λ_s/n is not needed ('' if it is): the two spacings before it have run, carry
    no asperity load (share ≤ 0.01) and their paired step is within CONVERGED_STEP of μ."""
    previous = [m for m in SPACINGS if m < n][-2:]
    if len(previous) < 2:
        return ""
    runs = [RESULTS / f"{run_name(point, m)}.json" for m in previous]
    if not all(path.exists() for path in runs):
        return ""
    coarse, fine = (json.loads(path.read_text()) for path in runs)
    step, sem, _ = paired_step(coarse, fine)
    if not (math.isfinite(step) and max(coarse["asperity_load_share"], fine["asperity_load_share"]) <= 0.01):
        return ""
    if abs(step) <= CONVERGED_STEP * abs(fine["mu"]) and abs(step) <= max(2.0 * sem, CONVERGED_STEP * abs(fine["mu"])):
        return (f"lambda_s/{previous[0]} -> /{previous[1]} step {step:+.5f} +- {sem:.5f}, no asperity load: "
                f"grid-converged")
    return ""


def queue(record: dict, spacings=SPACINGS, only: str | None = None, all_spacings: bool = False) -> list:
    """(estimated s, point, n) of every run not yet written (of ``spacings``, of the points whose name contains
    ``only``; without ``all_spacings`` not the runs :func:`converged_before` finds unneeded), cheapest first; points
    whose estimate failed go last."""
    items = [(run_cost(point, n, record), point, n) for point in POINTS for n in spacings
             if not (RESULTS / f"{run_name(point, n)}.json").exists() and (only is None or only in point_name(point))
             and (all_spacings or not converged_before(point, n))]
    return sorted(items, key=lambda item: item[0])


def run(record: dict, spacings=SPACINGS, only: str | None = None, all_spacings: bool = False) -> None:
    tried = set()
    while True:  # the queue is re-ordered after every run: a finished coarse run prices the finer ones
        pending = [item for item in queue(record, spacings, only, all_spacings)
                   if run_name(item[1], item[2]) not in tried]
        if not pending:
            return
        cost, point, n = pending[0]
        name = run_name(point, n)
        tried.add(name)
        path = RESULTS / f"{name}.json"
        case, state, options, profile = setup(point, n)
        checkpoint = FileCheckpoint(CHECKPOINTS / f"{name}.npz", portable=True)
        print(f"run {name} (estimate {cost:.0f} s) started {time.strftime('%H:%M:%S')}", flush=True)
        start = time.perf_counter()
        try:
            result = solve_deterministic(case, state, Effects.full(), options, roughness=profile,
                                         checkpoint=checkpoint)
        except Exception as error:  # one run's error must not stop the queue; its record says why
            message = portable(f"{type(error).__name__}: {error}")
            (RESULTS / f"{name}.error.json").write_text(json.dumps(
                {"run": name, "error": message, "model_version": MODEL_VERSION,
                 "wall_time_s": time.perf_counter() - start}, indent=1))
            print(f"error {name}: {message} (retried on the next start)", flush=True)
            continue
        wall = time.perf_counter() - start
        seg = segment(point, n, result, wall, case)
        path.write_text(json.dumps(seg, indent=1))
        if result.converged:
            checkpoint.remove()
        print(f"done {name}: mu {seg['mu']:.5f} ± {seg['mu_sem']:.5f}, share {seg['asperity_load_share']:.3f}, "
              f"lambda {seg['lambda_bar']:.3g}, smooth mu {seg['smooth_mu']}, converged {seg['converged']} "
              f"({seg['message']}), {wall:.0f} s", flush=True)


def paired_step(coarse: dict, fine: dict) -> tuple[float, float, int]:
    """(mean, standard error, windows) of μ_fine − μ_coarse over the time windows both runs averaged (the runs read
    the same roughness at the same times: LAYOUT_PASSES is shared), the error autocorrelation-corrected."""
    a = {w[0]: w[1] for w in coarse["mu_windows"]}
    b = {w[0]: w[1] for w in fine["mu_windows"]}
    common = sorted(set(a) & set(b))
    if len(common) < 2:
        return math.nan, math.nan, len(common)
    diff = time_mean(np.array([b[t] - a[t] for t in common]))
    return diff.mean, diff.standard_error, len(common)


def richardson(mu_coarse: float, step1: tuple[float, float], step2: tuple[float, float]) -> str:
    """The grid limit of μ from three spacings halving each time, by Richardson extrapolation of the paired steps
    s1 (coarse → middle) and s2 (middle → fine): observed order p = log2(s1/s2) and μ∞ = μ_fine + s2/(s1/s2 − 1),
    where the steps shrink (s1/s2 > 1.2 with both of one sign and s2 resolved); otherwise says why not."""
    (s1, e1), (s2, e2) = step1, step2
    fine = mu_coarse + s1 + s2
    if not (math.isfinite(s1) and math.isfinite(s2)) or abs(s2) <= 2.0 * e2 or s1 * s2 <= 0.0 or s1 / s2 <= 1.2:
        return (f"no Richardson limit (steps {s1:+.5f} +- {e1:.5f}, {s2:+.5f} +- {e2:.5f}: not shrinking, or the last "
                f"one not resolved); multilevel estimate at the finest spacing {fine:.5f}")
    ratio = s1 / s2
    limit = fine + s2 / (ratio - 1.0)
    return f"observed order {math.log2(ratio):.2f}, Richardson limit {limit:.5f} (finest spacing {fine:.5f})"


def summary() -> None:
    rows = [json.loads(p.read_text()) for p in sorted(RESULTS.glob("*_ls*.json")) if not p.name.endswith(".error.json")]
    by_point = {}
    for r in rows:
        by_point.setdefault(r["point"], {})[r["spacing_divisor"]] = r
    for name, runs in sorted(by_point.items()):
        spacings = sorted(runs)
        steps = []
        for coarse, fine in zip(spacings, spacings[1:]):
            mean, sem, count = paired_step(runs[coarse], runs[fine])
            steps.append((mean, sem))
            print(f"{name}: lambda_s/{coarse} -> /{fine}: paired step {mean:+.5f} +- {sem:.5f} over {count} windows")
        if len(steps) == 2:
            print(f"{name}: {richardson(runs[spacings[0]]['mu'], *steps)}")
    print(f"{'point':48s} {'n':>3s} {'lambda':>7s} {'mu':>8s} {'sem':>8s} {'share':>6s} {'smooth':>8s} {'conv':>5s} "
          f"{'wall_s':>7s}")
    for r in sorted(rows, key=lambda r: (r["sweep"], r["point"], r["spacing_divisor"])):
        print(f"{r['point']:48s} {r['spacing_divisor']:3d} {r['lambda_bar']:7.3f} {r['mu']:8.5f} {r['mu_sem']:8.5f} "
              f"{r['asperity_load_share']:6.3f} {r['smooth_mu'] or math.nan:8.5f} {str(r['converged']):>5s} "
              f"{r['wall_time_s']:7.0f}")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--estimate", action="store_true", help="measure the cost of each point (cached)")
    parser.add_argument("--run", action="store_true", help="run the queue, cheapest first (resumable)")
    parser.add_argument("--summary", action="store_true", help="print the segments written so far")
    parser.add_argument("--queue", action="store_true", help="print the remaining runs with their estimated cost")
    parser.add_argument("--spacings", type=int, nargs="+", choices=SPACINGS, default=list(SPACINGS),
                        help="run only these spacings λ_s/n (e.g. to split the queue across processes)")
    parser.add_argument("--only", default=None, help="run only the points whose name contains this text")
    parser.add_argument("--all-spacings", action="store_true",
                        help="queue the finest spacing of points already grid-converged too (CONVERGED_STEP)")
    args = parser.parse_args(argv)
    if not (args.estimate or args.run or args.summary or args.queue):
        parser.error("give --estimate, --run, --queue and/or --summary")
    record = estimate() if args.estimate or args.run or args.queue else None
    if args.queue:
        total = 0.0
        for cost, point, n in queue(record, args.spacings, args.only, args.all_spacings):
            total += cost
            print(f"{run_name(point, n):52s} {cost / 3600:6.2f} h   cumulative {total / 3600:7.1f} h")
        for point in POINTS:
            for n in args.spacings:
                why = "" if args.all_spacings else converged_before(point, n)
                if why and not (RESULTS / f"{run_name(point, n)}.json").exists():
                    print(f"{run_name(point, n):52s} not queued: {why}")
    if args.run:
        run(record, args.spacings, args.only, args.all_spacings)
    if args.summary:
        summary()
    return 0


if __name__ == "__main__":
    sys.exit(main())
