"""Shared figure conventions: size, grid, labels with units, crank-angle axes."""

from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure
from matplotlib.ticker import MultipleLocator

__all__ = ["angle_axis", "new_figure"]

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
