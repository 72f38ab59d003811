"""The synthesis's crests refined in batches across blocks of rows, and the Newton steps that
stop once a crest is settled (crankdyn.torsion.synthesis): every row's extremes against an
independent bounded scalar maximisation started from a dense grid, over more rows than one
block or one batch holds, with rows that are not finite among them."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from crankdyn.torsion import synthesis
from crankdyn.torsion.synthesis import half_range

# a two-stroke line's harmonics over the common period of its half orders (0.5, 1, 2, ... 24)
HARMONICS = np.concatenate([[1], np.arange(2, 49, 2)])


def _coefficients(rows: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    k = HARMONICS.size
    decay = np.exp(-0.15 * np.arange(k))
    return (rng.normal(size=(rows, k)) + 1j * rng.normal(size=(rows, k))) * decay


def _independent(c: np.ndarray, m: np.ndarray = HARMONICS) -> tuple[float, float]:
    """max and min of x(phi) = Re sum c_k exp(i m_k phi): the best of an 8192-point grid, then
    Brent's bounded search over the grid steps on either side (scipy; it stops within about
    sqrt(eps) |phi| of the crest), then two scalar Newton steps on x' = 0 from there (each
    squares the angle's error), for x and for -x."""
    phi = np.linspace(0.0, 2 * math.pi, 8192, endpoint=False)
    x = np.real(np.exp(1j * np.outer(phi, m)) @ c)

    def best(sign: float) -> float:
        j = int(np.argmax(sign * x))
        h = phi[1]

        def f(p: float) -> float:
            return float(-sign * np.real(np.exp(1j * p * m) @ c))

        found = minimize_scalar(
            f, bounds=(phi[j] - h, phi[j] + h), method="bounded", options={"xatol": 1e-12}
        )
        p = float(found.x)
        for _ in range(2):
            terms = sign * c * np.exp(1j * p * m)
            slope, curvature = -np.sum(m * terms.imag), -np.sum(m * m * terms.real)
            if curvature < 0.0:
                p -= slope / curvature
        return -f(p)

    return best(1.0), -best(-1.0)


def test_extremes_over_many_blocks_against_an_independent_search():
    rows = 1200  # several blocks of 256 rows, several batches of crests
    c = _coefficients(rows, 11)
    c[[5, 700, 1199]] = np.nan  # not finite: NaN, the rows around them computed as usual
    top, low = half_range(c, HARMONICS)
    assert np.isnan(top[[5, 700, 1199]]).all() and np.isnan(low[[5, 700, 1199]]).all()
    check = [0, 1, 4, 6, 255, 256, 257, 511, 512, 699, 701, 1023, 1024, 1198]
    for r in check:
        scale = float(np.abs(c[r]).sum())
        want_top, want_low = _independent(c[r])
        # Brent's tolerance 1e-12 rad moves the value by at most |x''| (1e-12)^2 / 2: the
        # refined extremes agree to round-off of the sum of the amplitudes
        assert top[r] == pytest.approx(want_top, abs=1e-13 * scale), r
        assert low[r] == pytest.approx(want_low, abs=1e-13 * scale), r


@pytest.mark.parametrize("blas", [1, 2])
def test_a_batch_size_of_one_block_changes_no_number(monkeypatch, blas):
    """The same bits whether each block's crests are refined alone or thousands together, with
    one BLAS thread (as the suite runs) and with two (as the command line may)."""
    from threadpoolctl import threadpool_limits

    c = _coefficients(2600, 12)  # more crests than one batch, a last block of 40 rows
    with threadpool_limits(blas):
        top, low = half_range(c, HARMONICS)
        monkeypatch.setattr(synthesis, "_CRESTS", 1)  # every block's crests on their own
        one_top, one_low = half_range(c, HARMONICS)
    assert np.array_equal(top, one_top) and np.array_equal(low, one_low)


def test_settled_crests_within_round_off_of_every_step(monkeypatch):
    c = _coefficients(600, 13)
    top, low = half_range(c, HARMONICS)
    monkeypatch.setattr(synthesis, "SETTLED", 0.0)  # every crest takes every step
    all_top, all_low = half_range(c, HARMONICS)
    scale = np.abs(c).sum(axis=1)
    assert np.all(np.abs(top - all_top) <= 1e-14 * scale)
    assert np.all(np.abs(low - all_low) <= 1e-14 * scale)


@pytest.mark.parametrize("harmonics", [[0, 3, 40, 97], [5, 11], [1]])
def test_sparse_and_mean_harmonics_against_an_independent_search(harmonics):
    """Harmonics too sparse for products of exp(i phi) (and a mean term, m = 0): the direct
    exponentials' path of the Newton steps, settled crests and batches as above."""
    m = np.array(harmonics)
    rng = np.random.default_rng(14)
    c = rng.normal(size=(400, m.size)) + 1j * rng.normal(size=(400, m.size))
    top, low = half_range(c, m)
    for r in (0, 1, 255, 256, 399):
        scale = float(np.abs(c[r]).sum())
        want_top, want_low = _independent(c[r], m)
        assert top[r] == pytest.approx(want_top, abs=1e-13 * scale), r
        assert low[r] == pytest.approx(want_low, abs=1e-13 * scale), r
