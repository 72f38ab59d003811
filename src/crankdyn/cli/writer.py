"""The one writer of command results: a table for people, CSV or JSON, to standard output or
(atomically, never over an existing file without ``--force``) to a file.

Every command builds what it shows from its result: :class:`TextTable` blocks (made with
:func:`result_table`, :func:`summary_table` or by hand), notes, the JSON data and the CSV text,
and hands them to :meth:`Output.write`. Numbers are shown in engineering units with sensible
digits (:mod:`crankdyn.display`); headers are words with their unit. A table wider than the
console is split into parts that fit, each repeating the first column, and a cell that still
does not fit folds onto the next line: a number is never cut.

The plausibility warnings of what a command shows (:mod:`crankdyn.plausibility`, carried by the
results as ``result.warnings``) go through the same writer: one ``crankdyn: warning: ...`` line
each on standard error, whatever the format, and a ``warnings`` list in the JSON.
"""

from __future__ import annotations

import builtins
import io
import json
import os
import sys
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any, TypeVar

import click
import numpy as np

from crankdyn.cli.common import before_work, console, stdout_width, warn
from crankdyn.display import column_text, csv_text, format_value, printable
from crankdyn.errors import InputError
from crankdyn.io.output import check_writable, write_text
from crankdyn.plausibility import PlausibilityWarning
from crankdyn.results import Result, jsonable
from crankdyn.summary import Summary, verdict_cells, warnings_dict

if TYPE_CHECKING:
    from rich.console import Console
    from rich.table import Table as RichTable

F = TypeVar("F", bound=Callable[..., Any])

__all__ = [
    "FORMATS",
    "Output",
    "TextTable",
    "figure_row",
    "json_text",
    "jsonable",
    "output_options",
    "plain_console",
    "plain_text",
    "printable_blocks",
    "result_table",
    "summary_blocks",
    "summary_table",
    "warnings_of",
]

FORMATS = ("table", "csv", "json")
"""The values of ``--format``."""
FILE_WIDTH = 120
"""Width of a table written to a file."""


@dataclass
class TextTable:
    """A table for people: a title, headers (words with units), rows of text, which columns
    hold text (left-aligned, may wrap) rather than numbers (right-aligned, never cut).

    Parameters
    ----------
    title : str
        The title printed above the table ("" for none).
    header : list of str
        The column headers, each a word or words and the display unit in brackets.
    rows : list of list of str
        The cells, as shown (numbers already formatted in the header's unit).
    text_columns : set of int
        The indices of the columns that hold text.
    caption : str
        A line printed below the table.
    keys : int
        How many leading columns name a row (repeated in every part of a table split to fit
        the console: a verdict row's component and condition).

    Examples
    --------
    >>> t = TextTable("Speeds", ["Case", "Speed (rpm)"], [["idle", "800"]], {0})
    >>> print(t.csv_text(), end="")
    Case,Speed (rpm)
    idle,800
    """

    title: str
    header: list[str]
    rows: list[list[str]]
    text_columns: set[int] = field(default_factory=set)
    caption: str = ""
    keys: int = 1

    def csv_text(self) -> str:
        """The header and rows as CSV text (the cells as shown, so in the header's units).

        Returns
        -------
        str
            One line per row, the header first, each ended by a newline (fields quoted as
            RFC 4180 requires, control characters escaped: :func:`crankdyn.display.csv_text`).
        """
        return csv_text([self.header, *self.rows])


def _header(label: str, unit: str) -> str:
    """``label (unit)``, or the label alone without a unit."""
    return f"{label} ({unit})" if unit else label


def result_table(
    result: Result, keys: Sequence[str] | None = None, title: str | None = None
) -> TextTable:
    """The columns of a result (all, or ``keys``) as a table: one engineering unit and one
    number of decimals per column.

    Parameters
    ----------
    result
        The result (:class:`crankdyn.results.Result`) whose columns are shown.
    keys
        The columns to show, in order; keys the result does not have are skipped. Default:
        all of its columns.
    title
        The table's title; default the result's ``title``.

    Returns
    -------
    TextTable
        Headers with the display unit (:func:`crankdyn.display.column_text`); text columns
        (names, labels) as they are.
    """
    cols = result.columns()
    labels = result.column_labels()
    keys = [k for k in (keys if keys is not None else list(cols)) if k in cols]
    header, columns, text = [], [], set()
    for n, key in enumerate(keys):
        label, unit = labels[key]
        values = cols[key]
        if np.asarray(values).dtype.kind in "OUS":
            header.append(label)
            columns.append([str(v) for v in values])
            text.add(n)
            continue
        cells, shown = column_text(values, unit)
        header.append(_header(label, shown))
        columns.append(cells)
    rows = [list(r) for r in zip(*columns, strict=True)] if columns else []
    return TextTable(title or getattr(result, "title", "") or "", header, rows, text)


def summary_table(
    source: Result | Summary | Iterable[Sequence[str]], title: str = "Summary"
) -> TextTable:
    """A result's key figures (or (label, value, unit) rows) as Quantity / Value / Unit.

    Parameters
    ----------
    source
        A result or its summary (the key figures: :meth:`crankdyn.summary.Summary.rows`) or
        rows of three texts, e.g. from :func:`figure_row`.
    title
        The table's title.

    Returns
    -------
    TextTable
        Three columns: Quantity, Value, Unit.

    Examples
    --------
    >>> summary_table([figure_row("Peak torque", 1.2345e3, "N·m")]).rows
    [['Peak torque', '1.2345', 'kN·m']]
    """
    if isinstance(source, Result):
        source = source.summary()
    rows = source.rows() if isinstance(source, Summary) else list(source)
    text = {0, 2}
    if any(len(r[1]) > 32 for r in rows):  # a long text (a source's name): left-aligned, wraps
        text.add(1)
    return TextTable(
        title, ["Quantity", "Value", "Unit"], [list(r) for r in rows], text_columns=text
    )


def summary_blocks(
    source: Result | Summary,
    title: str = "Summary",
    *,
    figures: bool = True,
    limit: int | None = None,
) -> list[TextTable | str]:
    """Everything a result's summary holds, as the terminal shows it: the key figures, the
    verdicts (the input warnings they stand on first, then the rows,
    :func:`crankdyn.summary.verdict_cells`, every column repeated in each part of a wide
    table's split: component, condition and quantity, then the verdict in words,
    :attr:`crankdyn.summary.Summary.verdict`), the summary's tables and its notes.

    Parameters
    ----------
    source
        A result or its summary.
    title
        The title of the key figures' table.
    figures
        Whether to show the key figures (False: only verdicts, tables and notes).
    limit
        The rows each table shows (its caption says how many more there are); None: all.

    Returns
    -------
    list of TextTable or str
        Blocks for :meth:`Output.write`.
    """
    summary = source.summary() if isinstance(source, Result) else source
    blocks: list[TextTable | str] = []
    if figures and summary.figures:
        blocks.append(summary_table(summary, title))
    if summary.verdicts:
        # the input warnings the verdict stands on, first; then the rows and the verdict
        blocks += [f"Input warning: {w.message}" for w in summary.input_warnings]
        header, rows = verdict_cells(summary.verdicts)
        blocks.append(TextTable("Verdicts", header, rows, text_columns={0, 1, 2, 5, 8, 9}, keys=2))
        blocks.append(f"Verdict: {summary.verdict}")
    for table in summary.tables:
        table = table.head(limit)
        header, rows = table.cells()
        keys = 2 if [c.key for c in table.columns[:2]] == ["component", "condition"] else 1
        blocks.append(
            TextTable(table.title, header, rows, table.text_columns(), table.caption, keys=keys)
        )
    blocks += [f"Note: {_sentence(n)}" for n in summary.notes]
    return blocks


def _sentence(text: str) -> str:
    """A note as a sentence: a capital first letter and a full stop."""
    text = text.strip()
    if not text:
        return text
    return text[0].upper() + text[1:] + ("" if text.endswith((".", "!", "?")) else ".")


def figure_row(
    label: str, value: object, unit: str = "", *, reference: float | None = None
) -> list[str]:
    """One (label, value, unit) row of a summary in engineering units.

    Parameters
    ----------
    label
        What the figure is.
    value
        The value, SI in ``unit`` (:func:`crankdyn.display.format_value`).
    unit
        Its SI unit.
    reference
        The magnitude the display unit is chosen for (same unit); default the value's own.

    Returns
    -------
    list of str
        The label, the digits and the display unit.

    Examples
    --------
    >>> figure_row("Peak pressure", 1.89441e7, "Pa")
    ['Peak pressure', '18.944', 'MPa']
    """
    text, shown = format_value(value, unit, reference=reference)
    return [label, text, shown]


JSON_INDENTED = 1 << 20
"""JSON text up to this many characters (compact) is indented for people; larger JSON (a large
model's every mode) stays compact: json's C encoder writes only compact text."""


def json_text(data: Any) -> str:
    """Strict JSON text of ``data`` (from :func:`jsonable`) and a newline: indented by two
    spaces, or compact when it is longer than :data:`JSON_INDENTED` characters.

    Parameters
    ----------
    data
        JSON data (:func:`jsonable`); numpy values left in it are converted.

    Returns
    -------
    str
        The JSON text and a newline.

    Raises
    ------
    ValueError
        On a NaN or infinity left in ``data`` (strict JSON has none; :func:`jsonable` makes
        them None).
    TypeError
        On a value JSON cannot hold.

    Examples
    --------
    >>> print(json_text({"speed": np.float64(157.08)}), end="")
    {
      "speed": 157.08
    }
    """
    text = json.dumps(data, allow_nan=False, separators=(",", ":"), default=_json_default)
    if len(text) <= JSON_INDENTED:
        text = json.dumps(data, indent=2, allow_nan=False, default=_json_default)
    return text + "\n"


def _json_default(value: object) -> Any:
    """numpy values a result left in its dict (the encoder calls this only for those)."""
    if isinstance(value, (np.ndarray, np.generic)):
        return jsonable(value.tolist() if isinstance(value, np.ndarray) else value.item())
    raise TypeError(f"{type(value).__name__} is not JSON serialisable")


def warnings_of(*sources: Any) -> list[PlausibilityWarning]:
    """The plausibility warnings of ``sources`` (results carrying ``warnings``, warnings, or
    lists of either), each once (by message), in order.

    Parameters
    ----------
    *sources
        Results (anything with a ``warnings`` attribute), warnings
        (:class:`crankdyn.plausibility.PlausibilityWarning`), lists or tuples of either, or None.

    Returns
    -------
    list of PlausibilityWarning
        The warnings, each message once, in the order first met.

    Examples
    --------
    >>> warnings_of(None, [])
    []
    """
    found: dict[str, Any] = {}

    def add(source: Any) -> None:
        """Collect the warnings of one source (recursively through lists)."""
        if source is None:
            return
        if hasattr(source, "message") and hasattr(source, "to_dict"):
            found.setdefault(source.message, source)
        elif isinstance(source, (list, tuple)):
            for item in source:
                add(item)
        else:
            for w in getattr(source, "warnings", ()) or ():
                add(w)

    for source in sources:
        add(source)
    return list(found.values())


# ---- rendering --------------------------------------------------------------------------------
def printable_blocks(blocks: Iterable[TextTable | str | None]) -> list[TextTable | str | None]:
    """Tables and notes with every control character of their text (titles, headers, cells,
    captions: user names among them) shown as its escape (:func:`crankdyn.display.printable`):
    no escape sequence of a name reaches the terminal, and every cell and title is one line
    (a note keeps its own line breaks).

    Parameters
    ----------
    blocks
        Tables and note lines, as for :func:`render`.

    Returns
    -------
    list
        The same blocks, their text printable (a table without control characters is kept as
        it is).
    """
    out: list[TextTable | str | None] = []
    for block in blocks:
        if isinstance(block, TextTable):
            texts = [block.title, block.caption, *block.header, *(c for r in block.rows for c in r)]
            if not all(str(t).isprintable() for t in texts):
                block = TextTable(
                    printable(block.title),
                    [printable(h) for h in block.header],
                    [[printable(c) for c in row] for row in block.rows],
                    set(block.text_columns),
                    printable(block.caption),
                )
        elif block:  # a note: its own line breaks kept, other control characters escaped
            block = "\n".join(printable(line) for line in str(block).split("\n"))
        out.append(block)
    return out


def _widths(table: TextTable) -> list[int]:
    """The width of each column: its longest number (never cut) or, for text, its longest word
    up to 24 characters; headers wrap at spaces to it (at least 10 wide)."""
    out = []
    for c, head in enumerate(table.header):
        words = [len(w) for w in head.split()] or [1]
        cells = [row[c] for row in table.rows]
        if c in table.text_columns:
            longest_word = max([max((len(w) for w in s.split()), default=1) for s in cells] or [1])
            longest = max((len(s) for s in cells), default=1)
            need = max(longest_word, min(longest, 24))
        else:
            need = max((len(s) for s in cells), default=1)
        out.append(max(max(words), need, min(len(head), 10)))
    return out


def _wrap(text: str, width: int) -> str:
    """Header words on lines of at most ``width`` characters."""
    lines: list[str] = []
    for word in text.split():
        if lines and len(lines[-1]) + 1 + len(word) <= width:
            lines[-1] += " " + word
        else:
            lines.append(word)
    return "\n".join(lines)


def _parts(table: TextTable, width: int) -> list[list[int]]:
    """Column groups that fit ``width`` (each after the first repeats the key columns)."""
    widths = _widths(table)
    keys = list(range(max(1, min(table.keys, len(widths) - 1))))
    if sum(w + 3 for w in widths) + 1 <= width or len(widths) <= len(keys) + 1:
        return [list(range(len(widths)))]
    key_width = sum(widths[c] + 3 for c in keys) + 1
    parts, current = [], list(keys)
    used = key_width
    for c in range(len(keys), len(widths)):
        need = widths[c] + 3
        if used + need > width and len(current) > len(keys):
            parts.append(current)
            current, used = list(keys), key_width
        current.append(c)
        used += need
    parts.append(current)
    # the same number of parts, the columns shared out evenly (no last part of one column)
    rest = list(range(len(keys), len(widths)))
    k = len(parts)
    size = -(-len(rest) // k)
    even = [[*keys, *rest[i : i + size]] for i in range(0, len(rest), size)]
    if all(sum(widths[c] + 3 for c in part) + 1 <= width for part in even):
        return even
    return parts


def _rich(table: TextTable, columns: list[int], title: str) -> RichTable:
    """The ``columns`` of a table as a rich table, every cell a Text (never markup)."""
    from rich.table import Table as RichTable
    from rich.text import Text

    # every string goes in as a Text: user text is never read as markup, whatever the console
    widths = _widths(table)
    rich = RichTable(title=Text(title) if title else None, header_style="bold")
    for c in columns:
        text = c in table.text_columns
        rich.add_column(
            Text(_wrap(table.header[c], widths[c])),
            justify="left" if text else "right",
            overflow="fold",
            no_wrap=not text,
            min_width=widths[c],
        )
    for row in table.rows:
        rich.add_row(*(Text(row[c]) for c in columns))
    if table.caption:
        rich.caption = Text(table.caption)
    return rich


def render(blocks: Iterable[TextTable | str | None], con: Console) -> None:
    """Print tables (split to fit the console) and note lines.

    Parameters
    ----------
    blocks
        Tables, each split into parts that fit the console's width (every part repeating the
        first column), and note lines, printed as written (empty ones skipped).
    con
        The console (:func:`crankdyn.cli.common.console`).
    """
    from rich.text import Text

    for block in blocks:
        if isinstance(block, TextTable):
            for title, cols in _titled_parts(block, con.width):
                con.print(_rich(block, cols, title))
        elif block:
            con.print(Text(str(block)), soft_wrap=False)


def _titled_parts(table: TextTable, width: int) -> list[tuple[str, list[int]]]:
    """The parts of a table that fit ``width`` (:func:`_parts`), each with its title."""
    parts = _parts(table, width)
    if len(parts) == 1:
        return [(table.title, parts[0])]
    return [
        (f"{table.title} (part {n + 1} of {len(parts)})".strip(), cols)
        for n, cols in enumerate(parts)
    ]


# ---- the same text without rich ---------------------------------------------------------------
# What rich prints for these tables on a console that is not a terminal (no styles) is plain
# text in a fixed layout; :func:`plain_text` writes it directly, in a fraction of the time
# (and without importing rich), whenever the layout is the simple one: every column at its
# natural width within the console, no cell wrapped, every character one column wide.
# tests/cli/test_writer.py holds it to rich's own output, character for character.

_ONE_CELL = frozenset(
    chr(c)
    for start, end in (
        (0x20, 0x7E),
        (0xA0, 0xAC),
        (0xAE, 0x2FF),
        (0x370, 0x482),
        (0x2500, 0x25FC),
        (0x2800, 0x28FF),
    )
    for c in range(start, end + 1)
)
"""The characters rich measures one column wide whatever the Unicode version (its own
single-cell ranges, rich.cells): no control character (no line break, no tab), nothing wide,
nothing of zero width."""


def _one_cell(text: str) -> bool:
    """Whether every character of ``text`` is one column wide to rich (:data:`_ONE_CELL`)."""
    return (text.isascii() and text.isprintable()) or _ONE_CELL.issuperset(text)


def plain_console(file: IO[str] | None) -> bool:
    """Whether rich would print to ``file`` without styles, boxes in Unicode, as on a pipe or
    in a file: not a terminal (nor told to act as one by ``TTY_COMPATIBLE`` or
    ``FORCE_COLOR``), not in Jupyter, on a platform without the legacy Windows console, in a
    UTF encoding. Only then does :func:`plain_text` stand in for rich.

    Parameters
    ----------
    file
        The text stream the console writes to (None: there is none, standard output closed;
        rich discards what it prints).

    Returns
    -------
    bool
        True when rich's output would be plain text.
    """
    file = getattr(file, "rich_proxied_file", file)  # what rich writes to under a live display
    if file is None or sys.platform == "win32" or hasattr(builtins, "get_ipython"):
        return False
    encoding = (getattr(file, "encoding", "utf-8") or "utf-8").lower()
    if not encoding.startswith("utf"):
        return False
    tty = os.environ.get("TTY_COMPATIBLE", "")
    if tty == "1":
        return False
    if tty != "0":
        if "FORCE_COLOR" in os.environ:
            return os.environ["FORCE_COLOR"] == ""
        isatty = getattr(file, "isatty", None)
        try:
            return isatty is None or not isatty()
        except ValueError:  # a closed file: rich takes it for no terminal
            return True
    return True


def _centred(text: str, width: int) -> str:
    """``text`` (its trailing blanks dropped) centred in ``width`` columns, as rich centres a
    table's title and caption."""
    text = text.rstrip()
    left = (width - len(text)) // 2
    return " " * left + text + " " * (width - len(text) - left)


def _plain_table(table: TextTable, columns: list[int], title: str, width: int) -> str | None:
    """The ``columns`` of a table as rich prints them (:func:`_rich`, without styles) on a
    console ``width`` columns wide, or None when the layout is not the simple one."""
    least = _widths(table)
    heads = [_wrap(table.header[c], least[c]).split("\n") for c in columns]
    cells = [[row[c] for c in columns] for row in table.rows]
    texts = [*(h for head in heads for h in head), *(x for row in cells for x in row)]
    if not all(_one_cell(t) for t in texts):
        return None
    widths = []
    for n, c in enumerate(columns):
        longest = max((len(row[n]) for row in cells), default=0)
        widths.append(max(least[c], longest, *(len(h) for h in heads[n])))
    inner = sum(w + 3 for w in widths) + 1  # each column padded by one space either side
    if not columns or inner > width:
        return None
    notes = [t for t in (title, table.caption) if t]
    if any(len(t) > inner or not _one_cell(t) for t in notes):
        return None
    right = [c not in table.text_columns for c in columns]  # numbers: right-aligned

    def line(texts: Sequence[str], edge: str) -> str:
        """One line of cells between ``edge`` characters."""
        parts = [
            f" {t.rstrip().rjust(w)} " if r else f" {t.ljust(w)} "
            for t, w, r in zip(texts, widths, right, strict=True)
        ]
        return edge + edge.join(parts) + edge

    def rule(ends: str, fill: str) -> str:
        """A horizontal rule: ``ends`` is left, crossing, right."""
        return ends[0] + ends[1].join(fill * (w + 2) for w in widths) + ends[2]

    out = [_centred(title, inner)] if title else []
    out.append(rule("┏┳┓", "━"))
    height = max(len(h) for h in heads)
    padded = [[""] * (height - len(h)) + h for h in heads]  # headers aligned at the bottom
    out.extend(line([h[i] for h in padded], "┃") for i in range(height))
    out.append(rule("┡╇┩", "━"))
    out.extend(line(row, "│") for row in cells)
    out.append(rule("└┴┘", "─"))
    if table.caption:
        out.append(_centred(table.caption, inner))
    return "\n".join(out) + "\n"


def plain_text(blocks: Iterable[TextTable | str | None], width: int) -> str | None:
    """What :func:`render` prints on a plain console (:func:`plain_console`) ``width`` columns
    wide, made without rich; None when a block needs rich's layout (a table wider than the
    console, a cell or title that would wrap, a character that is not one column wide).

    Parameters
    ----------
    blocks
        Tables and note lines, as for :func:`render`.
    width
        The console's width in columns.

    Returns
    -------
    str or None
        The text, every line ended by a newline; None: print through rich.
    """
    prints = _plain_prints(blocks, width)
    return None if prints is None else "".join(prints)


def _plain_prints(blocks: Iterable[TextTable | str | None], width: int) -> list[str] | None:
    """:func:`plain_text` as the texts of rich's print calls (one per table part and note,
    each of which rich writes and flushes on its own), or None."""
    out = []
    for block in blocks:
        if isinstance(block, TextTable):
            for title, cols in _titled_parts(block, width):
                text = _plain_table(block, cols, title, width)
                if text is None:
                    return None
                out.append(text)
        elif block:
            note = str(block)
            if len(note) > width or not _one_cell(note):
                return None
            out.append(note + "\n")
    return out


_Part = tuple["TextTable | None", list[int], str]
"""A print of :func:`render` that needs rich: a table's part (table, columns, title) or a note
(None, [], the note)."""


def _plain_parts(blocks: Iterable[TextTable | str | None], width: int) -> list[str | _Part]:
    """The prints of :func:`render` on a plain console (:func:`plain_console`) ``width``
    columns wide, each as its plain text (:func:`_plain_table`) where the layout is the simple
    one, else as what rich prints (:func:`_render_part`): rich lays out and writes every table
    part and note on its own, so a large table (a long chain's mode shapes) takes the plain
    path whatever its neighbours need (a cell that wraps, the width of the console)."""
    out: list[str | _Part] = []
    for block in blocks:
        if isinstance(block, TextTable):
            for title, cols in _titled_parts(block, width):
                text = _plain_table(block, cols, title, width)
                out.append(text if text is not None else (block, cols, title))
        elif block:
            note = str(block)
            if len(note) <= width and _one_cell(note):
                out.append(note + "\n")
            else:
                out.append((None, [], note))
    return out


def _render_part(part: _Part, con: Console) -> None:
    """Print one part of :func:`_plain_parts` that needs rich, as :func:`render` prints it."""
    from rich.text import Text

    table, columns, title = part
    if table is not None:
        con.print(_rich(table, columns, title))
    else:  # a note
        con.print(Text(title), soft_wrap=False)


# ---- the output of a command ------------------------------------------------------------------
class Output:
    """The ``--format``, ``-o/--output`` and ``--force`` of a command.

    Parameters
    ----------
    fmt : str
        ``table`` (for people), ``csv`` or ``json``.
    path : str or None
        The output file; None or ``-``: standard output.
    force : bool
        Whether an existing file may be replaced.

    Raises
    ------
    InputError
        On an unknown format, naming ``--format`` and the value.

    Examples
    --------
    >>> Output("json", "-").path is None
    True
    >>> Output("xml")
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: --format = "xml": expected one of table, csv, json
    """

    def __init__(self, fmt: str = "table", path: str | None = None, force: bool = False) -> None:
        if fmt not in FORMATS:
            raise InputError(f"expected one of {', '.join(FORMATS)}", key="--format", value=fmt)
        self.fmt = fmt
        self.path = None if path in (None, "-") else path
        self.force = force

    @property
    def for_people(self) -> bool:
        """Whether the output is a table for people (rather than CSV or JSON data)."""
        return self.fmt == "table"

    def check(self) -> None:
        """Refuse an output file crankdyn cannot write (an existing file without --force, a
        folder, a dangling link, a missing or unwritable folder:
        :func:`crankdyn.io.output.check_writable`) before any work is done;
        :func:`output_options` calls it before the command runs.

        Raises
        ------
        InputError
            On a target that cannot be written, naming the file and the reason.
        """
        if self.path is not None:
            check_writable(self.path, force=self.force, option="--force")

    def say_warnings(self, *sources: Any) -> list[PlausibilityWarning]:
        """Print the plausibility warnings of ``sources`` (:func:`warnings_of`) on standard
        error, one ``crankdyn: warning: ...`` line each (the writer's own path, also for the
        outputs written a piece at a time).

        Parameters
        ----------
        *sources
            Results, warnings, or lists of either.

        Returns
        -------
        list of PlausibilityWarning
            The warnings printed, each once.
        """
        found = warnings_of(*sources)
        for w in found:
            warn(w.message)
        return found

    def write(
        self,
        *,
        blocks: Sequence[TextTable | str | None] = (),
        json_data: Any = None,
        csv_text: str | None = None,
        what: str = "this command",
        warnings: Any = (),
    ) -> None:
        """Write the result: ``blocks`` (tables and note lines) for ``table``, ``json_data``
        (a dict or a Result) for ``json``, ``csv_text`` (default: the first table's rows) for
        ``csv``; to a file atomically, never over one that appeared meanwhile, the path written
        said on stderr (:func:`crankdyn.io.output.write_text`). The plausibility warnings of
        ``json_data`` (a Result) and of ``warnings`` (results or warnings, :func:`warnings_of`)
        are printed on standard error and listed in the JSON (``input_warnings`` for the
        values of the input files, ``warnings`` for the analyses' own).

        Parameters
        ----------
        blocks
            Tables and note lines, shown for ``table`` (:func:`render`).
        json_data
            The data for ``json``: a result, or a dict (:func:`jsonable`); None: the command
            has no JSON output.
        csv_text
            The text for ``csv``; default the first table's rows (:meth:`TextTable.csv_text`).
        what
            The command, named when a format is missing.
        warnings
            Further sources of plausibility warnings (:func:`warnings_of`).

        Raises
        ------
        InputError
            When the format asked for has no output (no JSON data; no CSV text and no table),
            naming ``--format`` and the format, or when the file cannot be written.
        """
        if self.fmt == "json" and json_data is None:
            raise InputError(f"{what} has no JSON output", key="--format", value="json")
        tables = [b for b in blocks if isinstance(b, TextTable)]
        if self.fmt == "csv" and csv_text is None and not tables:
            raise InputError(f"{what} has no CSV output", key="--format", value="csv")
        # after the checks: an error stays the one line
        found = self.say_warnings(json_data if isinstance(json_data, Result) else None, warnings)
        blocks = printable_blocks(blocks)  # no control character reaches the terminal
        if self.fmt == "json":
            data = jsonable(json_data)
            if found and isinstance(data, dict):
                for key, items in warnings_dict(found).items():  # input_warnings, warnings
                    listed = {w.get("message") for w in data.get(key, ())}
                    data[key] = list(data.get(key, ())) + [
                        w for w in items if w["message"] not in listed
                    ]
            text = json_text(data)
        elif self.fmt == "csv":
            text = csv_text if csv_text is not None else tables[0].csv_text()
        elif self.path is None:
            stdout = getattr(sys.stdout, "rich_proxied_file", sys.stdout)
            if not plain_console(stdout):
                render(blocks, console())
                return
            for part in _plain_parts(blocks, stdout_width()):  # as rich writes them
                if isinstance(part, str):  # each print one write, flushed
                    stdout.write(part)
                    stdout.flush()
                else:  # a part that needs rich's layout (a cell that wraps)
                    _render_part(part, console())
            return
        else:
            buffer = io.StringIO()
            if not plain_console(buffer):  # the shared console's settings
                render(blocks, console(file=buffer, width=FILE_WIDTH))
            else:
                for part in _plain_parts(blocks, FILE_WIDTH):
                    if isinstance(part, str):
                        buffer.write(part)
                    else:
                        _render_part(part, console(file=buffer, width=FILE_WIDTH))
            text = buffer.getvalue()
        if self.path is not None:
            written = write_text(self.path, text, force=self.force)
            click.echo(f"wrote {written}", err=True)
        else:
            click.echo(text, nl=False)


def output_options(f: F) -> F:
    """``--format``, ``-o/--output FILE`` and ``--force`` (the command's ``fmt``,
    ``output_path`` and ``force``; :class:`Output` holds them). The file is checked before the
    command's work (:meth:`Output.check` through :func:`crankdyn.cli.common.before_work`).

    Parameters
    ----------
    f
        The command callback.

    Returns
    -------
    callable
        ``f`` with the three options and the check of the output file.
    """

    f = before_work(
        lambda kw: Output(
            kw.get("fmt", "table"), kw.get("output_path"), bool(kw.get("force"))
        ).check()
    )(f)
    f = click.option("--force", is_flag=True, help="Overwrite an existing output file or folder.")(
        f
    )
    f = click.option(
        "-o",
        "--output",
        "output_path",
        default=None,
        metavar="FILE",
        help="Write to FILE (atomically) instead of standard output.",
    )(f)
    return click.option(
        "--format",
        "fmt",
        type=click.Choice(FORMATS),
        default="table",
        show_default=True,
        help="Output format: a table for people, CSV or JSON (SI units, the unit in the key).",
    )(f)


def path_suffix(path: str | None) -> str:
    """The suffix of ``path`` in lower case (``.csv``), or "" for none or no path.

    Parameters
    ----------
    path
        A file name, or None.

    Returns
    -------
    str
        The suffix with its dot, in lower case.

    Examples
    --------
    >>> path_suffix("Run.JSON"), path_suffix(None)
    ('.json', '')
    """
    return Path(path).suffix.lower() if path else ""
