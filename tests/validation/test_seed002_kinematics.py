"""Seed 002 (Makushev, Polyakova, Batrakov 2010): the VAZ-2108 table and the coefficient table."""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np
import pytest

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.kinematics import coefficient_table, piston_kinematics, slider_crank_approx

DATA = Path(__file__).parent / "data"


def _table3():
    with open(DATA / "seed002_vaz2108_kinematics.csv", encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def test_seed002_vaz2108_table3_with_source_pi():
    """Table 3: second-order formulas, R = 35.5 mm, lambda = 0.26, w = 3.14 x 4900 / 30.

    S and V are printed to 3 decimals and agree to half a unit of the last digit. J is printed to
    7 significant figures, but every printed J is larger than R w^2 (cos phi + lambda cos 2phi)
    by the same factor 1.0000015 +- 0.0000006 (the source's arithmetic carried w to about 6
    digits), so J is checked to 5e-6 relative: 6 significant figures.
    """
    t = _table3()
    w = 3.14 * 4900 / 30
    r = 0.071 / 2
    m = slider_crank_approx(np.radians(t["crank_angle_deg"]), r, r / 0.26, 0.0, w)
    np.testing.assert_allclose(m.displacement, t["displacement_m"], rtol=0, atol=0.0005)
    np.testing.assert_allclose(m.velocity, t["velocity_m_s"], rtol=0, atol=0.0005)
    np.testing.assert_allclose(m.acceleration, t["acceleration_m_s2"], rtol=5e-6)


def test_seed002_vaz2108_table3_exact_pi_about_0p1_percent():
    """With the exact pi the table's velocities and accelerations scale by pi/3.14 and
    (pi/3.14)^2: about 0.05 % and 0.1 % (reference README)."""
    t = _table3()
    r = 0.071 / 2
    w = math.pi * 4900 / 30
    m = slider_crank_approx(np.radians(t["crank_angle_deg"]), r, r / 0.26, 0.0, w)
    ratio = m.acceleration / t["acceleration_m_s2"]
    np.testing.assert_allclose(ratio, (math.pi / 3.14) ** 2, rtol=5e-6)
    assert 0.0009 < ratio.max() - 1 < 0.0011


def test_seed002_table2_coefficients():
    """Table 2 (lambda = 1/3.8): exact coefficients A, B, C printed to 2 decimals at 0..90 deg.

    The source's sign column shows "+" for C at 90 deg, but the printed magnitude 0.27 is
    tan(beta) = lambda / sqrt(1 - lambda^2) = 0.272 and C(90) = -tan(beta) < 0 by eq. 13 (the
    extraction lost the sign), so |C| is compared there.
    """
    table = coefficient_table([1 / 3.8], np.radians([0.0, 30.0, 60.0, 90.0]))
    a, b, c = table.displacement[0], table.velocity[0], table.acceleration[0]
    np.testing.assert_allclose(a, [0.0, 0.17, 0.60, 1.13], atol=0.005)
    np.testing.assert_allclose(b, [0.0, 0.61, 0.98, 1.0], atol=0.005)
    np.testing.assert_allclose(c[:3], [1.26, 1.0, 0.37], atol=0.005)
    assert c[3] < 0
    assert abs(c[3]) == pytest.approx(0.27, abs=0.005)


def test_seed002_table2_accelerations_from_rounded_coefficients():
    """Table 2's accelerations are R w^2 times the rounded C (R = 0.05 m, w = 628 1/s):
    24850 at 0 deg (C = 1.26), 19720 at 30 deg (C = 1.00), printed to 4 significant figures."""
    rw2 = 0.05 * 628.0**2
    assert rw2 * 1.26 == pytest.approx(24850, abs=5)
    assert rw2 * 1.00 == pytest.approx(19720, abs=5)
    exact = piston_kinematics(CrankGeometry(0.1, 0.05, 0.05 * 3.8), 628.0, np.radians([0.0]))
    assert exact.acceleration[0] / rw2 == pytest.approx(1.26, abs=0.005)


def test_seed002_speed_classes():
    """Table 1: low-speed up to 6 m/s, medium 6-9, high 9-12, very high above 12."""
    from crankdyn.crank.kinematics import speed_class

    assert speed_class(5.5) == "low-speed"
    assert speed_class(7.0) == "medium-speed"
    assert speed_class(10.0) == "high-speed"
    assert speed_class(13.0) == "very high-speed"
    # the VAZ engine: 0.071 m x 4900 / 30 = 11.6 m/s, high-speed
    s = piston_kinematics(
        CrankGeometry.from_stroke(0.076, 0.071, rod_ratio=0.26), 4900 * math.pi / 30
    ).extrema
    assert s.mean_piston_speed == pytest.approx(0.071 * 4900 / 30, rel=1e-12)
    assert s.speed_class == "high-speed"
