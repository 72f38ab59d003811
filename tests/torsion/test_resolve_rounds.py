"""The resolution layer's fast paths against their direct counterparts: the incremental
Refiner against refinement_speeds of the whole table every round, the Woodbury solve of the
load-dependent couplings against the direct elimination of the changed chain, the chain's
modal poles against the dense generalised eigenproblem."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.resolve import Refiner, modal_pole_rows, refinement_speeds
from crankdyn.torsion.solvers import linear_system
from crankdyn.torsion.sweep import low_rank_solve


def _curves(s: np.ndarray) -> np.ndarray:
    """Three resonance-like curves (one with two peaks) at speeds s."""
    peaks = [(10.3, 0.05), (14.71, 0.02), (17.2, 0.1)]
    a = 1.0 / np.hypot(s - peaks[0][0], peaks[0][1])
    b = 1.0 / np.hypot(s - peaks[1][0], peaks[1][1]) + 0.5 / np.hypot(s - 17.2, 0.1)
    c = 2.0 / np.hypot(s - 12.05, 0.3)
    return np.stack([a, b, c], axis=1)


def test_refiner_asks_what_refinement_speeds_asks_every_round():
    """Round by round the Refiner's requests equal refinement_speeds' of all rows so far in
    ascending speed (the same rule, the table kept incrementally): identical arrays."""
    s = np.linspace(8.0, 20.0, 25)
    y = _curves(s)
    refiner = Refiner(s, y, lambda top: top)
    rounds = 0
    for _ in range(12):
        new, column = refiner.request()
        order = np.argsort(s)
        expected, expected_column = refinement_speeds(s[order], y[order], y.max(axis=0))
        np.testing.assert_array_equal(new, expected)
        np.testing.assert_array_equal(column, expected_column)
        if new.size == 0:
            break
        rounds += 1
        refiner.add(new, _curves(new))
        s, y = np.concatenate([s, new]), np.concatenate([y, _curves(new)])
    assert rounds >= 2
    table_s, table_y = refiner.table()
    np.testing.assert_array_equal(table_s, np.sort(s))
    np.testing.assert_array_equal(table_y, y[np.argsort(s, kind="stable")])


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_refiner_keeps_the_local_maxima_of_the_whole_table(seed):
    """Rows added in random batches (speeds anywhere, next to each other or not), values
    rounded to a few levels so that ties and plateaus abound, and a few NaN: after every batch
    the Refiner's maxima are exactly those of the whole table in ascending speed by
    local_maxima's rule (mid >= both neighbours and above one of them; a NaN next to a row
    excludes it, since it compares false both ways)."""
    from crankdyn.torsion.resolve import local_maxima

    rng = np.random.default_rng(seed)

    def values(k):
        y = np.round(rng.random((k, 40)) * 4.0) / 4.0
        y[rng.random((k, 40)) < 0.02] = np.nan
        return y

    s = rng.permutation(np.linspace(0.0, 1.0, 30))
    y = values(s.size)
    refiner = Refiner(s, y, lambda top: top)
    for _ in range(8):
        new = rng.random(int(rng.integers(1, 12)))
        if rng.random() < 0.5:  # a cluster: new speeds next to each other
            new = new[0] + 1e-3 * np.arange(new.size)
        more = values(new.size)
        refiner.add(new, more)
        s, y = np.concatenate([s, new]), np.concatenate([y, more])
        order = np.argsort(s, kind="stable")
        table = y[order]
        mid, before, after = table[1:-1], table[:-2], table[2:]
        peak = (mid >= before) & (mid >= after) & ((mid > before) | (mid > after))
        rows, cols = np.nonzero(peak)
        expected = set(zip(order[rows + 1].tolist(), cols.tolist(), strict=True))
        found = set(zip(refiner.rows.tolist(), refiner.cols.tolist(), strict=True))
        assert found == expected
        if not np.isnan(np.max(y, axis=0)).any():  # local_maxima's, where no top is NaN
            rows, cols = local_maxima(table, floor=0.0)
            assert found == set(zip(order[rows].tolist(), cols.tolist(), strict=True))


def _chain(n: int = 9) -> TorsionModel:
    masses = tuple(Mass(f"m{i}", 0.3 + 0.05 * i, damping=2.0) for i in range(n))
    shafts = tuple(
        Shaft((f"m{i}", f"m{i + 1}"), 1e6 * (1 + 0.3 * i), damping=1.0, loss_factor=0.03)
        for i in range(n - 1)
    )
    return TorsionModel(masses=masses, shafts=(Shaft(("ground", "m0"), 2e5), *shafts))


def test_woodbury_solve_equals_the_direct_elimination():
    """Two changed couplings of a chain at 3 speeds x 2 orders: the Sherman-Morrison-Woodbury
    solution equals solve_with_change's direct elimination of the changed system to 1e-10."""
    system = linear_system(_chain())
    rng = np.random.default_rng(7)
    n = system.size
    omega = np.array([[300.0, 600.0], [450.0, 900.0], [800.0, 1600.0]])
    forcing = rng.normal(size=(3, 2, n)) + 1j * rng.normal(size=(3, 2, n))
    ends = np.array([[2, 3], [6, 5]])
    change = (rng.normal(size=(3, 2, 2)) + 0.2j) * 3e5
    direct = system.solve_with_change(omega, forcing, ends, change, 500.0)
    fast = low_rank_solve(system, omega, forcing, ends, change, 500.0)
    assert fast == pytest.approx(direct, rel=1e-10, abs=1e-10 * np.abs(direct).max())


def test_chain_modal_poles_equal_the_dense_eigenproblem():
    """The undamped frequencies below the top of modal_pole_rows equal scipy.linalg.eigh of
    (K, M) (1e-9 relative); the damping part b_r is phi^T C phi / 2 of the dense modes."""
    system = linear_system(_chain())
    kb, cb, hb, kg, cg, hg = system.chain
    top = 4000.0
    rows = modal_pole_rows(system.inertia, (kb, cb, 0 * hb), (kg, cg, 0 * hg), 0, top)
    lam, phi = scipy.linalg.eigh(system.stiffness, np.diag(system.inertia))
    omega = np.sqrt(lam)
    keep = omega <= top
    finite = rows[np.isfinite(rows)]  # one chain: (P,)
    assert finite.real == pytest.approx(omega[keep], rel=1e-9)
    damping = np.einsum("ir,ij,jr->r", phi, system.damping, phi)[keep] / 2.0
    assert finite.imag == pytest.approx(damping, rel=1e-8)
