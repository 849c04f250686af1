"""Coverage of the 90 % prediction intervals of coefficient files on held-out off-grid contacts.

Two independent samples of the factorial's box, solved by the factorial's route (:func:`workflows.surrogate_stage.
offgrid_stage`, resumable, reused when the work directory holds them):

* the file's own off-grid sample (seed 2009): its even rows calibrate the intervals (split conformal), so the
  coverage counts its odd rows only;
* a second sample (default seed 7) that took no part in any fit or calibration: all its rows count.

For an Eq. 9 file with ``interval_calibration`` both its calibrated interval and the plain statsmodels interval
(the same file without the table) are measured; a learned file is measured as it is. Usage::

    python validation/surrogate_intervals.py --work-dir DIR [FILE ...] [--factorial quick] [--seed 7]
        [--workers 1] [--out validation/results/surrogate_intervals.json]

FILE defaults to the shipped ``atf_quick`` and ``atf_quick_learned``.
"""

from __future__ import annotations

import argparse
import os
import sys
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from _common import emit_json, machine_info  # noqa: E402  (shared with the speed benchmarks)

RESULTS_DIR = Path(__file__).resolve().parent / "results"

COVERAGE = 0.90


def _solve(work: Path, name: str, factorial, lubricant, seed: int, workers: int) -> Path:
    from ehl_dataset.dataset.store import read_metadata
    from workflows.surrogate_stage import offgrid_stage

    out = work / name
    out.mkdir(parents=True, exist_ok=True)
    offgrid_stage(out, factorial, lubricant, level=factorial.level, effects=factorial.effects, model=factorial.model,
                  seed=seed, workers=workers, progress="none")
    path = out / "offgrid.h5"
    assert (read_metadata(path).get("factorial") or {}).get("seed") == seed
    return path


def _coverage(surrogate, table, rows: np.ndarray | None) -> dict:
    from surrogate.offgrid import offgrid_errors

    result = offgrid_errors(surrogate, table, coverage=COVERAGE, coverage_rows=rows)
    return {key: {"coverage": result[key].get("coverage"), "n_coverage": result[key].get("n_coverage"),
                  "median_rel_err_mu": result[key].get("median_rel_err_mu")}
            for key in ("overall", "mixed", "full_film") if result[key].get("n")}


def _plain_twin(surrogate):
    from surrogate.coefficients import content_hash, validate_coefficients
    from surrogate.evaluate import FrictionSurrogate

    doc = {k: v for k, v in surrogate.coefficients.document.items() if k != "interval_calibration"}
    doc["content_sha256"] = content_hash(doc)
    return FrictionSurrogate(validate_coefficients(doc, surrogate.coefficients.path))


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="*", default=["atf_quick", "atf_quick_learned"])
    parser.add_argument("--work-dir", required=True)
    parser.add_argument("--factorial", default="quick")
    parser.add_argument("--seed", type=int, default=7)
    parser.add_argument("--workers", type=int, default=1)
    parser.add_argument("--out", default=str(RESULTS_DIR / "surrogate_intervals.json"))
    args = parser.parse_args(argv)

    from ehl_dataset.dataset.factorial import load_factorial
    from surrogate.dataset_io import load_dataset
    from surrogate.evaluate import FrictionSurrogate
    from surrogate.offgrid import calibration_rows
    from workflows.sample_runs import OFFGRID_SEED

    warnings.simplefilter("ignore")
    work = Path(args.work_dir)
    factorial = load_factorial(args.factorial)
    load_start = os.getloadavg()[0]
    report = {"benchmark": "surrogate_intervals", "machine": machine_info(), "coverage_nominal": COVERAGE,
              "factorial": args.factorial, "files": {}}
    samples = {}
    for label, seed in (("own", OFFGRID_SEED), ("second", args.seed)):
        surrogate = FrictionSurrogate.load(args.files[0])
        path = _solve(work, f"seed{seed}", factorial, surrogate.lubricant, seed, args.workers)
        samples[label] = (load_dataset(path), seed)
    own, own_seed = samples["own"]
    second, second_seed = samples["second"]
    report["samples"] = {label: {"seed": seed, "n_points": int(len(d.table)), "sha256": d.source["sha256"],
                                 "solver_version": d.source.get("solver_version")}
                         for label, (d, seed) in samples.items()}
    odd = ~calibration_rows(len(own.table))
    for name in args.files:
        surrogate = FrictionSurrogate.load(name)
        variants = {"as shipped": surrogate}
        if surrogate.form == "eq9" and surrogate.coefficients.score_quantiles is not None:
            variants["plain statsmodels interval"] = _plain_twin(surrogate)
        entry = {"form": surrogate.form}
        for label, model in variants.items():
            entry[label] = {"interval_method": model.coefficients.interval_method,
                            f"seed {own_seed}, odd rows": _coverage(model, own.table, odd),
                            f"seed {second_seed}, all rows": _coverage(model, second.table, None)}
        report["files"][Path(str(name)).stem] = entry
    report["machine"]["load_average_1min"] = [load_start, os.getloadavg()[0]]
    emit_json(report, args.out, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
