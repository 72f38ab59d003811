"""Unit-annotated CSV tables of any length, read in chunks of lines at C speed (the long records
of a torsiograph): the same rows, values, checks and messages as
:func:`crankdyn.io.csv_tables.read_csv_table`, in memory bounded by a chunk.

The file is read :data:`CHUNK_BYTES` at a time, cut after its last line break. A chunk of plain
lines (ASCII numbers, commas, comment and blank lines; no quotes, no line breaks other than
``\\n`` and ``\\r\\n``) is parsed by :func:`numpy.loadtxt`'s C reader (correctly rounded, as
:class:`float`), its comment and blank lines found with array operations on the bytes; any
other chunk, and any chunk whose values fail a check, is read line by line as
:func:`~crankdyn.io.csv_tables.read_csv_table` reads a table
(:func:`~crankdyn.io.csv_tables.csv_rows`), which gives the message naming the line and the
cell. Both read the same numbers: every value checked as
:func:`~crankdyn.io.csv_tables.cell_value` checks it (a finite number whose SI value lies in
:data:`crankdyn.io.units.SI_RANGE`, or 0).

A *sparse* column (a signal's ``reference`` column: the marks' times on the first lines, blank
after) gives its non-blank cells only, with their lines.
"""

from __future__ import annotations

import io
import math
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError
from crankdyn.io.csv_tables import CsvTable, check_row_widths, csv_rows
from crankdyn.io.files import open_regular
from crankdyn.io.units import SI_RANGE, check_si_range

__all__ = ["CHUNK_BYTES", "MAX_LINE_BYTES", "CsvBlock", "CsvHeader", "csv_blocks", "csv_header"]

CHUNK_BYTES = 1 << 22
"""Bytes of a CSV file read at a time (4 MiB, some 300,000 lines of a pulse record)."""
MAX_LINE_BYTES = 1 << 20
"""The longest line read (1 MiB): a file with a longer one is not a table."""


@dataclass(frozen=True)
class CsvHeader:
    """The header of a CSV file and where its data begin.

    Parameters
    ----------
    name : str
        The file as named in messages.
    line : int
        The header's line number (1-based).
    cells : list of str
        The header's cells (stripped, trailing empty cells dropped).
    offset : int
        The byte offset of the line after the header.
    next_line : int
        That line's number.
    """

    name: str
    line: int
    cells: list[str]
    offset: int
    next_line: int


@dataclass(frozen=True)
class CsvBlock:
    """The data rows of a chunk.

    Parameters
    ----------
    lines : numpy.ndarray
        The line number of every data row.
    values : dict of int to numpy.ndarray
        Per dense column (its index): every row's value in SI units.
    sparse : dict of int to (numpy.ndarray, numpy.ndarray)
        Per sparse column: the SI values of its non-blank cells and their lines.
    """

    lines: NDArray[np.int64]
    values: dict[int, NDArray[np.float64]]
    sparse: dict[int, tuple[NDArray[np.float64], NDArray[np.int64]]]


def _decode(data: bytes, name: str, what: str, first_line: int) -> str:
    """UTF-8 text of a chunk; an invalid byte is an error naming its line (as
    :func:`crankdyn.io.files.read_text`)."""
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = first_line + data[: exc.start].count(b"\n")
        raise InputError(
            f"the {what} is not UTF-8 text (byte 0x{data[exc.start]:02x} on line {line})",
            file=name,
        ) from None


def _cut(data: bytes, at_end: bool) -> int:
    """Where a chunk's whole lines end: after its last ``\\n``, or after a lone ``\\r``
    (a file with ``\\r`` line breaks); all of it at the end of the file; 0 when it holds no
    line break."""
    if at_end:
        return len(data)
    cut = data.rfind(b"\n")
    if cut >= 0:
        return cut + 1
    cut = data.rfind(b"\r", 0, len(data) - 1)  # a \r at the very end may begin a \r\n
    return cut + 1 if cut >= 0 else 0


def _pieces(path: str | Path, name: str, what: str, offset: int) -> Iterator[bytes]:
    """The file's bytes from ``offset``, in chunks of whole lines."""
    with open_regular(path, what=what) as handle:
        handle.seek(offset)
        carry = b""
        while True:
            block = handle.read(CHUNK_BYTES)
            data = carry + block
            if not data:
                return
            cut = _cut(data, not block)
            if cut == 0:
                if len(data) > MAX_LINE_BYTES:
                    raise InputError(
                        f"a line longer than {MAX_LINE_BYTES >> 20} MiB: not a table", file=name
                    )
                carry = data
                continue
            yield data[:cut]
            carry = data[cut:]
            if not block:
                return


def _line_count(text: str) -> int:
    """Lines of a chunk as :meth:`str.splitlines` counts them."""
    return len(text.splitlines())


def csv_header(path: str | Path, name: str, what: str) -> CsvHeader | None:
    """The first row of a CSV file (comment and blank lines before it skipped), or None for a
    file without one.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.
    name : str
        The file as named in messages.
    what : str
        What the file is, in words (``"signal file"``).

    Returns
    -------
    CsvHeader or None
        The header and where the data begin.

    Raises
    ------
    InputError
        If the file cannot be read or is not UTF-8 text.
    """
    offset, line = 0, 1
    for data in _pieces(path, name, what, 0):
        text = _decode(data, name, what, line)
        if offset == 0 and text.startswith("\ufeff"):
            text, offset = text[1:], 3  # a byte-order mark: 3 bytes, no character
        for number, piece in enumerate(text.splitlines(keepends=True), start=line):
            rows = csv_rows(piece, number)
            offset += len(piece.encode("utf-8"))
            if rows:
                return CsvHeader(name, number, rows[0][1], offset, number + 1)
        line += _line_count(text)
    return None


def csv_blocks(
    path: str | Path,
    header: CsvHeader,
    dense: dict[int, tuple[float, str]],
    sparse: dict[int, float],
    what: str,
) -> Iterator[CsvBlock]:
    """The data rows of a CSV file after its header, chunk by chunk (module docstring).

    Parameters
    ----------
    path : str or pathlib.Path
        The file.
    header : CsvHeader
        Its header (:func:`csv_header`).
    dense : dict of int to (float, str)
        The columns every row must fill: column index to (SI factor of its unit, kind of
        quantity for the message; :func:`crankdyn.io.csv_tables.CsvTable.column`).
    sparse : dict of int to float
        Columns of times that may be blank: index to the SI factor of their unit.
    what : str
        What the file is, in words.

    Yields
    ------
    CsvBlock
        The rows of each chunk (possibly none).

    Raises
    ------
    InputError
        For a row with more cells than the header names, a missing, non-numeric, non-finite or
        out-of-range value, naming the file, the line and the cell.
    """
    line = header.next_line
    for data in _pieces(path, header.name, what, header.offset):
        block, count = _fast(data, line, len(header.cells), dense, sparse)
        if block is None:
            text = _decode(data, header.name, what, line)
            block, count = _slow(text, line, header, dense, sparse), _line_count(text)
        yield block
        line += count


# ---- the chunk at C speed ---------------------------------------------------------------------


_VALUE_START = np.ones(256, dtype=bool)
_VALUE_START[[9, 10, 13, 32, 35, 44]] = False  # a row's first byte: not blank, #, a comma


def _fast(
    data: bytes,
    first_line: int,
    width: int,
    dense: dict[int, tuple[float, str]],
    sparse: dict[int, float],
) -> tuple[CsvBlock | None, int]:
    """The rows of a plain chunk (module docstring) and its lines, by array operations and
    numpy's C reader; (None, 0) when the chunk is not plain or a value fails a check (the
    line-by-line reader then says which)."""
    b = np.frombuffer(data, dtype=np.uint8)
    if np.any(b >= 128) or np.any((b < 32) & (b != 9) & (b != 10) & (b != 13)) or b'"' in data:
        return None, 0
    if b"\r" in data:
        if data.count(b"\r") != data.count(b"\r\n"):
            return None, 0
        data = data.replace(b"\r\n", b"\n")
        b = np.frombuffer(data, dtype=np.uint8)
    breaks = np.flatnonzero(b == 10)
    ends = breaks if b.size and b[-1] == 10 else np.append(breaks, b.size)
    starts = np.concatenate([[0], ends[:-1] + 1])
    filled = _VALUE_START[np.append(b, 10)[starts]] & (ends > starts)  # a row, plainly
    odd = np.flatnonzero(~filled & (ends > starts))  # blank, comment or indented lines
    text = data.decode("ascii")
    skip = []
    for i in odd.tolist():  # rare: as csv_rows reads them
        line = text[starts[i] : ends[i]]
        if not line.strip() or line.lstrip().startswith("#") or not line.replace(",", "").strip():
            skip.append(i)
        elif "#" in line:
            return None, 0
        else:
            filled[i] = True
    if b"#" in data and np.any(filled[np.searchsorted(ends, np.flatnonzero(b == 35))]):
        return None, 0  # a # within a row: read line by line
    commas = np.flatnonzero(b == 44)
    per_line = np.bincount(np.searchsorted(ends, commas), minlength=ends.size)
    if np.any(per_line[filled] > width - 1):
        return None, 0  # more cells than the header names, or trailing empty ones
    rows = np.flatnonzero(filled)
    lines = (first_line + rows).astype(np.int64)
    if skip:  # the lines that are not rows become comments for numpy's reader
        chars = bytearray(data)
        for i in skip:
            chars[starts[i] : ends[i]] = b"#" * int(ends[i] - starts[i])
        text = chars.decode("ascii")
    values: dict[int, NDArray[np.float64]] = {col: np.empty(0) for col in dense}
    if dense and rows.size:
        columns = sorted(dense)
        try:
            table = np.loadtxt(
                io.StringIO(text),
                delimiter=",",
                comments="#",
                usecols=columns,
                ndmin=2,
                quotechar=None,
            )
        except ValueError:
            return None, 0
        if table.shape[0] != rows.size:
            return None, 0
        for k, col in enumerate(columns):
            si = table[:, k] * dense[col][0]
            if not _all_in_range(table[:, k], si):
                return None, 0
            values[col] = si
    out_sparse = {}
    for col, factor in sparse.items():
        found = _sparse(data, starts[rows], ends[rows], commas, col, factor)
        if found is None:
            return None, 0
        out_sparse[col] = (found[0], lines[found[1]])
    return CsvBlock(lines, values, out_sparse), int(ends.size)


def _all_in_range(raw: NDArray[np.float64], si: NDArray[np.float64]) -> bool:
    """Every value finite as written and in SI, within the range (or 0)."""
    magnitude = np.abs(si)
    ok = np.isfinite(raw) & np.isfinite(si)
    ok &= (magnitude == 0.0) | ((magnitude >= SI_RANGE[0]) & (magnitude <= SI_RANGE[1]))
    return bool(np.all(ok))


def _sparse(
    data: bytes,
    starts: NDArray[np.intp],
    ends: NDArray[np.intp],
    commas: NDArray[np.intp],
    col: int,
    factor: float,
) -> tuple[NDArray[np.float64], NDArray[np.intp]] | None:
    """The non-blank cells of column ``col`` of the rows (their values in SI and the rows), or
    None when one fails a check."""
    if commas.size == 0:  # one cell a row
        if col > 0:
            return np.empty(0), np.empty(0, dtype=np.intp)
        commas = np.array([np.iinfo(np.intp).max])
    first = np.searchsorted(commas, starts)  # each row's first comma
    last = commas.size - 1
    if col == 0:
        lo = starts
    else:
        k = np.minimum(first + col - 1, last)
        has = (first + col - 1 <= last) & (commas[k] < ends)
        lo = np.where(has, commas[k] + 1, ends)
    k = np.minimum(first + col, last)
    hi = np.where((first + col <= last) & (commas[k] < ends), commas[k], ends)
    rows = np.flatnonzero(hi > lo)
    cells = [data[lo[r] : hi[r]].strip() for r in rows.tolist()]
    keep = [i for i, c in enumerate(cells) if c]
    try:
        numbers = np.array([float(cells[i]) for i in keep], dtype=float)
    except ValueError:
        return None
    si = numbers * factor
    if not _all_in_range(numbers, si):
        return None
    return si, rows[keep]


# ---- the chunk line by line (the messages) ----------------------------------------------------


def _slow(
    text: str,
    first_line: int,
    header: CsvHeader,
    dense: dict[int, tuple[float, str]],
    sparse: dict[int, float],
) -> CsvBlock:
    """The rows of a chunk as :func:`~crankdyn.io.csv_tables.read_csv_table` reads them, with
    its checks and messages."""
    rows = csv_rows(text, first_line)
    check_row_widths(rows, header.cells, header.name)
    table = CsvTable(header.name, header.line, header.cells, rows)
    lines = np.array([number for number, _ in rows], dtype=np.int64)
    values = {col: table.column(col, factor, kind=kind) for col, (factor, kind) in dense.items()}
    out_sparse = {col: sparse_column(table, col, factor) for col, factor in sparse.items()}
    return CsvBlock(lines, values, out_sparse)


def sparse_column(
    table: CsvTable, col: int, factor: float
) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """The times in a column that may be blank (a signal's ``reference`` column), with their
    lines: every non-blank cell a finite number whose SI value lies in the range.

    Parameters
    ----------
    table : crankdyn.io.csv_tables.CsvTable
        The rows.
    col : int
        The column.
    factor : float
        The SI factor of its unit (a time unit).

    Returns
    -------
    tuple of (numpy.ndarray, numpy.ndarray)
        The times (s) and their lines.

    Raises
    ------
    InputError
        For a cell that is not a finite number or lies outside the range, naming the line and
        the cell.
    """
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
