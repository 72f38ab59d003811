"""Pulse records read in chunks (domain objects): a torsiograph record of any length.

A :class:`~crankdyn.measure.signals.PulseTrain` holds its pulse times in memory; a
:class:`PulseRecord` holds a way to read them: a callable that reads the record from its start
and yields it in :class:`PulseChunk` pieces of any size (a file reader's blocks of lines, or
slices of arrays). The order analysis of a long record (:mod:`crankdyn.measure.blocks`) reads
it two or three times, one chunk at a time, and never holds it whole; a short one it gathers
into a pulse train (:meth:`PulseRecord.train`).

The reference marks of a record come in the chunks too: the reference column of a signal file
lists the marks' times from its first line on (shorter than the pulse column), so each chunk
carries the marks written on its lines. A mark must come no later than the pulses around its
time (as in every such file, where the m-th mark sits on line m and its time near the pulse
of line m N); one that comes later is located by one more reading of the record.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError
from crankdyn.measure.signals import PulseTrain, check_increasing, check_teeth

__all__ = ["ChunkCheck", "PulseChunk", "PulseRecord"]


@dataclass(frozen=True, eq=False)
class PulseChunk:
    """A piece of a pulse record: consecutive pulse times, and the reference marks written
    beside them.

    Parameters
    ----------
    times : numpy.ndarray
        Pulse times (s), finite (the reader checks them), continuing the chunk before.
    lines : numpy.ndarray or None
        The file line of every pulse (for messages), or None.
    reference : numpy.ndarray or None
        Reference mark times (s) that come with this chunk, continuing the chunk before's.
    reference_lines : numpy.ndarray or None
        Their file lines, or None.
    """

    times: NDArray[np.float64]
    lines: NDArray[np.int64] | None = None
    reference: NDArray[np.float64] | None = None
    reference_lines: NDArray[np.int64] | None = None


@dataclass(frozen=True, eq=False)
class PulseRecord:
    """A pulse record read in chunks (module docstring).

    Parameters
    ----------
    read : callable
        ``read()`` reads the record from its start: an iterable of :class:`PulseChunk`. It is
        called once per pass of an analysis; every call must give the same pulses.
    teeth : int
        Pulses per revolution N of a complete wheel (as :class:`PulseTrain`), >= 4.
    source : str
        Where the record came from (for messages and titles).
    expected : int or None
        The pulses the record is expected to hold, known before it is read (a binary array's
        length, or a text file's size over its first lines' length), or None. Only whether a
        reading is kept in memory (:meth:`cached`) depends on it, never a result.

    Raises
    ------
    InputError
        If ``teeth`` is not a whole number >= 4.

    Examples
    --------
    A pulse train read back in chunks of 25 pulses:

    >>> train = PulseTrain(np.arange(100) / 600.0, 60)
    >>> record = PulseRecord.from_train(train, chunk=25)
    >>> [c.times.size for c in record.chunks()]
    [25, 25, 25, 25]
    >>> bool(np.array_equal(record.train().times, train.times))
    True
    """

    read: Callable[[], Iterable[PulseChunk]]
    teeth: int
    source: str = "signal"
    expected: int | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "teeth", check_teeth(self.teeth))

    def chunks(self) -> Iterator[PulseChunk]:
        """Read the record from its start.

        Returns
        -------
        iterator of PulseChunk
            Its chunks, in order.
        """
        return iter(self.read())

    @classmethod
    def from_train(
        cls, train: PulseTrain, *, chunk: int | Iterable[int] | None = None
    ) -> PulseRecord:
        """A pulse train as a record read in chunks (for records held in memory, and tests).

        Parameters
        ----------
        train : PulseTrain
            The pulses (s), reference marks (s) and lines.
        chunk : int, iterable of int or None
            Pulses per chunk: one size, or the sizes in turn (the last one repeated); None: one
            chunk. Reference mark m comes with the chunk that holds pulse m, as in a file's
            reference column (the marks beyond the pulses with the last chunk).

        Returns
        -------
        PulseRecord
            The same record, read in those chunks.
        """
        sizes = (
            [train.times.size]
            if chunk is None
            else [chunk]
            if isinstance(chunk, int)
            else list(chunk)
        )
        if not sizes or any(int(s) < 1 for s in sizes):
            raise ValueError("chunk sizes must be positive")

        def read() -> Iterator[PulseChunk]:
            total = train.times.size
            start, k = 0, 0
            while start < total:
                size = int(sizes[min(k, len(sizes) - 1)])
                stop = min(total, start + size)
                yield PulseChunk(
                    train.times[start:stop],
                    None if train.lines is None else train.lines[start:stop],
                    *_marks(train, start, stop, stop >= total),
                )
                start, k = stop, k + 1

        return cls(read, train.teeth, train.source, train.times.size)

    def cached(self, limit: int) -> PulseRecord:
        """This record, its pulse times kept in memory after a first whole reading when they
        are at most ``limit``: later readings replay them (without lines and marks, which the
        first reading gave) instead of reading the file again. A record expected to hold more
        than ``limit`` (:attr:`expected`) is not kept at all: its first reading would hold
        ``limit`` pulses only to let them go (on a long record, the peak of its memory).

        Parameters
        ----------
        limit : int
            The most pulses kept (8 bytes each).

        Returns
        -------
        PulseRecord
            The same record.
        """
        if self.expected is not None and self.expected > limit:
            return self
        kept: list[NDArray[np.float64]] | None = None

        def read() -> Iterator[PulseChunk]:
            nonlocal kept
            if kept is not None:
                yield from (PulseChunk(t) for t in kept)
                return
            parts: list[NDArray[np.float64]] | None = []
            count = 0
            for chunk in self.chunks():
                count += chunk.times.size
                if parts is not None and count <= limit:
                    parts.append(chunk.times)
                else:
                    parts = None
                yield chunk
            kept = parts

        return PulseRecord(read, self.teeth, self.source, self.expected)

    def train(self) -> PulseTrain:
        """The whole record as a pulse train in memory (its checks as a train's).

        Returns
        -------
        PulseTrain
            The pulse times (s), reference marks (s) and lines.

        Raises
        ------
        InputError
            As :class:`PulseTrain` for times that are not finite or do not increase.
        """
        times, lines, marks, mark_lines = [], [], [], []
        check = ChunkCheck(self.source)
        for c in self.chunks():
            check(c)  # a record that goes wrong stops at the chunk that does
            times.append(c.times)
            lines.append(c.lines)
            if c.reference is not None:
                marks.append(c.reference)
                mark_lines.append(c.reference_lines)
        whole = np.concatenate(times) if times else np.empty(0)
        times.clear()  # the chunks go before the train makes its copy
        return PulseTrain(
            whole,
            self.teeth,
            reference=np.concatenate(marks) if marks else None,
            source=self.source,
            lines=_joined(lines),
            reference_lines=_joined(mark_lines) if marks else None,
        )


class ChunkCheck:
    """The checks of :class:`PulseTrain` made chunk by chunk as a record is read: its times
    and its marks finite and increasing, across the chunks too (the same messages, naming the
    line, or the sample counted from the record's start).

    Parameters
    ----------
    source : str
        The record's source, for the messages.
    """

    def __init__(self, source: str) -> None:
        self.source = source
        self.pulses = 0  # pulses checked
        self.marks = 0
        self.last = math.nan
        self.last_line: int | None = None
        self.last_mark = math.nan

    def __call__(self, chunk: PulseChunk) -> None:
        """Check the next chunk.

        Parameters
        ----------
        chunk : PulseChunk
            The chunk.

        Raises
        ------
        InputError
            At the first time that is not finite or does not increase.
        """
        t = np.asarray(chunk.times, dtype=float)
        if t.size:
            _finite(t, "time", "pulse times", self.source)
            if self.pulses:
                lines = None
                if chunk.lines is not None and self.last_line is not None:
                    lines = np.array([self.last_line, int(chunk.lines[0])])
                check_increasing(
                    np.array([self.last, t[0]]), lines, file=self.source, offset=self.pulses - 1
                )
            check_increasing(t, chunk.lines, file=self.source, offset=self.pulses)
            self.pulses += t.size
            self.last = float(t[-1])
            self.last_line = None if chunk.lines is None else int(chunk.lines[-1])
        if chunk.reference is not None and np.size(chunk.reference):
            ref = np.asarray(chunk.reference, dtype=float)
            _finite(ref, "reference", "reference times", self.source)
            if self.marks:
                check_increasing(
                    np.array([self.last_mark, ref[0]]), None, key="reference", file=self.source
                )
            check_increasing(ref, chunk.reference_lines, key="reference", file=self.source)
            self.marks += ref.size
            self.last_mark = float(ref[-1])


def _finite(values: NDArray[np.float64], key: str, what: str, source: str) -> None:
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        raise InputError(
            f"{what} must be finite", key=key, value=float(values[bad[0]]), file=source
        )


def _marks(
    train: PulseTrain, start: int, stop: int, last: bool
) -> tuple[NDArray[np.float64] | None, NDArray[np.int64] | None]:
    """The reference marks of the chunk of pulses ``start:stop`` (mark m with pulse m)."""
    if train.reference is None:
        return None, None
    end = train.reference.size if last else stop
    marks = train.reference[start:end]
    lines = None if train.reference_lines is None else train.reference_lines[start:end]
    return (marks, lines) if marks.size else (None, None)


def _joined(parts: list[NDArray[np.int64] | None]) -> NDArray[np.int64] | None:
    """The concatenated line numbers, or None when a part has none."""
    if not parts or any(p is None for p in parts):
        return None
    return np.concatenate([p for p in parts if p is not None])
