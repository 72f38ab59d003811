"""Figures of the torsional vibration calculation: every checked quantity of a condition as a
fraction of its limit against speed, and every component's forced response per order and
synthesised against its limit, with the barred ranges shaded.

Every curve can be told apart: a curve's colour and line style together are its own (ten
colours, then the same colours dashed, dash-dotted, dotted), legends stand outside the plot
area, and the curve that crosses its limit is drawn thicker and labelled where it is largest.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from crankdyn.constants import RPM
from crankdyn.display import engineering_unit
from crankdyn.plots.style import new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from crankdyn.tvc.result import ConditionResult

__all__ = ["STYLES", "curve_style", "plot_condition", "plot_condition_orders"]

PALETTE = (
    "#1f77b4",
    "#d62728",
    "#2ca02c",
    "#9467bd",
    "#ff7f0e",
    "#17becf",
    "#8c564b",
    "#e377c2",
    "#7f7f7f",
    "#bcbd22",
)
"""Ten colours (matplotlib's tab10, red second so that the second curve stands out)."""

STYLES = ("-", "--", "-.", ":")
"""Line styles, taken in turn after every ten colours."""

_ORDERS_SHOWN = 5


def curve_style(k: int) -> tuple[str, str]:
    """The colour and line style of the k-th curve of a figure: unique for 40 curves.

    Parameters
    ----------
    k : int
        The curve's index (from 0).

    Returns
    -------
    colour : str
        A colour of :data:`PALETTE`.
    style : str
        A line style of :data:`STYLES`.

    Examples
    --------
    >>> curve_style(0), curve_style(10)
    (('#1f77b4', '-'), ('#1f77b4', '--'))
    """
    return PALETTE[k % len(PALETTE)], STYLES[(k // len(PALETTE)) % len(STYLES)]


def _text(words: str) -> str:
    """User text drawn literally (no mathtext)."""
    return words.replace("$", r"\$")


def _shade(ax: Axes, condition: Any, component: str | None = None) -> None:
    """The condition's declared barred ranges (of one component, or all): red where not
    permitted, amber where permitted."""
    for b in condition.barred_ranges:
        if component is not None and b.component != component:
            continue
        ax.axvspan(
            b.start * RPM,
            b.end * RPM,
            color="#c62828" if not b.permitted else "#b26a00",
            alpha=0.13,
            linewidth=0,
        )


def plot_condition(condition: ConditionResult, fig: Figure | None = None) -> Figure:
    """Value / limit of every check of a :class:`~crankdyn.tvc.ConditionResult` over its
    resolved speeds (the response's own, peaks refined), the line 1 the limit, the condition's
    barred ranges shaded (not permitted in red, permitted in amber). Each curve has its own
    colour and line style (:func:`curve_style`), the legend stands right of the plot, and a
    curve that crosses 1 is drawn thicker and labelled at its peak.

    The ratio is dimensionless; speed is drawn in rpm.

    Parameters
    ----------
    condition : crankdyn.tvc.result.ConditionResult
        One operating condition of a torsional vibration calculation (SI units).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    r: Any = condition.response  # the condition's ResponseResult
    speed = np.asarray(r.speed) * RPM
    fig, axes = new_figure(1, 1, width=10.0, height=6.4, fig=fig)
    ax = axes[0, 0]
    top = 1.0
    k = 0
    for (component, quantity), check in condition.curves.items():
        values = np.asarray(check.curve(r), dtype=float)
        limits = np.asarray(check.limit(r.speed), dtype=float)
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(np.isfinite(limits) & (limits > 0.0), values / limits, np.nan)
        if not np.any(np.isfinite(ratio)):
            continue
        peak = float(np.nanmax(ratio))
        top = max(top, peak)
        short = quantity.split(" vs ")[0].replace("synthesised ", "")
        color, style = curve_style(k)
        k += 1
        crosses = peak > 1.0
        ax.plot(
            speed,
            ratio,
            color=color,
            linestyle=style,
            linewidth=2.4 if crosses else 1.1,
            label=_text(f"{component}: {short}" + (" (exceeds)" if crosses else "")),
            zorder=3 if crosses else 2,
        )
        if crosses:
            j = int(np.nanargmax(ratio))
            ax.annotate(
                _text(component),
                (speed[j], ratio[j]),
                xytext=(4, 4),
                textcoords="offset points",
                fontsize=7,
                color=color,
                fontweight="bold",
            )
    ax.axhline(1.0, color="black", linewidth=1.2, linestyle="--", label="limit")
    _shade(ax, condition)
    ax.set_xlim(float(speed[0]), float(speed[-1]))
    ax.set_ylim(0.0, 1.1 * top)
    ax.set_xlabel("Speed (rpm)")
    ax.set_ylabel("Value / limit")
    ax.set_title(_text(f"{condition.name}: every component against its limit"), fontsize=10)
    ax.legend(
        loc="upper left", bbox_to_anchor=(0.0, -0.12), ncol=2, fontsize=7, frameon=False
    )  # below the plot area: it covers no curve
    return fig


def _per_order(r: Any, check: Any, values: np.ndarray) -> np.ndarray | None:
    """The check's quantity per order (S, Q), where it is proportional to a shaft's vibratory
    torque (a stress or a torque read on its shafts): at each speed the torque of each order on
    the shaft (of the check's elements, e.g. a distributed shaft's) whose synthesised torque is
    largest, scaled by the quantity / that synthesised torque; None otherwise."""
    if not check.elements or check.unit not in ("Pa", "N·m"):
        return None
    elements = list(check.elements)
    synth_all = np.asarray(r.synthesized_shaft_torque[:, elements], dtype=float)  # (S, E)
    at = np.argmax(synth_all, axis=1)
    synth = synth_all[np.arange(len(at)), at]
    with np.errstate(divide="ignore", invalid="ignore"):
        scale = np.where(synth > 0.0, values / synth, np.nan)
    per = np.asarray(r.order_shaft_torque[:, :, elements], dtype=float)  # (S, Q, E)
    return per[np.arange(len(at)), :, at] * scale[:, None]


def _transient(ax: Axes, transient: np.ndarray, speed: np.ndarray, top: float, unit: str) -> None:
    """The transient limit (red, dashed) where the plot's scale (up to ``top``, set by the
    response and the continuous limit) holds it; above it the legend gives its values instead
    of a stray piece of curve at the top edge."""
    finite = transient[np.isfinite(transient)]
    style: dict[str, Any] = {"color": "#c62828", "linewidth": 1.0, "linestyle": (0, (5, 2))}
    if finite.size and float(np.max(finite)) > top:
        lo, hi = float(np.min(finite)), float(np.max(finite))
        words = f"{lo:.3g}-{hi:.3g}" if hi > 1.001 * lo else f"{hi:.3g}"
        ax.plot([], [], **style, label=f"transient limit\n{words} {unit}, off scale")
        return
    ax.plot(speed, transient, **style, label="transient limit")


def plot_condition_orders(condition: ConditionResult, fig: Figure | None = None) -> Figure:
    """Every component that bars speeds (shafts, crank spans, couplings), one panel each: its
    quantity per order (the five orders with the largest peaks; major orders solid, the others
    dashed) and synthesised (black, thick) against the continuous limit (red) and, where one
    applies, the transient limit (red, dashed), the component's barred ranges shaded. Speed in
    rpm, each panel in the engineering unit of its limit.

    Parameters
    ----------
    condition : crankdyn.tvc.result.ConditionResult
        One operating condition of a torsional vibration calculation (SI units).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure (one panel saying so when no component bars speeds).
    """
    r: Any = condition.response
    checks = [c for c in condition.curves.values() if c.barred]
    cols = 2 if len(checks) > 1 else 1
    rows = max(1, -(-len(checks) // cols))
    fig, axes = new_figure(rows, cols, width=10.0, height=2.35 * rows + 0.9, fig=fig)
    speed = np.asarray(r.speed) * RPM
    q = np.asarray(r.orders)
    for ax in axes.flat[len(checks) :]:
        ax.set_axis_off()
    if not checks:
        axes[0, 0].text(0.5, 0.5, "no component bars speeds", ha="center", va="center")
    for check, ax in zip(checks, axes.flat, strict=False):
        values = np.asarray(check.curve(r), dtype=float)
        limit = np.asarray(check.limit(r.speed), dtype=float)
        finite = limit[np.isfinite(limit)]
        ref = float(np.max(np.abs(finite))) if finite.size else float(np.nanmax(values))
        shown, factor = engineering_unit(ref, check.unit)
        orders = _per_order(r, check, values)
        if orders is not None:
            peaks = np.nanmax(orders, axis=0)
            chosen = np.sort(np.argsort(np.nan_to_num(peaks))[::-1][:_ORDERS_SHOWN])
            for k, j in enumerate(chosen):
                major = r.major is not None and bool(r.major[j])
                ax.plot(
                    speed,
                    orders[:, j] * factor,
                    color=PALETTE[k % len(PALETTE)],
                    linestyle="-" if major else "--",
                    linewidth=0.9,
                    label=f"order {q[j]:g}" + (" (major)" if major else ""),
                )
        ax.plot(speed, values * factor, color="black", linewidth=1.8, label="synthesised")
        ax.plot(speed, limit * factor, color="#c62828", linewidth=1.4, label="limit")
        top = np.nanmax(np.concatenate([values, limit[np.isfinite(limit)]])) * factor
        if check.transient_limit is not None:
            _transient(ax, np.asarray(check.transient_limit(r.speed), dtype=float) * factor,
                       speed, 1.12 * float(top), shown)  # fmt: skip
        ax.set_ylim(0.0, 1.12 * float(top) if np.isfinite(top) and top > 0 else 1.0)
        ax.set_xlim(float(speed[0]), float(speed[-1]))
        ax.tick_params(labelsize=7)
        ax.set_title(_text(check.component), fontsize=8, loc="left")
        short = check.quantity.split(" vs ")[0].replace("synthesised ", "")
        ax.set_ylabel(_text(f"{short} ({shown})"), fontsize=6.5)
        ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=6, frameon=False)
    for ax in axes[-1, :]:
        ax.set_xlabel("Speed (rpm)", fontsize=8)
    fig.suptitle(_text(f"{condition.name}: forced response per order and synthesised"), fontsize=10)
    return fig
