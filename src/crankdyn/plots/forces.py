"""Plots of cylinder pressure, crank-train forces, bearing loads (polar diagrams) and torque."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any, cast

import numpy as np
from matplotlib.ticker import FuncFormatter, NullFormatter
from numpy.typing import ArrayLike

from crankdyn.constants import RPM
from crankdyn.plots.style import (
    COLORS,
    angle_axis,
    closed,
    coinciding,
    identical,
    legend_outside,
    new_figure,
    number_ranges,
)

if TYPE_CHECKING:
    import matplotlib.figure

    from crankdyn.crank.indicated import PressureResult
    from crankdyn.engine.bearings import BearingsResult
    from crankdyn.engine.forces import ForcesResult
    from crankdyn.engine.torque import TorqueResult

__all__ = [
    "plot_bearing_polars",
    "plot_cylinder_forces",
    "plot_pin_polar",
    "plot_pressure",
    "plot_torque",
]

_KN = 1e-3


def _zero(ax):
    ax.axhline(0.0, color="#808080", linewidth=0.6)


def plot_pressure(
    result: PressureResult, fig: matplotlib.figure.Figure | None = None
) -> matplotlib.figure.Figure:
    """p-phi and p-V diagrams (linear and log-log) of a cylinder pressure; pressure drawn in
    MPa, volume in cm³, crank angle in degrees, the indicated work in J.

    Parameters
    ----------
    result : crankdyn.crank.indicated.PressureResult
        The cylinder pressure and its indicated work (SI units).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(1, 3, width=13.0, height=4.2, fig=fig)
    ax_phi, ax_pv, ax_log = axes[0]
    phi = np.degrees(result.crank_angle)
    p = result.pressure / 1e6
    v = result.volume * 1e6  # cm^3
    ax_phi.plot(phi, p, color=COLORS[0], linewidth=1.5)
    ax_phi.plot(
        np.degrees(result.peak_angle),
        result.peak_pressure / 1e6,
        "o",
        color=COLORS[1],
        label=(
            f"peak {result.peak_pressure / 1e6:.3g} MPa at "
            f"{np.degrees(result.peak_angle):.1f}° after firing TDC"
        ),
    )
    ax_phi.set_ylabel("Cylinder pressure p (MPa, absolute)")
    angle_axis(ax_phi, phi, "Crank angle from firing TDC (deg)")
    legend_outside(ax_phi)
    vlabel = (
        "Displaced volume V - V_c (cm³)" if result.volume_is_swept else "Cylinder volume V (cm³)"
    )
    ax_pv.plot(v, p, color=COLORS[0], linewidth=1.3)
    ax_pv.set_xlabel(vlabel)
    ax_pv.set_ylabel("p (MPa)")
    ax_pv.set_title(
        f"W_i = {result.indicated_work:.4g} J, IMEP = {result.imep / 1e6:.4g} MPa", fontsize=9
    )
    if result.volume_is_swept:
        ax_log.text(
            0.5,
            0.5,
            "log p - log V needs the\ncompression ratio\n([pressure] compression_ratio)",
            ha="center",
            va="center",
            transform=ax_log.transAxes,
            fontsize=9,
        )
        ax_log.set_xticks([])
        ax_log.set_yticks([])
    else:
        ax_log.loglog(v, p, color=COLORS[0], linewidth=1.3)
        for axis in (ax_log.xaxis, ax_log.yaxis):
            # the decades as plain numbers (100, 1000 cm³; 1, 10 MPa), as an engineer reads
            # them, rather than powers of ten in mathtext
            axis.set_major_formatter(FuncFormatter(_plain_decade))
            axis.set_minor_formatter(NullFormatter())
        ax_log.set_xlabel("Cylinder volume V (cm³)")
        ax_log.set_ylabel("p (MPa)")
        ax_log.set_title("log p - log V", fontsize=9)
    fig.suptitle(f"Cylinder pressure: {result.source}", fontsize=10)
    return fig


def _plain_decade(value: float, _pos: object = None) -> str:
    """A log axis's tick as a plain number (``100``, ``0.1``; ``1e+06`` beyond six digits).

    Examples
    --------
    >>> [_plain_decade(v) for v in (0.1, 1.0, 10.0, 1000.0, 1e7)]
    ['0.1', '1', '10', '1000', '1e+07']
    """
    return f"{value:g}"


def plot_cylinder_forces(
    result: ForcesResult, fig: matplotlib.figure.Figure | None = None
) -> matplotlib.figure.Figure:
    """Six panels vs crankshaft angle: gas, inertia and resultant forces; inertia orders;
    tangential and radial forces; side and rod forces; torque; crank-pin load (formulas and
    sources in :mod:`crankdyn.engine.forces`). Forces drawn in kN, torque in N·m, angle in
    degrees.

    Parameters
    ----------
    result : crankdyn.engine.forces.ForcesResult
        The crank-train forces of one cylinder (SI units).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(3, 2, width=12.0, height=9.0, fig=fig, sharex=True)
    phi = np.degrees(result.crank_angle)
    panels = [
        (
            axes[0, 0],
            "Forces along the cylinder axis (kN)",
            [
                (result.gas_force, "gas force P_g"),
                (result.inertia_force, "inertia force P_j"),
                (result.piston_force, "resultant P"),
            ],
        ),
        (
            axes[0, 1],
            "Reciprocating inertia force (kN)",
            [
                (result.inertia_force, "total P_j"),
                (result.inertia_force_1, "1st order"),
                (result.inertia_force_2, "2nd order"),
            ],
        ),
        (
            axes[1, 0],
            "Crank-pin forces (kN)",
            [
                (result.tangential_force, "tangential T"),
                (result.radial_force, "radial Z (to centre)"),
            ],
        ),
        (
            axes[1, 1],
            "Rod and side forces (kN)",
            [(result.rod_force, "rod force K"), (result.side_force, "side force N")],
        ),
    ]
    for ax, label, series in panels:
        for j, (y, name) in enumerate(series):
            ax.plot(phi, np.asarray(y) * _KN, color=COLORS[j], linewidth=1.3, label=name)
        ax.set_ylabel(label)
        _zero(ax)
        legend_outside(ax)
    ax = axes[2, 0]
    for j, (y, name) in enumerate(
        [
            (result.torque, "total M = T R"),
            (result.gas_torque, "gas"),
            (result.inertia_torque, "inertia"),
        ]
    ):
        ax.plot(phi, y, color=COLORS[j], linewidth=1.3, label=name)
    ax.set_ylabel("Cylinder torque (N·m)")
    _zero(ax)
    legend_outside(ax)
    ax = axes[2, 1]
    ax.plot(phi, result.pin_load * _KN, color=COLORS[3], linewidth=1.3, label="|R_B|")
    ax.axhline(
        result.mean_pin_load * _KN,
        color=COLORS[6],
        linestyle="--",
        linewidth=1.0,
        label=f"mean {result.mean_pin_load * _KN:.3g} kN",
    )
    ax.set_ylabel("Crank-pin load (kN)")
    legend_outside(ax)
    for ax in axes[-1]:
        angle_axis(ax, phi, "Crankshaft angle (deg)")
    fig.suptitle(
        f"Cylinder {result.cylinder} forces at {result.speed * RPM:.0f} rpm "
        f"(m_j = {result.masses.reciprocating:.4g} kg, m_r = {result.masses.rotating:.4g} kg)",
        fontsize=10,
    )
    return fig


def _full_cycle(angles_deg: ArrayLike) -> str | None:
    """How crank angles sample a periodic load: ``"inclusive"`` (the last angle is the first one
    cycle later), ``"exclusive"`` (a full cycle without its end) or None (part of a cycle)."""
    a = np.asarray(angles_deg, dtype=float)
    if a.size < 3:
        return None
    step = float(np.median(np.diff(a)))
    span = float(a[-1] - a[0])
    for cycle in (360.0, 720.0):
        if abs(span - cycle) <= 1e-6 * cycle:
            return "inclusive"
        if abs(span + step - cycle) <= 1e-6 * cycle:
            return "exclusive"
    return None


def _polar(ax, x, y, color, label, marks=None, adjustable="datalim", periodic=None):
    """A load polar: y against x (N, drawn in kN); a periodic load drawn over a full cycle is
    closed (its first point repeated at the end when the data leave it out)."""
    x, y = np.asarray(x), np.asarray(y)
    if periodic == "inclusive":  # the end repeats the start (up to round-off): close exactly
        x, y = x[:-1], y[:-1]
    if periodic is not None:
        x, y = closed(x), closed(y)
    ax.plot(x * _KN, y * _KN, color=color, linewidth=1.2, label=label)
    if marks:
        span = max(float(np.ptp(x)), float(np.ptp(y)), 1e-12)
        placed: list[tuple[float, float]] = []
        for xi, yi, text in marks:
            ax.plot(xi * _KN, yi * _KN, ".", color=color, markersize=5)
            if all(np.hypot(xi - a, yi - b) > 0.06 * span for a, b in placed):
                placed.append((xi, yi))
                ax.annotate(
                    text,
                    (xi * _KN, yi * _KN),
                    fontsize=7,
                    color=color,
                    xytext=(4, 2),
                    textcoords="offset points",
                )
    ax.plot([0], [0], "+", color="black", markersize=10)
    ax.set_aspect("equal", adjustable=adjustable)


def _marks(x, y, angles_deg, every=90.0):
    marks = []
    for target in np.arange(0.0, float(np.max(angles_deg)) - 1e-9, every):
        i = int(np.argmin(np.abs(angles_deg - target)))
        marks.append((x[i], y[i], f"{target:.0f}°"))
    return marks


def plot_pin_polar(
    result: ForcesResult, fig: matplotlib.figure.Figure | None = None
) -> matplotlib.figure.Figure:
    """Polar diagram of one cylinder's crank-pin load in the crank frame (crank pointing up),
    drawn in kN.

    Parameters
    ----------
    result : crankdyn.engine.forces.ForcesResult
        The crank-train forces of one cylinder (SI units).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(1, 1, width=6.4, height=6.4, fig=fig)
    ax = axes[0, 0]
    x = np.asarray(result.pin_tangential)
    y = -np.asarray(result.pin_radial)
    phi = np.degrees(result.crank_angle)
    _polar(ax, x, y, COLORS[0], "crank-pin load", _marks(x, y, phi), periodic=_full_cycle(phi))
    ax.set_xlabel("Tangential, in the direction of rotation (kN)")
    ax.set_ylabel("Along the crank, outward (kN)")
    ax.set_title(
        f"Crank-pin load, throw {result.throw} (crank frame; labels: crankshaft angle)",
        fontsize=9,
    )
    return fig


def plot_bearing_polars(
    result: BearingsResult, fig: matplotlib.figure.Figure | None = None
) -> matplotlib.figure.Figure:
    """Polar diagrams: crank-pin loads of every throw in the crank frame (left), and the load of
    every main bearing in the engine frame seen from the free end (right, one panel each);
    loads drawn in kN (formulas and sources in :mod:`crankdyn.engine.bearings`).

    Parameters
    ----------
    result : crankdyn.engine.bearings.BearingsResult
        The crank-pin and main-bearing loads of an engine (SI units).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    from crankdyn.plots.style import Figure

    n_bearings = result.bearing_load.shape[0]
    cols = 2 if n_bearings <= 4 else 3
    rows = -(-n_bearings // cols)
    if fig is None:
        fig = Figure(figsize=(14.0, max(6.4, 2.9 * rows + 0.8)), layout="constrained")
    # two SubFigures (new_figure draws into a subfigure as into a figure)
    left, right = cast(Any, fig.subfigures(1, 2, width_ratios=[1.0, 1.15]))
    _, axes = new_figure(1, 1, fig=left)
    ax_pin = axes[0, 0]
    phi = np.degrees(result.crank_angle)
    periodic = _full_cycle(phi)
    tangential = np.asarray(result.pin_tangential)
    outward = -np.asarray(result.pin_radial)
    # throws whose polars coincide (every throw of an evenly firing in-line engine) are drawn
    # once and labelled as a group: drawn one over the other, only the last colour would show
    points = tangential + 1j * outward
    groups = coinciding(points[:, :-1] if periodic == "inclusive" else points)
    if periodic is None:  # part of a cycle: the curves are compared point by point only
        groups = identical(points)
    for k, group in enumerate(groups):
        j = group[0]
        x, y = tangential[j], outward[j]
        if len(group) == 1:
            label = f"throw {j + 1}"
        else:
            label = f"throws {number_ranges(np.asarray(group) + 1)} (identical)"
        _polar(
            ax_pin,
            x,
            y,
            COLORS[k % len(COLORS)],
            label,
            _marks(x, y, phi) if k == 0 else None,
            periodic=periodic,
        )
    ax_pin.set_xlabel("Tangential, in the direction of rotation (kN)")
    ax_pin.set_ylabel("Along the crank, outward (kN)")
    ax_pin.set_title("Crank-pin loads (crank frame; labels: crankshaft angle, throw 1)", fontsize=9)
    legend_outside(ax_pin)
    _, grid = new_figure(rows, cols, fig=right, sharex=True, sharey=True)
    for b, ax in enumerate(grid.flat):
        if b >= n_bearings:
            ax.set_visible(False)
            continue
        _polar(
            ax,
            result.bearing_horizontal[b],
            result.bearing_vertical[b],
            COLORS[b % len(COLORS)],
            f"bearing {b + 1}",
            adjustable="box",
            periodic=periodic,
        )
        ax.set_title(
            f"Main bearing {b + 1} (max {result.max_bearing_load[b] * _KN:.3g} kN)", fontsize=8
        )
    for b, ax in enumerate(grid.flat):
        if b < n_bearings and b + cols >= n_bearings:  # lowest panel of its column
            ax.xaxis.set_tick_params(labelbottom=True)
            ax.set_xlabel("Horizontal (kN)")
    for ax in grid[:, 0]:
        ax.set_ylabel("Vertical, up (kN)")
    right.suptitle(
        "Main-bearing loads (engine frame seen from the free end; bearing 1 at the free end)",
        fontsize=9,
    )
    fig.suptitle(f"Bearing loads at {result.speed * RPM:.0f} rpm", fontsize=10)
    return fig


def plot_torque(
    result: TorqueResult, fig: matplotlib.figure.Figure | None = None
) -> matplotlib.figure.Figure:
    """Three panels: the cylinders' torques, the total torque with its gas and inertia parts
    and the mean, and the main-journal torques (formulas and sources in
    :mod:`crankdyn.engine.torque`); torque drawn in N·m, angle in degrees.

    Parameters
    ----------
    result : crankdyn.engine.torque.TorqueResult
        The engine torque (SI units).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(3, 1, width=10.0, height=9.6, fig=fig, sharex=True)
    phi = np.degrees(result.crank_angle)
    ax = axes[0, 0]
    n = result.cylinder_torque.shape[0]
    for i in range(n):
        ax.plot(
            phi,
            result.cylinder_torque[i],
            color=COLORS[i % len(COLORS)],
            linewidth=1.6 if i == 0 else 0.8,
            alpha=1.0 if i == 0 else 0.7,
            label=f"cyl {i + 1}",
        )
    ax.set_ylabel("Cylinder torque (N·m)")
    _zero(ax)
    legend_outside(ax)
    ax = axes[1, 0]
    ax.plot(phi, result.total_torque, color=COLORS[0], linewidth=1.5, label="total")
    ax.plot(phi, result.gas_torque, color=COLORS[2], linewidth=0.9, label="gas")
    ax.plot(phi, result.inertia_torque, color=COLORS[1], linewidth=0.9, label="inertia")
    ax.axhline(
        result.mean_torque,
        color=COLORS[6],
        linestyle="--",
        linewidth=1.0,
        label=f"mean {result.mean_torque:.4g} N·m",
    )
    ax.set_ylabel("Engine torque (N·m)")
    _zero(ax)
    legend_outside(ax)
    ax = axes[2, 0]
    for j in range(result.journal_torque.shape[0]):
        ax.plot(
            phi,
            result.journal_torque[j],
            color=COLORS[j % len(COLORS)],
            linewidth=1.0,
            label=f"behind throw {j + 1}",
        )
    ax.set_ylabel("Main-journal torque (N·m)")
    _zero(ax)
    legend_outside(ax)
    angle_axis(ax, phi, "Crankshaft angle (deg, 0 at cylinder 1 firing TDC)")
    fig.suptitle(
        f"Torque at {result.speed * RPM:.0f} rpm: indicated power "
        f"{result.indicated_power / 1e3:.4g} kW, IMEP {result.imep / 1e6:.3g} MPa",
        fontsize=10,
    )
    return fig
