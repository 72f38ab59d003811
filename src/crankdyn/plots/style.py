"""Shared figure conventions: size, grid, labels with units, crank-angle axes; user text shown
as written."""

from __future__ import annotations

from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING, Any

import matplotlib.figure
import numpy as np
from matplotlib.axis import Axis
from matplotlib.text import Text
from matplotlib.ticker import LogFormatter, MultipleLocator, NullFormatter, ScalarFormatter
from numpy.typing import ArrayLike

from crankdyn.display import printable

if TYPE_CHECKING:
    from matplotlib.artist import Artist
    from matplotlib.axes import Axes
    from matplotlib.backend_bases import RendererBase
    from matplotlib.legend import Legend

__all__ = [
    "Figure",
    "angle_axis",
    "closed",
    "coinciding",
    "identical",
    "legend_outside",
    "new_figure",
    "number_ranges",
    "plain_text",
]


def _writes_math(formatter: object) -> bool:
    """Whether a tick formatter writes its labels in mathtext (log axes' powers of ten, a
    scalar formatter asked to); other tick labels are numbers or text set by the caller."""
    return isinstance(formatter, LogFormatter) or (
        isinstance(formatter, ScalarFormatter) and formatter.get_useMathText()
    )


def _writes_words(formatter: object) -> bool:
    """Whether a tick formatter's labels may hold words (a FixedFormatter's names of cylinders,
    masses, parameters; a FuncFormatter's text): not matplotlib's own number formatter
    (``ScalarFormatter`` itself, whose labels are digits, signs and a point: never a ``$``,
    so mathtext never parses them, whatever ``parse_math`` says), nor the null formatter,
    nor a formatter that writes mathtext."""
    return type(formatter) not in (ScalarFormatter, NullFormatter) and not _writes_math(formatter)


def _texts(artist: Artist) -> Iterator[Text]:
    """The Text artists under ``artist`` that may hold words: titles, axis labels, legends,
    annotations, and tick labels set as text (names of cylinders, masses, parameters); not the
    tick labels of formatters that write numbers or mathtext (:func:`_writes_words`; asking an
    axis for its ticks runs its locator and makes its ticks, which a figure of many panels paid
    at every draw), nor an axis's offset text (``1e6``)."""
    for child in artist.get_children():
        if isinstance(child, Axis):
            yield child.label
            for ticks, formatter in (
                (child.get_major_ticks, child.get_major_formatter()),
                (child.get_minor_ticks, child.get_minor_formatter()),
            ):
                if _writes_words(formatter):
                    for tick in ticks():
                        yield tick.label1
                        yield tick.label2
            continue
        if isinstance(child, Text):
            yield child
        yield from _texts(child)


def plain_text(fig: matplotlib.figure.Figure) -> None:
    """Show the words of a figure as written.

    Mathtext goes off (``parse_math``) on every title, label, legend entry, annotation and text
    tick label, so that a name holding ``$`` or a backslash (an engine called
    ``$\\undefinedcmd$``) is drawn literally instead of failing in matplotlib's math parser.
    crankdyn's own labels use no mathtext (units as ``N·m``, ``rad/s²``). Control characters
    other than line breaks (a name's ESC or BEL) are drawn as their escapes
    (:func:`crankdyn.display.printable`): an SVG holds none (XML forbids them).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure whose texts are made literal (changed in place).

    Examples
    --------
    >>> fig, axes = new_figure()
    >>> _ = axes[0, 0].set_title("engine $x$")
    >>> plain_text(fig)
    >>> axes[0, 0].title.get_parse_math()
    False
    """
    for text in _texts(fig):
        text.set_parse_math(False)
        words = text.get_text()
        if not words.isprintable():  # a name's control characters: escaped (line breaks kept)
            shown = "\n".join(printable(line) for line in words.split("\n"))
            if shown != words:
                text.set_text(shown)


NOTEBOOK_DPI = 96
"""Resolution of a figure shown in a notebook (dots per inch)."""


class Figure(matplotlib.figure.Figure):
    """The figure every crankdyn plot is drawn on (:func:`new_figure`): a matplotlib Figure
    whose words are made literal (:func:`plain_text`) each time it is drawn, whatever text was
    added after it was made; saving, the report and a notebook's display all draw it.

    Parameters
    ----------
    figsize, dpi, facecolor, edgecolor, linewidth, frameon, subplotpars, tight_layout, \
constrained_layout, layout, **kwargs
        Those of :class:`matplotlib.figure.Figure` (``figsize`` in inches, ``dpi`` in dots per
        inch, ``linewidth`` in points).
    """

    def draw(self, renderer: RendererBase) -> None:
        """Draw the figure with its words made literal (:func:`plain_text`) first.

        Parameters
        ----------
        renderer : matplotlib.backend_bases.RendererBase
            The renderer of the canvas being drawn.
        """
        plain_text(self)
        return super().draw(renderer)

    def _repr_png_(self) -> bytes:
        """The figure as PNG bytes, so that a notebook shows it as an image with no
        ``%matplotlib inline`` (IPython's display looks for ``_repr_png_``)."""
        import io

        buffer = io.BytesIO()
        self.savefig(buffer, format="png", dpi=NOTEBOOK_DPI)
        return buffer.getvalue()

    def set(self, **kwargs: Any) -> list[Any]:
        """Set several properties at once, as :meth:`matplotlib.artist.Artist.set` does.

        Parameters
        ----------
        **kwargs
            Property names and values (``figwidth`` in inches, ``dpi`` in dots per inch, ...).

        Returns
        -------
        list
            The values the setters returned.
        """
        return super().set(**kwargs)


COLORS = ("#1f4e79", "#c0504d", "#4f8a3c", "#8064a2", "#d08a1c", "#2aa3b8", "#7f7f7f", "#b5487d")


def new_figure(
    nrows: int = 1,
    ncols: int = 1,
    *,
    width: float = 9.0,
    height: float | None = None,
    fig: matplotlib.figure.Figure | None = None,
    **kw: Any,
) -> tuple[matplotlib.figure.Figure, np.ndarray]:
    """A figure with a grid of axes, light grid lines and constrained layout.

    Parameters
    ----------
    nrows, ncols : int
        Rows and columns of axes.
    width : float
        Width of a new figure (inches).
    height : float or None
        Height of a new figure (inches); None: 2.8 per row plus 0.6.
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new :class:`Figure`.
    **kw
        Passed to :meth:`matplotlib.figure.Figure.subplots` (``sharex``, ...).

    Returns
    -------
    fig : matplotlib.figure.Figure
        The figure.
    axes : numpy.ndarray
        (nrows, ncols) array of its Axes.

    Examples
    --------
    >>> fig, axes = new_figure(2, 3)
    >>> axes.shape, round(float(fig.get_figheight()), 3)
    ((2, 3), 6.2)
    """
    if height is None:
        height = 2.8 * nrows + 0.6
    if fig is None:
        fig = Figure(figsize=(width, height), layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=False, **kw)
    for ax in axes.flat:
        ax.grid(True, color="#d9d9d9", linewidth=0.6)
        ax.set_axisbelow(True)
    return fig, axes


def angle_axis(ax: Axes, angles_deg: ArrayLike, label: str = "Crank angle (deg)") -> None:
    """Label an x axis of crank angle with ticks every 90 degrees (every 180 above a 400-degree
    span), limited to the angles drawn.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes whose x axis is labelled.
    angles_deg : array_like
        The crank angles drawn (degrees).
    label : str
        The axis label.
    """
    span = float(np.max(angles_deg) - np.min(angles_deg)) if np.size(angles_deg) else 360.0
    ax.xaxis.set_major_locator(MultipleLocator(180 if span > 400 else 90))
    ax.set_xlim(float(np.min(angles_deg)), float(np.max(angles_deg)))
    ax.set_xlabel(label)


def legend_outside(
    ax: Axes, *, ncol: int | None = None, title: str | None = None, **kw: Any
) -> Legend | None:
    """The legend of ``ax`` above its plot area (outside the axes, so it covers no curve), in
    as many columns as fit; constrained layout makes room for it. A centred axes title moves
    into the legend's title (so the two do not overlap).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes whose labelled artists are listed.
    ncol : int or None
        Columns of the legend; None: as many as fit the axes' width (about 5.2 points per
        character of the longest label, plus 30 points).
    title : str or None
        The legend's title; None: the axes' centred title, if any.
    **kw
        Passed to :meth:`matplotlib.axes.Axes.legend` (overriding the defaults).

    Returns
    -------
    matplotlib.legend.Legend or None
        The legend, or None when nothing is labelled.
    """
    handles, labels = ax.get_legend_handles_labels()
    if not handles:
        return None
    heading = ax.get_title()
    if heading and title is None:
        title = heading
        ax.set_title("")
    if ncol is None:
        root = ax.figure
        while not hasattr(root, "get_figwidth"):  # a SubFigure: up to the Figure
            root = root.figure
        width = root.get_figwidth() * min(ax.get_position().width, 1.0)
        longest = max(len(label) for label in labels)
        ncol = max(1, min(len(labels), int(width * 72 / (5.2 * longest + 30))))
    handles, labels = _row_major(handles, ncol), _row_major(labels, ncol)
    options: dict[str, Any] = {
        "loc": "lower left",
        "bbox_to_anchor": (0.0, 1.01),
        "ncol": ncol,
        "fontsize": 8,
        "frameon": False,
        "borderaxespad": 0.0,
        "handlelength": 1.6,
        "columnspacing": 1.2,
        "title": title,
        "title_fontsize": 9,
        "alignment": "left",
    }
    options.update(kw)
    return ax.legend(handles, labels, **options)


def _row_major(items: list, ncol: int) -> list:
    """Reorder legend entries so that they read along the rows: matplotlib fills a legend's
    columns one after the other (np.array_split of the entries into ncol columns)."""
    n = len(items)
    sizes = [len(block) for block in np.array_split(np.arange(n), ncol)]
    slots = [(r, c) for r in range(max(sizes, default=0)) for c in range(ncol) if r < sizes[c]]
    placed = dict(zip(slots, items, strict=True))
    return [placed[(r, c)] for c in range(ncol) for r in range(sizes[c])]


def closed(values: ArrayLike, axis: int = -1) -> np.ndarray:
    """``values`` with the first point appended after the last (along ``axis``) unless it is
    there already: a periodic curve drawn over a full cycle then closes on itself.

    Parameters
    ----------
    values : array_like
        Samples of a periodic curve (any unit).
    axis : int
        The axis along which the curve runs.

    Returns
    -------
    numpy.ndarray
        The samples, closed (same unit).

    Examples
    --------
    >>> closed([1.0, 2.0, 3.0])
    array([1., 2., 3., 1.])
    >>> closed([1.0, 2.0, 1.0])
    array([1., 2., 1.])
    """
    arr = np.asarray(values)
    first = np.take(arr, [0], axis=axis)
    last = np.take(arr, [-1], axis=axis)
    if arr.shape[axis] and np.array_equal(first, last):
        return arr
    return np.concatenate([arr, first], axis=axis)


def coinciding(curves: ArrayLike, rtol: float = 1e-3) -> list[list[int]]:
    """Groups of curves that coincide as drawn: curve j joins the group of an earlier curve i
    when, for some cyclic shift of its points, no point lies farther from i's than ``rtol`` x the
    largest extent of all the curves (1e-3: a tenth of a line width on a 6 in plot).

    Parameters
    ----------
    curves : array_like
        (n, m) complex array (x + i y of n closed curves sampled at m points each, the last
        point not repeating the first) or (n, m) real array (any unit, the same for all).
    rtol : float
        Tolerance relative to the curves' largest extent (dimensionless).

    Returns
    -------
    list of lists of int
        Curve indices by group, in order of first appearance.

    Examples
    --------
    >>> t = np.linspace(0.0, 2.0 * np.pi, 8, endpoint=False)
    >>> circle = np.exp(1j * t)
    >>> coinciding([circle, np.roll(circle, 3), 2.0 * circle])
    [[0, 1], [2]]
    """
    z = np.asarray(curves)
    n = z.shape[0]
    scale = float(np.max(np.abs(z - z.mean())) if z.size else 0.0) or 1.0
    spectra = np.fft.fft(z, axis=1)
    groups: list[list[int]] = []
    for j in range(n):
        for group in groups:
            i = group[0]
            # the best cyclic shift maximises the sum of the dot products of the points (the
            # real part of the circular cross-correlation); then the largest distance decides
            corr = np.fft.ifft(spectra[i] * np.conj(spectra[j])).real
            shift = int(np.argmax(corr))
            if np.max(np.abs(np.roll(z[j], shift) - z[i])) <= rtol * scale:
                group.append(j)
                break
        else:
            groups.append([j])
    return groups


def identical(curves: ArrayLike, rtol: float = 1e-3) -> list[list[int]]:
    """Groups of curves equal point by point (no shift): curve j joins the group of an earlier
    curve when no point differs by more than ``rtol`` x the largest |value| of all the curves.

    Parameters
    ----------
    curves : array_like
        (n, m) real or complex array: n curves of m points (any unit, the same for all).
    rtol : float
        Tolerance relative to the largest |value| (dimensionless).

    Returns
    -------
    list of lists of int
        Curve indices by group, in order of first appearance.

    Examples
    --------
    >>> identical([[0.0, 1.0], [0.0, 1.0000001], [1.0, 0.0]])
    [[0, 1], [2]]
    """
    z = np.asarray(curves)
    scale = float(np.max(np.abs(z))) if z.size else 0.0
    scale = scale or 1.0
    groups: list[list[int]] = []
    for j in range(z.shape[0]):
        for group in groups:
            if np.max(np.abs(z[j] - z[group[0]])) <= rtol * scale:
                group.append(j)
                break
        else:
            groups.append([j])
    return groups


def number_ranges(numbers: Iterable[int]) -> str:
    """Whole numbers written as runs, for legend labels of grouped items (cylinders, masses).

    Parameters
    ----------
    numbers : iterable of int
        The numbers, in any order.

    Returns
    -------
    str
        Runs of consecutive numbers as ``first-last``, separated by commas.

    Examples
    --------
    >>> number_ranges([5, 1, 2, 3, 6, 9])
    '1-3, 5-6, 9'
    """
    values = sorted(int(v) for v in numbers)
    parts, start = [], None
    for k, v in enumerate(values):
        if start is None:
            start = v
        if k + 1 == len(values) or values[k + 1] != v + 1:
            parts.append(f"{start}" if start == v else f"{start}-{v}")
            start = None
    return ", ".join(parts)
