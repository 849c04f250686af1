"""Execution back-ends of the factorial runner, all behind one small ``submit`` / ``wait_first`` interface.

* :class:`SerialExecutor` — in the coordinating process (``workers=0``): debugging and profiling.
* :class:`LocalExecutor` — ``concurrent.futures.ProcessPoolExecutor`` on this machine (the default). On Linux the
  workers are forked, so code the parent compiled (numba) before the pool starts is inherited; workers ignore
  SIGINT so that Ctrl-C is handled once, by the coordinator.
* :class:`DaskExecutor` — a ``distributed.Client`` connected to a scheduler address (a cluster started by hand,
  ``dask-jobqueue`` on SLURM/PBS, or ``"dask-local"`` for a ``LocalCluster`` on this machine).

The runner calls only ``submit(fn, *args) -> future``, ``wait_first(futures, timeout) -> (done, not_done)``,
``restart()`` (after the pool broke) and ``shutdown(cancel=True)``; futures offer ``result()`` / ``exception()``.
"""

from __future__ import annotations

import concurrent.futures as cf
import multiprocessing
import os
import signal
import sys
from typing import Any, Callable, Iterable


def _init_local_worker(parent_pid: int) -> None:
    """Worker start-up: ignore Ctrl-C (the coordinator handles it) and die with the coordinator.

    A forked worker inherits the coordinator's open HDF5 file descriptor, and with it the file lock; were it to
    outlive a coordinator killed with SIGKILL, the file could not be resumed. On Linux ``PR_SET_PDEATHSIG`` has the
    kernel send SIGKILL to the worker when its parent dies.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    # A forked worker inherits the coordinator's Python SIGTERM handler (which only sets a stop flag); restore
    # the default so that stopping the pool terminates a long solve at once.
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if sys.platform.startswith("linux"):
        try:
            import ctypes

            libc = ctypes.CDLL(None, use_errno=True)
            pr_set_pdeathsig = 1
            libc.prctl(pr_set_pdeathsig, signal.SIGKILL, 0, 0, 0)
        except (OSError, AttributeError):  # pragma: no cover - no prctl: fall back to nothing
            pass
    if os.getppid() != parent_pid:  # the parent died before prctl took effect
        os._exit(1)


class SerialExecutor:
    """Runs each task at submission time in this process; futures are already done when returned."""

    name = "serial"
    n_workers = 1
    breaks_on_worker_death = False

    def submit(self, fn: Callable, *args: Any) -> cf.Future:
        future: cf.Future = cf.Future()
        try:
            future.set_result(fn(*args))
        except Exception as err:  # noqa: BLE001 - delivered through the future like a pool would
            future.set_exception(err)
        return future

    def wait_first(self, futures: Iterable, timeout: float):
        futures = set(futures)
        return futures, set()

    def restart(self) -> None:  # pragma: no cover - nothing to restart
        pass

    def shutdown(self, cancel: bool = True) -> None:
        pass

    def describe(self) -> dict:
        return {"executor": self.name, "workers": 1}


class LocalExecutor:
    """A process pool of ``workers`` processes on this machine."""

    name = "local"
    breaks_on_worker_death = True

    def __init__(self, workers: int):
        if workers < 1:
            raise ValueError("workers must be >= 1")
        self.n_workers = int(workers)
        methods = multiprocessing.get_all_start_methods()
        self._context = multiprocessing.get_context("fork" if "fork" in methods and sys.platform != "darwin"
                                                    else "spawn")
        self._pool = self._new_pool()

    def _new_pool(self) -> cf.ProcessPoolExecutor:
        return cf.ProcessPoolExecutor(max_workers=self.n_workers, mp_context=self._context,
                                      initializer=_init_local_worker, initargs=(os.getpid(),))

    def submit(self, fn: Callable, *args: Any):
        return self._pool.submit(fn, *args)

    def wait_first(self, futures: Iterable, timeout: float):
        return cf.wait(set(futures), timeout=timeout, return_when=cf.FIRST_COMPLETED)

    def restart(self) -> None:
        """Replace a broken pool (a worker process died) by a fresh one."""
        self.shutdown(cancel=True)
        self._pool = self._new_pool()

    def shutdown(self, cancel: bool = True) -> None:
        pool = self._pool
        if pool is None:
            return
        process_objects = list((getattr(pool, "_processes", None) or {}).values())
        pool.shutdown(wait=not cancel, cancel_futures=cancel)
        if cancel:
            # Running tasks cannot be cancelled through the pool API: stop their processes so that an interrupted
            # run ends now (their points stay pending in the store and are computed on resume).
            for process in process_objects:
                if process.is_alive():
                    process.terminate()
            for process in process_objects:
                process.join(timeout=5)
                if process.is_alive():
                    process.kill()
                    process.join(timeout=5)
        self._pool = None

    def describe(self) -> dict:
        return {"executor": self.name, "workers": self.n_workers, "start_method": self._context.get_start_method()}


class DaskExecutor:
    """Tasks on a Dask distributed cluster: ``address`` of a running scheduler, or ``"dask-local"``.

    ``"dask-local"`` starts a ``distributed.LocalCluster`` with ``workers`` single-threaded worker processes
    (used by tests and for trying the distributed path on one machine).
    """

    name = "dask"
    breaks_on_worker_death = False

    def __init__(self, address: str, workers: int = 2):
        try:
            import distributed
        except ImportError as err:  # pragma: no cover - optional dependency
            from ..validation import InputError

            raise InputError("scheduler", address, "an address usable with the optional 'distributed' package",
                             "install gearloss[distributed]") from err
        self._distributed = distributed
        self._cluster = None
        if address == "dask-local":
            self._cluster = distributed.LocalCluster(n_workers=max(int(workers), 1), threads_per_worker=1,
                                                     processes=True, dashboard_address=None)
            self.client = distributed.Client(self._cluster)
        else:
            try:
                self.client = distributed.Client(address, timeout="20s")
            except (OSError, TimeoutError) as err:
                from ..validation import InputError

                raise InputError("scheduler", address, "the address of a running Dask scheduler "
                                 "(e.g. tcp://host:8786) or 'dask-local'", str(err)) from None
        self.address = address
        self.n_workers = max(sum(self.client.nthreads().values()), 1)

    def submit(self, fn: Callable, *args: Any):
        return self.client.submit(fn, *args, pure=False)

    def wait_first(self, futures: Iterable, timeout: float):
        futures = list(futures)
        try:
            result = self._distributed.wait(futures, timeout=timeout, return_when="FIRST_COMPLETED")
        except TimeoutError:
            return set(), set(futures)
        return set(result.done), set(result.not_done)

    def restart(self) -> None:  # pragma: no cover - the scheduler reschedules tasks of dead workers itself
        pass

    def shutdown(self, cancel: bool = True) -> None:
        try:
            self.client.close()
        finally:
            if self._cluster is not None:
                self._cluster.close()

    def describe(self) -> dict:
        return {"executor": self.name, "scheduler": self.address, "workers": self.n_workers}


def make_executor(workers: int = 1, scheduler: str | None = None):
    """The executor for ``--workers N`` (0: in-process) and ``--scheduler ADDRESS``."""
    if scheduler:
        return DaskExecutor(scheduler, workers=workers)
    if workers == 0:
        return SerialExecutor()
    return LocalExecutor(workers)
