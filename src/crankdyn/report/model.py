"""The parts of a report: sections of key figures, plots, tables and cross-checks, and the
report that holds them and gives its ``summary.json``.

Values are SI (the unit in the key of summary.json: ``peak_pressure_Pa``); display strings carry
the units people read (``15.2 MPa``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any

from crankdyn.results import Result
from crankdyn.summary import KeyFigure as SummaryFigure
from crankdyn.summary import Summary, SummaryTable, verdict_cells, verdict_of, warnings_dict

__all__ = ["Check", "FrontMatter", "KeyFigure", "Plot", "Report", "Section", "Table"]

STATUSES = ("pass", "warn", "fail")


@dataclass
class KeyFigure:
    """A headline number: label, SI value, display value and unit, optional pass/warn/fail.

    Parameters
    ----------
    key : str
        The summary.json key, with the SI unit in it (``"peak_pressure_Pa"``).
    label : str
        What the number is, for people.
    value : Any
        The value in SI units (the unit the key names), as written to summary.json.
    display : str
        The value formatted for people, with its unit (``"15.2 MPa"``).
    status : {"pass", "warn", "fail"} or None
        A verdict, or None for information.
    note : str
        A remark shown with the value.
    headline : bool
        Whether the report's summary shows it (else its section only).
    unit : str
        The unit of ``value`` (the one the key names; ``""`` for numbers and text).
    where : str
        Where a reduction found it (``"throw 3"``), or ``""``.

    Raises
    ------
    ValueError
        ``status`` is not one of :data:`STATUSES` or None.

    Examples
    --------
    >>> KeyFigure("peak_pressure_Pa", "Peak pressure", 15.2e6, "15.2 MPa", status="pass").status
    'pass'
    """

    key: str  # summary.json key, unit in the key (SI): "peak_pressure_Pa"
    label: str
    value: Any  # SI value written to summary.json
    display: str  # formatted for people: "15.2 MPa"
    status: str | None = None  # "pass", "warn", "fail" or None (information)
    note: str = ""
    headline: bool = True  # shown in the report's summary (else with its section only)
    unit: str = ""  # the unit of value (the key's)
    where: str = ""  # where a reduction found it ("throw 3", "at 2165 rpm")

    def __post_init__(self) -> None:
        if self.status is not None and self.status not in STATUSES:
            raise ValueError(f"status must be one of {STATUSES}")

    @classmethod
    def of(cls, figure: SummaryFigure) -> KeyFigure:
        """The report's view of a result's key figure (:class:`crankdyn.summary.KeyFigure`):
        its key, label, value and status as declared, the value shown with its unit and where
        it was found.

        Parameters
        ----------
        figure : crankdyn.summary.KeyFigure
            The figure.

        Returns
        -------
        KeyFigure
            The same figure for the report.
        """
        return cls(
            figure.key,
            figure.label,
            figure.value,
            figure.display(),
            status=figure.status,
            note=figure.reduction,
            headline=figure.headline,
            unit=figure.unit,
            where=figure.where,
        )


@dataclass
class Check:
    """A cross-check that was run: two independent ways to the same number.

    Parameters
    ----------
    name : str
        What was compared (``"mean torque vs indicated work"``).
    detail : str
        The difference found, with its unit (``"0.01 %"``).
    passed : bool
        Whether the two agree within the check's tolerance.
    """

    name: str  # "mean torque vs indicated work"
    detail: str  # "0.01 %"
    passed: bool


@dataclass
class Plot:
    """A figure of the report.

    Parameters
    ----------
    name : str
        Its file stem under ``plots/`` (PNG and SVG).
    title : str
        The heading shown above it.
    figure : matplotlib.figure.Figure
        The figure (its axes carry their units).
    caption : str
        A sentence under it.
    """

    name: str
    title: str
    figure: Any  # matplotlib Figure
    caption: str = ""


@dataclass
class Table:
    """A data table: written to ``data/<name>.csv`` (every row) and shown in the page.

    Parameters
    ----------
    name : str
        The CSV file stem under ``data/``.
    title : str
        The heading shown above it.
    result : crankdyn.results.Result or None
        A result exported with :meth:`~crankdyn.results.Result.to_csv` (units in its
        column headers); None: ``header`` and ``rows``.
    header : list of str
        Column headers of explicit rows (with their units).
    rows : list of list of str
        Explicit rows, formatted.
    show : bool
        Whether the page shows the table (the CSV is always written).
    limit : int or None
        Rows shown in the page (the page says how many more the CSV has); None: all.
    caption : str
        A sentence under the title: what the rows are, how they are ordered.
    source : crankdyn.summary.SummaryTable or None
        The result's summary table the rows show (its CSV holds the values with the columns'
        keys), or None.
    page_rows : list of list of str or None
        Rows the page shows instead of ``rows`` (e.g. a long source text replaced by a
        reference to :attr:`notes`); the CSV keeps ``rows``.
    notes : list of str
        Numbered notes under the table (``[1] ...``).
    """

    name: str
    title: str
    result: Result | None = None  # exported with Result.to_csv()
    header: list[str] = field(default_factory=list)  # or explicit rows
    rows: list[list[str]] = field(default_factory=list)
    show: bool = True  # render in the page (CSV is always written)
    limit: int | None = None  # rows shown in the page (the page says how many more the CSV has)
    caption: str = ""  # a sentence under the title: what the rows are, how they are ordered
    source: SummaryTable | None = None  # a result's summary table (its CSV has the SI values)
    page_rows: list[list[str]] | None = None  # what the page shows instead of rows
    notes: list[str] = field(default_factory=list)  # numbered notes under the table

    @classmethod
    def of(cls, table: SummaryTable, limit: int | None = None) -> Table:
        """The report's view of a result's summary table: its CSV with the columns' keys, its
        page rows with the columns' labels and display units.

        Parameters
        ----------
        table : crankdyn.summary.SummaryTable
            The table.
        limit : int or None
            The rows the page shows (the CSV has them all); None: all.

        Returns
        -------
        Table
            The same table for the report.
        """
        header, rows = table.cells(aligned=False)
        if limit is not None and len(table.rows) > limit:
            # the page's units from the rows it shows (36 modes' frequencies would put the
            # first eight, 4-230 Hz, in kHz); the others are only counted on the page
            header, shown = replace(table, rows=table.rows[:limit]).cells(aligned=False)
            rows = shown + rows[limit:]
        return cls(
            table.key,
            table.title,
            header=header,
            rows=rows,
            caption=table.caption,
            source=table,
            limit=limit,
        )

    def csv_text(self) -> str:
        """The table as CSV text.

        Returns
        -------
        str
            The result's CSV (SI values, units in the headers), else the header and rows.

        Examples
        --------
        >>> print(Table("t", "T", header=["Speed (rpm)", "Why"], rows=[["900", "peak"]]).csv_text())
        Speed (rpm),Why
        900,peak
        <BLANKLINE>
        """
        if self.result is not None:
            return self.result.to_csv()
        if self.source is not None:
            return self.source.csv_text()
        from crankdyn.display import csv_text  # fields quoted as RFC 4180 requires

        return csv_text([self.header, *self.rows])


@dataclass
class Section:
    """One analysis in the report.

    Parameters
    ----------
    key : str
        Anchor and ordering name (``"kinematics"``).
    title : str
        The heading.
    intro : str
        A paragraph under the heading.
    figures : list of KeyFigure
        Headline numbers.
    plots : list of Plot
        Figures.
    tables : list of Table
        Data tables.
    checks : list of Check
        Cross-checks run.
    json : dict
        The full result data for summary.json (SI units).
    warnings : list
        :class:`crankdyn.plausibility.PlausibilityWarning` objects raised by the analysis.
    verdicts : list
        :class:`crankdyn.summary.Verdict` rows of the section's results.
    notes : list of str
        The results' notes.
    show_figures : bool
        Whether the page shows the section's key figures (a document whose summary shows
        them once says False; summary.json has them either way).
    verdict : str or None
        The verdict of the rows in words (:func:`crankdyn.summary.verdict_text`: never a
        clean "passed" while the inputs carry warnings), or None without rows.
    """

    key: str  # anchor and ordering name: "kinematics"
    title: str
    intro: str = ""
    figures: list[KeyFigure] = field(default_factory=list)
    plots: list[Plot] = field(default_factory=list)
    tables: list[Table] = field(default_factory=list)
    checks: list[Check] = field(default_factory=list)
    json: dict[str, Any] = field(default_factory=dict)  # full result data for summary.json
    warnings: list[Any] = field(default_factory=list)  # crankdyn.plausibility.Warning objects
    verdicts: list[Any] = field(default_factory=list)  # crankdyn.summary.Verdict rows
    notes: list[str] = field(default_factory=list)  # the results' notes
    show_figures: bool = True  # the page shows the key figures (summary.json has them anyway)
    verdict: str | None = None  # the rows' verdict in words, with the input warnings' count

    @property
    def input_warnings(self) -> list[Any]:
        """The input warnings among :attr:`warnings` (values of the input files outside the
        plausible range of their role), listed before the verdict."""
        from crankdyn.plausibility import input_warnings

        return list(input_warnings(self.warnings))

    @classmethod
    def of(
        cls,
        key: str,
        title: str,
        results: Sequence[Result | Summary],
        *,
        intro: str = "",
        plots: Sequence[Plot] = (),
        tables: Sequence[Table] = (),
        checks: Sequence[Check] = (),
        json: dict[str, Any] | None = None,
        limits: dict[str, int] | None = None,
        verdicts_name: str | None = None,
    ) -> Section:
        """A section that renders the summaries of its results (:mod:`crankdyn.summary`):
        their key figures (each key once), tables, verdicts, notes and warnings, as the
        results declare them; the section adds only its words, plots and data tables.

        Parameters
        ----------
        key, title : str
            As the fields.
        results : sequence of Result or Summary
            The results shown, in order.
        intro : str
            The paragraph under the heading.
        plots, tables, checks
            The section's plots, data tables (CSV) and cross-checks.
        json : dict or None
            The summary.json data; default none.
        limits : dict of str to int or None
            The rows the page shows of a summary table (by its key; the CSV has them all).
        verdicts_name : str or None
            The name of the verdict table (its ``data/<name>.csv``); default
            ``<key>-verdicts``.

        Returns
        -------
        Section
            The section.
        """
        summaries = [r if isinstance(r, Summary) else r.summary() for r in results]
        verdicts = [v for s in summaries for v in s.verdicts]
        figures: list[KeyFigure] = []
        seen: set[str] = set()
        warnings: list[Any] = []
        notes: list[str] = []
        all_tables = list(tables)
        for s in summaries:
            for f in s.figures:
                if f.key not in seen:
                    seen.add(f.key)
                    figures.append(KeyFigure.of(f))
            warnings += [w for w in s.warnings if w not in warnings]
            notes += [n for n in s.notes if n not in notes]
            all_tables += [Table.of(t, (limits or {}).get(t.key)) for t in s.tables]
        verdict = None
        if verdicts:  # the verdict rows as every front end shows them, first
            header, rows = verdict_cells(verdicts)
            all_tables.insert(
                0, Table(verdicts_name or f"{key}-verdicts", "Verdicts", header=header, rows=rows)
            )
            verdict = verdict_of(verdicts, warnings)  # each warning once
        return cls(
            key=key,
            title=title,
            intro=intro,
            figures=figures,
            plots=list(plots),
            tables=all_tables,
            checks=list(checks),
            json=json if json is not None else {},
            warnings=warnings,
            verdicts=verdicts,
            notes=notes,
            verdict=verdict,
        )


@dataclass
class FrontMatter:
    """The title page of a document: what it is about, its verdict, its document control.

    Parameters
    ----------
    title : str
        What the document is (``"Torsional vibration calculation"``).
    subtitle : str
        Its subject (the project or installation).
    verdict : str
        The overall verdict in words (``"passed"``, ``"FAILED: 2 rows"``), or ``""``.
    status : {"pass", "warn", "fail"} or None
        The verdict's status.
    rows : list of (str, str)
        The installation's data (label, text).
    document : list of (str, str)
        Document number, revision, date, rule set (label, text).
    revisions : list of tuple of str
        The revision table: (revision, date, description, by) per row.
    signatures : list of (str, str)
        (role, name) of who prepared, checked and approved it.
    note : str
        A remark (e.g. where the document control would come from).
    """

    title: str
    subtitle: str = ""
    verdict: str = ""
    status: str | None = None
    rows: list[tuple[str, str]] = field(default_factory=list)
    document: list[tuple[str, str]] = field(default_factory=list)
    revisions: list[tuple[str, str, str, str]] = field(default_factory=list)
    signatures: list[tuple[str, str]] = field(default_factory=list)
    note: str = ""


@dataclass
class Report:
    """A whole report.

    Parameters
    ----------
    title : str
        The subject's name (engine, model or line).
    inputs : list of (str, str)
        An echo of the input: name and value with its unit.
    sections : list of Section
        The analyses, in report order.
    source : str or None
        The input file, or None.
    version : str
        The crankdyn version that wrote it.
    created : str
        When it was written (ISO 8601).
    notes : list of str
        Analyses that did not apply, and why.
    data : dict
        Further top-level summary.json lists.
    subject : str
        What the report is about: the summary's key for its title.
    front : FrontMatter or None
        A title page (printed on a page of its own), or None.
    contents : bool
        Whether the page has a numbered contents list (in the PDF with page numbers).
    header : (str, str)
        The running header of the printed pages: left and right text.
    inputs_title, notes_title : str
        The headings of the input table and of the notes.
    summary_tables : list of Table
        Tables the summary shows under its key figures.
    """

    title: str
    inputs: list[tuple[str, str]]  # echo of the input, with units
    sections: list[Section]
    source: str | None = None
    version: str = ""
    created: str = ""
    notes: list[str] = field(default_factory=list)  # analyses that did not apply, and why
    data: dict[str, Any] = field(default_factory=dict)  # further top-level summary.json lists
    subject: str = "engine"  # what the report is about (the summary's key for its title)
    front: FrontMatter | None = None  # a title page
    contents: bool = False  # a numbered contents list
    header: tuple[str, str] = ("", "")  # the running header of the printed pages
    inputs_title: str = "Input"
    notes_title: str = "Not analysed"
    summary_tables: list[Table] = field(default_factory=list)

    def key_figures(self) -> list[KeyFigure]:
        """The headline numbers of every section, in section order.

        Returns
        -------
        list of KeyFigure
            The key figures.
        """
        return [f for s in self.sections for f in s.figures]

    def key_figures_csv(self) -> str:
        """Every key figure as CSV (``data/key_figures.csv``): key, label, value (in the unit
        the key names), unit, where it was found, how (the reduction), status; each key once.

        Returns
        -------
        str
            The CSV text (numbers with 10 significant digits; text quoted as RFC 4180 requires).
        """
        from crankdyn.display import csv_text
        from crankdyn.export import jsonable

        rows: list[list[object]] = [["key", "label", "value", "unit", "where", "how", "status"]]
        seen: set[str] = set()
        for f in self.key_figures():
            if f.key in seen:
                continue
            seen.add(f.key)
            value = jsonable(f.value)
            if isinstance(value, float):
                value = f"{value:.10g}"
            elif isinstance(value, list):
                value = " ".join(f"{v:.10g}" if isinstance(v, float) else str(v) for v in value)
            rows.append([f.key, f.label, value, f.unit, f.where, f.note, f.status or ""])
        return csv_text(rows)

    def checks(self) -> list[Check]:
        """The cross-checks of every section, in section order.

        Returns
        -------
        list of Check
            The checks.
        """
        return [c for s in self.sections for c in s.checks]

    def warnings(self) -> list[Any]:
        """The plausibility warnings of every section, each once (in section order).

        Returns
        -------
        list of crankdyn.plausibility.PlausibilityWarning
            The warnings, one per key.
        """
        seen, out = set(), []
        for s in self.sections:
            for w in s.warnings:
                if w.key not in seen:
                    seen.add(w.key)
                    out.append(w)
        return out

    def summary(self) -> dict[str, Any]:
        """The contents of summary.json: key figures in SI with the unit in the key, their
        statuses, checks, warnings, notes and the further lists of :attr:`data`.

        Returns
        -------
        dict
            The summary, ready for :func:`json.dumps`.

        Examples
        --------
        >>> fig = KeyFigure("mean_torque_Nm", "Mean torque", 812.5, "812.5 N·m")
        >>> report = Report("demo", [], [Section("torque", "Torque", figures=[fig])])
        >>> report.summary()["key_figures"]
        {'mean_torque_Nm': 812.5}
        """
        return {
            self.subject: self.title,
            "source": self.source,
            "crankdyn_version": self.version,
            "created": self.created,
            "key_figures": {f.key: f.value for f in self.key_figures()},
            "status": {f.key: f.status for f in self.key_figures() if f.status},
            "checks": [
                {"name": c.name, "detail": c.detail, "passed": c.passed} for c in self.checks()
            ],
            "warnings": [],  # the analyses' own; input_warnings (listed first) where any
            **warnings_dict(self.warnings()),
            "notes": self.notes,
            **self.data,
        }
