"""Plots of slider-crank kinematics."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from crankdyn.constants import RPM
from crankdyn.plots.style import COLORS, angle_axis, legend_outside, new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.crank.kinematics import KinematicsResult

__all__ = ["plot_kinematics"]


def plot_kinematics(result: KinematicsResult, fig: Figure | None = None) -> Figure:
    """Six panels against crank angle: piston displacement, velocity, acceleration; rod angle,
    angular velocity and angular acceleration. Extrema of the piston velocity and acceleration
    are marked.

    Displacement is drawn in mm, velocity in m/s, acceleration in m/s², the rod's angle in
    degrees, its angular velocity in rad/s and angular acceleration in rad/s², crank angle in
    degrees.

    Parameters
    ----------
    result : crankdyn.crank.kinematics.KinematicsResult
        The slider-crank kinematics (SI units).
    fig : matplotlib.figure.Figure or None
        A figure to draw into; None makes a new one.

    Returns
    -------
    matplotlib.figure.Figure
        The figure.
    """
    fig, axes = new_figure(3, 2, width=10.0, height=8.4, fig=fig, sharex=True)
    phi = np.degrees(result.crank_angle)
    s = result.extrema
    panels = [
        (axes[0, 0], result.displacement * 1e3, "Piston displacement x (mm)"),
        (axes[1, 0], result.velocity, "Piston velocity v (m/s)"),
        (axes[2, 0], result.acceleration, "Piston acceleration a (m/s²)"),
        (axes[0, 1], np.degrees(result.rod_angle), "Rod angle β (deg)"),
        (axes[1, 1], result.rod_angular_velocity, "Rod angular velocity (rad/s)"),
        (axes[2, 1], result.rod_angular_acceleration, "Rod angular acceleration (rad/s²)"),
    ]
    for i, (ax, y, label) in enumerate(panels):
        ax.plot(phi, y, color=COLORS[0 if i < 3 else 3], linewidth=1.6)
        ax.set_ylabel(label)
        ax.axhline(0.0, color="#808080", linewidth=0.6)
    for ax in axes[-1]:
        angle_axis(ax, phi)
    ax_v, ax_a = axes[1, 0], axes[2, 0]
    ax_v.plot(
        np.degrees(s.crank_angle_at_max_velocity),
        s.max_velocity,
        "o",
        color=COLORS[1],
        label=(
            f"v_max = {s.max_velocity:.2f} m/s at {np.degrees(s.crank_angle_at_max_velocity):.1f}°"
        ),
    )
    legend_outside(ax_v)
    for x in s.acceleration_extrema:
        ax_a.plot(np.degrees(x.crank_angle), x.acceleration, "o", color=COLORS[1], markersize=4)
    ax_a.plot(
        [],
        [],
        "o",
        color=COLORS[1],
        markersize=4,
        label=f"extrema: max {s.max_acceleration:.0f}, min {s.min_acceleration:.0f} m/s²",
    )
    legend_outside(ax_a)
    speed = s.speed * RPM
    fig.suptitle(
        f"Slider-crank kinematics ({s.method}), {speed:.0f} rpm, λ = {s.lam:.4g}, "
        f"k = {s.k:.3g}, stroke {s.stroke * 1e3:.4g} mm"
    )
    return fig
