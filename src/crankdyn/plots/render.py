"""Write many figures at once: each laid out once, drawn once per format, on every core.

A figure with a layout engine (constrained layout) is laid out once, by the engine run on its
own at the PNG's resolution (:func:`lay_out`), and then drawn without an engine: once for the
PNG, once for the SVG. Saving a figure that still has an engine, even a placeholder left by
``set_layout_engine("none")``, costs one more whole (undrawn) pass over every artist per file;
the files come out identical to the byte either way (tests/plots/test_render.py). The figures
are shared out over a pool of worker processes forked from this one, so the figures already
built here are rendered where they are, without pickling them: a worker renders figure ``i``
of the list it inherited, writes its files and returns the PNG bytes. Where a fork is not safe
(not Linux, or inside a daemonic process) or of no use (one figure, one core), the figures are
rendered here, one after another.
"""

from __future__ import annotations

import contextlib
import io
import multiprocessing
import os
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

__all__ = ["PNG_DPI", "lay_out", "render_figures", "workers_for"]

PNG_DPI = 110
"""Resolution of the PNG files (dots per inch)."""

PNG_COMPRESSION = 1
"""zlib level of the PNG files: the fastest (level 6, Pillow's default, took about twice as long
for files 5-25 % smaller)."""


def _png(figure: Any) -> bytes:
    """The PNG file of ``figure`` at :data:`PNG_DPI`."""
    buffer = io.BytesIO()
    figure.savefig(
        buffer, format="png", dpi=PNG_DPI, pil_kwargs={"compress_level": PNG_COMPRESSION}
    )
    return buffer.getvalue()


def _svg(figure: Any, path: str | Path) -> None:
    """Write the SVG file of ``figure``, its words written as text in the figure's font stack
    (``'DejaVu Sans', ..., 'Arial', 'Helvetica', ..., sans-serif``) rather than as glyph
    outlines: smaller files, the words searchable and selectable."""
    import matplotlib

    with matplotlib.rc_context({"svg.fonttype": "none"}):
        figure.savefig(path, format="svg")


def lay_out(figure: Any) -> None:
    """Lay ``figure`` out once, as its PNG's draw would, and fix that layout.

    The figure's layout engine (constrained layout) is run on its own, on an Agg canvas at
    :data:`PNG_DPI` with the figure's words made literal first (as
    :class:`crankdyn.plots.style.Figure` draws them), and then removed
    (``set_layout_engine(None)``): the PNG and the SVG drawn afterwards keep the layout and
    draw every artist once each. A figure without an engine, or whose engine is a placeholder,
    keeps its layout as it is.

    Parameters
    ----------
    figure : matplotlib.figure.Figure
        The figure (changed in place).

    Examples
    --------
    >>> from crankdyn.plots.style import new_figure
    >>> fig, axes = new_figure()
    >>> _ = axes[0, 0].set_ylabel("a rather long label (N·m)")
    >>> before = axes[0, 0].get_position().bounds
    >>> lay_out(fig)
    >>> fig.get_layout_engine() is None, axes[0, 0].get_position().bounds != before
    (True, True)
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.layout_engine import PlaceHolderLayoutEngine

    from crankdyn.plots.style import plain_text

    engine = figure.get_layout_engine()
    if engine is None:
        return
    if not isinstance(engine, PlaceHolderLayoutEngine) and figure.axes:
        plain_text(figure)
        dpi, canvas = figure.get_dpi(), figure.canvas
        figure.set_dpi(PNG_DPI)
        FigureCanvasAgg(figure)  # the engine measures the words with the PNG's renderer
        try:
            engine.execute(figure)
        finally:
            figure.set_dpi(dpi)
            figure.set_canvas(canvas)
    figure.set_layout_engine(None)


# (figure, png path or None, svg path or None) of the pool's figures
_JOBS: Sequence[tuple[Any, str | Path | None, str | Path | None]] = ()


def _render(index: int) -> bytes:
    """Draw figure ``index`` of :data:`_JOBS`: its PNG (bytes returned, and written when a path
    is given), then its SVG with the PNG's layout."""
    figure, png_path, svg_path = _JOBS[index]
    lay_out(figure)
    png = _png(figure)
    if png_path is not None:
        Path(png_path).write_bytes(png)
    if svg_path is not None:
        _svg(figure, svg_path)
    return png


def _render_part(index: int, part: str) -> bytes | None:
    """One part of figure ``index`` of :data:`_JOBS`, in a worker of its own: ``"png"`` its
    PNG (bytes returned, and written when a path is given); ``"svg"`` its SVG. Each worker
    lays the figure out itself (:func:`lay_out`, the same layout to the last digit of the file,
    which the tests check)."""
    figure, png_path, svg_path = _JOBS[index]
    lay_out(figure)
    if part == "png":
        png = _png(figure)
        if png_path is not None:
            Path(png_path).write_bytes(png)
        return png
    assert svg_path is not None  # only figures with an SVG are split
    _svg(figure, svg_path)
    return None


def _fresh_streams() -> None:
    """A worker's own standard output and error objects on the same files: a lock that a
    thread of the parent (a progress display) held at the fork is not inherited held."""
    for name, fd in (("stdout", 1), ("stderr", 2)):
        with contextlib.suppress(OSError):
            stream = open(os.dup(fd), "w", encoding="utf-8", errors="replace")  # noqa: SIM115
            setattr(sys, name, stream)


def _can_fork() -> bool:
    """Whether a forked pool is safe here: Linux (macOS's system libraries are not safe to use
    after a fork), and not inside a daemonic process (which may not have children)."""
    return (
        sys.platform.startswith("linux")
        and "fork" in multiprocessing.get_all_start_methods()
        and not multiprocessing.current_process().daemon
    )


def workers_for(count: int) -> int:
    """Worker processes for ``count`` figures: one per usable core, at most one per figure (a
    figure takes a few tenths of a second; more workers than cores would only queue).

    Parameters
    ----------
    count : int
        Number of figures to render.

    Returns
    -------
    int
        Worker processes, at least 1.

    Examples
    --------
    >>> workers_for(1)
    1
    >>> 1 <= workers_for(1000) <= (os.cpu_count() or 1)
    True
    """
    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        cores = os.cpu_count() or 1
    return max(1, min(cores, count))


def render_figures(
    jobs: Sequence[tuple[object, str | Path | None, str | Path | None]],
    *,
    progress: Callable[[int], object] | None = None,
    workers: int | None = None,
) -> list[bytes]:
    """Render figures to PNG (and SVG with the PNG's layout), in a forked pool where that is
    safe and useful, else one after another.

    Parameters
    ----------
    jobs : sequence of (figure, path or None, path or None)
        Each a matplotlib Figure, the PNG file to write (None: bytes only) and the SVG file to
        write (None: none). PNGs are drawn at :data:`PNG_DPI` dots per inch.
    progress : callable or None
        ``progress(i)`` is called as figure ``i`` starts (serially) or is done (in the pool).
    workers : int or None
        Worker processes (default :func:`workers_for`); 1 renders here.

    Returns
    -------
    list of bytes
        Every figure's PNG file contents, in the order of ``jobs``.
    """
    global _JOBS
    jobs = list(jobs)
    # fewer figures than cores (a study's summary: one figure): each figure's PNG and SVG are
    # drawn by workers of their own, the SVG's worker laying the figure out again
    parts = sum(1 for job in jobs if job[2] is not None)
    split = workers is None and len(jobs) < workers_for(len(jobs) + parts) and _can_fork()
    if split:
        n = workers_for(len(jobs) + parts)
    else:
        n = workers_for(len(jobs)) if workers is None else max(1, min(workers, len(jobs)))
    if n > 1 and _can_fork():
        from concurrent.futures import Future, ProcessPoolExecutor, as_completed

        _JOBS = jobs
        pool = ProcessPoolExecutor(
            n, mp_context=multiprocessing.get_context("fork"), initializer=_fresh_streams
        )
        try:
            futures: dict[Future[bytes | None], int] = {}
            left = [1] * len(jobs)  # parts of each figure still rendering
            for i, job in enumerate(jobs):
                if split:
                    futures[pool.submit(_render_part, i, "png")] = i
                    if job[2] is not None:
                        futures[pool.submit(_render_part, i, "svg")] = i
                        left[i] += 1
                else:
                    futures[pool.submit(_render, i)] = i
            out: list[bytes | None] = [None] * len(jobs)
            for future in as_completed(futures):
                i = futures[future]
                png = future.result()
                if png is not None:
                    out[i] = png
                left[i] -= 1
                if progress is not None and left[i] == 0:
                    progress(i)
            return [png for png in out if png is not None]
        finally:
            pool.shutdown(wait=True, cancel_futures=True)
            _JOBS = ()
    _JOBS = jobs
    try:
        out_serial = []
        for i in range(len(jobs)):
            if progress is not None:
                progress(i)
            out_serial.append(_render(i))
        return out_serial
    finally:
        _JOBS = ()
