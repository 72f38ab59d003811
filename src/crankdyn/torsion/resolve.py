"""Resolving a response against speed: resonance seeds, peak refinement and limit crossings
(numeric core).

A forced response sampled on a user's speed grid can miss a resonance peak: a lightly damped
peak is narrower than a 25 rpm step (half-power width about eta n_c for a loss factor eta), so
the largest sampled value, and every verdict drawn from it, depends on the grid. The sweep is
therefore resolved in three steps, each a batched evaluation of all new speeds at once (the
caller supplies the evaluation):

1. *Resonance seeds.* Every resonance inside the range is sampled across its width: for every
   damped natural frequency omega_p = a + i b of the system (the complex eigenvalues of
   (K + i H) + i omega C - omega^2 M: a the damped frequency, b the half-power half-width,
   D. J. Ewins, *Modal Testing*, 2nd ed., 2000, ch. 2) and every order q with a / q in the
   range, the speeds a/q + t b/q for t in :data:`SEED_OFFSETS`, where the grid has no speed
   within 0.35 b/q already (:func:`seed_speeds`). The critical speeds of the undamped modes
   (omega_r / q, seed 003 ch. 5) are added as well, so the outputs can list them.
2. *Peak refinement.* At every interior local maximum of every tracked curve that reaches
   half its curve's largest value (only those can hold the peak once the resonances are
   sampled across their widths), the vertex of the parabola through the maximum and its two
   neighbours is added (successive parabolic interpolation: R. P. Brent, *Algorithms for
   Minimization without Derivatives*, 1973, ch. 5; the parabola is fitted to 1/y^2, exact near
   a single resonance's peak; requests of several curves within 40 % of a bracket make one
   speed), until every candidate's parabola predicts a gain below a quarter of the
   tolerance, i.e. a further refinement changes no peak by more than the tolerance (0.1 % by
   default) (:func:`refinement_speeds`).
3. *Limit crossings.* Where a resolved curve exceeds a limit curve, the ends of each range are
   bracketed by neighbouring samples on either side and bisected, all brackets at once per
   round, until they are narrower than the speed tolerance (:func:`bisect_crossings`).
"""

from __future__ import annotations

import hashlib
import math
from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = [
    "MAX_ROUNDS",
    "SEED_OFFSETS",
    "TOLERANCE",
    "Refiner",
    "bisect_crossings",
    "crossing_brackets",
    "damped_frequencies",
    "damped_frequency_rows",
    "local_maxima",
    "merge_speeds",
    "modal_pole_rows",
    "refinement_speeds",
    "seed_speeds",
]

TOLERANCE = 1e-3
"""Relative change of a peak below which it counts as resolved (0.1 %)."""

SEED_OFFSETS = (-2.0, -1.0, -0.5, 0.0, 0.5, 1.0, 2.0)
"""Seed speeds around a resonance, in half-power half-widths from its centre."""

MAX_ROUNDS = 40
"""Refinement rounds at most (each at least halves every unresolved bracket)."""

_FLOOR = 0.5  # local maxima below this share of their curve's largest value are not refined
_SPACING = 1e-10  # relative: speeds closer than this are one speed


# ---- resonances -----------------------------------------------------------------------------
def damped_frequencies(
    inertia: ArrayLike, stiffness: ArrayLike, damping: ArrayLike, hysteretic: ArrayLike
) -> NDArray[np.complex128]:
    """Complex natural frequencies omega_p = a + i b (rad/s, a > 0) of
    (K + i H) x + i omega C x - omega^2 M x = 0, ascending in a.

    Linearised with v = omega x: omega [x; v] = [[0, I], [M^-1 (K + i H), i M^-1 C]] [x; v],
    a standard eigenproblem of twice the size (F. Tisseur and K. Meerbergen, "The quadratic
    eigenvalue problem", *SIAM Review* 43 (2001) 235-286, section 3.4). a is the damped natural
    frequency, b > 0 the decay rate, which is also the half-power half-width of the resonance
    in omega.

    Parameters
    ----------
    inertia : array_like
        Diagonal of M (kg m^2), (n,).
    stiffness, damping, hysteretic : array_like
        K (N m/rad), C (N m s/rad), H (N m/rad), (n, n).

    Returns
    -------
    numpy.ndarray
        The complex frequencies a + i b (rad/s) with a > 0, ascending in a.

    Examples
    --------
    One mass J = 1 kg m^2 on k = 1e6 N m/rad with c = 20 N m s/rad: the roots of
    k + i omega c - omega^2 J = 0 are omega = sqrt(k/J - (c/2J)^2) + i c/(2J).

    >>> w = damped_frequencies([1.0], [[1e6]], [[20.0]], [[0.0]])
    >>> round(float(w[0].real), 6), round(float(w[0].imag), 9)
    (999.949999, 10.0)
    """
    w = damped_frequency_rows(inertia, stiffness, damping, hysteretic)
    w = w[np.isfinite(w)]
    return np.sort_complex(w)


_POLE_CACHE: dict[tuple[tuple[tuple[int, ...], bytes], ...], NDArray[np.complex128]] = {}
_POLE_CACHE_SIZE = 64


def damped_frequency_rows(
    inertia: ArrayLike, stiffness: ArrayLike, damping: ArrayLike, hysteretic: ArrayLike
) -> NDArray[np.complex128]:
    """:func:`damped_frequencies` of a batch of systems, one row per system.

    The same linearisation (Tisseur and Meerbergen 2001, sec. 3.4). A pure function of its
    inputs, remembered for the last 64 distinct inputs (a calculation that solves the same
    system under several excitations, e.g. the misfiring cylinders of a TVC, finds its poles
    once).

    Parameters
    ----------
    inertia : array_like
        Diagonal of M (kg m^2), (n,).
    stiffness, damping, hysteretic : array_like
        K (N m/rad), C (N m s/rad), H (N m/rad), (..., n, n), broadcast together.

    Returns
    -------
    numpy.ndarray
        (..., 2n) complex frequencies a + i b (rad/s), ascending in a; a NaN real part where
        an eigenvalue is not a damped natural frequency (a <= 0), those last. Read-only.

    Examples
    --------
    Two stiffnesses of one damped mass at once (a batch of two systems):

    >>> rows = damped_frequency_rows(
    ...     [1.0], np.array([[[1e6]], [[4e6]]]), [[20.0]], [[0.0]]
    ... )
    >>> rows.shape, np.round(rows[:, 0].real, 3).tolist()
    ((2, 2), [999.95, 1999.975])
    """
    arrays = [
        np.ascontiguousarray(x, dtype=float) for x in (inertia, stiffness, damping, hysteretic)
    ]
    key = tuple((x.shape, hashlib.blake2b(x.tobytes(), digest_size=16).digest()) for x in arrays)
    found = _POLE_CACHE.get(key)
    if found is None:
        found = _damped_frequency_rows(*arrays)
        found.setflags(write=False)
        if len(_POLE_CACHE) >= _POLE_CACHE_SIZE:
            _POLE_CACHE.pop(next(iter(_POLE_CACHE)))
        _POLE_CACHE[key] = found
    return found


def _damped_frequency_rows(
    inertia: ArrayLike, stiffness: ArrayLike, damping: ArrayLike, hysteretic: ArrayLike
) -> NDArray[np.complex128]:
    m = np.asarray(inertia, dtype=float)
    n = m.size
    k = np.asarray(stiffness, dtype=float) + 1j * np.asarray(hysteretic, dtype=float)
    c = np.asarray(damping, dtype=float)
    lead = np.broadcast_shapes(k.shape[:-2], c.shape[:-2])
    a = np.zeros((*lead, 2 * n, 2 * n), dtype=complex)
    a[..., :n, n:] = np.eye(n)
    a[..., n:, :n] = k / m[:, None]
    a[..., n:, n:] = 1j * c / m[:, None]
    w = np.asarray(np.linalg.eigvals(a), dtype=complex)  # complex already (no copy): typed
    scale = np.max(np.abs(w), axis=-1, keepdims=True, initial=0.0)
    w = np.where(np.isfinite(w) & (w.real > 1e-9 * scale), w, np.nan)
    order = np.argsort(np.where(np.isnan(w), np.inf, w.real), axis=-1, kind="stable")
    return np.take_along_axis(w, order, axis=-1)


def modal_pole_rows(
    inertia: NDArray[np.float64],
    links: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]],
    ground: tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]],
    rigid: int,
    top: float,
) -> NDArray[np.complex128]:
    """Damped natural frequencies a + i b (rad/s) of chains approximated by their undamped modes
    with the damping of their shapes, b_r = phi_r^T (H + omega_r C) phi_r / (2 omega_r) for
    M-normalised phi_r (first-order perturbation of a lightly damped mode: Ewins 2000, ch. 2;
    the large systems' branch of :meth:`crankdyn.torsion.sweep.Sweep.poles`), the modes up to
    ``top`` only, for a batch of chains: each one's modes by bisection and inverse iteration on
    its mass-normalised tridiagonal matrix (LAPACK ``dstebz``/``dstein``, O(n p) for p modes),
    the modal damping by the chain's three-term products.

    Parameters
    ----------
    inertia : numpy.ndarray
        (n,) the inertias (kg m^2).
    links : (numpy.ndarray, numpy.ndarray, numpy.ndarray)
        (k, c, h) of the elements between neighbours, each (..., n - 1) (N m/rad, N m s/rad,
        N m/rad), broadcast together: one chain per leading index.
    ground : (numpy.ndarray, numpy.ndarray, numpy.ndarray)
        (k, c, h) of the elements to ground at every degree of freedom, each (n,).
    rigid : int
        The number of zero frequencies (rigid motions) left out, the lowest modes.
    top : float
        The highest undamped natural frequency kept (rad/s).

    Returns
    -------
    numpy.ndarray
        (..., P) complex frequencies a + i |b| (rad/s), ascending, NaN-padded.

    Examples
    --------
    One mass on a grounded shaft, J = 1 kg m^2, k = 1e6 N m/rad, c = 20 N m s/rad:
    omega = sqrt(k / J), b = c / (2 J).

    >>> rows = modal_pole_rows(
    ...     np.array([1.0]), (np.zeros(0), np.zeros(0), np.zeros(0)),
    ...     (np.array([1e6]), np.array([20.0]), np.array([0.0])), 0, 2e3,
    ... )
    >>> round(float(rows[0].real), 6), round(float(rows[0].imag), 9)
    (1000.0, 10.0)
    """
    import scipy.linalg

    kb, cb, hb = (np.asarray(x, dtype=float) for x in links)
    lead = np.broadcast_shapes(kb.shape[:-1], cb.shape[:-1], hb.shape[:-1])
    n = inertia.size
    batch = math.prod(lead)
    kb, cb, hb = (np.broadcast_to(x, (*lead, n - 1)).reshape(batch, n - 1) for x in (kb, cb, hb))
    kg, cg, hg = (np.asarray(x, dtype=float) for x in ground)
    scale = 1.0 / np.sqrt(inertia)
    found = []
    for k_link, c_link, h_link in zip(kb, cb, hb, strict=True):  # the chains (a few speeds)
        diag = kg.copy()
        diag[:-1] += k_link
        diag[1:] += k_link
        d = diag * scale * scale
        e = -k_link * scale[:-1] * scale[1:]
        bound = float(np.max(np.abs(d)) + 2.0 * np.max(np.abs(e), initial=0.0))
        if n == 1:
            keep = d <= top * top
            lam, psi = d[keep], np.ones((1, 1))[:, keep]
        else:
            lam, psi = scipy.linalg.eigh_tridiagonal(
                d, e, select="v", select_range=(-bound - 1.0, top * top)
            )
        lam, phi = lam[rigid:], psi[:, rigid:] * scale[:, None]
        omega = np.sqrt(np.maximum(lam, 0.0))
        dphi = np.diff(phi, axis=0)
        modal_h = h_link @ (dphi * dphi) + hg @ (phi * phi)
        modal_c = c_link @ (dphi * dphi) + cg @ (phi * phi)
        with np.errstate(divide="ignore", invalid="ignore"):
            b = (modal_h + omega * modal_c) / (2.0 * np.maximum(omega, 1e-300))
        found.append(np.where(omega > 0.0, omega + 1j * np.abs(b), np.nan))
    width = max((f.size for f in found), default=0)
    out = np.full((len(found), width), np.nan, dtype=complex)
    for i, f in enumerate(found):
        out[i, : f.size] = f
    return out.reshape(*lead, width)


def seed_speeds(
    existing: ArrayLike, centre: ArrayLike, half_width: ArrayLike, low: float, high: float
) -> tuple[NDArray[np.float64], NDArray[np.intp]]:
    """Speeds that sample resonances across their widths (module docstring, step 1).

    The centre a/q plus :data:`SEED_OFFSETS` half-power half-widths b/q (Ewins 2000, ch. 2:
    the half-power points of a resonance lie at a +/- b), leaving out those within 0.35
    half-widths of a speed already sampled or of another seed.

    Parameters
    ----------
    existing : array_like
        Speeds already sampled (rad/s).
    centre, half_width : array_like
        Centre and half-power half-width of every resonance in speed (rad/s), (R,).
    low, high : float
        The speed range (rad/s); seeds outside it are left out.

    Returns
    -------
    speeds : numpy.ndarray
        The new speeds (rad/s, ascending).
    resonance : numpy.ndarray
        The index of the resonance each samples (int).

    Examples
    --------
    >>> speeds, which = seed_speeds([99.0, 100.0], [100.0], [1.0], 90.0, 110.0)
    >>> speeds.tolist(), which.tolist()  # 99 and 100 are sampled already
    ([98.0, 99.5, 100.5, 101.0, 102.0], [0, 0, 0, 0, 0])
    """
    centre = np.asarray(centre, dtype=float)
    width = np.asarray(half_width, dtype=float)
    offsets = np.asarray(SEED_OFFSETS)
    points = centre[:, None] + offsets[None, :] * width[:, None]  # (R, T)
    which = np.broadcast_to(np.arange(centre.size)[:, None], points.shape)
    near = 0.35 * np.broadcast_to(width[:, None], points.shape)
    points, which, near = points.ravel(), which.ravel(), near.ravel()
    inside = (points >= low) & (points <= high)
    points, which, near = points[inside], which[inside], near[inside]
    order = np.argsort(points, kind="stable")
    points, which, near = points[order], which[order], near[order]
    have = np.sort(np.asarray(existing, dtype=float))
    far = _distance_to(points, have) > near
    points, which, near = points[far], which[far], near[far]
    keep = _thin(points, near)
    return points[keep], which[keep]


# ---- peaks ------------------------------------------------------------------------------------
def local_maxima(
    values: ArrayLike, floor: float = _FLOOR
) -> tuple[NDArray[np.intp], NDArray[np.intp]]:
    """Interior local maxima of every curve that reach a share of the curve's largest value.

    Parameters
    ----------
    values : array_like
        (S, C) curves sampled at ascending speeds (rows), in any one unit.
    floor : float
        Share of each column's largest value a maximum must reach (dimensionless, default
        0.5: only those can hold the peak once the resonances are sampled across their
        widths).

    Returns
    -------
    row, column : numpy.ndarray
        Indices (int) of the maxima; the first and last rows are never maxima.

    Examples
    --------
    >>> rows, cols = local_maxima([[1.0, 0.0], [3.0, 1.0], [2.0, 4.0], [1.0, 1.0]])
    >>> rows.tolist(), cols.tolist()
    ([1, 2], [0, 1])
    """
    y = np.asarray(values, dtype=float)
    if y.shape[0] < 3:
        return np.zeros(0, dtype=int), np.zeros(0, dtype=int)
    top = np.max(y, axis=0)
    mid = y[1:-1]
    peak = (mid >= y[:-2]) & (mid >= y[2:]) & ((mid > y[:-2]) | (mid > y[2:]))
    peak &= mid >= floor * top
    peak &= top > 0.0
    row, col = np.nonzero(peak)
    return row + 1, col


def refinement_speeds(
    speeds: ArrayLike,
    values: ArrayLike,
    scale: ArrayLike | None = None,
    tolerance: float = TOLERANCE,
    threshold: ArrayLike | None = None,
    exclude: ArrayLike = (),
) -> tuple[NDArray[np.float64], NDArray[np.intp]]:
    """New speeds that resolve the peaks of the curves ``values`` (module docstring, step 2).

    The vertex of the parabola through each local maximum and its neighbours, fitted to 1/y^2
    (successive parabolic interpolation, Brent 1973, ch. 5): near a single lightly damped
    resonance |H|^-2 is quadratic in the frequency, so the vertex is then exact.

    Parameters
    ----------
    speeds : array_like
        Ascending speeds (rad/s), (S,).
    values : array_like
        Curves sampled at them, (S, C) (or (S,) for one), in any one unit.
    scale : array_like or None
        The value each curve's tolerance is relative to, (C,), in the unit of ``values``;
        default its largest value.
    tolerance : float
        Relative change of a peak that counts as resolved (dimensionless, default 1e-3).
    threshold : array_like or None
        Refine only the local maxima above these values (C,) instead of those reaching half
        their curve's largest value (e.g. the maxima of a stress-to-limit ratio near 1).
    exclude : array_like
        Speeds (rad/s) whose neighbourhood is not refined: the resonances of undamped modes,
        where the response is unbounded.

    Returns
    -------
    speeds : numpy.ndarray
        New speeds (rad/s, ascending, none closer than 5 % of its bracket to another speed);
        empty when every peak is resolved.
    column : numpy.ndarray
        The curve that asked for each (int).

    Examples
    --------
    A resonance y = 1/sqrt((omega - 10.3)^2 + 0.01) sampled at 8, 9, ..., 12 rad/s: the
    parabola through 1/y^2 puts its peak at 10.3 exactly.

    >>> s = np.arange(8.0, 13.0)
    >>> new, column = refinement_speeds(s, 1.0 / np.sqrt((s - 10.3) ** 2 + 0.01))
    >>> np.round(new, 12).tolist(), column.tolist()
    ([10.3], [0])
    """
    s = np.asarray(speeds, dtype=float)
    y = np.asarray(values, dtype=float)
    y = y.reshape(y.shape[0], -1)
    if scale is None:
        scale = np.max(y, axis=0) if y.shape[0] else np.zeros(y.shape[1])
    if threshold is None:
        i, c = local_maxima(y)
    else:
        i, c = local_maxima(y, floor=0.0)
        keep = y[i, c] >= np.asarray(threshold)[c]
        i, c = i[keep], c[keep]
    if i.size == 0:
        return np.zeros(0), np.zeros(0, dtype=int)
    return _requests(s, s[i - 1], s[i], s[i + 1], y[i - 1, c], y[i, c], y[i + 1, c], c,
                     np.asarray(scale), tolerance, exclude)  # fmt: skip


def _requests(
    s: NDArray[np.float64],
    x0: NDArray[np.float64],
    x1: NDArray[np.float64],
    x2: NDArray[np.float64],
    y0: NDArray[np.float64],
    y1: NDArray[np.float64],
    y2: NDArray[np.float64],
    c: NDArray[np.intp],
    scale: NDArray[np.float64],
    tolerance: float,
    exclude: ArrayLike,
) -> tuple[NDArray[np.float64], NDArray[np.intp]]:
    """The new speeds of :func:`refinement_speeds` from its local maxima (x1, y1) of the curves
    c (row-major order) and their neighbours (x0, y0), (x2, y2), the sampled speeds s."""
    skip = np.asarray(exclude, dtype=float)
    if skip.size:
        clear = ~np.any((skip[None, :] >= x0[:, None]) & (skip[None, :] <= x2[:, None]), axis=1)
        x0, x1, x2 = x0[clear], x1[clear], x2[clear]
        y0, y1, y2, c = y0[clear], y1[clear], y2[clear], c[clear]
    vertex, top = _peak_estimate(x0, x1, x2, y0, y1, y2)
    gain = np.maximum(top - y1, 0.0)
    narrow = (x2 - x0) <= _SPACING * 100.0 * x1
    todo = (gain > 0.5 * tolerance * scale[c]) & ~narrow
    if not np.any(todo):
        return np.zeros(0), np.zeros(0, dtype=int)
    x0, x1, x2, vertex, c = x0[todo], x1[todo], x2[todo], vertex[todo], c[todo]
    span = x2 - x0
    # the vertex, kept off the bracket's ends (where the parabola puts the peak at the sample
    # itself, the midpoint of the wider neighbouring interval instead)
    wider = np.where(x1 - x0 > x2 - x1, 0.5 * (x0 + x1), 0.5 * (x1 + x2))
    vertex = np.where(np.abs(vertex - x1) > 1e-3 * span, vertex, wider)
    vertex = np.clip(vertex, x0 + 0.05 * span, x2 - 0.05 * span)
    # requests of several curves within 40 % of a bracket of each other: one speed (the others
    # ask again next round, in their narrower brackets); none on top of a sampled speed
    order = np.argsort(vertex, kind="stable")
    points, column, width = vertex[order], c[order], span[order]
    far = _distance_to(points, s) > np.maximum(1e-3 * width, _SPACING * points)
    points, column, width = points[far], column[far], width[far]
    keep = _thin(points, 0.25 * width)
    return points[keep], column[keep]


class Refiner:
    """:func:`refinement_speeds` over a response evaluated in rounds, each round's speeds
    added to the last (the same requests, round by round, as :func:`refinement_speeds` of all
    speeds and curves so far in ascending speed): the curves are held in the order the rows
    were added, and every round re-examines only the rows next to the new ones, where a local
    maximum can appear or vanish, so a round costs the new rows, not the whole table.

    Parameters
    ----------
    speeds : array_like
        (S,) the first rows' speeds (rad/s), distinct.
    values : array_like
        (S, C) their curves.
    scale_of : callable
        ``scale_of(top)`` -> (C,) the values the tolerance is relative to, from every curve's
        largest value so far (:func:`refinement_speeds`'s ``scale``).
    tolerance : float
        As :func:`refinement_speeds`.
    exclude : array_like
        As :func:`refinement_speeds`.

    Examples
    --------
    >>> s = np.arange(8.0, 13.0)
    >>> def curve(x):
    ...     return (1.0 / np.sqrt((x - 10.3) ** 2 + 0.01))[:, None]
    >>> r = Refiner(s, curve(s), lambda top: top)
    >>> new, _ = r.request()
    >>> np.round(new, 12).tolist()
    [10.3]
    >>> r.add(new, curve(new))
    >>> r.request()[0].size  # the peak is sampled
    0
    """

    def __init__(
        self,
        speeds: ArrayLike,
        values: ArrayLike,
        scale_of: Callable[[NDArray[np.float64]], NDArray[np.float64]],
        tolerance: float = TOLERANCE,
        exclude: ArrayLike = (),
    ) -> None:
        s = np.asarray(speeds, dtype=float)
        y = np.asarray(values, dtype=float).reshape(s.size, -1)
        self.scale_of = scale_of
        self.tolerance = tolerance
        self.exclude = exclude
        self.count = s.size
        self.speeds = np.empty(max(2 * s.size, 16))
        self.speeds[: s.size] = s
        self.values = np.empty((self.speeds.size, y.shape[1]))
        self.values[: s.size] = y
        self.top = np.max(y, axis=0) if s.size else np.zeros(y.shape[1])
        self.unordered = bool(np.isnan(y).any())  # whether a value is NaN (compares false)
        self.order = np.argsort(s, kind="stable")  # ascending speed -> row
        self.rows = np.zeros(0, dtype=np.intp)  # the local maxima: row and curve
        self.cols = np.zeros(0, dtype=np.intp)
        self._examine(np.arange(s.size))

    def _examine(self, rows: NDArray[np.intp]) -> None:
        """Re-examine ``rows`` (row indices): drop their maxima, find them again."""
        if self.rows.size:
            stale = np.isin(self.rows, rows)
            self.rows, self.cols = self.rows[~stale], self.cols[~stale]
        n = self.count
        position = np.empty(n, dtype=np.intp)
        position[self.order] = np.arange(n)
        p = position[rows]
        p = np.sort(p[(p >= 1) & (p <= n - 2)])  # the ends are never maxima
        if p.size == 0:
            return
        # the rows p - 1, p, p + 1 of every p gathered once (a new speed's neighbours are
        # examined with it: its window of five rows, not nine), compared once per adjacent pair
        window = np.unique(np.concatenate([p - 1, p, p + 1]))
        y = self.values[self.order[window]]
        rising, falling = y[1:] > y[:-1], y[1:] < y[:-1]
        at = np.searchsorted(window, p)  # p - 1 and p + 1 are its neighbours in the window
        # mid >= before, mid >= after and one of them strictly: local_maxima's rule
        peak = ~falling[at - 1] & ~rising[at] & (rising[at - 1] | falling[at])
        if self.unordered:  # a NaN compares false both ways: no maximum next to it
            bad = np.isnan(y)
            peak &= ~(bad[at - 1] | bad[at] | bad[at + 1])
        r, c = np.nonzero(peak)
        self.rows = np.concatenate([self.rows, self.order[p[r]]])
        self.cols = np.concatenate([self.cols, c])

    def add(self, speeds: ArrayLike, values: ArrayLike) -> None:
        """Add rows (new distinct speeds (rad/s) and their curves).

        Parameters
        ----------
        speeds : array_like
            (K,) the new speeds (rad/s).
        values : array_like
            (K, C) their curves.
        """
        s = np.asarray(speeds, dtype=float)
        y = np.asarray(values, dtype=float).reshape(s.size, -1)
        if s.size == 0:
            return
        n = self.count
        if n + s.size > self.speeds.size:  # grow by half at least (amortised copies)
            size = max(n + s.size, self.speeds.size * 3 // 2)
            speeds_new = np.empty(size)
            speeds_new[:n] = self.speeds[:n]
            values_new = np.empty((size, self.values.shape[1]))
            values_new[:n] = self.values[:n]
            self.speeds, self.values = speeds_new, values_new
        self.speeds[n : n + s.size] = s
        self.values[n : n + s.size] = y
        self.count = n + s.size
        self.top = np.maximum(self.top, np.max(y, axis=0))
        self.unordered = self.unordered or bool(np.isnan(y).any())
        self.order = np.argsort(self.speeds[: self.count], kind="stable")
        position = np.empty(self.count, dtype=np.intp)
        position[self.order] = np.arange(self.count)
        p = position[np.arange(n, self.count)]
        near = np.unique(np.clip(np.concatenate([p - 1, p, p + 1]), 0, self.count - 1))
        self._examine(self.order[near])

    def request(self) -> tuple[NDArray[np.float64], NDArray[np.intp]]:
        """The speeds that refine the peaks not yet resolved (:func:`refinement_speeds` of all
        rows so far).

        Returns
        -------
        speeds : numpy.ndarray
            New speeds (rad/s, ascending); empty when every peak is resolved.
        column : numpy.ndarray
            The curve that asked for each (int).
        """
        n = self.count
        if n < 3 or self.rows.size == 0:
            return np.zeros(0), np.zeros(0, dtype=int)
        y = self.values
        top = self.top
        r, c = self.rows, self.cols
        value = y[r, c]
        keep = (value >= _FLOOR * top[c]) & (top[c] > 0.0)
        r, c = r[keep], c[keep]
        if r.size == 0:
            return np.zeros(0), np.zeros(0, dtype=int)
        position = np.empty(n, dtype=np.intp)
        position[self.order] = np.arange(n)
        p = position[r]
        first = np.lexsort((c, p))  # row-major in ascending speed, as local_maxima
        p, c = p[first], c[first]
        s = self.speeds[:n]
        sorted_s = s[self.order]
        r0, r1, r2 = self.order[p - 1], self.order[p], self.order[p + 1]
        return _requests(sorted_s, s[r0], s[r1], s[r2], y[r0, c], y[r1, c], y[r2, c], c,
                         np.asarray(self.scale_of(top)), self.tolerance, self.exclude)  # fmt: skip

    def table(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """All rows so far in ascending speed.

        Returns
        -------
        speeds, values : numpy.ndarray
            (S,) and (S, C).
        """
        return self.speeds[: self.count][self.order], self.values[: self.count][self.order]


def _peak_estimate(
    x0: NDArray[np.float64],
    x1: NDArray[np.float64],
    x2: NDArray[np.float64],
    y0: NDArray[np.float64],
    y1: NDArray[np.float64],
    y2: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Vertex and value of a peak from three samples around it: the parabola through
    (x, 1/y^2), exact for a single lightly damped resonance near its peak (1/|H|^2 is quadratic
    in the frequency there: |H|^-2 = (omega_r^2 - omega^2)^2 + (eta omega_r^2)^2 ~ 4 omega_r^2
    (omega - omega_r)^2 + const), where all three samples are positive and that parabola opens
    upwards; else the parabola through (x, y)."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        z0, z1, z2 = 1.0 / (y0 * y0), 1.0 / (y1 * y1), 1.0 / (y2 * y2)
        xz, low = _parabola(x0, x1, x2, -z0, -z1, -z2)
        top_z = 1.0 / np.sqrt(-low)
    xy, top_y = _parabola(x0, x1, x2, y0, y1, y2)
    ok = (y0 > 0.0) & (y1 > 0.0) & (y2 > 0.0) & np.isfinite(top_z) & (low < 0.0)
    return np.where(ok, xz, xy), np.where(ok, top_z, top_y)


def _parabola(
    x0: NDArray[np.float64],
    x1: NDArray[np.float64],
    x2: NDArray[np.float64],
    y0: NDArray[np.float64],
    y1: NDArray[np.float64],
    y2: NDArray[np.float64],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Vertex abscissa and value of the parabola through three points (x0 < x1 < x2); where
    the points are collinear or convex, (x1, y1)."""
    d0, d2 = x1 - x0, x1 - x2
    num = d0 * d0 * (y1 - y2) - d2 * d2 * (y1 - y0)
    den = d0 * (y1 - y2) - d2 * (y1 - y0)
    with np.errstate(divide="ignore", invalid="ignore"):
        xv = x1 - 0.5 * num / den
    ok = np.isfinite(xv) & (den != 0.0) & (xv > x0) & (xv < x2)
    xv = np.where(ok, xv, x1)
    # Lagrange form at the vertex
    with np.errstate(divide="ignore", invalid="ignore"):
        l0 = (xv - x1) * (xv - x2) / ((x0 - x1) * (x0 - x2))
        l1 = (xv - x0) * (xv - x2) / ((x1 - x0) * (x1 - x2))
        l2 = (xv - x0) * (xv - x1) / ((x2 - x0) * (x2 - x1))
    top = np.where(ok, l0 * y0 + l1 * y1 + l2 * y2, y1)
    return xv, top


def merge_speeds(*groups: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.intp]]:
    """The sorted union of speed arrays, speeds equal to 1e-10 relative counting as one.

    Parameters
    ----------
    *groups : array_like
        Speed arrays (rad/s), any order.

    Returns
    -------
    speeds : numpy.ndarray
        The union (rad/s), ascending.
    first : numpy.ndarray
        For each speed of the union, the index of its first occurrence in the concatenation
        of the groups (int).

    Examples
    --------
    >>> speeds, first = merge_speeds([1.0, 3.0], [2.0, 3.0])
    >>> speeds.tolist(), first.tolist()
    ([1.0, 2.0, 3.0], [0, 2, 1])
    """
    every = np.concatenate([np.asarray(g, dtype=float).ravel() for g in groups])
    order = np.argsort(every, kind="stable")
    sorted_ = every[order]
    if sorted_.size == 0:
        return sorted_, order
    new = np.concatenate([[True], np.diff(sorted_) > _SPACING * sorted_[1:]])
    return sorted_[new], order[new]


# ---- crossings --------------------------------------------------------------------------------
def crossing_brackets(
    excess: ArrayLike,
) -> tuple[NDArray[np.intp], NDArray[np.intp], NDArray[np.bool_]]:
    """Where a sampled excess changes sign between neighbouring speeds (module docstring,
    step 3).

    Parameters
    ----------
    excess : array_like
        (S, C) curve minus limit at ascending speeds (any one unit; NaN where there is no
        limit: no crossing there).

    Returns
    -------
    row, column : numpy.ndarray
        The crossings (int), each between rows ``row`` and ``row + 1``.
    rising : numpy.ndarray
        True (bool) where the excess becomes positive.

    Examples
    --------
    >>> row, col, rising = crossing_brackets([[-1.0], [1.0], [2.0], [-1.0]])
    >>> row.tolist(), col.tolist(), rising.tolist()
    ([0, 2], [0, 0], [True, False])
    """
    e = np.asarray(excess, dtype=float)
    above = e > 0.0
    known = np.isfinite(e)
    change = (above[1:] != above[:-1]) & known[1:] & known[:-1]
    row, col = np.nonzero(change)
    return row, col, above[row + 1, col]


def bisect_crossings(
    evaluate: Callable[[NDArray[np.float64], NDArray[np.intp]], ArrayLike],
    low: ArrayLike,
    high: ArrayLike,
    rising: ArrayLike,
    width: float,
) -> NDArray[np.float64]:
    """Bisect brackets on the sign of an excess until each is narrower than ``width``.

    Bisection, all brackets at once per round (module docstring, step 3).

    Parameters
    ----------
    evaluate : callable
        ``evaluate(speeds, k)`` returns the excess (any unit, the sign counts) at ``speeds``
        (rad/s) for the brackets of index ``k``: one batched call per round for all brackets.
    low, high : array_like
        The brackets' ends (rad/s), (B,).
    rising : array_like
        (B,) bool: the excess is <= 0 at ``low`` and > 0 at ``high`` (else the reverse).
    width : float
        The final brackets' width (rad/s), > 0.

    Returns
    -------
    numpy.ndarray
        The crossings (rad/s): the midpoints of the final brackets, (B,).

    Examples
    --------
    >>> root = bisect_crossings(lambda s, k: s**2 - 2.0, [1.0], [2.0], [True], 1e-9)
    >>> round(float(root[0]), 8)  # sqrt(2)
    1.41421356
    """
    lo = np.array(low, dtype=float)
    hi = np.array(high, dtype=float)
    rising = np.asarray(rising, dtype=bool)
    rounds = max(0, math.ceil(math.log2(max(float(np.max(hi - lo, initial=0.0)), width) / width)))
    for _ in range(rounds + 1):
        todo = np.flatnonzero(hi - lo > width)
        if todo.size == 0:
            break
        mid = 0.5 * (lo[todo] + hi[todo])
        positive = np.asarray(evaluate(mid, todo), dtype=float) > 0.0
        goes_high = positive == rising[todo]  # the crossing lies below mid
        hi[todo] = np.where(goes_high, mid, hi[todo])
        lo[todo] = np.where(goes_high, lo[todo], mid)
    return 0.5 * (lo + hi)


# ---- helpers -----------------------------------------------------------------------------------
def _distance_to(
    points: NDArray[np.float64], sorted_values: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Distance of every point to the nearest of ascending ``sorted_values`` (inf if none)."""
    if sorted_values.size == 0:
        return np.full(points.shape, np.inf)
    j = np.searchsorted(sorted_values, points)
    left = sorted_values[np.clip(j - 1, 0, sorted_values.size - 1)]
    right = sorted_values[np.clip(j, 0, sorted_values.size - 1)]
    return np.minimum(np.abs(points - left), np.abs(right - points))


def _thin(points: NDArray[np.float64], near: NDArray[np.float64]) -> NDArray[np.bool_]:
    """Keep the first of every run of ascending points closer than ``near`` to the previous
    one (so a cluster of requests adds one speed)."""
    if points.size == 0:
        return np.zeros(0, dtype=bool)
    gap = np.diff(points)
    return np.concatenate([[True], gap > np.maximum(near[1:], _SPACING * points[1:])])
