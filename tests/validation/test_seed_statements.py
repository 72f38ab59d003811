"""Statements of the seeds that no other test checks word for word (docs/seeds.md)."""

import numpy as np
import pytest

from crankdyn.crank.kinematics import half_binomial, slider_crank_exact
from crankdyn.engine.forces import rod_forces


def test_seed000_positive_offset_lowers_rod_angle_and_side_thrust_in_expansion():
    """Seed 000 sec. 1.2: a positive offset gives a smaller rod angle while the piston moves down
    (the expansion stroke), so the side thrust there is smaller; docs/conventions.md's sign."""
    r, length, e = 0.05, 0.18, 0.004
    phi = np.radians(np.arange(5.0, 176.0, 5.0))  # piston moving away from the head
    central = slider_crank_exact(phi, r, length).rod_angle
    offset = slider_crank_exact(phi, r, length, e).rod_angle
    assert np.all(np.abs(offset) < np.abs(central))
    p = 30_000.0  # N, pushing the piston toward the crank
    side_central = rod_forces(p, phi, r / length, 0.0)[0]
    side_offset = rod_forces(p, phi, r / length, e / r)[0]
    assert np.all(np.abs(side_offset) < np.abs(side_central))


def test_seed002_binomial_terms_three_and_five_hundredths_percent():
    """Seed 002 sec. 4: cos(beta) = (1 - lambda^2 sin^2 phi)^(1/2) = 1 - (1/2) lambda^2 sin^2 phi
    - (1/8) lambda^4 sin^4 phi ...; at lambda = 1/4 and phi = 90 deg the second term is about 3 %
    and the third about 0.05 % of the first (printed to one figure: 3.1 % and 0.049 %)."""
    lam = 0.25
    second = abs(half_binomial(1)) * lam**2
    third = abs(half_binomial(2)) * lam**4
    assert second == pytest.approx(0.03, abs=0.005)
    assert third == pytest.approx(0.0005, abs=0.00005)
