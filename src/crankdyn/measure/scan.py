"""The checks and repairs of a pulse record read in chunks (analysis): what
:func:`crankdyn.measure.signals.prepare_pulses` does to a pulse train in memory, done segment by
segment, in memory bounded by a segment whatever the record's length.

A record is read in segments of :data:`SEGMENT` pulses, each with :data:`CONTEXT` pulses of the
record either side (fewer at its ends). Every quantity the whole-record preparation computes
depends on the pulses near it only, so a segment with its context gives the whole record's
values:

- the interval ratios are medians over four intervals either side (exact);
- the tooth position of a pulse counts the pulses missing in the gaps before it (carried from
  segment to segment, exact);
- a missing pulse's time is the quintic spline's through the recorded pulses
  (:func:`~crankdyn.measure.signals.fill_gaps`), and a reference mark's tooth position the cubic
  spline's (:func:`~crankdyn.measure.signals.reference_positions`): an interpolating spline
  depends on data k knots away by a factor decaying as lambda^k, lambda = 2 - sqrt(3) = 0.268
  for the cubic and 0.431 for the quintic (the smallest root of the Euler-Frobenius polynomial;
  C. de Boor, *A Practical Guide to Splines*, rev. ed., Springer 2001, ch. III and XII;
  I. J. Schoenberg, *Cardinal Spline Interpolation*, SIAM 1973, lecture 4), so over
  :data:`CONTEXT` = 256 pulses the spline of a segment and the record's differ by
  0.431^256 = 1e-94 of the data: they agree to rounding.

The checks that need the whole record (the dropped pulses' share, a missing-tooth wheel's gaps
every revolution, the reference marks' spacing) are kept as counts and the first places, and
made when the record has been read (:func:`scan_record`), with the messages of
:func:`~crankdyn.measure.signals.prepare_pulses`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError
from crankdyn.measure.records import ChunkCheck, PulseChunk, PulseRecord
from crankdyn.measure.signals import (
    MAX_DROPPED_FRACTION,
    MAX_DROPPED_RUN,
    check_marks,
    dropped_note,
    fill_gaps,
    interval_faults,
    interval_ratios,
    long_run,
    missing_tooth_note,
    odd_interval,
    reference_positions,
    sample_place,
    spurious_pulse,
    too_many_dropped,
)

__all__ = ["CONTEXT", "SEGMENT", "ScannedRecord", "prepared_segments", "scan_record"]

SEGMENT = 1 << 16
"""Pulses per segment of a record read in chunks."""
CONTEXT = 256
"""Pulses of context either side of a segment (module docstring)."""


@dataclass(frozen=True)
class _Window:
    """Pulses ``first .. first + times.size - 1`` of a record around the segment
    ``[start, stop)``; ``last``: the record ends in it."""

    first: int
    times: NDArray[np.float64]
    lines: NDArray[np.int64] | None
    start: int
    stop: int
    last: bool


def _windows(
    chunks: Iterator[PulseChunk],
    on_chunk: Callable[[int, PulseChunk], None] | None = None,
    segment: int = SEGMENT,
    context: int = CONTEXT,
) -> Iterator[_Window]:
    """The record's segments with their context (module docstring); ``on_chunk(first, chunk)``
    sees every chunk as it is read (``first``: the record's index of its first pulse)."""
    times: NDArray[np.float64] = np.empty(0)
    lines: NDArray[np.int64] | None = None
    with_lines = True
    first = start = read = 0
    ended = False
    while True:
        parts, line_parts = [times], [lines]
        have = times.size
        while not ended and have < (start - first) + segment + context + 1:
            try:
                chunk = next(chunks)
            except StopIteration:
                ended = True
                break
            if on_chunk is not None:
                on_chunk(read, chunk)
            read += chunk.times.size
            have += chunk.times.size
            parts.append(np.asarray(chunk.times, dtype=float))
            line_parts.append(chunk.lines)
            with_lines = with_lines and chunk.lines is not None
        times = np.concatenate(parts) if len(parts) > 1 else times
        lines = np.concatenate([p for p in line_parts if p is not None]) if with_lines else None
        total = first + times.size
        stop = start + segment
        if ended and stop + context >= total:
            stop = total
        if stop <= start:
            return
        yield _Window(first, times, lines, start, stop, ended and stop == total)
        if stop == total and ended:
            return
        start = stop
        cut = max(0, start - context - first)
        times = times[cut:]
        lines = None if lines is None else lines[cut:]
        first += cut


@dataclass
class _Positions:
    """The tooth positions of a window's pulses, their times (gaps filled) and what the
    window's segment holds."""

    index: NDArray[np.int64]  # tooth position of every pulse of the window
    times: NDArray[np.float64]  # times of tooth positions index[0] .. index[-1]
    ratio: NDArray[np.float64]
    gaps: NDArray[np.intp]  # the segment's gaps, indices into the window's intervals
    missing: NDArray[np.int_]
    short: NDArray[np.intp]
    off: NDArray[np.bool_]


def _positions(w: _Window, origin: int) -> _Positions:
    """Tooth positions and filled times of a window; ``origin`` is the tooth position of the
    segment's first pulse."""
    ratio = interval_ratios(w.times)
    faults = interval_faults(ratio)
    step = np.ones(w.times.size - 1, dtype=np.int64)
    step[faults.gaps] += faults.missing
    index = np.concatenate([[0], np.cumsum(step)])
    index += origin - index[w.start - w.first]
    lo, hi = w.start - w.first, min(w.stop, w.first + w.times.size - 1) - w.first
    inside = (faults.gaps >= lo) & (faults.gaps < hi)
    short = faults.short[(faults.short >= lo) & (faults.short < hi)]
    if faults.gaps.size:
        times, _ = fill_gaps(index, w.times)
    else:
        times = w.times
    return _Positions(
        index, times, ratio, faults.gaps[inside], faults.missing[inside], short, faults.off[inside]
    )


def prepared_segments(
    record: PulseRecord, gappy: frozenset[int] | None = None
) -> Iterator[tuple[int, NDArray[np.float64]]]:
    """The time of every tooth position of a record, segment by segment (module docstring):
    what :func:`~crankdyn.measure.signals.prepare_pulses` gives as ``times``, gaps filled.

    Parameters
    ----------
    record : crankdyn.measure.records.PulseRecord
        A record already checked by :func:`scan_record` (its errors are not repeated).
    gappy : frozenset of int or None
        The segments (numbered from 0) with gaps (:attr:`ScannedRecord.gappy`): the others'
        times are the pulses' own, taken as they are; None: every segment looked at.

    Yields
    ------
    tuple of (int, numpy.ndarray)
        The tooth position of the segment's first time, and the times (s) of its consecutive
        tooth positions.
    """
    origin = 0
    for number, w in enumerate(_windows(record.chunks())):
        if gappy is not None and number not in gappy:
            times = w.times[w.start - w.first : None if w.last else w.stop - w.first]
            yield origin, times
            origin += times.size
            continue
        pos = _positions(w, origin)
        b = w.stop - w.first if not w.last else w.times.size - 1
        end = pos.index[b] if not w.last else pos.index[-1] + 1
        yield origin, pos.times[origin - pos.index[0] : end - pos.index[0]]
        origin = int(end)


@dataclass(frozen=True)
class ScannedRecord:
    """A pulse record checked, its gaps counted and its reference marks located
    (:func:`scan_record`): what :class:`~crankdyn.measure.signals.PreparedPulses` says of a
    pulse train, without the times.

    Parameters
    ----------
    record : crankdyn.measure.records.PulseRecord
        The record.
    pulses : int
        Pulses recorded.
    positions : int
        Tooth positions from the first pulse to the last (gaps filled).
    first_time, last_time : float
        The first and the last pulse's times (s).
    reference_index : numpy.ndarray or None
        The fractional tooth position of every reference mark (or of the first tooth after
        each gap of a missing-tooth wheel), or None.
    reference_times : numpy.ndarray or None
        The reference marks' times within the record (s), or None (no reference column).
    reference_period : int or None
        Tooth positions between marks (N or 2N), or None.
    missing_tooth : bool
        The wheel has missing teeth.
    notes : tuple of str
        What was repaired or assumed.
    gappy : frozenset of int
        The segments of :data:`SEGMENT` pulses with gaps (dropped pulses or missing teeth).
    """

    record: PulseRecord
    pulses: int
    positions: int
    first_time: float
    last_time: float
    reference_index: NDArray[np.float64] | None
    reference_times: NDArray[np.float64] | None
    reference_period: int | None
    missing_tooth: bool
    notes: tuple[str, ...]
    gappy: frozenset[int] = frozenset()

    @property
    def teeth(self) -> int:
        """Tooth positions per revolution N."""
        return self.record.teeth

    @property
    def source(self) -> str:
        """Where the record came from."""
        return self.record.source


@dataclass
class _Gaps:
    """What the segments' gaps say, kept for the checks of the whole record (module
    docstring): counts, the first places, and the marks of a missing-tooth wheel while every
    gap so far is one revolution after the one before."""

    count: int = 0
    first_missing: int = 0
    regular: bool = True  # every gap of first_missing pulses, one revolution after the last
    last_start: int = 0
    total: int = 0
    places: list[str] = field(default_factory=list)
    run: tuple[int, str, float] | None = None  # the first gap of too many pulses in a row
    marks: list[int] = field(default_factory=list)  # first tooth after each gap


class _Scan:
    """The state of :func:`scan_record` from segment to segment."""

    def __init__(self, record: PulseRecord) -> None:
        self.record = record
        self.name = record.source
        self.teeth = record.teeth
        self.origin = 0
        self.segments = 0
        self.gappy: set[int] = set()
        self.gaps = _Gaps()
        self.off: InputError | None = None
        self.short: InputError | None = None
        self.check = ChunkCheck(record.source)
        self.last = math.nan  # the last pulse time read
        self.first_time = math.nan
        self.marks: list[NDArray[np.float64]] = []
        self.mark_lines: list[NDArray[np.int64] | None] = []
        self.read_marks = 0
        self.queue: NDArray[np.float64] = np.empty(0)  # marks read, not yet located
        self.queue_index: NDArray[np.float64] = np.empty(0)  # their indices among the marks
        self.located: list[NDArray[np.float64]] = []  # (kappa, time, index) rows
        self.late: list[NDArray[np.float64]] = []  # indices of marks read too late

    # ---- as the record is read --------------------------------------------------------------
    def chunk(self, first: int, chunk: PulseChunk) -> None:
        """Check a chunk as :class:`~crankdyn.measure.signals.PulseTrain` checks its times
        (:class:`~crankdyn.measure.records.ChunkCheck`) and queue its marks."""
        self.check(chunk)
        if first == 0 and chunk.times.size:
            self.first_time = float(chunk.times[0])
        if chunk.times.size:
            self.last = float(chunk.times[-1])
        if chunk.reference is not None and np.size(chunk.reference):
            ref = np.asarray(chunk.reference, dtype=float)
            lines = chunk.reference_lines
            self.marks.append(ref)
            self.mark_lines.append(None if lines is None else np.asarray(lines))
            index = np.arange(self.read_marks, self.read_marks + ref.size, dtype=float)
            self.queue = np.concatenate([self.queue, ref])
            self.queue_index = np.concatenate([self.queue_index, index])
            self.read_marks += ref.size

    # ---- segment by segment -----------------------------------------------------------------
    def segment(self, w: _Window) -> None:
        """Check a segment's intervals and gaps, locate the marks within it."""
        number, self.segments = self.segments, self.segments + 1
        if w.times.size < 2:
            return
        pos = _positions(w, self.origin)
        if pos.gaps.size:
            self.gappy.add(number)
        where = lambda i: sample_place(w.lines, i - w.first, w.first)  # noqa: E731 (record index i)
        if pos.short.size and self.short is None:
            i = int(pos.short[0]) + 1
            self.short = spurious_pulse(
                where(w.first + i), pos.ratio[i - 1], float(w.times[i]), self.name
            )
        if np.any(pos.off) and self.off is None:
            j = int(pos.gaps[np.argmax(pos.off)])
            self.off = odd_interval(
                where(w.first + j + 1), pos.ratio[j], float(w.times[j + 1]), self.name
            )
        self._gaps(w, pos, where)
        self._locate(w, pos)
        b = w.stop - w.first if not w.last else w.times.size - 1
        self.origin = int(pos.index[b]) + (1 if w.last else 0)

    def _gaps(self, w: _Window, pos: _Positions, where: Callable[[int], str]) -> None:
        g = self.gaps
        for j, m in zip(pos.gaps.tolist(), pos.missing.tolist(), strict=True):
            start = int(pos.index[j])
            if g.count == 0:
                g.first_missing = m
            elif m != g.first_missing or start - g.last_start != self.teeth:
                g.regular = False
                g.marks = []
            if g.regular:
                g.marks.append(start + m + 1)
            g.count += 1
            g.last_start = start
            g.total += m
            if len(g.places) < 5:
                g.places.append(where(w.first + j + 1))
            if m > MAX_DROPPED_RUN and g.run is None:
                g.run = (m, where(w.first + j + 1), float(w.times[j + 1]))

    def _locate(self, w: _Window, pos: _Positions) -> None:
        """The tooth positions of the marks read so far whose times fall in the segment (the
        marks before it, read too late, are located by one more reading: :meth:`finish`)."""
        if self.queue.size == 0:
            return
        t = self.queue
        start = float(w.times[w.start - w.first])
        end = float(w.times[-1]) if w.last else float(w.times[w.stop - w.first])
        before = t < start
        late = before & (t >= self.first_time)
        if np.any(late):
            self.late.append(self.queue_index[late])
        now = (t >= start) & ((t < end) | (w.last & (t <= end)))
        if np.any(now):
            kappa = reference_positions(pos.times, int(pos.index[0]), t[now])
            self.located.append(np.column_stack([kappa, t[now], self.queue_index[now]]))
        done = int(np.count_nonzero(before | now))  # a prefix: the marks are in time order
        self.queue, self.queue_index = self.queue[done:], self.queue_index[done:]

    # ---- when the record has been read ------------------------------------------------------
    def finish(self, pulses: int) -> ScannedRecord:
        """The checks of the whole record (module docstring), in the order of
        :func:`~crankdyn.measure.signals.prepare_pulses`."""
        if self.short is not None:
            raise self.short
        if self.off is not None:
            raise self.off
        g, n, notes = self.gaps, self.teeth, []
        missing_tooth = g.count >= 2 and g.regular and g.first_missing < n // 4
        if missing_tooth:
            notes.append(missing_tooth_note(g.first_missing, n))
        elif g.count:
            if g.run is not None:
                raise long_run(g.run[0], g.run[1], g.run[2], self.name)
            if g.total > max(1.0, MAX_DROPPED_FRACTION * pulses):
                raise too_many_dropped(g.total, g.places[0], self.name)
            notes.append(dropped_note(g.total, g.places, g.count))
        index = times = period = None
        if self.marks:
            index, times, period = self._marks_checked()
        elif missing_tooth:
            index, period = np.asarray(g.marks, dtype=float), n
        return ScannedRecord(
            self.record,
            pulses,
            self.origin,
            self.first_time,
            self.last,
            index,
            times,
            period,
            bool(missing_tooth),
            tuple(notes),
            frozenset(self.gappy),
        )

    def _marks_checked(self) -> tuple[NDArray[np.float64], NDArray[np.float64], int]:
        flat = np.concatenate(self.marks)
        rows = np.concatenate(self.located) if self.located else np.empty((0, 3))
        if self.late:
            index = np.concatenate(self.late)
            late = flat[index.astype(np.int64)]
            found = mark_positions(self.record, late, gappy=frozenset(self.gappy))
            rows = np.concatenate([rows, np.column_stack([found, late, index])])
            rows = rows[np.argsort(rows[:, 2], kind="stable")]
        if rows.shape[0] == 0:
            raise InputError(
                "no reference time falls within the pulse record", file=self.name, key="reference"
            )
        lines = None
        if all(m is not None for m in self.mark_lines):
            every = np.concatenate([m for m in self.mark_lines if m is not None])
            lines = every[rows[:, 2].astype(np.int64)]
        return check_marks(rows[:, 0], rows[:, 1], lines, self.teeth, self.name)


def scan_record(record: PulseRecord, check: Callable[[int], None] | None = None) -> ScannedRecord:
    """Read a pulse record once, checking it and locating its marks (module docstring).

    Parameters
    ----------
    record : crankdyn.measure.records.PulseRecord
        The record.
    check : callable or None
        ``check(pulses)``, called with the count of pulses once the record has been read and
        its pulse times checked, before the checks of its gaps and marks (the order of an
        analysis's checks of a record in memory).

    Returns
    -------
    ScannedRecord
        The counts of pulses and tooth positions, the notes and the marks' tooth positions.

    Raises
    ------
    InputError
        As :class:`~crankdyn.measure.signals.PulseTrain` and
        :func:`~crankdyn.measure.signals.prepare_pulses` for the same pulses, naming the line.
    """
    scan = _Scan(record)
    pulses = 0
    for w in _windows(record.chunks(), scan.chunk):
        scan.segment(w)
        pulses = w.first + w.times.size
    if pulses < 2:
        raise InputError("the signal holds fewer than two pulses", file=record.source)
    if check is not None:
        check(pulses)
    return scan.finish(pulses)


def mark_positions(
    record: PulseRecord,
    marks: NDArray[np.float64],
    value: Callable[[NDArray[np.int64]], NDArray[np.float64]] | None = None,
    gappy: frozenset[int] | None = None,
) -> NDArray[np.float64]:
    """A cubic spline through the tooth positions' times, at mark times, in one more reading of
    the record: of the tooth position (``value`` None) or of ``value(positions)``; each mark
    with :data:`CONTEXT` tooth positions either side of it (module docstring).

    Parameters
    ----------
    record : crankdyn.measure.records.PulseRecord
        The record (checked by :func:`scan_record`).
    marks : numpy.ndarray
        Mark times (s), increasing, within the record.
    value : callable or None
        The spline's values at tooth positions (an array of int positions to values); None:
        the positions themselves.
    gappy : frozenset of int or None
        The segments with gaps (:func:`prepared_segments`).

    Returns
    -------
    numpy.ndarray
        The spline's values at the marks (as
        :func:`~crankdyn.measure.signals.reference_positions` over the whole record).
    """
    from scipy.interpolate import CubicSpline  # imported here: keeps the start-up light

    out = np.empty(marks.size)
    done = 0

    def evaluate(first: int, times: NDArray[np.float64], upto: int) -> None:
        nonlocal done
        if upto > done:
            k = np.arange(first, first + times.size)
            y = k.astype(float) if value is None else value(k)
            out[done:upto] = CubicSpline(times, y)(marks[done:upto])
            done = upto

    first, buffer = 0, np.empty(0)
    for start, times in prepared_segments(record, gappy):
        if not buffer.size:
            first = start
        buffer = np.concatenate([buffer, times])
        if buffer.size > 2 * CONTEXT:
            evaluate(first, buffer, int(np.searchsorted(marks, buffer[-CONTEXT])))
            cut = buffer.size - 2 * CONTEXT
            first, buffer = first + cut, buffer[cut:]
    evaluate(first, buffer, marks.size)
    return out
