"""Run a factorial of EHL contacts into a :mod:`ehl_dataset.dataset.store` file: local processes or Dask, resumable.

One coordinating process owns the HDF5 file; workers only compute (:func:`compute_point`, a top-level picklable
function) and send back ``ContactResult.to_record()``. The coordinator keeps a bounded window of tasks in flight,
writes results as they arrive and flushes every ``flush_interval_s`` seconds.

Failures
    * The solver raises inside a worker -> the point is recorded ``failed`` with the exception text; the run goes on.
      Solver errors are deterministic, so they are not retried.
    * The solver returns ``converged=False`` -> ``ok`` with ``converged`` False and the solver's message in
      ``error`` (the surrogate stage filters on ``converged``); ``converged=True`` with a NaN output -> ``failed``.
    * The task itself fails (a worker process died, a Dask ``KilledWorker``, a result that cannot be sent back)
      -> retried up to ``max_attempts`` computations, then ``failed``. When a local worker dies, every task in
      flight fails with it; those points are then re-run one at a time, so only the point that really kills its
      worker is charged an attempt.
    * SIGINT (Ctrl-C) or SIGTERM -> no new tasks; results already received are written, the workers are stopped,
      the session is closed in the file; :class:`RunSummary` says ``interrupted``. A second Ctrl-C aborts at once.
      SIGKILL loses at most the last ``flush_interval_s`` seconds of results; the file stays readable.
    * ``time_limit_s`` (a wall-time budget per point, passed to the solver) runs out -> the solver returns
      ``converged=False`` with "wall-time limit of T s reached after k of n time steps ...", so the point is
      recorded like any non-converged result: ``ok``, not converged, the message in ``error``.
Resuming computes every row that is not ``ok`` (pending and failed). Non-converged rows are ``ok`` and are not
recomputed unless the resume asks for it with ``retry_not_converged=True`` (``gearloss dataset resume
--retry-not-converged``): then they are computed again too — e.g. a first pass with a short budget per point and a
second pass with a long one for the points it stopped. ``time_limit_s`` is an execution option like ``workers``: it is recorded
in the session entry of the file, not in the solver configuration that a resume must match.
"""

from __future__ import annotations

import dataclasses
import hashlib
import importlib
import inspect
import json
import math
import os
import signal
import socket
import sys
import threading
import time
import traceback
import warnings
from collections import Counter, deque
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Callable, TextIO

import numpy as np

from ..model.contact import ContactCase
from ..model.lubricant import CELSIUS_ZERO_K, Lubricant, load_lubricant, lubricant_from_dict
from ..solvers.deterministic import MODEL_VERSION as DETERMINISTIC_MODEL_VERSION
from ..solvers.wide_contact import WIDE_MODEL_VERSION
from ..solvers.levels import get_level
from ..solvers.planner import plan_effects
from ..solvers.steady import neighbour_warm_starts
from ..solvers.threads import one_blas_thread
from ..validation import InputError, check_time_limit as check_positive_seconds
from .executors import make_executor
from .factorial import EFFECTS_MODES, Factorial, canonical_json, load_factorial
from .roughness_choice import RoughnessChoice, choice_from_record, recorded_option, resolve_choice
from .store import FAILED, OK, SOLVER_DEFAULTS, DatasetStore, package_version

DEFAULT_SOLVER = "ehl_dataset.solver:solve_contact"
DEFAULT_MODEL = SOLVER_DEFAULTS["model"]
"""The contact model of a file that records none (files written before the model entered the configuration)."""
_FLOAT_CHECKED = ("mu", "mu_std", "h_min", "h_central", "asperity_load_share", "p_max")


# ---------------------------------------------------------------------------------------------------------------
# Worker side
# ---------------------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class PointTask:
    """Everything a worker needs for one point (picklable): row ``index``, SI ``point`` (p_h, r_eq, u_r, sr,
    temperature, rq1, rq2), the lubricant as JSON, level, effects, the solver (``"module:function"`` or a
    top-level function), the wall-time budget of the solve ``time_limit_s`` [s] (None: no limit; passed to the
    solver only when set, so solvers without that keyword work without a budget) and the contact ``model`` (a name
    of :data:`ehl_dataset.solver.MODELS`; passed to every solver that accepts a ``model`` keyword, and a solver
    without it is accepted only for ``"auto"``, :func:`check_model`); ``warm_start``: steady solves may start from
    the worker's kept solution of a neighbouring point (:func:`ehl_dataset.solvers.steady.neighbour_warm_starts`);
    ``roughness``: the run's roughness profile (:class:`~ehl_dataset.dataset.roughness_choice.RoughnessChoice`: name,
    sha256 and, for a user's file, its path; resolved and hash-checked once per worker process, passed to the solver
    as ``roughness`` unless it is the default profile; None: the solver's default)."""

    index: int
    point: tuple[float, ...]
    lubricant_json: str
    level: str
    effects: str
    solver: str | Callable = DEFAULT_SOLVER
    time_limit_s: float | None = None
    model: str = DEFAULT_MODEL
    warm_start: bool = False
    roughness: RoughnessChoice | None = None


_SOLVER_CACHE: dict[str, Callable] = {}
_LUBRICANT_CACHE: dict[str, Any] = {}


def solver_reference(solver: str | Callable) -> str:
    """``"module:qualname"`` of a solve function (how it is recorded in the file)."""
    if isinstance(solver, str):
        return solver
    return f"{solver.__module__}:{solver.__qualname__}"


def resolve_solver(solver: str | Callable) -> Callable:
    """The solve function of ``"module:function"`` (imported once per process) or the callable itself."""
    if callable(solver):
        return solver
    if solver not in _SOLVER_CACHE:
        module_name, _, qualname = solver.partition(":")
        if not module_name or not qualname:
            raise InputError("solver", solver, "MODULE:FUNCTION, e.g. ehl_dataset.solver:solve_contact")
        try:
            target: Any = importlib.import_module(module_name)
            for part in qualname.split("."):
                target = getattr(target, part)
        except (ImportError, AttributeError) as err:
            raise InputError("solver", solver, "an importable MODULE:FUNCTION", str(err)) from None
        _SOLVER_CACHE[solver] = target
    return _SOLVER_CACHE[solver]


def _lubricant(lubricant_json: str):
    lubricant = _LUBRICANT_CACHE.get(lubricant_json)
    if lubricant is None:
        lubricant = lubricant_from_dict(json.loads(lubricant_json), origin="dataset file")
        if len(_LUBRICANT_CACHE) > 8:
            _LUBRICANT_CACHE.clear()
        _LUBRICANT_CACHE[lubricant_json] = lubricant
    return lubricant


def describe_exception(err: BaseException) -> str:
    """``Type: message (at file:line in function)`` — one line, with where it was raised."""
    frames = traceback.extract_tb(err.__traceback__)
    where = f" (at {os.path.basename(frames[-1].filename)}:{frames[-1].lineno} in {frames[-1].name})" if frames else ""
    message = " ".join(str(err).split())
    return f"{type(err).__name__}: {message}{where}"


def judge_record(record: dict, message: str = "") -> tuple[int, str]:
    """Status and error text of a solver record: non-converged -> ok + message; converged with NaN -> failed."""
    if not record.get("converged", False):
        text = message.strip()
        return OK, text if text.startswith("not converged") else f"not converged: {text}".strip()
    bad = [name for name in _FLOAT_CHECKED if not math.isfinite(float(record.get(name, math.nan)))]
    if math.isnan(float(record.get("lambda_bar", math.nan))):
        bad.append("lambda_bar")
    if bad:
        values = ", ".join(f"{name}={record.get(name)!r}" for name in bad)
        return FAILED, f"solver reported converged=True with non-finite outputs: {values}"
    return OK, ""


def _one_blas_thread():
    """One BLAS/OpenMP thread during a solve (one core per case, docs/how-to/run-a-dataset.md, "Workers"). Without it
    every worker's LAPACK would start one thread per core (oversubscription), and a point's last bits would depend
    on where it ran (threaded reductions), so a resumed or distributed run could differ from an uninterrupted local
    one."""
    return one_blas_thread()


def summarize_warnings(counts: Counter) -> str:
    """``LinAlgWarning x12 (newton.py:237); RuntimeWarning x2 (newton.py:106)`` — most frequent first."""
    return "; ".join(f"{name} x{n} ({filename}:{lineno})" for (name, filename, lineno), n in counts.most_common())


def compute_point(task: PointTask) -> dict[str, Any]:
    """Solve one point (runs in a worker). Never raises for a solver error: the error is returned as text.

    Python warnings raised during the solve are counted (by category and location) and returned as one line
    instead of being printed: a 42,000-point run would otherwise flood the log with them.
    """
    start = time.perf_counter()
    record = None
    budget = {} if task.time_limit_s is None else {"time_limit_s": task.time_limit_s}
    caught: Counter = Counter()
    try:
        solve = resolve_solver(task.solver)
        if task.model != DEFAULT_MODEL or accepts_keyword(solve, "model"):
            budget["model"] = task.model
        profile = resolve_choice(task.roughness)
        if profile is not None:
            budget["roughness"] = profile
        case = ContactCase(*task.point)
        with warnings.catch_warnings(), _one_blas_thread():
            warnings.simplefilter("always")
            warnings.showwarning = lambda message, category, filename, lineno, *rest: caught.update(
                [(category.__name__, os.path.basename(filename), lineno)])
            with neighbour_warm_starts(task.warm_start):
                result = solve(case, _lubricant(task.lubricant_json), level=task.level, effects=task.effects,
                               **budget)
        record = result.to_record()
        status, error = judge_record(record, getattr(result, "message", ""))
    except Exception as err:  # noqa: BLE001 - any solver failure is recorded, the run goes on
        status, error = FAILED, describe_exception(err)
    return {
        "index": task.index,
        "status": status,
        "record": record,
        "error": error,
        "warnings": summarize_warnings(caught),
        "worker_time": time.perf_counter() - start,
        "worker": f"{socket.gethostname()}:{os.getpid()}",
    }


# ---------------------------------------------------------------------------------------------------------------
# Configuration
# ---------------------------------------------------------------------------------------------------------------
def solver_config(solver: str | Callable, level: str, effects: str, model: str = DEFAULT_MODEL,
                  roughness: RoughnessChoice | None = None) -> dict[str, Any]:
    """What identifies the computation of a point: function, its version, level (and its definition), effects and
    contact model (:func:`check_model`); with the deterministic model also its model version, so that a file is
    never resumed under other deterministic numerics. With a user's roughness file (``roughness``) also the length
    unit its columns were read in (``roughness_unit``): the file's record (name and sha256) does not hold it. The
    profile itself is recorded beside the configuration (:func:`dataset_roughness`).

    The version is the function's ``solver_version`` attribute, else its module's ``SOLVER_VERSION`` or
    ``__version__``, else ``gearloss <package version>``. The level definition comes from
    ``ehl_dataset.solvers.levels.get_level`` when that module exists (an unknown level name is rejected there).
    """
    if effects not in EFFECTS_MODES:
        raise InputError("effects", effects, f"one of {list(EFFECTS_MODES)}")
    fn = resolve_solver(solver)
    module = sys.modules.get(getattr(fn, "__module__", ""), None)
    version = (getattr(fn, "solver_version", None) or getattr(module, "SOLVER_VERSION", None)
               or getattr(module, "__version__", None) or f"gearloss {package_version()}")
    config = {
        "function": solver_reference(solver),
        "version": str(version),
        "level": level,
        "level_definition": _level_definition(level),
        "effects": effects,
        "model": check_model(model, solver),
    }
    if config["model"] == "deterministic" or level == "reference":
        # its numerics are versioned on their own (docs/explanation/mixed-regime.md); the reference level's planner sends
        # every rough contact to it
        config["model_version"] = DETERMINISTIC_MODEL_VERSION
        config["wide_model_version"] = WIDE_MODEL_VERSION
    check_roughness(roughness, solver)
    if roughness is not None and not roughness.registered:
        config["roughness_unit"] = roughness.unit
    return config


def dataset_roughness(solver: str | Callable, roughness: RoughnessChoice | None = None) -> dict[str, str] | None:
    """The roughness profile the rough points of a run use, as the file records it (``{"name", "sha256"}``,
    :func:`ehl_dataset.model.roughness_identity.roughness_identity`): the profile chosen for the run
    (``roughness``, :func:`ehl_dataset.dataset.roughness_choice.choose_roughness`), else the default profile that
    the package's solver takes (:data:`ehl_dataset.model.roughness.DEFAULT_PROFILE`); for another solve function
    with no profile chosen (or the default one) the runner does not know its profile and records none (None)."""
    if roughness is not None and (not roughness.is_default or solver_reference(solver) == DEFAULT_SOLVER):
        return roughness.record
    if solver_reference(solver) != DEFAULT_SOLVER:
        return None
    from ..model.roughness_identity import roughness_identity

    return roughness_identity()


def check_roughness(roughness: RoughnessChoice | None, solver: str | Callable | None = None) -> None:
    """Refuse (``InputError``, at the start instead of at every point) a roughness profile other than the default
    for a solve function without a ``roughness`` keyword (or ``**kwargs``), and anything but a
    :class:`~ehl_dataset.dataset.roughness_choice.RoughnessChoice` or None."""
    if roughness is None:
        return
    if not isinstance(roughness, RoughnessChoice):
        raise InputError("roughness", type(roughness).__name__, "a RoughnessChoice (choose_roughness) or None")
    if not roughness.is_default and solver is not None and not accepts_keyword(resolve_solver(solver), "roughness"):
        raise InputError("roughness", roughness.name, "the default profile for a solver without a roughness "
                         "parameter", f"{solver_reference(solver)} does not accept it")


def check_recorded_roughness(store: DatasetStore, solver: str | Callable,
                             roughness: RoughnessChoice | None) -> None:
    """Refuse (``InputError``) to compute into ``store`` on another roughness profile than the one it records,
    naming both profiles and the option that chooses the recorded one. A file that records none (written before
    the record, or by a solve function whose profile the runner does not know) is continued as before, but not on
    a chosen profile other than the default."""
    from ..model.roughness_identity import describe_roughness

    recorded, chosen = store.roughness, dataset_roughness(solver, roughness)
    if recorded is None and roughness is not None and not roughness.is_default:
        raise InputError("roughness_file" if not roughness.registered else "roughness", roughness.name,
                         f"no profile option for {store.path}, which records no roughness profile (its rows were "
                         "solved on the solver's default)", "start a new file (another --out, or --overwrite) for "
                         "another profile")
    if recorded is None or chosen is None or recorded == chosen:
        return
    raise InputError("roughness_file" if roughness is not None and not roughness.registered else "roughness",
                     describe_roughness(chosen), f"the roughness profile recorded in {store.path} "
                     f"({describe_roughness(recorded)})", f"continue it with {recorded_option(recorded)}, or start "
                     "a new file (another --out, or --overwrite) for another profile")


def recorded_model(recorded_solver: dict) -> str:
    """The contact model a file's solver configuration records; files written before the model was recorded ran
    the default (``"auto"``)."""
    return str(recorded_solver.get("model", DEFAULT_MODEL))


def check_model(model, solver: str | Callable | None = None) -> str:
    """``model`` if it is one of :data:`ehl_dataset.solver.MODELS` (read there, so a model added to the solver is
    accepted here without a change); with a ``solver`` that has no ``model`` keyword only ``"auto"`` is accepted
    (the run is refused at the start instead of failing every point)."""
    from ..solver import MODELS

    if model not in MODELS:
        raise InputError("model", model, f"one of {list(MODELS)} (ehl_dataset.solver.MODELS)")
    if model != DEFAULT_MODEL and solver is not None and not accepts_keyword(resolve_solver(solver), "model"):
        raise InputError("model", model, f"'{DEFAULT_MODEL}' for a solver without a model parameter",
                         f"{solver_reference(solver)} does not accept it")
    return model


def accepts_keyword(function: Callable, name: str) -> bool:
    """Whether ``function`` takes the keyword ``name`` (or ``**kwargs``); True when it has no inspectable
    signature (let the call decide)."""
    try:
        parameters = inspect.signature(function).parameters.values()
    except (TypeError, ValueError):
        return True
    return any(p.name == name or p.kind is p.VAR_KEYWORD for p in parameters)


def _level_definition(level: str):
    definition = get_level(level)
    if dataclasses.is_dataclass(definition):
        definition = dataclasses.asdict(definition)
    return json.loads(json.dumps(definition, default=str))


def _points_sha256(points: np.ndarray) -> str:
    return hashlib.sha256(np.ascontiguousarray(points).tobytes()).hexdigest()


# ---------------------------------------------------------------------------------------------------------------
# Progress
# ---------------------------------------------------------------------------------------------------------------
class CostModel:
    """Predicted computing time of the points still to do, from the measured cost of the points done.

    A point's cost is predicted by the mean measured cost of the done points that share its roughness pair, r_eq and
    p_h (the drivers of a solve's cost: smooth or rough, and the Hertz half width ∝ p_h·r_eq that sets the grid);
    failing that, of those sharing the roughness pair and r_eq, then the roughness pair, then all done points. The
    time to go is the predicted cost of the remaining points divided by the parallel speed-up measured in this
    session (computing seconds finished per wall second), or by ``workers`` before the session has finished a point.
    """

    KEYS = ((6, 5, 1, 0), (6, 5, 1), (6, 5), ())
    """Column groups of a point (indices into p_h, r_eq, u_r, sr, T, rq1, rq2), finest first."""

    def __init__(self, points: np.ndarray, workers: int = 1):
        table = np.column_stack([np.asarray(points[name], dtype=float) for name in points.dtype.names]) \
            if points.dtype.names else np.asarray(points, dtype=float)
        self.table = table
        self.workers = max(int(workers), 1)
        self.sums: list[dict] = [dict() for _ in self.KEYS]
        self.remaining: set[int] = set()
        self.session_cost = 0.0

    def _key(self, level: int, index: int) -> tuple:
        return tuple(self.table[index, c] for c in self.KEYS[level])

    def observe(self, index: int, cost: float, in_session: bool = True) -> None:
        if not math.isfinite(cost) or cost < 0:
            return
        for level in range(len(self.KEYS)):
            total, n = self.sums[level].get(self._key(level, index), (0.0, 0))
            self.sums[level][self._key(level, index)] = (total + cost, n + 1)
        if in_session:
            self.session_cost += cost
        self.remaining.discard(index)

    def predict(self, index: int) -> float:
        for level in range(len(self.KEYS)):
            total, n = self.sums[level].get(self._key(level, index), (0.0, 0))
            if n:
                return total / n
        return math.nan

    def seconds_to_go(self, elapsed: float) -> float:
        """Wall seconds until the remaining points are done (inf before any cost is known)."""
        if not self.remaining:
            return 0.0
        cost = sum(self.predict(i) for i in self.remaining)
        if not math.isfinite(cost):
            return math.inf
        speed_up = self.session_cost / elapsed if (elapsed > 0 and self.session_cost > 0) else self.workers
        return cost / max(speed_up, 1e-9)


class Progress:
    """A tqdm bar on a terminal, or a log line every ``log_every_s`` seconds; ``mode="none"`` silent.

    Counts are of the whole file: a resumed run starts at the ``initial`` points already done (``60/324``, not
    ``0/264``). The time to go comes from ``cost`` (:class:`CostModel`: the measured cost of the points done,
    earlier sessions included), not from the rate of the first points, which differ in cost from the rest.
    """

    def __init__(self, total: int, name: str, mode: str = "auto", stream: TextIO | None = None,
                 log_every_s: float = 30.0, initial: int = 0, cost: CostModel | None = None):
        self.stream = stream if stream is not None else sys.stderr
        if mode == "auto":
            mode = "bar" if getattr(self.stream, "isatty", lambda: False)() else "log"
        if mode not in ("bar", "log", "none"):
            raise InputError("progress", mode, "'auto', 'bar', 'log' or 'none'")
        self.mode, self.total, self.name, self.log_every_s = mode, total, name, log_every_s
        self.initial = initial
        self.cost = cost
        self.done = self.ok = self.failed = self.non_converged = 0
        self.start = self._last_log = time.monotonic()
        self._bar = None
        if mode == "bar":
            from tqdm import tqdm

            self._bar = tqdm(total=total, initial=initial, unit="pt", desc=name, file=self.stream,
                             dynamic_ncols=True, bar_format="{desc}: {percentage:3.0f}%|{bar}| {n_fmt}/{total_fmt} "
                                                            "[{elapsed}, {rate_fmt}, {postfix}]")
            self._bar.set_postfix_str(self._postfix(), refresh=False)

    def eta_s(self) -> float:
        elapsed = time.monotonic() - self.start
        if self.cost is not None:
            return self.cost.seconds_to_go(elapsed)
        rate = self.done / elapsed if elapsed > 0 else 0.0
        return (self.total - self.initial - self.done) / rate if rate > 0 else math.inf

    def _postfix(self) -> str:
        return f"ok {self.ok}, failed {self.failed}, ETA {_hms(self.eta_s())}"

    def advance(self, status: int, converged: bool = True) -> None:
        self.done += 1
        self.ok += status == OK
        self.failed += status == FAILED
        self.non_converged += status == OK and not converged
        if self._bar is not None:
            self._bar.set_postfix_str(self._postfix(), refresh=False)
            self._bar.update(1)
        elif self.mode == "log" and time.monotonic() - self._last_log >= self.log_every_s:
            self.log()

    def log(self, prefix: str = "") -> None:
        if self.mode != "log":
            return
        self._last_log = now = time.monotonic()
        elapsed = now - self.start
        rate = self.done / elapsed if elapsed > 0 else 0.0
        print(f"{time.strftime('%Y-%m-%dT%H:%M:%S')} {prefix}{self.name}: {self.initial + self.done}/{self.total} "
              f"points (this run: ok {self.ok}, failed {self.failed}, not converged {self.non_converged}), "
              f"{rate:.3g} points/s, elapsed {_hms(elapsed)}, ETA {_hms(self.eta_s())}", file=self.stream,
              flush=True)

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
        else:
            self.log("done " if self.initial + self.done == self.total else "stopped ")


def _hms(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "?"
    seconds = int(round(seconds))
    return f"{seconds // 3600}h{seconds % 3600 // 60:02d}m{seconds % 60:02d}s"


# ---------------------------------------------------------------------------------------------------------------
# Signals: a flag, checked by the loop, so that an interrupt never lands inside a write
# ---------------------------------------------------------------------------------------------------------------
class _StopFlag:
    def __init__(self):
        self.signal_name: str | None = None
        self._previous: dict[int, Any] = {}

    def __enter__(self):
        if threading.current_thread() is threading.main_thread():
            for signum in (signal.SIGINT, signal.SIGTERM):
                self._previous[signum] = signal.signal(signum, self._handle)
        return self

    def _handle(self, signum, frame):
        if self.signal_name is not None and signum == signal.SIGINT:
            raise KeyboardInterrupt  # second Ctrl-C: abort now
        self.signal_name = signal.Signals(signum).name

    def __exit__(self, *exc):
        for signum, handler in self._previous.items():
            signal.signal(signum, handler)


# ---------------------------------------------------------------------------------------------------------------
# The run
# ---------------------------------------------------------------------------------------------------------------
@dataclass
class RunSummary:
    """Outcome of one run or resume session.

    Parameters
    ----------
    path : str
        The dataset file [-].
    n_points : int
        Points of the factorial [-].
    computed : int
        Points computed in this run [-].
    ok : int
        Rows with status ok [-].
    failed : int
        Rows with status failed [-].
    pending : int
        Rows still pending [-].
    non_converged : int
        Rows stored ok whose solve did not converge [-].
    wall_time_s : float
        Wall time of the session [s].
    points_per_s : float
        Throughput of the session [1/s].
    store_time_s : float
        Time spent writing the file [s].
    interrupted : str or None
        Name of the signal that stopped the session early, or ``exception``; None when it finished [-].
    executor : dict
        Where it ran: workers, scheduler [-].
    """

    path: str
    n_points: int
    computed: int
    ok: int
    failed: int
    pending: int
    non_converged: int
    wall_time_s: float
    points_per_s: float
    store_time_s: float
    interrupted: str | None
    executor: dict

    def to_dict(self) -> dict[str, Any]:
        """The summary as a JSON-serialisable dict.

        Returns
        -------
        dict
            The fields.
        """
        out = dataclasses.asdict(self)
        out["store_time_per_point_s"] = self.store_time_s / self.computed if self.computed else 0.0
        return out


def run_factorial(out, factorial: Factorial | str | os.PathLike, *, lubricant=None, level: str | None = None,
                  effects: str | None = None, workers: int = 1, scheduler: str | None = None,
                  solver: str | Callable = DEFAULT_SOLVER, overwrite: bool = False, time_limit_s: float | None = None,
                  model: str | None = None, roughness: RoughnessChoice | None = None, **options) -> RunSummary:
    """Compute ``factorial`` into the HDF5 file ``out``.

    If ``out`` exists and records the same factorial, solver (model included), lubricant and roughness profile
    (:func:`dataset_roughness`), the run continues it (like :func:`resume_run`); if it records something else the
    call is refused unless ``overwrite``. A new file records the roughness profile.

    Parameters
    ----------
    out : str or Path
        The HDF5 dataset file [-].
    factorial : Factorial or str or Path
        The factorial: an object, a shipped name or a TOML path [-].
    lubricant : str or Path or Lubricant, optional
        Lubricant; None: the factorial's [-].
    level : str, optional
        Accuracy level; None: the factorial's [-].
    effects : str, optional
        Effect plan; None: the factorial's [-].
    workers : int
        Worker processes [-].
    scheduler : str, optional
        Address of a Dask scheduler; None: local processes [-].
    solver : str or callable
        The solve function or its ``"module:function"`` reference [-].
    overwrite : bool
        Replace a file that records another run [-].
    time_limit_s : float, optional
        Wall-time budget of each point's solve (None: none); an execution option that does not enter the solver
        configuration [s].
    model : str, optional
        Contact model (:data:`ehl_dataset.solver.MODELS`), recorded in the solver configuration and passed to the
        solver; None: the factorial's [-].
    roughness : RoughnessChoice, optional
        The roughness profile of the rough points (:func:`ehl_dataset.dataset.roughness_choice.choose_roughness`),
        recorded in the file and resolved once by every worker; None: the solver's default profile [-].
    **options
        Execution options: ``window``, ``max_attempts``, ``flush_interval_s``, ``flush_rows``, ``progress``,
        ``warm_up``, ``stream``, ``log_every_s`` [-].

    Returns
    -------
    RunSummary
        Counts, times and how the session ended.

    Raises
    ------
    InputError
        For bad input or a file that records another run.
    """
    _check_options(workers, options)
    time_limit_s = check_time_limit(time_limit_s, solver)
    plan = factorial if isinstance(factorial, Factorial) else load_factorial(factorial)
    lub = lubricant if isinstance(lubricant, Lubricant) else load_lubricant(lubricant or plan.lubricant)
    check_lubricant_covers(plan, lub)
    config = solver_config(solver, level or plan.level, effects or plan.effects, model or plan.model, roughness)
    lubricant_dict = json.loads(canonical_json(lub.to_json_dict()))
    factorial_dict = plan.to_dict()
    record = dataset_roughness(solver, roughness)
    out = Path(out)
    if out.exists() and not overwrite:
        store = DatasetStore.open(out, "r+")
        kind = "continue"
        try:
            check_recorded_roughness(store, solver, roughness)
            store.check_compatible(factorial_sha256=factorial_dict["points_sha256"], solver=config,
                                   lubricant=lubricant_dict, roughness=record)
        except BaseException:
            store.close()
            raise
    else:
        store = DatasetStore.create(out, plan.points(), factorial=factorial_dict, solver=config,
                                    lubricant=lubricant_dict, overwrite=overwrite, roughness=record)
        kind = "run"
    with store:
        return execute(store, solver=solver, workers=workers, scheduler=scheduler, kind=kind,
                       time_limit_s=time_limit_s, roughness=roughness, **options)


def check_lubricant_covers(plan: Factorial, lub: Lubricant) -> None:
    """Refuse (``InputError``, before anything is computed) a factorial with a temperature level outside the
    lubricant's data range: every point at that temperature would fail."""
    low, high = lub.t_min - CELSIUS_ZERO_K, lub.t_max - CELSIUS_ZERO_K
    for t_c in plan.temp_c:
        if not low <= t_c <= high:
            raise InputError("temp_c", t_c, f"[{low:g}, {high:g}] °C, the data range of lubricant {lub.name!r}",
                             f"a temperature level of factorial {plan.name!r}; extend the lubricant's "
                             "[temperature_range] only with property data that cover it")


def resume_run(path, *, workers: int = 1, scheduler: str | None = None, solver: str | Callable | None = None,
               factorial=None, lubricant=None, level: str | None = None, effects: str | None = None,
               model: str | None = None, time_limit_s: float | None = None, retry_not_converged: bool = False,
               roughness: RoughnessChoice | None = None, **options) -> RunSummary:
    """Continue the run recorded in ``path``: compute every row that is not ``ok``.

    The solver, level, effects, contact model and lubricant are those recorded in the file (a file that records no
    model ran ``"auto"``). The solver's current version (and level definition) must equal the recorded ones; the
    arguments below that name the configuration must match the file too, otherwise the resume is refused with
    ``InputError``. The roughness profile is the one the file records (a registered profile by its name, checked
    against its sha256) unless ``roughness`` is given, which must then match the record; a file that records a
    user's profile file needs ``roughness`` (its path is not recorded), and a file that records none runs the
    solver's default profile. A changed default profile is not mixed into a file. Rows stored not converged,
    including those stopped by an earlier budget, are ``ok`` and are not recomputed unless ``retry_not_converged``.

    Parameters
    ----------
    path : str or Path
        The HDF5 dataset file [-].
    workers : int
        Worker processes [-].
    scheduler : str, optional
        Address of a Dask scheduler; None: local processes [-].
    solver : str or callable, optional
        Must match the recorded solve function [-].
    factorial : Factorial or str, optional
        Must match the recorded factorial [-].
    lubricant : str or Lubricant, optional
        Must match the recorded lubricant [-].
    level : str, optional
        Must match the recorded level [-].
    effects : str, optional
        Must match the recorded effect plan [-].
    model : str, optional
        Must match the recorded contact model [-].
    time_limit_s : float, optional
        Wall-time budget per point, for the rows computed now; it may differ from earlier sessions' budgets [s].
    retry_not_converged : bool
        Also recompute the ``ok`` rows whose solve did not converge [-].
    roughness : RoughnessChoice, optional
        Must match the recorded roughness profile; None: the recorded one
        (:func:`ehl_dataset.dataset.roughness_choice.choice_from_record`) [-].
    **options
        Execution options, as for :func:`run_factorial` [-].

    Returns
    -------
    RunSummary
        Counts, times and how the session ended.
    """
    _check_options(workers, options)
    time_limit_s = check_time_limit(time_limit_s)  # the solver's keyword is checked by execute()
    with DatasetStore.open(path, "r+") as store:
        recorded = store.solver
        solver_used = solver if solver is not None else recorded.get("function", DEFAULT_SOLVER)
        if roughness is None:
            roughness = choice_from_record(store.roughness, where=str(store.path))
        config = solver_config(solver_used, level or recorded.get("level"), effects or recorded.get("effects"),
                               model or recorded_model(recorded), roughness)
        lubricant_dict = None
        if lubricant is not None:
            lub = lubricant if isinstance(lubricant, Lubricant) else load_lubricant(lubricant)
            lubricant_dict = json.loads(canonical_json(lub.to_json_dict()))
        factorial_hash = None
        if factorial is not None:
            plan = factorial if isinstance(factorial, Factorial) else load_factorial(factorial)
            factorial_hash = plan.points_hash()
        check_recorded_roughness(store, solver_used, roughness)
        store.check_compatible(factorial_sha256=factorial_hash, solver=config, lubricant=lubricant_dict,
                               roughness=dataset_roughness(solver_used, roughness))
        return execute(store, solver=solver_used, workers=workers, scheduler=scheduler, kind="resume",
                       time_limit_s=time_limit_s, retry_not_converged=retry_not_converged, roughness=roughness,
                       **options)


def warm_up_indices(points: np.ndarray, candidates: list[int], lubricant: dict, level: str, effects: str,
                    solver, roughness: RoughnessChoice | None = None) -> list[int]:
    """Points the coordinator computes before the workers start, so each compiled code path is built once.

    For the default solver with ``effects="auto"`` or ``"isothermal"``: for each distinct plan (roughness, transient, shear thinning)
    the planner makes among ``candidates``, the candidate with the narrowest contact (smallest p_h·r_eq, to which
    the Hertz half width and so the transient grid are proportional: the coordinator should not spend minutes on
    a wide rough contact while the workers wait); otherwise just the first candidate. The plans are made with the
    correlation length of the run's roughness profile (``roughness``; None: the default profile's).
    """
    if not candidates:
        return []
    if solver_reference(solver) != DEFAULT_SOLVER or effects not in ("auto", "isothermal"):
        return candidates[:1]
    lub = _lubricant(canonical_json(lubricant))
    profile = resolve_choice(roughness)
    beta = None if profile is None else profile.correlation_length
    chosen: dict[tuple, int] = {}
    for index in candidates:
        try:
            plan = plan_effects(ContactCase(*(float(v) for v in points[index])), lub, level, beta)
        except Exception:  # noqa: BLE001 - the point will report its own error when computed
            continue
        key = (plan.roughness, plan.transient, plan.shear_thinning)
        if key not in chosen or _width(points[index]) < _width(points[chosen[key]]):
            chosen[key] = index
    return sorted(chosen.values()) or candidates[:1]


def _width(point) -> float:
    """p_h·r_eq of a factorial point (columns as :class:`~ehl_dataset.model.contact.ContactCase`): ∝ the Hertz half width."""
    return float(point[0]) * float(point[1])


def check_time_limit(time_limit_s, solver: str | Callable | None = None) -> float | None:
    """``time_limit_s`` as a float, or None; ``InputError`` unless it is None or a finite number of seconds > 0
    (:func:`ehl_dataset.validation.check_time_limit`, the check of ``solve_contact`` too).

    With a ``solver`` and a budget, the solve function must accept the keyword ``time_limit_s`` (or ``**kwargs``):
    otherwise every point would fail on a ``TypeError``, so the run is refused at the start instead.
    """
    time_limit_s = check_positive_seconds(time_limit_s)
    if time_limit_s is not None and solver is not None:
        if not accepts_keyword(resolve_solver(solver), "time_limit_s"):
            raise InputError("time_limit_s", time_limit_s, "None for a solver without a time_limit_s parameter",
                             f"{solver_reference(solver)} does not accept it")
    return time_limit_s


def _check_options(workers: int, options: dict) -> None:
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 0:
        raise InputError("workers", workers, "an integer >= 0 (0: compute in this process)")
    attempts = options.get("max_attempts", 1)
    if not isinstance(attempts, int) or attempts < 1:
        raise InputError("max_attempts", attempts, "an integer >= 1")
    window = options.get("window")
    if window is not None and (not isinstance(window, int) or window < 1):
        raise InputError("window", window, "an integer >= 1")
    if options.get("progress", "auto") not in ("auto", "bar", "log", "none"):
        raise InputError("progress", options["progress"], "'auto', 'bar', 'log' or 'none'")
    if not isinstance(options.get("warm_start", False), bool):
        raise InputError("warm_start", options["warm_start"], "True or False")
    interval = options.get("flush_interval_s", 5.0)
    if not (isinstance(interval, (int, float)) and math.isfinite(interval) and interval >= 0):
        raise InputError("flush_interval_s", interval, "a finite number of seconds >= 0")


def execute(store: DatasetStore, *, solver: str | Callable = DEFAULT_SOLVER, workers: int = 1,
            scheduler: str | None = None, kind: str = "run", window: int | None = None, max_attempts: int = 3,
            flush_interval_s: float = 5.0, flush_rows: int = 2000, progress: str = "auto",
            warm_up: bool = True, stream: TextIO | None = None, log_every_s: float = 30.0,
            time_limit_s: float | None = None, retry_not_converged: bool = False,
            warm_start: bool = False, roughness: RoughnessChoice | None = None) -> RunSummary:
    """Compute every row of an open (writable) store that is not ``ok``, with the configuration it records
    (``retry_not_converged``: also the ``ok`` rows whose solve did not converge; their earlier result is
    overwritten by the new one, and their ``attempts`` count goes on).

    ``workers``: local processes (0: in this process); ``scheduler``: a Dask scheduler address or
    ``"dask-local"`` (then ``workers`` sizes the LocalCluster). ``window``: tasks in flight (default 4 per worker).
    ``max_attempts``: computations of a point whose *task* fails (worker death) before it is recorded failed.
    ``warm_up``: with local execution, compute in this process, before the workers start, one pending point of
    each distinct effect plan (:func:`warm_up_indices`), so numba-compiled code is in the cache (and, with fork,
    in memory) for every worker.
    ``time_limit_s``: wall-time budget of each point's solve [s] (None: none), handed to the solver in every
    :class:`PointTask`. A point that spends it is stored ``ok``, not converged, with the solver's "wall-time limit"
    message; later resumes recompute it only with ``retry_not_converged``. The budget is an
    execution option: it is recorded in this run's entry of the ``sessions`` attribute, not in the solver
    configuration, so runs with different budgets (or none) continue each other.
    ``warm_start``: the steady solves of a worker start from its kept solution of a neighbouring point where there is
    one (the points go out in the factorial's order, so a worker's previous points differ from the next in the fast
    axes: temperature, slide-to-roll ratio; :func:`ehl_dataset.solvers.steady.neighbour_warm_starts`); the results
    agree with cold starts within the level's Newton tolerances, but their last digits then depend on which points a
    worker solved before. An execution option, recorded in the session entry like ``time_limit_s``.
    ``roughness``: the roughness profile of the rough points
    (:class:`~ehl_dataset.dataset.roughness_choice.RoughnessChoice`; None: the solver's default); it must be the
    profile the store records (:func:`check_recorded_roughness`), and every task carries it.
    """
    _check_options(workers, {"max_attempts": max_attempts, "window": window, "progress": progress,
                             "flush_interval_s": flush_interval_s, "warm_start": warm_start})
    time_limit_s = check_time_limit(time_limit_s, solver)
    check_roughness(roughness, solver)
    check_recorded_roughness(store, solver, roughness)
    recorded = store.solver
    points = store.points()
    if _points_sha256(points) != store.metadata()["factorial_sha256"]:
        raise InputError("dataset file", str(store.path), "input columns matching the recorded factorial hash",
                         "the input columns were modified or are corrupt")
    lubricant_json = canonical_json(store.lubricant)
    level, effects, model = recorded["level"], recorded["effects"], check_model(recorded_model(recorded), solver)

    def task(index: int) -> PointTask:
        return PointTask(int(index), tuple(float(v) for v in points[index]), lubricant_json, level, effects, solver,
                         time_limit_s, model, warm_start, roughness)

    if not isinstance(retry_not_converged, bool):
        raise InputError("retry_not_converged", retry_not_converged, "True or False")
    status = store.status()
    todo = status != OK
    if retry_not_converged:
        todo |= (status == OK) & ~store.column("converged").astype(bool)
    pending = deque(int(i) for i in np.flatnonzero(todo))
    suspects: deque[int] = deque()
    failures: dict[int, int] = {}
    in_flight: dict[Any, int] = {}
    name = f"{store.factorial.get('name', 'dataset')}"
    cost = CostModel(points, workers)
    worker_time = store.column("worker_time")
    for index in np.flatnonzero(~todo):
        cost.observe(int(index), float(worker_time[index]), in_session=False)
    cost.remaining = set(pending)
    if kind != "run" and progress != "none" and len(pending) < store.n_points:
        print(f"resuming {store.path}: {store.n_points - len(pending)} of {store.n_points} points done, "
              f"{len(pending)} to compute", file=stream if stream is not None else sys.stderr, flush=True)
    reporter = Progress(store.n_points, name, progress, stream, log_every_s, initial=store.n_points - len(pending),
                        cost=cost)
    computed = 0
    store_time = 0.0
    started = time.perf_counter()
    executor = None
    session = store.begin_session(kind=kind, workers=workers, scheduler=scheduler or "",
                                  solver=solver_reference(solver), time_limit_s=time_limit_s,
                                  retry_not_converged=retry_not_converged, warm_start=warm_start)
    last_flush = time.monotonic()

    def record(result: dict, extra_attempts: int = 0) -> None:
        nonlocal computed, store_time
        t0 = time.perf_counter()
        store.record(result["index"], status=result["status"], record=result["record"], error=result["error"],
                     attempts=1 + extra_attempts, worker_time=result["worker_time"], worker=result["worker"],
                     warnings=result.get("warnings", ""))
        store_time += time.perf_counter() - t0
        computed += 1
        converged = bool(result["record"] and result["record"].get("converged"))
        cost.observe(int(result["index"]), float(result["worker_time"]))
        reporter.advance(result["status"], converged)

    def task_failed(index: int, err: BaseException, retry_alone: bool) -> None:
        nonlocal computed
        failures[index] = failures.get(index, 0) + 1
        if failures[index] >= max_attempts:
            store.record(index, status=FAILED, error=f"task failed {failures[index]} times, last: "
                         f"{describe_exception(err)}", attempts=failures[index], worker="")
            computed += 1
            cost.remaining.discard(index)
            reporter.advance(FAILED)
        elif retry_alone:
            suspects.append(index)
        else:
            pending.appendleft(index)

    crash = ""
    with _StopFlag() as stop:
        try:
            if warm_up and pending and not scheduler and workers > 0:
                for index in warm_up_indices(points, list(pending)[:500], store.lubricant, level, effects,
                                             solver, roughness):
                    pending.remove(index)
                    record(compute_point(task(index)))
                    if stop.signal_name is not None:
                        break
            if pending and stop.signal_name is None:
                executor = make_executor(workers, scheduler)
            window = window or 4 * (executor.n_workers if executor else 1)
            while (pending or suspects or in_flight) and stop.signal_name is None:
                if suspects:
                    if not in_flight:
                        index = suspects.popleft()
                        in_flight[executor.submit(compute_point, task(index))] = index
                else:
                    while pending and len(in_flight) < window:
                        index = pending.popleft()
                        in_flight[executor.submit(compute_point, task(index))] = index
                done, _ = executor.wait_first(list(in_flight), timeout=0.5)
                broken: list[int] = []
                for future in done:
                    index = in_flight.pop(future)
                    err = future.exception()
                    if err is None:
                        record(future.result(), failures.get(index, 0))
                    elif isinstance(err, BrokenProcessPool):
                        broken.append(index)
                    else:
                        task_failed(index, err, retry_alone=False)
                if broken:
                    for future, index in list(in_flight.items()):
                        if future.done() and future.exception() is None:
                            record(future.result(), failures.get(index, 0))
                        else:
                            broken.append(index)
                    in_flight.clear()
                    if len(broken) == 1:
                        task_failed(broken[0], BrokenProcessPool("the worker process died while computing this "
                                                                 "point"), retry_alone=True)
                    else:
                        suspects.extend(sorted(broken))
                    executor.restart()
                now = time.monotonic()
                if store.buffered and (now - last_flush >= flush_interval_s or store.buffered >= flush_rows):
                    t0 = time.perf_counter()
                    store.flush()
                    store_time += time.perf_counter() - t0
                    last_flush = now
            # Stopped by a signal: keep whatever already arrived.
            for future, index in list(in_flight.items()):
                if future.done() and future.exception() is None:
                    record(future.result(), failures.get(index, 0))
        except BaseException as err:
            crash = describe_exception(err)
            raise
        finally:
            if executor is not None:
                executor.shutdown(cancel=True)
            t0 = time.perf_counter()
            store.flush()
            store_time += time.perf_counter() - t0
            wall = time.perf_counter() - started
            store.end_session(session, computed=computed, wall_time_s=round(wall, 3),
                              interrupted=stop.signal_name or ("exception" if crash else None), error=crash,
                              **(executor.describe() if executor else {}))
            reporter.close()
    counts = store.counts()
    status = store.status()
    converged = store.column("converged")
    return RunSummary(
        path=str(store.path), n_points=store.n_points, computed=computed, ok=counts["ok"], failed=counts["failed"],
        pending=counts["pending"], non_converged=int(np.count_nonzero((status == OK) & ~converged)),
        wall_time_s=wall, points_per_s=computed / wall if wall > 0 else 0.0, store_time_s=store_time,
        interrupted=stop.signal_name, executor=executor.describe() if executor else {"executor": "parent"},
    )
