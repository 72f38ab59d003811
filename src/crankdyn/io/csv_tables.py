"""Unit-annotated CSV tables: the shared reader behind pressure traces, load curves and
harmonic-coefficient tables.

A table has a header line naming every column and its unit (after the last underscore:
``pressure_MPa``; in brackets: ``pressure [bar]``; or in parentheses: ``p (kPa)``), then one row
per point. Lines starting with ``#`` and blank lines are skipped. Every error names the file, the
line and the cell as written.
"""

from __future__ import annotations

import csv
import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError
from crankdyn.io.files import MAX_CSV_BYTES, display_name, read_text
from crankdyn.io.units import BARE_SPEED, KINDS, check_si_range, parse_quantity

__all__ = [
    "CsvTable",
    "cell_value",
    "check_row_widths",
    "csv_rows",
    "read_csv_table",
    "split_header_unit",
    "unit_factor",
]

_BRACKETED = re.compile(r"^(.*?)\s*[\[(]\s*([^\])]+?)\s*[\])]\s*$")
_DEGREES = ("deg", "degree", "degrees")


def split_header_unit(cell: str) -> tuple[str, str | None]:
    """Split a header cell into (name, unit): ``pressure_MPa``, ``pressure [MPa]``,
    ``p (MPa)``; unit None when the cell names none.

    Parameters
    ----------
    cell
        A header cell as written.

    Returns
    -------
    tuple of (str, str or None)
        The column's name and its unit text (not yet checked), or None for no unit.

    Examples
    --------
    >>> split_header_unit("pressure_MPa"), split_header_unit(" p (kPa) ")
    (('pressure', 'MPa'), ('p', 'kPa'))
    >>> split_header_unit("angle [deg]"), split_header_unit("pressure")
    (('angle', 'deg'), ('pressure', None))
    """
    cell = cell.strip()
    m = _BRACKETED.match(cell)
    if m:
        return m.group(1).strip(), m.group(2).strip()
    if "_" in cell:
        name, unit = cell.rsplit("_", 1)
        return name, unit
    return cell, None


def unit_factor(
    cell: str, unit: str | None, kind: str, file: str, *, missing: str, unknown: str
) -> float:
    """SI factor of a column's unit; ``missing`` and ``unknown`` are the messages for a column
    without a unit and with one crankdyn does not know (``{unit}`` is filled in).

    Parameters
    ----------
    cell
        The header cell as written (the ``value`` of an error).
    unit
        Its unit text (:func:`split_header_unit`), or None.
    kind
        The kind of quantity the column holds, a key of :data:`crankdyn.io.units.KINDS`;
        for ``"angle"`` also ``deg``/``degree``/``degrees``.
    file
        The file as named in messages.
    missing
        The message for a column without a unit (a speed column's names the speed's units,
        :data:`crankdyn.io.units.BARE_SPEED`).
    unknown
        The message for a unit crankdyn does not know or of the wrong kind; ``{unit}`` is
        replaced by the unit.

    Returns
    -------
    float
        The value of one ``unit`` in the SI unit of ``kind`` (e.g. 1e6 for MPa, pi/180 for
        deg).

    Raises
    ------
    InputError
        With ``missing`` or ``unknown``, naming the file, ``key="header"`` and the cell.

    Examples
    --------
    >>> unit_factor("p_MPa", "MPa", "pressure", "t.csv", missing="?", unknown="{unit}?")
    1000000.0
    >>> unit_factor("p_kg", "kg", "pressure", "t.csv", missing="?", unknown="unit {unit}?")
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: t.csv: header = "p_kg": unit 'kg'?
    """
    if not unit:
        if kind == "speed":  # a bare speed: rpm on the command line, so never SI in a file
            missing = f"{BARE_SPEED}: the column must name its unit, e.g. speed_rpm"
        raise InputError(missing, file=file, key="header", value=cell)
    try:
        return parse_quantity(f"1 {unit}", kind, key="header", file=file)
    except InputError:
        if kind == "angle" and unit.lower() in _DEGREES:
            return math.pi / 180.0
        raise InputError(
            unknown.format(unit=repr(unit)), file=file, key="header", value=cell
        ) from None


def cell_value(
    cell: str,
    factor: float = 1.0,
    *,
    file: str | None,
    key: str,
    column: str,
    kind: str | None = None,
) -> float:
    """A cell's number in SI units: a finite number whose SI value (the number times
    ``factor``) lies within the range every quantity must lie in
    (:data:`crankdyn.io.units.SI_RANGE`, 1e-12 to 1e12, or 0: beyond it the unit is wrong), as
    every quantity of a TOML file; the one check of every CSV table's numbers.

    Parameters
    ----------
    cell
        The cell as written.
    factor
        The SI value of the column's unit (:func:`unit_factor`); 1 for plain numbers.
    file
        The file as named in messages (None: the caller adds it).
    key
        Where the cell is (``"line 5"``, ``"line 5 inertia"``).
    column
        The column's name as written, for the message.
    kind
        The kind of quantity (a key of :data:`crankdyn.io.units.KINDS`), for the SI unit in the
        message; None for a plain number.

    Returns
    -------
    float
        The value in the SI unit of ``kind``.

    Raises
    ------
    InputError
        For a cell that is not a finite number or lies outside the range, naming the file,
        ``key`` and the cell.

    Examples
    --------
    >>> cell_value("2.5", 1e6, file="t.csv", key="line 3", column="p_MPa", kind="pressure")
    2500000.0
    >>> cell_value("1e-15", file="m.csv", key="line 3 inertia", column="inertia [kg*m^2]",
    ...            kind="inertia")
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: m.csv: line 3 inertia = "1e-15": 1e-15 kg*m^2 in column \
'inertia [kg*m^2]' lies outside the range crankdyn computes with (1e-12 to 1e12 in SI units, or \
0); check the unit
    """
    text = cell.strip()
    try:
        value = float(text)
    except ValueError:
        raise InputError(
            f"not a number in column {column!r}", file=file, key=key, value=text
        ) from None
    if not math.isfinite(value):
        raise InputError(
            f"not a finite number in column {column!r}", file=file, key=key, value=text
        )
    si = value * factor
    if not (math.isfinite(si) and check_si_range(si)):
        unit = KINDS[kind].si_unit if kind in KINDS else ""
        raise InputError(
            f"{si:.3g}{' ' + unit if unit else ''} in column {column!r} lies outside the range "
            "crankdyn computes with (1e-12 to 1e12 in SI units, or 0); check the unit",
            file=file,
            key=key,
            value=text,
        )
    return si


def is_number(text: str) -> bool:
    """Whether a cell reads as a number (:class:`float` accepts it).

    Parameters
    ----------
    text
        The cell.

    Returns
    -------
    bool
        True for a number.
    """
    try:
        float(text)
    except ValueError:
        return False
    return True


@dataclass
class CsvTable:
    """The header and the data rows of a CSV table, with their line numbers.

    Parameters
    ----------
    name
        The file as named in messages.
    header_line
        Line number (1-based, in the file) of the header.
    header
        The header's cells, stripped.
    rows
        The data rows as (line number, cells), comments and blank lines left out.
    """

    name: str  # the file as named in messages
    header_line: int
    header: list[str]
    rows: list[tuple[int, list[str]]]  # (line number, cells)

    @property
    def header_is_numeric(self) -> bool:
        """Whether the first line holds numbers (a table without a header)."""
        return bool(self.header) and is_number(self.header[0])

    def column(
        self, index: int, factor: float = 1.0, *, kind: str | None = None
    ) -> NDArray[np.float64]:
        """The values of column ``index`` in SI units (the cells times ``factor``, the SI value
        of the column's unit); a missing, non-numeric or non-finite cell, or a value outside the
        range every quantity must lie in (:data:`crankdyn.io.units.SI_RANGE`, or 0: beyond it
        the unit is wrong), is an error naming its line and column. ``kind`` names the SI unit
        in that message.

        Parameters
        ----------
        index
            The column (0-based).
        factor
            The SI value of the column's unit (:func:`unit_factor`), e.g. 1e5 for bar.
        kind
            The kind of quantity (a key of :data:`crankdyn.io.units.KINDS`), for the message.

        Returns
        -------
        numpy.ndarray
            One float per data row, in the SI unit of ``kind``.

        Raises
        ------
        InputError
            Naming the file, the line (``key``) and the cell (``value``).
        """
        label = self.header[index].strip() if index < len(self.header) else str(index + 1)
        out = np.empty(len(self.rows))
        for k, (number, row) in enumerate(self.rows):
            if index >= len(row):
                raise InputError(
                    f"expected a value in column {label!r}",
                    file=self.name,
                    key=f"line {number}",
                    value=",".join(row),
                )
            out[k] = cell_value(
                row[index], factor, file=self.name, key=f"line {number}", column=label, kind=kind
            )
        return out

    def cell(self, row: int, index: int) -> tuple[int, str]:
        """(line number, cell text) of data row ``row``, column ``index``.

        Parameters
        ----------
        row
            The data row (0-based, among the data rows).
        index
            The column (0-based).

        Returns
        -------
        tuple of (int, str)
            The row's line number in the file and the cell's text, stripped: the ``key`` and
            ``value`` of an error about it.
        """
        number, cells = self.rows[row]
        return number, cells[index].strip()


def read_csv_table(
    path: str | Path, *, display: str | None = None, what: str = "table", empty: str | None = None
) -> CsvTable:
    """Read a CSV table (bounded, UTF-8): header and data rows, comments and blanks skipped.

    Format: CSV with a header line (module docstring); lines starting with ``#`` and blank
    lines are skipped, trailing empty cells dropped; at most
    :data:`~crankdyn.io.files.MAX_CSV_BYTES`.

    Parameters
    ----------
    path
        The CSV file.
    display
        How to name the file in messages (default: the path as given).
    what
        What the table is, in words, for messages (``"pressure trace"``).
    empty
        The message for a file with no header and no data (default: "the <what> is empty").

    Returns
    -------
    CsvTable
        The header and the data rows with their line numbers (cells still text).

    Raises
    ------
    InputError
        On an unreadable, oversized or non-UTF-8 file, an empty one, or a data row with more
        cells than the header (a decimal comma?), naming the file, the line and the row.
    """
    name = display or display_name(path)
    try:
        text = read_text(path, limit=MAX_CSV_BYTES, what=what)
    except InputError as exc:
        raise InputError(exc.message, file=name) from None
    rows = csv_rows(text)
    if not rows:
        raise InputError(empty or f"the {what} is empty", file=name)
    (header_line, header), data = rows[0], rows[1:]
    check_row_widths(data, header, name)
    return CsvTable(name, header_line, header, data)


def csv_rows(text: str, first_line: int = 1) -> list[tuple[int, list[str]]]:
    """The rows of CSV text with their line numbers: comments (lines starting with ``#``),
    blank lines and rows of blank cells left out, cells stripped, trailing empty cells dropped.

    Parameters
    ----------
    text
        Whole lines of a CSV file (as :meth:`str.splitlines` splits them).
    first_line
        The line number of the text's first line (1-based).

    Returns
    -------
    list of (int, list of str)
        (line number, cells) per row.

    Examples
    --------
    >>> csv_rows("# c\\ntime [s],reference [s]\\n0.1,0.05\\n\\n0.2,\\n", first_line=3)
    [(4, ['time [s]', 'reference [s]']), (5, ['0.1', '0.05']), (7, ['0.2'])]
    """
    # a comment is a line that starts with # as written (a quoted "#1" is a cell)
    lines = [
        (number, line)
        for number, line in enumerate(text.splitlines(), start=first_line)
        if line.strip() and not line.lstrip().startswith("#")
    ]
    parsed = ((number, next(csv.reader([line]), [])) for number, line in lines)  # a row a line
    rows = [
        (number, [c.strip() for c in row]) for number, row in parsed if any(map(str.strip, row))
    ]
    return [(number, _trim(cells)) for number, cells in rows]


def check_row_widths(rows: list[tuple[int, list[str]]], header: list[str], name: str) -> None:
    """Refuse a data row with more cells than the header names (a decimal comma?).

    Parameters
    ----------
    rows
        (line number, cells) per data row (:func:`csv_rows`).
    header
        The header's cells.
    name
        The file as named in messages.

    Raises
    ------
    InputError
        Naming the file, the line and the row.
    """
    for number, cells in rows:
        if len(cells) > len(header):
            named = "the header names" if not is_number(header[0]) else "the first row has"
            raise InputError(
                f"{len(cells)} cells, but {named} {len(header)} columns: column "
                f"{len(header) + 1} has no name (a decimal comma? write 30.1, not 30,1)",
                file=name,
                key=f"line {number}",
                value=",".join(cells),
            )


def _trim(cells: list[str]) -> list[str]:
    """The cells without trailing empty ones (a trailing comma, as spreadsheets write)."""
    end = len(cells)
    while end > 1 and not cells[end - 1]:
        end -= 1
    return cells[:end]
