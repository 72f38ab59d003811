"""The synthesis's crests on a shoulder (crankdyn.torsion.synthesis): a grid crest whose
parabola's vertex falls where x is convex (the crest's own peak half a grid step away, past an
inflection) must still be climbed to the peak, not left at the grid's value. Found against a
dense evaluation of wide-band harmonics (every index to the highest, amplitudes falling only as
1/(1 + m)): the maxima of a few rows in ten thousand were short by up to 8e-5 of the amplitudes'
sum before the fix."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.torsion.synthesis import half_range


def _wide_band(top: int, rows: int, seed: int) -> tuple[np.ndarray, np.ndarray]:
    rng = np.random.default_rng(seed)
    m = np.array(sorted([*rng.choice(np.arange(1, top), 24, replace=False).tolist(), top]))
    c = (rng.normal(size=(rows, m.size)) + 1j * rng.normal(size=(rows, m.size))) / (1.0 + m)
    return c, m


def _dense(c: np.ndarray, m: np.ndarray, points: int) -> tuple[np.ndarray, np.ndarray]:
    """The largest and smallest of ``points`` evaluations of every row over the period: values
    the signal takes, so the synthesis's extremes may not lie inside them; and within
    (1/2) sum m^2 |c| (pi/points)^2 of them (the Taylor remainder about the nearest point)."""
    phi = 2.0 * math.pi * np.arange(points) / points
    basis = np.concatenate([np.cos(np.outer(m, phi)), -np.sin(np.outer(m, phi))])
    top, low = np.empty(c.shape[0]), np.empty(c.shape[0])
    for s in range(0, c.shape[0], 1000):
        x = np.concatenate([c[s : s + 1000].real, c[s : s + 1000].imag], axis=1) @ basis
        top[s : s + 1000], low[s : s + 1000] = x.max(axis=1), x.min(axis=1)
    return top, low


@pytest.mark.parametrize(("top", "seed"), [(32, 2), (64, 2), (48, 5)])
def test_wide_band_extremes_are_never_below_a_dense_evaluation(top, seed):
    c, m = _wide_band(top, 10000, seed)
    points = 64 * top
    high, low = half_range(c, m)
    dense_high, dense_low = _dense(c, m, points)
    scale = np.abs(c).sum(axis=1)
    remainder = 0.5 * (np.abs(c) @ (m * m.astype(float))) * (math.pi / points) ** 2
    # never short of a value the signal takes (to round-off of the amplitudes' sum) ...
    assert np.all(high >= dense_high - 1e-13 * scale)
    assert np.all(low <= dense_low + 1e-13 * scale)
    # ... and never beyond what the signal can reach between the dense points
    assert np.all(high <= dense_high + remainder + 1e-13 * scale)
    assert np.all(low >= dense_low - remainder - 1e-13 * scale)


def test_crests_refined_until_their_taylor_value_is_exact():
    """A two-stroke line's harmonics (tests/torsion/test_synthesis_batches.py): rows whose
    crests Newton's fixed four evaluations left short (the last step too long for its Taylor
    value: row 1125's maximum 7.6e-8 of the amplitudes' sum below the peak), against the
    independent bounded search, to round-off of the amplitudes' sum."""
    from tests.torsion.test_synthesis_batches import HARMONICS, _coefficients, _independent

    c = _coefficients(20000, 3)
    high, low = half_range(c, HARMONICS)
    for r in (167, 789, 1125, 4365, 4707, 11203, 19837):
        scale = float(np.abs(c[r]).sum())
        want_high, want_low = _independent(c[r])
        assert high[r] == pytest.approx(want_high, abs=1e-14 * scale), r
        assert low[r] == pytest.approx(want_low, abs=1e-14 * scale), r
