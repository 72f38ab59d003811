"""Plots of the crankshaft's beam model: mode shapes in three projections and the forced
response against speed."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING

import numpy as np

from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.plots.style import COLORS, new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.crankshaft.beam_modes import BeamModesResult
    from crankdyn.crankshaft.beam_response import BeamResponseResult

__all__ = ["plot_axial_response", "plot_beam_mode_shapes"]

HZ = 1.0 / (2.0 * np.pi)
VIEWS = (
    (2, 0, "side view: z (m)", "x (m)"),
    (2, 1, "top view: z (m)", "y (m)"),
    (0, 1, "end view from the free end: x (m)", "y (m)"),
)
"""The three projections: (horizontal axis, vertical axis, labels); z along the shaft from the
free end, x and y across it."""


def _chosen(result: BeamModesResult, modes: Iterable[int] | None) -> list[int]:
    """1-based mode numbers: given (checked), else the first four elastic modes."""
    if modes is None:
        elastic = [int(m) for m, lab in zip(result.mode, result.motion, strict=True)]
        elastic = [m for m, lab in zip(elastic, result.motion, strict=True) if "rigid" not in lab]
        return elastic[:4] or [int(result.mode[0])]
    chosen = [int(m) for m in modes]
    for m in chosen:
        if not 1 <= m <= result.mode.size:
            raise InputError(
                f"expected modes from 1 to {result.mode.size}", key="modes", value=chosen
            )
    return chosen


def _segments(
    xyz: np.ndarray, a: np.ndarray, b: np.ndarray, h: int, v: int
) -> tuple[np.ndarray, np.ndarray]:
    """The elements a-b as one polyline broken by NaN (one artist per panel)."""
    gap = np.full(a.size, np.nan)
    return (
        np.stack([xyz[a, h], xyz[b, h], gap], axis=1).ravel(),
        np.stack([xyz[a, v], xyz[b, v], gap], axis=1).ravel(),
    )


def plot_beam_mode_shapes(
    result: BeamModesResult, modes: Iterable[int] | None = None, fig: Figure | None = None
) -> Figure:
    """The shapes of the beam model's modes: one row per mode, the crankshaft's centre lines
    undeformed (grey) and deformed (coloured, the largest translation drawn as a fifth of a
    bearing span) in three projections (side, top and end views, :data:`VIEWS`).

    Parameters
    ----------
    result : crankdyn.crankshaft.beam_modes.BeamModesResult
        The modes, with their model and shapes.
    modes : iterable of int or None
        Mode numbers (from 1, as the result lists them); None: the first four elastic modes.
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.

    Raises
    ------
    crankdyn.errors.InputError
        A mode not computed, or a result without its model.
    """
    model = result.model
    if model is None:
        raise InputError("the modes' model is not held (a result read back from a file)")
    chosen = _chosen(result, modes)
    fig, axes = new_figure(len(chosen), 3, width=12.0, height=2.6 * len(chosen) + 0.8, fig=fig)
    axes = np.atleast_2d(axes)
    xyz = model.node_xyz
    beam = np.all(model.dof_index >= 0, axis=1)
    a, b = model.elements.node_a, model.elements.node_b
    span = model.geometry.throw.span
    for row, mode in enumerate(chosen):
        u = result.node_displacements(mode)[:, :3]
        largest = float(np.max(np.linalg.norm(u[beam], axis=1), initial=0.0))
        scale = 0.2 * span / largest if largest > 0.0 else 0.0
        moved = xyz + scale * u
        color = COLORS[row % len(COLORS)]
        i = mode - 1
        title = f"mode {mode}: {result.natural_frequency[i] * HZ:.4g} Hz, {result.motion[i]}"
        for col, (h, v, xlabel, ylabel) in enumerate(VIEWS):
            ax = axes[row, col]
            ax.plot(*_segments(xyz, a, b, h, v), color="#b0b0b0", linewidth=0.8)
            ax.plot(*_segments(moved, a, b, h, v), color=color, linewidth=1.4)
            ax.set_aspect("equal", adjustable="datalim")
            ax.set_xlabel(xlabel)
            ax.set_ylabel(ylabel)
            if col == 0:
                ax.set_title(title, loc="left", fontsize="medium")
    return fig


def plot_axial_response(result: BeamResponseResult, fig: Figure | None = None) -> Figure:
    """The forced response of the beam model against speed: the free end's axial vibration
    (synthesised, and the largest orders), and the webs' bending stress (the largest over the
    webs, nominal and from vibration).

    Parameters
    ----------
    result : crankdyn.crankshaft.beam_response.BeamResponseResult
        The response.
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(2, 1, width=9.0, fig=fig, sharex=True)
    top, bottom = axes.flat
    rpm = np.asarray(result.speed) * RPM
    axial = np.asarray(result.free_end_axial) * 1e3
    top.plot(rpm, axial, color=COLORS[0], linewidth=1.6, label="synthesised")
    by_order = np.asarray(result.free_end_axial_orders) * 1e3
    if by_order.size:
        largest = np.argsort(by_order.max(axis=0))[::-1][:4]
        for k, j in enumerate(largest):
            top.plot(
                rpm, by_order[:, j], color=COLORS[(k + 1) % len(COLORS)], linewidth=0.9,
                linestyle="--", label=f"order {float(result.orders[j]):g}",
            )  # fmt: skip
    top.set_ylabel("Axial vibration, free end (mm)")
    top.legend(fontsize="small")
    bottom.plot(
        rpm, np.max(result.web_stress, axis=1) / 1e6, color=COLORS[0], linewidth=1.4,
        label="nominal web bending stress",
    )  # fmt: skip
    bottom.plot(
        rpm, np.max(result.web_vibration_stress, axis=1) / 1e6, color=COLORS[1], linewidth=1.4,
        label="from vibration",
    )  # fmt: skip
    bottom.set_ylabel("Largest over the webs (MPa)")
    bottom.set_xlabel("Speed (rpm)")
    bottom.legend(fontsize="small")
    return fig
