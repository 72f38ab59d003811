"""Kinetostatics: matrix method vs virtual work, static hand solutions, friction, bad input."""

import math

import numpy as np
import pytest

from crankdyn.errors import InputError
from crankdyn.linkage.elements import GROUND, Driver, Force, Joint, Link, Torque
from crankdyn.linkage.fourbar import FourBar, fourbar_mechanism
from crankdyn.linkage.friction import efficiency
from crankdyn.linkage.kinetostatics import build_system, kinetostatics, known_loads
from crankdyn.linkage.planar import Mechanism, slider_crank_mechanism
from crankdyn.linkage.virtual_power import lever_moments, virtual_power_driving_torque

from .test_planar import inverted_slider_crank

G = 9.81
SEED = (0.0734, 0.12536, 0.1034, 0.10352)
THETA = np.radians(np.arange(0.0, 361.0, 7.5))


def _loaded_fourbar(**kw):
    fb = FourBar(*SEED, coupler_point=(0.06, 0.04))
    return fourbar_mechanism(
        fb,
        math.radians(60.0),
        masses=(0.09, 0.16, 0.13),
        inertias=(4e-5, 2.1e-4, 1.2e-4),
        cgs=(0.4, 0.55, 0.5),
        speed=kw.get("speed", 25.0),
        acceleration=kw.get("acceleration", 40.0),
        gravity=(0.0, -G),
        forces=(Force("coupler", "P", force=(12.0, -30.0)),),
        torques=(Torque("rocker", torque=-1.5),),
    )


def _relative_gap(result):
    scale = np.max(np.abs(result.driving_torque_virtual_work))
    return np.max(np.abs(result.driving_torque - result.driving_torque_virtual_work)) / scale


@pytest.mark.parametrize(
    "mechanism",
    [
        _loaded_fourbar(),
        slider_crank_mechanism(
            0.05,
            0.2,
            0.01,
            masses=(1.0, 2.0, 3.0),
            inertias=(0.002, 0.01),
            speed=80.0,
            acceleration=-300.0,
            gravity=(0.0, -G),
            forces=(Force("slider", "C", force=(-2000.0, 0.0)),),
        ),
        inverted_slider_crank(
            m1=0.5,
            i1=1e-4,
            m2=0.3,
            i2=2e-5,
            m3=1.2,
            i3=6e-3,
            alpha=5.0,
            gravity=(0.0, -G),
            torques=(Torque("bar", resistance=4.0),),
        ),
        Mechanism.example("conveyor-seed004"),
        Mechanism.example("fourbar-seed004"),
    ],
    ids=["fourbar", "slider-crank", "inverted-slider-crank", "conveyor", "fourbar-file"],
)
def test_matrix_method_agrees_with_virtual_work(mechanism):
    # seed 004: the matrix method [C]{R} = [D]{P} and Zhukovsky's lever give the same
    # balancing torque; they share only the known loads, not the reactions
    result = kinetostatics(mechanism.motion(THETA), friction=False)
    assert _relative_gap(result) < 1e-9


def test_balancing_force_agrees_with_virtual_work_and_gives_the_same_torque():
    mech = Mechanism.example("slider-crank-friction")
    theta = np.radians(np.arange(5.0, 180.0, 10.0))
    r = kinetostatics(mech.motion(theta), friction=False)
    assert _relative_gap(r) < 1e-9
    # perpendicular to the crank at B: torque = force * AB
    np.testing.assert_allclose(r.driving_torque, r.balancing_force * 0.1, rtol=1e-9)


def test_lever_moments_are_minus_the_powers():
    motion = _loaded_fourbar().motion(THETA)
    loads = known_loads(motion)
    power = np.sum(loads.W * loads.P, axis=1)
    np.testing.assert_allclose(np.sum(lever_moments(loads), axis=1), -power, rtol=1e-12)
    torque, force = virtual_power_driving_torque(motion, loads)
    assert force is None
    np.testing.assert_allclose(torque, -power, rtol=1e-12)


def test_four_bar_has_nine_unknowns_and_nine_equations():
    # seed 004 sec. 3.2: four lower pairs (2 unknowns each) and the balancing torque; three
    # moving links give nine equations
    system = build_system(_loaded_fourbar().motion(THETA[:3]))
    assert system.C.shape == (3, 9, 9)
    assert system.unknowns == (
        "A Rx",
        "A Ry",
        "B Rx",
        "B Ry",
        "C Rx",
        "C Ry",
        "D Rx",
        "D Ry",
        "driving torque",
    )
    assert system.D.shape[:2] == (3, 9)
    assert system.P.shape[1] == system.D.shape[2]


def test_residual_of_the_matrix_equation_is_round_off():
    system = build_system(_loaded_fourbar().motion(THETA))
    r = kinetostatics(_loaded_fourbar().motion(THETA), friction=False)
    residual = np.einsum("nij,nj->ni", system.C, r.reactions)
    rhs = np.einsum("nij,nj->ni", system.D, system.P)
    assert np.max(np.abs(residual - rhs)) < 1e-12 * np.max(np.abs(rhs))


# ---- gravity-only static cases with hand solutions ---------------------------------------------


def test_static_crank_alone_holds_its_weight():
    # one link on one pivot (F = 3 - 2 = 1): M_b = m g r cos(theta), R_A = (0, m g)
    m, r = 2.0, 0.15
    mech = Mechanism(
        name="crank",
        points={"A": (0.0, 0.0), "B": (0.3, 0.0)},
        links=(Link("crank", ("A", "B"), m, 0.01, (r, 0.0)),),
        joints=(Joint("A", "revolute", (GROUND, "crank"), "A"),),
        driver=Driver("A", "B", speed=0.0),
        gravity=(0.0, -G),
    )
    res = kinetostatics(mech.motion(THETA))
    np.testing.assert_allclose(res.driving_torque, m * G * r * np.cos(THETA), atol=1e-12)
    np.testing.assert_allclose(
        res.joint_force("A"), np.tile([0.0, m * G], (THETA.size, 1)), atol=1e-12
    )


def test_static_parallelogram_with_a_heavy_coupler():
    # the coupler (mass m, CG at its middle) translates; the rocker is a two-force member with
    # force f = m g / (2 sin theta) along it, and M_b = m g a cos(theta) (statics by hand)
    a, b, m = 0.1, 0.3, 5.0
    theta = np.radians([20.0, 45.0, 70.0, 110.0, 135.0, 160.0, 250.0, 300.0])
    fb = FourBar(a, b, a, b)
    mech = fourbar_mechanism(
        fb, math.radians(60.0), masses=(0.0, m, 0.0), speed=0.0, gravity=(0.0, -G)
    )
    res = kinetostatics(mech.motion(theta))
    np.testing.assert_allclose(res.driving_torque, m * G * a * np.cos(theta), atol=1e-11)
    f = m * G / (2 * np.sin(theta))
    # force of the coupler on the rocker at C is -f u (the rocker pushes the coupler with f u)
    u = np.stack([np.cos(theta), np.sin(theta)], axis=1)
    np.testing.assert_allclose(res.joint_force("C"), -f[:, None] * u, atol=1e-10)
    np.testing.assert_allclose(res.joint_force("D"), f[:, None] * u, atol=1e-10)
    # the crank carries the rest: force of the crank on the coupler = (0, m g) - f u
    np.testing.assert_allclose(
        res.joint_force("B"), np.array([0.0, m * G]) - f[:, None] * u, atol=1e-10
    )


def test_static_slider_crank_holding_the_slider_weight_along_the_guide():
    # guide along x, gravity along -x on the slider (weight W) only: massless rod = two-force
    # member; x_C = R cos t + sqrt(L^2 - R^2 sin^2 t), M_b = W dx_C/dt, guide force N = W tan(beta)
    R, L, W = 0.05, 0.2, 100.0
    theta = np.radians(np.arange(10.0, 360.0, 20.0))
    mech = slider_crank_mechanism(R, L, 0.0, masses=(0.0, 0.0, W / G), speed=0.0, gravity=(-G, 0.0))
    res = kinetostatics(mech.motion(theta))
    root = np.sqrt(L * L - (R * np.sin(theta)) ** 2)
    dx = -R * np.sin(theta) - R * R * np.sin(theta) * np.cos(theta) / root
    np.testing.assert_allclose(res.driving_torque, W * dx, atol=1e-11)
    # rod from B down to C: slope tan(beta) = R sin t / root; the rod pushes the slider with
    # (W, -W tan beta), the guide with (0, W tan beta)
    tan_beta = R * np.sin(theta) / root
    np.testing.assert_allclose(res.joint_force("S")[:, 1], W * tan_beta, atol=1e-10)
    np.testing.assert_allclose(res.joint_force("S")[:, 0], 0.0, atol=1e-12)


# ---- friction ---------------------------------------------------------------------------------


def test_friction_raises_the_driving_torque_and_efficiency_is_below_one():
    res = kinetostatics(Mechanism.example("slider-crank-friction").motion(THETA))
    moving = np.abs(res.driving_torque_frictionless) > 1e-6
    assert np.all(res.driving_torque[moving] > res.driving_torque_frictionless[moving])
    eta = res.efficiency[moving]
    assert np.all((eta > 0.0) & (eta < 1.0))
    assert 0.8 < res.mean_efficiency < 1.0


def test_zero_friction_coefficient_changes_nothing():
    plain = slider_crank_mechanism(0.05, 0.2, masses=(1, 2, 3), inertias=(0.01, 0.02), speed=30.0)
    zero = slider_crank_mechanism(
        0.05,
        0.2,
        masses=(1, 2, 3),
        inertias=(0.01, 0.02),
        speed=30.0,
        friction={"A": (0.01, 0.0), "S": (0.0, 0.0)},
    )
    a = kinetostatics(plain.motion(THETA))
    b = kinetostatics(zero.motion(THETA))
    np.testing.assert_allclose(a.driving_torque, b.driving_torque, rtol=0, atol=0)
    assert b.efficiency is None


def test_efficiency_definition():
    eta = efficiency(np.array([9.0, -10.0, 1.0, 0.0]), np.array([10.0, -9.0, -1.0, 1.0]))
    assert eta[0] == pytest.approx(0.9)
    assert eta[1] == pytest.approx(0.9)  # back-driven: |M| / |M0|
    assert np.isnan(eta[2]) and np.isnan(eta[3])


def test_self_locking_is_reported():
    # a huge guide friction locks a slider pushed nearly across its guide
    mech = slider_crank_mechanism(
        0.05,
        0.06,
        0.0,
        speed=10.0,
        forces=(Force("slider", "C", resistance=100.0),),
        friction={"S": (0.0, 3.0)},
    )
    with pytest.raises(InputError, match="self-locking"):
        kinetostatics(mech.motion(np.radians([60.0, 70.0, 80.0])))


# ---- singular positions -----------------------------------------------------------------------


def test_singular_kinetostatic_matrix_names_the_position():
    # a balancing force along x at B cannot turn the crank when B moves vertically (theta = 0)
    mech = Mechanism(
        name="bad balancing",
        points={"A": (0, 0), "B": (0.05, 0.0), "C": (0.25, 0.0)},
        links=(Link("crank", ("A", "B")), Link("rod", ("B", "C")), Link("slider", ("C",))),
        joints=(
            Joint("A", "revolute", (GROUND, "crank"), "A"),
            Joint("B", "revolute", ("crank", "rod"), "B"),
            Joint("C", "revolute", ("rod", "slider"), "C"),
            Joint("S", "prismatic", (GROUND, "slider"), "C", axis=0.0),
        ),
        driver=Driver("A", "B", balancing_point="B", balancing_direction=0.0),
        forces=(Force("slider", "C", force=(-10.0, 0.0)),),
    )
    with pytest.raises(InputError, match=r"singular at crank angle 180 deg \(position 3\)"):
        kinetostatics(mech.motion(np.radians([60.0, 120.0, 180.0])))
