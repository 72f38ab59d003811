"""Torque-time histories for transient events (CSV).

A history is a CSV file (the conventions of :mod:`crankdyn.io.csv_tables`) with a time column
and a torque column, their units in the header: ``time_s,torque_kN*m``,
``t [ms], torque [N*m]``; lines starting with ``#`` are comments. The times must increase; the
torque acts on a mass in its own sense of rotation (positive drives it)
(:class:`crankdyn.torsion.events.TabulatedTorque`).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError
from crankdyn.io.csv_tables import read_csv_table, split_header_unit, unit_factor

__all__ = ["read_torque_history"]

_TIME = ("time", "t")
_TORQUE = ("torque", "t_q", "q", "moment")


def read_torque_history(
    path: str | Path, display: str | None = None
) -> tuple[NDArray[np.float64], NDArray[np.float64], str]:
    """A torque-time history CSV (module docstring).

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file.
    display : str or None
        How to name the file in messages (default: the path as given).

    Returns
    -------
    time : numpy.ndarray
        (P,) times (s), increasing.
    torque : numpy.ndarray
        (P,) torques (N m).
    name : str
        The file as named in messages.

    Raises
    ------
    InputError
        An unreadable or empty file, a missing time or torque column, a missing or unknown
        unit, a cell that is not a number, fewer than two rows, or times that do not
        increase; naming the file, the line (or ``header``) and the cell.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "kick.csv").write_text("time_ms,torque_kN*m\\n0,0\\n5,-12\\n10,0\\n")
    >>> t, q, _name = read_torque_history(folder / "kick.csv")
    >>> t.tolist(), q.tolist()
    ([0.0, 0.005, 0.01], [0.0, -12000.0, 0.0])
    """
    what = "torque history"
    table = read_csv_table(
        path, display=display, what=what, empty=f"the {what} needs a header and two rows"
    )
    name, header = table.name, table.header
    columns: dict[str, tuple[int, str | None]] = {}
    for i, cell in enumerate(header):
        base, unit = split_header_unit(cell)
        key = base.strip().lower()
        if key in _TIME and "time" not in columns:
            columns["time"] = (i, unit)
        elif key in _TORQUE and "torque" not in columns:
            columns["torque"] = (i, unit)
    for key, example in (("time", "time_s"), ("torque", "torque_N*m")):
        if key not in columns:
            raise InputError(
                f"expected a {key} column, e.g. {example}",
                file=name,
                key="header",
                value=",".join(header),
            )
    if len(table.rows) < 2:
        raise InputError(f"the {what} needs at least two rows", file=name)
    out = []
    for key, kind in (("time", "time"), ("torque", "torque")):
        i, unit = columns[key]
        factor = unit_factor(
            header[i],
            unit,
            kind,
            name,
            missing=f"the {key} column must name its unit, e.g. time_s or torque_kN*m",
            unknown=f"unknown {kind} unit {{unit}}",
        )
        out.append(table.column(i, factor, kind=kind))
    time, torque = out
    steps = np.diff(time)
    if np.any(steps <= 0.0) or time[0] < 0.0:
        k = int(np.flatnonzero(steps <= 0.0)[0]) + 1 if np.any(steps <= 0.0) else 0
        line, cell = table.cell(k, columns["time"][0])
        raise InputError(
            "the times must increase from 0 or later", file=name, key=f"line {line}", value=cell
        )
    return time, torque, name
