"""Which cheap model for rough contacts: the transient mixed solver, the film-law homogenised model and the smooth
solver against the deterministic model, on the same factorial points, split into narrow (a/β < 15) and wide contacts
and at λ̄ = 1. Writes docs/validation/narrow_contacts.md and its figure from the JSON of benchmarks/bench_ehl_mixed.py:

    python validation/narrow_contact_models.py

The runs it reads (all at ``fast``, ATF, 600 s limit per case, random points of seed 1 and the 64 corners; the
deterministic run is resumed as time allows, the transient run has the first 54 random points):

    python benchmarks/bench_ehl_mixed.py --model deterministic --sample random --n 200 --seed 1 --level fast \\
        --roughness baseline_synthetic --time-limit-s 600 --resume \\
        --out benchmarks/results/ehl_mixed_random200_fast_deterministic.json
    python benchmarks/bench_ehl_mixed.py --model auto --sample random --n 54 --seed 1 --level fast \\
        --roughness baseline_synthetic --time-limit-s 600 \\
        --out benchmarks/results/ehl_mixed_random54_fast_transient.json
    python benchmarks/bench_ehl_mixed.py --model homogenised --closure film_law --effects isothermal \\
        --sample random --n 200 --seed 1 --level fast --roughness baseline_synthetic \\
        --out benchmarks/results/ehl_mixed_random200_fast_homogenised_film_law_isothermal.json
    python benchmarks/bench_ehl_mixed.py --model smooth --sample random --n 200 --seed 1 --level fast \\
        --roughness baseline_synthetic --out benchmarks/results/ehl_mixed_random200_fast_smooth.json
    (the same with --sample corners: ehl_mixed_corners_fast_deterministic.json, ehl_mixed_corners_fast.json (the
    transient solver, effects=full), ehl_mixed_corners_fast_homogenised_film_law_isothermal.json,
    ehl_mixed_corners_fast_smooth.json)

Every model here is isothermal (the deterministic and transient solvers have no thermal model; the film law runs
with ``--effects isothermal``, the smooth solve of ``--model smooth`` is isothermal). Points with SR = 0 (μ ≈ 0) and
points either side did not converge are left out. The deterministic model at ``fast`` is not the grid-converged
reference (docs/validation/accuracy_mixed.md: within 5.0 % in median of it on eleven cases under det-2026.11-13, +27 % on case G): the
differences are between models.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solver import SOLVER_VERSION
from ehl_dataset.model.micro_pressure import MICRO_PRESSURE_C0, MICRO_PRESSURE_INLET_SCALE
from ehl_dataset.solvers.levels import NARROW_CLOSURE_LAMBDA, NARROW_CLOSURE_ROUGHNESS, NARROW_FILM_LAW_EYRING
from ehl_dataset.solvers.planner import dimensionless_numbers, narrow_film_law_range, thresholds_for
from ehl_dataset.solvers.wide_contact import WIDE_A_OVER_BETA

ROOT = Path(__file__).resolve().parents[1]
BENCHMARK_RESULTS = ROOT / "benchmarks" / "results"
"""The factorial runs of benchmarks/bench_ehl_mixed.py compared here."""
RESULTS = ROOT / "validation" / "results"
DOC = ROOT / "docs" / "validation" / "narrow_contacts.md"
FIGURE = ROOT / "docs" / "figures" / "narrow_contacts.png"
SAMPLES = {
    "random": ("ehl_mixed_random200_fast_deterministic.json", {
        "transient": "ehl_mixed_random54_fast_transient.json",
        "film law": "ehl_mixed_random200_fast_homogenised_film_law_isothermal.json",
        "smooth": "ehl_mixed_random200_fast_smooth.json"}),
    "corners": ("ehl_mixed_corners_fast_deterministic.json", {
        "transient": "ehl_mixed_corners_fast.json",
        "film law": "ehl_mixed_corners_fast_homogenised_film_law_isothermal.json",
        "smooth": "ehl_mixed_corners_fast_smooth.json"}),
}
COMMAND = "python validation/narrow_contact_models.py"



def deterministic_fast_error_text() -> str:
    """The deterministic model's error at ``fast`` against the reference set, from docs/validation/accuracy_mixed.json: its
    median over the reference cases and the largest ones, named."""
    runs = json.loads((ROOT / "docs" / "validation" / "accuracy_mixed.json").read_text())["runs"]
    errors = {r["case"]: 100.0 * r["mu_error"] for r in runs if r["model"] == "deterministic-fast"}
    worst = sorted(errors.items(), key=lambda item: -item[1])[:4]
    return (f"a median {np.median(list(errors.values())):.1f} % ({len(errors)} reference cases; "
            + ", ".join(f"{value:.0f} % on {case}" for case, value in worst) + ")")

def _rows(name: str) -> tuple[dict, dict]:
    data = json.loads((BENCHMARK_RESULTS / name).read_text())
    return data, {tuple(r["case"]): r for r in data["rows"]}


def compare() -> list[dict]:
    """One record per (sample, model, point) where the model and the deterministic model both converged, SR > 0."""
    beta = baseline_profile().correlation_length
    atf = load_lubricant("atf")
    numbers: dict = {}  # the planner's numbers per point, shared by the models' rows
    out = []
    for sample, (reference_name, models) in SAMPLES.items():
        _, reference = _rows(reference_name)
        for model, name in models.items():
            data, rows = _rows(name)
            for key, row in rows.items():
                ref = reference.get(key)
                if ref is None or not (row.get("converged") and ref.get("converged")) or key[3] == 0:
                    continue
                case = ContactCase.from_engineering(*key)
                if key not in numbers:
                    numbers[key] = dimensionless_numbers(case, atf)
                out.append({"sample": sample, "model": model, "case": key, "lambda_bar": ref["lambda_bar"],
                            "eyring_number": numbers[key]["eyring_number"],
                            "roughness_parameter": numbers[key]["roughness_parameter"],
                            "a_over_beta": case.half_width / beta, "error": row["mu"] / ref["mu"] - 1.0,
                            "time_s": row.get("wall_time_s", np.nan), "reference_time_s": ref.get("wall_time_s"),
                            "version": data["solver_version"]})
    return out


def deterministic_versions() -> str:
    return ", ".join(f"{sample} {_rows(name)[0]['solver_version'].split()[0]}"
                     for sample, (name, _) in SAMPLES.items())


def _group_stats(errors: list[float], times: list[float]) -> str:
    e = np.asarray(errors)
    a = np.abs(e)
    return (f"{e.size} | {100 * np.median(e):+.1f} % | {100 * np.median(a):.1f} % | {100 * np.percentile(a, 90):.1f} % | "
            f"{100 * a.max():.0f} % | {np.median(times):.2g}")


def reference_cases() -> list[dict]:
    """The film law's signed error on the grid-converged reference cases (docs/validation/accuracy_mixed.json against
    data/reference/deterministic_validation.json's extrapolated μ), with their λ̄, a/β and X_h."""
    atf = load_lubricant("atf")
    beta = baseline_profile().correlation_length
    reference = {r["case"]: r for r in json.loads((ROOT / "data" / "reference" /
                                                   "deterministic_validation.json").read_text())["cases"]}
    out = []
    for run in json.loads((ROOT / "docs" / "validation" / "accuracy_mixed.json").read_text())["runs"]:
        if run["model"] != "homogenised-film_law-standard" or run["case"] not in reference:
            continue
        ref = reference[run["case"]]
        case = ContactCase.from_engineering(*(ref["inputs"][k] for k in ("p_h_gpa", "r_eq_mm", "u_r_m_s", "sr",
                                                                        "temp_c", "rq1_um", "rq2_um")))
        numbers = dimensionless_numbers(case, atf)
        out.append({"case": run["case"], "lambda_bar": numbers["lambda_bar"], "a_over_beta": case.half_width / beta,
                    "eyring_number": numbers["eyring_number"], "roughness_parameter": numbers["roughness_parameter"], "error": run["mu"] / ref["mu_extrapolated"] - 1.0,
                    "share": ref["asperity_load_share_extrapolated"]})
    return sorted(out, key=lambda r: r["eyring_number"])


def _fluctuation_table() -> list[str]:
    """The micro-EHL fluctuation measurements (validation/micro_ehl_fluctuations.py) as a Markdown table."""
    rows = json.loads((RESULTS / "micro_ehl_fluctuations.json").read_text())["rows"]
    lines = ["| run | X_h | std of p_f / p_h | μ_Couette, local p_f and h | mean p_f and h | mean p_f, local h | "
             "local p_f, mean h | gamma p_f (node's mean and std), mean h |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        gamma = r.get("couette_mu_gamma_pressure_mean_film")
        lines.append(f"| {r['run']} ({r['model_version']}) | {r['eyring_number']:.3g} | "
                     f"{r['pressure_std_over_p_h']:.2f} | {r['couette_mu_local']:.4f} | "
                     f"{r['couette_mu_mean_pressure_mean_film']:.4f} | {r['couette_mu_mean_pressure_local_film']:.4f} | "
                     f"{r['couette_mu_local_pressure_mean_film']:.4f} | "
                     + (f"{gamma:.4f} |" if gamma is not None else "n/a |"))
    return lines


def closure_range(r: dict) -> str:
    """Which side of the planner's narrow-contact limits (at ``standard``) a narrow point below λ̄ 1 is on."""
    within, limit = narrow_film_law_range(r, thresholds_for("standard"))
    if limit == "eyring_number":
        return f"X_h ≥ {NARROW_FILM_LAW_EYRING:g}"
    return f"X_h < {NARROW_FILM_LAW_EYRING:g}, " + ("closure range" if within else "outside")


def _holdout_sentence(record: dict) -> str:
    """The out-of-sample check of the shipped c: calibration-group contacts run after it was fitted."""
    h = record.get("holdout_at_shipped_c")
    if not h:
        return ""
    fitted_on = len(record["shipped_fit_points"])
    return (f" The shipped c was fitted on the first {fitted_on} of them; the {h['n']} run since "
            f"({', '.join(record['holdout_points'])}) are an out-of-sample check: at the shipped c their error is a "
            f"median {100 * h['median_abs']:.1f} % (bias {100 * h['median']:+.1f} %), 90th percentile "
            f"{100 * h['p90_abs']:.1f} %.")


def _inlet_lines() -> list[str]:
    """Why c is a function of L_in/β: the resolved wide contacts X1, X2 and validation/closure_forms.py."""
    forms = json.loads((RESULTS / "closure_forms.json").read_text())
    record = {p["label"]: p for p in json.loads((RESULTS / "micro_pressure_closure.json").read_text())["points"]}
    runs = {tag: json.loads((RESULTS / f"deterministic_run_{tag}.json").read_text()) for tag in ("X1", "X2")}
    window = json.loads((RESULTS / "deterministic_wide_X1.json").read_text())
    switch = next(v for k, v in forms["forms"].items() if k.startswith("ehl-2026.11-13"))
    inlet = forms["forms"]["c0 / (1 + (L_in/(β L0))²)"]
    others = [v["leave_one_out_median_abs"] for k, v in forms["forms"].items() if "λ̄" in k or "everywhere" in k]
    share = forms["paper_factorial_wide_unsaturated"]
    x = {tag: record[f"{tag} resolved"] for tag in runs}
    described = ", ".join(f"{tag} (a/β {p['a_over_beta']:.1f}, λ̄ {p['lambda_bar']:.2f}, X_h {p['eyring_number']:.2g}, "
                          f"L_in/β {p['inlet_over_beta']:.2f}) μ {runs[tag]['mu']:.4f} ± {runs[tag]['mu_sem']:.4f}"
                          for tag, p in x.items())
    return [
        "**Why c depends on the inlet length (measured 2026-11-25; shipped in ehl-2026.11-14).** Until -13 c was "
        "0.167 below a/β 15 and 0 above, because the wide route's periodic windows agreed with the film law without "
        "the closure on the wide factorial corners. Two wide unsaturated contacts resolved whole at "
        f"β/{runs['X1']['points_per_beta']:g} ({runs['X1']['model_version']}, {runs['X1']['passes']:g} passes; "
        "`python validation/deterministic_run.py --inputs " + " ".join(f"{v:g}" for v in runs["X1"]["inputs"])
        + f" --spacing 8 --passes 4 --tag X1`, and the same at r_eq {runs['X2']['inputs'][1]:g} mm with `--tag X2`) "
        f"showed that switch wrong: {described}; the film law without the closure is "
        f"{100 * x['X1']['error_without']:+.0f} % and {100 * x['X2']['error_without']:+.0f} %. The windows of the "
        f"wide route agree with the resolved X1 ({window['mu']:.4f} ± {window['mu_sem']:.4f}; `python "
        "validation/deterministic_wide.py --inputs " + " ".join(f"{v:g}" for v in window["inputs"]) + " --tag X1`), "
        "so windows do carry the fluctuation. What separates the contacts where c = 0 fits (corners 5 and 15, random "
        "53 and 165: L_in/β 9–12) from those where c ≈ 0.2 fits (L_in/β 1–3) is the film law's inlet length in "
        "correlation lengths: where the inlet is many β long the fluid smooths the micro-EHL pressure before the "
        "asperities reach the Hertz zone. On the "
        f"{len(forms['contacts'])} calibration contacts (`{forms['command']}`, validation/results/closure_forms.json) "
        f"the leave-one-out error of c = c0/(1 + (L_in/(β·L0))²) is a median "
        f"{100 * inlet['leave_one_out_median_abs']:.1f} %, 90th percentile {100 * inlet['leave_one_out_p90_abs']:.1f} "
        f"%, against {100 * switch['leave_one_out_median_abs']:.1f} % and {100 * switch['leave_one_out_p90_abs']:.1f} "
        "% for the -13 switch (at most "
        f"{100 * switch['wide_max_abs']:.0f} % on a wide contact) and a median of "
        f"{100 * min(others):.0f}–{100 * max(others):.0f} % for a constant c or c decaying with λ̄. "
        f"{100 * share['share']:.1f} % of the paper factorial's sliding points are wide, below λ̄ 1 and unsaturated "
        f"(a sample of {share['points']:,} points; a/β " + ", ".join(f"{k}: {v}" for k, v in share["a_over_beta"].items())
        + "): the points the switch had put about 40 % low."]


def _calibration_lines() -> list[str]:
    """The closure's calibration (validation/micro_pressure_closure.py) as a Markdown table."""
    record = json.loads((RESULTS / "micro_pressure_closure.json").read_text())
    lines = [f"Calibration (`{record['command']}`, EHL solver {record['solver_version']}, film law at "
             f"`{record['level']}`, isothermal, against the deterministic model: the validation set's grid-converged "
             "μ, the factorial points at `fast` and the resolved wide runs X1, X2): c0 = "
             f"{record['fitted']['c0']:.4f}, L0 = {record['fitted']['inlet_scale']:.3f} fitted, "
             f"{record['shipped']['c0']:g} and {record['shipped']['inlet_scale']:g} shipped; on the "
             f"{record['leave_one_out']['n']} calibration contacts the error at the shipped c is a median "
             f"{100 * record['calibration_at_shipped_c']['median_abs']:.1f} %, 90th percentile "
             f"{100 * record['calibration_at_shipped_c']['p90_abs']:.1f} %, and the leave-one-out error (c0, L0 "
             f"refitted without the point) a median {100 * record['leave_one_out']['median_abs']:.1f} %, 90th "
             f"percentile {100 * record['leave_one_out']['p90_abs']:.1f} %." + _holdout_sentence(record), "",
             "| contacts | points | median error without | median abs without | 90th pct abs without | "
             "median error with | median abs with | 90th pct abs with |", "|---|---|---|---|---|---|---|---|"]
    for name, g in record["groups"].items():
        a, b = g["without_closure"], g["with_closure"]
        lines.append(f"| {name} | {a['n']} | {100 * a['median']:+.1f} % | {100 * a['median_abs']:.1f} % | "
                     f"{100 * a['p90_abs']:.1f} % | {100 * b['median']:+.1f} % | {100 * b['median_abs']:.1f} % | "
                     f"{100 * b['p90_abs']:.1f} % |")
    lines += ["", "Below λ̄ 1 (with: at the shipped c(L_in/β)):", "",
              "| contact | a/β | λ̄ | X_h | α | L_in/β | c | deterministic μ | without | with | leave-one-out |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    for p in sorted(record["points"], key=lambda p: (p["group"], p["eyring_number"])):
        if p["lambda_bar"] > 1.0:
            continue
        loo = p.get("leave_one_out_error")
        lines.append(f"| {p['label']} | {p['a_over_beta']:.1f} | {p['lambda_bar']:.2f} | {p['eyring_number']:.3g} | "
                     f"{p['roughness_parameter']:.2f} | {p['inlet_over_beta']:.2f} | {p['c_shipped']:.3f} | "
                     f"{p['mu_det']:.4f} | {100 * p['error_without']:+.1f} % | "
                     f"{100 * p['error_with']:+.1f} % | " + (f"{100 * loo:+.1f} % |" if loo is not None else "– |"))
    return lines


def _film_law_split(records: list[dict]) -> list[str]:
    """Film law (with its closure) on narrow contacts below λ̄ 1, split at the planner's limits."""
    lines = ["| narrow, λ̄ ≤ 1 | points | median error | median abs | 90th pct abs | max abs |", "|---|---|---|---|---|---|"]
    groups = (f"X_h ≥ {NARROW_FILM_LAW_EYRING:g}", f"X_h < {NARROW_FILM_LAW_EYRING:g}, closure range",
              f"X_h < {NARROW_FILM_LAW_EYRING:g}, outside")
    for label in groups:
        sel = [r["error"] for r in records if r["model"] == "film law" and r["a_over_beta"] < WIDE_A_OVER_BETA
               and r["lambda_bar"] <= 1.0 and closure_range(r) == label]
        if sel:
            e = np.asarray(sel)
            lines.append(f"| {label} | {e.size} | {100 * np.median(e):+.1f} % | {100 * np.median(np.abs(e)):.1f} % | "
                         f"{100 * np.percentile(np.abs(e), 90):.1f} % | {100 * np.abs(e).max():.0f} % |")
    return lines


def markdown(records: list[dict]) -> str:
    n_random = len({r["case"] for r in records if r["sample"] == "random"})
    versions = sorted({(r["model"], r["sample"], r["version"].split()[0]) for r in records})
    lines = ["# Rough contacts: which cheap model, narrow and wide", "",
             f"*Made by `{COMMAND}` from the JSON runs named in its docstring (EHL solver versions of the runs: "
             + ", ".join(f"{m} {s} {v}" for m, s, v in versions)
             + f"; deterministic: {deterministic_versions()}; this page written under EHL solver "
             f"{SOLVER_VERSION}).*", "",
             "μ of three cheap models against the deterministic model at `fast` on the same points: random "
             f"factorial points (seed 1; {n_random} with a deterministic result, the transient solver on the first "
             "54 of them) and the 64 corners of the paper's factorial, ATF, all isothermal, "
             "points with SR > 0 that both converged. error = μ_model/μ_deterministic − 1. Narrow: a/β < "
             f"{WIDE_A_OVER_BETA:g} (the homogenisation limit of the planner, docs/explanation/planner.md). The deterministic "
             f"model at `fast` is itself {deterministic_fast_error_text()} off its grid-converged reference "
             "(docs/validation/accuracy_mixed.md), so these are differences between models, not errors against the exact "
             "answer. Time: the model's median wall time per point [s] (the deterministic model's: "
             f"{np.median([r['reference_time_s'] for r in records if r['model'] == 'film law']):.0f} s).", "",
             "| contact | λ̄ | model | points | median error | median abs | 90th pct abs | max abs | median time [s] |",
             "|---|---|---|---|---|---|---|---|---|"]
    for narrow in (True, False):
        for low in (True, False):
            for model in ("transient", "film law", "smooth"):
                sel = [r for r in records if r["model"] == model and (r["a_over_beta"] < WIDE_A_OVER_BETA) == narrow
                       and (r["lambda_bar"] <= 1.0) == low]
                if not sel:
                    continue
                lines.append(f"| {'narrow' if narrow else 'wide'} | {'≤ 1' if low else '> 1'} | {model} | "
                             + _group_stats([r["error"] for r in sel], [r["time_s"] for r in sel]) + " |")
    lines += ["", "![error of each model against the deterministic model](../figures/narrow_contacts.png)", "",
              f"*Made by `{COMMAND}` (EHL solver {SOLVER_VERSION}).*", "",
              "## What the planner does with it", "",
              "- The transient rows are a rough model the package no longer has, from its recorded runs: a median "
              "80–106 % high below λ̄ = 1, narrow and wide, with about a third of the load on asperities where the "
              "deterministic model has almost none.",
              "- Wide contacts: the film law is within a few per cent in median (its validated range, "
              "docs/explanation/mixed-regime.md).",
              "- Narrow contacts above λ̄ = 1: the film law is within 6 %.",
              "- **Narrow contacts below λ̄ = 1: micro-EHL pressure fluctuations.** What decides is the Eyring "
              "number at the Hertz pressure, X_h = η(p_h)|u_s|/(τ0 h_min,DH) (its τ_m/τ0 = asinh X_h). Deep in the "
              "Eyring plateau the shear stress τ0 ln(2X) grows linearly with the pressure, so the micro-EHL "
              "pressure fluctuations between asperities average out; where X_h is small τ still grows almost "
              "exponentially with the pressure, and the fluctuations raise the mean stress. Measured in the "
              "deterministic model's runs (Couette part of μ in |x| < 0.8a; "
              "`python validation/micro_ehl_fluctuations.py A:16 G:8 I:8 C:16`):", "",
              *_fluctuation_table(), "",
              "  A gamma distribution with each node's own mean and standard deviation (last column) reproduces "
              "the local pressures' mean stress (the column before it) within 1–12 %: that is the shape of the closure "
              "below.", "",
              "## Pressure-fluctuation closure (ehl-2026.11-13; c in L_in/β since ehl-2026.11-14)", "",
              "The film law averages the Eyring stress over a gamma distribution of the pressure about the smooth mean "
              "p̄(x), independent of the gap heights, with standard deviation σ_p = c·E'Δq/4: E'Δq/4 is the r.m.s. "
              "pressure that flattens the composite roughness of r.m.s. slope Δq on elastic half-spaces (Johnson, "
              "Contact Mechanics, §13.1), and c the fraction the film lets through, a function of the inlet length "
              f"in correlation lengths, c = c0/(1 + (L_in/(β·L0))²) with c0 = {MICRO_PRESSURE_C0:g}, "
              f"L0 = {MICRO_PRESSURE_INLET_SCALE:g}, fitted (`ehl_dataset/model/micro_pressure.py`), on narrow and "
              "wide contacts alike.", "",
              *_inlet_lines(), "",
              *_calibration_lines(), "",
              "Outside the closure's range the film law is off in either direction: below λ̄ "
              f"{NARROW_CLOSURE_LAMBDA:g} the asperities carry load (case B, share 0.53, and the narrow corner at "
              "λ̄ 0.027 stay low; the wide corner at λ̄ 0.062 is far high with the closure), and above a Greenwood–"
              f"Tripp roughness parameter α = S_c r_eq/a² of {NARROW_CLOSURE_ROUGHNESS:g} the mean pressure is not "
              "the Hertzian one the film law takes (case C and three corners at α 3.6, low). The limits bound few "
              "points: λ̄ 0.1 lies between the highest λ̄ outside for that reason (0.062, the wide corner) and the "
              "lowest inside (0.14); a factorial point at λ̄ 0.085 is outside and met; α 2.5 lies between the largest "
              "inside (1.8) and 3.6. Since ehl-2026.11-14 the same range applies to wide contacts.", "",
              "  The film law with its closure, on the factorial points (deterministic model at `fast`):",
              "", *_film_law_split(records), "",
              "  and on the grid-converged reference cases (docs/validation/accuracy_mixed.md, `standard`; share: the "
              "reference's asperity load share):", "",
              "| case | λ̄ | a/β | X_h | α | film law error | asperity share |", "|---|---|---|---|---|---|---|",
              *[f"| {r['case']} | {r['lambda_bar']:.2f} | {r['a_over_beta']:.1f} | {r['eyring_number']:.3g} | "
                f"{r['roughness_parameter']:.2f} | {100 * r['error']:+.1f} % | {r['share']:.3f} |"
                for r in reference_cases()], "",
              "## What the planner does", "",
              f"- Narrow contacts above λ̄ = 1, at X_h ≥ {NARROW_FILM_LAW_EYRING:g} (since ehl-2026.11-12) or within "
              f"the closure's range, λ̄ ≥ {NARROW_CLOSURE_LAMBDA:g} and α ≤ {NARROW_CLOSURE_ROUGHNESS:g} (since "
              "ehl-2026.11-13; `narrow_closure_lambda`, `narrow_closure_roughness` of `PlannerThresholds`), are "
              "within the film law's measured range and are solved by it at `fast` and `standard`. Wide rough "
              "contacts are solved by it whatever their numbers; since ehl-2026.11-14 those below λ̄ 1 with X_h < "
              f"{NARROW_FILM_LAW_EYRING:g} outside the closure's range are flagged the same way (the plan's "
              "`film_law_range`).",
              "- Only the others go to the level's `rough_model`. At `fast` and `standard` that is still the film "
              "law, recorded as outside its validated range: no cheap model is within those levels' tolerance there. "
              "The deterministic model (`--level reference` or `--model deterministic`, about a minute per point at "
              "its `fast` grid) is the accurate option; `python validation/planner_model_shares.py` counts how many "
              "factorial points that is.",
              "", "## Per point", "",
              "| sample | p_h [GPa] | r_eq [mm] | u_r [m/s] | SR | T [°C] | Rq1/Rq2 [µm] | λ̄ | a/β | X_h | transient "
              "| film law | smooth |", "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    by_point: dict = {}
    for r in records:
        by_point.setdefault((r["sample"], r["case"]), {})[r["model"]] = r
    for (sample, key), models in sorted(by_point.items(), key=lambda kv: (kv[0][0], next(iter(kv[1].values()))
                                                                           ["lambda_bar"])):
        first = next(iter(models.values()))
        cells = [f"{100 * models[m]['error']:+.1f} %" if m in models else "n/a"
                 for m in ("transient", "film law", "smooth")]
        lines.append(f"| {sample} | {key[0]:g} | {key[1]:g} | {key[2]:g} | {key[3]:g} | {key[4]:g} | "
                     f"{key[5]:g}/{key[6]:g} | {first['lambda_bar']:.3g} | {first['a_over_beta']:.3g} | "
                     f"{first['eyring_number']:.3g} | "
                     + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def plot(records: list[dict], path: Path) -> None:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4), sharey=True)
    styles = {"transient": ("tab:red", "o"), "film law": ("tab:blue", "s"), "smooth": ("tab:gray", "^")}
    for ax, narrow in zip(axes, (True, False)):
        for model, (colour, marker) in styles.items():
            sel = [r for r in records if r["model"] == model and (r["a_over_beta"] < WIDE_A_OVER_BETA) == narrow]
            ax.scatter([r["lambda_bar"] for r in sel], [100 * r["error"] for r in sel], c=colour, marker=marker,
                       s=22, alpha=0.75, label=f"{model} ({len(sel)})")
        ax.axhline(0.0, color="k", lw=0.8)
        ax.axvline(1.0, color="k", lw=0.6, ls=":")
        ax.set_xscale("log")
        ax.set_yscale("symlog", linthresh=10.0)
        ax.set_xlabel("λ̄ (Dowson–Higginson film over composite Rq)")
        ax.set_title(f"{'narrow' if narrow else 'wide'} contacts (a/β {'<' if narrow else '≥'} {WIDE_A_OVER_BETA:g})")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    ax = axes[2]
    for model, (colour, marker) in styles.items():
        if model == "transient":
            continue
        for outside in (False, True):
            sel = [r for r in records if r["model"] == model and r["a_over_beta"] < WIDE_A_OVER_BETA
                   and r["lambda_bar"] <= 1.0 and closure_range(r).endswith("outside") == outside]
            ax.scatter([r["eyring_number"] for r in sel], [100 * r["error"] for r in sel], marker=marker, s=22,
                       alpha=0.75, facecolors="none" if outside else colour, edgecolors=colour,
                       label=f"{model} vs deterministic-fast ({len(sel)}{', outside' if outside else ''})")
    refs = [r for r in reference_cases() if r["lambda_bar"] <= 1.0]
    ax.scatter([r["eyring_number"] for r in refs], [100 * r["error"] for r in refs], c="tab:blue", marker="*", s=110,
               edgecolors="k", label="film law vs reference case")
    for r in refs:
        ax.annotate(r["case"], (r["eyring_number"], 100 * r["error"]), textcoords="offset points", xytext=(5, 4),
                    fontsize=8)
    ax.axhline(0.0, color="k", lw=0.8)
    ax.axvline(NARROW_FILM_LAW_EYRING, color="k", lw=0.6, ls=":")
    ax.set_xscale("log")
    ax.set_xlabel("X_h = η(p_h)|u_s|/(τ0 h_min,DH)")
    ax.set_title(f"narrow, λ̄ ≤ 1 (film law with closure; hollow: outside λ̄ ≥ {NARROW_CLOSURE_LAMBDA:g}, "
                 f"α ≤ {NARROW_CLOSURE_ROUGHNESS:g})", fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    axes[0].set_ylabel("μ_model / μ_deterministic-fast − 1 [%]")
    fig.suptitle("Cheap rough-contact models against the deterministic model (fast, isothermal, SR > 0)", fontsize=10)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def main() -> int:
    records = compare()
    DOC.write_text(markdown(records), encoding="utf-8")
    plot(records, FIGURE)
    print(f"wrote {DOC} and {FIGURE} ({len(records)} comparisons)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
