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
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from crankdyn.measure.signals import PulseTrain

__all__ = ["PrescribedMotion", "synthetic_pulses"]


@dataclass(frozen=True, eq=False)
class PrescribedMotion:
    """An angular motion known exactly (module docstring).

    Parameters
    ----------
    speed
        Mean speed omega_0 at t = 0 (rad/s), > 0.
    acceleration
        Constant angular acceleration alpha of the mean rotation (rad/s^2).
    orders
        The orders q of the vibration (multiples of the crank speed).
    amplitudes
        Complex amplitudes X_q (rad), shape (Q,), or a callable taking mean speeds (S,)
        (rad/s) and returning (S, Q).
    """

    speed: float
    acceleration: float
    orders: np.ndarray
    amplitudes: np.ndarray | Callable

    def coefficients(self, omega) -> np.ndarray:
        """X_q at mean speeds omega (rad/s): (S, Q) complex."""
        omega = np.atleast_1d(np.asarray(omega, dtype=float))
        if callable(self.amplitudes):
            return np.asarray(self.amplitudes(omega), dtype=complex)
        x = np.asarray(self.amplitudes, dtype=complex)
        return np.broadcast_to(x, (omega.size, x.size))

    def mean_speed_at(self, psi) -> np.ndarray:
        """Omega at the mean angle psi (rad/s): Omega^2 = omega_0^2 + 2 alpha psi."""
        psi = np.asarray(psi, dtype=float)
        if self.acceleration == 0.0:
            return np.full_like(psi, self.speed)
        return np.sqrt(self.speed**2 + 2.0 * self.acceleration * psi)

    def time_at(self, psi) -> np.ndarray:
        """t at the mean angle psi (s)."""
        psi = np.asarray(psi, dtype=float)
        if self.acceleration == 0.0:
            return psi / self.speed
        return (self.mean_speed_at(psi) - self.speed) / self.acceleration

    def vibration(self, psi) -> np.ndarray:
        """v(psi) (rad)."""
        psi = np.asarray(psi, dtype=float)
        x = self.coefficients(self.mean_speed_at(psi))
        q = np.asarray(self.orders, dtype=float)
        return np.sum(np.real(x * np.exp(1j * psi[:, None] * q[None, :])), axis=1)

    def solve(self, theta) -> np.ndarray:
        """The mean angles psi at which psi + v(psi) = theta (rad), by Newton's method."""
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
    tooth_errors=None,
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
    motion
        The prescribed motion.
    teeth
        Teeth N (pulses per revolution).
    duration
        Length of the record (s).
    tooth_errors
        Angle errors e_j of the teeth (rad, N values), tooth 0 at the reference, or None.
    reference_every
        1 (once per revolution) or 2 (once per four-stroke cycle): reference pulses when the
        shaft's angle theta passes ``reference_angle`` + 2 pi m x this; None: no reference.
    reference_angle
        Crank angle at which the reference mark passes the sensor (rad).
    tooth_offset
        Where tooth 0 sits after the reference mark, in tooth pitches.
    jitter
        Standard deviation of the timing noise (s).
    clock
        Period of the counter clock (s): times are rounded to whole ticks; None: exact.
    seed
        Seed of the noise generator.

    Returns
    -------
    PulseTrain
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
