"""Write many figures at once: each laid out once, drawn once per format, on every core, from
the moment it is made.

A figure with a layout engine (constrained layout) is laid out once, by the engine run on its
own at the PNG's resolution (:func:`lay_out`), and then drawn without an engine: once for the
PNG, once for the SVG. Saving a figure that still has an engine, even a placeholder left by
``set_layout_engine("none")``, costs one more whole (undrawn) pass over every artist per file;
the files come out identical to the byte either way (tests/plots/test_render.py).

A :class:`Renderer` draws each figure submitted to it in a child process forked from this one
at once, so the figure is drawn where it was made, without pickling, while this process goes
on (a report's later analyses run while its first figures are drawn): as many children at a
time as there are cores, one fewer while this process is still busy making figures
(:meth:`Renderer.busy`); of the figures waiting, the one with the most axes is started first,
so that the small ones keep both cores busy at the end. A child lays its figure out on an Agg
canvas at the PNG's resolution and draws the PNG with that canvas's renderer, which has every
word's size cached already (:func:`lay_out`, ``keep_canvas``). A child writes its files into
the renderer's private temporary folder and exits; :meth:`Renderer.results` waits for them and
reads them back. Where a fork is not safe (not Linux, or inside a daemonic process) or of no use
(one core), or when a child fails, the figures are drawn here, one after another, when their
results are asked for. The fork itself (the signals held across it, the child's set-up) is
:mod:`crankdyn.forks`'s.
"""

from __future__ import annotations

import contextlib
import functools
import gc
import io
import os
import select
import shutil
import signal
import tempfile
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

from crankdyn.forks import can_fork, child_setup, hold_signals, release_signals
from crankdyn.threads import available_cores

__all__ = [
    "PNG_DPI",
    "Renderer",
    "collector_paused",
    "lay_out",
    "png_file",
    "prepare_children",
    "render_figures",
    "ticks_kept",
    "workers_for",
]

PNG_DPI = 110
"""Resolution of the PNG files (dots per inch)."""

PNG_COMPRESSION = 1
"""zlib level of the PNG files: the fastest (level 6 took about twice as long for files 5-25 %
smaller)."""


def _png(figure: Any) -> bytes:
    """The PNG file of ``figure`` at :data:`PNG_DPI`: the pixels Agg draws for matplotlib's own
    PNG (drawn as raw RGBA by the same ``print_figure``, on the figure's Agg canvas when it has
    one: see :func:`lay_out`), written by :func:`png_file`."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    previous = figure.canvas
    canvas = previous if isinstance(previous, FigureCanvasAgg) else FigureCanvasAgg(figure)
    buffer = io.BytesIO()
    try:
        with ticks_kept(figure):
            canvas.print_figure(buffer, format="rgba", dpi=PNG_DPI)
        renderer = canvas.renderer  # the one just drawn on, at the PNG's resolution
        width, height = int(renderer.width), int(renderer.height)
    finally:
        if canvas is not previous:
            figure.set_canvas(previous)
    return png_file(buffer.getbuffer(), width, height, dpi=PNG_DPI)


def _chunk(kind: bytes, data: bytes) -> bytes:
    """One PNG chunk: length, type, data, CRC of type and data."""
    import zlib

    return (
        len(data).to_bytes(4, "big")
        + kind
        + data
        + (zlib.crc32(data, zlib.crc32(kind)) & 0xFFFFFFFF).to_bytes(4, "big")
    )


def png_file(rgba: bytes | memoryview, width: int, height: int, *, dpi: float) -> bytes:
    """A PNG file of 8-bit RGBA pixels, every row unfiltered and the whole compressed by zlib
    at level :data:`PNG_COMPRESSION`, with the chunks matplotlib's own PNG has (its
    ``Software`` text and the resolution).

    Pillow, which matplotlib's PNG goes through, tries four filters on every row and keeps the
    one whose bytes sum least: for the report's figures that choice took about as long as the
    compression itself, and the files come out no smaller than unfiltered ones (large areas
    of one colour compress as well either way). The pixels are the same.

    Parameters
    ----------
    rgba : bytes or memoryview
        The pixels, row by row from the top, 4 bytes each (red, green, blue, alpha).
    width, height : int
        The image's size (pixels).
    dpi : float
        The resolution stored in the file (dots per inch).

    Returns
    -------
    bytes
        The PNG file.

    Examples
    --------
    >>> import io, PIL.Image
    >>> png = png_file(bytes([255, 0, 0, 255]) * 6, 3, 2, dpi=110)
    >>> image = PIL.Image.open(io.BytesIO(png))
    >>> image.mode, image.size, image.getpixel((2, 1)), round(image.info["dpi"][0])
    ('RGBA', (3, 2), (255, 0, 0, 255), 110)
    """
    import zlib

    import matplotlib

    stride = 4 * width
    view = memoryview(rgba).cast("B")
    if len(view) != stride * height:
        raise ValueError(f"{len(view)} bytes are not {width} x {height} RGBA pixels")
    compressor = zlib.compressobj(PNG_COMPRESSION)
    parts = []
    row_filter = b"\x00"  # filter type 0: the row as it is
    for top in range(0, height, 256):  # rows in blocks: no full copy of the image
        block = view[top * stride : min(height, top + 256) * stride]
        rows = [row_filter + block[k : k + stride] for k in range(0, len(block), stride)]
        parts.append(compressor.compress(b"".join(rows)))
    parts.append(compressor.flush())
    per_metre = int(dpi / 0.0254 + 0.5)
    software = f"Matplotlib version{matplotlib.__version__}, https://matplotlib.org/"
    return b"".join(
        (
            b"\x89PNG\r\n\x1a\n",
            _chunk(
                b"IHDR", width.to_bytes(4, "big") + height.to_bytes(4, "big") + b"\x08\x06\0\0\0"
            ),
            _chunk(b"tEXt", b"Software\0" + software.encode("latin-1")),
            _chunk(b"pHYs", per_metre.to_bytes(4, "big") * 2 + b"\x01"),
            _chunk(b"IDAT", b"".join(parts)),
            _chunk(b"IEND", b""),
        )
    )


def _svg(figure: Any, path: str | Path | io.BytesIO) -> None:
    """Write the SVG file of ``figure``, its words written as text in the figure's font stack
    (``'DejaVu Sans', ..., 'Arial', 'Helvetica', ..., sans-serif``) rather than as glyph
    outlines: smaller files, the words searchable and selectable."""
    import matplotlib

    with matplotlib.rc_context({"svg.fonttype": "none"}), ticks_kept(figure):
        figure.savefig(path, format="svg")


def lay_out(figure: Any, *, keep_canvas: bool = False) -> None:
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
    keep_canvas : bool
        Leave the figure on the Agg canvas the layout was measured on: its PNG (:func:`_png`,
        same resolution) is then drawn by the same renderer, whose cache already holds the
        size of every word, instead of measuring them all again on a new canvas (the file is
        the same to the byte). The renderer holds a full-size image buffer as long as the
        figure lives: for a figure drawn and then dropped (a renderer's child).

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
            with ticks_kept(figure):
                engine.execute(figure)
        finally:
            figure.set_dpi(dpi)
            if not keep_canvas:
                figure.set_canvas(canvas)
    figure.set_layout_engine(None)


@functools.lru_cache(maxsize=1)
def _checked_matplotlib() -> bool:
    """Whether the installed matplotlib is one :func:`ticks_kept` was checked with (3.8 to
    3.11: the private ``Axis._update_ticks`` and ``Axis._get_ticklabel_bboxes`` it stands in
    for, and the formatters' ``locs`` or ``_locs``); with another, figures are drawn as
    matplotlib draws them."""
    import matplotlib

    try:
        major, minor = (int(part) for part in matplotlib.__version__.split(".")[:2])
    except ValueError:
        return False
    return (3, 8) <= (major, minor) < (3, 12)


class _KeptTicks:
    """One axis's ticks, made and measured once per state of the axis (:func:`ticks_kept`).

    Stands in for the axis's own ``_update_ticks`` (locator, formatter, tick positions and
    labels: the ticks to draw) and ``_get_ticklabel_bboxes`` (their labels' extents) as
    instance attributes, and calls matplotlib's methods when the axis's state differs from the
    one they were last called in: its view interval, its axes' box on the canvas, the
    figure's resolution, its scale, locators, formatters and tick lists, and the locations its
    formatters last formatted (axes that share an axis share its formatter: another axis's
    ticks may have been formatted since).
    """

    def __init__(self, axis: Any) -> None:
        self.axis = axis
        self.update = type(axis)._update_ticks
        self.boxes = type(axis)._get_ticklabel_bboxes
        self.state: tuple[Any, ...] | None = None
        self.formatted: tuple[Any, Any] = (None, None)
        self.ticks: list[Any] = []
        self.measured: tuple[Any, list[Any], list[Any]] | None = None

    def _state(self) -> tuple[Any, ...]:
        axis = self.axis
        own = axis.__dict__
        return (
            tuple(axis.get_view_interval()),
            axis.axes.bbox.bounds,
            axis.axes.figure.dpi,  # a subfigure's is its figure's
            axis._scale,
            axis.major.locator,
            axis.major.formatter,
            axis.minor.locator,
            axis.minor.formatter,
            own.get("majorTicks"),
            own.get("minorTicks"),
        )

    def _formatted(self) -> tuple[Any, Any]:
        """The locations the formatters last formatted (matplotlib 3.11 keeps them as
        ``_locs``, earlier versions as ``locs``; a new object at every ``set_locs``)."""
        out = []
        for formatter in (self.axis.major.formatter, self.axis.minor.formatter):
            own = getattr(formatter, "__dict__", {})
            out.append(own.get("_locs", own.get("locs")))
        return out[0], out[1]

    def _current(self) -> bool:
        if self.state is None or self.state != self._state():
            return False
        now = self._formatted()
        return now[0] is self.formatted[0] and now[1] is self.formatted[1]

    def update_ticks(self) -> list[Any]:
        """The ticks to draw (``Axis._update_ticks``), made again only in a new state."""
        if not self._current():
            self.ticks = self.update(self.axis)
            self.state = self._state()
            self.formatted = self._formatted()
            self.measured = None
        return list(self.ticks)

    def ticklabel_bboxes(self, ticks: list[Any], renderer: Any) -> tuple[list[Any], list[Any]]:
        """The extents of the labels of ``ticks`` (``Axis._get_ticklabel_bboxes``), measured
        again only for other ticks, another renderer or a new state."""
        if ticks != self.ticks or not self._current():
            return self.boxes(self.axis, ticks, renderer)
        if self.measured is None or self.measured[0] is not renderer:
            first, second = self.boxes(self.axis, ticks, renderer)
            self.measured = (renderer, first, second)
        return list(self.measured[1]), list(self.measured[2])


def _all_axes(figure: Any) -> Iterator[Any]:
    """Every Axes of ``figure``: its own and its subfigures' (``figure.axes``) and the inset
    axes inside them."""
    pending = list(getattr(figure, "axes", ()))
    while pending:
        ax = pending.pop()
        yield ax
        pending.extend(getattr(ax, "child_axes", ()))


@contextlib.contextmanager
def ticks_kept(figure: Any) -> Iterator[None]:
    """Make and measure each axis's ticks once per state while ``figure`` is laid out or drawn.

    In one layout or one draw, matplotlib asks an axis for its ticks again and again: for the
    axis's extent, for each of its spines' extents, for its label's position (and each sibling
    axis's), for its drawing. Each time it runs the locator and the formatter, moves every tick
    and sets every label's text, and the labels are measured again. Inside this block each
    axis does that once per state (:class:`_KeptTicks`: a new view interval, a new position of
    its axes, another resolution or renderer do it again), and gives the same ticks and
    extents in between. The files are the same to the byte (tests/plots/test_render.py).

    Parameters
    ----------
    figure : matplotlib.figure.Figure
        The figure about to be laid out or drawn, not changed meanwhile except by matplotlib's
        layout and drawing.

    Yields
    ------
    None
        Control to the ``with`` block; the axes' own methods are back after it.

    Examples
    --------
    >>> from crankdyn.plots.style import new_figure
    >>> fig, axes = new_figure()
    >>> with ticks_kept(fig):
    ...     "_update_ticks" in vars(axes[0, 0].xaxis)
    True
    >>> "_update_ticks" in vars(axes[0, 0].xaxis)
    False
    """
    if not _checked_matplotlib():
        yield
        return
    kept = []
    for ax in _all_axes(figure):
        for axis in getattr(ax, "_axis_map", {}).values():
            own = axis.__dict__
            if "_update_ticks" in own or "_get_ticklabel_bboxes" in own:
                continue  # kept already (an enclosing block) or changed by someone else
            memo = _KeptTicks(axis)
            own["_update_ticks"] = memo.update_ticks
            own["_get_ticklabel_bboxes"] = memo.ticklabel_bboxes
            kept.append(axis)
    try:
        yield
    finally:
        for axis in kept:
            axis.__dict__.pop("_update_ticks", None)
            axis.__dict__.pop("_get_ticklabel_bboxes", None)


@contextlib.contextmanager
def collector_paused() -> Iterator[None]:
    """Pause Python's cyclic garbage collector while figures are made and drawn (a report, a
    study's summary), and resume it after.

    The figures live to the end of that work, so the collector's automatic passes free nothing
    there: each full pass traverses every object the process has imported and made (about a
    tenth of a second with matplotlib's figures, several times in a report), and after a fork
    it writes to pages the children share, so that they are copied. The children of a
    :class:`Renderer` run without it too. On resuming, what was made meanwhile joins the
    oldest generation (:func:`gc.freeze` then :func:`gc.unfreeze`, unless objects are frozen
    already), as if it had survived the young passes it was spared, so that the next young
    pass does not traverse it all at once; a later full pass frees it as usual.

    Yields
    ------
    None
        Control to the ``with`` block, the collector paused.

    Examples
    --------
    >>> with collector_paused():
    ...     gc.isenabled()
    False
    >>> gc.isenabled()
    True
    """
    was = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if gc.get_freeze_count() == 0:
            gc.freeze()
            gc.unfreeze()
        if was:
            gc.enable()


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
    return max(1, min(available_cores(), count))


_PREPARED = False


def prepare_children() -> None:
    """Load in this process, once, what every child of a :class:`Renderer` would otherwise load
    for itself: the Agg and SVG backends, the PNG writer with the image plugins Pillow loads at
    its first save (``PIL.Image.preinit``: BMP, GIF, JPEG, PPM, about 10 ms a child) and the
    default font (its file read and its glyph tables built by a measured word).

    A renderer does this before its first child; a caller that waits for other work (a study
    runner while its workers run the cases) may do it earlier, off the path of the figures.
    """
    global _PREPARED
    if _PREPARED:
        return
    import matplotlib.backends.backend_agg as agg
    import matplotlib.backends.backend_svg  # noqa: F401
    import PIL.Image
    import PIL.PngImagePlugin

    from crankdyn.plots.style import Figure

    PIL.Image.preinit()

    figure = Figure(figsize=(1.0, 1.0))
    text = figure.text(0.5, 0.5, "Crank angle (deg) 0123456789")
    text.get_window_extent(agg.FigureCanvasAgg(figure).get_renderer())
    _PREPARED = True


class Renderer:
    """Figures drawn to PNG and SVG in forked children from the moment they are submitted (module
    docstring).

    Parameters
    ----------
    workers : int or None
        Children drawing at a time (default: one per core); 1 draws every figure here, when its
        results are asked for.

    Examples
    --------
    >>> from crankdyn.plots.style import new_figure
    >>> fig, axes = new_figure()
    >>> _ = axes[0, 0].plot([0.0, 1.0], [0.0, 1.0])
    >>> with Renderer() as renderer:
    ...     index = renderer.submit(fig)
    ...     ((png, svg),) = renderer.results()
    >>> png[:4], svg.lstrip()[:5]
    (b'\\x89PNG', b'<?xml')
    """

    def __init__(self, workers: int | None = None) -> None:
        self.workers = available_cores() if workers is None else max(1, workers)
        """Children drawing at a time."""
        self._forking = self.workers > 1 and can_fork()
        self._figures: list[Any] = []
        self._cost: list[int] = []  # per figure: its axes (the largest is started first)
        self._parts: list[tuple[str, ...]] = []  # per figure: ("both",), ("png",), ("png", "svg")
        self._index: dict[int, int] = {}  # id(figure) -> index
        self._queue: list[tuple[int, str]] = []  # (figure, part) not started yet
        self._running: dict[int, tuple[int, int, str]] = {}  # read end -> (pid, figure, part)
        self._left: list[int] = []  # per figure: parts not finished by a child
        self._finished: list[int] = []  # figures whose children are all done, in that order
        self._busy = False
        self._folder: Path | None = None

    # -- submitting ------------------------------------------------------------------------
    def submit(self, figure: Any, *, svg: bool = True, split: bool = False) -> int:
        """Draw ``figure`` (its PNG, and its SVG unless ``svg`` is false) as soon as a child is
        free; submitting a figure again returns its first index.

        Parameters
        ----------
        figure : matplotlib.figure.Figure
            The figure; not to be changed after it is submitted.
        svg : bool
            Whether its SVG is drawn too.
        split : bool
            Draw its PNG and its SVG in two children of their own (each lays the figure out
            itself): for fewer figures than cores.

        Returns
        -------
        int
            The figure's index in :meth:`results`.
        """
        known = self._index.get(id(figure))
        if known is not None:
            return known
        index = len(self._figures)
        self._figures.append(figure)
        self._cost.append(len(getattr(figure, "axes", ())))
        self._index[id(figure)] = index
        parts = ("png", "svg") if svg and split else ("both",) if svg else ("png",)
        self._parts.append(parts)
        self._left.append(len(parts))
        self._queue.extend((index, part) for part in parts)
        self._start()
        return index

    def busy(self, busy: bool = True) -> None:
        """Say whether this process is still making figures: while it is, one child fewer
        draws (its own work takes a core).

        Parameters
        ----------
        busy : bool
            True while figures are still being made here.
        """
        self._busy = busy
        self._start()

    def __contains__(self, figure: object) -> bool:
        return id(figure) in self._index

    # -- children --------------------------------------------------------------------------
    def _reap(self, block: bool) -> None:
        """Collect the children that have finished (waiting for one at least when ``block``):
        a child's pipe reads as ended when it exits."""
        if not self._running:
            return
        ready, _, _ = select.select(list(self._running), [], [], None if block else 0.0)
        for fd in ready:
            pid, index, _ = self._running.pop(fd)
            os.close(fd)
            os.waitpid(pid, 0)  # a child that failed left no file: its figure is drawn here
            self._left[index] -= 1
            if self._left[index] == 0:
                self._finished.append(index)

    def _start(self) -> None:
        """Start children for queued figures while there is room."""
        if not self._forking or not self._queue:
            return
        self._reap(block=False)
        if self._folder is None:
            try:
                self._folder = Path(tempfile.mkdtemp(prefix="crankdyn-plots-"))
            except OSError:  # no temporary folder: draw here instead
                self._forking = False
                return
            prepare_children()
        room = max(1, self.workers - 1) if self._busy else self.workers
        while self._queue and len(self._running) < room:
            # the figure with the most axes first (their count is a fair measure of the drawing
            # time): the small ones left for the end fill both cores to the last
            at = max(range(len(self._queue)), key=lambda k: self._cost[self._queue[k][0]])
            index, part = self._queue[at]
            # SIGINT and SIGTERM held across the fork: a signal handled in the child before its
            # try (the command line's handlers raise) would unwind it into this process's
            # stack, to run on as a copy of it (close() then waits for it for ever)
            mask = hold_signals()
            try:
                read, write = os.pipe()
                pid = os.fork()
            except OSError:  # no more processes: the rest are drawn here
                release_signals(mask)
                self._forking = False
                return
            if pid == 0:  # the child: draw, write, exit without running this process's exits
                code = 1
                try:
                    # the default actions (close()'s SIGTERM ends the child), released; no
                    # collector passes (a child lives for one figure); its own streams
                    child_setup(mask)
                    os.close(read)
                    self._draw(index, part)
                    code = 0
                finally:
                    os._exit(code)
            release_signals(mask)
            os.close(write)
            self._queue.pop(at)
            self._running[read] = (pid, index, part)

    def _files(self, index: int) -> tuple[Path, Path]:
        assert self._folder is not None
        return self._folder / f"{index}.png", self._folder / f"{index}.svg"

    def _draw(self, index: int, part: str) -> None:
        """In a child: draw figure ``index``'s ``part`` into the private folder (each file
        written aside and renamed, so that a file there is complete)."""
        figure = self._figures[index]
        png_path, svg_path = self._files(index)
        with ticks_kept(figure):  # the PNG's draw finds the ticks of the layout's last pass
            lay_out(figure, keep_canvas=True)  # this process ends with the figure drawn
            if part in ("png", "both"):
                aside = png_path.with_suffix(".part")
                aside.write_bytes(_png(figure))
                os.replace(aside, png_path)
            if part in ("svg", "both"):
                aside = svg_path.with_suffix(".svg-part")
                _svg(figure, aside)
                os.replace(aside, svg_path)

    # -- results ---------------------------------------------------------------------------
    def results(
        self, progress: Callable[[int], object] | None = None
    ) -> list[tuple[bytes, bytes | None]]:
        """Wait for every figure submitted and return its files.

        Parameters
        ----------
        progress : callable or None
            ``progress(i)`` is called as figure ``i`` is done (in the order they finish).

        Returns
        -------
        list of (bytes, bytes or None)
            Each figure's PNG file and its SVG file (None when not asked for), in the order
            they were submitted.
        """
        self._busy = False
        told = 0
        while self._forking and (self._queue or self._running):
            self._start()
            self._reap(block=True)
            for index in self._finished[told:]:
                if progress is not None:
                    progress(index)
            told = len(self._finished)
        drawn = set(self._finished)
        out: list[tuple[bytes, bytes | None]] = []
        for i, figure in enumerate(self._figures):
            wants_svg = self._parts[i] != ("png",)
            png = svg = None
            if i in drawn and self._folder is not None:
                png_path, svg_path = self._files(i)
                png = _read(png_path)
                svg = _read(svg_path) if wants_svg else None
            if png is None or (wants_svg and svg is None):  # not drawn by a child: here
                with ticks_kept(figure):
                    lay_out(figure)
                    png = _png(figure)
                    if wants_svg:
                        buffer = io.BytesIO()
                        _svg(figure, buffer)
                        svg = buffer.getvalue()
                if progress is not None:
                    progress(i)
            out.append((png, svg))
        return out

    def close(self) -> None:
        """Stop the children still drawing and remove the private folder."""
        for pid, _, _ in self._running.values():
            with contextlib.suppress(OSError):
                os.kill(pid, signal.SIGTERM)
        for fd, (pid, _, _) in self._running.items():
            with contextlib.suppress(OSError):
                os.close(fd)
            with contextlib.suppress(OSError):
                os.waitpid(pid, 0)
        self._running.clear()
        self._queue.clear()
        if self._folder is not None:
            shutil.rmtree(self._folder, ignore_errors=True)
            self._folder = None

    def __enter__(self) -> Renderer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def _read(path: Path | None) -> bytes | None:
    """The contents of ``path``, or None when it is not there."""
    if path is None:
        return None
    try:
        return path.read_bytes()
    except OSError:
        return None


def render_figures(
    jobs: Sequence[tuple[object, str | Path | None, str | Path | None]],
    *,
    progress: Callable[[int], object] | None = None,
    workers: int | None = None,
    renderer: Renderer | None = None,
) -> list[bytes]:
    """Render figures to PNG (and SVG with the PNG's layout) on every core, and write them.

    Parameters
    ----------
    jobs : sequence of (figure, path or None, path or None)
        Each a matplotlib Figure, the PNG file to write (None: bytes only) and the SVG file to
        write (None: none). PNGs are drawn at :data:`PNG_DPI` dots per inch.
    progress : callable or None
        ``progress(i)`` is called as figure ``i`` is done.
    workers : int or None
        Children drawing at a time (default :func:`workers_for`); 1 renders here.
    renderer : Renderer or None
        A renderer the figures may already have been submitted to (drawing since); None: one
        made here.

    Returns
    -------
    list of bytes
        Every figure's PNG file contents, in the order of ``jobs``.
    """
    jobs = list(jobs)
    own = renderer is None
    if renderer is None:
        renderer = Renderer(workers)
    try:
        # fewer figures than cores (a study's summary: one figure): the PNG and the SVG of a
        # figure are drawn by children of their own, each laying the figure out
        split = own and workers is None and len(jobs) < renderer.workers
        indices = [
            renderer.submit(figure, svg=svg_path is not None, split=split)
            for figure, _, svg_path in jobs
        ]
        by_index = {index: k for k, index in enumerate(indices)}

        def told(index: int) -> None:
            if progress is not None and index in by_index:
                progress(by_index[index])

        results = renderer.results(progress=told)
    finally:
        if own:
            renderer.close()
    pngs = []
    for (_, png_path, svg_path), index in zip(jobs, indices, strict=True):
        png, svg = results[index]
        if png_path is not None:
            Path(png_path).write_bytes(png)
        if svg_path is not None and svg is not None:
            Path(svg_path).write_bytes(svg)
        pngs.append(png)
    return pngs
