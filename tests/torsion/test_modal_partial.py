"""The lowest modes of a long chain without the whole spectrum (issue 37 item 4): the round-off
thresholds of the listed modes need only their neighbours' eigenvalues and the largest one
(crankdyn.torsion.nodes: tau_r = 10 eps ||A||_2 / gap_r), found by bisection. The node counts,
resolved flags and round-off regions are those the thresholds of the whole spectrum (LAPACK
``dsterf``, as before) give to the same shapes, on chains whose lowest modes have round-off
regions; the frequencies are the whole solve's (``dstevd``, an independent driver) within the
eigenvalues' error bound, a few eps ||A||_2 in omega^2."""

import numpy as np
import pytest

from crankdyn.torsion import Shaft, TorsionModel, modal
from crankdyn.torsion.modal import natural_modes


def _chain(n: int, seed: int, grounded: bool) -> TorsionModel:
    rng = np.random.default_rng(seed)  # inertias and stiffnesses over decades: a large ||A||
    model = TorsionModel.chain_of(10 ** rng.uniform(-4, 1, n), 10 ** rng.uniform(5, 8, n - 1))
    if grounded:
        model = TorsionModel(
            model.masses, (*model.shafts, Shaft((model.masses[0].name, "ground"), 4e6))
        )
    return model


@pytest.mark.parametrize(("n", "grounded"), [(1500, False), (1200, True), (300, False)])
def test_lowest_modes_of_a_long_chain(monkeypatch, n, grounded):
    model = _chain(n, 37 + n, grounded)
    count = 15
    part = natural_modes(model, count=count)
    assert part.all_natural_frequency is None  # the whole spectrum was not computed
    assert part.modes_of_the_model == n
    full = natural_modes(model)
    top = float(full.natural_frequency[-1])
    assert part.highest_natural_frequency == pytest.approx(top, rel=1e-12)
    bound = 100 * np.finfo(float).eps * top**2  # eigenvalue error bound, omega^2
    assert np.all(np.abs(part.natural_frequency**2 - full.natural_frequency[:count] ** 2) < bound)
    # the same shapes with the thresholds from the whole spectrum
    monkeypatch.setattr(modal, "_spectrum_edges", lambda m, k: modal.chain_frequencies(m)[k:])
    whole = natural_modes(model, count=count)
    assert np.array_equal(part.mode_shapes, whole.mode_shapes)
    assert part.node_count.tolist() == whole.node_count.tolist()
    assert part.nodes_resolved.tolist() == whole.nodes_resolved.tolist()
    assert part.roundoff_regions == whole.roundoff_regions
    if n > 1000:  # the case the test is for: round-off among the lowest modes
        assert not all(part.nodes_resolved.tolist())


def test_one_mode_short_of_the_whole_spectrum():
    """count = n - 1: the first mode not listed is the highest one."""
    model = TorsionModel.chain_of([1.0, 2.0, 0.5, 1.5, 1.0], [1e5, 2e5, 1.5e5, 3e5])
    full = natural_modes(model)
    part = natural_modes(model, count=4)
    assert part.highest_natural_frequency == pytest.approx(
        float(full.natural_frequency[-1]), rel=1e-12
    )
    assert part.node_count.tolist() == full.node_count[:4].tolist() == [0, 1, 2, 3]
