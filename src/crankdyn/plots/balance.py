"""Polar plots of the free forces and moments, order by order (seed 000 section 2.2)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from crankdyn.constants import RPM
from crankdyn.plots.style import COLORS, new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from crankdyn.engine.balance import BalanceResult

__all__ = ["plot_balance"]

_T = np.linspace(0.0, 2.0 * math.pi, 361)


def _scale(values: Sequence[float], unit: str) -> tuple[float, str]:
    """(factor, unit label) so that the largest value reads in the hundreds at most."""
    peak = max(values, default=0.0)
    if peak >= 1e4:
        return 1e-3, "k" + unit
    return 1.0, unit


def _locus(
    ax: Axes,
    x: complex | np.ndarray,
    y: complex | np.ndarray,
    factor: float,
    color: str,
    *,
    label_x: str,
    label_y: str,
    amplitude: float,
    tiny: float,
) -> None:
    """Draw the path of the vector (Re[x e^(jt)], Re[y e^(jt)]) over a period."""
    ax.set_aspect("equal", adjustable="box")
    ax.axhline(0.0, color="#9a9a9a", linewidth=0.6)
    ax.axvline(0.0, color="#9a9a9a", linewidth=0.6)
    if amplitude <= tiny:
        # nothing to scale: no ticks (numbers on a balanced order's axes would suggest a scale
        # it does not have), the point at the origin
        ax.plot(0.0, 0.0, "o", color=color, markersize=5)
        ax.text(0.0, 0.25, "balanced", ha="center", fontsize=8, transform=ax.transData)
        ax.set_xlim(-1.0, 1.0)
        ax.set_ylim(-1.0, 1.0)
        ax.set_xticks([])
        ax.set_yticks([])
    else:
        e = np.exp(1j * _T)
        hx, hy = np.real(x * e) * factor, np.real(y * e) * factor
        ax.plot(hx, hy, color=color, linewidth=1.6)
        ax.annotate(
            "",
            xy=(hx[0], hy[0]),
            xytext=(0.0, 0.0),
            arrowprops={"arrowstyle": "->", "color": color, "linewidth": 1.2},
        )
        lim = 1.15 * amplitude * factor
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, lim)
    ax.set_xlabel(label_x, fontsize=8)
    ax.set_ylabel(label_y, fontsize=8)
    ax.tick_params(labelsize=7)


def plot_balance(result: BalanceResult, fig: Figure | None = None) -> Figure:
    """For every order (and the rotating masses, and the first-order total): the path of the
    free-force vector seen from the free end (top row) and of the free-moment vector (bottom
    row) over one revolution, the arrow at theta = 0.

    A phasor pair (x, y) of one order traces (Re[x e^(jt)], Re[y e^(jt)]) over t in [0, 2 pi]
    (an ellipse; seed 000 section 2.2). Forces are drawn in N (kN above 10 kN), moments in N·m
    (kN·m above 10 kN·m).

    Parameters
    ----------
    result : crankdyn.engine.balance.BalanceResult
        The free forces and moments of an engine (SI units).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    rows = result.rows()
    has_moments = any(r.free_moment is not None for r in rows)
    n = len(rows)
    fig, axes = new_figure(
        2 if has_moments else 1,
        n,
        width=max(2.3 * n, 8.0),
        height=5.6 if has_moments else 3.1,
        fig=fig,
    )
    f_factor, f_unit = _scale([r.free_force for r in rows], "N")
    m_factor, m_unit = _scale([r.free_moment or 0.0 for r in rows], "N·m")
    f_tiny = 1e-9 * max(max(r.free_force for r in rows), 1e-300)
    m_tiny = 1e-9 * max(max((r.free_moment or 0.0) for r in rows), 1e-300)
    for k, r in enumerate(rows):
        color = COLORS[k % len(COLORS)]
        name = (
            f"order {r.order}"
            if r.source == "reciprocating"
            else ("rotating" if r.source == "rotating" else "1st order total")
        )
        ph = r.phasors
        assert ph is not None  # every row of a BalanceResult carries its phasors
        ax = axes[0, k]
        _locus(
            ax,
            ph.x,
            ph.y,
            f_factor,
            color,
            label_x=f"horizontal ({f_unit})",
            label_y=f"vertical ({f_unit})",
            amplitude=r.free_force,
            tiny=f_tiny,
        )
        ax.set_title(f"{name}\nF = {_value(r.free_force * f_factor, f_tiny)} {f_unit}", fontsize=9)
        if has_moments:
            ax = axes[1, k]
            if r.free_moment is None:
                ax.set_axis_off()
                continue
            # moment vector: (yaw, pitch) = (M_y, M_x) = (Re[xz e], -Re[yz e])
            assert ph.xz is not None and ph.yz is not None  # a free moment has its phasors
            _locus(
                ax,
                ph.xz,
                -ph.yz,
                m_factor,
                color,
                label_x=f"horizontal plane ({m_unit})",
                label_y=f"vertical plane ({m_unit})",
                amplitude=r.free_moment,
                tiny=m_tiny,
            )
            ax.set_title(f"M = {_value(r.free_moment * m_factor, m_tiny)} {m_unit}", fontsize=9)
    cw = ""
    if result.counterweight_ratio or result.reciprocating_balance_ratio:
        cw = (
            f", counterweights c = {result.counterweight_ratio:g}, "
            f"b = {result.reciprocating_balance_ratio:g}"
        )
    fig.suptitle(
        f"{result.engine}: free forces (top) and moments (bottom) over one revolution at "
        f"{result.speed * RPM:.0f} rpm{cw}"
    )
    return fig


def _value(value: float, tiny: float) -> str:
    return "0" if abs(value) <= tiny else f"{value:.4g}"
