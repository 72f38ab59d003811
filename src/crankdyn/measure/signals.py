"""Torsiograph signals (domain objects): pulse trains from a toothed wheel or an encoder, and
sampled angular-speed signals.

A *pulse train* is what a torsiograph's counter records (seed 003, "使用LMS QTV进行发动机曲轴扭振
试验": the speed sensor's signal is conditioned, its zero crossings are detected and timed, and the
speed variation is computed from the times; the V6 paper of seed 003 measures the pulley's and
the flywheel's angles with teeth machined on the pulley): the time t_k at which tooth k passes
the sensor, N pulses per revolution, and optionally the times of a once-per-revolution (or
once-per-cycle) reference mark. Between two pulses the shaft turns by one tooth pitch 2 pi / N,
so the record samples the shaft's time-of-arrival t(theta) at equal angles: it is angle-domain
data from the start.

A *speed signal* is an instantaneous angular speed sampled in time (the output of a torsiograph
that already did the zero-crossing work, or of a laser vibrometer); :meth:`SpeedSignal.to_pulses`
integrates it to the shaft angle and returns the times at which the shaft reaches equally spaced
angles, a pulse train of a perfect wheel.

:func:`prepare_pulses` checks a pulse train and repairs it where that is safe: a gap of a whole
number of pulses recurring once per revolution is a missing-tooth wheel (e.g. 60-2), whose gap
marks the revolution; isolated dropped pulses (at most two in a row, at most one in a hundred)
are interpolated; every repair is said in the notes. Anything else (an interval that is neither
one pulse pitch nor a whole number of them, a spurious extra pulse, a reference that does not
divide into the pulse count) is an error naming the line.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError

__all__ = ["PreparedPulses", "PulseTrain", "SpeedSignal", "prepare_pulses"]

GAP_RATIO = 1.5
"""An interval longer than this many times its neighbours' is a gap (missing pulses)."""
SHORT_RATIO = 0.6
"""An interval shorter than this fraction of its neighbours' holds a spurious pulse."""
_WHOLE_TOLERANCE = 0.3  # a gap must be within this many pitches of a whole number of pulses
MAX_DROPPED_RUN = 2
"""Dropped pulses in a row that are interpolated; longer runs are an error."""
MAX_DROPPED_FRACTION = 0.01
"""Largest share of dropped pulses interpolated; more is an error (the record is unreliable)."""
MIN_TEETH = 4
"""The fewest pulses per revolution accepted."""
MAX_PULSES = 1 << 22
"""The most pulses a speed signal is resampled to (:meth:`SpeedSignal.to_pulses`): 4,194,304,
as many values as a signal file may hold (:data:`crankdyn.io.files.MAX_ARRAY_VALUES`); the
angle samples per revolution are checked against the record's revolutions before anything is
allocated."""


def _times(name: str, values: ArrayLike, what: str) -> np.ndarray:
    try:
        arr = np.array(values, dtype=float, copy=True)
    except (TypeError, ValueError):
        raise InputError(f"expected {what} as numbers", key=name) from None
    arr = np.atleast_1d(arr)
    if arr.ndim != 1:
        raise InputError(f"expected one column of {what}", key=name)
    bad = ~np.isfinite(arr)
    if np.any(bad):
        raise InputError(f"{what} must be finite", key=name, value=float(arr[bad][0]))
    arr.setflags(write=False)
    return arr


def check_teeth(teeth: object) -> int:
    """The pulses per revolution of a wheel, checked: a whole number >= :data:`MIN_TEETH`.

    Parameters
    ----------
    teeth : object
        The value given (int or numpy integer).

    Returns
    -------
    int
        ``teeth`` as an int.

    Raises
    ------
    InputError
        For anything else (``key="teeth"``).
    """
    if isinstance(teeth, bool) or not isinstance(teeth, (int, np.integer)):
        raise InputError(
            "expected a whole number of pulses per revolution", key="teeth", value=teeth
        )
    if teeth < MIN_TEETH:
        raise InputError(
            f"at least {MIN_TEETH} pulses per revolution are needed", key="teeth", value=int(teeth)
        )
    return int(teeth)


def sample_place(lines: ArrayLike | None, index: int, offset: int = 0) -> str:
    """Where a sample of a record is, for messages.

    Parameters
    ----------
    lines : array_like or None
        The file line of every sample of this part of the record, or None.
    index : int
        The sample, counted from this part's start.
    offset : int
        The record's index of this part's first sample.

    Returns
    -------
    str
        ``"line L"`` when the file's line numbers are known, else ``"sample i"`` (1-based,
        counted from the record's start).
    """
    if lines is not None and 0 <= index < np.size(lines):
        return f"line {int(np.asarray(lines)[index])}"
    return f"sample {offset + index + 1}"


def check_increasing(
    times: np.ndarray,
    lines: ArrayLike | None = None,
    *,
    key: str = "time",
    file: str | None = None,
    offset: int = 0,
) -> None:
    """Raise one line naming the first time that does not increase.

    Parameters
    ----------
    times : numpy.ndarray
        Times (s), 1-D.
    lines : array_like or None
        The file line of every time (for the message), or None (then the sample is counted).
    key : str
        The column the times come from, for the message; default ``"time"``.
    file : str or None
        The file (or source) for the message.
    offset : int
        The record's index of ``times[0]`` (a part of a record read in chunks), for the
        sample counted in the message; default 0.

    Raises
    ------
    InputError
        At the first time not above the one before.
    """
    step = np.diff(times)
    bad = np.flatnonzero(~(step > 0.0))
    if bad.size:
        i = int(bad[0]) + 1
        raise InputError(
            f"times must increase: {sample_place(lines, i, offset)} has {times[i]:.9g} s after "
            f"{times[i - 1]:.9g} s",
            file=file,
            key=key,
            value=float(times[i]),
        )


@dataclass(frozen=True, eq=False)
class PulseTrain:
    """Pulse times of a toothed wheel or an encoder (module docstring).

    Parameters
    ----------
    times : array_like
        Times of the pulses (s), strictly increasing: one per tooth passing the sensor.
    teeth : int
        Pulses per revolution N of a complete wheel (for a missing-tooth wheel such as 60-2,
        the number of tooth positions, 60), >= 4.
    reference : array_like or None
        Times (s) of a once-per-revolution or once-per-cycle reference mark, or None.
    source : str
        Where the signal came from (for messages and titles).
    lines : array_like or None
        The file line of every pulse (for messages), or None.
    reference_lines : array_like or None
        The file line of every reference time, or None.

    Raises
    ------
    InputError
        If ``teeth`` is not a whole number >= 4, there are fewer than two pulses, or a time is
        not a finite number or does not increase.

    Examples
    --------
    A steady 10 rev/s on a 60-tooth wheel for 0.1 s:

    >>> train = PulseTrain(np.arange(61) / 600.0, 60)
    >>> round(train.duration, 12)
    0.1
    """

    times: np.ndarray
    teeth: int
    reference: np.ndarray | None = None
    source: str = "signal"
    lines: np.ndarray | None = field(default=None, repr=False)
    reference_lines: np.ndarray | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "teeth", check_teeth(self.teeth))
        times = _times("time", self.times, "pulse times")
        if times.size < 2:
            raise InputError("the signal holds fewer than two pulses", file=self.source)
        check_increasing(times, self.lines, file=self.source)
        object.__setattr__(self, "times", times)
        if self.reference is not None:
            ref = _times("reference", self.reference, "reference times")
            if ref.size:
                check_increasing(ref, self.reference_lines, key="reference", file=self.source)
            object.__setattr__(self, "reference", ref if ref.size else None)

    @property
    def duration(self) -> float:
        """Time from the first to the last pulse (s)."""
        return float(self.times[-1] - self.times[0])


@dataclass(frozen=True, eq=False)
class SpeedSignal:
    """An instantaneous angular speed sampled in time (module docstring).

    Parameters
    ----------
    times : array_like
        Sample times (s), strictly increasing (a constant rate is usual, not required).
    speed : array_like
        Angular speed of the shaft at those times (rad/s), > 0.
    reference : array_like or None
        Times (s) of a once-per-revolution or once-per-cycle reference mark, or None.
    source, lines, reference_lines
        As for :class:`PulseTrain`.

    Raises
    ------
    InputError
        If there are fewer than four samples, not one speed per time, a value is not finite,
        a time does not increase or a speed is not positive.

    Examples
    --------
    10 rev/s sampled at 1 kHz: 100 samples per revolution; as a perfect 60-tooth wheel, one
    pulse every 1/600 s.

    >>> sig = SpeedSignal(np.arange(100) / 1000.0, np.full(100, 20 * np.pi))
    >>> round(sig.samples_per_revolution(), 9), sig.default_teeth()
    (100.0, 128)
    >>> pulses = sig.to_pulses(60)
    >>> pulses.times.size, round(float(pulses.times[1]) * 600, 9)
    (60, 1.0)
    """

    times: np.ndarray
    speed: np.ndarray
    reference: np.ndarray | None = None
    source: str = "signal"
    lines: np.ndarray | None = field(default=None, repr=False)
    reference_lines: np.ndarray | None = field(default=None, repr=False)

    def __post_init__(self) -> None:
        times = _times("time", self.times, "sample times")
        speed = _times("speed", self.speed, "speeds")
        if times.size != speed.size:
            raise InputError("expected one speed per sample time", key="speed", file=self.source)
        if times.size < 4:
            raise InputError("the signal holds fewer than four samples", file=self.source)
        check_increasing(times, self.lines, file=self.source)
        bad = np.flatnonzero(~(speed > 0.0))
        if bad.size:
            raise InputError(
                f"the speed must be positive: {sample_place(self.lines, int(bad[0]))}",
                file=self.source,
                key="speed",
                value=float(speed[bad[0]]),
            )
        object.__setattr__(self, "times", times)
        object.__setattr__(self, "speed", speed)
        if self.reference is not None:
            ref = _times("reference", self.reference, "reference times")
            if ref.size:
                check_increasing(ref, self.reference_lines, key="reference", file=self.source)
            object.__setattr__(self, "reference", ref if ref.size else None)

    def samples_per_revolution(self) -> float:
        """Samples per revolution at the highest speed (the signal's own angular resolution).

        Returns
        -------
        float
            2 pi f_s / max(omega) (dimensionless), f_s the median sample rate.
        """
        rate = 1.0 / np.median(np.diff(self.times))
        return float(rate * 2.0 * math.pi / np.max(self.speed))

    def default_teeth(self) -> int:
        """Angle samples per revolution for :meth:`to_pulses` when none is given.

        Returns
        -------
        int
            The power of two at or above the signal's own samples per revolution, at least 64.
        """
        return max(64, 1 << math.ceil(math.log2(max(self.samples_per_revolution(), 1.0))))

    def to_pulses(self, teeth: int | None = None) -> PulseTrain:
        """The times at which the shaft reaches the angles 2 pi k / N (a perfect wheel).

        The angle is the integral of the speed, theta(t) = int omega dt, of the cubic spline
        through the samples (not-a-knot ends; error O(h^4) for a smooth speed: C. de Boor,
        *A Practical Guide to Splines*, rev. ed., Springer 2001, ch. IV and V); the pulse times
        solve theta(t_k) = 2 pi k / N by Newton's method on that spline (theta' = omega > 0,
        so the root is unique).

        Parameters
        ----------
        teeth : int or None
            Angle samples per revolution N (default :meth:`default_teeth`).

        Returns
        -------
        PulseTrain
            The times (s) at which the shaft reaches 2 pi k / N, k = 0, 1, ..., with this
            signal's reference and source.

        Raises
        ------
        InputError
            If N is below :data:`MIN_TEETH`, or the record's revolutions at N angles each make
            more than :data:`MAX_PULSES` pulses (``key="teeth"``, checked before anything is
            allocated; the message gives the largest N this record takes).
        """
        n = self.default_teeth() if teeth is None else int(teeth)
        if n < MIN_TEETH:
            raise InputError(
                f"at least {MIN_TEETH} angle samples per revolution are needed",
                file=self.source,
                key="teeth",
                value=n,
            )
        from scipy.interpolate import CubicSpline  # imported here: keeps the start-up light

        spline = CubicSpline(self.times, self.speed)
        angle = spline.antiderivative()
        theta = angle(self.times)
        if np.any(np.diff(theta) <= 0.0):  # pragma: no cover - a positive speed integrates up
            raise InputError("the integrated angle does not increase", file=self.source)
        revolutions = float(theta[-1]) / (2.0 * math.pi)
        if revolutions * n >= MAX_PULSES:
            raise InputError(
                f"the record's {revolutions:.4g} revolutions at {n:,} angle samples each make "
                f"{revolutions * n:,.0f} pulses; crankdyn resamples a speed signal to at most "
                f"{MAX_PULSES:,} (this record takes at most "
                f"{max(math.floor((MAX_PULSES - 1) / revolutions), 0):,} per revolution)",
                file=self.source,
                key="teeth",
                value=n,
            )
        count = math.floor(theta[-1] * n / (2.0 * math.pi) + 1e-9) + 1
        target = 2.0 * math.pi * np.arange(count) / n
        t = np.interp(target, theta, self.times)
        with np.errstate(divide="ignore", invalid="ignore"):
            for _ in range(4):
                t = np.clip(t - (angle(t) - target) / spline(t), self.times[0], self.times[-1])
        return PulseTrain(t, n, reference=self.reference, source=self.source)


# ---- checks and repairs of a pulse train --------------------------------------------------------
@dataclass(frozen=True, eq=False)
class PreparedPulses:
    """A pulse train with every tooth position accounted for (:func:`prepare_pulses`).

    Parameters
    ----------
    times : numpy.ndarray
        ``times[k]`` the time (s) of tooth position k (0, 1, ...) counted from the first pulse,
        interpolated where ``filled[k]``.
    filled : numpy.ndarray
        Bool, per tooth position: its time is interpolated (a dropped pulse or a missing
        tooth).
    teeth : int
        Tooth positions per revolution N.
    reference_index : numpy.ndarray or None
        The (fractional) tooth position of every reference mark: of ``reference_times`` within
        the record, or of the first tooth after each gap of a missing-tooth wheel; None without
        a mark.
    reference_times : numpy.ndarray or None
        The reference times (s) within the record; None without a reference signal (also for
        a missing-tooth wheel, whose gap is the mark).
    reference_period : int or None
        Tooth positions between marks (N or 2N), or None without a mark.
    missing_tooth : bool
        The wheel has missing teeth (e.g. 60-2).
    notes : tuple of str
        What was repaired or assumed.
    """

    times: NDArray[np.float64]
    filled: NDArray[np.bool_]
    teeth: int
    reference_index: NDArray[np.float64] | None
    reference_times: NDArray[np.float64] | None
    reference_period: int | None
    missing_tooth: bool
    notes: tuple[str, ...]


def _local_intervals(d: np.ndarray) -> np.ndarray:
    """A running median of the pulse intervals (9 intervals), the interval expected at each."""
    if d.size < 9:
        return np.full_like(d, np.median(d))
    from scipy.ndimage import median_filter  # imported here: keeps the start-up light

    return median_filter(d, size=9, mode="nearest")


def interval_ratios(times: np.ndarray) -> np.ndarray:
    """Every pulse interval over the running median of its neighbours' (dimensionless): 1 for a
    regular pulse, about m + 1 after m dropped pulses, below 1 before a spurious one.

    Parameters
    ----------
    times : numpy.ndarray
        Pulse times (s), increasing.

    Returns
    -------
    numpy.ndarray
        ``times.size - 1`` ratios. Each depends on the four intervals either side only (the
        record's ends repeat their interval), so a part of a record with four intervals of
        context on either side gives the ratios of the whole.
    """
    d = np.diff(times)
    return d / _local_intervals(d)


@dataclass(frozen=True)
class IntervalFaults:
    """The intervals of a pulse record that are not one pitch (:func:`interval_faults`).

    Parameters
    ----------
    short : numpy.ndarray
        Indices of the intervals shorter than :data:`SHORT_RATIO` of their neighbours'.
    gaps : numpy.ndarray
        Indices of the intervals longer than :data:`GAP_RATIO` of their neighbours'.
    missing : numpy.ndarray
        The pulses missing in each gap (int).
    off : numpy.ndarray
        Per gap: its length is not within a tolerance of a whole number of pitches (bool).
    """

    short: NDArray[np.intp]
    gaps: NDArray[np.intp]
    missing: NDArray[np.int_]
    off: NDArray[np.bool_]


def interval_faults(ratio: np.ndarray) -> IntervalFaults:
    """The short intervals and the gaps among interval ratios (:func:`interval_ratios`).

    Parameters
    ----------
    ratio : numpy.ndarray
        Pulse intervals over their neighbours' (dimensionless).

    Returns
    -------
    IntervalFaults
        Indices into ``ratio`` and the pulses missing in each gap.
    """
    short = np.flatnonzero(ratio < SHORT_RATIO)
    gaps = np.flatnonzero(ratio > GAP_RATIO)
    missing = np.round(ratio[gaps]).astype(int) - 1
    off = np.abs(ratio[gaps] - np.round(ratio[gaps])) > _WHOLE_TOLERANCE
    return IntervalFaults(short, gaps, missing, off)


def spurious_pulse(where: str, ratio: float, time: float, name: str) -> InputError:
    """The error of a spurious pulse: the interval ending at ``where`` (``"line 12"``) is
    ``ratio`` of its neighbours'; ``time`` (s) is the pulse's.

    Parameters
    ----------
    where, ratio, time, name
        The place, the interval ratio (dimensionless), the pulse time (s), the file.

    Returns
    -------
    InputError
        The one-line error.
    """
    return InputError(
        f"a spurious pulse: the interval ending at {where} is {ratio:.2f} "
        "of its neighbours' (a double trigger or noise); clean the signal",
        file=name,
        key="time",
        value=time,
    )


def odd_interval(where: str, ratio: float, time: float, name: str) -> InputError:
    """The error of an interval neither one pitch nor a whole number of them.

    Parameters
    ----------
    where, ratio, time, name
        The place of the pulse ending it, the interval ratio (dimensionless), the pulse time
        (s), the file.

    Returns
    -------
    InputError
        The one-line error.
    """
    return InputError(
        f"the interval ending at {where} is {ratio:.2f} times its "
        "neighbours': neither one pulse pitch nor a whole number of them (is the speed "
        "steady enough for this wheel?)",
        file=name,
        key="time",
        value=time,
    )


def long_run(count: int, where: str, time: float, name: str) -> InputError:
    """The error of ``count`` > :data:`MAX_DROPPED_RUN` pulses missing in a row before
    ``where`` (the pulse at ``time``, s).

    Parameters
    ----------
    count, where, time, name
        The pulses missing, the place, the time (s) and the file.

    Returns
    -------
    InputError
        The one-line error.
    """
    return InputError(
        f"{count} pulses are missing before {where}: too many in a row to interpolate safely",
        file=name,
        key="time",
        value=time,
    )


def too_many_dropped(total: int, where: str, name: str) -> InputError:
    """The error of ``total`` dropped pulses, more than :data:`MAX_DROPPED_FRACTION` of the
    record (the first before ``where``).

    Parameters
    ----------
    total, where, name
        The pulses missing, the place of the first gap, the file.

    Returns
    -------
    InputError
        The one-line error.
    """
    return InputError(
        f"{total} pulses are missing (first before {where}):"
        f" more than {MAX_DROPPED_FRACTION:.1%} of the record, too many to "
        "interpolate safely",
        file=name,
        key="time",
    )


def missing_tooth_note(missing: int, teeth: int) -> str:
    """The note on a wheel with ``missing`` teeth of ``teeth`` (a 60-2 wheel).

    Parameters
    ----------
    missing, teeth
        The teeth missing in the gap and the wheel's tooth positions.

    Returns
    -------
    str
        The note.
    """
    return (
        f"a gap of {missing} pulse{'s' if missing > 1 else ''} every revolution: "
        f"a {teeth}-{missing} wheel; the gap marks the revolution and the missing "
        "pulses are interpolated"
    )


def dropped_note(total: int, places: list[str], gaps: int) -> str:
    """The note on ``total`` dropped pulses interpolated, in ``gaps`` gaps, the first five
    before ``places``.

    Parameters
    ----------
    total, places, gaps
        The pulses, the places of the first (up to five) gaps, the gaps.

    Returns
    -------
    str
        The note.
    """
    more = f" and {gaps - 5} more" if gaps > 5 else ""
    return (
        f"{total} dropped pulse{'s' if total > 1 else ''} (before {', '.join(places)}{more}) "
        "interpolated"
    )


def regular_gaps(missing: np.ndarray, start: np.ndarray, teeth: int) -> bool:
    """Whether gaps make a missing-tooth wheel: at least two, all of the same number of pulses
    (fewer than a quarter of the wheel), one revolution apart.

    Parameters
    ----------
    missing : numpy.ndarray
        The pulses missing in each gap.
    start : numpy.ndarray
        The tooth position of the pulse before each gap.
    teeth : int
        Tooth positions per revolution.

    Returns
    -------
    bool
        True for a missing-tooth wheel.
    """
    return bool(
        missing.size >= 2
        and np.all(missing == missing[0])
        and np.all(np.diff(start) == teeth)
        and missing[0] < teeth // 4
    )


def fill_gaps(index: np.ndarray, times: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The time of every tooth position from the recorded pulses' (module docstring): a
    quintic spline through (tooth position, time) at the positions without a pulse.

    Parameters
    ----------
    index : numpy.ndarray
        The tooth position of every recorded pulse (int, increasing; the first is the origin).
    times : numpy.ndarray
        Their times (s).

    Returns
    -------
    times : numpy.ndarray
        The time (s) of tooth positions ``index[0]`` .. ``index[-1]``.
    filled : numpy.ndarray
        Bool per tooth position: interpolated.
    """
    full = np.arange(index[0], index[-1] + 1)
    filled = np.ones(full.size, dtype=bool)
    filled[index - index[0]] = False
    if np.any(filled):
        out = np.empty(full.size)
        out[index - index[0]] = times
        from scipy.interpolate import make_interp_spline  # imported here: keeps the start-up light

        out[filled] = make_interp_spline(index, times, k=5)(full[filled])
    else:
        out = times.copy()
    return out, filled


def prepare_pulses(train: PulseTrain) -> PreparedPulses:
    """Check a pulse train for gaps and spurious pulses, repair what is safe (module docstring),
    and locate the reference marks among the tooth positions.

    Dropped pulses and missing teeth are interpolated by a quintic spline through the recorded
    times against tooth position; a reference's tooth position by a cubic spline in time.

    Parameters
    ----------
    train : PulseTrain
        The recorded pulses.

    Returns
    -------
    PreparedPulses
        The time (s) of every tooth position, which are filled in, and the reference marks'
        tooth positions.

    Raises
    ------
    InputError
        One line naming the file line: a spurious pulse, an interval that is not a whole number
        of pitches, too many or too long runs of dropped pulses, or references that do not fall
        every N (or 2N) tooth positions.

    Examples
    --------
    Four revolutions of a 60-2 wheel at 10 rev/s: three gaps of two pulses, each marking the
    revolution (the last one is past the end of the record).

    >>> t = np.arange(240) / 600.0
    >>> prepared = prepare_pulses(PulseTrain(t[np.arange(240) % 60 < 58], 60))
    >>> prepared.missing_tooth, int(prepared.filled.sum()), prepared.reference_period
    (True, 6, 60)
    >>> prepared.reference_index.tolist()
    [60.0, 120.0, 180.0]
    """
    t, n, lines, name = train.times, train.teeth, train.lines, train.source
    ratio = interval_ratios(t)
    faults = interval_faults(ratio)
    if faults.short.size:
        i = int(faults.short[0]) + 1
        raise spurious_pulse(sample_place(lines, i), ratio[i - 1], float(t[i]), name)
    gaps, missing = faults.gaps, faults.missing
    if np.any(faults.off):
        j = int(gaps[np.argmax(faults.off)])
        raise odd_interval(sample_place(lines, j + 1), ratio[j], float(t[j + 1]), name)
    # tooth position of every recorded pulse
    step = np.ones(t.size - 1, dtype=int)
    step[gaps] += missing
    index = np.concatenate([[0], np.cumsum(step)])
    notes: list[str] = []
    missing_tooth = False
    if gaps.size:
        if regular_gaps(missing, index[gaps], n):
            missing_tooth = True
            notes.append(missing_tooth_note(int(missing[0]), n))
        else:
            if np.any(missing > MAX_DROPPED_RUN):
                j = int(gaps[np.argmax(missing > MAX_DROPPED_RUN)])
                count = int(missing[np.argmax(missing > MAX_DROPPED_RUN)])
                raise long_run(count, sample_place(lines, j + 1), float(t[j + 1]), name)
            total = int(np.sum(missing))
            if total > max(1.0, MAX_DROPPED_FRACTION * t.size):
                raise too_many_dropped(total, sample_place(lines, int(gaps[0]) + 1), name)
            places = [sample_place(lines, int(g) + 1) for g in gaps[:5]]
            notes.append(dropped_note(total, places, int(gaps.size)))
    times, filled = fill_gaps(index, t)
    ref_index, ref_times, period = _reference(
        train, times, index, gaps, missing, missing_tooth, notes
    )
    times.setflags(write=False)
    filled.setflags(write=False)
    return PreparedPulses(
        times, filled, n, ref_index, ref_times, period, missing_tooth, tuple(notes)
    )


def _reference(
    train: PulseTrain,
    times: np.ndarray,
    index: np.ndarray,
    gaps: np.ndarray,
    missing: np.ndarray,
    missing_tooth: bool,
    notes: list[str],
) -> tuple[np.ndarray | None, np.ndarray | None, int | None]:
    """Fractional tooth positions of the references, checked to fall every N or 2N positions."""
    n, name = train.teeth, train.source
    ref = train.reference
    if ref is None:
        if missing_tooth:
            # the first tooth after each gap is the mark
            first = index[gaps] + missing + 1
            return first.astype(float), None, n
        return None, None, None
    inside = (ref >= times[0]) & (ref <= times[-1])
    kept = ref[inside]
    lines = None if train.reference_lines is None else np.asarray(train.reference_lines)[inside]
    if kept.size == 0:
        raise InputError(
            "no reference time falls within the pulse record", file=name, key="reference"
        )
    kappa = reference_positions(times, 0, kept)
    return check_marks(kappa, kept, lines, n, name)


def reference_positions(times: np.ndarray, first: int, marks: np.ndarray) -> np.ndarray:
    """The fractional tooth positions of reference marks: a cubic spline of the tooth position
    through the times of the tooth positions, at the marks' times (linear interpolation would
    err by theta'' dt^2 / 8: 1 mrad for 20 mrad of order 6 on a 60-tooth wheel).

    Parameters
    ----------
    times : numpy.ndarray
        The times (s) of consecutive tooth positions ``first``, ``first + 1``, ...
    first : int
        The tooth position of ``times[0]``.
    marks : numpy.ndarray
        The marks' times (s), within ``times``.

    Returns
    -------
    numpy.ndarray
        Their tooth positions (fractional). The spline's dependence on a tooth's time decays by
        2 - sqrt(3) = 0.27 per position, so a part of the record reaching 64 positions beyond
        the marks either way gives the positions of the whole to rounding.
    """
    from scipy.interpolate import CubicSpline  # imported here: keeps the start-up light

    position = np.arange(first, first + times.size, dtype=float)
    return np.asarray(CubicSpline(times, position)(marks))


def check_marks(
    kappa: np.ndarray, kept: np.ndarray, lines: np.ndarray | None, n: int, name: str
) -> tuple[np.ndarray, np.ndarray, int]:
    """The reference marks' tooth positions checked to fall every N or 2N positions.

    Parameters
    ----------
    kappa : numpy.ndarray
        The marks' tooth positions (fractional, :func:`reference_positions`).
    kept : numpy.ndarray
        Their times (s).
    lines : numpy.ndarray or None
        Their file lines, for the messages.
    n : int
        Tooth positions per revolution.
    name : str
        The file, for the messages.

    Returns
    -------
    tuple of (numpy.ndarray, numpy.ndarray, int)
        ``kappa``, ``kept`` and the tooth positions between marks (N or 2N).

    Raises
    ------
    InputError
        When the marks are not N or 2N positions apart (naming the lines).
    """
    if kept.size == 1:
        return kappa, kept, n
    spacing = np.diff(kappa)
    per = float(np.median(spacing)) / n
    c = round(per)
    if c not in (1, 2) or abs(per - c) * n > 0.5:
        raise InputError(
            f"there are {np.median(spacing):.1f} pulses per reference mark, which --teeth {n} does "
            "not divide into whole revolutions (wrong --teeth, or a wheel with missing teeth?)",
            file=name,
            key="reference",
        )
    bad = np.flatnonzero(np.abs(spacing - c * n) > 0.5)
    if bad.size:
        j = int(bad[0])
        where = (
            f"lines {int(lines[j])} and {int(lines[j + 1])}"
            if lines is not None
            else f"{kept[j]:.6g} s and {kept[j + 1]:.6g} s"
        )
        raise InputError(
            f"{spacing[j]:.1f} pulses between the references at {where}, expected {c * n}: "
            "dropped or extra pulses, or a wrong --teeth",
            file=name,
            key="reference",
            value=float(kept[j + 1]),
        )
    return kappa, kept, c * n
