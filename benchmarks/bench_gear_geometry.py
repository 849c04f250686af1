"""Speed of the gear geometry / feasibility / ISO 6336 code and the sensitivity of the paper's feasible count.

Writes one JSON object (stdout, and ``--out FILE`` if given) with medians over repeats and the machine noted:
- time to screen the paper's 30,464 designs (vectorised geometry + every feasibility criterion),
- time per scalar design: GearPair construction + check_design, and the ISO 6336 reference values,
- the feasible count under alternative assumptions the paper does not state (backlash policy, rack tip radius,
  tip-thickness limit, backlash definition, an extra ε_α ≥ 1 requirement).

Run: ``python benchmarks/bench_gear_geometry.py [--repeats 7] [--out benchmarks/results/gear_geometry.json]``
"""

from __future__ import annotations

import argparse
import dataclasses
import sys
from pathlib import Path

import numpy as np

# _common.py sits next to this file (sys.path: see bench_ehl_mixed.py)
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import emit_json, machine_info, median_time  # noqa: E402


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--out", help="also write the JSON here")
    args = parser.parse_args(argv)

    from efficiency import iso6336
    from efficiency.design_io import load_study, paper_design
    from efficiency.feasibility import check_design, count_feasible, feasibility_masks

    study = load_study("paper2009")
    space, limits = study.space, study.limits

    screen_s = median_time(lambda: count_feasible(space, limits), args.repeats)
    n_scalar = 200
    designs = [(int(n), float(p), float(s), float(w)) for n, p, s, w in zip(
        np.random.default_rng(1).integers(20, 54, n_scalar), np.random.default_rng(2).choice(space.pressure_angles_deg,
                                                                                           n_scalar),
        np.random.default_rng(3).choice(space.helix_angles_deg, n_scalar),
        np.random.default_rng(4).choice(space.working_depths, n_scalar))]

    def scalar_checks():
        for d in designs:
            check_design(paper_design(*d), limits)

    scalar_s = median_time(scalar_checks, args.repeats) / n_scalar
    pair_d = study.design("D")
    iso_s = median_time(lambda: [iso6336.reference_values(pair_d, 250.0) for _ in range(100)], args.repeats) / 100

    def count(space_changes=None, limit_changes=None, extra=None):
        s = dataclasses.replace(space, **(space_changes or {}))
        lim = dataclasses.replace(limits, **(limit_changes or {}))
        masks = feasibility_masks(s.pairs(), lim)
        ok = masks["feasible"]
        if extra == "eps_alpha":
            ok = ok & (s.pairs().contact_ratio >= 1.0)
        return int(np.count_nonzero(ok))

    sensitivity = {
        "default (iso10064 thinning, rack tip radius 0.25 m_n, tip >= 0.2 m_n)": count(),
        "no thinning (j = 0 at the standard centre distance)": count({"backlash_policy": "constant",
                                                                       "backlash_policy_value": 0.0}),
        "thinning A_sn = 0.0232 mm per gear (just above 0.04 mm j_bn)": count(
            {"backlash_policy": "constant", "backlash_policy_value": 0.0232e-3}),
        "thinning A_sn = 0.05 mm per gear": count({"backlash_policy": "constant", "backlash_policy_value": 0.05e-3}),
        "thinning A_sn = 0.10 mm per gear": count({"backlash_policy": "constant", "backlash_policy_value": 0.10e-3}),
        "thinning A_sn = 0.01 m_n per gear": count({"backlash_policy": "module", "backlash_policy_value": 0.01}),
        "thinning A_sn = 0.02 m_n per gear": count({"backlash_policy": "module", "backlash_policy_value": 0.02}),
        "circumferential backlash j_wt instead of j_bn, A_sn = 0.0232 mm": count(
            {"backlash_policy": "constant", "backlash_policy_value": 0.0232e-3}, {"backlash_kind": "circumferential"}),
        "rack tip radius 0.0 m_n": count({"root_fillet_coefficient": 0.0}),
        "rack tip radius 0.38 m_n": count({"root_fillet_coefficient": 0.38}),
        "tip thickness >= 0.3 m_n": count(limit_changes={"min_tip_thickness": 0.3}),
        "tip thickness >= 0.4 m_n": count(limit_changes={"min_tip_thickness": 0.4}),
        "additionally eps_alpha >= 1": count(extra="eps_alpha"),
    }
    counts = count_feasible(space, limits)
    result = {
        "benchmark": "gear_geometry",
        **machine_info(),
        "repeats": args.repeats,
        "paper_space_designs": space.size,
        "screen_paper_space_median_s": screen_s,
        "scalar_design_check_median_s": scalar_s,
        "iso6336_reference_values_median_s": iso_s,
        "feasible_by_criterion": counts,
        "paper_feasible_count": study.paper_feasible_count,
        "feasible_count_sensitivity": sensitivity,
    }
    emit_json(result, args.out, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main())
