"""CSV tables for the forced torsional response: load curves and harmonic-coefficient tables.

Both are CSV files with a header that names every column and its unit (as pressure traces do:
``speed_rpm``, ``peak_pressure [MPa]``, ``phase (deg)``), lines starting with ``#`` are comments.

- Load curve: a speed column and one of ``peak_pressure`` (a pressure), ``imep`` (a pressure) or
  ``load_factor`` (no unit), e.g. ``speed_rpm,peak_pressure_MPa``.
- Harmonic table: ``order`` (no unit), ``imep`` and ``amplitude`` (pressures) and optionally
  ``phase`` (an angle): one row per order and mean indicated pressure.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError
from crankdyn.io.csv_tables import CsvTable, read_csv_table, split_header_unit, unit_factor
from crankdyn.torsion.excitation_spec import HarmonicTable, LoadCurve

__all__ = ["read_harmonic_table", "read_load_curve"]

_PLAIN = ("load_factor", "order")


def _columns(header: list[str], name: str) -> dict[str, tuple[int, str | None]]:
    out: dict[str, tuple[int, str | None]] = {}
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
    return unit_factor(
        cell,
        unit,
        kind,
        name,
        missing="the column must name its unit, e.g. speed_rpm or peak_pressure_MPa",
        unknown="unknown unit {unit}",
    )


def _table(path: str | Path, display: str | None, what: str) -> CsvTable:
    table = read_csv_table(
        path,
        display=display,
        what=what,
        empty=f"the {what} needs a header line and at least one row",
    )
    if not table.rows:
        raise InputError(f"the {what} needs a header line and at least one row", file=table.name)
    return table


def read_load_curve(path: str | Path, display: str | None = None) -> LoadCurve:
    """A load curve CSV (module docstring): the engine's load against speed.

    Format: a speed column (``speed_rpm``, ``speed [rad/s]``...) and one of ``peak_pressure``
    (a pressure), ``imep`` (a pressure) or ``load_factor`` (no unit); rows in any order.

    Parameters
    ----------
    path
        The CSV file.
    display
        How to name the file in messages (default: the path as given).

    Returns
    -------
    LoadCurve
        Speeds (rad/s, sorted) and the values (Pa for ``peak_pressure`` and ``imep``, a bare
        factor for ``load_factor``), with the column's name and the file as its source.

    Raises
    ------
    InputError
        On an unreadable or empty file, a missing speed or value column, a missing or unknown
        unit (or a unit on ``load_factor``), a non-numeric or out-of-range cell, or a curve
        the LoadCurve refuses (repeated speeds, negative values); naming the file, the line
        or ``header`` (``key``) and the cell.
    """
    table = _table(path, display, "load curve")
    name, header = table.name, table.header
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
    speed = table.column(i_s, _factor(unit_s, "speed", header[i_s], name), kind="speed")
    value = table.column(
        i_v, _factor(unit_v, kinds[value_key], header[i_v], name), kind=kinds[value_key]
    )
    order = np.argsort(speed, kind="stable")
    try:
        return LoadCurve(speed[order], value[order], value_key, name)
    except InputError as exc:
        raise exc.within(file=name) from None


def read_harmonic_table(path: str | Path, display: str | None = None) -> HarmonicTable:
    """A harmonic-coefficient table CSV (module docstring): the tangential-pressure harmonics
    of a cylinder against its mean indicated pressure.

    Format: columns ``order`` (no unit), ``imep`` and ``amplitude`` (pressures, e.g.
    ``imep_bar``) and optionally ``phase`` (an angle); one row per order and imep.

    Parameters
    ----------
    path
        The CSV file.
    display
        How to name the file in messages (default: the path as given).

    Returns
    -------
    HarmonicTable
        Orders (of the crank speed), imep (Pa), amplitudes (Pa) and phases (rad, or None).

    Raises
    ------
    InputError
        On an unreadable or empty file, a missing column, a missing or unknown unit, a
        non-numeric or out-of-range cell, or a table the HarmonicTable refuses; naming the
        file, the line or ``header`` (``key``) and the cell.
    """
    table = _table(path, display, "harmonic table")
    name, header = table.name, table.header
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
        values[key] = table.column(i, _factor(unit, kind, header[i], name), kind=kind)
    phase = None
    if "phase" in cols:
        i, unit = cols["phase"]
        phase = table.column(i, _factor(unit, "angle", header[i], name), kind="angle")
    try:
        return HarmonicTable(values["order"], values["imep"], values["amplitude"], phase, name)
    except InputError as exc:
        raise exc.within(file=name) from None


def read_source_table(
    path: str | Path, display: str | None = None
) -> tuple[
    NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], NDArray[np.float64] | None
]:
    """An excitation source's harmonics against speed (docs/torsion-file.md): columns ``order``
    (of the mass's speed, no unit), ``speed`` (e.g. ``speed_rpm``), ``amplitude`` (a torque,
    e.g. ``amplitude [kN*m]``) and optionally ``phase`` (an angle); one row per order and speed,
    every order at every speed. Returns (orders (K,), speeds (T,) rad/s, amplitudes (T, K) N m,
    phases (T, K) rad or None)."""
    table = _table(path, display, "source table")
    name, header = table.name, table.header
    cols = _columns(header, name)
    speed_key = next((k for k in cols if k.startswith("speed") or k in ("n", "rpm")), None)
    for key, present in (
        ("order", "order" in cols),
        ("speed", speed_key),
        ("amplitude", "amplitude" in cols),
    ):
        if not present:
            raise InputError(
                f"expected a column {key!r} (columns order, speed, amplitude and optionally phase)",
                file=name,
                key="header",
                value=",".join(header),
            )
    i, unit = cols["order"]
    order = table.column(i) * _factor(unit, "ratio", header[i], name)
    assert speed_key is not None  # checked above; for the type checker
    i, unit = cols[speed_key]
    speed = table.column(i) * _factor(unit, "speed", header[i], name)
    i, unit = cols["amplitude"]
    amplitude = table.column(i) * _factor(unit, "torque", header[i], name)
    phase = None
    if "phase" in cols:
        i, unit = cols["phase"]
        phase = table.column(i) * _factor(unit, "angle", header[i], name)
    if not (np.all(np.isfinite(order)) and np.all(order > 0.0)):
        raise InputError("orders must be positive", file=name, key="order")
    if not np.all(speed > 0.0):
        raise InputError("speeds must be positive", file=name, key="speed")
    if np.any(amplitude < 0.0):
        raise InputError("amplitudes must not be negative", file=name, key="amplitude")
    orders = np.unique(order)
    speeds = np.unique(speed)
    if orders.size * speeds.size != order.size:
        raise InputError(
            f"expected every order at every speed: {orders.size} orders x {speeds.size} speeds "
            f"= {orders.size * speeds.size} rows, found {order.size}",
            file=name,
        )
    k = np.searchsorted(orders, order)
    s = np.searchsorted(speeds, speed)
    grid = np.full((speeds.size, orders.size), np.nan)
    grid[s, k] = amplitude
    if np.any(np.isnan(grid)):
        raise InputError("an order appears twice at one speed", file=name)
    phases = None
    if phase is not None:
        phases = np.zeros_like(grid)
        phases[s, k] = phase
    return orders, speeds, grid, phases
