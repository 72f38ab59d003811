"""Seed 000 section 1 accuracy statements (reference README), each to the digits printed."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.kinematics import piston_kinematics, slider_crank_approx, slider_crank_exact

PHI = np.linspace(0.0, 2 * math.pi, 72001)


def _both(lam):
    return slider_crank_exact(PHI, 1.0, 1.0 / lam), slider_crank_approx(PHI, 1.0, 1.0 / lam)


def test_seed000_approx_displacement_error_0p003R_near_90deg():
    """lambda = 1/3.5: largest error of the approximate displacement 'about 0.003 R' at 90 deg."""
    exact, approx = _both(1 / 3.5)
    err = np.abs(exact.displacement - approx.displacement)
    assert err.max() == pytest.approx(0.003, abs=0.0005)
    assert math.degrees(PHI[err.argmax()]) % 180 == pytest.approx(90.0, abs=1.0)


def test_seed000_approx_velocity_error_below_0p0057Rw_and_0p83_percent():
    """lambda = 0.32: the approximate velocity is off by at most 0.0057 R w, relative < 0.83 %."""
    exact, approx = _both(0.32)
    err = np.abs(exact.velocity - approx.velocity)
    assert err.max() <= 0.0057 + 0.00005
    moving = np.abs(exact.velocity) > 1e-6
    assert (err[moving] / np.abs(exact.velocity[moving])).max() < 0.0083 + 0.00005


def test_seed000_approx_acceleration_exact_at_dead_centres_5p3_percent_at_90():
    """lambda = 0.32: no error at 0 and 180 deg, the largest at 90/270 deg, about 5.3 %."""
    lam = 0.32
    at = np.radians([0.0, 180.0, 90.0, 270.0])
    exact = slider_crank_exact(at, 1.0, 1 / lam).acceleration
    approx = slider_crank_approx(at, 1.0, 1 / lam).acceleration
    np.testing.assert_allclose(approx[:2], exact[:2], rtol=1e-14)
    rel = np.abs(approx[2:] - exact[2:]) / np.abs(exact[2:])
    np.testing.assert_allclose(rel, 0.053, atol=0.0005)
    e_all, a_all = _both(lam)
    worst = math.degrees(PHI[np.argmax(np.abs(e_all.acceleration - a_all.acceleration))])
    assert min(abs(worst - 90), abs(worst - 270)) < 0.01


@pytest.mark.parametrize("lam", [0.2, 0.25, 0.28, 1 / 3.5, 0.32])
def test_seed000_vmax_over_cm_about_1p6_near_phi_plus_beta_90(lam):
    """v_max / c_m is about 1.6 and v_max occurs near phi + beta = 90 deg."""
    s = piston_kinematics(CrankGeometry(0.1, 1.0, 1.0 / lam), 1.0).extrema
    assert s.velocity_ratio == pytest.approx(1.6, abs=0.05)
    beta = math.asin(lam * math.sin(s.crank_angle_at_max_velocity))
    assert math.degrees(s.crank_angle_at_max_velocity + beta) == pytest.approx(90.0, abs=2.0)


@pytest.mark.parametrize("lam, count", [(0.2, 2), (0.24, 2), (0.26, 4), (0.3, 4), (1 / 3.2, 4)])
def test_seed000_acceleration_extrema_count_and_minimum(lam, count):
    """Approximate formula: two extrema for lambda < 1/4, four for lambda > 1/4, the minimum
    -R w^2 (lambda + 1/(8 lambda)) at cos(phi) = -1/(4 lambda)."""
    s = piston_kinematics(CrankGeometry(0.1, 1.0, 1.0 / lam), 1.0, method="approx").extrema
    assert len(s.acceleration_extrema) == count
    if lam > 0.25:
        assert s.min_acceleration == pytest.approx(-(lam + 1 / (8 * lam)), rel=1e-12)
        assert math.cos(s.crank_angle_at_min_acceleration) == pytest.approx(
            -1 / (4 * lam), rel=1e-9
        )
    else:
        assert s.min_acceleration == pytest.approx(-(1 - lam), rel=1e-12)
    assert s.max_acceleration == pytest.approx(1 + lam, rel=1e-12)


def test_exact_formula_four_extrema_threshold():
    """For the exact acceleration the second pair of extrema appears at
    lambda* = (sqrt(21) - 3)/6 = 0.2638 (a(pi + psi) = lambda - 1 + psi^2 (1/2 - 2 lambda
    + 3 lambda^3/2) + O(psi^4)), not at the approximate formula's 1/4."""
    threshold = (math.sqrt(21) - 3) / 6
    below = piston_kinematics(CrankGeometry(0.1, 1.0, 1.0 / (threshold - 0.002)), 1.0).extrema
    above = piston_kinematics(CrankGeometry(0.1, 1.0, 1.0 / (threshold + 0.002)), 1.0).extrema
    assert len(below.acceleration_extrema) == 2
    assert len(above.acceleration_extrema) == 4
