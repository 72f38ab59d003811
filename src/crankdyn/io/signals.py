"""Reading torsiograph signals: pulse times or sampled speeds from CSV or NumPy files, or a
built-in example (docs/measurement.md).

CSV (unit-annotated, :mod:`crankdyn.io.csv_tables`): a ``time`` column with its unit
(``time [s]``, ``time_ms``) holds the pulse times, one per tooth; with a ``speed`` column
(``speed [rpm]``) the file is a sampled speed signal instead, ``time`` then holding the sample
times. An optional ``reference`` column (a time unit) holds the times of the once-per-revolution
or once-per-cycle mark; it is shorter than the others, its cells blank after the last mark.

NumPy (SI, no units to name): ``.npy`` with one column of pulse times (s), or two columns of
sample times (s) and speeds (rad/s); ``.npz`` with arrays ``time`` (s), optionally ``speed``
(rad/s) and ``reference`` (s).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError, did_you_mean
from crankdyn.io.csv_tables import CsvTable, read_csv_table, split_header_unit, unit_factor
from crankdyn.io.files import display_name, read_numpy
from crankdyn.io.units import SI_RANGE, check_si_range
from crankdyn.measure.signals import PulseTrain, SpeedSignal
from crankdyn.measure.torque import TorqueRecord

__all__ = ["COLUMNS", "TORQUE_COLUMNS", "read_signal", "read_torque_record", "resolve_signal"]

COLUMNS = {"time": "time", "speed": "speed", "reference": "time"}
"""The columns a signal file may hold, with the kind of quantity of each."""


def resolve_signal(spec: str, teeth: int | None) -> PulseTrain | SpeedSignal:
    """A SIGNAL argument: a CSV/NumPy file, or the name of a built-in example signal.

    Parameters
    ----------
    spec
        File path or built-in name.
    teeth
        Pulses per revolution (required for pulse times; for a speed signal the angle samples
        per revolution of the resampling, or None for the default).

    Returns
    -------
    PulseTrain or SpeedSignal
        The pulse times (s) of a toothed wheel, or sampled speeds (rad/s) at sample times (s).

    Raises
    ------
    InputError
        For a name that is neither a file nor a built-in signal (``key="SIGNAL"``), a
        ``teeth`` other than the built-in signal's (``key="--teeth"``), or any error of
        :func:`read_signal`.
    """
    from crankdyn.measure.examples import EXAMPLES, TEETH, example_signal

    path = Path(spec)
    if spec in EXAMPLES and not path.exists():
        if teeth is not None and teeth != TEETH:
            raise InputError(
                f"the built-in signal was measured with {TEETH} teeth", key="--teeth", value=teeth
            )
        return example_signal(spec)
    if not path.exists() and path.suffix.lower() not in (".csv", ".npy", ".npz", ".txt"):
        raise InputError(
            "no such signal file, and no built-in signal of that name"
            f"{did_you_mean(spec, EXAMPLES)} (built-in: {', '.join(EXAMPLES)})",
            key="SIGNAL",
            value=spec,
        )
    return read_signal(path, teeth)


def read_signal(path: str | Path, teeth: int | None) -> PulseTrain | SpeedSignal:
    """Read a signal file (module docstring) as a PulseTrain (needs ``teeth``) or a
    SpeedSignal.

    Parameters
    ----------
    path
        A CSV file (unit-annotated header), a ``.npy`` or a ``.npz`` file (SI).
    teeth
        Pulses per revolution of the wheel (needed for pulse times; for a speed signal the
        angle samples per revolution of the resampling, or None for the default).

    Returns
    -------
    PulseTrain or SpeedSignal
        Pulse times (s) with their reference marks (s), or sampled speeds (rad/s) at their
        sample times (s).

    Raises
    ------
    InputError
        On an unreadable or malformed file, an unknown column or array, a missing unit,
        non-numeric or out-of-range values, or pulse times without ``teeth``; naming the file,
        the line or array (``key``) and the value.
    """
    suffix = Path(path).suffix.lower()
    if suffix == ".npy":
        return _read_npy(path, teeth)
    if suffix == ".npz":
        return _read_npz(path, teeth)
    return _read_csv(path, teeth)


def _pulses(name: str, times: NDArray[np.float64], teeth: int | None, **kw: Any) -> PulseTrain:
    if teeth is None:
        raise InputError(
            "pulse times need --teeth N, the pulses per revolution of the wheel", file=name
        )
    return PulseTrain(times, teeth, source=name, **kw)


def _read_csv(path: str | Path, teeth: int | None) -> PulseTrain | SpeedSignal:
    name = display_name(path)
    table = read_csv_table(path, what="signal file")
    if table.header_is_numeric:
        raise InputError(
            "the first line must name the columns with their units, e.g. time [s] (pulse "
            "times) or time [s],speed [rpm] (a speed signal)",
            file=name,
            key=f"line {table.header_line}",
        )
    index: dict[str, tuple[int, float]] = {}
    for i, cell in enumerate(table.header):
        label, unit = split_header_unit(cell)
        key = label.strip().lower()
        if key not in COLUMNS:
            from crankdyn.errors import did_you_mean

            raise InputError(
                f"unknown column {label!r}{did_you_mean(key, COLUMNS)} (a signal file has "
                f"{', '.join(COLUMNS)})",
                file=name,
                key="header",
                value=cell,
            )
        if key in index:
            raise InputError(f"the column {key} appears twice", file=name, key="header", value=cell)
        kind = COLUMNS[key]
        example, quantity = (
            ("time [s]", "a time")
            if kind == "time"
            else (
                "speed [rpm]",
                "a rotational speed",
            )
        )
        factor = unit_factor(
            cell,
            unit,
            kind,
            name,
            missing=f"the column {key} needs a unit, e.g. {example}",
            unknown=f"the unit {{unit}} of the column {key} is not {quantity}",
        )
        index[key] = (i, factor)
    if "time" not in index:
        raise InputError(
            "the signal file needs a time column, e.g. time [s]", file=name, key="header"
        )
    if not table.rows:
        raise InputError("the signal file holds no data", file=name)
    lines = np.array([number for number, _ in table.rows])
    col, factor = index["time"]
    times = table.column(col, factor, kind="time")
    reference = reference_lines = None
    if "reference" in index:
        reference, reference_lines = _reference_column(table, *index["reference"])
    if "speed" in index:
        col_s, factor_s = index["speed"]
        speed = table.column(col_s, factor_s, kind="speed")
        return SpeedSignal(
            times,
            speed,
            reference=reference,
            source=name,
            lines=lines,
            reference_lines=reference_lines,
        )
    return _pulses(
        name, times, teeth, reference=reference, lines=lines, reference_lines=reference_lines
    )


def _reference_column(
    table: CsvTable, col: int, factor: float
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """The mark times of a reference column (s), shorter than the others (blank cells after
    the last mark), with their lines."""
    name = table.name
    values, lines = [], []
    for number, row in table.rows:
        cell = row[col].strip() if col < len(row) else ""
        if not cell:
            continue
        try:
            value = float(cell)
        except ValueError:
            value = math.nan
        if not math.isfinite(value):
            raise InputError(
                "not a finite number in column 'reference'",
                file=name,
                key=f"line {number}",
                value=cell,
            )
        if not check_si_range(value * factor):
            raise InputError(
                f"{value * factor:.3g} s in column 'reference' lies outside the range "
                "crankdyn computes with (1e-12 to 1e12 in SI units, or 0); check the unit",
                file=name,
                key=f"line {number}",
                value=cell,
            )
        values.append(value * factor)
        lines.append(number)
    return np.array(values), np.array(lines, dtype=np.int64)


TORQUE_COLUMNS = {"torque": "torque", "time": "time", "crank_angle": "angle", "reference": "time"}
"""The columns a torque record may hold, with the kind of quantity of each."""
_TORQUE_EXAMPLES = {
    "torque": "torque [N*m]",
    "time": "time [s]",
    "crank_angle": "crank_angle [deg]",
    "reference": "reference [s]",
}


def read_torque_record(path: str | Path, *, speed: float | None = None) -> TorqueRecord:
    """Read a measured shaft torque (strain gauges): CSV with a ``torque`` column (``torque
    [N*m]``) and either ``crank_angle`` (``crank_angle [deg]``, increasing over the cycles;
    optionally ``time``) or ``time`` with a ``reference`` column of the once-per-cycle mark's
    times (shorter, blank after the last mark); or a NumPy ``.npz`` archive of the same arrays
    in SI (docs/measurement.md).

    Parameters
    ----------
    path
        The file.
    speed
        The mean crank speed (rad/s) of an angle-domain record without times, or None.

    Returns
    -------
    crankdyn.measure.torque.TorqueRecord
        The torque (N m) over crank angle (rad) or time (s) with its marks (s).

    Raises
    ------
    InputError
        An unreadable file, an unknown column or unit, a missing torque column, a value that
        is not a number, or an inconsistent record; naming the file, the line and the cell.
    """
    name = display_name(path)
    if Path(path).suffix.lower() == ".npz":
        archive = read_numpy(path, names=TORQUE_COLUMNS, what="torque record")
        assert isinstance(archive, dict)  # an .npz archive: its named arrays
        if "torque" not in archive:
            raise InputError("the archive needs an array named torque (N m)", file=name)
        arrays = {k: _float_array(name, k, v) for k, v in archive.items()}
    else:
        arrays = _torque_csv(path, name)
    try:
        return TorqueRecord(
            arrays["torque"],
            crank_angle=arrays.get("crank_angle"),
            time=arrays.get("time"),
            reference=arrays.get("reference"),
            speed=speed,
            source=name,
        )
    except InputError as exc:
        raise exc.within(file=name) from None


def _torque_csv(path: str | Path, name: str) -> dict[str, NDArray[np.float64]]:
    """The columns of a torque record's CSV, in SI."""
    from crankdyn.errors import did_you_mean

    table = read_csv_table(path, what="torque record")
    if table.header_is_numeric:
        raise InputError(
            "the first line must name the columns with their units, e.g. "
            "crank_angle [deg],torque [N*m] or time [s],torque [N*m],reference [s]",
            file=name,
            key=f"line {table.header_line}",
        )
    index: dict[str, tuple[int, float]] = {}
    for i, cell in enumerate(table.header):
        label, unit = split_header_unit(cell)
        key = label.strip().lower().replace(" ", "_")
        if key not in TORQUE_COLUMNS:
            raise InputError(
                f"unknown column {label!r}{did_you_mean(key, TORQUE_COLUMNS)} (a torque record "
                f"has {', '.join(TORQUE_COLUMNS)})",
                file=name,
                key="header",
                value=cell,
            )
        if key in index:
            raise InputError(f"the column {key} appears twice", file=name, key="header", value=cell)
        factor = unit_factor(
            cell,
            unit,
            TORQUE_COLUMNS[key],
            name,
            missing=f"the column {key} needs a unit, e.g. {_TORQUE_EXAMPLES[key]}",
            unknown=f"the unit {{unit}} of the column {key} is not a {TORQUE_COLUMNS[key]}",
        )
        index[key] = (i, factor)
    if "torque" not in index:
        raise InputError("a torque record needs a torque column, e.g. torque [N*m]", file=name)
    if not table.rows:
        raise InputError("the torque record holds no data", file=name)
    out = {}
    for key, (col, factor) in index.items():
        if key == "reference":
            out[key] = _reference_column(table, col, factor)[0]
        else:
            out[key] = table.column(col, factor, kind=TORQUE_COLUMNS[key])
    return out


def _float_array(name: str, key: str, value: Any) -> NDArray[np.float64]:
    """An array of numbers in SI units: each finite and within the range every quantity must
    lie in (1e-12 to 1e12, or 0; :func:`crankdyn.io.units.check_si_range`)."""
    arr = np.asarray(value)
    if arr.dtype.kind not in "fiu":
        raise InputError("expected numbers", file=name, key=key, value=str(arr.dtype))
    arr = arr.astype(float)
    magnitude = np.abs(arr)
    bad = ~np.isfinite(arr) | (
        (magnitude != 0.0) & ((magnitude < SI_RANGE[0]) | (magnitude > SI_RANGE[1]))
    )
    if np.any(bad):
        k = int(np.flatnonzero(bad.ravel())[0])
        raise InputError(
            "not a finite number within the range crankdyn computes with (1e-12 to 1e12 in SI "
            f"units, or 0) at index {k}",
            file=name,
            key=key,
            value=float(arr.ravel()[k]),
        )
    return arr


def _read_npy(path: str | Path, teeth: int | None) -> PulseTrain | SpeedSignal:
    name = display_name(path)
    data = _float_array(name, "array", read_numpy(path))
    if data.ndim == 1:
        return _pulses(name, data, teeth)
    if data.ndim == 2 and data.shape[1] == 2:
        return SpeedSignal(data[:, 0], data[:, 1], source=name)
    raise InputError(
        "expected one column of pulse times (s) or two columns of times (s) and speeds (rad/s)",
        file=name,
        key="shape",
        value=list(data.shape),
    )


def _read_npz(path: str | Path, teeth: int | None) -> PulseTrain | SpeedSignal:
    name = display_name(path)
    archive = read_numpy(path, names=COLUMNS)  # every size checked before it is read
    assert isinstance(archive, dict)  # an .npz archive (type checker)
    if "time" not in archive:
        raise InputError("the archive needs an array named time (s)", file=name)
    arrays = {k: _float_array(name, k, value) for k, value in archive.items()}
    reference = arrays.get("reference")
    if "speed" in arrays:
        return SpeedSignal(arrays["time"], arrays["speed"], reference=reference, source=name)
    return _pulses(name, arrays["time"], teeth, reference=reference)
