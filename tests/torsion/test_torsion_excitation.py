"""Excitation: Fourier coefficients, phase vectors and major orders, speed dependence of the gas
and inertia parts, load curves, harmonic tables, misfire."""

import dataclasses
import math

import numpy as np
import pytest

from crankdyn.engine.forces import crank_train
from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.torsion.excitation import SAMPLES, EngineExcitation, excitation_for
from crankdyn.torsion.excitation_spec import ExcitationSpec, HarmonicTable, LoadCurve
from crankdyn.torsion.orders import (
    check_orders,
    fourier_coefficients,
    major_orders,
    phase_vector_sums,
)

RPM = math.pi / 30


def test_fourier_coefficients_of_a_trig_polynomial():
    theta = np.arange(720) * (4 * math.pi / 720)
    f = 3.0 + 2.0 * np.cos(0.5 * theta - 0.3) + 0.7 * np.sin(3.0 * theta)
    c = fourier_coefficients(f, [0.5, 1.0, 3.0], "four-stroke")
    assert c == pytest.approx([2.0 * np.exp(-0.3j), 0.0, -0.7j], abs=1e-12)


def test_orders_must_fit_the_cycle():
    assert check_orders([0.5, 1.5], "four-stroke").tolist() == [0.5, 1.5]
    with pytest.raises(InputError, match="does not fit the two-stroke cycle"):
        check_orders([0.5], "two-stroke")
    with pytest.raises(InputError, match="must be positive"):
        check_orders([0.0], "four-stroke")
    with pytest.raises(InputError, match="distinct"):
        check_orders([1.0, 1.0], "four-stroke")


def test_major_orders_of_an_inline_six():
    """Even firing, Z = 6, four-stroke: the major orders are the multiples of Z/2 = 3."""
    engine = Engine.example("inline6-diesel")
    orders = np.arange(1, 25) * 0.5
    major = major_orders(engine.cylinders.firing_angles, orders)
    assert orders[major].tolist() == [3.0, 6.0, 9.0, 12.0]
    sums = phase_vector_sums(engine.cylinders.firing_angles, orders)
    assert sums[major] == pytest.approx(6.0)
    assert np.all(sums[~major] < 1e-9)


@pytest.fixture(scope="module")
def diesel():
    engine = Engine.example("inline6-diesel")
    return engine, EngineExcitation(engine)


def test_harmonics_equal_the_crank_train_torque(diesel):
    """The coefficients rebuild every cylinder's torque of crankdyn.engine.forces at a speed."""
    engine, ex = diesel
    w = 1800 * RPM
    orders = np.arange(1, 1001) * 0.5  # the trace's kinks need many orders
    c = ex.harmonics([w], orders)[0]  # (Q, Z)
    theta = np.linspace(0.0, 4 * math.pi, 97)[:-1]
    train = crank_train(engine, w, theta)
    torque = train.tangential * engine.geometry.crank_radius
    rebuilt = np.real(np.exp(1j * np.outer(theta, orders)) @ c).T
    fluctuation = torque - torque.mean(axis=1, keepdims=True)
    rebuilt -= rebuilt.mean(axis=1, keepdims=True)
    assert np.max(np.abs(rebuilt - fluctuation)) < 1e-3 * np.max(np.abs(torque))


def test_phase_vector_rule(diesel):
    """c_q,i = c_q,1 exp(-i q Phi_i) for identical cylinders (seed 003 section 4.2)."""
    engine, ex = diesel
    orders = np.arange(1, 25) * 0.5
    c = ex.harmonics([2000 * RPM], orders)[0]
    phi = np.asarray(engine.cylinders.firing_angles)
    expected = c[:, :1] * np.exp(-1j * np.outer(orders, phi))
    # firing angles on the 0.1 deg analysis grid: exact to rounding
    assert c == pytest.approx(expected, rel=1e-9, abs=1e-11 * np.abs(c).max())


def test_inertia_part_scales_with_speed_squared_and_has_integer_orders(diesel):
    _, ex = diesel
    orders = np.arange(1, 13) * 0.5
    _, i1 = ex.parts([1000 * RPM], orders)
    _, i2 = ex.parts([2000 * RPM], orders)
    assert i2 == pytest.approx(4 * i1, rel=1e-12, abs=1e-12)
    half = orders % 1 != 0
    assert np.all(np.abs(i1[0, half]) < 1e-9 * np.abs(i1).max())


def test_load_curve_scales_the_absolute_pressure(diesel):
    engine, _ = diesel
    peak = engine.pressure.peak[0]
    curve = LoadCurve([1000 * RPM, 2000 * RPM], [0.5 * peak, peak], "peak_pressure")
    ex = EngineExcitation(engine, ExcitationSpec(load_curve=curve))
    orders = [0.5, 1.0, 3.0]
    gas, _ = ex.parts([1000 * RPM], orders)
    half = EngineExcitation(
        dataclasses.replace(engine, pressure=engine.pressure.scaled(0.5)), None
    ).parts([1000 * RPM], orders)[0]
    assert gas == pytest.approx(half, rel=1e-12)
    assert ex.load_factor([1500 * RPM]) == pytest.approx([0.75])
    assert ex.notes([3000 * RPM])  # outside the curve: noted


def test_harmonic_table_interpolates_in_imep(diesel):
    engine, _ = diesel
    table = HarmonicTable(
        order=[3.0, 3.0, 6.0, 6.0],
        imep=[0.5e6, 1.5e6, 0.5e6, 1.5e6],
        amplitude=[0.2e6, 0.6e6, 0.05e6, 0.15e6],
        phase=[0.0, 0.0, 0.5, 0.5],
    )
    ex = EngineExcitation(engine, ExcitationSpec(harmonics=table, imep=1.0e6))
    gas, _ = ex.parts([2000 * RPM], [3.0, 6.0])
    area_r = engine.geometry.piston_area * engine.geometry.crank_radius
    one = gas[0, :, 0]  # cylinder 1 fires at 0
    assert one == pytest.approx(
        [
            0.4e6 * area_r * np.exp(-0.5j * math.pi),
            0.1e6 * area_r * np.exp(1j * (0.5 - math.pi / 2)),
        ]
    )
    with pytest.raises(InputError, match=r"order 1\.5 is not in the harmonic table"):
        ex.parts([2000 * RPM], [1.5])
    with pytest.raises(InputError, match="needs the mean indicated pressure"):
        EngineExcitation(engine, ExcitationSpec(harmonics=table))


def test_table_without_phases_adds_in_phase(diesel):
    engine, _ = diesel
    table = HarmonicTable(order=[2.0], imep=[1e6], amplitude=[0.3e6])
    ex = EngineExcitation(engine, ExcitationSpec(harmonics=table, imep=1e6))
    gas, inertia = ex.parts([2000 * RPM], [2.0])
    total = abs((gas + inertia)[0, 0, 0])
    assert total == pytest.approx(abs(gas[0, 0, 0]) + abs(inertia[0, 0, 0]), rel=1e-12)


def test_misfire_needs_the_compression_ratio_and_lowers_the_half_orders(diesel):
    engine, _ = diesel
    from crankdyn.crank.pressure import PressureTrace

    p = engine.pressure
    no_ratio = dataclasses.replace(
        engine, pressure=PressureTrace(p.crank_angle, p.pressure, p.cycle_angle, p.source)
    )
    with pytest.raises(InputError, match="compression ratio"):
        EngineExcitation(no_ratio, None, (3,)).parts([2000 * RPM], [0.5])
    engine16 = dataclasses.replace(
        engine, pressure=PressureTrace(p.crank_angle, p.pressure, p.cycle_angle, p.source, 16.0)
    )
    normal = EngineExcitation(engine16).harmonics([2000 * RPM], [0.5, 1.0, 3.0])
    misfire = EngineExcitation(engine16, None, (3,)).harmonics([2000 * RPM], [0.5, 1.0, 3.0])
    # all cylinders firing cancel order 0.5 over the engine; one misfire leaves it
    assert abs(normal[0, 0].sum()) < 1e-6 * abs(normal[0, 0, 0])
    assert abs(misfire[0, 0].sum()) > 0.3 * abs(normal[0, 0, 0])
    assert misfire[0, :, 0] == pytest.approx(normal[0, :, 0])  # the others unchanged


def test_excitation_for_models_without_engine():
    from crankdyn.torsion import TorsionModel

    model = TorsionModel.example("seed003-v6")
    ex = excitation_for(model)  # the built-in model states a firing order (an assumption)
    assert ex.torque == 1.0 and ex.phases_known and not ex.note
    ex = excitation_for(dataclasses.replace(model, excitation=None))
    assert ex.torque == 1.0 and "in phase" in ex.note and not ex.phases_known
    spec = ExcitationSpec(firing_order=(1, 4, 2, 5, 3, 6), torque=2.0)
    ex = excitation_for(dataclasses.replace(model, excitation=spec))
    assert ex.torque == 2.0
    assert np.degrees(ex.firing_angles).tolist() == pytest.approx([0, 240, 480, 120, 360, 600])
    assert SAMPLES >= 4096
