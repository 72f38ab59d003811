"""The results of a study: one table with the parameters and figures of every finished case
(Parquet and CSV), and a short HTML summary (cases, best cases, sensitivity).

Both are rebuilt from the journal (crankdyn.study.run.journal) and written atomically, so a reader
never sees half a table. Columns, in order:

- ``case``: the case's number in the study's order (1-based); ``case_id``: its stable id;
  ``status``: ``ok`` or ``failed``; ``sample``: the Monte Carlo sample (0-based), Monte Carlo
  studies only;
- one column per parameter: numeric parameters in the unit of the study file, with the unit in
  the column name (``geometry.rod_length_mm``); categorical ones as text (``[1, 3, 4, 2]``);
- one column per figure, in SI with the unit in the name (``max_main_bearing_load_N``); empty
  (NaN, null) for failed cases and undefined figures;
- ``error``: the failed case's message on one line; ``elapsed_s``: the case's run time.

The Parquet file carries each column's label and unit as field metadata and the study (name,
fingerprint, base file) as schema metadata under the key ``crankdyn``.
"""

from __future__ import annotations

import csv
import datetime as _dt
import io
import json
import math
from collections import Counter
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from crankdyn import __version__
from crankdyn.constants import RPM
from crankdyn.extras import require
from crankdyn.io.output import write_bytes, write_text
from crankdyn.study.cases import Case
from crankdyn.study.figures import FIGURES, SETTINGS, Figure
from crankdyn.study.spec import Parameter, StudySpec

if TYPE_CHECKING:
    import pyarrow as pa

    from crankdyn.report.model import Report, Section

__all__ = [
    "SUMMARY_MODULES",
    "WRITING_MODULES",
    "CaseTable",
    "TableColumn",
    "import_writers",
    "read_table",
    "write_outputs",
]

BEST_ROWS = 5
"""Rows of each best-cases table of the summary."""
PANELS_PER_PLOT = 24  # sensitivity panels per image (rows of figures x parameters)


@dataclass(frozen=True)
class TableColumn:
    """A column of the results table (module docstring).

    Parameters
    ----------
    name : str
        The column name (unit in the name where there is one).
    label : str
        For tables and plots.
    unit : str
        The values' unit (``""`` for none).
    role : str
        ``"meta"``, ``"parameter"`` or ``"figure"``.
    dtype : str
        ``"int"``, ``"float"`` or ``"str"``.
    key : str
        The parameter's key paths or the figure's name; ``""`` for the meta columns.
    """

    name: str
    label: str
    unit: str
    role: str
    dtype: str
    key: str = ""  # parameter key path or figure name


class CaseTable:
    """The finished cases of a study as columns (lists in case order; :meth:`build`).

    Parameters
    ----------
    spec : crankdyn.study.spec.StudySpec
        The study.
    columns : list of TableColumn
        The columns, in order.
    data : dict of str to list
        Column name -> values in case order (figures in SI, NaN where undefined).
    """

    def __init__(
        self, spec: StudySpec, columns: list[TableColumn], data: dict[str, list[Any]]
    ) -> None:
        self.spec = spec
        self.columns = columns
        self.data = data

    # ---- building -------------------------------------------------------------------------
    @classmethod
    def build(
        cls, spec: StudySpec, cases: list[Case], records: dict[str, dict[str, Any]]
    ) -> CaseTable:
        """The table of the cases that have a record.

        Parameters
        ----------
        spec : crankdyn.study.spec.StudySpec
            The study.
        cases : list of crankdyn.study.cases.Case
            Its cases (:func:`crankdyn.study.cases.expand`).
        records : dict of str to dict
            Case id -> journal record (:func:`crankdyn.study.run.journal.read_journal`).

        Returns
        -------
        CaseTable
            One row per case with a record, in case order.
        """
        columns = [
            TableColumn("case", "Case", "", "meta", "int"),
            TableColumn("case_id", "Case id", "", "meta", "str"),
            TableColumn("status", "Status", "", "meta", "str"),
        ]
        if spec.random_parameters:
            columns.append(TableColumn("sample", "Monte Carlo sample", "", "meta", "int"))
        for p in spec.parameters:
            columns.append(
                TableColumn(
                    p.column,
                    p.key,
                    p.unit or "",
                    "parameter",
                    "float" if p.is_numeric else "str",
                    ", ".join(q.text for q in p.paths),
                )
            )
        for name in spec.figures:
            f = FIGURES[name]
            columns.append(TableColumn(f.key, f.label, f.si_unit or "", "figure", "float", name))
        columns.append(TableColumn("error", "Error", "", "meta", "str"))
        columns.append(TableColumn("elapsed_s", "Case run time", "s", "meta", "float"))
        data: dict[str, list[Any]] = {c.name: [] for c in columns}
        seen: set[str] = set()
        for case in cases:
            record = records.get(case.case_id)
            if record is None or case.case_id in seen:
                continue
            seen.add(case.case_id)
            data["case"].append(case.index + 1)
            data["case_id"].append(case.case_id)
            status = "ok" if record.get("status") == "ok" else "failed"
            data["status"].append(status)
            if spec.random_parameters:
                data["sample"].append(case.sample)
            for p in spec.parameters:
                data[p.column].append(case.numbers[p.key])
            figures = record.get("figures") or {}
            for name in spec.figures:
                value = figures.get(name)
                data[FIGURES[name].key].append(math.nan if value is None else float(value))
            data["error"].append(record.get("error") or "")
            elapsed = record.get("elapsed_s")
            data["elapsed_s"].append(math.nan if elapsed is None else float(elapsed))
        return cls(spec, columns, data)

    # ---- counts -------------------------------------------------------------------------
    @property
    def finished(self) -> int:
        """Cases with a record."""
        return len(self.data["case"])

    @property
    def ok(self) -> int:
        """Cases with results."""
        return sum(1 for s in self.data["status"] if s == "ok")

    @property
    def failed(self) -> int:
        """Failed cases."""
        return self.finished - self.ok

    def common_errors(self, n: int = 3) -> tuple[tuple[str, int], ...]:
        """The most frequent error messages of the failed cases.

        Parameters
        ----------
        n : int
            How many; default 3.

        Returns
        -------
        tuple of (str, int)
            (message, number of cases), most frequent first.
        """
        counts = Counter(
            e for e, s in zip(self.data["error"], self.data["status"], strict=True) if s == "failed"
        )
        return tuple(counts.most_common(n))

    def column(self, name: str) -> np.ndarray:
        """A column as a numpy array.

        Parameters
        ----------
        name : str
            The column name.

        Returns
        -------
        numpy.ndarray
            Float for numbers (the column's unit), int for counts (-1 where missing), object
            for text.
        """
        kind = next(c.dtype for c in self.columns if c.name == name)
        values = self.data[name]
        if kind == "float":
            return np.asarray(values, dtype=float)
        if kind == "int":
            return np.asarray([-1 if v is None else v for v in values], dtype=int)
        return np.asarray(values, dtype=object)

    # ---- export -------------------------------------------------------------------------
    def to_arrow(self) -> pa.Table:
        """The table as a pyarrow Table (module docstring).

        Returns
        -------
        pyarrow.Table
            The columns, with label, unit, role and key as field metadata and the study as
            schema metadata under ``crankdyn``.
        """
        import pyarrow as pa

        types = {"int": pa.int64(), "float": pa.float64(), "str": pa.string()}
        fields = []
        arrays = []
        for c in self.columns:
            values = self.data[c.name]
            if c.dtype == "float":
                array = pa.array(
                    np.asarray(values, dtype=float), type=pa.float64(), from_pandas=True
                )
            elif c.name == "error":
                array = pa.array([v or None for v in values], type=pa.string())
            else:
                array = pa.array(values, type=types[c.dtype])
            metadata = {"label": c.label, "unit": c.unit, "role": c.role}
            if c.key:
                metadata["key"] = c.key
            fields.append(pa.field(c.name, types[c.dtype], metadata=metadata))
            arrays.append(array)
        meta = {
            "study": self.spec.name,
            "source": self.spec.source,
            "base": self.spec.base.source,
            "fingerprint": self.spec.fingerprint(),
            "crankdyn_version": __version__,
        }
        schema = pa.schema(fields, metadata={"crankdyn": json.dumps(meta)})
        return pa.Table.from_arrays(arrays, schema=schema)

    def to_parquet_bytes(self) -> bytes:
        """The table as a Parquet file (:meth:`to_arrow`).

        Returns
        -------
        bytes
            The file's contents.
        """
        import pyarrow.parquet as pq

        buffer = io.BytesIO()
        pq.write_table(self.to_arrow(), buffer)
        return buffer.getvalue()

    def to_csv(self) -> str:
        """The table as CSV.

        Returns
        -------
        str
            A header of column names, numbers written exactly (shortest round-trip form),
            empty cells for NaN.
        """
        buffer = io.StringIO()
        writer = csv.writer(buffer, lineterminator="\n")
        writer.writerow([c.name for c in self.columns])
        cols = [self.data[c.name] for c in self.columns]
        for row in zip(*cols, strict=True):
            writer.writerow([_cell(v) for v in row])
        return buffer.getvalue()


def _cell(value: Any) -> str:
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else ""
    return str(value)


def read_table(path: str | Path) -> pa.Table:
    """Read a study's ``results.parquet``.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.

    Returns
    -------
    pyarrow.Table
        The table with its metadata (module docstring).
    """
    require("studies", "pyarrow")
    import pyarrow.parquet as pq

    # one file: ParquetFile reads it as read_table does, without importing pyarrow.dataset
    # (0.1-0.3 s of every `crankdyn study`, which shows the best cases from this table)
    with pq.ParquetFile(path) as file:
        return file.read()


# ---- writing -------------------------------------------------------------------------------------

WRITING_MODULES = ("pyarrow.parquet", "crankdyn.study.sensitivity")
"""Modules :func:`write_outputs` imports for the tables (Parquet) and the best cases."""
SUMMARY_MODULES = (
    "crankdyn.plots.study",
    "crankdyn.report.model",
    "crankdyn.report.html",
    "crankdyn.report.write",
    "crankdyn.plots.render",
    "matplotlib.backends.backend_agg",
    "matplotlib.backends.backend_svg",
    "PIL.PngImagePlugin",
)
"""Modules it imports for the HTML summary: matplotlib (about half a second), the report, the
PNG and SVG writers (imported here, the forked workers that render the plots inherit them)."""


def import_writers(summary: bool = True) -> None:
    """Import what :func:`write_outputs` will need, ahead of it, and prepare the summary's
    drawing (:func:`crankdyn.plots.render.prepare_children`): the runner calls this while
    the local pool's or the cluster's workers run the first cases and this process waits
    (the imports take a core that would otherwise idle before the summary is built, instead
    of a second of its own after the cases). A module that fails to import is left for
    :func:`write_outputs` to report.

    Parameters
    ----------
    summary : bool
        Also the summary's modules (matplotlib, the report); default True.
    """
    import importlib

    for name in WRITING_MODULES + (SUMMARY_MODULES if summary else ()):
        try:
            importlib.import_module(name)
        except ImportError:
            return
    if summary:  # what the summary's drawing children would otherwise load first
        from crankdyn.plots.render import prepare_children

        prepare_children()


def write_outputs(
    spec: StudySpec,
    table: CaseTable,
    out: Path,
    *,
    summary: bool = True,
    run_info: dict[str, Any] | None = None,
) -> list[Path]:
    """Write the tables and the summary, each atomically.

    Parameters
    ----------
    spec : crankdyn.study.spec.StudySpec
        The study.
    table : CaseTable
        Its finished cases.
    out : pathlib.Path
        The study folder.
    summary : bool
        Also write the HTML summary (``summary/``); default True.
    run_info : dict of str to object or None
        About the run, for the summary (``elapsed_s``, s).

    Returns
    -------
    list of pathlib.Path
        results.parquet, results.csv and (``summary``) the summary's index.
    """
    paths = [
        write_bytes(out / "results.parquet", table.to_parquet_bytes(), force=True),
        write_text(out / "results.csv", table.to_csv(), force=True),
    ]
    if summary:
        from crankdyn.plots.render import collector_paused
        from crankdyn.report.write import write_report

        with collector_paused():  # the summary's figures live to the end of its writing
            report = build_summary(spec, table, run_info or {})
            paths.append(write_report(report, out / "summary", force=True))
    return paths


def _display(value: float, figure: Figure) -> str:
    """A figure's value for people, in the engineering unit of its magnitude."""
    from crankdyn.display import quantity

    return quantity(value, figure.unit) if math.isfinite(value) else "-"


def _parameter_text(table: CaseTable, row: int) -> str:
    parts = []
    for p in table.spec.parameters:
        value = table.data[p.column][row]
        if p.is_numeric:
            parts.append(f"{p.key} = {value:.6g} {p.unit}".rstrip())
        else:
            parts.append(f"{p.key} = {value}")
    return "; ".join(parts)


def build_summary(spec: StudySpec, table: CaseTable, run_info: dict[str, Any]) -> Report:
    """The HTML summary as a crankdyn report (crankdyn.report): the cases, the best cases per
    figure, the sensitivity of every figure to every parameter, and for Monte Carlo studies the
    distributions of the figures. Every figure is shown with the label and in the unit its
    result declares (:mod:`crankdyn.study.figures`)."""
    from crankdyn.report.model import Report

    ok_mask = table.column("status") == "ok" if table.finished else np.zeros(0, dtype=bool)
    sections = [_cases_section(spec, table)]
    best = _best_section(spec, table, ok_mask)
    if best is not None:
        sections.append(best)
    if table.ok >= 2:
        sections += _sensitivity_sections(spec, table, ok_mask)
    return Report(
        title=f"Study: {spec.name}",
        inputs=_inputs(spec, run_info),
        sections=sections,
        source=spec.source,
        version=__version__,
        created=_dt.datetime.now().strftime("%Y-%m-%d %H:%M"),
    )


def _cases_section(spec: StudySpec, table: CaseTable) -> Section:
    """The cases: how many, how many with results, failed or pending, and the errors."""
    from crankdyn.report.model import KeyFigure, Section
    from crankdyn.report.model import Table as ReportTable

    total = spec.case_count
    grid = (
        f"a grid of {math.prod(len(p.values or ()) for p in spec.grid_parameters)} points"
        if spec.grid_parameters
        else "no grid"
    )
    samples = (
        f" x {spec.samples} Monte Carlo samples ({spec.sampling}, seed {spec.seed})"
        if spec.random_parameters
        else ""
    )
    cases = Section(
        key="cases",
        title="Cases",
        intro=f"{total} cases: {grid}{samples}. The full table is results.parquet / results.csv "
        "in the study folder.",
    )
    pending = total - table.finished
    cases.figures += [
        KeyFigure("cases", "Cases in the study", total, str(total)),
        KeyFigure(
            "ok",
            "Cases with results",
            table.ok,
            str(table.ok),
            "pass" if table.ok == total else None,
        ),
        KeyFigure(
            "failed",
            "Failed cases",
            table.failed,
            str(table.failed),
            "warn" if table.failed else None,
            "their errors are listed below" if table.failed else "",
        ),
        KeyFigure(
            "pending",
            "Cases not run yet",
            pending,
            str(pending),
            "warn" if pending else None,
            "run the study again to resume" if pending else "",
        ),
    ]
    if table.failed:
        errors = table.common_errors(10)
        cases.tables.append(
            ReportTable(
                name="errors",
                title="Most frequent errors of the failed cases",
                header=["Cases", "Error"],
                rows=[[str(count), text] for text, count in errors],
            )
        )
        failed_rows = [i for i, s in enumerate(table.data["status"]) if s == "failed"]
        cases.tables.append(
            ReportTable(
                name="failed_cases",
                title="Failed cases",
                header=["Case", "Parameters", "Error"],
                rows=[
                    [str(table.data["case"][i]), _parameter_text(table, i), table.data["error"][i]]
                    for i in failed_rows
                ],
            )
        )
    return cases


def _figure_header(figure: Figure, values: Any) -> tuple[str, float]:
    """A figure's column header with the engineering unit of its values, and the factor to
    that unit."""
    factor, unit = figure.display(values)
    return (f"{figure.name} ({unit})" if unit else figure.name), factor


def _best_section(spec: StudySpec, table: CaseTable, ok_mask: np.ndarray) -> Section | None:
    """The best cases of every figure with a sense of better; None when there are none."""
    from crankdyn.report.model import KeyFigure, Section
    from crankdyn.report.model import Table as ReportTable
    from crankdyn.study.sensitivity import negligible_spread

    best = Section(key="best", title="Best cases")
    best.intro = (
        f"The {BEST_ROWS} best cases for each figure with a sense of better (smaller loads, "
        "larger torque...; [best] in the study file changes it)."
    )
    param_cols = [p.column for p in spec.parameters]
    constant: list[str] = []
    for name in spec.figures:
        figure = FIGURES[name]
        sense = spec.better(name)
        values = table.column(figure.key) if table.finished else np.zeros(0)
        finite = np.flatnonzero(ok_mask & np.isfinite(values))
        if sense is None or finite.size == 0:
            continue
        if negligible_spread(values[finite]):
            constant.append(figure.label)
            continue
        order = finite[np.argsort(values[finite], kind="stable")]
        if sense == "max":
            order = order[::-1]
        top = order[:BEST_ROWS]
        first = int(top[0])
        best.figures.append(
            KeyFigure(
                f"best_{figure.key}",
                f"{figure.label}: {'lowest' if sense == 'min' else 'highest'}",
                float(values[first]),
                _display(float(values[first]), figure),
                note=f"case {table.data['case'][first]}: {_parameter_text(table, first)}",
            )
        )
        header = ["Case"] + [p.key + (f" ({p.unit})" if p.unit else "") for p in spec.parameters]
        factors = []
        for n in spec.figures:
            text, factor = _figure_header(FIGURES[n], table.data[FIGURES[n].key][top])
            header.append(text)
            factors.append(factor)
        rows = []
        for i in top:
            row = [str(table.data["case"][i])]
            for col, p in zip(param_cols, spec.parameters, strict=True):
                v = table.data[col][i]
                row.append(f"{v:.6g}" if p.is_numeric else str(v))
            for n, factor in zip(spec.figures, factors, strict=True):
                v = table.data[FIGURES[n].key][i]
                row.append(f"{v * factor:.5g}" if math.isfinite(v) else "-")
            rows.append(row)
        best.tables.append(
            ReportTable(
                name=f"best_{name}",
                title=f"{figure.label}: the {top.size} {'lowest' if sense == 'min' else 'highest'}",
                header=header,
                rows=rows,
            )
        )
    if constant:
        best.intro += (
            " The same in every case (to 1 part in a million): " + ", ".join(constant) + "."
        )
    return best if best.figures or constant else None


def _shown_series(spec: StudySpec, table: CaseTable, ok_mask: np.ndarray) -> list[Any]:
    """Each figure's values over the cases with results, in the engineering unit of their
    magnitude (for the plots)."""
    from crankdyn.plots.study import Series

    out = []
    for n in spec.figures:
        f = FIGURES[n]
        values = table.column(f.key)[ok_mask]
        factor, unit = f.display(values)
        out.append(Series(f.label, unit, values * factor))
    return out


def _sensitivity_sections(spec: StudySpec, table: CaseTable, ok_mask: np.ndarray) -> list[Section]:
    """The sensitivity of every figure to every parameter (a table and plots) and, for Monte
    Carlo studies, the figures' distributions."""
    from crankdyn.plots.study import Series, plot_distributions, plot_sensitivity
    from crankdyn.report.model import Plot, Section
    from crankdyn.report.model import Table as ReportTable
    from crankdyn.study.sensitivity import main_effect, negligible_spread, spearman

    sens = Section(
        key="sensitivity",
        title="Sensitivity",
        intro=(
            "Each figure against each parameter over the cases with results, with the "
            "main effect (mean of the figure per parameter value, or per bin of a Monte "
            "Carlo parameter) and Spearman's rank correlation ρ; the table gives the range "
            "of the main effect (largest minus smallest mean) and ρ."
        ),
    )
    params = [
        Series(p.key, p.unit or "", table.column(p.column)[ok_mask], p.is_numeric)
        for p in spec.parameters
    ]
    series = _shown_series(spec, table, ok_mask)
    rows = []
    for p, param in zip(spec.parameters, params, strict=True):
        row = [p.key + (f" ({p.unit})" if p.unit else "")]
        for shown in series:
            y = shown.values
            if negligible_spread(y):
                row.append("none (the figure is the same in every case)")
                continue
            effect = main_effect(param.values, y, numeric=p.is_numeric).effect
            text = f"{effect:.4g} {shown.unit}".strip() if math.isfinite(effect) else "-"
            if p.is_numeric:
                rho = spearman(param.values, y)
                text += f" (ρ = {rho:+.2f})" if math.isfinite(rho) else ""
            row.append(text)
        rows.append(row)
    sens.tables.append(
        ReportTable(
            name="sensitivity",
            title="Main-effect range (and Spearman's ρ) of each figure per parameter",
            header=["Parameter", *spec.figures],
            rows=rows,
        )
    )
    shown = [f for f in series if np.isfinite(f.values).any()]
    rows_per_plot = max(1, PANELS_PER_PLOT // len(params))
    for k in range(0, len(shown), rows_per_plot):
        part = shown[k : k + rows_per_plot]
        suffix = "" if len(shown) <= rows_per_plot else f"_{k // rows_per_plot + 1}"
        sens.plots.append(
            Plot(
                name=f"sensitivity{suffix}",
                title="Sensitivity of " + ", ".join(f.label for f in part),
                figure=plot_sensitivity(part, params),
                caption="Points: cases with results; line: mean of the figure per "
                "parameter value (or per bin of a Monte Carlo parameter); ρ: Spearman's rank "
                "correlation.",
            )
        )
    out = [sens]
    if spec.random_parameters:
        dist = Section(key="distributions", title="Distributions")
        dist.plots.append(
            Plot(
                name="distributions",
                title="Distribution of the figures",
                figure=plot_distributions(series),
                caption="Histograms over the Monte Carlo cases with results.",
            )
        )
        out.append(dist)
    return out


def _inputs(spec: StudySpec, run_info: dict[str, Any]) -> list[tuple[str, str]]:
    """The summary's echo of the study's input."""
    inputs = [
        ("Study", spec.name),
        ("Study file", spec.source or "-"),
        (f"Base {spec.base.kind}", spec.base.source),
    ]
    if spec.remove:
        inputs.append(("Removed keys", ", ".join(p.text for p in spec.remove)))
    for p in spec.parameters:
        inputs.append((f"Parameter {', '.join(q.text for q in p.paths)}", _describe(p)))
    for name, value in spec.settings.values:
        inputs.append((f"[analysis] {name}", _setting_text(SETTINGS[name], value)))
    inputs.append(("Figures", ", ".join(spec.figures)))
    if "elapsed_s" in run_info:
        inputs.append(("Run time of the last run", f"{run_info['elapsed_s']:.3g} s"))
    return inputs


def _describe(p: Parameter) -> str:
    if p.distribution is not None:
        from crankdyn.study.spec import DISTRIBUTIONS

        names = DISTRIBUTIONS[p.distribution.name][0]
        args = ", ".join(
            f"{n} {a:.6g} {p.unit}".rstrip()
            for n, a in zip(names, p.distribution.args, strict=True)
        )
        return f"{p.distribution.name} ({args})"
    assert p.values is not None  # a grid parameter
    shown = [str(v) for v in p.values[:8]]
    more = f", ... ({len(p.values)} values)" if len(p.values) > 8 else ""
    return ", ".join(shown) + more


def _setting_text(setting: Any, value: Any) -> str:
    if isinstance(value, (tuple, list)):
        from types import SimpleNamespace

        inner = SimpleNamespace(kind=setting.kind.removeprefix("list:"))
        return ", ".join(str(v) if isinstance(v, str) else _setting_text(inner, v) for v in value)
    if setting.kind == "speed":
        return f"{value * RPM:.6g} rpm"
    if setting.kind == "angle":
        return f"{math.degrees(value):.6g} deg"
    if setting.kind == "number":
        return f"{value:.6g}"
    from crankdyn.io.units import KINDS

    return f"{value:.6g} {KINDS[setting.kind].si_unit}"
