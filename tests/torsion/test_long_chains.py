"""Long chains in O(n) memory (issue 37 item 3): the linear system of a chain holds no dense
matrix, the steady state of a long chain matches the dense solve, and the damped poles that
resolve a long chain's sweep come from its tridiagonal form, the same as the dense modal
solution (an independent method: LAPACK's dense symmetric eigensolver)."""

import math

import numpy as np
import pytest

from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.excitation import UniformExcitation
from crankdyn.torsion.solvers import linear_system, steady_state
from crankdyn.torsion.sweep import POLE_LIMIT, Sweep


def _chain(n: int, seed: int = 5, grounded: bool = False) -> TorsionModel:
    rng = np.random.default_rng(seed)
    masses = tuple(
        Mass(
            f"m{i}",
            float(rng.uniform(0.2, 2.0)),
            damping=float(rng.choice([0.0, 4.0])),
            cylinders=(i + 1,) if i < 6 else (),
        )
        for i in range(n)
    )
    shafts = tuple(
        Shaft(
            (f"m{i}", f"m{i + 1}"),
            float(rng.uniform(1e6, 5e6)),
            damping=1.0,
            loss_factor=float(rng.choice([0.0, 0.02])),
        )
        for i in range(n - 1)
    )
    if grounded:
        shafts += (Shaft(("ground", f"m{n - 1}"), 3e6),)
    return TorsionModel(masses, shafts, name=f"chain {n}")


def test_a_chain_system_holds_no_dense_matrix():
    system = linear_system(_chain(50))
    assert system.chain is not None
    assert "stiffness" not in vars(system) and "damping" not in vars(system)
    assert all(np.asarray(v).size <= 3 * 50 for v in vars(system).values() if hasattr(v, "size"))


def test_long_chain_steady_state_matches_the_dense_solve():
    model = _chain(250, grounded=True)
    system = linear_system(model)
    w = np.linspace(5.0, 4000.0, 13)
    f = np.zeros((w.size, 250), dtype=complex)
    f[:, :6] = np.exp(2j * np.arange(6))
    x = steady_state(model, w, f)
    ref = np.linalg.solve(system.matrix(w), f[..., None])[..., 0]
    dev = np.max(np.abs(x - ref), axis=-1) / np.max(np.abs(ref), axis=-1)
    assert dev.max() < 1e-9


@pytest.mark.parametrize("frozen", [None, 300.0])
def test_long_chain_poles_from_the_tridiagonal_form(frozen):
    """Above POLE_LIMIT the poles of a chain are the undamped modes up to the top frequency
    with their modal damping: the same as the dense branch (every mode of the dense matrix,
    the modal damping from the dense C and H) to 1e-9."""
    n = POLE_LIMIT + 40
    model = _chain(n)
    excitation = UniformExcitation(1.0, np.radians([0, 120, 240, 360, 480, 600]))
    sweep = Sweep(model, excitation, np.array([1.5, 3.0]), (), frozen, ())
    top = 2.0 * float(sweep.undamped()[12])
    mine = sweep.poles(top)
    dense = sweep._dense_pole_rows(sweep.system.stiffness, *sweep._damping(), exact=False)
    dense = np.sort_complex(dense[np.isfinite(dense) & (dense.real <= top)])
    assert mine.size == dense.size >= 13
    assert np.allclose(mine.real, dense.real, rtol=1e-9, atol=0)
    assert np.allclose(mine.imag, dense.imag, rtol=1e-7, atol=1e-9 * top)
    assert math.isfinite(float(np.max(mine.real)))


def test_long_chain_blocks_split_evenly_match_the_dense_solve(monkeypatch):
    """A long chain's frequencies in several blocks (the buffer cap forced low here), its rows
    built a few at a time: every system the dense solve's to 1e-9 (exact and frozen loss
    factors, two right-hand sides)."""
    import crankdyn.torsion.solvers as solvers

    monkeypatch.setattr(solvers, "_BLOCK_ELEMENTS", 1)
    monkeypatch.setattr(solvers, "_MIN_BLOCK", 7)
    model = _chain(120, seed=9, grounded=True)
    system = linear_system(model)
    w = np.linspace(5.0, 3000.0, 25)[:, None] * np.array([1.0, 2.5])  # 25 x 2: 9 blocks of 3 speeds
    f = np.zeros((*w.shape, 120, 2), dtype=complex)
    f[..., :6, 0] = np.exp(2j * np.arange(6))
    f[..., -1, 1] = 1.0
    for frozen in (None, 400.0):
        x = steady_state(model, w, f, hysteretic_frequency=frozen)
        ref = np.linalg.solve(system.matrix(w, frozen), f)
        dev = np.max(np.abs(x - ref), axis=-2) / np.max(np.abs(ref), axis=-2)
        assert dev.max() < 1e-9
