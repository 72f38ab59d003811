"""Unit factors used at the boundary of the SI core (one place, so every module agrees)."""

from __future__ import annotations

import math

__all__ = ["CYCLE_ANGLE", "DEG", "RPM"]

DEG = 180.0 / math.pi
"""Radians to degrees: ``angle_deg = angle_rad * DEG``."""

RPM = 30.0 / math.pi
"""rad/s to rpm: ``speed_rpm = speed_rad_s * RPM``."""

CYCLE_ANGLE = {"four-stroke": 4.0 * math.pi, "two-stroke": 2.0 * math.pi}
"""Crank angle of one working cycle (rad) by cycle."""
