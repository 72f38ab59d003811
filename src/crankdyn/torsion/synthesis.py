"""Time-domain synthesis of harmonic orders (numeric core): the largest and smallest value over
one period of a sum of harmonics, by an inverse FFT and Newton refinement of every near-extreme
crest (:func:`half_range`; the synthesised half-range amplitude of
:mod:`crankdyn.torsion.response`)."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["NEWTON", "half_range"]

_BLOCK = 1 << 19  # elements per block of the time-domain synthesis (2048 rows: in cache)
NEWTON = 4  # evaluations per crest in the time-domain synthesis (the last step by Taylor)


# ---- the synthesis ----------------------------------------------------------------------
def half_range(
    coefficients: ArrayLike, harmonic: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(max, min) over one cycle of x(phi) = sum_k Re(c_k exp(i m_k phi)), phi in [0, 2 pi),
    for complex coefficients (..., K) at integer harmonic indices m_k (module docstring).

    x is sampled by an inverse FFT at N >= 8 points per period of the highest harmonic. A
    grid value lies within B = (1/2) (pi/N)^2 sum_k m_k^2 |c_k| of the nearest crest, so every
    grid crest within B of the grid's extreme is refined (not only the grid's extreme: two
    crests of nearly equal height are otherwise confused, by up to B): from the vertex of the
    parabola through its three grid points, by Newton's method on x'(phi) = 0 (three steps,
    each kept within one grid step; the fourth taken in the Taylor expansion of x). The
    harmonics exp(i m phi) are products of exp(i phi) where the indices are small. Vectorised
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
    top = max(int(m.max()), 1)
    samples = max(64, 1 << math.ceil(math.log2(8 * top)))
    out_max = np.empty(c2.shape[0])
    out_min = np.empty(c2.shape[0])
    rows = max(1, _BLOCK // samples)
    finite = np.all(np.isfinite(c2), axis=1)
    out_max[~finite] = np.nan  # e.g. an undamped system exactly at resonance
    out_min[~finite] = np.nan
    c2 = c2[finite]
    at = np.flatnonzero(finite)
    for start in range(0, c2.shape[0], rows):  # blocks of rows, not a loop per speed
        block = c2[start : start + rows]
        where = at[start : start + block.shape[0]]
        out_max[where], out_min[where] = _extremes(block, m, samples)
    return out_max.reshape(lead), out_min.reshape(lead)


def _crests(
    sx: NDArray[np.float64], bound: NDArray[np.float64]
) -> tuple[NDArray[np.intp], NDArray[np.float64], NDArray[np.float64]]:
    """(row, position in grid steps, grid value) of every crest of the rows of ``sx`` within
    ``bound`` of the row's largest value, the position from the parabola through the crest's
    three grid points."""
    samples = sx.shape[1]
    best = np.max(sx, axis=1)
    row, j = np.nonzero(sx >= (best - bound)[:, None])
    y0, y1, y2 = sx[row, (j - 1) % samples], sx[row, j], sx[row, (j + 1) % samples]
    crest = (y1 >= y0) & (y1 >= y2)
    row, j, y0, y1, y2 = row[crest], j[crest], y0[crest], y1[crest], y2[crest]
    den = y0 - 2.0 * y1 + y2
    with np.errstate(divide="ignore", invalid="ignore"):
        shift = np.where(den < 0.0, 0.5 * (y0 - y2) / den, 0.0)
    return row, j + np.clip(shift, -0.5, 0.5), y1


def _extremes(
    block: NDArray[np.complex128], m: NDArray[np.int_], samples: int
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Largest and smallest value over the cycle of every row of ``block`` (:func:`half_range`)."""
    count = block.shape[0]
    spectrum = np.zeros((count, samples // 2 + 1), dtype=complex)
    spectrum[:, m] = block * (samples / 2.0)
    x = np.fft.irfft(spectrum, n=samples, axis=-1)
    mf = m.astype(float)
    m2 = mf * mf
    step = 2.0 * math.pi / samples
    bound = 0.5 * (0.5 * step) ** 2 * (np.abs(block) @ m2)
    r1, p1, y1 = _crests(x, bound)
    r2, p2, y2 = _crests(-x, bound)
    row = np.concatenate([r1, r2])
    phi = np.concatenate([p1, p2]) * step
    coef = block[row]
    coef[r1.size :] *= -1.0  # the minima as maxima of -x
    top = int(m.max())
    powers = top <= 4 * m.size and bool(np.all(m >= 1))
    for k in range(NEWTON):  # Newton on x'(phi) = 0, all crests at once
        if powers:  # exp(i m phi) as powers of exp(i phi)
            z = np.exp(1j * phi)
            e = np.cumprod(np.broadcast_to(z[:, None], (z.size, top)), axis=1)[:, m - 1]
        else:
            e = np.exp(1j * phi[:, None] * mf)
        p = coef * e
        value = p.real.sum(axis=1)
        d1 = -(p.imag @ mf)
        d2 = -(p.real @ m2)
        with np.errstate(divide="ignore", invalid="ignore"):
            move = np.clip(np.where(d2 < 0.0, -d1 / d2, 0.0), -step, step)
        if k < NEWTON - 1:
            phi = phi + move
    value = value + d1 * move + 0.5 * d2 * move * move  # the last step, by Taylor
    value = np.maximum(value, np.concatenate([y1, y2]))
    out = []
    for rows, values in ((r1, value[: r1.size]), (r2, value[r1.size :])):
        starts = np.flatnonzero(np.concatenate([[True], rows[1:] != rows[:-1]]))
        out.append(np.maximum.reduceat(values, starts))
    return out[0], -out[1]
