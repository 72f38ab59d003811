"""The schematic of a mass-elastic system, drawn from its torsional model: every mass a block
whose height grows with the logarithm of its inertia, shafts as lines labelled with their
stiffness, couplings as springs, gear meshes as paired wheels with their ratio, branches on rows
of their own, dampers on the mass they are mounted on and the cylinders named on their masses.

Layout: the masses are walked from the first (the free end) along the shafts and meshes; the
line goes on to the right in the same row, a gear mesh steps down to the next row (the wheel
under its pinion) and every further branch of a mass starts a new row below the others. A
distributed shaft (a shaft divided into elements, :mod:`crankdyn.torsion.distributed`) is drawn
as one shaft from its first to its last mass; its interior elements are not drawn.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from crankdyn.display import quantity
from crankdyn.plots.style import COLORS, new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from crankdyn.torsion.model import TorsionModel

__all__ = ["Link", "SchematicLayout", "layout_schematic", "plot_schematic"]

GROUND = "ground"


@dataclass(frozen=True)
class Link:
    """A connection drawn between two masses (or a mass and ground).

    Parameters
    ----------
    a, b : str
        The masses (``"ground"`` for a grounded shaft's end).
    kind : str
        ``"shaft"``, ``"coupling"``, ``"distributed"``, ``"mesh"`` (a gear mesh, rigid or
        elastic) or ``"joint"`` (two models joined rigidly).
    label : str
        The words drawn with it (stiffness, ratio, designation).
    """

    a: str
    b: str
    kind: str
    label: str = ""


@dataclass
class SchematicLayout:
    """Where every mass of a schematic goes (:func:`layout_schematic`).

    Parameters
    ----------
    position : dict of str to (float, float)
        (column, row) of every mass drawn; rows go down from 0.
    links : list of Link
        The connections drawn.
    inertia : dict of str to float
        The inertia of every mass drawn (kg m^2).
    """

    position: dict[str, tuple[float, float]] = field(default_factory=dict)
    links: list[Link] = field(default_factory=list)
    inertia: dict[str, float] = field(default_factory=dict)

    @property
    def rows(self) -> int:
        """The number of rows used."""
        return 1 + int(max((r for _c, r in self.position.values()), default=0))


def _links(model: TorsionModel) -> list[Link]:
    """The connections of the model, the elements of a distributed shaft as one."""
    out: list[Link] = []
    seen: set[tuple[str, str]] = set()
    for s in model.shafts:
        segment = getattr(s, "segment_of", None)
        if segment is not None:
            if tuple(segment) not in seen:
                seen.add(tuple(segment))
                count = sum(1 for x in model.shafts if getattr(x, "segment_of", None) == segment)
                stiff = 1.0 / sum(
                    1.0 / x.stiffness
                    for x in model.shafts
                    if getattr(x, "segment_of", None) == segment
                )
                out.append(
                    Link(segment[0], segment[1], "distributed", f"{_stiffness(stiff)}\n{count} el.")
                )
            continue
        a, b = s.between
        if s.coupling is not None:
            out.append(Link(a, b, "coupling", _stiffness(s.stiffness)))
        elif s.gear is not None:
            out.append(Link(a, b, "mesh", f"i = {1.0 / s.ratio:.4g}\n(elastic)"))
        else:
            out.append(Link(a, b, "shaft", _stiffness(s.stiffness)))
    for g in model.gears:
        a, b = g.between
        if g.joint:
            out.append(Link(a, b, "joint", ""))
        else:
            out.append(Link(a, b, "mesh", f"i = {1.0 / g.ratio:.4g}"))
    return out


def _stiffness(k: float) -> str:
    """A stiffness in MN·m/rad, the class forms' unit (the unit is in the figure's title)."""
    return f"{k / 1e6:.4g}"


def layout_schematic(model: TorsionModel) -> SchematicLayout:
    """Place the masses of a model (module docstring).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model.

    Returns
    -------
    SchematicLayout
        The positions (column, row), the connections and the inertias (kg m^2).

    Examples
    --------
    A flywheel driving a pinion; its wheel drives a propeller, and a pump hangs on the
    flywheel: the mesh steps down a row, the pump's branch gets a row of its own.

    >>> from crankdyn.torsion import Gear, Mass, Shaft, TorsionModel
    >>> m = TorsionModel(
    ...     (Mass("flywheel", 10.0), Mass("pinion", 0.5), Mass("wheel", 4.0),
    ...      Mass("propeller", 90.0), Mass("pump", 0.2)),
    ...     (Shaft(("flywheel", "pinion"), 1e6), Shaft(("wheel", "propeller"), 9e6),
    ...      Shaft(("flywheel", "pump"), 1e4)),
    ...     gears=(Gear(("pinion", "wheel"), 1 / 3),))
    >>> layout_schematic(m).position
    {'flywheel': (0, 0), 'pinion': (1, 0), 'wheel': (1, 1), 'propeller': (2, 1), 'pump': (1, 2)}
    """
    links = _links(model)
    drawn = [m.name for m in model.masses]
    linked = {n for lk in links for n in (lk.a, lk.b)}
    inner = {n for n in drawn if n not in linked}  # interior elements of distributed shafts
    names = [n for n in drawn if n not in inner]
    neighbours: dict[str, list[tuple[str, Link]]] = {n: [] for n in names}
    for lk in links:
        if lk.a in neighbours and lk.b in neighbours:
            neighbours[lk.a].append((lk.b, lk))
            neighbours[lk.b].append((lk.a, lk))
    out = SchematicLayout(
        links=links, inertia={m.name: m.inertia for m in model.masses if m.name not in inner}
    )
    next_row = 0

    def follow(name: str) -> tuple[list[tuple[str, str, Link]], list[tuple[str, str, Link]]]:
        """Lay the line on from ``name`` to the right; return the meshes and branches met."""
        meshes: list[tuple[str, str, Link]] = []
        branches: list[tuple[str, str, Link]] = []
        while True:
            col, row = out.position[name]
            ahead = [(o, lk) for o, lk in neighbours[name] if o not in out.position]
            straight = next((o for o, lk in ahead if lk.kind != "mesh"), None)
            for o, lk in ahead:
                if o != straight:
                    (meshes if lk.kind == "mesh" else branches).append((name, o, lk))
            if straight is None:
                return meshes, branches
            out.position[straight] = (col + 1, row)
            name = straight

    for start in names:  # every connected part (a model is connected: one start)
        if start in out.position:
            continue
        out.position[start] = (0, next_row)
        next_row += 1
        meshes, branches = follow(start)
        while meshes or branches:
            frm, other, lk = meshes.pop(0) if meshes else branches.pop(0)
            if other in out.position:
                continue
            col, _row = out.position[frm]
            out.position[other] = (col if lk.kind == "mesh" else col + 1, next_row)
            next_row += 1
            more_meshes, more_branches = follow(other)
            meshes, branches = more_meshes + meshes, more_branches + branches
    return out


def _heights(inertia: dict[str, float]) -> dict[str, float]:
    """Block heights (rows' units) growing with log10 of the inertia, 0.2 to 0.8."""
    values = np.array([max(v, 1e-12) for v in inertia.values()])
    lo, hi = float(np.log10(values.min())), float(np.log10(values.max()))
    span = hi - lo if hi > lo else 1.0
    return {n: 0.2 + 0.6 * (math.log10(max(v, 1e-12)) - lo) / span for n, v in inertia.items()}


def _spring(ax: Axes, x0: float, x1: float, y: float, color: str) -> None:
    """A zigzag spring from x0 to x1 at height y (a coupling)."""
    xs = np.linspace(x0, x1, 13)
    ys = y + 0.08 * np.array([0, 1, -1, 1, -1, 1, -1, 1, -1, 1, -1, 1, 0]) * (x1 > x0)
    ax.plot(xs, ys, color=color, linewidth=1.4, zorder=2)


def _draw_link(ax: Axes, lk: Link, pos: dict, half: dict[str, float]) -> None:
    """One connection: a shaft line, a spring, a double line or a mesh."""
    if GROUND in (lk.a, lk.b):
        name = lk.b if lk.a == GROUND else lk.a
        x, y = pos[name]
        ax.plot([x, x + 0.35], [y, y], color="black", linewidth=1.6, zorder=1)
        ax.plot([x + 0.35] * 2, [y - 0.2, y + 0.2], color="black", linewidth=2.0)
        for k in range(5):
            yy = y - 0.2 + 0.1 * k
            ax.plot([x + 0.35, x + 0.45], [yy, yy - 0.08], color="black", linewidth=0.8)
        return
    (xa, ya), (xb, yb) = pos[lk.a], pos[lk.b]
    if lk.kind in ("mesh", "joint"):
        if lk.kind == "joint":
            ax.plot([xa, xb], [ya, yb], color="#7f7f7f", linewidth=1.0, linestyle=":")
        else:  # two wheels in mesh: a short thick bar between them, the ratio beside it
            ax.plot([xa, xb], [ya, yb], color=COLORS[3], linewidth=3.0, zorder=1)
        ax.annotate(  # beside the bar, below the upper mass's name (drawn down its right)
            lk.label,
            (xa + 0.4 * (xb - xa), ya + 0.6 * (yb - ya)),
            xytext=(12, 0),
            textcoords="offset points",
            fontsize=7,
            color=COLORS[3] if lk.kind == "mesh" else "#7f7f7f",
            va="center",
        )
        return
    y_line = ya if ya == yb else (ya + yb) / 2
    if ya != yb:  # a branch: down from a, then across to b
        ax.plot([xa, xa, xb], [ya, yb, yb], color="black", linewidth=1.6, zorder=1)
        xa, ya = xa, yb
        y_line = yb
    if lk.kind == "coupling":
        gap_a, gap_b = xa + 0.22, xb - 0.22
        ax.plot([xa, gap_a], [y_line] * 2, color="black", linewidth=1.6, zorder=1)
        ax.plot([gap_b, xb], [y_line] * 2, color="black", linewidth=1.6, zorder=1)
        _spring(ax, gap_a, gap_b, y_line, COLORS[1])
        color = COLORS[1]
        y_line += 0.08  # the label above the spring
    elif lk.kind == "distributed":
        ax.plot([xa, xb], [y_line] * 2, color="black", linewidth=3.2, zorder=1)
        ax.plot([xa, xb], [y_line] * 2, color="white", linewidth=1.2, zorder=1)
        color = "black"
    else:
        ax.plot([xa, xb], [y_line] * 2, color="black", linewidth=1.6, zorder=1)
        color = "#404040"
    ax.text(
        (xa + xb) / 2,
        y_line + 0.06,
        lk.label,
        fontsize=7.5 if "\n" not in lk.label else 6.5,
        linespacing=1.0,
        color=color,
        ha="center",
        va="bottom",
        zorder=4,
    )


def plot_schematic(model: TorsionModel, fig: Figure | None = None) -> Figure:
    """The schematic of the mass-elastic system of ``model`` (module docstring): blocks for the
    masses (height growing with log10 of the inertia, its value in kg·m² under the name), lines
    for the shafts (stiffness in MN·m/rad), springs for the couplings, bars for the gear meshes
    (ratio i = n_a / n_b), a double line for a distributed shaft; cylinders (C1, C2...) and
    dampers marked on their masses.

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The lumped torsional model (SI units).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    lay = layout_schematic(model)
    cols = 1 + max(int(c) for c, _r in lay.position.values())
    rows = lay.rows
    fig, axes = new_figure(
        1, 1, width=min(max(7.0, 0.62 * cols + 1.2), 10.0), height=0.9 + 1.45 * rows, fig=fig
    )
    ax = axes[0, 0]
    ax.grid(False)
    ax.set_axis_off()
    pos = {n: (float(c), -1.45 * float(r)) for n, (c, r) in lay.position.items()}
    half = {n: h / 2 for n, h in _heights(lay.inertia).items()}
    for lk in lay.links:
        if (lk.a in pos or lk.a == GROUND) and (lk.b in pos or lk.b == GROUND):
            _draw_link(ax, lk, pos, half)
    masses = {m.name: m for m in model.masses}
    dampers: dict[str, list[Any]] = {}
    for d in model.dampers:
        dampers.setdefault(d.at, []).append(d)
    for name, (x, y) in pos.items():
        m = masses[name]
        h = half[name]
        cylinders = tuple(getattr(m, "cylinders", ()) or ())
        color = COLORS[0] if cylinders else ("#5b6b7b" if m.role != "propeller" else COLORS[2])
        ax.add_patch(_rectangle((x - 0.17, y - h), 0.34, 2 * h, color))
        if cylinders:
            ax.text(x, y, "C" + ",".join(map(str, cylinders)), fontsize=6, color="white",
                    ha="center", va="center", zorder=5)  # fmt: skip
        ax.text(
            x,
            y - 0.5,
            f"{name}\n{quantity(m.inertia, 'kg·m²', significant=4)}",
            fontsize=7.5,
            ha="right",
            va="top",
            rotation=35,
            rotation_mode="anchor",
            zorder=4,
            bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.8, "pad": 0.5},
        )
        for k, d in enumerate(dampers.get(name, [])):
            ax.add_patch(_rectangle((x - 0.14, y + h + 0.08 + 0.3 * k), 0.28, 0.22, COLORS[4]))
            ax.text(x + 0.2, y + h + 0.19 + 0.3 * k, f"{d.name} ({d.kind})", fontsize=7.5,
                    color=COLORS[4], va="center")  # fmt: skip
    xs = [p[0] for p in pos.values()]
    ys = [p[1] for p in pos.values()]
    ax.set_xlim(min(xs) - 0.8, max(xs) + 1.0)
    ax.set_ylim(min(ys) - 1.3, max(ys) + 0.9)
    ax.set_title(
        f"Mass-elastic system: {model.name}\n(inertia in kg·m², stiffness in MN·m/rad, "
        "gear ratio i = n_in / n_out;\nblue: cylinders, green: propeller, "
        "red spring: elastic coupling, dotted: rigid joint)",
        fontsize=9,
    )
    return fig


def _rectangle(xy: tuple[float, float], width: float, height: float, color: str) -> Any:
    """A filled block (a mass or a damper ring)."""
    from matplotlib.patches import Rectangle

    return Rectangle(xy, width, height, facecolor=color, edgecolor="black", linewidth=0.6,
                     zorder=3)  # fmt: skip
