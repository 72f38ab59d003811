"""Plots of a design search: the candidates in the plane of two objectives with the Pareto
front, or the objective of every candidate in the order evaluated."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from crankdyn.plots.style import COLORS, new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.design.result import DesignResult

__all__ = ["plot_design"]


def _axis(label: str, unit: str) -> str:
    return f"{label} ({unit})" if unit else label


def plot_design(result: DesignResult, fig: Figure | None = None) -> Figure:
    """The candidates of a design search (feasible, infeasible) in the plane of the first two
    objectives with the Pareto front joined, or with one objective, the objective of every
    feasible candidate against its number.

    Parameters
    ----------
    result : crankdyn.design.result.DesignResult
        The search.
    fig : matplotlib.figure.Figure or None
        Figure to draw into (new when None).

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(1, 1, width=7.0, height=4.6, fig=fig)
    ax = axes[0, 0]
    space = result.space
    assert space is not None  # a search's result
    objectives = space.objectives
    ok = [c for c in result.candidates if c.ok and None not in c.objectives[:2]]
    feasible = [c for c in ok if c.feasible]
    infeasible = [c for c in ok if not c.feasible]
    first = objectives[0]
    if len(objectives) >= 2:
        second = objectives[1]
        for group, color, name in (
            (infeasible, COLORS[6], "infeasible"),
            (feasible, COLORS[0], "feasible"),
        ):
            if group:
                xs = np.array([c.objectives[0] for c in group], dtype=float)
                ys = np.array([c.objectives[1] for c in group], dtype=float)
                ax.scatter(xs, ys, s=14, color=color, label=name)
        front = [result.candidates[i] for i in result.front]
        if front:
            xs = np.array([c.objectives[0] for c in front], dtype=float)
            ys = np.array([c.objectives[1] for c in front], dtype=float)
            order = np.argsort(xs)
            ax.plot(xs[order], ys[order], "-o", color=COLORS[1], label="Pareto front")
        ax.set_xlabel(_axis(first.label or first.name, first.unit))
        ax.set_ylabel(_axis(second.label or second.name, second.unit))
        ax.set_title("Design search: candidates and Pareto front")
    else:
        for group, color, name in (
            (infeasible, COLORS[6], "infeasible"),
            (feasible, COLORS[0], "feasible"),
        ):
            if group:
                xs = np.array([c.number for c in group], dtype=float)
                ys = np.array([c.objectives[0] for c in group], dtype=float)
                ax.scatter(xs, ys, s=14, color=color, label=name)
        ax.set_xlabel("Candidate (order evaluated)")
        ax.set_ylabel(_axis(first.label or first.name, first.unit))
        ax.set_title("Design search: objective of every candidate")
    if ok:
        ax.legend(loc="best", fontsize="small")
    return fig
