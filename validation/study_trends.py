"""The numbers of the verification table of docs/explanation/gear-model.md: the paper's Fig. 3a, 4a-c and 6a trend lines with a
constant μ = 0.05 at the study point (data/studies/paper2009.toml), exactly as tests/efficiency/test_studies.py
evaluates them (the tests assert the trends; this prints their values).

Run: ``python validation/study_trends.py`` → validation/results/study_trends.json; ``--friction SPEC`` (e.g. ``atf``,
any spec of :func:`efficiency.friction.friction_from_spec`) evaluates the same lines with that friction model into
validation/results/study_trends_SPEC.json.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))  # _common.py, shared with the speed benchmarks
from _common import emit_json, machine_info  # noqa: E402

FIG3_LINE = {"normal_pressure_angle_deg": 22.5, "helix_angle_deg": 20.0, "working_depth": 2.286}
FIG4 = {"normal_pressure_angle_deg": {"teeth": 30, "helix_angle_deg": 20.0, "working_depth": 2.286},
        "helix_angle_deg": {"teeth": 30, "normal_pressure_angle_deg": 22.5, "working_depth": 2.286},
        "working_depth": {"teeth": 30, "normal_pressure_angle_deg": 22.5, "helix_angle_deg": 20.0}}


def main(argv=None) -> int:
    from efficiency.design_io import load_study
    from efficiency.friction import ConstantFriction
    from efficiency.loss_factor import ohlendorf_loss_factor
    from efficiency.mesh_cycle import MeshOptions
    from efficiency.studies import StudyPoint, design_pair, design_sweep, modification_study, trend_line

    import argparse

    from efficiency.friction import friction_from_spec

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--friction", default=None, help="friction spec (default: constant mu = 0.05)")
    args = parser.parse_args(argv)
    mu = ConstantFriction(0.05) if args.friction is None else friction_from_spec(args.friction)
    study = load_study("paper2009")
    point = StudyPoint.from_operating_point(study.operating_point)
    out = {"friction": "constant mu = 0.05" if args.friction is None else args.friction, "machine": machine_info()}

    def line(where, vary, stride=1, at=point):
        table = design_sweep(study.space, mu, at, study.limits, MeshOptions(), where=where, stride=stride)
        return trend_line(table, vary, {})

    fig3 = line(FIG3_LINE, "teeth", stride=3)
    out["fig3a"] = {"teeth": fig3["teeth"].tolist(), "power_loss_w": fig3["power_loss_w"].tolist(),
                    "ratio_last_first": float(fig3["power_loss_w"].iloc[-1] / fig3["power_loss_w"].iloc[0])}
    bare = StudyPoint(point.input_torque, point.input_speed, point.oil_temperature, point.rq1, point.rq2)
    fig3_bare = line(FIG3_LINE, "teeth", stride=3, at=bare)
    hv = np.array([ohlendorf_loss_factor(design_pair(row, study.space)) for _, row in fig3_bare.iterrows()])
    p = fig3_bare["power_loss_w"].to_numpy()
    out["fig3a_unmodified"] = {"max_deviation_from_hv_ratio": float(np.max(np.abs((p / p[0]) / (hv / hv[0]) - 1))),
                               "p_over_mu_hv_pin": (p / (0.05 * hv * point.input_torque * point.input_speed)).tolist()}
    for vary, where in FIG4.items():
        t = line(where, vary)
        out[f"fig4_{vary}"] = {vary: t[vary].tolist(), "power_loss_w": t["power_loss_w"].tolist()}
    mods = modification_study(study.design("D"), mu, [0.0, 15e-6, 30e-6], [0.0, 12e-6, 30e-6], [50.0, 250.0, 500.0],
                              point)
    sel = mods[(mods["torque_nm"] == 250.0) & np.isclose(mods["lead_crown_m"], 12e-6)].sort_values("profile_crown_m")
    out["fig6a_250nm_ml12"] = {"profile_crown_um": (sel["profile_crown_m"] * 1e6).tolist(),
                               "power_loss_w": sel["power_loss_w"].tolist()}
    name = "study_trends.json" if args.friction is None else f"study_trends_{Path(args.friction).stem}.json"
    emit_json(out, str(Path(__file__).parent / "results" / name), indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
