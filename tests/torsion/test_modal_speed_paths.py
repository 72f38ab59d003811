"""The fast paths of the modal analysis (issue 9): node counts computed with the result agree
with the nodes located on demand; the chain arrays assembled without a loop agree with the dense
matrices; mode shapes are read-only."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from crankdyn.torsion import Gear, Mass, Shaft, TorsionModel
from crankdyn.torsion.modal import natural_modes


def _branched_with_gears() -> TorsionModel:
    masses = (
        Mass("engine", 0.5, cylinders=(1,)),
        Mass("pinion", 0.01),
        Mass("wheel a", 0.05),
        Mass("load a", 1.0),
        Mass("wheel b", 0.03),
        Mass("load b", 0.4),
    )
    shafts = (
        Shaft(("engine", "pinion"), 2e5),
        Shaft(("wheel a", "load a"), 5e4),
        Shaft(("wheel b", "load b"), 3e4),
        Shaft(("load b", "ground"), 1e4),
    )
    gears = (Gear(("pinion", "wheel a"), 0.5), Gear(("pinion", "wheel b"), 2.0))
    return TorsionModel(masses=masses, shafts=shafts, gears=gears)


def _shuffled_chain() -> TorsionModel:
    """A chain whose shafts are listed out of chain order and one mass listed last."""
    masses = (Mass("a", 1.0), Mass("c", 0.3), Mass("d", 0.2), Mass("b", 0.5))
    shafts = (
        Shaft(("c", "d"), 3e5),
        Shaft(("a", "b"), 1e5),
        Shaft(("b", "c"), 2e5, damping=3.0, loss_factor=0.02),
        Shaft(("ground", "d"), 4e4),
    )
    return TorsionModel(masses=masses, shafts=shafts)


MODELS = {
    "uniform chain": TorsionModel.chain_of([1.0] * 9, [1e5] * 8),  # nodes at masses
    "branched, geared": _branched_with_gears(),
    "shuffled chain": _shuffled_chain(),
}


@pytest.mark.parametrize("name", list(MODELS))
@pytest.mark.parametrize("solver", ["eigen", "transfer"])
def test_node_counts_match_the_located_nodes(name, solver):
    model = MODELS[name]
    if solver != "eigen" and not model.is_chain:
        pytest.skip("the transfer-matrix method needs a chain")
    r = natural_modes(model, solver)
    assert [len(n) for n in r.nodes] == r.node_count.tolist()
    # an elastic mode r of a chain has r nodes; the rigid-body mode none
    if model.is_chain and model.is_free:
        assert r.node_count.tolist() == list(range(r.mode.size))


def test_nodes_at_masses_counted():
    # a uniform free chain of an odd number of masses: the middle mass rests in every mode
    # that is antisymmetric about it
    r = natural_modes(TorsionModel.chain_of([1.0] * 5, [1e5] * 4))
    at_mass = [sum(1 for n in mode if n.mass is not None) for mode in r.nodes]
    assert at_mass == [0, 1, 0, 1, 0]
    assert [len(n) for n in r.nodes] == r.node_count.tolist() == [0, 1, 2, 3, 4]


@settings(max_examples=30, deadline=None)
@given(n=st.integers(2, 30), seed=st.integers(0, 2**32 - 1))
def test_node_counts_match_on_random_chains(n, seed):
    rng = np.random.default_rng(seed)
    model = TorsionModel.chain_of(10 ** rng.uniform(-2, 0.5, n), 10 ** rng.uniform(5, 7, n - 1))
    r = natural_modes(model)
    assert [len(x) for x in r.nodes] == r.node_count.tolist()


@pytest.mark.parametrize("name", ["shuffled chain", "uniform chain"])
def test_chain_arrays_agree_with_the_dense_matrices(name):
    model = MODELS[name]
    ch = model.chain
    k = model.stiffness_matrix()
    c = model.damping_matrix()
    h = model.hysteretic_matrix()
    for dense, between, ground in (
        (k, ch.stiffness, ch.ground_stiffness),
        (c, ch.damping, ch.ground_damping),
        (h, ch.hysteretic, ch.ground_hysteretic),
    ):
        assert np.allclose(-np.diagonal(dense, 1), between, rtol=0, atol=0)
        assert np.allclose(dense.sum(axis=1), ground, rtol=1e-14, atol=1e-9)


def test_result_arrays_are_read_only():
    r = natural_modes(MODELS["shuffled chain"])
    for arr in (r.mode_shapes, r.eigenvectors, r.shapes_dof, r.natural_frequency):
        with pytest.raises(ValueError):
            arr[0] = 1.0


def test_chain_of_builds_the_same_objects_as_the_constructors():
    model = TorsionModel.chain_of([1.5, 2, np.float64(0.25)], [1e5, np.int64(300000)])
    assert model.masses == (Mass("1", 1.5), Mass("2", 2.0), Mass("3", 0.25))
    assert model.shafts == (Shaft(("1", "2"), 1e5), Shaft(("2", "3"), 3e5))
    assert all(type(m.inertia) is float for m in model.masses)
    assert all(type(s.stiffness) is float for s in model.shafts)


@pytest.mark.parametrize(
    ("inertias", "stiffnesses", "message"),
    [
        ([1.0, -2.0], [1e5], "inertia.*must be positive"),
        ([1.0, float("nan")], [1e5], "inertia.*not finite"),
        ([1.0, 2.0], [0.0], "stiffness.*must be positive"),
        ([1.0, "2 kg"], [1e5], "inertia.*expected a number"),
    ],
)
def test_chain_of_reports_a_bad_value_as_the_constructors_do(inertias, stiffnesses, message):
    from crankdyn.errors import InputError

    with pytest.raises(InputError, match=message):
        TorsionModel.chain_of(inertias, stiffnesses)


@pytest.mark.parametrize("grounded", [False, True])
@pytest.mark.parametrize("branched", [False, True])
def test_the_lowest_modes_are_those_of_the_whole_solve(grounded, branched):
    """natural_modes(count=k) (bisection and inverse iteration on a chain, a subset of the
    dense solve otherwise) gives the first k modes of the complete solve (issue 16)."""
    if branched:
        model = _branched_with_gears()
    else:
        rng = np.random.default_rng(16)
        n = 60
        inertia = rng.uniform(0.05, 2.0, n)
        stiffness = rng.uniform(0.2e6, 5e6, n - 1)
        model = TorsionModel.chain_of(inertia, stiffness)
        if grounded:
            masses = model.masses
            shafts = (*model.shafts, Shaft((masses[-1].name, "ground"), 1e6))
            model = TorsionModel(masses, shafts)
    full = natural_modes(model)
    k = min(4, full.mode.size - 1)
    part = natural_modes(model, count=k)
    assert part.mode.tolist() == full.mode[:k].tolist()
    assert part.modes_of_the_model == full.mode.size
    np.testing.assert_allclose(part.natural_frequency, full.natural_frequency[:k], rtol=1e-11)
    assert part.highest_natural_frequency == pytest.approx(full.natural_frequency[-1], rel=1e-11)
    if part.all_natural_frequency is not None:  # a branched model's whole spectrum
        np.testing.assert_allclose(part.all_natural_frequency, full.natural_frequency, rtol=1e-11)
    np.testing.assert_allclose(part.mode_shapes, full.mode_shapes[:k], atol=1e-9)
    np.testing.assert_allclose(part.modal_inertia, full.modal_inertia[:k], rtol=1e-9)
    assert part.node_count.tolist() == full.node_count[:k].tolist()
    assert part.nodes_resolved.tolist() == full.nodes_resolved[:k].tolist()
    for a, b in zip(part.nodes, full.nodes[:k], strict=True):
        assert [(n.shaft, n.mass, n.determined) for n in a] == [
            (n.shaft, n.mass, n.determined) for n in b
        ]
        np.testing.assert_allclose(
            [n.fraction or 0.0 for n in a], [n.fraction or 0.0 for n in b], atol=1e-9
        )
    assert full.modes_of_the_model is None and "modes_of_the_model" not in full.to_dict()
    assert part.to_dict()["modes_of_the_model"] == full.mode.size
