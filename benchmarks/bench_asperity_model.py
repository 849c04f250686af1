"""Benchmark: the asperity-load closure of the homogenised model against the steady smooth solve on the same contacts.

    python benchmarks/bench_asperity_model.py [--level standard] [--repeats 3] [--out FILE]

For each case of the deterministic validation set (data/reference/deterministic_validation.json) the median wall
time of ``solve_contact`` with the steady smooth model, the film-law closure and the asperity closure (isothermal,
as ``gearloss accuracy --mixed`` runs them), after one warm-up call each (numba compilation, dry-contact table load),
with the steady solver's solution cache emptied before every call (each call solves its smooth problem).
The ratio asperity/smooth per case and its median are the cost the asperity closure adds (target ≤ 3). Default
output: benchmarks/results/asperity_model.json.
"""

from __future__ import annotations

import argparse
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from _common import RESULTS_DIR, emit_json, median_time, machine_info  # noqa: E402

from ehl_dataset.model.lubricant import load_lubricant  # noqa: E402
from ehl_dataset.model.roughness import baseline_profile  # noqa: E402
from ehl_dataset.solver import SOLVER_VERSION, solve_contact  # noqa: E402
from ehl_dataset.solvers.asperity_model import ASPERITY_MODEL_VERSION  # noqa: E402
from ehl_dataset.solvers import steady  # noqa: E402
from ehl_dataset.solvers.homogenised import HomogenisedOptions  # noqa: E402
from workflows.accuracy_mixed import load_reference, reference_case  # noqa: E402


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--level", default="standard")
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--out", default=str(RESULTS_DIR / "asperity_model.json"))
    args = parser.parse_args(argv)
    lub = load_lubricant("atf")
    def uncached(solve):
        def call(case):
            steady._STEADY_CACHE.clear()  # the steady solver keeps solved contacts; time the solve, not the lookup
            return solve(case)
        return call

    profile = baseline_profile()  # the validation cases' roughness, as gearloss accuracy --mixed solves them
    calls = {
        "smooth": uncached(lambda c: solve_contact(c, lub, args.level, "smooth")),
        "film_law": uncached(lambda c: solve_contact(c, lub, args.level, "isothermal", model="homogenised",
                                                     homogenised=HomogenisedOptions(closure="film_law"),
                                                     roughness=profile)),
        "asperity": uncached(lambda c: solve_contact(c, lub, args.level, "isothermal", model="homogenised",
                                                     homogenised=HomogenisedOptions(closure="asperity"),
                                                     roughness=profile)),
    }
    rows = []
    for row in load_reference():
        case = reference_case(row)
        times = {}
        for name, call in calls.items():
            call(case)  # warm-up
            times[f"{name}_s"] = median_time(lambda: call(case), args.repeats)
        times["asperity_over_smooth"] = times["asperity_s"] / times["smooth_s"]
        times["asperity_over_film_law"] = times["asperity_s"] / times["film_law_s"]
        rows.append({"case": row["case"], **times})
    ratios = [r["asperity_over_smooth"] for r in rows]
    report = {
        "benchmark": "asperity closure vs steady smooth solve, deterministic validation cases",
        "command": "python benchmarks/bench_asperity_model.py"
                   + (f" --level {args.level}" if args.level != "standard" else "")
                   + (f" --repeats {args.repeats}" if args.repeats != 3 else ""),
        "machine": machine_info(), "solver_version": SOLVER_VERSION, "model_version": ASPERITY_MODEL_VERSION,
        "level": args.level, "repeats": args.repeats,
        "median_asperity_over_smooth": statistics.median(ratios), "max_asperity_over_smooth": max(ratios),
        "median_asperity_over_film_law": statistics.median(r["asperity_over_film_law"] for r in rows),
        "total_smooth_s": sum(r["smooth_s"] for r in rows), "total_asperity_s": sum(r["asperity_s"] for r in rows),
        "cases": rows,
    }
    emit_json(report, args.out, indent=1)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
