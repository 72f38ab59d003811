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
import re
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
_EXOTIC = re.compile(r"[\x0b\x0c\x1c-\x1e\x85\u2028\u2029]")  # line breaks of str.splitlines
_SPACE = (32, 9, 13)  # what a plain line's cells hold besides their values


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
        text = _decode(data, header.name, what, line)
        block = _fast(data, text, line, len(header.cells), dense, sparse)
        if block is None:
            block = _slow(text, line, header, dense, sparse)
        yield block
        line += _line_count(text)


# ---- the chunk at C speed ---------------------------------------------------------------------


def _plain(data: bytes, text: str) -> bytes | None:
    """The chunk's bytes when it is plain (module docstring), ``\\r\\n`` made ``\\n``."""
    if '"' in text or _EXOTIC.search(text):
        return None
    if "\r" in text:
        if text.count("\r") != text.count("\r\n"):
            return None
        data = data.replace(b"\r\n", b"\n")
    return data


def _fast(
    data: bytes,
    text: str,
    first_line: int,
    width: int,
    dense: dict[int, tuple[float, str]],
    sparse: dict[int, float],
) -> CsvBlock | None:
    """The rows of a plain chunk by array operations and numpy's C reader, or None when the
    chunk is not plain or a value fails a check (the line-by-line reader then says which)."""
    plain = _plain(data, text)
    if plain is None:
        return None
    buf = np.frombuffer(plain, dtype=np.uint8).copy()
    if np.any(buf >= 128) or np.any((buf < 32) & (buf != 9) & (buf != 10) & (buf != 13)):
        return None
    if not np.any(~np.isin(buf, (*_SPACE, 10, 44))):  # no value at all: no rows
        return CsvBlock(
            np.empty(0, dtype=np.int64),
            {c: np.empty(0) for c in dense},
            {c: (np.empty(0), np.empty(0, dtype=np.int64)) for c in sparse},
        )
    breaks = np.flatnonzero(buf == 10)
    ends = breaks if buf.size and buf[-1] == 10 else np.append(breaks, buf.size)
    starts = np.concatenate([[0], ends[:-1] + 1]).astype(np.int64)
    nonspace = ~np.isin(buf, (*_SPACE, 10))
    where = np.flatnonzero(nonspace)
    at = np.searchsorted(where, starts)
    first = np.where(at < where.size, where[np.minimum(at, where.size - 1)], buf.size)
    first = np.where(first < ends, first, -1)
    comment = (first >= 0) & (buf[np.maximum(first, 0)] == ord("#"))
    value = np.flatnonzero(nonspace & (buf != 44))
    last_at = np.searchsorted(value, ends) - 1  # the last value byte before each line's end
    last = np.where(last_at >= 0, value[np.maximum(last_at, 0)], -1)
    filled = (last >= starts) & ~comment
    hashes = np.flatnonzero(buf == ord("#"))
    line_of = np.searchsorted(ends, hashes)
    if np.any(filled[line_of]):  # a # within a row: read line by line
        return None
    commas = np.flatnonzero(buf == 44)
    cells = np.searchsorted(commas, last) - np.searchsorted(commas, starts) + 1
    if np.any(cells[filled] > width):
        return None
    # the lines that are not rows become comments for numpy's reader
    mask = np.zeros(buf.size + 1, dtype=np.int64)
    skip = ~filled & (ends > starts)
    np.add.at(mask, starts[skip], 1)
    np.add.at(mask, ends[skip], -1)
    buf[np.cumsum(mask[:-1]) > 0] = ord("#")
    rows = np.flatnonzero(filled)
    lines = (first_line + rows).astype(np.int64)
    values: dict[int, NDArray[np.float64]] = {}
    if dense and rows.size:
        columns = sorted(dense)
        try:
            table = np.loadtxt(
                io.StringIO(buf.tobytes().decode("ascii")),
                delimiter=",",
                comments="#",
                usecols=columns,
                ndmin=2,
                quotechar=None,
            )
        except ValueError:
            return None
        if table.shape[0] != rows.size:
            return None
        for k, col in enumerate(columns):
            si = table[:, k] * dense[col][0]
            if not _all_in_range(table[:, k], si):
                return None
            values[col] = si
    elif dense:
        values = {col: np.empty(0) for col in dense}
    out_sparse = {}
    for col, factor in sparse.items():
        found = _sparse(buf, starts[rows], ends[rows], commas, col, factor)
        if found is None:
            return None
        out_sparse[col] = (found[0], lines[found[1]])
    return CsvBlock(lines, values, out_sparse)


def _all_in_range(raw: NDArray[np.float64], si: NDArray[np.float64]) -> bool:
    """Every value finite as written and in SI, within the range (or 0)."""
    magnitude = np.abs(si)
    ok = np.isfinite(raw) & np.isfinite(si)
    ok &= (magnitude == 0.0) | ((magnitude >= SI_RANGE[0]) & (magnitude <= SI_RANGE[1]))
    return bool(np.all(ok))


def _sparse(
    buf: NDArray[np.uint8],
    starts: NDArray[np.int64],
    ends: NDArray[np.int64],
    commas: NDArray[np.intp],
    col: int,
    factor: float,
) -> tuple[NDArray[np.float64], NDArray[np.intp]] | None:
    """The non-blank cells of column ``col`` of the rows (their values in SI and the rows), or
    None when one fails a check."""
    first = np.searchsorted(commas, starts)  # each row's first comma
    if col == 0:
        lo = starts
    else:
        k = first + col - 1
        has = (k < commas.size) & (commas[np.minimum(k, commas.size - 1)] < ends)
        lo = np.where(has, commas[np.minimum(k, commas.size - 1)] + 1, ends)
    k = first + col
    nxt = np.where(k < commas.size, commas[np.minimum(k, commas.size - 1)], ends)
    hi = np.minimum(nxt, ends)
    hi = np.maximum(hi, lo)
    value = np.flatnonzero(~np.isin(buf, (*_SPACE, 10, 44)))
    nonblank = np.searchsorted(value, hi) > np.searchsorted(value, lo)
    rows = np.flatnonzero(nonblank)
    raw = buf.tobytes()
    cells = [raw[lo[r] : hi[r]] for r in rows]
    try:
        numbers = np.array([float(c) for c in cells], dtype=float)
    except ValueError:
        return None
    si = numbers * factor
    if not _all_in_range(numbers, si):
        return None
    return si, rows


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
