"""CSV tables for the forced torsional response: load curves, harmonic-coefficient tables and
the engine builder's harmonic torques of one cylinder.

Both are CSV files with a header that names every column and its unit (as pressure traces do:
``speed_rpm``, ``peak_pressure [MPa]``, ``phase (deg)``), lines starting with ``#`` are comments.

- Load curve: a speed column and one of ``peak_pressure`` (a pressure), ``imep`` (a pressure) or
  ``load_factor`` (no unit), e.g. ``speed_rpm,peak_pressure_MPa``.
- Harmonic table: ``order`` (no unit), ``imep`` and ``amplitude`` (pressures) and optionally
  ``phase`` (an angle): one row per order and mean indicated pressure.
- Cylinder harmonics (a model file without an engine, ``[excitation] cylinder_harmonics``):
  ``order`` (no unit), optionally a speed column, and for a firing cylinder either
  ``normal_sin`` and ``normal_cos`` (torques) or ``normal_amplitude`` (a torque) and
  ``normal_phase`` (an angle), for a misfiring cylinder the same with ``misfire_``:
  :func:`read_cylinder_harmonics`.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError
from crankdyn.io.csv_tables import CsvTable, read_csv_table, split_header_unit, unit_factor
from crankdyn.torsion.excitation_spec import CylinderHarmonics, HarmonicTable, LoadCurve

__all__ = ["read_cylinder_harmonics", "read_harmonic_table", "read_load_curve"]

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


def _complex_column(
    table: CsvTable, cols: dict[str, tuple[int, str | None]], prefix: str
) -> NDArray[np.complex128] | None:
    """The complex coefficients c = b - i a (N m) of ``<prefix>_sin`` (a) and ``<prefix>_cos``
    (b), or T exp(i (psi - pi/2)) of ``<prefix>_amplitude`` (T) and ``<prefix>_phase`` (psi);
    None when neither pair is there."""
    name, header = table.name, table.header
    pairs = ((f"{prefix}_sin", "torque"), (f"{prefix}_cos", "torque"))
    polar = ((f"{prefix}_amplitude", "torque"), (f"{prefix}_phase", "angle"))
    found = [pair for pair in (pairs, polar) if any(key in cols for key, _ in pair)]
    if not found:
        return None
    if len(found) == 2:
        raise InputError(
            f"give {prefix}_sin and {prefix}_cos, or {prefix}_amplitude and {prefix}_phase, "
            "not both",
            file=name,
            key="header",
            value=",".join(header),
        )
    values = []
    for key, kind in found[0]:
        if key not in cols:
            raise InputError(
                f"expected a column {key!r} with {found[0][0][0]!r}",
                file=name,
                key="header",
                value=",".join(header),
            )
        i, unit = cols[key]
        values.append(table.column(i, _factor(unit, kind, header[i], name), kind=kind))
    first, second = values
    if found[0] is pairs:
        return second - 1j * first
    if np.any(first < 0.0):
        raise InputError("amplitudes must not be negative", file=name, key=f"{prefix}_amplitude")
    return first * np.exp(1j * (second - np.pi / 2.0))


def read_cylinder_harmonics(path: str | Path, display: str | None = None) -> CylinderHarmonics:
    """The engine builder's harmonic torques of one cylinder per order, firing and misfiring
    (module docstring; :class:`~crankdyn.torsion.excitation_spec.CylinderHarmonics`).

    Format: ``order`` (no unit); optionally a speed column (``speed_rpm``), every order at every
    speed; ``normal_sin`` and ``normal_cos`` (torques, e.g. ``normal_sin_kN*m``: the cylinder's
    torque a sin(q theta) + b cos(q theta), theta its crank angle from its firing TDC) or
    ``normal_amplitude`` and ``normal_phase`` (T sin(q theta + psi)); optionally the same
    with ``misfire_`` for the misfiring cylinder. Lines starting with ``#`` are comments.

    Parameters
    ----------
    path
        The CSV file.
    display
        How to name the file in messages (default: the path as given).

    Returns
    -------
    CylinderHarmonics
        Orders, speeds (rad/s, or None), the firing and misfiring cylinder's complex
        coefficients (N m).

    Raises
    ------
    InputError
        On an unreadable or empty file, a missing column, a missing or unknown unit, a
        non-numeric or out-of-range cell, both forms of one cylinder's coefficients, an order
        missing at a speed or given twice; naming the file, the line or ``header`` (``key``)
        and the cell.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "h.csv").write_text(
    ...     "order,normal_amplitude_kN*m,normal_phase_deg,misfire_sin_kN*m,misfire_cos_kN*m\\n"
    ...     "0.5,2.0,90,0.5,0.0\\n1.0,3.0,0,0.0,1.0\\n")
    >>> table = read_cylinder_harmonics(folder / "h.csv")
    >>> np.round(table.normal, 6).tolist(), np.round(table.misfire, 6).tolist()
    ([[(2000+0j), -3000j]], [[-500j, (1000+0j)]])
    """
    table = _table(path, display, "cylinder harmonics")
    name, header = table.name, table.header
    cols = _columns(header, name)
    if "order" not in cols:
        raise InputError(
            "expected a column 'order' (and normal_sin, normal_cos or normal_amplitude, "
            "normal_phase; optionally a speed and misfire_...)",
            file=name,
            key="header",
            value=",".join(header),
        )
    i, unit = cols["order"]
    order = table.column(i, _factor(unit, "ratio", header[i], name))
    normal = _complex_column(table, cols, "normal")
    if normal is None:
        raise InputError(
            "expected columns normal_sin and normal_cos, or normal_amplitude and normal_phase",
            file=name,
            key="header",
            value=",".join(header),
        )
    misfire = _complex_column(table, cols, "misfire")
    speed_key = next((k for k in cols if k.startswith("speed") or k in ("n", "rpm")), None)
    if speed_key is None:
        speeds = None
        grid_order, rows = order, np.zeros(order.size, dtype=int)
    else:
        i, unit = cols[speed_key]
        speed = table.column(i, _factor(unit, "speed", header[i], name), kind="speed")
        speeds = np.unique(speed)
        rows = np.searchsorted(speeds, speed)
        grid_order = np.unique(order)
    orders = np.unique(grid_order)
    count = 1 if speeds is None else speeds.size
    if orders.size * count != order.size:
        raise InputError(
            f"expected every order at every speed: {orders.size} orders x {count} speed(s) = "
            f"{orders.size * count} rows, found {order.size}",
            file=name,
        )
    k = np.searchsorted(orders, order)
    taken = np.zeros((count, orders.size), dtype=bool)
    taken[rows, k] = True
    if not np.all(taken):
        raise InputError("an order appears twice at one speed", file=name, key="order")
    grids: list[NDArray[np.complex128] | None] = []
    for values in (normal, misfire):
        if values is None:
            grids.append(None)
            continue
        grid = np.zeros((count, orders.size), dtype=complex)
        grid[rows, k] = values
        grids.append(grid)
    try:
        assert grids[0] is not None  # the normal coefficients are required (above)
        return CylinderHarmonics(orders, grids[0], grids[1], speeds, name)
    except InputError as exc:
        raise exc.within(file=name) from None
