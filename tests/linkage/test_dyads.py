"""Closed-form dyads against the general Newton-Raphson solver and against closed forms of their
own (slider-crank, Scotch yoke, slotted crank), branch continuity, and the behaviour at dead
points and change points (the closed form hands those to the general solver)."""

import math
import types

import numpy as np
import pytest

from crankdyn.errors import InputError
from crankdyn.linkage.dyads import NoClosedForm
from crankdyn.linkage.elements import GROUND, Driver, Joint, Link
from crankdyn.linkage.fourbar import FourBar, fourbar_mechanism
from crankdyn.linkage.planar import Mechanism, slider_crank_mechanism

from .test_planar import inverted_slider_crank

FULL_TURN = np.radians(np.arange(0.0, 360.0, 1.0))


def scotch_yoke(r=0.05, theta=0.6):
    """Crank AB; the block at B slides in the yoke's vertical slot; the yoke slides along x on
    the ground: an RPP dyad (block, yoke). The yoke moves by r (cos theta - cos theta_drawn)."""
    b = (r * math.cos(theta), r * math.sin(theta))
    return Mechanism(
        name="Scotch yoke",
        points={"A": (0.0, 0.0), "B": b, "Y": (b[0], -0.02), "Z": (b[0] + 0.1, -0.02)},
        links=(
            Link("crank", ("A", "B")),
            Link("block", ("B",)),
            Link("yoke", ("Y", "Z"), cg=(b[0] + 0.03, -0.01)),
        ),
        joints=(
            Joint("A", "revolute", (GROUND, "crank"), "A"),
            Joint("B", "revolute", ("crank", "block"), "B"),
            Joint("slot", "prismatic", ("yoke", "block"), "B", axis=math.pi / 2),
            Joint("guide", "prismatic", (GROUND, "yoke"), "Y", axis=0.0),
        ),
        driver=Driver("A", "B", 0.0, 2.0, 3.0),
    )


def slotted_crank(h=0.1, theta=1.2):
    """The crank carries a slot along its line; the slider a in the slot is pinned to the
    slider b on the ground guide y = h: a PRP dyad (a, b). S = (h / tan theta, h)."""
    s = (h / math.tan(theta), h)
    b = (0.05 * math.cos(theta), 0.05 * math.sin(theta))
    return Mechanism(
        name="slotted crank",
        points={"A": (0.0, 0.0), "B": b, "S": s},
        links=(Link("crank", ("A", "B")), Link("a", ("S",), cg=s), Link("b", ("S",), cg=s)),
        joints=(
            Joint("A", "revolute", (GROUND, "crank"), "A"),
            Joint("slot", "prismatic", ("crank", "a"), "S", axis=theta),
            Joint("pin", "revolute", ("a", "b"), "S"),
            Joint("guide", "prismatic", (GROUND, "b"), "S", axis=0.0),
        ),
        driver=Driver("A", "B", 0.0, 1.5, -2.0),
    )


def triad():
    """A class III group: the ternary link T held by L1 (from the crank pin B), L2 and L3 (from
    ground pivots): one group of four links, no dyad, so the general solver runs."""
    pts = {
        "A": (0.0, 0.0),
        "B": (0.025, 0.0433),
        "E1": (0.10, 0.12),
        "E2": (0.16, 0.15),
        "E3": (0.14, 0.08),
        "G2": (0.22, 0.25),
        "G3": (0.25, 0.0),
    }
    links = (
        Link("crank", ("A", "B"), 0.1, 1e-5),
        Link("L1", ("B", "E1"), 0.2, 2e-4),
        Link("L2", ("G2", "E2"), 0.2, 2e-4),
        Link("L3", ("G3", "E3"), 0.2, 2e-4),
        Link("T", ("E1", "E2", "E3"), 0.5, 8e-4),
    )
    joints = (
        Joint("A", "revolute", (GROUND, "crank"), "A"),
        Joint("B", "revolute", ("crank", "L1"), "B"),
        Joint("E1", "revolute", ("L1", "T"), "E1"),
        Joint("E2", "revolute", ("L2", "T"), "E2"),
        Joint("E3", "revolute", ("L3", "T"), "E3"),
        Joint("G2", "revolute", (GROUND, "L2"), "G2"),
        Joint("G3", "revolute", (GROUND, "L3"), "G3"),
    )
    return Mechanism("triad", pts, links, joints, Driver("A", "B", 0.0, 3.0, 1.0))


MECHANISMS = {
    "fourbar-open (RRR)": (
        lambda: fourbar_mechanism(FourBar(0.0734, 0.12536, 0.1034, 0.10352), 1.0),
        FULL_TURN,
    ),
    "fourbar-crossed (RRR)": (
        lambda: fourbar_mechanism(FourBar(0.0734, 0.12536, 0.1034, 0.10352, branch="crossed"), 2),
        FULL_TURN,
    ),
    "slider-crank (RRP)": (
        lambda: slider_crank_mechanism(0.0355, 0.1365, 0.006, math.radians(30.0)),
        FULL_TURN,
    ),
    "inverted slider-crank (RPR)": (inverted_slider_crank, FULL_TURN),
    "Scotch yoke (RPP)": (scotch_yoke, FULL_TURN),
    "slotted crank (PRP)": (slotted_crank, np.radians(np.arange(25.0, 155.0, 1.0))),
    "conveyor-seed004 (RRR, RRP)": (lambda: Mechanism.example("conveyor-seed004"), FULL_TURN),
    "fourbar-seed004 (RRR)": (lambda: Mechanism.example("fourbar-seed004"), FULL_TURN),
    "slider-crank-friction (RRP)": (
        lambda: Mechanism.example("slider-crank-friction"),
        FULL_TURN,
    ),
}


def _deviations(mech, got, ref):
    """Largest position deviation relative to the mechanism's size (rotations as arcs of it),
    and of the rates relative to their peaks."""
    scale = mech.length_scale
    w = mech._model.weights
    return (
        float(np.max(np.abs(got[0] - ref[0]) * w) / scale),
        float(np.max(np.abs(got[1] - ref[1]) * w) / np.max(np.abs(ref[1]) * w)),
        float(np.max(np.abs(got[2] - ref[2]) * w) / np.max(np.abs(ref[2]) * w)),
    )


@pytest.mark.parametrize("name", list(MECHANISMS))
def test_closed_form_equals_the_general_newton_solver_over_the_cycle(name):
    build, theta = MECHANISMS[name]
    mech = build()
    model = mech._model
    assert model.closed is not None
    got = model._solve_closed(theta)  # the closed form itself, no fallback
    ref = model.solve(theta, method="newton")
    assert max(_deviations(mech, got, ref)) < 1e-9
    # the public path takes the closed form and gives the same arrays
    motion = mech.motion(theta)
    np.testing.assert_array_equal(motion.q, got[0])
    np.testing.assert_array_equal(motion.qpp, got[2])


def test_dyad_kinds_of_the_test_mechanisms():
    kinds = {
        name: [g.kind for g in build().link_groups()[:-1]]
        for name, (build, _t) in MECHANISMS.items()
    }
    assert kinds["inverted slider-crank (RPR)"] == ["RPR dyad"]
    assert kinds["Scotch yoke (RPP)"] == ["RPP dyad"]
    assert kinds["slotted crank (PRP)"] == ["PRP dyad"]
    assert kinds["conveyor-seed004 (RRR, RRP)"] == ["RRP dyad", "RRR dyad"]


def test_scotch_yoke_against_its_closed_form():
    # x_yoke = r cos(theta) + const: v = -r omega sin, a = -r (omega^2 cos + alpha sin)
    r, w, e = 0.05, 2.0, 3.0
    mech = scotch_yoke(r)
    m = mech.motion(FULL_TURN)
    x = m.link_state("yoke")[:, 0]
    np.testing.assert_allclose(x - x[0], r * (np.cos(FULL_TURN) - 1.0), atol=1e-15)
    np.testing.assert_allclose(
        m.link_state("yoke", "qd")[:, 0], -r * w * np.sin(FULL_TURN), atol=1e-15
    )
    acc = -r * (w * w * np.cos(FULL_TURN) + e * np.sin(FULL_TURN))
    np.testing.assert_allclose(m.link_state("yoke", "qdd")[:, 0], acc, atol=1e-14)
    assert np.all(m.link_state("yoke")[:, 1:] == [-0.01, 0.0])  # on its guide, not turning


def test_slotted_crank_against_its_closed_form():
    # S = (h cot theta, h): dx/dtheta = -h / sin^2, d2x/dtheta2 = 2 h cos / sin^3
    h = 0.1
    theta = np.radians(np.arange(25.0, 155.0, 1.0))
    m = slotted_crank(h).motion(theta, 1.0, 0.0)
    s = np.sin(theta)
    np.testing.assert_allclose(m.point("S", link="b")[:, 0], h * np.cos(theta) / s, atol=1e-15)
    np.testing.assert_allclose(m.point("S", link="b", which="qd")[:, 0], -h / s**2, rtol=1e-12)
    np.testing.assert_allclose(
        m.point("S", link="b", which="qdd")[:, 0], 2 * h * np.cos(theta) / s**3, atol=1e-12
    )


def test_drag_link_rotations_continue_through_whole_turns():
    # a double crank (ground shortest): coupler and follower turn fully; over two crank turns
    # the follower's rotation grows by 4 pi, as the continuation from the drawn angle says
    fb = FourBar(0.1, 0.12, 0.1, 0.04)
    mech = fourbar_mechanism(fb, math.radians(30.0))
    theta = np.radians(np.arange(0.0, 720.5, 2.5))
    got = mech._model._solve_closed(theta)
    ref = mech._model.solve(theta, method="newton")
    assert max(_deviations(mech, got, ref)) < 1e-9
    rocker = mech.motion(theta).link_state("rocker")[:, 2]
    assert rocker[-1] - rocker[0] == pytest.approx(4 * math.pi, abs=1e-9)
    assert np.all(np.diff(rocker) > 0.0)


def test_unsorted_and_repeated_angles_and_angles_beyond_a_turn():
    mech = Mechanism.example("conveyor-seed004")
    theta = np.radians([400.0, -30.0, 90.0, 90.0, 725.0, 40.0])
    got = mech._model._solve_closed(theta)
    ref = mech._model.solve(theta, method="newton")
    assert max(_deviations(mech, got, ref)) < 1e-9
    m = mech.motion(theta)
    np.testing.assert_allclose(m.point("F")[0], m.point("F")[5], atol=1e-12)  # 400 = 40 + 360
    np.testing.assert_array_equal(m.q[2], m.q[3])


def test_fine_path_over_two_turns_keeps_the_branch():
    mech = Mechanism.example("conveyor-seed004")
    theta = np.radians(np.arange(-360.0, 360.0, 0.05))
    m = mech.motion(theta)
    f = m.point("F")
    step = np.linalg.norm(np.diff(f, axis=0), axis=1)
    v = np.linalg.norm(m.point("F", which="qp"), axis=1)
    assert np.all(step <= np.maximum(v[1:], v[:-1]) * math.radians(0.05) * 1.01 + 1e-15)
    np.testing.assert_allclose(f[:7200], f[7200:], atol=1e-12)


# ---- dead points and change points: the closed form defers to the general solver -----------


def _outcome(call):
    try:
        return call()
    except InputError as err:
        return err


def _same_as_general(mech, theta):
    ref = _outcome(lambda: mech._model.solve(theta, method="newton"))
    got = _outcome(lambda: mech.motion(theta))
    if isinstance(ref, InputError):
        assert isinstance(got, InputError)
        assert str(got) == str(ref)
        return ref
    assert not isinstance(got, InputError), got
    assert max(_deviations(mech, (got.q, got.qp, got.qpp), ref)) < 1e-9
    return None


def test_narrow_assembly_gap_between_two_requested_angles_is_not_jumped():
    # a + d just above b + c: the crank cannot pass 179.07 .. 180.93 deg; the requested angles
    # lie on both sides, closer than the path's 3 deg anchors, and both assemble
    fb = FourBar(1.0, 2.0, 1.9999, 3.0)
    mech = fourbar_mechanism(fb, math.radians(60.0))
    theta = np.radians([178.5, 181.5])
    err = _same_as_general(mech, theta)
    assert err is not None
    assert "cannot be assembled at crank angle 181.5 deg" in str(err)
    assert "locks at crank angle 179.0" in str(err)


def test_triple_rocker_at_and_beyond_its_dead_point_behaves_as_before():
    fb = FourBar(3.0, 3.5, 4.0, 5.0)
    mech = fourbar_mechanism(fb, math.radians(20.0))
    limit = fb.crank_ranges()[0][1]
    err = _same_as_general(mech, np.array([math.radians(20.0), math.radians(150.0)]))
    assert "locks at crank angle" in str(err)
    _same_as_general(mech, np.array([0.0, limit]))
    _same_as_general(mech, np.array([0.0, limit - 1e-9]))


def test_parallelogram_change_points_behave_as_before():
    # at a change point (all links in line) the branch is not determined by continuity; the
    # closed form hands such a path to the general solver, which continues as it always did
    fb = FourBar(0.05, 0.12, 0.05, 0.12)
    mech = fourbar_mechanism(fb, math.radians(60.0))
    through = np.radians(np.arange(0.0, 361.0, 30.0))
    with pytest.raises(NoClosedForm):
        mech._model._solve_closed(through)
    _same_as_general(mech, through)
    away = np.radians(np.arange(10.0, 170.0, 5.0))
    got = mech._model._solve_closed(away)
    assert max(_deviations(mech, got, mech._model.solve(away, method="newton"))) < 1e-9
    np.testing.assert_allclose(got[1][:, 8], 1.0, rtol=1e-12)  # the rocker follows the crank


# ---- the general solver: a class III group ----------------------------------------------------


def test_class_iii_group_uses_the_general_solver_and_its_rates_are_derivatives():
    mech = triad()
    groups = mech.link_groups()
    assert [g.kind for g in groups] == ["group of 4 links", "driver"]
    assert mech._model.closed is None
    theta = np.radians(np.arange(40.0, 76.0, 2.0))
    m = mech.motion(theta, 1.0, 0.0)
    phi = mech._model.constraints(m.q, theta)
    assert np.max(np.abs(phi)) < 1e-13 * mech.length_scale
    h = 1e-6
    plus, minus = mech.motion(theta + h, 1.0, 0.0), mech.motion(theta - h, 1.0, 0.0)
    np.testing.assert_allclose(m.qp, (plus.q - minus.q) / (2 * h), atol=1e-8)
    np.testing.assert_allclose(m.qpp, (plus.qp - minus.qp) / (2 * h), atol=1e-6)


def test_blocks_of_angles_give_the_same_result(monkeypatch):
    # memory stays bounded by solving blocks of angles; the blocks must not change a number
    import crankdyn.linkage.solver as solver

    theta = np.radians(np.concatenate([np.arange(-400.0, 400.0, 0.7), [-3000.0, 4000.0]]))
    mech = Mechanism.example("conveyor-seed004")
    whole = mech._model._solve_closed(theta)
    newton = mech._model.solve(theta[:40], method="newton")
    monkeypatch.setattr(solver, "_PATH_BLOCK", 64)  # anchors then solved block by block too
    monkeypatch.setattr(solver, "_BLOCK", 7)
    fresh = Mechanism.example("conveyor-seed004")
    for a, b in zip(fresh._model._solve_closed(theta), whole, strict=True):
        np.testing.assert_array_equal(a, b)
    for a, b in zip(fresh._model.solve(theta[:40], method="newton"), newton, strict=True):
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-13 * max(1.0, np.max(np.abs(b))))


# ---- the continuation's shortcuts and their general branches -----------------------------------


def test_every_row_of_the_closed_form_is_written_and_closes_the_loops():
    # the dyads write each link's rows of the output once, in place: none may be left out
    for name, (build, theta) in MECHANISMS.items():
        mech = build()
        model = mech._model
        out = np.full((3, model.nq, theta.shape[0]), np.nan)
        model.closed.evaluate(theta, out=out)
        assert not np.any(np.isnan(out)), name
        np.testing.assert_array_equal(out, model.closed.evaluate(theta), err_msg=name)
        # loop closure (the general solver's constraint equations), rotations continued or not
        phi = model.constraints(out[0].T, theta)
        assert np.max(np.abs(phi)) < 1e-12 * mech.length_scale, name


def test_path_without_and_with_anchors_against_its_rule():
    # the path: the requested angles in order, the drawn angle, and equal steps in every gap
    # wider than 3 deg; the test for "no gap needs anchors" and the anchored path agree at the
    # limit (a gap of exactly 3 deg needs none, one just above needs one)
    from crankdyn.linkage.solver import _MAX_STEP

    mech = Mechanism.example("conveyor-seed004")
    model = mech._model
    t0 = model.theta0
    cases = {
        "fine": t0 + np.radians(np.arange(-10.0, 10.0, 0.1)) + 1e-3,
        "coarse, unsorted": np.radians([300.0, -20.0, 91.0, 91.0, 400.0]),
    }
    for name, theta in cases.items():
        pt, src = model._path(theta)
        order = np.argsort(theta, kind="stable")
        np.testing.assert_array_equal(pt[src >= 0], theta[order], err_msg=name)
        np.testing.assert_array_equal(src[src >= 0], order, err_msg=name)
        assert pt[src == -2].tolist() == [t0], name
        assert np.all(np.diff(pt) >= 0.0) and np.all(np.diff(pt) <= _MAX_STEP * (1 + 1e-12))
        # anchors only where the gap between neighbours of the path without them exceeds 3 deg
        bare = np.sort(np.append(theta, t0))
        wanted = np.maximum(np.ceil(np.diff(bare) / _MAX_STEP) - 1, 0).sum()
        assert np.count_nonzero(src == -1) == wanted, name
    # at the limit (a path drawn at 0: gaps of exactly 3 deg, and one a bit wider)
    at_zero = types.SimpleNamespace(theta0=0.0)
    for theta, wanted in (
        ([_MAX_STEP, 2 * _MAX_STEP, 4 * _MAX_STEP], [-2, 0, 1, -1, 2]),
        ([np.nextafter(_MAX_STEP, 1.0)], [-2, -1, 0]),
        ([-2 * _MAX_STEP, -_MAX_STEP], [0, 1, -2]),
    ):
        pt, src = model._path.__func__(at_zero, np.array(theta))
        assert src.tolist() == wanted
        assert np.all(np.diff(pt) <= _MAX_STEP * (1 + 1e-12))


def _wrapped_rotation(total, n, turns_per_unit):
    """A rotation phi = turns_per_unit * 2 pi x^2 / 2 over x in [0, total] wrapped to (-pi, pi]:
    (3, 1, n) values, first and second derivatives along the n path angles x."""
    x = np.linspace(0.0, total, n)
    c = TWO_PI_TEST * turns_per_unit
    phi = 0.5 * c * x * x
    wrapped = np.arctan2(np.sin(phi), np.cos(phi))
    return x, np.stack([wrapped, c * x, np.full_like(x, c)])[:, None, :], phi


TWO_PI_TEST = 2.0 * math.pi


def test_turns_shortcut_and_the_full_test_agree():
    from crankdyn.linkage.solver import KinematicModel, _turns

    # a rotation accelerating to many turns (wrapped): whole turns are found step by step and
    # the continued rotation is the true one; the same rotation slower than half a turn in all
    # takes the shortcut (no turn) and leaves the values alone
    x, angles, phi = _wrapped_rotation(1.0, 2001, 3.0)
    turns = KinematicModel._continue(x, angles, None)
    assert turns is not None
    np.testing.assert_allclose(angles[0, 0, 1:] + TWO_PI_TEST * turns[0], phi[1:], atol=1e-9)
    x, angles, phi = _wrapped_rotation(1.0, 2001, 0.2)
    assert np.all(np.abs(phi) < math.pi)
    assert KinematicModel._continue(x, angles, None) is None
    # a carried turn from a block before is kept, with and without new turns
    carry = np.array([2.0])
    np.testing.assert_array_equal(
        KinematicModel._continue(x, angles, carry), np.full((1, 2000), 2.0)
    )
    x, angles, phi = _wrapped_rotation(1.0, 2001, 3.0)
    np.testing.assert_array_equal(
        KinematicModel._continue(x, angles, carry), 2.0 + KinematicModel._continue(x, angles, None)
    )
    # a step that disagrees with its prediction (a branch change) fails in both branches: a
    # jump of a quarter turn (no whole turn near), and a whole turn plus a quarter
    h = np.diff(x)
    for extra in (0.5 * math.pi, TWO_PI_TEST + 0.5 * math.pi):
        bad = angles.copy()
        bad[0, 0, 1000:] += extra
        with pytest.raises(NoClosedForm, match="disagrees"):
            _turns(h, bad[:, :, :-1], bad[:, :, 1:])
    # a rotation predicted above 90 deg in one step, of either sign, and NaN
    for sign in (1.0, -1.0):
        fast = angles.copy()
        fast[1] *= sign * 1e4
        with pytest.raises(NoClosedForm, match="too fast"):
            _turns(h, fast[:, :, :-1], fast[:, :, 1:])
    nan = angles.copy()
    nan[0, 0, 7] = np.nan
    with pytest.raises(NoClosedForm):
        _turns(h, nan[:, :, :-1], nan[:, :, 1:])


def test_whole_turns_carried_across_blocks_give_the_same_result(monkeypatch):
    # a double crank over two turns: the rotations gain whole turns in every block; blocks of
    # 16 angles (turns carried from block to block, anchors solved apart) change no number
    import crankdyn.linkage.solver as solver

    fb = FourBar(0.1, 0.12, 0.1, 0.04)
    grids = (
        np.radians(np.arange(-400.0, 420.0, 2.5)),  # blocks of one run each, but one
        np.radians(np.concatenate([np.arange(-400.0, 420.0, 2.5), [-3000.0, 4000.0]])),
    )
    wholes = [fourbar_mechanism(fb, math.radians(30.0))._model._solve_closed(t) for t in grids]
    monkeypatch.setattr(solver, "_PATH_BLOCK", 16)  # the second: anchors apart from the rest
    for theta, whole in zip(grids, wholes, strict=True):
        fresh = fourbar_mechanism(fb, math.radians(30.0))
        for a, b in zip(fresh._model._solve_closed(theta), whole, strict=True):
            np.testing.assert_array_equal(a, b)
        ref = fresh._model.solve(theta[::20], method="newton")
        assert max(_deviations(fresh, [a[::20] for a in whole], ref)) < 1e-9


def test_determinant_test_scaled_after_the_reduction_is_the_same():
    # min(det * scale) == min(det) * scale to the bit (rounding is monotonic), NaN fails
    from crankdyn.linkage.dyads import DET_LIMIT, _check_det

    rng = np.random.default_rng(4)
    for _ in range(200):
        det = rng.normal(size=50) * 10.0 ** rng.uniform(-12, 2)
        scale = 10.0 ** rng.uniform(-3, 3)
        assert np.min(det * scale) == np.min(det) * scale
        assert np.max(det * scale) == np.max(det) * scale
        for sign in (1.0, -1.0):
            ref = (
                np.min(det * scale) >= DET_LIMIT if sign > 0 else np.max(det * scale) <= -DET_LIMIT
            )
            try:
                _check_det(det, sign, scale)
                got = True
            except NoClosedForm:
                got = False
            assert got == ref
    with pytest.raises(NoClosedForm):
        _check_det(np.array([1.0, np.nan]), 1.0, 2.0)
