"""Plot of a measured shaft torque's orders beside the model's (seed 003)."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from crankdyn.plots.style import COLORS, new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.measure.torque import TorqueSpectrum

__all__ = ["plot_torque_orders"]


def plot_torque_orders(result: TorqueSpectrum, fig: Figure | None = None) -> Figure:
    """Torque amplitude (N·m) per order, measured (with the cycle-to-cycle scatter) and, when
    the result holds a comparison, the model's at the same span.

    Parameters
    ----------
    result : crankdyn.measure.torque.TorqueSpectrum
        The measured orders (N m), with or without the model's.
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(1, 1, width=8.0, height=4.2, fig=fig)
    ax = axes[0, 0]
    q = np.asarray(result.orders)
    width = 0.18 if result.comparison is not None else 0.3
    shift = width / 2 if result.comparison is not None else 0.0
    ax.bar(
        q - shift,
        result.amplitude,
        width,
        yerr=result.scatter,
        color=COLORS[0],
        label=f"measured ({result.cycles} cycles, scatter as error bars)",
    )
    if result.comparison is not None:
        ax.bar(
            q + shift,
            result.comparison.model_amplitude,
            width,
            color=COLORS[1],
            label=f"model, span {result.comparison.span}",
        )
    ax.set_xlabel("Order")
    ax.set_ylabel("Torque amplitude (N·m)")
    ax.set_title(
        f"{result.source}: torque orders at {result.speed * 30.0 / np.pi:.5g} rpm, "
        f"mean {result.mean_torque:.5g} N·m"
    )
    ax.legend(fontsize=8)
    return fig
