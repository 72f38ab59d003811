"""Branched lines by elimination from the leaves inward (issue 37 item 2,
:mod:`crankdyn.torsion.tree`): the same amplitudes as LU decomposition with partial pivoting of
the dense dynamic stiffness (an independent method, LAPACK ``zgesv``) to round-off, on a
marine line with a gearbox and a power take-off branch, on random trees with damper rings and
grounded shafts, with the load-dependent couplings' change, and at undamped resonances (the
flagged systems re-solved with pivoting); loops and modal damping keep the dense solve."""

import dataclasses
import math

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.io.catalogue import resolve_model_and_engine
from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.dampers import Damper
from crankdyn.torsion.elements import Gear
from crankdyn.torsion.solvers import change_matrix, linear_system, steady_state
from crankdyn.torsion.tree import TreeSolver, elimination_tree


def _marine_with_pto() -> TorsionModel:
    """The marine-propulsion example's line (engine, elastic coupling, 25:80 gearbox,
    subdivided shafts, propeller) with a power take-off: a 80:30 PTO pinion meshing with the
    wheel, a shaft and a shaft generator (a branch at the gearbox)."""
    model, _ = resolve_model_and_engine("marine-propulsion")
    masses = (*model.masses, Mass("pto pinion", 2.5, role="gear"), Mass("generator", 40.0))
    shafts = (*model.shafts, Shaft(("pto pinion", "generator"), 3e6, damping=80.0))
    gears = (*model.gears, Gear(("wheel", "pto pinion"), 80 / 30))
    return TorsionModel(masses, shafts, gears, name="marine line with PTO")


def _random_tree(seed: int, n: int) -> TorsionModel:
    """A random tree of n masses (each joined to an earlier one), random inertias, shaft
    stiffnesses, shaft and absolute damping and loss factors, two shafts to ground."""
    rng = np.random.default_rng(seed)
    masses = tuple(
        Mass(f"m{i}", float(rng.uniform(0.05, 3.0)), damping=float(rng.choice([0.0, 5.0])))
        for i in range(n)
    )
    shafts = [
        Shaft(
            (f"m{int(rng.integers(0, i))}", f"m{i}"),
            float(rng.uniform(1e5, 5e6)),
            damping=float(rng.choice([0.0, 2.0])),
            loss_factor=float(rng.choice([0.0, 0.02])),
        )
        for i in range(1, n)
    ]
    shafts += [Shaft(("ground", f"m{int(i)}"), 2e5) for i in rng.choice(n, 2, replace=False)]
    return TorsionModel(masses, tuple(shafts), name=f"tree {seed}")


def _dense(system, w, f, hysteretic_frequency=None):
    """The reference: numpy's LU solve of the dense D(omega) at every frequency."""
    return np.linalg.solve(system.matrix(w, hysteretic_frequency), f[..., None])[..., 0]


def _deviation(x, ref):
    """Largest |x - ref| at each frequency relative to the largest amplitude there."""
    return np.max(np.abs(x - ref), axis=-1) / np.max(np.abs(ref), axis=-1)


def _backward_error(system, w, x, f, hysteretic_frequency=None):
    """|D x - f| / (|D| |x| + |f|) at each frequency (infinity norms): round-off is a few eps."""
    d = system.matrix(w, hysteretic_frequency)
    r = np.einsum("...ij,...j->...i", d, x) - f
    norm = np.max(np.sum(np.abs(d), axis=-1), axis=-1)
    return np.max(np.abs(r), axis=-1) / (norm * np.max(np.abs(x), axis=-1) + np.abs(f).max())


def test_marine_line_with_pto_is_a_tree_and_matches_the_dense_solve():
    model = _marine_with_pto()
    assert not model.is_chain and model.junction is not None
    system = linear_system(model)
    assert system.chain is None and system.tree is not None
    speeds = np.linspace(300.0, 800.0, 101) / RPM
    orders = np.arange(1, 25) * 0.5
    w = speeds[:, None] * orders[None, :]
    f = np.zeros((*w.shape, system.size), dtype=complex)
    f[..., 1:7] = np.exp(1j * np.arange(6))  # the throws, in their phases
    x = steady_state(model, w, f)
    assert x.shape == f.shape
    assert _deviation(x, _dense(system, w, f)).max() < 1e-9
    assert _backward_error(system, w, x, f).max() < 1e-14


@pytest.mark.parametrize("seed", range(6))
def test_random_trees_match_the_dense_solve(seed):
    model = _random_tree(seed, 5 + 4 * seed)
    rng = np.random.default_rng(100 + seed)
    n = model.dof_count
    hubs = rng.choice(n, 2, replace=False)
    dampers = (
        Damper("ring a", f"m{hubs[0]}", 0.2, stiffness=2e5, damping=20.0),
        Damper("ring b", f"m{hubs[1]}", 0.1, damping=15.0),  # viscous
    )
    system = linear_system(model, dampers)
    assert system.chain is None and system.tree is not None
    lam = np.linalg.eigvalsh(system.stiffness / np.sqrt(np.outer(system.inertia, system.inertia)))
    near = np.sqrt(np.abs(lam[lam > 1.0])) * (1.0 + 1e-6)  # next to every natural frequency
    w = np.concatenate([np.linspace(1.0, 1.2 * near.max(), 300), near])
    f = rng.normal(size=(w.size, system.size, 2)) + 1j * rng.normal(size=(w.size, system.size, 2))
    for hf in (None, 400.0):
        x = system.solve(w, f, hf)
        ref = np.linalg.solve(system.matrix(w, hf), f)
        assert np.max(np.abs(x - ref), axis=(1, 2)).max() < 1e-9 * np.abs(ref).max()
        for r in range(2):
            assert _backward_error(system, w, x[..., r], f[..., r], hf).max() < 1e-14


def test_the_change_of_a_coupling_on_a_tree_matches_the_dense_solve():
    """solve_with_change (the load-dependent couplings at each speed) keeps the tree."""
    model = _marine_with_pto()
    system = linear_system(model)
    s = [s.between for s in model.shafts].index(("coupling primary", "coupling secondary"))
    ends = system.element_dofs[s : s + 1]
    rng = np.random.default_rng(7)
    w = (np.linspace(300.0, 800.0, 40) / RPM)[:, None] * np.array([0.5, 1.0, 6.0])[None, :]
    change = (rng.uniform(-5e4, 1e5, w.shape) * (1.0 + 0.1j))[..., None]
    f = np.zeros((*w.shape, system.size), dtype=complex)
    f[..., 3] = 1.0
    x = system.solve_with_change(w, f, ends, change)
    d = system.matrix(w) + change_matrix(ends, change, system.size)
    ref = np.linalg.solve(d, f[..., None])[..., 0]
    assert _deviation(x, ref).max() < 1e-9


def test_small_pivots_are_flagged_and_solved_with_pivoting():
    """An undamped star (a hub and three arms) at and next to the arms' resonance
    w = sqrt(k / J), where a leaf's pivot k - w^2 J vanishes: those systems are flagged and
    re-solved with partial pivoting; the others are not flagged; singular ones give NaN."""
    masses = (Mass("hub", 2.0), Mass("a", 1.0), Mass("b", 1.5), Mass("c", 0.5))
    shafts = tuple(Shaft(("hub", x), 1e4) for x in "abc")
    model = TorsionModel(masses, shafts)
    system = linear_system(model)
    wa = math.sqrt(1e4 / 1.0)  # arm a alone, its pivot 0
    w = np.array([0.3 * wa, wa * (1 + 1e-12), wa * (1 - 1e-10), 1.7 * wa])
    f = np.zeros((w.size, 4))
    f[:, 0] = 1.0
    solver = TreeSolver(
        system.tree, system.inertia, system.links, system.link_values, system.ground_values
    )
    _x, flagged = solver.solve(w, f[..., None].astype(complex), None)
    assert flagged.tolist() == [1, 2]
    x = system.solve(w, f)
    ref = _dense(system, w, f)
    assert _deviation(x, ref).max() < 1e-6  # the near-singular systems' own conditioning
    assert _backward_error(system, w, x, f).max() < 1e-14


def test_a_large_tree_solves_flagged_systems_sparsely():
    """A 300-mass undamped chain with a ring on an inner mass (a tree above the dense
    fallback's size): at the ring's own frequency sqrt(k / J) the sparse LU takes over."""
    model = TorsionModel.chain_of(np.full(300, 1.0), np.full(299, 1e6))
    ring = Damper("ring", model.masses[150].name, 0.25, stiffness=1e4)
    system = linear_system(model, (ring,))
    assert system.tree is not None and system.size > 200
    w = np.array([math.sqrt(1e4 / 0.25) * (1 + 1e-13), 55.0])
    f = np.zeros((2, system.size))
    f[:, 0] = 1.0
    x = system.solve(w, f)
    assert np.all(np.isfinite(x))
    assert _backward_error(system, w, x, f).max() < 1e-14


def test_loops_and_modal_damping_take_the_dense_solve():
    """A closed loop (three masses in a ring of shafts) has no elimination tree; modal damping
    couples every mass: both solved by the dense LU, the same numbers as numpy's solve."""
    masses = tuple(Mass(x, 1.0 + i, damping=3.0) for i, x in enumerate("abc"))
    loop = TorsionModel(
        masses, (Shaft(("a", "b"), 1e5), Shaft(("b", "c"), 2e5), Shaft(("c", "a"), 3e5))
    )
    assert elimination_tree(3, np.array([[0, 1], [1, 2], [0, 2]])) is None
    system = linear_system(loop)
    assert system.chain is None and system.tree is None
    w = np.linspace(10.0, 900.0, 50)
    f = np.ones((50, 3))
    assert np.array_equal(system.solve(w, f), _dense(system, w, f))
    tree = _random_tree(3, 8)
    damped = linear_system(tree, modal_damping=0.02)
    assert damped.tree is None and damped.modal_damping is not None
    f8 = np.ones((50, 8))
    assert np.array_equal(damped.solve(w, f8), _dense(damped, w, f8))


def test_sparse_storage_assembles_the_model_matrices():
    """The links and terms to ground give back the model's dense K, C and H exactly."""
    model = _marine_with_pto()
    system = linear_system(model)
    assert np.array_equal(system.stiffness, model.stiffness_matrix())
    assert np.array_equal(system.damping, model.damping_matrix())
    assert np.array_equal(system.hysteretic, model.hysteretic_matrix())
    # parallel shafts are one link with their values added
    twin = TorsionModel(
        (Mass("a", 1.0), Mass("b", 2.0)), (Shaft(("a", "b"), 1e5), Shaft(("b", "a"), 2e5))
    )
    system = linear_system(twin)
    assert system.links.tolist() == [[0, 1]] and system.link_values[0].tolist() == [3e5]
    assert dataclasses.replace(system).stiffness.tolist() == [[3e5, -3e5], [-3e5, 3e5]]
