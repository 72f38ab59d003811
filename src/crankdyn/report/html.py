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
@media print {
  @page { size: A4; margin: 12mm; }
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
    if text == "FAILED":  # a verdict cell
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
        header, body = table.header, table.rows
    head = "".join(f"<th>{escape(str(h))}</th>" for h in header)
    shown = body if table.limit is None else body[: table.limit]
    rows = "".join("<tr>" + "".join(_cell(v) for v in row) + "</tr>" for row in shown)
    more = ""
    if len(shown) < len(body):
        more = (
            f"<p class='note'>The first {len(shown)} of {len(body)} rows; all {len(body)} in "
            f"<a href='data/{escape(table.name)}.csv'>data/{escape(table.name)}.csv</a>.</p>"
        )
    return (
        f"<table class='data' id='table-{escape(table.name)}'><thead><tr>{head}</tr></thead>"
        f"<tbody>{rows}</tbody></table>{more}"
    )


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


def _section(section: Section, images: dict[str, bytes]) -> str:
    parts = [f"<section id='{escape(section.key)}'><h2>{escape(section.title)}</h2>"]
    if section.intro:
        parts.append(f"<p>{escape(section.intro)}</p>")
    parts.append(_verdict(section))
    if section.figures or section.warnings:
        parts.append(_figures_table(section.figures, section.warnings))
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


def render_html(report: Report, images: dict[str, bytes]) -> str:
    """The report as one self-contained HTML page: summary (key figures, plausibility
    warnings, cross-checks, analyses not run), input, then every section with its figures,
    plots (embedded PNG, links to the SVG and PNG files) and tables (links to their CSV
    files). Values are shown as the sections formatted them, with their units; all text is
    escaped and the page has no scripts.

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
    nav = "".join(f"<a href='#{escape(s.key)}'>{escape(s.title)}</a>" for s in [*report.sections])
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
        "<section id='summary'><h2>Summary</h2>",
        _figures_table([f for f in report.key_figures() if f.headline], report.warnings()),
    ]
    if checks:
        summary.append(f"<h3>Cross-checks run</h3><ul class='checks'>{check_items}</ul>")
    if notes:
        summary.append(f"<h3>Not analysed</h3><ul class='note'>{notes}</ul>")
    summary.append("</section>")
    body = "".join(_section(s, images) for s in report.sections)
    title = escape(report.title)
    return (
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
        "<meta name='viewport' content='width=device-width, initial-scale=1'>"
        f"<title>crankdyn report: {title}</title><style>{_CSS}</style></head><body>"
        f"<header><h1>{title}</h1><p>crankdyn {escape(report.version)} report · "
        f"{escape(report.created)} · source: {escape(report.source or '-')}</p></header>"
        f"<nav><a href='#summary'>Summary</a><a href='#inputs'>Input</a>{nav}</nav><main>"
        + "".join(summary)
        + f"<section id='inputs'><h2>Input</h2><table>{inputs}</table></section>"
        + body
        + "</main><footer>Generated by crankdyn. Formulas and sources: "
        "<code>crankdyn docs</code> (theory and file-format pages).</footer></body></html>"
    )
