"""The Ohio State spur pair of Petry-Johnson et al. (J. Mech. Des. 130 (2008) 062601) at 413 N·m and
2,000–10,000 rpm: mesh friction power loss and efficiency against speed with the project's friction routes.

The pair from its manufacturing data (shared/reference/gear_cases.md: z 40/40, pitch diameter 92.74 mm, α 28°,
outside diameter 95.95 mm, root diameter 85.90 mm, circular tooth thickness 2.925 mm, fillet radius 0.83 mm, face
width 26.7 mm, centre distance 91.5 mm, Rq 0.07 µm), unmodified flanks (no modifications are published), the
75W90 oil of data/lubricants/gear_oil_75w90.toml at the inlet temperature at which its published η0 = 10.6 mPa·s
holds (100 °C in that file, an assumption it flags). Routes:
- ``xu2007``: Xu et al. 2007's formula (fitted to this 75W90) at every contact point of the elastic mesh cycle;
- ``ehl-grid:fast``: the project's EHL solver on a grid per side of the pitch point, interpolated;
- ``iso14179-2``: ISO/TR 14179-2's μ_mz with X_L of a mineral base oil (0.846; the base of this 75W90 is not
  published) and Ra = √(2/π) Rq, P_VZP = μ_mz H_V P_in (efficiency.iso14179).
No thermal correction of the contact friction is applied (issue 17, deliverable 5: pending). The measured losses
of the paper are not in the sources available to this project; see docs/gear_validation.md.

Run: ``python benchmarks/validation_petry_johnson.py [--figure docs/figures/petry_johnson.png]``; writes
benchmarks/results/petry_johnson.json.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import emit_json, machine_info  # noqa: E402

SPEEDS_RPM = (2000, 4000, 6000, 8000, 10000)
TORQUE_NM = 413.0
RQ = 0.07e-6
OIL_TEMPERATURE_K = 373.15


def osu_pair():
    """The OSU test pair from its manufacturing data (module docstring)."""
    from efficiency.geometry import GearPair

    return GearPair(z1=40, z2=40, normal_module=92.74e-3 / 40, normal_pressure_angle=math.radians(28.0),
                    helix_angle=0.0, face_width=26.7e-3, center_distance=91.5e-3,
                    root_fillet_coefficient=0.83 / (92.74 / 40), tip_diameters=(95.95e-3, 95.95e-3),
                    root_diameters_given=(85.90e-3, 85.90e-3), normal_thicknesses_given=(2.925e-3, 2.925e-3))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "petry_johnson.json"))
    parser.add_argument("--figure", help="write the loss/efficiency plot here (PNG)")
    parser.add_argument("--routes", default="xu2007,iso14179-2,ehl-grid:fast")
    args = parser.parse_args(argv)

    from ehl_dataset.model.lubricant import load_lubricant
    from efficiency.friction_accuracy import friction_from_name
    from efficiency.iso14179 import iso_14179_2_mesh, lubricant_factor
    from efficiency.mesh_cycle import MeshOptions, evaluate_mesh
    from efficiency.power_loss import mesh_power_loss
    from surrogate.features import lubricant_properties
    from surrogate.published import RA_PER_RQ

    pair = osu_pair()
    lubricant = load_lubricant("gear_oil_75w90")
    eta, _ = lubricant_properties(lubricant, OIL_TEMPERATURE_K)
    routes = [r.strip() for r in args.routes.split(",") if r.strip()]
    rows = []
    for rpm in SPEEDS_RPM:
        omega = rpm * math.pi / 30.0
        mesh = evaluate_mesh(pair, TORQUE_NM, omega, options=MeshOptions(outputs=frozenset()))
        row = {"speed_rpm": rpm, "input_power_w": TORQUE_NM * omega, "loss_factor": mesh.loss_factor,
               "pitch_line_velocity_m_s": omega * float(pair.working_pitch_radii[0])}
        for route in routes:
            started = time.perf_counter()
            if route == "iso14179-2":
                out = iso_14179_2_mesh(pair, TORQUE_NM, omega, float(eta), RA_PER_RQ * RQ, RA_PER_RQ * RQ,
                                       lubricant_factor("mineral"))
                loss, mu = out["p_vzp_w"], out["mu_mz"]
            else:
                result = mesh_power_loss(mesh, friction_from_name(route, lubricant), OIL_TEMPERATURE_K, RQ, RQ)
                loss = result.power_loss
                loaded = mesh.loads > 0
                mu = float((result.mu[loaded] * mesh.loads[loaded]).sum() / mesh.loads[loaded].sum())
            row[route] = {"power_loss_w": loss, "efficiency": 1.0 - loss / row["input_power_w"], "mu_mean": mu,
                          "time_s": time.perf_counter() - started}
        rows.append(row)
        print(rpm, {r: round(row[r]["power_loss_w"], 1) for r in routes}, file=sys.stderr)
    report = {"benchmark": "Petry-Johnson et al. 2008 OSU spur pair: mesh friction loss against speed",
              "torque_nm": TORQUE_NM, "oil_temperature_k": OIL_TEMPERATURE_K, "eta_oil_pa_s": float(eta),
              "rq_m": RQ, "thermal_correction": "none (pending, issue 17 deliverable 5)",
              "measured_losses": "not available in the project's sources", "machine": machine_info(), "rows": rows}
    emit_json(report, args.out)
    if args.figure:
        draw(report, routes, args.figure)
    return 0


def draw(report, routes, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = report["rows"]
    speeds = [r["speed_rpm"] for r in rows]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    for route, marker in zip(routes, "osd^v"):
        ax1.plot(speeds, [r[route]["power_loss_w"] / 1e3 for r in rows], marker=marker, label=route)
        ax2.plot(speeds, [100 * r[route]["efficiency"] for r in rows], marker=marker, label=route)
    ax1.set_xlabel("pinion speed [rpm]")
    ax1.set_ylabel("mesh friction power loss [kW]")
    ax2.set_xlabel("pinion speed [rpm]")
    ax2.set_ylabel("mechanical mesh efficiency [%]")
    ax1.set_title("OSU spur pair, 413 N·m, 75W90 (no thermal correction)", fontsize=9)
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    raise SystemExit(main())
