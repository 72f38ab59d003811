"""Plots of plane trusses and of force polygons: the truss with its member forces (tension and
compression), and the force polygons of a mechanism's link groups (seed 004)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.patches import Polygon

from crankdyn.plots.style import COLORS, new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import NDArray

    from crankdyn.linkage.polygon import ForcePolygon
    from crankdyn.linkage.truss import Truss, TrussResult

__all__ = ["plot_force_polygons", "plot_truss"]

TENSION, COMPRESSION, ZERO = COLORS[0], COLORS[1], COLORS[6]
MEMBER_LABEL = "member-force"
"""gid of the member-force annotations (tests find them)."""


def _support(ax: Axes, xy: NDArray[np.float64], kind: str, direction: float, size: float) -> None:
    """A support symbol: a triangle under a pin, a triangle on a line for a roller (turned so
    that it pushes along its reaction's direction)."""
    ux, uy = math.cos(direction), math.sin(direction)
    if kind == "pin":
        ux, uy = 0.0, 1.0
    nx, ny = -uy, ux
    x, y = xy
    base = (x - size * ux, y - size * uy)
    tri = [
        (x, y),
        (base[0] + 0.6 * size * nx, base[1] + 0.6 * size * ny),
        (base[0] - 0.6 * size * nx, base[1] - 0.6 * size * ny),
    ]
    ax.add_patch(
        Polygon(tri, closed=True, facecolor="#e6e6e6", edgecolor="#404040", lw=0.8, zorder=1)
    )
    if kind == "roller":
        off = 1.25 * size
        ax.plot(
            [x - off * ux + size * nx, x - off * ux - size * nx],
            [y - off * uy + size * ny, y - off * uy - size * ny],
            color="#404040",
            lw=1.0,
            zorder=1,
        )


def plot_truss(
    truss: Truss, result: TrussResult | None = None, fig: Figure | None = None
) -> Figure:
    """The truss: members (blue in tension, red in compression, grey unloaded when a result is
    given, with the force in N on each), supports and joint loads.

    Parameters
    ----------
    truss : crankdyn.linkage.truss.Truss
        The truss (coordinates in m, loads in N).
    result : crankdyn.linkage.truss.TrussResult or None
        Its member forces (N), or None for the geometry alone.
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(1, 1, width=8.0, height=5.5, fig=fig)
    ax = axes[0, 0]
    xy = np.asarray(truss.coordinates)
    span = float(max(np.ptp(xy[:, 0]), np.ptp(xy[:, 1]), 1e-9))
    ends = truss.member_ends
    forces = None if result is None else np.asarray(result.force)
    for k, (p, q) in enumerate(ends):
        color = "#404040"
        if forces is not None:
            f = forces[k]
            color = TENSION if f > 0 else COMPRESSION if f < 0 else ZERO
        ax.plot(xy[[p, q], 0], xy[[p, q], 1], color=color, lw=2.4, zorder=2)
        if forces is not None:
            mid = 0.5 * (xy[p] + xy[q])
            ax.annotate(
                f"{forces[k]:.4g} N",
                mid,
                fontsize=7,
                color=color,
                ha="center",
                va="center",
                bbox={"boxstyle": "round,pad=0.15", "fc": "white", "ec": "none", "alpha": 0.8},
                zorder=4,
                gid=MEMBER_LABEL,
            )
    for support in truss.supports:
        _support(ax, xy[truss.index(support.node)], support.kind, support.direction, 0.04 * span)
    peak = max((math.hypot(*ld.force) for ld in truss.loads), default=0.0)
    for ld in truss.loads:
        x, y = xy[truss.index(ld.node)]
        fx, fy = ld.force
        if peak <= 0.0 or math.hypot(fx, fy) == 0.0:
            continue
        s = 0.18 * span / peak
        ax.annotate(
            "",
            xy=(x, y),
            xytext=(x - fx * s, y - fy * s),
            arrowprops={"arrowstyle": "-|>", "color": COLORS[4], "lw": 1.4},
            zorder=5,
        )
        ax.annotate(
            f"{math.hypot(fx, fy):.4g} N",
            (x - fx * s, y - fy * s),
            fontsize=7,
            color=COLORS[4],
            ha="center",
            va="bottom" if fy < 0 else "top",
        )
    ax.plot(xy[:, 0], xy[:, 1], "o", ms=5, mfc="white", color="#202020", zorder=6)
    for name, (x, y) in zip(truss.nodes, xy, strict=True):
        ax.annotate(name, (x, y), xytext=(4, 4), textcoords="offset points", fontsize=8)
    pad = 0.25 * span
    ax.set_xlim(xy[:, 0].min() - pad, xy[:, 0].max() + pad)
    ax.set_ylim(xy[:, 1].min() - pad, xy[:, 1].max() + pad)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    if forces is not None:
        ax.plot([], [], color=TENSION, lw=2.4, label="tension")
        ax.plot([], [], color=COMPRESSION, lw=2.4, label="compression")
        ax.legend(loc="upper right", fontsize=8)
    ax.set_title(truss.name)
    return fig


def plot_force_polygons(
    polygons: tuple[ForcePolygon, ...], title: str = "", fig: Figure | None = None
) -> Figure:
    """The force polygons of a mechanism's link groups at one position (seed 004 sec. 2): each
    group's forces drawn head to tail, the known loads solid, the reactions dashed, each
    labelled with its magnitude (N).

    Parameters
    ----------
    polygons : tuple of crankdyn.linkage.polygon.ForcePolygon
        The groups' polygons (:func:`crankdyn.linkage.polygon.force_polygons`), forces in N.
    title : str
        The figure's title (the mechanism and position).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    count = max(len(polygons), 1)
    fig, axes = new_figure(1, count, width=4.2 * count, height=4.8, fig=fig)
    for ax, poly in zip(axes[0], polygons, strict=False):
        corners = poly.vertices
        for k, (f, known) in enumerate(zip(poly.forces, poly.known, strict=True)):
            start, end = corners[k], corners[k + 1]
            color = COLORS[k % len(COLORS)]
            ax.annotate(
                "",
                xy=end,
                xytext=start,
                arrowprops={
                    "arrowstyle": "-|>",
                    "color": color,
                    "lw": 1.6,
                    "linestyle": "-" if known else "--",
                },
            )
            ax.plot([], [], color=color, ls="-" if known else "--", label=poly.labels[k])
            mid = 0.5 * (start + end)
            ax.annotate(f"{math.hypot(*f):.4g} N", mid, fontsize=7, color=color)
        span = float(max(np.ptp(corners[:, 0]), np.ptp(corners[:, 1]), 1e-9))
        pad = 0.12 * span
        ax.set_xlim(corners[:, 0].min() - pad, corners[:, 0].max() + pad)
        ax.set_ylim(corners[:, 1].min() - pad, corners[:, 1].max() + pad)
        ax.set_aspect("equal", adjustable="box")
        ax.set_xlabel("F_x (N)")
        ax.set_ylabel("F_y (N)")
        ax.set_title(poly.group, fontsize=9)
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.18), fontsize=7, frameon=False)
    if title:
        fig.suptitle(title, fontsize=10)
    return fig
