"""Transient events in the TVC (issue 36): ``[[tvc.event]]`` tables, each event judged by the
installation's own checks (the TVC's one evaluation), its rows against closed forms, the
built-in lines' events with their plots."""

from __future__ import annotations

import math
import tomllib
from functools import lru_cache

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.io.catalogue import resolve_model_and_engine
from crankdyn.io.torsion_file import parse_torsion_model
from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
from crankdyn.torsion.coupling import Coupling
from crankdyn.torsion.event_run import event_response
from crankdyn.torsion.events import StepTorque
from crankdyn.torsion.rules import RuleSet, ShaftLimit
from crankdyn.tvc import TvcSpec, tvc
from crankdyn.tvc.events import judge_event


def _rows(run):
    return {v.quantity.split(" vs ")[-1]: v for v in run.verdicts}


def test_coupling_step_against_t_kmax_and_its_severity():
    """A torque T = 100 N m suddenly applied to J_1 = 2 kg m^2 of an (almost) undamped
    two-mass line through a coupling (J_2 = 3 kg m^2): the coupling torque
    T_s (1 - cos wt), T_s = T J_2/(J_1 + J_2) = 60 N m, peaks at 120 N m (Thomson 1993,
    sec. 4.2); above a level L it spends the fraction arccos(1 - L/T_s)... of each period:
    T_s (1 - cos x) > L for cos x < 1 - L/T_s, a fraction arccos(L/T_s - 1)/pi."""
    coupling = Coupling(
        stiffness=1e5,
        relative_damping=1e-6,  # zeta = 8e-8: the peak 2 T_s to 3e-7
        maximum_torque=200.0,
        maximum_torque_1=100.0,
        maximum_torque_2=300.0,
    )
    line = TorsionModel(
        (Mass("a", 2.0), Mass("b", 3.0)),
        (Shaft(("a", "b"), coupling=coupling, name="C1"),),
    )
    for severity, names in (
        ("normal", ["T_Kmax", "T_Kmax1"]),
        ("exceptional", ["T_Kmax", "T_Kmax2"]),
    ):
        run = event_response(line, StepTorque("a", 100.0, severity=severity))
        run = judge_event(line, run, TvcSpec(), 1.0)
        rows = _rows(run)
        assert sorted(rows) == names
        for row in rows.values():
            assert row.component == "coupling C1" and row.worst == pytest.approx(120.0, rel=1e-6)
        assert rows["T_Kmax"].passed and rows[names[1]].passed == (severity == "exceptional")
    # the time above T_Kmax1 = 100 N m: a fraction arccos(100/60 - 1)/pi of the run
    normal = judge_event(line, event_response(line, StepTorque("a", 100.0)), TvcSpec(), 1.0)
    above = float(_rows(normal)["T_Kmax1"].note.split("; ")[1].split(" s above")[0])
    expected = math.acos(100.0 / 60.0 - 1.0) / math.pi * normal.duration
    omega = math.sqrt(1e5 * (1 / 2 + 1 / 3))
    periods = normal.duration * omega / (2 * math.pi)
    # two crossings per period, each found by linear interpolation between samples h apart:
    # an error below h^2 |T''| / (8 |T'|) per crossing, where cos x = -2/3, sin x = sqrt(5)/3:
    # |T''| / |T'| = omega (2/3) / (sqrt(5)/3) = omega 2/sqrt(5); the note prints 3 digits
    h = float(normal.time[1] - normal.time[0])
    bound = 2 * periods * h * h * omega * (2 / math.sqrt(5)) / 8 + 0.0005
    assert above == pytest.approx(expected, abs=bound)


def test_m68_shaft_against_tau_t_at_the_speed_ratio():
    """A torque of 100 N m suddenly applied at J_1 = 1 kg m^2 of a line running at 50 rad/s
    (n_0 = 100 rad/s) through a 50 mm shaft (sigma_B = 600 N/mm^2, C_K = 1) to J_2 = 3 kg m^2:
    the shaft's vibratory torque peaks at 2 x 100 x 3/4 = 150 N m, over W_p = pi d^3 / 16 =
    2.45437e-5 m^3: 6.1115 MPa, against IACS UR M68.4's tau_T = 1.7 tau_C / sqrt(C_K),
    tau_C = (600 + 160)/18 C_D (3 - 2 lambda^2), C_D = 0.35 + 0.93 x 50^-0.2 = 0.775294, at
    the speed ratio of the peak: the torque accelerates the free line at 100/4 = 25 rad/s^2, so
    lambda = 0.5 + 0.25 t_peak (at lambda = 0.5 exactly: tau_C = 42.2222 x 0.775294 x 2.5 =
    81.8366 MPa, tau_T = 139.122 MPa)."""
    line = TorsionModel(
        (Mass("a", 1.0), Mass("b", 3.0)),
        (Shaft(("a", "b"), stiffness=1e5, geometry=ShaftGeometry(0.05), name="shaft"),),
        rules=RuleSet(100.0, (ShaftLimit(("a", "b"), 600e6),)),
    )
    run = event_response(line, StepTorque("a", 100.0), speed=50.0)
    (row,) = judge_event(line, run, TvcSpec(), 100.0).verdicts
    t_peak = run.vibratory_peak_time(0)
    assert row.speed == pytest.approx(50.0 + 25.0 * t_peak, rel=1e-6)
    lam = row.speed / 100.0
    hand = 1.7 * (760.0 / 18.0) * 0.775294 * (3.0 - 2.0 * lam**2)
    assert row.limit / 1e6 == pytest.approx(hand, rel=1e-6)  # C_D to 6 digits
    at_half = 1.7 * (760.0 / 18.0) * 0.775294 * 2.5  # lambda = 0.5: the docstring's digits
    assert at_half == pytest.approx(139.122, abs=0.0005)
    assert row.worst == pytest.approx(150.0 / (math.pi * 0.05**3 / 16), rel=1e-6)
    assert row.passed and row.source.startswith("IACS UR M68")
    assert row.clause.startswith("τ_T: M68.4")  # the rule set's citation of tau_T


MODEL = """
name = "line"
[operating]
speed_range = ["400 rpm", "1000 rpm"]
rated_speed = "1000 rpm"
[excitation]
torque = "1 kN*m"
[tvc]
misfire = false
[[tvc.event]]
kind = "step"
name = "load kick"
at = "b"
torque = "-2 kN*m"
rise_time = "10 ms"
speed = "800 rpm"
duration = "0.2 s"
harmonics = false
[[tvc.event]]
kind = "clutch"
between = ["a", "b"]
torque = "5 kN*m"
rise_time = "0.1 s"
speeds = ["600 rpm", "0 rpm"]
[[mass]]
name = "a"
inertia = "1 kg*m^2"
cylinders = [1]
[[mass]]
name = "b"
inertia = "2 kg*m^2"
[[shaft]]
between = ["a", "b"]
kind = "coupling"
name = "C1"
dynamic_stiffness = "50 kN*m/rad"
relative_damping = 1.0
maximum_torque = "20 kN*m"
maximum_torque_1 = "15 kN*m"
maximum_torque_2 = "25 kN*m"
"""


def test_tvc_event_tables_and_their_rows():
    model = parse_torsion_model(tomllib.loads(MODEL), file="line.toml")
    step, clutch = model.tvc.events
    assert (step.name, step.speed, step.duration, step.harmonics) == (
        "load kick",
        pytest.approx(800 / RPM),
        0.2,
        False,
    )
    assert clutch.name == "clutch engagement" and not clutch.harmonics  # a clutch: none
    c = model.shafts[0].coupling
    assert (c.maximum_torque_1, c.maximum_torque_2) == (15e3, 25e3)
    res = tvc(model, passage=False, conditions=("normal",))
    assert [e.name for e in res.events] == ["load kick", "clutch engagement"]
    for event in res.events:
        rows = [v for v in res.verdicts if v.condition == event.name]
        assert rows == list(event.verdicts) and rows
        assert {v.quantity.split(" vs ")[-1] for v in rows} == {"T_Kmax", "T_Kmax1"}
    assert res.to_dict()["events"][0]["condition"] == "load kick"
    assert "verdicts" not in res.to_dict()["events"][0]  # the rows once, in "verdicts"
    assert any(t.key == "events" for t in res.summary().tables)


@pytest.mark.parametrize(
    ("change", "key"),
    [
        ('speed = "800 rpm"', "speed = -5"),
        ('duration = "0.2 s"', 'duration = "0 s"'),
        ("harmonics = false", "harmonic = false"),
        ('at = "b"', 'at = "nowhere"'),
        ('name = "load kick"', 'name = "clutch engagement"'),
    ],
)
def test_tvc_event_errors_name_their_entry(change, key):
    text = MODEL.replace(change, key)
    with pytest.raises(InputError) as err:
        parse_torsion_model(tomllib.loads(text), file="line.toml")
    message = str(err.value)
    assert "line.toml" in message and "\n" not in message
    assert "event" in message


@lru_cache(maxsize=1)
def _marine():
    from crankdyn.session import Analysis

    _model, engine = resolve_model_and_engine("marine-propulsion")
    session = Analysis(engine)
    model = session.loaded_model
    from crankdyn.tvc.checks import model_checks

    checks, _notes = model_checks(model, model.tvc, 750 / RPM, model.dampers)
    return session, model, checks


@pytest.mark.parametrize("index", [0, 1, 2], ids=["clutch-in", "start", "ice"])
def test_marine_events_rows_and_plots(index):
    """The built-in marine line's clutch-in, start through its barred range and ice impact
    (issue 36's "done when"): each its rows (shafts against tau_T, the coupling against T_Kmax
    and T_Kmax1, the reduction gear's reversal) and its plot."""
    from dataclasses import replace

    from crankdyn.tvc.events import event_conditions

    session, model, checks = _marine()
    spec = replace(model.tvc, events=(model.tvc.events[index],))
    (event,) = event_conditions(
        model, spec, 750 / RPM, session.excitation(), session.orders, checks
    )
    limits = {v.quantity.split(" vs ")[-1] for v in event.verdicts}
    assert limits == {"τ_T", "T_Kmax", "T_Kmax1", "the mean (torque reversal)"}
    assert {v.condition for v in event.verdicts} == {event.name}
    shafts = {v.component.split(" (")[0] for v in event.verdicts if "τ_T" in v.quantity}
    assert shafts == {"thrust shaft", "intermediate shaft", "propeller shaft"}
    assert all(v.source for v in event.verdicts) and len(event.curves) == 5
    fig = event.plot()
    assert len(fig.axes) == 3 and fig.axes[0].get_ylabel() == "Value / limit"


def test_genset_short_circuit_in_the_tvc():
    """The genset line through a three-phase short circuit (issue 36's "done when"): the
    coupling against T_Kmax and T_Kmax2 (an exceptional event), in the TVC's rows."""
    model, engine = resolve_model_and_engine("genset-1500")
    res = tvc(model, engine, passage=False, conditions=("normal",))
    (event,) = res.events
    assert event.name == "three-phase short circuit" and event.severity == "exceptional"
    rows = {v.quantity.split(" vs ")[-1]: v for v in res.verdicts if v.condition == event.name}
    assert set(rows) == {"T_Kmax", "T_Kmax2"}
    assert rows["T_Kmax2"].limit == 25e3 and rows["T_Kmax"].limit == 16e3
    # the air-gap torque's peak is near T_r/cos(phi)/X''d = 3596.9/0.8/0.12 = 37.5 kN m; the
    # coupling, tuned far below 50 Hz, carries a fraction of it
    assert 0.0 < rows["T_Kmax"].worst < 37.5e3 and rows["T_Kmax"].passed
    assert event.plot().axes
    assert np.isfinite(event.duration) and event.speed == pytest.approx(1500 / RPM)


def test_a_governed_clutch_says_so_in_its_description():
    """The report's description of a clutch event names the engine's governor and its settings
    when the engine is governed (a [tvc] engine_torque_curve turns it on), and says nothing of
    one when it is not (MODEL above: no torque curve)."""
    governed = MODEL.replace(
        "misfire = false",
        'misfire = false\nengine_torque_curve = [["300 rpm", "4 kN*m"], ["1000 rpm", "6 kN*m"]]',
    ).replace('speeds = ["600 rpm", "0 rpm"]', 'speeds = ["600 rpm", "0 rpm"]\nduration = "0.5 s"')
    descriptions = []
    for text in (MODEL, governed):
        model = parse_torsion_model(tomllib.loads(text), file="line.toml")
        res = tvc(model, passage=False, conditions=("normal",))
        (clutch,) = [e for e in res.events if e.name == "clutch engagement"]
        descriptions.append(clutch.description)
    assert "governor" not in descriptions[0]
    assert "the engine on its governor: sampled PI speed governor" in descriptions[1]
    assert "(k_p = 10, T_i = 1 s, droop 0)" in descriptions[1]  # crankdyn.defaults' values


def test_a_clutch_run_lasts_forty_periods_of_the_locked_line():
    """A clutch whose halves are free while it slips (MODEL: the clutch and the coupling both
    between a and b) has no elastic mode until it locks: its default run is the clutch's rise
    (0.1 s) and 40 periods of the locked line's mode, omega = sqrt(k (1/J_a + 1/J_b)) =
    sqrt(50e3 x 1.5) = 273.86 rad/s (hand-worked), not 40 periods of 1 rad/s (251 s: with the
    engine governed, 25,000 governor samples)."""
    model = parse_torsion_model(tomllib.loads(MODEL), file="line.toml")
    res = tvc(model, passage=False, conditions=("normal",))
    (clutch,) = [e for e in res.events if e.name == "clutch engagement"]
    omega = math.sqrt(50e3 * (1.0 / 1.0 + 1.0 / 2.0))
    assert clutch.duration == pytest.approx(0.1 + 40 * 2 * math.pi / omega, rel=1e-9)
