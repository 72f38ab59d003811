"""crankdyn.roots.brentq: the same algorithm as scipy's brentq, so the same root to the bit."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq as scipy_brentq

from crankdyn.roots import CONVERGE_ERROR, CONVERGED, SIGN_ERROR, brentq, brentq_many

CASES = [
    (lambda x: x**3 - 2.0, 0.0, 2.0),
    (lambda x: math.cos(x) - x, 0.0, 1.0),
    (lambda x: math.exp(x) - 10.0, -5.0, 10.0),
    (lambda x: math.tanh(50.0 * (x - 0.3)), -1.0, 1.0),  # a near-step: many bisections
    (lambda x: (x - 1.0) ** 5, 0.0, 3.0),  # a flat root
    (lambda x: 1e-300 * (x - 0.25), 0.0, 1.0),  # tiny values
    (lambda x: x, -1.0, 0.0),  # a root at an end
    # the extrapolation's divisor underflows to 0: C's x/0 (inf or NaN) means a bisection
    (lambda x: 1e-300 * math.sin(x), 3.118811881188119, 3.2574257425742577),
]


@pytest.mark.parametrize("case", range(len(CASES)))
@pytest.mark.parametrize(
    "xtol, rtol", [(2e-12, 4 * np.finfo(float).eps), (1e-6, 1e-10), (1e-15, 1e-15)]
)
def test_same_root_as_scipy(case, xtol, rtol):
    f, a, b = CASES[case]
    ours = brentq(f, a, b, xtol=xtol, rtol=rtol, maxiter=200)
    assert ours == scipy_brentq(f, a, b, xtol=xtol, rtol=rtol, maxiter=200)


def test_random_cubics_agree_with_scipy():
    rng = np.random.default_rng(16)
    for c in rng.uniform(-3.0, 3.0, (50, 4)):
        f = lambda x, c=c: ((c[0] * x + c[1]) * x + c[2]) * x + c[3]  # noqa: E731
        grid = np.linspace(-10.0, 10.0, 41)
        values = np.array([f(x) for x in grid])
        i = np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:]))
        for j in i:
            assert brentq(f, grid[j], grid[j + 1]) == scipy_brentq(f, grid[j], grid[j + 1])


def test_errors():
    with pytest.raises(ValueError, match="different signs"):
        brentq(lambda x: x * x + 1.0, -1.0, 1.0)
    with pytest.raises(RuntimeError, match="converge"):
        brentq(lambda x: math.tanh(50.0 * (x - 0.3)), -1.0, 1.0, maxiter=3)
    with pytest.raises(ValueError, match="rtol"):
        brentq(lambda x: x, -1.0, 1.0, rtol=1e-17)


# ---- brentq_many: the same steps on many brackets in lockstep, each root brentq's to the bit ----


def _one_by_one(vf, a, b, **kw):
    """brentq on each bracket, f called on a 1-element array as a scalar caller would."""
    roots, status = [], []
    for lo, hi in zip(a, b, strict=True):
        try:
            roots.append(brentq(lambda t: float(vf(np.array([t]))[0]), lo, hi, **kw))
            status.append(CONVERGED)
        except ValueError:
            roots.append(math.nan)
            status.append(SIGN_ERROR)
        except RuntimeError:
            roots.append(math.nan)
            status.append(CONVERGE_ERROR)
    return np.array(roots), np.array(status)


def _assert_same(vf, a, b, **kw):
    want_root, want_status = _one_by_one(vf, a, b, **kw)
    got = brentq_many(vf, a, b, **kw)
    assert got.status.tolist() == want_status.tolist()
    ok = want_status == CONVERGED
    # the same bits (== would pass -0.0 for 0.0)
    assert got.root[ok].view(np.int64).tolist() == want_root[ok].view(np.int64).tolist()
    assert np.isnan(got.root[want_status == SIGN_ERROR]).all()


def _sign_brackets(vf, lo, hi, n):
    grid = np.linspace(lo, hi, n + 1)
    s = np.signbit(vf(grid))
    i = np.flatnonzero(s[:-1] != s[1:])
    return grid[i], grid[i + 1]


def _poly(c):
    def f(x):
        y = np.zeros_like(x) + c[0]
        for ci in c[1:]:
            y = y * x + ci
        return y

    return f


def test_many_random_polynomials_every_count():
    """Random polynomials of degree 3 to 7: all their brackets at once, and every prefix and
    shuffled subset of them (counts 1 to many), the same roots as one brentq each."""
    rng = np.random.default_rng(1716)
    for _ in range(40):
        f = _poly(rng.uniform(-3.0, 3.0, rng.integers(4, 9)))
        a, b = _sign_brackets(f, -4.0, 4.0, 97)
        if a.size == 0:
            continue
        _assert_same(f, a, b)
        for count in range(1, a.size + 1):
            pick = rng.permutation(a.size)[:count]
            _assert_same(f, a[pick], b[pick])


def test_many_trig_and_tolerances():
    """Trigonometric functions (numpy's vectorised sin, cos, tanh), three tolerance pairs."""
    funcs = [
        lambda x: np.cos(x) - 0.3 * x,
        lambda x: np.sin(7.0 * x) + 0.2 * np.cos(3.0 * x),
        lambda x: np.tanh(50.0 * (np.sin(x) - 0.3)),  # near-steps: many bisections
        lambda x: np.sin(x) ** 5,  # flat roots (of order 5)
        lambda x: 1e-300 * np.sin(x),  # tiny values
    ]
    for f in funcs:
        a, b = _sign_brackets(f, -7.0, 7.0, 101)
        assert a.size > 1
        for xtol, rtol in [(2e-12, 4 * np.finfo(float).eps), (1e-6, 1e-10), (1e-15, 1e-15)]:
            _assert_same(f, a, b, xtol=xtol, rtol=rtol, maxiter=200)


def test_many_ends_signs_and_maxiter_in_one_call():
    """Zeros at either end (brentq's early returns), same signs (its ValueError) and brackets
    too slow for maxiter (its RuntimeError), mixed with ordinary ones in one call."""

    def f(x):
        return np.tanh(50.0 * (x - 0.3)) * (x + 2.0)

    a = np.array([0.3, -1.0, 0.5, -1.0, 0.0, -2.0, 0.29, 0.2, 0.4, -3.0])
    b = np.array([1.0, 0.3, 0.9, 1.0, 0.31, 0.0, 0.31, 0.35, 0.9, -1.0])
    for maxiter in (0, 1, 3, 6, 10, 100):
        _assert_same(f, a, b, maxiter=maxiter)
    got = brentq_many(f, a, b, maxiter=3)
    assert set(got.status.tolist()) == {CONVERGED, SIGN_ERROR, CONVERGE_ERROR}


def test_many_crank_train_derivative():
    """The use in local_extrema: the complex-step derivative of the exact piston motion."""
    from crankdyn.crank.kinematics import complex_step, slider_crank_exact

    for e in (0.0, 0.004):
        for index in (1, 2, 4, 5):
            df = complex_step(
                lambda p, i=index, e=e: slider_crank_exact(p, 0.0355, 0.14, e, 586.4)[i]
            )
            a, b = _sign_brackets(df, 0.0, 2 * math.pi, 1440)
            _assert_same(df, a, b, xtol=1e-14)


def test_many_shapes_and_errors():
    empty = brentq_many(np.sin, [], [])
    assert empty.root.size == 0 and empty.status.size == 0
    one = brentq_many(np.sin, 3.0, [4.0])  # broadcast
    assert one.root.tolist() == [brentq(math.sin, 3.0, 4.0)]
    with pytest.raises(ValueError, match="rtol"):
        brentq_many(np.sin, [3.0], [4.0], rtol=1e-17)
    with pytest.raises(ValueError, match="xtol"):
        brentq_many(np.sin, [3.0], [4.0], xtol=0.0)
    with pytest.raises(ValueError, match="shape"):
        brentq_many(lambda x: np.sin(x)[:1], [3.0, 0.5], [4.0, 4.0])
