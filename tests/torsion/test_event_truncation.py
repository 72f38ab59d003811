"""The event runs' modal truncation and the peaks' refinement at a few dofs (issue 37, item 1):
the refined peaks equal those of a refinement on the whole state, the truncated run (the
modes up to the cut-off integrated, those above quasi-statically) equals the all-mode run to
its reported bound, on a hand-worked three-mass line and on the marine example."""

from __future__ import annotations

import itertools
from functools import lru_cache

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.io.event_spec import event_from_table
from crankdyn.torsion import Mass, Shaft, TorsionModel, event_run
from crankdyn.torsion.event_run import REFINE_POINTS, _series, event_response
from crankdyn.torsion.events import StepTorque
from crankdyn.torsion.integrator import modal_system
from crankdyn.tvc.events import EVENT_MODE_FACTOR

PEAKS = ("max_torque", "min_torque", "max_vibratory", "min_vibratory")
TIMES = ("max_time", "min_time", "max_vibratory_time", "min_vibratory_time")


@lru_cache(maxsize=1)
def _marine():
    from crankdyn.io.catalogue import resolve_model_and_engine
    from crankdyn.session import Analysis

    _model, engine = resolve_model_and_engine("marine-propulsion")
    return Analysis(engine)


def _full_refine(line, rec):
    """The refinement on the whole state (every dof's angle and rate, every element's torque
    by :func:`_series`), one window at a time: the reference of the few-dof refinement."""
    for (e, which), w in rec.windows.items():
        sign = 1.0 if which == 0 else -1.0
        system = w.mode.system

        def evaluate(s, taus, w=w, system=system):
            taus = np.asarray(taus, dtype=float)
            st = system.within(w.states[s], w.u[s], w.u[s + 1], w.g[s], w.g[s + 1], w.step, taus)
            slope = (w.f[s + 1] - w.f[s]) / w.step
            force = w.f[s][None, :] + taus[:, None] * slope[None, :]
            x, v = system.to_physical(st, None, force, np.broadcast_to(slope, force.shape))
            t = w.t0 + s * w.step + taus
            return t, _series(line, w.mode, t, x, v, w.force, w.mean)

        taus = np.linspace(0.0, w.step, REFINE_POINTS)
        parts = [evaluate(s, taus) for s in range(len(w.states) - 1)]
        t_all = np.concatenate([p[0] for p in parts])
        v_all = sign * np.concatenate([p[1] for p in parts])[:, e]
        k = int(np.argmax(v_all))
        best, at = float(v_all[k]), float(t_all[k])
        if 0 < k < v_all.size - 1:
            y0, y1, y2 = v_all[k - 1], v_all[k], v_all[k + 1]
            den = y0 - 2.0 * y1 + y2
            if den < 0.0:
                vertex = float(t_all[k] + 0.5 * (y0 - y2) / den * (t_all[k + 1] - t_all[k]))
                s = min(int((vertex - w.t0) // w.step), len(w.states) - 2)
                _t, series = evaluate(s, [vertex - w.t0 - s * w.step])
                value = float(sign * series[0, e])
                if value > best:
                    best, at = value, vertex
        target, times = (rec.high, rec.high_at) if sign > 0 else (rec.low, rec.low_at)
        if best > sign * target[e]:
            target[e] = sign * best
            times[e] = at


def _all_modes(monkeypatch):
    """event_run's systems built with every mode (the same step rule: the cut-off still sets
    the step): the exact all-mode reference of a truncated run."""
    original = modal_system

    def every_mode(*args, max_frequency=None, **kwargs):
        return original(*args, **kwargs)

    monkeypatch.setattr(event_run, "modal_system", every_mode)


def _ice():
    session = _marine()
    model = session.loaded_model
    event = event_from_table({"kind": "ice", "q_max": "120 kN*m", "case": 1}, model=model)
    speed = 750 / RPM
    top = EVENT_MODE_FACTOR * float(np.max(session.orders)) * speed
    kwargs = {
        "speed": speed,
        "excitation": session.excitation(),
        "orders": session.orders,
        "max_frequency": top,
    }
    return model, event, kwargs


@pytest.mark.parametrize("truncated", [False, True])
def test_refined_peaks_equal_the_whole_state_refinement(monkeypatch, truncated):
    """The marine line's ice impact with its harmonic torques (the rigid gear mesh's column
    reads its wheel's neighbours): the peaks refined at the few dofs every element reads equal
    those refined on the whole state, rtol 1e-12 (the same exact solution, other products)."""
    model, event, kwargs = _ice()
    if not truncated:
        _all_modes(monkeypatch)
    run = event_response(model, event, **kwargs)
    monkeypatch.setattr(event_run, "_refine", _full_refine)
    reference = event_response(model, event, **kwargs)
    for name in PEAKS:
        np.testing.assert_allclose(
            getattr(run, name), getattr(reference, name), rtol=1e-12, atol=0.0, err_msg=name
        )
    # the instant of a flat maximum moves with the values' last digits: to 1e-3 of the
    # refinement's spacing (h / 40)
    spacing = run.step / (REFINE_POINTS - 1)
    for name in TIMES:
        np.testing.assert_allclose(
            getattr(run, name), getattr(reference, name), rtol=0.0, atol=1e-3 * spacing
        )


def _three_masses():
    """J = 1, 0.5, 2 kg m^2 in a free line, k_ab = 1e4 N m/rad, k_bc = 1e6 N m/rad: the elastic
    modes at 118.0 rad/s and 1585 rad/s."""
    return TorsionModel(
        masses=(Mass("a", 1.0), Mass("b", 0.5), Mass("c", 2.0)),
        shafts=(Shaft(("a", "b"), 1e4), Shaft(("b", "c"), 1e6)),
    )


def test_three_masses_stiff_element_above_the_cutoff(monkeypatch):
    """A torque T = 100 N m suddenly applied at a; the cut-off 1000 rad/s keeps the lower mode
    and leaves the stiff element's mode (1585 rad/s) quasi-static. Hand-worked (b and c one
    rigid body, Thomson 1993, sec. 4.2): the soft shaft's peak 2 T (J_b + J_c) / J = 142.857
    N m, the stiff one's 2 T J_c / J = 114.286 N m (J = 3.5 kg m^2), to (omega_1 / omega_2)^2
    = 5.5e-3; the truncated run equals the all-mode run within its reported bound (the step's
    jump: the dropped mode's quasi-static torque of the jump; no damping, no frequency: beta
    = 0)."""
    model = _three_masses()
    event = StepTorque("a", 100.0)
    kwargs = {"max_frequency": 1000.0, "duration": 1.0}  # h = 1/200 of the run in both runs
    run = event_response(model, event, **kwargs)
    assert run.modes_kept == 1
    assert run.cutoff_frequency == pytest.approx(1000.0)
    assert any("modal truncation" in n for n in run.notes)
    assert run.truncation_bound == 0.0
    assert run.peak(0) == pytest.approx(2 * 100.0 * 2.5 / 3.5, rel=5.5e-3)
    assert run.peak(1) == pytest.approx(2 * 100.0 * 2.0 / 3.5, rel=5.5e-3)
    _all_modes(monkeypatch)
    exact = event_response(model, event, **kwargs)
    assert exact.cutoff_frequency is None and exact.modes_kept == 2
    assert exact.peak(1) == pytest.approx(2 * 100.0 * 2.0 / 3.5, rel=5.5e-3)
    bound = np.asarray(run.truncation_torque)
    assert np.all(bound > 0.0) and run.truncation_error == pytest.approx(float(np.max(bound)))
    _within(run, exact, bound)


def _within(run, exact, bound):
    """The torques at every kept sample (the same instants: the same step) within the bound
    per element; the refined peaks within twice it (each run's refinement on its own curve:
    the exact one's carries the dropped modes' ripple, itself within the bound)."""
    np.testing.assert_allclose(run.time, exact.time, rtol=1e-15, atol=0.0)  # to the last bit
    for name in ("torque", "vibratory_torque"):
        difference = np.abs(getattr(run, name) - getattr(exact, name))
        assert np.all(difference <= bound[None, :]), (name, np.max(difference / bound))
    for name in ("max_torque", "min_torque", "max_vibratory", "min_vibratory"):
        difference = np.abs(getattr(run, name) - getattr(exact, name))
        assert np.all(difference <= 2.0 * bound), (name, np.max(difference / bound))


def test_without_cutoff_every_mode_runs():
    """Without max_frequency (the plain event's default) the run is the exact all-mode one:
    no truncation fields, no note."""
    run = event_response(_three_masses(), StepTorque("a", 100.0))
    assert run.modes_kept == 2 and run.cutoff_frequency is None
    assert run.truncation_error == 0.0 and run.truncation_torque is None
    assert not any("modal truncation" in n for n in run.notes)


def test_cutoff_must_be_positive():
    """A cut-off that is not a positive number is refused, naming the key."""
    from crankdyn.errors import InputError

    with pytest.raises(InputError, match="max_frequency"):
        event_response(_three_masses(), StepTorque("a", 1.0), max_frequency=-1.0)


def test_marine_ice_impact_truncated_within_its_bound(monkeypatch):
    """The marine line's ice impact (harmonic torques up to the highest order, the impacts'
    half sines): the truncated run's element torques (and vibratory torques) equal the
    all-mode run's within the bound reported per element (observed: at most 0.07 of it, the
    largest difference 800 N m of the crank's free-end span's -11.5 kN m)."""
    model, event, kwargs = _ice()
    run = event_response(model, event, **kwargs)
    assert run.modes_kept == 14 and run.cutoff_frequency == pytest.approx(kwargs["max_frequency"])
    # r = 1/4, but the dropped modes (from 603 Hz) are overdamped (the loss factors as viscous
    # damping): beta = |H / H_qs - 1| near 1
    assert 0.9 < run.truncation_bound < 1.0
    _all_modes(monkeypatch)
    exact = event_response(model, event, **kwargs)
    _within(run, exact, np.asarray(run.truncation_torque))


def test_residual_flexibility_columns_equal_the_dropped_modes():
    """R's columns (a solve with the shifted stiffness, the kept modes projected off) equal
    sum over the dropped modes of phi phi^T / omega^2 from the all-mode solution, for a free
    line and a grounded one; the truncated static twist equals the all-mode one."""
    rng = np.random.default_rng(7)
    n = 12
    m = rng.uniform(0.5, 2.0, n)
    k = np.zeros((n, n))
    for i, value in enumerate(10.0 ** rng.uniform(3, 7, n - 1)):
        k[i : i + 2, i : i + 2] += value * np.array([[1.0, -1.0], [-1.0, 1.0]])
    for grounded in (False, True):
        kk = k.copy()
        if grounded:
            kk[0, 0] += 1e5
        full = modal_system(m, kk, 1e-4 * kk)
        cut = float(full.natural_frequency[4]) * 1.0001
        part = modal_system(m, kk, 1e-4 * kk, max_frequency=cut)
        assert part.modes.shape[1] == 5 and part.dropped == n - int(not grounded) - 5
        assert part.lowest_dropped == pytest.approx(float(full.natural_frequency[5]), rel=1e-10)
        phi, w = full.modes[:, 5:], full.natural_frequency[5:]
        expected = (phi / w**2) @ phi.T
        cols = [0, 3, n - 1]
        got = part.residual.columns(cols)
        scale = np.max(np.abs(expected[:, cols]))
        np.testing.assert_allclose(got, expected[:, cols], rtol=0, atol=1e-9 * scale)
        f = np.zeros(n)
        f[[0, 3]] = [1.0, -2.0]
        np.testing.assert_allclose(part.static(f), full.static(f), rtol=1e-9, atol=1e-18)


def test_damper_ring_without_stiffness_stays_at_zero_frequency():
    """A viscous damper's ring (joined by damping only) is a zero-frequency motion: kept, at
    exactly zero frequency by both eigen-solvers (a rounding-positive eigenvalue would make
    the static twist 1/omega^2 huge: seen on the marine line at 100 masses), and the
    truncated static twist equals the all-mode one."""
    n = 30
    m = np.linspace(0.5, 3.0, n)
    m[-1] = 0.05  # the ring
    k = np.zeros((n, n))
    for i in range(n - 2):
        k[i : i + 2, i : i + 2] += 10.0 ** (4 + (i % 3)) * np.array([[1.0, -1.0], [-1.0, 1.0]])
    c = 1e-5 * k
    c[[0, n - 1], [0, n - 1]] += 50.0
    c[0, n - 1] = c[n - 1, 0] = -50.0
    full = modal_system(m, k, c)
    part = modal_system(m, k, c, max_frequency=float(full.natural_frequency[6]) * 1.0001)
    assert full.natural_frequency[0] == 0.0 and part.natural_frequency[0] == 0.0
    f = np.zeros(n)
    f[[1, 12]] = [3e3, -1e3]
    expected = full.static(f)
    np.testing.assert_allclose(
        part.static(f), expected, rtol=0, atol=1e-9 * np.max(np.abs(expected))
    )


@pytest.mark.parametrize("index", [0, 1])
def test_marine_tvc_clutch_and_start_within_their_bounds(monkeypatch, index):
    """The marine TVC's clutch engagement (a switch slip -> locked: the dropped modes restart
    quasi-statically in the locked line; the governor's held torques jump at every sample)
    and its start through the barred range (a speed ramp with the harmonic torques): every
    element's peaks of the truncated run within the reported bound of the all-mode run's
    (observed: 0.23 and 0.035 of it). The 38-mass line is below the TVC's truncation
    threshold (it integrates every mode): the threshold is lowered here."""
    from crankdyn.tvc.events import _run

    monkeypatch.setattr("crankdyn.tvc.events.EVENT_TRUNCATION_DOFS", 1)
    session = _marine()
    te = session.tvc_spec.events[index]
    args = (session.loaded_model, te, 750 / RPM, session.excitation(), session.orders)
    run = _run(*args)
    assert run.cutoff_frequency is not None and run.truncation_error > 0.0
    _all_modes(monkeypatch)
    exact = _run(*args)
    bound = np.asarray(run.truncation_torque)
    for name in ("max_torque", "min_torque", "max_vibratory", "min_vibratory"):
        difference = np.abs(getattr(run, name) - getattr(exact, name))
        assert np.all(difference <= bound), (name, np.max(difference - bound))


@pytest.mark.parametrize(
    ("forcing", "lowest", "damping"), [(1.0, 4.0, 0.0), (1.0, 4.0, 30.0), (2.0, 3.0, 5.0)]
)
def test_truncation_factor_is_the_largest_dynamic_part(forcing, lowest, damping):
    """beta against the steady state of q'' + c q' + w^2 q = p e^{i W t} evaluated on a grid
    of dropped modes (w from the lowest to 20 times it, c from 0 to the bound) and forcing
    frequencies (0 to W): the largest |H / H_qs - 1| equals beta (at w lowest, c largest, the
    forcing's top), to the grid."""
    from crankdyn.torsion.event_run import truncation_factor

    w = lowest * np.linspace(1.0, 20.0, 400)[:, None, None]
    c = np.linspace(0.0, damping, 41)[None, :, None]
    f = forcing * np.linspace(0.0, 1.0, 101)[None, None, :]
    ratio = np.abs(w**2 / (w**2 - f**2 + 1j * f * c) - 1.0)
    beta = truncation_factor(forcing, lowest, damping)
    assert np.max(ratio) == pytest.approx(beta, rel=1e-12)


def _long_line():
    """A six-throw engine, a flywheel and a propeller on a long shaft subdivided into 190
    elements (197 masses), loss factors as damping: a line like the TVC's subdivided ones."""
    from crankdyn.torsion.events import TabulatedTorque

    names = [f"throw {i}" for i in range(1, 7)]
    masses = [Mass(n, 50.0, damping=20.0) for n in names]
    masses += [Mass("flywheel", 400.0), Mass("propeller", 2000.0, damping=2e3)]
    shafts = [Shaft((a, b), 5e7, loss_factor=0.02) for a, b in itertools.pairwise(names)]
    shafts += [
        Shaft(("throw 6", "flywheel"), 1e8, loss_factor=0.02),
        Shaft(("flywheel", "propeller"), 2e6, loss_factor=0.01, inertia=30.0, elements=190),
    ]
    model = TorsionModel(masses=tuple(masses), shafts=tuple(shafts))
    t = np.linspace(0.0, 0.01, 41)  # a half-sine impact of 50 kN m, 10 ms
    event = TabulatedTorque("propeller", 0.05 + t, 5e4 * np.sin(np.pi * t / 0.01))
    return model, event


def test_subdivided_line_truncated_within_its_bound(monkeypatch):
    """The 197-mass line through a half-sine impact at the propeller, the cut-off 4 x pi / 10 ms:
    a few modes integrated, the element torques at every sample and the peaks of the truncated
    run within the bound of the all-mode run (the impact's kinks at the table's points, every
    dropped mode ringing on its own: a wave along the shaft the quasi-static shape alone would
    miss; observed: at most 0.03 of the bound, the differences at most 8e-4 of each element's
    peak)."""
    model, event = _long_line()
    kwargs = {"max_frequency": 4.0 * np.pi / 0.01, "duration": 0.4}
    run = event_response(model, event, **kwargs)
    assert len(model.masses) > 150 and run.modes_kept < 20
    _all_modes(monkeypatch)
    exact = event_response(model, event, **kwargs)
    bound = np.asarray(run.truncation_torque)
    _within(run, exact, bound)
    ratio = np.max(np.abs(run.torque - exact.torque) / np.maximum(bound, 1e-300)[None, :])
    assert ratio < 0.5  # not trivially loose


def test_the_tvc_truncates_from_its_threshold_on(monkeypatch):
    """Below :data:`crankdyn.tvc.events.EVENT_TRUNCATION_DOFS` degrees of freedom the TVC's runs
    integrate every mode (no cut-off, bound 0, no truncation columns in its tables); from it
    on they truncate at the cut-off and the tables show the modes, cut-off and bound."""
    from crankdyn.tvc.events import EVENT_TRUNCATION_DOFS, _run, truncates

    session = _marine()
    model = session.loaded_model
    assert model.dof_count < EVENT_TRUNCATION_DOFS and not truncates(model)
    te = session.tvc_spec.events[2]  # the ice impact
    args = (model, te, 750 / RPM, session.excitation(), session.orders)
    whole = _run(*args)
    assert whole.cutoff_frequency is None and whole.truncation_error == 0.0
    monkeypatch.setattr("crankdyn.tvc.events.EVENT_TRUNCATION_DOFS", model.dof_count)
    assert truncates(model)
    cut = _run(*args)
    assert cut.cutoff_frequency is not None and 0 < cut.modes_kept < whole.modes_kept
