"""The engine's speed governor in a clutch engagement (crankdyn.torsion.event_governor),
against independent methods:

- a two-inertia line (an engine, a load, the clutch's shaft between them) closing its clutch
  with the engine on a sampled PI governor limited by a rising torque curve, integrated here by
  scipy's ``solve_ivp`` (RK45, rtol 1e-11) between the governor's samples, the lock found by its
  event location and the locked line continued with the shaft carrying the friction torque of
  that instant (VDI 2241 Blatt 1's engagement, written out here); the governor's law written
  out from its statement (Altosole et al. 2019; ISO 3046-4:2009's droop): the speeds at every
  kept sample, the lock instant and the held torques agree to the reference's tolerance;
- the steady speed of a droop governor: droop x load, closed form (ISO 3046-4:2009: the speed
  settles delta w_ref T / T_ref below the set speed);
- the torque limit: the governed torque never exceeds the torque curve at the sensed speed.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.event_governor import Governor
from crankdyn.torsion.event_run import event_response
from crankdyn.torsion.events import ClutchEngagement
from crankdyn.torsion.sources import HarmonicSource, LoadLaw

J1, J2, K = 10.0, 15.0, 2.0e5  # kg m^2, kg m^2, N m/rad
CAPACITY, RISE = 5000.0, 1.0  # N m, s
W0 = 100.0  # rad/s: the engine before the clutch closes, the load at rest
CURVE = ([50.0, 150.0], [800.0, 1600.0])  # rad/s, N m: the engine's torque limit
GAIN, TI, DT = 10.0, 0.5, 0.01


def two_inertia() -> TorsionModel:
    return TorsionModel(
        masses=(Mass("engine", J1), Mass("load", J2)), shafts=(Shaft(("engine", "load"), K),)
    )


def reference(t_end: float):
    """The run integrated here (module docstring): (dense speeds, lock time, held torques)."""
    w_ref, t_ref = CURVE[0][-1], max(CURVE[1])
    kp = GAIN * t_ref / w_ref

    def friction(t):
        return CAPACITY * min(t / RISE, 1.0)

    y = np.array([0.0, 0.0, W0, 0.0])  # x1, x2, w1, w2
    locked, delta, lock_time = False, 0.0, None
    integral, held, pieces, torques = None, 0.0, [], []
    t = 0.0
    while t < t_end - 1e-12:
        # the governor's sample at t (the law of crankdyn.torsion.event_governor, written out)
        error = W0 - y[2]
        if integral is None:
            integral = 0.0 - kp * error
        top = float(np.interp(y[2], *CURVE))
        step = kp / TI * error * DT
        want = kp * error + integral + step
        if not ((want > top and error > 0) or (want < 0 and error < 0)):
            integral += step
        held = min(max(kp * error + integral, 0.0), top)
        torques.append(held)
        stop = min(t + DT, t_end)
        while t < stop - 1e-15:
            if locked:

                def rhs(s, z, T=held, d=delta):
                    m = K * (z[0] - z[1] - d)
                    return [z[2], z[3], (T - m) / J1, m / J2]

                sol = solve_ivp(rhs, (t, stop), y, rtol=1e-11, atol=1e-11, dense_output=True)
                pieces.append(sol)
                y, t = sol.y[:, -1], stop
                continue

            def rhs(s, z, T=held):
                f = friction(s)
                return [z[2], z[3], (T - f) / J1, f / J2]

            def meet(s, z):
                return z[2] - z[3]

            meet.terminal = True
            sol = solve_ivp(
                rhs, (t, stop), y, rtol=1e-11, atol=1e-11, dense_output=True, events=meet
            )
            pieces.append(sol)
            y, t = sol.y[:, -1], float(sol.t[-1])
            if sol.status == 1:  # the speeds meet: locked, the shaft carrying the friction
                locked, lock_time = True, t
                delta = y[0] - y[1] - friction(t) / K
                y = sol.y_events[0][0]
    return pieces, lock_time, np.array(torques)


def speeds_at(pieces, times):
    out = np.empty((times.size, 2))
    for k, tt in enumerate(times):
        sol = next(p for p in pieces if p.t[0] - 1e-12 <= tt <= p.t[-1] + 1e-12)
        out[k] = sol.sol(min(max(tt, sol.t[0]), sol.t[-1]))[2:]
    return out


@pytest.fixture(scope="module")
def governed():
    event = ClutchEngagement(
        ("engine", "load"),
        CAPACITY,
        RISE,
        speeds=(W0, 0.0),
        governor=Governor(CURVE, gain=GAIN, integral_time=TI, sample_time=DT),
    )
    return event_response(two_inertia(), event, duration=1.5)


def test_the_governed_clutch_engagement_equals_the_integration_by_solve_ivp(governed):
    pieces, lock_time, torques = reference(1.5)
    assert len(governed.switches) == 1 and lock_time is not None
    locked_at = float(governed.switches[0].split(" at ")[1].rstrip(" s"))
    assert locked_at == pytest.approx(lock_time, abs=1e-5)  # the switch text's 6 digits
    assert governed.loaded_from == pytest.approx(lock_time, abs=1e-9)
    times = np.asarray(governed.time)
    want = speeds_at(pieces, times)
    # the reference's rtol 1e-11 over 150 samples; the speeds are of order 100 rad/s
    np.testing.assert_allclose(np.asarray(governed.mass_speed), want, rtol=0, atol=1e-6)
    # the held torques at the samples (the torque at each sample instant holds until the next)
    samples = np.arange(torques.size) * DT
    held = np.interp(samples + DT / 2, times, np.asarray(governed.engine_torque))
    np.testing.assert_allclose(held, torques, rtol=0, atol=1e-6 * max(CURVE[1]))
    # the engine was on its torque limit while the clutch took the load up
    assert np.any(np.isclose(torques, np.interp(want[np.searchsorted(times, samples), 0], *CURVE)))


def test_the_governed_torque_never_exceeds_the_torque_curve(governed):
    times = np.asarray(governed.time)
    speed = np.asarray(governed.mass_speed)[:, 0]
    torque = np.asarray(governed.engine_torque)
    samples = np.arange(0.0, 1.5 - 1e-9, DT)
    at = np.searchsorted(times, samples - 1e-12)  # the kept sample at each sample instant
    assert np.allclose(times[at], samples, rtol=0, atol=1e-12)
    held = torque[np.minimum(at + 1, times.size - 1)]  # what it holds from that instant
    assert np.all(held <= np.interp(speed[at], *CURVE) * (1 + 1e-12))
    assert np.all(torque >= 0.0)


def test_a_droop_governor_settles_droop_times_load_below_its_set_speed():
    load, droop = 500.0, 0.05  # N m at the load mass, 5 % droop
    curve = ([0.0, 200.0], [2000.0, 2000.0])  # w_ref = 200 rad/s, T_ref = 2000 N m
    source = HarmonicSource("load", [1.0], amplitude=[0.0], load=LoadLaw(load, 50.0, exponent=0.0))
    model = TorsionModel(
        masses=(Mass("engine", J1), Mass("load", J2)),
        shafts=(Shaft(("engine", "load"), K, damping=200.0),),
        sources=(source,),
    )
    event = ClutchEngagement(
        ("engine", "load"),
        CAPACITY,
        0.2,
        speeds=(W0, 0.0),
        governor=Governor(curve, droop=droop, gain=GAIN, integral_time=TI),
    )
    run = event_response(model, event, duration=12.0)
    settled = float(np.asarray(run.mass_speed)[-1, 0])
    expected = W0 - droop * 200.0 * load / 2000.0  # ISO 3046-4: droop x load
    # the slowest closed-loop pole decays as exp(-t / 0.6 s) or faster: after 11 s the rest of
    # the 16 rad/s dip is below 1e-6 of it
    assert settled == pytest.approx(expected, abs=2e-4)
    assert float(np.asarray(run.engine_torque)[-1]) == pytest.approx(load, rel=1e-5)
