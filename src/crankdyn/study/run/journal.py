"""The study folder: its manifest, the append-only journal of finished cases, and a lock.

Layout of a study folder (``--out DIR``)::

    study.json       manifest: the study's fingerprint, name, source, crankdyn version
    journal.jsonl    one JSON object per finished case, appended as cases finish
    results.parquet  the results table, rebuilt from the journal (atomically)
    results.csv      the same table as CSV
    summary/         the HTML summary (index.html, plots/, data/)

The journal is the record: each line is written in one ``write`` call and flushed to the
operating system before the next case is taken up, so a finished case survives Ctrl-C and a
killed process. The file is fsync'ed to the disk with a record when :data:`SYNC_INTERVAL` has
passed since the previous fsync (so every record of a study whose cases take longer than that),
and when the journal is closed; a power cut can lose only the records of a burst since the last
fsync (an fsync costs milliseconds: once per record it would cap a fast study at a few hundred
cases per second). A line cut short by a crash is a case that did not finish: it is
dropped when the journal is next opened. The tables and the summary are derived files, rebuilt
from the journal.

Rules for an existing folder: a folder holding the same study (same fingerprint) resumes; one
holding another study, or other files, is refused unless ``force``, which discards only the
files listed above (and starts the study over). A lock keeps two runs out of one folder.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import json
import os
import shutil
import time
from pathlib import Path
from typing import IO, Any

from crankdyn.errors import InputError
from crankdyn.io.output import check_output_dir, write_text

__all__ = ["JOURNAL", "MANIFEST", "Journal", "StudyFolder", "read_journal"]

MANIFEST = "study.json"
"""The manifest's file name in a study folder."""
JOURNAL = "journal.jsonl"
"""The journal's file name in a study folder."""
LOCK = ".lock"
DERIVED = ("results.parquet", "results.csv", "summary")
FORMAT = "crankdyn-study"
SYNC_INTERVAL = 0.2  # s, the longest a recorded case waits for fsync


def read_journal(path: Path) -> tuple[dict[str, dict[str, Any]], int]:
    """The latest record of every case in a journal.

    Parameters
    ----------
    path : pathlib.Path
        The journal (it may not exist yet).

    Returns
    -------
    records : dict of str to dict
        {case id: its latest record}.
    damaged : int
        The damaged lines skipped (a final line without its newline is a case cut short, not
        damage, and is not counted).
    """
    records: dict[str, dict[str, Any]] = {}
    damaged = 0
    if not path.exists():
        return records, 0
    data = path.read_bytes()
    lines = data.split(b"\n")
    complete = lines[:-1]  # the part after the last newline is an unfinished line (or empty)
    for line in complete:
        if not line.strip():
            continue
        try:
            record = json.loads(line)
            records[str(record["case_id"])] = record
        except (ValueError, KeyError, TypeError):
            damaged += 1
    return records, damaged


class Journal:
    """Append-only writer of finished cases (module docstring); a context manager that closes
    it.

    Parameters
    ----------
    path : pathlib.Path
        The journal, created when missing; a final line cut short is dropped first.
    """

    def __init__(self, path: Path) -> None:
        self.path = path
        _drop_torn_tail(path)
        self._handle = path.open("ab")
        self._synced = time.monotonic()

    def append(self, record: dict[str, Any]) -> None:
        """Write one record as a line, flushed to the operating system (fsync'ed when
        :data:`SYNC_INTERVAL` has passed).

        Parameters
        ----------
        record : dict of str to object
            A finished case (JSON, no NaN).
        """
        line = json.dumps(record, allow_nan=False, separators=(",", ":"), ensure_ascii=False)
        self._handle.write(line.encode("utf-8") + b"\n")
        self._handle.flush()
        now = time.monotonic()
        if now - self._synced >= SYNC_INTERVAL:
            os.fsync(self._handle.fileno())
            self._synced = now

    def close(self) -> None:
        """Flush, fsync and close the journal (again: nothing)."""
        if not self._handle.closed:
            self._handle.flush()
            os.fsync(self._handle.fileno())
            self._handle.close()

    def __enter__(self) -> Journal:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _drop_torn_tail(path: Path) -> None:
    """Cut a final line that lacks its newline (a write cut short by a crash)."""
    if not path.exists():
        return
    with path.open("rb+") as handle:
        handle.seek(0, os.SEEK_END)
        size = handle.tell()
        if size == 0:
            return
        handle.seek(size - 1)
        if handle.read(1) == b"\n":
            return
        # find the last newline (read backwards in blocks)
        position = size
        keep = 0
        while position > 0:
            start = max(0, position - 65536)
            handle.seek(start)
            block = handle.read(position - start)
            index = block.rfind(b"\n")
            if index >= 0:
                keep = start + index + 1
                break
            position = start
        handle.truncate(keep)


class StudyFolder:
    """An output folder opened for a study run (module docstring for the rules).

    Use as a context manager: it holds the folder's lock until closed.

    Parameters
    ----------
    path : str or pathlib.Path
        The folder (created when missing; its parent must exist).
    fingerprint : str
        The study's fingerprint (:meth:`crankdyn.study.spec.StudySpec.fingerprint`).
    force : bool
        Start over in a folder that holds another study or other files (only the study's own
        files are discarded).
    info : dict of str to object
        More of the manifest (name, source, crankdyn version...).

    Raises
    ------
    InputError
        If the folder cannot be used, holds another study or other files (without
        ``force``), or is locked by another run.
    """

    def __init__(
        self, path: str | Path, fingerprint: str, *, force: bool, info: dict[str, Any]
    ) -> None:
        self.path = Path(path)
        self.fingerprint = fingerprint
        self.resumed = False
        self.created = False
        self._lock_handle: IO[str] | None = None
        self._open(force, info)

    # ---- paths ---------------------------------------------------------------------------------
    @property
    def journal_path(self) -> Path:
        """The journal's path."""
        return self.path / JOURNAL

    @property
    def manifest_path(self) -> Path:
        """The manifest's path."""
        return self.path / MANIFEST

    def records(self) -> tuple[dict[str, dict[str, Any]], int]:
        """The journal's records (:func:`read_journal`).

        Returns
        -------
        records : dict of str to dict
            {case id: its latest record}.
        damaged : int
            The damaged lines skipped.
        """
        return read_journal(self.journal_path)

    # ---- opening -------------------------------------------------------------------------------
    def _open(self, force: bool, info: dict[str, Any]) -> None:
        p = self.path
        shown = str(p)
        # a file, a dangling link, a missing or unwritable parent: refused before the work (an
        # existing folder is fine: a study resumes in it)
        check_output_dir(p, force=True, reuse=True)
        try:
            if not p.exists():
                p.mkdir()
                self.created = True
            self._lock()
        except InputError:
            raise
        except (OSError, ValueError) as exc:
            reason = getattr(exc, "strerror", None) or str(exc)
            raise InputError(f"cannot use the folder: {reason}", file=shown) from None
        try:
            self._check(force)
            if not self.resumed:
                manifest = {
                    "format": FORMAT,
                    "format_version": 1,
                    "fingerprint": self.fingerprint,
                    "created": _dt.datetime.now(_dt.UTC).isoformat(timespec="seconds"),
                    **info,
                }
                write_text(self.manifest_path, json.dumps(manifest, indent=2) + "\n", force=True)
        except BaseException:
            self.close()
            raise

    def _check(self, force: bool) -> None:
        p = self.path
        shown = str(p)
        manifest = None
        if self.manifest_path.exists():
            try:
                manifest = json.loads(self.manifest_path.read_text(encoding="utf-8"))
                if manifest.get("format") != FORMAT:
                    raise ValueError
            except (ValueError, OSError, AttributeError):
                if not force:
                    raise InputError(
                        f"{MANIFEST} is not a crankdyn study manifest; give --force to start "
                        "the study over in this folder, or choose another --output",
                        file=shown,
                    ) from None
                manifest = None
        if manifest is not None and not force:
            if manifest.get("fingerprint") == self.fingerprint:
                self.resumed = True
                return
            raise InputError(
                "holds the results of a different study (or of this one before its base file, "
                "[analysis], figures, removed keys or crankdyn version changed); give --force to "
                "discard them and start over, or choose another --output",
                file=shown,
            )
        ours = {MANIFEST, JOURNAL, LOCK, *DERIVED}
        others = [q.name for q in p.iterdir() if q.name not in ours]
        if manifest is None and not force and (others or self.journal_path.exists()):
            raise InputError(
                "is not empty and holds no crankdyn study; choose another --output, or give "
                "--force to write the study into it (only the study's own files are replaced)",
                file=shown,
            )
        if force:
            for name in (JOURNAL, *DERIVED):
                target = p / name
                if target.is_dir():
                    shutil.rmtree(target)
                elif target.exists():
                    target.unlink()

    def discard_if_unused(self) -> None:
        """Undo the opening of a folder that received no case (e.g. the cluster could not be
        reached): remove a new folder, or a manifest written into an empty one."""
        if self.resumed or self.journal_path.exists():
            return
        self.close()
        with contextlib.suppress(OSError):
            self.manifest_path.unlink()
            (self.path / LOCK).unlink()
            if self.created:
                self.path.rmdir()

    # ---- the lock ------------------------------------------------------------------------------
    def _lock(self) -> None:
        handle = (self.path / LOCK).open("a+")
        try:
            import fcntl
        except ImportError:  # Windows: no advisory lock; documented
            self._lock_handle = handle
            return
        try:
            fcntl.flock(handle.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError:
            handle.close()
            raise InputError(
                "is in use by another crankdyn study run (wait for it, or stop it)",
                file=str(self.path),
            ) from None
        self._lock_handle = handle

    def close(self) -> None:
        """Release the folder's lock (again: nothing)."""
        if self._lock_handle is not None:
            with contextlib.suppress(OSError):
                self._lock_handle.close()  # closing releases the lock
            self._lock_handle = None

    def __enter__(self) -> StudyFolder:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
