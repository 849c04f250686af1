"""One validation case at a spacing outside its three (e.g. B at β/128) as a short run with the validation set's
layout and options, recorded like the validation runs (validation/deterministic_validation.py):

    python validation/deterministic_extra_spacing.py B 128 validation/results/deterministic/B_beta128.json

A stopped run continues from its saved state when the command is given again (deterministic_validation.py's
``checkpoint_path``). Pair it with a recorded run by ``deterministic_validation.paired_difference(run, base, "mu_series")``.
"""

import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from deterministic_validation import solve_and_record  # noqa: E402


def main(argv=None) -> int:
    name, n, out = argv if argv is not None else sys.argv[1:]
    record = solve_and_record(name, int(n), long=False, out=Path(out))
    print(name, n, record["mu"], record["mu_sem"], record["asperity_load_share"], record["converged"],
          record["message"], record["wall_time_s"], flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
