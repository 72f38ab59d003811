"""Plots of the forced torsional response: response against speed per order and synthesised,
the Campbell diagram, shaft stress against the rule limits, the torque harmonics, damper
comparisons and time-domain runs."""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

import numpy as np

from crankdyn.plots.style import COLORS, new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.torsion.campbell import CampbellResult
    from crankdyn.torsion.harmonics import HarmonicResult
    from crankdyn.torsion.response import ResponseResult
    from crankdyn.torsion.transient import TransientResult

__all__ = [
    "plot_campbell",
    "plot_damper_comparison",
    "plot_harmonics",
    "plot_response",
    "plot_stress_limits",
    "plot_transient",
]

from crankdyn.constants import RPM

_SHOWN_ORDERS = 8


def _quantity(result: Any, what: str, item: Any) -> tuple[Any, Any, Any, Any, str, str, float]:
    """(speeds (S,) rad/s, per-order amplitudes (S, Q), order sum (S,), synthesised (S,), label,
    unit, scale). A relative angle has its own speeds (its peaks are resolved too, which may add
    speeds to the response's)."""
    if what == "amplitude":
        i = 0 if item is None else result.mass_index(item)
        name = result.masses[i]
        return (
            result.speed,
            result.amplitude[:, :, i],
            result.order_sum_amplitude[:, i],
            result.synthesized_amplitude[:, i],
            f"Angular amplitude at {name}",
            "mrad",
            1e3,
        )
    if what == "relative":
        a, b = item if item is not None else (result.masses[0], result.masses[-1])
        rel = result.relative_angle(a, b)
        return (
            rel.speed,
            rel.amplitude,
            rel.order_sum,
            rel.synthesized,
            f"Relative angle {a} - {b}",
            "mrad",
            1e3,
        )
    if what in ("torque", "stress"):
        if item is None:  # the result's own choice: the most loaded (most stressed) shaft
            item = result.most_loaded_shaft() if what == "torque" else result.most_stressed_shaft()
        s = result.shaft_index(item)
        a, b = result.shafts[s]
        if what == "torque":
            return (
                result.speed,
                result.order_shaft_torque[:, :, s],
                result.shaft_torque[:, s],
                result.synthesized_shaft_torque[:, s],
                f"Vibratory torque, shaft {a} - {b}",
                "kN·m",
                1e-3,
            )
        modulus = result.section_modulus[s]
        if not np.isfinite(modulus):
            raise ValueError(f"shaft {a} - {b} has no diameters: no stress")
        return (
            result.speed,
            result.order_shaft_torque[:, :, s] / modulus,
            result.shaft_stress[:, s],
            result.synthesized_shaft_stress[:, s],
            f"Nominal shear stress, shaft {a} - {b}",
            "MPa",
            1e-6,
        )
    raise ValueError(f"unknown quantity {what!r}: amplitude, relative, torque or stress")


def plot_response(
    result: ResponseResult,
    what: str = "amplitude",
    item: Any = None,
    fig: Figure | None = None,
    orders: Iterable[float] | None = None,
    log: bool = False,
) -> Figure:
    """Response against speed: the largest orders (major orders solid and thicker, minor
    dashed), the sum of the order amplitudes and the synthesised half-range amplitude (the
    forced response and its synthesis as in :mod:`crankdyn.torsion.response`); speed drawn in
    rpm.

    Parameters
    ----------
    result : crankdyn.torsion.response.ResponseResult
        The forced torsional response (SI units).
    what : {"amplitude", "relative", "torque", "stress"}
        The angular amplitude of a mass (drawn in mrad), the relative angle of two masses
        (mrad), the vibratory torque of a shaft (kN·m) or its nominal shear stress (MPa).
    item : str or (str, str) or None
        The mass (``"amplitude"``, default the first), the pair of masses (``"relative"``,
        default the first and last) or the shaft as its pair of masses (``"torque"``,
        ``"stress"``, default the most loaded, resp. most stressed, shaft:
        :meth:`~crankdyn.torsion.response.ResponseResult.most_loaded_shaft`).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.
    orders : iterable of float or None
        The orders to draw (dimensionless; the nearest computed order each); None: the eight
        with the largest peaks.
    log : bool
        A logarithmic amplitude axis (else linear from 0).

    Returns
    -------
    matplotlib.figure.Figure
        The figure.

    Raises
    ------
    ValueError
        ``what`` is unknown, or a stress is asked of a shaft without diameters.
    """
    speed, per_order, total, synth, label, unit, scale = _quantity(result, what, item)
    fig, axes = new_figure(1, 1, width=9.5, height=5.2, fig=fig)
    ax = axes[0, 0]
    n = np.asarray(speed) * RPM
    q = np.asarray(result.orders)
    chosen: np.ndarray | list[int]
    if orders is None:
        peaks = np.max(per_order, axis=0)
        chosen = np.sort(np.argsort(peaks)[::-1][:_SHOWN_ORDERS])
    else:
        chosen = [int(np.argmin(np.abs(q - o))) for o in orders]
    for k, j in enumerate(chosen):
        major = result.major is not None and bool(result.major[j])
        ax.plot(
            n,
            per_order[:, j] * scale,
            color=COLORS[k % len(COLORS)],
            linewidth=1.6 if major else 1.0,
            linestyle="-" if major else "--",
            label=f"order {q[j]:g}" + (" (major)" if major else ""),
        )
    ax.plot(
        n,
        total * scale,
        color="black",
        linewidth=1.2,
        linestyle=":",
        label="sum of order amplitudes",
    )
    ax.plot(n, synth * scale, color="black", linewidth=2.0, label="synthesised (half range)")
    if log:
        ax.set_yscale("log")
    else:
        ax.set_ylim(bottom=0.0)
    ax.set_xlim(float(n[0]), float(n[-1]))
    ax.set_xlabel("Engine speed (rpm)")
    ax.set_ylabel(f"{label} ({unit})")
    ax.set_title(f"{label}: {result.model_name}", fontsize=10)
    ax.legend(loc="upper left", fontsize=8, ncol=2)
    return fig


def plot_damper_comparison(
    with_damper: ResponseResult,
    without: ResponseResult,
    what: str = "amplitude",
    item: Any = None,
    fig: Figure | None = None,
) -> Figure:
    """Synthesised response with and without the damper(s) against speed (rpm).

    Parameters
    ----------
    with_damper, without : crankdyn.torsion.response.ResponseResult
        The forced response of the model with its damper(s) and without (SI units).
    what : {"amplitude", "relative", "torque", "stress"}
        The angular amplitude of a mass (drawn in mrad), the relative angle of two masses
        (mrad), the vibratory torque of a shaft (kN·m) or its nominal shear stress (MPa).
    item : str or (str, str) or None
        The mass (``"amplitude"``, default the first), the pair of masses (``"relative"``,
        default the first and last) or the shaft as its pair of masses (``"torque"``,
        ``"stress"``, default the most loaded, resp. most stressed, shaft:
        :meth:`~crankdyn.torsion.response.ResponseResult.most_loaded_shaft`).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(1, 1, width=9.5, height=5.0, fig=fig)
    ax = axes[0, 0]
    for result, color, text in (
        (without, COLORS[1], "without damper"),
        (with_damper, COLORS[0], "with damper"),
    ):
        speed, _, total, synth, label, unit, scale = _quantity(result, what, item)
        n = np.asarray(speed) * RPM
        ax.plot(n, synth * scale, color=color, linewidth=1.8, label=f"{text}, synthesised")
        ax.plot(
            n,
            total * scale,
            color=color,
            linewidth=1.0,
            linestyle=":",
            label=f"{text}, sum of orders",
        )
    ax.set_ylim(bottom=0.0)
    ax.set_xlim(float(n[0]), float(n[-1]))
    ax.set_xlabel("Engine speed (rpm)")
    ax.set_ylabel(f"{label} ({unit})")
    ax.set_title(f"{label} with and without damper: {with_damper.model_name}", fontsize=10)
    ax.legend(loc="upper left", fontsize=8)
    return fig


def plot_campbell(
    result: CampbellResult, fig: Figure | None = None, max_speed: float | None = None
) -> Figure:
    """Campbell diagram: excitation frequency of every order against speed, every order
    labelled at its end (half orders included; the engine's orders grey, its major orders dark
    and thick, the orders of other sources such as a propeller's blade orders orange and
    dashed), natural frequencies as horizontal lines, the operating range shaded and the
    critical speeds inside it marked (filled: major orders; diamonds when the major orders are
    undetermined). An order q crosses a natural frequency f at the critical speed n = 60 f / q
    (f in Hz, n in rpm; :mod:`crankdyn.torsion.campbell`). Speed drawn in rpm, frequency in Hz.

    Parameters
    ----------
    result : crankdyn.torsion.campbell.CampbellResult
        Natural frequencies, orders and critical speeds (SI units).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.
    max_speed : float or None
        The highest speed drawn (rad/s); None: 1.15 times the top of the operating range.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(1, 1, width=9.5, height=6.4, fig=fig)
    ax = axes[0, 0]
    top_speed = (max_speed or result.high * 1.15) * RPM
    f_nat = np.asarray(result.natural_frequency) / (2.0 * math.pi)
    shown = f_nat[f_nat <= np.max(result.orders) * top_speed / 60.0 * 1.05]
    f_top = 1.1 * max(
        float(shown.max()) if shown.size else 0.0, float(np.min(result.orders)) * top_speed / 60.0
    )
    n = np.array([0.0, top_speed])
    sources = result.order_sources or ("engine",) * len(result.orders)
    drawn: set[str] = set()
    style: Any
    for j, q in enumerate(result.orders):
        major = result.major is not None and bool(result.major[j])
        engine = "engine" in sources[j].split(", ") if sources[j] else True
        if engine:  # the engine's orders grey (major dark and thick), the sources' coloured
            color, style, kind = ("#303030" if major else "#8a8a8a"), "-", "engine order"
            if major:
                kind = "engine order, major"
        else:
            color, style, kind = COLORS[4], (0, (6, 2)), f"{sources[j] or 'source'} order"
        label = None if kind in drawn else kind
        drawn.add(kind)
        ax.plot(n, q * n / 60.0, color=color, linestyle=style,
                linewidth=1.3 if major else 0.8, zorder=1, label=label)  # fmt: skip
        end = min(top_speed, f_top * 60.0 / q)
        # every order labelled at its end (the top or the right edge of the plot)
        at_top = end < top_speed
        ax.annotate(
            f"{q:g}",
            (end, q * end / 60.0),
            fontsize=6.5,
            color=color,
            xytext=(0, 2) if at_top else (2, 0),
            textcoords="offset points",
            ha="center" if at_top else "left",
            va="bottom" if at_top else "center",
            fontweight="bold" if major else "normal",
            annotation_clip=False,
        )
    for k, (mode, f) in enumerate(zip(result.modes, f_nat, strict=True)):
        if f > f_top:
            continue
        ax.axhline(
            f,
            color=COLORS[k % len(COLORS)],
            linewidth=1.2,
            zorder=2,
            label=f"mode {int(mode)}: {f:.4g} Hz",
        )
    ax.axvspan(
        result.low * RPM, result.high * RPM, color="#dde8f3", zorder=0, label="operating range"
    )
    # undetermined: the engine's orders without firing angles (a source's own orders, e.g. a
    # propeller's blade orders, are never major: drawn as minor)
    unknown = [c for c in result.critical_speeds if c.major is None]
    major_pts = [c for c in result.critical_speeds if c.major]
    minor_pts = [c for c in result.critical_speeds if c.major is False]
    if unknown:
        ax.plot(
            [c.speed * RPM for c in unknown],
            [c.frequency_hz for c in unknown],
            "D",
            color="#606060",
            markersize=5,
            zorder=3,
            label="critical speed (major orders undetermined: no firing order)",
        )
    if major_pts:
        ax.plot(
            [c.speed * RPM for c in major_pts],
            [c.frequency_hz for c in major_pts],
            "o",
            color="black",
            markersize=6,
            zorder=3,
            label="critical speed, major order",
        )
    if minor_pts:
        ax.plot(
            [c.speed * RPM for c in minor_pts],
            [c.frequency_hz for c in minor_pts],
            "o",
            markerfacecolor="white",
            markeredgecolor="black",
            markersize=5,
            zorder=3,
            label="critical speed, minor order",
        )
    ax.set_xlim(0.0, top_speed)
    ax.set_ylim(0.0, f_top)
    ax.set_xlabel("Engine speed (rpm)")
    ax.set_ylabel("Frequency (Hz)")
    ax.set_title(f"Campbell diagram: {result.model_name}", fontsize=10, pad=14)
    ax.legend(loc="upper left", bbox_to_anchor=(1.06, 1.0), fontsize=7, frameon=False)
    return fig


def plot_stress_limits(condition: Any, fig: Figure | None = None) -> Figure:
    """Synthesised shear stress of every propulsion shaft checked against the rule set's tau_C
    and tau_T (the IACS UR M68.4 form; :class:`crankdyn.tvc.checks.M68Shafts`), the declared
    barred speed ranges shaded (red where not permitted) and the ranges as found
    hatched, drawn on every speed of the resolved response (the peaks included); stress in MPa,
    speed in rpm. The curves and limits are the checks' own (:mod:`crankdyn.tvc.checks`).

    Parameters
    ----------
    condition : crankdyn.tvc.ConditionResult
        A judged condition (:meth:`crankdyn.session.Analysis.judged`, or a TVC condition).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.

    Raises
    ------
    ValueError
        The condition has no M68 shaft check or no response.
    """
    checks = [c for c in condition.curves.values() if c.m68]
    r = condition.response
    if not checks or r is None:
        raise ValueError("the condition has no IACS UR M68 shaft check")
    count = len(checks)
    fig, axes = new_figure(count, 1, width=9.5, height=3.4 * count + 0.8, fig=fig)
    w = np.asarray(r.speed)
    n = w * RPM
    for check, ax in zip(checks, axes[:, 0], strict=True):
        ax.plot(
            n,
            check.curve(r) * 1e-6,
            color=COLORS[0],
            linewidth=1.8,
            label="synthesised stress (half range)",
        )
        ax.plot(n, check.limit(w) * 1e-6, color=COLORS[2], linewidth=1.3, label="τ_C continuous")
        if check.transient_limit is not None:
            ax.plot(
                n,
                check.transient_limit(w) * 1e-6,
                color=COLORS[1],
                linewidth=1.3,
                linestyle="--",
                label="τ_T transient (λ ≤ 0.8)",
            )
        for barred in condition.barred_ranges:
            if barred.component != check.component:
                continue
            ax.axvspan(
                barred.start * RPM,
                barred.end * RPM,
                color="#f4c7c3" if not barred.permitted else "#fbe5c8",
                zorder=0,
                label="declared barred range" + ("" if barred.permitted else " (not permitted)"),
            )
            ax.axvspan(
                barred.exceeds_start * RPM,
                barred.exceeds_end * RPM,
                facecolor="none",
                edgecolor="#7a1f1f",
                hatch="///",
                linewidth=0.0,
                zorder=0,
                label="found (stress above τ_C)",
            )
        ax.set_xlim(float(n[0]), float(n[-1]))
        ax.set_ylim(bottom=0.0)
        ax.set_ylabel("Shear stress (MPa)")
        ax.set_title(f"Shaft {check.component}", fontsize=10)
        ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8)
    axes[-1, 0].set_xlabel("Engine speed (rpm)")
    fig.suptitle(f"Torsional stress against the rule set's τ_C, τ_T: {condition.name}", fontsize=11)
    return fig


def plot_harmonics(result: HarmonicResult, fig: Figure | None = None) -> Figure:
    """Single-cylinder harmonic amplitudes per order: gas, inertia and total; major orders
    marked (the harmonic analysis of :mod:`crankdyn.torsion.excitation`).

    Parameters
    ----------
    result : crankdyn.torsion.harmonics.HarmonicResult
        The harmonic components of one cylinder's tangential effort (SI units).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(1, 1, width=9.5, height=4.6, fig=fig)
    ax = axes[0, 0]
    q = np.asarray(result.orders)
    width = 0.8 * (q[1] - q[0] if q.size > 1 else 0.5) / 3.0
    ax.bar(q - width, result.gas_amplitude, width, color=COLORS[1], label="gas part")
    ax.bar(q, result.inertia_amplitude, width, color=COLORS[2], label="inertia part")
    ax.bar(q + width, result.amplitude, width, color=COLORS[0], label="total")
    for j in np.flatnonzero(result.major if result.major is not None else []):
        ax.annotate(
            "major",
            (q[j], result.amplitude[j]),
            fontsize=7,
            ha="center",
            xytext=(0, 3),
            textcoords="offset points",
        )
    ax.set_xlabel("Order")
    ax.set_ylabel("Harmonic torque amplitude (N·m)")
    ax.set_title(f"Single-cylinder torque harmonics at {result.speed * RPM:.0f} rpm", fontsize=10)
    ax.legend(loc="upper right", fontsize=8)
    return fig


def plot_transient(
    result: TransientResult, shaft: tuple[str, str] | None = None, fig: Figure | None = None
) -> Figure:
    """Shaft torque against time (a run-up also against speed, on a second axis); torque drawn
    in kN·m, time in s, speed in rpm.

    Parameters
    ----------
    result : crankdyn.torsion.transient.TransientResult
        The time-domain response (SI units).
    shaft : (str, str) or None
        The shaft as its pair of masses; None: the one with the largest torque.
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    if shaft is None:
        s = int(np.argmax(np.max(np.abs(result.shaft_torque), axis=0)))
    else:
        s = next(i for i, label in enumerate(result.shafts) if tuple(label) == tuple(shaft))
    a, b = result.shafts[s]
    fig, axes = new_figure(1, 1, width=9.5, height=4.6, fig=fig)
    ax = axes[0, 0]
    ax.plot(result.time, result.shaft_torque[:, s] * 1e-3, color=COLORS[0], linewidth=0.7)
    ax.set_xlabel("Time (s)")
    ax.set_ylabel(f"Torque, shaft {a} - {b} (kN·m)")
    ax.set_xlim(float(result.time[0]), float(result.time[-1]))
    speed = np.asarray(result.speed) * RPM
    if np.ptp(speed) > 0.0:
        twin = ax.twinx()
        twin.plot(result.time, speed, color=COLORS[1], linewidth=1.0)
        twin.set_ylabel("Speed (rpm)", color=COLORS[1])
    ax.set_title(f"Time-domain response: {result.model_name}", fontsize=10)
    return fig
