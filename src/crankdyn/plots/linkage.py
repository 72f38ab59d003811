"""Plots of planar linkages: the mechanism with force vectors, coupler curves, transmission angle,
driving torque over the cycle, and a GIF animation of a full cycle."""

from __future__ import annotations

import io
import math
import textwrap
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.patches import Polygon, Rectangle

from crankdyn.plausibility import TRANSMISSION_ANGLE_MIN
from crankdyn.plots.style import COLORS, angle_axis, identical, legend_outside, new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from crankdyn.linkage.fourbar import FourBarResult
    from crankdyn.linkage.kinetostatics import KinetostaticsResult
    from crankdyn.linkage.motion import MechanismMotion

__all__ = [
    "animate_mechanism",
    "draw_mechanism",
    "plot_fourbar",
    "plot_kinetostatics",
    "plot_mechanism",
    "plot_paths",
]

_LINK_COLORS = COLORS[:6] + COLORS[7:]
JOINT_LABEL = "joint-label"
FORCE_LABEL = "force-label"
"""gid of the joint-name and force-value annotations (so tests and the de-cluttering find them)."""


def _link_color(i: int) -> str:
    return _LINK_COLORS[i % len(_LINK_COLORS)]


def _ground_mark(ax, xy, size):
    """A hatched ground symbol under a fixed pivot."""
    x, y = xy
    tri = Polygon(
        [(x, y), (x - 0.6 * size, y - size), (x + 0.6 * size, y - size)],
        closed=True,
        facecolor="#e6e6e6",
        edgecolor="#404040",
        linewidth=0.8,
        zorder=1,
    )
    ax.add_patch(tri)
    ax.plot([x - size, x + size], [y - size, y - size], color="#404040", linewidth=1.0, zorder=1)


def draw_mechanism(
    ax: Axes,
    motion: MechanismMotion,
    index: int = 0,
    *,
    forces: KinetostaticsResult | None = None,
    labels: bool = True,
    scale: float | None = None,
) -> None:
    """Draw the mechanism of a :class:`~crankdyn.linkage.motion.MechanismMotion` at position
    ``index`` on ``ax``: links, joints, fixed pivots, sliders and guides, centres of gravity, and,
    with a :class:`~crankdyn.linkage.kinetostatics.KinetostaticsResult`, the joint forces on the
    second link of each joint as arrows (scaled to the largest force of the cycle).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        The axes to draw on (in the mechanism's lengths, m).
    motion : crankdyn.linkage.motion.MechanismMotion
        The positions of the mechanism over the crank angles (lengths in m, angles in rad).
    index : int
        The position drawn (index into the crank angles).
    forces : crankdyn.linkage.kinetostatics.KinetostaticsResult or None
        The joint forces (N) and driving torque (N·m) over the same positions, or None.
    labels : bool
        Name the joints (and give the force values).
    scale : float or None
        Arrow length per unit force (m/N); None: the largest force of the cycle drawn 0.35
        times the mechanism's length scale.
    """
    from crankdyn.linkage.elements import GROUND

    mech = motion.mechanism
    size = mech.length_scale
    mark = 0.035 * size
    pos = {n: p[index] for n, p in motion.all_points().items()}
    for i, link in enumerate(mech.links):
        color = _link_color(i)
        pts = [motion.point(p, link=link.name)[index] for p in link.points]
        if len(pts) >= 3:
            ax.add_patch(
                Polygon(pts, closed=True, facecolor=color, alpha=0.18, edgecolor=color, zorder=2)
            )
        if len(pts) >= 2:
            xs, ys = zip(*(pts + ([pts[0]] if len(pts) >= 3 else [])), strict=True)
            ax.plot(xs, ys, color=color, linewidth=3.0, solid_capstyle="round", zorder=3)
        if len(pts) == 1:  # a slider block
            angle = 0.0
            for j in mech.joints:
                if j.kind == "prismatic" and j.links[1] == link.name:
                    rot = 0.0 if j.links[0] == GROUND else motion.link_state(j.links[0])[index, 2]
                    assert j.axis is not None  # a prismatic joint has its axis
                    angle = j.axis + rot
            w, h = 2.4 * mark, 1.4 * mark
            c, s = math.cos(angle), math.sin(angle)
            x0, y0 = pts[0]
            corner = (x0 - (w / 2) * c + (h / 2) * s, y0 - (w / 2) * s - (h / 2) * c)
            ax.add_patch(
                Rectangle(
                    corner,
                    w,
                    h,
                    angle=math.degrees(angle),
                    facecolor=color,
                    alpha=0.5,
                    edgecolor=color,
                    zorder=3,
                )
            )
        g = motion.link_state(link.name)[index, :2]
        if link.mass > 0.0:
            ax.plot(*g, marker="o", markersize=5, markerfacecolor="white", color=color, zorder=5)
    # guides of prismatic joints
    for j in mech.joints:
        if j.kind != "prismatic":
            continue
        r = motion.point(j.point, link=j.links[1])
        rot = 0.0 if j.links[0] == GROUND else motion.link_state(j.links[0])[:, 2]
        ang = j.axis + np.broadcast_to(rot, r.shape[:1])
        t = np.stack([np.cos(ang), np.sin(ang)], axis=1)
        along = np.sum((r - r[index]) * t[index], axis=1)
        lo, hi = float(np.min(along)) - 2 * mark, float(np.max(along)) + 2 * mark
        if j.links[0] != GROUND:
            lo, hi = -1.5 * size * 0.3, 1.5 * size * 0.3
        p0 = r[index] + lo * t[index]
        p1 = r[index] + hi * t[index]
        ax.plot([p0[0], p1[0]], [p0[1], p1[1]], color="#404040", linewidth=1.0, zorder=1)
    # joints and fixed pivots
    for j in mech.joints:
        p = pos[j.point] if j.kind == "revolute" else None
        if p is None:
            continue
        if GROUND in j.links:
            _ground_mark(ax, p, mark)
        ax.plot(*p, marker="o", markersize=6, markerfacecolor="white", color="#202020", zorder=6)
    if labels:
        for name, p in pos.items():
            ax.annotate(
                name,
                p,
                xytext=(5, 5),
                textcoords="offset points",
                fontsize=8,
                color="#202020",
                zorder=7,
                gid=JOINT_LABEL,
            )
    if forces is not None:
        assert forces.joint_forces is not None  # a kinetostatics result carries its forces
        peak = max(
            (float(np.max(np.hypot(f["x"], f["y"]))) for f in forces.joint_forces.values()),
            default=0.0,
        )
        scale = scale or (0.35 * size / peak if peak > 0 else 0.0)
        for j in mech.joints:
            f = forces.joint_forces[j.name]
            fx, fy = float(f["x"][index]), float(f["y"][index])
            p = motion.point(j.point, link=j.links[1])[index]
            if math.hypot(fx, fy) * scale < 1e-3 * size:
                continue
            ax.annotate(
                "",
                xy=(p[0] + fx * scale, p[1] + fy * scale),
                xytext=(p[0], p[1]),
                arrowprops={"arrowstyle": "-|>", "color": COLORS[1], "linewidth": 1.4},
                zorder=8,
            )
            # the label beyond the arrow's tip, on the side it points to (away from the joint)
            norm = math.hypot(fx, fy)
            ux, uy = fx / norm, fy / norm
            ax.annotate(
                f"{norm:.4g} N",
                (p[0] + fx * scale, p[1] + fy * scale),
                fontsize=7,
                color=COLORS[1],
                xytext=(6 * ux, 6 * uy),
                textcoords="offset points",
                ha="left" if ux > 0.3 else "right" if ux < -0.3 else "center",
                va="bottom" if uy > 0.3 else "top" if uy < -0.3 else "center",
                zorder=8,
                gid=FORCE_LABEL,
            )
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")


def _frame_limits(ax, motion, margin=0.12):
    xy = np.concatenate([p for p in motion.all_points().values()], axis=0)
    lo, hi = xy.min(axis=0), xy.max(axis=0)
    pad = margin * float(max(hi - lo))
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)


def plot_mechanism(
    motion: MechanismMotion,
    index: int = 0,
    forces: KinetostaticsResult | None = None,
    fig: Figure | None = None,
) -> Figure:
    """The mechanism at one position, with the paths of its points and (given a kinetostatics
    result) the joint forces as arrows; crank angle in degrees, torque in N·m in the title.

    Parameters
    ----------
    motion : crankdyn.linkage.motion.MechanismMotion
        The positions of the mechanism over the crank angles (lengths in m, angles in rad).
    index : int
        The position drawn (index into the crank angles).
    forces : crankdyn.linkage.kinetostatics.KinetostaticsResult or None
        The joint forces (N) and driving torque (N·m) over the same positions, or None.
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(1, 1, width=8.0, height=6.5, fig=fig)
    ax = axes[0, 0]
    for name, p in motion.all_points().items():
        if np.ptp(p[:, 0]) + np.ptp(p[:, 1]) > 0:
            ax.plot(p[:, 0], p[:, 1], color="#b0b0b0", linewidth=0.8, zorder=0)
            del name
    draw_mechanism(ax, motion, index, forces=forces)
    _frame_limits(ax, motion)
    theta = math.degrees(motion.crank_angle[index])
    state = f"crank angle {theta:.4g}°"
    if forces is not None:
        state += f", driving torque {forces.driving_torque[index]:.4g} N·m"
        ax.plot([], [], color=COLORS[1], label="joint force on the second link (N)")
        legend_outside(ax)
    _title(fig, motion.mechanism.name, state)
    declutter(fig, ax)
    return fig


def _title(fig: Figure, name: str, state: str = "", fontsize: float = 10.0) -> None:
    """The figure title: the (user's) mechanism name wrapped to the figure's width, the state
    on a line of its own; it stays inside the figure whatever the name's length."""
    chars = max(int(fig.get_figwidth() * 72 / (0.62 * fontsize)), 20)
    lines = textwrap.wrap(name, chars) or [""]
    if state:
        lines += textwrap.wrap(state, chars)
    fig.suptitle("\n".join(lines), fontsize=fontsize)


def declutter(fig: Any, ax: Any) -> None:
    """Move each force label (gid FORCE_LABEL) to the first place around its arrow's tip where
    it overlaps no joint label and no other force label (in the final layout). Needs a
    renderer: draws the figure once on an Agg canvas."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    texts = [t for t in ax.texts if t.get_gid() in (JOINT_LABEL, FORCE_LABEL)]
    forces = [t for t in texts if t.get_gid() == FORCE_LABEL]
    if not forces:
        return
    if not isinstance(fig.canvas, FigureCanvasAgg):
        FigureCanvasAgg(fig)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    fig.set_layout_engine("none")  # keep the layout these positions were found in

    def box(text):
        return text.get_window_extent(renderer).expanded(1.05, 1.1)

    taken = [box(t) for t in texts if t not in forces]
    for text in forces:
        places = [(text.xyann, text.get_ha(), text.get_va()), *_PLACES]
        for offset, ha, va in places:
            text.xyann = offset
            text.set_ha(ha)
            text.set_va(va)
            if not any(box(text).overlaps(other) for other in taken):
                break
        else:  # nowhere free: keep the first place
            text.xyann, ha, va = places[0]
            text.set_ha(ha)
            text.set_va(va)
        taken.append(box(text))


_PLACES = tuple(  # other places for a force label: (dx, dy) points from the arrow's tip
    ((dx, dy), "left" if dx > 0 else "right" if dx < 0 else "center", va)
    for dx, dy, va in (
        (6.0, 6.0, "bottom"),
        (6.0, -6.0, "top"),
        (-6.0, 6.0, "bottom"),
        (-6.0, -6.0, "top"),
        (0.0, 12.0, "bottom"),
        (0.0, -12.0, "top"),
        (16.0, 0.0, "center"),
        (-16.0, 0.0, "center"),
        (12.0, 18.0, "bottom"),
        (12.0, -18.0, "top"),
        (-12.0, 18.0, "bottom"),
        (-12.0, -18.0, "top"),
    )
)


def plot_paths(motion: MechanismMotion, fig: Figure | None = None) -> Figure:
    """Paths (coupler curves) of every moving point over the crank angles (in m), the
    mechanism drawn at its first position.

    Parameters
    ----------
    motion : crankdyn.linkage.motion.MechanismMotion
        The positions of the mechanism over the crank angles (lengths in m, angles in rad).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(1, 1, width=8.0, height=6.5, fig=fig)
    ax = axes[0, 0]
    i = 0
    for name, p in motion.all_points().items():
        if np.ptp(p[:, 0]) + np.ptp(p[:, 1]) <= 1e-12:
            continue
        ax.plot(p[:, 0], p[:, 1], color=COLORS[i % len(COLORS)], linewidth=1.4, label=name)
        i += 1
    draw_mechanism(ax, motion, 0, labels=True)
    _frame_limits(ax, motion)
    legend_outside(ax, title="Point paths")
    _title(fig, motion.mechanism.name, "point paths (coupler curves)")
    return fig


def plot_fourbar(result: FourBarResult, fig: Figure | None = None) -> Figure:
    """Four panels: the linkage at the first angle with the coupler curve, the transmission angle
    with its extremes (against the plausibility limit), the angular velocities and the angular
    accelerations (formulas and sources in :mod:`crankdyn.linkage.fourbar`); angles drawn in
    degrees, angular velocities in rad/s, accelerations in rad/s².

    Parameters
    ----------
    result : crankdyn.linkage.fourbar.FourBarResult
        The four-bar analysis (SI units).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(2, 2, width=11.0, height=8.0, fig=fig)
    fb = result.linkage
    assert fb is not None  # a four-bar result carries its linkage
    ax = axes[0, 0]
    theta = result.crank_angle
    a, _b, c, d = fb.lengths
    bx, by = a * np.cos(theta), a * np.sin(theta)
    cx, cy = d + c * np.cos(result.rocker_angle), c * np.sin(result.rocker_angle)
    ax.plot(cx, cy, color="#b0b0b0", linewidth=0.9, label="path of C")
    if result.coupler_point_x is not None:
        ax.plot(
            result.coupler_point_x, result.coupler_point_y, color=COLORS[3], label="coupler curve"
        )
    # draw the linkage at the angle nearest 60 deg (a clear, open position)
    i = int(np.argmin(np.abs(np.remainder(theta - math.pi / 3 + math.pi, 2 * math.pi) - math.pi)))
    ax.plot([0, bx[i]], [0, by[i]], color=COLORS[0], linewidth=3, label="crank AB")
    ax.plot([bx[i], cx[i]], [by[i], cy[i]], color=COLORS[2], linewidth=3, label="coupler BC")
    ax.plot([d, cx[i]], [0, cy[i]], color=COLORS[4], linewidth=3, label="rocker DC")
    if result.coupler_point_x is not None:
        assert result.coupler_point_y is not None  # set together with the x coordinates
        px, py = result.coupler_point_x[i], result.coupler_point_y[i]
        ax.add_patch(
            Polygon([(bx[i], by[i]), (cx[i], cy[i]), (px, py)], alpha=0.2, color=COLORS[2])
        )
        ax.plot(px, py, "o", color=COLORS[3], zorder=5)
        ax.annotate("P", (px, py), xytext=(5, 5), textcoords="offset points", fontsize=8)
    size = max(fb.lengths)
    for x in (0.0, d):
        _ground_mark(ax, (x, 0.0), 0.04 * size)
    for x, y, n in ((0, 0, "A"), (bx[i], by[i], "B"), (cx[i], cy[i], "C"), (d, 0, "D")):
        ax.plot(x, y, "o", markerfacecolor="white", color="#202020", zorder=5)
        ax.annotate(n, (x, y), xytext=(5, 5), textcoords="offset points", fontsize=8)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(
        f"{result.grashof_type}, {result.branch} branch, θ2 = {math.degrees(theta[i]):.4g}°",
        fontsize=10,
    )
    legend_outside(ax)
    deg = np.degrees(theta)
    ax = axes[0, 1]
    ax.plot(deg, np.degrees(result.transmission), color=COLORS[0], label="μ")
    lim = result.limits
    for v, text in ((lim.transmission_angle_min, "min"), (lim.transmission_angle_max, "max")):
        ax.axhline(math.degrees(v), color=COLORS[1], linewidth=0.8, linestyle="--")
        ax.annotate(
            f"{text} {math.degrees(v):.2f}°",
            (0.5 * (deg[0] + deg[-1]), math.degrees(v)),
            fontsize=8,
            xytext=(0, 3),
            textcoords="offset points",
            ha="center",
            color=COLORS[1],
        )
    for limit in (TRANSMISSION_ANGLE_MIN, math.pi - TRANSMISSION_ANGLE_MIN):
        ax.axhline(math.degrees(limit), color="#808080", linewidth=0.8, linestyle=":")
    ax.plot([], [], color="#808080", linewidth=0.8, linestyle=":", label="design limits 40°/140°")
    legend_outside(ax)
    ax.set_ylabel("Transmission angle μ (deg)")
    angle_axis(ax, deg)
    ax = axes[1, 0]
    ax.plot(deg, result.coupler_angular_velocity, color=COLORS[2], label="coupler ω3")
    ax.plot(deg, result.rocker_angular_velocity, color=COLORS[4], label="rocker ω4")
    ax.set_ylabel("Angular velocity (rad/s)")
    legend_outside(ax)
    angle_axis(ax, deg)
    ax = axes[1, 1]
    ax.plot(deg, result.coupler_angular_acceleration, color=COLORS[2], label="coupler α3")
    ax.plot(deg, result.rocker_angular_acceleration, color=COLORS[4], label="rocker α4")
    ax.set_ylabel("Angular acceleration (rad/s²)")
    legend_outside(ax)
    angle_axis(ax, deg)
    fig.suptitle(
        f"Four-bar a = {a * 1e3:.5g}, b = {fb.coupler * 1e3:.5g}, c = {c * 1e3:.5g}, "
        f"d = {d * 1e3:.5g} mm; crank speed {result.crank_speed:.4g} rad/s"
    )
    return fig


def plot_kinetostatics(result: KinetostaticsResult, fig: Figure | None = None) -> Figure:
    """Driving torque over the cycle by the matrix method and by virtual work (and without
    friction, with the efficiency), and the joint force magnitudes (methods and sources in
    :mod:`crankdyn.linkage.kinetostatics`, seed 004); torque drawn in N·m, forces in N, crank
    angle in degrees.

    Parameters
    ----------
    result : crankdyn.linkage.kinetostatics.KinetostaticsResult
        The kinetostatic analysis (SI units).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(2, 1, width=10.0, height=7.5, fig=fig, sharex=True)
    deg = np.degrees(result.crank_angle)
    ax = axes[0, 0]
    ax.plot(
        deg,
        result.driving_torque,
        color=COLORS[0],
        linewidth=1.8,
        label="matrix method [C]{R} = [D]{P}" + (" with friction" if result.with_friction else ""),
    )
    ax.plot(
        deg,
        result.driving_torque_virtual_work,
        color=COLORS[1],
        linewidth=1.0,
        linestyle="--",
        label="Zhukovsky lever / virtual work (no friction)",
    )
    ax.axhline(0.0, color="#808080", linewidth=0.6)
    ax.set_ylabel("Driving torque (N·m)")
    if result.efficiency is not None:
        twin = ax.twinx()
        twin.plot(deg, result.efficiency, color=COLORS[2], linewidth=1.0, label="efficiency η")
        twin.set_ylabel("Instantaneous efficiency η")
        twin.set_ylim(0.0, 1.05)
        # one legend for both scales, above the plot (the twin's curve is listed with them)
        extra, names = twin.get_legend_handles_labels()
        ax.plot([], [], color=COLORS[2], linewidth=1.0, label=names[0] + " (right scale)")
        del extra
    legend_outside(ax, ncol=2)
    ax = axes[1, 0]
    assert result.joint_forces is not None  # a kinetostatics result carries its forces
    names = list(result.joint_forces)
    magnitudes = np.array([np.hypot(f["x"], f["y"]) for f in result.joint_forces.values()])
    # joints that carry the same force all cycle long (e.g. the two ends of a two-force
    # member) are drawn once: drawn one over the other, only the last colour would show
    for k, group in enumerate(identical(magnitudes)):
        label = ", ".join(names[j] for j in group) + (" (identical)" if len(group) > 1 else "")
        ax.plot(deg, magnitudes[group[0]], color=COLORS[k % len(COLORS)], label=label)
    ax.set_ylabel("Joint force magnitude (N)")
    legend_outside(ax, title="Joint")
    angle_axis(ax, deg)
    _title(fig, result.mechanism_name, f"kinetostatics at {result.crank_speed:.4g} rad/s", 12.0)
    return fig


def animate_mechanism(
    motion: MechanismMotion,
    forces: KinetostaticsResult | None = None,
    *,
    fps: int = 20,
    dpi: int = 80,
) -> bytes:
    """A GIF of the mechanism moving through the positions of ``motion`` (one frame each), with
    the joint forces when given (frames rendered with the Agg canvas and assembled by Pillow,
    as matplotlib's PillowWriter does).

    Parameters
    ----------
    motion : crankdyn.linkage.motion.MechanismMotion
        The positions of the mechanism over the crank angles (lengths in m, angles in rad).
    forces : crankdyn.linkage.kinetostatics.KinetostaticsResult or None
        The joint forces (N) and driving torque (N·m) over the same positions, or None.
    fps : int
        Frames per second (1/s; at most 50: a frame lasts at least 20 ms).
    dpi : int
        The frames' resolution (dots per inch) on the 6.4 x 5.2 inch figure: the default 80
        gives frames of 512 x 416 pixels.

    Returns
    -------
    bytes
        The GIF file's contents.

    Raises
    ------
    ValueError
        If ``dpi`` is not positive (a programming error; the command line has no such option).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    if not dpi > 0:
        raise ValueError(f"dpi must be positive, not {dpi!r}")
    frames = []
    fig, axes = new_figure(1, 1, width=6.4, height=5.2)
    fig.set_dpi(dpi)  # the Agg canvas renders width x dpi by height x dpi pixels
    FigureCanvasAgg(fig)
    ax = axes[0, 0]
    scale = None
    if forces is not None:
        assert forces.joint_forces is not None  # a kinetostatics result carries its forces
        peak = max(
            (float(np.max(np.hypot(f["x"], f["y"]))) for f in forces.joint_forces.values()),
            default=0.0,
        )
        scale = 0.35 * motion.mechanism.length_scale / peak if peak > 0 else None
    paths = {n: p for n, p in motion.all_points().items() if np.ptp(p[:, 0]) + np.ptp(p[:, 1]) > 0}
    for p in paths.values():  # static: drawn once
        ax.plot(p[:, 0], p[:, 1], color="#c8c8c8", linewidth=0.8, zorder=0)
    static = (len(ax.lines), len(ax.patches), len(ax.texts))
    for i in range(motion.crank_angle.size):
        for group, keep in zip((ax.lines, ax.patches, ax.texts), static, strict=True):
            for artist in list(group)[keep:]:
                artist.remove()
        draw_mechanism(ax, motion, i, forces=forces, labels=True, scale=scale)
        _frame_limits(ax, motion)
        title = f"{motion.mechanism.name}\ncrank angle {math.degrees(motion.crank_angle[i]):.1f}°"
        if forces is not None:
            title += f", driving torque {forces.driving_torque[i]:.4g} N·m"
        ax.set_title(title, fontsize=9)
        fig.canvas.draw()
        if i == 0:
            fig.set_layout_engine("none")  # keep the first frame's layout: steady, and faster
        rgba = np.asarray(fig.canvas.buffer_rgba())  # type: ignore[attr-defined]  # an Agg canvas
        adaptive = Image.ADAPTIVE  # type: ignore[attr-defined]  # Image.Palette.ADAPTIVE
        frames.append(Image.fromarray(rgba[..., :3].copy()).convert("P", palette=adaptive))
    buffer = io.BytesIO()
    frames[0].save(
        buffer,
        format="GIF",
        save_all=True,
        append_images=frames[1:],
        duration=max(int(1000 / fps), 20),
        loop=0,
        disposal=2,
    )
    return buffer.getvalue()
