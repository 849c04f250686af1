"""Benchmark of the surrogate stage: fit time on 42,000 synthetic rows and vectorised evaluation rates.

Data: the paper's full factorial (docs/reference/dataset-format.md, 42,000 points) with μ from the exact Eq. 9 forms (coefficients from
:func:`surrogate.synthetic.reference_coefficients`) plus N(0, 0.05²) noise in ln μ. Timings are medians of
``--repeats`` runs on this machine; the JSON records the platform. Usage::

    python benchmarks/bench_surrogate.py [--repeats 5] [--points 1000000] [--out benchmarks/results/surrogate.json]
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import sys
import time
import warnings
from pathlib import Path

import numpy as np

# _common.py sits next to this file (sys.path: see bench_ehl_mixed.py)
sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import machine_info, median_time, repeat_times  # noqa: E402


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--points", type=int, default=1_000_000)
    parser.add_argument("--out", default=str(Path(__file__).parent / "results" / "surrogate.json"))
    args = parser.parse_args(argv)

    import scipy
    import sklearn
    import statsmodels

    from ehl_dataset.model.lubricant import load_lubricant
    from ehl_dataset.model.materials import STEEL, reduced_modulus
    from surrogate.coefficients import write_coefficients
    from surrogate.evaluate import FrictionSurrogate
    from surrogate.fit import cross_validate, fit_surrogate, prepare_table
    from surrogate.learned import LearnedFriction
    from surrogate.published import PUBLISHED_MODELS, published_mu
    from surrogate.synthetic import PAPER_LEVELS, eq9_table, factorial_inputs, reference_coefficients

    warnings.simplefilter("ignore")
    atf = load_lubricant("atf")
    e = reduced_modulus(STEEL, STEEL)
    table = eq9_table(factorial_inputs(PAPER_LEVELS), reference_coefficients(atf, e), atf, e, noise_sd=0.05, seed=0)
    results: dict = {
        "benchmark": "surrogate",
        "machine": {**machine_info(), "scipy": scipy.__version__, "statsmodels": statsmodels.__version__,
                    "scikit_learn": sklearn.__version__, "load_average_1min_at_start": os.getloadavg()[0]},
        "data": {"rows": len(table), "source": "paper factorial, exact Eq. 9 + N(0, 0.05^2) in ln mu"},
        "repeats": args.repeats,
    }

    fit_holder = {"fit_times": []}

    def do_fit():
        fit_holder["fit"] = fit_surrogate(table, atf, e, k_folds=5, allow_unstable=True)
        fit_holder["fit_times"].append(fit_holder["fit"].fit_time_s)

    raw = repeat_times(do_fit, args.repeats)
    t_total = statistics.median(raw)
    fit = fit_holder["fit"]
    prepared = prepare_table(table, atf, e)
    t_cv = median_time(lambda: cross_validate(fit.formula, prepared.features, prepared.ln_mu, k_folds=5,
                                              blend_half_width=0.1), args.repeats)
    t_prep = median_time(lambda: prepare_table(table, atf, e), args.repeats)
    results["fit"] = {
        "rows_in": fit.n_input_rows, "rows_used": fit.n_used,
        "median_total_s": t_total, "all_total_s": raw,
        "median_features_and_exclusions_s": t_prep,
        "median_features_ols_diagnostics_s": float(np.median(fit_holder["fit_times"])),
        "median_5fold_cv_s": t_cv,
        "adj_r2": {b: f.adj_r2 for b, f in fit.branches.items()},
        "cv_rmse_ln_mu": fit.cv["overall"]["rmse_ln_mu"],
        "condition_number_standardized": {b: f.condition_number_standardized for b, f in fit.branches.items()},
        "jump_at_lambda_1": fit.jump,
    }
    tmp = Path(args.out).with_name("_bench_surrogate_coefficients.json")
    write_coefficients(fit, tmp, source={"path": "synthetic"})
    surrogate = FrictionSurrogate.load(tmp)
    tmp.unlink()
    tmp.with_name(tmp.stem + ".summary.txt").unlink()

    rng = np.random.default_rng(1)
    n = args.points
    inputs = (rng.uniform(0.5e9, 2.5e9, n), rng.uniform(0.005, 0.08, n), rng.uniform(1.0, 20.0, n),
              rng.uniform(0.0, 1.0, n), rng.choice([298.15, 323.15, 348.15, 373.15], n),
              rng.choice([0.1e-6, 0.4e-6, 1.0e-6], n), rng.choice([0.1e-6, 0.4e-6, 1.0e-6], n))
    evals = {}
    surrogate.mu(*inputs)
    t = median_time(lambda: surrogate.mu(*inputs), args.repeats)
    evals["li_kahraman_2009_eq9 (FrictionSurrogate.mu, validated)"] = {"median_s": t, "points_per_s": n / t}
    learned = LearnedFriction(atf, e)
    start = time.perf_counter()
    learned.fit_features(prepared.features, prepared.ln_mu)
    learned_fit = time.perf_counter() - start
    t = median_time(lambda: learned.mu(*inputs), max(1, args.repeats // 2))
    evals["hist_gradient_boosting (1 thread, 400 trees)"] = {"median_s": t, "points_per_s": n / t,
                                                             "fit_s_42000_rows": learned_fit}
    for name in PUBLISHED_MODELS:
        t = median_time(lambda: published_mu(name, *inputs, atf, e), args.repeats)
        evals[name] = {"median_s": t, "points_per_s": n / t}
    results["evaluation"] = {"points": n, "models": evals}
    results["machine"]["load_average_1min_at_end"] = os.getloadavg()[0]
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(results, indent=1) + "\n")
    print(json.dumps(results, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
