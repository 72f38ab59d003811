"""Seed 002 sec. 1 (Makushev, Polyakova, Batrakov 2010): the path of the piston against the crank
angle, "needed to find the cylinder pressure from the indicator diagram drawn in p-V coordinates
and to re-draw it in p-phi coordinates". The seed's Table 3 (VAZ-2108 based engine, lambda = 0.26,
stroke 71 mm) gives the path S at every 30 deg; converting each S back to a crank
angle (crankdyn.crank.pressure_volume, the exact displacement solved for phi, the stroke told by
the direction of motion) must give the table's angles. S is printed to 1 mm, so the tolerance of
each angle is 0.5 mm / |dS/dphi| at that angle (the slope of the exact path); the dead centres,
where S is flat in phi, are left out."""

import math
from pathlib import Path

import numpy as np

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.kinematics import slider_crank_exact
from crankdyn.crank.pressure_volume import crank_angle_of_displacement

TABLE3 = Path(__file__).parent / "data" / "seed002_vaz2108_kinematics.csv"


def test_seed002_table3_paths_give_back_their_crank_angles():
    rows = np.loadtxt(TABLE3, delimiter=",", comments="#", skiprows=1)
    phi_deg, path = rows[:, 0], rows[:, 1]
    g = CrankGeometry.from_stroke(0.076, 0.071, rod_ratio=0.26)
    inside = (phi_deg % 180.0) != 0.0
    phi = np.radians(phi_deg[inside])
    away = phi < math.pi  # 0-180 deg: the piston moves away from the head
    got = crank_angle_of_displacement(path[inside], g, away) % (2 * math.pi)
    slope = np.abs(slider_crank_exact(phi, g.crank_radius, g.rod_length).velocity)  # dS/dphi
    tolerance = 0.0005 / slope
    assert np.all(np.abs(got - phi) <= tolerance), np.degrees(got - phi)
    assert got.size == 10
