"""Shared figure conventions: size, grid, labels with units, crank-angle axes; user text shown
as written."""

from __future__ import annotations

import matplotlib.figure
import numpy as np
from matplotlib.axis import Axis
from matplotlib.text import Text
from matplotlib.ticker import LogFormatter, MultipleLocator, ScalarFormatter

__all__ = ["Figure", "angle_axis", "new_figure", "plain_text"]


def _writes_math(formatter) -> bool:
    """Whether a tick formatter writes its labels in mathtext (log axes' powers of ten, a
    scalar formatter asked to); other tick labels are numbers or text set by the caller."""
    return isinstance(formatter, LogFormatter) or (
        isinstance(formatter, ScalarFormatter) and formatter.get_useMathText()
    )


def _texts(artist):
    """The Text artists under ``artist`` that may hold words: titles, axis labels, legends,
    annotations, and tick labels set as text (names of cylinders, masses, parameters); not the
    tick labels of formatters that write mathtext, nor an axis's offset text (``1e6``)."""
    for child in artist.get_children():
        if isinstance(child, Axis):
            yield child.label
            for ticks, formatter in (
                (child.get_major_ticks, child.get_major_formatter()),
                (child.get_minor_ticks, child.get_minor_formatter()),
            ):
                if not _writes_math(formatter):
                    for tick in ticks():
                        yield tick.label1
                        yield tick.label2
            continue
        if isinstance(child, Text):
            yield child
        yield from _texts(child)


def plain_text(fig) -> None:
    """Show the words of a figure as written: mathtext off (``parse_math``) on every title,
    label, legend entry, annotation and text tick label, so that a name holding ``$`` or a
    backslash (an engine called ``$\\undefinedcmd$``) is drawn literally instead of failing in
    matplotlib's math parser. crankdyn's own labels use no mathtext (units as ``N·m``, ``rad/s²``).
    """
    for text in _texts(fig):
        text.set_parse_math(False)


class Figure(matplotlib.figure.Figure):
    """The figure every crankdyn plot is drawn on (:func:`new_figure`): a matplotlib Figure
    whose words are made literal (:func:`plain_text`) each time it is drawn, whatever text was
    added after it was made; saving, the report and a notebook's display all draw it."""

    def draw(self, renderer):
        plain_text(self)
        return super().draw(renderer)


COLORS = ("#1f4e79", "#c0504d", "#4f8a3c", "#8064a2", "#d08a1c", "#2aa3b8", "#7f7f7f", "#b5487d")


def new_figure(
    nrows: int = 1,
    ncols: int = 1,
    *,
    width: float = 9.0,
    height: float | None = None,
    fig: Figure | None = None,
    **kw,
):
    """A Figure with a grid of axes (returned as a 2-D array), constrained layout."""
    if height is None:
        height = 2.8 * nrows + 0.6
    if fig is None:
        fig = Figure(figsize=(width, height), layout="constrained")
    axes = fig.subplots(nrows, ncols, squeeze=False, **kw)
    for ax in axes.flat:
        ax.grid(True, color="#d9d9d9", linewidth=0.6)
        ax.set_axisbelow(True)
    return fig, axes


def angle_axis(ax, angles_deg: np.ndarray, label: str = "Crank angle (deg)") -> None:
    """Label an x axis of crank angle with ticks every 90 (or 180) degrees."""
    span = float(np.max(angles_deg) - np.min(angles_deg)) if np.size(angles_deg) else 360.0
    ax.xaxis.set_major_locator(MultipleLocator(180 if span > 400 else 90))
    ax.set_xlim(float(np.min(angles_deg)), float(np.max(angles_deg)))
    ax.set_xlabel(label)
