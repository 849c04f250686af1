"""How much of a fit's scatter is the thermal correction? Refit a dataset with the thermally corrected rows replaced
by their isothermal μ (docs/getting-started.md).

    gearloss pipeline quick --workers 2 --out-dir pq       # first: the main job
    python validation/quick_fit_isothermal.py pq/dataset.h5

Every row whose recorded effect plan has ``thermal`` on is solved again at the dataset's level with
``effects="isothermal"`` (same model choice, no thermal correction); Eq. 9 is fitted to both tables and the adjusted
R² per branch and the 5-fold CV error of each are printed.
"""

from __future__ import annotations

import json
import sys

from ehl_dataset.dataset.roughness_choice import choice_from_record, resolve_choice
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.solver import solve_contact
from surrogate.dataset_io import load_dataset
from surrogate.fit import fit_surrogate

COLUMNS = ("p_h", "r_eq", "u_r", "sr", "temperature", "rq1", "rq2")


def describe(fit, label: str) -> str:
    branches = ", ".join(f"{name} adj R² {branch.adj_r2:.3f} (n={branch.n_obs})" for name, branch in fit.branches.items())
    return f"{label}: {branches}; CV {json.dumps(fit.cv, default=float)}"


def main(argv: list[str]) -> int:
    dataset = load_dataset(argv[0])
    table = dataset.table
    level = str(table["level"].iloc[0]) if "level" in table else "fast"
    # the profile the dataset records (None: the default), not always the package's default: a dataset made
    # before the flank default was computed on baseline_synthetic
    roughness = resolve_choice(choice_from_record(dataset.roughness, where=argv[0]))
    print(describe(fit_surrogate(table, dataset.lubricant, dataset.e_reduced), "as computed"))
    isothermal = table.copy()
    replaced = 0
    for i, effects in enumerate(table["effects"]):
        plan = json.loads(effects) if isinstance(effects, (str, bytes)) else effects
        if plan.get("thermal"):
            case = ContactCase(*(float(table[c].iloc[i]) for c in COLUMNS))
            isothermal.loc[isothermal.index[i], "mu"] = solve_contact(case, dataset.lubricant, level, "isothermal",
                                                                       roughness=roughness).mu
            replaced += 1
    print(f"{replaced} thermally corrected rows solved again isothermal at level {level}")
    print(describe(fit_surrogate(isothermal, dataset.lubricant, dataset.e_reduced), "isothermal"))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
