"""Transient events against closed forms and an independent integration.

- A torque suddenly applied to an undamped two-mass line: the shaft torque is
  T J2 / (J1 + J2) (1 - cos omega t), its peak twice the static torque (W. T. Thomson, *Theory
  of Vibration with Applications*, 4th ed., 1993, sec. 4.2, the response to a step).
- A torque suddenly applied to a damped single-degree-of-freedom line (a mass on a grounded
  shaft): x(t) = (T / k) [1 - e^(-zeta omega t) (cos omega_d t + zeta / sqrt(1 - zeta^2)
  sin omega_d t)] (Thomson 1993, sec. 4.2).
- A friction clutch engaging (VDI 2241 Blatt 1's model: the friction torque rising linearly,
  Coulomb friction while slipping, locked when the speeds meet) against scipy's ``solve_ivp``
  (DOP853, rtol 1e-10) with its terminal event at the lock: an independent integration of the
  same equations, written here from the masses and stiffnesses.
- The exact integrator's energy: an undamped line keeps its energy over 10^5 steps.

The integrator is exact for a piecewise-linear forcing, so the closed forms hold to rounding
(tolerances 1e-9 of the static torque); the clutch's tolerance is the reference's own error at
rtol 1e-10 (1e-6 of the peak torque, 1e-9 s on the lock).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.event_run import event_response
from crankdyn.torsion.events import ClutchEngagement, StepTorque
from crankdyn.torsion.integrator import modal_system


def test_thomson1993_step_torque_two_masses_twice_static():
    """Undamped free two-mass line, 100 N m at mass a from t = 0: peak 2 x 60 N m."""
    j1, j2, k, torque = 2.0, 3.0, 1e4, 100.0
    line = TorsionModel(masses=(Mass("a", j1), Mass("b", j2)), shafts=(Shaft(("a", "b"), k),))
    run = event_response(line, StepTorque("a", torque), duration=0.5, max_samples=100_000)
    static = torque * j2 / (j1 + j2)  # 60 N m: the torque that accelerates b with the line
    omega = math.sqrt(k * (j1 + j2) / (j1 * j2))
    exact = static * (1.0 - np.cos(omega * run.time))
    assert np.max(np.abs(run.torque[:, 0] - exact)) < 1e-9 * static
    assert run.max_torque[0] == pytest.approx(2.0 * static, rel=1e-9)
    # the peak is found between the samples: at t = pi / omega (+ whole periods, undamped)
    periods = (run.max_time[0] - math.pi / omega) / (2.0 * math.pi / omega)
    assert periods == pytest.approx(round(periods), abs=1e-6)
    # the line as a whole accelerates at T / (J1 + J2)
    mean = run.speed[-1]
    assert mean == pytest.approx(torque / (j1 + j2) * run.time[-1], rel=1e-9)


def test_thomson1993_suddenly_applied_torque_with_damping():
    """A mass on a grounded shaft with viscous damping (zeta = 0.05): the step response."""
    j, k, c, torque = 1.5, 6e4, 30.0, 250.0
    line = TorsionModel(masses=(Mass("m", j),), shafts=(Shaft(("ground", "m"), k, damping=c),))
    run = event_response(line, StepTorque("m", torque, start=0.01), duration=0.6)
    omega = math.sqrt(k / j)
    zeta = c / (2.0 * math.sqrt(k * j))
    wd = omega * math.sqrt(1.0 - zeta**2)
    tau = np.clip(run.time - 0.01, 0.0, None)
    x = (torque / k) * (
        1.0
        - np.exp(-zeta * omega * tau)
        * (np.cos(wd * tau) + zeta / math.sqrt(1.0 - zeta**2) * np.sin(wd * tau))
    )
    # the shaft carries -k x (its torque from ground to the mass: the mass twisted ahead)
    assert np.max(np.abs(-run.torque[:, 0] - k * x)) < 1e-9 * torque
    overshoot = torque * (1.0 + math.exp(-zeta * math.pi / math.sqrt(1.0 - zeta**2)))
    assert -run.min_torque[0] == pytest.approx(overshoot, rel=1e-9)


def _clutch_reference(j, k, c, t_max, rise, w0, t_end, t_eval):
    """The clutch engagement integrated by solve_ivp: slip until the speeds meet (terminal
    event), then locked with the clutch shaft carrying the friction torque of that instant."""
    n = len(j)

    def matrices(with_clutch):
        kk, cc = np.zeros((n, n)), np.zeros((n, n))
        for e, (a, b) in enumerate(((0, 1), (1, 2), (2, 3))):
            if e == 1 and not with_clutch:
                continue
            for m, v in ((kk, k[e]), (cc, c[e])):
                m[a, a] += v
                m[b, b] += v
                m[a, b] -= v
                m[b, a] -= v
        return kk, cc

    ks, cs = matrices(False)
    kl, cl = matrices(True)

    def friction(t):
        return t_max * min(t / rise, 1.0)

    def slip(t, y):
        f = np.zeros(n)
        f[1], f[2] = -friction(t), friction(t)
        return np.concatenate([y[n:], (f - ks @ y[:n] - cs @ y[n:]) / j])

    def meet(t, y):
        return y[n + 1] - y[n + 2]

    meet.terminal, meet.direction = True, -1
    y0 = np.concatenate([np.zeros(n), w0])
    first = solve_ivp(
        slip,
        (0.0, t_end),
        y0,
        method="DOP853",
        rtol=1e-10,
        atol=1e-12,
        events=meet,
        t_eval=t_eval[t_eval < 2.0],
    )
    t_lock = float(first.t_events[0][0])
    y_lock = first.y_events[0][0]
    first = solve_ivp(
        slip,
        (0.0, t_lock),
        y0,
        method="DOP853",
        rtol=1e-10,
        atol=1e-12,
        t_eval=t_eval[t_eval < t_lock],
    )
    delta = y_lock[1] - y_lock[2] - friction(t_lock) / k[1]

    def locked(t, y):
        f = np.zeros(n)
        f[1], f[2] = k[1] * delta, -k[1] * delta
        return np.concatenate([y[n:], (f - kl @ y[:n] - cl @ y[n:]) / j])

    after = t_eval[t_eval > t_lock]
    second = solve_ivp(
        locked, (t_lock, t_end), y_lock, method="DOP853", rtol=1e-10, atol=1e-12, t_eval=after
    )
    x1, x2 = first.y[:n].T, second.y[:n].T
    t1 = first.t
    torque1 = np.stack(
        [
            k[0] * (x1[:, 0] - x1[:, 1]),
            np.array([friction(t) for t in t1]),
            k[2] * (x1[:, 2] - x1[:, 3]),
        ],
        axis=1,
    )
    torque2 = np.stack(
        [
            k[0] * (x2[:, 0] - x2[:, 1]),
            k[1] * (x2[:, 1] - x2[:, 2] - delta),
            k[2] * (x2[:, 2] - x2[:, 3]),
        ],
        axis=1,
    )
    return t_lock, np.concatenate([t1, second.t]), np.concatenate([torque1, torque2])


def test_clutch_engagement_against_solve_ivp():
    """Engine side at 100 rad/s, driven side at rest; 300 N m rising over 0.2 s."""
    j = np.array([5.0, 1.0, 2.0, 10.0])
    k = (2e5, 5e5, 1e5)
    c = (5.0, 2.0, 5.0)
    model = TorsionModel(
        masses=tuple(
            Mass(name, v) for name, v in zip(("engine", "a", "b", "load"), j, strict=True)
        ),
        shafts=(
            Shaft(("engine", "a"), k[0], damping=c[0]),
            Shaft(("a", "b"), k[1], damping=c[1]),
            Shaft(("b", "load"), k[2], damping=c[2]),
        ),
    )
    event = ClutchEngagement(("a", "b"), 300.0, 0.2, speeds=(100.0, 0.0))
    run = event_response(model, event, duration=1.8)
    assert len(run.switches) == 1 and run.switches[0].startswith("slip -> locked")
    t_lock, times, ref = _clutch_reference(
        j, k, c, 300.0, 0.2, np.array([100.0, 100.0, 0.0, 0.0]), 1.8, run.time
    )
    lock = float(run.switches[0].split(" at ")[1].split()[0])
    assert lock == pytest.approx(t_lock, abs=1e-5)  # printed to 6 digits
    keep = np.isin(run.time, times) & (np.abs(run.time - t_lock) > 1e-9)
    mine = run.torque[keep]
    theirs = ref[np.searchsorted(times, run.time[keep])]
    peak = np.max(np.abs(ref), axis=0)
    assert np.all(np.max(np.abs(mine - theirs), axis=0) < 1e-6 * peak)
    # the friction torque's full value is the clutch's largest, and the speeds meet at lock
    assert run.max_torque[1] == pytest.approx(300.0, rel=1e-12)


def test_undamped_line_keeps_its_energy():
    """Free vibration of an undamped three-mass line over 1e5 steps: energy to 1e-9."""
    m = np.array([1.0, 2.0, 0.5])
    k = np.array([[3e4, -3e4, 0.0], [-3e4, 5e4, -2e4], [0.0, -2e4, 2e4]])
    system = modal_system(m, k, np.zeros((3, 3)))
    x0, v0 = np.array([0.01, 0.0, -0.02]), np.array([1.0, 0.0, 0.0])
    count = 100_000
    u, g = system.modal_forcing(np.zeros((count + 1, 3)))
    x, v = system.to_physical(system.run(system.to_modal(x0, v0), u, g, 1e-3))

    def energy(x, v):  # the strain energy from the twists (x grows with the rotation)
        twist = np.stack([x[..., 0] - x[..., 1], x[..., 1] - x[..., 2]], axis=-1)
        return 0.5 * np.sum(m * v * v, axis=-1) + 0.5 * np.sum(
            np.array([3e4, 2e4]) * twist**2, axis=-1
        )

    e0 = energy(x0, v0)
    assert np.max(np.abs(energy(x, v) - e0)) < 1e-9 * e0
