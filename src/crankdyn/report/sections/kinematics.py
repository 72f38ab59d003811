"""Report section: slider-crank kinematics."""

from __future__ import annotations

import math

from crankdyn.constants import RPM
from crankdyn.report.model import KeyFigure, Plot, Section, Table

G = 9.80665
# seed 000 section 1.1: typical maximum piston accelerations
TYPICAL_ACCELERATION_G = {"petrol": (500.0, 1500.0), "diesel": (200.0, 800.0)}


def build(ctx) -> Section:
    kin = ctx.analysis.kinematics()
    s = kin.summary
    g = ctx.engine.geometry
    amax_g = s.max_acceleration / G
    limit = TYPICAL_ACCELERATION_G["petrol"][1]
    figures = [
        KeyFigure("stroke_m", "Stroke", s.stroke, f"{s.stroke * 1e3:.4g} mm"),
        KeyFigure("rod_ratio", "Crank-rod ratio λ = R/L", g.lam, f"{g.lam:.4f}"),
        KeyFigure(
            "mean_piston_speed_m_s",
            "Mean piston speed",
            s.mean_piston_speed,
            f"{s.mean_piston_speed:.2f} m/s ({s.speed_class})",
        ),
        KeyFigure(
            "max_piston_speed_m_s",
            "Max piston speed",
            s.max_velocity,
            f"{s.max_velocity:.2f} m/s at {math.degrees(s.crank_angle_at_max_velocity):.1f}°",
        ),
        KeyFigure(
            "max_piston_acceleration_m_s2",
            "Max piston acceleration",
            s.max_acceleration,
            f"{s.max_acceleration:.0f} m/s² ({amax_g:.0f} g)",
            status="pass" if amax_g <= limit else "warn",
            note=f"typical: petrol 500-1500 g, diesel 200-800 g (seed 000); warn above {limit:g} g",
        ),
        KeyFigure(
            "min_piston_acceleration_m_s2",
            "Min piston acceleration",
            s.min_acceleration,
            f"{s.min_acceleration:.0f} m/s² at "
            f"{math.degrees(s.crank_angle_at_min_acceleration):.1f}°",
        ),
        KeyFigure(
            "max_rod_angle_deg",
            "Max rod angle",
            math.degrees(s.max_rod_angle),
            f"{math.degrees(s.max_rod_angle):.2f}°",
        ),
    ]
    return Section(
        key="kinematics",
        title="Slider-crank kinematics",
        intro=(
            f"Exact piston and rod motion at {ctx.speed * RPM:.0f} rpm "
            f"(seed 000 §1, seed 002). v_max/c_m = {s.velocity_ratio:.3f}; "
            f"{len(s.acceleration_extrema)} acceleration extrema per revolution."
        ),
        figures=figures,
        plots=[
            Plot(
                "kinematics",
                "Piston and rod motion",
                kin.plot(),
                "Displacement, velocity and acceleration of the piston; angle, angular "
                "velocity and angular acceleration of the rod; extrema marked.",
            )
        ],
        tables=[
            Table("kinematics", "Kinematics over one revolution (1° steps)", result=kin, show=False)
        ],
        json={"kinematics_summary": s.to_dict()},
    )
