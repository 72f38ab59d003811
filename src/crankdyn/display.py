"""Numbers for people: engineering units, sensible digits, round-off shown as 0; the one formatter
of every front end (the terminal tables of the command line, the HTML report, the notebook views,
the messages of the plausibility warnings). Files for machines (JSON, CSV) keep SI values at
full precision.

- :func:`format_value`: (text, display unit) of one value: ``1.89441e6 Pa`` reads
  ``("1.8944", "MPa")``, ``130733 N`` reads ``("130.73", "kN")``; the unit follows the
  magnitude the value is shown beside (``reference``, e.g. its column's largest value) and
  round-off next to it reads ``0``, never ``1.393e-14``.
- :func:`quantity`: the same as one string, ``"1.8944 MPa"``; :func:`number`: the digits alone,
  in the value's own unit (``12346``, not ``1.235e+04``).
- :func:`column_text`: a column of a table: one unit for all its cells, and either one number of
  decimals for all (the digits line up: the terminal tables) or ``significant`` digits in each
  cell (``aligned=False``: tables whose values span decades, e.g. the report's).
- :func:`engineering_unit`: the prefixed unit that puts a magnitude between 1 and 1000;
  :func:`unit_label`: a header, ``"Stiffness (MN·m/rad)"``.
- :func:`clean`: a float without representation artefacts (``6000.000000000001`` -> ``6000.0``)
  for grid values written to JSON.
- HTML views for notebooks: :func:`html_table`, :func:`engine_html`, :func:`torsion_model_html`
  (the mass-elastic system as the report shows it, :func:`mass_elastic_tables`),
  :func:`mechanism_html`.
- User text in every output: :func:`printable` (control characters shown as their escapes,
  ``\x1b``, ``\n``: the terminal, figures), :func:`html_text` (the same, HTML-escaped: the
  reports, the notebook views) and :func:`csv_text` (CSV fields quoted as RFC 4180 requires,
  control characters escaped: every CSV file crankdyn writes). No control character of a name
  reaches a terminal, an HTML page, a PDF or a CSV file.

Everything here is pure (no I/O, no boundary imports), importable from every layer.
"""

from __future__ import annotations

import html
import math
import unicodedata
from collections.abc import Callable, Iterable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from crankdyn.engine.model import Engine
    from crankdyn.linkage.planar import Mechanism
    from crankdyn.torsion.model import TorsionModel

__all__ = [
    "CLASS_UNITS",
    "ROUNDOFF",
    "SIGNIFICANT",
    "clean",
    "column_text",
    "csv_text",
    "engine_html",
    "engineering_unit",
    "format_value",
    "html_table",
    "html_text",
    "mass_elastic_tables",
    "mechanism_html",
    "number",
    "printable",
    "quantity",
    "shaft_kind",
    "torsion_model_html",
    "unit_label",
]


def _escape(ch: str) -> str:
    r"""A control character as its Python escape (``\x1b``, ``\n``), else the character."""
    if unicodedata.category(ch) == "Cc" or ch in "\u2028\u2029":
        return repr(ch)[1:-1]
    return ch


def printable(text: str) -> str:
    r"""User text with every control character (C0, DEL, C1; line and paragraph separators)
    shown as its escape: ESC as ``\x1b``, a line break as ``\n``. A terminal title, a table
    cell, a figure's label is then one line of what was typed, and no escape sequence
    reaches the terminal (colours, cursor moves, a rewritten title).

    Parameters
    ----------
    text
        The text (a name, a note, a file name).

    Returns
    -------
    str
        The text, its control characters escaped; unchanged when it has none.

    Examples
    --------
    >>> printable("pump \x1b[31mred\x07"), printable("a\r\nb"), printable("Müller 1")
    ('pump \\x1b[31mred\\x07', 'a\\r\\nb', 'Müller 1')
    """
    text = str(text)
    if text.isprintable():
        return text
    return "".join(_escape(ch) for ch in text)


def html_text(text: object) -> str:
    r"""User text for HTML: control characters escaped (:func:`printable`), then ``&``, ``<``,
    ``>`` and quotes as entities (:func:`html.escape`).

    Parameters
    ----------
    text
        The text (any object, as its ``str``).

    Returns
    -------
    str
        Text safe in HTML content and quoted attribute values, without control characters.

    Examples
    --------
    >>> html_text("<b>\x1b[1m</b> & co")
    '&lt;b&gt;\\x1b[1m&lt;/b&gt; &amp; co'
    """
    return html.escape(printable(str(text)))


def _csv_field(value: object) -> str:
    r"""One CSV field (RFC 4180, sec. 2): quoted, its quotes doubled, when it holds a comma, a
    quote or (none are left) a line break; also when it starts with ``#`` or white space or
    ends with white space, which crankdyn's readers take for a comment or strip."""
    field = "" if value is None else printable(str(value))
    if any(ch in field for ch in ',"\r\n') or field[:1] == "#" or field != field.strip():
        return '"' + field.replace('"', '""') + '"'
    return field


def csv_text(rows: Iterable[Iterable[object]]) -> str:
    r"""Rows as CSV text, every field as RFC 4180 (sec. 2) requires: a field holding a comma or
    a quote is quoted and its quotes doubled; control characters (a name's CR or LF, which
    would split its row) are escaped first (:func:`printable`), so every row is one line.
    Lines end in ``\n``; None is an empty field; numbers are written as ``str`` writes them.

    Parameters
    ----------
    rows
        The rows (the header first, if any), each an iterable of fields.

    Returns
    -------
    str
        The CSV text, each row ended by a newline.

    Examples
    --------
    >>> print(csv_text([["name", "inertia"], ["disc, 1", 2.5], ['say "hi"\r', None]]), end="")
    name,inertia
    "disc, 1",2.5
    "say ""hi""\r",
    """
    return "".join(",".join(_csv_field(v) for v in row) + "\n" for row in rows)


SIGNIFICANT = 5
"""Significant digits of a figure (of the largest value of a column with aligned decimals)."""

ROUNDOFF = 1e-9
"""A value below this fraction of the reference magnitude of its quantity is round-off (the
solvers work to about 1e-12 relative; 1e-9 leaves margin) and reads 0."""

# unit -> ladder of (display unit, factor from the unit), smallest first
_LADDERS: dict[str, tuple[tuple[str, float], ...]] = {
    "N": (("N", 1.0), ("kN", 1e-3), ("MN", 1e-6)),
    "N·m": (("N·m", 1.0), ("kN·m", 1e-3), ("MN·m", 1e-6)),
    "Pa": (("Pa", 1.0), ("kPa", 1e-3), ("MPa", 1e-6), ("GPa", 1e-9)),
    "W": (("W", 1.0), ("kW", 1e-3), ("MW", 1e-6)),
    "kW": (("W", 1e3), ("kW", 1.0), ("MW", 1e-3)),
    "J": (("J", 1.0), ("kJ", 1e-3), ("MJ", 1e-6)),
    "Hz": (("Hz", 1.0), ("kHz", 1e-3)),
    "m": (("µm", 1e6), ("mm", 1e3), ("m", 1.0)),
    "m³": (("cm³", 1e6), ("L", 1e3), ("m³", 1.0)),
    "rad": (("µrad", 1e6), ("mrad", 1e3), ("rad", 1.0)),
    "N·m/rad": (("N·m/rad", 1.0), ("kN·m/rad", 1e-3), ("MN·m/rad", 1e-6)),
    "N·m·s/rad": (("N·m·s/rad", 1.0), ("kN·m·s/rad", 1e-3)),
    "N·m²": (("N·m²", 1.0), ("kN·m²", 1e-3)),
}
_ALIASES = {"Nm": "N·m", "N*m": "N·m", "N m": "N·m", "Nm/rad": "N·m/rad", "Nms/rad": "N·m·s/rad"}
# display units that may be asked for by name (format_value's ``to``): factor from SI
_FACTORS = {name: factor for ladder in _LADDERS.values() for name, factor in ladder}
_FACTORS.update({"bar": 1e-5, "deg": 1.0, "rpm": 1.0})


def _canonical(unit: str) -> str:
    return _ALIASES.get(unit, unit)


def engineering_unit(magnitude: float, unit: str) -> tuple[str, float]:
    """The prefixed unit that puts a magnitude between 1 and 1000.

    Parameters
    ----------
    magnitude : float
        The largest magnitude to show, in ``unit``.
    unit : str
        Its SI unit (``"Pa"``, ``"N·m"``, ``"m"``...).

    Returns
    -------
    display_unit : str
        The prefixed unit; ``unit`` itself when it has no prefixes (rpm, deg, m/s, kg·m²) or
        for zero.
    factor : float
        Multiply a value in ``unit`` by it to get it in ``display_unit``.

    Examples
    --------
    >>> engineering_unit(1.89441e6, "Pa")
    ('MPa', 1e-06)
    >>> engineering_unit(0.076, "m")
    ('mm', 1000.0)
    """
    unit = _canonical(unit)
    ladder = _LADDERS.get(unit)
    if ladder is None or not (math.isfinite(magnitude) and magnitude > 0.0):
        return unit, 1.0
    chosen = ladder[0]
    for name, factor in ladder:
        if magnitude * factor >= 1.0 - 1e-12:
            chosen = (name, factor)
    return chosen


def _decimals(magnitude: float, significant: int = SIGNIFICANT) -> int:
    if not (math.isfinite(magnitude) and magnitude > 0.0):
        return 0
    return max(0, significant - 1 - math.floor(math.log10(magnitude) + 1e-12))


def _figure(x: float, significant: int) -> str:
    """``significant`` digits without trailing zeros (``0.05``, not ``0.0500``); positional
    notation for everyday magnitudes (1e-4 to 1e9; integer digits are never rounded away:
    ``12346``), an exponent outside them (``3.2e-07``)."""
    if x == 0.0:
        return "0"
    magnitude = abs(x)
    if 1e-4 <= magnitude < 1e9:
        text = f"{x:.{_decimals(magnitude, significant)}f}"
        if "." in text:
            text = text.rstrip("0").rstrip(".")
        return "0" if text in ("-0", "0") else text
    mantissa, _, power = f"{x:.{max(significant - 1, 0)}e}".partition("e")
    if "." in mantissa:
        mantissa = mantissa.rstrip("0").rstrip(".")
    return f"{mantissa}e{power}"


def format_value(
    value: object,
    unit: str = "",
    *,
    reference: float | None = None,
    significant: int = SIGNIFICANT,
    to: str | None = None,
) -> tuple[str, str]:
    """(text, display unit) of one figure.

    Parameters
    ----------
    value : object
        The value, SI in ``unit``; None, NaN and inf read ``-``, booleans yes/no, integers as
        they are, text as it is.
    unit : str
        Its SI unit (``"Pa"``, ``"N"``, ``"N·m"``, ``"W"``, ``"J"``, ``"m"``, ``"Hz"``,
        ``"N·m/rad"``...); units without prefixes (``"rpm"``, ``"kg·m²"``) are kept.
    reference : float or None
        The magnitude the value is shown beside (same unit), e.g. the largest value of its
        column: the display unit is chosen for it, and a value below :data:`ROUNDOFF` x
        ``reference`` is round-off and reads ``0``.
    significant : int
        Significant digits (>= 1); default :data:`SIGNIFICANT`.
    to : str or None
        A display unit to use instead of the automatic choice (e.g. ``"bar"``, ``"kPa"``).

    Returns
    -------
    text : str
        The digits in the display unit.
    display_unit : str
        The unit the text is in.

    Raises
    ------
    ValueError
        If ``to`` is not a known display unit (a programming error).

    Examples
    --------
    >>> format_value(1.89441e6, "Pa")
    ('1.8944', 'MPa')
    >>> format_value(1.393e-14, "N", reference=130733.0)
    ('0', 'kN')
    """
    if value is None:
        return "-", unit
    if isinstance(value, (bool, np.bool_)):
        return ("yes" if value else "no"), unit
    if isinstance(value, (int, np.integer)):
        return str(int(value)), unit
    if not isinstance(value, (float, np.floating)):
        return str(value), unit
    v = float(value)
    if not math.isfinite(v):
        return "-", unit
    if to is not None:
        if to not in _FACTORS:
            raise ValueError(f"unknown display unit {to!r}")
        shown, factor = to, _FACTORS[to]
    else:
        ref = abs(float(reference)) if reference else 0.0
        shown, factor = engineering_unit(ref if ref > 0.0 else abs(v), unit)
    if v == 0.0 or (reference and abs(v) <= ROUNDOFF * abs(float(reference))):
        return "0", shown
    return _figure(v * factor, significant), shown


def quantity(
    value: object,
    unit: str = "",
    significant: int = SIGNIFICANT,
    *,
    reference: float | None = None,
    to: str | None = None,
) -> str:
    """An SI value with its engineering unit as one string.

    Parameters
    ----------
    value : object
        The value, SI in ``unit`` (as :func:`format_value`).
    unit : str
        Its SI unit.
    significant : int
        Significant digits; default :data:`SIGNIFICANT`.
    reference : float or None
        The magnitude the value is shown beside (as :func:`format_value`).
    to : str or None
        A display unit to use instead of the automatic choice.

    Returns
    -------
    str
        Digits and display unit; ``"-"`` for no value.

    Examples
    --------
    >>> quantity(1.89441e6, "Pa")
    '1.8944 MPa'
    >>> quantity(2.2e6, "Pa", to="bar")
    '22 bar'
    """
    text, shown = format_value(value, unit, reference=reference, significant=significant, to=to)
    return text if text == "-" else f"{text} {shown}".rstrip()


def number(value: object, significant: int = SIGNIFICANT, *, reference: float | None = None) -> str:
    """A value with ``significant`` digits in its own unit (no prefix), as people write numbers.

    Parameters
    ----------
    value : object
        The value (any unit; it is not converted).
    significant : int
        Significant digits; default :data:`SIGNIFICANT`.
    reference : float or None
        The magnitude the value is shown beside: round-off next to it reads ``0``.

    Returns
    -------
    str
        E.g. ``12346``, ``0.05``, ``3.2e-07``.

    Examples
    --------
    >>> number(12345.678), number(0.05), number(3.2e-7)
    ('12346', '0.05', '3.2e-07')
    """
    return format_value(value, "", reference=reference, significant=significant)[0]


def column_text(
    values: Iterable[Any],
    unit: str = "",
    *,
    reference: float | None = None,
    significant: int = SIGNIFICANT,
    aligned: bool = True,
) -> tuple[list[str], str]:
    """The texts of a numeric column in one engineering unit.

    One unit for all cells, from the largest magnitude (or ``reference``, the magnitude the
    values are compared with, when that is larger: a column of round-off next to it reads 0);
    NaN and None read "-". Round-off next to the column's magnitude reads 0.

    Parameters
    ----------
    values : iterable
        The values, SI in ``unit`` (or text, kept as it is).
    unit : str
        Their SI unit.
    reference : float or None
        The magnitude the values are compared with (same unit).
    significant : int
        Significant digits; default :data:`SIGNIFICANT`.
    aligned : bool
        True (default): one number of decimals for every cell (``significant`` digits of the
        largest), so that the digits line up; False: ``significant`` digits in each cell, for
        columns whose values span decades (a small value keeps its digits).

    Returns
    -------
    texts : list of str
        One text per value.
    display_unit : str
        The unit of the texts.

    Examples
    --------
    >>> column_text([1250.0, 20000.0, None], "N")
    (['1.25', '20.00', '-'], 'kN')
    """
    raw = list(values)
    if any(v is None for v in raw):
        raw = [math.nan if v is None else v for v in raw]
    arr = np.asarray(raw)
    if arr.dtype.kind not in "fiu":
        return [str(v) for v in arr.tolist()], unit
    arr = arr.astype(float)
    finite = np.isfinite(arr)
    top = float(np.max(np.abs(arr[finite]))) if finite.any() else 0.0
    if reference is not None and top <= ROUNDOFF * abs(reference):
        top = abs(reference)
    shown, factor = engineering_unit(top, unit)
    limit = ROUNDOFF * max(top, abs(reference or 0.0))
    if not aligned:
        return [
            "-"
            if not ok
            else "0"
            if limit > 0.0 and abs(v) <= limit
            else _figure(v * factor, significant)
            for v, ok in zip(arr.tolist(), finite.tolist(), strict=True)
        ], shown
    scaled_top = top * factor
    decimals = _decimals(scaled_top, significant)
    if scaled_top >= 10 ** (significant + 1):
        decimals = 0
    out = []
    for v, ok in zip(arr.tolist(), finite.tolist(), strict=True):
        if not ok:
            out.append("-")
        elif limit > 0.0 and abs(v) <= limit:
            out.append("0")
        else:
            text = f"{v * factor:.{decimals}f}"
            out.append("0" if float(text) == 0.0 else text)
    # decimals that are zero in every row say nothing: 10, 20, 30 rather than 10.00, 20.00
    while decimals > 0:
        fractional = [s for s in out if "." in s]
        if not fractional or not all(s.endswith("0") for s in fractional):
            break
        out = [s[:-1].rstrip(".") if "." in s else s for s in out]
        decimals -= 1
    return out, shown


def unit_label(label: str, unit: str) -> str:
    """A column header with its unit.

    Parameters
    ----------
    label : str
        The quantity (``"Stiffness"``).
    unit : str
        Its display unit, or ``""``.

    Returns
    -------
    str
        ``"Stiffness (MN·m/rad)"``; the label alone when there is no unit.
    """
    return f"{label} ({unit})" if unit else label


def clean(value: float, digits: int = 12) -> float:
    """A value rounded to ``digits`` significant digits, without representation artefacts.

    Drops the binary representation artefacts of grid arithmetic
    (``1000 + 20 x 250.00000000000003`` -> ``6000.0``). For grid values and other numbers that
    are round by construction, never for computed results.

    Parameters
    ----------
    value : float
        The value (any unit).
    digits : int
        Significant digits kept; default 12.

    Returns
    -------
    float
        The rounded value (NaN, inf and 0 unchanged).

    Examples
    --------
    >>> clean(6000.000000000001)
    6000.0
    """
    x = float(value)
    if x == 0.0 or not math.isfinite(x):
        return x
    return float(f"{x:.{digits}g}")


# ---- notebook views ---------------------------------------------------------------------------
def html_table(
    header: Sequence[object],
    rows: Iterable[Sequence[object]],
    *,
    title: str = "",
    caption: str = "",
) -> str:
    """A small HTML table (every cell escaped; text left, numbers right).

    Parameters
    ----------
    header : sequence
        The column headers.
    rows : iterable of sequences
        The cells of each row (formatted already; shown with ``str``).
    title : str
        A title above the table, or ``""``.
    caption : str
        A note below the table, or ``""``.

    Returns
    -------
    str
        The HTML (a ``<div>``).
    """

    def cell(tag: str, text: object) -> str:
        text = str(text)
        numeric = text.replace(".", "", 1).replace("-", "", 1).replace("e", "").isdigit()
        align = "right" if numeric else "left"
        return f"<{tag} style='text-align:{align}'>{html_text(text)}</{tag}>"

    head = "".join(cell("th", h) for h in header)
    body = "".join("<tr>" + "".join(cell("td", c) for c in row) + "</tr>" for row in rows)
    title_html = f"<strong>{html_text(title)}</strong>" if title else ""
    cap = f"<p>{html_text(caption)}</p>" if caption else ""
    return f"<div>{title_html}<table><tr>{head}</tr>{body}</table>{cap}</div>"


CLASS_UNITS = {
    "kg·m²": "kg·m²",
    "N·m/rad": "MN·m/rad",
    "N·m·s/rad": "kN·m·s/rad",
    "m": "mm",
    "Pa": "GPa",
    "N·m": "kN·m",
    "W": "kW",
}
"""The units of a mass-elastic table, as class societies' forms give them (one unit per
column, whatever the magnitudes: inertia kg·m², stiffness MN·m/rad, lengths mm)."""


def _elastic_table(
    name: str, title: str, columns: Iterable[tuple[str, str | None, Sequence[Any]]], caption: str
) -> tuple[str, str, list[str], list[list[str]], str]:
    """(name, title, header, rows, caption) from (label, SI unit, values) columns: numbers in
    the column's class-form unit (:data:`CLASS_UNITS`, else one engineering unit per column)
    with five significant digits in each cell (the values of a model span decades), None as
    '-'; text columns have unit None; a column given for no row is left out."""
    header: list[str] = []
    cells: list[list[str]] = []
    for label, unit, values in columns:
        if all(v is None for v in values):
            continue  # not given for any row (e.g. shaft diameters of given stiffnesses)
        if unit is None:
            header.append(label)
            cells.append(["-" if v is None else str(v) for v in values])
            continue
        shown = CLASS_UNITS.get(unit)
        if shown is None:
            texts, shown = column_text(values, unit, aligned=False)
        else:
            factor = dict(_LADDERS.get(unit, ((unit, 1.0),)))[shown]
            texts = [
                "-" if v is None or not math.isfinite(float(v)) else _figure(float(v) * factor, 5)
                for v in values
            ]
        header.append(unit_label(label, shown))
        cells.append(texts)
    rows = [list(r) for r in zip(*cells, strict=True)]
    return name, title, header, rows, caption


def shaft_kind(s: Any) -> str:
    """What an elastic connection is.

    Parameters
    ----------
    s : crankdyn.torsion.elements.Shaft
        A shaft of the model.

    Returns
    -------
    str
        A shaft (its role), a coupling (its designation), an elastic gear mesh (its speed
        ratio), or an element of a distributed-mass shaft.
    """
    if getattr(s, "gear", None) is not None:
        return f"elastic gear mesh, speed ratio {s.ratio:.6g}"
    coupling = getattr(s, "coupling", None)
    if coupling is not None:
        return "coupling" + (f" ({coupling.designation})" if coupling.designation else "")
    segment = getattr(s, "segment_of", None)
    if segment is not None:
        return f"element of the distributed shaft {segment[0]} - {segment[1]}"
    return getattr(s, "role", None) or "shaft"


def mass_elastic_tables(
    model: TorsionModel, *, elements: bool = True
) -> list[tuple[str, str, list[str], list[list[str]], str]]:
    """The mass-elastic system of a torsional model as the report and the notebook view show it.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The lumped torsional model.
    elements : bool
        Whether a distributed shaft's elements are listed one by one (True) or as one row of
        the whole shaft (False: its stiffness 1 / sum(1 / k_i), its length the sum; the
        interior element masses left out, their count and inertia in the caption).

    Returns
    -------
    list of (str, str, list of str, list of list of str, str)
        (name, title, header, rows, caption) of the masses (inertia, absolute damping,
        cylinders, role; speed ratio and reflected inertia with gears), the shafts, couplings,
        elastic gear meshes and distributed shafts' elements (stiffness, relative damping,
        loss factor, diameters, length, shear modulus), the couplings' catalogue data, the
        rigid gear meshes (ratio, teeth, sense of rotation), the dampers and the excitation
        sources; numbers in engineering units, the unit in the header.
    """
    tables = [table for build in _ELASTIC_TABLES if (table := build(model)) is not None]
    return tables if elements else [_whole_shafts(model, t) for t in tables]


_Table = tuple[str, str, list[str], list[list[str]], str]


def _whole_shafts(model: TorsionModel, table: _Table) -> _Table:
    """A masses or shafts table with every distributed shaft as one row (see
    :func:`mass_elastic_tables`); other tables as they are."""
    name, title, header, rows, caption = table
    groups: dict[tuple[str, str], list[int]] = {}
    for i, sh in enumerate(model.shafts):
        segment = getattr(sh, "segment_of", None)
        if segment is not None:
            groups.setdefault(tuple(segment), []).append(i)
    if not groups:
        return table
    inner = {n for idx in groups.values() for i in idx for n in model.shafts[i].between}
    inner -= {n for pair in groups for n in pair}
    if name == "torsion_masses":
        kept = [r for r, m in zip(rows, model.masses, strict=True) if m.name not in inner]
        total = sum(m.inertia for m in model.masses if m.name in inner)
        note = (
            f" The {len(inner)} interior element masses of the distributed shafts (together "
            f"{_figure(total, 5)} kg·m²) are not listed."
        )
        return name, title, header, kept, caption + note
    if name != "torsion_shafts":
        return table
    col = {h.split(" (")[0]: k for k, h in enumerate(header)}
    out: list[list[str]] = []
    for i, row in enumerate(rows):
        sh = model.shafts[i]
        segment = getattr(sh, "segment_of", None)
        if segment is None:
            out.append(row)
            continue
        idx = groups[tuple(segment)]
        if i != idx[0]:
            continue
        merged = list(row)
        merged[col["Between"]] = f"{segment[0]} - {segment[1]}"
        if "Kind" in col:
            merged[col["Kind"]] = f"distributed shaft, {len(idx)} elements"
        k = 1.0 / sum(1.0 / model.shafts[j].stiffness for j in idx)
        merged[col["Stiffness k"]] = _figure(k * 1e-6, 5)
        lengths = [getattr(model.shafts[j].geometry, "length", None) for j in idx]
        if "Length" in col and all(x is not None for x in lengths):
            merged[col["Length"]] = _figure(sum(lengths) * 1e3, 5)  # type: ignore[arg-type]
        out.append(merged)
    note = " Every distributed shaft in one row: its stiffness 1/Σ(1/k_i), its whole length."
    return name, title, header, out, caption + note


def _masses_table(model: TorsionModel) -> _Table:
    """The masses: inertia, absolute damping, cylinders, role; with gears the speed ratio and
    the inertia reflected to the reference speed."""
    ratios = np.asarray(model.speed_ratios, dtype=float)
    masses = model.masses
    mass_columns: list[tuple[str, str | None, Sequence[Any]]] = [
        ("No.", None, [str(i) for i in range(1, len(masses) + 1)]),
        ("Mass", None, [m.name for m in masses]),
        ("Moment of inertia J", "kg·m²", [m.inertia for m in masses]),
        ("Absolute damping", "N·m·s/rad", [m.damping for m in masses]),
        ("Cylinders", None, [", ".join(str(c) for c in m.cylinders) or "-" for m in masses]),
    ]
    if any(getattr(m, "role", None) for m in masses):
        mass_columns.append(("Role", None, [getattr(m, "role", None) or "-" for m in masses]))
    geared = bool(model.gears) or bool(np.any(np.abs(np.abs(ratios) - 1.0) > 1e-12))
    if geared:
        mass_columns.append(("Speed ratio to the reference", "", list(ratios)))
        reflected = ratios**2 * np.array([m.inertia for m in masses])
        mass_columns.append(("Inertia reflected to the reference", "kg·m²", list(reflected)))
    segments = sum(1 for s in model.shafts if getattr(s, "segment_of", None) is not None)
    return _elastic_table(
        "torsion_masses",
        "Masses",
        mass_columns,
        f"{len(masses)} masses, numbered from the free end"
        + (
            " (the masses inside a distributed shaft are its lumped elements)." if segments else "."
        ),
    )


def _shafts_table(model: TorsionModel) -> _Table:
    """The shafts, couplings, elastic gear meshes and distributed shafts' elements: stiffness,
    relative damping, loss factor, diameters, length, shear modulus."""
    shafts = model.shafts
    geometry = [s.geometry for s in shafts]
    kinds = [shaft_kind(s) for s in shafts]
    shaft_columns: list[tuple[str, str | None, Sequence[Any]]] = [
        ("No.", None, [str(i) for i in range(1, len(shafts) + 1)]),
        ("Between", None, [s.label for s in shafts]),
        ("Kind", None, kinds),
        ("Stiffness k", "N·m/rad", [s.stiffness for s in shafts]),
        ("Relative damping", "N·m·s/rad", [s.damping for s in shafts]),
        ("Loss factor η", "", [s.loss_factor for s in shafts]),
        ("Outer diameter", "m", [g.outer_diameter if g else None for g in geometry]),
        ("Bore", "m", [g.inner_diameter if g else None for g in geometry]),
        ("Length", "m", [g.length if g else None for g in geometry]),
        ("Shear modulus G", "Pa", [g.shear_modulus if g else None for g in geometry]),
    ]
    if all(k == "shaft" for k in kinds):
        shaft_columns.pop(2)
    segments = sum(1 for s in shafts if getattr(s, "segment_of", None) is not None)
    return _elastic_table(
        "torsion_shafts",
        "Shafts and couplings",
        shaft_columns,
        f"{len(shafts)} elastic connection(s)"
        + (
            "; '-': diameters, length or shear modulus not given (the stiffness was given directly)"
            if any(g is not None for g in geometry)
            else "; the stiffnesses were given directly (no shaft dimensions)"
        )
        + (
            f"; {segments} element(s) of distributed-mass shafts (each shaft divided so "
            "that its own modes are resolved)."
            if segments
            else "."
        ),
    )


def _couplings_table(model: TorsionModel) -> _Table | None:
    """The couplings' catalogue data (DIN 740-2), or None without couplings."""
    couplings = [s for s in model.shafts if s.coupling is not None]
    if not couplings:
        return None
    c = [s.coupling for s in couplings if s.coupling is not None]
    return _elastic_table(
        "torsion_couplings",
        "Elastic couplings",
        [
            ("Between", None, [s.label for s in couplings]),
            ("Designation", None, [x.designation or "-" for x in c]),
            ("C_Tdyn of the model", "N·m/rad", [x.model_stiffness for x in c]),
            ("At mean torque", "N·m", [x.model_torque for x in c]),
            (
                "Stiffness table",
                None,
                [
                    f"{len(x.table_torque)} points"
                    if x.load_dependent and x.table_torque is not None
                    else "-"
                    for x in c
                ],
            ),
            ("Relative damping ψ", "", [x.psi for x in c]),
            ("T_KN", "N·m", [x.nominal_torque for x in c]),
            ("T_Kmax", "N·m", [x.maximum_torque for x in c]),
            *[
                (label, "N·m", values)
                for label, values in (
                    ("T_Kmax1 (normal transients)", [x.maximum_torque_1 for x in c]),
                    ("T_Kmax2 (exceptional transients)", [x.maximum_torque_2 for x in c]),
                )
                if any(v is not None for v in values)
            ],
            ("T_KW", "N·m", [x.vibratory_torque for x in c]),
            ("P_KV", "W", [x.power_loss for x in c]),
        ],
        "Catalogue data (DIN 740-2): a stiffness table makes the forced response take "
        "C_Tdyn at each speed's mean torque; the natural frequencies use the model's "
        "C_Tdyn.",
    )


def _gears_table(model: TorsionModel) -> _Table | None:
    """The rigid and elastic gear meshes (ratio, teeth, sense of rotation), or None."""
    meshes = list(model.gears) + [s.gear for s in model.shafts if s.gear is not None]
    if not meshes:
        return None
    return _elastic_table(
        "torsion_gears",
        "Gear meshes",
        [
            ("Between", None, [f"{g.between[0]} - {g.between[1]}" for g in meshes]),
            (
                "Kind",
                None,
                [
                    "rigid joint (a line joined to an engine)"
                    if getattr(g, "joint", False)
                    else "gear mesh"
                    for g in meshes
                ],
            ),
            ("Speed ratio n_b / n_a", "", [g.ratio for g in meshes]),
            (
                "Teeth z_a : z_b",
                None,
                [f"{g.teeth[0]} : {g.teeth[1]}" if g.teeth else None for g in meshes],
            ),
            ("Sense of rotation", None, [g.direction for g in meshes]),
            ("Mesh stiffness", "N·m/rad", [g.stiffness for g in meshes]),
        ],
        "Rigid meshes reflect the masses beyond them to the reference speed with the "
        "square of the speed ratio; an elastic mesh is a spring of its mesh stiffness "
        "(listed with the shafts).",
    )


def _dampers_table(model: TorsionModel) -> _Table | None:
    """The dampers the forced response adds, or None."""
    if not model.dampers:
        return None
    d = model.dampers
    return _elastic_table(
        "torsion_dampers",
        "Dampers",
        [
            ("Damper", None, [x.name for x in d]),
            ("On mass", None, [x.at for x in d]),
            ("Ring inertia", "kg·m²", [x.inertia for x in d]),
            ("Stiffness", "N·m/rad", [x.stiffness for x in d]),
            ("Damping", "N·m·s/rad", [x.damping for x in d]),
            ("Loss factor η", "", [x.loss_factor for x in d]),
        ],
        "Added by the forced response (not part of the natural frequencies).",
    )


def _sources_table(model: TorsionModel) -> _Table | None:
    """The excitation sources besides the cylinders, or None."""
    sources = tuple(getattr(model, "sources", ()) or ())
    if not sources:
        return None
    return _elastic_table(
        "torsion_sources",
        "Excitation sources",
        [
            ("Source", None, [x.name for x in sources]),
            ("Kind", None, [getattr(x, "kind", "engine") for x in sources]),
            ("On masses", None, [", ".join(x.mass_names()) for x in sources]),
            ("Excitation and load", None, [x.describe() for x in sources]),
        ],
        "Harmonic torques at orders of their mass's own speed, besides the cylinders' "
        "(crankdyn docs torsion-file).",
    )


_ELASTIC_TABLES: tuple[Callable[[TorsionModel], _Table | None], ...] = (
    _masses_table,
    _shafts_table,
    _couplings_table,
    _gears_table,
    _dampers_table,
    _sources_table,
)
"""The tables of :func:`mass_elastic_tables`, in their order: each gives its table, or None when
the model has nothing of its kind."""


def torsion_model_html(model: TorsionModel) -> str:
    """The mass-elastic system of a torsional model (notebook view).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The lumped torsional model.

    Returns
    -------
    str
        HTML: the report's tables (:func:`mass_elastic_tables`) under a title.
    """
    title = (
        f"{model.name}: {model.mass_count} masses, "
        + ("chain" if model.is_chain else "branched")
        + (", free" if model.is_free else ", grounded")
    )
    out = f"<div><strong>{html_text(title)}</strong></div>"
    for _name, table_title, header, rows, caption in mass_elastic_tables(model):
        out += html_table(header, rows, title=table_title, caption=caption)
    return out


def engine_html(engine: Engine) -> str:
    """The engine's main data and, with a [torsion] section, its mass-elastic system.

    Parameters
    ----------
    engine : crankdyn.engine.model.Engine
        The engine.

    Returns
    -------
    str
        HTML (the notebook view of an engine).
    """
    from crankdyn.constants import DEG, RPM

    g, c = engine.geometry, engine.cylinders
    layout = f"{c.count} {c.layout}" + (
        f", bank angle {c.bank_angle * DEG:g}°" if c.layout == "V" else ""
    )
    rows = [
        ["Cycle", engine.cycle],
        ["Cylinders", layout],
        ["Firing order", "-".join(str(i) for i in c.firing_order)],
        ["Bore x stroke", f"{number(g.bore * 1e3)} x {number(g.nominal_stroke * 1e3)} mm"],
        ["Rod length", f"{quantity(g.rod_length, 'm')} (λ = {g.lam:.4f})"],
        ["Displacement", f"{number(engine.displacement * 1e3, 4)} L"],
    ]
    if getattr(engine, "fuel", None) or getattr(engine, "aspiration", None):
        kind = " ".join(x for x in (engine.aspiration, engine.fuel) if x)
        rows.append(["Engine type", kind])
    if engine.speed is not None:
        rows.append(["Operating speed", f"{number(engine.speed * RPM)} rpm"])
    if engine.masses is not None:
        m = engine.masses
        for label, value in (
            ("Reciprocating mass", m.reciprocating),
            ("Rotating mass", m.rotating),
        ):
            if value is not None:
                rows.append([label, f"{number(value)} kg"])
    pressure = "synthetic" if engine.pressure is None else engine.pressure.source or "given trace"
    rows.append(["Pressure", pressure])
    out = html_table(["", ""], rows, title=engine.name)
    if engine.torsion is not None:
        out += torsion_model_html(engine.torsion)
    return out


def mechanism_html(mech: Mechanism) -> str:
    """A planar mechanism's links (masses, inertias) and joints (notebook view).

    Parameters
    ----------
    mech : crankdyn.linkage.planar.Mechanism
        The mechanism.

    Returns
    -------
    str
        HTML: a table of the links (mass in kg, inertia in kg m^2) and one of the joints.
    """
    links = [
        [link.name, ", ".join(link.points), number(link.mass), number(link.inertia)]
        for link in mech.links
    ]
    joints = [[j.name, j.kind, " - ".join(j.links)] for j in mech.joints]
    out = html_table(
        ["Link", "Points", "Mass (kg)", "Inertia (kg·m²)"],
        links,
        title=f"{mech.name}: {len(mech.links)} links, {len(mech.joints)} joints",
    )
    return out + html_table(["Joint", "Kind", "Between"], joints, title="Joints")
