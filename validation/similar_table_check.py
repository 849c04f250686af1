"""The asperity-load closure with a shipped dry-contact table scaled to the pair (the production route for a pair
without a table of its own, :func:`ehl_dataset.model.dry_contact.similar_dry_contact_table`) against the same closure
on the pair's own computed table, at `standard`, isothermal, on flank_ground.

    python validation/similar_table_check.py     # → validation/results/similar_table_check.json (≈ 10 min)

A fresh cache directory makes every "own" table a computed one.
"""

import json
import os
import tempfile
import time
from pathlib import Path

os.environ["GEARLOSS_CACHE_DIR"] = tempfile.mkdtemp(prefix="gearloss_tables_")

import ehl_dataset.solvers.asperity_model as am  # noqa: E402
from ehl_dataset.model import dry_contact as dc  # noqa: E402
from ehl_dataset.model.contact import ContactCase  # noqa: E402
from ehl_dataset.model.lubricant import load_lubricant  # noqa: E402
from ehl_dataset.solver import SOLVER_VERSION, solve_contact  # noqa: E402

OUT = Path(__file__).resolve().parent / "results" / "similar_table_check.json"
CONDITIONS = {"A": (0.5, 5, 5, 0.3, 90), "gear": (1.2, 20, 5, 0.3, 80), "S": (1.0, 2.5, 2, 0.4, 50)}
CASES = [("A", (0.15, 0.15)), ("A", (0.3, 0.6)), ("A", (0.25, 0.35)), ("A", (0.6, 0.1)), ("A", (0.45, 0.45)),
         ("A", (0.8, 0.3)), ("gear", (0.6, 0.1)), ("gear", (0.8, 1.04)), ("S", (0.25, 0.35))]


def _own(profile, rq1, rq2, e_reduced, settings=None, **_):
    return dc.dry_contact_table(profile, rq1, rq2, e_reduced, settings=settings), 1.0, (rq1, rq2)


def main() -> None:
    atf = load_lubricant("atf")
    similar = am.similar_dry_contact_table
    rows = []
    for name, (rq1, rq2) in CASES:
        case = ContactCase.from_engineering(*CONDITIONS[name], rq1, rq2)
        am.similar_dry_contact_table = similar
        scaled = solve_contact(case, atf, "standard", "isothermal")
        am.similar_dry_contact_table = _own
        started = time.perf_counter()
        own = solve_contact(case, atf, "standard", "isothermal")
        rows.append({"conditions": name, "inputs": list(CONDITIONS[name]) + [rq1, rq2],
                     "table_rq_um": [v * 1e6 for v in scaled.extra["asperity"]["table_rq_m"]],
                     "table_scale": scaled.extra["asperity"]["table_scale"],
                     "mu_scaled_table": scaled.mu, "mu_own_table": own.mu, "mu_error": scaled.mu / own.mu - 1.0,
                     "share_scaled_table": scaled.asperity_load_share, "share_own_table": own.asperity_load_share,
                     "own_table_and_solve_s": time.perf_counter() - started})
        print(json.dumps(rows[-1]), flush=True)
    am.similar_dry_contact_table = similar
    OUT.write_text(json.dumps({"command": "python validation/similar_table_check.py", "solver_version": SOLVER_VERSION,
                               "asperity_model_version": am.ASPERITY_MODEL_VERSION, "level": "standard",
                               "effects": "isothermal", "profile": "flank_ground", "rows": rows}, indent=1) + "\n")


if __name__ == "__main__":
    main()
