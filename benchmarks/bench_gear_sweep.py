"""Time per design of the paper's design sweep (Li & Kahraman 2009 §3) and the study figures.

Evaluates the feasible designs of ``paper2009`` (all of them, or every ``--stride``-th) at the study's operating
point with a friction model, and writes one JSON object (stdout and ``--out``) with the time per design (median,
p10, p90 over the designs; first design excluded: it loads the numba cache), the resolution, the totals and the
design-D search result, plus the machine (platform, cpu count, python/numpy versions). Optionally:
``--csv FILE`` the sweep table, ``--figures DIR`` the study figures (P against N, m, d_o, Φ, Ψ, Λ_wd with the
paper's "sole influence" lines, and P against TE, σ_c, σ_b with Designs A–D marked), ``--modifications`` the Fig. 6
study on Design D (M_P, M_L 0–30 µm at 50, 250, 500 N·m) with its figure.

Run: ``python benchmarks/bench_gear_sweep.py [--stride 1] [--friction xu2007] [--positions 24 --slices 30]
[--out benchmarks/results/gear_sweep.json] [--csv sweep.csv] [--figures docs/figures] [--modifications]``
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np

# _common.py sits next to this file (sys.path: see bench_ehl_mixed.py)
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import emit_json, machine_info  # noqa: E402

FIG3_LINE = {"normal_pressure_angle_deg": 22.5, "helix_angle_deg": 20.0, "working_depth": 2.286}
FIG4_LINES = {
    "normal_pressure_angle_deg": {"teeth": 30, "helix_angle_deg": 20.0, "working_depth": 2.286},
    "helix_angle_deg": {"teeth": 30, "normal_pressure_angle_deg": 22.5, "working_depth": 2.286},
    "working_depth": {"teeth": 30, "normal_pressure_angle_deg": 22.5, "helix_angle_deg": 20.0},
}


def machine() -> dict:
    return {**machine_info(), "load_average_1min_at_start": os.getloadavg()[0]}


def _scatter(ax, table, x, scale, label, line=None, line_x=None):
    ax.scatter(table[x] * scale, table["power_loss_w"] / 1e3, s=2, alpha=0.25, color="0.6", rasterized=True,
               label="feasible designs")
    if line is not None and len(line):
        ax.plot(line[line_x or x] * scale, line["power_loss_w"] / 1e3, "o-", color="C3", ms=4, label="sole influence")
    ax.set_xlabel(label)
    ax.set_ylabel("P [kW]")
    ax.grid(alpha=0.3)


def figures(table, study, out_dir: Path, friction_label: str, designs: dict, lines: dict) -> list[str]:
    """The study figures; ``lines`` maps "teeth" and the FIG4_LINES columns to the tables of the paper's "sole
    influence" lines (evaluated on their own, so that they are complete for subset runs too)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out_dir.mkdir(parents=True, exist_ok=True)
    valid = table[table["converged"].astype(bool)]
    lines = {k: v[v["converged"].astype(bool)] for k, v in lines.items()}
    written = []

    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5), sharey=True)
    line3 = lines["teeth"]
    _scatter(axes[0, 0], valid, "teeth", 1.0, "N", line3)
    _scatter(axes[0, 1], valid, "normal_module_m", 1e3, "m_n [mm]", line3)
    _scatter(axes[0, 2], valid, "tip_diameter_m", 1e3, "d_o [mm]", line3)
    for ax, column, label in zip(axes[1], ("normal_pressure_angle_deg", "helix_angle_deg", "working_depth"),
                                 ("Φ [deg]", "Ψ [deg]", "Λ_wd")):
        _scatter(ax, valid, column, 1.0, label, lines[column])
    axes[0, 0].legend(loc="upper right", fontsize=8)
    fig.suptitle(f"Power loss of {len(valid)} feasible designs, 250 N·m, 4000 rpm, ATF 90 °C, Rq 0.4 µm, "
                 f"M_P 15 µm, M_L 12 µm; friction: {friction_label}\n(cf. Li & Kahraman 2009, Fig. 3a-c and 4a-c; "
                 "lines: Φ 22.5°, Ψ 20°, Λ_wd 2.286 for N, m, d_o; N = 30 with the other two fixed for Φ, Ψ, Λ_wd)",
                 fontsize=10)
    fig.tight_layout()
    path = out_dir / "sweep_power_loss.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    written.append(str(path))

    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2), sharey=True)
    for ax, column, scale, label, limit_key, limit_scale in (
            (axes[0], "te_pp_m", 1e6, "peak-to-peak TE [µm]", "max_transmission_error_m", 1e6),
            (axes[1], "sigma_c_pa", 1e-9, "max σ_c [GPa]", "max_contact_stress_pa", 1e-9),
            (axes[2], "sigma_b_pa", 1e-6, "max σ_b [MPa]", "max_root_stress_pa", 1e-6)):
        _scatter(ax, valid, column, scale, label)
        limit = study.search_limits.get(limit_key)
        if limit is not None:
            ax.axvline(limit * limit_scale, color="C0", ls="--", lw=1, label="design-D search limit")
        ax.axhline(study.search_limits.get("max_power_loss_w", np.nan) / 1e3, color="C0", ls=":", lw=1)
        for name, row in designs.items():
            ax.plot(row[column] * scale, row["power_loss_w"] / 1e3, "s", ms=7, mfc="none", color="C1")
            ax.annotate(name, (row[column] * scale, row["power_loss_w"] / 1e3), xytext=(4, 4),
                        textcoords="offset points", color="C1", fontsize=10, weight="bold")
    axes[0].legend(loc="upper right", fontsize=8)
    fig.suptitle(f"P against TE, σ_c, σ_b (cf. Li & Kahraman 2009, Fig. 5); Table 1 designs A-D marked; "
                 f"friction: {friction_label}", fontsize=10)
    fig.tight_layout()
    path = out_dir / "sweep_tradeoffs.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    written.append(str(path))
    return written


def modification_figure(table, out_dir: Path, friction_label: str) -> str:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 4, figsize=(16, 4.2))
    quantities = (("power_loss_w", 1e-3, "P [kW]"), ("te_pp_m", 1e6, "peak-to-peak TE [µm]"),
                  ("sigma_c_pa", 1e-9, "max σ_c [GPa]"), ("sigma_b_pa", 1e-6, "max σ_b [MPa]"))
    leads = sorted(set(np.round(table["lead_crown_m"], 9)))
    shown = [leads[0], leads[len(leads) // 2], leads[-1]]
    for ax, (column, scale, label) in zip(axes, quantities):
        for k, torque in enumerate(sorted(set(table["torque_nm"]))):
            for style, lead in zip(("-", "--", ":"), shown):
                rows = table[(table["torque_nm"] == torque) & np.isclose(table["lead_crown_m"], lead)]
                rows = rows.sort_values("profile_crown_m")
                ax.plot(rows["profile_crown_m"] * 1e6, rows[column] * scale, style, color=f"C{k}", marker="o", ms=3,
                        label=f"T = {torque:.0f} N·m, M_L = {lead * 1e6:.0f} µm")
        ax.set_xlabel("profile crown M_P [µm]")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.suptitle(f"Design D: tooth modifications (cf. Li & Kahraman 2009, Fig. 6); friction: {friction_label}",
                 fontsize=10)
    fig.tight_layout()
    path = out_dir / "modifications_design_d.png"
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return str(path)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--stride", type=int, default=1, help="every K-th feasible design (default 1: all)")
    parser.add_argument("--limit", type=int, default=None, help="at most N designs")
    parser.add_argument("--friction", default="xu2007")
    parser.add_argument("--positions", type=int, default=24)
    parser.add_argument("--slices", type=int, default=30)
    parser.add_argument("--out", help="also write the JSON here")
    parser.add_argument("--csv", help="write the sweep table here")
    parser.add_argument("--figures", help="directory for the study figures")
    parser.add_argument("--modifications", action="store_true", help="also run the Fig. 6 study on Design D")
    args = parser.parse_args(argv)

    from efficiency.design_io import load_study
    from efficiency.friction import describe_friction, friction_from_spec
    from efficiency.mesh_cycle import MeshOptions
    from efficiency.studies import (StudyPoint, design_sweep, evaluate_design, feasible_designs, find_design_like_d,
                                    modification_study, rank_by_limits, trend_line)

    study = load_study("paper2009")
    point = StudyPoint.from_operating_point(study.operating_point)
    friction = friction_from_spec(args.friction, study.operating_point.lubricant)
    options = MeshOptions(positions=args.positions, slices=args.slices)
    n_feasible = len(feasible_designs(study.space, study.limits))

    host = machine()
    started, cpu_started = time.perf_counter(), time.process_time()
    table = design_sweep(study.space, friction, point, study.limits, options, stride=args.stride, limit=args.limit)
    total, cpu_total = time.perf_counter() - started, time.process_time() - cpu_started
    times = table["wall_time_s"].to_numpy()[1:]
    matches = find_design_like_d(table, study.search_limits)
    nearest = rank_by_limits(table, study.search_limits).head(5)
    published = {name: evaluate_design(study.design(name), friction, point, options) for name in study.designs}

    def brief(row) -> dict:
        return {k: (int(row[k]) if k == "teeth" else float(row[k])) for k in (
            "teeth", "normal_pressure_angle_deg", "helix_angle_deg", "working_depth", "power_loss_w", "te_pp_m",
            "sigma_c_pa", "sigma_b_pa", "worst_ratio")}

    result = {
        "benchmark": "gear_sweep", **host, "load_average_1min_at_end": os.getloadavg()[0],
        "note": "wall times include waiting for the CPU when the machine is shared (see the load averages); "
                "cpu_time_per_design_s is this process's CPU time per design (single-threaded)",
        "friction_model": describe_friction(friction), "positions": options.positions, "slices": options.slices,
        "contact_model": options.contact_model, "stride": args.stride, "designs_feasible": n_feasible,
        "designs_evaluated": int(len(table)), "converged": int(table["converged"].sum()),
        "errors": int((~table["error"].isna() & (table["error"].astype(str) != "")).sum()),
        "time_per_design_median_s": float(np.median(times)) if times.size else None,
        "time_per_design_p10_s": float(np.percentile(times, 10)) if times.size else None,
        "time_per_design_p90_s": float(np.percentile(times, 90)) if times.size else None,
        "sweep_wall_time_s": total, "cpu_time_per_design_s": cpu_total / max(len(table), 1),
        "projected_full_sweep_s": float(np.median(times)) * n_feasible if times.size else None,
        "power_loss_w_range": [float(table["power_loss_w"].min()), float(table["power_loss_w"].max())],
        "te_pp_m_range": [float(table["te_pp_m"].min()), float(table["te_pp_m"].max())],
        "sigma_c_pa_range": [float(table["sigma_c_pa"].min()), float(table["sigma_c_pa"].max())],
        "sigma_b_pa_range": [float(table["sigma_b_pa"].min()), float(table["sigma_b_pa"].max())],
        "design_d_search_limits": study.search_limits, "designs_like_d": int(len(matches)),
        "nearest_to_limits": [brief(r) for _, r in nearest.iterrows()],
        "table1_designs": {name: {k: row[k] for k in ("power_loss_w", "efficiency", "te_pp_m", "sigma_c_pa",
                                                      "sigma_b_pa", "converged")}
                           for name, row in published.items()},
    }
    if args.csv:
        table.to_csv(args.csv, index=False)
        result["csv"] = args.csv
    if args.figures:
        lines = {"teeth": trend_line(design_sweep(study.space, friction, point, study.limits, options,
                                                  where=FIG3_LINE), "teeth", {})}
        for column, fixed in FIG4_LINES.items():
            lines[column] = trend_line(design_sweep(study.space, friction, point, study.limits, options,
                                                    where=fixed), column, {})
        result["figures"] = figures(table, study, Path(args.figures), describe_friction(friction), published, lines)
    if args.modifications:
        started = time.perf_counter()
        grid = [i * 5e-6 for i in range(7)]
        mods = modification_study(study.design("D"), friction, grid, grid, [50.0, 250.0, 500.0], point, options)
        result["modification_study_wall_time_s"] = time.perf_counter() - started
        result["modification_cases"] = int(len(mods))
        if args.figures:
            result["figures"].append(modification_figure(mods, Path(args.figures), describe_friction(friction)))
    emit_json(result, args.out, indent=2, default=float)
    return 0


if __name__ == "__main__":
    sys.exit(main())
