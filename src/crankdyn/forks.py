"""Work done beside this process, in a child forked from it (core): a figure drawn while the
report goes on (:mod:`crankdyn.plots.render`), the TVC's transient events run while its
conditions' forced responses are computed (:func:`crankdyn.tvc.analysis.tvc`).

A fork gives the child this process's state as it is (the model, the caches, the imported
libraries) at no cost of copying, and the child's result comes back pickled through a pipe, its
arrays' memory as out-of-band buffers read straight into the arrays the parent then holds
(pickle protocol 5, PEP 574: no second copy of a gigabyte of time series in each process). It
is safe only on Linux (macOS's system libraries are not safe to use after a fork) and outside a
daemonic process (which may not have children): :func:`can_fork`. SIGINT and SIGTERM are held
across the fork (:func:`hold_signals`): a signal handled in the child before it has set its own
actions (the command line's handlers raise) would unwind it into this process's stack, to run
on as a copy of it.

:class:`Beside` runs one function so. Where it cannot fork, where the child fails in any way
(an exception, a result that does not pickle, a signal) or where it is not wanted, the function
is run here when its result is asked for: the result, or the exception, is always the one this
process would have computed itself, since the child computes it from the same state with the
same code. While the child computes, this process and the child each hold the linear algebra
(BLAS) to one thread (threadpoolctl, set before the fork, so the child inherits it; this
process's own limits restored when the result is in): OpenBLAS's threads wait for each other by
spinning, and two processes each with a thread per core took turns on the cores, slower than
one process alone (measured on the marine TVC: 10.5 s against 7.8 s).
"""

from __future__ import annotations

import contextlib
import gc
import multiprocessing
import os
import pickle
import signal
import struct
import sys
from collections.abc import Callable
from typing import Any, Generic, TypeVar

try:
    import fcntl
except ImportError:  # not on Windows
    fcntl = None  # type: ignore[assignment]

__all__ = [
    "Beside",
    "can_fork",
    "child_setup",
    "fresh_streams",
    "hold_signals",
    "release_signals",
    "room_for_a_copy",
]

T = TypeVar("T")

_HELD = {signal.SIGINT, getattr(signal, "SIGTERM", signal.SIGINT)}


def can_fork() -> bool:
    """Whether forking a child is safe here (module docstring).

    Returns
    -------
    bool
        True on Linux outside a daemonic process.
    """
    return (
        sys.platform.startswith("linux")
        and "fork" in multiprocessing.get_all_start_methods()
        and not multiprocessing.current_process().daemon
    )


def room_for_a_copy() -> bool:
    """Whether the memory available now (``MemAvailable`` of /proc/meminfo) holds another
    process as large as this one (its ``VmRSS``): a child's own pages may grow to the parent's
    size (the TVC's events on a 1000-mass line: some 3 GB beside the parent's 3.7 GB), and a
    fork that made the machine swap would be slower than no fork. True where the system does
    not say.

    Returns
    -------
    bool
        Whether a copy fits.
    """
    try:
        with open("/proc/meminfo", encoding="ascii") as handle:
            available = next(
                int(line.split()[1]) for line in handle if line.startswith("MemAvailable:")
            )
        with open("/proc/self/status", encoding="ascii") as handle:
            resident = next(int(line.split()[1]) for line in handle if line.startswith("VmRSS:"))
    except (OSError, ValueError, IndexError, StopIteration):
        return True
    return available >= resident


def hold_signals() -> set[int | signal.Signals] | None:
    """Block SIGINT and SIGTERM in this thread (delivered when released).

    Returns
    -------
    set or None
        The signal mask before, or None where threads have no signal mask.
    """
    if not hasattr(signal, "pthread_sigmask"):  # pragma: no cover - not POSIX
        return None
    return signal.pthread_sigmask(signal.SIG_BLOCK, _HELD)


def release_signals(mask: set[int | signal.Signals] | None) -> None:
    """Restore the signal mask :func:`hold_signals` returned.

    Parameters
    ----------
    mask : set or None
        The mask before.
    """
    if mask is not None:
        signal.pthread_sigmask(signal.SIG_SETMASK, mask)


def fresh_streams() -> None:
    """In a child: its own standard output and error objects on the same files, so that a lock
    a thread of the parent (a progress display) held at the fork is not inherited held."""
    for name, fd in (("stdout", 1), ("stderr", 2)):
        with contextlib.suppress(OSError):
            stream = open(os.dup(fd), "w", encoding="utf-8", errors="replace")  # noqa: SIM115
            setattr(sys, name, stream)


def child_setup(mask: set[int | signal.Signals] | None, *, lasting: bool = False) -> None:
    """In a child just forked with the signals held: their default actions (a SIGTERM from the
    parent ends it), then released; its own streams; and the collector kept off the parent's
    objects, whose every page a collection would touch and so copy: off altogether for a child
    that lives for a moment (a figure), or, for one that computes for long (``lasting``), the
    parent's objects frozen out of its collections (:func:`gc.freeze`) and its own collected.

    Parameters
    ----------
    mask : set or None
        The mask :func:`hold_signals` returned before the fork.
    lasting : bool
        Whether the child computes for long.
    """
    with contextlib.suppress(ValueError):  # not the main thread
        signal.signal(signal.SIGINT, signal.SIG_DFL)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
    release_signals(mask)
    if lasting:
        gc.freeze()
    else:
        gc.disable()
    fresh_streams()


def widen_pipe(fd: int) -> None:
    """Give the pipe of ``fd`` a buffer of 1 MiB (Linux's limit for an unprivileged process,
    ``/proc/sys/fs/pipe-max-size``) instead of 64 KiB: a child's result of a gigabyte then
    passes in a sixteenth of the writes and wake-ups; left as it is where that is refused."""
    setsize = getattr(fcntl, "F_SETPIPE_SZ", None) if fcntl is not None else None
    if setsize is not None:
        with contextlib.suppress(OSError):
            fcntl.fcntl(fd, setsize, 1 << 20)


def _pickled(value: object) -> list[bytes | memoryview]:
    """The parts a child writes for ``value``: a header (the number of out-of-band buffers, the
    pickle's length, each buffer's length and whether it is read-only), the pickle (protocol
    5) and the buffers themselves, the arrays' memory as it is, not copied into the pickle
    (PEP 574; a TVC's events on a 1000-mass line: about 1 GB of time series, pickled in band
    then copied again out of the pickle in the parent)."""
    buffers: list[pickle.PickleBuffer] = []
    data = pickle.dumps(value, protocol=5, buffer_callback=buffers.append)
    views = [b.raw() for b in buffers]
    header = struct.pack(
        f"<{2 + 2 * len(views)}Q",
        len(views),
        len(data),
        *(x for v in views for x in (v.nbytes, int(v.readonly))),
    )
    return [header, data, *views]


def _read_exactly(pipe: Any, size: int) -> bytearray:
    """``size`` bytes from ``pipe`` into a new buffer (EOFError if the pipe ends first)."""
    out = bytearray(size)
    view = memoryview(out)
    done = 0
    while done < size:
        got = pipe.readinto(view[done:])
        if not got:
            raise EOFError("the child's result ended early")
        done += got
    return out


def _unpickled(pipe: Any) -> list[Any]:
    """[value] from the parts :func:`_pickled` wrote to ``pipe``; [] when the child wrote
    nothing (it failed). The buffers are read straight into the memory the arrays then use,
    read-only where they were."""
    head = pipe.read(8)
    if not head:
        return []
    (count,) = struct.unpack("<Q", head)
    length, *sizes = struct.unpack(f"<{1 + 2 * count}Q", _read_exactly(pipe, 8 * (1 + 2 * count)))
    data = _read_exactly(pipe, length)
    buffers = []
    for size, readonly in zip(sizes[0::2], sizes[1::2], strict=True):
        view = memoryview(_read_exactly(pipe, size))
        buffers.append(view.toreadonly() if readonly else view)
    return [pickle.loads(data, buffers=buffers)]


class Beside(Generic[T]):
    """``function()`` computed in a forked child while this process goes on (module docstring).

    Parameters
    ----------
    function : callable
        What to compute; its result must pickle to come back from the child (else it is
        computed here).
    fork : bool
        Whether to fork at all (the caller's judgement of the cores free); False computes it
        here, when :meth:`result` is called.

    Attributes
    ----------
    from_child : bool
        Whether the result came from the child (set by :meth:`result`).

    Examples
    --------
    >>> work = Beside(lambda: sum(range(10)))
    >>> work.result()
    45
    >>> Beside(lambda: 1 / 0, fork=False).result()
    Traceback (most recent call last):
    ...
    ZeroDivisionError: division by zero
    """

    def __init__(self, function: Callable[[], T], *, fork: bool = True) -> None:
        self._function = function
        self._pid: int | None = None
        self._read: int | None = None
        self._limits: Any = None
        self.from_child = False  # whether the result came from a child
        if fork and can_fork():
            from threadpoolctl import threadpool_limits

            self._limits = threadpool_limits(limits=1, user_api="blas")
            self._start()
            if self._pid is None:
                self._restore()

    def _restore(self) -> None:
        """This process's linear-algebra threads as they were before the fork."""
        if self._limits is not None:
            self._limits.restore_original_limits()
            self._limits = None

    @property
    def forked(self) -> bool:
        """Whether a child is computing it."""
        return self._pid is not None

    def _start(self) -> None:
        mask = hold_signals()
        try:
            read, write = os.pipe()
            widen_pipe(write)
            pid = os.fork()
        except OSError:  # no more processes: computed here
            release_signals(mask)
            return
        if pid == 0:  # the child: compute, write, exit without running this process's exits
            code = 1
            try:
                child_setup(mask, lasting=True)
                os.close(read)
                try:
                    parts = _pickled(self._function())
                except BaseException:  # any failure: the parent computes it
                    parts = []
                with os.fdopen(write, "wb") as out:
                    for part in parts:
                        out.write(part)
                code = 0
            finally:
                os._exit(code)
        release_signals(mask)
        os.close(write)
        self._pid, self._read = pid, read

    def result(self) -> T:
        """The function's result: the child's, or computed here (module docstring).

        Returns
        -------
        object
            What ``function()`` returns.
        """
        if self._read is not None:
            found: list[Any] = []
            with os.fdopen(self._read, "rb") as pipe:
                self._read = None
                with contextlib.suppress(Exception):
                    found = _unpickled(pipe)
            self._wait()
            self._restore()
            if found:
                self.from_child = True
                value: T = found[0]
                return value
        return self._function()

    def _wait(self) -> None:
        if self._pid is not None:
            with contextlib.suppress(OSError):
                os.waitpid(self._pid, 0)
            self._pid = None

    def close(self) -> None:
        """Stop the child if it is still computing (the result is no longer wanted)."""
        if self._pid is not None:
            with contextlib.suppress(OSError):
                os.kill(self._pid, signal.SIGTERM)
        if self._read is not None:
            with contextlib.suppress(OSError):
                os.close(self._read)
            self._read = None
        self._wait()
        self._restore()

    def __enter__(self) -> Beside[T]:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
