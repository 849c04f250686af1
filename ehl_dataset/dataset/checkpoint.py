"""A file that holds the state of a long deterministic run so that it can continue after the process is stopped
(a machine restart, a session's end): the IO side of ``solve_deterministic(..., checkpoint=...)``.

The solver decides what its state is and checks, on loading, that it was saved by the same run (same inputs,
options and model version); this module only writes it atomically and reads it back. Two file forms:

* the default, a Python pickle of the whole state (the run continues step for step as if never stopped): read only
  files you wrote yourself;
* ``portable=True``, a compressed NumPy ``.npz`` archive of plain data (arrays, numbers, strings; loaded with
  ``allow_pickle=False``, so it executes no code), without the solver's factorised preconditioner, which the run
  rebuilds on its next step. Small enough to commit beside a long run's results so that the run survives a change of
  machine; the continued run differs from an uninterrupted one only at the level of the linear solver's tolerance.
"""

from __future__ import annotations

import os
import pickle
import zipfile
from pathlib import Path

import numpy as np

from ..validation import InputError

DEFAULT_EVERY_S = 600.0
"""Wall time [s] between two saves of a run's state (a save of a 1,000-node run with 10⁵ recorded steps takes
well under a second)."""


class FileCheckpoint:
    """The saved state of one run in the file ``path``, written every ``every_s`` seconds of wall time.

    Protocol used by :func:`ehl_dataset.solvers.deterministic.solve_deterministic`: ``every_s``, ``load()`` (the saved
    state, or None when there is none) and ``save(state)``; optionally ``save_failure(state)`` (the state before a step
    that failed, returning where it is kept).

    Parameters
    ----------
    path : str or Path
        The checkpoint file [-].
    every_s : float
        Wall time between saves [s].
    portable : bool
        Write the plain-data ``.npz`` form (no pickle, no preconditioner) instead of a pickle; either form is read
        back whatever this flag says [-].
    """

    def __init__(self, path: str | os.PathLike, every_s: float = DEFAULT_EVERY_S, portable: bool = False):
        self.path = Path(path)
        self.every_s = float(every_s)
        self.portable = bool(portable)

    def load(self) -> dict | None:
        """The saved state.

        Returns
        -------
        dict or None
            The state, or None when there is none.
        """
        if not self.path.exists():
            return None
        try:
            if zipfile.is_zipfile(self.path):
                with np.load(self.path, allow_pickle=False) as archive:
                    state = unflatten_state({name: archive[name] for name in archive.files})
            else:
                with self.path.open("rb") as handle:
                    state = pickle.load(handle)
        except (OSError, EOFError, pickle.UnpicklingError, AttributeError, ImportError, ValueError, KeyError,
                zipfile.BadZipFile) as error:
            raise InputError("checkpoint", str(self.path), "a run state written by FileCheckpoint; this file could "
                             f"not be read ({type(error).__name__}: {error}); delete it to start the run afresh")
        if not isinstance(state, dict):
            raise InputError("checkpoint", str(self.path), "a run state written by FileCheckpoint (a dict); delete "
                             "it to start the run afresh")
        return state

    def save(self, state: dict) -> None:
        """Write ``state`` to a temporary file next to ``path`` and move it into place.

        A stop mid-write leaves the previous state intact.

        Parameters
        ----------
        state : dict
            The solver's state [-].
        """
        self.path.parent.mkdir(parents=True, exist_ok=True)
        partial = self.path.with_name(self.path.name + ".partial")
        with partial.open("wb") as handle:
            if self.portable:
                np.savez_compressed(handle, **flatten_state(state))
            else:
                pickle.dump(state, handle, protocol=pickle.HIGHEST_PROTOCOL)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(partial, self.path)

    @property
    def failure_path(self) -> Path:
        """Where a run that failed keeps its state before the failing step (``<path>.failed``)."""
        return self.path.with_name(self.path.name + ".failed")

    def save_failure(self, state: dict) -> Path:
        """Keep the state before a step the solver could not pass in :attr:`failure_path`, which :meth:`remove` leaves.

        ``FileCheckpoint(checkpoint.failure_path)`` handed to the same run replays that step.

        Parameters
        ----------
        state : dict
            The solver's state before the failed step [-].

        Returns
        -------
        Path
            Where it is kept.
        """
        FileCheckpoint(self.failure_path, portable=self.portable).save(state)
        return self.failure_path

    def remove(self) -> None:
        """Delete the saved state (once the run's result is recorded); a failure's state stays."""
        self.path.unlink(missing_ok=True)


_SEPARATOR = "/"
_NONE = "__none__"
_KINDS = {bool: "b", int: "i", float: "f", str: "s"}


def flatten_state(state: dict, prefix: str = "") -> dict[str, np.ndarray]:
    """A nested dict of plain data as flat ``.npz`` entries: ``"a/b"`` for ``state["a"]["b"]``.

    Arrays keep their dtype; a number or string becomes a 0-d array under ``"<key>:<kind>"`` (kind b, i, f, s, so
    that it comes back as the same Python type); None is listed in the ``__none__`` entry.

    Parameters
    ----------
    state : dict
        Nested dict with string keys of arrays, numbers, strings, None and dicts [-].
    prefix : str
        Key prefix of this level [-].

    Returns
    -------
    dict of str to ndarray
        The entries [-].

    Raises
    ------
    TypeError
        A value of another type (named by its key), or a key that contains ``/`` or ``:``.
    """
    entries: dict[str, np.ndarray] = {}
    nones: list[str] = []
    for key, value in state.items():
        if not isinstance(key, str) or _SEPARATOR in key or ":" in key:
            raise TypeError(f"checkpoint state key {prefix}{key!r}: a string without '/' or ':'")
        name = prefix + key
        if value is None:
            nones.append(name)
        elif isinstance(value, dict):
            inner = flatten_state(value, name + _SEPARATOR)
            nones.extend(inner.pop(_NONE, np.array([], dtype=str)).tolist())
            if not inner and not value:
                entries[name + ":d"] = np.array(0)
            entries.update(inner)
        elif isinstance(value, np.ndarray):
            if value.dtype == object:
                raise TypeError(f"checkpoint state {name}: an array of objects cannot be stored without pickle")
            entries[name] = value
        elif type(value) in _KINDS or isinstance(value, (np.floating, np.integer, np.bool_)):
            kind = _KINDS.get(type(value)) or {"f": "f", "i": "i", "u": "i", "b": "b"}[np.asarray(value).dtype.kind]
            entries[f"{name}:{kind}"] = np.asarray(value)
        else:
            raise TypeError(f"checkpoint state {name}: {type(value).__name__} is not plain data (arrays, numbers, "
                            "strings, None, dicts)")
    if nones:
        entries[_NONE] = np.array(nones, dtype=str)
    return entries


def unflatten_state(entries: dict[str, np.ndarray]) -> dict:
    """The nested dict :func:`flatten_state` stored.

    Parameters
    ----------
    entries : dict of str to ndarray
        The ``.npz`` entries [-].

    Returns
    -------
    dict
        The state [-].
    """
    state: dict = {}

    def place(name: str, value) -> None:
        *parents, leaf = name.split(_SEPARATOR)
        level = state
        for parent in parents:
            level = level.setdefault(parent, {})
        level[leaf] = value

    for name, array in entries.items():
        if name == _NONE:
            for missing in array.tolist():
                place(missing, None)
        elif ":" in name:
            name, kind = name.rsplit(":", 1)
            convert = {"b": bool, "i": int, "f": float, "s": str, "d": lambda _: {}}[kind]
            place(name, convert(array.item()))
        else:
            place(name, np.array(array))
    return state
