"""Numerical edge cases (robustness issue, item 4): results stay finite and right, or a clear
error says why. Linkage dead points, change points and singular kinetostatic matrices are tested
in tests/linkage (test_fourbar, test_planar, test_kinetostatics)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.kinematics import piston_kinematics, slider_crank_exact
from crankdyn.crank.pressure import PressureTrace
from crankdyn.engine.model import Engine
from crankdyn.engine.torque import engine_torque
from crankdyn.torsion.modal import natural_modes
from crankdyn.torsion.model import Mass, Shaft, TorsionModel
from crankdyn.torsion.response import steady_state


@pytest.mark.parametrize("lam", [0.9, 0.99, 0.999, 0.999999])
def test_lambda_close_to_one(lam):
    """The rod nearly perpendicular to the axis at 90 deg: every quantity finite, the velocity
    still the derivative of the displacement, the extrema found."""
    g = CrankGeometry(0.1, 0.05, 0.05 / lam)
    res = piston_kinematics(g, 100.0)
    for arr in (res.displacement, res.velocity, res.acceleration, res.rod_angular_acceleration):
        assert np.all(np.isfinite(arr))
    s = res.summary
    assert s.max_acceleration == pytest.approx(0.05 * 100.0**2 * (1 + lam), rel=1e-9)
    assert s.max_rod_angle == pytest.approx(math.asin(lam), rel=1e-12)
    phi = np.linspace(0.1, 1.2, 50)  # away from 90 deg, where the rates grow like 1/cos(beta)
    h = 1e-7
    fd = (
        slider_crank_exact(phi + h, 0.05, 0.05 / lam).displacement
        - slider_crank_exact(phi - h, 0.05, 0.05 / lam).displacement
    ) / (2 * h)
    np.testing.assert_allclose(fd, slider_crank_exact(phi, 0.05, 0.05 / lam).velocity, rtol=1e-6)


@pytest.mark.parametrize("fraction", [0.99, 0.9999, -0.9999])
def test_offset_close_to_its_limit(fraction):
    r, l = 0.05, 0.15
    g = CrankGeometry(0.1, r, l, fraction * (l - r))
    res = piston_kinematics(g, 50.0)
    assert np.all(np.isfinite(res.acceleration))
    s = res.summary
    assert s.stroke > 2 * r
    assert res.displacement.min() >= -1e-12 and res.displacement.max() <= s.stroke * (1 + 1e-12)


@pytest.mark.parametrize("speed", [1e-3, 1e-6])
def test_speeds_near_zero(speed):
    """At a crawl the inertia parts vanish and the torque is the gas torque."""
    engine = Engine.example("vaz2108")
    kin = piston_kinematics(engine.geometry, speed)
    assert np.all(np.isfinite(kin.acceleration))
    assert kin.extrema.max_velocity == pytest.approx(
        kin.extrema.velocity_ratio * kin.extrema.mean_piston_speed
    )
    t = engine_torque(engine, speed, step=math.radians(2))
    assert np.all(np.isfinite(t.total_torque))
    assert np.max(np.abs(t.inertia_torque)) < 1e-6 * np.max(np.abs(t.gas_torque))


def test_pressure_trace_with_a_spike():
    """A one-point knock spike (30 MPa) in a trace: the peak is found, and the mean torque still
    equals Z x indicated work / cycle angle."""
    base = Engine.example("inline6-diesel")
    angle = np.array(base.pressure.crank_angle)
    p = np.array(base.pressure.pressure)
    i = int(np.argmin(np.abs(angle - math.radians(12.0))))
    p[i] = 30e6
    spiky = PressureTrace(angle, p, base.pressure.cycle_angle, "spike.csv")
    engine = dataclasses.replace(base, pressure=spiky)
    t = engine_torque(engine, engine.speed, step=math.radians(0.1))
    assert t.peak_pressure == pytest.approx(30e6)
    expected = engine.cylinders.count * t.indicated_work / engine.cycle_angle
    assert t.mean_torque == pytest.approx(expected, rel=1e-4)
    assert np.all(np.isfinite(t.total_torque))


def _weakly_coupled(epsilon: float) -> TorsionModel:
    """Two identical two-mass systems joined by a weak shaft: two elastic frequencies a relative
    distance of about epsilon apart."""
    k = 1e5
    masses = [Mass(n, 0.5) for n in "ABCD"]
    shafts = [
        Shaft(("A", "B"), k, loss_factor=0.02),
        Shaft(("B", "C"), epsilon * k),
        Shaft(("C", "D"), k, loss_factor=0.02),
    ]
    return TorsionModel(tuple(masses), tuple(shafts), name="weakly coupled")


@pytest.mark.parametrize("epsilon", [1e-3, 1e-6])
def test_nearly_equal_natural_frequencies(epsilon):
    """Eigen, Holzer and transfer-matrix solvers separate two nearly equal frequencies and agree;
    the damped response at them is finite."""
    model = _weakly_coupled(epsilon)
    eig = natural_modes(model).frequencies_hz
    hol = natural_modes(model, solver="holzer").frequencies_hz
    tra = natural_modes(model, solver="transfer").frequencies_hz
    close = eig[-2:]
    assert 0 < (close[1] - close[0]) / close[1] < 10 * epsilon
    np.testing.assert_allclose(hol, eig, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(tra, eig, rtol=1e-9, atol=1e-9)
    w = 2 * math.pi * np.linspace(close[0] * 0.99, close[1] * 1.01, 201)
    forcing = np.zeros(4, dtype=complex)
    forcing[0] = 1.0
    x = steady_state(model, w, forcing)
    assert np.all(np.isfinite(x))
