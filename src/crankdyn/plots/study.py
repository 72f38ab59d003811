"""Plots of parameter studies: sensitivity (figure against each parameter, with the main
effect) and the distributions of the figures over the cases."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.ticker import MaxNLocator

from crankdyn.plots.style import COLORS, new_figure, plain_text
from crankdyn.plots.style import Figure as _Figure
from crankdyn.study.sensitivity import main_effect, negligible_spread, spearman

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.backend_bases import RendererBase
    from matplotlib.figure import Figure

__all__ = ["Series", "plot_distributions", "plot_sensitivity"]


@dataclass(frozen=True)
class Series:
    """Values over the cases with their label and display unit (numbers already scaled to it,
    or text for a categorical parameter).

    Parameters
    ----------
    label : str
        What the values are (a figure or a parameter of the study).
    unit : str
        The display unit the values are in (``""``: dimensionless or text).
    values : numpy.ndarray
        One value per case, in ``unit`` (numbers, or text for a categorical parameter).
    numeric : bool
        Whether the values are numbers (else categories).

    Examples
    --------
    >>> Series("Peak pressure", "MPa", np.array([15.1, 15.4])).axis_label
    'Peak pressure (MPa)'
    """

    label: str
    unit: str
    values: np.ndarray
    numeric: bool = True

    @property
    def axis_label(self) -> str:
        """The axis label: the label with the unit in parentheses (none when dimensionless)."""
        return f"{self.label} ({self.unit})" if self.unit else self.label


def _short(text: str, limit: int = 16) -> str:
    text = str(text)
    return text if len(text) <= limit else text[: limit - 1] + "…"


def _panel(ax: Axes, y: np.ndarray, p: Series, legend: bool, constant: bool) -> None:
    effect = main_effect(p.values, y, numeric=p.numeric)
    if p.numeric:
        x = np.asarray(p.values, dtype=float)
        ax.plot(x, y, "o", color=COLORS[0], alpha=0.35, markersize=3.5, label="cases")
        ax.plot(
            np.asarray(effect.levels, dtype=float),
            effect.means,
            "-s" if effect.binned else "-o",
            color=COLORS[1],
            linewidth=1.6,
            markersize=4,
            label="mean per bin" if effect.binned else "mean per value",
        )
        rho = math.nan if constant else spearman(x, y)
        note = f"ρ = {rho:+.2f}" if math.isfinite(rho) else "ρ undefined"
    else:
        labels = [str(v) for v in effect.levels]
        where = {label: i for i, label in enumerate(labels)}
        x = np.array([where.get(str(v), -1) for v in p.values], dtype=float)
        keep = x >= 0
        jitter = (np.arange(x.size) % 7 - 3) * 0.03
        ax.plot(
            x[keep] + jitter[keep],
            y[keep],
            "o",
            color=COLORS[0],
            alpha=0.35,
            markersize=3.5,
            label="cases",
        )
        ax.plot(
            np.arange(len(labels)),
            effect.means,
            "-o",
            color=COLORS[1],
            linewidth=1.6,
            markersize=4,
            label="mean per value",
        )
        ax.set_xticks(np.arange(len(labels)))
        slanted = max((len(s) for s in labels), default=0) > 6 or len(labels) > 4
        ax.set_xticklabels(
            [_short(s) for s in labels],
            rotation=20 if slanted else 0,
            ha="right" if slanted else "center",
            fontsize=8,
        )
        ax.set_xlim(-0.5, len(labels) - 0.5)
        note = ""
    if constant:
        note = "the same in every case"
    if note:
        ax.text(
            0.03,
            0.95,
            note,
            transform=ax.transAxes,
            ha="left",
            va="top",
            fontsize=8,
            bbox={"boxstyle": "round,pad=0.2", "facecolor": "white", "edgecolor": "#d9d9d9"},
        )
    if legend:
        ax.legend(fontsize=7, loc="lower right")


def plot_sensitivity(
    figures: list[Series], parameters: list[Series], fig: Figure | None = None
) -> Figure:
    """A grid of panels, one row per figure and one column per parameter: the figure of every
    finished case against the parameter (points) and its main effect, the mean per value or bin
    (line), with Spearman's rho for numeric parameters (formulas and sources, Saltelli et al.
    2008 for the main effect, in :mod:`crankdyn.study.sensitivity`). Rows share their y axis,
    columns their x axis.

    Parameters
    ----------
    figures : list of Series
        The study's figures over the finished cases (each in its display unit).
    parameters : list of Series
        The varied parameters over the same cases (each in its display unit, or text).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    nrows, ncols = len(figures), len(parameters)
    width, height = min(3.3 * ncols + 0.9, 16.0), 2.3 * nrows + 0.8
    fixed = fig is None
    fig, axes = new_figure(
        nrows,
        ncols,
        width=width,
        height=height,
        fig=_Figure(figsize=(width, height)) if fixed else fig,
        sharex="col",
        sharey="row",
    )
    for i, f in enumerate(figures):
        y = np.asarray(f.values, dtype=float)
        finite = y[np.isfinite(y)]
        constant = negligible_spread(finite)
        for j, p in enumerate(parameters):
            ax = axes[i, j]
            _panel(ax, y, p, legend=(i == 0 and j == 0), constant=constant)
            ax.ticklabel_format(axis="y", useOffset=False, style="plain")
            if p.numeric:
                ax.xaxis.set_major_locator(MaxNLocator(nbins=5))
            if j == 0:
                ax.set_ylabel(_wrap(f.axis_label), fontsize=9)
            if i == nrows - 1:
                ax.set_xlabel(p.axis_label)
        if constant:
            middle = float(finite.mean())
            pad = 0.01 * abs(middle) or 1.0
            axes[i, 0].set_ylim(middle - pad, middle + pad)
    fig.suptitle("Sensitivity of the figures to the parameters")
    if fixed:
        grid_layout(fig, axes)
    return fig


LAYOUT_PAD = 4 / 72
"""Space around and between the panels of a fixed grid layout (inches)."""


def _outer_extents(
    axes: np.ndarray, renderer: RendererBase, dpi: float
) -> dict[tuple[int, int], tuple[float, float, float, float]]:
    """How far the outer panels' axis labels reach beyond their frames (inches: left, right,
    below, above): the y axes of the first column and the x axes of the bottom row, where a
    grid whose rows share y and columns share x shows its tick labels and axis labels (inner
    panels show tick marks only, which :data:`LAYOUT_PAD` covers)."""
    nrows, ncols = axes.shape
    reach: dict[tuple[int, int], tuple[float, float, float, float]] = {}
    for key, axis in [((i, 0), axes[i, 0].yaxis) for i in range(nrows)] + [
        ((nrows - 1, j), axes[nrows - 1, j].xaxis) for j in range(ncols)
    ]:
        frame = axis.axes.get_window_extent(renderer)
        tight = axis.get_tightbbox(renderer)
        mine = (
            (0.0, 0.0, 0.0, 0.0)
            if tight is None
            else (
                max(0.0, frame.x0 - tight.x0) / dpi,
                max(0.0, tight.x1 - frame.x1) / dpi,
                max(0.0, frame.y0 - tight.y0) / dpi,
                max(0.0, tight.y1 - frame.y1) / dpi,
            )
        )
        before = reach.get(key, (0.0, 0.0, 0.0, 0.0))
        reach[key] = (
            max(before[0], mine[0]),
            max(before[1], mine[1]),
            max(before[2], mine[2]),
            max(before[3], mine[3]),
        )
    return reach


def grid_layout(fig: Figure, axes: np.ndarray, passes: int = 2) -> None:
    """Lay out a grid of panels whose rows share y and columns share x once, as a fixed
    layout: the margins and gaps measured from the outer panels' labels (the first column's
    y labels, the bottom row's x labels, the suptitle), every panel the same size. Constrained
    layout finds the same kind of grid by measuring every panel twice at every draw (most of a
    large grid's drawing time, paid again for its SVG); this measures the outer ones, at the
    PNG's resolution, ``passes`` times (the tick labels may change with the panels' size).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A figure without a layout engine, holding ``axes`` and perhaps a suptitle.
    axes : numpy.ndarray
        (rows, columns) array of its Axes, made by ``fig.subplots``.
    passes : int
        Measurements (>= 1).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from crankdyn.plots.render import PNG_DPI

    plain_text(fig)  # measured as drawn
    dpi, canvas = fig.get_dpi(), fig.canvas
    fig.set_dpi(PNG_DPI)
    renderer = FigureCanvasAgg(fig).get_renderer()
    width, height = fig.get_size_inches()
    nrows, ncols = axes.shape
    pad = LAYOUT_PAD
    title = getattr(fig, "_suptitle", None)  # the figure's suptitle, when it has one
    title_height = 0.0
    if title is not None:
        extent = title.get_window_extent(renderer)
        title_height = extent.height / PNG_DPI
        title.set_y(1.0 - pad / height)
        title.set_verticalalignment("top")
    try:
        for _ in range(max(1, passes)):
            reach = _outer_extents(axes, renderer, PNG_DPI)
            left = max(reach[i, 0][0] for i in range(nrows)) + pad
            right = reach[nrows - 1, ncols - 1][1] + pad
            bottom = max(reach[nrows - 1, j][2] for j in range(ncols)) + pad
            top = reach[0, 0][3] + pad
            if title_height:
                top += title_height + pad
            wgap = pad + max(
                (reach[nrows - 1, j][1] + reach[nrows - 1, j + 1][0] for j in range(ncols - 1)),
                default=0.0,
            )
            hgap = pad + max(
                (reach[i, 0][2] + reach[i + 1, 0][3] for i in range(nrows - 1)), default=0.0
            )
            panel_w = (width - left - right - (ncols - 1) * wgap) / ncols
            panel_h = (height - top - bottom - (nrows - 1) * hgap) / nrows
            if panel_w <= 0 or panel_h <= 0:  # labels larger than the figure: leave as made
                return
            fig.subplots_adjust(
                left=left / width,
                right=1.0 - right / width,
                bottom=bottom / height,
                top=1.0 - top / height,
                wspace=wgap / panel_w,
                hspace=hgap / panel_h,
            )
    finally:
        fig.set_dpi(dpi)
        fig.set_canvas(canvas)


def _wrap(text: str, width: int = 26) -> str:
    """Break a long axis label onto two lines at a space near the middle."""
    if len(text) <= width:
        return text
    cut = text.rfind(" ", 0, len(text) // 2 + 6)
    return text if cut <= 0 else text[:cut] + "\n" + text[cut + 1 :]


def plot_distributions(
    figures: list[Series], fig: Figure | None = None, columns: int = 3
) -> Figure:
    """Histogram of every figure over the finished cases (a Monte Carlo study's output
    distributions), with the mean and the 5 % and 95 % quantiles marked.

    Parameters
    ----------
    figures : list of Series
        The study's figures over the finished cases (each in its display unit).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.
    columns : int
        Panels per row, at most.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    n = len(figures)
    ncols = min(n, columns)
    nrows = math.ceil(n / ncols)
    fig, axes = new_figure(nrows, ncols, width=3.8 * ncols + 0.6, height=2.9 * nrows + 0.7, fig=fig)
    for ax, f in zip(axes.flat, figures, strict=False):
        values = np.asarray(f.values, dtype=float)
        values = values[np.isfinite(values)]
        if values.size == 0:
            ax.text(0.5, 0.5, "no finite values", ha="center", va="center", transform=ax.transAxes)
            ax.set_xlabel(f.axis_label)
            continue
        bins = int(np.clip(np.sqrt(values.size), 5, 40))
        ax.hist(values, bins=bins, color=COLORS[0], alpha=0.8)
        mean = float(values.mean())
        low, high = np.quantile(values, [0.05, 0.95])
        ax.axvline(mean, color=COLORS[1], linewidth=1.6, label=f"mean {mean:.4g}")
        ax.axvline(low, color=COLORS[3], linewidth=1.0, linestyle="--", label="5 % / 95 %")
        ax.axvline(high, color=COLORS[3], linewidth=1.0, linestyle="--")
        ax.ticklabel_format(axis="x", useOffset=False, style="plain")
        ax.xaxis.set_major_locator(MaxNLocator(nbins=4))
        ax.set_xlabel(_wrap(f.axis_label, 40))
        ax.set_ylabel("cases")
        ax.legend(fontsize=8, loc="best")
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    fig.suptitle("Distribution of the figures over the cases")
    return fig
