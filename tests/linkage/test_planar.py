"""General planar mechanisms: Newton-Raphson positions with branch control, Jacobian rates."""

import math
import re

import numpy as np
import pytest

from crankdyn.crank.kinematics import slider_crank_exact
from crankdyn.errors import InputError
from crankdyn.linkage.elements import (
    GROUND,
    Driver,
    Joint,
    Link,
    degrees_of_freedom,
    is_statically_determinate,
)
from crankdyn.linkage.fourbar import FourBar, fourbar_mechanism
from crankdyn.linkage.motion import linkage_kinematics
from crankdyn.linkage.planar import Mechanism, slider_crank_mechanism

SEED = (0.0734, 0.12536, 0.1034, 0.10352)
THETA = np.radians(np.arange(0.0, 361.0, 5.0))


def wrap(x):
    return np.remainder(np.asarray(x) + math.pi, 2 * math.pi) - math.pi


def inverted_slider_crank(a=0.05, d=0.12, theta=0.7, speed=3.0, **kw):
    """Crank AB turns about A; the block at B slides on the bar pivoted at D (a Whitworth-type
    inverted slider-crank)."""
    b = np.array([a * math.cos(theta), a * math.sin(theta)])
    u = (b - np.array([d, 0.0])) / np.linalg.norm(b - np.array([d, 0.0]))
    e = np.array([d, 0.0]) + 0.25 * u
    return Mechanism(
        name="inverted slider-crank",
        points={"A": (0, 0), "B": tuple(b), "D": (d, 0), "E": tuple(e)},
        links=(
            Link("crank", ("A", "B"), kw.get("m1", 0.0), kw.get("i1", 0.0)),
            Link("block", ("B",), kw.get("m2", 0.0), kw.get("i2", 0.0), tuple(b)),
            Link("bar", ("D", "E"), kw.get("m3", 0.0), kw.get("i3", 0.0)),
        ),
        joints=(
            Joint("A", "revolute", (GROUND, "crank"), "A"),
            Joint("B", "revolute", ("crank", "block"), "B"),
            Joint("P", "prismatic", ("bar", "block"), "B", axis=math.atan2(u[1], u[0])),
            Joint("D", "revolute", (GROUND, "bar"), "D"),
        ),
        driver=Driver("A", "B", 0.0, speed, kw.get("alpha", 0.0)),
        gravity=kw.get("gravity", (0.0, 0.0)),
        forces=kw.get("forces", ()),
        torques=kw.get("torques", ()),
    )


def test_mobility_and_static_determinacy_formulas():
    # seed 004: 3n = 2 p_l + p_h for a statically determinate group
    assert degrees_of_freedom(3, 4) == 1
    assert is_statically_determinate(2, 3)  # a dyad
    assert is_statically_determinate(4, 6)  # a triad group
    assert not is_statically_determinate(2, 2)
    assert is_statically_determinate(1, 1, 1)  # one link, a lower and a higher pair


@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_newton_solver_reproduces_the_closed_form_four_bar(branch):
    fb = FourBar(*SEED, coupler_point=(0.06, 0.04), branch=branch)
    mech = fourbar_mechanism(fb, math.radians(200.0), speed=10.0, acceleration=2.0)
    mm = mech.motion(THETA)
    m = fb.motion(THETA, 10.0, 2.0)
    assert np.max(np.abs(wrap(mm.link_angle("rocker") - m.theta4))) < 1e-10
    assert np.max(np.abs(wrap(mm.link_angle("coupler") - m.theta3))) < 1e-10
    np.testing.assert_allclose(mm.angular_velocity("rocker"), m.omega4, atol=1e-9)
    np.testing.assert_allclose(mm.angular_velocity("coupler"), m.omega3, atol=1e-9)
    np.testing.assert_allclose(mm.angular_acceleration("rocker"), m.alpha4, atol=1e-7)
    np.testing.assert_allclose(mm.angular_acceleration("coupler"), m.alpha3, atol=1e-7)
    _pos, _vel, acc = fb.coupler_point_motion(m)
    p = mm.point("P", which="qdd")
    np.testing.assert_allclose(p[:, 0] + 1j * p[:, 1], acc, atol=1e-8)


def test_slider_crank_matches_the_engine_kinematics_module():
    # Engine convention (kinematics.py): crank angle phi from the cylinder axis toward the head,
    # positive in the direction of rotation; piston displacement x from TDC toward the crank;
    # offset e toward the side the pin moves to after TDC. Planar model: the cylinder axis
    # along +x (head at +x), the crank turning counter-clockwise, so theta = phi, the guide at
    # y = e, x = x_TDC - x_C, and the rod angle beta = -(angle of B->C).
    r, l, e, w = 0.0355, 0.1365, 0.006, 512.0
    mech = slider_crank_mechanism(r, l, e, math.radians(30.0), speed=w)
    mm = mech.motion(THETA)
    ref = slider_crank_exact(THETA, r, l, e, w)
    x_tdc = math.sqrt((l + r) ** 2 - e * e)
    c = mm.point("C")
    np.testing.assert_allclose(x_tdc - c[:, 0], ref.displacement, atol=1e-15)
    np.testing.assert_allclose(-mm.point("C", which="qd")[:, 0], ref.velocity, atol=1e-11)
    scale = np.max(np.abs(ref.acceleration))
    np.testing.assert_allclose(
        -mm.point("C", which="qdd")[:, 0], ref.acceleration, atol=1e-12 * scale
    )
    np.testing.assert_allclose(-wrap(mm.link_angle("rod")), ref.rod_angle, atol=1e-13)
    np.testing.assert_allclose(-mm.angular_velocity("rod"), ref.rod_angular_velocity, atol=1e-10)
    np.testing.assert_allclose(
        -mm.angular_acceleration("rod"), ref.rod_angular_acceleration, atol=1e-6
    )
    assert np.max(np.abs(c[:, 1] - e)) < 1e-15


def test_inverted_slider_crank_against_its_closed_form_and_finite_differences():
    a, d = 0.05, 0.12
    mech = inverted_slider_crank(a, d)
    mm = mech.motion(THETA, 1.0)
    bar = np.arctan2(a * np.sin(THETA), a * np.cos(THETA) - d)
    assert np.max(np.abs(wrap(mm.link_angle("bar") - bar))) < 1e-12
    h = 1e-6
    plus, minus = mech.motion(THETA + h, 1.0), mech.motion(THETA - h, 1.0)
    for link in ("bar", "block", "crank"):
        fd = wrap(plus.link_angle(link) - minus.link_angle(link)) / (2 * h)
        np.testing.assert_allclose(mm.angular_velocity(link), fd, atol=1e-7)
        fd2 = (plus.angular_velocity(link) - minus.angular_velocity(link)) / (2 * h)
        np.testing.assert_allclose(mm.angular_acceleration(link), fd2, atol=1e-6)
    for point in ("B", "E"):
        fd = (plus.point(point) - minus.point(point)) / (2 * h)
        np.testing.assert_allclose(mm.point(point, which="qd"), fd, atol=1e-9)
        fd2 = (plus.point(point, which="qd") - minus.point(point, which="qd")) / (2 * h)
        np.testing.assert_allclose(mm.point(point, which="qdd"), fd2, atol=1e-7)


def test_six_bar_conveyor_rates_match_finite_differences_and_the_cycle_closes():
    mech = Mechanism.example("conveyor-seed004")
    theta = np.radians(np.arange(0.0, 361.0, 10.0))
    mm = mech.motion(theta, 1.0)
    h = 1e-6
    plus, minus = mech.motion(theta + h, 1.0), mech.motion(theta - h, 1.0)
    for point in ("C", "E", "F", "S2"):
        fd = (plus.point(point) - minus.point(point)) / (2 * h)
        np.testing.assert_allclose(mm.point(point, which="qd"), fd, atol=1e-8)
        fd2 = (plus.point(point, which="qd") - minus.point(point, which="qd")) / (2 * h)
        np.testing.assert_allclose(mm.point(point, which="qdd"), fd2, atol=1e-6)
    # 0 and 360 deg are reached from opposite sides of the drawn position: same branch
    for point in ("C", "E", "F"):
        p = mm.point(point)
        assert np.max(np.abs(p[0] - p[-1])) < 1e-12


def test_branch_is_kept_through_a_cycle_in_fine_steps():
    mech = Mechanism.example("conveyor-seed004")
    theta = np.radians(np.arange(0.0, 360.5, 0.5))
    mm = mech.motion(theta, 1.0)
    f = mm.point("F")
    v = np.linalg.norm(mm.point("F", which="qd"), axis=1)
    step = np.linalg.norm(np.diff(f, axis=0), axis=1)
    assert np.all(step <= np.maximum(v[1:], v[:-1]) * math.radians(0.5) * 1.05 + 1e-12)


def test_crank_that_cannot_turn_stops_at_its_dead_point_with_both_angles_named():
    fb = FourBar(3.0, 3.5, 4.0, 5.0)  # triple rocker, limit at +-137.9 deg
    mech = fourbar_mechanism(fb, math.radians(20.0))
    limit = math.degrees(fb.crank_ranges()[0][1])
    with pytest.raises(InputError) as err:
        mech.motion(np.radians([20.0, 150.0]))
    text = str(err.value)
    assert "cannot be assembled at crank angle 150 deg" in text
    found = float(re.search(r"locks at crank angle ([0-9.]+) deg", text).group(1))
    assert found == pytest.approx(limit, abs=1e-3)


def test_link_groups_of_the_conveyor_follow_the_seed():
    groups = Mechanism.example("conveyor-seed004").link_groups()
    assert [g.links for g in groups] == [("link", "slider"), ("coupler", "rocker"), ("crank",)]
    assert [g.kind for g in groups] == ["RRP dyad", "RRR dyad", "driver"]


def _simple(**over):
    base = dict(
        name="m",
        points={"A": (0, 0), "B": (0.05, 0.0), "C": (0.15, 0.08), "D": (0.12, 0.0)},
        links=(Link("crank", ("A", "B")), Link("coupler", ("B", "C")), Link("rocker", ("D", "C"))),
        joints=(
            Joint("A", "revolute", (GROUND, "crank"), "A"),
            Joint("B", "revolute", ("crank", "coupler"), "B"),
            Joint("C", "revolute", ("coupler", "rocker"), "C"),
            Joint("D", "revolute", (GROUND, "rocker"), "D"),
        ),
        driver=Driver("A", "B"),
    )
    base.update(over)
    return Mechanism(**base)


def test_valid_mechanism_builds():
    assert _simple().degrees_of_freedom == 1


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ({"joints": ()}, "degrees of freedom"),
        ({"driver": Driver("B", "C")}, "revolute joint between the ground and the crank"),
        ({"driver": Driver("Q", "B")}, "no joint of that name"),
        ({"driver": Driver("A", "A")}, "other than its pivot"),
    ],
)
def test_structural_errors_are_named(change, message):
    if "joints" in change and not change["joints"]:
        change = {"joints": (Joint("A", "revolute", (GROUND, "crank"), "A"),)}
    with pytest.raises(InputError, match=message):
        _simple(**change)


def test_unknown_link_in_a_joint_is_named():
    joints = (
        Joint("A", "revolute", (GROUND, "crank"), "A"),
        Joint("B", "revolute", ("crank", "couplr"), "B"),
        Joint("C", "revolute", ("coupler", "rocker"), "C"),
        Joint("D", "revolute", (GROUND, "rocker"), "D"),
    )
    with pytest.raises(InputError, match='did you mean "coupler"') as err:
        _simple(joints=joints)
    assert err.value.key == 'joint "B" links'


def test_negative_mass_and_inertia_are_rejected():
    with pytest.raises(InputError, match="must not be negative"):
        Link("crank", ("A", "B"), mass=-1.0)
    with pytest.raises(InputError, match="must not be negative"):
        Link("crank", ("A", "B"), inertia=-1.0)


def test_singular_drawn_configuration_is_rejected():
    # coupler and rocker drawn in line (a dead point for the crank)
    points = {"A": (0, 0), "B": (0.05, 0.0), "C": (0.25, 0.0), "D": (0.2, 0.0)}
    with pytest.raises(InputError, match="drawn configuration is singular"):
        _simple(points=points)


def test_kinematics_result_exports_links_and_points():
    mech = Mechanism.example("fourbar-seed004")
    r = linkage_kinematics(mech.motion(np.radians([0.0, 90.0])))
    d = r.to_dict()
    assert set(d["link_angle_deg"]) == {"crank", "coupler", "rocker"}
    assert d["link_angle_deg"]["crank"] == pytest.approx([0.0, 90.0])
    assert {"B", "C", "P"} <= set(d["point_position_m"])
    assert "point_velocity_m_s.C.x" in r.to_csv().splitlines()[0]
