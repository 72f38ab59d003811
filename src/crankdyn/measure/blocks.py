"""Order analysis of a pulse record of any length in bounded memory (analysis): the angle-domain
processing of :mod:`crankdyn.measure.angle` and the windows of :mod:`crankdyn.measure.windows`,
block by block, combined exactly as the whole record's.

A record longer than :data:`BLOCK` tooth positions is read three or four times
(:class:`~crankdyn.measure.records.PulseRecord`), never held whole:

1. :func:`~crankdyn.measure.scan.scan_record`: the checks and repairs of the pulses, the count of
   tooth positions K and the reference marks' positions, from which the crank angle of tooth
   position 0 follows (it needs every mark: their mean position);
2. with ``tooth_correction="self"``, the tooth-spacing pattern: the sum of the vibration at each
   tooth over the record's first whole revolutions (pairs), added block by block in the order
   the whole record's sum adds them; with tooth errors and a reference column, the marks'
   positions in the teeth's actual angles (one more reading,
   :func:`~crankdyn.measure.scan.mark_positions`);
3. the blocks: tooth positions [c0, c1) (the *core*, :data:`BLOCK` of them) with ``pad``
   positions of the record either side (:class:`Layout`). In each, the mean-rotation filter
   (exact: a moving sum over two cycles either side), the cubic spline of the crank-angle
   position, the quintic spline of the resampling and the cubic spline of the mean rotation's
   time; each spline depends on data k knots away by a factor decaying as 0.268^k (cubic) or
   0.431^k (quintic; :mod:`crankdyn.measure.scan`), so with :data:`MARGIN` = 96 positions of
   data beyond every point used (2 x 96 for the resampling, whose data are the position
   spline's values) a block's values are the whole record's to rounding (0.431^96 = 1e-35);
   a block's resampled vibration is used on its core only, so every crank angle of the grid is
   computed once. The whole cycles, their boundary times and the windows follow as the cores
   come: a window of c cycles that spans two cores takes the first core's last c - 1 cycles
   with it.

The result is the whole-record analysis's to rounding (tests/measure/test_blocks.py splits
records at arbitrary points and compares). The working memory is that of one block, about 240
bytes per tooth position of core + 2 pad (60 MB for the default :data:`BLOCK`, wheels up to
10,000 teeth), plus what the result holds: 16 bytes per order per cycle (and per window of a
run-up) and the per-cycle trace envelope, 40 bytes per cycle.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError
from crankdyn.measure.angle import (
    actual_positions,
    cycle_length,
    grid_start,
    mark_numbering,
    positions,
    pulse_speed,
)
from crankdyn.measure.records import PulseRecord
from crankdyn.measure.scan import ScannedRecord, mark_positions, prepared_segments
from crankdyn.measure.signals import PulseTrain
from crankdyn.measure.windows import Windows, window_coefficients

__all__ = [
    "BLOCK",
    "MARGIN",
    "BlockedAnalysis",
    "Envelope",
    "Layout",
    "blocked_analysis",
    "blocked_pattern",
    "gathered",
    "layout",
]

BLOCK = 1 << 18
"""Tooth positions per block (its core): records up to this many pulses are analysed whole."""
MARGIN = 96
"""Tooth positions of data a block's splines have beyond every point used (module docstring)."""


def gathered(record: PulseRecord, limit: int = BLOCK) -> PulseTrain | None:
    """The record as a pulse train when it holds at most ``limit`` pulses, else None (read up
    to ``limit`` + 1 pulses only).

    Parameters
    ----------
    record : crankdyn.measure.records.PulseRecord
        The record.
    limit : int
        The most pulses gathered.

    Returns
    -------
    PulseTrain or None
        The whole record (checked as a pulse train), or None for a longer one.
    """
    count = 0
    for chunk in record.chunks():
        count += chunk.times.size
        if count > limit:
            return None
    return record.train()


@dataclass(frozen=True)
class Layout:
    """How a record of ``positions`` tooth positions is cut into blocks (module docstring).

    Parameters
    ----------
    positions : int
        Tooth positions K of the record.
    length : int
        Tooth positions per working cycle L.
    core : int
        Tooth positions per block core.
    pad : int
        Tooth positions of the record either side of a core: the filter's 2 x 2 L/2, 2
        :data:`MARGIN` for the splines and L for the vibration's own excursion from the mean
        rotation (up to one cycle's teeth).
    """

    positions: int
    length: int
    core: int
    pad: int

    @property
    def s(self) -> int:
        """The mean-rotation filter's offset s (tooth positions;
        :func:`~crankdyn.measure.angle.mean_rotation_times`)."""
        return 4 * (self.length // 2)

    def blocks(self) -> Iterator[tuple[int, int, int, int]]:
        """The blocks: (c0, c1, a, e), the core [c0, c1) within the data [a, e).

        Yields
        ------
        tuple of int
            Tooth positions.
        """
        for c0 in range(0, self.positions, self.core):
            c1 = min(self.positions, c0 + self.core)
            yield c0, c1, max(0, c0 - self.pad), min(self.positions, c1 + self.pad)


def layout(positions: int, length: int, block: int = BLOCK) -> Layout:
    """The blocks of a record (:class:`Layout`): cores of ``block`` positions, or twice the pad
    for a wheel so large that its cycles need more.

    Parameters
    ----------
    positions, length : int
        Tooth positions of the record and of a working cycle.
    block : int
        Tooth positions per core (default :data:`BLOCK`).

    Returns
    -------
    Layout
        The layout.
    """
    pad = 4 * (length // 2) + 2 * MARGIN + length
    return Layout(positions, length, max(int(block), 2 * pad), pad)


def _block_times(
    scan: ScannedRecord, lay: Layout
) -> Iterator[tuple[int, int, int, NDArray[np.float64]]]:
    """(c0, c1, a, times of tooth positions a .. e - 1) of every block, in one reading."""
    segments = prepared_segments(scan.record, scan.gappy)
    parts: list[NDArray[np.float64]] = []
    first = have = 0
    for c0, c1, a, e in lay.blocks():
        while first + have < e:
            start, times = next(segments)
            if start != first + have:  # pragma: no cover - segments are consecutive
                raise RuntimeError("tooth positions out of order")
            parts.append(times)
            have += times.size
        data = np.concatenate(parts) if len(parts) > 1 else parts[0]
        data = data[a - first :]
        first, have, parts = a, data.size, [data]
        yield c0, c1, a, data[: e - a]


def blocked_pattern(
    scan: ScannedRecord, length: int, tooth_origin: int, block: int = BLOCK
) -> NDArray[np.float64]:
    """The tooth-spacing pattern of a record (:func:`crankdyn.measure.angle.tooth_pattern`),
    block by block.

    Parameters
    ----------
    scan : crankdyn.measure.scan.ScannedRecord
        The record, scanned.
    length : int
        Tooth positions per working cycle L.
    tooth_origin : int
        The tooth number of tooth position 0.
    block : int
        Tooth positions per block core.

    Returns
    -------
    numpy.ndarray
        (N,) the mean of v at each tooth over the record's whole revolutions (an even number),
        less its mean over the teeth (rad).

    Raises
    ------
    InputError
        If the record holds fewer than two whole revolutions after filtering.
    """
    n = scan.teeth
    lay = layout(scan.positions, length, block)
    s, pitch = lay.s, 2.0 * math.pi / n
    revolutions = ((scan.positions - 2 * s) // n) // 2 * 2
    if revolutions < 2:
        raise InputError("at least two whole revolutions are needed for the tooth correction")
    end = s + revolutions * n
    pattern = np.zeros(n)
    for c0, c1, a, t in _block_times(scan, lay):
        lo, hi = max(c0, s), min(c1, end)
        if lo < hi:
            pos = positions(t, a, length)
            v = pos.vibration(pitch)[lo - a - pos.s : hi - a - pos.s]
            np.add.at(pattern, (np.arange(lo, hi) + tooth_origin) % n, v)
        if c1 >= end:
            break
    pattern /= revolutions
    return pattern - pattern.mean()


def corrected_marks(scan: ScannedRecord, errors: NDArray[np.float64], tooth_origin: int) -> float:
    """kappa_0 with the tooth errors taken into account (as
    :func:`crankdyn.measure.angle.angle_domain` for a record in memory): the marks located in
    the teeth's actual angles.

    Parameters
    ----------
    scan : crankdyn.measure.scan.ScannedRecord
        The record, scanned (with marks).
    errors : numpy.ndarray
        The tooth errors (rad, N values numbered from the mark).
    tooth_origin : int
        The tooth number of tooth position 0.

    Returns
    -------
    float
        The first mark's fractional tooth position.
    """
    n = scan.teeth
    if scan.reference_index is None or scan.reference_period is None:
        raise ValueError("no reference mark")  # the caller checks
    if scan.reference_times is None:  # a missing-tooth gap: the mark is a tooth
        marks = actual_positions(scan.reference_index.astype(int), errors, tooth_origin, n)
    else:
        marks = mark_positions(
            scan.record,
            scan.reference_times,
            lambda k: actual_positions(k, errors, tooth_origin, n),
            scan.gappy,
        )
    m = np.arange(marks.size)
    return float(np.mean(marks - scan.reference_period * m))


@dataclass(frozen=True)
class Envelope:
    """The trace of a record analysed in blocks, per working cycle (the plots of a long record
    draw the band between the least and the largest value of each cycle).

    Parameters
    ----------
    angle : numpy.ndarray
        (C,) the crank angle at each cycle's start (rad).
    speed_low, speed_high : numpy.ndarray
        (C,) the least and the largest instantaneous speed over the cycle's pulse intervals
        (rad/s).
    vibration_low, vibration_high : numpy.ndarray
        (C,) the least and the largest angular vibration over the cycle (rad).
    """

    angle: NDArray[np.float64]
    speed_low: NDArray[np.float64]
    speed_high: NDArray[np.float64]
    vibration_low: NDArray[np.float64]
    vibration_high: NDArray[np.float64]


@dataclass(frozen=True)
class BlockedAnalysis:
    """What the order analysis takes from a record analysed in blocks (:func:`blocked_analysis`).

    Parameters
    ----------
    per_cycle : crankdyn.measure.windows.Windows or None
        The orders of every single cycle (uniform one-cycle windows); None when not kept
        (``keep_cycles``).
    cycle_speed : numpy.ndarray
        (cycles,) the mean rotation's speed over each cycle (rad/s).
    mean : numpy.ndarray
        (Q,) the single cycles' mean orders (rad): their complex (synchronous) average.
    scatter : numpy.ndarray
        (Q,) the single cycles' RMS scatter about it (rad).
    windows : crankdyn.measure.windows.Windows or None
        The order-tracking windows, or None when not asked for.
    cycles : int
        Whole cycles analysed.
    length : int
        Samples per cycle L.
    speed : float
        The mean speed over the whole cycles (rad/s).
    average : numpy.ndarray
        (L,) the vibration averaged over the cycles (rad).
    cycle_angle : numpy.ndarray
        (L,) the crank angles of a cycle's samples from its boundary (rad).
    envelope : Envelope
        The trace per cycle.
    """

    per_cycle: Windows | None
    cycle_speed: NDArray[np.float64]
    mean: NDArray[np.complex128]
    scatter: NDArray[np.float64]
    windows: Windows | None
    cycles: int
    length: int
    speed: float
    average: NDArray[np.float64]
    cycle_angle: NDArray[np.float64]
    envelope: Envelope


class _Series:
    """Windows written in order into arrays allocated once, for at most ``capacity`` of them:
    the record's per-cycle figures are not interleaved on the heap with the blocks' working
    arrays, whose memory is then reused from block to block, and are not joined at the end.

    With ``keep`` false the windows' coefficients are not kept, only their running mean and
    the sum of their squared deviations from it (Chan, Golub and LeVeque's pairwise update,
    exact to rounding; 16 bytes per order in all instead of per order per window): what a
    steady analysis reads of them."""

    def __init__(self, capacity: int, orders: int, keep: bool = True) -> None:
        self.keep = keep
        self.coefficients = np.empty((capacity if keep else 0, orders), dtype=complex)
        self.speed = np.empty(capacity)
        self.start_angle = np.empty(capacity)
        self.count = 0
        self.mean = np.zeros(orders, dtype=complex)
        self.squares = np.zeros(orders)  # sum of |V - mean|^2

    def add(self, part: Windows) -> None:
        """The next windows."""
        n, i = part.speed.size, self.count
        if self.keep:
            self.coefficients[i : i + n] = part.coefficients
        if n:
            mean = np.mean(part.coefficients, axis=0)
            squares = np.sum(np.abs(part.coefficients - mean) ** 2, axis=0)
            delta = mean - self.mean
            self.mean += delta * (n / (i + n))
            self.squares += squares + np.abs(delta) ** 2 * (i * n / (i + n))
        self.speed[i : i + n] = part.speed
        self.start_angle[i : i + n] = part.start_angle
        self.count = i + n

    def windows(self) -> Windows | None:
        """The windows added (None when their coefficients were not kept)."""
        n = self.count
        if not self.keep:
            return None
        return Windows(self.coefficients[:n], self.speed[:n], self.start_angle[:n])

    def moments(self) -> tuple[NDArray[np.complex128], NDArray[np.float64]]:
        """The windows' mean coefficients and their RMS scatter about it (rad)."""
        return self.mean.copy(), np.sqrt(self.squares / max(self.count, 1))


class _Cycles:
    """The whole cycles of the grid as the blocks give them: the windows over them, their
    average and envelope (module docstring, step 3), for at most ``capacity`` cycles."""

    def __init__(
        self,
        length: int,
        orders: NDArray[np.float64],
        cycle_angle: float,
        window_cycles: int,
        window: str,
        tracking: bool,
        capacity: int,
        keep_cycles: bool = True,
    ) -> None:
        self.length, self.orders, self.cycle_angle = length, orders, cycle_angle
        self.window_cycles, self.window, self.tracking = window_cycles, window, tracking
        self.angle0 = math.nan  # the crank angle of the grid's first sample
        self.samples: NDArray[np.float64] = np.empty(0)
        self.first = 0  # the cycle of samples[0]
        self.boundaries = np.empty(capacity + 1)  # the boundary times known, in order
        self.known = 0
        self.next_cycle = 0  # the next single cycle's window
        self.next_window = 0  # the next tracking window
        self.total: NDArray[np.float64] | None = None
        self.singles = _Series(capacity, orders.size, keep_cycles)
        self.windows = _Series(capacity if tracking else 0, orders.size)
        # the envelope: per cycle, the least and largest vibration and pulse speed
        self.low, self.high = np.empty(capacity), np.empty(capacity)
        self.speed_low, self.speed_high = np.empty(capacity), np.empty(capacity)
        self.speeds = 0

    def add(
        self,
        vibration: NDArray[np.float64],
        boundary_times: NDArray[np.float64],
        speeds: NDArray[np.float64],
    ) -> None:
        """The next grid samples (rad), boundary times (s) and cycles' pulse speeds (rad/s,
        (cycles, L))."""
        self.samples = np.concatenate([self.samples, vibration])
        k, n = self.known, boundary_times.size
        self.boundaries[k : k + n] = boundary_times
        self.known = k + n
        if speeds.size:
            j, m = self.speeds, speeds.shape[0]
            np.min(speeds, axis=1, out=self.speed_low[j : j + m])
            np.max(speeds, axis=1, out=self.speed_high[j : j + m])
            self.speeds = j + m
        self._flush()

    def _times(self, start: int, stop: int) -> NDArray[np.float64]:
        return self.boundaries[: self.known][start:stop]

    def _flush(self) -> None:
        L, wc = self.length, self.window_cycles
        complete = self.first + self.samples.size // L
        upto = min(complete, self.known - 1)
        if upto > self.next_cycle:  # single cycles: their windows, sum and envelope
            c0 = self.next_cycle
            per = self._cycles(c0, upto)
            self.singles.add(
                window_coefficients(
                    per,
                    c0,
                    self.angle0,
                    self._times(c0, upto + 1),
                    self.orders,
                    self.cycle_angle,
                    1,
                )
            )
            part = np.add.reduce(per, axis=0)
            self.total = part if self.total is None else self.total + part
            np.min(per, axis=1, out=self.low[c0:upto])
            np.max(per, axis=1, out=self.high[c0:upto])
            self.next_cycle = upto
        if self.tracking:
            last = min(complete, self.known - 1) - wc  # the last window's first cycle
            if last >= self.next_window:
                per = self._cycles(self.next_window, last + wc)
                self.windows.add(
                    window_coefficients(
                        per,
                        self.next_window,
                        self.angle0,
                        self._times(self.next_window, last + wc + 1),
                        self.orders,
                        self.cycle_angle,
                        wc,
                        self.window,
                    )
                )
                self.next_window = last + 1
        keep = min(self.next_cycle, self.next_window if self.tracking else self.next_cycle)
        if keep > self.first:
            self.samples = self.samples[(keep - self.first) * L :]
            self.first = keep

    def _cycles(self, start: int, stop: int) -> NDArray[np.float64]:
        L = self.length
        return self.samples[(start - self.first) * L : (stop - self.first) * L].reshape(-1, L)

    def result(self, cycles: int) -> tuple[_Series, Windows | None, NDArray[np.float64], Envelope]:
        """The single cycles, the tracking windows, the average and the envelope."""
        average = (np.zeros(self.length) if self.total is None else self.total) / cycles
        done = self.next_cycle
        envelope = Envelope(
            np.asarray(self.angle0 + self.cycle_angle * np.arange(cycles), dtype=float),
            self.speed_low[: min(cycles, self.speeds)],
            self.speed_high[: min(cycles, self.speeds)],
            self.low[:done],
            self.high[:done],
        )
        windows = self.windows.windows() if self.tracking else None
        return self.singles, windows, average, envelope


def _too_wide(reason: str) -> InputError:
    return InputError(
        f"the angular vibration moves the pulses {reason} by more than a working cycle's teeth "
        "from the mean rotation: not a torsional vibration (a slipping or reversing shaft?)",
        key="time",
    )


def blocked_analysis(
    scan: ScannedRecord,
    orders: ArrayLike,
    cycle_angle: float,
    *,
    reference_angle: float = 0.0,
    tooth_errors: NDArray[np.float64] | None = None,
    kappa: float | None = None,
    window_cycles: int = 1,
    window: str = "uniform",
    tracking: bool = False,
    block: int = BLOCK,
    keep_cycles: bool = True,
) -> BlockedAnalysis:
    """The angle domain and the windows of a scanned record, block by block (module docstring).

    Parameters
    ----------
    scan : crankdyn.measure.scan.ScannedRecord
        The record, scanned.
    orders : array_like
        The orders q (per revolution).
    cycle_angle : float
        Crank angle of one working cycle (rad).
    reference_angle : float
        Crank angle at the reference mark (rad).
    tooth_errors : numpy.ndarray or None
        Tooth errors e_j numbered from the mark (rad, N values), or None.
    kappa : float or None
        The first mark's tooth position with the tooth errors taken into account
        (:func:`corrected_marks`); None: the marks' nominal positions.
    window_cycles : int
        Cycles per order-tracking window.
    window : str
        ``"uniform"`` or ``"hann"``.
    tracking : bool
        Compute the order-tracking windows too.
    block : int
        Tooth positions per block core (default :data:`BLOCK`).
    keep_cycles : bool
        Keep every single cycle's orders (16 bytes per order per cycle); false: only their
        mean and scatter (a steady analysis).

    Returns
    -------
    BlockedAnalysis
        The windows, the average cycle and the envelope.

    Raises
    ------
    InputError
        As :func:`crankdyn.measure.angle.angle_domain` does for the same record.
    """
    n, q = scan.teeth, np.asarray(orders, dtype=float)
    length = cycle_length(cycle_angle, n)
    lay = layout(scan.positions, length, block)
    pitch, K = 2.0 * math.pi / n, scan.positions
    nominal, tooth_origin, _ = (
        mark_numbering(scan.reference_index, scan.reference_period, n)
        if scan.reference_index is not None and scan.reference_period is not None
        else (0.0, 0, 0.0)
    )
    origin = reference_angle - (nominal if kappa is None else kappa) * pitch
    errors = None if tooth_errors is None else np.asarray(tooth_errors, dtype=float)
    # at most K / L whole cycles (and boundaries, and cycles of pulse speeds)
    cyc = _Cycles(
        length, q, cycle_angle, window_cycles, window, tracking, K // length + 2, keep_cycles
    )
    start = end = -1
    first_cycle = np.empty(0)
    for c0, c1, a, t in _block_times(scan, lay):
        pos = positions(t, a, length)
        keep = pos.keep
        v = pos.vibration(pitch)
        if errors is not None:
            v = v + errors[(np.arange(a + pos.s, a + t.size - pos.s) + tooth_origin) % n]
        psi = origin + pos.position * pitch
        theta = origin + pitch * pos.index
        if a == 0:
            start = grid_start(theta, float(psi[0]), cycle_angle, pitch)
            cyc.angle0 = float(theta[start])
            first_cycle = theta[start : start + length].copy()
        if a + t.size == K and end < 0:
            cycles = int((a + np.searchsorted(theta, psi[-1], side="right") - start) // length)
            if cycles < 1:
                raise InputError(
                    "the record holds no whole working cycle after filtering", key="time"
                )
            end = start + cycles * length
        g0, g1 = max(c0, start), (c1 if end < 0 or c1 < end else end)
        if c1 == K:
            g1 = end
        grid = theta[g0 - a : max(g0, g1) - a]
        if grid.size and (
            (a > 0 and grid[0] < psi[2 * MARGIN])
            or (a + t.size < K and grid[-1] > psi[-1 - 2 * MARGIN])
        ):
            raise _too_wide("within a block")
        from scipy.interpolate import CubicSpline, make_interp_spline  # keeps the start-up light

        vibration = make_interp_spline(psi, v, k=5)(grid) if grid.size else np.empty(0)
        # the cycle boundaries in the core (the last one, at the grid's end, with the last core)
        b0 = max(0, -(-(c0 - start) // length))
        b1 = (end - start) // length + 1 if c1 == K else max(b0, -(-(c1 - start) // length))
        if end >= 0:
            b1 = min(b1, (end - start) // length + 1)
        arrival = CubicSpline(origin + pos.index[keep] * pitch, pos.smooth)
        boundary_times = arrival(cyc.angle0 + cycle_angle * np.arange(b0, b1))
        # the pulse speeds over the cycles starting in the core
        s0 = max(0, -(-(c0 - start) // length))
        s1 = -(-(g1 - start) // length) if g1 > start else s0
        speeds = np.empty((0, length))
        if s1 > s0:
            j0 = start + s0 * length
            span = t[j0 - a : j0 - a + (s1 - s0) * length + 1]
            speeds = pulse_speed(span, j0, pitch, errors, tooth_origin).reshape(-1, length)
        cyc.add(vibration, boundary_times, speeds)
    cycles = (end - start) // length
    single, windows, average, envelope = cyc.result(cycles)
    speed = cycle_angle * cycles / (cyc._times(cycles, cycles + 1)[0] - cyc._times(0, 1)[0])
    # crank angle within the cycle (the grid starts at the first tooth after a boundary)
    angles = first_cycle - math.floor(cyc.angle0 / cycle_angle + 1e-9) * cycle_angle
    mean, scatter = single.moments()
    return BlockedAnalysis(
        single.windows(),
        single.speed[: single.count].copy(),
        mean,
        scatter,
        windows,
        cycles,
        length,
        float(speed),
        average,
        angles,
        envelope,
    )
