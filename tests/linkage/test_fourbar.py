"""Four-bar closed form: identities, finite differences, limits, branches and bad input."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from crankdyn.errors import InputError
from crankdyn.linkage.fourbar import (
    FourBar,
    fourbar_analysis,
    fourbar_motion,
    fourbar_positions,
    grashof_type,
    transmission_angle,
)

SEED = (0.0734, 0.12536, 0.1034, 0.10352)  # crank, coupler, rocker, ground (seed 004 set 1)


def wrap(x):
    return np.remainder(np.asarray(x) + math.pi, 2 * math.pi) - math.pi


@pytest.mark.parametrize(
    ("lengths", "kind"),
    [
        ((1.0, 3.0, 2.5, 3.5), "crank-rocker"),  # shortest = crank
        ((2.5, 3.0, 3.5, 1.0), "double-crank"),  # shortest = ground (drag link)
        ((3.0, 1.0, 3.5, 2.5), "double-rocker"),  # shortest = coupler
        ((3.0, 3.5, 1.0, 2.5), "rocker-crank"),  # shortest = output
        ((2.0, 3.0, 2.0, 3.0), "change-point"),  # parallelogram, s + l = p + q
        ((1.0, 3.0, 2.0, 4.0), "change-point"),
        ((3.0, 3.5, 4.0, 5.0), "triple-rocker"),  # s + l > p + q
    ],
)
def test_grashof_classes(lengths, kind):
    # Norton, Design of Machinery, Table 2-4 (Grashof inversions, change point, non-Grashof)
    assert grashof_type(*lengths) == kind
    assert FourBar(*lengths).grashof_type == kind


def test_crank_rotates_only_when_grashof_with_shortest_crank_or_ground():
    assert FourBar(1.0, 3.0, 2.5, 3.5).crank_rotates
    assert FourBar(2.5, 3.0, 3.5, 1.0).crank_rotates
    assert not FourBar(3.0, 1.0, 3.5, 2.5).crank_rotates
    assert not FourBar(3.0, 3.5, 1.0, 2.5).crank_rotates
    assert not FourBar(3.0, 3.5, 4.0, 5.0).crank_rotates


def test_loop_closure_holds_for_both_branches():
    theta = np.linspace(0, 2 * math.pi, 721)
    a, b, c, d = SEED
    for branch in ("open", "crossed"):
        t3, t4 = fourbar_positions(theta, a, b, c, d, branch)
        gap = a * np.exp(1j * theta) + b * np.exp(1j * t3) - d - c * np.exp(1j * t4)
        assert np.max(np.abs(gap)) < 1e-15


def test_open_branch_is_convex_above_the_ground_line():
    a, b, c, d = SEED
    theta = np.radians([30.0, 60.0, 90.0, 120.0])
    _t3, t4 = fourbar_positions(theta, a, b, c, d, "open")
    bx, by = a * np.cos(theta), a * np.sin(theta)
    cx, cy = d + c * np.cos(t4), c * np.sin(t4)
    cross = (d - bx) * (cy - by) - (0 - by) * (cx - bx)
    assert np.all(cross > 0)  # C to the left of B->D


def test_crossed_branch_is_the_mirror_image_of_the_open_one():
    a, b, c, d = SEED
    theta = np.linspace(0, 2 * math.pi, 361)
    t3o, t4o = fourbar_positions(theta, a, b, c, d, "open")
    t3c, t4c = fourbar_positions(-theta, a, b, c, d, "crossed")
    assert np.max(np.abs(wrap(t4c + t4o))) < 1e-12
    assert np.max(np.abs(wrap(t3c + t3o))) < 1e-12


@pytest.mark.parametrize("branch", ["open", "crossed"])
def test_velocities_and_accelerations_match_finite_differences(branch):
    a, b, c, d = SEED
    theta = np.linspace(0.01, 2 * math.pi, 97)
    h = 1e-6
    m = fourbar_motion(theta, a, b, c, d, 1.0, 0.0, branch)
    p = fourbar_motion(theta + h, a, b, c, d, 1.0, 0.0, branch)
    n = fourbar_motion(theta - h, a, b, c, d, 1.0, 0.0, branch)
    t3p, t4p = fourbar_positions(theta + h, a, b, c, d, branch)
    t3n, t4n = fourbar_positions(theta - h, a, b, c, d, branch)
    scale3 = np.max(np.abs(m.omega3))
    assert np.max(np.abs(wrap(t3p - t3n) / (2 * h) - m.omega3)) < 1e-6 * scale3
    assert np.max(np.abs(wrap(t4p - t4n) / (2 * h) - m.omega4)) < 1e-6 * np.max(np.abs(m.omega4))
    assert np.max(np.abs((p.omega3 - n.omega3) / (2 * h) - m.alpha3)) < 1e-5 * np.max(
        np.abs(m.alpha3)
    )
    assert np.max(np.abs((p.omega4 - n.omega4) / (2 * h) - m.alpha4)) < 1e-5 * np.max(
        np.abs(m.alpha4)
    )


def test_rates_scale_with_crank_speed_and_acceleration():
    # omega_i = omega2 k_i(theta), alpha_i = omega2^2 k_i'(theta) + alpha2 k_i(theta)
    a, b, c, d = SEED
    theta = np.linspace(0, 2 * math.pi, 50)
    unit = fourbar_motion(theta, a, b, c, d, 1.0, 0.0)
    m = fourbar_motion(theta, a, b, c, d, 7.0, 3.0)
    np.testing.assert_allclose(m.omega3, 7.0 * unit.omega3, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(m.alpha4, 49.0 * unit.alpha4 + 3.0 * unit.omega4, atol=1e-10)


def test_coupler_point_rates_match_finite_differences():
    fb = FourBar(*SEED, coupler_point=(0.06, 0.04))
    theta = np.linspace(0, 2 * math.pi, 73)
    h = 1e-6
    pos, vel, acc = fb.coupler_point_motion(fb.motion(theta, 2.0))
    pp = fb.coupler_point_motion(fb.motion(theta + h, 2.0))
    pn = fb.coupler_point_motion(fb.motion(theta - h, 2.0))
    # d/dt = omega2 d/dtheta at constant crank speed
    assert np.max(np.abs(2.0 * (pp[0] - pn[0]) / (2 * h) - vel)) < 1e-6 * np.max(np.abs(vel))
    assert np.max(np.abs(2.0 * (pp[1] - pn[1]) / (2 * h) - acc)) < 1e-5 * np.max(np.abs(acc))
    # the coupler point is rigidly attached: |P - B| and |P - C| constant
    joints = fb.joint_positions(fb.motion(theta))
    assert np.ptp(np.abs(pos - joints["B"])) < 1e-15
    assert np.ptp(np.abs(pos - joints["C"])) < 1e-15


def test_limits_agree_with_a_dense_sweep():
    fb = FourBar(*SEED)
    theta = np.linspace(0, 2 * math.pi, 200_001)
    m = fb.motion(theta)
    lim = fb.limits
    mu = transmission_angle(theta, *fb.lengths)
    assert lim.transmission_angle_min == pytest.approx(mu.min(), abs=1e-9)
    assert lim.transmission_angle_max == pytest.approx(mu.max(), abs=1e-9)
    assert lim.rocker_angle_min == pytest.approx(m.theta4.min(), abs=1e-9)
    assert lim.rocker_angle_max == pytest.approx(m.theta4.max(), abs=1e-9)
    # rocker extremes at the toggles (omega4 = 0), reached after the forward stroke
    t_max = theta[np.argmax(m.theta4)]
    t_min = theta[np.argmin(m.theta4)]
    stroke = (t_min - t_max) % (2 * math.pi)
    assert lim.forward_stroke_crank_angle == pytest.approx(stroke, abs=1e-4)
    ratio = max(stroke, 2 * math.pi - stroke) / min(stroke, 2 * math.pi - stroke)
    assert lim.time_ratio == pytest.approx(ratio, rel=1e-4)
    toggles = np.array(lim.toggle_crank_angles)
    w = fb.motion(toggles).omega4
    assert np.max(np.abs(w)) < 1e-9


def test_transmission_angle_is_the_angle_between_coupler_and_rocker():
    fb = FourBar(*SEED)
    theta = np.linspace(0, 2 * math.pi, 91)
    m = fb.motion(theta)
    mu = np.abs(wrap(m.theta3 - m.theta4))
    np.testing.assert_allclose(transmission_angle(theta, *fb.lengths), mu, atol=1e-12)


def test_branch_is_kept_through_a_full_cycle_in_fine_steps():
    fb = FourBar(*SEED)
    theta = np.linspace(0, 2 * math.pi, 3601)
    m = fb.motion(theta, 1.0)
    step = theta[1] - theta[0]
    jumps = np.abs(wrap(np.diff(m.theta4)))
    bound = np.maximum(np.abs(m.omega4[1:]), np.abs(m.omega4[:-1])) * step * 1.05 + 1e-12
    assert np.all(jumps <= bound)
    assert abs(wrap(m.theta4[-1] - m.theta4[0])) < 1e-12


def test_parallelogram_stays_a_parallelogram_with_indeterminate_rates_at_change_points():
    fb = FourBar(0.05, 0.2, 0.05, 0.2)
    theta = np.radians(np.arange(0.0, 361.0, 1.0))
    m = fourbar_motion(theta, *fb.lengths, 1.0, 0.0, "open")
    assert np.max(np.abs(wrap(m.theta3))) < 1e-6
    assert np.max(np.abs(wrap(m.theta4 - theta))) < 1e-6
    singular = np.isin(np.round(np.degrees(theta)), [0.0, 180.0, 360.0])
    assert np.array_equal(m.singular, singular)
    assert np.all(np.isnan(m.omega4[singular]))
    np.testing.assert_allclose(m.omega4[~singular], 1.0, atol=1e-6)


def test_non_rotating_crank_ranges_and_dead_points():
    fb = FourBar(3.0, 3.5, 4.0, 5.0)  # triple rocker
    ((lo, hi),) = fb.crank_ranges()
    assert lo == pytest.approx(-hi)
    # at the ends of the range coupler and rocker are in line: |BD| = b + c
    b_pt = 3.0 * np.exp(1j * hi)
    assert abs(5.0 - b_pt) == pytest.approx(7.5, rel=1e-12)
    assert fb.limits.dead_point_crank_angles
    with pytest.raises(InputError, match=r"cannot be assembled at crank angle 180 deg"):
        fb.motion(np.array([math.pi]))


@pytest.mark.parametrize("name", ["crank", "coupler", "rocker", "ground"])
def test_negative_or_zero_length_is_rejected(name):
    values = dict(zip(("crank", "coupler", "rocker", "ground"), SEED, strict=True))
    values[name] = -0.01
    with pytest.raises(InputError, match="must be positive") as err:
        FourBar(**values)
    assert err.value.key == name


def test_links_that_never_assemble_are_rejected():
    with pytest.raises(InputError, match="cannot be assembled at any crank angle"):
        FourBar(0.01, 0.01, 0.01, 0.5)


def test_bad_branch_is_rejected():
    with pytest.raises(InputError, match="open, crossed"):
        FourBar(*SEED, branch="sideways")


def test_analysis_result_exports_the_documented_keys():
    fb = FourBar(*SEED)
    r = fourbar_analysis(fb, np.radians([0.0, 60.0]), 10.0)
    d = r.to_dict()
    for key in (
        "grashof_type",
        "transmission_angle_min_deg",
        "transmission_angle_max_deg",
        "rocker_angle_min_deg",
        "rocker_angle_max_deg",
        "crank_angle_deg",
        "coupler_angle_deg",
        "rocker_angle_deg",
        "coupler_angular_velocity_rad_s",
        "rocker_angular_velocity_rad_s",
        "coupler_angular_acceleration_rad_s2",
        "rocker_angular_acceleration_rad_s2",
    ):
        assert key in d
    assert d["crank_angle_deg"][1] == pytest.approx(60.0)


@settings(max_examples=40, deadline=None)
@given(
    st.floats(0.2, 5.0),
    st.floats(0.2, 5.0),
    st.floats(0.2, 5.0),
    st.floats(0.2, 5.0),
    st.floats(0.0, 2 * math.pi),
)
def test_closure_and_velocity_identity_for_random_linkages(a, b, c, d, theta):
    t3, t4 = fourbar_positions(np.array([theta]), a, b, c, d)
    if not np.isfinite(t4[0]):
        return
    m = fourbar_motion(np.array([theta]), a, b, c, d, 1.0)
    if m.singular[0] or abs(math.sin(t3[0] - t4[0])) < 1e-3:
        return
    gap = a * np.exp(1j * theta) + b * np.exp(1j * t3[0]) - d - c * np.exp(1j * t4[0])
    assert abs(gap) < 1e-12 * max(a, b, c, d)
    # velocity loop: i a w2 e^{i t2} + i b w3 e^{i t3} - i c w4 e^{i t4} = 0
    vel = a * np.exp(1j * theta) + b * m.omega3[0] * np.exp(1j * t3[0])
    vel -= c * m.omega4[0] * np.exp(1j * t4[0])
    assert abs(vel) < 1e-9 * max(a, b, c, d) * (1 + abs(m.omega3[0]) + abs(m.omega4[0]))
