"""Angle-domain processing of a pulse train (numeric core): mean rotation, angular vibration,
tooth-spacing correction and resampling to the crank angle.

The shaft's angle is theta(t) = psi(t) + v(t): a smooth *mean rotation* psi (the speed trend of
a steady run, a run-up or a run-down) and the *angular vibration* v, a sum of engine orders
(multiples of 0.5 of the crank speed for a four-stroke engine). A pulse train gives the times
t_k at which theta = theta_k, the tooth angles, equally spaced by 2 pi / N.

1. **Mean rotation.** t(theta) sampled at equal angles is the smooth time-of-arrival of the mean
   rotation plus a part periodic in the working cycle (the vibration) plus the tooth-spacing
   errors (periodic in the revolution). The mean over exactly one cycle (L = N x revolutions per
   cycle samples, the end samples weighted 1/2 when L is even so that the window is centred) is
   zero for every order of the cycle and keeps a straight line; applied twice as
   ``2 M - M M`` ("twicing": J. W. Tukey, *Exploratory Data Analysis*, Addison-Wesley 1977,
   ch. 16) it keeps every cubic too, so the speed trend of a run-up passes unchanged while all
   orders are removed exactly. Applied twice, it also removes orders modulated linearly, as the
   speed's changes modulate them (:func:`mean_rotation_times`). Each pass needs one cycle on
   either side: the first and the last two cycles of a record are not analysed.
2. **Angular vibration.** psi = P(t) is the inverse of that smooth time-of-arrival (a cubic
   spline through (t_bar_k, theta_k), monotone because the mean speed is positive). At each
   pulse v_k = theta_k - P(t_k) exactly: no linearisation in the vibration amplitude.
3. **Resampling to the crank angle.** The samples v_k sit at psi_k = theta_k - v_k, not at equal
   angles; a quintic spline through (psi_k, v_k) gives v at the equally spaced crank angles of
   the teeth, psi_j = theta_j (0 at the reference mark's crank angle), each sample moved by v
   only (the interpolation error of a spline grows with the fraction of a pitch a sample is
   moved and with the order's share of the Nyquist order; de Boor 2001, ch. XII). Analysing v
   at theta_k instead (the shortcut of taking the tooth angles as the crank angles) errs by
   v v', which is
   q A / 2 of the amplitude A of order q: 6 % for 20 mrad at order 6. This is the computed
   order tracking of K. R. Fyfe and E. D. S. Munck, "Analysis of computed order tracking",
   *Mechanical Systems and Signal Processing* 11 (1997) 187-205, with the mean rotation as the
   tachometer (the vibration itself must not be the reference it is sampled against).
4. **Tooth-spacing errors.** A tooth k placed at 2 pi k / N + e_j (j = k mod N) makes the
   record read v - e_j. Their pattern is the mean over whole revolutions of v at each tooth
   position, less its mean; it is exact for the wheel when the vibration's content periodic in
   one revolution (its integer orders) averages out over the revolutions used (a calibration
   run with little vibration: a coast-down with the ignition off, or a motored run). Half
   orders of a four-stroke engine cancel over an even number of revolutions always; integer
   orders and tooth errors cannot be told apart in one steady record (docs/measurement.md).
5. **Instantaneous speed** at the measured point: the tooth pitch over the pulse interval,
   omega_k = (2 pi / N + e_(k+1) - e_k) / (t_(k+1) - t_k), the torsiograph's classical output.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError
from crankdyn.measure.signals import PreparedPulses

__all__ = [
    "AngleDomain",
    "angle_domain",
    "cycle_mean",
    "mean_rotation_times",
    "tooth_pattern",
]


def cycle_mean(x: ArrayLike, length: int) -> tuple[NDArray[np.float64], int]:
    """Centred mean of ``x`` over exactly ``length`` samples (one period).

    For an even length the window spans length + 1 samples with the two end samples weighted
    1/2 (the trapezoidal rule over one period, which sums each residue once for a periodic
    sequence); for an odd length it spans length samples. Either way every harmonic of the
    period is removed exactly and a straight line is kept.

    Parameters
    ----------
    x : array_like
        Samples at equal spacing (any unit).
    length : int
        Samples per period L, >= 2.

    Returns
    -------
    mean : numpy.ndarray
        The means at the samples h .. n-1-h (x's unit).
    h : int
        The half-width, L // 2.

    Examples
    --------
    A harmonic of the period goes, a straight line stays:

    >>> k = np.arange(40.0)
    >>> m, h = cycle_mean(2.0 + 0.5 * k + np.sin(2 * np.pi * k / 8), 8)
    >>> h, m.size, bool(np.allclose(m, 2.0 + 0.5 * k[h : 40 - h]))
    (4, 32, True)
    """
    x = np.asarray(x, dtype=float)
    h = length // 2
    s = np.concatenate([[0.0], np.cumsum(x)])
    n = x.size
    centre = np.arange(h, n - h)
    if length % 2:
        total = s[centre + h + 1] - s[centre - h]
    else:
        total = s[centre + h] - s[centre - h + 1] + 0.5 * (x[centre - h] + x[centre + h])
    return total / length, h


def _twice(x: np.ndarray, length: int) -> tuple[np.ndarray, int]:
    """``2 M(x) - M(M(x))`` at the samples s .. n-1-s, and s."""
    m1, h = cycle_mean(x, length)
    m2, _ = cycle_mean(m1, length)
    return 2.0 * m1[h : m1.size - h] - m2, 2 * h


def mean_rotation_times(times: ArrayLike, length: int) -> tuple[NDArray[np.float64], int]:
    """The smooth time-of-arrival t_bar of the mean rotation at every tooth position (s).

    F = 2 M - M M (module docstring, step 1) applied twice. One pass keeps cubics and removes
    every order exactly while the speed is steady; but the vibration enters the time of arrival
    as -v / Omega, and while the speed changes the factor 1/Omega modulates every order. F has
    a simple zero at each order, so a linearly modulated order leaks a part of relative size
    (dOmega/dpsi) / (q Omega) in quadrature (0.4 % of order 0.5 at 500 rpm/s and 1600 rpm); F F
    has double zeros, which remove the linear modulation too, and still keeps cubics. The
    straight line through the ends is taken out first and put back after, so that the running
    sums hold small numbers.

    Parameters
    ----------
    times : array_like
        The time t_k of every tooth position (s), gaps filled.
    length : int
        Tooth positions per working cycle L.

    Returns
    -------
    t_bar : numpy.ndarray
        t_bar at the tooth positions s .. n-1-s (s).
    s : int
        The offset (two cycles for even L: each pass of F uses up one cycle at either end).

    Examples
    --------
    A cubic time-of-arrival (a run-up) plus a harmonic of the cycle (L = 8): the cubic comes
    back to rounding.

    >>> k = np.arange(200.0)
    >>> smooth = 1e-3 * k + 2e-9 * k**3
    >>> t_bar, s = mean_rotation_times(smooth + 1e-5 * np.sin(2 * np.pi * k / 8 + 0.3), 8)
    >>> s, bool(np.max(np.abs(t_bar - smooth[s : 200 - s])) < 1e-15)
    (16, True)
    """
    t = np.asarray(times, dtype=float)
    n = t.size
    k = np.arange(n, dtype=float)
    slope = (t[-1] - t[0]) / (n - 1)
    line = t[0] + slope * k
    first, s1 = _twice(t - line, length)
    second, s2 = _twice(first, length)
    s = s1 + s2
    return second + line[s : n - s], s


def tooth_pattern(
    v: NDArray[np.float64], tooth: NDArray[np.int_], teeth: int
) -> tuple[NDArray[np.float64], int]:
    """The tooth-spacing pattern of a record (module docstring, step 4).

    Parameters
    ----------
    v : numpy.ndarray
        Angular vibration at the pulses (rad).
    tooth : numpy.ndarray
        The tooth number of every pulse (integers, taken modulo ``teeth``).
    teeth : int
        Teeth N.

    Returns
    -------
    pattern : numpy.ndarray
        (N,) mean of v at each tooth position over the whole revolutions of the record, less
        its mean over the teeth (rad).
    revolutions : int
        The revolutions averaged, an even number so that half orders cancel.

    Raises
    ------
    InputError
        If the record holds fewer than two whole revolutions.

    Examples
    --------
    >>> v = np.tile([0.01, -0.01, 0.0, 0.0], 4) + 0.5
    >>> pattern, revolutions = tooth_pattern(v, np.arange(16), 4)
    >>> [round(float(p), 12) for p in pattern], revolutions
    ([0.01, -0.01, 0.0, 0.0], 4)
    """
    revolutions = (v.size // teeth) // 2 * 2
    if revolutions < 2:
        raise InputError("at least two whole revolutions are needed for the tooth correction")
    use = revolutions * teeth
    pattern = np.zeros(teeth)
    np.add.at(pattern, tooth[:use] % teeth, v[:use])
    pattern /= revolutions
    return pattern - pattern.mean(), revolutions


@dataclass(frozen=True, eq=False)
class AngleDomain:
    """Angular vibration resampled to equal crank angles (module docstring).

    Parameters
    ----------
    angle : numpy.ndarray
        The crank angles psi_j of the tooth positions (rad; 0 at the reference crank angle),
        equally spaced by 2 pi / N, over whole cycles only, from the first tooth at or after a
        cycle boundary.
    vibration : numpy.ndarray
        v(psi_j) (rad).
    times : numpy.ndarray
        The times of the mean rotation at those angles (s).
    boundary_times : numpy.ndarray
        The times of the mean rotation at the cycle boundaries (s), cycles + 1 values.
    samples_per_cycle : int
        L, tooth positions per working cycle.
    teeth : int
        Teeth N.
    tooth_errors : numpy.ndarray or None
        The tooth errors e_j applied (rad, N values, numbered from the mark), or None.
    pulse_angle : numpy.ndarray
        Crank angle psi_k of every analysed pulse (rad), for plots.
    pulse_vibration : numpy.ndarray
        v_k at those pulses (rad).
    pulse_speed_angle : numpy.ndarray
        Crank angles at the middles of the pulse intervals (rad).
    pulse_speed : numpy.ndarray
        The instantaneous speed over every pulse interval (rad/s), module docstring step 5.
    """

    angle: NDArray[np.float64]
    vibration: NDArray[np.float64]
    times: NDArray[np.float64]
    boundary_times: NDArray[np.float64]
    samples_per_cycle: int
    teeth: int
    tooth_errors: NDArray[np.float64] | None
    pulse_angle: NDArray[np.float64]
    pulse_vibration: NDArray[np.float64]
    pulse_speed_angle: NDArray[np.float64]
    pulse_speed: NDArray[np.float64]

    @property
    def cycles(self) -> int:
        """Whole working cycles resampled."""
        return self.angle.size // self.samples_per_cycle


class Marks(Protocol):
    """Where a record's reference marks sit (:class:`~crankdyn.measure.signals.PreparedPulses`,
    or :class:`~crankdyn.measure.scan.ScannedRecord` for a record read in chunks)."""

    @property
    def teeth(self) -> int:
        """Tooth positions per revolution N."""

    @property
    def reference_index(self) -> NDArray[np.float64] | None:
        """The fractional tooth position of every mark, or None."""

    @property
    def reference_times(self) -> NDArray[np.float64] | None:
        """The marks' times (s), or None (a missing-tooth wheel's gaps)."""

    @property
    def reference_period(self) -> int | None:
        """Tooth positions between marks, or None."""


def tooth_numbering(prep: Marks) -> tuple[float, int, float]:
    """Where the reference mark sits among the tooth positions of a prepared pulse train.

    Returns (kappa_0, tooth_origin, fraction): the fractional tooth position of the first mark
    (the mean over every mark of its position less a whole number of periods), the number of
    tooth position 0 when the teeth are numbered from the mark (tooth 0 the first at or after
    it), and the fraction of a pitch from the mark to tooth 0. Without a mark: (0, 0, 0)."""
    if prep.reference_index is None or prep.reference_period is None:
        return 0.0, 0, 0.0
    return mark_numbering(prep.reference_index, prep.reference_period, prep.teeth)


def mark_numbering(positions: np.ndarray, period: int, teeth: int) -> tuple[float, int, float]:
    """(kappa_0, tooth_origin, fraction) of marks at tooth ``positions`` every ``period``
    positions (:func:`tooth_numbering`)."""
    m = np.arange(positions.size)
    kappa = float(np.mean(positions - period * m))
    first = math.ceil(kappa - 1e-6)
    return kappa, (-first) % teeth, first - kappa


def actual_positions(
    k: np.ndarray, errors: np.ndarray, tooth_origin: int, teeth: int
) -> NDArray[np.float64]:
    """The teeth's actual angles in tooth pitches: k + e_j N / (2 pi), j = (k + origin) mod N.

    Parameters
    ----------
    k : numpy.ndarray
        Tooth positions (int).
    errors : numpy.ndarray
        Tooth errors e_j (rad, N values numbered from the mark).
    tooth_origin : int
        The tooth number of position 0.
    teeth : int
        N.

    Returns
    -------
    numpy.ndarray
        The actual angles (tooth pitches).
    """
    return k + np.asarray(errors)[(k + tooth_origin) % teeth] * (teeth / (2.0 * math.pi))


def _mark_position(prep: PreparedPulses, errors: np.ndarray, tooth_origin: int) -> float:
    """kappa_0 with the tooth errors taken into account: the mark's time interpolated in the
    teeth's actual angles (cubic in time), not their nominal ones."""
    n = prep.teeth
    k = np.arange(prep.times.size)
    actual = actual_positions(k, errors, tooth_origin, n)
    if prep.reference_index is None or prep.reference_period is None:
        raise ValueError("no reference mark")  # the caller checks
    if prep.reference_times is None:  # a missing-tooth gap: the mark is a tooth
        index = prep.reference_index.astype(int)
        positions = actual[index]
    else:
        from scipy.interpolate import CubicSpline  # imported here: keeps the start-up light

        positions = CubicSpline(prep.times, actual)(prep.reference_times)
    m = np.arange(positions.size)
    return float(np.mean(positions - prep.reference_period * m))


def cycle_length(cycle_angle: float, teeth: int) -> int:
    """Tooth positions per working cycle L (a whole number).

    Parameters
    ----------
    cycle_angle : float
        Crank angle of one working cycle (rad).
    teeth : int
        Teeth N.

    Returns
    -------
    int
        L = N cycle_angle / (2 pi).
    """
    per_cycle = cycle_angle * teeth / (2.0 * math.pi)
    length = round(per_cycle)
    if abs(per_cycle - length) > 1e-9 * length:  # pragma: no cover - N per revolution is whole
        raise InputError("the cycle is not a whole number of tooth pitches")
    return length


def too_short(positions: int, length: int) -> InputError | None:
    """The error of a record of ``positions`` tooth positions shorter than six working cycles
    of ``length`` positions, or None.

    Parameters
    ----------
    positions, length
        Tooth positions of the record and of a cycle.

    Returns
    -------
    InputError or None
        The error (``key="time"``).
    """
    if positions >= 6 * length:
        return None
    return InputError(
        f"the record holds {positions / length:.1f} working cycles; at least 6 are needed (the "
        "first and the last two are used up by the mean-rotation filter)",
        key="time",
    )


@dataclass(frozen=True)
class Positions:
    """The mean rotation and the crank-angle position of consecutive tooth positions
    (:func:`positions`; module docstring, steps 1 and 2).

    Parameters
    ----------
    index : numpy.ndarray
        The tooth positions k of the times (float).
    smooth : numpy.ndarray
        t_bar, the mean rotation's time at positions ``index[s:-s]`` (s).
    s : int
        The filter's offset: the first ``s`` and the last ``s`` positions have no t_bar.
    position : numpy.ndarray
        P(t_k) in tooth positions at ``index[s:-s]``: where the mean rotation is at each pulse.
    """

    index: NDArray[np.float64]
    smooth: NDArray[np.float64]
    s: int
    position: NDArray[np.float64]

    @property
    def keep(self) -> slice:
        """The positions with a mean rotation: ``s`` to ``size - s``."""
        return slice(self.s, self.index.size - self.s)

    def vibration(self, pitch: float) -> NDArray[np.float64]:
        """v_k = (k - P(t_k)) 2 pi / N at the kept positions (rad), before tooth errors.

        Parameters
        ----------
        pitch : float
            The tooth pitch 2 pi / N (rad).

        Returns
        -------
        numpy.ndarray
            v at ``index[keep]`` (rad).
        """
        return (self.index[self.keep] - self.position) * pitch


def positions(times: np.ndarray, first: int, length: int) -> Positions:
    """The mean rotation of consecutive tooth positions and where it is at each pulse.

    Parameters
    ----------
    times : numpy.ndarray
        The times of tooth positions ``first``, ``first + 1``, ... (s), gaps filled.
    first : int
        The tooth position of ``times[0]``.
    length : int
        Tooth positions per working cycle L.

    Returns
    -------
    Positions
        t_bar (s) and P(t_k) (tooth positions), module docstring steps 1 and 2.

    Raises
    ------
    InputError
        If the mean rotation does not advance (a stop or a reversal).
    """
    smooth, s = mean_rotation_times(times, length)
    if np.any(np.diff(smooth) <= 0.0):
        raise InputError(
            "the mean rotation does not advance steadily (a stop or a reversal in the record)",
            key="time",
        )
    index = np.arange(first, first + times.size, dtype=float)
    keep = slice(s, times.size - s)
    # psi = P(t) in tooth positions: the inverse of the smooth time-of-arrival
    from scipy.interpolate import CubicSpline  # imported here: keeps the start-up light

    position = CubicSpline(smooth, index[keep])(times[keep])
    return Positions(index, smooth, s, position)


def grid_start(theta: np.ndarray, psi0: float, cycle_angle: float, pitch: float) -> int:
    """The first tooth at or after a cycle boundary that the record reaches.

    Parameters
    ----------
    theta : numpy.ndarray
        The tooth angles from position 0 (rad).
    psi0 : float
        The crank angle of the first analysed pulse (rad).
    cycle_angle, pitch : float
        The cycle's and a tooth's angle (rad).

    Returns
    -------
    int
        Its tooth position.
    """
    first = math.ceil(psi0 / cycle_angle - 1e-9)
    start = int(np.searchsorted(theta, first * cycle_angle - 1e-9 * pitch))
    while theta[start] < psi0:
        start += 1
    return start


def pulse_speed(
    times: np.ndarray, first: int, pitch: float, errors: np.ndarray | None, tooth_origin: int
) -> NDArray[np.float64]:
    """The instantaneous speed over every pulse interval (rad/s), module docstring step 5.

    Parameters
    ----------
    times : numpy.ndarray
        Times of consecutive tooth positions from ``first`` (s).
    first : int
        The tooth position of ``times[0]``.
    pitch : float
        2 pi / N (rad).
    errors : numpy.ndarray or None
        The tooth errors (rad, N values numbered from the mark), or None.
    tooth_origin : int
        The tooth number of position 0.

    Returns
    -------
    numpy.ndarray
        ``times.size - 1`` speeds (rad/s).
    """
    dtheta = np.full(times.size - 1, pitch)
    if errors is not None:
        n = errors.size
        e = errors[(np.arange(first, first + times.size) + tooth_origin) % n]
        dtheta = dtheta + np.diff(e)
    return dtheta / np.diff(times)


def angle_domain(
    prep: PreparedPulses,
    cycle_angle: float,
    *,
    reference_angle: float = 0.0,
    tooth_errors: np.ndarray | None = None,
    estimate_teeth: bool = False,
    tooth_shift: int = 0,
) -> tuple[AngleDomain, np.ndarray | None]:
    """Angular vibration at equal crank angles from a prepared pulse train (module docstring).

    Parameters
    ----------
    prep : crankdyn.measure.signals.PreparedPulses
        The time of every tooth position (gaps filled) and the reference marks.
    cycle_angle : float
        Crank angle of one working cycle (rad): 4 pi four-stroke, 2 pi two-stroke.
    reference_angle : float
        Crank angle at the reference mark (rad); without a mark, the first pulse is 0.
    tooth_errors : numpy.ndarray or None
        Angle errors e_j of the teeth numbered from the mark (rad, N values), or None.
    estimate_teeth : bool
        Estimate the pattern from this record's revolutions and remove it (module docstring).
    tooth_shift : int
        Added to the tooth numbers (to align a calibration record's numbering).

    Returns
    -------
    domain : AngleDomain
        The resampled vibration (rad at crank angles in rad).
    estimated : numpy.ndarray or None
        The tooth errors estimated from this record (rad, N values), or None.

    Raises
    ------
    InputError
        If the record holds fewer than six working cycles, the mean rotation stops or
        reverses, or no whole cycle is left after filtering.
    """
    n = prep.teeth
    length = cycle_length(cycle_angle, n)
    t = np.asarray(prep.times, dtype=float)
    pitch = 2.0 * math.pi / n
    short = too_short(t.size, length)
    if short is not None:
        raise short
    kappa, tooth_origin, _ = tooth_numbering(prep)
    tooth_origin = (tooth_origin + tooth_shift) % n
    pos = positions(t, 0, length)
    keep, index, smooth, position = pos.keep, pos.index, pos.smooth, pos.position
    v = pos.vibration(pitch)  # nominal tooth angles, before the tooth errors
    tooth = (np.arange(t.size)[keep] + tooth_origin) % n
    estimated = None
    errors = tooth_errors
    if estimate_teeth:
        pattern, _revs = tooth_pattern(v, tooth, n)
        estimated = errors = -pattern  # a tooth ahead of its nominal place reads as a lag
    if errors is not None:
        errors = np.asarray(errors, dtype=float)
        v = v + errors[tooth]
        if prep.reference_index is not None:
            kappa = _mark_position(prep, errors, tooth_origin)
    origin = reference_angle - kappa * pitch  # crank angle of tooth position 0
    psi = origin + position * pitch
    # the tooth angles over whole cycles: the grid starts at the first tooth at or after a
    # cycle boundary (the samples sit close to the teeth: the resampling shifts them by v only)
    theta = origin + pitch * index
    start = grid_start(theta, float(psi[0]), cycle_angle, pitch)
    cycles = int((np.searchsorted(theta, psi[-1], side="right") - start) // length)
    if cycles < 1:
        raise InputError("the record holds no whole working cycle after filtering", key="time")
    grid = theta[start : start + cycles * length]
    from scipy.interpolate import CubicSpline, make_interp_spline  # keeps the start-up light

    vibration = make_interp_spline(psi, v, k=5)(grid)
    arrival = CubicSpline(origin + index[keep] * pitch, smooth)  # mean rotation's time at an angle
    grid_times = arrival(grid)
    boundary_times = arrival(grid[0] + cycle_angle * np.arange(cycles + 1))
    speed = pulse_speed(t, 0, pitch, errors, tooth_origin)
    domain = AngleDomain(
        angle=grid,
        vibration=vibration,
        times=grid_times,
        boundary_times=boundary_times,
        samples_per_cycle=length,
        teeth=n,
        tooth_errors=errors,
        pulse_angle=psi,
        pulse_vibration=v,
        pulse_speed_angle=0.5 * (theta[1:] + theta[:-1]),
        pulse_speed=speed,
    )
    return domain, estimated
