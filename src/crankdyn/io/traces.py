"""Reading cylinder-pressure traces from CSV files.

Format (docs/engine-file.md): a header line naming the columns with their units, then one row per
point: crank angle over one cycle (any origin, any spacing, increasing) and absolute pressure, e.g.

    crank_angle_deg,pressure_MPa
    0.0,0.267
    ...

or a p-V indicator diagram: the cylinder volume (``volume_cm3``) or the piston displacement from
TDC (``displacement_mm``) and the pressure of every point in the order of the cycle, converted to
crank angle by the exact kinematics (:mod:`crankdyn.crank.pressure_volume`, seed 002 sec. 1).

Units are written after the last underscore (``pressure_MPa``), in brackets (``pressure [bar]``)
or parentheses (``p (kPa)``); any pint angle and pressure unit is accepted. Lines starting with
``#`` are comments. The engine file says where firing TDC lies in the trace (``firing_tdc``).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.pressure import PressureTrace
from crankdyn.errors import InputError
from crankdyn.io.csv_tables import CsvTable, read_csv_table, split_header_unit, unit_factor

__all__ = ["read_pressure_trace", "split_header_unit"]


_EXAMPLES = {
    "angle": "crank_angle_deg",
    "pressure": "pressure_MPa",
    "volume": "volume_cm3",
    "length": "displacement_mm",
}


def _abscissa(lowered: list[str]) -> tuple[int, str]:
    """The column the pressure is given over and its kind: a crank angle, a volume or a piston
    displacement (the first column when its name says none of them: an angle)."""
    for i, c in enumerate(lowered):
        if "angle" in c:
            return i, "angle"
    for i, c in enumerate(lowered):
        if "volume" in c or c.startswith("v"):
            return i, "volume"
    for i, c in enumerate(lowered):
        if "displacement" in c or c.startswith(("x", "s ", "s_", "s[", "s(")):
            return i, "length"
    return 0, "angle"


def _column_factor(cell: str, kind: str, file: str, column: str) -> float:
    example = _EXAMPLES[kind]
    unit = split_header_unit(cell)[1]
    if kind == "volume" and unit:  # volume_cm3: a power written without the caret
        unit = re.sub(r"(?<=[A-Za-z])3$", "^3", unit)
    return unit_factor(
        cell,
        unit,
        kind,
        file,
        missing=f"the {column} column must name its unit, e.g. {example}",
        unknown=f"unknown {column} unit {{unit}}",
    )


def read_pressure_trace(
    path: str | Path,
    *,
    firing_tdc: float = 0.0,
    cycle_angle: float = 4.0 * math.pi,
    display: str | None = None,
    geometry: CrankGeometry | None = None,
    compression_ratio: float | None = None,
) -> PressureTrace:
    """Read a pressure trace CSV: over crank angle, or a p-V diagram over volume or piston
    displacement (module docstring).

    Parameters
    ----------
    path
        The CSV file.
    firing_tdc
        Crank angle (rad) in the trace's own angle scale at which firing TDC occurs (traces
        over crank angle only: a p-V diagram finds firing TDC itself).
    cycle_angle
        Cycle length (rad): 4 pi four-stroke, 2 pi two-stroke.
    display
        How to name the file in messages (default: the path as given).
    geometry
        The cylinder (m): needed for a trace over volume or displacement.
    compression_ratio
        eps (dimensionless): needed for a trace over volume (the clearance volume).

    Returns
    -------
    PressureTrace
        The trace over one cycle: crank angle (rad, firing TDC at 0) and absolute pressure
        (Pa), converted from the header's units.

    Raises
    ------
    InputError
        On an unreadable file, a missing or unit-less header, unknown units, non-numeric cells,
        non-increasing angles, non-positive pressure, or a trace that does not cover the cycle;
        for a p-V diagram, a missing geometry or compression ratio, or a point outside the
        stroke or against the cycle's order; the error names the file, the line (``key``) and
        the offending cell (``value``).
    """
    table = read_csv_table(path, display=display, what="pressure trace")
    name, header, header_line = table.name, table.header, table.header_line
    if len(header) < 2:
        raise InputError(
            "expected two columns: crank angle and pressure",
            file=name,
            key=f"line {header_line}",
            value=",".join(header),
        )
    if table.header_is_numeric:
        raise InputError(
            "the first line must be a header naming the units, e.g. crank_angle_deg,pressure_MPa",
            file=name,
            key=f"line {header_line}",
            value=",".join(header),
        )
    lowered = [c.lower() for c in header]
    i_angle, abscissa = _abscissa(lowered)
    i_press = next(
        (
            i
            for i, c in enumerate(lowered)
            if i != i_angle and ("pressure" in c or c.startswith("p"))
        ),
        1 if i_angle == 0 else 0,
    )
    what = {"angle": "crank-angle", "volume": "volume", "length": "displacement"}[abscissa]
    angle_factor = _column_factor(header[i_angle], abscissa, name, what)
    pressure_factor = _column_factor(header[i_press], "pressure", name, "pressure")
    angles = table.column(i_angle, angle_factor, kind=abscissa)
    pressures = table.column(i_press, pressure_factor, kind="pressure")
    bad = np.flatnonzero(pressures <= 0.0)
    if bad.size:
        number, cell = table.cell(int(bad[0]), i_press)
        raise InputError(
            "absolute pressure must be positive (traces hold absolute pressures)",
            file=name,
            key=f"line {number}",
            value=cell,
        )
    if abscissa != "angle":
        return _from_volume(
            table, i_angle, abscissa, angles, pressures, firing_tdc, cycle_angle, geometry,
            compression_ratio,
        )  # fmt: skip
    back = np.flatnonzero(np.diff(angles) <= 0.0)
    if back.size:
        number, cell = table.cell(int(back[0]) + 1, i_angle)
        raise InputError(
            "crank angles must increase from line to line",
            file=name,
            key=f"line {number}",
            value=cell,
        )
    try:
        return PressureTrace.from_cycle_data(
            angles,
            pressures,
            firing_tdc=firing_tdc,
            cycle_angle=cycle_angle,
            source=name,
        )
    except InputError as exc:
        raise exc.within(file=name) from None


def _from_volume(
    table: CsvTable,
    column: int,
    kind: str,
    values: np.ndarray,
    pressures: np.ndarray,
    firing_tdc: float,
    cycle_angle: float,
    geometry: CrankGeometry | None,
    compression_ratio: float | None,
) -> PressureTrace:
    """A p-V diagram (over volume, or over piston displacement) converted to crank angle by the
    exact kinematics (:mod:`crankdyn.crank.pressure_volume`)."""
    from crankdyn.crank.pressure_volume import (
        StrokePointError,
        trace_from_displacement,
        trace_from_volume,
    )

    name = table.name
    over = "volume" if kind == "volume" else "piston displacement"
    if geometry is None:
        raise InputError(
            f"a trace over {over} needs the cylinder's geometry (read it through an engine file)",
            file=name,
        )
    if firing_tdc != 0.0:
        raise InputError(
            f"a trace over {over} finds firing TDC itself (the TDC of the higher pressure); "
            "firing_tdc applies to traces over crank angle",
            file=name,
            key="firing_tdc",
        )
    if kind == "volume" and compression_ratio is None:
        raise InputError(
            "a trace over volume needs the compression ratio (compression_ratio) to place the "
            "clearance volume",
            file=name,
            key="compression_ratio",
        )
    cycle = "four-stroke" if cycle_angle > 3.0 * math.pi else "two-stroke"
    try:
        if kind == "volume":
            assert compression_ratio is not None  # (checked above)
            return trace_from_volume(
                values, pressures, geometry, compression_ratio, cycle=cycle, source=name
            )
        return trace_from_displacement(
            values,
            pressures,
            geometry,
            cycle=cycle,
            source=name,
            compression_ratio=compression_ratio,
        )
    except StrokePointError as exc:
        number, cell = table.cell(exc.index, column)
        raise InputError(exc.message, file=name, key=f"line {number}", value=cell) from None
    except InputError as exc:
        raise exc.within(file=name) from None
