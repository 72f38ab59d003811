"""Indicated quantities of a cylinder-pressure trace: work, IMEP, peak pressure; the p-V diagram.

The indicated work of one cylinder per cycle is the closed integral W_i = oint p dV
(Heywood 1988, section 2.4) of the pressure the force analysis uses (the trace, interpolated
linearly and periodically) against the exact cylinder volume change dV = A dx (seed 000
section 1: x is the exact piston displacement). It is evaluated with the trapezoidal rule on the
trace's own points refined to at most 0.05 deg spacing, so that the rule's error (of order
h^2 x'') stays below about 1e-6 of the work; the clearance volume drops out, so no compression
ratio is needed. The indicated mean effective pressure is
IMEP = W_i / V_d with the swept volume V_d = A S. Pressures are absolute; the crankcase pressure
does not change W_i (its closed integral vanishes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import DEG
from crankdyn.crank.geometry import CrankGeometry, check_step
from crankdyn.crank.kinematics import slider_crank_exact
from crankdyn.crank.pressure import PressureTrace
from crankdyn.plausibility import PlausibilityWarning, pressure_warnings
from crankdyn.results import Result, column, freeze, scalar

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["PressureResult", "indicated_work", "pressure_analysis"]

_FINE = math.radians(0.05)


def _displacement(theta: ArrayLike, geometry: CrankGeometry) -> np.ndarray:
    return slider_crank_exact(
        theta, geometry.crank_radius, geometry.rod_length, geometry.offset
    ).displacement


def indicated_work(trace: PressureTrace, geometry: CrankGeometry) -> float:
    """Indicated work per cylinder and cycle, W_i = oint p dV (Heywood 1988, section 2.4).

    The closed integral of the interpolated trace against dV = A dx with the exact piston
    displacement x (seed 000 section 1), by the trapezoidal rule on the trace's points refined
    to at most 0.05 deg (module docstring).

    Parameters
    ----------
    trace : PressureTrace
        Absolute cylinder pressure over the cycle.
    geometry : CrankGeometry
        The cylinder's geometry (bore and crank train).

    Returns
    -------
    float
        W_i (J per cylinder and cycle); IMEP = W_i / V_d.

    Examples
    --------
    A constant pressure does no work over a closed cycle:

    >>> import numpy as np
    >>> from crankdyn.crank.geometry import CrankGeometry
    >>> g = CrankGeometry(0.1, 0.05, 0.2)
    >>> flat = PressureTrace(np.radians(np.arange(0.0, 720.0, 10.0)), np.full(72, 1e5))
    >>> abs(indicated_work(flat, g)) < 1e-9
    True
    """
    fine = np.linspace(0.0, trace.cycle_angle, round(trace.cycle_angle / _FINE) + 1)[:-1]
    theta = np.union1d(np.asarray(trace.crank_angle), fine)
    p = trace.at(theta)
    x = _displacement(theta, geometry)
    dx = np.diff(np.append(x, x[0]))  # the cycle closes: last point back to the first
    return float(geometry.piston_area * np.sum(0.5 * (p + np.roll(p, -1)) * dx))


@dataclass(frozen=True)
class PressureResult(Result):
    """Cylinder pressure over one cycle with its indicated figures (:func:`pressure_analysis`).

    Parameters
    ----------
    cycle_angle : float
        Crank angle of the cycle (rad); 4 pi four-stroke (default), 2 pi two-stroke.
    warnings : tuple of crankdyn.plausibility.PlausibilityWarning
        Plausibility warnings of the IMEP and the peak pressure.
    """

    title = "Cylinder pressure"
    crank_angle: NDArray[np.float64] = column("crank_angle_deg", "Crank angle", "deg", DEG)
    pressure: NDArray[np.float64] = column("pressure_Pa", "Pressure", "Pa")
    volume: NDArray[np.float64] = column("volume_m3", "Cylinder volume", "m³")
    indicated_work: float = scalar(
        "indicated_work_J", "Indicated work per cylinder", "J", headline=True
    )
    imep: float = scalar(
        "imep_Pa", "IMEP", "Pa", checked="imep", headline=True, better="max",
        description="Indicated mean effective pressure",
    )  # fmt: skip
    peak_pressure: float = scalar(
        "peak_pressure_Pa", "Peak pressure", "Pa", checked="peak_pressure", headline=True,
        better="min",
    )  # fmt: skip
    peak_angle: float = scalar(
        "peak_pressure_angle_deg", "Peak pressure after firing TDC", "deg", DEG
    )
    swept_volume: float = scalar("swept_volume_m3", "Swept volume per cylinder", "m³")
    compression_ratio: float | None = scalar("compression_ratio", "Compression ratio", "")
    volume_is_swept: bool = scalar(
        "volume_is_displacement", "Volume without clearance (compression ratio unknown)", ""
    )
    source: str = scalar("pressure_source", "Pressure from", "")
    cycle_angle: float = field(default=4.0 * math.pi, repr=False)
    warnings: tuple[PlausibilityWarning, ...] = field(default=(), repr=False, compare=False)

    def plot(self, fig: Figure | None = None) -> Figure:
        """The p-phi and p-V diagrams.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.forces import plot_pressure

        return plot_pressure(self, fig=fig)


def pressure_analysis(
    trace: PressureTrace,
    geometry: CrankGeometry,
    step: float = math.radians(0.5),
    *,
    fuel: str | None = None,
    aspiration: str | None = None,
) -> PressureResult:
    """The pressure over one cycle with the volume, indicated work, IMEP and peak pressure.

    The pressure is sampled every ``step`` from half a cycle before firing TDC to half a cycle
    after it (periodic interpolation of the trace); the indicated work is
    :func:`indicated_work` and IMEP = W_i / V_d (Heywood 1988, section 2.4). The volume is
    V_c + A x when the trace knows the compression ratio, else the displaced volume A x
    (``volume_is_swept``).

    Parameters
    ----------
    trace : PressureTrace
        Absolute cylinder pressure over the cycle.
    geometry : CrankGeometry
        The cylinder's geometry.
    step : float
        Crank-angle step of the table (rad); it must divide the cycle. Default 0.5 deg.
    fuel, aspiration : str or None
        The engine type (``"petrol"``/``"diesel"``, ``"natural"``/``"turbocharged"``) or None:
        they select the typical ranges of the plausibility warnings of the IMEP and the peak
        pressure (:func:`crankdyn.plausibility.pressure_warnings`), held in ``warnings``.

    Returns
    -------
    PressureResult
        Pressure (Pa) and volume (m^3) over the crank angle (rad), the indicated work (J), the
        IMEP (Pa), the peak pressure (Pa) and its angle (rad after firing TDC).

    Raises
    ------
    InputError
        If ``step`` does not divide the cycle.

    Examples
    --------
    The measured trace of the MWM inline-6 diesel (Mendes 2008):

    >>> import crankdyn
    >>> engine = crankdyn.Engine.example("inline6-diesel")
    >>> r = pressure_analysis(engine.pressure, engine.geometry)
    >>> round(r.peak_pressure / 1e5, 1), round(math.degrees(r.peak_angle), 1)  # bar, deg
    (152.0, 7.7)
    >>> round(r.imep / 1e5, 2)  # bar
    18.94
    """
    count = check_step(step, trace.cycle_angle)
    half = trace.cycle_angle / 2.0
    theta = np.linspace(-half, half, count + 1)
    x = _displacement(theta, geometry)
    area = geometry.piston_area
    eps = trace.compression_ratio
    clearance = 0.0 if eps is None else area * geometry.stroke / (eps - 1.0)
    work = indicated_work(trace, geometry)
    peak, at = trace.peak
    return PressureResult(
        crank_angle=freeze(theta),
        pressure=freeze(trace.at(theta)),
        volume=freeze(clearance + area * x),
        indicated_work=work,
        imep=work / geometry.swept_volume,
        peak_pressure=peak,
        peak_angle=at,
        swept_volume=geometry.swept_volume,
        compression_ratio=eps,
        volume_is_swept=eps is None,
        source=trace.source or "",
        cycle_angle=trace.cycle_angle,
        warnings=pressure_warnings(work / geometry.swept_volume, peak, fuel, aspiration),
    )
