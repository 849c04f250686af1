"""How much thicker is the film of a rough contact than the smooth one? The feeding law of the periodic window.

A periodic window of the Hertzian centre (ehl_dataset.solvers.periodic_window) needs the mean lubricant content the
inlet delivers, which it cannot compute itself (docs/explanation/mixed-regime.md, "Periodic window"). This script
measures it on resolved deterministic runs: the time-averaged content film θ·max(h, h_b) over the centre |x| < 0.2 a
against the steady smooth solver's film over the same band, as the excess Δ = h̄_rough − h_smooth in units of the
composite roughness σ = √(Rq1² + Rq2²), against H = h_smooth/σ and the length of the smooth inlet build-up zone in correlation lengths,
L_in/β = a·(h_smooth r_eq/a²)^(2/3)/β, and fits

    Δ/σ = c·(L_in/β)^k / (H + d)        (→ c (L_in/β)^k σ²/h_smooth for thick films, → c (L_in/β)^k/d σ as H → 0)

by least squares (scipy.optimize.curve_fit), with leave-one-group-out errors; the one-variable law c/(H + d)
(k = 0) is fitted too, for comparison.

Runs: roughness sweeps at fixed load, speed, sliding and temperature (``FAMILIES``: case A's conditions, a/β 2.9,
and case I's load and speed, a/β 8.8), at Δx = β/16 over 4 passes, plus every resolved run already in the repository
that recorded its mean profiles (validation runs validation/results/deterministic/*.json, whole-contact runs
validation/results/deterministic_window_*_full.npz). Resumable; runs are cached in
validation/results/deterministic_film_law/ (kept across model versions, each point recording its own; ``--rerun-stale``
recomputes them).

    python validation/deterministic_film_law.py            # run the families, fit, write the JSON
    python validation/deterministic_film_law.py --plot     # and docs/figures/film_law.png

With ``--closures`` each point also gets the central film of the homogenised model's two flow-factor closures
(transverse, isotropic; ehl_dataset.solvers.homogenised) on the same band, so that the figure shows which film each
closure entrains against the resolved one.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np
from scipy.optimize import curve_fit

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solvers.deterministic import MODEL_VERSION, DeterministicOptions, solve_deterministic
from ehl_dataset.solvers.levels import get_level
from ehl_dataset.solvers.steady import dowson_higginson_lambda, solve_steady
from ehl_dataset.solvers.wide_contact import inlet_length

RESULTS = Path(__file__).resolve().parent / "results"
RUNS = RESULTS / "deterministic_film_law"
VALIDATION_RUNS = RESULTS / "deterministic"
OUT = RESULTS / "deterministic_film_law.json"
FIGURE = Path(__file__).resolve().parents[1] / "docs" / "figures" / "film_law.png"
LUBRICANT = "atf"
CENTRE = 0.2
"""Half width of the central band [a] over which films are averaged."""
FAMILIES = {
    # name: ((p_h GPa, r_eq mm, u_r m/s, SR, T °C), Rq1 = Rq2 values [µm])
    "A": ((0.5, 5.0, 5.0, 0.3, 90.0), (0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.8)),
    "I": ((1.5, 5.0, 5.0, 0.2, 75.0), (0.05, 0.15, 0.3, 0.6)),
}
SPACING = 16.0
PASSES = 4.0


def smooth_centre_film(case: ContactCase, state) -> float:
    """Mean film [m] of the steady smooth solve (standard level) over |x| < CENTRE·a."""
    full = Effects.full()
    plan = Effects(False, False, full.shear_thinning, full.compressibility, full.mode, {})
    smooth = solve_steady(case, state, get_level("standard"), plan)
    return float(np.mean(smooth.film[np.abs(smooth.x / case.half_width) < CENTRE]))


def centre_mean(x_over_a: np.ndarray, profile) -> float:
    return float(np.mean(np.asarray(profile)[np.abs(x_over_a) < CENTRE]))


def point(source: str, inputs, content_film_m: float, mu: float, share: float, version: str, state) -> dict:
    case = ContactCase.from_engineering(*inputs)
    sigma = float(np.hypot(case.rq1, case.rq2))
    h_smooth = smooth_centre_film(case, state)
    return {"source": source, "inputs": list(inputs), "model_version": version, "sigma_m": sigma,
            "lambda_bar": dowson_higginson_lambda(case, state)[1],
            "a_over_beta": case.half_width / baseline_profile().correlation_length,
            "smooth_film_m": h_smooth, "content_film_m": content_film_m, "H": h_smooth / sigma,
            "excess_over_sigma": (content_film_m - h_smooth) / sigma, "mu": mu, "asperity_share": share}


def family_run(name: str, conditions, rq: float, lubricant, rerun_stale: bool = False) -> dict:
    """One run of a family (cached; a run cached under another model version is kept, its version recorded with
    the point, unless ``rerun_stale``)."""
    path = RUNS / f"{name}_{rq:g}.json"
    if path.exists():
        record = json.loads(path.read_text())
        if record["model_version"] == MODEL_VERSION or not rerun_stale:
            return record
    case = ContactCase.from_engineering(*conditions, rq, rq)
    state = lubricant.state(case.temperature)
    beta = baseline_profile().correlation_length
    options = DeterministicOptions(dx_m=beta / SPACING, max_passes=PASSES, mu_sem_target=1.0,
                                   min_average_passes=PASSES - 1.5)
    start = time.time()
    # the baseline profile (spacing, a/β and L_in/β in its β, as the recorded runs fitted with it), not the default
    result = solve_deterministic(case, state, Effects.full(), options, roughness=baseline_profile())
    x = result.x / case.half_width
    film = centre_mean(x, result.extra["mean_content_film_profile_m"])
    record = point(f"family {name}", (*conditions, rq, rq), film, result.mu, result.asperity_load_share,
                   MODEL_VERSION, state)
    record.update({"converged": result.converged, "mu_sem": result.mu_sem, "wall_time_s": time.time() - start,
                   "points_per_beta": SPACING})
    RUNS.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(record, indent=1))
    print(f"{name} Rq {rq:g}: H {record['H']:.3f} excess {record['excess_over_sigma']:.3f} sigma, "
          f"mu {result.mu:.4f}, {record['wall_time_s']:.0f} s", flush=True)
    return record


def recorded_runs(lubricant) -> list[dict]:
    """Points from the resolved runs already in the repository that carry mean profiles (the finest spacing of each
    validation case; the whole-contact runs of the window study)."""
    points = []
    finest: dict[str, dict] = {}
    for path in sorted(VALIDATION_RUNS.glob("*_beta*.json")):
        run = json.loads(path.read_text())
        if "mean_content_film_profile_m" not in run["extra"]:
            continue
        if run["case"] not in finest or run["points_per_beta"] > finest[run["case"]]["points_per_beta"]:
            finest[run["case"]] = run
    domain = DeterministicOptions().domain
    for name, run in sorted(finest.items()):
        profile = np.asarray(run["extra"]["mean_content_film_profile_m"])
        x = np.linspace(domain[0], domain[1], profile.size)
        case = ContactCase.from_engineering(*run["inputs"])
        points.append(point(f"validation {name} (β/{run['points_per_beta']})", run["inputs"], centre_mean(x, profile),
                            run["mu"], run["asperity_load_share"], run["solver_version"],
                            lubricant.state(case.temperature)))
    for path in sorted(RESULTS.glob("deterministic_window_*_full.npz")):
        data = np.load(path)
        record = json.loads((RESULTS / path.name.replace("_full.npz", ".json")).read_text())
        inputs = record["inputs"]
        case = ContactCase.from_engineering(*inputs)
        x = data["x_m"] / case.half_width
        points.append(point(f"whole contact {path.name.split('_')[2]} (β/{record['points_per_beta']:g})", inputs,
                            centre_mean(x, data["mean_content_film_profile_m"]), float(data["mu"]),
                            float(data["share"]), str(data["model_version"]), lubricant.state(case.temperature)))
    return points


def closure_films(points: list[dict], lubricant) -> None:
    """Add the homogenised model's central excess film (both closures, standard level) to each point."""
    from ehl_dataset.solvers.homogenised import HomogenisedOptions, solve_homogenised

    for p in points:
        case = ContactCase.from_engineering(*p["inputs"])
        state = lubricant.state(case.temperature)
        for closure in ("transverse", "isotropic"):
            result = solve_homogenised(case, state, get_level("standard"), Effects.full(),
                                       roughness=baseline_profile(),  # the resolved runs' profile
                                       options=HomogenisedOptions(closure=closure))
            film = centre_mean(result.x / case.half_width, result.film)
            p[f"{closure}_excess_over_sigma"] = (film - p["smooth_film_m"]) / p["sigma_m"]
            p[f"{closure}_converged"] = bool(result.converged)


def law(X, c, d, k):
    H, inlet = X
    return c * inlet**k / (H + d)


def one_variable_law(H, c, d):
    return c / (H + d)


def inlet_over_beta(p: dict) -> float:
    case = ContactCase.from_engineering(*p["inputs"])
    return inlet_length(case, p["smooth_film_m"]) / baseline_profile().correlation_length


def group(p: dict) -> str:
    return p["source"].split(" (")[0] if p["source"].startswith("family") else "recorded"


def fit(points: list[dict]) -> dict:
    for p in points:
        p["inlet_over_beta"] = inlet_over_beta(p)
    H = np.array([p["H"] for p in points])
    inlet = np.array([p["inlet_over_beta"] for p in points])
    y = np.array([p["excess_over_sigma"] for p in points])
    film = np.array([p["smooth_film_m"] for p in points])
    sigma = np.array([p["sigma_m"] for p in points])
    content = np.array([p["content_film_m"] for p in points])
    (c, d, k), cov = curve_fit(law, (H, inlet), y, p0=(0.4, 0.4, 0.4))
    residual = y - law((H, inlet), c, d, k)
    held_out = {}
    for name in sorted({group(p) for p in points}):
        member = np.array([group(p) == name for p in points])
        if member.all() or (~member).sum() < 4:
            continue
        (cf, df, kf), _ = curve_fit(law, (H[~member], inlet[~member]), y[~member], p0=(c, d, k))
        predicted = film[member] + sigma[member] * law((H[member], inlet[member]), cf, df, kf)
        held_out[name] = {"c": float(cf), "d": float(df), "k": float(kf),
                          "film_error_max": float(np.max(np.abs(predicted / content[member] - 1.0)))}
    predicted = film + sigma * law((H, inlet), c, d, k)
    (c1, d1), _ = curve_fit(one_variable_law, H, y, p0=(0.6, 0.5))
    residual1 = y - one_variable_law(H, c1, d1)
    return {"c": float(c), "d": float(d), "k": float(k), "c_sd": float(np.sqrt(cov[0, 0])),
            "d_sd": float(np.sqrt(cov[1, 1])), "k_sd": float(np.sqrt(cov[2, 2])),
            "residual_rms_sigma": float(np.sqrt(np.mean(residual**2))),
            "residual_max_sigma": float(np.max(np.abs(residual))),
            "film_error_max": float(np.max(np.abs(predicted / content - 1.0))), "leave_one_group_out": held_out,
            "range": {"H": [float(H.min()), float(H.max())], "inlet_over_beta": [float(inlet.min()),
                                                                                  float(inlet.max())]},
            "one_variable": {"c": float(c1), "d": float(d1),
                             "residual_rms_sigma": float(np.sqrt(np.mean(residual1**2))),
                             "residual_max_sigma": float(np.max(np.abs(residual1)))}}


def out_of_sample(result: dict, lubricant) -> list[dict]:
    """The law against resolved runs that recorded only their time-averaged film at x = 0 (not in the fit):
    the whole-contact run of W1 (validation/results/deterministic_run_W1.json)."""
    checks = []
    for path in sorted(RESULTS.glob("deterministic_run_*.json")):
        run = json.loads(path.read_text())
        case = ContactCase.from_engineering(*run["inputs"])
        p = point(f"whole contact {path.stem.split('_')[-1]} (β/{run['points_per_beta']:g})", run["inputs"],
                  run["h_central_m"], run["mu"], run["asperity_load_share"], run["model_version"],
                  lubricant.state(case.temperature))
        p["inlet_over_beta"] = inlet_over_beta(p)
        predicted = p["smooth_film_m"] + p["sigma_m"] * law((p["H"], p["inlet_over_beta"]), result["c"],
                                                             result["d"], result["k"])
        one = p["smooth_film_m"] + p["sigma_m"] * one_variable_law(p["H"], result["one_variable"]["c"],
                                                                    result["one_variable"]["d"])
        p.update({"film_definition": "time-averaged gap at x = 0", "law_film_m": predicted,
                  "law_film_error": predicted / p["content_film_m"] - 1.0, "one_variable_law_film_m": one,
                  "one_variable_law_film_error": one / p["content_film_m"] - 1.0})
        checks.append(p)
        print(f"out of sample {p['source']}: resolved {p['content_film_m'] * 1e9:.0f} nm, law {predicted * 1e9:.0f} nm "
              f"({p['law_film_error']:+.1%}), one-variable law {one * 1e9:.0f} nm ({p['one_variable_law_film_error']:+.1%})")
    return checks


def plot(points: list[dict], result: dict) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    groups: dict[str, list[dict]] = {}
    for p in points:
        groups.setdefault(p["source"].split(" (")[0].split(" Rq")[0], []).append(p)
    k = result["k"]
    for (name, members), marker in zip(sorted(groups.items()), "osD^vP*X"):
        ax.plot([p["H"] for p in members], [p["excess_over_sigma"] / p["inlet_over_beta"]**k for p in members],
                marker, ls="none", label=name, ms=6, mfc="none")
    grid = np.geomspace(0.08, 8.0, 200)
    for closure, colour in (("transverse", "tab:red"), ("isotropic", "tab:blue")):
        key = f"{closure}_excess_over_sigma"
        shown = [p for p in points if key in p and p[key] > 0.0]
        if shown:
            ax.plot([p["H"] for p in shown], [p[key] / p["inlet_over_beta"]**k for p in shown], "x", color=colour,
                    ms=6, label=f"homogenised model, {closure} closure")
    ax.plot(grid, result["c"] / (grid + result["d"]), "k-",
            label=f"Δ/σ = {result['c']:.3f}·(L_in/β)^{k:.3f}/(H + {result['d']:.3f})")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("H = smooth central film / σ")
    ax.set_ylabel("(rough − smooth central film) / σ / (L_in/β)^k")
    versions = ", ".join(sorted({p["model_version"] for p in points}))
    ax.set_title(f"Film excess of resolved rough contacts (deterministic {versions})", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    FIGURE.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(FIGURE, dpi=120)
    print(f"wrote {FIGURE}")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--families", nargs="*", default=list(FAMILIES), help="which sweeps to run (none: fit only)")
    parser.add_argument("--plot", action="store_true")
    parser.add_argument("--closures", action="store_true", help="also the homogenised model's films")
    parser.add_argument("--rerun-stale", action="store_true",
                        help="recompute family runs cached under another deterministic model version")
    args = parser.parse_args(argv)
    lubricant = load_lubricant(LUBRICANT)
    points = recorded_runs(lubricant)
    for name in args.families:
        conditions, rqs = FAMILIES[name]
        points += [family_run(name, conditions, rq, lubricant, args.rerun_stale) for rq in rqs]
    result = fit(points)
    result["out_of_sample"] = out_of_sample(result, lubricant)
    if args.closures:
        closure_films(points, lubricant)
    OUT.write_text(json.dumps({"law": "excess/sigma = c (inlet/beta)^k/(H + d)", "centre_half_width_a": CENTRE,
                               "fit": result, "points": points}, indent=1))
    for p in points:
        print(f"{p['source']:<34} H {p['H']:6.3f}  excess {p['excess_over_sigma']:6.3f} σ  "
              f"law {law((p['H'], p['inlet_over_beta']), result['c'], result['d'], result['k']):6.3f} σ  "
              f"L_in/β {p['inlet_over_beta']:4.2f}  a/β {p['a_over_beta']:5.1f}  {p['model_version']}"
              + (f"  transverse {p['transverse_excess_over_sigma']:6.3f} σ  isotropic "
                 f"{p['isotropic_excess_over_sigma']:6.3f} σ" if args.closures else ""))
    print(json.dumps(result, indent=1))
    if args.plot:
        plot(points, result)
    return 0


if __name__ == "__main__":
    sys.exit(main())
