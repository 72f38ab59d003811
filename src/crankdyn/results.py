"""Result objects: named SI arrays with JSON/CSV export, an HTML summary and plots.

A result is a frozen dataclass that mixes in :class:`Result`. Its public fields are declared with
:func:`column` (an array over the main axis of the result, e.g. crank angle or speed; numbers, or
text such as mass names, which is exported as it is),
:func:`array` (any other array, e.g. one row per cylinder or a mode-shape matrix) or
:func:`scalar` (a figure), each with its JSON key (unit in the key, DESIGN.md), a label and a unit
for tables, and the factor from the SI value held in memory to the value written (1 except for
angles, which are held in rad and written in deg under a ``_deg`` key). Fields without this
metadata are internal and are not exported.

Everything else follows: :meth:`Result.to_dict`, :meth:`Result.to_json`, :meth:`Result.to_csv`,
:meth:`Result.summary_rows` and the notebook view :meth:`Result._repr_html_`.
"""

from __future__ import annotations

import dataclasses
import io
import json
from collections.abc import Iterator, Sequence
from dataclasses import Field, field, fields
from typing import TYPE_CHECKING, Any, ClassVar, Self

import numpy as np
from numpy.typing import ArrayLike, DTypeLike, NDArray

from crankdyn.export import jsonable, scaled, scaled_value, to_jsonable
from crankdyn.summary import (
    FigureSpec,
    KeyFigure,
    Summary,
    SummaryColumn,
    SummaryTable,
    Verdict,
    verdict_of,
    warnings_dict,
)

if TYPE_CHECKING:
    from crankdyn.plausibility import PlausibilityWarning

__all__ = [
    "DEG",
    "Result",
    "array",
    "column",
    "freeze",
    "frozen",
    "jsonable",
    "scalar",
    "scaled_value",
]

from crankdyn.constants import DEG
from crankdyn.display import csv_text, html_text


def _meta(kind: str, key: str, label: str, unit: str, scale: float, **extra: Any) -> dict[str, Any]:
    return {"kind": kind, "key": key, "label": label, "unit": unit, "scale": scale, **extra}


def column(key: str, label: str, unit: str, scale: float = 1.0, **kw: Any) -> Any:
    """A field holding an array over the result's main axis (one CSV/table column per row).

    Or a (nested) dict of such arrays, e.g. {joint: {"x": ..., "y": ...}}: exported to JSON as
    nested objects and to CSV as columns named ``key.joint.x``.

    Parameters
    ----------
    key : str
        The JSON key (and CSV column name), with the unit in it (``"torque_Nm"``,
        ``"crank_angle_deg"``).
    label : str
        The quantity for people, in tables and notebook views (``"Torque"``).
    unit : str
        The unit of the exported value (``"N·m"``, ``"deg"``; ``""`` for dimensionless numbers
        and text).
    scale : float
        Factor from the SI value held in memory to the exported value: 1 (default), or
        :data:`crankdyn.constants.DEG` for angles exported in degrees,
        :data:`crankdyn.constants.RPM` for speeds in rpm.
    **kw
        Passed to :func:`dataclasses.field` (``default``, ``repr``...).

    Returns
    -------
    dataclasses.Field
        The field specifier (typed as the field's value, like :func:`dataclasses.field`).
    """
    return field(metadata=_meta("column", key, label, unit, scale), **kw)


def array(key: str, label: str, unit: str, scale: float = 1.0, **kw: Any) -> Any:
    """A field holding any other array (exported to JSON as nested lists).

    Parameters
    ----------
    key : str
        The JSON key (and CSV column name), with the unit in it (``"torque_Nm"``,
        ``"crank_angle_deg"``).
    label : str
        The quantity for people, in tables and notebook views (``"Torque"``).
    unit : str
        The unit of the exported value (``"N·m"``, ``"deg"``; ``""`` for dimensionless numbers
        and text).
    scale : float
        Factor from the SI value held in memory to the exported value: 1 (default), or
        :data:`crankdyn.constants.DEG` for angles exported in degrees,
        :data:`crankdyn.constants.RPM` for speeds in rpm.
    **kw
        Passed to :func:`dataclasses.field` (``default``, ``repr``...).

    Returns
    -------
    dataclasses.Field
        The field specifier (typed as the field's value, like :func:`dataclasses.field`).
    """
    return field(metadata=_meta("array", key, label, unit, scale), **kw)


def scalar(
    key: str,
    label: str,
    unit: str,
    scale: float = 1.0,
    fmt: str = ".6g",
    *,
    name: str | None = None,
    better: str | None = None,
    summary: bool = True,
    description: str = "",
    checked: str | None = None,
    headline: bool = False,
    **kw: Any,
) -> Any:
    """A field holding a single figure (number, string, bool or a nested Result / list of them).

    Every scalar field is a key figure of the result's :meth:`Result.summary` (shown by the
    command line, the report, the study and notebooks) unless ``summary`` is False; a nested
    result's figures join its parent's.

    Parameters
    ----------
    key : str
        The JSON key (and CSV column name), with the unit in it (``"torque_Nm"``,
        ``"crank_angle_deg"``).
    label : str
        The quantity for people, in tables and notebook views (``"Torque"``).
    unit : str
        The unit of the exported value (``"N·m"``, ``"deg"``; ``""`` for dimensionless numbers
        and text).
    scale : float
        Factor from the SI value held in memory to the exported value: 1 (default), or
        :data:`crankdyn.constants.DEG` for angles exported in degrees,
        :data:`crankdyn.constants.RPM` for speeds in rpm.
    fmt : str
        Format specification of the value in tables; default ``.6g``.
    name : str or None
        The figure's name in parameter studies; default the field's name.
    better : {"min", "max"} or None
        Which way is better, for a study's ranking.
    summary : bool
        Whether the field is a key figure of the summary (False: exported only, e.g. inputs
        echoed for the JSON).
    description : str
        A sentence for the study's figure list; default the label.
    checked : str or None
        The key of the plausibility check of the figure (:mod:`crankdyn.plausibility`): its
        status is ``"warn"`` when the result carries that warning, else ``"pass"``.
    headline : bool
        Whether the figure is one of the few a whole report's summary shows.
    **kw
        Passed to :func:`dataclasses.field` (``default``, ``repr``...).

    Returns
    -------
    dataclasses.Field
        The field specifier (typed as the field's value, like :func:`dataclasses.field`).
    """
    meta = _meta(
        "scalar",
        key,
        label,
        unit,
        scale,
        fmt=fmt,
        name=name,
        better=better,
        summary=summary,
        description=description,
        checked=checked,
        headline=headline,
    )
    return field(metadata=meta, **kw)


def freeze(values: ArrayLike, dtype: DTypeLike = float) -> NDArray[Any]:
    """A read-only copy of values as a numpy array (result arrays are immutable).

    Parameters
    ----------
    values : array_like
        The values (any unit: they are copied as they are).
    dtype : data-type
        The array's type; default float.

    Returns
    -------
    numpy.ndarray
        A copy with ``writeable`` False.

    Examples
    --------
    >>> a = freeze([1, 2, 3])
    >>> a, a.flags.writeable
    (array([1., 2., 3.]), False)
    """
    arr = np.array(values, dtype=dtype, copy=True)
    arr.setflags(write=False)
    return arr


def frozen(values: NDArray[Any], dtype: DTypeLike = float) -> NDArray[Any]:
    """``values`` itself made read-only, where it is an array of ``dtype`` that owns its data
    (one the caller has just computed, e.g. a sum or a concatenation, and keeps no other
    reference to): a large result's arrays are not copied once more; anything else (a view, a
    list, another type) is copied as :func:`freeze` copies it.

    Parameters
    ----------
    values : numpy.ndarray
        The values (any unit), no longer written by the caller.
    dtype : data-type
        The array's type; default float.

    Returns
    -------
    numpy.ndarray
        ``values`` or a copy, with ``writeable`` False.

    Examples
    --------
    >>> a = np.arange(3.0) * 2.0
    >>> frozen(a) is a, a.flags.writeable
    (True, False)
    >>> b = np.arange(4.0)
    >>> c = frozen(b[1:])  # a view: copied, b stays writeable
    >>> c.base is None, c.flags.writeable, b.flags.writeable
    (True, False, True)
    """
    if (
        isinstance(values, np.ndarray)
        and values.base is None
        and values.flags.owndata
        and values.dtype == np.dtype(dtype)
    ):
        values.setflags(write=False)
        return values
    return freeze(values, dtype)


class Result:
    """Mixin for result dataclasses; see the module docstring.

    A result whose inputs may be legal but implausible declares a field ``warnings`` (a tuple of
    :class:`crankdyn.plausibility.PlausibilityWarning`); they are exported as a ``warnings``
    list in :meth:`to_dict`, shown in the notebook view and printed by the command line. The
    analysis session puts the input warnings of its subject's files first
    (:class:`crankdyn.plausibility.InputWarning`, exported as ``input_warnings``); a result
    carrying one shows no key figure with status "pass" (it reads "warn") and no clean
    "passed" verdict (:func:`crankdyn.summary.verdict_text`).
    """

    warnings: tuple[PlausibilityWarning, ...] = ()
    if TYPE_CHECKING:  # every Result is a dataclass (the subclasses are decorated)
        __dataclass_fields__: ClassVar[dict[str, Field[Any]]]

    # ---- field introspection ------------------------------------------------------------------
    def _fields(self, *kinds: str) -> Iterator[tuple[Field[Any], Any, Any]]:
        for f in fields(self):
            meta = f.metadata
            if meta.get("kind") in kinds:
                yield f, meta, getattr(self, f.name)

    # ---- export -------------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """The result as a JSON-ready dict.

        Returns
        -------
        dict
            {key: value} of every exported field: SI values (degrees where the key says
            ``_deg``, rpm where it says ``_rpm``), the unit in the key; arrays as lists, NaN
            and inf as None, nested results as dicts; ``input_warnings`` and ``warnings``
            when there are any (:func:`crankdyn.summary.warnings_dict`), and ``verdict`` (in
            words, :func:`crankdyn.summary.verdict_text`) when the result has verdicts.
        """
        out: dict[str, Any] = {}
        for _f, meta, value in self._fields("column", "array", "scalar"):
            if value is None:
                continue
            out[meta["key"]] = to_jsonable(value, meta["scale"])
        for spec in self._derived_specs():  # the key figures the class derives, under their keys
            got = spec.value(self)
            if got is not None:
                out.setdefault(spec.key, to_jsonable(got[0], 1.0))
        if self.warnings:
            out.update(warnings_dict(self.warnings))
        verdicts = self.summary_verdicts()
        if verdicts:  # the verdict in words, never a clean "passed" on implausible inputs
            out.setdefault("verdict", verdict_of(verdicts, self.warnings))
        return out

    def to_json(self, indent: int | None = 2) -> str:
        """Strict JSON text of :meth:`to_dict` (NaN and inf written as null).

        Parameters
        ----------
        indent : int or None
            Indentation (characters); None for one line. Default 2.

        Returns
        -------
        str
            The JSON text.
        """
        return json.dumps(self.to_dict(), indent=indent, allow_nan=False)

    def columns(self) -> dict[str, np.ndarray]:
        """The column fields as 1-D arrays in export units.

        Returns
        -------
        dict of str to numpy.ndarray
            {key: values} in the unit of the key (angles in degrees under ``_deg`` keys); a 2-D
            column field of shape (m, n) becomes m columns ``key_1`` ... ``key_m``, a dict of
            arrays the columns ``key.name.x``; text columns (names) are kept as text.
        """
        out: dict[str, np.ndarray] = {}
        for _f, meta, value in self._fields("column"):
            if value is None:
                continue
            if isinstance(value, dict):
                for name, arr in _flatten(meta["key"], value):
                    out[name] = scaled(np.asarray(arr, dtype=float), meta["scale"])
                continue
            arr = np.asarray(value)
            if arr.dtype.kind in "OUS":  # a text column (e.g. names) is exported as it is
                out[meta["key"]] = arr
                continue
            arr = scaled(arr.astype(float), meta["scale"])
            if arr.ndim == 1:
                out[meta["key"]] = arr
            else:
                for i, row in enumerate(arr.reshape(arr.shape[0], -1), start=1):
                    out[f"{meta['key']}_{i}"] = row
        return out

    def column_labels(self) -> dict[str, tuple[str, str]]:
        """Label and unit of every column of :meth:`columns`.

        Returns
        -------
        dict of str to (str, str)
            {column key: (label, unit)}.
        """
        out: dict[str, tuple[str, str]] = {}
        for _f, meta, value in self._fields("column"):
            if value is None:
                continue
            if isinstance(value, dict):
                for name, _arr in _flatten(meta["key"], value):
                    parts = name[len(meta["key"]) + 1 :].split(".")
                    out[name] = (f"{meta['label']} {' '.join(parts)}", meta["unit"])
                continue
            arr = np.asarray(value)
            if arr.ndim == 1:
                out[meta["key"]] = (meta["label"], meta["unit"])
            else:
                for i in range(1, arr.shape[0] + 1):
                    out[f"{meta['key']}_{i}"] = (f"{meta['label']} {i}", meta["unit"])
        return out

    def to_csv(self) -> str:
        """CSV text of the column fields, one row per point, header = JSON keys.

        Returns
        -------
        str
            The CSV text (numbers with 10 significant digits, in the units of the keys).
        """
        cols = self.columns()
        buffer = io.StringIO()
        buffer.write(csv_text([list(cols)]))
        if cols and all(np.asarray(v).dtype.kind == "f" for v in cols.values()):
            # numbers only: a row at a time through one format, as _csv_cell writes each
            line = ",".join(["%.10g"] * len(cols)) + "\n"
            for row in np.column_stack(list(cols.values())).tolist():
                buffer.write(line % tuple(row))
        elif cols:  # text in the cells (names): quoted as RFC 4180 requires, no control char
            buffer.write(
                csv_text([_csv_cell(v) for v in row] for row in zip(*cols.values(), strict=True))
            )
        return buffer.getvalue()

    # ---- summary: key figures, tables, notes, warnings, verdicts (crankdyn.summary) -----------
    FIGURES: ClassVar[tuple[FigureSpec, ...]] = ()
    """Key figures the class derives from its fields (:func:`crankdyn.summary.reduced`,
    :func:`crankdyn.summary.derived`), after its scalar fields."""

    @classmethod
    def figure_specs(cls) -> tuple[FigureSpec, ...]:
        """How every key figure of the class is made, known before any result exists (a
        study lists them): the numeric scalar fields (nested results' included), then
        :attr:`FIGURES` (completed from their fields' metadata).

        Returns
        -------
        tuple of crankdyn.summary.FigureSpec
            The declarations, in order.
        """
        cached = cls.__dict__.get("_figure_specs")
        if cached is not None:
            return cached
        specs = list(_scalar_specs(cls, ()))
        for spec in cls.FIGURES:
            if spec.field_name:
                meta = cls.__dataclass_fields__[spec.field_name].metadata
                spec = dataclasses.replace(
                    spec,
                    key=spec.key or meta["key"],
                    label=spec.label or meta["label"],
                    unit=meta["unit"],
                )
            specs.append(spec)
        out = tuple(specs)
        setattr(cls, "_figure_specs", out)  # noqa: B010 (class cache)
        return out

    def key_figures(self) -> list[KeyFigure]:
        """The key figures of this result: its scalar fields (numbers, text, flags; a nested
        result's figures in its place; lists of results and ``notes`` left to the tables and
        notes), then those of :attr:`FIGURES` that apply.

        Returns
        -------
        list of crankdyn.summary.KeyFigure
            In declaration order.
        """
        out: list[KeyFigure] = []
        for f, meta, value in self._fields("scalar"):
            if value is None or f.name == "notes" or not meta.get("summary", True):
                continue
            if isinstance(value, Result):
                out.extend(value.key_figures())
                continue
            if isinstance(value, (list, tuple)) and (not value or not _plain(value[0])):
                continue  # lists of sub-results: tables, not figures; empty lists: nothing
            out.append(
                KeyFigure(
                    meta.get("name") or f.name,
                    meta["key"],
                    meta["label"],
                    meta["unit"],
                    _figure_value(value, meta["scale"]),
                    status="pass" if meta.get("checked") else None,
                    better=meta.get("better"),
                    description=meta.get("description") or meta["label"],
                    check=meta.get("checked") or "",
                    headline=bool(meta.get("headline")),
                )
            )
        for spec in self._derived_specs():
            figure = spec.make(self)
            if figure is not None:
                out.append(figure)
        if self.warnings:
            out = [_with_status(f, self.warnings) for f in out]
        return out

    @classmethod
    def _derived_specs(cls) -> tuple[FigureSpec, ...]:
        """The completed declarations of :attr:`FIGURES`."""
        specs = cls.figure_specs()
        return specs[len(specs) - len(cls.FIGURES) :]

    @classmethod
    def table_of(
        cls, items: Sequence[Result], key: str, title: str, caption: str = ""
    ) -> SummaryTable:
        """A summary table of several results of this class, one row each: a column per
        scalar field that holds a number, text or flag (labels, units and scales as the fields
        declare them; a field None in every row is left out).

        Parameters
        ----------
        items : sequence of Result
            The rows (instances of this class).
        key, title, caption : str
            As :class:`crankdyn.summary.SummaryTable`.

        Returns
        -------
        crankdyn.summary.SummaryTable
            The table.
        """
        columns: list[SummaryColumn] = []
        cells: list[list[Any]] = []
        for f in fields(cls):
            meta = f.metadata
            if meta.get("kind") != "scalar" or f.name == "notes":
                continue
            values = [getattr(item, f.name) for item in items]
            if all(v is None for v in values) or not all(v is None or _plain(v) for v in values):
                continue
            columns.append(SummaryColumn(meta["key"], meta["label"], meta["unit"]))
            cells.append([None if v is None else _figure_value(v, meta["scale"]) for v in values])
        rows = tuple(tuple(row) for row in zip(*cells, strict=True))
        return SummaryTable(key, title, tuple(columns), rows, caption=caption)

    def summary_tables(self) -> list[SummaryTable]:
        """The tables of the summary (none by default; a result with per-item figures, e.g.
        the balance by order, declares them here).

        Returns
        -------
        list of crankdyn.summary.SummaryTable
            The tables.
        """
        return []

    def summary_verdicts(self) -> list[Verdict]:
        """The rule checks' verdicts of this result (none by default).

        Returns
        -------
        list of crankdyn.summary.Verdict
            The verdicts.
        """
        return []

    def summary(self) -> Summary:
        """What this result says about itself, for every front end (:mod:`crankdyn.summary`).

        Returns
        -------
        crankdyn.summary.Summary
            Key figures, tables, notes, warnings and verdicts.
        """
        notes = getattr(self, "notes", None) or ()
        if isinstance(notes, str):
            notes = (notes,)
        return Summary(
            title=str(getattr(self, "title", "") or type(self).__name__),
            figures=tuple(self.key_figures()),
            tables=tuple(self.summary_tables()),
            notes=tuple(str(n) for n in notes),
            warnings=tuple(self.warnings),
            verdicts=tuple(self.summary_verdicts()),
        )

    def summary_rows(self) -> list[tuple[str, str, str]]:
        """The key figures as table rows (:meth:`crankdyn.summary.Summary.rows`).

        Returns
        -------
        list of (str, str, str)
            (label, formatted value, display unit) of every key figure; numbers in
            engineering units with sensible digits (:mod:`crankdyn.display`).
        """
        return self.summary().rows()

    def with_summary_of(self, full: Result) -> Self:
        """This result's rows with every scalar figure of another result of the same analysis.

        What a display grid shows never changes a summary: the figures come from ``full``.

        Parameters
        ----------
        full : Result
            The same analysis on a finer or complete grid (same class).

        Returns
        -------
        Result
            A copy of this result with the scalar fields (and the warnings) of ``full``.
        """
        from dataclasses import replace

        if full is self:
            return self
        changes = {f.name: getattr(full, f.name) for f, _m, _v in full._fields("scalar")}
        if any(f.name == "warnings" for f in fields(self)):  # verdicts of the full analysis too
            changes["warnings"] = full.warnings
        return replace(self, **changes)

    # ---- notebook view ------------------------------------------------------------------------
    def _repr_html_(self) -> str:
        from crankdyn.summary import summary_html

        out = summary_html(self.summary())
        cols = self.column_labels()
        if cols:
            n = len(next(iter(self.columns().values())))
            names = ", ".join(html_text(k) for k in cols)
            out += f"<p>{n} rows: {names} (.to_csv(), .to_dict(), .plot())</p>"
        return out

    def _short_repr(self) -> str:
        """A one-line repr: the scalar figures, and the shapes of the arrays (never their
        values)."""
        parts = []
        for f, meta, value in self._fields("scalar", "column", "array"):
            if value is None:
                continue
            if meta["kind"] == "scalar":
                if isinstance(value, Result) or (
                    isinstance(value, (list, tuple)) and value and isinstance(value[0], Result)
                ):
                    parts.append(f"{f.name}=<{type(value).__name__}>")
                    continue
                if isinstance(value, (float, np.floating)):
                    parts.append(f"{f.name}={float(value):.6g}")
                elif isinstance(value, np.ndarray):
                    parts.append(f"{f.name}=<{value.shape} array>")
                elif isinstance(value, str) and len(value) > 40:
                    parts.append(f"{f.name}={value[:37]!r}...")
                else:
                    parts.append(f"{f.name}={value!r}")
            elif isinstance(value, dict):
                parts.append(f"{f.name}=<{len(value)} series>")
            else:
                parts.append(f"{f.name}=<{np.shape(value)} array>")
        text = ", ".join(parts)
        if len(text) > 600:
            text = text[:597] + "..."
        return f"{type(self).__name__}({text})"

    @classmethod
    def _assembled(cls, **values: Any) -> Self:
        """The result from values its analysis made, every field given, without the dataclass
        ``__init__``: a frozen dataclass sets each field through ``object.__setattr__``, which
        is most of the cost of a small model's result (3 µs of a 10-mass chain's 60 µs of
        modes). Only for results that check nothing in ``__post_init__``.

        Raises
        ------
        TypeError
            Unless the values are exactly the class's fields (a programming error).
        """
        if len(values) != len(cls.__dataclass_fields__):
            raise TypeError(f"{cls.__name__}._assembled needs every field")
        result = object.__new__(cls)
        result.__dict__.update(values)
        return result

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        # set in the class itself, so that @dataclass keeps it rather than writing a repr of
        # every array value (a 361-element array per field)
        if "__repr__" not in cls.__dict__:
            setattr(cls, "__repr__", Result._short_repr)  # noqa: B010 (a method, assigned)


def _csv_cell(value: Any) -> str:
    if isinstance(value, (float, np.floating, int, np.integer)) and not isinstance(value, bool):
        return f"{value:.10g}"
    return str(value)


def _flatten(key: str, value: dict[str, Any]) -> Iterator[tuple[str, Any]]:
    """(column name, 1-D array) pairs of a column field holding a (nested) dict of arrays, the
    names joined with dots: ``joint_forces_N.B.x``."""
    for name, sub in value.items():
        if isinstance(sub, dict):
            yield from _flatten(f"{key}.{name}", sub)
        else:
            yield f"{key}.{name}", sub


def _format(value: Any, meta: Any) -> tuple[str, str]:
    """(text, unit) of a scalar figure in engineering units (:func:`crankdyn.display.
    format_value`)."""
    from crankdyn.display import format_value

    unit = meta["unit"]
    if isinstance(value, (float, np.floating)) and not isinstance(value, bool):
        return format_value(float(value) * meta["scale"], unit)
    if isinstance(value, (list, tuple, np.ndarray)):
        items = np.asarray(value, dtype=object).ravel().tolist()
        if items and all(
            isinstance(v, (float, np.floating)) and not isinstance(v, bool) for v in items
        ):
            scaled = np.asarray(items, dtype=float) * meta["scale"]
            top = float(np.max(np.abs(scaled[np.isfinite(scaled)]), initial=0.0))
            texts = [format_value(v, unit, reference=top) for v in scaled.tolist()]
            return ", ".join(text for text, _ in texts), texts[0][1]
        return ", ".join(_format(v, meta)[0] for v in items), unit
    return format_value(value, unit)


def _with_status(figure: KeyFigure, warnings: Any) -> KeyFigure:
    """The figure with status ``"warn"`` when one of the warnings is its plausibility check's,
    or when it says "pass" and the inputs carry warnings (a verdict on implausible inputs is
    never a clean pass, :func:`crankdyn.summary.verdict_text`)."""
    from crankdyn.plausibility import input_warnings

    if figure.check and any(w.key == figure.check for w in warnings):
        return dataclasses.replace(figure, status="warn")
    given = len(input_warnings(warnings))
    if figure.status == "pass" and given:
        plural = "s" if given != 1 else ""
        return dataclasses.replace(
            figure, status="warn", qualifier=f"with {given} input warning{plural}"
        )
    return figure


def _plain(value: Any) -> bool:
    """Whether a list item is a plain figure value (number, text, flag), not a sub-result."""
    return isinstance(value, (str, bool, int, float, np.generic))


def _figure_value(value: Any, scale: float) -> Any:
    """A scalar field's value in its exported unit, as a key figure holds it."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return scaled_value(float(value), scale)
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "fc":
            return [scaled_value(v, scale) for v in value.ravel().tolist()]
        return value.ravel().tolist()
    if isinstance(value, (list, tuple)):
        return [_figure_value(v, scale) for v in value]
    return value


_NUMERIC = {"float", "int", "float | None", "int | None", "None | float"}


def _scalar_specs(cls: type, path: tuple[str, ...]) -> Iterator[FigureSpec]:
    """Static declarations of the numeric scalar fields of a result class (and of the result
    classes its scalar fields hold, resolved from their annotations), for the study's registry
    of figures."""
    import sys

    module = sys.modules.get(cls.__module__)
    names = vars(module) if module is not None else {}
    hints: dict[str, Any] = {}
    for klass in reversed(cls.__mro__):
        hints.update(getattr(klass, "__annotations__", {}))
    for f in fields(cls):
        meta = f.metadata
        if meta.get("kind") != "scalar" or not meta.get("summary", True) or f.name == "notes":
            continue
        hint = hints.get(f.name)
        text = hint if isinstance(hint, str) else getattr(hint, "__name__", "")
        nested = names.get(text.replace(" | None", ""))
        if isinstance(nested, type) and issubclass(nested, Result):
            if not dataclasses.is_dataclass(nested):  # an abstract result: figures at run time
                continue
            yield from _scalar_specs(nested, (*path, f.name))
            for spec in nested._derived_specs():  # its derived figures, read through the field
                yield dataclasses.replace(spec, value=_nested_reader((*path, f.name), spec.value))
            continue
        if text not in _NUMERIC:
            continue
        yield FigureSpec(
            meta.get("name") or f.name,
            meta["key"],
            meta["label"],
            meta["unit"],
            _field_reader((*path, f.name), meta["scale"]),
            better=meta.get("better"),
            description=meta.get("description") or meta["label"],
            check=meta.get("checked") or "",
            headline=bool(meta.get("headline")),
        )


def _nested_reader(path: tuple[str, ...], value: Any) -> Any:
    """``value(result)`` of a derived figure of a nested result, read through ``path``."""

    def read(result: Any) -> tuple[Any, str] | None:
        for name in path:
            result = getattr(result, name, None)
            if result is None:
                return None
        return value(result)

    return read


def _field_reader(path: tuple[str, ...], scale: float) -> Any:
    """``value(result)`` of a (nested) scalar field: (value in its exported unit, "")."""

    def value(result: Any) -> tuple[Any, str] | None:
        for name in path:
            result = getattr(result, name, None)
            if result is None:
                return None
        return _figure_value(result, scale), ""

    return value
