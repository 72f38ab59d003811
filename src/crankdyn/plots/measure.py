"""Plots of measured torsional vibration: order spectra, order amplitudes against speed beside the
model's prediction, the colour map of a run-up, resonance fits and the angle-domain traces."""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import TYPE_CHECKING

import numpy as np

from crankdyn.constants import DEG, RPM
from crankdyn.plots.style import COLORS, new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.measure.orders import OrderSpectrum, OrderTracking

__all__ = ["plot_measurement"]

_SHOWN = 6
WHATS = ("orders", "map", "fit", "trace")


def _plain(text: str) -> str:
    """User text shown literally (no mathtext)."""
    return str(text).replace("$", r"\$")


def plot_measurement(
    result: OrderSpectrum | OrderTracking,
    what: str = "orders",
    fig: Figure | None = None,
    orders: Iterable[float] | None = None,
) -> Figure:
    """A figure of an order analysis (:mod:`crankdyn.measure.orders`, which cites the
    synchronous-sampling and window formulas): amplitudes drawn in mrad, speeds in rpm, crank
    angles in degrees.

    Parameters
    ----------
    result : crankdyn.measure.orders.OrderSpectrum or crankdyn.measure.orders.OrderTracking
        The order analysis of a steady-speed record or of a run-up/run-down (SI units).
    what : {"orders", "map", "fit", "trace"}
        The order amplitudes (and phases) beside the model's, the colour map of a run-up,
        the resonance fits of a run-up, or the angle-domain trace.
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.
    orders : iterable of float or None
        The orders to draw in ``"orders"`` of a run-up (dimensionless); None: the six largest.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.

    Raises
    ------
    ValueError
        ``what`` is unknown, or ``"map"``/``"fit"`` of a steady-speed record.
    """
    steady = result.kind == "steady"
    if what == "orders":
        return _steady_orders(result, fig) if steady else _tracking_orders(result, fig, orders)
    if what == "trace":
        return _steady_trace(result, fig) if steady else _tracking_trace(result, fig)
    if what in ("map", "fit") and steady:
        raise ValueError(f"{what!r} needs a run-up or run-down, not a steady-speed record")
    if what == "map":
        return _map(result, fig)
    if what == "fit":
        return _fits(result, fig)
    raise ValueError(f"unknown plot {what!r}: one of {', '.join(WHATS)}")


def _steady_orders(result, fig):
    fig, axes = new_figure(2, 1, width=9.5, height=6.2, fig=fig, sharex=True)
    q = np.asarray(result.orders)
    cmp = result.comparison
    width = 0.2 if cmp is not None else 0.3
    shift = -width / 2 if cmp is not None else 0.0
    ax = axes[0, 0]
    ax.bar(q + shift, result.amplitude * 1e3, width=width, color=COLORS[0], label="measured")
    if cmp is not None:
        ax.bar(
            q - shift,
            np.asarray(cmp.amplitude[0]) * 1e3,
            width=width,
            color=COLORS[1],
            label=_plain(f"model: {cmp.name}"),
        )
        ax.legend(fontsize=8)
    ax.set_ylabel(
        _plain(f"Amplitude at {cmp.mass}" if cmp is not None else "Amplitude") + " (mrad)"
    )
    ax.set_title(
        _plain(
            f"{result.source}: {result.speed * RPM:.1f} rpm, {result.cycles} cycles averaged,"
            f" synthesised {result.synthesized * 1e3:.3g} mrad"
        ),
        fontsize=10,
    )
    ax2 = axes[1, 0]
    ax2.plot(q, np.degrees(result.phase), "o", color=COLORS[0], label="measured")
    if cmp is not None:
        ax2.plot(
            q,
            np.degrees(np.asarray(cmp.phase[0])),
            "s",
            color=COLORS[1],
            fillstyle="none",
            label="model",
        )
        ax2.legend(fontsize=8)
    ax2.set_ylim(-180, 180)
    ax2.set_yticks([-180, -90, 0, 90, 180])
    ax2.set_ylabel("Phase (deg)")
    ax2.set_xlabel("Order")
    ax2.set_xticks(q[:: max(1, q.size // 12)])
    return fig


def _steady_trace(result, fig):
    fig, axes = new_figure(2, 1, width=9.5, height=6.2, fig=fig, sharex=True)
    angle = np.asarray(result.cycle_angle) * DEG
    ax = axes[0, 0]
    ax.plot(
        angle, np.asarray(result.cycle_vibration) * 1e3, color=COLORS[0], label="averaged cycle"
    )
    psi = np.asarray(result.cycle_angle)
    synth = np.sum(
        np.real(result.coefficients[None, :] * np.exp(1j * psi[:, None] * result.orders[None, :])),
        axis=1,
    )
    ax.plot(angle, synth * 1e3, color=COLORS[1], linestyle="--", label="analysed orders")
    ax.set_ylabel("Angular vibration (mrad)")
    ax.legend(fontsize=8)
    ax.set_title(_plain(f"{result.source}: {result.speed * RPM:.1f} rpm"), fontsize=10)
    ax2 = axes[1, 0]
    ax2.plot(angle, np.asarray(result.cycle_speed) * RPM, color=COLORS[0])
    ax2.set_ylabel("Instantaneous speed (rpm)")
    ax2.set_xlabel("Crank angle from the reference (deg)")
    ax2.set_xlim(float(angle[0]), float(angle[-1]))
    return fig


def _chosen(result, orders):
    if orders is None:
        peaks = np.max(result.amplitude, axis=0)
        return np.sort(np.argsort(peaks)[::-1][:_SHOWN])
    return [result.order_index(o) for o in orders]


def _tracking_orders(result, fig, orders):
    fig, axes = new_figure(
        2, 1, width=9.5, height=7.4, fig=fig, sharex=True, gridspec_kw={"height_ratios": [3, 2]}
    )
    n = np.asarray(result.speed) * RPM
    cmp = result.comparison
    ax = axes[0, 0]
    for k, j in enumerate(_chosen(result, orders)):
        color = COLORS[k % len(COLORS)]
        ax.plot(
            n,
            result.amplitude[:, j] * 1e3,
            color=color,
            linewidth=1.5,
            label=f"order {result.orders[j]:g}",
        )
        if cmp is not None:
            ax.plot(
                np.asarray(cmp.curve_speed) * RPM,
                cmp.curve_amplitude[:, j] * 1e3,
                color=color,
                linewidth=1.0,
                linestyle="--",
            )
    ax.set_ylabel("Order amplitude (mrad)")
    ax.set_ylim(bottom=0.0)
    where = f" at {cmp.mass}" if cmp is not None else ""
    title = f"{result.source}{where}: measured (solid)"
    if cmp is not None:
        title += f"\nmodel (dashed): {cmp.name}"
    ax.set_title(_plain(title), fontsize=10)
    ax.legend(fontsize=8, ncol=2, loc="upper left")
    ax2 = axes[1, 0]
    ax2.plot(n, result.synthesized * 1e3, color="black", linewidth=1.6, label="measured")
    if cmp is not None:
        ax2.plot(
            np.asarray(cmp.curve_speed) * RPM,
            cmp.curve_synthesized * 1e3,
            color="black",
            linestyle="--",
            linewidth=1.0,
            label="model",
        )
    ax2.set_ylabel("Synthesised (mrad)")
    ax2.set_ylim(bottom=0.0)
    ax2.set_xlabel("Engine speed (rpm)")
    ax2.legend(fontsize=8, loc="upper left")
    ax2.set_xlim(float(np.min(n)), float(np.max(n)))
    return fig


def _map(result, fig):
    fig, axes = new_figure(1, 1, width=9.5, height=6.4, fig=fig)
    ax = axes[0, 0]
    ax.grid(False)
    speed = np.asarray(result.window_speed) * RPM
    order = np.argsort(speed)
    q = np.asarray(result.orders)
    step = q[1] - q[0] if q.size > 1 else 0.5
    edges_q = np.concatenate([q - step / 2, [q[-1] + step / 2]])
    s = speed[order]
    mid = 0.5 * (s[1:] + s[:-1])
    edges_s = np.concatenate(
        [
            [s[0] - (mid[0] - s[0]) if mid.size else s[0] - 1],
            mid,
            [s[-1] + (s[-1] - mid[-1]) if mid.size else s[-1] + 1],
        ]
    )
    mesh = ax.pcolormesh(
        edges_q, edges_s, result.window_amplitude[order] * 1e3, cmap="viridis", shading="flat"
    )
    fig.colorbar(mesh, ax=ax, label="Order amplitude (mrad)")
    for fit in result.resonances:
        ax.plot(fit.order, fit.peak_speed * RPM, "w+", markersize=10)
    ax.set_xlabel("Order")
    ax.set_ylabel("Engine speed (rpm)")
    ax.set_title(
        _plain(f"{result.source}: order amplitudes over the {result.kind} (+ resonance peaks)"),
        fontsize=10,
    )
    return fig


def _fits(result, fig):
    fits = list(result.resonances)
    if not fits:
        raise ValueError("no resonance was found in the record: nothing to fit")
    count = min(len(fits), 4)
    fits = sorted(fits, key=lambda f: -f.peak_amplitude)[:count]
    fig, axes = new_figure(count, 1, width=9.0, height=3.0 * count + 0.6, fig=fig)
    cmp = result.comparison
    for ax, fit in zip(axes[:, 0], fits, strict=True):
        j = result.order_index(fit.order)
        s = np.asarray(result.window_speed)
        a = np.asarray(result.window_amplitude[:, j])
        lo, hi = fit.half_power_speeds or (fit.peak_speed, fit.peak_speed)
        span = 3.0 * max(hi - lo, 1e-6 * fit.peak_speed)
        near = np.abs(s - fit.peak_speed) <= span
        ax.plot(
            s[near] * RPM,
            a[near] * 1e3,
            ".",
            color=COLORS[0],
            markersize=4,
            label="measured windows",
        )
        b_lo, b_hi = fit.band or (fit.peak_speed - span, fit.peak_speed + span)
        grid = np.linspace(b_lo, b_hi, 400)  # the fit holds over its band only
        ax.plot(
            grid * RPM,
            np.abs(fit.curve(grid)) * 1e3,
            color=COLORS[1],
            label=f"single-mode fit: ζ = {fit.damping:.4f}",
        )
        level = fit.peak_amplitude / math.sqrt(2.0) * 1e3
        if fit.half_power_speeds is not None:
            ax.hlines(
                level,
                lo * RPM,
                hi * RPM,
                color=COLORS[2],
                linestyle=":",
                label=f"half-power: ζ = {fit.half_power_damping:.4f}",
            )
        if cmp is not None and cmp.curve_speed is not None:
            inside = np.abs(np.asarray(cmp.curve_speed) - fit.peak_speed) <= span
            ax.plot(
                np.asarray(cmp.curve_speed)[inside] * RPM,
                cmp.curve_amplitude[inside, j] * 1e3,
                color="black",
                linestyle="--",
                linewidth=1.0,
                label="model",
            )
        ax.set_ylabel(f"Order {fit.order:g} (mrad)")
        ax.set_ylim(bottom=0.0)
        ax.set_title(
            f"Order {fit.order:g}: resonance at {fit.critical_speed * RPM:.0f} rpm, "
            f"{fit.natural_frequency / (2 * math.pi):.2f} Hz",
            fontsize=10,
        )
        ax.legend(fontsize=8, loc="upper left")
    axes[-1, 0].set_xlabel("Engine speed (rpm)")
    return fig


def _tracking_trace(result, fig):
    fig, axes = new_figure(2, 1, width=9.5, height=6.2, fig=fig)
    d = result.domain
    ax = axes[0, 0]
    ax2 = axes[1, 0]
    if d is None:  # a record analysed block by block: the band of each cycle
        return _envelope_trace(result, fig, ax, ax2)
    ax.plot(
        d.pulse_speed_angle / (2 * math.pi),
        d.pulse_speed * RPM,
        color=COLORS[0],
        linewidth=0.5,
        label="per tooth interval",
    )
    ax.set_ylabel("Instantaneous speed (rpm)")
    ax.set_title(_plain(f"{result.source}: {result.kind}"), fontsize=10)
    ax2.plot(d.angle / (2 * math.pi), d.vibration * 1e3, color=COLORS[1], linewidth=0.5)
    ax2.set_ylabel("Angular vibration (mrad)")
    ax2.set_xlabel("Crank revolutions from the reference")
    ax.set_xlim(float(d.angle[0] / (2 * math.pi)), float(d.angle[-1] / (2 * math.pi)))
    ax2.set_xlim(*ax.get_xlim())
    return fig


def _envelope_trace(result, fig, ax, ax2):
    """The trace of a long record: per working cycle, the band from the least to the largest
    instantaneous speed and angular vibration (:class:`crankdyn.measure.blocks.Envelope`)."""
    e = result.envelope
    revolutions = e.angle / (2 * math.pi)
    ax.fill_between(
        revolutions,
        e.speed_low * RPM,
        e.speed_high * RPM,
        color=COLORS[0],
        step="post",
        linewidth=0,
        label="least to largest in each cycle",
    )
    ax.set_ylabel("Instantaneous speed (rpm)")
    ax.set_title(_plain(f"{result.source}: {result.kind}, per cycle"), fontsize=10)
    ax.legend(fontsize=8, loc="upper left")
    ax2.fill_between(
        revolutions,
        e.vibration_low * 1e3,
        e.vibration_high * 1e3,
        color=COLORS[1],
        step="post",
        linewidth=0,
    )
    ax2.set_ylabel("Angular vibration (mrad)")
    ax2.set_xlabel("Crank revolutions from the reference")
    ax.set_xlim(float(revolutions[0]), float(revolutions[-1]))
    ax2.set_xlim(*ax.get_xlim())
    return fig
