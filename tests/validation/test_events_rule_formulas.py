"""The short-circuit torque and the propeller ice torque against their formulas worked by hand.

- Short circuit (IEC 60034-4-1:2018's current components, the constant-flux-linkage torque of
  :mod:`crankdyn.torsion.short_circuit`): a 565 kW, 1500 rpm, 50 Hz generator (T_r = 3596.9
  N m, cos phi = 0.8) with X''_d = 0.12, X'_d = 0.25, X_d = 2.0, T''_d = 20 ms, T'_d = 0.4 s,
  T_a = 50 ms; the torque at t = 5 ms and 12 ms worked step by step below (six digits).
- Two-phase fault without decay: the peak 3 sqrt(3) / 4 = 1.29904 times T_b / X''_d at
  omega t = 2 pi / 3 (the classic factor 1.3).
- Ice (Finnish-Swedish Ice Class Rules 2017 ch. 6, IACS UR I3): Q_max of an open propeller,
  D = 4.0 m > D_limit = 1.8 x 1.5 = 2.7 m (class IA), worked by hand; the milling sequence's
  N_Q = 2 H_ice = 3 revolutions and Z N_Q = 12 impacts; case 1 peaks of 0.75 Q_max.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.torsion.events import IceImpact, ShortCircuit
from crankdyn.torsion.ice import design_ice_torque, ice_torque, milling_revolutions
from crankdyn.torsion.short_circuit import short_circuit_torque

MACHINE = {
    "xd2": 0.12,
    "xd1": 0.25,
    "xd": 2.0,
    "td2": 0.02,
    "td1": 0.4,
    "ta": 0.05,
}


def test_three_phase_short_circuit_by_hand():
    """T_b = 3596.9 / 0.8 = 4496.1 N m; T_b / X''_d = 37 467.7 N m."""
    tr = 565e3 / (1500 * 2 * math.pi / 60)  # 3596.90 N m
    tb_x = tr / 0.8 / 0.12  # 37 467.7 N m
    # t = 5 ms: omega t = pi / 2, sin = 1
    # e = 0.12 [(8.33333 - 4) e^-0.25 + (4 - 0.5) e^-0.0125 + 0.5]
    #   = 0.12 [4.33333 x 0.778801 + 3.5 x 0.987578 + 0.5] = 0.12 x 7.331328 = 0.879759
    # dc = e^-0.1 = 0.904837; T = 37 467.7 x 0.879759 x 0.904837 = 29 825.8 N m
    e1 = 0.12 * (4.333333 * 0.778801 + 3.5 * 0.987578 + 0.5)
    assert e1 == pytest.approx(0.879759, abs=2e-6)
    hand_5ms = tb_x * e1 * 0.904837
    # t = 12 ms: omega t = 1.2 pi, sin = -0.587785
    # e = 0.12 [4.33333 e^-0.6 + 3.5 e^-0.03 + 0.5] = 0.12 [2.378185 + 3.396559 + 0.5]
    #   = 0.752969
    # dc = e^-0.24 = 0.786628; T = 37 467.7 x 0.752969 x 0.786628 x -0.587785 = -13 044.4 N m
    hand_12ms = tb_x * 0.752969 * 0.786628 * -0.587785
    got = short_circuit_torque(
        [0.005, 0.012], phases=3, frequency=2 * math.pi * 50, base_torque=tr / 0.8, **MACHINE
    )
    assert got[0] == pytest.approx(hand_5ms, rel=2e-6)
    assert got[1] == pytest.approx(hand_12ms, rel=2e-6)
    # the event acts against the rotation
    event = ShortCircuit("alternator", rated_torque=tr, line_frequency=50.0, **MACHINE)
    assert float(event.torque(np.array([0.005]))[0]) == pytest.approx(-hand_5ms, rel=2e-6)


def test_two_phase_short_circuit_peak_factor_1_3():
    """Without decay the two-phase torque T_b / X''_d (sin x - sin 2x / 2) peaks at 1.29904."""
    t = np.linspace(0.0, 0.02, 200_001)
    got = short_circuit_torque(
        t,
        phases=2,
        frequency=2 * math.pi * 50,
        base_torque=1000.0,
        xd2=0.1,
        xd1=0.1,
        xd=0.1,
        td2=1e9,
        td1=1e9,
        ta=1e9,
    )
    assert np.max(got) / 10_000.0 == pytest.approx(3 * math.sqrt(3) / 4, abs=1e-9)
    assert t[np.argmax(got)] == pytest.approx(1 / 150, abs=1e-7)  # omega t = 2 pi / 3


def test_fsicr2017_design_ice_torque_by_hand():
    """Open propeller D = 4.0 m, d = 1.2 m, P_0.7 = 3.2 m, t_0.7 = 0.12 m, n = 2 rps, IA
    (H_ice = 1.5 m): D > D_limit = 2.7 m, so
    Q_max = 20.7 (1 - 0.3) (0.8)^0.16 (0.03)^0.6 (8)^0.17 4^1.9 1.5^1.1 kN m.
    (0.8)^0.16 = 0.964927, (0.03)^0.6 = 0.121976, 8^0.17 = 1.424050, 4^1.9 = 13.928809,
    1.5^1.1 = 1.562070: Q_max = 20.7 x 0.7 x 0.964927 x 0.121976 x 1.424050 x 13.928809
    x 1.562070 = 52.8415 kN m."""
    hand = 20.7 * 0.7 * 0.964927 * 0.121976 * 1.424050 * 13.928809 * 1.562070
    assert hand == pytest.approx(52.8415, abs=5e-4)
    q = design_ice_torque(
        diameter=4.0,
        hub_diameter=1.2,
        pitch=3.2,
        thickness=0.12,
        speed=4 * math.pi,
        ice_thickness=1.5,
    )
    # the factors to 6 decimals: relative error at most 0.5e-6 sum(1 / factor) = 5.3e-6
    assert q / 1e3 == pytest.approx(hand, rel=6e-6)
    # a smaller propeller (D = 2.5 m <= 2.7 m): 10.9 (1 - 0.3) (0.8)^0.16 (t/D)^0.6 (nD)^0.17 D^3
    small = design_ice_torque(
        diameter=2.5,
        hub_diameter=0.75,
        pitch=2.0,
        thickness=0.075,
        speed=4 * math.pi,
        ice_thickness=1.5,
    )
    hand_small = 10.9 * 0.7 * 0.964927 * 0.121976 * 5.0**0.17 * 2.5**3
    assert small / 1e3 == pytest.approx(hand_small, rel=6e-6)


def test_fsicr2017_ice_sequence_impacts():
    """Case 1, Z = 4, N_Q = 2 x 1.5 = 3 revolutions: 12 half-sine impacts of 0.75 Q_max over
    90 deg each, the blades 90 deg apart (back to back), none after the third revolution."""
    assert milling_revolutions(1.5) == 3.0
    phi = np.radians(np.arange(0.0, 5 * 360.0, 0.5))
    q = ice_torque(phi, q_max=1.0, case=1, blades=4, revolutions=3.0)
    peaks = np.radians(45.0 + 90.0 * np.arange(12))
    assert ice_torque(peaks, q_max=1.0, case=1, blades=4, revolutions=3.0) == pytest.approx(
        np.full(12, 0.75), abs=1e-12
    )
    assert np.all(q[phi >= np.radians(3 * 360.0 + 1e-9)] == 0.0)
    # the mean torque of the sequence: 0.75 x 2 / pi over every angle of it
    inside = phi < np.radians(3 * 360.0)
    assert np.mean(q[inside]) == pytest.approx(0.75 * 2 / math.pi, rel=1e-4)
    # case 2: alpha_i = 135 deg, consecutive blades overlap by 45 deg
    q2 = ice_torque(np.radians([100.0]), q_max=1.0, case=2, blades=4, revolutions=3.0)
    hand = math.sin(math.radians(100 * 180 / 135)) + math.sin(math.radians(10 * 180 / 135))
    assert float(q2[0]) == pytest.approx(hand, rel=1e-12)
    event = IceImpact("propeller", q_max=2e5, blades=4, revolutions=3.0, speed=2 * math.pi)
    assert len(event.breakpoints()) == 24  # the start and end of 12 impacts
