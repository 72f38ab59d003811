"""Writing outputs safely: checked before the work, atomic, never over what was not checked.

Every output goes through this module:

- :func:`check_writable` (a file) and :func:`check_output_dir` (a folder) check a target before
  the work starts: an existing target needs ``force``; a folder where a file is expected (and the
  reverse), a dangling symbolic link, a device or FIFO, a missing or unwritable parent folder are
  refused with one line. Commands call them first, so a mistake costs no computing time.
- :func:`write_bytes` / :func:`write_text` write a file to a temporary sibling (created with the
  user's umask, like any file the user makes) and move it into place; :func:`atomic_file` does
  the same for an output written a piece at a time (a large model's modes, streamed);
  :func:`atomic_directory` builds a folder of outputs (a report) in a temporary sibling folder
  the same way.
- The move never replaces what was not checked: without ``force`` it is a *no-replace* rename
  (:func:`rename_noreplace`: Linux ``renameat2(RENAME_NOREPLACE)``; elsewhere ``link`` + ``unlink``
  for a file and, for a folder, ``mkdir`` of the target as a lock followed by a rename that
  fails on a non-empty folder). When the target appeared while the work ran (another run, a
  user's folder), it is left as it is and the finished output is kept under the next free
  sibling name (``rep.2``, ``forces.2.json``), said on stderr. With ``force`` the old target is
  replaced only at the very end (an atomic exchange where Linux offers it).
- ``force`` never deletes what crankdyn did not write: every folder :func:`atomic_directory`
  makes holds crankdyn's marker file (:data:`MARKER`), and an existing folder is replaced only
  when it holds that marker (or nothing) and is not a symbolic link; anything else is refused in
  one line naming the folder and what it holds, before the work and again at the replacement.
- The moves and the removal of a temporary output run with SIGINT and SIGTERM held
  (:func:`deferred_signals`): an interrupt there is delivered once the step is done, so an
  output is either complete in place or absent, and no temporary file or folder is left.
- An operating-system error while writing (no space, permission, read-only file system, a
  folder removed meanwhile) becomes a one-line :class:`~crankdyn.errors.InputError` naming the
  target: the file, or the folder being built (a write into it that names no file, such as a
  full disk under ``Path.write_bytes``, is a write of that folder).
"""

from __future__ import annotations

import contextlib
import errno
import functools
import os
import shutil
import signal
import stat
import sys
import threading
from collections.abc import Iterator
from pathlib import Path
from types import TracebackType
from typing import IO, Literal

from crankdyn.errors import InputError

__all__ = [
    "MARKER",
    "AtomicFile",
    "atomic_directory",
    "atomic_file",
    "check_output_dir",
    "check_writable",
    "deferred_signals",
    "os_error_message",
    "rename_noreplace",
    "write_bytes",
    "write_text",
]

_MAX_SIBLINGS = 1000

MARKER = ".crankdyn-output"
"""The marker file in every output folder crankdyn writes (:func:`atomic_directory`): ``--force``
replaces an existing folder only when it holds this file (or nothing at all)."""
_MARKER_TEXT = (
    "This folder was written by crankdyn {version}. crankdyn replaces an existing output folder\n"
    "(--force) only when it holds this file; remove the file to keep crankdyn from replacing it.\n"
)
_LISTED = 3  # entries named in the message about a folder crankdyn did not write
_COUNTED = 1000  # entries counted at most


# ---- signals -------------------------------------------------------------------------------------

_HELD = tuple(getattr(signal, name) for name in ("SIGINT", "SIGTERM") if hasattr(signal, name))


@contextlib.contextmanager
def deferred_signals() -> Iterator[None]:
    """Hold SIGINT and SIGTERM while a short critical step runs (a move into place, the removal
    of a temporary output); a signal that arrives meanwhile is delivered when the step is done.

    Signals the process ignores stay ignored; outside the main thread (where Python cannot set
    handlers) the step runs unprotected.

    Yields
    ------
    None
        Control to the critical step, inside a ``with`` block.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    received: list[int] = []
    previous = {}
    for sig in _HELD:
        old = signal.getsignal(sig)
        if old in (signal.SIG_IGN, None):
            continue
        previous[sig] = old
        signal.signal(sig, lambda signum, _frame: received.append(signum))
    try:
        yield
    finally:
        for sig, old in previous.items():
            signal.signal(sig, old)
        for sig in dict.fromkeys(received):
            old = previous[sig]
            if callable(old):
                old(sig, None)  # e.g. raises KeyboardInterrupt
            else:  # SIG_DFL: let the default action happen now
                os.kill(os.getpid(), sig)


# ---- no-replace rename ---------------------------------------------------------------------------

_AT_FDCWD = -100
_RENAME_NOREPLACE = 1
_RENAME_EXCHANGE = 2


@functools.cache
def _renameat2():
    """libc's renameat2 (Linux, glibc 2.28 or later), or None."""
    if not sys.platform.startswith("linux"):
        return None
    import ctypes

    try:
        function = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):  # no such function in this libc
        return None
    path, fd = ctypes.c_char_p, ctypes.c_int
    function.argtypes = [fd, path, fd, path, ctypes.c_uint]
    function.restype = ctypes.c_int
    return function


_UNSUPPORTED = {errno.ENOSYS, errno.EINVAL, getattr(errno, "ENOTSUP", errno.EINVAL)}


def _rename2(src: Path, dst: Path, flags: int) -> bool:
    """renameat2 with ``flags``; False where the system or file system cannot do it."""
    function = _renameat2()
    if function is None:
        return False
    if function(_AT_FDCWD, os.fsencode(src), _AT_FDCWD, os.fsencode(dst), flags) == 0:
        return True
    import ctypes

    code = ctypes.get_errno()
    if code in _UNSUPPORTED:
        return False
    raise OSError(code, os.strerror(code), str(src), None, str(dst))


def rename_noreplace(src: str | Path, dst: str | Path) -> None:
    """Move ``src`` (a file or a folder) to ``dst`` unless ``dst`` exists.

    Parameters
    ----------
    src
        The finished output (a file or a folder), normally a temporary sibling of ``dst``.
    dst
        Where it goes; on the same file system as ``src``.

    Raises
    ------
    FileExistsError
        If ``dst`` exists (anything, also a dangling symbolic link) when the move happens; then
        ``src`` is where it was and ``dst`` is untouched.
    OSError
        On any other failure of the move (the caller turns it into an InputError).
    """
    src, dst = Path(src), Path(dst)
    if _rename2(src, dst, _RENAME_NOREPLACE):
        return
    if os.name == "nt":  # Windows' rename never replaces
        os.rename(src, dst)
        return
    if src.is_dir() and not src.is_symlink():
        # the target folder made here is the lock: mkdir fails if anything is there, and POSIX
        # rename replaces an empty folder but fails on one that someone has put a file into
        os.mkdir(dst, 0o700)
        try:
            os.rename(src, dst)
        except OSError as exc:
            if exc.errno in (errno.ENOTEMPTY, errno.EEXIST):
                raise FileExistsError(errno.EEXIST, "appeared meanwhile", str(dst)) from None
            with contextlib.suppress(OSError):
                os.rmdir(dst)
            raise
        return
    try:
        os.link(src, dst)  # fails if dst exists
    except FileExistsError:
        raise
    except OSError:  # a file system without hard links: the check and the move are separate
        if os.path.lexists(dst):
            raise FileExistsError(errno.EEXIST, "exists", str(dst)) from None
        os.rename(src, dst)
        return
    os.unlink(src)


def _exchange(a: Path, b: Path) -> bool:
    """Swap two paths atomically (Linux); False where that is not possible."""
    return _rename2(a, b, _RENAME_EXCHANGE)


# ---- messages ------------------------------------------------------------------------------------


def os_error_message(exc: OSError) -> str:
    """The reason of an OS error in words (``No space left on device``).

    Parameters
    ----------
    exc
        The error.

    Returns
    -------
    str
        Its ``strerror``, else its text on one line, else its class name.

    Examples
    --------
    >>> import errno
    >>> os_error_message(OSError(errno.ENOSPC, "No space left on device"))
    'No space left on device'
    """
    return exc.strerror or " ".join(str(exc).split()) or type(exc).__name__


def _notice(text: str) -> None:
    from crankdyn.display import printable

    with contextlib.suppress(OSError, ValueError):
        print(f"crankdyn: {printable(' '.join(text.split()))}", file=sys.stderr, flush=True)


def _within(path: str | None, folder: Path) -> bool:
    if not path:
        return False
    try:
        return Path(path) == folder or folder in Path(path).parents
    except (TypeError, ValueError):
        return False


# ---- checks before the work ----------------------------------------------------------------------


def _parent_of(p: Path) -> Path:
    return p.parent if str(p.parent) else Path(".")


def _ours(folder: Path) -> bool:
    """Whether ``folder`` is a folder crankdyn wrote (it holds :data:`MARKER`) or an empty one:
    a real folder, not a symbolic link; the only folders ``force`` may replace."""
    try:
        if not stat.S_ISDIR(os.lstat(folder).st_mode):
            return False
        marker = os.lstat(folder / MARKER)
    except FileNotFoundError:
        try:
            with os.scandir(folder) as entries:
                return next(entries, None) is None
        except OSError:
            return False
    except OSError:
        return False
    return stat.S_ISREG(marker.st_mode)


def _contents(folder: Path) -> str:
    """What a folder holds, in words, for a message: ``3 entries (a.txt, b, c.csv)``."""
    import itertools

    try:
        with os.scandir(folder) as entries:
            names = sorted(e.name for e in itertools.islice(entries, _COUNTED + 1))
    except OSError as exc:
        return f"entries crankdyn cannot list ({os_error_message(exc)})"
    count = f"more than {_COUNTED}" if len(names) > _COUNTED else str(len(names))
    shown = ", ".join(names[:_LISTED]) + (", ..." if len(names) > _LISTED else "")
    return f"{count} {'entry' if len(names) == 1 else 'entries'} ({shown})"


def _check_replaceable(p: Path, shown: str, option: str) -> None:
    """Refuse to replace (with ``option``) a folder crankdyn did not write: a symbolic link to
    a folder, or a folder without :data:`MARKER` that is not empty."""
    if p.is_symlink():
        raise InputError(
            f"is a symbolic link to the folder {os.readlink(p)}; {option} does not replace a "
            "linked folder (it would delete the files where the link points): remove the link "
            "or choose another name",
            file=shown,
        )
    if not _ours(p):
        raise InputError(
            f"holds {_contents(p)} and no {MARKER}, the marker of a folder crankdyn wrote; "
            f"{option} replaces only crankdyn's own output folders: remove it yourself or "
            "choose another name",
            file=shown,
        )


def _check_target(
    path: str | Path, *, force: bool, option: str, folder: bool, reuse: bool = False
) -> Path:
    shown = str(path)
    p = Path(path)
    if not shown or shown in (".", "..") or p.name in ("", ".", ".."):
        raise InputError("is not a name crankdyn can write to", file=shown or '""')
    try:
        linked = p.is_symlink()
        if linked:
            if not p.exists():
                raise InputError(
                    f"is a symbolic link to {os.readlink(p)}, which does not exist; remove the "
                    "link or choose another name",
                    file=shown,
                )
            if folder and force and not reuse and p.is_dir():
                _check_replaceable(p, shown, option)  # refused: a linked folder
            p = Path(os.path.realpath(p))  # write where the link points
        if p.exists():
            mode = p.stat().st_mode
            if folder and not stat.S_ISDIR(mode):
                raise InputError("exists and is not a folder", file=shown)
            if not folder and stat.S_ISDIR(mode):
                raise InputError("is a folder; give a file name", file=shown)
            if not folder and not stat.S_ISREG(mode):
                raise InputError("is not a regular file (a device or a FIFO?)", file=shown)
            if not force:
                raise InputError(f"already exists; not overwritten without {option}", file=shown)
            if folder and not reuse:
                _check_replaceable(p, shown, option)
        parent = _parent_of(p)
        if not parent.is_dir():
            if parent.exists():
                raise InputError(f"{parent} is not a folder", file=shown)
            raise InputError(f"the folder {parent} does not exist", file=shown)
        if not os.access(parent, os.W_OK | os.X_OK):
            raise InputError(
                f"cannot write into the folder {parent}: permission denied", file=shown
            )
    except OSError as exc:
        raise InputError(f"cannot write: {os_error_message(exc)}", file=shown) from None
    return p


def check_writable(path: str | Path, *, force: bool, option: str = "--force") -> Path:
    """Check a file output before the work: return the path to write (a symbolic link's
    target), or raise a one-line :class:`InputError`.

    Refused: an existing file without ``force``; a folder; a device or FIFO; a dangling
    symbolic link; a missing or unwritable parent folder.

    Parameters
    ----------
    path
        The output file.
    force
        Whether an existing file may be replaced.
    option
        The command-line option that grants ``force``, named in the message.

    Returns
    -------
    Path
        The path to write (a symbolic link resolved to its target).

    Raises
    ------
    InputError
        On a refused target, naming it (``file``) and the reason.
    """
    return _check_target(path, force=force, option=option, folder=False)


def check_output_dir(
    path: str | Path, *, force: bool, option: str = "--force", reuse: bool = False
) -> Path:
    """Check a folder output (a report) before the work: return the folder to write, or raise a
    one-line :class:`InputError` (an existing folder without ``force``, a file, a dangling
    symbolic link, a missing or unwritable parent folder; with ``force``, a folder crankdyn did
    not write: a symbolic link to a folder, or a folder that holds anything but lacks
    :data:`MARKER`).

    Parameters
    ----------
    path
        The output folder.
    force
        Whether an existing folder may be replaced (only one crankdyn wrote).
    option
        The command-line option that grants ``force``, named in the message.
    reuse
        An existing folder is written into, not replaced (a study's folder, whose own files
        the caller manages): with ``force`` it is accepted whatever it holds.

    Returns
    -------
    Path
        The folder to write (a symbolic link resolved to its target).

    Raises
    ------
    InputError
        On a refused target, naming it (``file``) and the reason.
    """
    return _check_target(path, force=force, option=option, folder=True, reuse=reuse)


# ---- files ---------------------------------------------------------------------------------------


def _sync(handle: IO[bytes]) -> None:
    handle.flush()
    os.fsync(handle.fileno())


def _temporary(p: Path, suffix: str = ".tmp") -> Path:
    return _parent_of(p) / f".{p.name}.{os.urandom(6).hex()}{suffix}"  # secrets.token_hex(6)


def _sibling(p: Path, n: int, folder: bool) -> Path:
    if folder or not p.suffix:
        return p.with_name(f"{p.name}.{n}")
    return p.with_name(f"{p.stem}.{n}{p.suffix}")


def _place(tmp: Path, p: Path, shown: str, *, force: bool, folder: bool) -> Path:
    """Move a finished temporary output into place (module docstring); return where it went."""
    why = "appeared while the output was being written"
    if force and os.path.lexists(p):
        if not folder:
            os.replace(tmp, p)
            return p
        if _replace_folder(tmp, p):
            return p
        # p is not (or no longer) a folder crankdyn wrote: kept, the output goes to a sibling
        why = "is no longer a folder crankdyn wrote (its marker is gone)"
    try:
        rename_noreplace(tmp, p)
        return p
    except FileExistsError:
        pass
    for n in range(2, _MAX_SIBLINGS):
        candidate = _sibling(p, n, folder)
        try:
            rename_noreplace(tmp, candidate)
        except FileExistsError:
            continue
        _notice(f"{shown} {why} and was left as it is; the new output is in {candidate}")
        return candidate
    raise InputError(
        f"appeared while the output was being written, and so did {_MAX_SIBLINGS - 2} "
        "numbered siblings; nothing was replaced",
        file=shown,
    )


def _replace_folder(tmp: Path, p: Path) -> bool:
    """Replace the folder ``p`` by ``tmp`` if ``p`` is crankdyn's (:func:`_ours`), checked on
    the very folder that is removed (after the exchange, which is undone if it is not);
    False, with both left in place, when it is not."""
    if _exchange(tmp, p):
        if _ours(tmp):  # now the old output
            _remove(tmp)
            return True
        _exchange(tmp, p)  # not crankdyn's: swapped back
        return False
    if not _ours(p):
        return False
    old = _temporary(p, ".old")
    os.rename(p, old)
    if not _ours(old):  # changed between the check and the move
        os.rename(old, p)
        return False
    try:
        os.rename(tmp, p)
    except BaseException:
        os.rename(old, p)
        raise
    _remove(old)
    return True


def _place_held(tmp: Path, p: Path, shown: str, *, force: bool, folder: bool) -> Path:
    """:func:`_place` with the signals held; an interrupt that arrived meanwhile is delivered
    after the move, and said not to have undone it."""
    placed = None
    try:
        with deferred_signals():
            placed = _place(tmp, p, shown, force=force, folder=folder)
    except KeyboardInterrupt:
        if placed is not None:
            _notice(f"the interrupt came after {placed} was complete; it is in place")
        raise
    return placed


def _remove(path: Path) -> None:
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path, ignore_errors=True)
    else:
        with contextlib.suppress(OSError):
            path.unlink()


class AtomicFile:
    """A file written through a handle to a temporary sibling and moved into place on success
    (:func:`atomic_file`); :attr:`path` is where it went.

    Parameters
    ----------
    path
        The output file (checked at once by :func:`check_writable`).
    force
        Whether an existing file may be replaced.
    """

    def __init__(self, path: str | Path, *, force: bool = False) -> None:
        self.shown = str(path)
        self.force = force
        self.target = check_writable(path, force=force)
        self.path = self.target
        self.tmp = _temporary(self.target)
        self._handle: IO[bytes] | None = None

    def __enter__(self) -> IO[bytes]:
        try:
            # the user's umask applies (0o666 & ~umask), as for any file the user makes
            flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)
            self._handle = os.fdopen(os.open(self.tmp, flags, 0o666), "wb")
        except BaseException as exc:
            self._discard()
            if isinstance(exc, OSError):
                raise self._error(exc) from None
            raise
        return self._handle

    def __exit__(
        self,
        kind: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> Literal[False]:
        handle = self._handle
        if exc is None and handle is not None:
            try:
                _sync(handle)
                handle.close()
                self.path = _place_held(
                    self.tmp, self.target, self.shown, force=self.force, folder=False
                )
            except BaseException as err:
                self._discard()
                if isinstance(err, OSError):
                    raise self._error(err) from None
                raise
            return False
        self._discard()
        # an error of the handle (no space, an I/O error) names no file, or the temporary one
        if isinstance(exc, OSError) and (exc.filename is None or _within(exc.filename, self.tmp)):
            raise self._error(exc) from None
        return False

    def _discard(self) -> None:
        with deferred_signals():
            if self._handle is not None:
                with contextlib.suppress(OSError):
                    self._handle.close()
            _remove(self.tmp)

    def _error(self, exc: OSError) -> InputError:
        return InputError(f"cannot write: {os_error_message(exc)}", file=self.shown)


def atomic_file(path: str | Path, *, force: bool = False) -> AtomicFile:
    """Write a file through a handle, a piece at a time, atomically (a large output streamed).

    ``with atomic_file(path, force=...) as handle:`` yields a binary handle to a temporary
    sibling of ``path`` (created with the user's umask); on success it is flushed to disk and
    moved into place as :func:`write_bytes` does (never over a file that appeared meanwhile
    without ``force``: a numbered sibling then, said on stderr); on any error or interrupt it is
    removed and ``path`` is left as it was. The target is checked when this is called
    (:func:`check_writable`). The returned object's ``path`` is where the file went.

    Parameters
    ----------
    path
        The output file.
    force
        Whether an existing file may be replaced (only once the new one is complete).

    Returns
    -------
    AtomicFile
        The context manager; entering it gives the binary handle to write to.

    Raises
    ------
    InputError
        On a refused target (at the call), or an operating-system error while writing or moving
        the file, naming the target.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> out = atomic_file(folder / "modes.csv")
    >>> with out as handle:
    ...     _ = handle.write(b"mode,")
    ...     _ = handle.write(b"1")
    >>> out.path.read_text()
    'mode,1'
    """
    return AtomicFile(path, force=force)


def write_bytes(path: str | Path, data: bytes, *, force: bool = False) -> Path:
    """Write ``data`` to ``path`` atomically (module docstring); an existing file needs
    ``force``. Returns the path written: ``path``, or a numbered sibling when ``path`` appeared
    while the data was written.

    Parameters
    ----------
    path
        The output file.
    data
        The bytes to write.
    force
        Whether an existing file may be replaced.

    Returns
    -------
    Path
        Where the data went: ``path`` (a symbolic link's target), or a numbered sibling
        (``forces.2.json``) when ``path`` appeared meanwhile.

    Raises
    ------
    InputError
        On a refused target (:func:`check_writable`) or an operating-system error while
        writing, naming the target; nothing is left half-written.
    """
    out = atomic_file(path, force=force)
    with out as handle:
        handle.write(data)
    return out.path


def write_text(path: str | Path, text: str, *, force: bool = False) -> Path:
    """Write UTF-8 text atomically; an existing file needs ``force`` (:func:`write_bytes`).

    Parameters
    ----------
    path
        The output file.
    text
        The text, written as UTF-8.
    force
        Whether an existing file may be replaced.

    Returns
    -------
    Path
        Where the text went (``path`` or a numbered sibling, as :func:`write_bytes`).

    Raises
    ------
    InputError
        As :func:`write_bytes`.
    """
    return write_bytes(path, text.encode("utf-8"), force=force)


# ---- folders -------------------------------------------------------------------------------------


class AtomicDirectory:
    """A folder of outputs built in a temporary sibling and moved into place on success
    (:func:`atomic_directory`); :attr:`path` is where it went.

    Parameters
    ----------
    path
        The output folder (checked at once by :func:`check_output_dir`).
    force
        Whether an existing folder may be replaced.
    """

    def __init__(self, path: str | Path, *, force: bool = False) -> None:
        self.shown = str(path)
        self.force = force
        self.target = check_output_dir(path, force=force)
        self.path = self.target
        self.tmp = _temporary(self.target)

    def __enter__(self) -> Path:
        try:
            # the name is known before the folder exists, so an interrupt at any point (even
            # inside the mkdir) is cleaned up; the user's umask applies
            self.tmp.mkdir()
            from crankdyn import __version__

            (self.tmp / MARKER).write_text(
                _MARKER_TEXT.format(version=__version__), encoding="utf-8"
            )
        except BaseException as exc:
            self._discard()
            if isinstance(exc, OSError):
                raise self._error(exc) from None
            raise
        return self.tmp

    def __exit__(
        self,
        kind: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> Literal[False]:
        if exc is None:
            try:
                self.path = _place_held(
                    self.tmp, self.target, self.shown, force=self.force, folder=True
                )
            except BaseException as err:
                self._discard()
                if isinstance(err, OSError):
                    raise self._error(err) from None
                raise
            return False
        self._discard()
        # a write into the folder that names no file (Path.write_bytes on a full disk: the
        # error of the handle) or that names a file in it is an error of this output; the
        # block writes into the folder, not to standard output
        if isinstance(exc, OSError) and (
            exc.filename is None
            or _within(exc.filename, self.tmp)
            or _within(exc.filename2, self.tmp)
        ):
            raise self._error(exc) from None
        return False

    def _discard(self) -> None:
        with deferred_signals():
            _remove(self.tmp)

    def _error(self, exc: OSError) -> InputError:
        return InputError(f"cannot write: {os_error_message(exc)}", file=self.shown)


def atomic_directory(path: str | Path, *, force: bool = False) -> AtomicDirectory:
    """Build a folder of outputs in a temporary sibling and move it into place on success.

    ``with atomic_directory(path, force=...) as tmp:`` yields the temporary folder to write
    into (it already holds crankdyn's marker, :data:`MARKER`); the block writes into it, not to
    standard output (an OS error that names no file is taken for a write of the folder). The
    target is checked when this is called (:func:`check_output_dir`). On any error or
    interrupt the temporary folder is removed and ``path`` is left as it was. An existing
    ``path`` needs ``force``, must be a folder crankdyn wrote (holding the marker, or empty;
    not a symbolic link) and is only replaced once the new folder is complete; a ``path``
    that appeared meanwhile is never replaced without ``force`` (the output goes to a numbered
    sibling, said on stderr), nor with it unless it is crankdyn's. The returned object's
    ``path`` is where the folder went.

    Parameters
    ----------
    path
        The output folder.
    force
        Whether an existing folder may be replaced (only once the new one is complete).

    Returns
    -------
    AtomicDirectory
        The context manager; entering it gives the temporary folder (a Path) to write into.

    Raises
    ------
    InputError
        On a refused target (at the call), or an operating-system error while creating or
        moving the folder, naming the target.
    """
    return AtomicDirectory(path, force=force)
