"""Every mode of a large chain block by block (issue 17 point 5): the blocked eigenvectors
(bisection and inverse iteration, LAPACK dstebz/dsterf + dstein) agree with dstevd's, the
streamed JSON and CSV writers write what the whole-array path writes, byte for byte, and the
memory stays bounded by a block of modes, never N x N."""

from __future__ import annotations

import json
import os
import tracemalloc

import numpy as np
import pytest

from crankdyn.torsion import TorsionModel
from crankdyn.torsion.modal import natural_modes
from crankdyn.torsion.mode_blocks import ModeBlocks, modes_csv_chunks, modes_json_chunks


def _chain(n: int, seed: int = 17, grounded: bool = False) -> TorsionModel:
    rng = np.random.default_rng(seed)
    model = TorsionModel.chain_of(rng.uniform(0.05, 2.0, n), rng.uniform(2e5, 5e6, n - 1))
    if grounded:
        from crankdyn.torsion import Shaft

        shafts = (*model.shafts, Shaft((model.masses[-1].name, "ground"), 3e5))
        model = TorsionModel(masses=model.masses, shafts=shafts, name="grounded")
    return model


def _compact(result) -> str:
    return json.dumps(result.to_dict(), separators=(",", ":"), allow_nan=False) + "\n"


@pytest.mark.parametrize("grounded", [False, True])
@pytest.mark.parametrize("block", [1, 3, 7, 64])
def test_streamed_writers_are_byte_identical_to_the_whole_array_path(grounded, block):
    # the whole-array path: Result.to_dict through json (compact, as the CLI writes large JSON)
    # and Result.to_csv; the streamed writers on the same modes in tiny blocks
    r = natural_modes(_chain(50, grounded=grounded))
    assert any(r.roundoff_regions), "the case must exercise round-off regions"
    assert "".join(modes_json_chunks(r, block=block)) == _compact(r)
    assert "".join(modes_csv_chunks(r, block=block)) == r.to_csv()
    lowest = natural_modes(_chain(50, grounded=grounded), count=10)
    assert "".join(modes_json_chunks(lowest, block=block)) == _compact(lowest)


@pytest.mark.parametrize("grounded", [False, True])
@pytest.mark.parametrize("n", [1, 2, 50, 300])
def test_blocked_modes_agree_with_dstevd(n, grounded):
    """Independent solvers: bisection/inverse iteration per block against divide and conquer
    on the whole matrix; the shapes carry the same sign convention (first amplitude > 0)."""
    if n == 1 and not grounded:
        model = TorsionModel.chain_of([0.7], [])
    else:
        model = _chain(max(n, 2), grounded=grounded)
    whole = natural_modes(model)
    blocked = ModeBlocks(model, block=4).result()
    assert np.allclose(blocked.natural_frequency, whole.natural_frequency, rtol=1e-10, atol=0)
    assert np.max(np.abs(blocked.eigenvectors - whole.eigenvectors)) < 1e-9
    assert np.max(np.abs(blocked.mode_shapes - whole.mode_shapes)) < 1e-9
    assert blocked.node_count.tolist() == whole.node_count.tolist()
    assert blocked.nodes_resolved.tolist() == whole.nodes_resolved.tolist()
    assert blocked.roundoff_regions == whole.roundoff_regions
    for a, b in zip(blocked.nodes, whole.nodes, strict=True):
        assert [(n.shaft, n.region, n.determined) for n in a] == [
            (n.shaft, n.region, n.determined) for n in b
        ]
    # a node's position t = ta / (ta - tb) moves by at most 2 d / |ta - tb| when the
    # amplitudes move by d (ta, tb of opposite signs)
    arrays, shapes = whole.node_arrays, whole.shapes_dof
    ends = model.shaft_dofs[arrays.shaft]
    span = np.abs(shapes[arrays.shaft_mode, ends[:, 0]] - shapes[arrays.shaft_mode, ends[:, 1]])
    d = np.max(np.abs(blocked.shapes_dof - shapes)) if shapes.size else 0.0
    moved = np.abs(blocked.node_arrays.fraction - arrays.fraction)
    assert np.all(moved <= 2.0 * d / span + 1e-15)


def test_blocked_lowest_modes_are_those_of_the_partial_solver():
    model = _chain(120)
    lowest = natural_modes(model, count=9)
    blocked = ModeBlocks(model, 9, block=4).result()
    assert blocked.modes_of_the_model == lowest.modes_of_the_model == 120
    assert np.allclose(blocked.natural_frequency, lowest.natural_frequency, rtol=1e-12)
    assert np.max(np.abs(blocked.mode_shapes - lowest.mode_shapes)) < 1e-9
    assert blocked.node_count.tolist() == lowest.node_count.tolist()


def test_a_split_matrix_gives_orthonormal_modes():
    # a shaft so soft that LAPACK splits the tridiagonal matrix (e^2 below |d d'| ulp^2): the
    # blocks' eigenvalues merged in order, their vectors M-orthonormal
    model = TorsionModel.chain_of([1.0, 1.0, 2.0, 1.0, 0.5], [1e6, 1e-10, 1e6, 2e6])
    blocked = ModeBlocks(model, block=2).result()
    whole = natural_modes(model)
    # the mode of the soft shaft is below round-off (eps ||A||) in both: the others agree
    assert np.allclose(blocked.natural_frequency[2:], whole.natural_frequency[2:], rtol=1e-12)
    phi = blocked.eigenvectors[:, 2:]
    assert np.allclose(phi.T @ np.diag(model.dof_inertia) @ phi, np.eye(3), atol=1e-9)


def test_the_blocks_never_hold_n_by_n():
    """3,000 masses (the 10,000-mass case takes a minute): the peak of the blocked
    computation stays below half of one N x N float64 matrix (72 MB here; dstevd's workspace
    alone is N^2 floats, the whole-array path holds several)."""
    model = _chain(3000)
    ModeBlocks(_chain(3), block=2).result()  # imports outside the measurement
    tracemalloc.start()
    try:
        for _ in ModeBlocks(model).blocks():
            pass
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 0.5 * 3000 * 3000 * 8


@pytest.mark.parametrize("writer", [modes_json_chunks, modes_csv_chunks])
def test_the_streamed_writers_hold_a_block(writer, tmp_path):
    """The streamed writers' peak is a fraction of the whole-array path's on the same chain
    (which holds the N x N shapes, their lists and the whole text)."""
    model = _chain(200)
    "".join(writer(ModeBlocks(_chain(3))))  # imports outside the measurement

    def peak(write) -> int:
        tracemalloc.start()
        try:
            with open(os.devnull, "w", encoding="utf-8") as sink:
                write(sink)
            return tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()

    def streamed(sink):
        for chunk in (
            writer(ModeBlocks(model), spool_dir=tmp_path)
            if writer is modes_json_chunks
            else writer(ModeBlocks(model))
        ):
            sink.write(chunk)

    def whole(sink):
        r = natural_modes(model)
        sink.write(_compact(r) if writer is modes_json_chunks else r.to_csv())

    assert peak(streamed) < 0.25 * peak(whole)
    assert list(tmp_path.iterdir()) == []  # the spool files are gone
