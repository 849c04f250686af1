"""Check: the two forms of a friction coefficient file give the same gear loss within their bands.

For each coefficient file given (e.g. the Eq. 9 and the learned file of one lubricant) the mesh friction power loss
P and its 90 % band (every contact point at the same end of its μ interval, :mod:`efficiency.power_loss`) on

* design D of the paper's study at the study's operating point (``gearloss gear evaluate`` of that design), and
* the Ohio State spur pair of Petry-Johnson et al. 2008 (``validation/petry_johnson.py``: ``osu_pair``) at 413 N·m,
  2,000-10,000 rpm, oil inlet 100 °C, Rq 0.07 µm. The files carry their own lubricant: with an ATF file this is the
  OSU geometry and kinematics with the ATF, a check of the surrogates against each other, not of the 75W90 test.

and, for every pair of files, whether each P lies inside the other's band. Usage::

    python benchmarks/bench_surrogate_gear.py FILE [FILE ...] [--out benchmarks/results/surrogate_gear.json]
"""

from __future__ import annotations

import argparse
import itertools
import json
import math
import sys
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "validation"))
from _common import machine_info  # noqa: E402

PJ_TORQUE_NM = 413.0
PJ_SPEEDS_RPM = (2000, 4000, 6000, 8000, 10000)
PJ_OIL_K = 373.15
PJ_RQ_M = 0.07e-6


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="+")
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "surrogate_gear.json"))
    args = parser.parse_args(argv)

    from efficiency.design_io import load_study
    from efficiency.friction import friction_from_spec
    from efficiency.mesh_cycle import MeshOptions, evaluate_mesh
    from efficiency.power_loss import mesh_power_loss
    from efficiency.studies import StudyPoint, evaluate_design
    from petry_johnson import osu_pair

    warnings.simplefilter("ignore")
    study = load_study("paper2009")
    point = StudyPoint.from_operating_point(study.operating_point)
    cases = {}
    for spec in args.files:
        friction = friction_from_spec(spec)
        label = Path(spec).name
        row = evaluate_design(study.design("D"), friction, point, MeshOptions())
        band = [row["power_loss_low_w"], row["power_loss_high_w"]]
        cases.setdefault("design_D", {})[label] = {"p_w": row["power_loss_w"],
                                                    "band_w": band if all(math.isfinite(v) for v in band) else None,
                                                    "efficiency": row["efficiency"], "valid": row["valid"]}
        pair = osu_pair()
        for rpm in PJ_SPEEDS_RPM:
            mesh = evaluate_mesh(pair, PJ_TORQUE_NM, rpm * math.pi / 30.0, options=MeshOptions(outputs=frozenset()))
            loss = mesh_power_loss(mesh, friction, PJ_OIL_K, PJ_RQ_M, PJ_RQ_M)
            cases.setdefault(f"petry_johnson_{rpm}rpm", {})[label] = {
                "p_w": loss.power_loss, "band_w": list(loss.power_loss_band) if loss.power_loss_band else None,
                "efficiency": loss.efficiency, "clipped_inputs": loss.extra.get("clipped_inputs")}
    checks = []
    for case, rows in cases.items():
        for a, b in itertools.permutations(rows, 2):
            band = rows[b]["band_w"]
            inside = None if band is None else bool(band[0] <= rows[a]["p_w"] <= band[1])
            checks.append({"case": case, "p_of": a, "band_of": b, "inside": inside,
                           "ratio": rows[a]["p_w"] / rows[b]["p_w"]})
    out = {"benchmark": "surrogate_gear", "machine": machine_info(), "files": args.files, "cases": cases,
           "checks": checks, "all_inside": all(c["inside"] for c in checks if c["inside"] is not None)}
    Path(args.out).parent.mkdir(parents=True, exist_ok=True)
    Path(args.out).write_text(json.dumps(out, indent=1) + "\n")
    for case, rows in cases.items():
        for label, r in rows.items():
            band = r["band_w"]
            print(f"{case:24s} {label:28s} P {r['p_w']:8.2f} W  band "
                  + (f"[{band[0]:8.2f}, {band[1]:8.2f}] W" if band else "none"))
    print("every P inside the other file's band:", out["all_inside"])
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
