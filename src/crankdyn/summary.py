"""A result's summary: its key figures, tables, notes, warnings and verdicts, declared once by the
result and rendered by every front end.

Every result class (:class:`crankdyn.results.Result`) gives :meth:`~crankdyn.results.Result.
summary`, a :class:`Summary`. Its parts are declared by the result class, never by a front end:

- **key figures** (:class:`KeyFigure`): every scalar field declared with
  :func:`crankdyn.results.scalar` (key, label and unit from its metadata), and the figures the
  class derives from its arrays or its scalars, declared in its ``FIGURES`` tuple with
  :func:`reduced` (a maximum, minimum or largest magnitude over an axis of an array field, with
  where it occurs: "bearing 3", "at 2165 rpm") or :func:`derived` (a formula of the result);
- **tables** (:class:`SummaryTable`): what the result's ``summary_tables()`` method returns
  (SI values with their columns' keys, labels and units);
- **notes** and **warnings**: the result's ``notes`` field and its plausibility warnings
  (the input warnings among them: values of the input files outside the plausible range of
  their role, :mod:`crankdyn.io.plausibility`);
- **verdicts** (:class:`Verdict`): what the result's ``summary_verdicts()`` returns (a rule
  check, the TVC): check, component, condition, quantity, worst value, limit, margin, passed,
  rule and clause; and the verdict in words (:attr:`Summary.verdict`,
  :func:`verdict_text`): never a clean "passed" while the inputs carry warnings
  ("passed, with 1 input warning").

The command line prints the figures as its summary table, the report lays them out as the
section's key figures, the study keeps them as the columns of its table (by their ``name``), the
JSON has them under their keys and notebooks show them: one declaration, one label, one unit and
one value everywhere (``tests/engine/test_front_ends.py``).

Examples
--------
>>> from dataclasses import dataclass
>>> import numpy as np
>>> from crankdyn.results import Result, array, scalar
>>> @dataclass(frozen=True)
... class Loads(Result):
...     load: np.ndarray = array("load_N", "Load per bearing", "N")
...     speed: float = scalar("speed_rad_s", "Speed", "rad/s")
...     FIGURES = (reduced("load", "max", over="bearing", name="max_load", key="max_load_N",
...                        label="Max bearing load"),)
>>> s = Loads(np.array([3.0e4, 5.5e4, 2.0e4]), 150.0).summary()
>>> [(f.key, f.value, f.where) for f in s.figures]
[('speed_rad_s', 150.0, ''), ('max_load_N', 55000.0, 'bearing 2')]
>>> s.figure("max_load_N").display()
'55 kN (bearing 2)'
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from crankdyn.plausibility import PlausibilityWarning

__all__ = [
    "FigureSpec",
    "KeyFigure",
    "Summary",
    "SummaryColumn",
    "SummaryTable",
    "Verdict",
    "derived",
    "reduced",
    "summary_html",
    "verdict_cells",
    "verdict_of",
    "verdict_status",
    "verdict_text",
    "warnings_dict",
]

REDUCTIONS = ("max", "min", "maxabs")
"""How :func:`reduced` reduces an array: its largest value, its smallest, its largest
magnitude (the value kept is the magnitude)."""

STATUSES = ("pass", "warn", "fail")
"""A key figure's status (None: information)."""


def verdict_text(passed: bool | None, input_warnings: int = 0, undecided: int = 0) -> str | None:
    """The verdict in words, as every front end shows it: ``passed`` or ``FAILED``, with the
    number of input warnings the verdict stands on (values of the input files outside the
    plausible range of their role, :mod:`crankdyn.io.plausibility`) and of undecided rows (rows
    whose worst value lies within its computation's error bound of the limit,
    :attr:`Verdict.undecided`): a verdict on implausible inputs or on a bound that could
    overturn it is never a clean "passed".

    Parameters
    ----------
    passed : bool or None
        Whether every verdict row passed; None without verdict rows.
    input_warnings : int
        How many input warnings the result carries.
    undecided : int
        How many verdict rows are undecided.

    Returns
    -------
    str or None
        The verdict; None without verdict rows.

    Examples
    --------
    >>> verdict_text(True), verdict_text(True, 1), verdict_text(False, 2)
    ('passed', 'passed, with 1 input warning', 'FAILED, with 2 input warnings')
    >>> verdict_text(True, 1, 2)
    'passed, with 1 input warning and 2 undecided rows'
    """
    if passed is None:
        return None
    word = "passed" if passed else "FAILED"
    parts = []
    if input_warnings:
        parts.append(f"{input_warnings} input warning{'s' if input_warnings != 1 else ''}")
    if undecided:
        parts.append(f"{undecided} undecided row{'s' if undecided != 1 else ''}")
    return f"{word}, with {' and '.join(parts)}" if parts else word


def verdict_of(
    verdicts: Sequence[Verdict], warnings: Sequence[PlausibilityWarning] = ()
) -> str | None:
    """The verdict in words of verdict rows (:func:`verdict_text`): passed when every row
    passed, with the input warnings among ``warnings`` and the undecided rows counted; the one
    place every result and front end takes it from.

    Parameters
    ----------
    verdicts : sequence of Verdict
        The rows.
    warnings : sequence of PlausibilityWarning
        The result's warnings (its input warnings are counted).

    Returns
    -------
    str or None
        The verdict; None without rows.

    Examples
    --------
    >>> v = Verdict("shaft", "event", "peak", 40e6, 41e6, "Pa", True, "UR M68", error_bound=2e6)
    >>> v.undecided, verdict_of([v])
    (True, 'passed, with 1 undecided row')
    """
    from crankdyn.plausibility import input_warnings

    if not verdicts:
        return None
    passed = all(v.passed for v in verdicts)
    undecided = sum(1 for v in verdicts if v.undecided)
    return verdict_text(passed, len(input_warnings(tuple(warnings))), undecided)


def verdict_status(text: str | None) -> str | None:
    """The status of a verdict in words (:func:`verdict_text`): ``"pass"`` for a clean
    "passed", ``"warn"`` for one with input warnings, ``"fail"`` for a failure.

    Parameters
    ----------
    text : str or None
        The verdict.

    Returns
    -------
    str or None
        The status; None without a verdict.

    Examples
    --------
    >>> verdict_status("passed"), verdict_status("passed, with 1 input warning")
    ('pass', 'warn')
    """
    if text is None:
        return None
    if text == "passed":
        return "pass"
    return "warn" if text.startswith("passed") else "fail"


@dataclass(frozen=True)
class KeyFigure:
    """One key figure of a result, as every front end shows it.

    Parameters
    ----------
    name : str
        The study's name of the figure (``"max_crank_pin_load"``).
    key : str
        The JSON key, with the unit of :attr:`value` in it (``"max_crank_pin_load_N"``).
    label : str
        What it is, for people.
    unit : str
        The unit of :attr:`value` (the unit the key names; ``""`` for numbers and text).
    value : object
        The value (a float, int, bool, text, or a list of floats), in :attr:`unit`.
    reduction : str
        How it was made from the result's data (``"max over throws"``); ``""`` for a figure the
        analysis gives directly.
    where : str
        Where the reduction found it (``"throw 3"``, ``"at 2165 rpm"``), or ``""``.
    status : {"pass", "warn", "fail"} or None
        A verdict carried by the figure, or None (information).
    better : {"min", "max"} or None
        Which way is better (for a study's ranking); None: neither.
    description : str
        A sentence for the study's figure list (default the label).
    check : str
        The key of the plausibility check that judges it (:mod:`crankdyn.plausibility`), or
        ``""``.
    headline : bool
        Whether it is one of the few figures a whole report's summary shows (every figure is
        shown with its own analysis).
    qualifier : str
        What the value stands on, shown after it (``"with 1 input warning"``: a "pass" on
        implausible inputs reads "warn"); ``""`` for nothing.
    """

    name: str
    key: str
    label: str
    unit: str
    value: Any
    reduction: str = ""
    where: str = ""
    status: str | None = None
    better: str | None = None
    description: str = ""
    check: str = ""
    headline: bool = False
    qualifier: str = ""

    def text(self, significant: int = 5) -> tuple[str, str]:
        """(digits, display unit) in engineering units (:func:`crankdyn.display.
        format_value`); a list of numbers shares the unit of its largest.

        Parameters
        ----------
        significant : int
            Significant digits.

        Returns
        -------
        digits : str
            The value (or values, comma-separated).
        unit : str
            The display unit.
        """
        from crankdyn.display import format_value

        value = self.value
        if isinstance(value, (list, tuple, np.ndarray)):
            items = np.asarray(value, dtype=object).ravel().tolist()
            if items and all(_is_number(v) for v in items):
                arr = np.asarray(items, dtype=float)
                finite = arr[np.isfinite(arr)]
                top = float(np.max(np.abs(finite), initial=0.0))
                texts = [
                    format_value(v, self.unit, reference=top, significant=significant)
                    for v in arr.tolist()
                ]
                return ", ".join(t for t, _ in texts), texts[0][1]
            return ", ".join(format_value(v, self.unit)[0] for v in items), self.unit
        return format_value(value, self.unit, significant=significant)

    def display(self, significant: int = 5) -> str:
        """The value with its display unit and where it was found: ``"55 kN (bearing 2)"``.

        Parameters
        ----------
        significant : int
            Significant digits.

        Returns
        -------
        str
            The text.
        """
        digits, unit = self.text(significant)
        out = f"{digits} {unit}".rstrip() if digits != "-" else digits
        out = f"{out} ({self.where})" if self.where else out
        return f"{out}, {self.qualifier}" if self.qualifier else out

    def number(self) -> float | None:
        """The value as a float.

        Returns
        -------
        float or None
            The value; None when it is not a finite number (text, None, NaN).
        """
        if not _is_number(self.value):
            return None
        v = float(self.value)
        return v if math.isfinite(v) else None


def _is_number(v: object) -> bool:
    return isinstance(v, (int, float, np.integer, np.floating)) and not isinstance(
        v, (bool, np.bool_)
    )


@dataclass(frozen=True)
class SummaryColumn:
    """A column of a :class:`SummaryTable`.

    Parameters
    ----------
    key : str
        Its key in the CSV and JSON (the unit in it).
    label : str
        Its header for people.
    unit : str
        The unit of its values (``""`` for numbers and text).
    """

    key: str
    label: str
    unit: str = ""


@dataclass(frozen=True)
class SummaryTable:
    """A table of a result's summary (e.g. the balance by order, the modes' frequencies).

    Parameters
    ----------
    key : str
        Its name (the report's ``data/<key>.csv``, the JSON key).
    title : str
        The heading.
    columns : tuple of SummaryColumn
        The columns.
    rows : tuple of tuple
        The values, in the columns' units (numbers, text or None for none).
    caption : str
        A sentence under the title: what the rows are.
    reference : tuple of float or None
        Per column, the magnitude next to which a value is round-off and shows as 0 (e.g. the
        rotating mass's centrifugal force for free forces), or None for each column's largest.
    """

    key: str
    title: str
    columns: tuple[SummaryColumn, ...]
    rows: tuple[tuple[Any, ...], ...]
    caption: str = ""
    reference: tuple[float | None, ...] | None = None

    def cells(self, aligned: bool = True) -> tuple[list[str], list[list[str]]]:
        """(header, rows) as text: each number column in one engineering unit chosen for its
        largest value (or its reference), text as it is.

        Parameters
        ----------
        aligned : bool
            One number of decimals per column so digits line up (terminal tables), or five
            significant digits per cell (the report).

        Returns
        -------
        header : list of str
            ``label (display unit)`` per column.
        rows : list of list of str
            The cells.
        """
        from crankdyn.display import column_text, unit_label

        header: list[str] = []
        columns: list[list[str]] = []
        for i, col in enumerate(self.columns):
            values = [row[i] for row in self.rows]
            numbers = [v for v in values if v is not None]
            if numbers and all(_is_number(v) for v in numbers):
                ref = self.reference[i] if self.reference is not None else None
                arr = np.array([math.nan if v is None else float(v) for v in values])
                cells, shown = column_text(arr, col.unit, reference=ref, aligned=aligned)
                header.append(unit_label(col.label, shown))
                columns.append(list(cells))
            else:
                header.append(unit_label(col.label, col.unit) if col.unit else col.label)
                columns.append(["-" if v is None else _text(v) for v in values])
        rows = [list(r) for r in zip(*columns, strict=True)] if columns else []
        return header, rows

    def head(self, count: int | None) -> SummaryTable:
        """The table with its first ``count`` rows; the caption says how many more there are.

        Parameters
        ----------
        count : int or None
            The rows kept; None: all.

        Returns
        -------
        SummaryTable
            The table (itself when nothing is left out).
        """
        if count is None or count >= len(self.rows):
            return self
        more = f"Showing the first {count} of {len(self.rows)} rows."
        caption = f"{self.caption} {more}" if self.caption else more
        return replace(self, rows=self.rows[:count], caption=caption)

    def text_columns(self) -> set[int]:
        """The indices of the columns that hold text (left-aligned in tables).

        Returns
        -------
        set of int
            The column indices.
        """
        out = set()
        for i, _col in enumerate(self.columns):
            values = [row[i] for row in self.rows if row[i] is not None]
            if not values or not all(_is_number(v) for v in values):
                out.add(i)
        return out

    def to_dict(self) -> dict[str, Any]:
        """The table as JSON data.

        Returns
        -------
        dict
            ``title`` and ``rows``: one dict per row, {column key: value}.
        """
        from crankdyn.export import jsonable

        keys = [c.key for c in self.columns]
        return {
            "title": self.title,
            "rows": [dict(zip(keys, jsonable(list(row)), strict=True)) for row in self.rows],
        }

    def csv_text(self) -> str:
        """The table as CSV text.

        Returns
        -------
        str
            The column keys as header, the values as numbers (10 significant digits) or text
            (quoted as RFC 4180 requires).
        """
        from crankdyn.display import csv_text

        rows = [["" if v is None else _csv(v) for v in row] for row in self.rows]
        return csv_text([[c.key for c in self.columns], *rows])


def _text(v: object) -> str:
    if isinstance(v, (bool, np.bool_)):
        return "yes" if v else "no"
    return str(v)


def _csv(v: object) -> str:
    if _is_number(v):
        return f"{float(v):.10g}" if isinstance(v, (float, np.floating)) else str(v)
    return _text(v)


@dataclass(frozen=True)
class Verdict:
    """One rule check's verdict on one component in one condition: the worst value of a
    quantity against its limit.

    Parameters
    ----------
    component : str
        The component (``"intermediate shaft"``, ``"coupling C1"``).
    condition : str
        The running condition (``"normal firing"``, ``"misfire cylinder 3"``).
    quantity : str
        What is checked (``"synthesised vibratory shear stress (half range)"``).
    worst : float
        The worst value found (in ``unit``); NaN when nothing was evaluated.
    limit : float
        The limit there (in ``unit``); NaN where none applies.
    unit : str
        The unit of worst and limit (SI: Pa, N·m, W, rad/s², rad, or ``""``).
    passed : bool
        Whether the check passed.
    source : str
        The rule with its edition (``"IACS UR M68 (Aug 2014 text)"``) or the maker's document
        the limit comes from, and how the limit was found.
    clause : str
        The clause (``"M68.4"``); ``""`` where the source has none.
    speed : float or None
        The speed (rad/s) of the worst value, or None.
    note : str
        Why (a barred range not permitted: widened by the tachometer tolerance beyond 0.8 n_0).
    margin : float or None
        1 - worst / limit (dimensionless; negative where the limit is exceeded, -inf where a
        check fails without a limit); None: computed from worst and limit.
    kind : str
        What the row checks, whatever its range (the worst misfiring cylinder is chosen per
        component and kind); not exported.
    error_bound : float
        A bound on the error of ``worst`` from the way it was computed (in ``unit``; e.g. the
        modal truncation's of a transient event, :mod:`crankdyn.torsion.integrator`); 0: none
        stated. A row whose worst value lies within it of the limit is :attr:`undecided`.

    Examples
    --------
    >>> from crankdyn.constants import RPM
    >>> v = Verdict("intermediate shaft", "normal firing", "shear stress", 30e6, 40e6, "Pa",
    ...             True, "IACS UR M68", "M68.4", speed=300 / RPM)
    >>> v.margin, v.to_dict()["speed_rpm"]
    (0.25, 300.0)
    """

    component: str
    condition: str
    quantity: str
    worst: float
    limit: float
    unit: str
    passed: bool
    source: str
    clause: str = ""
    speed: float | None = None
    note: str = ""
    margin: float = None  # type: ignore[assignment]  # computed in __post_init__ when None
    kind: str = field(default="", compare=False)
    error_bound: float = 0.0

    def __post_init__(self) -> None:
        if self.margin is None:
            margin = math.nan
            if math.isfinite(self.limit) and self.limit != 0.0 and math.isfinite(self.worst):
                margin = 1.0 - self.worst / self.limit
            object.__setattr__(self, "margin", margin)

    @property
    def undecided(self) -> bool:
        """Whether the error bound could overturn the row: its worst value lies within
        ``error_bound`` of the limit (a row that passed could fail, or one that failed pass)."""
        return (
            self.error_bound > 0.0
            and math.isfinite(self.worst)
            and math.isfinite(self.limit)
            and abs(self.worst - self.limit) <= self.error_bound
        )

    @property
    def rule(self) -> str:
        """The source and clause as one text."""
        return f"{self.source}, {self.clause}" if self.clause else self.source

    def to_dict(self) -> dict[str, Any]:
        """The verdict as JSON data.

        Returns
        -------
        dict
            Every field (SI, the speed in rpm under ``speed_rpm``; NaN as None).
        """
        from crankdyn.constants import RPM

        def number(x: float) -> float | None:
            return float(x) if math.isfinite(x) else None

        return {
            "component": self.component,
            "condition": self.condition,
            "quantity": self.quantity,
            "worst": number(self.worst),
            "limit": number(self.limit),
            "unit": self.unit,
            "margin": number(self.margin),
            "passed": bool(self.passed),
            "source": self.source,
            "clause": self.clause,
            "speed_rpm": None if self.speed is None else round(self.speed * RPM, 9),
            "note": self.note or None,
            **({"error_bound": self.error_bound} if self.error_bound > 0.0 else {}),
            **({"undecided": True} if self.undecided else {}),
        }


@dataclass(frozen=True)
class Summary:
    """What a result says about itself (module docstring).

    Parameters
    ----------
    title : str
        The result's title.
    figures : tuple of KeyFigure
        The key figures, in declaration order.
    tables : tuple of SummaryTable
        The tables.
    notes : tuple of str
        Remarks (what was assumed, what was left out).
    warnings : tuple of PlausibilityWarning
        Inputs that are legal but implausible.
    verdicts : tuple of Verdict
        Rule checks' verdicts.
    """

    title: str
    figures: tuple[KeyFigure, ...] = ()
    tables: tuple[SummaryTable, ...] = ()
    notes: tuple[str, ...] = ()
    warnings: tuple[PlausibilityWarning, ...] = field(default=())
    verdicts: tuple[Verdict, ...] = ()

    def figure(self, key: str) -> KeyFigure:
        """The key figure with this key (or study name).

        Parameters
        ----------
        key : str
            The figure's key or name.

        Returns
        -------
        KeyFigure
            The figure.

        Raises
        ------
        KeyError
            If the summary has none.
        """
        for f in self.figures:
            if key in (f.key, f.name):
                return f
        raise KeyError(key)

    def rows(self) -> list[tuple[str, str, str]]:
        """The figures as a Quantity / Value / Unit table.

        Returns
        -------
        list of (str, str, str)
            (label, value with where it was found and what it stands on, display unit) of
            every figure.
        """
        out = []
        for f in self.figures:
            digits, unit = f.text()
            shown = f"{digits} ({f.where})" if f.where else digits
            out.append((f.label, f"{shown}, {f.qualifier}" if f.qualifier else shown, unit))
        return out

    @property
    def passed(self) -> bool | None:
        """Whether every verdict passed; None without verdicts."""
        if not self.verdicts:
            return None
        return all(v.passed for v in self.verdicts)

    @property
    def input_warnings(self) -> tuple[PlausibilityWarning, ...]:
        """The input warnings among :attr:`warnings` (values of the input files outside the
        plausible range of their role)."""
        from crankdyn.plausibility import input_warnings

        return input_warnings(self.warnings)

    @property
    def verdict(self) -> str | None:
        """The verdict in words (:func:`verdict_text`): ``"passed"``, ``"passed, with 1 input
        warning"``, ``"FAILED"``...; None without verdicts."""
        return verdict_of(self.verdicts, self.warnings)

    def to_dict(self) -> dict[str, Any]:
        """The summary as JSON data.

        Returns
        -------
        dict
            ``key_figures`` {key: value}, ``where`` {key: text} of the reduced ones,
            ``tables``, ``notes``, ``input_warnings`` (listed first), ``warnings`` (the
            analyses' own), ``verdicts``, ``passed`` and ``verdict`` (in words).
        """
        from crankdyn.export import jsonable

        out: dict[str, Any] = {
            "title": self.title,
            "key_figures": {f.key: jsonable(f.value) for f in self.figures},
        }
        where = {f.key: f.where for f in self.figures if f.where}
        if where:
            out["where"] = where
        if self.tables:
            out["tables"] = {t.key: t.to_dict() for t in self.tables}
        if self.notes:
            out["notes"] = list(self.notes)
        out.update(warnings_dict(self.warnings))
        if self.verdicts:
            out["verdicts"] = [v.to_dict() for v in self.verdicts]
            out["passed"] = self.passed
            out["verdict"] = self.verdict
        return out


def warnings_dict(warnings: Sequence[PlausibilityWarning]) -> dict[str, list[dict[str, Any]]]:
    """Warnings as JSON lists: ``input_warnings`` (values of the input files outside the
    plausible range of their role) and ``warnings`` (the analyses' plausibility warnings),
    each present only when it has any.

    Parameters
    ----------
    warnings : sequence of PlausibilityWarning
        The warnings.

    Returns
    -------
    dict
        ``{"input_warnings": [...], "warnings": [...]}``, without empty lists.
    """
    from crankdyn.plausibility import InputWarning

    out: dict[str, list[dict[str, Any]]] = {}
    given = [w.to_dict() for w in warnings if isinstance(w, InputWarning)]
    own = [w.to_dict() for w in warnings if not isinstance(w, InputWarning)]
    if given:
        out["input_warnings"] = given
    if own:
        out["warnings"] = own
    return out


VERDICT_HEADER = (
    "Component",
    "Condition",
    "Quantity",
    "Worst",
    "Limit",
    "Unit",
    "Margin",
    "Speed (rpm)",
    "Verdict",
    "Rule",
)
"""The columns of a verdict table, in every front end."""


def verdict_cells(verdicts: Sequence[Verdict]) -> tuple[list[str], list[list[str]]]:
    """(header, rows) of a verdict table as text: worst and limit in the engineering unit of
    the limit, the margin in %, the speed of the worst value, passed or FAILED, rule and
    clause.

    Parameters
    ----------
    verdicts : sequence of Verdict
        The rows.

    Returns
    -------
    header : list of str
        :data:`VERDICT_HEADER`.
    rows : list of list of str
        The cells.

    Examples
    --------
    >>> v = Verdict("shaft 1", "normal firing", "stress vs tau_C", 30e6, 40e6, "Pa", True,
    ...             "IACS UR M68", "M68.4", speed=80.0)
    >>> verdict_cells([v])[1]
    [['shaft 1', 'normal firing', 'stress vs tau_C', '30', '40', 'MPa', '25 %', '763.94', \
'passed', 'IACS UR M68, M68.4']]
    """
    from crankdyn.constants import RPM
    from crankdyn.display import format_value, number

    rows = []
    for v in verdicts:
        ref = v.limit if math.isfinite(v.limit) else None
        worst, unit = format_value(v.worst, v.unit, reference=ref)
        limit, _ = format_value(v.limit, v.unit, reference=ref)
        margin = v.margin
        rows.append(
            [
                v.component,
                v.condition,
                v.quantity,
                worst,
                limit,
                unit,
                "-" if not math.isfinite(margin) else f"{number(margin * 100.0, 3)} %",
                "-" if v.speed is None else number(v.speed * RPM),
                ("passed" if v.passed else "FAILED") + (" (undecided)" if v.undecided else ""),
                v.rule,
            ]
        )
    return list(VERDICT_HEADER), rows


# ---- declarations of derived figures (class level, static: a study lists them before a case) ----


@dataclass(frozen=True)
class FigureSpec:
    """How a result class makes one of its key figures (the study's registry reads these before
    any case is computed).

    Parameters
    ----------
    name : str
        The study's name.
    key, label, unit : str
        As :class:`KeyFigure`; a reduced figure may take them from its field's metadata.
    value : callable
        ``value(result)`` -> (value in ``unit``, where) or None when the figure does not apply.
    reduction : str
        As :class:`KeyFigure`.
    better : {"min", "max"} or None
        As :class:`KeyFigure`.
    description : str
        As :class:`KeyFigure`.
    field_name : str
        The field a reduced figure reduces (its metadata completes key, label and unit).
    check : str
        The key of the plausibility check that judges it, or ``""``.
    headline : bool
        As :class:`KeyFigure`.
    status : callable or None
        ``status(value)`` -> ``"pass"``, ``"warn"``, ``"fail"`` or None: a judgement the figure
        carries of its own (e.g. critical speeds of major orders in the range: warn).
    unavailable : str
        Why the figure may not apply (``"no shaft of the torsional model has diameters"``): the
        summary leaves it out; a study that asks for it stops with this reason.
    """

    name: str
    key: str
    label: str
    unit: str
    value: Callable[[Any], tuple[Any, str] | None]
    reduction: str = ""
    better: str | None = None
    description: str = ""
    field_name: str = ""
    check: str = ""
    headline: bool = False
    status: Callable[[Any], str | None] | None = None
    unavailable: str = ""

    def make(self, result: Any) -> KeyFigure | None:
        """The key figure of a result.

        Parameters
        ----------
        result : crankdyn.results.Result
            A result of the declaring class.

        Returns
        -------
        KeyFigure or None
            The figure; None when it does not apply.
        """
        got = self.value(result)
        if got is None:
            return None
        value, where = got
        status = self.status(value) if self.status is not None else None
        return KeyFigure(
            self.name,
            self.key,
            self.label,
            self.unit,
            value,
            self.reduction,
            where,
            status or ("pass" if self.check else None),
            self.better,
            self.description or self.label,
            self.check,
            self.headline,
        )


def reduced(
    field_name: str,
    how: str,
    *,
    over: str,
    name: str,
    key: str | None = None,
    label: str | None = None,
    better: str | None = None,
    description: str = "",
    labels: str | Callable[[Any], Sequence[str]] | None = None,
    mask: Callable[[Any], Any] | None = None,
    check: str = "",
    headline: bool = False,
) -> FigureSpec:
    """A key figure that reduces an array field of the result: its largest value (``"max"``),
    smallest (``"min"``) or largest magnitude (``"maxabs"``) over its items, with where.

    Parameters
    ----------
    field_name : str
        The array field (declared with :func:`crankdyn.results.array`, :func:`~crankdyn.
        results.column` or :func:`~crankdyn.results.scalar`); its unit and scale apply.
    how : {"max", "min", "maxabs"}
        The reduction.
    over : str
        What an item is (``"throw"``, ``"bearing"``): where reads ``"throw 3"`` (numbered from
        1), or the item's label from ``labels``.
    name : str
        The study's name.
    key, label : str or None
        Default: the field's key and label.
    better : {"min", "max"} or None
        For studies.
    description : str
        For the study's figure list.
    labels : str or callable or None
        The items' names: a field of the result holding them, or ``labels(result)``; None:
        numbers from 1.
    mask : callable or None
        ``mask(result)`` -> the items that count (a boolean array), or None for all.
    check : str
        The key of the plausibility check that judges the figure, or ``""``.
    headline : bool
        Whether a whole report's summary shows it.

    Returns
    -------
    FigureSpec
        The declaration (for the result class's ``FIGURES``).
    """
    if how not in REDUCTIONS:
        raise ValueError(f"how must be one of {REDUCTIONS}")
    words = {"max": "max", "min": "min", "maxabs": "largest magnitude"}[how]
    plural = over if over.endswith("s") else f"{over}s"

    def value(result: Any) -> tuple[Any, str] | None:
        meta = type(result).__dataclass_fields__[field_name].metadata
        raw = getattr(result, field_name)
        if raw is None:
            return None
        arr = np.asarray(raw, dtype=float).ravel()
        use = np.ones(arr.shape, bool) if mask is None else np.asarray(mask(result), bool)
        use = use & np.isfinite(arr)
        if not use.any():
            return None
        data = np.abs(arr) if how == "maxabs" else arr
        pick = np.where(use, data, -np.inf if how != "min" else np.inf)
        i = int(np.argmin(pick) if how == "min" else np.argmax(pick))
        if labels is None:
            where = f"{over} {i + 1}"
        else:
            names = getattr(result, labels) if isinstance(labels, str) else labels(result)
            where = _where(over, names[i])
        from crankdyn.export import scaled_value

        return scaled_value(float(data[i]), meta["scale"]), where

    return FigureSpec(
        name,
        key or "",
        label or "",
        "",
        value,
        f"{words} over {plural}",
        better,
        description,
        field_name,
        check,
        headline,
    )


def _where(over: str, item: object) -> str:
    if isinstance(item, (float, np.floating)):
        return f"{over} {float(item):g}"
    return f"{over} {item}"


def derived(
    name: str,
    key: str,
    label: str,
    unit: str,
    function: Callable[[Any], Any],
    *,
    reduction: str = "",
    better: str | None = None,
    description: str = "",
    check: str = "",
    headline: bool = False,
    status: Callable[[Any], str | None] | None = None,
    unavailable: str = "",
) -> FigureSpec:
    """A key figure computed from the result by a formula (cite it in the result's docstring).

    Parameters
    ----------
    name, key, label, unit : str
        As :class:`KeyFigure`.
    function : callable
        ``function(result)`` -> the value in ``unit``, or (value, where), or None when it does
        not apply.
    reduction, better, description, check : str
        As :class:`KeyFigure`.
    headline : bool
        As :class:`KeyFigure`.
    status : callable or None
        ``status(value)`` -> the figure's own judgement (:attr:`FigureSpec.status`), or None.
    unavailable : str
        Why the figure may not apply (:attr:`FigureSpec.unavailable`).

    Returns
    -------
    FigureSpec
        The declaration (for the result class's ``FIGURES``).
    """

    def value(result: Any) -> tuple[Any, str] | None:
        got = function(result)
        if got is None:
            return None
        if isinstance(got, tuple):
            return got
        return got, ""

    return FigureSpec(
        name,
        key,
        label,
        unit,
        value,
        reduction,
        better,
        description,
        "",
        check,
        headline,
        status,
        unavailable,
    )


def summary_html(summary: Summary) -> str:
    """The notebook view of a result's summary (:class:`crankdyn.summary.Summary`): its
    warnings, key figures, verdicts, tables and notes, every text escaped.

    Parameters
    ----------
    summary : crankdyn.summary.Summary
        The summary.

    Returns
    -------
    str
        The HTML.
    """
    from crankdyn.display import html_table, html_text

    parts = []
    if summary.warnings:
        items = "".join(f"<li>warning: {html_text(w.message)}</li>" for w in summary.warnings)
        parts.append(f"<ul style='color:#b26a00'>{items}</ul>")
    rows = [list(r) for r in summary.rows()]
    parts.append(html_table(["Quantity", "Value", "Unit"], rows, title=summary.title))
    if summary.verdicts:
        header, cells = verdict_cells(summary.verdicts)
        parts.append(html_table(header, cells, title="Verdicts"))
        parts.append(f"<p><strong>Verdict: {html_text(summary.verdict or '')}</strong></p>")
    for table in summary.tables:
        header, cells = table.cells(aligned=False)
        parts.append(html_table(header, cells, title=table.title, caption=table.caption))
    if summary.notes:
        items = "".join(f"<li>{html_text(n)}</li>" for n in summary.notes)
        parts.append(f"<ul>{items}</ul>")
    return "".join(parts)
