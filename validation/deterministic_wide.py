"""The deterministic model's wide-contact route (ehl_dataset.solvers.wide_contact) on one contact: five periodic
windows across the Hertzian zone fed the smooth pressure and the film law, against the contact's resolved run when
there is one (docs/explanation/mixed-regime.md, "Wide contacts").

    python validation/deterministic_wide.py --inputs 1.0 10 5 0.2 75 0.4 0.4 --tag V1
    python validation/deterministic_wide.py --inputs 1.0 10 5 0.2 75 0.4 0.4 --tag V1 --offset-sigma -0.05

``--inputs``: p_h [GPa], r_eq [mm], u_r [m/s], SR, T [°C], Rq1, Rq2 [µm] (ATF); the windows are the default
layout (WideOptions: 8 β at β/16, the default Courant number); ``--offset-sigma`` shifts the law's excess by that
many σ (its scatter). Writes validation/results/deterministic_wide_<tag>[_<offset>].json.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from ehl_dataset.model.contact import ContactCase
from ehl_dataset.model.effects import Effects
from ehl_dataset.model.lubricant import load_lubricant
from ehl_dataset.model.roughness import baseline_profile
from ehl_dataset.solvers.deterministic import MODEL_VERSION
from ehl_dataset.solvers.wide_contact import WIDE_MODEL_VERSION, WideOptions, solve_wide

RESULTS = Path(__file__).resolve().parent / "results"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--inputs", nargs=7, type=float, required=True, metavar="X")
    parser.add_argument("--tag", required=True)
    parser.add_argument("--offset-sigma", type=float, default=0.0)
    args = parser.parse_args(argv)
    case = ContactCase.from_engineering(*args.inputs)
    state = load_lubricant("atf").state(case.temperature)
    # the baseline profile the resolved runs it is compared with were computed on, not the package's default
    result = solve_wide(case, state, Effects.full(), WideOptions(film_offset_sigma=args.offset_sigma),
                        roughness=baseline_profile(), deterministic_version=MODEL_VERSION)
    record = {"inputs": args.inputs, "model_version": MODEL_VERSION, "wide_model_version": WIDE_MODEL_VERSION,
              "offset_sigma": args.offset_sigma, "mu": result.mu, "mu_sem": result.mu_sem,
              "asperity_load_share": result.asperity_load_share, "h_central_m": result.h_central,
              "h_min_m": result.h_min, "converged": result.converged, "message": result.message,
              "wall_time_s": result.wall_time, "extra": result.extra}
    suffix = f"_{args.offset_sigma:+g}" if args.offset_sigma else ""
    (RESULTS / f"deterministic_wide_{args.tag}{suffix}.json").write_text(json.dumps(record, indent=1, default=float))
    print(f"{args.tag}: mu {result.mu:.5f} ± {result.mu_sem:.5f}, fed central film "
          f"{result.extra.get('fed_central_film_m', float('nan')) * 1e9:.0f} nm, {result.message}, "
          f"{result.wall_time:.0f} s")
    return 0 if result.converged else 1


if __name__ == "__main__":
    sys.exit(main())
