"""The angle-domain core: identities of the one-cycle mean and the mean-rotation filter."""

import math

import numpy as np
import pytest

from crankdyn.measure.angle import cycle_mean, mean_rotation_times, tooth_pattern


@pytest.mark.parametrize("length", [120, 121, 60])
def test_cycle_mean_removes_every_harmonic_and_keeps_a_line(length):
    k = np.arange(2000, dtype=float)
    line = 3.0 + 0.25 * k
    harmonics = sum(
        a * np.cos(2 * math.pi * m * k / length + p)
        for m, a, p in ((1, 2.0, 0.3), (2, 0.5, -1.0), (7, 0.1, 2.0), (length // 2 - 1, 0.3, 0.1))
    )
    mean, h = cycle_mean(line + harmonics, length)
    assert np.max(np.abs(mean - line[h : k.size - h])) < 1e-9


def test_mean_rotation_keeps_cubics_and_removes_orders():
    """F F with F = 2 M - M M keeps a cubic time-of-arrival exactly and removes every order of
    the cycle, also one modulated linearly (the double zeros)."""
    length = 120
    k = np.arange(3000, dtype=float)
    smooth = 0.1 + 4e-4 * k + 3e-9 * k**2 - 2e-13 * k**3
    ramp = 1.0 + 2e-4 * k  # a linear modulation of the orders
    orders = ramp * sum(
        a * np.sin(2 * math.pi * m * k / length + p)
        for m, a, p in ((1, 1e-5, 0.2), (3, 4e-5, 1.0), (12, 2e-5, -0.5))
    )
    t_bar, s = mean_rotation_times(smooth + orders, length)
    assert s == 2 * length
    assert np.max(np.abs(t_bar - smooth[s : k.size - s])) < 1e-12
    single, _ = cycle_mean(smooth + orders, length)  # one M: a linear modulation leaks
    assert np.max(np.abs(single - smooth[60 : k.size - 60])) > 1e-9


def test_tooth_pattern_is_the_mean_over_whole_revolutions():
    teeth = 36
    rng = np.random.default_rng(0)
    pattern = rng.normal(0.0, 1e-3, teeth)
    pattern -= pattern.mean()
    k = np.arange(teeth * 11)  # 11 revolutions: the first 10 are used (an even count)
    half_order = 1e-2 * np.cos(0.5 * 2 * math.pi * k / teeth)  # cancels over two revolutions
    got, revolutions = tooth_pattern(pattern[k % teeth] + half_order, k, teeth)
    assert revolutions == 10
    assert np.max(np.abs(got - pattern)) < 1e-15
