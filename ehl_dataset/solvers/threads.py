"""One BLAS/OpenMP thread for a solve, at the cost of a context switch rather than a library scan.

``threadpoolctl.threadpool_limits`` scans the loaded shared libraries on every call (about 1 ms, 10 ms on a loaded
machine: as much as a warm smooth solve). :func:`one_blas_thread` keeps one ``ThreadpoolController`` per process,
created on first use, after numpy and scipy have loaded their BLAS.
"""

from __future__ import annotations

from threadpoolctl import ThreadpoolController

_CONTROLLER: ThreadpoolController | None = None

__all__ = ["one_blas_thread"]


def one_blas_thread():
    """Context manager limiting every thread pool known to this process (BLAS, OpenMP) to one thread.

    Returns
    -------
    contextlib.AbstractContextManager
        ``ThreadpoolController.limit(limits=1)`` of the process's controller; the previous limits are restored
        on exit.
    """
    global _CONTROLLER
    if _CONTROLLER is None:
        import numpy  # noqa: F401  (the BLAS the solvers use is loaded before the scan)
        import scipy.linalg  # noqa: F401

        _CONTROLLER = ThreadpoolController()
    return _CONTROLLER.limit(limits=1)
