"""Reading cylinder-pressure traces from CSV files.

Format (docs/engine-file.md): a header line naming the columns with their units, then one row per
point: crank angle over one cycle (any origin, any spacing, increasing) and absolute pressure, e.g.

    crank_angle_deg,pressure_MPa
    0.0,0.267
    ...

Units are written after the last underscore (``pressure_MPa``), in brackets (``pressure [bar]``)
or parentheses (``p (kPa)``); any pint angle and pressure unit is accepted. Lines starting with
``#`` are comments. The engine file says where firing TDC lies in the trace (``firing_tdc``).
"""

from __future__ import annotations

import csv
import math
import re
from pathlib import Path

import numpy as np

from crankdyn.errors import InputError
from crankdyn.io.files import MAX_CSV_BYTES, display_name, read_text
from crankdyn.io.units import parse_quantity
from crankdyn.pressure import PressureTrace

__all__ = ["read_pressure_trace", "split_header_unit"]

_BRACKETED = re.compile(r"^(.*?)\s*[\[(]\s*([^\])]+?)\s*[\])]\s*$")


def split_header_unit(cell: str) -> tuple[str, str | None]:
    """Split a header cell into (name, unit): ``pressure_MPa``, ``pressure [MPa]``,
    ``p (MPa)``; unit None when the cell names none."""
    cell = cell.strip()
    m = _BRACKETED.match(cell)
    if m:
        return m.group(1).strip(), m.group(2).strip()
    if "_" in cell:
        name, unit = cell.rsplit("_", 1)
        return name, unit
    return cell, None


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _column_factor(cell: str, kind: str, file: str, column: str) -> float:
    unit = split_header_unit(cell)[1]
    if not unit:
        raise InputError(
            f"the {column} column must name its unit, e.g. "
            + ("crank_angle_deg" if kind == "angle" else "pressure_MPa"),
            file=file,
            key="header",
            value=cell,
        )
    try:
        return parse_quantity(f"1 {unit}", kind, key="header", file=file)
    except InputError:
        if kind == "angle" and unit.lower() in ("deg", "degree", "degrees"):
            return math.pi / 180.0
        raise InputError(
            f"unknown {column} unit {unit!r}", file=file, key="header", value=cell
        ) from None


def read_pressure_trace(
    path: str | Path,
    *,
    firing_tdc: float = 0.0,
    cycle_angle: float = 4.0 * math.pi,
    display: str | None = None,
) -> PressureTrace:
    """Read a pressure trace CSV.

    Parameters
    ----------
    path
        The CSV file.
    firing_tdc
        Crank angle (rad) in the trace's own angle scale at which firing TDC occurs.
    cycle_angle
        Cycle length (rad): 4 pi four-stroke, 2 pi two-stroke.
    display
        How to name the file in messages (default: the path as given).

    Raises
    ------
    InputError
        On an unreadable file, a missing or unit-less header, unknown units, non-numeric cells,
        non-increasing angles, non-positive pressure, or a trace that does not cover the cycle.
    """
    name = display or display_name(path)
    try:
        text = read_text(path, limit=MAX_CSV_BYTES, what="pressure trace")
    except InputError as exc:
        raise InputError(exc.message, file=name) from None
    rows = [
        (number, row)
        for number, row in enumerate(csv.reader(text.splitlines()), start=1)
        if row and any(c.strip() for c in row) and not row[0].lstrip().startswith("#")
    ]
    if not rows:
        raise InputError("the pressure trace is empty", file=name)
    header_line, header = rows[0]
    if len(header) < 2:
        raise InputError(
            "expected two columns: crank angle and pressure",
            file=name,
            key=f"line {header_line}",
            value=",".join(header),
        )
    if _is_number(header[0]):
        raise InputError(
            "the first line must be a header naming the units, e.g. crank_angle_deg,pressure_MPa",
            file=name,
            key=f"line {header_line}",
            value=",".join(header),
        )
    lowered = [c.lower() for c in header]
    i_angle = next((i for i, c in enumerate(lowered) if "angle" in c), 0)
    i_press = next(
        (
            i
            for i, c in enumerate(lowered)
            if i != i_angle and ("pressure" in c or c.startswith("p"))
        ),
        1 if i_angle == 0 else 0,
    )
    angle_factor = _column_factor(header[i_angle], "angle", name, "crank-angle")
    pressure_factor = _column_factor(header[i_press], "pressure", name, "pressure")
    need = max(i_angle, i_press) + 1
    angles, pressures = [], []
    for number, row in rows[1:]:
        if len(row) < need:
            raise InputError(
                f"expected {need} columns", file=name, key=f"line {number}", value=",".join(row)
            )
        values = []
        for i in (i_angle, i_press):
            cell = row[i].strip()
            try:
                v = float(cell)
            except ValueError:
                raise InputError(
                    f"not a number in column {header[i].strip()!r}",
                    file=name,
                    key=f"line {number}",
                    value=cell,
                ) from None
            if not math.isfinite(v):
                raise InputError(
                    f"not a finite number in column {header[i].strip()!r}",
                    file=name,
                    key=f"line {number}",
                    value=cell,
                )
            values.append(v)
        if values[1] <= 0.0:
            raise InputError(
                "absolute pressure must be positive (traces hold absolute pressures)",
                file=name,
                key=f"line {number}",
                value=row[i_press].strip(),
            )
        if angles and values[0] * angle_factor <= angles[-1]:
            raise InputError(
                "crank angles must increase from line to line",
                file=name,
                key=f"line {number}",
                value=row[i_angle].strip(),
            )
        angles.append(values[0] * angle_factor)
        pressures.append(values[1] * pressure_factor)
    try:
        return PressureTrace.from_cycle_data(
            np.array(angles),
            np.array(pressures),
            firing_tdc=firing_tdc,
            cycle_angle=cycle_angle,
            source=name,
        )
    except InputError as exc:
        raise exc.within(file=name) from None
