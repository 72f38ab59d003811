"""The short-circuit air-gap torque of :mod:`crankdyn.torsion.short_circuit` against an
independent route: the phase currents from the circuit equation and the air-gap power summed
over the phases, numerically.

- Constant flux linkages (every time constant infinite): each faulted phase is an inductance
  L = X''_d / omega behind its EMF, so v = L di/dt (Faraday's law) with no current before the
  fault; the currents are integrated numerically (cumulative trapezoidal rule, 400 001 points
  over two periods: the rule's error is below 1e-9 of the peak), the power sum_k v_k i_k taken
  on the base 3 E_b I_b (rms), and the torque the power over the synchronous speed (1 per
  unit), times T_b. Three-phase fault at several fault instants (the closed form holds for
  every instant); line-to-line fault, a and b shorted, the loop inductance 2 L.
- With the decays: the textbook currents of the module docstring (the alternating component
  falling with e(t), the aperiodic with T_a) times EMFs falling with e(t), summed over the
  phases numerically at random instants.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.torsion.short_circuit import envelope, short_circuit_torque

W = 2.0 * math.pi * 50.0  # rad/s
TB = 4496.1  # N m, T_r / cos(phi)
X2 = 0.12  # X''_d (per unit)
E = 1.1  # the internal EMF (per unit): the torque goes with E^2


def _cumulative_trapezoid(y: np.ndarray, t: np.ndarray) -> np.ndarray:
    out = np.zeros_like(y)
    out[1:] = np.cumsum(0.5 * (y[1:] + y[:-1]) * np.diff(t))
    return out


def _closed(t, phases, angle=0.0, **decays):
    data = {"xd2": X2, "xd1": X2, "xd": X2, "td2": 1e30, "td1": 1e30, "ta": 1e30} | decays
    return short_circuit_torque(
        t, phases=phases, frequency=W, base_torque=TB, voltage=E, angle=angle, **data
    )


@pytest.mark.parametrize("alpha", [0.0, 0.4, 1.3, 2.9])
def test_three_phase_torque_from_the_circuit_equation(alpha):
    t = np.linspace(0.0, 0.04, 400_001)
    inductance = X2 / W
    power = np.zeros_like(t)
    for k in range(3):
        v = math.sqrt(2.0) * E * np.sin(W * t + alpha - 2.0 * math.pi * k / 3.0)
        i = _cumulative_trapezoid(v / inductance, t)  # v = L di/dt, i(0) = 0
        power += v * i
    torque = TB * power / 3.0  # base 3 E_b I_b, speed 1 per unit
    peak = TB * E * E / X2
    assert np.max(np.abs(torque - _closed(t, 3))) < 1e-9 * peak


@pytest.mark.parametrize("alpha", [0.0, 0.7, -1.1])
def test_two_phase_torque_from_the_circuit_equation(alpha):
    t = np.linspace(0.0, 0.04, 400_001)
    inductance = X2 / W
    v_ab = math.sqrt(3.0) * math.sqrt(2.0) * E * np.sin(W * t + alpha)  # line-to-line EMF
    i = _cumulative_trapezoid(v_ab / (2.0 * inductance), t)  # the loop a-b: 2 L di/dt = v_ab
    torque = TB * v_ab * i / 3.0
    peak = TB * E * E / X2
    assert np.max(np.abs(torque - _closed(t, 2, alpha))) < 1e-9 * peak


def test_decaying_torques_are_the_phase_power_of_the_textbook_currents():
    """The alternating current falls with e(t), the aperiodic with T_a, the EMF with e(t)."""
    decays = {"xd1": 0.25, "xd": 2.0, "td2": 0.02, "td1": 0.4, "ta": 0.05}
    rng = np.random.default_rng(36)
    t = np.sort(rng.uniform(0.0, 0.5, 400))
    env = envelope(t, X2, 0.25, 2.0, 0.02, 0.4)
    dc = np.exp(-t / 0.05)
    peak = TB * E * E / X2
    for alpha in rng.uniform(-math.pi, math.pi, 3):
        power = np.zeros_like(t)
        for k in range(3):
            theta = alpha - 2.0 * math.pi * k / 3.0
            v = math.sqrt(2.0) * E * env * np.sin(W * t + theta)
            i = math.sqrt(2.0) * E / X2 * (dc * math.cos(theta) - env * np.cos(W * t + theta))
            power += v * i
        got = _closed(t, 3, **decays)
        assert np.max(np.abs(TB * power / 3.0 - got)) < 1e-12 * peak
        v_ab = math.sqrt(6.0) * E * env * np.sin(W * t + alpha)
        ac = env * np.cos(W * t + alpha)
        i_ab = math.sqrt(6.0) * E / (2.0 * X2) * (dc * math.cos(alpha) - ac)
        got2 = _closed(t, 2, alpha, **decays)
        assert np.max(np.abs(TB * v_ab * i_ab / 3.0 - got2)) < 1e-12 * peak
