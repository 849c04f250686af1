"""Which contact model the planner picks over a factorial: the share of points solved steady smooth, by the film-law
homogenised model within its validated range (rough and a/β ≥ 15, or narrow within its measured range: λ̄ > 1 or
X_h ≥ 150, since ehl-2026.11-12, or λ̄ ≥ 0.1 and roughness parameter α ≤ 2.5, the range of its pressure-fluctuation
closure, since ehl-2026.11-13), by the same model outside it (the other narrow rough contacts: the level's rough
model since ehl-2026.11-11; and, since ehl-2026.11-14, the wide ones below λ̄ 1 and X_h 150 outside the closure's
range) and by the deterministic solver (a level whose rough model is deterministic: the reference), at the
factorial's level.

    python validation/planner_model_shares.py                    # quick (all 324) and paper2009 (every 14th point)

Planning only (ehl_dataset.solvers.planner.plan_effects with the shipped roughness profile): no solve is run.
"""

from __future__ import annotations

import collections
import sys

from ehl_dataset.dataset.factorial import load_factorial
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solvers.planner import plan_effects

STRIDES = {"quick": 1, "paper2009": 14}


def shares(name: str, stride: int) -> dict[str, int]:
    factorial = load_factorial(name)
    lubricant = load_lubricant(factorial.lubricant or "atf")
    counts: collections.Counter = collections.Counter()
    for row in factorial.points()[::stride]:
        plan = plan_effects(ContactCase(*(float(v) for v in row)), lubricant, factorial.level or "standard")
        wide = plan.reasons["numbers"]["a_over_beta"] >= plan.reasons["thresholds"]["a_over_beta_homogenised"]
        outside = not plan.reasons.get("film_law_range", {}).get("within_measured_range", True)
        counts["smooth" if not plan.roughness else "deterministic" if plan.transient else
               ("film_law_wide_outside" if outside else "film_law") if wide else
               "film_law_narrow" if outside else "film_law_narrow_within"] += 1
    return dict(counts)


def main() -> int:
    for name, stride in STRIDES.items():
        counts = shares(name, stride)
        total = sum(counts.values())
        rough = total - counts.get("smooth", 0)
        outside = (counts.get("film_law_narrow", 0) + counts.get("film_law_wide_outside", 0)
                   + counts.get("deterministic", 0))  # outside the film law's measured range
        print(f"{name} (every {stride}th point, {total} points, level {load_factorial(name).level}): "
              f"smooth {counts.get('smooth', 0)}, film-law (a/beta >= 15) within its measured range "
              f"{counts.get('film_law', 0)}, outside it {counts.get('film_law_wide_outside', 0)}, film-law "
              f"within its measured range (narrow) {counts.get('film_law_narrow_within', 0)}, film-law "
              f"outside its validated range (narrow) {counts.get('film_law_narrow', 0)}, deterministic "
              f"{counts.get('deterministic', 0)} (outside: {100 * outside / max(rough, 1):.0f} % of the rough points, "
              f"{100 * outside / total:.1f} % of all)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
