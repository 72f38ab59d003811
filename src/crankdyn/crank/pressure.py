"""Cylinder pressure over the working cycle (domain object and numeric core).

A :class:`PressureTrace` holds absolute cylinder pressure against the crank angle measured from
firing TDC, over one cycle (720 deg four-stroke, 360 deg two-stroke), and interpolates it
periodically. Traces are read from CSV files at the boundary (:mod:`crankdyn.io.traces`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError
from crankdyn.results import freeze

__all__ = ["ATMOSPHERE", "MAX_TRACE_GAP_FRACTION", "PressureTrace"]

ATMOSPHERE = 101_325.0
"""Standard atmosphere (Pa): the default crankcase and intake pressure."""
MAX_TRACE_GAP_FRACTION = 1.0 / 12.0
"""Largest gap allowed between neighbouring trace points, as a fraction of the cycle (60 deg for
a four-stroke cycle), the wrap-around from the last point to the first included: a trace with a
wider gap does not cover the cycle."""


@dataclass(frozen=True, eq=False)
class PressureTrace:
    """Absolute cylinder pressure over one cycle, crank angle from firing TDC.

    Parameters
    ----------
    crank_angle : array_like
        Crank angles (rad) from firing TDC, strictly increasing, within one cycle:
        0 <= angle < cycle_angle; held as a read-only float array.
    pressure : array_like
        Absolute pressure at those angles (Pa), > 0; held as a read-only float array.
    cycle_angle : float
        Length of the cycle (rad): 4 pi for a four-stroke engine (default), 2 pi for a
        two-stroke.
    source : str or None
        Where the trace came from (file name), for messages and reports.
    compression_ratio : float or None
        Compression ratio eps of the engine the trace belongs to (dimensionless, > 1), or None
        when unknown; it fixes the clearance volume for p-V diagrams (the indicated work does
        not need it).

    Raises
    ------
    InputError
        If there are fewer than 3 points, a value is not finite, a pressure is not positive,
        the angles do not increase strictly within one cycle, a gap between points exceeds
        :data:`MAX_TRACE_GAP_FRACTION` of the cycle, or the compression ratio is not above 1.

    Examples
    --------
    A coarse trace, 1 bar everywhere but 50 bar at firing TDC:

    >>> import numpy as np
    >>> theta = np.radians(np.arange(0.0, 720.0, 30.0))
    >>> trace = PressureTrace(theta, np.where(theta == 0.0, 50e5, 1e5))
    >>> trace.at(np.radians([15.0, 735.0]))  # periodic linear interpolation (Pa)
    array([2550000., 2550000.])
    >>> trace.peak  # (Pa, rad)
    (5000000.0, 0.0)
    """

    crank_angle: NDArray[np.float64]
    pressure: NDArray[np.float64]
    cycle_angle: float = 4.0 * math.pi
    source: str | None = None
    compression_ratio: float | None = None

    def __post_init__(self) -> None:
        angle = np.asarray(self.crank_angle, dtype=float)
        p = np.asarray(self.pressure, dtype=float)
        if angle.ndim != 1 or angle.shape != p.shape or angle.size < 3:
            raise InputError("a pressure trace needs at least 3 points of angle and pressure")
        if not (np.all(np.isfinite(angle)) and np.all(np.isfinite(p))):
            raise InputError("the pressure trace holds values that are not finite numbers")
        if np.any(p <= 0.0):
            i = int(np.argmax(p <= 0.0))
            raise InputError(
                f"absolute pressure must be positive (point {i + 1} at "
                f"{math.degrees(angle[i]):.6g} deg)",
                key="pressure",
                value=float(p[i]),
            )
        if np.any(np.diff(angle) <= 0.0) or angle[0] < 0.0 or angle[-1] >= self.cycle_angle:
            raise InputError("trace angles must increase strictly within one cycle")
        gaps = np.diff(np.append(angle, angle[0] + self.cycle_angle))
        if gaps.max() > MAX_TRACE_GAP_FRACTION * self.cycle_angle * (1 + 1e-12):
            i = int(np.argmax(gaps))
            start = math.degrees(angle[i])
            raise InputError(
                f"the trace does not cover the cycle: no points for {math.degrees(gaps[i]):.4g} "
                f"deg after {start:.6g} deg from firing TDC (at most "
                f"{math.degrees(MAX_TRACE_GAP_FRACTION * self.cycle_angle):.4g} deg allowed)"
            )
        if self.compression_ratio is not None:
            eps = float(self.compression_ratio)
            if not (math.isfinite(eps) and eps > 1.0):
                raise InputError(
                    "the compression ratio must exceed 1",
                    key="compression_ratio",
                    value=self.compression_ratio,
                )
            object.__setattr__(self, "compression_ratio", eps)
        object.__setattr__(self, "crank_angle", freeze(angle))
        object.__setattr__(self, "pressure", freeze(p))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, PressureTrace):
            return NotImplemented
        return (
            self.cycle_angle == other.cycle_angle
            and np.array_equal(self.crank_angle, other.crank_angle)
            and np.array_equal(self.pressure, other.pressure)
        )

    __hash__: ClassVar[None] = None  # type: ignore[assignment]  # arrays inside: not hashable

    @classmethod
    def from_cycle_data(
        cls,
        crank_angle: ArrayLike,
        pressure: ArrayLike,
        *,
        firing_tdc: float = 0.0,
        cycle_angle: float = 4.0 * math.pi,
        source: str | None = None,
        compression_ratio: float | None = None,
    ) -> PressureTrace:
        """Build from angles as recorded (any origin) with firing TDC at ``firing_tdc``.

        Angles are shifted so that firing TDC is 0, wrapped into one cycle and sorted; a closing
        point that repeats the first one a cycle later is dropped.

        Parameters
        ----------
        crank_angle : array_like
            Crank angles as recorded (rad), strictly increasing, spanning less than one cycle.
        pressure : array_like
            Absolute pressure at those angles (Pa).
        firing_tdc : float
            The recorded angle of firing TDC (rad); default 0.
        cycle_angle : float
            Length of the cycle (rad); default 4 pi (four-stroke).
        source : str or None
            Where the trace came from, for messages.
        compression_ratio : float or None
            Compression ratio (dimensionless, > 1), or None.

        Returns
        -------
        PressureTrace
            The trace with angles from firing TDC in [0, cycle_angle).

        Raises
        ------
        InputError
            If the angles do not increase strictly or span more than one cycle, or the trace is
            invalid (:class:`PressureTrace`).
        """
        angle = np.asarray(crank_angle, dtype=float)
        p = np.asarray(pressure, dtype=float)
        if angle.size >= 2 and abs(angle[-1] - angle[0] - cycle_angle) < 1e-9 * cycle_angle:
            angle, p = angle[:-1], p[:-1]
        if angle.size >= 2 and np.any(np.diff(angle) <= 0.0):
            i = int(np.argmax(np.diff(angle) <= 0.0)) + 1
            raise InputError(
                f"trace angles must increase strictly (point {i + 1})",
                value=float(np.degrees(angle[i])),
            )
        if angle.size and angle[-1] - angle[0] >= cycle_angle:
            raise InputError(
                f"the trace spans more than one {math.degrees(cycle_angle):.0f} deg cycle",
                value=float(np.degrees(angle[-1])),
            )
        shifted = np.mod(angle - firing_tdc, cycle_angle)
        order = np.argsort(shifted, kind="stable")
        return cls(
            shifted[order],
            p[order],
            cycle_angle=cycle_angle,
            source=source,
            compression_ratio=compression_ratio,
        )

    def at(self, phi: ArrayLike) -> NDArray[np.float64]:
        """Pressure at crank angles, by periodic linear interpolation of the trace.

        Parameters
        ----------
        phi : array_like
            Crank angles (rad from firing TDC, any range: the trace repeats every cycle).

        Returns
        -------
        numpy.ndarray
            Absolute pressure (Pa), of the shape of ``phi``.
        """
        # np.interp(phi, angle, pressure, period=cycle) to the bit: numpy's own steps, the
        # trace's wrapped points made once per trace instead of at every call
        xp, fp = self._periodic
        return np.interp(np.asarray(phi, dtype=np.float64) % abs(self.cycle_angle), xp, fp)

    @cached_property
    def _periodic(self) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """The trace's points as ``np.interp(..., period=cycle)`` wraps them: angles modulo
        the cycle, sorted, with the last point repeated a cycle before the first and the first
        a cycle after the last (the pressures alike)."""
        period = abs(self.cycle_angle)
        xp = np.asarray(self.crank_angle, dtype=np.float64) % period
        order = np.argsort(xp)
        xp, fp = xp[order], np.asarray(self.pressure, dtype=np.float64)[order]
        xp = np.concatenate((xp[-1:] - period, xp, xp[0:1] + period))
        fp = np.concatenate((fp[-1:], fp, fp[0:1]))
        return freeze(xp), freeze(fp)

    @property
    def peak(self) -> tuple[float, float]:
        """Largest pressure of the trace points (Pa) and its crank angle (rad from firing TDC)."""
        i = int(np.argmax(self.pressure))
        return float(self.pressure[i]), float(self.crank_angle[i])

    def scaled(self, factor: float) -> PressureTrace:
        """The trace with every pressure multiplied by a factor.

        Parameters
        ----------
        factor : float
            The factor (dimensionless, > 0).

        Returns
        -------
        PressureTrace
            The scaled trace, same angles, source and compression ratio.
        """
        return PressureTrace(
            self.crank_angle,
            self.pressure * float(factor),
            self.cycle_angle,
            self.source,
            self.compression_ratio,
        )
