"""A file that holds the state of a long deterministic run so that it can continue after the process is stopped
(a machine restart, a session's end): the IO side of ``solve_deterministic(..., checkpoint=...)``.

The solver decides what its state is and checks, on loading, that it was saved by the same run (same inputs,
options and model version); this module only writes it atomically and reads it back. The files are Python pickles
of the solver's arrays: read only files you wrote yourself.
"""

from __future__ import annotations

import os
import pickle
from pathlib import Path

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
    """

    def __init__(self, path: str | os.PathLike, every_s: float = DEFAULT_EVERY_S):
        self.path = Path(path)
        self.every_s = float(every_s)

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
            with self.path.open("rb") as handle:
                state = pickle.load(handle)
        except (OSError, EOFError, pickle.UnpicklingError, AttributeError, ImportError, ValueError) as error:
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
        FileCheckpoint(self.failure_path).save(state)
        return self.failure_path

    def remove(self) -> None:
        """Delete the saved state (once the run's result is recorded); a failure's state stays."""
        self.path.unlink(missing_ok=True)
