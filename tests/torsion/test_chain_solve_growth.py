"""The chain solve's small-pivot test (issue 16): the exact growth test made only on the
candidates the forward loop filters flags the same systems as the test on every system, and
the pivoting fallback solves them; the loss factors built inside the loop as before."""

import dataclasses

import numpy as np
import pytest

from crankdyn.torsion import Mass, Shaft, TorsionModel, solvers
from crankdyn.torsion.dampers import Damper
from crankdyn.torsion.solvers import LinearSystem, linear_system


def _abs2(z):
    return z.real**2 + z.imag**2


def _reference(system, w):
    """(flagged, largest |multiplier|) per frequency by the former code: elimination without
    interchanges on the whole diagonals, then the growth test on every system and row."""
    off, d = system._diagonals_of(w, None)
    d = d.copy()
    multiplier = np.zeros(w.size)
    with np.errstate(all="ignore"):
        for i in range(1, system.size):
            m = off[i - 1] / d[i - 1]
            multiplier = np.fmax(multiplier, np.abs(m))
            d[i] = d[i] - m * off[i - 1]
        flagged = ~np.all(_abs2(off) <= 1e16 * _abs2(d[:-1]), axis=0)
    return flagged, multiplier


def _scaled(system, scale):
    """The system with every inertia, stiffness and damping times ``scale`` (the same
    amplitudes under forces times ``scale``; beyond a model's magnitude limit on purpose)."""
    return dataclasses.replace(
        system,
        inertia=system.inertia * scale,
        link_values=system.link_values * scale,
        ground_values=system.ground_values * scale,
        chain=tuple(a * scale for a in system.chain),
    )


def _near_resonance():
    """An undamped chain whose first pivot 1 - w^2 passes through zero at w = 1: multipliers
    from 1e6 to 1e9 and one division by zero, around the candidate bound 1e7 and the growth
    bound 1e8; frequencies elsewhere for ordinary systems."""
    model = TorsionModel.chain_of([1.0, 2.0, 3.0], [1.0, 1.0])
    delta = np.array([1e-6, 2e-7, 1.1e-7, 9e-8, 5e-8, 2e-8, 1.1e-8, 9e-9, 5e-9, 1e-9, 0.0])
    w = np.concatenate([np.sqrt(1.0 + delta), np.sqrt(1.0 - delta), [0.3, 0.8, 1.4, 2.0]])
    return model, w


@pytest.mark.parametrize("scale", [1.0, 1e160, 1e-161])
@pytest.mark.parametrize("block", [3, 1 << 13])
@pytest.mark.parametrize("ring", [False, True])
def test_growth_filter_flags_the_same_systems(monkeypatch, scale, block, ring):
    """The systems sent to the pivoting solver are exactly those the growth test on every
    system and row flags (the former code), with candidates filtered in the loop (scale 1),
    rows whose |off| may leave the filter's range tested in full (a viscous damper ring: no
    stiffness; everything scaled by 1e160 or 1e-161, where |off|^2 and |pivot|^2 overflow or
    underflow), in one block or in blocks of three frequencies; the
    answers satisfy D X = F."""
    model, w = _near_resonance()
    dampers = [Damper("ring", "3", 0.2, damping=1e-3)] if ring else []
    system = _scaled(linear_system(model, dampers), scale)
    assert system.chain is not None
    expected, multiplier = _reference(system, w)
    if scale == 1.0 and not ring:  # the cases the filter must tell apart are present
        assert np.any(expected) and np.any(~expected)
        assert np.any((multiplier > solvers._CANDIDATE) & ~expected)
    sent: list[np.ndarray] = []
    former = LinearSystem._diagonals_of

    def recording(self, w, hysteretic_frequency):
        sent.append(np.array(w))
        return former(self, w, hysteretic_frequency)

    monkeypatch.setattr(solvers, "_FREQUENCY_BLOCK", block)
    monkeypatch.setattr(LinearSystem, "_diagonals_of", recording)
    f = np.zeros((w.size, system.size), dtype=complex)
    f[:, 1] = scale
    x = system.solve(w, f)
    got = np.concatenate(sent) if sent else np.empty(0)
    assert sorted(got.tolist()) == sorted(w[expected].tolist())
    d = system.matrix(w)
    residual = np.einsum("fij,fj->fi", d, x) - f
    size = np.max(np.abs(d), axis=(1, 2)) * np.max(np.abs(x), axis=1) + np.max(np.abs(f), axis=1)
    assert np.all(np.isfinite(x))
    assert np.all(np.max(np.abs(residual), axis=1) <= 1e-12 * size)


@pytest.mark.parametrize("hysteretic_frequency", [None, 300.0])
@pytest.mark.parametrize("block", [4, 1 << 13])
def test_chain_solve_with_loss_factors_matches_the_dense_solve(
    monkeypatch, hysteretic_frequency, block
):
    """Loss factors of shafts and of a damper ring, built inside the forward loop (exact
    hysteretic damping, or viscous at omega_h), give the dense solve's amplitudes; the
    diagonals are those of :meth:`LinearSystem.diagonals`."""
    masses = (
        Mass("a", 1.0, damping=2.0),
        Mass("b", 0.5),
        Mass("c", 2.0),
        Mass("d", 0.7, damping=1.0),
    )
    shafts = (
        Shaft(("a", "b"), 1e5, loss_factor=0.02),
        Shaft(("b", "c"), 2e5, damping=3.0),
        Shaft(("c", "d"), 8e4, loss_factor=0.05),
    )
    model = TorsionModel(masses=masses, shafts=shafts)
    system = linear_system(model, [Damper("ring", "d", 0.1, stiffness=1e4, loss_factor=0.1)])
    assert system.chain is not None
    w = np.linspace(10.0, 2000.0, 41)[:, None] * np.array([1.0, 2.5])
    rng = np.random.default_rng(5)
    f = rng.normal(size=(*w.shape, system.size)) + 1j * rng.normal(size=(*w.shape, system.size))
    monkeypatch.setattr(solvers, "_FREQUENCY_BLOCK", block)
    x = system.solve(w, f, hysteretic_frequency)
    d = system.matrix(w, hysteretic_frequency)
    expected = np.linalg.solve(d, f[..., None])[..., 0]
    assert x.flags.c_contiguous
    assert np.allclose(x, expected, rtol=1e-10, atol=1e-14 * np.max(np.abs(expected)))
    lower, diag, _upper = system.diagonals(w, hysteretic_frequency)
    off, main = system._diagonals_of(w.reshape(-1), hysteretic_frequency)
    assert np.array_equal(-off.T, lower.reshape(-1, system.size - 1))
    assert np.allclose(main.T, diag.reshape(-1, system.size), rtol=1e-15, atol=0.0)
