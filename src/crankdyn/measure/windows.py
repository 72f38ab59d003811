"""The windows of an order analysis (numeric core): the orders of the angular vibration over
windows of whole working cycles (:mod:`crankdyn.measure.orders`, module docstring).

A window of c cycles starting at cycle boundary m holds the vibration at the L c crank angles
psi_j = psi_m + j 2 pi / N; its discrete Fourier transform gives every order of the cycle
exactly (synchronous sampling), the phase referred to the crank angle:

    V_q = (2 / sum(w)) sum_j w_j v_j exp(-i q psi_j),

w_j = 1 (uniform) or (1 - cos(2 pi j / (L c))) / 2 (periodic Hann). A window depends on its own
cycles only, so the windows of a record are the same whether its cycles come all at once or a
few at a time (:func:`window_coefficients` takes any run of consecutive cycles).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["Windows", "window_coefficients"]


@dataclass(frozen=True)
class Windows:
    """The orders of consecutive windows.

    Parameters
    ----------
    coefficients : numpy.ndarray
        (W, Q) complex V_q of every window (rad).
    speed : numpy.ndarray
        (W,) the mean rotation's speed over each window (rad/s): its crank angle over the time
        the mean rotation takes.
    start_angle : numpy.ndarray
        (W,) the crank angle of each window's first sample (rad).
    """

    coefficients: NDArray[np.complex128]
    speed: NDArray[np.float64]
    start_angle: NDArray[np.float64]


def window_coefficients(
    per: NDArray[np.float64],
    first: int,
    angle0: float,
    boundary_times: NDArray[np.float64],
    orders: ArrayLike,
    cycle_angle: float,
    cycles: int,
    shape: str = "uniform",
) -> Windows:
    """The orders over every window of ``cycles`` cycles within a run of whole cycles.

    Parameters
    ----------
    per : numpy.ndarray
        (C, L) the vibration over C consecutive cycles (rad), L samples each.
    first : int
        The record's number of the first of them (0 for the record's first whole cycle).
    angle0 : float
        The crank angle of the record's first whole cycle's first sample (rad).
    boundary_times : numpy.ndarray
        (C + 1,) the mean rotation's times at the boundaries of those cycles (s).
    orders : array_like
        The orders q (per revolution), multiples of the cycle's fundamental order.
    cycle_angle : float
        The crank angle of a working cycle (rad).
    cycles : int
        Cycles per window c (>= 1); windows step by one cycle.
    shape : str
        ``"uniform"`` or ``"hann"`` (module docstring).

    Returns
    -------
    Windows
        The C - c + 1 windows starting at cycles ``first``, ``first + 1``, ... (none when
        C < c).

    Examples
    --------
    One cycle of two orders on a 16-sample cycle of 4 pi (orders 0.5, 1, ...), the first
    sample at crank angle 0:

    >>> psi = 4 * np.pi * np.arange(16) / 16
    >>> v = 2e-3 * np.cos(1.5 * psi + 0.3) + 1e-3 * np.cos(2.0 * psi)
    >>> w = window_coefficients(v[None, :], 0, 0.0, np.array([0.0, 0.1]), [1.5, 2.0],
    ...                         4 * np.pi, 1)
    >>> [round(float(abs(c)) * 1e3, 12) for c in w.coefficients[0]], round(float(w.speed[0]), 9)
    ([2.0, 1.0], 125.663706144)
    """
    length = per.shape[1]
    count = per.shape[0] - cycles + 1
    q = np.asarray(orders, dtype=float)
    if count < 1:
        return Windows(np.empty((0, q.size), dtype=complex), np.empty(0), np.empty(0))
    if cycles == 1:
        data = per
    else:
        view = np.lib.stride_tricks.sliding_window_view(per, cycles, axis=0)  # (W, L, c)
        data = np.moveaxis(view, -1, 1).reshape(count, cycles * length)
    n = data.shape[1]
    if shape == "hann":
        w = 0.5 - 0.5 * np.cos(2.0 * math.pi * np.arange(n) / n)  # periodic Hann
        spectrum = np.fft.rfft(data * w, axis=1) * (2.0 / np.sum(w))
    else:
        spectrum = np.fft.rfft(data, axis=1) * (2.0 / n)
    bins = np.round(q * cycles * cycle_angle / (2.0 * math.pi)).astype(int)
    start = angle0 + cycle_angle * np.arange(first, first + count)
    # the window starts at the crank angle psi_s: V_q = (2 / n) sum v_j exp(-i q (psi_s + ...))
    coefficients = spectrum[:, bins] * np.exp(-1j * start[:, None] * q[None, :])
    times = boundary_times
    speed = cycles * cycle_angle / (times[cycles:] - times[:count])
    return Windows(coefficients, speed, start)
