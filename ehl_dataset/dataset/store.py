"""The HDF5 store of a factorial run: one file per run, one preallocated row per point, resumable
(docs/reference/dataset-format.md).

Layout (format ``gearloss-ehl-dataset``, version :data:`FORMAT_VERSION`)::

    /                     root attributes: format, format_version, package_version, created (ISO 8601, UTC),
                          git_revision, n_points, factorial (JSON), factorial_sha256, solver (JSON),
                          lubricant (JSON, ``Lubricant.to_json_dict()``), sessions (JSON list of runs/resumes),
                          roughness (JSON ``{"name", "sha256"}``: the roughness profile of the rough points; absent
                          from files written before it was recorded, and for a solve function other than the
                          package's, whose profile the runner does not know)
    /points/point         row index 0..N-1 (an HDF5 dimension scale attached to every column)
    /points/<column>      one 1-D dataset per column, length N; attributes ``units`` and ``description``

Columns: the inputs (:data:`ehl_dataset.dataset.factorial.POINT_FIELDS`, SI), the solver outputs
(:data:`ehl_dataset.solvers.result.RECORD_UNITS`), ``status`` (enum pending/ok/failed), ``error`` (failure text, or the
solver's message for a non-converged result), ``attempts`` (how many computations of the point were recorded, over
all sessions), ``worker_time`` [s] (worker-side time including retries), ``finished_at`` [s since the Unix epoch],
``worker`` (host:pid) and ``warnings`` (Python warnings raised during the solve, counted by category and place).
The grid of a solve (``dx``, ``n_nodes``, ``n_steps``), ``mu_sem`` and ``warnings`` were added within format version 1
(:data:`OPTIONAL_COLUMNS`): files without them are read and resumed.

Crash safety. Every dataset is contiguous, fixed-size and written in full when the file is created (strings are
fixed-length UTF-8), and the file is built under a temporary name and renamed into place. After creation a run
only overwrites raw data in place — no HDF5 metadata (heaps, B-trees, chunk indices) changes while points are being
computed — so killing the writer at any moment loses at most the rows buffered since the last :meth:`flush`, never
the file. Only the ``sessions`` attribute is rewritten, once when a session starts and once when it ends.
Readers open the file without HDF5 file locking, so ``gearloss dataset info`` works while a run is writing.
"""

from __future__ import annotations

import datetime as _dt
import json
import math
import os
import socket
import subprocess
import time
from contextlib import contextmanager
from dataclasses import dataclass
from importlib import metadata as _metadata
from pathlib import Path
from typing import Any, Iterable

import numpy as np

from ..model.roughness_identity import check_roughness_record, describe_roughness
from ..solvers.result import RECORD_UNITS
from ..validation import InputError
from .factorial import POINT_DTYPE, POINT_FIELDS, POINT_UNITS, canonical_json

FORMAT_NAME = "gearloss-ehl-dataset"
FORMAT_VERSION = 1
STATUS_NAMES: tuple[str, ...] = ("pending", "ok", "failed")
PENDING, OK, FAILED = 0, 1, 2

EFFECTS_WIDTH = 1536
"""Bytes reserved per row for the effect plan (compact JSON; the planner's plans with reasons are ~0.9 kB)."""
ERROR_WIDTH = 512
"""Bytes reserved per row for the error text (longer text is cut, keeping its start and end)."""

OPTIONAL_COLUMNS = frozenset({"warnings", "mu_sem", "dx", "n_nodes", "n_steps"})
"""Columns added within format version 1: files written before them are read (as "") and resumed without them."""

WARNINGS_WIDTH = 256
"""Bytes reserved per row for the summary of Python warnings raised during the solve."""

_GRID_OUTPUTS = ("dx", "n_nodes", "n_steps")

_FLOAT_OUTPUTS = ("mu", "mu_std", "mu_sem", "h_min", "h_central", "lambda_bar", "asperity_load_share", "p_max", "wall_time")

_DESCRIPTIONS: dict[str, str] = {
    "p_h": "maximum Hertz pressure",
    "r_eq": "equivalent radius of curvature",
    "u_r": "rolling (entrainment) velocity",
    "sr": "slide-to-roll ratio (u1 - u2)/u_r",
    "temperature": "oil inlet temperature",
    "rq1": "RMS roughness of surface 1",
    "rq2": "RMS roughness of surface 2",
    "mu": "friction coefficient (time average)",
    "mu_std": "standard deviation of mu over the averaging window",
    "mu_sem": "standard error of the time-averaged mu (autocorrelation-corrected; 0 for steady solves)",
    "h_min": "minimum film thickness",
    "h_central": "film thickness at x = 0",
    "lambda_bar": "Dowson-Higginson minimum film over composite roughness",
    "asperity_load_share": "share of the load carried where asperities touch",
    "p_max": "maximum pressure",
    "iterations": "solver iterations (-1: not computed)",
    "converged": "solver met its tolerances",
    "wall_time": "solver wall time reported by the solver",
    "effects": "effect plan simulated (JSON)",
    "level": "accuracy level",
    "status": "pending / ok / failed",
    "error": "error text of a failed point, or the solver message of a non-converged one",
    "attempts": "computations of this point recorded in the file (all sessions)",
    "worker_time": "worker-side time of the last computation, retries included",
    "finished_at": "time the result was received, seconds since the Unix epoch (UTC)",
    "worker": "host:pid of the worker process",
    "warnings": "Python warnings raised during the solve: category x count (file:line); ...",
    "dx": "uniform grid spacing of the deterministic model (NaN: a steady solver's graded grid)",
    "n_nodes": "grid nodes of the solve (-1: not recorded)",
    "n_steps": "time steps of the solve (0: steady; -1: not recorded)",
}


@dataclass(frozen=True)
class Column:
    """One per-point dataset: name, numpy dtype, fill value of a pending row, unit."""

    name: str
    dtype: Any
    fill: Any
    units: str


def _str_dtype(length: int):
    import h5py

    return h5py.string_dtype("utf-8", length)


def _columns() -> tuple[Column, ...]:
    import h5py

    cols = [Column(name, "<f8", math.nan, POINT_UNITS[name]) for name in POINT_FIELDS]
    cols += [Column(name, "<f8", math.nan, RECORD_UNITS[name]) for name in _FLOAT_OUTPUTS if name != "wall_time"]
    cols += [
        Column("iterations", "<i4", -1, RECORD_UNITS["iterations"]),
        Column("converged", np.bool_, False, RECORD_UNITS["converged"]),
        Column("wall_time", "<f8", math.nan, RECORD_UNITS["wall_time"]),
        Column("effects", _str_dtype(EFFECTS_WIDTH), b"", RECORD_UNITS["effects"]),
        Column("level", _str_dtype(32), b"", RECORD_UNITS["level"]),
        Column("status", h5py.enum_dtype({n: i for i, n in enumerate(STATUS_NAMES)}, basetype="i1"), PENDING,
               "enum"),
        Column("error", _str_dtype(ERROR_WIDTH), b"", "text"),
        Column("attempts", "<i4", 0, "1"),
        Column("worker_time", "<f8", math.nan, "s"),
        Column("finished_at", "<f8", math.nan, "s since 1970-01-01T00:00:00Z"),
        Column("worker", _str_dtype(64), b"", "host:pid"),
        Column("warnings", _str_dtype(WARNINGS_WIDTH), b"", "text"),
        Column("dx", "<f8", math.nan, RECORD_UNITS["dx"]),
        Column("n_nodes", "<i4", -1, RECORD_UNITS["n_nodes"]),
        Column("n_steps", "<i8", -1, RECORD_UNITS["n_steps"]),
    ]
    return tuple(cols)


TABLE_COLUMNS: tuple[str, ...] = (
    "point", *POINT_FIELDS, "mu", "mu_std", "h_min", "h_central", "lambda_bar", "asperity_load_share", "p_max",
    "iterations", "converged", "wall_time", "effects", "level", "status", "error",
    "attempts", "worker_time", "finished_at", "worker", "warnings", "mu_sem", "dx", "n_nodes", "n_steps",
)
"""Column order of :func:`read_table` (the first 22 are the contract used by the surrogate stage)."""


# ---------------------------------------------------------------------------------------------------------------
# Provenance helpers
# ---------------------------------------------------------------------------------------------------------------
def package_version() -> str:
    """Installed gearloss version (``unknown`` when run from an uninstalled tree)."""
    try:
        return _metadata.version("gearloss")
    except _metadata.PackageNotFoundError:  # pragma: no cover
        return "unknown"


def git_revision() -> str:
    """``<sha>`` of the source checkout, with ``+dirty`` if it has uncommitted changes; ``""`` if not a checkout."""
    here = Path(__file__).resolve().parent
    try:
        sha = subprocess.run(["git", "rev-parse", "HEAD"], cwd=here, capture_output=True, text=True, timeout=5)
        if sha.returncode != 0:
            return ""
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=here,
                               capture_output=True, text=True, timeout=5)
        return sha.stdout.strip() + ("+dirty" if dirty.stdout.strip() else "")
    except (OSError, subprocess.SubprocessError):
        return ""


def _now_iso() -> str:
    return _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")


def _fit_utf8(text: str, width: int) -> bytes:
    """UTF-8 bytes of ``text`` cut to ``width`` bytes (keeping the start and the end, which hold the useful parts)."""
    raw = text.encode("utf-8")
    if len(raw) <= width:
        return raw
    marker = " ... ".encode()
    head = (width - len(marker)) * 2 // 3
    tail = width - len(marker) - head
    return (raw[:head].decode("utf-8", "ignore") + " ... " + raw[-tail:].decode("utf-8", "ignore")).encode()[:width]


def _round_floats(value, digits: int = 4):
    if isinstance(value, float):
        return float(f"{value:.{digits}g}") if math.isfinite(value) else value
    if isinstance(value, dict):
        return {k: _round_floats(v, digits) for k, v in value.items()}
    if isinstance(value, list):
        return [_round_floats(v, digits) for v in value]
    return value


def encode_effects(effects: str | dict) -> bytes:
    """Compact JSON of an effect plan within :data:`EFFECTS_WIDTH` bytes.

    The flags are always kept. If the plan is too long, the numbers in its ``reasons`` are rounded to 4
    significant digits; if still too long, the ``reasons`` are replaced by a note saying so.
    """
    plan = json.loads(effects) if isinstance(effects, str) else dict(effects)
    candidates = [plan, {**plan, "reasons": _round_floats(plan.get("reasons", {}))},
                  {**plan, "reasons": {"omitted": f"plan longer than {EFFECTS_WIDTH} bytes"}}]
    for candidate in candidates:
        raw = json.dumps(candidate, sort_keys=True, separators=(",", ":")).encode()
        if len(raw) <= EFFECTS_WIDTH:
            return raw
    raise ValueError(f"effect plan does not fit in {EFFECTS_WIDTH} bytes even without reasons: {raw[:80]!r}...")


def _bad_file(path, detail: str) -> InputError:
    return InputError("dataset file", str(path), f"a {FORMAT_NAME} HDF5 file (format version <= {FORMAT_VERSION})",
                      detail)


def _unreadable(path, err: OSError) -> InputError:
    """A file h5py opened but could not read: corrupt, or read without a lock while its writer was flushing."""
    return _bad_file(path, f"its contents could not be read ({err}); if a run is writing it, read it again "
                           "after the next flush")


def _open_h5(path, mode: str):
    import h5py

    path = Path(path)
    if not path.exists():
        raise FileNotFoundError(2, "No such file", str(path))
    try:
        if mode == "r":
            try:
                return h5py.File(path, "r", locking=False)
            except OSError as err:
                if "locking flag values don't match" not in str(err):
                    raise
                return h5py.File(path, "r")  # already open for writing in this process: share that handle
        return h5py.File(path, mode)
    except OSError as err:
        text = str(err)
        if "truncated" in text.lower():
            raise _bad_file(path, f"the file is truncated: {text}") from None
        if "unable to lock" in text.lower() or "file locking" in text.lower():
            raise InputError("dataset file", str(path), "a file no other process is writing",
                             f"it is locked: is a run still going on? ({text})") from None
        raise _bad_file(path, f"not a readable HDF5 file: {text}") from None


# ---------------------------------------------------------------------------------------------------------------
# The store
# ---------------------------------------------------------------------------------------------------------------
SOLVER_DEFAULTS = {"model": "auto"}
"""Solver-configuration entries that files written before they existed lack, with the value those files ran."""


class DatasetStore:
    """A dataset file opened for reading (``mode="r"``) or by the single writer (``mode="r+"``).

    Create with :meth:`create`, open with :meth:`open`; use as a context manager. The writer buffers results
    (:meth:`record`) and writes them on :meth:`flush` (which the runner calls every few seconds).
    """

    def __init__(self, handle, path: Path, writable: bool):
        self._h5 = handle
        self.path = Path(path)
        self.writable = writable
        self._buffer: dict[int, dict[str, Any]] = {}
        self._columns = {c.name: c for c in _columns()}
        self._validate()
        points = self._h5["points"]
        try:
            self._status = points["status"][...].astype(np.int8)
            self._attempts = points["attempts"][...].astype(np.int64)
        except OSError as err:
            raise _bad_file(self.path, f"cannot read the status column: {err}") from None

    # -- creation and opening ---------------------------------------------------------------------------------
    @classmethod
    def create(cls, path, points: np.ndarray, *, factorial: dict, solver: dict, lubricant: dict,
               overwrite: bool = False, roughness: dict | None = None) -> "DatasetStore":
        """Create a new file for ``points`` (dtype :data:`POINT_DTYPE`) and open it for writing.

        ``factorial`` (with ``points_sha256``), ``solver`` (function, version, level, effects, ...),
        ``lubricant`` (``Lubricant.to_json_dict()``) and ``roughness`` (``{"name", "sha256"}`` of the profile the
        rough points use, :func:`ehl_dataset.model.roughness_identity.roughness_identity`; None: not recorded) are
        stored as JSON root attributes and checked on resume.
        """
        import h5py

        path = Path(path)
        roughness = check_roughness_record(roughness, "roughness")
        if path.exists() and not overwrite:
            raise InputError("out", str(path), "a new file (or pass overwrite to replace it)", "the file exists")
        points = np.asarray(points)
        if points.dtype != POINT_DTYPE or points.ndim != 1 or points.size == 0:
            raise ValueError(f"points must be a non-empty 1-D array of dtype {POINT_DTYPE}")
        n = points.size
        path.parent.mkdir(parents=True, exist_ok=True)
        tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
        try:
            with h5py.File(tmp, "w", track_order=True) as h5:
                attrs = h5.attrs
                attrs["format"] = FORMAT_NAME
                attrs["format_version"] = FORMAT_VERSION
                attrs["package_version"] = package_version()
                attrs["created"] = _now_iso()
                attrs["git_revision"] = git_revision()
                attrs["n_points"] = n
                attrs["factorial"] = canonical_json(factorial)
                attrs["factorial_sha256"] = str(factorial.get("points_sha256", ""))
                attrs["solver"] = canonical_json(solver)
                attrs["lubricant"] = canonical_json(lubricant)
                if roughness is not None:
                    attrs["roughness"] = canonical_json(roughness)
                attrs["sessions"] = "[]"
                group = h5.create_group("points", track_order=True)
                scale = group.create_dataset("point", data=np.arange(n, dtype="<i8"), track_times=False)
                scale.make_scale("point")
                scale.attrs["units"] = "1"
                scale.attrs["description"] = "row index of the factorial point (C order over the axes)"
                for col in _columns():
                    if col.name in POINT_FIELDS:
                        data = np.ascontiguousarray(points[col.name])
                    else:
                        data = np.full(n, col.fill, dtype=col.dtype)
                    ds = group.create_dataset(col.name, data=data, dtype=col.dtype, track_times=False)
                    ds.attrs["units"] = col.units
                    ds.attrs["description"] = _DESCRIPTIONS[col.name]
                    ds.dims[0].attach_scale(scale)
                    if col.name == "status":
                        ds.attrs["states"] = ", ".join(f"{i}={s}" for i, s in enumerate(STATUS_NAMES))
            os.replace(tmp, path)
        finally:
            if tmp.exists():
                tmp.unlink()
        return cls.open(path, "r+")

    @classmethod
    def open(cls, path, mode: str = "r") -> "DatasetStore":
        """Open an existing dataset file; ``mode`` is ``"r"`` (reader, no lock) or ``"r+"`` (the one writer)."""
        if mode not in ("r", "r+"):
            raise ValueError("mode must be 'r' or 'r+'")
        handle = _open_h5(path, mode)
        try:
            return cls(handle, Path(path), mode == "r+")
        except OSError as err:
            handle.close()
            raise _unreadable(path, err) from None
        except BaseException:
            handle.close()
            raise

    def _validate(self) -> None:
        attrs = self._h5.attrs
        fmt = attrs.get("format")
        if fmt is None:
            raise _bad_file(self.path, "no 'format' attribute: a foreign HDF5 file")
        if _as_str(fmt) != FORMAT_NAME:
            raise _bad_file(self.path, f"format is {_as_str(fmt)!r}")
        version = int(attrs.get("format_version", -1))
        if not 1 <= version <= FORMAT_VERSION:
            raise _bad_file(self.path, f"format_version {version} is not supported by this gearloss")
        for key in ("factorial", "solver", "lubricant", "sessions"):
            try:
                json.loads(_as_str(attrs[key]))
            except (KeyError, ValueError) as err:
                raise _bad_file(self.path, f"root attribute {key!r} missing or not JSON ({err})") from None
        n = int(attrs.get("n_points", -1))
        if "points" not in self._h5:
            raise _bad_file(self.path, "the 'points' group is missing")
        group = self._h5["points"]
        for name in ("point", *self._columns):
            if name in OPTIONAL_COLUMNS and name not in group:
                continue
            if name not in group:
                raise _bad_file(self.path, f"column 'points/{name}' is missing")
            if group[name].shape != (n,):
                raise _bad_file(self.path, f"column 'points/{name}' has shape {group[name].shape}, expected ({n},)")
            if self.writable and group[name].chunks is not None:
                raise InputError("dataset file", str(self.path), "a file written by gearloss (contiguous layout)",
                                 f"column {name!r} is chunked: a repacked/compressed copy is read-only, "
                                 "resume the original")

    # -- metadata ------------------------------------------------------------------------------------------------
    @property
    def n_points(self) -> int:
        return int(self._h5.attrs["n_points"])

    def _json_attr(self, key: str):
        return json.loads(_as_str(self._h5.attrs[key]))

    @property
    def factorial(self) -> dict:
        return self._json_attr("factorial")

    @property
    def solver(self) -> dict:
        return self._json_attr("solver")

    @property
    def lubricant(self) -> dict:
        return self._json_attr("lubricant")

    @property
    def sessions(self) -> list:
        return self._json_attr("sessions")

    @property
    def roughness(self) -> dict | None:
        """The recorded roughness profile ``{"name", "sha256"}``, or None where the file records none."""
        if "roughness" not in self._h5.attrs:
            return None
        try:
            return check_roughness_record(self._json_attr("roughness"), "roughness")
        except (ValueError, InputError) as err:
            raise _bad_file(self.path, f"root attribute 'roughness' is not a roughness record ({err})") from None

    def counts(self) -> dict[str, int]:
        """Number of rows per status (including results still in the write buffer)."""
        return {name: int(np.count_nonzero(self._status == i)) for i, name in enumerate(STATUS_NAMES)}

    def metadata(self) -> dict[str, Any]:
        """Root attributes decoded (JSON parsed) plus counts by status."""
        attrs = self._h5.attrs
        counts = self.counts()
        return {
            "path": str(self.path),
            "format": FORMAT_NAME,
            "format_version": int(attrs["format_version"]),
            "package_version": _as_str(attrs["package_version"]),
            "created": _as_str(attrs["created"]),
            "git_revision": _as_str(attrs["git_revision"]),
            "n_points": self.n_points,
            "factorial": self.factorial,
            "factorial_sha256": _as_str(attrs["factorial_sha256"]),
            "solver": self.solver,
            "lubricant": self.lubricant,
            "roughness": self.roughness,
            "sessions": self.sessions,
            "counts": counts,
            "n_ok": counts["ok"],
            "n_failed": counts["failed"],
            "n_pending": counts["pending"],
        }

    # -- reading ---------------------------------------------------------------------------------------------------
    def status(self) -> np.ndarray:
        """Status codes (int8: 0 pending, 1 ok, 2 failed) of every row, buffered results included."""
        return self._status.copy()

    def pending_indices(self) -> np.ndarray:
        """Rows that still need computing: every row whose status is not ``ok``."""
        return np.flatnonzero(self._status != OK)

    def points(self) -> np.ndarray:
        """The input table (dtype :data:`POINT_DTYPE`, SI)."""
        out = np.empty(self.n_points, dtype=POINT_DTYPE)
        for name in POINT_FIELDS:
            out[name] = self._read(name)
        return out

    def column(self, name: str) -> np.ndarray:
        """One stored column as written so far (buffered results not included until :meth:`flush`)."""
        if name != "point" and name not in self._columns:
            raise InputError("column", name, f"one of {list(TABLE_COLUMNS)}")
        return self._read(name)

    def _read(self, name: str) -> np.ndarray:
        if name in OPTIONAL_COLUMNS and name not in self._h5["points"]:
            return np.full(self.n_points, self._columns[name].fill, dtype=self._columns[name].dtype)
        try:
            return self._h5["points"][name][...]
        except OSError as err:
            raise _bad_file(self.path, f"cannot read column {name!r}: {err}") from None

    def table(self, status: str | None = "ok"):
        """Tidy :class:`pandas.DataFrame` (columns :data:`TABLE_COLUMNS`), filtered by ``status`` (None: all)."""
        import pandas as pd

        if status is not None and status not in STATUS_NAMES:
            raise InputError("status", status, f"one of {list(STATUS_NAMES)} or None")
        columns: dict[str, Any] = {"point": self._read("point").astype(np.int64)}
        for name in TABLE_COLUMNS[1:]:
            data = self._read(name)
            if name == "status":
                data = np.asarray(STATUS_NAMES, dtype=object)[data.astype(np.int64)]
            elif data.dtype.kind == "S":
                data = np.char.decode(data, "utf-8").astype(object)
            elif data.dtype.kind == "O":  # pragma: no cover - variable-length strings (not written by this version)
                data = np.array([v.decode() if isinstance(v, bytes) else str(v) for v in data], dtype=object)
            columns[name] = data
        frame = pd.DataFrame(columns)
        frame["converged"] = frame["converged"].astype(bool)
        if status is not None:
            frame = frame[frame["status"] == status].reset_index(drop=True)
        return frame

    # -- compatibility ------------------------------------------------------------------------------------------
    def check_compatible(self, *, factorial_sha256: str | None = None, solver: dict | None = None,
                         lubricant: dict | None = None, roughness: dict | None = None) -> None:
        """Refuse (``InputError``) to continue this file with a different factorial, solver, lubricant or roughness
        profile (a file that records no roughness is continued as before)."""
        hint = "start a new file (another --out, or --overwrite) to change it"
        recorded_hash = _as_str(self._h5.attrs["factorial_sha256"])
        if factorial_sha256 is not None and factorial_sha256 != recorded_hash:
            raise InputError("factorial", f"points_sha256 {factorial_sha256[:16]}...",
                             f"the factorial recorded in {self.path} "
                             f"({self.factorial.get('name')!r}, points_sha256 {recorded_hash[:16]}...)", hint)
        if solver is not None:
            recorded, solver = {**SOLVER_DEFAULTS, **self.solver}, {**SOLVER_DEFAULTS, **solver}
            # the level definition last: it changes with the code, and the version (or the option the user
            # changed) says why
            for key in sorted(set(recorded) | set(solver), key=lambda k: (k == "level_definition", k)):
                if canonical_json(recorded.get(key)) != canonical_json(solver.get(key)):
                    raise InputError(f"solver.{key}", solver.get(key),
                                     f"{recorded.get(key)!r} as recorded in {self.path}", hint)
        if lubricant is not None and canonical_json(lubricant) != canonical_json(self.lubricant):
            raise InputError("lubricant", lubricant.get("name", "<unnamed>"),
                             f"the lubricant definition recorded in {self.path} "
                             f"({self.lubricant.get('name', '<unnamed>')!r}, compared field by field)", hint)
        recorded_roughness = self.roughness
        if roughness is not None and recorded_roughness is not None and roughness != recorded_roughness:
            raise InputError("roughness", describe_roughness(roughness), f"the roughness profile recorded in "
                             f"{self.path} ({describe_roughness(recorded_roughness)})", hint)

    # -- writing ---------------------------------------------------------------------------------------------------
    def _require_writable(self):
        if not self.writable:
            raise PermissionError(f"{self.path} is open read-only")

    def record(self, index: int, *, status: int, record: dict | None = None, error: str = "",
               attempts: int = 1, worker_time: float = math.nan, worker: str = "",
               finished_at: float | None = None, warnings: str = "") -> None:
        """Buffer the result of one point; written at the next :meth:`flush`.

        ``record`` is ``ContactResult.to_record()`` (may be None for a failed point); ``attempts`` computations
        are added to the row's counter.
        """
        self._require_writable()
        index = int(index)
        if not 0 <= index < self.n_points:
            raise IndexError(f"point {index} outside 0..{self.n_points - 1}")
        if status not in (OK, FAILED):
            raise ValueError("status must be OK or FAILED")
        row: dict[str, Any] = {name: self._columns[name].fill for name in
                               (*_FLOAT_OUTPUTS, "iterations", "converged", "effects", "level", *_GRID_OUTPUTS)}
        if record:
            for name in _FLOAT_OUTPUTS:
                row[name] = float(record.get(name, math.nan))
            for name in _GRID_OUTPUTS:  # cast to the column's dtype at flush
                row[name] = record.get(name, self._columns[name].fill)
            row["iterations"] = int(record.get("iterations", -1))
            row["converged"] = bool(record.get("converged", False))
            row["effects"] = encode_effects(record["effects"]) if record.get("effects") else b""
            row["level"] = _fit_utf8(str(record.get("level", "")), 32)
        row["status"] = status
        row["error"] = _fit_utf8(error, ERROR_WIDTH)
        self._attempts[index] += int(attempts)
        row["attempts"] = int(self._attempts[index])
        row["worker_time"] = float(worker_time)
        row["finished_at"] = time.time() if finished_at is None else float(finished_at)
        row["worker"] = _fit_utf8(worker, 64)
        row["warnings"] = _fit_utf8(warnings, WARNINGS_WIDTH)
        self._buffer[index] = row
        self._status[index] = status

    @property
    def buffered(self) -> int:
        """Results waiting for the next flush."""
        return len(self._buffer)

    def flush(self) -> int:
        """Write the buffered rows (contiguous runs as slices, the status column last) and flush the file; return the
        rows written."""
        if not self._buffer:
            return 0
        self._require_writable()
        indices = np.array(sorted(self._buffer), dtype=np.int64)
        breaks = np.flatnonzero(np.diff(indices) != 1) + 1
        group = self._h5["points"]
        # status last: it commits the row, so a process killed inside a flush leaves the row pending (it is
        # computed again on resume), never "ok" with half its columns written
        names = [name for name in next(iter(self._buffer.values())) if name != "status"] + ["status"]
        for run in np.split(indices, breaks):
            start, stop = int(run[0]), int(run[-1]) + 1
            rows = [self._buffer[int(i)] for i in run]
            for name in names:
                if name in OPTIONAL_COLUMNS and name not in group:
                    continue
                col = self._columns[name]
                group[name][start:stop] = np.array([r[name] for r in rows], dtype=col.dtype)
        self._h5.flush()
        written = len(self._buffer)
        self._buffer.clear()
        return written

    def begin_session(self, **info: Any) -> int:
        """Append a session entry (kind, workers, scheduler, started) to the ``sessions`` attribute; flush."""
        self._require_writable()
        sessions = self.sessions
        entry = {"started": _now_iso(), "host": socket.gethostname(), "pid": os.getpid(), **info,
                 "pending_at_start": int(np.count_nonzero(self._status != OK))}
        sessions.append(entry)
        self._h5.attrs["sessions"] = canonical_json(sessions)
        self._h5.flush()
        return len(sessions) - 1

    def end_session(self, number: int, **info: Any) -> None:
        """Complete session ``number`` with its outcome (computed, wall time, interrupted, ...); flush."""
        self._require_writable()
        self.flush()
        sessions = self.sessions
        sessions[number].update({"ended": _now_iso(), **info})
        self._h5.attrs["sessions"] = canonical_json(sessions)
        self._h5.flush()

    def close(self) -> None:
        """Flush buffered rows (writer) and close the file."""
        if self._h5 is None:
            return
        try:
            if self.writable and self._buffer:
                self.flush()
        finally:
            self._h5.close()
            self._h5 = None

    def __enter__(self) -> "DatasetStore":
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def _as_str(value) -> str:
    return value.decode("utf-8") if isinstance(value, bytes) else str(value)


# ---------------------------------------------------------------------------------------------------------------
# The reader contract (used by the surrogate stage)
# ---------------------------------------------------------------------------------------------------------------
@contextmanager
def _reading(path):
    """The store opened for reading; an h5py error while reading it is the store's InputError naming the file."""
    with DatasetStore.open(path, "r") as store:
        try:
            yield store
        except OSError as err:
            raise _unreadable(path, err) from None


def read_table(path, status: str | None = "ok"):
    """Tidy table of a dataset file (SI units), rows filtered by ``status``.

    Columns: ``point`` (row index), ``p_h`` [Pa], ``r_eq`` [m], ``u_r`` [m/s], ``sr`` [-], ``temperature`` [K],
    ``rq1``, ``rq2`` [m], ``mu``, ``mu_std``, ``h_min`` [m], ``h_central`` [m], ``lambda_bar``,
    ``asperity_load_share``, ``p_max`` [Pa], ``iterations``, ``converged``, ``wall_time`` [s], ``effects`` (JSON
    str), ``level``, ``status`` (pending/ok/failed), ``error``; then ``attempts``, ``worker_time`` [s],
    ``finished_at`` (s since the epoch), ``worker``, ``warnings``, ``mu_sem``, ``dx`` [m], ``n_nodes``, ``n_steps``
    (the last four absent from older files: read as their fill, NaN or -1).

    Parameters
    ----------
    path : str or Path
        The HDF5 dataset file [-].
    status : str, optional
        Keep the rows of this status (``ok``, ``failed``, ``pending``); None: every row [-].

    Returns
    -------
    pandas.DataFrame
        One row per point.

    Raises
    ------
    InputError
        For a corrupt, truncated or foreign file, naming the file and the problem.
    """
    with _reading(path) as store:
        return store.table(status)


def read_metadata(path) -> dict[str, Any]:
    """Provenance of a dataset file.

    Parameters
    ----------
    path : str or Path
        The HDF5 dataset file [-].

    Returns
    -------
    dict
        format_version, package_version, created, git_revision, factorial (dict), solver (dict: function, version,
        level, effects, ...), lubricant (dict as parsed from the lubricant TOML: rebuild with
        :func:`ehl_dataset.model.lubricant.lubricant_from_dict`), roughness (``{"name", "sha256"}`` of the roughness
        profile, None where not recorded), sessions, n_points and counts by status.
    """
    with _reading(path) as store:
        return store.metadata()


def iter_status_names(codes: Iterable[int]) -> list[str]:
    """Status names of integer codes."""
    return [STATUS_NAMES[int(c)] for c in codes]


_INPUT_KEYS = {"p_h": "p_h_pa", "r_eq": "r_eq_m", "u_r": "u_r_m_s", "sr": "sr", "temperature": "temperature_k",
               "rq1": "rq1_m", "rq2": "rq2_m"}


def summarize(path, slowest: int = 5, failures: int = 5) -> dict[str, Any]:
    """What ``gearloss dataset info`` shows: counts by status, time spent, slowest points, failures, configuration
    (solver, lubricant, roughness profile: None where the file records none).

    Times: ``solver_time_s`` sums the solvers' own wall times of the recorded results, ``worker_time_s`` the
    worker-side times (retries included), ``session_wall_time_s`` the coordinator's wall time over the sessions that
    ended; ``open_sessions`` counts sessions without an end (still running, or killed).

    Parameters
    ----------
    path : str or Path
        The HDF5 dataset file [-].
    slowest : int
        How many of the slowest points to list [-].
    failures : int
        How many failures to list [-].

    Returns
    -------
    dict
        The summary.
    """
    with _reading(path) as store:
        meta = store.metadata()
        table = store.table(None)
    done = table[table["status"] != "pending"]
    ok = table[table["status"] == "ok"]
    top = ok.nlargest(max(int(slowest), 0), "wall_time")
    failed = table[table["status"] == "failed"].head(max(int(failures), 0))
    sessions = meta["sessions"]
    return {
        "path": meta["path"],
        "format_version": meta["format_version"],
        "package_version": meta["package_version"],
        "created": meta["created"],
        "git_revision": meta["git_revision"],
        "n_points": meta["n_points"],
        "counts": meta["counts"],
        "non_converged": int((~ok["converged"]).sum()),
        "max_attempts": int(table["attempts"].max()) if len(table) else 0,
        "solver_time_s": float(np.nansum(ok["wall_time"])),
        "median_solver_time_s": float(np.nanmedian(ok["wall_time"])) if len(ok) else math.nan,
        "worker_time_s": float(np.nansum(done["worker_time"])),
        "session_wall_time_s": float(sum(s.get("wall_time_s", 0.0) or 0.0 for s in sessions)),
        "n_sessions": len(sessions),
        "open_sessions": sum(1 for s in sessions if not s.get("ended")),
        "sessions": sessions,
        "slowest": [
            {"point": int(row.point), "wall_time_s": float(row.wall_time), "level": row.level,
             **{key: float(getattr(row, name)) for name, key in _INPUT_KEYS.items()}}
            for row in top.itertuples()
        ],
        "failures": [{"point": int(row.point), "error": row.error} for row in failed.itertuples()],
        "factorial": meta["factorial"],
        "solver": meta["solver"],
        "lubricant_name": meta["lubricant"].get("name", ""),
        "lubricant": meta["lubricant"],
        "roughness": meta["roughness"],
    }
