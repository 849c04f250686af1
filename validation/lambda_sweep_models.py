"""μ(λ̄) of every contact model on the roughness sweep of validation/deterministic_lambda_sweep.py: the trend of the
paper's Fig. 2 as each model draws it, against the deterministic solver.

    python validation/deterministic_lambda_sweep.py --spacing 16 --passes 11     # first: the deterministic runs
    python validation/lambda_sweep_models.py                                       # then: the other models + figure
    python validation/lambda_sweep_models.py --plot                                # the figure from the JSON only
    python validation/lambda_sweep_models.py --sweep J --models smooth-standard homogenised-film_law-standard

``--sweep TAG``: the tagged sweep of another contact (deterministic_lambda_sweep_<TAG>.json), written to
lambda_sweep_models_<TAG>.json and docs/figures/mu_lambda_models_<TAG>.png; ``--models``: a subset of the models.

Same conditions (case A of the validation set: 0.5 GPa / 5 mm / 5 m/s / SR 0.3 / 90 °C, ATF, Rq1 = Rq2 = each Rq of
the deterministic sweep); the models of workflows.accuracy_mixed.MIXED_MODELS except the deterministic levels.
Writes validation/results/lambda_sweep_models.json (resumable) and docs/figures/mu_lambda_models.png.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solver import SOLVER_VERSION
from workflows.accuracy_mixed import solve_model

ROOT = Path(__file__).resolve().parents[1]
SWEEP = ROOT / "validation" / "results" / "deterministic_lambda_sweep.json"
OUT = ROOT / "validation" / "results" / "lambda_sweep_models.json"
FIGURE = ROOT / "docs" / "figures" / "mu_lambda_models.png"
MODELS = ("smooth-standard", "homogenised-transverse-standard", "homogenised-isotropic-standard",
          "homogenised-film_law-standard")
"""The models run and drawn (the results file may hold rows of other models; the figure draws only these)."""
COMMAND = "python validation/lambda_sweep_models.py"


def paths(tag: str | None) -> tuple[Path, Path, Path]:
    """(deterministic sweep, this script's record, figure) of the sweep ``tag`` (None: case A's)."""
    if not tag:
        return SWEEP, OUT, FIGURE
    return (SWEEP.with_name(f"{SWEEP.stem}_{tag}.json"), OUT.with_name(f"{OUT.stem}_{tag}.json"),
            FIGURE.with_name(f"{FIGURE.stem}_{tag}.png"))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--plot", action="store_true", help="the figure from the JSON only")
    parser.add_argument("--sweep", default=None, help="tag of another contact's deterministic sweep")
    parser.add_argument("--models", nargs="+", default=list(MODELS), choices=MODELS)
    args = parser.parse_args(argv)
    sweep_path, out, figure = paths(args.sweep)
    if args.plot:
        plot(json.loads(out.read_text()), figure)
        return 0
    sweep = json.loads(sweep_path.read_text())
    lubricant = load_lubricant("atf")
    record = json.loads(out.read_text()) if out.exists() else {}
    if record.get("solver_version") != SOLVER_VERSION:
        record = {"solver_version": SOLVER_VERSION, "conditions": sweep["conditions"], "runs": {}}
    record["deterministic"] = {"model_version": sweep["model_version"], "points_per_beta": sweep["points_per_beta"],
                               "passes": sweep["passes"],
                               "runs": {k: {f: v[f] for f in ("rq_um", "lambda_bar", "mu", "mu_sem",
                                                              "asperity_load_share", "wall_time_s")}
                                        for k, v in sweep["runs"].items()}}
    out.write_text(json.dumps(record, indent=1, default=float))
    for key, run in sorted(sweep["runs"].items(), key=lambda kv: kv[1]["rq_um"]):
        case = ContactCase.from_engineering(*sweep["conditions"], run["rq_um"], run["rq_um"])
        for name in args.models:
            slot = record["runs"].setdefault(name, {})
            if key in slot:
                continue
            start = time.perf_counter()
            result = solve_model(case, lubricant, name)
            slot[key] = {"rq_um": run["rq_um"], "lambda_bar": result.lambda_bar, "mu": result.mu,
                         "mu_sem": result.mu_sem, "asperity_load_share": result.asperity_load_share,
                         "converged": result.converged, "wall_time_s": time.perf_counter() - start}
            out.write_text(json.dumps(record, indent=1, default=float))
            print(f"{name} Rq {run['rq_um']:g}: μ {result.mu:.5f} ({slot[key]['wall_time_s']:.1f} s)", flush=True)
    plot(record, figure)
    return 0


def plot(record: dict, figure: Path = FIGURE) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.ticker

    det = sorted(record["deterministic"]["runs"].values(), key=lambda r: r["lambda_bar"])
    fig, ax = plt.subplots(figsize=(7.0, 4.6))
    lam = np.array([r["lambda_bar"] for r in det])
    ax.errorbar(lam, [r["mu"] for r in det], yerr=[2 * r["mu_sem"] for r in det], color="k", marker="o", lw=2,
                capsize=3, label=f"deterministic (β/{record['deterministic']['points_per_beta']:g}, ±2 SE)")
    styles = {"smooth-standard": ("tab:gray", "s", "--"), "homogenised-transverse-standard": ("tab:blue", "D", "-"),
              "homogenised-isotropic-standard": ("tab:green", "D", "-"),
              "homogenised-film_law-standard": ("tab:purple", "o", "-.")}
    for name, runs in record["runs"].items():
        if name not in MODELS:  # rows of models the package no longer has stay in the results file, not the figure
            continue
        rows = sorted((r for r in runs.values() if r["converged"]), key=lambda r: r["lambda_bar"])
        missing = len(runs) - len(rows)
        color, marker, line = styles.get(name, ("tab:purple", "x", "-"))
        ax.plot([r["lambda_bar"] for r in rows], [r["mu"] for r in rows], color=color, marker=marker, ls=line,
                label=name + (f" ({missing} not converged, left out)" if missing else ""))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.axvline(1.0, color="0.7", lw=0.8)
    ax.set_xlabel("λ̄ (Dowson–Higginson film / composite Rq)")
    ax.set_ylabel("μ")
    c = record["conditions"]
    ax.set_title(f"μ(λ̄) per contact model: {c[0]} GPa, {c[1]} mm, {c[2]} m/s, SR {c[3]}, {c[4]} °C, ATF\n"
                 f"solver {record['solver_version']}, deterministic {record['deterministic']['model_version']}",
                 fontsize=9)
    ticks = [0.1, 0.2, 0.5, 1.0, 2.0, 5.0]
    ax.xaxis.set_major_locator(matplotlib.ticker.FixedLocator(ticks))
    ax.xaxis.set_major_formatter(matplotlib.ticker.FixedFormatter([f"{t:g}" for t in ticks]))
    ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    figure.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(figure, dpi=110)
    plt.close(fig)
    return figure


if __name__ == "__main__":
    sys.exit(main())
