"""A plain numpy/scipy order analysis of a torsiograph record: the bare limit ``crankdyn
measure`` is measured against (issue 37, item 5).

    python -m bench.bare_measure RECORD.csv TEETH OUT.json

Nothing here is crankdyn: the record is read whole by :func:`numpy.loadtxt` (one column of
pulse times in seconds after a header line), then the formulas of crankdyn's method
(docs/measurement.md, "Method"; :mod:`crankdyn.measure.angle`), written as plainly as numpy and
scipy allow, with no checks, no repairs (dropped pulses, missing teeth, references), no result
objects: the mean rotation by the one-cycle mean twiced twice, the crank-angle position by a
cubic spline, the vibration at the pulses, the quintic resampling to equal crank angles, one
discrete Fourier transform per four-stroke cycle and their complex average. It writes the
mean speed and the amplitude and phase of every order as JSON (SI, phases in degrees).
"""

from __future__ import annotations

import json
import math
import sys

import numpy as np
from scipy.interpolate import CubicSpline, make_interp_spline

__all__ = ["order_analysis"]


def _mean(x: np.ndarray, length: int) -> tuple[np.ndarray, int]:
    h = length // 2
    s = np.concatenate([[0.0], np.cumsum(x)])
    c = np.arange(h, x.size - h)
    if length % 2:
        total = s[c + h + 1] - s[c - h]
    else:
        total = s[c + h] - s[c - h + 1] + 0.5 * (x[c - h] + x[c + h])
    return total / length, h


def _twice(x: np.ndarray, length: int) -> tuple[np.ndarray, int]:
    m1, h = _mean(x, length)
    m2, _ = _mean(m1, length)
    return 2.0 * m1[h : m1.size - h] - m2, 2 * h


def order_analysis(t: np.ndarray, teeth: int, orders: np.ndarray) -> dict:
    """Mean speed (rad/s) and complex order amplitudes (rad) of pulse times ``t`` (s) of a
    ``teeth``-tooth wheel, four-stroke cycles from the first pulse (module docstring)."""
    cycle, length, pitch = 4.0 * math.pi, 2 * teeth, 2.0 * math.pi / teeth
    n = t.size
    k = np.arange(n, dtype=float)
    line = t[0] + (t[-1] - t[0]) / (n - 1) * k
    first, s1 = _twice(t - line, length)
    second, s2 = _twice(first, length)
    s = s1 + s2
    smooth = second + line[s : n - s]
    keep = slice(s, n - s)
    position = CubicSpline(smooth, k[keep])(t[keep])
    v = (k[keep] - position) * pitch
    psi = position * pitch
    theta = pitch * k
    start = int(np.searchsorted(theta, math.ceil(psi[0] / cycle - 1e-9) * cycle - 1e-9 * pitch))
    while theta[start] < psi[0]:
        start += 1
    cycles = int((np.searchsorted(theta, psi[-1], side="right") - start) // length)
    grid = theta[start : start + cycles * length]
    per = make_interp_spline(psi, v, k=5)(grid).reshape(cycles, length)
    spectrum = np.fft.rfft(per, axis=1) * (2.0 / length)
    bins = np.round(orders * cycle / (2.0 * math.pi)).astype(int)
    angles = grid[0] + cycle * np.arange(cycles)
    mean = np.mean(spectrum[:, bins] * np.exp(-1j * angles[:, None] * orders[None, :]), axis=0)
    arrival = CubicSpline(k[keep] * pitch, smooth)(grid[0] + cycle * np.array([0, cycles]))
    return {"speed": cycle * cycles / (arrival[1] - arrival[0]), "coefficients": mean}


def main(argv: list[str]) -> int:
    path, teeth, out = argv[0], int(argv[1]), argv[2]
    orders = np.arange(1, 25) * 0.5  # every order up to 12, as crankdyn's default
    t = np.loadtxt(path, delimiter=",", comments="#", skiprows=1, usecols=0, ndmin=1)
    result = order_analysis(t, teeth, orders)
    c = result["coefficients"]
    data = {
        "speed_rpm": result["speed"] * 30.0 / math.pi,
        "orders": orders.tolist(),
        "amplitude_rad": np.abs(c).tolist(),
        "phase_deg": np.degrees(np.angle(c)).tolist(),
    }
    with open(out, "w", encoding="utf-8") as handle:
        json.dump(data, handle)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
