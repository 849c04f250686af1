"""Repository hygiene over every tracked file (``git ls-files``): no absolute machine paths, no citations of a design
note that is not in the repository, no work-log wording; and the tracked result files stay small.

Text files are read whole (code, tests, docs, shipped data, result JSON); PNG figures through their text chunks
(tEXt, zTXt, iTXt: the metadata a plotting library writes); other binary files (NumPy archives, HDF5) are skipped.
The path pattern is the one of the project's tooling:
``(^|[[:space:]"'`(=])/(work|scratch|tmp|root|home|mnt)/<name>/``.
"""

from __future__ import annotations

import re
import shutil
import struct
import subprocess
import zlib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

MACHINE_PATH = re.compile(r"""(^|[\s"'`(=])/(work|scratch|tmp|root|home|mnt)/[A-Za-z0-9_.-]+/""", re.MULTILINE)
"""An absolute path under a machine's top-level folders, at the start of a line or after a space, quote, backtick,
parenthesis or equals sign."""
DESIGN_NOTE = re.compile(r"DESIGN[ ]§")
"""A section citation of the design note, which is not part of the repository."""
WORK_LOG = re.compile(r"\bsessions?[ ][0-9]+|\bthis[ ]session\b|\bissues?[ ]#?[0-9]+", re.IGNORECASE)
"""Work-log wording: numbered work sessions, the current session, issue numbers."""
CHECKS = (("machine path", MACHINE_PATH), ("design-note citation", DESIGN_NOTE), ("work-log wording", WORK_LOG))

RESULT_FOLDERS = ("benchmarks/results", "validation/results")
MAX_RESULT_FILE_BYTES = 1_000_000
MAX_RESULT_TOTAL_BYTES = 10_000_000

PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"


def tracked_files(*folders: str) -> list[Path]:
    """The files git tracks (under ``folders`` if given) that exist in the working tree."""
    git = shutil.which("git")
    if git is None or not (ROOT / ".git").exists():
        pytest.skip("not a git checkout: the tracked files are unknown")
    out = subprocess.run([git, "ls-files", "-z", "--", *folders], cwd=ROOT, capture_output=True, check=True).stdout
    return [ROOT / name for name in out.decode("utf-8").split("\0") if name and (ROOT / name).is_file()]


def png_text(data: bytes) -> str:
    """The text chunks (tEXt, zTXt, iTXt) of a PNG file's bytes, one ``key: value`` per line."""
    lines, i = [], len(PNG_SIGNATURE)
    while i + 8 <= len(data):
        (length,), kind = struct.unpack(">I", data[i:i + 4]), data[i + 4:i + 8]
        body = data[i + 8:i + 8 + length]
        i += 12 + length
        if kind == b"tEXt":
            key, _, value = body.partition(b"\0")
        elif kind == b"zTXt":
            key, _, rest = body.partition(b"\0")
            value = zlib.decompress(rest[1:])
        elif kind == b"iTXt":
            key, _, rest = body.partition(b"\0")
            compressed, rest = rest[0], rest[2:]
            rest = rest.partition(b"\0")[2].partition(b"\0")[2]  # language tag, translated keyword
            value = zlib.decompress(rest) if compressed else rest
        else:
            continue
        lines.append(f"{key.decode('latin-1')}: {value.decode('utf-8', 'replace')}")
    return "\n".join(lines)


def readable_text(path: Path) -> str | None:
    """What the checks read of ``path``: its text, a PNG's text chunks, or None for other binary files."""
    data = path.read_bytes()
    if data.startswith(PNG_SIGNATURE):
        return png_text(data)
    if b"\0" in data[:8192]:
        return None
    return data.decode("utf-8", "replace")


def findings(path: Path) -> list[str]:
    """Every hit of :data:`CHECKS` in ``path`` as ``"<file>:<line>: <kind>: <excerpt>"``."""
    text = readable_text(path)
    if text is None:
        return []
    name = path.relative_to(ROOT) if path.is_relative_to(ROOT) else path
    hits = []
    for kind, pattern in CHECKS:
        for match in pattern.finditer(text):
            line = text.count("\n", 0, match.start()) + 1
            excerpt = text[max(match.start() - 30, 0):match.end() + 30].replace("\n", " ")
            hits.append(f"{name}:{line}: {kind}: …{excerpt}…")
    return hits


def test_no_machine_paths_design_note_citations_or_work_log_wording_in_tracked_files():
    hits = [hit for path in tracked_files() for hit in findings(path)]
    assert not hits, f"{len(hits)} hits:\n" + "\n".join(hits[:60])


@pytest.mark.parametrize("planted, kind", [
    ('"path": "' + "/" + 'work/scratch/dataset.h5"', "machine path"),
    ("title = " + "/" + "home/someone/figures/fit.png", "machine path"),
    ("(`python run.py --out " + "/" + "tmp/out/x.json`)", "machine path"),
    ("limits (" + "DESIGN" + " §6)", "design-note citation"),
    ("measured in " + "session" + " 25", "work-log wording"),
])
def test_the_checker_catches_what_is_planted_in_a_copy_of_a_clean_tracked_file(tmp_path, planted, kind):
    """A shipped coefficient file passes; the same file with one planted line fails, naming the line and the kind."""
    source = ROOT / "data" / "coefficients" / "atf_quick.json"
    clean = tmp_path / source.name
    clean.write_bytes(source.read_bytes())
    assert findings(clean) == []
    lines = clean.read_text(encoding="utf-8").splitlines(keepends=True)
    lines.insert(3, planted + "\n")
    clean.write_text("".join(lines), encoding="utf-8")
    hits = findings(clean)
    assert len(hits) == 1 and f":4: {kind}:" in hits[0]


def test_relative_paths_and_urls_are_not_machine_paths(tmp_path):
    """Repository-relative paths, file names and URLs whose path has the same folder names pass."""
    path = tmp_path / "ok.md"
    path.write_text("data/reference/deterministic_validation.json, dataset.h5, https://example.org/home/page/,\n"
                    "validation/results/work/x.json, a/tmp/b/c\n", encoding="utf-8")
    assert findings(path) == []


def test_the_checker_reads_png_text_chunks(tmp_path):
    """A figure's metadata is checked: a tEXt chunk with an absolute path planted in a copy of a tracked PNG fails."""
    figures = [p for p in tracked_files("docs") if p.suffix == ".png"]
    if not figures:
        pytest.skip("no tracked PNG figure")
    data = figures[0].read_bytes()
    assert findings(figures[0]) == []
    body = b"Title\0" + ("/" + "root/plots/fit.png").encode()
    chunk = struct.pack(">I", len(body)) + b"tEXt" + body + struct.pack(">I", zlib.crc32(b"tEXt" + body))
    end = data.rindex(b"IEND") - 4  # the IEND chunk starts with its length
    planted = tmp_path / "figure.png"
    planted.write_bytes(data[:end] + chunk + data[end:])
    hits = findings(planted)
    assert len(hits) == 1 and "machine path" in hits[0] and "Title: " in png_text(planted.read_bytes())


def test_tracked_result_files_are_small():
    """Tracked files under benchmarks/results and validation/results: each ≤ 1 MB, together ≤ 10 MB (raw series are
    regenerated by their command into untracked folders)."""
    sizes = {p.relative_to(ROOT).as_posix(): p.stat().st_size for p in tracked_files(*RESULT_FOLDERS)}
    too_large = {name: size for name, size in sizes.items() if size > MAX_RESULT_FILE_BYTES}
    assert too_large == {}
    assert sum(sizes.values()) <= MAX_RESULT_TOTAL_BYTES, f"{sum(sizes.values()):,} bytes in {len(sizes)} files"


@pytest.mark.parametrize("folder", ["benchmarks", "validation"])
def test_every_script_has_its_line_in_the_folders_readme(folder):
    """benchmarks/README.md and validation/README.md name every tracked script of their folder (sub-folders included,
    by their path relative to it), so each one has a documented command."""
    readme = (ROOT / folder / "README.md").read_text(encoding="utf-8")
    scripts = [p.relative_to(ROOT / folder).as_posix() for p in tracked_files(folder)
               if p.suffix == ".py" and "results" not in p.relative_to(ROOT / folder).parts]
    assert scripts
    assert [name for name in scripts if f"`{name}`" not in readme] == []
