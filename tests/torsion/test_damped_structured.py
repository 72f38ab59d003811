"""Damped modes per mode (issue 33): the Rayleigh functional iteration on a chain's tridiagonal
pencil (:mod:`crankdyn.torsion.quadratic`) against the closed forms of proportionally damped
chains, against an independent dense solution of random chains (lightly and heavily damped),
the loss factors at each mode's own frequency against that definition computed independently
(dense, mode by mode), a branched model's per-mode path and the dense fallback; memory that
grows as the n x n mode shapes do, and the refusal above the bound in one line before any
allocation.

Tolerances. Proportional damping: the undamped eigenvalues omega_r^2 are known to about
eps omega_max^2 absolutely (LAPACK Users' Guide, 3rd ed., section 4.7.1), so omega_r to
eps (omega_max / omega_r)^2 / 2 relatively; 1e3 eps (omega_max / omega_r)^2 is allowed (observed
below 1e2). Against the dense state-space solution: both are backward stable (numpy's ``eig`` on
the state-space matrix, the iteration by its stopping test eta <= 16 eps), so an eigenvalue
differs by at most about kappa_r eps |lambda_r| times a small factor, kappa_r the eigenvalue's
condition number (Tisseur 2000, :func:`crankdyn.torsion.quadratic.condition_numbers`); 1e3
eps kappa_r is allowed (observed at most 30 eps kappa_r on these chains, 85 in the bench's,
kappa_r up to 1e5).
"""

from __future__ import annotations

import math
import tracemalloc

import numpy as np
import pytest
import scipy.linalg
from scipy.optimize import linear_sum_assignment

import crankdyn.torsion.damped as damped
from crankdyn.errors import InputError
from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.damped import damped_modes
from crankdyn.torsion.quadratic import ChainPencil, condition_numbers

pytestmark = pytest.mark.slow  # long: started first (tests/conftest.py)

EPS = float(np.finfo(float).eps)


def _chain(n, *, seed=1, alpha=0.0, beta=0.0, eta=0.0, free=True, absolute=None, relative=None):
    """A chain of n random masses (0.05..2 kg m^2) and shafts (0.2..5 MN m/rad); damping
    alpha J at every mass and beta k on every shaft (Rayleigh), or the arrays ``absolute`` and
    ``relative``; loss factor eta (scalar or per shaft); grounded at its first mass unless
    ``free``."""
    rng = np.random.default_rng(seed)
    inertia = rng.uniform(0.05, 2.0, n)
    k = rng.uniform(0.2e6, 5e6, n - 1 if free else n)
    names = [f"m{i}" for i in range(n)]
    c_abs = alpha * inertia if absolute is None else absolute
    c_rel = beta * k if relative is None else relative
    loss = np.broadcast_to(np.asarray(eta, dtype=float), k.shape)
    masses = tuple(Mass(a, j, damping=c) for a, j, c in zip(names, inertia, c_abs, strict=True))
    ends = [("ground", names[0])] if not free else []
    ends += [(names[i], names[i + 1]) for i in range(n - 1)]
    shafts = tuple(
        Shaft(e, s, damping=c, loss_factor=h)
        for e, s, c, h in zip(ends, k, c_rel, loss, strict=True)
    )
    return TorsionModel(masses=masses, shafts=shafts, name=f"chain-{n}")


def _undamped(model):
    """omega_r (rad/s, ascending) by the dense symmetric-definite solver (LAPACK dsyevr via
    scipy.linalg.eigh: another driver than the chain's dstevd)."""
    lam = scipy.linalg.eigh(model.stiffness_matrix(), model.mass_matrix(), eigvals_only=True)
    lam = np.maximum(lam, 0.0)
    if model.is_free:
        lam[0] = 0.0
    return np.sqrt(lam)


def _state_space(model, c):
    n = model.dof_count
    m = model.dof_inertia
    a = np.zeros((2 * n, 2 * n))
    a[:n, n:] = np.eye(n)
    a[n:, :n] = -model.stiffness_matrix() / m[:, None]
    a[n:, n:] = -c / m[:, None]
    return a


# ---- closed forms: proportional damping decouples the modes -----------------------------------
@pytest.mark.parametrize("free", [True, False])
def test_rayleigh_damped_chain_closed_form(free):
    """C = alpha M + beta K (Rayleigh damping; T. K. Caughey and M. E. J. O'Kelly, "Classical
    normal modes in damped linear dynamic systems", J. Appl. Mech. 32 (1965) 583-588): every
    undamped mode stays a mode, lambda^2 + (alpha + beta omega_r^2) lambda + omega_r^2 = 0, so
    omega_n = omega_r and zeta_r = alpha / (2 omega_r) + beta omega_r / 2, overdamped (zeta > 1,
    two real eigenvalues, no damped frequency) at both ends of the spectrum here."""
    model = _chain(400, alpha=60.0, beta=3e-4, free=free)
    r = damped_modes(model)
    wr = _undamped(model)
    el = slice(1, None) if free else slice(None)
    zeta = 60.0 / (2.0 * wr[el]) + 3e-4 * wr[el] / 2.0
    assert np.sum(zeta > 1.0) >= 2 and zeta[0] > 1.0 and zeta[-1] > 1.0  # both ends overdamped
    tol = 1e3 * EPS * (wr[-1] / wr[el]) ** 2
    assert np.all(np.abs(r.natural_frequency[el] / wr[el] - 1.0) <= tol)
    assert np.all(np.abs(r.damping_ratio[el] / zeta - 1.0) <= tol)
    under = zeta < 1.0
    wd = wr[el] * np.sqrt(1.0 - np.minimum(zeta, 1.0) ** 2)
    assert np.all(np.abs(r.damped_frequency[el][under] - wd[under]) <= tol[under] * wr[el][under])
    assert np.all(r.damped_frequency[el][~under] == 0.0)
    assert np.all(np.isnan(r.log_decrement[el][~under]))
    if free:  # the rigid-body mode: no vibration, and no elastic mode took its eigenvalues
        assert r.natural_frequency[0] == 0.0 and math.isnan(r.damping_ratio[0])


def test_overdamped_partners_found_directly_where_they_can_be(monkeypatch):
    """The Rayleigh-damped chain above: every partner (and the free chain's rigid-body pair's)
    refined from its own other root, no Arnoldi pool (the modes are checked against the closed
    form above)."""
    pools = []
    real_pool = damped._Modes._real_pool

    def counted(self, estimates, count):
        pools.append(count)
        return real_pool(self, estimates, count)

    monkeypatch.setattr(damped._Modes, "_real_pool", counted)
    r = damped_modes(_chain(400, alpha=60.0, beta=3e-4, free=True))
    assert not pools and np.sum(r.damping_ratio[1:] > 1.0) >= 20


@pytest.mark.parametrize(("eta", "free"), [(0.02, True), (0.3, False), (0.9, True)])
def test_uniform_loss_factor_chain_closed_form(eta, free):
    """Every shaft with the same loss factor: H = eta K, so each undamped mode stays a mode with
    lambda^2 + (eta omega_r^2 / omega_h) lambda + omega_r^2 = 0, and at the mode's own damped
    frequency omega_h = omega_d (the definition) the single-mass fixed point
    omega_d^2 = omega_r^2 (1 + sqrt(1 - eta^2)) / 2, zeta = eta omega_r / (2 omega_d)."""
    model = _chain(400, eta=eta, free=free, seed=3)
    r = damped_modes(model)
    wr = _undamped(model)
    el = slice(1, None) if free else slice(None)
    wd = wr[el] * math.sqrt((1.0 + math.sqrt(1.0 - eta**2)) / 2.0)
    tol = 1e3 * EPS * (wr[-1] / wr[el]) ** 2
    assert np.all(np.abs(r.damped_frequency[el] / wd - 1.0) <= tol)
    assert np.all(np.abs(r.damping_ratio[el] / (eta * wr[el] / (2.0 * wd)) - 1.0) <= tol)
    assert r.hysteretic == "at each mode's damped frequency (iterated)"


# ---- random chains against an independent dense solution ----------------------------------------
def _random_chain(seed, heavy):
    """n = 30..150 masses, free for odd seeds; absolute and relative dampers on about half the
    masses and shafts, up to 200 N m s/rad and 500 N m s/rad (``heavy``) or 30 times less."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(30, 150))
    free = bool(seed % 2)
    shafts = n - 1 if free else n
    scale = 10.0 if heavy else 0.3
    absolute = rng.uniform(0.0, 20.0 * scale, n) * (rng.random(n) < 0.5)
    relative = rng.uniform(0.0, 50.0 * scale, shafts) * (rng.random(shafts) < 0.5)
    return _chain(n, seed=seed, free=free, absolute=absolute, relative=relative)


def _dense_labelled(model):
    """The state-space eigenvalues labelled by the undamped modes by the MAC's optimal
    assignment, computed here from numpy's dense ``eig`` and scipy's ``linear_sum_assignment``
    (for models whose elastic modes are all underdamped)."""
    n = model.dof_count
    lam, vec = np.linalg.eig(_state_space(model, model.damping_matrix()))
    m = model.dof_inertia
    _, phi = scipy.linalg.eigh(model.stiffness_matrix(), model.mass_matrix())
    upper = np.flatnonzero(lam.imag > 1e-9 * np.abs(lam))
    v = vec[:n, upper]
    mac = np.abs(phi.T @ (m[:, None] * v)) ** 2
    mac /= np.sum(m[:, None] * phi**2, axis=0)[:, None] * np.sum(m[:, None] * np.abs(v) ** 2, 0)
    first = 1 if model.is_free else 0
    rows, cols = linear_sum_assignment(-mac[first:])
    out = np.full(n - first, np.nan, dtype=complex)
    out[rows] = lam[upper[cols]]
    return out, lam


@pytest.mark.parametrize("heavy", [False, True])
@pytest.mark.parametrize("seed", range(6))
def test_random_chains_agree_with_the_dense_state_space(seed, heavy):
    """Every eigenvalue (and each overdamped mode's pair) is one of the dense solution's, each
    mode labelled as the MAC's optimal assignment labels it, within 1e3 eps kappa_r (module
    docstring); the whole spectrum is accounted for."""
    model = _random_chain(seed, heavy)
    r = damped_modes(model)
    first = 1 if model.is_free else 0
    lam = (r.eigenvalue_real + 1j * r.eigenvalue_imag)[first:]
    x = np.ascontiguousarray(r.mode_shapes[first:])
    kappa = condition_numbers(ChainPencil.of(model.chain), lam, np.ones(lam.size), x)
    tol = 1e3 * EPS * kappa * np.abs(lam)
    labelled, every = _dense_labelled(model)
    under = r.damped_frequency[first:] > 0.0
    assert np.all(np.abs(lam[under] - labelled[under]) <= tol[under])
    # an overdamped mode: both real eigenvalues (lambda_b = omega_n^2 / lambda_a) are the
    # dense solution's, and no two modes share one
    wn = r.natural_frequency[first:][~under]
    pairs = np.r_[lam[~under], wn**2 / lam[~under]]
    for value, bound in zip(pairs, np.r_[tol[~under], tol[~under]], strict=True):
        assert np.min(np.abs(every - value)) <= bound
    assert np.unique(np.round(pairs.real, 6)).size == pairs.size


def test_mixed_modes_are_repaired(monkeypatch):
    """A heavily damped chain (absolute dampers up to 400 N m s/rad: 13 overdamped modes, zeta
    about 0.3 at 2400 rad/s) where the iteration from two undamped modes reaches one eigenpair:
    the repair (shift-invert Arnoldi near the start) finds the other; every eigenvalue is the
    dense solution's, and no two modes share one."""
    calls = []
    repair = damped._Modes.repair

    def counted(self, bad, bad_partner, count):
        calls.append((bad.tolist(), bad_partner.tolist()))
        return repair(self, bad, bad_partner, count)

    monkeypatch.setattr(damped._Modes, "repair", counted)
    n = 500
    rng = np.random.default_rng(1)
    rng.uniform(size=2 * n - 1)  # the draws of _chain's inertias and stiffnesses
    absolute, relative = rng.uniform(0.0, 400.0, n), rng.uniform(0.0, 50.0, n - 1)
    model = _chain(n, seed=1, absolute=absolute, relative=relative)
    r = damped_modes(model)
    assert calls, "the case must exercise the repair"
    lam, x = r.eigenvalue_real[1:] + 1j * r.eigenvalue_imag[1:], r.mode_shapes[1:]
    every = np.linalg.eigvals(_state_space(model, model.damping_matrix()))
    kappa = condition_numbers(ChainPencil.of(model.chain), lam, np.ones(lam.size), x)
    dev = np.array([np.min(np.abs(every - v)) for v in lam])
    assert np.all(dev <= 1e3 * EPS * kappa * np.abs(lam))
    under = lam[r.damped_frequency[1:] > 0.0]
    assert np.unique(np.round(under / np.abs(under), 9)).size == under.size  # all distinct


# ---- loss factors at each mode's own frequency: the definition, independently -------------------
def _iterated_definition(model, r):
    """Mode r's eigenvalue with the loss factors at its own damped frequency, by the definition
    (module docstring of crankdyn.torsion.damped): the dense state-space eigenvalues at omega_h,
    the one nearest mode r in the MAC, omega_h = its |Im lambda|, until omega_h is settled."""
    n = model.dof_count
    m = model.dof_inertia
    _, phi = scipy.linalg.eigh(model.stiffness_matrix(), model.mass_matrix())
    c, h = model.damping_matrix(), model.hysteretic_matrix()
    w = math.sqrt(max(scipy.linalg.eigh(model.stiffness_matrix(), model.mass_matrix())[0][r], 0))
    for _ in range(100):
        lam, vec = np.linalg.eig(_state_space(model, c + h / w))
        v = vec[:n]
        mac = np.abs(phi[:, r] @ (m[:, None] * v)) ** 2 / np.sum(m[:, None] * np.abs(v) ** 2, 0)
        mac[lam.imag < 0.0] = -1.0
        j = int(np.argmax(mac))
        if abs(abs(lam[j].imag) - w) <= 1e-13 * w:
            return lam[j]
        w = abs(lam[j].imag)
    raise AssertionError("the definition did not settle")


@pytest.mark.parametrize("seed", range(4))
def test_loss_factors_at_each_modes_frequency_against_the_definition(seed):
    rng = np.random.default_rng(seed + 10)
    n = int(rng.integers(5, 40))
    model = _chain(
        n,
        seed=seed,
        free=bool(seed % 2),
        eta=rng.uniform(0.0, 0.1, n - 1 if seed % 2 else n),
        absolute=rng.uniform(0.0, 5.0, n),
        relative=np.zeros(n - 1 if seed % 2 else n),
    )
    r = damped_modes(model)
    first = 1 if model.is_free else 0
    for i in range(first, n):
        ref = _iterated_definition(model, i)
        assert r.eigenvalue_real[i] + 1j * r.eigenvalue_imag[i] == pytest.approx(ref, rel=1e-9)


def _branched(eta):
    """A geared-style branched model: a drive line a-b-c with two branches d-e and f from b."""
    inertia = (2.0, 1.0, 0.5, 0.8, 0.3, 0.6)
    masses = tuple(Mass(name, j, damping=3.0) for name, j in zip("abcdef", inertia, strict=True))
    pairs = (("ground", "a"), ("a", "b"), ("b", "c"), ("b", "d"), ("d", "e"), ("b", "f"))
    shafts = tuple(
        Shaft(p, k, loss_factor=eta)
        for p, k in zip(pairs, (2e6, 1.5e6, 8e5, 6e5, 4e5, 9e5), strict=True)
    )
    return TorsionModel(masses=masses, shafts=shafts, name="branched")


def test_branched_model_with_loss_factors_against_the_definition():
    """The general path (dense LU per step, per mode) of a branched model."""
    model = _branched(0.08)
    assert not model.is_chain
    r = damped_modes(model)
    for i in range(model.dof_count):
        ref = _iterated_definition(model, i)
        assert r.eigenvalue_real[i] + 1j * r.eigenvalue_imag[i] == pytest.approx(ref, rel=1e-9)


@pytest.mark.parametrize(
    ("alpha", "beta", "eta", "free"), [(300.0, 5e-4, 0.0, True), (3.0, 2e-5, 0.05, False)]
)
def test_dense_fallback_gives_the_same_modes(monkeypatch, alpha, beta, eta, free):
    """The dense fallback (every mode reported failed) against the per-mode iteration: two
    independent computations of the same modes (the first case with overdamped modes at both
    ends of the spectrum and the rigid-body mode's split double zero: both paired by the MAC's
    assignment)."""
    model = _chain(60, seed=4, alpha=alpha, beta=beta, eta=eta, free=free)
    direct = damped_modes(model)
    per_mode = damped._per_mode

    def failing(*args):
        values, eig, _failed = per_mode(*args)
        return values * np.nan, eig, np.arange(values.shape[0])

    monkeypatch.setattr(damped, "_per_mode", failing)
    fallback = damped_modes(model)
    assert eta or np.sum(direct.damping_ratio[1:] > 1.0) >= 4
    for name in ("natural_frequency", "damped_frequency", "damping_ratio"):
        assert getattr(fallback, name) == pytest.approx(
            getattr(direct, name), rel=1e-9, nan_ok=True
        )


# ---- bounds: memory and the refusal -------------------------------------------------------------
def _traced_peak(call):
    tracemalloc.start()
    try:
        call()
        return tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()


@pytest.mark.parametrize("kind", ["viscous", "hysteretic"])
def test_memory_grows_as_the_mode_shapes(kind):
    """Traced peak memory within 4x the n x n complex mode shapes the result holds (n = 250 and
    500), and growing 4x when n doubles (an (n, n, n) array would grow 8x and need 1 GB)."""
    peaks = {}
    for n in (250, 500):
        if kind == "viscous":
            model = _chain(n, seed=2, absolute=np.full(n, 5.0), relative=np.full(n - 1, 20.0))
        else:
            model = _chain(n, seed=2, eta=np.linspace(0.01, 0.1, n - 1))
        _ = model.chain  # the model's own arrays built before the measurement
        peaks[n] = _traced_peak(lambda model=model: damped_modes(model))
        assert peaks[n] <= 4 * 16 * n * n + 2**20
    assert peaks[500] / peaks[250] < 5.0


def test_refused_above_the_bound_before_any_allocation(monkeypatch):
    monkeypatch.setattr(damped, "CHAIN_MAX_DOF", 100)
    model = _chain(101, eta=0.05)
    _ = model.chain  # the model's own arrays built before the measurement
    refused = []

    def call():
        with pytest.raises(InputError) as info:
            damped_modes(model)
        refused.append(info.value)

    assert _traced_peak(call) < 64 * 1024  # nothing n x n (80 KB of floats) was allocated
    error = refused[0]
    assert "\n" not in str(error) and error.key == "degrees of freedom" and error.value == 101
    assert "a chain take at most 100 degrees of freedom" in str(error)
    damped_modes(_chain(100, eta=0.05))  # at the bound: accepted


def test_the_general_paths_bounds(monkeypatch):
    monkeypatch.setattr(damped, "DENSE_MAX_DOF", 5)
    monkeypatch.setattr(damped, "DENSE_ITERATED_MAX_DOF", 4)
    with pytest.raises(InputError, match="branched or geared model with loss factors"):
        damped_modes(_branched(0.05))
    with pytest.raises(InputError, match="at most 5 degrees of freedom"):
        damped_modes(_branched(0.05), hysteretic=100.0)  # one omega_h: one eigenproblem
    with pytest.raises(InputError, match="a model with modal damping take at most 5"):
        damped_modes(_chain(6), modal_damping=0.02)
    damped_modes(_chain(6, eta=0.05))  # a chain: the structured path's bound


@pytest.mark.parametrize("name", ["marine-shaft-line", "verdict-geared-line", "genset-line"])
def test_example_lines_per_mode_equal_the_dense_solution(monkeypatch, name):
    """The built-in shaft lines (gears reflected, couplings with loss factors, absolute dampers)
    with the loss factors at one frequency: the dense solution their size gets by default and
    the per-mode iteration (forced), two independent computations, agree."""
    model = TorsionModel.example(name)
    dense = damped_modes(model, hysteretic=2 * math.pi * 20.0)
    monkeypatch.setattr(damped, "_SMALL", 0)
    per_mode = damped_modes(model, hysteretic=2 * math.pi * 20.0)
    for field in ("natural_frequency", "damped_frequency", "damping_ratio"):
        assert getattr(per_mode, field) == pytest.approx(
            getattr(dense, field), rel=1e-9, abs=1e-12, nan_ok=True
        )
    assert np.allclose(np.abs(per_mode.mode_shapes), np.abs(dense.mode_shapes), atol=1e-8)
