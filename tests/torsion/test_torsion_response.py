"""Forced response: the batched tridiagonal solver, the chain and dense paths, closed forms,
the time-domain synthesis, dampers and geared models."""

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from crankdyn.errors import InputError
from crankdyn.torsion import Gear, Mass, Shaft, TorsionModel
from crankdyn.torsion.dampers import Damper
from crankdyn.torsion.excitation import UniformExcitation
from crankdyn.torsion.solvers import linear_system, steady_state
from crankdyn.torsion.sweep import forced_response
from crankdyn.torsion.synthesis import half_range
from crankdyn.torsion.tridiagonal import solve_tridiagonal


def _dense(lower, diag, upper):
    n = diag.shape[-1]
    a = np.zeros((*diag.shape[:-1], n, n), dtype=np.result_type(lower, diag, upper))
    idx = np.arange(n)
    a[..., idx, idx] = diag
    a[..., idx[:-1], idx[1:]] = upper
    a[..., idx[1:], idx[:-1]] = lower
    return a


@settings(max_examples=40, deadline=None)
@given(n=st.integers(1, 12), seed=st.integers(0, 10_000), rhs=st.integers(1, 3))
def test_tridiagonal_matches_dense_solve(n, seed, rhs):
    rng = np.random.default_rng(seed)
    shape = (4,)
    lower = rng.normal(size=(*shape, n - 1)) + 1j * rng.normal(size=(*shape, n - 1))
    upper = rng.normal(size=(*shape, n - 1)) + 1j * rng.normal(size=(*shape, n - 1))
    # small diagonals force row interchanges
    diag = 1e-3 * (rng.normal(size=(*shape, n)) + 1j * rng.normal(size=(*shape, n)))
    b = rng.normal(size=(*shape, n, rhs)) + 1j * rng.normal(size=(*shape, n, rhs))
    x = solve_tridiagonal(lower, diag, upper, b)
    a = _dense(lower, diag, upper)
    assert np.allclose(a @ x, b, rtol=1e-9, atol=1e-9 * np.abs(b).max())


def test_tridiagonal_zero_diagonal_needs_pivoting():
    lower = np.array([1.0, 1.0])
    diag = np.array([0.0, 0.0, 1.0])
    upper = np.array([1.0, 1.0])
    b = np.array([1.0, 2.0, 3.0])
    x = solve_tridiagonal(lower, diag, upper, b)
    assert np.allclose(_dense(lower, diag, upper) @ x, b)


def _branched():
    masses = (
        Mass("a", 1.0, damping=2.0, cylinders=(1,)),
        Mass("hub", 0.5),
        Mass("b", 2.0, cylinders=(2,)),
        Mass("c", 0.7),
    )
    shafts = (
        Shaft(("a", "hub"), 1e5, loss_factor=0.02),
        Shaft(("hub", "b"), 2e5, damping=3.0),
        Shaft(("hub", "c"), 8e4),
    )
    return TorsionModel(masses=masses, shafts=shafts)


def test_dense_path_for_branched_models():
    model = _branched()
    assert not model.is_chain
    system = linear_system(model)
    assert system.chain is None
    w = np.linspace(10.0, 800.0, 50)
    f = np.zeros((50, 4), dtype=complex)
    f[:, 0] = 1.0
    x = steady_state(model, w, f)
    k, c, h, m = (
        model.stiffness_matrix(),
        model.damping_matrix(),
        model.hysteretic_matrix(),
        model.mass_matrix(),
    )
    for i, omega in enumerate(w):
        d = k + 1j * h - omega**2 * m + 1j * omega * c
        assert np.allclose(d @ x[i], f[i], atol=1e-10)


def test_two_mass_closed_form():
    """Two free masses on one shaft (k, c), torque T on mass 1, by Cramer's rule:
    theta_1 = T (z - w^2 J2) / det, theta_2 = T z / det, z = k + i w c,
    det = (z - w^2 J1)(z - w^2 J2) - z^2."""
    j1, j2, k, c, t = 0.3, 1.7, 4.0e5, 25.0, 80.0
    model = TorsionModel(
        masses=(Mass("1", j1, cylinders=(1,)), Mass("2", j2)),
        shafts=(Shaft(("1", "2"), k, damping=c),),
    )
    w = np.array([50.0, 300.0, math.sqrt(k * (j1 + j2) / (j1 * j2)), 2000.0])
    r = forced_response(model, UniformExcitation(t, [0.0], "two-stroke"), w, [1.0], resolve=False)
    z = k + 1j * w * c
    det = (z - w**2 * j1) * (z - w**2 * j2) - z**2
    assert r.mass_response[:, 0, 0] == pytest.approx(t * (z - w**2 * j2) / det, rel=1e-12)
    assert r.mass_response[:, 0, 1] == pytest.approx(t * z / det, rel=1e-12)
    # shaft torque k (theta_2 - theta_1)
    assert r.shaft_response[:, 0, 0] == pytest.approx(
        k * t * (z - (z - w**2 * j2)) / det, rel=1e-12
    )


def test_half_range_against_dense_sampling():
    rng = np.random.default_rng(3)
    c = rng.normal(size=(20, 6)) + 1j * rng.normal(size=(20, 6))
    m = np.array([1, 2, 3, 6, 9, 24])
    top, low = half_range(c, m)
    phi = np.linspace(0.0, 2 * math.pi, 200_001)
    x = np.real(c @ np.exp(1j * np.outer(m, phi)))
    # the grid's extremes lie within (dphi m)^2 / 2 ~ 3e-7 of the true ones, never beyond them
    scale = np.abs(c).sum(axis=1)
    assert np.all(top >= x.max(axis=1) - 1e-12 * scale)
    assert np.all(low <= x.min(axis=1) + 1e-12 * scale)
    assert top == pytest.approx(x.max(axis=1), abs=1e-6 * scale.max())
    assert low == pytest.approx(x.min(axis=1), abs=1e-6 * scale.max())


def test_synthesis_bounded_by_order_sum_and_equal_for_one_order():
    model = TorsionModel.example("seed003-v6")
    ex = UniformExcitation(1.0, np.radians([0, 120, 240, 360, 480, 600]))
    w = np.linspace(1000, 2000, 11) * math.pi / 30
    r = forced_response(model, ex, w, [1.5, 3.0, 4.5, 6.0])
    assert np.all(r.synthesized_amplitude <= r.order_sum_amplitude * (1 + 1e-12))
    one = forced_response(model, ex, w, [3.0])
    assert one.synthesized_amplitude == pytest.approx(one.order_sum_amplitude, rel=1e-9)
    assert r.peak_to_peak == pytest.approx(2 * r.synthesized_amplitude)


def test_damper_at_chain_end_equals_dense_path():
    base = TorsionModel.example("seed003-v6")
    # the seed's damper ring as a Damper on the pulley, instead of a mass and a shaft
    model = TorsionModel(masses=base.masses[1:], shafts=base.shafts[1:], name="v6")
    ring = Damper("ring", "pulley", 0.1670, stiffness=160e3, damping=70.0)
    ex = UniformExcitation(1.0, np.zeros(6))
    w = np.linspace(800, 2200, 15) * math.pi / 30
    with_ring = forced_response(model, ex, w, [3.0, 6.0], dampers=(ring,), resolve=False)
    assert linear_system(model, (ring,)).chain is not None
    reference = forced_response(base, ex, w, [3.0, 6.0], resolve=False)
    i, j = with_ring.mass_index("flywheel"), reference.mass_index("flywheel")
    assert with_ring.amplitude[:, :, i] == pytest.approx(reference.amplitude[:, :, j], rel=1e-10)
    # a ring in the middle of the chain: dense path, same equations as a mass and a shaft
    mid = Damper("ring2", "cylinder 3", 0.05, stiffness=1e5, damping=10.0)
    x = forced_response(model, ex, w, [3.0], dampers=(mid,), resolve=False)
    assert linear_system(model, (mid,)).chain is None
    as_mass = TorsionModel(
        masses=(*model.masses, Mass("ring2", 0.05)),
        shafts=(*model.shafts, Shaft(("cylinder 3", "ring2"), 1e5, damping=10.0)),
    )
    y = forced_response(as_mass, ex, w, [3.0], resolve=False)
    assert x.amplitude == pytest.approx(y.amplitude, rel=1e-10)
    # the damper's power is the work of its damping torque: 1/2 w^2 c |twist|^2
    twist = (
        x.mass_response[:, 0, x.mass_index("ring2")]
        - x.mass_response[:, 0, x.mass_index("cylinder 3")]
    )
    assert x.damper_power[:, 0] == pytest.approx(0.5 * (3 * w) ** 2 * 10.0 * np.abs(twist) ** 2)


def test_viscous_damper_ring_has_no_stiffness():
    model = dataclasses.replace(
        TorsionModel.example("seed003-v6"), dampers=(Damper("visc", "flywheel", 0.2, damping=50),)
    )
    r = forced_response(model, UniformExcitation(1.0, np.zeros(6)), [200.0], [3.0])
    assert r.shafts[-1] == ("flywheel", "visc")
    twist = r.mass_response[0, 0, -1] - r.mass_response[0, 0, r.mass_index("flywheel")]
    # the coupling torque is the damping torque i w c (ring - hub)
    assert r.order_shaft_torque[0, 0, -1] == pytest.approx(abs(600.0 * 50 * twist))
    without = forced_response(
        model, UniformExcitation(1.0, np.zeros(6)), [200.0], [3.0], dampers=()
    )
    assert "visc" not in without.masses


@pytest.mark.parametrize(("direction", "sign"), [("same", 1.0), ("opposite", -1.0)])
def test_geared_model_reflects_torque_and_angles(direction, sign):
    """A 2:1 gear: the driven shaft's actual torque is half the crank-side torque in a rigid
    ratio, and its angle twice; against the same system written at the crank speed. Beyond an
    external (reversing) mesh the angles and torques change sign."""
    geared = TorsionModel(
        masses=(
            Mass("crank", 0.5, damping=1.0, cylinders=(1,)),
            Mass("pinion", 0.01),
            Mass("wheel", 0.04),
            Mass("load", 2.0),
        ),
        shafts=(Shaft(("crank", "pinion"), 5e4), Shaft(("wheel", "load"), 2e4)),
        gears=(Gear(("pinion", "wheel"), 0.5, direction=direction),),
    )
    # reflected to the crank speed: inertia and stiffness x r^2 = 0.25
    plain = TorsionModel(
        masses=(
            Mass("crank", 0.5, damping=1.0, cylinders=(1,)),
            Mass("gears", 0.01 + 0.04 * 0.25),
            Mass("load", 2.0 * 0.25),
        ),
        shafts=(Shaft(("crank", "gears"), 5e4), Shaft(("gears", "load"), 2e4 * 0.25)),
    )
    ex = UniformExcitation(10.0, [0.0], "two-stroke")
    w = np.linspace(50.0, 600.0, 12)
    a = forced_response(geared, ex, w, [1.0], resolve=False)
    b = forced_response(plain, ex, w, [1.0], resolve=False)
    assert a.mass_response[:, 0, a.mass_index("load")] == pytest.approx(
        sign * 0.5 * b.mass_response[:, 0, b.mass_index("load")], rel=1e-10
    )
    assert a.shaft_response[:, 0, 1] == pytest.approx(
        sign * b.shaft_response[:, 0, 1] / 0.5, rel=1e-10
    )
    assert a.order_shaft_torque[:, 0, 1] == pytest.approx(
        b.order_shaft_torque[:, 0, 1] / 0.5, rel=1e-10
    )


def test_bad_inputs():
    model = TorsionModel.example("seed003-v6")
    ex = UniformExcitation(1.0, np.zeros(6))
    with pytest.raises(InputError, match="speeds must be positive"):
        forced_response(model, ex, [-100.0, 100.0], [1.0])
    with pytest.raises(InputError, match="speed range is empty"):
        forced_response(model, ex, [], [1.0])
    with pytest.raises(InputError, match="does not fit the four-stroke cycle"):
        forced_response(model, ex, [100.0], [0.75])
    bare = TorsionModel.chain_of([1.0, 2.0], [1e5])
    with pytest.raises(InputError, match="no excitation point"):
        forced_response(bare, ex, [100.0], [1.0])
    r = forced_response(model, ex, [100.0], [1.0])
    with pytest.raises(InputError, match='no mass named "flywhel" \\(did you mean "flywheel"'):
        r.relative_angle("pulley", "flywhel")


def test_chain_solve_falls_back_to_pivoting_at_a_zero_pivot():
    """Undamped chain at omega^2 = k/J_1: the first pivot k - omega^2 J vanishes, so elimination
    without interchanges breaks down; the pivoting solver takes over for that frequency."""
    model = TorsionModel.chain_of([1.0, 2.0, 3.0], [1.0, 1.0])
    system = linear_system(model)
    w = np.array([0.3, 1.0, 1.5])
    f = np.array([[0.0, 1.0, 0.0]] * 3, dtype=complex)
    x = system.solve(w, f)
    d = system.matrix(w)
    assert np.all(np.isfinite(x))
    assert np.allclose(np.einsum("fij,fj->fi", d, x), f, atol=1e-12)
    # several right-hand sides at once give the columns of the receptance
    eye = np.broadcast_to(np.eye(3, dtype=complex), (3, 3, 3))
    receptance = system.solve(w, eye)
    assert np.allclose(receptance, np.linalg.inv(d), atol=1e-12)


def test_peak_api():
    """ResponseResult.peak: the largest value of a quantity, its speed, item and order."""
    model = TorsionModel.example("seed003-v6")
    ex = UniformExcitation(1.0, np.radians([0, 120, 240, 360, 480, 600]))
    w = np.arange(1000.0, 3001.0, 50.0) * math.pi / 30
    r = forced_response(model, ex, w, [1.5, 3.0, 4.5, 6.0])
    p = r.peak("synthesized_amplitude", "pulley")
    i = r.mass_index("pulley")
    assert p.value == np.max(r.synthesized_amplitude[:, i])
    assert r.speed[np.argmax(r.synthesized_amplitude[:, i])] == p.speed
    assert p.on_grid == bool(r.on_grid[np.argmax(r.synthesized_amplitude[:, i])])
    top = r.peak("shaft_torque")  # over every shaft
    assert top.value == np.max(r.shaft_torque) and top.item in {f"{a} - {b}" for a, b in r.shafts}
    per_order = r.peak("amplitude", "flywheel", order=4.5)
    assert per_order.order == 4.5
    assert per_order.value == np.max(r.amplitude[:, 2, r.mass_index("flywheel")])
    assert r.peak("amplitude", "flywheel").order in (1.5, 3.0, 4.5, 6.0)
    d = p.to_dict()
    assert d["value_rad"] == p.value and d["speed_rpm"] == pytest.approx(p.speed * 30 / math.pi)
    with pytest.raises(InputError, match="expected one of"):
        r.peak("torque")
    with pytest.raises(InputError, match="give no order"):
        r.peak("shaft_torque", order=3.0)
    with pytest.raises(InputError, match="not among the response's orders"):
        r.peak("amplitude", "pulley", order=2.0)
    with pytest.raises(InputError, match='no mass named "puley"'):
        r.peak("synthesized_amplitude", "puley")
    with pytest.raises(InputError, match="no finite values"):
        r.peak("shaft_stress")  # no shaft has diameters
    assert {q["quantity"] for q in r.to_dict()["peaks"]} >= {
        "synthesized_amplitude",
        "shaft_torque",
    }
    assert not hasattr(forced_response(model, ex, w, [3.0]), "rule_check")  # judges nothing


def test_undamped_resonances_are_noted_not_chased():
    """Without damping a resonance is unbounded: the resolved sweep does not evaluate the
    critical speed (a singular solve) nor refine next to it, and says so."""
    model = TorsionModel(
        masses=(Mass("a", 1.0, cylinders=(1,)), Mass("b", 2.0)), shafts=(Shaft(("a", "b"), 1e5),)
    )
    w = np.arange(1000.0, 3001.0, 100.0) * math.pi / 30
    r = forced_response(model, UniformExcitation(1.0, [0.0]), w, [1.0, 2.0, 3.0])
    assert "undamped resonances" in " ".join(r.notes)
    assert np.all(np.isfinite(r.synthesized_amplitude))
    assert r.speed.size == w.size
    top, low = half_range(np.array([[1.0, np.nan], [1.0, 0.0]]), [1, 2])
    assert np.isnan(top[0]) and np.isnan(low[0]) and top[1] == pytest.approx(1.0)


@pytest.mark.parametrize("shape", ["speeds x orders", "orders broadcast", "one frequency"])
def test_chain_solve_in_blocks_matches_the_dense_solve(monkeypatch, shape):
    """The chain solve in blocks of frequencies (issue 16: in place, the forcing read block by
    block) gives the dense solve's amplitudes, whatever the block size, with a pivoting
    fallback inside a block and a short last block; it is laid out as the caller's batch."""
    from crankdyn.torsion import solvers

    model = TorsionModel.example("seed003-v6")
    system = linear_system(model)
    n = system.size
    rng = np.random.default_rng(16)
    if shape == "one frequency":
        omega = np.float64(700.0)
        forcing = rng.normal(size=(n, 2))
    else:
        omega = np.linspace(50.0, 4000.0, 37)[:, None] * np.array([0.5, 1.0, 3.0, 6.5])
        forcing = (
            rng.normal(size=(1, 4, n))
            if shape == "orders broadcast"
            else rng.normal(size=(37, 4, n))
        )
    if shape == "one frequency":
        expected = np.linalg.solve(system.matrix(omega), forcing)
    else:
        full = np.broadcast_to(forcing, (*omega.shape, n))
        expected = np.linalg.solve(system.matrix(omega), full[..., None])[..., 0]
    for block in (1, 5, 1 << 13):
        monkeypatch.setattr(solvers, "_FREQUENCY_BLOCK", block)
        x = system.solve(omega, forcing)
        assert x.shape == expected.shape and x.flags.c_contiguous
        assert np.allclose(x, expected, rtol=1e-10, atol=1e-14 * np.max(np.abs(expected)))
