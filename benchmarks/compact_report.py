"""Rewrite benchmark reports compactly: the ``rows`` one per line, their null-valued fields left out.

    python benchmarks/compact_report.py benchmarks/results/ehl_mixed_random1000_seed2_standard_isothermal.json ...

A report of ``bench_ehl_mixed.py`` over a thousand points written with indentation exceeds 1 MB, the limit of a tracked
result file. Every other key is kept as it was; a row field that is left out was ``null`` (``row.get(key)`` reads it
back as ``None``, as ``bench_ehl_mixed.py``'s summary and resume do). Lossless otherwise: the summary, the machine and
every non-null value are unchanged.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path


def compact_text(report: dict) -> str:
    """The JSON text of ``report`` with its top-level keys indented and each row of ``report["rows"]`` on one line
    without its null-valued fields.

    Parameters
    ----------
    report : dict
        A benchmark report (``bench_ehl_mixed.py`` layout: ``rows`` a list of flat dicts) [-].

    Returns
    -------
    str
        The JSON text, ending with a newline.
    """
    marker = "\u0000rows\u0000"
    head = json.dumps({**report, "rows": marker} if "rows" in report else report, indent=1, default=float)
    if "rows" not in report:
        return head + "\n"
    lines = [json.dumps({k: v for k, v in row.items() if v is not None}, separators=(",", ":"), default=float)
             for row in report["rows"]]
    return head.replace(json.dumps(marker), "[\n" + ",\n".join(lines) + "\n ]") + "\n"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("files", nargs="+", type=Path, help="report JSON files, rewritten in place")
    args = parser.parse_args(argv)
    for path in args.files:
        report = json.loads(path.read_text())
        text = compact_text(report)
        restored = json.loads(text)
        expected = {**report, "rows": [{k: v for k, v in r.items() if v is not None} for r in report.get("rows", [])]}
        if "rows" not in report:
            expected.pop("rows")
        if restored != expected:
            raise SystemExit(f"{path}: the compact text does not read back to the report")
        before = path.stat().st_size
        path.write_text(text)
        print(f"{path}: {before:,} -> {path.stat().st_size:,} bytes")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
