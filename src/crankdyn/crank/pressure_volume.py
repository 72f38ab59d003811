"""A pressure trace given over the cylinder volume (a p-V indicator diagram) converted to crank
angle by the exact slider-crank kinematics (numeric core and domain constructor; seed 002 sec. 1).

Seed 002 (Makushev et al. 2010, sec. 1 "Определение пути поршня") draws the mechanism every
10 deg of crank angle, reads the piston's path at each, and uses the graph of path against crank
angle "to find the cylinder pressure from the indicator diagram drawn in p-V coordinates and to
re-draw it in p-phi coordinates". This module does the same analytically: each point's volume V
gives the piston displacement from TDC, x = (V - V_c) / A_p (A_p the piston area, V_c the
clearance volume V_s / (eps - 1) for the swept volume V_s and compression ratio eps), and x gives
the crank angle by the exact displacement x = y_TDC - (R cos(phi) + L cos(beta)) (seed 000 sec. 1,
seed 002 eq. 2; :func:`crankdyn.crank.kinematics.slider_crank_exact`) solved for phi. With the
cylinder axis at lateral offset e and the piston pin at height y = y_TDC - x above the crank
centre, the rod closes the triangle (R sin(phi) - e)^2 + (R cos(phi) - y)^2 = L^2, i.e.::

    e sin(phi) + y cos(phi) = c,   c = (R^2 + e^2 + y^2 - L^2) / (2 R),

so that phi = delta +- arccos(c / rho) with rho = sqrt(e^2 + y^2) and delta = atan2(e, y):
the + sign while the piston moves away from the head (TDC to BDC: phi from phi_TDC to phi_BDC)
and the - sign on its way back. At the dead centres this is exactly seed 000's
phi_TDC = arcsin(e / (L + R)) and phi_BDC = pi + arcsin(e / (L - R)).

**The strokes.** The points are taken in the file's order, which must be the order of the cycle
(a p-V diagram traced around its loop). The volume's dead centres are its turning points: the
points are split into the runs above and below mid-stroke; each run below holds a TDC (its
smallest volume) and each run above a BDC (its largest); a four-stroke cycle has two of each, a
two-stroke cycle one. A dead centre falls between two points: its nearest point is counted to
the stroke before it when its previous neighbour lies farther from it in volume than its next one
(the turning point then lies after it, for points about evenly spaced in crank angle), else to the
stroke after it. The TDC with the higher pressure (the largest pressure within its run) is
firing TDC: compression before it, expansion after it; then exhaust (to the other TDC,
gas-exchange TDC) and intake. Between two dead centres the volume runs one way, the piston
moving away from the head after a TDC (+ sign) and toward it after a BDC (- sign). Crank angles
are measured from the cylinder axis, as every trace's (firing TDC at 0 for the central
mechanism), over [0, 720) deg (four-stroke) or [0, 360) deg (two-stroke).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.kinematics import slider_crank_exact
from crankdyn.crank.pressure import PressureTrace
from crankdyn.errors import InputError

__all__ = [
    "RANGE_TOLERANCE",
    "StrokePointError",
    "clearance_volume",
    "crank_angle_of_displacement",
    "identify_strokes",
    "trace_from_displacement",
    "trace_from_volume",
    "volume_at",
]

RANGE_TOLERANCE = 0.01
"""A point's displacement may lie outside [0, S] by this share of the stroke S (rounding of a
digitised diagram); it is then taken at the dead centre. Farther out it is an error."""
STROKES = {"four-stroke": ("expansion", "exhaust", "intake", "compression"),
           "two-stroke": ("expansion", "compression")}  # fmt: skip
"""The strokes from firing TDC, in the order of the cycle."""


class StrokePointError(InputError):
    """An InputError about one point of a p-V trace: ``index`` is the point (0-based), for the
    reader to name the file's line.

    Parameters
    ----------
    message : str
        What is wrong.
    index : int
        The point (0-based).
    value : object
        The offending value, or None.
    """

    def __init__(self, message: str, index: int, value: object = None) -> None:
        super().__init__(message, key=f"point {index + 1}", value=value)
        self.index = index


def clearance_volume(geometry: CrankGeometry, compression_ratio: float) -> float:
    """Clearance volume V_c = V_s / (eps - 1) (m^3).

    Parameters
    ----------
    geometry : CrankGeometry
        The cylinder (its swept volume V_s = A_p S, m^3).
    compression_ratio : float
        eps (dimensionless), > 1.

    Returns
    -------
    float
        V_c (m^3).

    Raises
    ------
    InputError
        A compression ratio that is not above 1 (key ``compression_ratio``).

    Examples
    --------
    >>> g = CrankGeometry(0.1, 0.05, 0.2)
    >>> round(clearance_volume(g, 11.0) * 1e6, 6)  # cm^3: 785.398 / 10
    78.539816
    """
    eps = float(compression_ratio)
    if not (math.isfinite(eps) and eps > 1.0):
        raise InputError(
            "the compression ratio must exceed 1", key="compression_ratio", value=compression_ratio
        )
    return geometry.swept_volume / (eps - 1.0)


def crank_angle_of_displacement(
    displacement: ArrayLike, geometry: CrankGeometry, away: ArrayLike
) -> NDArray[np.float64]:
    """The crank angle at which the piston stands at a displacement, within one revolution.

    phi = delta + arccos(c / rho) while the piston moves away from the head (TDC to BDC),
    delta - arccos(c / rho) on its way back (module docstring; the exact displacement of seed
    000 sec. 1 solved for phi).

    Parameters
    ----------
    displacement : array_like
        Piston displacement x from TDC toward the crank (m), 0 <= x <= S (clipped there).
    geometry : CrankGeometry
        R, L and the offset e (m).
    away : array_like of bool
        True where the piston moves away from the head (broadcast against ``displacement``).

    Returns
    -------
    numpy.ndarray
        phi (rad): in [phi_TDC, phi_BDC] where ``away``, in [phi_BDC - 2 pi, phi_TDC] else.

    Examples
    --------
    The displacement at 60 deg of the VAZ-2108 (seed 002) gives 60 deg back:

    >>> g = CrankGeometry.from_stroke(0.076, 0.071, rod_ratio=0.26)
    >>> x = slider_crank_exact(math.radians(60), g.crank_radius, g.rod_length).displacement
    >>> round(math.degrees(float(crank_angle_of_displacement(x, g, True))), 9)
    60.0
    """
    r, l, e = geometry.crank_radius, geometry.rod_length, geometry.offset
    x = np.clip(np.asarray(displacement, dtype=float), 0.0, geometry.stroke)
    y = math.sqrt((l + r) ** 2 - e * e) - x
    rho = np.sqrt(e * e + y * y)
    c = (r * r + e * e + y * y - l * l) / (2.0 * r)
    half = np.arccos(np.clip(c / rho, -1.0, 1.0))
    delta = np.arctan2(e, y)
    return np.asarray(np.where(np.asarray(away, dtype=bool), delta + half, delta - half))


def volume_at(
    phi: ArrayLike, geometry: CrankGeometry, compression_ratio: float
) -> NDArray[np.float64]:
    """Cylinder volume V = V_c + A_p x(phi) with the exact displacement (m^3).

    Parameters
    ----------
    phi : array_like
        Crank angles (rad).
    geometry : CrankGeometry
        The cylinder (m).
    compression_ratio : float
        eps (dimensionless), > 1.

    Returns
    -------
    numpy.ndarray
        V (m^3), of the shape of ``phi``.
    """
    x = slider_crank_exact(
        phi, geometry.crank_radius, geometry.rod_length, geometry.offset
    ).displacement
    return clearance_volume(geometry, compression_ratio) + geometry.piston_area * x


def identify_strokes(
    displacement: ArrayLike, pressure: ArrayLike, cycle: str = "four-stroke"
) -> tuple[NDArray[np.int64], NDArray[np.bool_], int]:
    """The stroke of every point of a trace taken in the order of the cycle (module docstring).

    Parameters
    ----------
    displacement : array_like
        Piston displacement of every point (m), in the order of the cycle, shape (n,).
    pressure : array_like
        Absolute pressure of every point (Pa), shape (n,).
    cycle : str
        ``"four-stroke"`` or ``"two-stroke"``.

    Returns
    -------
    stroke : numpy.ndarray
        (n,) the stroke of each point, counted from firing TDC: 0 expansion, 1 exhaust,
        2 intake, 3 compression (two-stroke: 0 expansion, 1 compression).
    away : numpy.ndarray
        (n,) True where the piston moves away from the head.
    firing : int
        Index of the point at firing TDC.

    Raises
    ------
    StrokePointError
        The volume passes TDC or BDC a number of times other than the cycle's, or turns back
        within a stroke (names the point).
    """
    x = np.asarray(displacement, dtype=float)
    p = np.asarray(pressure, dtype=float)
    n = x.size
    tdcs = 2 if cycle == "four-stroke" else 1
    mid = 0.5 * (np.min(x) + np.max(x))
    low = x < mid
    # runs of points on one side of mid-stroke, cyclic (the last run may go on at the start)
    change = np.flatnonzero(low != np.roll(low, 1))
    if change.size != 2 * tdcs:
        raise StrokePointError(
            f"the volume passes TDC {max(change.size // 2, 1)} time(s) in the trace; a {cycle} "
            f"cycle passes it {tdcs} time(s) (points in the order of the cycle, one cycle)",
            int(change[0]) if change.size else 0,
        )
    starts = change
    ends = np.roll(change, -1)
    centres, kinds = [], []
    for a, b in zip(starts, ends, strict=True):
        idx = np.arange(a, b if b > a else b + n) % n
        if low[a]:
            centres.append(int(idx[np.argmin(x[idx])]))
            kinds.append("tdc")
        else:
            centres.append(int(idx[np.argmax(x[idx])]))
            kinds.append("bdc")
    tdc_runs = [k for k, kind in enumerate(kinds) if kind == "tdc"]
    peak = []
    for k in tdc_runs:
        a, b = starts[k], ends[k]
        idx = np.arange(a, b if b > a else b + n) % n
        peak.append(float(np.max(p[idx])))
    fire_run = tdc_runs[int(np.argmax(peak))]
    firing = centres[fire_run]
    # a dead centre lies between samples: its sample belongs to the stroke before it when the
    # turning point lies after it (its previous neighbour farther away in x than its next one,
    # the vertex of the parabola through the three, for points about evenly spaced in angle)
    begins = []
    for c in centres:
        before, after = abs(x[(c - 1) % n] - x[c]), abs(x[(c + 1) % n] - x[c])
        begins.append((c + 1) % n if before > after else c)
    # walk the cycle from firing TDC: the strokes are the spans between successive dead centres
    m = len(centres)
    order = [(fire_run + k) % m for k in range(m)]
    stroke = np.empty(n, dtype=np.int64)
    away = np.empty(n, dtype=bool)
    for s, k in enumerate(order):
        begin, end = begins[k], begins[order[(s + 1) % m]]
        span = np.arange(begin, end if end > begin else end + n) % n
        stroke[span] = s
        away[span] = kinds[k] == "tdc"
        step = np.diff(x[span])
        wrong = np.flatnonzero(step < 0.0) if kinds[k] == "tdc" else np.flatnonzero(step > 0.0)
        if wrong.size:
            i = int(span[wrong[0] + 1])
            raise StrokePointError(
                f"the volume turns back within the {STROKES[cycle][s]} stroke (the points must "
                "follow the cycle, the volume running one way between the dead centres)",
                i,
            )
    return stroke, away, firing


def trace_from_displacement(
    displacement: ArrayLike,
    pressure: ArrayLike,
    geometry: CrankGeometry,
    *,
    cycle: str = "four-stroke",
    source: str | None = None,
    compression_ratio: float | None = None,
) -> PressureTrace:
    """A pressure trace over crank angle from one over the piston displacement (module
    docstring; seed 002 sec. 1).

    Parameters
    ----------
    displacement : array_like
        Piston displacement x from TDC toward the crank (m) of every point, in the order of
        the cycle (one cycle, any starting point).
    pressure : array_like
        Absolute pressure (Pa) of every point.
    geometry : CrankGeometry
        The cylinder (m).
    cycle : str
        ``"four-stroke"`` (default) or ``"two-stroke"``.
    source : str or None
        Where the trace came from, for messages.
    compression_ratio : float or None
        eps (dimensionless), kept on the trace.

    Returns
    -------
    PressureTrace
        Absolute pressure (Pa) against crank angle from the cylinder axis (rad), firing TDC's
        revolution first.

    Raises
    ------
    StrokePointError
        A point outside the stroke by more than :data:`RANGE_TOLERANCE` of it, strokes that
        cannot be told apart (:func:`identify_strokes`), or two points at one crank angle.
    InputError
        An unknown cycle, or fewer than 3 points.

    Examples
    --------
    A motored single-cylinder trace sampled every 10 deg, given over displacement, comes back
    at its angles:

    >>> g = CrankGeometry(0.1, 0.05, 0.2)
    >>> phi = np.radians(np.arange(0.0, 720.0, 10.0))
    >>> x = slider_crank_exact(phi, g.crank_radius, g.rod_length).displacement
    >>> p = 1e5 * (1.0 + 9.0 * np.exp(-((phi / 0.6) ** 2)))  # a peak at firing TDC only
    >>> trace = trace_from_displacement(x, p, g)
    >>> float(np.max(np.abs(trace.crank_angle - phi))) < 1e-7
    True
    """
    if cycle not in STROKES:
        raise InputError("expected four-stroke or two-stroke", key="cycle", value=cycle)
    x = np.asarray(displacement, dtype=float)
    p = np.asarray(pressure, dtype=float)
    if x.ndim != 1 or x.shape != p.shape or x.size < 3:
        raise InputError("a p-V trace needs at least 3 points of volume and pressure")
    if x[-1] == x[0] and p[-1] == p[0]:  # a closing point that repeats the first: dropped
        x, p = x[:-1], p[:-1]
    stroke_length = geometry.stroke
    slack = RANGE_TOLERANCE * stroke_length
    out = np.flatnonzero((x < -slack) | (x > stroke_length + slack))
    if out.size:
        i = int(out[0])
        raise StrokePointError(
            f"the piston displacement {x[i] * 1e3:.6g} mm lies outside the stroke "
            f"(0 to {stroke_length * 1e3:.6g} mm): check the geometry, the compression ratio "
            "and the column's unit",
            i,
            float(x[i]),
        )
    stroke, away, _firing = identify_strokes(x, p, cycle)
    # within one revolution: [phi_TDC, phi_BDC] away from the head, [phi_BDC - 2 pi, phi_TDC]
    # back toward it; the strokes from firing TDC lie 0, 1, 1, 2 revolutions on (expansion,
    # exhaust, intake, compression; two-stroke: expansion 0, compression 1)
    within = crank_angle_of_displacement(x, geometry, away)
    cycle_angle = 4.0 * math.pi if cycle == "four-stroke" else 2.0 * math.pi
    angle = np.mod(within + 2.0 * math.pi * ((stroke + 1) // 2), cycle_angle)
    order = np.argsort(angle, kind="stable")
    same = np.flatnonzero(np.diff(angle[order]) <= 0.0)
    if same.size:
        i = int(order[same[0] + 1])
        raise StrokePointError(
            f"two points fall at the crank angle {math.degrees(angle[i]):.6g} deg",
            i,
            float(x[i]),
        )
    return PressureTrace(
        angle[order],
        p[order],
        cycle_angle=cycle_angle,
        source=source,
        compression_ratio=compression_ratio,
    )


def trace_from_volume(
    volume: ArrayLike,
    pressure: ArrayLike,
    geometry: CrankGeometry,
    compression_ratio: float,
    *,
    cycle: str = "four-stroke",
    source: str | None = None,
) -> PressureTrace:
    """A pressure trace over crank angle from a p-V diagram (module docstring; seed 002 sec. 1):
    x = (V - V_c) / A_p, then :func:`trace_from_displacement`.

    Parameters
    ----------
    volume : array_like
        Cylinder volume of every point (m^3), in the order of the cycle.
    pressure : array_like
        Absolute pressure (Pa) of every point.
    geometry : CrankGeometry
        The cylinder (m).
    compression_ratio : float
        eps (dimensionless), > 1: fixes the clearance volume V_c = V_s / (eps - 1).
    cycle : str
        ``"four-stroke"`` (default) or ``"two-stroke"``.
    source : str or None
        Where the trace came from, for messages.

    Returns
    -------
    PressureTrace
        Absolute pressure (Pa) against crank angle (rad), with the compression ratio.

    Raises
    ------
    StrokePointError
        As :func:`trace_from_displacement`.
    InputError
        A compression ratio not above 1.
    """
    v_c = clearance_volume(geometry, compression_ratio)
    x = (np.asarray(volume, dtype=float) - v_c) / geometry.piston_area
    return trace_from_displacement(
        x,
        pressure,
        geometry,
        cycle=cycle,
        source=source,
        compression_ratio=float(compression_ratio),
    )
