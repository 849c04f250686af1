"""The Ohio State spur pair of Petry-Johnson et al. (J. Mech. Des. 130 (2008) 062601) at 413 N·m and
2,000–10,000 rpm: mesh friction power loss and efficiency against speed with the project's friction routes, with and
without the thermal correction of the EHL traction (ehl_dataset/model/thermal.py).

The pair from its manufacturing data (Petry-Johnson et al. 2008, gear table: z 40/40, pitch diameter 92.74 mm, α 28°,
outside diameter 95.95 mm, root diameter 85.90 mm, circular tooth thickness 2.925 mm, fillet radius 0.83 mm, face
width 26.7 mm, centre distance 91.5 mm, Rq 0.07 µm), unmodified flanks (no modifications are published), the
75W90 oil of data/lubricants/gear_oil_75w90.toml at the inlet temperature at which its published η0 = 10.6 mPa·s
holds (100 °C in that file, an assumption it flags); the bulk temperature of the teeth is taken equal to it. Routes:
- ``xu2007``: Xu et al. 2007's formula (fitted to a thermal EHL model for this 75W90) at every contact point of the
  elastic mesh cycle;
- ``iso14179-2``: ISO/TR 14179-2's μ_mz with X_L of a mineral base oil (0.846; the base of this 75W90 is not
  published) and Ra = √(2/π) Rq, P_VZP = μ_mz H_V P_in (efficiency.iso14179);
- ``ehl-grid:fast``: the project's default EHL route (the planner decides every effect, the thermal correction
  included; where λ̄ < 3.5 the rough contact goes to the steady film-law model);
- ``ehl-grid:fast:isothermal``: the same without the thermal correction;
- ``ehl-smooth:isothermal`` / ``ehl-smooth:thermal``: the EHL solver on smooth surfaces (steady), without and with
  the thermal correction at every point (``fast`` level, the same 5 × 9 grid per side of the pitch point).
The measured losses of the paper are not in the sources available to this project; see docs/validation/gear.md.

Run: ``python validation/petry_johnson.py [--figure docs/figures/petry_johnson.png]``; writes
validation/results/petry_johnson.json (``--from-json validation/results/petry_johnson.json --figure F`` redraws the
figure only).

``--finish`` compares the surface finishes of the tests instead, superfinished (Rq 0.07 µm) against ground (Rq
0.3 µm), at 2,000 and 10,000 rpm: Xu's formula (its roughness term, fitted to a mixed-EHL model), ISO/TR 14179-2
(through Ra) and the default EHL route ``ehl-grid:fast`` (the asperity-load closure on the flank-like default
profile, spectral pressure spread), the same with the inlet form of the spread, and on the Gaussian baseline profile;
writes validation/results/petry_johnson_finish.json.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))  # _common.py, shared with the speed benchmarks
from _common import emit_json, machine_info  # noqa: E402

SPEEDS_RPM = (2000, 4000, 6000, 8000, 10000)
ROUTES = ("xu2007", "iso14179-2", "ehl-grid:fast", "ehl-grid:fast:isothermal", "ehl-smooth:isothermal",
          "ehl-smooth:thermal")
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
    parser.add_argument("--routes", default=",".join(ROUTES))
    parser.add_argument("--from-json", help="only redraw the figure from this JSON (a previous run's --out)")
    parser.add_argument("--finish", action="store_true",
                        help="superfinished against ground flanks (module docstring) instead of the speed sweep")
    args = parser.parse_args(argv)
    if args.finish:
        return finish(Path(__file__).parent / "results" / "petry_johnson_finish.json"
                      if args.out == parser.get_default("out") else Path(args.out))
    if args.from_json:
        import json

        report = json.loads(Path(args.from_json).read_text())
        draw(report, [r for r in ROUTES if r in report["rows"][0]], args.figure)
        return 0

    from ehl_dataset.model.contact import ContactCase
    from ehl_dataset.model.effects import Effects
    from ehl_dataset.model.lubricant import load_lubricant
    from ehl_dataset.solver import SOLVER_VERSION
    from ehl_dataset.solvers.planner import dimensionless_numbers
    from efficiency.friction import EhlGridFriction, friction_from_spec
    from efficiency.iso14179 import iso_14179_2_mesh, lubricant_factor
    from efficiency.mesh_cycle import MeshOptions, evaluate_mesh
    from efficiency.power_loss import contact_conditions, mesh_power_loss
    from surrogate.features import lubricant_properties
    from surrogate.published import RA_PER_RQ

    pair = osu_pair()
    lubricant = load_lubricant("gear_oil_75w90")
    eta, _ = lubricant_properties(lubricant, OIL_TEMPERATURE_K)
    smooth = {"ehl-smooth:isothermal": Effects(False, False, True, True, "forced",
                                               {"forced": "smooth surfaces, isothermal traction"}),
              "ehl-smooth:thermal": Effects(False, False, True, True, "forced",
                                            {"forced": "smooth surfaces, thermal correction"}, thermal=True)}
    routes = [r.strip() for r in args.routes.split(",") if r.strip()]
    rows = []
    for rpm in SPEEDS_RPM:
        omega = rpm * math.pi / 30.0
        mesh = evaluate_mesh(pair, TORQUE_NM, omega, options=MeshOptions(outputs=frozenset()))
        row = {"speed_rpm": rpm, "input_power_w": TORQUE_NM * omega, "loss_factor": mesh.loss_factor,
               "pitch_line_velocity_m_s": omega * float(pair.working_pitch_radii[0]),
               "planner_at_max_sliding": _planner_at_max_sliding(mesh, lubricant, contact_conditions, ContactCase,
                                                                 dimensionless_numbers)}
        for route in routes:
            started = time.perf_counter()
            if route == "iso14179-2":
                out = iso_14179_2_mesh(pair, TORQUE_NM, omega, float(eta), RA_PER_RQ * RQ, RA_PER_RQ * RQ,
                                       lubricant_factor("mineral"))
                loss, mu = out["p_vzp_w"], out["mu_mz"]
            else:
                friction = (EhlGridFriction(lubricant, "fast", smooth[route]) if route in smooth
                            else friction_from_spec(route, lubricant))
                result = mesh_power_loss(mesh, friction, OIL_TEMPERATURE_K, RQ, RQ)
                loss = result.power_loss
                loaded = mesh.loads > 0
                mu = float((result.mu[loaded] * mesh.loads[loaded]).sum() / mesh.loads[loaded].sum())
            row[route] = {"power_loss_w": loss, "efficiency": 1.0 - loss / row["input_power_w"], "mu_mean": mu,
                          "time_s": time.perf_counter() - started}
        rows.append(row)
        print(rpm, {r: round(row[r]["power_loss_w"], 1) for r in routes}, file=sys.stderr)
    report = {"benchmark": "Petry-Johnson et al. 2008 OSU spur pair: mesh friction loss against speed",
              "torque_nm": TORQUE_NM, "oil_temperature_k": OIL_TEMPERATURE_K, "eta_oil_pa_s": float(eta),
              "rq_m": RQ, "solver_version": SOLVER_VERSION,
              "thermal_correction": "ehl_dataset.model.thermal (flash temperature + film conduction, traction "
                                    "of the isothermal film); in ehl-grid:fast where the planner switches it on "
                                    "and the contact is solved smooth; everywhere in ehl-smooth:thermal",
              "measured_losses": "not available in the project's sources", "machine": machine_info(), "rows": rows}
    emit_json(report, args.out)
    if args.figure:
        draw(report, routes, args.figure)
    return 0


FINISHES_RQ = {"superfinished": 0.07e-6, "ground": 0.3e-6}
"""Rq of both flanks [m]: the tests' superfinished gears (Rq 0.07 µm, Petry-Johnson et al. 2008) and ground ones (0.3 µm)."""
FINISH_SPEEDS_RPM = (2000, 10000)
FINISH_ROUTES = ("xu2007", "iso14179-2", "ehl-grid:fast", "ehl-grid:fast inlet", "ehl-grid:fast baseline_synthetic")


def finish(out: Path) -> int:
    """Mesh loss of the superfinished and the ground pair per route and speed (module docstring)."""
    from ehl_dataset.model.lubricant import load_lubricant
    from ehl_dataset.model.roughness import named_profile
    from ehl_dataset.solver import SOLVER_VERSION
    from efficiency.friction import EhlGridFriction, friction_from_spec
    from efficiency.iso14179 import iso_14179_2_mesh, lubricant_factor
    from efficiency.mesh_cycle import MeshOptions, evaluate_mesh
    from efficiency.power_loss import mesh_power_loss
    from surrogate.features import lubricant_properties
    from surrogate.published import RA_PER_RQ

    pair = osu_pair()
    lubricant = load_lubricant("gear_oil_75w90")
    eta, _ = lubricant_properties(lubricant, OIL_TEMPERATURE_K)
    frictions = {"xu2007": friction_from_spec("xu2007", lubricant),
                 "ehl-grid:fast": EhlGridFriction(lubricant, "fast"),
                 "ehl-grid:fast inlet": EhlGridFriction(lubricant, "fast", fluctuations="inlet"),
                 "ehl-grid:fast baseline_synthetic": EhlGridFriction(lubricant, "fast",
                                                                     roughness=named_profile("baseline_synthetic"))}
    rows = []
    for rpm in FINISH_SPEEDS_RPM:
        omega = rpm * math.pi / 30.0
        mesh = evaluate_mesh(pair, TORQUE_NM, omega, options=MeshOptions(outputs=frozenset()))
        for finish_name, rq in FINISHES_RQ.items():
            row = {"speed_rpm": rpm, "finish": finish_name, "rq_m": rq, "input_power_w": TORQUE_NM * omega}
            for route in FINISH_ROUTES:
                started = time.perf_counter()
                if route == "iso14179-2":
                    res = iso_14179_2_mesh(pair, TORQUE_NM, omega, float(eta), RA_PER_RQ * rq, RA_PER_RQ * rq,
                                           lubricant_factor("mineral"))
                    loss, mu = res["p_vzp_w"], res["mu_mz"]
                else:
                    result = mesh_power_loss(mesh, frictions[route], OIL_TEMPERATURE_K, rq, rq)
                    loaded = mesh.loads > 0
                    loss = result.power_loss
                    mu = float((result.mu[loaded] * mesh.loads[loaded]).sum() / mesh.loads[loaded].sum())
                row[route] = {"power_loss_w": loss, "mu_mean": mu, "time_s": time.perf_counter() - started}
            rows.append(row)
            print(rpm, finish_name, {r: round(row[r]["power_loss_w"], 1) for r in FINISH_ROUTES}, file=sys.stderr)
    ratios = {}
    for rpm in FINISH_SPEEDS_RPM:
        by = {r["finish"]: r for r in rows if r["speed_rpm"] == rpm}
        ratios[str(rpm)] = {route: by["ground"][route]["power_loss_w"] / by["superfinished"][route]["power_loss_w"]
                            for route in FINISH_ROUTES}
    report = {"benchmark": "Petry-Johnson et al. 2008 OSU spur pair: superfinished against ground flanks",
              "torque_nm": TORQUE_NM, "oil_temperature_k": OIL_TEMPERATURE_K, "eta_oil_pa_s": float(eta),
              "solver_version": SOLVER_VERSION, "routes": list(FINISH_ROUTES),
              "ground_over_superfinished_loss": ratios,
              "measured_losses": "not available in the project's sources", "machine": machine_info(), "rows": rows}
    emit_json(report, str(out))
    return 0


def _planner_at_max_sliding(mesh, lubricant, contact_conditions, ContactCase, dimensionless_numbers) -> dict:
    """The planner's numbers at the most loaded point of the largest sliding (SR) of the cycle (λ̄, thermal
    estimate), to show which regime the contacts are in."""
    import numpy as np

    cond = contact_conditions(mesh)
    loaded = cond["loaded"]
    sr = np.where(loaded, cond["sr"], -1.0)
    index = np.unravel_index(int(np.argmax(sr)), sr.shape)
    case = ContactCase(float(cond["p_h"][index]), float(cond["r_eq"][index]), float(cond["u_r"][index]),
                       float(cond["sr"][index]), OIL_TEMPERATURE_K, RQ, RQ)
    nums = dimensionless_numbers(case, lubricant)
    keys = ("lambda_bar", "thermal_change", "flash_rise_k", "film_centre_rise_k", "nahme_number", "surface_peclet",
            "film_peclet")
    return {"p_h_pa": case.p_h, "r_eq_m": case.r_eq, "u_r_m_s": case.u_r, "sr": case.sr,
            **{k: float(nums[k]) for k in keys}}


def draw(report, routes, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    rows = report["rows"]
    speeds = [r["speed_rpm"] for r in rows]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
    for route, marker in zip(routes, "osd^v<>"):
        style = {"marker": marker, "label": route, "linestyle": "--" if "isothermal" in route else "-",
                 "markersize": 7 if "isothermal" in route else 5}
        ax1.plot(speeds, [r[route]["power_loss_w"] / 1e3 for r in rows], **style)
        ax2.plot(speeds, [100 * r[route]["efficiency"] for r in rows], **style)
    ax1.set_xlabel("pinion speed [rpm]")
    ax1.set_ylabel("mesh friction power loss [kW]")
    ax2.set_xlabel("pinion speed [rpm]")
    ax2.set_ylabel("mechanical mesh efficiency [%]")
    ax1.set_title("OSU spur pair, 413 N·m, 75W90 at 100 °C", fontsize=9)
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    raise SystemExit(main())
