"""How the C library's allocator keeps the memory the arrays free (boundary).

The numeric core allocates and frees arrays of a few to a few hundred megabytes per block of
speeds or samples (a 1000-mass line's responses, syntheses and time series). GNU libc's
``malloc`` serves a request above its *mmap threshold* with a fresh mapping and unmaps it when
freed, and gives the free memory at the top of its heap back to the system beyond its *trim
threshold* (the mmap threshold starts at 128 KiB and rises up to 32 MiB as such blocks are
freed, the trim threshold with it to twice that: glibc manual, "Memory Allocation Tunables";
``mallopt(3)``). Every fresh page costs a page fault and
is zeroed by the kernel on its first use: a 1000-mass TVC spent 22 s in the kernel against 84
s in its own code, most of it zeroing fresh pages (``perf``: ``clear_page_erms`` 12 % of the
samples), for arrays freed and allocated again a moment later.

:func:`keep_freed_memory`, called by the command line, therefore sets (``mallopt``) the mmap
threshold to 32 MiB (its largest value on a 64-bit system), the trim threshold to 2 GiB (the
largest ``mallopt`` takes) and the top pad (the extra memory asked for whenever the heap grows)
to 256 MiB: an array up to 32 MiB is then served from the heap, whose freed memory is used again
instead of returned. The peak of the resident memory stays what was in use at the peak; what
changes is that a process keeps its freed heap, up to 2 GiB, until it ends. Measured on the
1000-mass line of ``bench/`` (the same run, in turn): about 3 s less system time, 2-3 s of the
run's 50 s; the forked children (:mod:`crankdyn.forks`) inherit the settings.

Nothing is changed where the user has set the allocator's own variables (``MALLOC_*`` or
``GLIBC_TUNABLES``: theirs win) or where the C library is not glibc (musl, macOS, Windows).
"""

from __future__ import annotations

import ctypes
import os
from collections.abc import Mapping

__all__ = ["SETTINGS", "keep_freed_memory"]

_M_TRIM_THRESHOLD = -1  # mallopt's parameters (glibc's malloc.h)
_M_TOP_PAD = -2
_M_MMAP_THRESHOLD = -3

SETTINGS = {
    "mmap_threshold": 32 << 20,
    "trim_threshold": (2 << 30) - 1,
    "top_pad": 256 << 20,
}
"""The values :func:`keep_freed_memory` sets (bytes)."""


def _user_set(environ: Mapping[str, str]) -> bool:
    """Whether the user has set the allocator's variables themselves."""
    return "GLIBC_TUNABLES" in environ or any(key.startswith("MALLOC_") for key in environ)


def _glibc() -> bool:
    """Whether this process runs on GNU libc (its version string, as ``getconf
    GNU_LIBC_VERSION`` gives it: no reading of the executable, as ``platform.libc_ver`` does)."""
    try:
        return (os.confstr("CS_GNU_LIBC_VERSION") or "").startswith("glibc")
    except (AttributeError, ValueError, OSError):  # not a POSIX system, or no such name
        return False


def keep_freed_memory(environ: Mapping[str, str] | None = None) -> bool:
    """Have glibc's ``malloc`` keep the memory freed arrays leave (module docstring).

    Parameters
    ----------
    environ : mapping or None
        The environment to look for the user's own settings in (default ``os.environ``).

    Returns
    -------
    bool
        Whether the settings were made (False where the user set the allocator's variables,
        the C library is not glibc, or it refused).

    Examples
    --------
    The user's own setting wins:

    >>> keep_freed_memory({"MALLOC_ARENA_MAX": "2"})
    False
    """
    if _user_set(os.environ if environ is None else environ):
        return False
    if not _glibc():
        return False
    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):  # pragma: no cover - a glibc without mallopt
        return False
    mallopt.argtypes = (ctypes.c_int, ctypes.c_int)
    mallopt.restype = ctypes.c_int
    done = [
        mallopt(_M_MMAP_THRESHOLD, SETTINGS["mmap_threshold"]),
        mallopt(_M_TRIM_THRESHOLD, SETTINGS["trim_threshold"]),
        mallopt(_M_TOP_PAD, SETTINGS["top_pad"]),
    ]
    return all(done)
