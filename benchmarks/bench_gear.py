"""Speed of one loaded mesh-cycle evaluation (load distribution + TE + stresses) and its scaling with resolution.

Writes one JSON object (stdout, and ``--out FILE``, default benchmarks/results/gear.json) with medians over
repeats and the machine noted:
- time per full mesh-cycle evaluation of the paper's design D (M_P 15 µm, M_L 12 µm, 250 N·m) at the default
  resolution (30 slices × 24 positions), for the Weber (default) and the linear contact model, and with only the
  loads (no TE/stresses) requested;
- the same over a sample of designs from the paper's design space (feasible ones only);
- scaling with the number of slices S (at M = 24) and positions M (at S = 30), and the change of TE, σ_c, σ_b
  against a fine 90 × 72 reference (accuracy versus time, docs/validation/speed.md).

Run: ``python benchmarks/bench_gear.py [--repeats 7] [--out benchmarks/results/gear.json]``
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import time
from pathlib import Path

import numpy as np

# _common.py sits next to this file (sys.path: see bench_ehl_mixed.py)
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import emit_json, machine_info, median_time  # noqa: E402


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--designs", type=int, default=40, help="sampled designs of the paper's space")
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "gear.json"))
    parser.add_argument("--figure", help="also draw the design-D figure of docs/explanation/gear-model.md here")
    args = parser.parse_args(argv)
    if args.figure:
        draw_figure(args.figure)

    from efficiency.design_io import paper_design
    from efficiency.feasibility import check_design
    from efficiency.geometry import GearPair
    from efficiency.mesh_cycle import MeshOptions, evaluate_mesh
    from efficiency.modifications import Modifications

    deg = math.pi / 180
    design_d = GearPair.from_paper(32, 30 * deg, 19 * deg, 2.068)
    mods = Modifications.paper()
    evaluate_mesh(design_d, 250.0, modifications=mods)  # load the numba cache / compile once

    def timed(options, pair=design_d):
        return median_time(lambda: evaluate_mesh(pair, 250.0, modifications=mods, options=options), args.repeats)

    default = MeshOptions()
    from _common import repeat_times  # noqa: E402

    warm = repeat_times(lambda: evaluate_mesh(design_d, 250.0, modifications=mods, options=default),
                        max(args.repeats, 15))
    results = {
        "design_d_default_s": statistics.median(warm),
        "design_d_default_min_s": min(warm),
        "design_d_default_positions": int(evaluate_mesh(design_d, 250.0, modifications=mods).kinematics.shape[0]),
        "design_d_linear_contact_s": timed(MeshOptions(contact_model="linear")),
        "design_d_loads_only_s": timed(MeshOptions(outputs=frozenset())),
    }

    # a sample of feasible designs of the paper's space
    rng = np.random.default_rng(2009)
    sample_times = []
    tried = 0
    while len(sample_times) < args.designs and tried < 20 * args.designs:
        tried += 1
        try:
            pair = paper_design(int(rng.integers(20, 54)), float(rng.choice(np.arange(15, 30.1, 2.5))),
                                float(rng.integers(15, 31)), float(rng.choice(np.linspace(1.85, 3.376, 8))))
            if not check_design(pair).feasible:
                continue
            start = time.perf_counter()
            evaluate_mesh(pair, 250.0, modifications=mods)
            sample_times.append(time.perf_counter() - start)
        except Exception:  # noqa: BLE001 - a benchmark records, it does not stop
            continue
    results["paper_space_sample"] = {"designs": len(sample_times), "median_s": statistics.median(sample_times),
                                     "max_s": max(sample_times)}

    reference = evaluate_mesh(design_d, 250.0, modifications=mods, options=MeshOptions(slices=90, positions=72))

    def accuracy(options):
        r = evaluate_mesh(design_d, 250.0, modifications=mods, options=options)
        return {
            "te_pp_rel_error": abs(r.te_peak_to_peak / reference.te_peak_to_peak - 1),
            "sigma_c_rel_error": abs(r.sigma_c_max / reference.sigma_c_max - 1),
            "sigma_b_rel_error": abs(r.sigma_b_max / reference.sigma_b_max - 1),
        }

    results["scaling_slices"] = [
        {"slices": s, "positions": 24, "median_s": timed(MeshOptions(slices=s, positions=24)),
         **accuracy(MeshOptions(slices=s, positions=24))} for s in (10, 20, 30, 45, 60, 90)]
    results["scaling_positions"] = [
        {"slices": 30, "positions": m, "median_s": timed(MeshOptions(slices=30, positions=m)),
         **accuracy(MeshOptions(slices=30, positions=m))} for m in (8, 16, 24, 36, 48, 72)]
    results["reference_90x72"] = {"te_pp_m": reference.te_peak_to_peak, "sigma_c_pa": reference.sigma_c_max,
                                  "sigma_b_pa": reference.sigma_b_max, "wall_time_s": reference.wall_time_s}

    payload = {
        "benchmark": "gear mesh cycle (efficiency.mesh_cycle.evaluate_mesh)",
        "case": "design D (N 32, Φ 30°, Ψ 19°, Λ_wd 2.068, b 25 mm), M_P 15 µm, M_L 12 µm, 250 N·m",
        "repeats": args.repeats,
        "machine": {**machine_info(), "load_average_1_5_15_min_at_end": list(os.getloadavg())},
        "results": results,
    }
    emit_json(payload, args.out, indent=2)
    return 0


def draw_figure(path: str) -> None:
    """Design D: loads on the plane of action at the σ_c position, TE over a cycle at 50/250/500 N·m, and the mesh
    stiffness of the unmodified pair against ISO 6336-1's c_γα."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from efficiency import iso6336
    from efficiency.geometry import GearPair
    from efficiency.mesh_cycle import MeshOptions, evaluate_mesh
    from efficiency.modifications import Modifications

    pair = GearPair.from_paper(32, math.radians(30), math.radians(19), 2.068)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4))
    r = evaluate_mesh(pair, 250.0, modifications=Modifications.paper(), options=MeshOptions(slices=60, positions=48))
    kin = r.kinematics
    m = r.sigma_c_position
    inside = kin.in_contact[m]
    z = np.broadcast_to(kin.z, inside.shape)[inside] * 1e3
    s = kin.roll[m][inside] * 1e3
    sc = axes[0].scatter(z, s, c=r.load_per_length[m][inside] / 1e3, s=12, cmap="viridis")
    axes[0].axhline(kin.contact_start * 1e3, color="k", lw=0.8)
    axes[0].axhline(kin.contact_end * 1e3, color="k", lw=0.8)
    axes[0].axhline(float(pair.pitch_point) * 1e3, color="r", lw=0.8, ls="--", label="pitch point")
    axes[0].set_xlabel("face z [mm]")
    axes[0].set_ylabel("roll distance s from T1 [mm]")
    axes[0].set_title(f"design D, 250 N·m, M_P 15 / M_L 12 µm: load at φ_{m}")
    axes[0].legend(loc="upper right", fontsize=8)
    fig.colorbar(sc, ax=axes[0], label="load per length [N/mm]")
    for torque in (50.0, 250.0, 500.0):
        rt = evaluate_mesh(pair, torque, modifications=Modifications.paper(),
                           options=MeshOptions(slices=60, positions=48, outputs=frozenset({"te"})))
        axes[1].plot(rt.kinematics.mesh_angle * 1e3, rt.transmission_error * 1e6, marker=".",
                     label=f"{torque:.0f} N·m: TE_pp {rt.te_peak_to_peak * 1e6:.2f} µm")
    axes[1].set_xlabel("mesh rotation φ of gear 1 [mrad] (one base pitch)")
    axes[1].set_ylabel("loaded TE at the base circle [µm]")
    axes[1].set_title("transmission error over a mesh cycle")
    axes[1].legend(fontsize=8)
    r0 = evaluate_mesh(pair, 250.0, options=MeshOptions(slices=60, positions=48, outputs=frozenset()))
    axes[2].plot(r0.kinematics.mesh_angle * 1e3, r0.mesh_stiffness / float(pair.face_width) / 1e9, marker=".",
                 label=f"model, mean {r0.mesh_stiffness_per_width / 1e9:.1f}")
    axes[2].axhline(iso6336.mesh_stiffness(pair)[0] / 1e9, color="k", ls="--",
                    label=f"ISO 6336-1 c_γα {iso6336.mesh_stiffness(pair)[0] / 1e9:.1f}")
    axes[2].set_xlabel("mesh rotation φ of gear 1 [mrad]")
    axes[2].set_ylabel("mesh stiffness per face width [N/(mm·µm)]")
    axes[2].set_title("unmodified design D, 250 N·m")
    axes[2].legend(fontsize=8)
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
