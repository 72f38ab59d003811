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

Pulse records of any length are read in chunks (:func:`open_signal`: a
:class:`~crankdyn.measure.records.PulseRecord`; CSV by :mod:`crankdyn.io.csv_chunks`, NumPy
files :data:`CHUNK_VALUES` values at a time, their headers checked before anything is read);
a sampled speed signal is read whole, at most :data:`MAX_SPEED_SAMPLES` samples.
"""

from __future__ import annotations

import contextlib
import os
import zipfile
from collections.abc import Iterator
from pathlib import Path
from typing import IO, Any

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError, did_you_mean
from crankdyn.io.csv_chunks import CsvBlock, CsvHeader, csv_blocks, csv_header, sparse_column
from crankdyn.io.csv_tables import is_number, read_csv_table, split_header_unit, unit_factor
from crankdyn.io.files import (
    MAX_ARRAY_BYTES,
    MAX_ARRAY_VALUES,
    NPY_HEADER,
    check_npy_data,
    display_name,
    npy_array,
    npy_header,
    open_regular,
    read_numpy,
)
from crankdyn.io.units import SI_RANGE
from crankdyn.measure.records import PulseChunk, PulseRecord
from crankdyn.measure.signals import PulseTrain, SpeedSignal
from crankdyn.measure.torque import TorqueRecord

__all__ = [
    "CHUNK_VALUES",
    "COLUMNS",
    "MAX_SPEED_SAMPLES",
    "TORQUE_COLUMNS",
    "open_signal",
    "read_signal",
    "read_torque_record",
    "resolve_signal",
]

CHUNK_VALUES = 1 << 18
"""Values read at a time from a NumPy signal file (2 MiB of float64)."""
MAX_SPEED_SAMPLES = MAX_ARRAY_VALUES
"""The most samples of a sampled speed signal (4,194,304), which is read and resampled whole
(:meth:`crankdyn.measure.signals.SpeedSignal.to_pulses`)."""

SAMPLE_BYTES = 1 << 16
"""Bytes of a text signal file read to estimate its number of lines."""

COLUMNS = {"time": "time", "speed": "speed", "reference": "time"}
"""The columns a signal file may hold, with the kind of quantity of each."""


def resolve_signal(spec: str, teeth: int | None) -> PulseTrain | PulseRecord | SpeedSignal:
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
    PulseTrain, PulseRecord or SpeedSignal
        The pulse times (s) of a toothed wheel (a built-in signal's in memory, a file's read in
        chunks: :func:`open_signal`), or sampled speeds (rad/s) at sample times (s).

    Raises
    ------
    InputError
        For a name that is neither a file nor a built-in signal (``key="SIGNAL"``), a
        ``teeth`` other than the built-in signal's (``key="--teeth"``), or any error of
        :func:`open_signal`.
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
    return open_signal(path, teeth)


def open_signal(path: str | Path, teeth: int | None) -> PulseRecord | SpeedSignal:
    """Open a signal file (module docstring): pulse times as a record read in chunks (needs
    ``teeth``; any length, never held whole), a sampled speed signal read whole.

    Parameters
    ----------
    path
        A CSV file (unit-annotated header), a ``.npy`` or a ``.npz`` file (SI).
    teeth
        Pulses per revolution of the wheel (needed for pulse times; for a speed signal the
        angle samples per revolution of the resampling, or None for the default).

    Returns
    -------
    PulseRecord or SpeedSignal
        The pulse times (s) with their reference marks (s), read as the record is read; or
        sampled speeds (rad/s) at their sample times (s).

    Raises
    ------
    InputError
        On an unreadable or malformed file or header, an unknown column or array, a missing
        unit, pulse times without ``teeth`` or a speed signal of more than
        :data:`MAX_SPEED_SAMPLES` samples (here); on non-numeric or out-of-range values and
        times that do not increase when the record is read; naming the file, the line or
        array (``key``) and the value.
    """
    suffix = Path(path).suffix.lower()
    if suffix == ".npy":
        return _open_npy(path, teeth)
    if suffix == ".npz":
        return _open_npz(path, teeth)
    return _open_csv(path, teeth)


def read_signal(path: str | Path, teeth: int | None) -> PulseTrain | SpeedSignal:
    """Read a signal file (module docstring) whole, as a PulseTrain (needs ``teeth``) or a
    SpeedSignal (:func:`open_signal` reads a long record in chunks instead).

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
    signal = open_signal(path, teeth)
    return signal.train() if isinstance(signal, PulseRecord) else signal


def _need_teeth(name: str, teeth: int | None) -> int:
    if teeth is None:
        raise InputError(
            "pulse times need --teeth N, the pulses per revolution of the wheel", file=name
        )
    return teeth


def _pulses(name: str, times: NDArray[np.float64], teeth: int | None, **kw: Any) -> PulseTrain:
    return PulseTrain(times, _need_teeth(name, teeth), source=name, **kw)


# ---- CSV ----------------------------------------------------------------------------------------


def _csv_columns(header: CsvHeader) -> dict[str, tuple[int, float]]:
    """{column: (index, SI factor)} of a signal file's header, each column checked."""
    name = header.name
    if is_number(header.cells[0]):
        raise InputError(
            "the first line must name the columns with their units, e.g. time [s] (pulse "
            "times) or time [s],speed [rpm] (a speed signal)",
            file=name,
            key=f"line {header.line}",
        )
    index: dict[str, tuple[int, float]] = {}
    for i, cell in enumerate(header.cells):
        label, unit = split_header_unit(cell)
        key = label.strip().lower()
        if key not in COLUMNS:
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
            ("time [s]", "a time") if kind == "time" else ("speed [rpm]", "a rotational speed")
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
    return index


def _open_csv(path: str | Path, teeth: int | None) -> PulseRecord | SpeedSignal:
    name = display_name(path)
    header = csv_header(path, name, "signal file")
    if header is None:
        raise InputError("the signal file is empty", file=name)
    index = _csv_columns(header)
    dense = {index["time"][0]: (index["time"][1], "time")}
    if "speed" in index:
        dense[index["speed"][0]] = (index["speed"][1], "speed")
    sparse = {index["reference"][0]: index["reference"][1]} if "reference" in index else {}

    def blocks() -> Iterator[CsvBlock]:
        rows = 0
        for block in csv_blocks(path, header, dense, sparse, "signal file"):
            rows += block.lines.size
            yield block
        if not rows:
            raise InputError("the signal file holds no data", file=name)

    if "speed" in index:
        return _speed_csv(name, blocks(), index)
    time_col = index["time"][0]
    ref_col = index["reference"][0] if "reference" in index else None

    def read() -> Iterator[PulseChunk]:
        for block in blocks():
            marks = mark_lines = None
            if ref_col is not None and block.sparse[ref_col][0].size:
                marks, mark_lines = block.sparse[ref_col]
            if block.lines.size or marks is not None:
                yield PulseChunk(block.values[time_col], block.lines, marks, mark_lines)

    return PulseRecord(read, _need_teeth(name, teeth), name, _expected_lines(path))


def _expected_lines(path: str | Path) -> int:
    """The lines a text file is expected to hold: its size over the mean length of the lines in
    its first :data:`SAMPLE_BYTES` (exact for a shorter file); an estimate that decides only
    whether a reading is kept in memory (:meth:`PulseRecord.cached`)."""
    with open_regular(path, what="signal file") as handle:
        size = os.fstat(handle.fileno()).st_size
        sample = handle.read(SAMPLE_BYTES)
    lines = sample.count(b"\n")
    if len(sample) >= size or not lines:
        return lines
    return int(size * lines / len(sample))


def _speed_csv(
    name: str, blocks: Iterator[CsvBlock], index: dict[str, tuple[int, float]]
) -> SpeedSignal:
    """A sampled speed signal read whole (at most :data:`MAX_SPEED_SAMPLES` samples)."""
    t_col, s_col = index["time"][0], index["speed"][0]
    ref_col = index["reference"][0] if "reference" in index else None
    times, speed, lines, marks, mark_lines = [], [], [], [], []
    count = 0
    for block in blocks:
        count += block.lines.size
        if count > MAX_SPEED_SAMPLES:
            raise _too_many_samples(name)
        times.append(block.values[t_col])
        speed.append(block.values[s_col])
        lines.append(block.lines)
        if ref_col is not None:
            marks.append(block.sparse[ref_col][0])
            mark_lines.append(block.sparse[ref_col][1])
    return SpeedSignal(
        np.concatenate(times),
        np.concatenate(speed),
        reference=np.concatenate(marks) if ref_col is not None else None,
        source=name,
        lines=np.concatenate(lines),
        reference_lines=np.concatenate(mark_lines) if ref_col is not None else None,
    )


def _too_many_samples(name: str) -> InputError:
    return InputError(
        f"a sampled speed signal holds at most {MAX_SPEED_SAMPLES:,} samples (crankdyn "
        "resamples it whole; a pulse record may be of any length)",
        file=name,
    )


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
            out[key] = sparse_column(table, col, factor)[0]
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


def _checked(name: str, key: str, raw: NDArray[Any], offset: int) -> NDArray[np.float64]:
    """Values read from a NumPy file as numbers in SI units (:func:`_float_array`); ``offset``
    is the array's index of ``raw[0]``, for the message."""
    arr = raw.astype(float)
    magnitude = np.abs(arr)
    bad = ~np.isfinite(arr) | (
        (magnitude != 0.0) & ((magnitude < SI_RANGE[0]) | (magnitude > SI_RANGE[1]))
    )
    if np.any(bad):
        k = int(np.flatnonzero(bad)[0])
        raise InputError(
            "not a finite number within the range crankdyn computes with (1e-12 to 1e12 in SI "
            f"units, or 0) at index {offset + k}",
            file=name,
            key=key,
            value=float(arr[k]),
        )
    return arr


def _values(
    handle: IO[bytes], dtype: np.dtype, count: int, name: str, key: str
) -> Iterator[NDArray[np.float64]]:
    """The ``count`` values after a NumPy header, :data:`CHUNK_VALUES` at a time, checked."""
    done = 0
    while done < count:
        n = min(CHUNK_VALUES, count - done)
        data = handle.read(n * dtype.itemsize)
        if len(data) < n * dtype.itemsize:
            raise InputError(
                f"the file ends after {done + len(data) // dtype.itemsize:,} of the {count:,} "
                "values its header claims (truncated?)",
                file=name,
                key=key,
            )
        yield _checked(name, key, np.frombuffer(data, dtype=dtype), done)
        done += n


def _open_npy(path: str | Path, teeth: int | None) -> PulseRecord | SpeedSignal:
    name = display_name(path)
    with open_regular(path, what="signal file") as handle:
        shape, _, dtype = npy_header(handle, name, "array")
        start = handle.tell()
        held = os.fstat(handle.fileno()).st_size - start
    if len(shape) != 1:  # a speed signal (or a wrong shape): read whole, bounded
        return _whole(_read_npy(path, teeth))
    count = check_npy_data(shape, dtype, held, name, "array")

    def read() -> Iterator[PulseChunk]:
        with open_regular(path, what="signal file") as handle:
            handle.seek(start)
            for times in _values(handle, dtype, count, name, "array"):
                yield PulseChunk(times)

    return PulseRecord(read, _need_teeth(name, teeth), name, count)


def _open_npz(path: str | Path, teeth: int | None) -> PulseRecord | SpeedSignal:
    """A ``.npz`` of pulse times: its ``time`` array read in chunks, its ``reference`` whole
    (each header checked before anything is read); a speed signal read whole."""
    name = display_name(path)
    with _archive(path, name) as archive:
        members = {info.filename.removesuffix(".npy"): info for info in archive.infolist()}
        for key in members:
            if key not in COLUMNS:
                raise InputError(
                    f"unknown array {key!r} (the archive may hold {', '.join(COLUMNS)})",
                    file=name,
                )
        if "time" not in members:
            raise InputError("the archive needs an array named time (s)", file=name)
        if "speed" in members:
            return _whole(_read_npz(path, teeth))
        with archive.open(members["time"]) as member:
            shape, _, dtype = npy_header(member, name, "time")
            held = members["time"].file_size - member.tell()
        if len(shape) != 1:
            return _whole(_read_npz(path, teeth))  # (its message)
        count = check_npy_data(shape, dtype, held, name, "time")
        reference = None
        if "reference" in members:
            info = members["reference"]
            if info.file_size > MAX_ARRAY_BYTES + NPY_HEADER:
                raise InputError(
                    f"the reference array unpacks to {info.file_size:,} bytes; crankdyn reads "
                    f"at most {MAX_ARRAY_BYTES >> 20} MiB of it",
                    file=name,
                    key="reference",
                )
            with archive.open(info) as member:
                raw = member.read(MAX_ARRAY_BYTES + NPY_HEADER + 1)
            reference = _float_array(name, "reference", npy_array(raw, name, "reference"))
    teeth = _need_teeth(name, teeth)

    def read() -> Iterator[PulseChunk]:
        with _archive(path, name) as archive, archive.open("time.npy") as member:
            npy_header(member, name, "time")
            marks = reference
            for times in _values(member, dtype, count, name, "time"):
                yield PulseChunk(times, reference=marks)
                marks = None

    return PulseRecord(read, teeth, name, count)


def _whole(signal: PulseTrain | SpeedSignal) -> PulseRecord | SpeedSignal:
    """A signal read whole, pulse times as a record (of one chunk)."""
    return PulseRecord.from_train(signal) if isinstance(signal, PulseTrain) else signal


@contextlib.contextmanager
def _archive(path: str | Path, name: str) -> Iterator[zipfile.ZipFile]:
    """An ``.npz`` archive open for reading; its errors one line naming the file."""
    import zlib

    with open_regular(path, what="signal file") as handle:
        try:
            with zipfile.ZipFile(handle) as archive:
                yield archive
        except InputError:
            raise
        except (zipfile.BadZipFile, zlib.error, OSError, EOFError, ValueError, KeyError,
                NotImplementedError, RuntimeError) as exc:  # fmt: skip
            detail = " ".join(str(exc).split())[:80]
            raise InputError(f"not a readable NumPy .npz file ({detail})", file=name) from None


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
