"""The synthesis's grid in single precision (crankdyn.torsion.synthesis): its values only choose
the crests Newton's method refines in double precision, so the extremes must be those of the
double-precision signal whatever single precision cannot tell apart or represent: crests whose
heights differ below its resolution, rows of any size (1e-300 to 1e300, no underflow or
overflow), rows of zeros. (The wide-band rows of tests/torsion/test_synthesis_shoulders.py
check the extremes against a dense evaluation in double precision.)"""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.torsion.synthesis import half_range


@pytest.mark.parametrize("eps", [1e-5, 1e-7, 1e-9, 1e-12])
def test_crests_closer_than_single_precision_are_told_apart(eps):
    """x = cos(5 (phi + a)) + eps cos(phi + a): five crests and five troughs of cos(5 .), their
    heights apart by eps (1 - cos(2 pi/5)) and less, below single precision's 6e-8 for eps <=
    1e-7; the largest is 1 + eps (at phi = -a), the smallest -1 - eps (at phi = pi - a),
    exactly, whatever a: found to a few units of round-off (1e-15, 4.5 units in the last place
    of 1; the crests next to them are eps (1 - cos(2 pi/5)) = 0.69 eps lower)."""
    a = np.linspace(0.0, 2.0 * math.pi, 97, endpoint=False)
    m = np.array([1, 5])
    c = np.stack([eps * np.exp(1j * a), np.exp(5j * a)], axis=1)
    high, low = half_range(c, m)
    assert np.all(np.abs(high - (1.0 + eps)) <= 1e-15)
    assert np.all(np.abs(low + (1.0 + eps)) <= 1e-15)


@pytest.mark.parametrize("size", [1e-300, 1e-45, 1e-20, 1.0, 1e20, 1e45, 1e300])
def test_any_size_of_row_gives_the_same_extremes_scaled(size):
    """Rows of 1e-300 (below single precision's smallest, 1e-45) to 1e300 (above its largest,
    3e38): the extremes scale with the row to round-off (a power of two's scale exactly)."""
    rng = np.random.default_rng(7)
    m = np.array([1, 2, 3, 5, 6, 9, 12, 24])
    c = (rng.normal(size=(200, m.size)) + 1j * rng.normal(size=(200, m.size))) / (1.0 + m)
    high1, low1 = half_range(c, m)
    high, low = half_range(c * size, m)
    assert np.all(np.isfinite(high)) and np.all(np.isfinite(low))
    assert np.allclose(high / size, high1, rtol=1e-14, atol=0.0)
    assert np.allclose(low / size, low1, rtol=1e-14, atol=0.0)
    two = 2.0 ** round(math.log2(size))
    assert np.array_equal(half_range(c * two, m)[0], high1 * two)


def test_rows_of_zeros_and_a_single_harmonic():
    m = np.array([2, 3, 7])
    c = np.array([[0j, 0j, 0j], [0j, 2.0 - 1.0j, 0j]])
    high, low = half_range(c, m)
    assert high[0] == 0.0 and low[0] == 0.0
    assert high[1] == pytest.approx(math.sqrt(5.0), rel=1e-15)
    assert low[1] == pytest.approx(-math.sqrt(5.0), rel=1e-15)
