"""Render a report as one self-contained HTML page (inline CSS, images embedded).

All user text (engine and mass names, file names, notes) goes through :func:`html.escape`; the
page has no scripts and loads nothing from the network.
"""

from __future__ import annotations

import base64
from html import escape

from crankdyn.report.model import Report, Section, Table

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
table { border-collapse: collapse; margin: 8px 0 16px; font-size: 14px; }
th, td { border-bottom: 1px solid var(--line); padding: 5px 10px; text-align: left;
         vertical-align: top; }
th { background: var(--bg); font-weight: 600; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
.badge { display: inline-block; min-width: 44px; text-align: center; border-radius: 10px;
         padding: 1px 8px; font-size: 12px; font-weight: 600; color: white; }
.badge.pass { background: var(--pass); } .badge.warn { background: var(--warn); }
.badge.fail { background: var(--fail); }
.note { color: var(--muted); font-size: 13px; }
figure { margin: 12px 0 20px; }
figure img { max-width: 100%; height: auto; border: 1px solid var(--line); }
figcaption { color: var(--muted); font-size: 13px; margin-top: 4px; }
.scroll { max-height: 420px; overflow: auto; display: inline-block; max-width: 100%; }
ul.checks { padding-left: 20px; }
footer { color: var(--muted); font-size: 12px; text-align: center; padding: 24px; }
"""


def _status(status: str | None) -> str:
    if not status:
        return ""
    return f'<span class="badge {escape(status)}">{escape(status)}</span>'


def _figures_table(section_figures) -> str:
    rows = "".join(
        f"<tr><td>{escape(f.label)}</td><td class='num'>{escape(f.display)}</td>"
        f"<td>{_status(f.status)}</td><td class='note'>{escape(f.note)}</td></tr>"
        for f in section_figures
    )
    return (
        "<table class='figures'><thead><tr><th>Quantity</th><th>Value</th><th>Status</th>"
        f"<th>Note</th></tr></thead><tbody>{rows}</tbody></table>"
    )


def _data_table(table: Table, max_rows: int = 400) -> str:
    if table.result is not None:
        cols = table.result.columns()
        labels = table.result.column_labels()
        header = [
            f"{labels[k][0]} ({labels[k][1]})" if labels[k][1] else labels[k][0] for k in cols
        ]
        body = [[f"{v:.6g}" for v in row] for row in zip(*cols.values(), strict=True)]
    else:
        header, body = table.header, table.rows
    head = "".join(f"<th>{escape(str(h))}</th>" for h in header)
    rows = "".join(
        "<tr>" + "".join(f"<td class='num'>{escape(str(v))}</td>" for v in row) + "</tr>"
        for row in body[:max_rows]
    )
    more = (
        f"<p class='note'>{len(body) - max_rows} more rows in the CSV.</p>"
        if len(body) > max_rows
        else ""
    )
    return (
        f"<div class='scroll'><table><thead><tr>{head}</tr></thead><tbody>{rows}</tbody>"
        f"</table></div>{more}"
    )


def _section(section: Section, images: dict[str, bytes]) -> str:
    parts = [f"<section id='{escape(section.key)}'><h2>{escape(section.title)}</h2>"]
    if section.intro:
        parts.append(f"<p>{escape(section.intro)}</p>")
    if section.figures:
        parts.append(_figures_table(section.figures))
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
    """The report page; ``images`` maps each plot name to its PNG bytes."""
    nav = "".join(f"<a href='#{escape(s.key)}'>{escape(s.title)}</a>" for s in [*report.sections])
    inputs = "".join(
        f"<tr><th>{escape(label)}</th><td>{escape(value)}</td></tr>"
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
        _figures_table(report.key_figures()),
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
        + "</main><footer>Generated by crankdyn. Formulas and sources: see the docs/ folder of "
        "the project.</footer></body></html>"
    )
