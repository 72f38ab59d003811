"""Write a report folder atomically: index.html, summary.json, data/*.csv, plots/*.png/.svg."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from crankdyn.io.output import atomic_directory
from crankdyn.report.html import render_html
from crankdyn.report.model import Report

if TYPE_CHECKING:
    from crankdyn.plots.render import Renderer
    from crankdyn.report.model import Section

__all__ = ["write_drawn", "write_report"]


def write_drawn(
    make: Callable[[Callable[[Section], object]], Report],
    out: str | Path,
    *,
    force: bool = False,
    finish: Callable[[Path], object] | None = None,
) -> Path:
    """Make a report with each section's figures drawn (on the other cores) while the next
    sections are made, and write it (:func:`write_report`).

    Parameters
    ----------
    make : callable
        ``make(built)`` returns the report, calling ``built(section)`` as each section is
        made (e.g. ``lambda built: build_tvc_report(result, built=built)``).
    out : str or pathlib.Path
        The folder to write.
    force : bool
        Replace an existing folder (else it is an error).
    finish : callable or None
        ``finish(folder)`` is called on the complete temporary folder before it is moved into
        place (e.g. to print the page to PDF).

    Returns
    -------
    pathlib.Path
        The folder written (:func:`write_report`).
    """
    from crankdyn.plots.render import Renderer, collector_paused

    # no collector passes over the figures kept to the end
    with collector_paused(), Renderer() as renderer:
        renderer.busy()

        def built(section: Section) -> None:
            """Start drawing the figures of ``section``."""
            for plot in section.plots:
                renderer.submit(plot.figure)

        report = make(built)
        return write_report(report, out, force=force, finish=finish, renderer=renderer)


def write_report(
    report: Report,
    out: str | Path,
    *,
    force: bool = False,
    progress: Callable[[str], object] | None = None,
    finish: Callable[[Path], object] | None = None,
    renderer: Renderer | None = None,
) -> Path:
    """Write ``report`` into the folder ``out``: ``index.html``, ``summary.json`` (SI values,
    the unit in each key; NaN and infinity as null), ``data/*.csv`` and ``plots/*.png`` and
    ``.svg``. The folder is built in a temporary sibling and moved into place
    (:func:`crankdyn.io.output.atomic_directory`); the plots are rendered on every core, each
    laid out once (:mod:`crankdyn.plots.render`).

    Parameters
    ----------
    report : crankdyn.report.model.Report
        The report.
    out : str or pathlib.Path
        The folder to write.
    force : bool
        Replace an existing folder (else it is an error).
    progress : callable or None
        ``progress(name)`` is called per plot, with the plot's name.
    finish : callable or None
        ``finish(folder)`` is called on the complete temporary folder before it is moved into
        place (e.g. to print the page to PDF).
    renderer : crankdyn.plots.render.Renderer or None
        A renderer the report's figures were submitted to as they were made (already drawn
        or drawing); None: they are drawn here.

    Returns
    -------
    pathlib.Path
        The folder written: ``out``, or a numbered sibling (``out.2``) when ``out`` appeared
        while the report was written.

    Raises
    ------
    crankdyn.errors.InputError
        ``out`` exists and ``force`` is not given, or it cannot be written.
    """
    from crankdyn.plots.render import render_figures

    taken: set[str] = {t.name for t in report.summary_tables}
    for section in report.sections:  # one CSV per table: a name taken before gets its section's
        for table in section.tables:
            if table.name in taken:
                table.name = f"{section.key}-{table.name}"
            taken.add(table.name)
    folder = atomic_directory(out, force=force)
    with folder as tmp:
        (tmp / "plots").mkdir()
        (tmp / "data").mkdir()
        plots = [plot for section in report.sections for plot in section.plots]
        pngs = render_figures(
            [
                (p.figure, tmp / "plots" / f"{p.name}.png", tmp / "plots" / f"{p.name}.svg")
                for p in plots
            ],
            progress=None if progress is None else (lambda i: progress(plots[i].name)),
            renderer=renderer,
        )
        images: dict[str, bytes] = {p.name: png for p, png in zip(plots, pngs, strict=True)}
        for table in [*report.summary_tables, *(t for s in report.sections for t in s.tables)]:
            (tmp / "data" / f"{table.name}.csv").write_text(table.csv_text(), encoding="utf-8")
        (tmp / "data" / "key_figures.csv").write_text(report.key_figures_csv(), encoding="utf-8")
        summary = report.summary()
        summary["sections"] = {s.key: s.json for s in report.sections if s.json}
        (tmp / "summary.json").write_text(
            json.dumps(_finite(summary), indent=2, allow_nan=False, default=_json_default) + "\n",
            encoding="utf-8",
        )
        (tmp / "index.html").write_text(render_html(report, images), encoding="utf-8")
        if finish is not None:
            finish(tmp)
    return folder.path


def _finite(value):
    """NaN and inf become null: summary.json is strict JSON."""
    import math

    import numpy as np

    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_finite(v) for v in value]
    if isinstance(value, np.ndarray):
        return _finite(value.tolist())
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    return value


def _json_default(value):
    import numpy as np

    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"not JSON serialisable: {type(value).__name__}")
