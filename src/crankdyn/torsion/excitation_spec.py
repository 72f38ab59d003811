"""What a torsional model or engine file says about its excitation: load curves, harmonic-
coefficient tables and pressure traces at several speeds (domain objects; the ``[excitation]``
table, docs/torsion-file.md). :mod:`crankdyn.torsion.excitation` turns them into the cylinders'
harmonic torques at any speed (its module docstring: the dependence on speed, after Mendes et
al. 2008 and W. Ker Wilson, *Practical Solution of Torsional Vibration Problems*, vol. 2, ch. 20).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError
from crankdyn.results import freeze
from crankdyn.torsion.orders import CYCLES, Complex

if TYPE_CHECKING:
    from crankdyn.crank.pressure import PressureTrace

__all__ = [
    "LOAD_KINDS",
    "CylinderHarmonics",
    "ExcitationSpec",
    "HarmonicTable",
    "LoadCurve",
    "SpeedTrace",
]

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
    IMEP; :mod:`crankdyn.torsion.excitation`): the gas torque of order q is
    A R T_q sin(q theta + psi_q).

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


@dataclass(frozen=True, eq=False)
class CylinderHarmonics:
    """An engine builder's table of one cylinder's harmonic torques per order, firing and
    misfiring, for a model file without an engine (:class:`crankdyn.torsion.excitation.
    TabulatedExcitation`; the CSV: :func:`crankdyn.io.torsion_tables.read_cylinder_harmonics`).

    The torque of one cylinder over its cycle is the Fourier series in its own crank angle
    theta from its firing TDC (seed 003, 第4章: the cylinder's tangential torque as a sum of
    orders),

        T(theta) = sum_q [a_q sin(q theta) + b_q cos(q theta)] = sum_q T_q sin(q theta + psi_q),

    held here as the complex coefficient c_q = b_q - i a_q = T_q exp(i (psi_q - pi/2)), so that
    T(theta) = Re(sum_q c_q exp(i q theta)) (the convention of :class:`HarmonicTable` and
    :mod:`crankdyn.torsion.excitation`); every cylinder has the same coefficients, phased by its
    firing angle. The table may give the coefficients at several speeds (an engine builder's
    table along the propeller law, say): they are interpolated linearly in speed (real and
    imaginary parts), held at the table's ends; a table without speeds holds at every speed.

    Parameters
    ----------
    order : array_like
        The orders q (of the crankshaft speed), shape (orders,), > 0, distinct.
    normal : array_like
        c_q of a firing cylinder (N m, complex), shape (speeds, orders) (or (orders,) without
        speeds).
    misfire : array_like or None
        c_q of a misfiring cylinder (N m, complex), the shape of ``normal``; None: the table
        gives no misfire.
    speed : array_like or None
        The speeds of the rows (rad/s), shape (speeds,), > 0, increasing; None: one set of
        coefficients at every speed.
    source : str or None
        The file, for reports.

    Raises
    ------
    crankdyn.errors.InputError
        Shapes that do not match, values that are not finite, orders not positive or repeated
        (key ``order``), speeds not positive or not increasing (key ``speed``).

    Examples
    --------
    A cylinder whose order-1 torque is 100 sin(theta) N m at every speed:

    >>> table = CylinderHarmonics(order=[1.0], normal=[-100j])
    >>> table.at([50.0, 80.0], [1.0, 2.0]).imag.tolist()  # order 2 is not in the table: 0
    [[-100.0, 0.0], [-100.0, 0.0]]
    """

    order: NDArray[np.float64]
    normal: NDArray[np.complex128]
    misfire: NDArray[np.complex128] | None = None
    speed: NDArray[np.float64] | None = None
    source: str | None = None

    if TYPE_CHECKING:  # what the constructor accepts; the fields hold read-only arrays

        def __init__(
            self,
            order: ArrayLike,
            normal: ArrayLike,
            misfire: ArrayLike | None = None,
            speed: ArrayLike | None = None,
            source: str | None = None,
        ) -> None: ...

    def __post_init__(self) -> None:
        q = np.atleast_1d(np.asarray(self.order, dtype=float))
        if q.ndim != 1 or q.size == 0 or not np.all(np.isfinite(q)):
            raise InputError("expected finite orders", key="order")
        if np.any(q <= 0.0):
            raise InputError("orders must be positive", key="order", value=float(q[q <= 0][0]))
        if np.unique(np.round(q * 1e9)).size != q.size:
            raise InputError("an order appears twice at one speed", key="order")
        speeds = None
        if self.speed is not None:
            speeds = np.atleast_1d(np.asarray(self.speed, dtype=float))
            if speeds.ndim != 1 or not np.all(np.isfinite(speeds)) or np.any(speeds <= 0.0):
                raise InputError("the speeds must be positive", key="speed")
            if np.any(np.diff(speeds) <= 0.0):
                raise InputError("the speeds must increase strictly", key="speed")
        rows = 1 if speeds is None else speeds.size
        out = {}
        for key in ("normal", "misfire"):
            value = getattr(self, key)
            if value is None:
                continue
            c = np.asarray(value, dtype=complex).reshape(rows, q.size)
            if not np.all(np.isfinite(c)):
                raise InputError("the coefficients must be finite numbers", key=key)
            out[key] = freeze(c, complex)
        object.__setattr__(self, "order", freeze(q))
        object.__setattr__(self, "speed", None if speeds is None else freeze(speeds))
        for key, value in out.items():
            object.__setattr__(self, key, value)

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, CylinderHarmonics):
            return NotImplemented
        return all(
            (a is None and b is None)
            or (a is not None and b is not None and a.shape == b.shape and np.array_equal(a, b))
            for a, b in (
                (self.order, other.order),
                (self.normal, other.normal),
                (self.misfire, other.misfire),
                (self.speed, other.speed),
            )
        )

    __hash__: ClassVar[None] = None  # type: ignore[assignment]  # arrays inside: not hashable

    def at(self, speeds: ArrayLike, orders: ArrayLike, *, misfiring: bool = False) -> Complex:
        """The coefficients c_q (N m, complex) of one cylinder at speeds and orders (class
        docstring): interpolated linearly in speed, held at the table's ends; 0 for an order
        the table does not hold.

        Parameters
        ----------
        speeds : array_like
            Crankshaft speeds (rad/s), shape (speeds,) or a scalar.
        orders : array_like
            Orders (dimensionless), shape (orders,).
        misfiring : bool
            The misfiring cylinder's coefficients instead of the firing one's.

        Returns
        -------
        numpy.ndarray
            (speeds, orders) complex torques (N m).

        Raises
        ------
        crankdyn.errors.InputError
            A misfiring cylinder's coefficients asked of a table without them (key
            ``misfire``, naming the file).
        """
        table = self.misfire if misfiring else self.normal
        if table is None:
            raise InputError(
                "the harmonic table gives no misfiring cylinder's coefficients (columns "
                "misfire_sin and misfire_cos, or misfire_amplitude and misfire_phase)",
                file=self.source,
                key="misfire",
            )
        w = np.atleast_1d(np.asarray(speeds, dtype=float))
        q = np.atleast_1d(np.asarray(orders, dtype=float))
        if self.speed is None or self.speed.size == 1:
            rows = np.broadcast_to(table[0], (w.size, self.order.size))
        else:
            pos = np.interp(w, self.speed, np.arange(self.speed.size, dtype=float))
            cell = np.minimum(pos.astype(int), self.speed.size - 2)
            frac = (pos - cell)[:, None]
            rows = table[cell] * (1.0 - frac) + table[cell + 1] * frac
        out = np.zeros((w.size, q.size), dtype=complex)
        for j, order in enumerate(q):  # the requested orders: a few dozen at most
            k = np.flatnonzero(np.abs(self.order - order) <= 1e-9 * max(order, 1.0))
            if k.size:
                out[:, j] = rows[:, int(k[0])]
        return out

    def missing(self, orders: ArrayLike) -> NDArray[np.float64]:
        """The orders the table does not hold (their coefficients are taken as 0).

        Parameters
        ----------
        orders : array_like
            Orders (dimensionless).

        Returns
        -------
        numpy.ndarray
            The orders of ``orders`` not in the table.
        """
        q = np.atleast_1d(np.asarray(orders, dtype=float))
        gap = np.abs(q[:, None] - self.order[None, :])
        held = np.any(gap <= 1e-9 * np.maximum(q, 1.0)[:, None], axis=1)
        return q[~held]


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
    cylinder_harmonics : CylinderHarmonics or None
        The engine builder's harmonic torques of one cylinder, firing and misfiring, per order
        (a model without an engine: :class:`CylinderHarmonics`).
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
    cylinder_harmonics: CylinderHarmonics | None = None
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
        if self.cylinder_harmonics is not None and self.torque is not None:
            raise InputError(
                "give a uniform torque or the cylinders' harmonic table, not both",
                key="cylinder_harmonics",
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
