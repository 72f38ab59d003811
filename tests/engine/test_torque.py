"""Engine torque: identities (mean torque x cycle = Z W_i), order content, journal torques."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.indicated import indicated_work
from crankdyn.crank.masses import Masses
from crankdyn.crank.pressure import ATMOSPHERE, PressureTrace
from crankdyn.crank.pressure_model import WiebePressureModel, default_pressure
from crankdyn.engine.model import Cylinders, Engine
from crankdyn.engine.torque import engine_torque, journal_torques
from crankdyn.errors import InputError


@pytest.mark.parametrize("name", ["inline6-diesel", "vaz2108", "v8-crossplane", "single-cylinder"])
def test_mean_torque_times_cycle_is_indicated_work(name):
    """oint M dtheta = Z oint p dV (M dtheta = P dx; the inertia and crankcase parts close to
    zero). The mean torque is taken on a 0.1 deg grid, the work on the trace refined to
    0.05 deg; both rules are second-order accurate at the trace's kinks, which bounds their
    difference near 1e-6 of the work (seen: 4e-7 for the 76-point Mendes trace)."""
    eng = Engine.example(name)
    t = engine_torque(eng, eng.speed, step=math.radians(2))
    work = indicated_work(default_pressure(eng), eng.geometry)
    assert t.mean_torque * eng.cycle_angle == pytest.approx(eng.cylinders.count * work, rel=2e-6)
    assert t.indicated_power == pytest.approx(t.mean_torque * eng.speed, rel=1e-12)


def test_two_stroke_identity():
    geometry = CrankGeometry(bore=0.1, crank_radius=0.06, rod_length=0.24)
    trace = WiebePressureModel(compression_ratio=15, peak_pressure=9e6).trace(
        geometry, "two-stroke"
    )
    eng = Engine(
        name="two-stroke twin",
        geometry=geometry,
        cylinders=Cylinders(2, (1, 2), cycle="two-stroke"),
        masses=Masses(reciprocating=2.0, rotating=2.5),
        pressure=trace,
    )
    t = engine_torque(eng, 150.0, step=math.radians(1))
    work = indicated_work(trace, geometry)
    assert t.mean_torque * 2 * math.pi == pytest.approx(2 * work, rel=2e-6)
    assert t.crank_angle[-1] == pytest.approx(2 * math.pi)


def test_inertia_torque_averages_to_zero_and_keeps_only_firing_orders():
    """Inertia torque of an even-firing inline 6: zero mean, and only orders that are multiples
    of 3 per revolution survive (the others cancel between the cylinders)."""
    eng = Engine.example("inline6-diesel")
    t = engine_torque(eng, 250.0, step=math.radians(0.5))
    m = t.inertia_torque[:-1]  # 1440 points over two revolutions
    spectrum = np.abs(np.fft.rfft(m)) / m.size
    scale = spectrum.max()
    assert abs(np.mean(m)) < 1e-12 * np.max(np.abs(m))
    orders = np.arange(spectrum.size) / 2.0  # index k = order k/2 per revolution
    keep = np.isclose(np.mod(orders, 3.0), 0.0)
    assert np.all(spectrum[~keep] < 1e-12 * scale)


def test_inline4_inertia_torque_leading_term():
    """Inline 4, flat crank, no gas force, long rods: the single-cylinder inertia torque
    m_j R^2 w^2 [lambda/4 sin(phi) - 1/2 sin(2 phi) - 3 lambda/4 sin(3 phi) - ...] adds to
    -2 m_j R^2 w^2 sin(2 theta) up to terms of order lambda."""
    lam, r, m_j, w = 1e-3, 0.04, 0.5, 400.0
    geometry = CrankGeometry(bore=0.08, crank_radius=r, rod_length=r / lam)
    angles = np.linspace(0, 4 * math.pi, 200, endpoint=False)
    eng = Engine(
        name="i4",
        geometry=geometry,
        cylinders=Cylinders(4, (1, 3, 4, 2)),
        masses=Masses(reciprocating=m_j, rotating=0.0),
        pressure=PressureTrace(angles, np.full(200, ATMOSPHERE)),
    )
    t = engine_torque(eng, w, step=math.radians(2))
    c = m_j * r * r * w * w
    np.testing.assert_allclose(t.total_torque, -2 * c * np.sin(2 * t.crank_angle), atol=4 * lam * c)


def test_journal_and_pin_torques():
    eng = Engine.example("vaz2108")
    t = engine_torque(eng, eng.speed, step=math.radians(5))
    np.testing.assert_allclose(t.journal_torque[-1], t.total_torque, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(t.journal_torque[0], t.cylinder_torque[0], rtol=1e-12)
    np.testing.assert_allclose(
        t.journal_torque[2], t.cylinder_torque[:3].sum(axis=0), rtol=1e-12, atol=1e-9
    )
    # pin of throw 3: torque coming in through journal 2 plus half of throw 3's own torque
    np.testing.assert_allclose(
        t.pin_torque[2], t.journal_torque[1] + 0.5 * t.cylinder_torque[2], rtol=1e-12, atol=1e-9
    )
    np.testing.assert_allclose(t.total_torque, t.gas_torque + t.inertia_torque, atol=1e-9)


def test_v_engine_journal_torques_sum_both_banks():
    eng = Engine.example("v8-crossplane")
    t = engine_torque(eng, eng.speed, step=math.radians(5))
    throw1 = t.cylinder_torque[0] + t.cylinder_torque[1]  # cylinders 1 and 2 share throw 1
    np.testing.assert_allclose(t.journal_torque[0], throw1, rtol=1e-12, atol=1e-9)
    assert t.journal_torque.shape[0] == 4


def test_journal_torques_function():
    m = np.array([[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]])
    journal, pin = journal_torques(m)
    np.testing.assert_array_equal(journal, [[1, 2], [4, 6], [9, 12]])
    np.testing.assert_array_equal(pin, [[0.5, 1], [2.5, 4], [6.5, 9]])


def test_effective_torque_and_power():
    eng = Engine.example("vaz2108")
    t = engine_torque(eng, eng.speed, step=math.radians(5), mechanical_efficiency=0.85)
    assert t.mean_effective_torque == pytest.approx(0.85 * t.mean_torque)
    assert t.effective_power == pytest.approx(0.85 * t.indicated_power)
    # seed 000: P (kW) = M n / 9550 with n in rpm; 9550 is 30000/pi = 9549.3 rounded to three
    # significant digits (955 x 10), so it holds to 5 / 9550 = 5.2e-4
    n = eng.speed * 30 / math.pi
    assert t.indicated_power / 1e3 == pytest.approx(t.mean_torque * n / 9550, rel=5.3e-4)
    d = t.to_dict()
    assert d["indicated_power_W"] == pytest.approx(t.indicated_power)
    assert "effective_power_W" in d
    assert "effective_power_W" not in engine_torque(eng, eng.speed).to_dict()


@pytest.mark.parametrize("eta", [0.0, 1.2, -0.5])
def test_bad_mechanical_efficiency(eta):
    eng = Engine.example("vaz2108")
    with pytest.raises(InputError, match="mechanical efficiency"):
        engine_torque(eng, 100.0, mechanical_efficiency=eta)


@settings(max_examples=15, deadline=None)
@given(
    count=st.integers(1, 6),
    lam=st.floats(0.15, 0.38),
    peak=st.floats(4e6, 1.8e7),
    m_j=st.floats(0.2, 3.0),
    rpm=st.floats(800, 6000),
    two_stroke=st.booleans(),
)
def test_random_engines_mean_torque_identity(count, lam, peak, m_j, rpm, two_stroke):
    """Random even-firing inline engines with random synthetic pressure: mean torque x cycle
    angle = Z W_i, and the inertia torque averages to zero."""
    cycle = "two-stroke" if two_stroke else "four-stroke"
    geometry = CrankGeometry(bore=0.09, crank_radius=0.045, rod_length=0.045 / lam)
    trace = WiebePressureModel(compression_ratio=14, peak_pressure=peak).trace(
        geometry, cycle, step=math.radians(0.5)
    )
    eng = Engine(
        name="random",
        geometry=geometry,
        cylinders=Cylinders(count, tuple(range(1, count + 1)), cycle=cycle),
        masses=Masses(reciprocating=m_j, rotating=1.0),
        pressure=trace,
    )
    t = engine_torque(eng, rpm * math.pi / 30, step=math.radians(3))
    work = indicated_work(trace, geometry)
    assert t.mean_torque * eng.cycle_angle == pytest.approx(count * work, rel=2e-6)
    amplitude = np.max(np.abs(t.inertia_torque)) + 1e-30
    assert abs(np.mean(t.inertia_torque[:-1])) < 1e-10 * amplitude


def test_mechanical_efficiency_from_engine_file():
    """[operating] mechanical_efficiency gives the effective torque; the option overrides it."""
    eng = Engine.example("inline6-diesel")
    assert eng.mechanical_efficiency == 0.85
    t = engine_torque(eng, eng.speed, step=math.radians(5))
    assert t.mean_effective_torque == pytest.approx(0.85 * t.mean_torque, rel=1e-12)
    t2 = engine_torque(eng, eng.speed, step=math.radians(5), mechanical_efficiency=0.9)
    assert t2.mean_effective_torque == pytest.approx(0.9 * t2.mean_torque, rel=1e-12)
