"""CSV tables for the forced torsional response: load curves and harmonic-coefficient tables.

Both are CSV files with a header that names every column and its unit (as pressure traces do:
``speed_rpm``, ``peak_pressure [MPa]``, ``phase (deg)``), lines starting with ``#`` are comments.

- Load curve: a speed column and one of ``peak_pressure`` (a pressure), ``imep`` (a pressure) or
  ``load_factor`` (no unit), e.g. ``speed_rpm,peak_pressure_MPa``.
- Harmonic table: ``order`` (no unit), ``imep`` and ``amplitude`` (pressures) and optionally
  ``phase`` (an angle): one row per order and mean indicated pressure.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from crankdyn.errors import InputError
from crankdyn.io.files import MAX_CSV_BYTES, display_name, read_text
from crankdyn.io.traces import split_header_unit
from crankdyn.io.units import parse_quantity
from crankdyn.torsion.excitation import HarmonicTable, LoadCurve

__all__ = ["read_harmonic_table", "read_load_curve"]

_PLAIN = ("load_factor", "order")


def _read(path: Path, name: str, what: str):
    try:
        text = read_text(path, limit=MAX_CSV_BYTES, what=what)
    except InputError as exc:
        raise InputError(exc.message, file=name) from None
    rows = [
        (number, [c.strip() for c in row])
        for number, row in enumerate(csv.reader(text.splitlines()), start=1)
        if row and any(c.strip() for c in row) and not row[0].lstrip().startswith("#")
    ]
    if len(rows) < 2:
        raise InputError(f"the {what} needs a header line and at least one row", file=name)
    return rows


def _columns(header: list[str], name: str) -> dict[str, tuple[int, str | None]]:
    out = {}
    for i, cell in enumerate(header):
        whole = cell.strip().lower().replace(" ", "_")
        if whole in _PLAIN:  # a unit-less column whose name holds an underscore
            out[whole] = (i, None)
            continue
        base, unit = split_header_unit(cell)
        key = base.strip().lower().replace(" ", "_")
        if key:
            out[key] = (i, unit)
    return out


def _factor(unit: str | None, kind: str, cell: str, name: str) -> float:
    if kind == "ratio":
        if unit:
            raise InputError("this column takes no unit", file=name, key="header", value=cell)
        return 1.0
    if not unit:
        raise InputError(
            "the column must name its unit, e.g. speed_rpm or peak_pressure_MPa",
            file=name,
            key="header",
            value=cell,
        )
    try:
        return parse_quantity(f"1 {unit}", kind, key="header", file=name)
    except InputError:
        if kind == "angle" and unit.lower() in ("deg", "degree", "degrees"):
            return math.pi / 180.0
        raise InputError(f"unknown unit {unit!r}", file=name, key="header", value=cell) from None


def _numbers(rows, index: int, header_cell: str, name: str) -> np.ndarray:
    out = []
    for number, row in rows:
        if index >= len(row):
            raise InputError(
                f"expected a value in column {header_cell!r}",
                file=name,
                key=f"line {number}",
                value=",".join(row),
            )
        cell = row[index]
        try:
            value = float(cell)
        except ValueError:
            raise InputError(
                f"not a number in column {header_cell!r}",
                file=name,
                key=f"line {number}",
                value=cell,
            ) from None
        if not math.isfinite(value):
            raise InputError(
                f"not a finite number in column {header_cell!r}",
                file=name,
                key=f"line {number}",
                value=cell,
            )
        out.append(value)
    return np.array(out)


def read_load_curve(path: str | Path, display: str | None = None) -> LoadCurve:
    """A load curve CSV (module docstring)."""
    name = display or display_name(path)
    rows = _read(Path(path), name, "load curve")
    header = rows[0][1]
    cols = _columns(header, name)
    speed_key = next((k for k in cols if k.startswith("speed") or k in ("n", "rpm")), None)
    if speed_key is None:
        raise InputError(
            "expected a speed column, e.g. speed_rpm",
            file=name,
            key="header",
            value=",".join(header),
        )
    kinds = {"peak_pressure": "pressure", "imep": "pressure", "load_factor": "ratio"}
    value_key = next((k for k in kinds if k in cols), None)
    if value_key is None:
        raise InputError(
            "expected a column peak_pressure, imep or load_factor",
            file=name,
            key="header",
            value=",".join(header),
        )
    i_s, unit_s = cols[speed_key]
    i_v, unit_v = cols[value_key]
    speed = _numbers(rows[1:], i_s, header[i_s], name) * _factor(unit_s, "speed", header[i_s], name)
    value = _numbers(rows[1:], i_v, header[i_v], name) * _factor(
        unit_v, kinds[value_key], header[i_v], name
    )
    order = np.argsort(speed, kind="stable")
    try:
        return LoadCurve(speed[order], value[order], value_key, name)
    except InputError as exc:
        raise exc.within(file=name) from None


def read_harmonic_table(path: str | Path, display: str | None = None) -> HarmonicTable:
    """A harmonic-coefficient table CSV (module docstring)."""
    name = display or display_name(path)
    rows = _read(Path(path), name, "harmonic table")
    header = rows[0][1]
    cols = _columns(header, name)
    for key in ("order", "imep", "amplitude"):
        if key not in cols:
            raise InputError(
                f"expected a column {key!r} (columns order, imep, amplitude and optionally phase)",
                file=name,
                key="header",
                value=",".join(header),
            )
    values = {}
    for key, kind in (("order", "ratio"), ("imep", "pressure"), ("amplitude", "pressure")):
        i, unit = cols[key]
        values[key] = _numbers(rows[1:], i, header[i], name) * _factor(unit, kind, header[i], name)
    phase = None
    if "phase" in cols:
        i, unit = cols["phase"]
        phase = _numbers(rows[1:], i, header[i], name) * _factor(unit, "angle", header[i], name)
    try:
        return HarmonicTable(values["order"], values["imep"], values["amplitude"], phase, name)
    except InputError as exc:
        raise exc.within(file=name) from None
