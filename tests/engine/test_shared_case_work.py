"""The work a study case shares between its analyses (issue 16): the kinematics summary made once
per geometry and speed (the session's kinematics and the forces' plausibility warnings), its
extrema bracketed from one evaluation of the motion, the indicated work made once per crank
train, and the pressure trace's periodic interpolation prepared once; every shared number equal,
to the bit, to the one computed on its own."""

from __future__ import annotations

import math
from dataclasses import fields, replace

import numpy as np
import pytest

import crankdyn
from crankdyn.crank import kinematics as kin
from crankdyn.crank.indicated import indicated_work, pressure_analysis
from crankdyn.crank.kinematics import (
    complex_step,
    extrema_grid,
    kinematics_summary,
    local_extrema,
    piston_kinematics,
    slider_crank_exact,
    slider_crank_series,
)
from crankdyn.crank.pressure import PressureTrace
from crankdyn.engine import forces as engine_forces_module
from crankdyn.engine.forces import engine_warnings
from crankdyn.session import Analysis


def _same(a, b) -> bool:
    """Two summaries equal field by field, floats to the bit."""
    for f in fields(a):
        x, y = getattr(a, f.name), getattr(b, f.name)
        if isinstance(x, float):
            if x.hex() != y.hex():
                return False
        elif x != y:
            return False
    return True


def _fresh(geometry):
    """An equal geometry without the original's cached summaries."""
    return replace(geometry)


@pytest.mark.parametrize("method", ["exact", "approx", "series"])
@pytest.mark.parametrize("offset", [0.0, 0.004])
def test_summary_from_one_grid_evaluation_equals_one_per_quantity(method, offset):
    engine = crankdyn.Engine.example("vaz2108")
    g = replace(engine.geometry, offset=offset)
    w = 5600 * math.pi / 30
    motion = kin._motion_function(method, 4)
    got = kinematics_summary(g, w, method=method)
    # the form it replaces: each quantity's complex-step derivative evaluated on its own
    r, l, e = g.crank_radius, g.rod_length, g.offset
    piston = method != "series"
    expected = {}
    for index, elementwise in ((1, piston), (2, piston), (4, True), (5, True)):

        def f(p, index=index):
            return motion(p, r, l, e, w)[index]

        expected[index] = local_extrema(f, elementwise=elementwise)
    assert got.max_velocity.hex() == max(x.value for x in expected[1]).hex()
    assert got.min_velocity.hex() == min(x.value for x in expected[1]).hex()
    assert [
        (x.kind, x.crank_angle.hex(), x.acceleration.hex()) for x in got.acceleration_extrema
    ] == [(x.kind, x.angle.hex(), x.value.hex()) for x in expected[2]]
    assert got.max_rod_angular_velocity.hex() == max(x.value for x in expected[4]).hex()
    assert got.min_rod_angular_acceleration.hex() == min(x.value for x in expected[5]).hex()


@pytest.mark.parametrize("motion", [slider_crank_exact, slider_crank_series])
def test_grid_slopes_equal_the_derivative_evaluated_on_the_grid(motion):
    def f(p):
        return motion(p, 0.0355, 0.1365, 0.002, 586.0).acceleration

    elementwise = motion is slider_crank_exact
    slopes = complex_step(f)(extrema_grid())
    a = local_extrema(f, elementwise=elementwise)
    b = local_extrema(f, elementwise=elementwise, grid_slopes=slopes)
    assert [(x.kind, x.angle.hex(), x.value.hex()) for x in a] == [
        (x.kind, x.angle.hex(), x.value.hex()) for x in b
    ]
    with pytest.raises(ValueError, match="grid_slopes"):
        local_extrema(f, grid_slopes=slopes[:-1])


def test_kinematics_summary_is_computed_once_per_case(monkeypatch):
    calls = []
    original = kin._summary

    def counted(*args, **kwargs):
        calls.append(args[2:])
        return original(*args, **kwargs)

    monkeypatch.setattr(kin, "_summary", counted)
    engine = crankdyn.Engine.example("vaz2108")
    engine = replace(engine, geometry=_fresh(engine.geometry))
    a = Analysis(engine, speed=5600 * math.pi / 30, step=math.radians(2.0))
    torque = a.torque  # the crank train's plausibility warnings need the summary first
    summary = a.kinematics().summary
    a.forces()
    a.bearings()
    assert len(calls) == 1
    # the same figures as a summary computed on its own, and the same warnings
    alone = piston_kinematics(_fresh(engine.geometry), a.speed, fuel=engine.fuel)
    assert _same(summary, alone.summary)
    old_pressure = pressure_analysis(
        a._train().trace, engine.geometry, fuel=engine.fuel, aspiration=engine.aspiration
    )
    assert torque.warnings == (*alone.warnings, *old_pressure.warnings)


def test_summaries_are_kept_per_speed_method_and_order():
    g = _fresh(crankdyn.Engine.example("vaz2108").geometry)
    s1 = kinematics_summary(g, 500.0)
    assert kinematics_summary(g, 500.0) is s1
    assert kinematics_summary(g, 600.0) is not s1
    assert kinematics_summary(g, 500.0, method="series", order=6) is not kinematics_summary(
        g, 500.0, method="series", order=4
    )
    # the cache is no part of the geometry's value
    assert g == _fresh(g) and hash(g) == hash(_fresh(g)) and "_derived" not in repr(g)


def test_indicated_work_is_computed_once_per_train(monkeypatch):
    calls = []
    original = engine_forces_module.indicated_work

    def counted(trace, geometry):
        calls.append(1)
        return original(trace, geometry)

    monkeypatch.setattr(engine_forces_module, "indicated_work", counted)
    engine = crankdyn.Engine.example("vaz2108")
    a = Analysis(engine, speed=5600 * math.pi / 30)
    torque = a.torque
    a.forces()
    a.bearings()
    assert len(calls) == 1
    expected = indicated_work(a._train().trace, engine.geometry)
    assert torque.indicated_work.hex() == expected.hex()


@pytest.mark.parametrize("name", ["vaz2108", "inline6-diesel"])
def test_engine_warnings_with_the_work_equal_those_without(name):
    engine = crankdyn.Engine.example(name)
    w = 9000 * math.pi / 30  # fast enough for a piston-speed warning
    work = indicated_work(crankdyn.crank.pressure_model.default_pressure(engine), engine.geometry)
    alone = piston_kinematics(_fresh(engine.geometry), w, fuel=engine.fuel).warnings
    pressure = pressure_analysis(
        crankdyn.crank.pressure_model.default_pressure(engine),
        engine.geometry,
        fuel=engine.fuel,
        aspiration=engine.aspiration,
    ).warnings
    assert engine_warnings(engine, w) == (*alone, *pressure)
    assert engine_warnings(engine, w, work=work) == (*alone, *pressure)


def test_trace_interpolation_equals_numpy_periodic_interp_to_the_bit():
    rng = np.random.default_rng(16)
    angle = np.sort(rng.uniform(0.0, 4.0 * math.pi, 300))
    trace = PressureTrace(angle, rng.uniform(1e5, 8e6, 300))
    x = np.concatenate(
        [rng.uniform(-20.0, 20.0, 5000), angle, angle + 4.0 * math.pi, [-0.0, 0.0, 4 * math.pi]]
    )
    expected = np.interp(x, trace.crank_angle, trace.pressure, period=trace.cycle_angle)
    got = trace.at(x)
    assert np.array_equal(got, expected)
    assert float(trace.at(1.234)) == float(
        np.interp(1.234, trace.crank_angle, trace.pressure, period=trace.cycle_angle)
    )
    two_stroke = PressureTrace(angle / 2.0, trace.pressure, cycle_angle=2.0 * math.pi)
    assert np.array_equal(
        two_stroke.at(x), np.interp(x, angle / 2.0, trace.pressure, period=2.0 * math.pi)
    )


@pytest.mark.parametrize(
    "name", ["vaz2108", "inline6-diesel", "inline3-petrol", "v8-crossplane", "v12-60"]
)
def test_crank_tangential_equals_the_trains_to_the_bit(name):
    from crankdyn.engine.forces import crank_tangential, crank_train, cycle_grid

    engine = crankdyn.Engine.example(name)
    w = 3000 * math.pi / 30
    grid = cycle_grid(engine, math.radians(0.1))[:-1]
    train = crank_train(engine, w, grid)
    got = crank_tangential(engine, w, grid, pressure=train.trace)
    assert got.tobytes() == train.tangential.tobytes()


@pytest.mark.parametrize("speed", [0.0, -10.0, float("nan"), float("inf")])
def test_a_speed_that_is_not_positive_and_finite_is_named(speed):
    """The summary (and the kinematics built on it) refuses a speed without motion or without a
    number, naming the key, instead of failing inside its extrema search."""
    from crankdyn.crank.geometry import CrankGeometry
    from crankdyn.crank.kinematics import kinematics_summary, piston_kinematics
    from crankdyn.errors import InputError

    g = CrankGeometry(bore=0.1, crank_radius=0.05, rod_length=0.16)
    for call in (kinematics_summary, piston_kinematics):
        with pytest.raises(InputError, match="speed"):
            call(g, speed)
