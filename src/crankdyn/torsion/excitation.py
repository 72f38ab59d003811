"""Engine excitation of torsional vibration: harmonic analysis of the cylinder torques (analysis).

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

Dependence on speed. The inertia part -m_j a R sin(phi + beta)/cos(beta) scales with Omega^2
(a = R Omega^2 f(phi) at constant speed), so its harmonics are Omega^2 times those at 1 rad/s.
The gas part follows the pressure at that speed or load:

- a load curve (speed against peak pressure, IMEP or a plain load factor) scales the absolute
  pressure of the engine's trace by s(Omega) = peak(Omega)/peak(trace) (or IMEP ratio, or the
  factor): the gas torque harmonics are s c_q[p A lever R] - c_q[p_cc A lever R] (the crankcase
  pressure p_cc is not scaled) - the calculation of Mendes et al. (2008), who scale their
  full-load trace by the measured peak-pressure curve;
- or traces at several speeds: the harmonics of each, interpolated linearly in speed;
- or a harmonic-coefficient table (the classical tables of tangential-pressure harmonics
  against mean indicated pressure, e.g. W. Ker Wilson, *Practical Solution of Torsional
  Vibration Problems*, vol. 2, ch. 20): T_q(p_mi) per order, in the sine form
  T_q sin(q theta + psi_q) from firing TDC, so c_q = A R T_q exp(i (psi_q - pi/2)); without
  phases the gas and inertia harmonics of an order are added as if in phase (their amplitudes
  add: the conservative choice; the phase between cylinders comes from the firing angles and is
  exact either way).

Major and minor orders. The phase-vector sum of an order over the cylinders,
|sum_i exp(-i q Phi_i)|, equals the number of cylinders Z when all cylinders' vectors of that
order line up (a *major* order: q = k Z/2 for an evenly firing four-stroke engine); the other
orders are *minor*. Over a mode shape the sum weighs each cylinder by the relative amplitude
beta_i of its mass in that mode: the *relative amplitude sum* |sum_i beta_i exp(-i q Phi_i)|
(seed 003 section 4.2; Ker Wilson vol. 2), large for the orders that excite that mode.
Both need the firing angles: a model that gives neither firing angles nor a firing order is
excited with all cylinders in phase (an assumption, noted), and its major orders and relative
amplitude sums are *undetermined* (None, with :data:`MAJOR_UNDETERMINED` as the note) rather
than every order marked major.

Misfire (or cylinder cut-out, the same physics: no combustion in the cylinder, compression kept):
the cylinder's gas pressure is replaced by the motored pressure, polytropic compression and
expansion from the intake pressure (the synthetic model of :mod:`crankdyn.crank.pressure_model`
with no heat release), which needs the compression ratio. Under a load curve the motored
pressure is scaled by the same factor s(Omega) as the firing cylinders' absolute pressure: the
cylinders share the intake manifold, so at part load a misfiring cylinder compresses the same
(lower) charge as its neighbours, whose scaled traces carry that charge's compression.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, ClassVar, TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import DEG, RPM
from crankdyn.engine.firing import CYCLE_ANGLE, even_firing_interval
from crankdyn.errors import InputError
from crankdyn.results import Result, array, freeze, scalar

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.crank.pressure import PressureTrace
    from crankdyn.engine.model import Engine
    from crankdyn.torsion.modal import ModalResult
    from crankdyn.torsion.model import TorsionModel

__all__ = [
    "CYCLES",
    "MAJOR_UNDETERMINED",
    "EngineExcitation",
    "ExcitationSpec",
    "HarmonicResult",
    "HarmonicTable",
    "LoadCurve",
    "SpeedTrace",
    "UniformExcitation",
    "check_orders",
    "excitation_for",
    "fourier_coefficients",
    "fundamental_order",
    "harmonic_analysis",
    "known_major_orders",
    "major_orders",
    "order_grid",
    "phase_vector_sums",
    "relative_amplitude_sums",
]

Complex: TypeAlias = NDArray[np.complex128]
"""Complex harmonic amplitudes (N m, or Pa for tangential pressures)."""

CYCLES = ("four-stroke", "two-stroke")
SAMPLES = 7200
"""Samples per cycle for the harmonic analysis (FFT length)."""
_ORDER_TOL = 1e-9
_MAJOR_TOL = 1e-6
MAJOR_UNDETERMINED = (
    "major orders undetermined: the model gives no firing order or firing angles, so every "
    "cylinder is excited in phase (an assumption); give [excitation] firing_order or "
    "firing_angles to mark the major orders"
)


# ---- numeric core -------------------------------------------------------------------------------
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


def known_major_orders(excitation: Excitation, orders: ArrayLike) -> NDArray[np.bool_] | None:
    """:func:`major_orders` of an excitation's firing angles, or None when the excitation does
    not know its cylinders' phases (module docstring: a model without firing angles).

    Parameters
    ----------
    excitation : Excitation
        An :class:`EngineExcitation`, :class:`UniformExcitation` or :class:`SourceExcitation`.
    orders : array_like
        Orders (dimensionless), shape (orders,).

    Returns
    -------
    numpy.ndarray or None
        Whether each order is major, shape (orders,); None when the phases are an assumption.

    Examples
    --------
    >>> known = UniformExcitation(1.0, np.radians([0.0, 360.0]))
    >>> known_major_orders(known, [0.5, 1.0])
    array([False,  True])
    >>> print(known_major_orders(UniformExcitation(1.0, [0.0, 0.0], phases_known=False), [1.0]))
    None
    """
    if not getattr(excitation, "phases_known", True):
        return None
    return major_orders(excitation.firing_angles, orders)


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


def _cycle_grid(cycle: str, samples: int = SAMPLES) -> NDArray[np.float64]:
    return np.arange(samples, dtype=float) * (CYCLE_ANGLE[cycle] / samples)


# ---- domain: excitation data --------------------------------------------------------------------
LOAD_KINDS = ("peak_pressure", "imep", "load_factor")


@dataclass(frozen=True, eq=False)
class LoadCurve:
    """Engine load against speed: peak pressure (Pa), IMEP (Pa) or a load factor, interpolated
    linearly in speed and held at the end values outside the curve.

    Parameters
    ----------
    speed : array_like
        Speeds (rad/s), shape (points,), strictly increasing, > 0.
    value : array_like
        Peak pressure (Pa), IMEP (Pa) or load factor (dimensionless) at those speeds, shape
        (points,), > 0.
    kind : str
        ``"peak_pressure"``, ``"imep"`` or ``"load_factor"``.
    source : str or None
        The file, for reports.

    Raises
    ------
    crankdyn.errors.InputError
        An unknown kind (key ``kind``), mismatched or empty arrays, values not finite, speeds
        not positive and strictly increasing, or values not positive.

    Examples
    --------
    >>> curve = LoadCurve([100.0, 200.0], [1.0e7, 1.6e7])
    >>> curve.at([50.0, 150.0, 250.0])
    array([10000000., 13000000., 16000000.])
    >>> curve.outside([150.0]), curve.outside([250.0])
    (False, True)
    """

    speed: NDArray[np.float64]
    value: NDArray[np.float64]
    kind: str = "peak_pressure"
    source: str | None = None

    def __post_init__(self) -> None:
        if self.kind not in LOAD_KINDS:
            raise InputError(f"expected one of {', '.join(LOAD_KINDS)}", key="kind")
        w = np.asarray(self.speed, dtype=float)
        v = np.asarray(self.value, dtype=float)
        if w.ndim != 1 or w.shape != v.shape or w.size < 1:
            raise InputError("a load curve needs at least one point of speed and value")
        if not (np.all(np.isfinite(w)) and np.all(np.isfinite(v))):
            raise InputError("the load curve holds values that are not finite numbers")
        if np.any(w <= 0.0) or np.any(np.diff(w) <= 0.0):
            raise InputError("the load curve's speeds must be positive and increase strictly")
        if np.any(v <= 0.0):
            raise InputError(f"the load curve's {self.kind.replace('_', ' ')} must be positive")
        object.__setattr__(self, "speed", freeze(w))
        object.__setattr__(self, "value", freeze(v))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, LoadCurve):
            return NotImplemented
        return (
            self.kind == other.kind
            and np.array_equal(self.speed, other.speed)
            and np.array_equal(self.value, other.value)
        )

    __hash__: ClassVar[None] = None  # type: ignore[assignment]  # arrays inside: not hashable

    def at(self, speeds: ArrayLike) -> NDArray[np.float64]:
        """The value at speeds, interpolated linearly (held at the curve's end values).

        Parameters
        ----------
        speeds : array_like
            Speeds (rad/s).

        Returns
        -------
        numpy.ndarray
            Peak pressure (Pa), IMEP (Pa) or load factor at those speeds, same shape.
        """
        return np.interp(np.asarray(speeds, dtype=float), self.speed, self.value)

    def outside(self, speeds: ArrayLike) -> bool:
        """Whether any speed lies outside the curve (its end values are used there).

        Parameters
        ----------
        speeds : array_like
            Speeds (rad/s).

        Returns
        -------
        bool
            True when a speed is below the first or above the last point (to a relative 1e-9
            below, 1e-6 above).
        """
        s = np.asarray(speeds, dtype=float)
        return bool(np.any(s < self.speed[0] * (1 - 1e-9)) or np.any(s > self.speed[-1] * 1.000001))


@dataclass(frozen=True, eq=False)
class HarmonicTable:
    """Gas tangential-pressure harmonics against mean indicated pressure (one row per order and
    IMEP; module docstring): the gas torque of order q is A R T_q sin(q theta + psi_q).

    Parameters
    ----------
    order : array_like
        Order of every row (dimensionless), shape (rows,), > 0.
    imep : array_like
        Mean indicated pressure of every row (Pa), shape (rows,), >= 0.
    amplitude : array_like
        T_q (Pa) of every row, shape (rows,), >= 0.
    phase : array_like or None
        psi_q (rad) of every row, shape (rows,), or None (gas and inertia harmonics then added
        in phase).
    source : str or None
        The file, for reports.

    Raises
    ------
    crankdyn.errors.InputError
        Mismatched or empty rows, values not finite, an order not positive (key ``order``), a
        negative amplitude (key ``amplitude``) or IMEP (key ``imep``), two rows of one order
        at the same IMEP (key ``imep``).

    Examples
    --------
    >>> table = HarmonicTable(order=[1.0, 1.0, 2.0], imep=[0.0, 1.0e6, 1.0e6],
    ...                       amplitude=[1.0e5, 3.0e5, 1.0e5])
    >>> table.orders
    array([1., 2.])
    >>> np.abs(table.coefficients([1.0, 2.0], [5.0e5]))
    array([[200000., 100000.]])
    """

    order: NDArray[np.float64]
    imep: NDArray[np.float64]
    amplitude: NDArray[np.float64]
    phase: NDArray[np.float64] | None = None
    source: str | None = None

    def __post_init__(self) -> None:
        q = np.asarray(self.order, dtype=float)
        p = np.asarray(self.imep, dtype=float)
        a = np.asarray(self.amplitude, dtype=float)
        if q.ndim != 1 or q.size == 0 or p.shape != q.shape or a.shape != q.shape:
            raise InputError("a harmonic table needs rows of order, imep and amplitude")
        if not (np.all(np.isfinite(q)) and np.all(np.isfinite(p)) and np.all(np.isfinite(a))):
            raise InputError("the harmonic table holds values that are not finite numbers")
        if np.any(q <= 0.0):
            raise InputError("orders must be positive", key="order", value=float(q[q <= 0][0]))
        if np.any(a < 0.0):
            raise InputError("amplitudes must not be negative", key="amplitude")
        if np.any(p < 0.0):
            raise InputError("mean indicated pressures must not be negative", key="imep")
        keys = np.round(q * 1e9)
        for value in np.unique(keys):
            rows = keys == value
            if np.unique(p[rows]).size != np.count_nonzero(rows):
                raise InputError(
                    f"order {q[rows][0]:g} has two rows at the same mean indicated pressure",
                    key="imep",
                )
        object.__setattr__(self, "order", freeze(q))
        object.__setattr__(self, "imep", freeze(p))
        object.__setattr__(self, "amplitude", freeze(a))
        if self.phase is not None:
            ph = np.asarray(self.phase, dtype=float)
            if ph.shape != q.shape or not np.all(np.isfinite(ph)):
                raise InputError("the harmonic table's phases must be finite, one per row")
            object.__setattr__(self, "phase", freeze(ph))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, HarmonicTable):
            return NotImplemented
        same_phase = (self.phase is None and other.phase is None) or (
            self.phase is not None
            and other.phase is not None
            and np.array_equal(self.phase, other.phase)
        )
        return (
            same_phase
            and np.array_equal(self.order, other.order)
            and np.array_equal(self.imep, other.imep)
            and np.array_equal(self.amplitude, other.amplitude)
        )

    __hash__: ClassVar[None] = None  # type: ignore[assignment]  # arrays inside: not hashable

    @property
    def orders(self) -> NDArray[np.float64]:
        """The distinct orders of the table, ascending (dimensionless)."""
        return np.unique(self.order)

    def coefficients(self, orders: ArrayLike, imep: ArrayLike) -> Complex:
        """Complex tangential-pressure harmonics T_q exp(i (psi_q - pi/2)), interpolated
        linearly in IMEP (held at the table's ends); with no phases the phase is 0 (the caller
        aligns it). The sine form T_q sin(q theta + psi_q) of Ker Wilson's tables (vol. 2,
        ch. 20) is Re(T_q exp(i (psi_q - pi/2)) exp(i q theta)).

        Parameters
        ----------
        orders : array_like
            Orders (dimensionless), shape (orders,); each must be in the table.
        imep : array_like
            Mean indicated pressures (Pa), shape (points,) or a scalar.

        Returns
        -------
        numpy.ndarray
            Complex harmonics (Pa), shape (points, orders).

        Raises
        ------
        crankdyn.errors.InputError
            An order not in the table (names the table's file, key ``order`` and the order).
        """
        orders = np.asarray(orders, dtype=float)
        imep = np.atleast_1d(np.asarray(imep, dtype=float))
        out = np.zeros((imep.size, orders.size), dtype=complex)
        for j, q in enumerate(orders):  # per order of the table: a few dozen at most
            rows = np.flatnonzero(np.abs(self.order - q) <= 1e-9 * max(q, 1.0))
            if rows.size == 0:
                listed = ", ".join(f"{x:g}" for x in self.orders[:12])
                raise InputError(
                    f"order {q:g} is not in the harmonic table (its orders: {listed}"
                    + (", ..." if self.orders.size > 12 else "")
                    + ")",
                    file=self.source,
                    key="order",
                    value=float(q),
                )
            by = np.argsort(self.imep[rows])
            rows = rows[by]
            amp = np.interp(imep, self.imep[rows], self.amplitude[rows])
            if self.phase is None:
                out[:, j] = amp
            else:
                # interpolate the complex harmonic (amplitude and phase together)
                z = self.amplitude[rows] * np.exp(1j * (self.phase[rows] - math.pi / 2.0))
                out[:, j] = np.interp(imep, self.imep[rows], z.real) + 1j * np.interp(
                    imep, self.imep[rows], z.imag
                )
        return out


@dataclass(frozen=True)
class SpeedTrace:
    """A cylinder-pressure trace measured at one speed.

    Parameters
    ----------
    speed : float
        Crankshaft speed of the measurement (rad/s), > 0.
    trace : crankdyn.crank.pressure.PressureTrace
        The cylinder pressure over the cycle.

    Raises
    ------
    crankdyn.errors.InputError
        A speed not positive (key ``speed`` and its value).
    """

    speed: float
    trace: PressureTrace

    def __post_init__(self) -> None:
        if not (math.isfinite(self.speed) and self.speed > 0.0):
            raise InputError("the speed must be positive", key="speed", value=self.speed)


@dataclass(frozen=True)
class ExcitationSpec:
    """How a torsional model is excited (the ``[excitation]`` table; docs/torsion-file.md).

    Parameters
    ----------
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"`` (engine-less models; engines use their own).
    firing_angles : tuple of float or None
        Firing angle of every cylinder (rad, cylinder 1 first), or None: the engine's, or for a
        model without engine even firing in ``firing_order`` (or all cylinders in phase when
        neither is given).
    firing_order : tuple of int or None
        Cylinder numbers in firing order (engine-less models; even firing).
    torque : float or None
        Harmonic torque amplitude of every order at every cylinder (N m) for an engine-less model
        (uniform excitation, e.g. 1 N m for receptances).
    load_curve : LoadCurve or None
        Load against speed (engines).
    traces : tuple of SpeedTrace
        Pressure traces at several speeds (engines), speeds increasing.
    harmonics : HarmonicTable or None
        Gas harmonic-coefficient table (engines).
    imep : float or None
        Mean indicated pressure (Pa) for the table when no load curve gives it.
    misfire : tuple of int
        Cylinders (1-based) that misfire (motored pressure).

    Raises
    ------
    crankdyn.errors.InputError
        An unknown cycle, a torque or IMEP not positive, traces given with a peak-pressure or
        load-factor curve or with a table, trace speeds not increasing, or repeated or
        non-positive misfiring cylinders; the message names the key and value.
    """

    cycle: str = "four-stroke"
    firing_angles: tuple[float, ...] | None = None
    firing_order: tuple[int, ...] | None = None
    torque: float | None = None
    load_curve: LoadCurve | None = None
    traces: tuple[SpeedTrace, ...] = ()
    harmonics: HarmonicTable | None = None
    imep: float | None = None
    misfire: tuple[int, ...] = ()

    def __post_init__(self) -> None:
        if self.cycle not in CYCLES:
            raise InputError(f"expected one of {', '.join(CYCLES)}", key="cycle", value=self.cycle)
        if self.torque is not None and not (math.isfinite(self.torque) and self.torque > 0.0):
            raise InputError("the torque amplitude must be positive", key="torque")
        if self.traces and self.load_curve is not None and self.load_curve.kind != "imep":
            raise InputError(
                "give traces at several speeds or a load curve that scales one trace, not both",
                key="load_curve",
            )
        if self.traces and self.harmonics is not None:
            raise InputError(
                "give traces at several speeds or a harmonic table, not both", key="harmonics"
            )
        speeds = [t.speed for t in self.traces]
        if speeds and np.any(np.diff(speeds) <= 0.0):
            raise InputError("the traces' speeds must increase strictly", key="trace")
        if self.imep is not None and not (math.isfinite(self.imep) and self.imep > 0.0):
            raise InputError("the mean indicated pressure must be positive", key="imep")
        misfire = tuple(int(c) for c in self.misfire)
        if any(c < 1 for c in misfire) or len(set(misfire)) != len(misfire):
            raise InputError("expected distinct cylinder numbers", key="misfire", value=misfire)
        object.__setattr__(self, "misfire", misfire)


# ---- evaluation ---------------------------------------------------------------------------------
def _check_cylinder_list(numbers: Iterable[int], count: int, key: str) -> tuple[int, ...]:
    out = tuple(int(c) for c in numbers)
    for c in out:
        if not 1 <= c <= count:
            raise InputError(f"the engine has cylinders 1 to {count}", key=key, value=c)
    return out


@dataclass(frozen=True, eq=False)
class UniformExcitation:
    """The same harmonic torque amplitude for every order at every cylinder, phased by the
    firing angles: c_q,i = T exp(-i q Phi_i) (N m). Receptance-type studies (unit torque) and
    models without an engine.

    Parameters
    ----------
    torque : float
        T (N m), > 0.
    firing_angles : array_like
        Firing angle of every cylinder (rad), shape (cylinders,), cylinder 1 first; zeros put
        all in phase.
    cycle : str
        The working cycle, ``"four-stroke"`` or ``"two-stroke"`` (sets the admissible orders).
    note : str
        Text for reports.
    phases_known : bool
        Whether the firing angles are the engine's (False: an assumption, e.g. all in phase for
        a model without a firing order; major orders are then undetermined).

    Raises
    ------
    crankdyn.errors.InputError
        A torque not positive (key ``torque``).

    Examples
    --------
    >>> exc = UniformExcitation(2.0, np.radians([0.0, 360.0]))
    >>> np.round(exc.harmonics([100.0], [0.5, 1.0]), 12)
    array([[[ 2.+0.j, -2.-0.j],
            [ 2.+0.j,  2.+0.j]]])
    """

    torque: float
    firing_angles: NDArray[np.float64]
    cycle: str = "four-stroke"
    note: str = ""
    phases_known: bool = True

    def __post_init__(self) -> None:
        if not (math.isfinite(self.torque) and self.torque > 0.0):
            raise InputError("the torque amplitude must be positive", key="torque")
        object.__setattr__(self, "firing_angles", freeze(np.atleast_1d(self.firing_angles)))

    @property
    def cylinder_count(self) -> int:
        """Number of cylinders (one per firing angle)."""
        return int(self.firing_angles.size)

    @property
    def description(self) -> str:
        """One line describing the excitation, for reports."""
        return f"uniform harmonic torque {self.torque:g} N·m per order at every cylinder"

    def notes(self, speeds: ArrayLike) -> tuple[str, ...]:
        """Notes for reports on the excitation at these speeds.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s).

        Returns
        -------
        tuple of str
            The excitation's note, if any.
        """
        return (self.note,) if self.note else ()

    def parts(self, speeds: ArrayLike, orders: ArrayLike) -> tuple[Complex, Complex]:
        """(gas, inertia) harmonics: the uniform torque counts as gas, the inertia part is zero.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,).
        orders : array_like
            Orders (dimensionless), shape (orders,), valid for the cycle.

        Returns
        -------
        gas, inertia : numpy.ndarray
            Complex harmonic torques (N m), each of shape (speeds, orders, cylinders).
        """
        speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
        orders = check_orders(orders, self.cycle)
        one = self.torque * phase_vectors(self.firing_angles, orders)
        gas = np.broadcast_to(one, (speeds.size, *one.shape)).copy()
        return gas, np.zeros_like(gas)

    def harmonics(self, speeds: ArrayLike, orders: ArrayLike) -> Complex:
        """Harmonic torque of every cylinder, T exp(-i q Phi_i).

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,).
        orders : array_like
            Orders (dimensionless), shape (orders,), valid for the cycle.

        Returns
        -------
        numpy.ndarray
            Complex harmonic torques (N m), shape (speeds, orders, cylinders).
        """
        gas, _ = self.parts(speeds, orders)
        return gas


@dataclass(frozen=True, eq=False)
class EngineExcitation:
    """The gas and inertia torques of an engine's cylinders (module docstring).

    Parameters
    ----------
    engine : crankdyn.engine.model.Engine
        The engine (its masses are required for the inertia part).
    spec : ExcitationSpec or None
        Load curve, traces at speeds or harmonic table, and misfiring cylinders; None for the
        engine's trace at every speed.
    misfire : tuple of int
        Misfiring cylinders, 1-based (in addition to ``spec.misfire``).

    Raises
    ------
    crankdyn.errors.InputError
        A misfiring cylinder the engine does not have (key ``misfire``), or a harmonic table
        without a mean indicated pressure (key ``harmonics``, naming the engine file).
    """

    engine: Engine
    spec: ExcitationSpec | None = None
    misfire: tuple[int, ...] = ()

    def __post_init__(self) -> None:
        count = self.engine.cylinders.count
        both = tuple(self.misfire) + (self.spec.misfire if self.spec else ())
        object.__setattr__(
            self, "misfire", tuple(sorted(set(_check_cylinder_list(both, count, "misfire"))))
        )
        if self.spec is not None and self.spec.harmonics is not None:
            self._table_imep_source()  # fail early without an IMEP

    # ---- properties ---------------------------------------------------------------------------
    @property
    def cycle(self) -> str:
        """The engine's working cycle, ``"four-stroke"`` or ``"two-stroke"``."""
        return self.engine.cycle

    @property
    def firing_angles(self) -> NDArray[np.float64]:
        """Firing angle of every cylinder (rad), cylinder 1 first."""
        return np.asarray(self.engine.cylinders.firing_angles, dtype=float)

    @property
    def cylinder_count(self) -> int:
        """Number of cylinders of the engine."""
        return self.engine.cylinders.count

    @property
    def description(self) -> str:
        """One line describing the excitation (pressure source, load, misfire), for reports."""
        spec = self.spec
        if spec is not None and spec.harmonics is not None:
            gas = f"harmonic table {spec.harmonics.source or ''}".strip()
        elif spec is not None and spec.traces:
            gas = f"pressure traces at {len(spec.traces)} speeds"
        else:
            gas = f"pressure trace {self._trace.source or ''}".strip()
            if spec is not None and spec.load_curve is not None:
                gas += f" scaled by the {spec.load_curve.kind.replace('_', ' ')} curve"
                if spec.load_curve.source:
                    gas += f" {spec.load_curve.source}"
        text = f"{self.engine.name}: gas ({gas}) and inertia torques"
        if self.misfire:
            text += f"; cylinder(s) {', '.join(map(str, self.misfire))} misfiring (motored)"
        return text

    def breakpoints(self) -> NDArray[np.float64]:
        """Speeds where the excitation is not smooth in speed: the points of a load curve
        (interpolated linearly) or of the traces at several speeds. A resolved forced response
        samples them, so a peak at such a kink is found exactly.

        Returns
        -------
        numpy.ndarray
            The speeds (rad/s), shape (points,); empty without a load curve or traces.
        """
        spec = self.spec
        points: list[NDArray[np.float64]] = []
        if spec is not None and spec.load_curve is not None:
            points.append(np.asarray(spec.load_curve.speed, dtype=float))
        if spec is not None and spec.traces:
            points.append(np.array([t.speed for t in spec.traces], dtype=float))
        return np.concatenate(points) if points else np.zeros(0)

    def notes(self, speeds: ArrayLike) -> tuple[str, ...]:
        """Notes for reports on the excitation at these speeds: speeds outside the load curve or
        the traces, a synthetic pressure trace, a harmonic table without phases.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s).

        Returns
        -------
        tuple of str
            The notes (empty when there is nothing to say).
        """
        out = []
        curve = self.spec.load_curve if self.spec else None
        if curve is not None and curve.outside(speeds):
            out.append(
                f"speeds outside the load curve ({curve.speed[0] * RPM:.0f}-"
                f"{curve.speed[-1] * RPM:.0f} rpm) use its end values"
            )
        if self.spec is not None and self.spec.traces:
            w = [t.speed for t in self.spec.traces]
            s = np.asarray(speeds)
            if np.any(s < w[0] * (1 - 1e-9)) or np.any(s > w[-1] * (1 + 1e-9)):
                out.append("speeds outside the traces' speeds use the nearest trace")
        if self.engine.pressure is None and (
            self.spec is None or (not self.spec.traces and self.spec.harmonics is None)
        ):
            out.append("no pressure trace: synthetic Wiebe model with default parameters")
        table = self.spec.harmonics if self.spec else None
        if table is not None and table.phase is None:
            out.append(
                "the harmonic table has no phases: gas and inertia harmonics added in phase "
                "(amplitudes add, conservative)"
            )
        return tuple(out)

    # ---- spectra of the basis signals (computed once) -----------------------------------------
    @cached_property
    def _trace(self) -> PressureTrace:
        from crankdyn.crank.pressure_model import default_pressure

        return default_pressure(self.engine)

    @cached_property
    def _theta(self) -> NDArray[np.float64]:
        return _cycle_grid(self.cycle)

    @cached_property
    def _lever(self) -> NDArray[np.float64]:
        """R sin(phi + beta)/cos(beta) (m) of every cylinder over the cycle grid."""
        from crankdyn.engine.forces import rod_forces

        g, cyl = self.engine.geometry, self.engine.cylinders
        phi = self._theta[None, :] - np.asarray(cyl.throw_angles)[:, None]
        return rod_forces(np.ones_like(phi), phi, g.lam, g.k)[2] * g.crank_radius

    @cached_property
    def _phase(self) -> NDArray[np.float64]:
        """Every cylinder's angle from its firing TDC over the grid (rad)."""
        return np.mod(self._theta[None, :] - self.firing_angles[:, None], self.engine.cycle_angle)

    def _pressure_spectrum(self, trace: PressureTrace) -> Complex:
        """rfft of p A R lever (absolute pressure) of every cylinder, shape (Z, N/2+1)."""
        area = self.engine.geometry.piston_area
        return np.fft.rfft(trace.at(self._phase) * area * self._lever, axis=-1)

    @cached_property
    def _crankcase_spectrum(self) -> Complex:
        area = self.engine.geometry.piston_area
        return np.fft.rfft(self.engine.crankcase_pressure * area * self._lever, axis=-1)

    @cached_property
    def _inertia_spectrum(self) -> Complex:
        """rfft of the inertia torque at 1 rad/s, shape (Z, N/2+1)."""
        from crankdyn.crank.kinematics import slider_crank_exact
        from crankdyn.engine.forces import engine_masses

        g, cyl = self.engine.geometry, self.engine.cylinders
        m_j = np.array([m.reciprocating for m in engine_masses(self.engine)])[:, None]
        phi = self._theta[None, :] - np.asarray(cyl.throw_angles)[:, None]
        a = slider_crank_exact(phi, g.crank_radius, g.rod_length, g.offset, 1.0).acceleration
        return np.fft.rfft(-m_j * a * self._lever, axis=-1)

    @cached_property
    def _trace_spectrum(self) -> Complex:
        return self._pressure_spectrum(self._trace)

    @cached_property
    def _speed_trace_spectra(self) -> Complex:
        traces = self.spec.traces if self.spec is not None else ()
        return np.stack([self._pressure_spectrum(t.trace) for t in traces])

    @cached_property
    def _motored_trace(self) -> PressureTrace:
        from crankdyn.crank.pressure_model import WiebePressureModel

        trace = self._trace
        eps = trace.compression_ratio
        if eps is None:
            raise InputError(
                "a misfiring cylinder is motored (compression without combustion), which needs "
                "the compression ratio: give [pressure] compression_ratio",
                file=self.engine.source,
                key="misfire",
                value=list(self.misfire),
            )
        p_in = float(trace.at(np.array([self.engine.cycle_angle - math.pi]))[0])
        model = WiebePressureModel(compression_ratio=eps, fuel_energy=0.0, intake_pressure=p_in)
        return model.trace(self.engine.geometry, self.cycle, source="motored")

    @cached_property
    def _motored_spectrum(self) -> Complex:
        return self._pressure_spectrum(self._motored_trace)

    # ---- load ----------------------------------------------------------------------------------
    def load_factor(self, speeds: ArrayLike) -> NDArray[np.float64]:
        """Scale s(Omega) of the absolute pressure at every speed (module docstring; Mendes et
        al. 2008): the load curve's peak pressure over the trace's, its IMEP over the trace's,
        or the load factor itself; 1 without a load curve (or with an IMEP curve feeding a
        harmonic table).

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,) or a scalar.

        Returns
        -------
        numpy.ndarray
            The scale (dimensionless), shape (speeds,).

        Raises
        ------
        crankdyn.errors.InputError
            An IMEP curve scaling a trace whose IMEP is not positive (key ``load_curve``).
        """
        speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
        spec = self.spec
        curve = spec.load_curve if spec else None
        if curve is None or (
            spec is not None and spec.harmonics is not None and curve.kind == "imep"
        ):
            return np.ones(speeds.size)
        value = curve.at(speeds)
        if curve.kind == "load_factor":
            return value
        if curve.kind == "peak_pressure":
            return value / self._trace.peak[0]
        from crankdyn.crank.indicated import indicated_work

        imep = indicated_work(self._trace, self.engine.geometry) / self.engine.geometry.swept_volume
        if not imep > 0.0:
            raise InputError(
                "the trace's IMEP is not positive, so an IMEP curve cannot scale it",
                key="load_curve",
            )
        return value / imep

    def _table_imep_source(self) -> Callable[[ArrayLike], NDArray[np.float64]]:
        spec = self.spec
        if spec is not None and spec.load_curve is not None and spec.load_curve.kind == "imep":
            return spec.load_curve.at
        if spec is not None and spec.imep is not None:
            imep = spec.imep
            return lambda s: np.full(np.size(s), imep)
        raise InputError(
            "a harmonic table needs the mean indicated pressure: give imep, or a load curve "
            "of IMEP against speed",
            file=self.engine.source,
            key="harmonics",
        )

    def imep(self, speeds: ArrayLike) -> NDArray[np.float64] | None:
        """Mean indicated pressure at every speed for a harmonic table, else None.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,) or a scalar.

        Returns
        -------
        numpy.ndarray or None
            The IMEP (Pa) that enters the harmonic table, shape (speeds,); None without a table.
        """
        if self.spec is None or self.spec.harmonics is None:
            return None
        return self._table_imep_source()(np.atleast_1d(np.asarray(speeds, dtype=float)))

    # ---- harmonics ------------------------------------------------------------------------------
    def parts(self, speeds: ArrayLike, orders: ArrayLike) -> tuple[Complex, Complex]:
        """(gas, inertia) harmonic torques of every cylinder, phased by the firing angles: the
        FFT of the cylinder torques over the cycle (seed 003 ch. 4; module docstring), the
        inertia part scaled by Omega^2, the gas part by the load, traces or table.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,) or a scalar.
        orders : array_like
            Orders (dimensionless), shape (orders,), multiples of the fundamental order below
            1800 (four-stroke) or 3600 (two-stroke).

        Returns
        -------
        gas, inertia : numpy.ndarray
            Complex harmonic torques (N m), each of shape (speeds, orders, cylinders).

        Raises
        ------
        crankdyn.errors.InputError
            Orders that do not fit the cycle or are not resolved (key ``orders``), a misfire
            without a compression ratio (key ``misfire``, naming the engine file).
        """
        speeds = np.atleast_1d(np.asarray(speeds, dtype=float))
        orders = check_orders(orders, self.cycle)
        m = harmonic_index(orders, self.cycle)
        if np.any(m >= SAMPLES // 2):
            raise InputError(
                f"orders above {SAMPLES // 2 * fundamental_order(self.cycle):g} are not resolved",
                key="orders",
            )
        scale = 2.0 / SAMPLES
        inertia1 = (self._inertia_spectrum[:, m] * scale).T  # (Q, Z)
        inertia = speeds[:, None, None] ** 2 * inertia1[None]
        cc = (self._crankcase_spectrum[:, m] * scale).T
        spec = self.spec
        if spec is not None and spec.harmonics is not None:
            gas = self._table_gas(speeds, orders, inertia)
        elif spec is not None and spec.traces:
            w = np.array([t.speed for t in spec.traces])
            base = np.transpose(self._speed_trace_spectra[:, :, m] * scale, (0, 2, 1)) - cc
            gas = interp_complex(speeds, w, base)  # (S, Q, Z)
        else:
            p = (self._trace_spectrum[:, m] * scale).T
            s = self.load_factor(speeds)
            gas = s[:, None, None] * p[None] - cc[None]
        if self.misfire:
            idx = np.asarray(self.misfire) - 1
            motored = (self._motored_spectrum[:, m] * scale).T  # (Q, Z), absolute pressure
            if spec is not None and spec.harmonics is None and not spec.traces:
                # a load curve scales the absolute pressure of every cylinder alike: the
                # misfiring cylinder shares the intake manifold (module docstring)
                motored = self.load_factor(speeds)[:, None, None] * motored[None]
            else:
                motored = np.broadcast_to(motored, (speeds.size, *motored.shape))
            gas = np.array(gas, copy=True)
            gas[:, :, idx] = motored[:, :, idx] - cc[None, :, idx]
        return gas, inertia

    def _table_gas(
        self, speeds: NDArray[np.float64], orders: NDArray[np.float64], inertia: Complex
    ) -> Complex:
        table = self.spec.harmonics if self.spec is not None else None
        assert table is not None  # parts() calls this with a harmonic table only
        imep = self._table_imep_source()(speeds)
        g = self.engine.geometry
        t = table.coefficients(orders, imep) * g.piston_area * g.crank_radius  # (S, Q)
        if table.phase is None:
            # in phase with the inertia harmonic of cylinder 1's own cycle (conservative)
            own = inertia[:, :, 0] * np.exp(1j * orders * self.firing_angles[0])[None, :]
            unit = np.where(np.abs(own) > 0.0, own / np.where(own == 0, 1, np.abs(own)), 1.0)
            t = np.abs(t) * unit
        return t[:, :, None] * phase_vectors(self.firing_angles, orders)[None]

    def harmonics(self, speeds: ArrayLike, orders: ArrayLike) -> Complex:
        """Harmonic torque of every cylinder, gas + inertia (:meth:`parts`).

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,) or a scalar.
        orders : array_like
            Orders (dimensionless), shape (orders,).

        Returns
        -------
        numpy.ndarray
            Complex harmonic torques (N m), shape (speeds, orders, cylinders).
        """
        gas, inertia = self.parts(speeds, orders)
        return gas + inertia


def interp_complex(x: ArrayLike, xp: NDArray[np.float64], fp: Complex) -> Complex:
    """Linear interpolation along the first axis of fp (held at the ends), vectorised.

    Parameters
    ----------
    x : array_like
        Where to interpolate (unit of ``xp``), shape (points,).
    xp : numpy.ndarray
        Abscissae (e.g. speeds in rad/s), increasing, shape (n,).
    fp : numpy.ndarray
        Values, complex, shape (n, ...).

    Returns
    -------
    numpy.ndarray
        Interpolated values, shape (points, ...).

    Examples
    --------
    >>> interp_complex([0.5, 2.0], np.array([0.0, 1.0]), np.array([0j, 2 + 2j]))
    array([1.+1.j, 2.+2.j])
    """
    x = np.asarray(x, dtype=float)
    if len(xp) == 1:
        return np.broadcast_to(fp[0], (x.size, *fp.shape[1:])).copy()
    i = np.clip(np.searchsorted(xp, x) - 1, 0, len(xp) - 2)
    t = np.clip((x - xp[i]) / (xp[i + 1] - xp[i]), 0.0, 1.0)
    t = t.reshape((-1,) + (1,) * (fp.ndim - 1))
    return (1.0 - t) * fp[i] + t * fp[i + 1]


# ---- engine-less excitation ----------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class SourceExcitation:
    """The excitation of a model whose masses carry no cylinders: only its sources act (the
    interface of :class:`~crankdyn.torsion.excitation.UniformExcitation`, with no cylinder).

    Parameters
    ----------
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"``.

    Examples
    --------
    >>> SourceExcitation().harmonics([10.0, 20.0], [1.0]).shape
    (2, 1, 0)
    """

    cycle: str = "four-stroke"

    @property
    def firing_angles(self) -> NDArray[np.float64]:
        """No firing angles (rad): an empty array."""
        return np.zeros(0)

    @property
    def cylinder_count(self) -> int:
        """No cylinders: 0."""
        return 0

    @property
    def description(self) -> str:
        """One line describing the excitation, for reports."""
        return "the model's excitation sources (no engine cylinders)"

    def notes(self, speeds: ArrayLike) -> tuple[str, ...]:
        """Notes for reports: none.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s).

        Returns
        -------
        tuple of str
            An empty tuple.
        """
        return ()

    def parts(self, speeds: ArrayLike, orders: ArrayLike) -> tuple[Complex, Complex]:
        """(gas, inertia) harmonics of no cylinder.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,).
        orders : array_like
            Orders (dimensionless), shape (orders,).

        Returns
        -------
        gas, inertia : numpy.ndarray
            Complex zeros (N m), each of shape (speeds, orders, 0).
        """
        s = np.atleast_1d(np.asarray(speeds, dtype=float))
        q = np.atleast_1d(np.asarray(orders, dtype=float))
        zero = np.zeros((s.size, q.size, 0), dtype=complex)
        return zero, zero.copy()

    def harmonics(self, speeds: ArrayLike, orders: ArrayLike) -> Complex:
        """Harmonic torques of no cylinder.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,).
        orders : array_like
            Orders (dimensionless), shape (orders,).

        Returns
        -------
        numpy.ndarray
            Complex zeros (N m), shape (speeds, orders, 0).
        """
        return self.parts(speeds, orders)[0]


Excitation: TypeAlias = UniformExcitation | EngineExcitation | SourceExcitation
"""The excitation of a torsional model (:func:`excitation_for`): every kind has ``cycle``,
``firing_angles``, ``cylinder_count``, ``description``, ``notes``, ``parts`` and ``harmonics``."""


def excitation_for(
    model: TorsionModel,
    engine: Engine | None = None,
    *,
    misfire: Sequence[int] = (),
    torque: float | None = None,
) -> Excitation:
    """The excitation of a torsional model: the engine's cylinder torques when an engine is
    given (or attached), else the model's ``[excitation]`` (uniform torque, default 1 N m).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model; its masses' ``cylinders`` are the excitation points.
    engine : crankdyn.engine.model.Engine or None
        The engine whose cylinder torques excite the model; None for the model's own engine
        (``[[engine]]``, the first) or, without one, its ``[excitation]`` table.
    misfire : sequence of int
        Misfiring cylinders (1-based); needs an engine.
    torque : float or None
        Forces a uniform excitation of that amplitude (N m) even with an engine (its firing
        angles are kept).

    Returns
    -------
    Excitation
        An :class:`EngineExcitation`, a :class:`UniformExcitation`, or for a model with
        excitation sources but no cylinders a :class:`SourceExcitation` (its sources act,
        :mod:`crankdyn.torsion.sources`).

    Raises
    ------
    crankdyn.errors.InputError
        A model with no cylinder and no source (naming the model file), a misfire without an
        engine (key ``misfire``), firing angles not one per cylinder (key ``firing_angles``).
    """
    spec = getattr(model, "excitation", None)
    cylinders = sorted(model.cylinder_dofs)
    if engine is None:
        engine = getattr(model, "engine", None)
    if not cylinders and getattr(model, "sources", None):
        if misfire:
            raise InputError(
                "a misfire needs engine cylinders on the model", key="misfire", value=list(misfire)
            )
        return SourceExcitation(spec.cycle if spec is not None else "four-stroke")
    if not cylinders:
        raise InputError(
            "the model has no excitation point: no mass carries a cylinder (give cylinders = "
            "[...] on the crank-throw masses)",
            file=model.source,
        )
    if engine is not None and torque is None:
        return EngineExcitation(engine, spec, tuple(misfire))
    if misfire:
        raise InputError(
            "a misfire needs the engine's pressure (an engine file with a [torsion] section)",
            key="misfire",
            value=list(misfire),
        )
    count = max(cylinders)
    known = True
    if engine is not None:
        angles = np.asarray(engine.cylinders.firing_angles, dtype=float)
        cycle, note = engine.cycle, ""
    else:
        cycle = spec.cycle if spec is not None else "four-stroke"
        angles, note = _model_firing_angles(spec, count, cycle)
        known = not note
    if torque is None:
        torque = spec.torque if spec is not None and spec.torque is not None else 1.0
    return UniformExcitation(torque, angles, cycle, note, phases_known=known)


def _model_firing_angles(
    spec: ExcitationSpec | None, count: int, cycle: str
) -> tuple[NDArray[np.float64], str]:
    """Firing angles of an engine-less model's cylinders and a note on where they came from."""
    if spec is not None and spec.firing_angles is not None:
        angles = np.asarray(spec.firing_angles, dtype=float)
        if angles.size != count:
            raise InputError(
                f"expected {count} firing angles (cylinders 1 to {count})",
                key="firing_angles",
                value=angles.size,
            )
        return angles, ""
    if spec is not None and spec.firing_order is not None:
        from crankdyn.engine.firing import check_firing_order

        order = check_firing_order(spec.firing_order, count)
        interval = even_firing_interval(count, cycle)
        angles = np.empty(count)
        for k, c in enumerate(order):
            angles[c - 1] = k * interval
        return angles, ""
    return np.zeros(count), MAJOR_UNDETERMINED


# ---- harmonic analysis result -------------------------------------------------------------------
@dataclass(frozen=True)
class HarmonicResult(Result):
    """Harmonic analysis of the cylinder torque at one speed: per order the single-cylinder
    amplitude (gas, inertia, total), phase, the phase-vector sum over the cylinders and whether
    the order is major; with a model, the relative amplitude sums over its modes
    (:func:`harmonic_analysis`; module docstring)."""

    title = "Torque harmonics"
    orders: NDArray[np.float64] = array("orders", "Order", "")
    amplitude: NDArray[np.float64] = array("amplitude_Nm", "Single-cylinder amplitude", "N·m")
    gas_amplitude: NDArray[np.float64] = array("gas_amplitude_Nm", "Gas part", "N·m")
    inertia_amplitude: NDArray[np.float64] = array("inertia_amplitude_Nm", "Inertia part", "N·m")
    phase: NDArray[np.float64] = array("phase_deg", "Phase from firing TDC", "deg", DEG)
    phase_sum: NDArray[np.float64] | None = array(
        "phase_vector_sum", "Phase-vector sum |Σ e^(-iqΦ)|", ""
    )
    """None when the firing angles are unknown (module docstring)."""
    major: NDArray[np.bool_] | None = array("major", "Major order", "")
    """None when the firing angles are unknown (module docstring)."""
    engine_amplitude: NDArray[np.float64] = array(
        "engine_amplitude_Nm", "All cylinders |Σ c|", "N·m"
    )
    relative_amplitude_sums: NDArray[np.float64] | None = array(
        "relative_amplitude_sums", "Relative amplitude sums (mode x order)", ""
    )
    modes: NDArray[np.int_] | None = array("modes", "Modes", "")
    speed: float = scalar("speed_rpm", "Speed", "rpm", RPM)
    cylinders: int = scalar("cylinders", "Cylinders", "")
    firing_angles: NDArray[np.float64] = array("firing_angles_deg", "Firing angles", "deg", DEG)
    source: str = scalar("excitation", "Excitation", "")
    notes: tuple[str, ...] | None = scalar("notes", "Notes", "")

    def plot(self, fig: Figure | None = None) -> Figure:
        """Bar chart of the single-cylinder harmonics per order.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.torsion_response import plot_harmonics

        return plot_harmonics(self, fig=fig)


def harmonic_analysis(
    excitation: Excitation,
    speed: float,
    orders: ArrayLike,
    modes: ModalResult | None = None,
    model: TorsionModel | None = None,
) -> HarmonicResult:
    """Harmonic analysis of the excitation at one speed: the Fourier coefficients of the
    cylinder torque (seed 003 ch. 4 and eq. 5), the phase-vector sums and major orders (seed 003
    section 4.2) and, with modes, the relative amplitude sums (module docstring).

    Parameters
    ----------
    excitation : Excitation
        An :class:`EngineExcitation` or :class:`UniformExcitation`.
    speed : float
        Crankshaft speed (rad/s), > 0.
    orders : array_like
        Orders to list (dimensionless), shape (orders,).
    modes : crankdyn.torsion.modal.ModalResult or None
        Optionally the modes of ``model`` for the relative amplitude sums (elastic modes; each
        mode's shape normalised to a largest amplitude of 1 over the cylinder masses).
    model : crankdyn.torsion.model.TorsionModel or None
        The model of ``modes`` (which mass carries which cylinder).

    Returns
    -------
    HarmonicResult
        Per order the single-cylinder amplitudes (N m), phase (rad), phase-vector sum, major
        flag and the engine's total amplitude (N m).

    Raises
    ------
    crankdyn.errors.InputError
        A speed not positive (key ``speed``) or orders that do not fit the cycle (key
        ``orders``).

    Examples
    --------
    >>> exc = UniformExcitation(1.0, np.radians([0.0, 540.0, 180.0, 360.0]))
    >>> res = harmonic_analysis(exc, 100.0, [1.0, 2.0])
    >>> res.major, np.round(res.engine_amplitude, 12)
    (array([False,  True]), array([0., 4.]))
    """
    if not (math.isfinite(speed) and speed > 0.0):
        raise InputError("the speed must be positive", key="speed", value=speed)
    orders = check_orders(orders, excitation.cycle)
    gas, inertia = excitation.parts(np.array([speed]), orders)
    angles = excitation.firing_angles
    # cylinder 1's own harmonic (measured from its firing TDC)
    own = np.exp(1j * orders * angles[0])
    total = (gas + inertia)[0]
    one = total[:, 0] * own
    known = getattr(excitation, "phases_known", True)
    sums = rel = mode_numbers = None
    if modes is not None and model is not None and known:
        elastic = np.flatnonzero(modes.natural_frequency > 0.0)
        beta = cylinder_amplitudes(modes, model, excitation.cylinder_count)[elastic]
        rel = relative_amplitude_sums(beta, angles, orders)
        mode_numbers = modes.mode[elastic]
    sums = phase_vector_sums(angles, orders)
    return HarmonicResult(
        orders=freeze(orders),
        amplitude=freeze(np.abs(one)),
        gas_amplitude=freeze(np.abs(gas[0][:, 0])),
        inertia_amplitude=freeze(np.abs(inertia[0][:, 0])),
        phase=freeze(np.angle(one)),
        phase_sum=freeze(sums) if known else None,
        major=freeze(major_orders(angles, orders), dtype=bool) if known else None,
        engine_amplitude=freeze(np.abs(np.sum(total, axis=1))),
        relative_amplitude_sums=None if rel is None else freeze(rel),
        modes=None if mode_numbers is None else freeze(mode_numbers, dtype=int),
        speed=float(speed),
        cylinders=excitation.cylinder_count,
        firing_angles=freeze(angles),
        source=excitation.description,
        notes=tuple(excitation.notes([speed])) or None,
    )


def cylinder_amplitudes(modes: ModalResult, model: TorsionModel, count: int) -> NDArray[np.float64]:
    """Mode-shape amplitude of the mass carrying each cylinder, each mode normalised to a
    largest absolute cylinder amplitude of 1 (0 for cylinders on no mass).

    Parameters
    ----------
    modes : crankdyn.torsion.modal.ModalResult
        The modes of ``model``.
    model : crankdyn.torsion.model.TorsionModel
        The model (its masses' ``cylinders``).
    count : int
        Number of cylinders.

    Returns
    -------
    numpy.ndarray
        Relative amplitudes beta (dimensionless), shape (modes, cylinders).
    """
    shapes = np.asarray(modes.mode_shapes)  # mode x mass
    out = np.zeros((shapes.shape[0], count))
    for i, m in enumerate(model.masses):
        for c in m.cylinders:
            if c <= count:
                out[:, c - 1] = shapes[:, i]
    peak = np.max(np.abs(out), axis=1, keepdims=True)
    return out / np.where(peak > 0.0, peak, 1.0)
