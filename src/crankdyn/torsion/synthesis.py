"""Time-domain synthesis of harmonic orders (numeric core): the largest and smallest value over
one period of a sum of harmonics, by an inverse FFT and Newton refinement of every near-extreme
crest (:func:`half_range`; the synthesised half-range amplitude of
:mod:`crankdyn.torsion.response`)."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["NEWTON", "half_range"]

_BLOCK = 1 << 18  # grid values per block of the synthesis (single precision: 1 MiB, in cache)
_CRESTS = 2048  # crests refined together (their coefficients a few MB)
NEWTON = 4  # evaluations per crest in the time-domain synthesis (the last step by Taylor)
TAYLOR = 1e-5  # a last Newton step longer than this fraction of a grid step is evaluated
NEWTON_MAX = 12  # evaluations of a crest at most (NEWTON, more after steps not Newton's own)
SETTLED = 1e-6  # a Newton step below this fraction of a grid step ends a crest's refinement


# ---- the synthesis ----------------------------------------------------------------------
def half_range(
    coefficients: ArrayLike, harmonic: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(max, min) over one cycle of x(phi) = sum_k Re(c_k exp(i m_k phi)), phi in [0, 2 pi),
    for complex coefficients (..., K) at integer harmonic indices m_k (module docstring).

    x is sampled at N >= 8 points per period of the highest harmonic (the inverse discrete
    Fourier transform as one matrix product with the grid's cosines and sines). A
    grid value lies within B = (1/2) (pi/N)^2 sum_k m_k^2 |c_k| of the nearest crest, so every
    grid crest within B of the grid's extreme is refined (not only the grid's extreme: two
    crests of nearly equal height are otherwise confused, by up to B): from the vertex of the
    parabola through its three grid points, by Newton's method on x'(phi) = 0 (three steps,
    each kept within one grid step; the fourth taken in the Taylor expansion of x). Where x is
    not concave at a crest's point (the vertex past an inflection, on the shoulder of a peak up
    to a grid step away) the step is half a grid step up the slope instead, and where a step
    was not Newton's own (that, or one cut to a grid step) or the last is longer than
    :data:`TAYLOR` of a grid step (its Taylor value then not exact to round-off) the crest takes
    one more evaluation, up to :data:`NEWTON_MAX` (found against a dense evaluation of
    wide-band harmonics and an independent bounded search: a few rows in ten thousand were
    short by up to 8e-5 of sum_k |c_k| with the fixed four evaluations). The
    harmonics exp(i m phi) are products of exp(i phi) where the indices are small (each the last
    times the power of the step between them); a crest whose step falls below
    :data:`SETTLED` of a grid step takes no further step (its Taylor value then differs from
    the further steps' by O(sum_k m_k^3 |c_k| d^3) for a step d, under 1e-18 of
    sum_k |c_k| for d < 1e-6 grid steps of 8 per period of the highest harmonic). Vectorised
    over the leading axes and the crests, in blocks to bound memory. The bound B is the Taylor
    remainder of x about a crest, |x''| <= sum_k m_k^2 |c_k|, over half a grid step.

    Parameters
    ----------
    coefficients : array_like
        Complex amplitudes c_k (any unit, e.g. N m or rad), shape (..., K).
    harmonic : array_like
        Integer harmonic indices m_k >= 0 over the period, shape (K,), distinct.

    Returns
    -------
    max, min : numpy.ndarray
        Largest and smallest value of x over the period (unit of the coefficients), shape
        (...); NaN for rows with a coefficient that is not finite.

    Examples
    --------
    x = cos(phi) + cos(2 phi) peaks at 2 (phi = 0) and dips to -9/8 (cos(phi) = -1/4):

    >>> top, low = half_range([[1.0 + 0j, 1.0 + 0j]], [1, 2])
    >>> round(float(top[0]), 12), round(float(low[0]), 12)
    (2.0, -1.125)
    """
    c = np.asarray(coefficients, dtype=complex)
    m = np.asarray(harmonic, dtype=int)
    lead = c.shape[:-1]
    c2 = c.reshape(-1, m.size)
    highest = max(int(m.max()), 1)
    samples = max(64, 1 << math.ceil(math.log2(8 * highest)))
    out_max = np.empty(c2.shape[0])
    out_min = np.empty(c2.shape[0])
    rows = max(1, _BLOCK // samples)
    finite = np.all(np.isfinite(c2), axis=1)
    out_max[~finite] = np.nan  # e.g. an undamped system exactly at resonance
    out_min[~finite] = np.nan
    c2 = c2[finite]
    at = np.flatnonzero(finite)
    found: list[
        tuple[NDArray[np.intp], NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]
    ]
    found = []
    count = 0
    for start in range(0, c2.shape[0], rows):  # blocks of rows, not a loop per speed
        row, pos, grid_value, is_max = _block_crests(c2[start : start + rows], m, samples)
        found.append((row + start, pos, grid_value, is_max))
        count += row.size
        if count >= _CRESTS or start + rows >= c2.shape[0]:
            # the crests of several blocks refined at once: Newton's few dozen array operations
            # per step are then over thousands of crests, not hundreds
            row, pos, grid_value, is_max = (np.concatenate(a) for a in zip(*found, strict=True))
            largest, smallest = _extremes(
                c2, row, pos * (2.0 * math.pi / samples), grid_value, is_max, m, samples
            )
            first, last = int(row[0]), int(row[-1]) + 1
            out_max[at[first:last]], out_min[at[first:last]] = largest, smallest
            found, count = [], 0
    return out_max.reshape(lead), out_min.reshape(lead)


def _grid(m: NDArray[np.int_], samples: int, dtype: type = np.float64) -> NDArray[np.floating]:
    """(samples, 2K) the basis [cos(m_k phi_j), -sin(m_k phi_j)] of the grid phi_j = 2 pi j /
    samples, C-contiguous: x(phi_j) = basis @ [Re c, Im c], the inverse FFT's values as one
    matrix product (K harmonics of a few dozen: cheaper than a transform of every row); in
    ``dtype`` (the double-precision values rounded)."""
    key = (m.tobytes(), samples, np.dtype(dtype).char)
    found = _BASES.get(key)
    if found is None:
        phi = (2.0 * math.pi / samples) * np.arange(samples)
        angle = np.outer(phi, m.astype(float))
        found = np.ascontiguousarray(np.concatenate([np.cos(angle), -np.sin(angle)], axis=1))
        found = found.astype(dtype)
        if len(_BASES) >= 8:
            _BASES.clear()
        _BASES[key] = found
    return found


_BASES: dict[tuple[bytes, int, str], NDArray[np.floating]] = {}


def _crests(
    x: NDArray[np.floating], bound: NDArray[np.float64]
) -> tuple[NDArray[np.intp], NDArray[np.float64], NDArray[np.intp], NDArray[np.bool_]]:
    """(row, position in grid steps, grid point, which: True for a maximum) of every crest of
    the columns of ``x`` (samples, rows: one column per row of coefficients) within ``bound``
    of the column's largest value (maxima) or of its smallest (minima, as maxima of -x), the
    position from the parabola through the crest's three grid points; the maxima of each row
    before its minima. The thresholds are rounded outwards to the precision of ``x`` (a value
    at a threshold is kept)."""
    samples, count = x.shape
    best = np.max(x, axis=0)  # along the first axis: elementwise over contiguous rows, fast
    worst = np.min(x, axis=0)
    high = np.nextafter((best - bound).astype(x.dtype), -np.inf)
    low = np.nextafter((worst + bound).astype(x.dtype), np.inf)
    near = (x >= high) | (x <= low)
    flat = np.flatnonzero(near)
    j, row = np.divmod(flat, count)  # by grid point, then row: each row's crests by angle
    y1 = x.ravel()[flat].astype(float)
    top = y1 >= high[row]
    # a value near both extremes (a row of round-off) is a candidate of both
    both = top & (y1 <= low[row])
    if np.any(both):
        row = np.concatenate([row, row[both]])
        j = np.concatenate([j, j[both]])
        y1 = np.concatenate([y1, y1[both]])
        top = np.concatenate([top, np.zeros(int(np.count_nonzero(both)), dtype=bool)])
    sign = np.where(top, 1.0, -1.0)
    y0 = x[(j - 1) % samples, row] * sign
    y2 = x[(j + 1) % samples, row] * sign
    y1 = y1 * sign
    crest = (y1 >= y0) & (y1 >= y2)
    row, j, y0, y1, y2, top = row[crest], j[crest], y0[crest], y1[crest], y2[crest], top[crest]
    den = y0 - 2.0 * y1 + y2
    with np.errstate(divide="ignore", invalid="ignore"):
        shift = np.where(den < 0.0, 0.5 * (y0 - y2) / den, 0.0)
    first = np.lexsort((~top, row))  # by row, the maxima first
    pos = (j + np.clip(shift, -0.5, 0.5))[first]
    return row[first], pos, j[first], top[first]


def _powers(z: NDArray[np.complex128], m: NDArray[np.int_]) -> NDArray[np.complex128]:
    """z^m_k for every z (C,) and harmonic index m_k >= 1 (K,): (C, K), each power the last
    times z to the step between them (the steps' powers by a product over the largest step),
    one product per harmonic, not per index up to the largest."""
    order = np.argsort(m, kind="stable")
    ms = m[order]
    steps = np.diff(np.concatenate([[0], ms]))
    table = np.cumprod(np.broadcast_to(z[:, None], (z.size, int(steps.max()))), axis=1)
    out = np.empty((m.size, z.size), dtype=complex)
    previous = -1
    for j, step in zip(order.tolist(), steps.tolist(), strict=True):  # the K harmonics
        if previous < 0:
            out[j] = table[:, step - 1]
        elif step == 0:  # pragma: no cover - the indices are distinct (half_range)
            out[j] = out[previous]
        else:
            np.multiply(out[previous], table[:, step - 1], out=out[j])
        previous = j
    return out.T


def _block_crests(
    block: NDArray[np.complex128], m: NDArray[np.int_], samples: int
) -> tuple[NDArray[np.intp], NDArray[np.float64], NDArray[np.float64], NDArray[np.bool_]]:
    """:func:`_crests` of the grid of every row of ``block`` (:func:`half_range`): the grid's
    values as one matrix product in single precision (half the time and memory traffic of
    double), each row first scaled by a power of two to the order of one (exact; no row
    underflows or overflows), the bound B of every row widened by twice the product's rounding
    error, so that every crest the double-precision grid would select is selected; the
    candidates' grid values then evaluated again in double precision (they are the floor of
    the row's refined extremes)."""
    parts = np.concatenate([block.real, block.imag], axis=1)  # (R, 2K): [Re c, Im c]
    size = np.sum(np.abs(parts), axis=1)  # sum |Re c| + |Im c| >= every grid value's size
    exponent = np.frexp(np.where(size > 0.0, size, 1.0))[1]
    scale = np.ldexp(1.0, -exponent)  # a power of two: size * scale in [1/2, 1)
    # (samples, R): a column per row, so that the rows' extremes are elementwise maxima of
    # contiguous rows (twice as fast as maxima along the last axis)
    x = _grid(m, samples, np.float32) @ (parts * scale[:, None]).astype(np.float32).T
    mf = m.astype(float)
    step = 2.0 * math.pi / samples
    bound = 0.5 * (0.5 * step) ** 2 * (np.abs(block) @ (mf * mf)) * scale
    # single precision: each of the 2K products and their sum rounded, every input too, so a
    # grid value is within gamma_(2K+2) * sum(|Re c| + |Im c|) (<= (2K+2) u / (1 - (2K+2) u)
    # of the scaled size 1, u = 2^-24; Higham, Accuracy and Stability, 2nd ed., eq. 3.5) of
    # its exact value: a value is selected where its exact one would be, and the row's largest
    # and smallest are off by as much, hence twice the error
    terms = parts.shape[1] + 2
    unit = float(np.finfo(np.float32).eps) / 2.0
    bound = bound + 2.0 * (terms * unit / (1.0 - terms * unit))
    row, pos, j, is_max = _crests(x, bound)
    exact = np.einsum("ij,ij->i", parts[row], _grid(m, samples)[j])
    return row, pos, np.where(is_max, exact, -exact), is_max


def _extremes(
    c: NDArray[np.complex128],
    row: NDArray[np.intp],
    phi: NDArray[np.float64],
    grid_value: NDArray[np.float64],
    is_max: NDArray[np.bool_],
    m: NDArray[np.int_],
    samples: int,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Largest and smallest value over the cycle of the rows ``row[0]..row[-1]`` of ``c``, every
    one with crests (:func:`_crests`, the rows ascending, each row's maxima first) at angles
    ``phi`` (:func:`half_range`)."""
    mf = m.astype(float)
    m2 = mf * mf
    step = 2.0 * math.pi / samples
    phi = phi.copy()  # moved in place, crest by crest
    coef = c[row]
    coef[~is_max] *= -1.0  # the minima as maxima of -x
    top = int(m.max())
    powers = top <= 4 * m.size and bool(np.all(m >= 1))
    weights = np.zeros((2 * m.size, 3))  # (re, im) of every term -> x, x', x''
    weights[0::2, 0] = 1.0
    weights[1::2, 1] = -mf
    weights[0::2, 2] = -m2
    value = np.empty(row.size)
    d1 = np.empty(row.size)
    d2 = np.empty(row.size)
    move = np.empty(row.size)
    # evaluations of every crest: NEWTON, one more for every step that was not Newton's own
    # (clipped to a grid step, or up a shoulder where x is not concave)
    budget = np.full(row.size, NEWTON)
    active = np.arange(row.size)  # the crests still moving
    for k in range(NEWTON_MAX):  # Newton on x'(phi) = 0, all crests at once
        # exp(i m phi) as powers of exp(i phi) where the indices are small
        p = phi[active]
        e = _powers(np.exp(1j * p), m) if powers else np.exp(1j * p[:, None] * mf)
        # x = Re sum_k t_k, x' = -Im sum_k m_k t_k, x'' = -Re sum_k m_k^2 t_k of the terms
        # t_k = c_k exp(i m_k phi): one real product of the terms' (re, im) parts with the
        # weights, its rows padded to a multiple of 8 so that BLAS computes every one in its
        # main kernel (an edge row may be summed in another order: the bits would depend on
        # how many crests are refined together)
        n = p.size
        terms = np.zeros((-(-n // 8) * 8, m.size), dtype=complex)
        np.multiply(coef if n == row.size else coef[active], e, out=terms[:n])
        value[active], d1[active], d2[active] = (terms.view(float) @ weights)[:n].T
        slope, curve = d1[active], d2[active]
        concave = curve < 0.0
        with np.errstate(divide="ignore", invalid="ignore"):
            newton = np.clip(np.where(concave, -slope / curve, 0.0), -step, step)
        # where x is not concave (the parabola's vertex past an inflection, on the shoulder of
        # a crest whose peak is up to a grid step away) half a grid step up the slope instead;
        # such a point's value is its own, not a Taylor step's
        now = np.where(concave, newton, np.copysign(0.5 * step, slope))
        move[active] = newton
        # and one more where the last step would be too long for its Taylor value to be exact
        # to round-off (its error O(sum m^3 |c| d^3): d above TAYLOR of a grid step)
        last = (k + 1 >= budget[active]) & (np.abs(newton) > TAYLOR * step)
        budget[active[~concave | (np.abs(newton) >= step) | last]] += 1
        # a crest whose step is below SETTLED of a grid step keeps its last value and step:
        # further steps would change its Taylor value by O(x''' d^3), far below round-off (the
        # steps shrink quadratically from the parabola's vertex)
        go = (k + 1 < np.minimum(budget[active], NEWTON_MAX)) & (
            (np.abs(now) > SETTLED * step) | ~concave
        )
        phi[active[go]] = p[go] + now[go]
        active = active[go]
        if active.size == 0:
            break
    value = value + d1 * move + 0.5 * d2 * move * move  # the last step, by Taylor
    value = np.maximum(value, grid_value)
    # per row: the largest refined maximum, the largest refined maximum of -x
    key = row * 2 + (~is_max)
    starts = np.flatnonzero(np.concatenate([[True], key[1:] != key[:-1]]))
    best = np.maximum.reduceat(value, starts)
    kind = is_max[starts]
    return best[kind], -best[~kind]
