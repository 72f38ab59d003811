"""Synthetic torsiograph signals from a prescribed angular motion (for validation and the
built-in examples).

The motion is theta(t) = psi(t) + v(psi(t)): a mean rotation psi with a constant angular
acceleration (a steady run when it is zero, a run-up or run-down otherwise),

    psi(t) = omega_0 t + alpha t^2 / 2,       Omega(t) = omega_0 + alpha t,

and an angular vibration that is a sum of orders with complex amplitudes X_q that may depend on
the mean speed (the steady-state response at the instantaneous speed, a quasi-static sweep):

    v(psi) = sum_q Re( X_q(Omega) exp(i q psi) ).

A wheel with N teeth at the angles 2 pi k / N + e_(k mod N) gives a pulse when theta reaches a
tooth angle: psi + v(psi) = theta_k is solved by Newton's method (to 1e-13 rad), then t_k from
psi_k in closed form. Timing jitter (normal, standard deviation sigma) and the quantisation of a
counter clock (rounding to whole ticks) are added last, as a torsiograph's counter would.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.measure.records import PulseChunk, PulseRecord
from crankdyn.measure.signals import PulseTrain

__all__ = ["PrescribedMotion", "synthetic_pulses", "synthetic_record"]


@dataclass(frozen=True, eq=False)
class PrescribedMotion:
    """An angular motion known exactly (module docstring).

    Parameters
    ----------
    speed : float
        Mean speed omega_0 at t = 0 (rad/s), > 0.
    acceleration : float
        Constant angular acceleration alpha of the mean rotation (rad/s^2).
    orders : numpy.ndarray
        The orders q of the vibration (per revolution), shape (Q,).
    amplitudes : numpy.ndarray or callable
        Complex amplitudes X_q (rad), shape (Q,), or a callable taking mean speeds (S,)
        (rad/s) and returning (S, Q).

    Examples
    --------
    A steady 100 rad/s with 0.01 rad of order 2, v = 0.01 cos(2 psi): the shaft leads by
    0.01 rad at psi = 0 and reaches theta = 0.5 rad when psi + v(psi) = 0.5.

    >>> m = PrescribedMotion(100.0, 0.0, np.array([2.0]), np.array([0.01]))
    >>> round(float(m.vibration(np.array([0.0]))[0]), 12)
    0.01
    >>> psi = m.solve(np.array([0.5]))
    >>> abs(float(psi[0] + 0.01 * np.cos(2 * psi[0])) - 0.5) < 1e-13
    True
    >>> round(float(m.time_at(psi)[0]) * 1e3, 4)  # ms, psi / omega_0
    4.945
    """

    speed: float
    acceleration: float
    orders: np.ndarray
    amplitudes: np.ndarray | Callable

    def coefficients(self, omega: ArrayLike) -> NDArray[np.complex128]:
        """The order amplitudes X_q at mean speeds.

        Parameters
        ----------
        omega : array_like
            Mean speeds Omega (rad/s), S of them.

        Returns
        -------
        numpy.ndarray
            (S, Q) complex X_q (rad).
        """
        omega = np.atleast_1d(np.asarray(omega, dtype=float))
        if callable(self.amplitudes):
            return np.asarray(self.amplitudes(omega), dtype=complex)
        x = np.asarray(self.amplitudes, dtype=complex)
        return np.broadcast_to(x, (omega.size, x.size))

    def mean_speed_at(self, psi: ArrayLike) -> NDArray[np.float64]:
        """The mean speed at a mean angle: Omega^2 = omega_0^2 + 2 alpha psi.

        Parameters
        ----------
        psi : array_like
            Mean angles psi (rad) from t = 0.

        Returns
        -------
        numpy.ndarray
            Omega (rad/s), of psi's shape.
        """
        psi = np.asarray(psi, dtype=float)
        if self.acceleration == 0.0:
            return np.full_like(psi, self.speed)
        return np.sqrt(self.speed**2 + 2.0 * self.acceleration * psi)

    def time_at(self, psi: ArrayLike) -> NDArray[np.float64]:
        """The time at a mean angle: t = psi / omega_0, or (Omega - omega_0) / alpha.

        Parameters
        ----------
        psi : array_like
            Mean angles psi (rad).

        Returns
        -------
        numpy.ndarray
            t (s), of psi's shape.
        """
        psi = np.asarray(psi, dtype=float)
        if self.acceleration == 0.0:
            return psi / self.speed
        return (self.mean_speed_at(psi) - self.speed) / self.acceleration

    def vibration(self, psi: ArrayLike) -> NDArray[np.float64]:
        """The angular vibration v(psi) = sum_q Re(X_q(Omega) exp(i q psi)).

        Parameters
        ----------
        psi : array_like
            Mean angles psi (rad), 1-D.

        Returns
        -------
        numpy.ndarray
            v (rad), of psi's shape.
        """
        psi = np.asarray(psi, dtype=float)
        x = self.coefficients(self.mean_speed_at(psi))
        q = np.asarray(self.orders, dtype=float)
        return np.sum(np.real(x * np.exp(1j * psi[:, None] * q[None, :])), axis=1)

    def solve(self, theta: ArrayLike) -> NDArray[np.float64]:
        """The mean angles at which the shaft reaches given angles, by Newton's method.

        psi + v(psi) = theta, iterated to 1e-13 rad (relative to the largest theta above 1).

        Parameters
        ----------
        theta : array_like
            Shaft angles theta (rad), 1-D.

        Returns
        -------
        numpy.ndarray
            psi (rad), of theta's shape.
        """
        theta = np.asarray(theta, dtype=float)
        q = np.asarray(self.orders, dtype=float)
        psi = theta.copy()
        for _ in range(50):
            x = self.coefficients(self.mean_speed_at(psi))
            e = np.exp(1j * psi[:, None] * q[None, :])
            value = psi + np.sum(np.real(x * e), axis=1) - theta
            slope = 1.0 + np.sum(np.real(1j * q * x * e), axis=1)
            psi = psi - value / slope
            if np.max(np.abs(value)) < 1e-13 * max(1.0, float(np.max(np.abs(theta)))):
                break
        return psi


def synthetic_pulses(
    motion: PrescribedMotion,
    teeth: int,
    duration: float,
    *,
    tooth_errors: ArrayLike | None = None,
    reference_every: int | None = None,
    reference_angle: float = 0.0,
    tooth_offset: float = 0.3,
    jitter: float = 0.0,
    clock: float | None = None,
    seed: int = 0,
    source: str = "synthetic",
) -> PulseTrain:
    """Pulse times of a wheel on a shaft that moves as ``motion`` for ``duration`` seconds.

    Parameters
    ----------
    motion : PrescribedMotion
        The prescribed motion.
    teeth : int
        Teeth N (pulses per revolution).
    duration : float
        Length of the record (s).
    tooth_errors : array_like or None
        Angle errors e_j of the teeth (rad, N values), tooth 0 at the reference, or None.
    reference_every : int or None
        1 (once per revolution) or 2 (once per four-stroke cycle): reference pulses when the
        shaft's angle theta passes ``reference_angle`` + 2 pi m x this; None: no reference.
    reference_angle : float
        Crank angle at which the reference mark passes the sensor (rad).
    tooth_offset : float
        Where tooth 0 sits after the reference mark, in tooth pitches (dimensionless).
    jitter : float
        Standard deviation of the timing noise (s); default 0.
    clock : float or None
        Period of the counter clock (s): times are rounded to whole ticks; None: exact.
    seed : int
        Seed of the noise generator.
    source : str
        Where the train comes from, for messages and the report; default ``"synthetic"``.

    Returns
    -------
    PulseTrain
        The pulse times (s) and, with ``reference_every``, the reference times (s).

    Examples
    --------
    A steady 10 rev/s for 1 s on a 60-tooth wheel, no vibration: one pulse every 1/600 s.

    >>> m = PrescribedMotion(20 * math.pi, 0.0, np.array([1.0]), np.array([0.0]))
    >>> train = synthetic_pulses(m, 60, 1.0)
    >>> train.times.size, round(float(np.diff(train.times).mean()) * 600, 12)
    (600, 1.0)
    """
    psi_end = motion.speed * duration + 0.5 * motion.acceleration * duration**2
    pitch = 2.0 * math.pi / teeth
    # tooth k = 0 sits tooth_offset pitches after the reference mark
    start = reference_angle + tooth_offset * pitch
    first = math.ceil(-start / pitch) - 2
    last = math.floor((psi_end - start) / pitch) + 2
    k = np.arange(first, last + 1)
    theta = start + pitch * k
    if tooth_errors is not None:
        theta = theta + np.asarray(tooth_errors, dtype=float)[k % teeth]
    psi = motion.solve(theta)
    inside = (psi >= 0.0) & (psi <= psi_end)
    times = motion.time_at(psi[inside])
    rng = np.random.default_rng(seed)
    reference = None
    if reference_every is not None:
        span = 2.0 * math.pi * reference_every
        m = np.arange(math.ceil(-reference_angle / span), math.floor(psi_end / span) + 1)
        ref_psi = motion.solve(reference_angle + span * m)
        ok = (ref_psi >= 0.0) & (ref_psi <= psi_end)
        reference = motion.time_at(ref_psi[ok])
    if jitter:
        times = times + rng.normal(0.0, jitter, times.size)
    if clock:
        times = np.round(times / clock) * clock
        if reference is not None:
            reference = np.round(reference / clock) * clock
    return PulseTrain(times, teeth, reference=reference, source=source)


def synthetic_record(
    motion: PrescribedMotion,
    teeth: int,
    duration: float,
    *,
    reference_every: int | None = None,
    reference_angle: float = 0.0,
    tooth_offset: float = 0.3,
    jitter: float = 0.0,
    seed: int = 0,
    chunk: int = 1 << 18,
    source: str = "synthetic",
) -> PulseRecord:
    """The pulses of :func:`synthetic_pulses` as a record read in chunks, made as it is read:
    a record of any length (10^7 pulses and more) in memory bounded by a chunk.

    Every chunk solves its own teeth (:meth:`PrescribedMotion.solve`), so the pulse times are
    those of :func:`synthetic_pulses` without jitter and clock; the jitter of chunk m comes
    from the generator seeded with (``seed``, m), the same at every reading. The reference marks
    come with the first chunk.

    Parameters
    ----------
    motion : PrescribedMotion
        The prescribed motion.
    teeth : int
        Teeth N (pulses per revolution).
    duration : float
        Length of the record (s).
    reference_every : int or None
        1 or 2 (as :func:`synthetic_pulses`), or None: no reference.
    reference_angle, tooth_offset : float
        As :func:`synthetic_pulses` (rad; tooth pitches).
    jitter : float
        Standard deviation of the timing noise (s); default 0.
    seed : int
        Seed of the noise generator.
    chunk : int
        Pulses per chunk.
    source : str
        Where the record comes from, for messages; default ``"synthetic"``.

    Returns
    -------
    crankdyn.measure.records.PulseRecord
        The record.

    Examples
    --------
    >>> m = PrescribedMotion(20 * math.pi, 0.0, np.array([1.0]), np.array([1e-3]))
    >>> record = synthetic_record(m, 60, 1.0, chunk=250)
    >>> whole = synthetic_pulses(m, 60, 1.0)
    >>> bool(np.array_equal(record.train().times, whole.times))
    True
    """
    psi_end = motion.speed * duration + 0.5 * motion.acceleration * duration**2
    pitch = 2.0 * math.pi / teeth
    start = reference_angle + tooth_offset * pitch
    first = math.ceil(-start / pitch) - 2
    last = math.floor((psi_end - start) / pitch) + 2
    reference = None
    if reference_every is not None:
        span = 2.0 * math.pi * reference_every
        m = np.arange(math.ceil(-reference_angle / span), math.floor(psi_end / span) + 1)
        ref_psi = motion.solve(reference_angle + span * m)
        reference = motion.time_at(ref_psi[(ref_psi >= 0.0) & (ref_psi <= psi_end)])

    def read() -> Iterator[PulseChunk]:
        marks = reference
        for index, k0 in enumerate(range(first, last + 1, chunk)):
            k = np.arange(k0, min(last + 1, k0 + chunk))
            psi = motion.solve(start + pitch * k)
            times = motion.time_at(psi[(psi >= 0.0) & (psi <= psi_end)])
            if jitter:
                times = times + np.random.default_rng([seed, index]).normal(0, jitter, times.size)
            if times.size or marks is not None:
                yield PulseChunk(times, reference=marks)
                marks = None

    return PulseRecord(read, teeth, source)
