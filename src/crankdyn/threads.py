"""How many threads the linear algebra (BLAS/LAPACK) may use (boundary).

OpenBLAS and MKL start one thread per processor by default, whatever else the machine runs: on
a machine whose processors are busy, a threaded LAPACK call then waits for its slowest thread
and can take ten times longer than a single-threaded one (docs/benchmarks.md). The command line
therefore gives the linear algebra the processors this process may use
(``os.sched_getaffinity``) less the load already on them (the one-minute load average, rounded),
at least one: :func:`blas_threads`. Threads set by the user win: when ``CRANKDYN_THREADS`` is
set it is the number; when one of the libraries' own variables (``OPENBLAS_NUM_THREADS``,
``OMP_NUM_THREADS``, ``MKL_NUM_THREADS``) is set nothing is changed.

The libraries read their variables when they are loaded, so :func:`limit_blas_threads` sets them
for those not loaded yet, and limits those already loaded through threadpoolctl (a library made
for this: ``threadpoolctl.threadpool_limits``), so both numpy's and scipy's copies of OpenBLAS
follow, whichever is loaded first.
"""

from __future__ import annotations

import math
import os
import sys
from collections.abc import Mapping

from crankdyn.errors import InputError

__all__ = [
    "LIBRARY_VARIABLES",
    "VARIABLE",
    "available_cores",
    "blas_threads",
    "free_cores",
    "limit_blas_threads",
]

VARIABLE = "CRANKDYN_THREADS"
"""The environment variable that sets the number of linear-algebra threads (a whole number >= 1)."""

LIBRARY_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
"""The libraries' own variables: when one is set, crankdyn leaves the threads alone."""


def available_cores() -> int:
    """The processors this process may run on (its affinity; ``os.cpu_count()`` where the
    system has no affinity), at least 1.

    Returns
    -------
    int
        The number of processors.
    """
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):  # pragma: no cover - systems without affinity
        return max(1, os.cpu_count() or 1)


def blas_threads(cores: int | None = None, load: float | None = None) -> int:
    """The linear algebra's threads: the processors not already busy (module docstring).

    Parameters
    ----------
    cores : int or None
        The processors available (default :func:`available_cores`).
    load : float or None
        The runnable processes already on them (default the one-minute load average,
        ``os.getloadavg()[0]``; 0 where the system has none).

    Returns
    -------
    int
        max(1, min(cores, round(cores - load))).

    Examples
    --------
    >>> blas_threads(2, 0.1), blas_threads(2, 1.4), blas_threads(2, 9.0), blas_threads(8, 2.6)
    (2, 1, 1, 5)
    """
    n = available_cores() if cores is None else int(cores)
    if load is None:
        try:
            load = os.getloadavg()[0]
        except (AttributeError, OSError):  # pragma: no cover - systems without a load average
            load = 0.0
    free = math.floor(n - load + 0.5) if math.isfinite(load) else n
    return max(1, min(n, free))


def free_cores(cores: int | None = None, running: int | None = None) -> int:
    """The processors this process may use that are not busy now, for work run beside it in a
    child (:mod:`crankdyn.forks`; with fewer than two, a child would only take turns with this
    process): its cores less the tasks running now other than itself (``/proc/loadavg``'s
    fourth field, an instant count, not an average: a benchmark's or a script's previous run
    that has just ended leaves a load average of about one for a minute, but no running task),
    at least 1; where the system gives no such count, :func:`blas_threads`'s (load average).
    ``CRANKDYN_THREADS`` caps it (``CRANKDYN_THREADS=1``: one process, one thread).

    Parameters
    ----------
    cores : int or None
        The processors available (default :func:`available_cores`).
    running : int or None
        The tasks running now, this process included (default read from ``/proc/loadavg``).

    Returns
    -------
    int
        The free processors.

    Raises
    ------
    crankdyn.errors.InputError
        ``CRANKDYN_THREADS`` that is not a whole number >= 1.

    Examples
    --------
    >>> free_cores(2, 1), free_cores(2, 2), free_cores(2, 5), free_cores(8, 3)
    (2, 1, 1, 6)
    """
    n = available_cores() if cores is None else int(cores)
    cap = _requested(os.environ) or n
    if running is None:
        try:
            with open("/proc/loadavg", encoding="ascii") as handle:
                running = int(handle.read().split()[3].partition("/")[0])
        except (OSError, ValueError, IndexError):  # not Linux: the load average
            return min(cap, blas_threads(n))
    return max(1, min(n, cap, n - max(0, running - 1)))


def _requested(environ: Mapping[str, str]) -> int | None:
    """``CRANKDYN_THREADS`` as a number, None when unset; one line naming it when it is not
    a whole number >= 1."""
    text = environ.get(VARIABLE)
    if text is None or not text.strip():
        return None
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise InputError("expected a whole number of threads >= 1", key=VARIABLE, value=text)
    return value


def limit_blas_threads(threads: int | None = None) -> int | None:
    """Limit the linear algebra to ``threads`` (default ``CRANKDYN_THREADS``, else
    :func:`blas_threads`), unless one of :data:`LIBRARY_VARIABLES` is set (module docstring).

    Parameters
    ----------
    threads : int or None
        The number of threads (>= 1), default as said.

    Returns
    -------
    int or None
        The number set, or None when the user's variables were left alone.

    Raises
    ------
    crankdyn.errors.InputError
        ``CRANKDYN_THREADS`` that is not a whole number >= 1.
    """
    environ = os.environ
    if threads is None:
        threads = _requested(environ)
        if threads is None:
            if any(environ.get(v) for v in LIBRARY_VARIABLES):
                return None
            threads = blas_threads()
    for variable in LIBRARY_VARIABLES:  # the libraries loaded from now on
        environ[variable] = str(threads)
    if "numpy" in sys.modules or "scipy" in sys.modules:  # those already loaded
        from threadpoolctl import threadpool_limits

        threadpool_limits(limits=threads, user_api="blas")
    return threads
