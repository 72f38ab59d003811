"""Brent's root finder without scipy.optimize.

Importing :mod:`scipy.optimize` takes most of a second (it loads scipy.linalg, sparse and more);
the few scalar root searches a command runs on its start-up path (the extrema of the piston
motion, the flywheel's mean speed, the pressure model's scale) need only Brent's method. This
is the same algorithm, step for step, as scipy's ``brentq`` (``scipy/optimize/Zeros/brentq.c``,
Charles Harris), so it returns the same root to the last bit: a zero of f bracketed by a sign
change, found by inverse quadratic interpolation or extrapolation, falling back to bisection
when a step would not shrink the bracket fast enough. :func:`brentq_many` runs the same steps on
many brackets in lockstep, each iteration one call of a vectorised f on every bracket still open,
so a handful of roots costs the calls of the slowest one instead of the sum of all. Both drive one
generator of the steps (:func:`_brent`), so each bracket sees the same operations in the same
order on the same doubles, and gets the same root to the bit.

References
----------
R. P. Brent, *Algorithms for Minimization without Derivatives*, Prentice-Hall, 1973, ch. 4.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Generator
from typing import NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "CONVERGED",
    "CONVERGE_ERROR",
    "RTOL",
    "SIGN_ERROR",
    "XTOL",
    "ManyRoots",
    "brentq",
    "brentq_many",
]

XTOL = 2e-12
"""Default absolute tolerance on the root (in the unit of x), as scipy's."""
RTOL = 4 * 2.220446049250313e-16
"""Default (and smallest) relative tolerance, 4 machine epsilons, as scipy's."""


def brentq(
    f: Callable[[float], float],
    a: float,
    b: float,
    *,
    xtol: float = XTOL,
    rtol: float = RTOL,
    maxiter: int = 100,
) -> float:
    """A root of f in [a, b] by Brent's method (Brent 1973, ch. 4; scipy's ``brentq``).

    Parameters
    ----------
    f
        A continuous function of one float returning a float (the unit of x to the unit of y);
        f(a) and f(b) must differ in sign.
    a, b
        The bracket (the unit of x).
    xtol, rtol
        The root x0 returned lies within xtol + rtol |x0| of a zero (x's unit; dimensionless).
    maxiter
        Most iterations.

    Returns
    -------
    float
        The root (the unit of x).

    Raises
    ------
    ValueError
        When f(a) and f(b) have the same sign, or a tolerance is out of range.
    RuntimeError
        When maxiter iterations did not converge.
    """
    _check_tolerances(xtol, rtol)
    xpre, xcur = float(a), float(b)
    steps = _brent(xpre, xcur, float(f(xpre)), float(f(xcur)), xtol, rtol, maxiter)
    try:
        x = next(steps)
        while True:
            x = steps.send(float(f(x)))
    except StopIteration as found:
        return found.value


def _check_tolerances(xtol: float, rtol: float) -> None:
    if xtol <= 0.0:
        raise ValueError(f"xtol too small ({xtol:g} <= 0)")
    if rtol < RTOL:
        raise ValueError(f"rtol too small ({rtol:g} < {RTOL:g})")


def _brent(
    xpre: float, xcur: float, fpre: float, fcur: float, xtol: float, rtol: float, maxiter: int
) -> Generator[float, float, float]:
    """Brent's steps as scipy's ``brentq.c`` takes them, from the bracket [xpre, xcur] and f there.

    Yields each abscissa at which f is wanted and is sent f there; returns the root (as
    ``StopIteration.value``). Raises ValueError when f(a) and f(b) have the same sign and
    RuntimeError after maxiter iterations.
    """
    if fpre == 0.0:
        return xpre
    if fcur == 0.0:
        return xcur
    if math.copysign(1.0, fpre) == math.copysign(1.0, fcur):
        raise ValueError("f(a) and f(b) must have different signs")
    xblk = fblk = spre = scur = 0.0
    for _ in range(maxiter):
        if fpre != 0.0 and fcur != 0.0 and math.copysign(1.0, fpre) != math.copysign(1.0, fcur):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0.0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:  # interpolate
                stry = -fcur * (xcur - xpre) / (fcur - fpre)
            else:  # extrapolate
                dpre = (fpre - fcur) / (xpre - xcur)
                dblk = (fblk - fcur) / (xblk - xcur)
                den = dblk * dpre * (fblk - fpre)  # may underflow to 0 (f of order 1e-300)
                # C's x/0 is +-inf or NaN, never a good step: a bisection, as in brentq.c
                stry = -fcur * (fblk * dblk - fpre * dpre) / den if den != 0.0 else math.inf
            if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta):  # a good short step
                spre, scur = scur, stry
            else:  # bisect
                spre = scur = sbis
        else:  # bisect
            spre = scur = sbis
        xpre, fpre = xcur, fcur
        xcur += scur if abs(scur) > delta else (delta if sbis > 0 else -delta)
        fcur = yield xcur
    raise RuntimeError(f"Brent's method did not converge in {maxiter} iterations")


CONVERGED = 0
"""Status of :func:`brentq_many`: the root is found (where :func:`brentq` returns it)."""
SIGN_ERROR = -1
"""Status of :func:`brentq_many`: f(a) and f(b) have the same sign (:func:`brentq`'s ValueError)."""
CONVERGE_ERROR = -2
"""Status of :func:`brentq_many`: maxiter iterations did not converge (:func:`brentq`'s
RuntimeError)."""


class ManyRoots(NamedTuple):
    """The roots of :func:`brentq_many`, one per bracket.

    Attributes
    ----------
    root : numpy.ndarray
        The roots (the unit of x): where the status is :data:`CONVERGED`, the number
        :func:`brentq` returns for that bracket, to the bit; NaN on :data:`SIGN_ERROR`; the last
        iterate on :data:`CONVERGE_ERROR`.
    status : numpy.ndarray
        :data:`CONVERGED`, :data:`SIGN_ERROR` or :data:`CONVERGE_ERROR` per bracket (int8).
    """

    root: NDArray[np.float64]
    status: NDArray[np.int8]


def _values(f: Callable[[NDArray[np.float64]], ArrayLike], x: list[float]) -> list[float]:
    y = np.asarray(f(np.array(x)), dtype=float)
    if y.shape != (len(x),):
        raise ValueError(f"f returned shape {y.shape} for an array of shape ({len(x)},)")
    return y.tolist()


def brentq_many(
    f: Callable[[NDArray[np.float64]], ArrayLike],
    a: ArrayLike,
    b: ArrayLike,
    *,
    xtol: float = XTOL,
    rtol: float = RTOL,
    maxiter: int = 100,
) -> ManyRoots:
    """Roots of f in many brackets [a_i, b_i] at once, each as :func:`brentq` finds it (Brent 1973).

    The brackets advance in lockstep: f is called once on the ends of all brackets, then once
    per iteration on the array of the brackets not yet converged, and each bracket takes
    :func:`brentq`'s steps (scipy's ``brentq.c``; the same generator of steps, on Python
    floats): the same root to the last bit, as long as f's value at an element does not depend
    on the other elements of the array (numpy's elementwise arithmetic and functions; not a
    matrix product, whose BLAS kernel may sum in another order for another number of rows).
    The steps are taken one bracket at a time, a few microseconds each: meant for a handful
    of brackets and an f that costs more than that per call.

    Parameters
    ----------
    f
        A vectorised function: a 1-D float array (the unit of x) to an array of its shape
        (the unit of y); f(a_i) and f(b_i) must differ in sign.
    a, b
        The brackets (the unit of x), arrays broadcast to one 1-D shape.
    xtol, rtol
        Each root x0 lies within xtol + rtol |x0| of a zero (x's unit; dimensionless).
    maxiter
        Most iterations of each bracket.

    Returns
    -------
    ManyRoots
        The roots and a status per bracket: :data:`CONVERGED`, :data:`SIGN_ERROR` (where
        :func:`brentq` raises ValueError) or :data:`CONVERGE_ERROR` (its RuntimeError).

    Raises
    ------
    ValueError
        When a tolerance is out of range or the brackets are not 1-D.

    Examples
    --------
    >>> r = brentq_many(np.cos, [0.0, 3.0, 0.0], [3.0, 6.0, 1.0])
    >>> r.root[:2].tolist() == [brentq(math.cos, 0.0, 3.0), brentq(math.cos, 3.0, 6.0)]
    True
    >>> r.status.tolist()
    [0, 0, -1]
    """
    _check_tolerances(xtol, rtol)
    lo, hi = np.broadcast_arrays(np.asarray(a, dtype=float), np.asarray(b, dtype=float))
    if lo.ndim != 1:
        raise ValueError(f"the brackets must be 1-D, not of shape {lo.shape}")
    n = lo.size
    root = np.full(n, math.nan)
    status = np.full(n, CONVERGED, dtype=np.int8)
    if n == 0:
        return ManyRoots(root, status)
    xa, xb = lo.tolist(), hi.tolist()
    ends = _values(f, xa + xb)  # f(a) and f(b) of every bracket, one call
    # the open brackets: (index, its steps, the abscissa it waits for f at)
    waiting: list[tuple[int, Generator[float, float, float], float]] = []
    for i in range(n):
        steps = _brent(xa[i], xb[i], ends[i], ends[n + i], xtol, rtol, maxiter)
        try:
            waiting.append((i, steps, next(steps)))
        except StopIteration as found:
            root[i] = found.value
        except ValueError:
            status[i] = SIGN_ERROR
        except RuntimeError:  # maxiter < 1
            root[i], status[i] = xb[i], CONVERGE_ERROR
    while waiting:
        values = _values(f, [x for _, _, x in waiting])
        still: list[tuple[int, Generator[float, float, float], float]] = []
        for (i, steps, x), y in zip(waiting, values, strict=True):
            try:
                still.append((i, steps, steps.send(y)))
            except StopIteration as found:
                root[i] = found.value
            except RuntimeError:
                root[i], status[i] = x, CONVERGE_ERROR
        waiting = still
    return ManyRoots(root, status)
