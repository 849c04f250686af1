"""One BLAS/OpenMP thread for a solve, at the cost of a context switch rather than a library scan.

``threadpoolctl.threadpool_limits`` scans the loaded shared libraries on every call (about 1 ms, 10 ms on a loaded
machine: as much as a warm smooth solve). :func:`one_blas_thread` keeps one ``ThreadpoolController`` per process,
created on first use, after numpy and scipy have loaded their BLAS, and made anew when modules were imported since
(an import can load another BLAS or OpenMP runtime, e.g. scikit-learn's or numba's, that an older scan does not
know of); in a worker that has solved its first case this no longer happens.
"""

from __future__ import annotations

import sys

from threadpoolctl import ThreadpoolController

_CONTROLLER: ThreadpoolController | None = None
_MODULES_AT_SCAN = 0

__all__ = ["one_blas_thread"]


def one_blas_thread():
    """Context manager limiting every thread pool known to this process (BLAS, OpenMP) to one thread.

    Returns
    -------
    contextlib.AbstractContextManager
        ``ThreadpoolController.limit(limits=1)`` of the process's controller; the previous limits are restored
        on exit.
    """
    global _CONTROLLER, _MODULES_AT_SCAN
    if _CONTROLLER is None or len(sys.modules) != _MODULES_AT_SCAN:
        import numpy  # noqa: F401  (the BLAS the solvers use is loaded before the scan)
        import scipy.linalg  # noqa: F401

        _CONTROLLER = ThreadpoolController()
        _MODULES_AT_SCAN = len(sys.modules)
    return _CONTROLLER.limit(limits=1)
