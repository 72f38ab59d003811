"""Figures of a transient event: shaft torques, coupling torques and speeds against time, with
their limits drawn; and the TVC's event (:func:`plot_event_checks`): every checked quantity
against its limit over the run."""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np

from crankdyn.constants import RPM
from crankdyn.plots.style import COLORS, legend_outside, new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.torsion.event_result import EventResult
    from crankdyn.tvc.result import EventCondition

__all__ = ["plot_event", "plot_event_checks"]

SHAFTS_DRAWN = 4
"""The most shafts the first panel draws (the most loaded, one per named shaft)."""
STYLES = ("-", "--", "-.", ":")


def _most_loaded(result: EventResult, kinds: tuple[str, ...], count: int) -> list[int]:
    """The most loaded elements of ``kinds``, one per named component (a subdivided shaft's
    most loaded element)."""
    best: dict[str, int] = {}
    for e, kind in enumerate(result.element_kinds):
        if kind not in kinds:
            continue
        name = result.element_names[e]
        name = name.split(" (")[0] if " (" in name else "unnamed"
        if name not in best or result.peak(e) > result.peak(best[name]):
            best[name] = e
    return sorted(best.values(), key=result.peak, reverse=True)[:count]


def plot_event(
    result: EventResult,
    *,
    limits: bool | Mapping[str, float] = True,
    fig: Figure | None = None,
) -> Figure:
    """Three panels against time (s): the most loaded shafts' torques (kN m), the couplings'
    and gear meshes' torques (kN m) with their limits (+- T_Kmax of the couplings), and the
    speeds (rpm) of the first and last mass and of every coupling's halves.

    Parameters
    ----------
    result : crankdyn.torsion.event_result.EventResult
        The event's result (SI).
    limits : bool or mapping of str to float
        True: draw the limits the result holds (the couplings' T_Kmax); a mapping
        {element name or "a - b": limit torque (N m)} adds limits (e.g. tau_T x W_p of a
        shaft); False: none.
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(3, 1, width=9.5, height=9.0, fig=fig, sharex=True)
    t = result.time
    extra: dict[int, float] = {}
    if isinstance(limits, Mapping):
        extra = {result.element_index(k): float(v) for k, v in limits.items()}
    panels = (
        (axes[0, 0], _most_loaded(result, ("shaft",), SHAFTS_DRAWN), "Shaft torque (kN·m)"),
        (
            axes[1, 0],
            _most_loaded(result, ("coupling", "mesh", "gear"), 6),
            "Coupling and mesh torque (kN·m)",
        ),
    )
    for ax, elements, label in panels:
        for i, e in enumerate(elements):
            colour, style = COLORS[i % len(COLORS)], STYLES[(i // len(COLORS)) % len(STYLES)]
            ax.plot(
                t,
                result.torque[:, e] * 1e-3,
                color=colour,
                linestyle=style,
                linewidth=0.8,
                label=result.element_names[e],
            )
            level = extra.get(e)
            if level is None and limits is not False and np.isfinite(result.limit_torque[e]):
                level = float(result.limit_torque[e])
            if level is not None:
                for sign in (1.0, -1.0):
                    ax.axhline(
                        sign * level * 1e-3,
                        color=colour,
                        linestyle=":",
                        linewidth=1.0,
                        label=f"limit {result.element_names[e]}" if sign > 0 else None,
                    )
        ax.set_ylabel(label)
        if not elements:
            ax.text(0.5, 0.5, "none in the model", transform=ax.transAxes, ha="center")
        legend_outside(ax)
    ax = axes[2, 0]
    rings = sum(1 for kind in result.element_kinds if kind == "damper")
    shown = [0, len(result.masses) - 1 - rings]
    for e, kind in enumerate(result.element_kinds):
        if kind == "coupling":
            shown += [result.masses.index(n) for n in result.elements[e] if n in result.masses]
    for i, m in enumerate(dict.fromkeys(shown)):
        ax.plot(
            t,
            result.mass_speed[:, m] * RPM,
            color=COLORS[i % len(COLORS)],
            linestyle=STYLES[(i // len(COLORS)) % len(STYLES)],
            linewidth=0.9,
            label=result.masses[m],
        )
    ax.set_ylabel("Speed (rpm)")
    ax.set_xlabel("Time (s)")
    ax.set_xlim(float(t[0]), float(t[-1]))
    legend_outside(ax)
    fig.suptitle(f"{result.event}: {result.model_name}", fontsize=10)
    return fig


def plot_event_checks(condition: EventCondition, fig: Figure | None = None) -> Figure:
    """A TVC event's time history with its limits, three panels against time (s): every
    checked quantity as a fraction of its governing limit (the shafts' vibratory stress over
    tau_T, the couplings' torque over T_Kmax/T_Kmax1/T_Kmax2, the gear meshes' drop below
    their mean over the mean: a reversal above 1), the line 1 the limit; the couplings' torques
    (kN m) with their limits; and the speeds (rpm) of the first and last mass and of the
    couplings' halves.

    Parameters
    ----------
    condition : crankdyn.tvc.result.EventCondition
        The event, with its run and curves (SI).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    run: Any = condition.run  # the EventResult
    fig, axes = new_figure(3, 1, width=9.5, height=9.0, fig=fig, sharex=True)
    t = np.asarray(run.time)
    ax = axes[0, 0]
    top = 1.0
    for i, c in enumerate(condition.curves):
        with np.errstate(divide="ignore", invalid="ignore"):
            ratio = np.where(c.limit > 0.0, c.value / c.limit, np.nan)
        if not np.any(np.isfinite(ratio)):
            continue
        top = max(top, float(np.nanmax(ratio)))
        colour, style = COLORS[i % len(COLORS)], STYLES[(i // len(COLORS)) % len(STYLES)]
        label = f"{c.component}: {c.quantity} / {c.limit_name}"
        ax.plot(t, ratio, color=colour, linestyle=style, linewidth=0.8, label=label)
    ax.axhline(1.0, color="black", linewidth=1.2, linestyle="--", label="limit")
    ax.set_ylim(0.0, 1.1 * top)
    ax.set_ylabel("Value / limit")
    legend_outside(ax)
    ax = axes[1, 0]
    torques = [c for c in condition.curves if c.torque]
    for i, c in enumerate(torques):
        colour, style = COLORS[i % len(COLORS)], STYLES[(i // len(COLORS)) % len(STYLES)]
        ax.plot(t, c.value * 1e-3, color=colour, linestyle=style, linewidth=0.8,
                label=f"{c.component} |T|")  # fmt: skip
        ax.plot(t, c.limit * 1e-3, color=colour, linestyle=":", linewidth=1.0,
                label=f"{c.component} {c.limit_name}")  # fmt: skip
    if not torques:
        ax.text(0.5, 0.5, "no coupling with a maximum torque", transform=ax.transAxes,
                ha="center")  # fmt: skip
    ax.set_ylabel("Coupling torque (kN·m)")
    legend_outside(ax)
    ax = axes[2, 0]
    rings = sum(1 for kind in run.element_kinds if kind == "damper")
    shown = [0, len(run.masses) - 1 - rings]
    for e, kind in enumerate(run.element_kinds):
        if kind == "coupling":
            shown += [run.masses.index(n) for n in run.elements[e] if n in run.masses]
    for i, m in enumerate(dict.fromkeys(shown)):
        ax.plot(t, np.asarray(run.mass_speed)[:, m] * RPM, color=COLORS[i % len(COLORS)],
                linestyle=STYLES[(i // len(COLORS)) % len(STYLES)], linewidth=0.9,
                label=run.masses[m])  # fmt: skip
    ax.set_ylabel("Speed (rpm)")
    ax.set_xlabel("Time (s)")
    ax.set_xlim(float(t[0]), float(t[-1]))
    legend_outside(ax)
    fig.suptitle(f"{condition.name}: every checked component against its limit", fontsize=10)
    return fig
