"""Every ``gearloss`` example in README.md and docs/ runs: extract them, run them, and regenerate the figures.

A fenced code block that holds a ``gearloss`` command must be preceded (on the line before its opening fence) by a
marker comment that says what it is:

* ``<!-- example -->`` — run it; every command must exit 0 (``<!-- example exit=1 -->``: exit 1, e.g. a result flagged
  outside the validity). Quick examples: ``tests/test_doc_examples.py`` runs them all;
* ``<!-- example slow -->`` — a long run (the main job, a full figure): run only by this script with
  ``--all``;
* ``<!-- synopsis -->`` — option syntax with placeholders (``[--json]``, ``FILE``), not a command.

The commands of a block are its lines that start with ``gearloss`` — or, in a block that shows output after a ``$ ``
prompt, its lines that start with ``$ gearloss`` (a trailing backslash continues a line; ``cmd && gearloss ...`` runs
the gearloss part). The blocks of one page run in order in one temporary
directory, so an example may use the files an earlier one wrote. Figures made by ``gearloss report`` carry their
command under them (``*Made by `gearloss report ...` ...*``); ``--figures`` re-runs those commands from the
repository root (after a change of the solver or of the coefficients the figures are regenerated this way).

    python -m workflows.doc_examples            # run the quick examples
    python -m workflows.doc_examples --all      # and the slow ones
    python -m workflows.doc_examples --list     # list every example and its kind
    python -m workflows.doc_examples --figures  # regenerate the docs figures made by gearloss report
"""

from __future__ import annotations

import argparse
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
MARKER = re.compile(r"<!--\s*(example|synopsis)\b([^>]*)-->\s*$")
FENCE = re.compile(r"^```")
CAPTION = re.compile(r"\*Made by `([^`]+)`")


@dataclass
class Example:
    """One marked block: its page and line, ``kind`` (example or synopsis), ``slow``, the expected exit code and
    its gearloss commands (argument lists without the leading ``gearloss``)."""

    page: str
    line: int
    kind: str
    slow: bool
    exit_code: int
    commands: list[list[str]]


def pages(root: Path = REPO) -> list[Path]:
    """README.md and every Markdown page under ``docs/`` (sub-folders included), in a stable order."""
    return [root / "README.md", *sorted((root / "docs").rglob("*.md"))]


def _commands(block: list[str]) -> list[list[str]]:
    joined, current = [], ""
    for line in block:
        current += line.rstrip("\\").rstrip() + " " if line.rstrip().endswith("\\") else line
        if not line.rstrip().endswith("\\"):
            joined.append(current)
            current = ""
    prompted = any(line.strip().startswith("$ ") for line in joined)
    out = []
    for line in joined:
        text = line.strip()
        if prompted and not text.startswith("$ "):
            continue  # output of a command shown with a prompt
        if text.startswith("$ "):
            text = text[2:]
        if "&& gearloss " in text:
            text = "gearloss " + text.split("&& gearloss ", 1)[1]
        if text.startswith("gearloss "):
            try:
                out.append(shlex.split(text)[1:])
            except ValueError:  # a synopsis with unbalanced quotes: not run, only listed
                out.append(text.split()[1:])
    return out


def extract(path: Path) -> tuple[list[Example], list[tuple[int, str]]]:
    """The marked examples of a page, and the unmarked blocks that hold a gearloss command (line, first command)."""
    lines = path.read_text().splitlines()
    examples, unmarked = [], []
    i = 0
    while i < len(lines):
        if FENCE.match(lines[i]):
            start = i
            j = i + 1
            while j < len(lines) and not FENCE.match(lines[j]):
                j += 1
            body = lines[start + 1:j]
            commands = _commands(body)
            if commands:
                marker = MARKER.search(lines[start - 1]) if start > 0 else None
                name = str(path.relative_to(REPO)) if path.is_relative_to(REPO) else str(path)
                if marker is None:
                    unmarked.append((start + 1, "gearloss " + " ".join(commands[0])))
                else:
                    options = marker.group(2)
                    code = re.search(r"exit=(\d+)", options)
                    examples.append(Example(name, start + 1, marker.group(1), "slow" in options.split(),
                                            int(code.group(1)) if code else 0, commands))
            i = j + 1
        else:
            i += 1
    return examples, unmarked


def run_example(example: Example, cwd: Path, timeout: float = 900.0) -> list[tuple[list[str], int, str, float]]:
    """Run the commands of an example in ``cwd``: [(argv, exit code, stderr tail, seconds)]."""
    results = []
    env = {**os.environ, "PYTHONPATH": str(REPO) + os.pathsep + os.environ.get("PYTHONPATH", "")}
    for argv in example.commands:
        started = time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", "workflows.cli", *argv], cwd=cwd, capture_output=True,
                              text=True, timeout=timeout, env=env)
        results.append((argv, proc.returncode, proc.stderr.strip()[-600:], time.perf_counter() - started))
    return results


def run_pages(include_slow: bool = False, verbose: bool = True) -> list[str]:
    """Run the examples of every page; the list of failures (empty: all ran as documented)."""
    failures = []
    ran: set[tuple[str, ...]] = set()  # a command that needs no file of its page runs once, on its first page
    for path in pages():
        examples, unmarked = extract(path)
        for line, command in unmarked:
            failures.append(f"{path.name}:{line}: unmarked block with `{command}` (mark it <!-- example --> or "
                            "<!-- synopsis -->)")
        runnable = [e for e in examples if e.kind == "example" and (include_slow or not e.slow)]
        if not runnable:
            continue
        with tempfile.TemporaryDirectory(prefix="gearloss_doc_") as tmp:
            for example in runnable:
                if len(example.commands) == 1 and tuple(example.commands[0]) in ran:
                    continue
                ran.update(tuple(c) for c in example.commands if len(example.commands) == 1)
                for argv, code, err, seconds in run_example(example, Path(tmp)):
                    ok = code == example.exit_code
                    if verbose:
                        print(f"{'ok  ' if ok else 'FAIL'} {example.page}:{example.line} exit {code} "
                              f"({seconds:.1f} s) gearloss {shlex.join(argv)}", flush=True)
                    if not ok:
                        failures.append(f"{example.page}:{example.line}: gearloss {shlex.join(argv)} exited {code} "
                                        f"(documented {example.exit_code}): {err}")
    return failures


def figure_captions(root: Path = REPO) -> list[tuple[str, str, str]]:
    """(page, figure path, caption) of every image in the docs; the caption is the first line starting with
    ``*Made by`` among the lines after the image up to the next image or heading (empty when there is none)."""
    out = []
    for path in pages(root):
        lines = path.read_text().splitlines()
        for i, line in enumerate(lines):
            for image in re.findall(r"!\[[^\]]*\]\(([^)]+\.png)\)", line):
                caption = ""
                for following in lines[i + 1:i + 12]:
                    if following.strip().startswith(("![", "#")):
                        break
                    if following.strip().startswith("*Made by"):
                        caption = following.strip()
                        break
                out.append((str(path.relative_to(root)), image, caption))
    return out


def regenerate_figures(verbose: bool = True) -> list[str]:
    """Re-run, from the repository root, every ``gearloss report`` command written under a docs figure."""
    failures = []
    seen = set()
    for page, image, caption in figure_captions():
        match = CAPTION.search(caption)
        if not match or not match.group(1).startswith("gearloss report") or match.group(1) in seen:
            continue
        seen.add(match.group(1))
        argv = shlex.split(match.group(1))[1:]
        started = time.perf_counter()
        proc = subprocess.run([sys.executable, "-m", "workflows.cli", *argv], cwd=REPO, capture_output=True,
                              text=True)
        if verbose:
            print(f"{'ok  ' if proc.returncode == 0 else 'FAIL'} {match.group(1)} ({time.perf_counter() - started:.0f} s)",
                  flush=True)
        if proc.returncode != 0:
            failures.append(f"{match.group(1)}: exit {proc.returncode}: {proc.stderr.strip()[-400:]}")
    return failures


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--all", action="store_true", help="also run the slow examples")
    parser.add_argument("--list", action="store_true", help="list the examples and their kinds")
    parser.add_argument("--figures", action="store_true", help="regenerate the docs figures of gearloss report")
    args = parser.parse_args(argv)
    if args.list:
        for path in pages():
            examples, unmarked = extract(path)
            for e in examples:
                kind = e.kind + (" slow" if e.slow else "") + (f" exit={e.exit_code}" if e.exit_code else "")
                for command in e.commands:
                    print(f"{e.page}:{e.line}  [{kind}]  gearloss {shlex.join(command)}")
            for line, command in unmarked:
                print(f"{path.name}:{line}  [UNMARKED]  {command}")
        return 0
    failures = regenerate_figures() if args.figures else run_pages(include_slow=args.all)
    for failure in failures:
        print(f"FAILED {failure}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
