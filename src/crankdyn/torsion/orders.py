"""Orders of the working cycle: the Fourier coefficients of a torque over the cycle, phase
vectors and major orders (numeric core of :mod:`crankdyn.torsion.excitation`).

Each cylinder's tangential torque M_i(theta) (gas and inertia parts, :mod:`crankdyn.engine.forces`)
repeats once per working cycle, so it is a Fourier series in the *orders* q of the crankshaft
speed, q = 0.5, 1, 1.5, ... for a four-stroke engine (cycle 720 deg) and q = 1, 2, ... for a
two-stroke engine (seed 003, 第4章 "曲轴系统的激发力矩": the single-cylinder torque and its
harmonics; the V6 paper of seed 003, eq. 5, T(wt) = a_0/2 + sum (a_n cos + b_n sin)):

    M_i(theta) = M_mean + sum_q Re( c_q,i exp(i q theta) ),   theta = Omega t the crankshaft angle
    (0 at cylinder 1's firing TDC),

with complex amplitude c_q,i = (2/Theta) int_0^Theta M_i(theta) exp(-i q theta) dtheta over the
cycle Theta. Computed over the crankshaft angle, the coefficient already carries the cylinder's
phase: a cylinder firing at Phi_i has c_q,i = c_q exp(-i q Phi_i), c_q being the coefficient of the
torque measured from its own firing TDC (phase-vector rule, seed 003 section 4.2
"多拐曲轴上第k阶力矩谐量的相位关系"). The integral is evaluated with the FFT of the torque sampled
at 7200 equally spaced angles over the cycle (0.1 deg for a four-stroke cycle, so that firing
angles in tenths of a degree fall on the grid; the trapezoidal rule, exact for a periodic
trigonometric polynomial, with an error of order h^2 at the kinks of the interpolated trace).

Major and minor orders. The phase-vector sum of an order over the cylinders,
|sum_i exp(-i q Phi_i)|, equals the number of cylinders Z when all cylinders' vectors of that
order line up (a *major* order: q = k Z/2 for an evenly firing four-stroke engine); the other
orders are *minor*. Over a mode shape the sum weighs each cylinder by the relative amplitude
beta_i of its mass in that mode: the *relative amplitude sum* |sum_i beta_i exp(-i q Phi_i)|
(seed 003 section 4.2; Ker Wilson vol. 2), large for the orders that excite that mode.
Both need the firing angles: a model that gives neither firing angles nor a firing order is
excited with all cylinders in phase (an assumption, noted), and its major orders and relative
amplitude sums are *undetermined* (None, with
:data:`crankdyn.torsion.excitation.MAJOR_UNDETERMINED` as the note) rather than every order
marked major.
"""

from __future__ import annotations

import math
from typing import TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.engine.firing import CYCLE_ANGLE
from crankdyn.errors import InputError

__all__ = [
    "CYCLES",
    "check_orders",
    "fourier_coefficients",
    "fundamental_order",
    "harmonic_index",
    "major_orders",
    "order_grid",
    "phase_vector_sums",
    "phase_vectors",
    "relative_amplitude_sums",
]

Complex: TypeAlias = NDArray[np.complex128]
"""Complex harmonic amplitudes (N m, or Pa for tangential pressures)."""

CYCLES = ("four-stroke", "two-stroke")
_ORDER_TOL = 1e-9
_MAJOR_TOL = 1e-6


def fundamental_order(cycle: str) -> float:
    """Lowest order of a working cycle: 0.5 for four-stroke, 1 for two-stroke engines.

    The cylinder torque repeats once per cycle Theta (720 deg four-stroke, 360 deg two-stroke),
    so its orders are multiples of 2 pi / Theta (seed 003, ch. 4; module docstring).

    Parameters
    ----------
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"``.

    Returns
    -------
    float
        The fundamental order (per crankshaft revolution, dimensionless).

    Examples
    --------
    >>> fundamental_order("four-stroke"), fundamental_order("two-stroke")
    (0.5, 1.0)
    """
    return 2.0 * math.pi / CYCLE_ANGLE[cycle]


def check_orders(
    orders: ArrayLike, cycle: str = "four-stroke", *, key: str = "orders"
) -> NDArray[np.float64]:
    """Validate orders: finite, positive, distinct, each a multiple of the cycle's fundamental
    order (0.5 four-stroke, 1 two-stroke).

    Parameters
    ----------
    orders : array_like
        Orders (per crankshaft revolution, dimensionless), shape (orders,) or a scalar.
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"``.
    key : str
        The input key named in an error message.

    Returns
    -------
    numpy.ndarray
        The orders as floats, snapped to the exact multiples of the fundamental order, in the
        order given; shape (orders,).

    Raises
    ------
    crankdyn.errors.InputError
        No order, an order not positive or not finite, not a multiple of the fundamental order,
        or given twice; the message names ``key`` and the offending value.

    Examples
    --------
    >>> check_orders([1, 0.5, 3])
    array([1. , 0.5, 3. ])
    >>> check_orders([1.0, -1.0], "two-stroke")
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: orders = -1.0: orders must be positive
    """
    q = np.atleast_1d(np.asarray(orders, dtype=float))
    if q.ndim != 1 or q.size == 0:
        raise InputError("expected at least one order", key=key)
    if not np.all(np.isfinite(q)) or np.any(q <= 0.0):
        bad = q[~(np.isfinite(q) & (q > 0.0))][0]
        raise InputError("orders must be positive", key=key, value=float(bad))
    base = fundamental_order(cycle)
    m = q / base
    off = np.abs(m - np.round(m)) > _ORDER_TOL * np.maximum(m, 1.0)
    if np.any(off):
        raise InputError(
            f"order {q[off][0]:g} does not fit the {cycle} cycle: orders are multiples of {base:g}",
            key=key,
            value=float(q[off][0]),
        )
    if np.unique(np.round(m)).size != q.size:
        raise InputError("orders must be distinct", key=key)
    return np.round(m) * base


def order_grid(
    first: float, last: float, step: float | None = None, cycle: str = "four-stroke"
) -> NDArray[np.float64]:
    """Orders first, first + step, ... last (step defaults to the fundamental order).

    Parameters
    ----------
    first, last : float
        First and last order (dimensionless); ``last`` is included when the steps reach it.
    step : float or None
        Step between orders (dimensionless), > 0; None for the cycle's fundamental order.
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"``.

    Returns
    -------
    numpy.ndarray
        The orders (:func:`check_orders`), shape (orders,).

    Raises
    ------
    crankdyn.errors.InputError
        A step not positive, an empty range, more than 10000 orders or orders that do not fit
        the cycle (key ``orders``).

    Examples
    --------
    >>> order_grid(0.5, 2.0)
    array([0.5, 1. , 1.5, 2. ])
    >>> order_grid(1, 6, 2, "two-stroke")
    array([1., 3., 5.])
    """
    step = fundamental_order(cycle) if step is None else step
    if not (math.isfinite(first) and math.isfinite(last) and math.isfinite(step)) or step <= 0:
        raise InputError("expected FIRST:LAST[:STEP] with a positive step", key="orders")
    if last < first:
        raise InputError("the order range is empty: LAST is below FIRST", key="orders")
    count = math.floor((last - first) / step * (1 + 1e-12)) + 1
    if count > 10_000:
        raise InputError("too many orders (more than 10000)", key="orders")
    return check_orders(first + step * np.arange(count), cycle)


def harmonic_index(orders: ArrayLike, cycle: str) -> NDArray[np.int_]:
    """Index m of each order in the Fourier series over the cycle: m = q Theta / (2 pi).

    Parameters
    ----------
    orders : array_like
        Orders (dimensionless).
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"``.

    Returns
    -------
    numpy.ndarray
        The integer index of every order, same shape.

    Examples
    --------
    >>> harmonic_index([0.5, 1.0, 3.0], "four-stroke")
    array([1, 2, 6])
    """
    return np.round(np.asarray(orders) / fundamental_order(cycle)).astype(int)


def fourier_coefficients(samples: ArrayLike, orders: ArrayLike, cycle: str) -> Complex:
    """Complex amplitudes c_q of a periodic signal sampled at N equally spaced angles over one
    cycle (last axis, endpoint excluded): f(theta) = mean + sum_q Re(c_q exp(i q theta)),
    c_q = (2/N) sum_j f_j exp(-i q theta_j) (the FFT; the trapezoidal rule over the period,
    seed 003 eq. 5; module docstring).

    Parameters
    ----------
    samples : array_like
        The signal (any unit), shape (..., N): N samples over one cycle, at theta_j = j Theta/N.
    orders : array_like
        Orders to extract (dimensionless), shape (orders,), multiples of the fundamental order.
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"`` (the period Theta).

    Returns
    -------
    numpy.ndarray
        Complex amplitudes c_q (unit of the signal), shape (..., orders).

    Raises
    ------
    crankdyn.errors.InputError
        An order at or above the Nyquist order of the sampling.

    Examples
    --------
    >>> theta = np.arange(8) * (2 * np.pi / 8)
    >>> c = fourier_coefficients(3.0 * np.cos(2 * theta - 0.5), [1, 2], "two-stroke")
    >>> np.round(np.abs(c), 12), round(float(np.angle(c[1])), 12)
    (array([0., 3.]), -0.5)
    """
    f = np.asarray(samples, dtype=float)
    n = f.shape[-1]
    m = harmonic_index(orders, cycle)
    if np.any(m >= n // 2):
        raise InputError(f"orders above {n // 2 * fundamental_order(cycle):g} are not resolved")
    spectrum = np.fft.rfft(f, axis=-1)
    return spectrum[..., m] * (2.0 / n)


def phase_vectors(firing_angles: ArrayLike, orders: ArrayLike) -> Complex:
    """exp(-i q Phi_i), shape (orders, cylinders): the phase of order q of a cylinder firing at
    Phi_i (rad) relative to one firing at 0 (seed 003 section 4.2, phase-vector rule).

    Parameters
    ----------
    firing_angles : array_like
        Firing angle Phi_i of every cylinder (rad), shape (cylinders,).
    orders : array_like
        Orders q (dimensionless), shape (orders,).

    Returns
    -------
    numpy.ndarray
        Unit complex phase vectors (dimensionless), shape (orders, cylinders).
    """
    q = np.asarray(orders, dtype=float)[:, None]
    return np.exp(-1j * q * np.asarray(firing_angles, dtype=float)[None, :])


def phase_vector_sums(firing_angles: ArrayLike, orders: ArrayLike) -> NDArray[np.float64]:
    """Phase-vector sum |sum_i exp(-i q Phi_i)| of every order (seed 003 section 4.2; Ker
    Wilson vol. 2; module docstring).

    Parameters
    ----------
    firing_angles : array_like
        Firing angle Phi_i of every cylinder (rad), shape (cylinders,).
    orders : array_like
        Orders q (dimensionless), shape (orders,).

    Returns
    -------
    numpy.ndarray
        The sums (dimensionless, 0 ... Z for Z cylinders), shape (orders,).

    Examples
    --------
    An in-line four, four-stroke, firing 1-3-4-2 (cylinders at 0, 540, 180, 360 deg): only
    the multiples of order 2 are major.

    >>> phi = np.radians([0.0, 540.0, 180.0, 360.0])
    >>> np.round(phase_vector_sums(phi, [0.5, 1.0, 2.0]), 12)
    array([0., 0., 4.])
    """
    return np.abs(np.sum(phase_vectors(firing_angles, orders), axis=1))


def major_orders(firing_angles: ArrayLike, orders: ArrayLike) -> NDArray[np.bool_]:
    """Whether each order is major: the phase vectors of all cylinders line up (sum = Z).

    Parameters
    ----------
    firing_angles : array_like
        Firing angle Phi_i of every cylinder (rad), shape (cylinders,).
    orders : array_like
        Orders q (dimensionless), shape (orders,).

    Returns
    -------
    numpy.ndarray
        True for a major order (:func:`phase_vector_sums` equal to Z to a relative 1e-6),
        shape (orders,).

    Examples
    --------
    >>> major_orders(np.radians([0.0, 540.0, 180.0, 360.0]), [0.5, 1.0, 2.0, 4.0])
    array([False, False,  True,  True])
    """
    z = len(np.atleast_1d(firing_angles))
    return phase_vector_sums(firing_angles, orders) >= z * (1.0 - _MAJOR_TOL)


def relative_amplitude_sums(
    cylinder_amplitudes: ArrayLike, firing_angles: ArrayLike, orders: ArrayLike
) -> NDArray[np.float64]:
    """Relative amplitude sums |sum_i beta_i exp(-i q Phi_i)| (seed 003 section 4.2; Ker Wilson
    vol. 2; module docstring).

    Parameters
    ----------
    cylinder_amplitudes : array_like
        Relative amplitude beta_i (dimensionless) of the mass carrying each cylinder in each
        mode, shape (modes, cylinders), normalised by the caller (e.g. largest cylinder
        amplitude 1).
    firing_angles : array_like
        Firing angle Phi_i of every cylinder (rad), shape (cylinders,).
    orders : array_like
        Orders q (dimensionless), shape (orders,).

    Returns
    -------
    numpy.ndarray
        The sums (dimensionless), shape (modes, orders).

    Examples
    --------
    A mode in which cylinders 1 and 4 swing against 2 and 3 of an in-line four firing
    1-3-4-2: the major order 2 cancels, the minor order 1 adds up.

    >>> phi = np.radians([0.0, 540.0, 180.0, 360.0])
    >>> np.round(relative_amplitude_sums([[1.0, -1.0, -1.0, 1.0]], phi, [1.0, 2.0]), 12)
    array([[4., 0.]])
    """
    beta = np.asarray(cylinder_amplitudes, dtype=float)
    return np.abs(beta @ phase_vectors(firing_angles, orders).T)
