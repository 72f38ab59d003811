"""Render a report as one self-contained HTML page (inline CSS, images embedded).

All user text (engine and mass names, file names, notes) goes through
:func:`crankdyn.display.html_text` (control characters escaped, then :func:`html.escape`); the
page has no scripts and loads nothing from the network.
"""

from __future__ import annotations

import base64
import re
from collections.abc import Iterable
from typing import TYPE_CHECKING

from crankdyn.display import column_text, unit_label
from crankdyn.display import html_text as escape  # control characters too
from crankdyn.report.model import KeyFigure, Report, Section, Table
from crankdyn.results import Result
from crankdyn.summary import verdict_status

if TYPE_CHECKING:
    from crankdyn.plausibility import PlausibilityWarning

__all__ = ["render_html"]

_CSS = """
:root { --ink:#1d2733; --muted:#5b6b7b; --line:#d8dee6; --accent:#1f4e79; --bg:#f6f8fa;
        --pass:#2e7d32; --warn:#b26a00; --fail:#c62828; }
* { box-sizing: border-box; }
body { margin:0; font: 15px/1.5 system-ui, -apple-system, "Segoe UI", Roboto, sans-serif;
       color: var(--ink); background: white; }
header { background: var(--accent); color: white; padding: 18px 32px; }
header h1 { margin: 0; font-size: 24px; }
header p { margin: 4px 0 0; opacity: .85; font-size: 13px; }
nav { position: sticky; top: 0; background: white; border-bottom: 1px solid var(--line);
      padding: 8px 32px; font-size: 13px; z-index: 1; }
nav a { color: var(--accent); margin-right: 16px; text-decoration: none; }
main { max-width: 1180px; margin: 0 auto; padding: 8px 32px 48px; }
section { margin-top: 28px; }
h2 { font-size: 20px; border-bottom: 2px solid var(--accent); padding-bottom: 4px; }
h3 { font-size: 16px; margin-bottom: 6px; }
table { border-collapse: collapse; margin: 8px 0 16px; font-size: 14px; max-width: 100%; }
th, td { border-bottom: 1px solid var(--line); padding: 5px 10px; text-align: left;
         vertical-align: top; overflow-wrap: break-word; }
th { background: var(--bg); font-weight: 600; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap;
         overflow-wrap: normal; }
td.text { text-align: left; white-space: normal; }
td.failed { color: #a8322d; font-weight: 600; }
table.figures { width: 100%; }
table.figures td:first-child { width: 26%; }
table.figures td:nth-child(2) { width: 34%; }
.badge { display: inline-block; min-width: 44px; text-align: center; border-radius: 10px;
         padding: 1px 8px; font-size: 12px; font-weight: 600; color: white; }
.badge.pass { background: var(--pass); } .badge.warn { background: var(--warn); }
.badge.fail { background: var(--fail); }
.note { color: var(--muted); font-size: 13px; }
.input-warnings { color: var(--warn); } p.verdict { font-weight: 600; }
figure { margin: 12px 0 20px; }
figure img { max-width: 100%; height: auto; border: 1px solid var(--line); }
figcaption { color: var(--muted); font-size: 13px; margin-top: 4px; }
ul.checks { padding-left: 20px; }
footer { color: var(--muted); font-size: 12px; text-align: center; padding: 24px; }
.title-page { padding: 24px 0; }
.title-page h1 { font-size: 28px; color: var(--accent); margin: 8px 0 4px; }
.title-page .subtitle { font-size: 18px; margin: 0 0 18px; }
.title-page .verdict { font-size: 18px; font-weight: 700; margin: 12px 0 18px; }
.title-page table { width: 100%; }
.title-page th { width: 32%; }
.signatures td { height: 34px; }
ol.contents { list-style: none; padding-left: 0; max-width: 720px; }
ol.contents li { display: flex; border-bottom: 1px dotted var(--line); padding: 3px 0; }
ol.contents a { color: var(--ink); text-decoration: none; flex: 1; }
ol.contents .toc-page { min-width: 3em; text-align: right; }
ol.table-notes { font-size: 12px; color: var(--muted); padding-left: 0; list-style: none; }
table.verdicts { font-size: 12.5px; }
h2 .number { color: var(--accent); margin-right: 8px; }
@media print {
  @page { size: A4; margin: 16mm 12mm; }
  .title-page, .contents-page { break-after: page; page-break-after: always; }
  .title-page { padding: 0; }
  body.document > header { display: none; }
  table.verdicts { font-size: 7.5pt; }
  ol.table-notes { font-size: 7.5pt; }
  body { font-size: 10pt; }
  * { -webkit-print-color-adjust: exact; print-color-adjust: exact; }
  header { padding: 8px 12px; }
  nav { display: none; }
  main { max-width: none; padding: 0; }
  section { margin-top: 12pt; }
  h2, h3 { break-after: avoid; page-break-after: avoid; }
  table { width: 100%; font-size: 8.5pt; }
  .note, figcaption { font-size: 8.5pt; }
  a { color: inherit; text-decoration: none; }
  th, td { padding: 2px 4px; }
  thead { display: table-header-group; }
  tr, figure, img { break-inside: avoid; page-break-inside: avoid; }
  figure img { max-height: 240mm; }
  footer { padding: 8pt; }
}
"""

_NUMBER = re.compile(r"^[-+−]?(\d+(\.\d*)?|\.\d+)([eE][-+]?\d+)?$")


def _cell(value: object) -> str:
    """A body cell: numbers right-aligned and kept on one line, text left-aligned and wrapped."""
    text = str(value)
    kind = "num" if _NUMBER.match(text.strip()) or text.strip() in ("-", "") else "text"
    if text.startswith("FAILED"):  # a verdict cell ("FAILED (undecided)" too)
        kind += " failed"
    return f"<td class='{kind}'>{escape(text)}</td>"


def _status(status: str | None) -> str:
    if not status:
        return ""
    return f'<span class="badge {escape(status)}">{escape(status)}</span>'


def _figure_row(label: str, display: str, status: str | None, note: str) -> str:
    return (
        f"<tr><td class='text'>{escape(label)}</td><td class='text'>{escape(display)}</td>"
        f"<td>{_status(status)}</td><td class='text note'>{escape(note)}</td></tr>"
    )


def _warning_row(w: PlausibilityWarning) -> str:
    """A plausibility warning as a summary row (status warn)."""
    label = w.quantity[:1].upper() + w.quantity[1:]
    return _figure_row(f"Plausibility: {label}", w.value_text, "warn", w.message)


def _figures_table(
    section_figures: Iterable[KeyFigure], warnings: Iterable[PlausibilityWarning] = ()
) -> str:
    rows = "".join(_figure_row(f.label, f.display, f.status, f.note) for f in section_figures)
    rows += "".join(_warning_row(w) for w in warnings)
    return (
        "<table class='figures'><thead><tr><th>Quantity</th><th>Value</th><th>Status</th>"
        f"<th>Note</th></tr></thead><tbody>{rows}</tbody></table>"
    )


def _result_rows(result: Result) -> tuple[list[str], list[list[str]]]:
    """Header (words with engineering units) and formatted rows of a result's columns."""
    cols = result.columns()
    labels = result.column_labels()
    header, columns = [], []
    for key, values in cols.items():
        label, unit = labels[key]
        if values.dtype.kind in "OUS":
            header.append(label)
            columns.append([str(v) for v in values])
            continue
        texts, shown = column_text(values, unit, aligned=False)  # small values keep digits
        header.append(unit_label(label, shown))
        columns.append(texts)
    return header, [list(row) for row in zip(*columns, strict=True)]


def _data_table(table: Table) -> str:
    """The whole table: every row, or the first ``table.limit`` with the count of the others
    and the file that holds them all."""
    if table.result is not None:
        header, body = _result_rows(table.result)
    else:
        header, body = table.header, table.page_rows if table.page_rows is not None else table.rows
    head = "".join(f"<th>{escape(str(h))}</th>" for h in header)
    shown = body if table.limit is None else body[: table.limit]
    rows = "".join("<tr>" + "".join(_cell(v) for v in row) + "</tr>" for row in shown)
    more = ""
    if len(shown) < len(body):
        more = (
            f"<p class='note'>The first {len(shown)} of {len(body)} rows; all {len(body)} in "
            f"<a href='data/{escape(table.name)}.csv'>data/{escape(table.name)}.csv</a>.</p>"
        )
    notes = ""
    if table.notes:
        items = "".join(f"<li>{escape(n)}</li>" for n in table.notes)
        notes = f"<ol class='table-notes'>{items}</ol>"
    kind = "data verdicts" if table.page_rows is not None else "data"
    return (
        f"<table class='{kind}' id='table-{escape(table.name)}'><thead><tr>{head}</tr></thead>"
        f"<tbody>{rows}</tbody></table>{notes}{more}"
    )


def _heading(key: str, title: str, number: str) -> str:
    """A section's opening: its anchor and its heading, numbered in a document with contents."""
    mark = f"<span class='number'>{escape(number)}</span>" if number else ""
    return f"<section id='{escape(key)}'><h2 id='h-{escape(key)}'>{mark}{escape(title)}</h2>"


def _verdict(section: Section) -> str:
    """The section's verdict in words with its status, the input warnings it stands on
    listed first (:attr:`crankdyn.report.model.Section.verdict`); ``""`` without verdicts."""
    if section.verdict is None:
        return ""
    items = "".join(f"<li>{escape(w.message)}</li>" for w in section.input_warnings)
    listed = (
        f"<p class='note'>Input warnings (values outside the plausible range of their role; "
        f"check them before the verdict):</p><ul class='input-warnings'>{items}</ul>"
        if items
        else ""
    )
    badge = _status(verdict_status(section.verdict))
    return f"{listed}<p class='verdict'>{badge} Verdict: {escape(section.verdict)}</p>"


def _section(section: Section, images: dict[str, bytes], number: str = "") -> str:
    parts = [_heading(section.key, section.title, number)]
    if section.intro:
        parts.append(f"<p>{escape(section.intro)}</p>")
    parts.append(_verdict(section))
    shown = section.figures if section.show_figures else []
    if shown or section.warnings:
        parts.append(_figures_table(shown, section.warnings))
    if section.notes:
        items = "".join(f"<li>{escape(n)}</li>" for n in section.notes)
        parts.append(f"<ul class='note'>{items}</ul>")
    for plot in section.plots:
        data = base64.b64encode(images[plot.name]).decode("ascii")
        parts.append(
            f"<figure><img src='data:image/png;base64,{data}' alt='{escape(plot.title)}'>"
            f"<figcaption><strong>{escape(plot.title)}.</strong> {escape(plot.caption)} "
            f"<a href='plots/{escape(plot.name)}.svg'>SVG</a> · "
            f"<a href='plots/{escape(plot.name)}.png'>PNG</a></figcaption></figure>"
        )
    for table in section.tables:
        link = f"<a href='data/{escape(table.name)}.csv'>data/{escape(table.name)}.csv</a>"
        parts.append(f"<h3>{escape(table.title)}</h3>")
        if table.caption:
            parts.append(f"<p class='note'>{escape(table.caption)}</p>")
        if table.show:
            parts.append(_data_table(table))
        parts.append(f"<p class='note'>CSV: {link}</p>")
    if section.checks:
        items = "".join(
            f"<li>{_status('pass' if c.passed else 'fail')} {escape(c.name)}: "
            f"{escape(c.detail)}</li>"
            for c in section.checks
        )
        parts.append(f"<h3>Cross-checks</h3><ul class='checks'>{items}</ul>")
    parts.append("</section>")
    return "".join(parts)


def _front(report: Report) -> str:
    """The title page: what the document is, its verdict, the installation, the document
    control (number, revision, date), the revision table and the signatures."""
    f = report.front
    if f is None:
        return ""

    def rows(items: list[tuple[str, str]]) -> str:
        return "".join(
            f"<tr><th>{escape(a)}</th><td class='text'>{escape(b)}</td></tr>" for a, b in items
        )

    parts = [
        "<section class='title-page' id='title-page'>",
        f"<h1>{escape(f.title)}</h1><p class='subtitle'>{escape(f.subtitle)}</p>",
    ]
    if f.verdict:
        parts.append(f"<p class='verdict'>Verdict: {_status(f.status)} {escape(f.verdict)}</p>")
    if f.rows:
        parts.append(f"<h3>Installation</h3><table class='title-block'>{rows(f.rows)}</table>")
    if f.document:
        parts.append(f"<h3>Document</h3><table class='title-block'>{rows(f.document)}</table>")
    if f.revisions:
        body = "".join(
            "<tr>" + "".join(f"<td class='text'>{escape(c)}</td>" for c in r) + "</tr>"
            for r in f.revisions
        )
        parts.append(
            "<h3>Revisions</h3><table class='revisions'><thead><tr><th>Revision</th>"
            f"<th>Date</th><th>Description</th><th>By</th></tr></thead><tbody>{body}</tbody>"
            "</table>"
        )
    if f.signatures:
        body = "".join(
            f"<tr><th>{escape(role)}</th><td class='text'>{escape(name)}</td><td></td></tr>"
            for role, name in f.signatures
        )
        parts.append(
            "<h3>Signatures</h3><table class='signatures'><thead><tr><th></th><th>Name</th>"
            f"<th>Signature and date</th></tr></thead><tbody>{body}</tbody></table>"
        )
    if f.note:
        parts.append(f"<p class='note'>{escape(f.note)}</p>")
    parts.append("</section>")
    return "".join(parts)


def _contents(entries: list[tuple[str, str, str]]) -> str:
    """The numbered contents list; the PDF printer fills in the pages (``.toc-page``)."""
    items = "".join(
        f"<li><a href='#{escape(key)}'>{escape(number)} {escape(title)}</a>"
        f"<span class='toc-page' data-for='h-{escape(key)}'></span></li>"
        for key, number, title in entries
    )
    return (
        "<section class='contents-page' id='contents'><h2>Contents</h2>"
        f"<ol class='contents'>{items}</ol></section>"
    )


def render_html(report: Report, images: dict[str, bytes]) -> str:
    """The report as one self-contained HTML page: a title page and a numbered contents list
    where the report has them, the summary (key figures, plausibility warnings, cross-checks,
    notes), the input, then every section with its figures, plots (embedded PNG, links to the
    SVG and PNG files) and tables (links to their CSV files). Values are shown as the sections
    formatted them, with their units; all text is escaped and the page has no scripts.

    Parameters
    ----------
    report : crankdyn.report.model.Report
        The report.
    images : dict of str to bytes
        Each plot's name mapped to its PNG file contents.

    Returns
    -------
    str
        The HTML page.

    Examples
    --------
    >>> page = render_html(Report("<V8>", [("Bore", "80 mm")], []), {})
    >>> "<h1>&lt;V8&gt;</h1>" in page and "<script" not in page
    True
    """
    numbered = report.contents
    keys = [("summary", "Summary"), ("inputs", report.inputs_title)]
    keys += [(s.key, s.title) for s in report.sections]
    numbers = {key: (f"{i + 1}" if numbered else "") for i, (key, _t) in enumerate(keys)}
    nav = "".join(f"<a href='#{escape(k)}'>{escape(t)}</a>" for k, t in keys)
    inputs = "".join(
        f"<tr><th>{escape(label)}</th><td class='text'>{escape(value)}</td></tr>"
        for label, value in report.inputs
    )
    checks = report.checks()
    check_items = "".join(
        f"<li>{_status('pass' if c.passed else 'fail')} {escape(c.name)}: {escape(c.detail)}</li>"
        for c in checks
    )
    notes = "".join(f"<li>{escape(n)}</li>" for n in report.notes)
    summary = [
        _heading("summary", "Summary", numbers["summary"]),
        _figures_table([f for f in report.key_figures() if f.headline], report.warnings()),
    ]
    for table in report.summary_tables:
        summary.append(f"<h3>{escape(table.title)}</h3>")
        if table.caption:
            summary.append(f"<p class='note'>{escape(table.caption)}</p>")
        summary.append(_data_table(table))
    if checks:
        summary.append(f"<h3>Cross-checks run</h3><ul class='checks'>{check_items}</ul>")
    if notes:
        summary.append(f"<h3>{escape(report.notes_title)}</h3><ul class='note'>{notes}</ul>")
    summary.append("</section>")
    body = "".join(_section(s, images, numbers[s.key]) for s in report.sections)
    title = escape(report.title)
    left, right = report.header
    meta = (
        f"<meta name='crankdyn-running-header' content='{escape(left)}'>"
        f"<meta name='crankdyn-running-header-right' content='{escape(right)}'>"
        if left or right
        else ""
    )
    contents = _contents([(k, numbers[k], t) for k, t in keys]) if numbered else ""
    return (
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
        "<meta name='viewport' content='width=device-width, initial-scale=1'>"
        f"{meta}<title>crankdyn report: {title}</title><style>{_CSS}</style></head>"
        f"<body class='{'document' if report.front is not None else 'report'}'>"
        f"<header><h1>{title}</h1><p>crankdyn {escape(report.version)} report · "
        f"{escape(report.created)} · source: {escape(report.source or '-')}</p></header>"
        f"<nav>{nav}</nav><main>"
        + _front(report)
        + contents
        + "".join(summary)
        + _heading("inputs", report.inputs_title, numbers["inputs"])
        + f"<table>{inputs}</table></section>"
        + body
        + "</main><footer>Generated by crankdyn. Formulas and sources: "
        "<code>crankdyn docs</code> (theory and file-format pages).</footer></body></html>"
    )
