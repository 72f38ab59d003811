"""Cylinder pressure over the working cycle (domain object and numeric core).

A :class:`PressureTrace` holds absolute cylinder pressure against the crank angle measured from
firing TDC, over one cycle (720 deg four-stroke, 360 deg two-stroke), and interpolates it
periodically. Traces are read from CSV files at the boundary (:mod:`crankdyn.io.traces`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from crankdyn.errors import InputError
from crankdyn.results import freeze

__all__ = ["ATMOSPHERE", "MAX_TRACE_GAP_FRACTION", "PressureTrace"]

ATMOSPHERE = 101_325.0  # Pa, standard atmosphere (default crankcase pressure)
MAX_TRACE_GAP_FRACTION = 1.0 / 12.0
"""Largest gap allowed between neighbouring trace points, as a fraction of the cycle (60 deg for
a four-stroke cycle), the wrap-around from the last point to the first included: a trace with a
wider gap does not cover the cycle."""


@dataclass(frozen=True, eq=False)
class PressureTrace:
    """Absolute cylinder pressure over one cycle, crank angle from firing TDC.

    Parameters
    ----------
    crank_angle
        Crank angles (rad) from firing TDC, strictly increasing, within one cycle:
        0 <= angle < cycle_angle.
    pressure
        Absolute pressure at those angles (Pa), > 0.
    cycle_angle
        Length of the cycle (rad): 4 pi for a four-stroke engine, 2 pi for a two-stroke.
    source
        Where the trace came from (file name), for messages and reports.
    compression_ratio
        Compression ratio eps of the engine the trace belongs to (dimensionless, > 1), or None
        when unknown; it fixes the clearance volume for p-V diagrams (the indicated work does
        not need it).
    """

    crank_angle: np.ndarray
    pressure: np.ndarray
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

    __hash__ = None  # mutable-looking contents: not hashable

    @classmethod
    def from_cycle_data(
        cls,
        crank_angle,
        pressure,
        *,
        firing_tdc: float = 0.0,
        cycle_angle: float = 4.0 * math.pi,
        source: str | None = None,
        compression_ratio: float | None = None,
    ) -> PressureTrace:
        """Build from angles as recorded (rad, any origin) with firing TDC at ``firing_tdc``.

        Angles are shifted so that firing TDC is 0, wrapped into one cycle and sorted; a closing
        point that repeats the first one a cycle later is dropped.
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

    def at(self, phi) -> np.ndarray:
        """Pressure (Pa) at crank angles phi (rad from firing TDC, any range), by periodic linear
        interpolation of the trace."""
        return np.interp(
            np.asarray(phi, dtype=float), self.crank_angle, self.pressure, period=self.cycle_angle
        )

    @property
    def peak(self) -> tuple[float, float]:
        """Largest pressure of the trace points (Pa) and its crank angle (rad from firing TDC)."""
        i = int(np.argmax(self.pressure))
        return float(self.pressure[i]), float(self.crank_angle[i])

    def scaled(self, factor: float) -> PressureTrace:
        """The trace with every pressure multiplied by factor (> 0)."""
        return PressureTrace(
            self.crank_angle,
            self.pressure * float(factor),
            self.cycle_angle,
            self.source,
            self.compression_ratio,
        )
