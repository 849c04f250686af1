"""What the friction model costs in accuracy and time inside the gear power loss (docs/validation/gear.md).

For the paper's design D at its study point and an FZG test-gear case, the mean mechanical power loss P (Li &
Kahraman 2009, Eq. 11) of one loaded mesh cycle (default 24 positions × 30 slices) with

* the EHL solver at every loaded contact point, smooth surfaces, ``fast`` and ``standard`` levels (``ehl:standard``
  is the reference of the error column);
* the EHL solver on a small grid per side of the pitch point, interpolated (:class:`EhlGridFriction`), several grid
  sizes (error against the per-point solve of the same level = interpolation error alone, and against the
  reference);
* rough surfaces (Rq 0.4 µm) with ``effects=auto`` (the transient mixed solver where the planner asks for it):
  the grid on the full mesh, and (``--rough-per-point``) the per-point solve on a coarser mesh with the grid on
  the same mesh;
* the published formulas (Xu et al. 2007, Benedict & Kelley 1961, ISO/TR 14179-2) and any fitted coefficient file
  in data/coefficients/ (a row is skipped while none exists), all at Rq 0.4 µm;

with the wall time of each (friction evaluation included, mesh excluded). Writes one JSON object to ``--out``
(default benchmarks/results/gear_friction.json) and prints a Markdown table.

Run: ``python benchmarks/bench_gear_friction.py [--cases design_D,fzg_C] [--rough-per-point]``; rough rows only, added
to the existing file: ``--rough-only --rough-models ehl-grid:standard:auto:3x3``; the figure of
docs/validation/gear.md from the file: ``--figure docs/figures/gear_friction_accuracy.png``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
import warnings
from pathlib import Path

import numpy as np

# _common.py sits next to this file (sys.path: see bench_ehl_mixed.py)
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import machine_info  # noqa: E402

RESULTS = Path(__file__).parent / "results" / "gear_friction.json"
GRID_SIZES = ((3, 5), (4, 6), (5, 9), (7, 12))


def cases():
    from efficiency.design_io import load_study
    from efficiency.geometry import GearPair
    from efficiency.modifications import Modifications

    study = load_study("paper2009")
    op = study.operating_point
    return {
        "design_D": {
            "pair": study.design("D"), "torque_nm": op.input_torque, "speed_rpm": op.input_speed * 30 / math.pi,
            "lubricant": "atf", "oil_temp_c": op.oil_temperature - 273.15, "rq_um": op.rq1 * 1e6,
            "modifications": Modifications(profile_crown=op.profile_crown, lead_crown=op.lead_crown),
            "source": "Li & Kahraman 2009 Table 1 design D at the §3 study point (data/studies/paper2009.toml)",
        },
        "fzg_C": {
            "pair": GearPair(16, 24, 4.5e-3, math.radians(20), 0.0, 14e-3, 0.1817, 0.1715, center_distance=0.0915),
            "torque_nm": 302.0, "speed_rpm": 2170.0, "lubricant": "gear_oil_75w90", "oil_temp_c": 90.0,
            "rq_um": 0.4, "modifications": Modifications(),
            "source": "FZG type C spur gears (DIN ISO 14635-1), pinion torque 302 N·m (FZG load "
                      "stage 9), 2170 rpm, 75W90 at 90 °C, no flank modifications",
        },
    }


def run_model(mesh, spec, lubricant, temperature, rq):
    from efficiency.friction import friction_from_spec
    from efficiency.friction_accuracy import load_weighted_mu, pitch_region_share
    from efficiency.power_loss import mesh_power_loss
    from ehl_dataset.validation import InputError, SolverError

    started = time.perf_counter()
    try:
        friction = friction_from_spec(spec, lubricant)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = mesh_power_loss(mesh, friction, temperature, rq, rq)
    except (SolverError, InputError) as err:
        return {"model": spec, "rq_m": rq, "error": f"{type(err).__name__}: {err}"[:400],
                "wall_time_s": time.perf_counter() - started}, None
    row = {"model": spec, "description": result.friction_model, "rq_m": rq, "power_loss_w": result.power_loss,
           "efficiency": result.efficiency, "mu_mean": load_weighted_mu(result, mesh),
           "pitch_region_power_share": pitch_region_share(result, mesh, 0.02),
           "mu_at_min_sr": float(result.mu[mesh.loads > 0][np.argmin(result.sr[mesh.loads > 0])]),
           "min_sr": float(result.sr[mesh.loads > 0].min()),
           "wall_time_s": time.perf_counter() - started,
           "ehl_solves": int(result.extra.get("ehl_solves", 0)), "loaded_points": int((mesh.loads > 0).sum()),
           "warnings": sorted({str(w.message)[:200] for w in caught})}
    return row, result


def evaluate_case(name, case, positions, slices, rough_per_point, rough_positions, rough_slices,
                  rough_models=("ehl-grid:fast:auto:4x6",), rough_only=False, previous=None):
    from efficiency.mesh_cycle import MeshOptions, evaluate_mesh

    speed = case["speed_rpm"] * math.pi / 30
    mesh = evaluate_mesh(case["pair"], case["torque_nm"], speed, case["modifications"],
                         MeshOptions(positions=positions, slices=slices, outputs=frozenset()))
    temperature = case["oil_temp_c"] + 273.15
    rq = case["rq_um"] * 1e-6
    lub = case["lubricant"]
    rows, results = [], {}

    def add(spec, rq_m, group, mesh_=mesh, label=None):
        row, result = run_model(mesh_, spec, lub, temperature, rq_m)
        row["group"] = group
        row["label"] = label or spec
        rows.append(row)
        results[row["label"]] = result
        print(f"  {name} {row['label']:<28} P = {row.get('power_loss_w', float('nan')):8.2f} W  "
              f"{row['wall_time_s']:7.2f} s  {row.get('ehl_solves', '')} {row.get('error', '')[:120]}",
              file=sys.stderr, flush=True)
        return row

    coefficient_files = sorted(Path(__file__).resolve().parents[1].joinpath("data", "coefficients").glob("*.json"))
    if not rough_only:
        add("ehl:standard", 0.0, "smooth EHL per point")
        add("ehl:fast", 0.0, "smooth EHL per point")
        for level in ("fast", "standard"):
            for ns, npn in GRID_SIZES if level == "fast" else ((5, 9),):
                add(f"ehl-grid:{level}:{ns}x{npn}", 0.0, "smooth EHL grid")
        for spec in ("xu2007", "benedict_kelley", "iso14179"):
            add(spec, rq, "published")
        for path in coefficient_files:
            add(path.stem, rq, "surrogate", label=f"surrogate {path.name}")  # the shipped name: no machine path
    for spec in rough_models:
        add(spec, rq, "rough EHL grid")
    if rough_per_point:
        coarse = evaluate_mesh(case["pair"], case["torque_nm"], speed, case["modifications"],
                               MeshOptions(positions=rough_positions, slices=rough_slices, outputs=frozenset()))
        tag = f" ({rough_positions}x{rough_slices} mesh)"
        add("ehl:fast:auto", rq, "rough EHL per point, coarse mesh", coarse, "ehl:fast:auto" + tag)
        add("ehl-grid:fast:auto:4x6", rq, "rough EHL per point, coarse mesh", coarse, "ehl-grid:fast:auto:4x6" + tag)
        add("ehl:fast", 0.0, "rough EHL per point, coarse mesh", coarse, "ehl:fast smooth" + tag)

    reference = results.get("ehl:standard")
    p_ref = reference.power_loss if reference is not None else None
    if previous is not None:  # --rough-only: keep the earlier rows, take the reference from them
        p_ref = next((r["power_loss_w"] for r in previous["rows"] if r["label"] == "ehl:standard"
                      and "power_loss_w" in r), None)
    per_level = {"fast": results.get("ehl:fast"), "standard": reference}
    for row in rows:
        p = row.get("power_loss_w")
        row["rel_error_vs_reference"] = (p / p_ref - 1) if (p is not None and p_ref is not None
                                                            and "coarse" not in row["group"]) else None
        if row["group"] == "smooth EHL grid":
            base = per_level[row["model"].split(":")[1]]
            row["rel_error_vs_same_level_per_point"] = p / base.power_loss - 1 if (p is not None and base) else None
            if p is not None and base is not None:
                loaded = mesh.loads > 0
                grid_mu = results[row["label"]].mu[loaded]
                base_mu = base.mu[loaded]
                weight = base_mu * mesh.loads[loaded] * np.abs(mesh.kinematics.u_s[loaded])
                rel = np.abs(grid_mu / base_mu - 1)
                row["mu_rel_error_power_weighted"] = float(np.sum(rel * weight) / weight.sum())
                row["mu_rel_error_max"] = float(rel.max())
    coarse_ref = results.get("ehl:fast:auto" + f" ({rough_positions}x{rough_slices} mesh)")
    for row in rows:
        if "coarse" in row["group"] and coarse_ref is not None and row.get("power_loss_w") is not None:
            row["rel_error_vs_rough_per_point"] = row["power_loss_w"] / coarse_ref.power_loss - 1
    if previous is not None:
        labels = {row["label"] for row in rows}
        rows = [r for r in previous["rows"] if r["label"] not in labels] + rows
    return {
        "case": name, "source": case["source"], "torque_nm": case["torque_nm"], "speed_rpm": case["speed_rpm"],
        "lubricant": lub, "oil_temperature_k": temperature, "rq_m": rq, "positions": positions, "slices": slices,
        "loaded_points": int((mesh.loads > 0).sum()), "input_power_w": case["torque_nm"] * speed,
        "mesh_time_s": mesh.wall_time_s, "coefficient_files": [p.name for p in coefficient_files],
        "rows": rows,
    }


def markdown(report) -> str:
    lines = []
    for case in report["cases"]:
        lines.append(f"\n### {case['case']}: {case['source']}\n")
        lines.append(f"{case['positions']} positions × {case['slices']} slices, {case['loaded_points']} loaded "
                     f"points, "
                     f"input power {case['input_power_w'] / 1e3:.1f} kW\n")
        lines.append("| model | Rq [µm] | P [W] | η [%] | μ̄ | error vs EHL standard | interp. error (same level) "
                     "| EHL solves | wall time [s] |")
        lines.append("|---|---|---|---|---|---|---|---|---|")
        for row in case["rows"]:
            if "error" in row:
                lines.append(f"| {row['label']} | {row['rq_m'] * 1e6:.2g} | failed: {row['error'][:160]} | | | | | | "
                             f"{row['wall_time_s']:.1f} |")
                continue
            err = row.get("rel_error_vs_reference")
            err_txt = f"{err * 100:+.2f} %" if err is not None else (
                f"{row['rel_error_vs_rough_per_point'] * 100:+.2f} % vs rough per point"
                if row.get("rel_error_vs_rough_per_point") is not None else "")
            same = row.get("rel_error_vs_same_level_per_point")
            lines.append(f"| {row['label']} | {row['rq_m'] * 1e6:.2g} | {row['power_loss_w']:.1f} | "
                         f"{row['efficiency'] * 100:.3f} | {row['mu_mean']:.4f} | {err_txt} | "
                         f"{'' if same is None else f'{same * 100:+.2f} %'} | {row['ehl_solves'] or ''} | "
                         f"{row['wall_time_s']:.2f} |")
    return "\n".join(lines)


def draw_figure(report, path) -> None:
    """|error in P| against the EHL standard per-point reference versus wall time, per case (log-log)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, len(report["cases"]), figsize=(5.5 * len(report["cases"]), 4.2), squeeze=False)
    styles = {"smooth EHL per point": ("s", "C0"), "smooth EHL grid": ("o", "C1"), "published": ("^", "C2"),
              "surrogate": ("D", "C3")}
    for ax, case in zip(axes[0], report["cases"]):
        for row in case["rows"]:
            err = row.get("rel_error_vs_reference")
            if row["group"] not in styles or err is None or row["label"] == "ehl:standard":
                continue
            marker, color = styles[row["group"]]
            ax.loglog(row["wall_time_s"], max(abs(err), 1e-5) * 100, marker, color=color)
            label = row["label"].replace("ehl-grid:", "grid ").replace("ehl:", "per point ")
            ax.annotate(label.replace("surrogate ", "").replace(".json", ""),
                        (row["wall_time_s"], max(abs(err), 1e-5) * 100), fontsize=7,
                        xytext=(4, -10) if row["group"] == "smooth EHL per point" else (4, 2),
                        textcoords="offset points")
        ref = next((r for r in case["rows"] if r["label"] == "ehl:standard"), None)
        if ref is not None:
            ax.axvline(ref["wall_time_s"], color="C0", ls=":", lw=1)
            ax.text(ref["wall_time_s"], ax.get_ylim()[1], " reference\n (EHL standard\n per point)", fontsize=7,
                    va="top", color="C0")
        present = {row["group"] for row in case["rows"] if row.get("rel_error_vs_reference") is not None}
        for group, (marker, color) in styles.items():
            if group in present:
                ax.plot([], [], marker, color=color, label=group)
        ax.set_xlabel("wall time of the loss evaluation [s] (2-core shared machine)")
        ax.set_ylabel("|P / P_ref − 1| [%]")
        ax.set_title(f"{case['case']}: P_ref = {ref['power_loss_w']:.0f} W" if ref else case["case"], fontsize=9)
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", default="design_D,fzg_C")
    parser.add_argument("--positions", type=int, default=24)
    parser.add_argument("--slices", type=int, default=30)
    parser.add_argument("--rough-per-point", action="store_true",
                        help="also the rough per-point EHL on a coarser mesh (slow: transient solves)")
    parser.add_argument("--rough-positions", type=int, default=8)
    parser.add_argument("--rough-slices", type=int, default=8)
    parser.add_argument("--rough-models", default="ehl-grid:fast:auto:4x6",
                        help="comma-separated EHL models for the rough surfaces (default ehl-grid:fast:auto:4x6)")
    parser.add_argument("--rough-only", action="store_true",
                        help="run only the rough models and add their rows to the existing --out file")
    parser.add_argument("--out", default=str(RESULTS))
    parser.add_argument("--figure", help="draw error versus wall time from --out into this PNG and exit")
    args = parser.parse_args(argv)
    if args.figure:
        report = json.loads(Path(args.out).read_text())
        draw_figure(report, args.figure)
        print(markdown(report))
        return 0

    started = time.perf_counter()
    all_cases = cases()
    report = {"benchmark": "gear_friction", "cases": []}
    previous = {}
    if Path(args.out).exists():  # keep the other cases of an earlier run (and, with --rough-only, its rows)
        old = json.loads(Path(args.out).read_text())
        if args.rough_only:
            previous = {c["case"]: c for c in old["cases"]}
        report["cases"] = [c for c in old["cases"] if c["case"] not in args.cases.split(",")]
    for name in args.cases.split(","):
        report["cases"].append(evaluate_case(name, all_cases[name], args.positions, args.slices,
                                             args.rough_per_point, args.rough_positions, args.rough_slices,
                                             tuple(m for m in args.rough_models.split(",") if m), args.rough_only,
                                             previous.get(name)))
        Path(args.out).parent.mkdir(parents=True, exist_ok=True)
        _write(report, args.out, started)
    print(markdown(report))
    return 0


def _write(report, path, started):
    report["total_time_s"] = time.perf_counter() - started
    report["machine"] = {**machine_info(), "load_average_1min": os.getloadavg()[0]}
    with open(path, "w") as handle:
        json.dump(report, handle, indent=1, default=lambda v: v.item() if hasattr(v, "item") else str(v))


if __name__ == "__main__":
    sys.exit(main())
