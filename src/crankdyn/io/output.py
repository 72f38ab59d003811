"""Writing outputs safely: atomically, and never over an existing file without ``force``.

A file is written to a temporary file in the destination directory and moved into place with
``os.replace`` (atomic on POSIX and Windows), so a reader never sees half a file and an
interrupted run leaves nothing behind. A folder of outputs (a report) is built in a temporary
sibling folder and renamed into place the same way (:func:`atomic_directory`).
"""

from __future__ import annotations

import contextlib
import os
import secrets
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path

from crankdyn.errors import InputError

__all__ = ["atomic_directory", "check_writable", "write_bytes", "write_text"]


def check_writable(path: str | Path, *, force: bool, option: str = "--force") -> Path:
    """Refuse to overwrite an existing path unless ``force``; make sure the parent exists."""
    p = Path(path)
    if p.exists() and not force:
        raise InputError(f"already exists; not overwritten without {option}", file=str(path))
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.is_dir():
        raise InputError(f"the folder {parent} does not exist", file=str(path))
    return p


def write_bytes(path: str | Path, data: bytes, *, force: bool = False) -> Path:
    """Write ``data`` to ``path`` atomically; an existing file needs ``force``."""
    p = check_writable(path, force=force)
    if p.is_dir():
        raise InputError("is a directory", file=str(path))
    fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".tmp", dir=p.parent or ".")
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
            handle.flush()
            os.fsync(handle.fileno())
        os.replace(tmp, p)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise
    return p


def write_text(path: str | Path, text: str, *, force: bool = False) -> Path:
    """Write UTF-8 text atomically; an existing file needs ``force``."""
    return write_bytes(path, text.encode("utf-8"), force=force)


@contextlib.contextmanager
def atomic_directory(path: str | Path, *, force: bool = False) -> Iterator[Path]:
    """Build a folder of outputs in a temporary sibling and move it into place on success.

    Yields the temporary folder to write into. On any error or interrupt the temporary folder
    is removed and ``path`` is left as it was. An existing ``path`` needs ``force`` and is only
    replaced once the new folder is complete.
    """
    target = Path(path)
    if target.exists() and not force:
        raise InputError("already exists; not overwritten without --force", file=str(path))
    if target.exists() and not target.is_dir():
        raise InputError("exists and is not a folder", file=str(path))
    parent = target.parent if str(target.parent) else Path(".")
    if not parent.is_dir():
        raise InputError(f"the folder {parent} does not exist", file=str(path))
    # the name is known before the folder exists, so an interrupt at any point (even inside the
    # mkdir) is cleaned up by the handler below
    tmp = parent / f".{target.name}.{secrets.token_hex(6)}.tmp"
    try:
        tmp.mkdir()
        yield tmp
        if target.exists():
            old = Path(tempfile.mkdtemp(prefix=f".{target.name}.", suffix=".old", dir=parent))
            old.rmdir()
            os.replace(target, old)
            os.replace(tmp, target)
            shutil.rmtree(old, ignore_errors=True)
        else:
            os.replace(tmp, target)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
