"""One validation case at a spacing outside its three (e.g. B at β/128) as a short run with the validation set's
layout and options, recorded like the validation runs (benchmarks/deterministic_validation.py):

    python benchmarks/deterministic_extra_spacing.py B 128 benchmarks/results/deterministic/B_beta128.json

Pair it with a recorded run by ``deterministic_validation.paired_difference(run, base, "mu_series")``."""
import json, sys, time
import numpy as np
from pathlib import Path
sys.path.insert(0, str(Path(__file__).resolve().parent))
import deterministic_validation as dv
from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.solvers.deterministic import MODEL_VERSION, solve_deterministic

name, n = sys.argv[1], int(sys.argv[2])
out = sys.argv[3]
lub = load_lubricant(dv.LUBRICANT)
case = ContactCase.from_engineering(*dv.CASES[name])
state = lub.state(case.temperature)
t0 = time.time()
r = solve_deterministic(case, state, Effects.full(), dv.options_for(n, False))
extra = {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in r.extra.items()}
rec = {"case": name, "inputs": dv.CASES[name], "points_per_beta": n, "solver_version": MODEL_VERSION,
       "layout_passes": dv.LAYOUT_PASSES, "mu": r.mu, "mu_sem": r.mu_sem, "asperity_load_share": r.asperity_load_share,
       "h_min_m": r.h_min, "h_central_m": r.h_central, "converged": r.converged, "message": r.message,
       "wall_time_s": r.wall_time, "lambda_bar": r.lambda_bar, "residuals": r.residuals, "extra": extra}
open(out, "w").write(json.dumps(rec))
print(name, n, r.mu, r.mu_sem, r.asperity_load_share, r.converged, r.message, time.time() - t0, flush=True)
