"""Behaviour snapshot of the command line: record what the main commands print, and compare two records.

A pure re-organisation of the code must not change a single solved value. This script runs, through the console
script only (so the same script works whatever the package layout):

* ``gearloss contact solve --json`` for one smooth and one rough case at ``--level fast``,
* ``gearloss gear evaluate --json`` for the paper's design D with ``--friction atf_quick``,
* ``gearloss surrogate predict atf_quick --json``,
* ``gearloss dataset run --factorial smoke --json``, and the HDF5 file it writes, read back with h5py (every column
  of ``/points`` and the JSON root attributes),
* ``gearloss pipeline smoke --json`` (factorial -> surrogate fit -> Design D) and the coefficient file it writes,

and writes them to one JSON file. ``compare`` reports every difference between two such files, ignoring wall
times, timestamps, hosts and paths (and the file:line locations in warning texts, and the scratch directory
the commands ran in); keys that exist only in the
newer file are listed as additions, not as differences; ``--rename OLD=NEW`` compares a renamed key under its new
name. Numbers must be equal bit for bit unless ``--rtol`` says otherwise.

    python benchmarks/behaviour_snapshot.py record --out benchmarks/results/behaviour_before.json
    python benchmarks/behaviour_snapshot.py compare benchmarks/results/behaviour_before.json \
        benchmarks/results/behaviour_after.json

``partial`` writes a smoke-factorial HDF5 file in which all rows but ``--pending`` are computed (a run that was
interrupted), to check that a file written by one version of the code resumes with another
(``tests/ehl_dataset/data/smoke_partial_v7.h5``).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

SMOOTH = ["--p-h-gpa", "1", "--r-eq-mm", "10", "--u-r", "5", "--sr", "0.3", "--temp-c", "90", "--level", "fast"]
ROUGH = SMOOTH + ["--rq1-um", "0.2", "--rq2-um", "0.2"]
DESIGN_D = ["--teeth", "32", "--pressure-angle-deg", "30", "--helix-angle-deg", "19", "--working-depth", "2.068",
            "--torque-nm", "250", "--speed-rpm", "4000", "--profile-crown-um", "15", "--lead-crown-um", "12",
            "--friction", "atf_quick"]
PREDICT = ["atf_quick", "--p-h-gpa", "1", "--r-eq-mm", "10", "--u-r", "5", "--sr", "0.3", "--temp-c", "90",
           "--rq1-um", "0.2", "--rq2-um", "0.2"]

VOLATILE_KEYS = {"created", "git_revision", "sessions", "package_version", "finished_at", "worker", "worker_time",
                 "wall_time", "path", "coefficients", "file", "points_per_s", "store_time_per_point_s",
                 "created_utc", "content_sha256", "sha256"}
"""Keys whose values depend on when, where or how fast a command ran (also every key ending in ``time_s``); the
hashes of a coefficient file and of the dataset file it was fitted from cover their creation times (their
contents are compared field by field)."""
_LOCATION = re.compile(r"\(([^()]*?\.py):\d+( in [^()]*)?\)")
_SCRATCH = re.compile(re.escape(tempfile.gettempdir()) + r"/tmp\w+")
"""The scratch directory a record ran in (it appears in output paths and resume commands)."""


def _gearloss() -> list[str]:
    exe = shutil.which("gearloss")
    return [exe] if exe else [sys.executable, "-c", "from workflows.cli import main; raise SystemExit(main())"]


def run_json(args: list[str], cwd: Path) -> dict:
    """Run ``gearloss ARGS --json`` and return its JSON output, with the exit status and the wall time."""
    start = time.perf_counter()
    proc = subprocess.run(_gearloss() + args + ["--json"], cwd=cwd, capture_output=True, text=True,
                          env=dict(os.environ, MPLBACKEND="Agg"))
    out = json.loads(proc.stdout) if proc.stdout.strip() else {"stderr": proc.stderr}
    return {"exit": proc.returncode, "command_wall_time_s": time.perf_counter() - start, "output": out}


def _plain(value):
    """HDF5 values as JSON: arrays as lists, bytes as text, NaN/inf as strings."""
    import numpy as np

    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if isinstance(value, np.ndarray):
        return [_plain(v) for v in value.tolist()]
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return str(value)
    return value


def read_h5(path: Path) -> dict:
    """Every column of ``/points`` and every root attribute (JSON attributes parsed) of a dataset file."""
    import h5py

    with h5py.File(path, "r", locking=False) as f:
        attrs = {}
        for key, value in f.attrs.items():
            value = _plain(value)
            if isinstance(value, str) and value[:1] in "[{":
                value = json.loads(value)
            attrs[key] = value
        columns = {name: _plain(f["points"][name][()]) for name in sorted(f["points"])}
    return {"attributes": attrs, "columns": columns}


def record(out: Path, workers: int) -> dict:
    report = {"tool": "behaviour_snapshot", "python": sys.version.split()[0]}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        report["contact_smooth"] = run_json(["contact", "solve"] + SMOOTH, tmp)
        report["contact_rough"] = run_json(["contact", "solve"] + ROUGH, tmp)
        report["gear_evaluate"] = run_json(["gear", "evaluate"] + DESIGN_D, tmp)
        report["surrogate_predict"] = run_json(["surrogate", "predict"] + PREDICT, tmp)
        h5 = tmp / "smoke.h5"
        report["dataset_run"] = run_json(["dataset", "run", "--factorial", "smoke", "--out", str(h5),
                                          "--workers", str(workers), "--progress", "none"], tmp)
        report["dataset_file"] = read_h5(h5)
        pipe = tmp / "pipeline"
        report["pipeline_smoke"] = run_json(["pipeline", "smoke", "--out-dir", str(pipe), "--workers", str(workers),
                                             "--progress", "none"], tmp)
        report["pipeline_coefficients"] = {f.name: json.loads(f.read_text()) for f in sorted(pipe.glob("*.json"))}
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(report, indent=1, sort_keys=True) + "\n")
    return report


def _volatile(key: str) -> bool:
    return key in VOLATILE_KEYS or key.endswith("time_s") or key.endswith("_at")


def _normalise(value):
    if isinstance(value, str):
        return _SCRATCH.sub("<scratch>", _LOCATION.sub(r"(\1)", value))
    return value


def differences(before, after, where: str = "", rtol: float = 0.0) -> tuple[list[str], list[str]]:
    """(differences, additions) between two snapshot trees; volatile keys are skipped."""
    diffs: list[str] = []
    added: list[str] = []
    if isinstance(before, dict) and isinstance(after, dict):
        for key in sorted(set(before) | set(after)):
            if _volatile(key):
                continue
            here = f"{where}.{key}" if where else key
            if key not in after:
                diffs.append(f"{here}: missing after")
            elif key not in before:
                added.append(here)
            else:
                d, a = differences(before[key], after[key], here, rtol)
                diffs += d
                added += a
        return diffs, added
    if isinstance(before, list) and isinstance(after, list):
        if len(before) != len(after):
            return [f"{where}: length {len(before)} -> {len(after)}"], added
        for i, (b, a) in enumerate(zip(before, after)):
            d, ad = differences(b, a, f"{where}[{i}]", rtol)
            diffs += d
            added += ad
        return diffs, added
    b, a = _normalise(before), _normalise(after)
    if isinstance(b, (int, float)) and isinstance(a, (int, float)) and not isinstance(b, bool) and rtol > 0:
        if math.isclose(b, a, rel_tol=rtol, abs_tol=0.0):
            return diffs, added
    if b != a:
        diffs.append(f"{where}: {before!r} -> {after!r}")
    return diffs, added


def renamed(tree, names: dict[str, str]):
    """``tree`` with every key named in ``names`` (old -> new) renamed, at any depth."""
    if isinstance(tree, dict):
        return {names.get(k, k): renamed(v, names) for k, v in tree.items()}
    if isinstance(tree, list):
        return [renamed(v, names) for v in tree]
    return tree


def partial(out: Path, pending: list[int]) -> None:
    """A smoke-factorial file with every row computed except ``pending``, as an interrupted run leaves it."""
    from ehl_dataset.dataset.factorial import load_factorial
    import ehl_dataset.dataset.runner as runner
    from ehl_dataset.dataset.store import DatasetStore

    lubricant_mod = __import__("ehl_dataset.model.lubricant", fromlist=["load_lubricant"])
    plan = load_factorial("smoke")
    lub = lubricant_mod.load_lubricant(plan.lubricant)
    config = runner.solver_config(runner.DEFAULT_SOLVER, plan.level, plan.effects)
    lubricant_dict = json.loads(runner.canonical_json(lub.to_json_dict()))
    if out.exists():
        out.unlink()
    store = DatasetStore.create(out, plan.points(), factorial=plan.to_dict(), solver=config, lubricant=lubricant_dict)
    with store:
        session = store.begin_session(kind="run", workers=0, scheduler="", solver=runner.DEFAULT_SOLVER,
                                      time_limit_s=None, retry_not_converged=False)
        pts = store.points()
        lubricant_json = runner.canonical_json(store.lubricant)
        todo = [i for i in range(store.n_points) if i not in pending]
        for index in todo:
            task = runner.PointTask(index, tuple(float(v) for v in pts[index]), lubricant_json, plan.level,
                                    plan.effects, runner.DEFAULT_SOLVER, None)
            result = runner.compute_point(task)
            store.record(index, status=result["status"], record=result["record"], error=result["error"],
                         attempts=1, worker_time=result["worker_time"], worker=result["worker"],
                         warnings=result["warnings"])
        store.flush()
        store.end_session(session, computed=len(todo), wall_time_s=0.0, interrupted="SIGINT", error="")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    rec = sub.add_parser("record", help="run the commands and write the snapshot JSON")
    rec.add_argument("--out", required=True, type=Path)
    rec.add_argument("--workers", type=int, default=2, help="workers of the dataset run (default 2)")
    cmp_ = sub.add_parser("compare", help="compare two snapshots (exit 1 on a difference)")
    cmp_.add_argument("before", type=Path)
    cmp_.add_argument("after", type=Path)
    cmp_.add_argument("--rtol", type=float, default=0.0, help="relative tolerance of numbers (default 0: exact)")
    cmp_.add_argument("--rename", nargs="*", default=[], metavar="OLD=NEW",
                      help="keys renamed between the two records (the changelog lists them): compared under NEW")
    part = sub.add_parser("partial", help="write a partially computed smoke dataset file")
    part.add_argument("--out", required=True, type=Path)
    part.add_argument("--pending", default="6,7,8,12",
                      help="rows left pending (default 6,7,8,12: two smooth and two short rough ones)")
    args = parser.parse_args(argv)
    if args.command == "record":
        report = record(args.out, args.workers)
        print(json.dumps({k: v.get("exit") for k, v in report.items() if isinstance(v, dict) and "exit" in v}))
        return 0
    if args.command == "partial":
        partial(args.out, [int(i) for i in args.pending.split(",") if i.strip()])
        print(f"{args.out}: {args.out.stat().st_size} bytes")
        return 0
    before = renamed(json.loads(args.before.read_text()), dict(r.split("=", 1) for r in args.rename))
    after = json.loads(args.after.read_text())
    diffs, added = differences(before, after, rtol=args.rtol)
    for line in added:
        print(f"added: {line}")
    for line in diffs:
        print(f"DIFFERENT: {line}")
    print(f"{len(diffs)} differences, {len(added)} additions (volatile keys ignored: wall times, timestamps, "
          "hosts, paths)")
    return 1 if diffs else 0


if __name__ == "__main__":
    raise SystemExit(main())
