"""The torsional vibration calculation: every component check, the barred ranges with their
margins, the passage, the misfire and damper conditions, the summary fields and bad input."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.io.catalogue import resolve_model_and_engine
from crankdyn.io.torsion_file import parse_torsion_model
from crankdyn.torsion.excitation import excitation_for
from crankdyn.torsion.sources import default_orders
from crankdyn.torsion.sweep import forced_response
from crankdyn.tvc import CrankshaftLimit, TvcSpec, tvc
from crankdyn.tvc import curves as cv
from crankdyn.tvc.analysis import judge

VERDICT_FIELDS = {
    "component",
    "condition",
    "quantity",
    "worst",
    "limit",
    "unit",
    "margin",
    "passed",
    "source",
}
BARRED_FIELDS = {"component", "condition", "start_rpm", "end_rpm", "permitted"}


@pytest.fixture(scope="module")
def genset():
    model, engine = resolve_model_and_engine("genset-1500")
    return model, engine, tvc(model, engine, passage=False)


@pytest.fixture(scope="module")
def geared():
    model, _ = resolve_model_and_engine("verdict-geared-line")
    return model


def _rows(result, component, quantity=""):
    return [v for v in result.verdicts if v.component == component and quantity in v.quantity]


def test_genset_conditions_and_summary_fields(genset):
    _model, _engine, res = genset
    names = [c.name for c in res.conditions]
    assert names == ["normal firing", "misfire (worst cylinder per check)", "damper out of order"]
    assert res.load == "constant-speed"
    d = res.to_dict()
    assert d["verdicts"] and all(set(v) >= VERDICT_FIELDS for v in d["verdicts"])
    assert all(set(b) >= BARRED_FIELDS for b in d["barred_speed_ranges"])
    misfire = [v for v in res.verdicts if v.condition.startswith("misfire cylinder")]
    assert misfire, "the misfire rows name their cylinder"
    # every row is traceable to a rule or a maker's limit
    assert all(v.source for v in res.verdicts)


def test_genset_coupling_and_alternator_rows(genset):
    model, _engine, res = genset
    label = "elastic coupling"
    (kw,) = [v for v in _rows(res, label, "T_KW") if v.condition == "normal firing"]
    (kv,) = [v for v in _rows(res, label, "P_KV") if v.condition == "normal firing"]
    (kn,) = [v for v in _rows(res, label, "T_KN") if v.condition == "normal firing"]
    assert (kw.limit, kv.limit, kn.limit) == (1600.0, 400.0, 6300.0)
    # the worst T_KW row is the resolved peak of the synthesised coupling torque
    r = res.conditions[0].response
    s = next(i for i, sh in enumerate(model.shafts) if sh.coupling is not None)
    peak = r.peak("synthesized_shaft_torque", model.shafts[s].between)
    assert kw.worst == pytest.approx(peak.value, rel=1e-3)
    # the mean torque is the load law's (565 kW at 1500 rpm, constant torque)
    assert kn.worst == pytest.approx(565e3 / (1500 / RPM), rel=1e-9)
    rows = _rows(res, "alternator")
    assert {v.quantity for v in rows} == {
        "synthesised vibratory torque at the rotor",
        "synthesised angular acceleration",
    }


def test_alternator_acceleration_against_finite_differences(genset):
    model, engine, _ = genset
    exc = excitation_for(model, engine)
    orders = default_orders(model, exc.cycle)
    speed = 1440.0 / RPM
    r = forced_response(model, exc, [speed], orders, resolve=False)
    j = model.mass_names.index("alternator")
    got = cv.synthesized(r, cv.acceleration_coefficients(r, j))[0]
    t = np.linspace(0.0, 4 * np.pi / speed, 200_001)
    x = np.real(r.mass_response[0, :, j][None, :] * np.exp(1j * np.outer(t, orders * speed)))
    x = x.sum(axis=1)
    acc = np.gradient(np.gradient(x, t), t)
    expected = 0.5 * (acc[10:-10].max() - acc[10:-10].min())
    assert got == pytest.approx(expected, rel=1e-4)


def test_grid_does_not_change_the_verdicts(genset):
    model, engine, res = genset
    coarse = tvc(
        model, engine, TvcSpec(step=50.0 / RPM, misfire=False, damper_out=False), passage=False
    )
    fine = {(v.component, v.quantity): v for v in res.verdicts if v.condition == "normal firing"}
    for v in coarse.verdicts:
        w = fine[(v.component, v.quantity)]
        assert v.worst == pytest.approx(w.worst, rel=1e-3)
        assert v.passed == w.passed


def test_damper_heat_and_damper_out(genset):
    model, engine, _ = genset
    damper = model.dampers[0]
    import dataclasses

    limited = dataclasses.replace(
        model, dampers=(dataclasses.replace(damper, permissible_power=50.0),)
    )
    res = tvc(limited, engine, TvcSpec(misfire=False), passage=False)
    (row,) = _rows(res, "damper ring")
    r = res.conditions[0].response
    assert row.worst == pytest.approx(r.peak("damper_power", "damper ring").value, rel=1e-3)
    assert row.passed is (row.worst <= 50.0)
    out = [v for v in res.verdicts if v.condition == "damper out of order"]
    assert out and not any(v.component.startswith("damper ring") for v in out)


def test_barred_range_ends_margins_and_placement(geared):
    # normal firing only: the overspeed condition above 1000 rpm has its own ranges
    exact = tvc(geared, spec=TvcSpec(tachometer_tolerance=0.0, overspeed=False), passage=False)
    # the same checks on a response of another grid (7 rpm): the ranges do not move
    _, ranges = judge(
        exact.model,
        forced_response(
            exact.model,
            excitation_for(exact.model),
            np.arange(400.0, 1000.0 + 1e-9, 7.0) / RPM,
            default_orders(geared, "four-stroke"),
        ),
        TvcSpec(tachometer_tolerance=0.0),
    )
    assert len(exact.barred_ranges) == len(ranges) == 2
    for b, ref in zip(exact.barred_ranges, ranges, strict=True):
        assert b.start == pytest.approx(ref.start, abs=0.011 / RPM)
        assert b.end == pytest.approx(ref.end, abs=0.011 / RPM)
        assert b.permitted  # below 0.8 n_0 and under tau_T
        assert 700.0 < b.start * RPM < b.end * RPM < 800.0
    tol = tvc(geared, spec=TvcSpec(tachometer_tolerance=0.02, overspeed=False), passage=False)
    for b, ref in zip(tol.barred_ranges, exact.barred_ranges, strict=True):
        assert b.start == pytest.approx(ref.start * 0.98, rel=1e-12)
        assert b.end == pytest.approx(ref.end * 1.02, rel=1e-12)
        assert not b.permitted  # the declared range reaches above 0.8 n_0 = 800 rpm
    ends = [v for v in tol.verdicts if "end of the declared" in v.quantity]
    assert ends and not any(v.passed for v in ends) and all(v.limit == 0.8 for v in ends)
    lr = tvc(
        geared,
        spec=TvcSpec(tachometer_tolerance=0.0, rules="lr", overspeed=False),
        passage=False,
    )
    for b in lr.barred_ranges:
        nc, lam = b.critical_speed, b.critical_speed / (1000 / RPM)
        assert b.start == pytest.approx(16 * nc / (18 - lam), rel=1e-12)
        assert b.end == pytest.approx((18 - lam) * nc / 16, rel=1e-12)


def test_passage_time_and_transient_peak(geared):
    torque = 30e3
    spec = TvcSpec(tachometer_tolerance=0.0, engine_torque=torque, misfire=False)
    res = tvc(geared, spec=spec)
    (p,) = res.passages
    from crankdyn.torsion.solvers import linear_system

    inertia = float(np.sum(linear_system(geared, geared.dampers).inertia))
    # no load law: the whole engine torque accelerates the line, dOmega/dt = T / J
    assert p.time_in_range == pytest.approx(inertia * (p.end - p.start) / torque, rel=1e-9)
    assert p.duration == pytest.approx(inertia * (p.run_to - p.run_from) / torque, rel=1e-9)
    steady = {v.component: v for v in res.verdicts if "steady state in the" in v.quantity}
    transient = [v for v in res.verdicts if v.quantity.startswith("transient peak passing")]
    assert {v.component for v in transient} == set(steady)
    for v in transient:
        assert v.passed
        assert 0.0 < v.worst < steady[v.component].worst  # passing quickly stays below resonance


def test_crank_spans_against_the_builders_limit():
    model, engine = resolve_model_and_engine("marine-propulsion")
    limit = CrankshaftLimit(stress=35e6, diameter=0.3, stress_concentration=1.2, source="test")
    spec = TvcSpec(misfire=False, damper_out=False, overspeed=False, crankshaft=limit)
    res = tvc(model, engine, spec, passage=False)
    spans = [v for v in res.verdicts if v.component.startswith("crank span")]
    assert len(spans) == 7  # every crank throw shaft, with the free end and flywheel spans
    r = res.conditions[0].response
    for v in spans:
        label = v.component.removeprefix("crank span ")
        s = next(i for i, sh in enumerate(model.shafts) if sh.label == label)
        at = r.at([v.speed])
        expected = at.synthesized_shaft_torque[0, s] * 1.2 / (math.pi * 0.3**3 / 16)
        assert v.worst == pytest.approx(expected, rel=1e-9)
        assert v.limit == 35e6 and "test" in v.source


def test_tvc_file_table_and_errors():
    text = """
name = "line"
[operating]
speed_range = ["400 rpm", "1000 rpm"]
rated_speed = "1000 rpm"
[excitation]
torque = "1 kN*m"
[tvc]
rules = "lr"
tachometer_tolerance = 0.03
speed_step = "20 rpm"
engine_torque_curve = [["400 rpm", "20 kN*m"], ["1000 rpm", "40 kN*m"]]
[tvc.speed_ranges]
misfire = ["500 rpm", "900 rpm"]
[tvc.crankshaft]
permissible_torque = "20 kN*m"
source = "builder"
[[mass]]
name = "a"
inertia = "1 kg*m^2"
cylinders = [1]
[[mass]]
name = "b"
inertia = "2 kg*m^2"
[[shaft]]
between = ["a", "b"]
stiffness = "1 MN*m/rad"
"""
    model = parse_torsion_model(tomllib.loads(text), file="line.toml")
    spec = model.tvc
    assert spec.rules == "lr" and spec.tachometer_tolerance == 0.03 and spec.tolerance == 0.03
    assert spec.step == pytest.approx(20 / RPM)
    assert spec.ranges["misfire"] == pytest.approx((500 / RPM, 900 / RPM))
    assert spec.crankshaft.torque == 20e3 and spec.crankshaft.source == "builder"
    w, q = spec.engine_torque_curve
    assert w == pytest.approx([400 / RPM, 1000 / RPM]) and q == pytest.approx([20e3, 40e3])
    bad = text.replace('["1000 rpm", "40 kN*m"]]', '"1000 rpm"]')
    with pytest.raises(InputError, match="engine_torque_curve"):
        parse_torsion_model(tomllib.loads(bad), file="line.toml")
    bad = text.replace('rules = "lr"', 'rules = "dvn"')
    with pytest.raises(InputError, match='did you mean "dnv"') as err:
        parse_torsion_model(tomllib.loads(bad), file="line.toml")
    assert "rules" in str(err.value) and "line.toml" in str(err.value)
    bad = text.replace('rules = "lr"', 'widening = "lr"')  # retired: one line naming rules
    with pytest.raises(InputError, match=r'retired.*write rules = "lr"') as err:
        parse_torsion_model(tomllib.loads(bad), file="line.toml")
    assert "\n" not in str(err.value) and "[tvc] widening" in str(err.value)
    bad = text.replace('permissible_torque = "20 kN*m"', "")
    with pytest.raises(InputError, match="permissible"):
        parse_torsion_model(tomllib.loads(bad), file="line.toml")
    bad = text.replace("tachometer_tolerance = 0.03", "tachometer_tolerance = 0.5")
    with pytest.raises(InputError, match="tachometer_tolerance"):
        parse_torsion_model(tomllib.loads(bad), file="line.toml")


def test_session_tvc_is_the_calculation(geared):
    import crankdyn

    session = crankdyn.Analysis(geared)
    result = session.tvc(passage=False)
    assert session.tvc(passage=False) is result  # computed once
    direct = tvc(geared, passage=False, orders=session.orders)
    assert [(v.component, v.quantity, v.worst) for v in result.verdicts] == [
        (v.component, v.quantity, v.worst) for v in direct.verdicts
    ]


def test_transient_started_in_the_steady_state_stays_there(genset):
    """The passage's run starts in the steady state: at constant speed the time-domain torque
    equals the frequency-domain synthesis from the first sample on (same equations, the loss
    factors as viscous damping at omega_h)."""
    from crankdyn.torsion.transient import transient_response

    model, engine, _ = genset
    exc = excitation_for(model, engine)
    orders = default_orders(model, exc.cycle)
    w = 1300.0 / RPM
    run = transient_response(model, exc, orders, speed=w, cycles=1.0, start="steady")
    r = forced_response(
        model,
        exc,
        [w],
        orders,
        resolve=False,
        hysteretic_frequency=run.hysteretic_frequency,
    )
    s = next(i for i, sh in enumerate(model.shafts) if sh.coupling is not None)
    phase = np.exp(1j * np.outer(run.crank_angle, orders))
    expected = np.real(phase @ r.shaft_response[0, :, s])
    got = run.shaft_torque[:, s]
    assert np.max(np.abs(got - expected)) <= 1e-5 * np.max(np.abs(expected))
    with pytest.raises(InputError, match="rest or steady"):
        transient_response(model, exc, orders, speed=w, cycles=1.0, start="cold")


def test_passage_with_the_engines_torque_speed_curve(geared):
    """A linear torque-speed curve T(n) = T_0 + b n and no load: the time in the range is
    J/b ln(T(n_2)/T(n_1)) (dt = J dn / T(n))."""
    speeds = np.array([400.0, 1000.0]) / RPM
    torques = np.array([20e3, 40e3])
    spec = TvcSpec(tachometer_tolerance=0.0, misfire=False, engine_torque_curve=(speeds, torques))
    res = tvc(geared, spec=spec)
    (p,) = res.passages
    from crankdyn.torsion.solvers import linear_system

    inertia = float(np.sum(linear_system(geared, geared.dampers).inertia))
    slope = (torques[1] - torques[0]) / (speeds[1] - speeds[0])

    def torque(w):
        return torques[0] + slope * (w - speeds[0])

    expected = inertia / slope * np.log(torque(p.end) / torque(p.start))
    assert p.time_in_range == pytest.approx(expected, rel=1e-6)
    assert "torque-speed curve" in p.note
    with pytest.raises(InputError, match="not both"):
        TvcSpec(engine_torque=1.0, engine_torque_curve=(speeds, torques))
    with pytest.raises(InputError, match="increasing positive speeds"):
        TvcSpec(engine_torque_curve=(speeds[::-1], torques))


def test_resolved_worst_takes_a_constant_limit():
    """A limit that gives one number for every speed (a maker's constant torque): the same
    worst as the limit given per speed (a constant limit failed in the refinement)."""
    from crankdyn.torsion.excitation import UniformExcitation
    from crankdyn.torsion.model import Mass, Shaft, TorsionModel
    from crankdyn.torsion.sweep import forced_response
    from crankdyn.tvc.curves import resolved_worst

    model = TorsionModel(
        (Mass("a", 1.0, cylinders=(1,)), Mass("b", 3.0)),
        (Shaft(("a", "b"), stiffness=1e5, loss_factor=0.1),),
    )
    r = forced_response(
        model, UniformExcitation(100.0, [0.0]), np.linspace(100, 400, 31), [1.0, 2.0]
    )

    def torque(x):
        return x.synthesized_shaft_torque[:, 0]

    per_speed = resolved_worst(r, torque, lambda w: np.full(np.size(w), 1000.0), [(170.0, 200.0)])
    constant = resolved_worst(r, torque, lambda w: 1000.0, [(170.0, 200.0)])
    assert per_speed is not None and constant == per_speed
    assert per_speed[0] == pytest.approx(750.0, abs=0.01)  # T J_2 / (J_1 + J_2) / eta
