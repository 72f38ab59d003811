"""Seed 004 (four-bar force analysis course notes, 004_8e6d1ebdb91d8ca3.txt): link sets and
their Grashof check, the matrix method, the friction-circle slider-crank, the conveyor's link
groups. The seed's figures and most of its numbers are not in the extracted text; where it gives
no numbers the cases are solved here by its own construction (by hand, in closed form) and
compared with crankdyn's independent matrix solution."""

import itertools
import math

import numpy as np
import pytest

from crankdyn.linkage.elements import Force
from crankdyn.linkage.fourbar import FourBar, grashof_type
from crankdyn.linkage.kinetostatics import kinetostatics
from crankdyn.linkage.planar import Mechanism, slider_crank_mechanism

# The three measured four-bars, L1..L4 in mm as printed (seed 004, sec. 1.2 "第一组/第二组/第三组")
SEED004_LINK_SETS = (
    (125.36, 73.4, 103.4, 103.52),
    (125.36, 50.1, 109.8, 72.85),
    (163.2, 61.6, 150.0, 90.0),
)
# the seed's check "s + l <= p + q" with its own sums (mm): (s + l, p + q)
SEED004_SUMS = ((198.76, 206.92), (175.46, 182.65), (224.8, 240.0))


@pytest.mark.parametrize(("links", "sums"), list(zip(SEED004_LINK_SETS, SEED004_SUMS, strict=True)))
def test_seed004_link_sets_are_crank_rockers_with_the_shortest_link_as_crank(links, sums):
    lengths = [x / 1e3 for x in links]
    s, *_pq, l = sorted(lengths)
    # the seed's sums, to its printed 0.01 mm
    assert (s + l) * 1e3 == pytest.approx(sums[0], abs=5e-3)
    assert (sum(lengths) - s - l) * 1e3 == pytest.approx(sums[1], abs=5e-3)
    others = [x for x in lengths if x != s]
    # the text does not say which link is the frame; with the shortest link as the crank (a side
    # link, "最短杆为连架杆") every choice of frame among the others gives a crank-rocker
    for coupler, rocker, ground in itertools.permutations(others):
        fb = FourBar(s, coupler, rocker, ground)
        assert fb.grashof_type == "crank-rocker"
        assert fb.crank_rotates
        assert fb.limits.grashof_sum == pytest.approx((sums[0] - sums[1]) / 1e3, abs=5e-6)
    # the other Grashof inversions of the same links (Norton Fig. 2-16)
    a, b, c = others
    assert grashof_type(a, b, c, s) == "double-crank"  # shortest link as the frame
    assert grashof_type(a, s, b, c) == "double-rocker"  # shortest link as the coupler


def test_seed004_issue_four_bar_figures():
    # the quick command's example linkage: set 1 with AB = 73.4, BC = 125.36, DC = 103.4,
    # AD = 103.52 mm. Transmission-angle extremes by the cosine rule at theta2 = 0 and 180 deg:
    # cos mu = (b^2 + c^2 - (d -+ a)^2) / (2 b c), computed here by hand.
    a, b, c, d = 73.4, 125.36, 103.4, 103.52
    fb = FourBar(a / 1e3, b / 1e3, c / 1e3, d / 1e3)
    mu_min = math.degrees(math.acos((b * b + c * c - (d - a) ** 2) / (2 * b * c)))
    mu_max = math.degrees(math.acos((b * b + c * c - (d + a) ** 2) / (2 * b * c)))
    assert math.degrees(fb.limits.transmission_angle_min) == pytest.approx(mu_min, abs=1e-9)
    assert math.degrees(fb.limits.transmission_angle_max) == pytest.approx(mu_max, abs=1e-9)
    # rocker extremes where crank and coupler are in line: AC = b + a and b - a (triangle ACD)
    ext = math.degrees(math.acos((d * d + c * c - (a + b) ** 2) / (2 * d * c)))
    fold = math.degrees(math.acos((d * d + c * c - (b - a) ** 2) / (2 * d * c)))
    # the rocker angle from A->D at D is 180 deg minus the triangle's angle at D
    assert math.degrees(fb.limits.rocker_angle_min) == pytest.approx(180.0 - ext, abs=1e-9)
    assert math.degrees(fb.limits.rocker_angle_max) == pytest.approx(180.0 - fold, abs=1e-9)


def test_seed004_conveyor_link_groups_4_5_then_2_3():
    # seed 004 sec. 2 example: "分解杆组: 4-5, 2-3", each with 3n = 2 p_l, solved from 4-5
    groups = Mechanism.example("conveyor-seed004").link_groups()
    assert [g.links for g in groups[:2]] == [("link", "slider"), ("coupler", "rocker")]
    for g in groups[:2]:
        assert 3 * len(g.links) == 2 * len(g.joints)


def _friction_circle_solution(R, L, Q, f, rho_a, rho_b, rho_c, theta):
    """Seed 004 sec. 3.5 by its own construction, for a massless central slider-crank with the
    resistance Q on the slider, crank turning counter-clockwise: the rod is a two-force member
    whose line of action is offset by the friction circles at B and C; the slider is held by Q,
    the rod force and the guide reaction inclined by the friction angle; the crank by the rod
    force, the pivot reaction (tangent to its friction circle) and the driving torque."""
    out = []
    for t in theta:
        B = R * np.array([math.cos(t), math.sin(t)])
        root = math.sqrt(L * L - (R * math.sin(t)) ** 2)
        C = np.array([R * math.cos(t) + root, 0.0])
        e = (C - B) / L
        e_perp = np.array([-e[1], e[0]])
        w_rod = -R * math.cos(t) / root  # d(rod angle)/d(theta), rod angle = -asin(R sin t / L)
        v_c = -R * math.sin(t) - R * R * math.sin(t) * math.cos(t) / root
        s_v = math.copysign(1.0, v_c)
        s_b = math.copysign(1.0, w_rod - 1.0)  # rod relative to crank at B
        s_c = math.copysign(1.0, w_rod)  # rod relative to slider at C
        k = rho_b * s_b + rho_c * s_c
        solutions = []
        for s_p in (1.0, -1.0):
            sin_d = -k * s_p / L
            d = math.sqrt(1 - sin_d**2) * e + sin_d * e_perp
            p = Q * s_v / (d[0] - f * s_v * s_p * abs(d[1]))
            if math.copysign(1.0, p) == s_p:
                solutions.append(p * d)
        assert len(solutions) == 1
        F = solutions[0]  # force of the crank on the rod at B
        mag = float(np.hypot(*F))
        torque = (B[0] * F[1] - B[1] * F[0]) - rho_b * mag * s_b + rho_a * mag
        out.append((torque, F))
    return out


def test_seed004_slider_crank_with_friction_circles():
    R, L, Q, f = 0.1, 0.3, 1000.0, 0.1
    radii = (0.015, 0.010, 0.008)  # journals A, B, C
    mech = slider_crank_mechanism(
        R,
        L,
        0.0,
        math.radians(30.0),
        speed=10.0,
        forces=(Force("slider", "C", resistance=Q),),
        friction={"A": (radii[0], f), "B": (radii[1], f), "C": (radii[2], f), "S": (0.0, f)},
    )
    theta = np.radians([15.0, 40.0, 75.0, 100.0, 140.0, 200.0, 250.0, 290.0, 330.0])
    res = kinetostatics(mech.motion(theta))
    hand = _friction_circle_solution(R, L, Q, f, *(r * f for r in radii), theta)
    torque = np.array([h[0] for h in hand])
    force_b = np.array([h[1] for h in hand])
    # both are exact solutions of the same equations: agreement to round-off
    np.testing.assert_allclose(res.driving_torque, torque, rtol=1e-10)
    np.testing.assert_allclose(res.joint_force("B"), force_b, rtol=1e-10, atol=1e-9)
    np.testing.assert_allclose(res.joint_force("A"), force_b, rtol=1e-10, atol=1e-9)
    # the guide's total reaction leans from its normal by the friction angle arctan f
    guide = res.joint_force("S")
    np.testing.assert_allclose(np.abs(guide[:, 0]), f * np.abs(guide[:, 1]), rtol=1e-10)
    # without friction the torque is Q times the slider's velocity coefficient
    ideal = res.driving_torque_frictionless
    v = -R * np.sin(theta) - R * R * np.sin(theta) * np.cos(theta) / np.sqrt(
        L * L - (R * np.sin(theta)) ** 2
    )
    np.testing.assert_allclose(ideal, Q * np.abs(v), rtol=1e-10)
    assert np.all(res.efficiency < 1.0)
