"""The event library, the exact integrator's parts and the event runner's identities."""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.io.event_spec import event_from_table
from crankdyn.io.event_tables import read_torque_history
from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.event_run import event_response
from crankdyn.torsion.events import (
    ClutchEngagement,
    IceImpact,
    ShortCircuit,
    SpeedChange,
    StepTorque,
    TabulatedTorque,
)
from crankdyn.torsion.integrator import free_bodies, linear_recurrence, phi_functions
from crankdyn.tvc.events import judge_event


def _line() -> TorsionModel:
    return TorsionModel(
        masses=(Mass("engine", 4.0), Mass("flywheel", 10.0), Mass("propeller", 30.0)),
        shafts=(
            Shaft(("engine", "flywheel"), 4e5, damping=20.0),
            Shaft(("flywheel", "propeller"), 2e5, damping=10.0),
        ),
    )


# ---- the integrator's parts ------------------------------------------------------------------
def test_phi_functions_continuous_across_the_series_switch():
    z = np.array([0.00999999, 0.01000001, -0.00999999j, -0.01000001j])
    p1, p2 = phi_functions(z)
    assert abs(p1[0] - p1[1]) < 1e-7 and abs(p2[0] - p2[1]) < 1e-7
    assert abs(p1[2] - p1[3]) < 1e-7 and abs(p2[2] - p2[3]) < 1e-7
    e = np.exp(0.5 + 2.0j)
    p1, p2 = phi_functions([0.5 + 2.0j])
    assert p1[0] == pytest.approx((e - 1) / (0.5 + 2.0j), rel=1e-14)
    assert p2[0] == pytest.approx((e - 1 - (0.5 + 2.0j)) / (0.5 + 2.0j) ** 2, rel=1e-14)


def test_linear_recurrence_equals_the_loop():
    rng = np.random.default_rng(3)
    a = np.exp(np.array([-0.01 + 0.3j, 0.2j, -0.5]))
    c = rng.normal(size=(1000, 3)) + 1j * rng.normal(size=(1000, 3))
    w = np.array([1.0, -2.0j, 0.5])
    got = linear_recurrence(a, c, w)
    ref = np.empty_like(c)
    for k in range(c.shape[0]):
        w = a * w + c[k]
        ref[k] = w
    assert np.max(np.abs(got - ref)) < 1e-11 * np.max(np.abs(ref))


def test_free_bodies_of_a_split_line_and_a_grounded_one():
    k = np.array(
        [[1.0, -1.0, 0.0, 0.0], [-1.0, 1.0, 0.0, 0.0], [0.0, 0.0, 2.0, -1.0], [0.0, 0.0, -1.0, 1.0]]
    )
    assert [b.tolist() for b in free_bodies(k, np.zeros((4, 4)))] == [[0, 1]]
    k[2, 2] = 1.0  # no ground: two free bodies
    assert [b.tolist() for b in free_bodies(k, np.zeros((4, 4)))] == [[0, 1], [2, 3]]


# ---- events ----------------------------------------------------------------------------------
@pytest.mark.parametrize(
    ("make", "key"),
    [
        (lambda: StepTorque("", 1.0), "at"),
        (lambda: StepTorque("a", 1.0, rise_time=-1.0), "rise_time"),
        (lambda: TabulatedTorque("a", [0.0, 0.0], [1.0, 2.0]), "time"),
        (lambda: ShortCircuit("g", 1.0, 50.0, 0.3, 0.2, 1.0, 0.02, 0.4, 0.05), "xd2"),
        (lambda: ShortCircuit("g", 1.0, 50.0, 0.1, 0.2, 1.0, 0.02, 0.4, 0.05, phases=1), "phases"),
        (lambda: IceImpact("p", 1e5, blades=4, case=5), "case"),
        (lambda: ClutchEngagement(("a", "b"), 1e3, 0.1, speeds=(10.0, 10.0)), "speeds"),
        (lambda: SpeedChange("start", 80.0, 30.0), "end_speed"),
        (lambda: SpeedChange("launch", 30.0, 80.0), "kind"),
    ],
)
def test_events_refuse_bad_data(make, key):
    with pytest.raises(InputError) as err:
        make()
    assert err.value.key == key


def test_runner_names_an_unknown_mass_and_a_clutch_without_element():
    with pytest.raises(InputError, match=r'no mass named "flywhel".*flywheel') as err:
        event_response(_line(), StepTorque("flywhel", 1.0))
    assert err.value.key == "at"
    with pytest.raises(InputError) as err:
        event_response(_line(), ClutchEngagement(("engine", "propeller"), 1e3, 0.1, (1.0, 0.0)))
    assert err.value.key == "between"


# ---- identities of the runner ----------------------------------------------------------------
def test_ice_impact_momentum_balance():
    """The line's angular momentum changes by the ice torque's impulse (mean torques off,
    damping on the vibration only): to rounding, the impulse of the forcing as integrated
    (linear between the samples: the trapezoidal rule on the run's steps); within that rule's
    error (pi / 20)^2 / 12 = 0.2 %, the exact one: 12 half sines of Q alpha_i / omega (2 / pi)."""
    line = _line()
    w0 = 20.0
    q = 1e3
    event = IceImpact("propeller", q_max=q, blades=4, case=1, revolutions=3.0)
    run = event_response(line, event, speed=w0, mean_torques=False, max_samples=10**6)
    assert run.stride == 1
    j = np.array([4.0, 10.0, 30.0])
    change = float(np.sum(j * run.mass_speed[-1]) - np.sum(j * run.mass_speed[0]))
    applied = event.prepared(w0).torque(run.time)
    sampled = float(np.sum(0.5 * (applied[1:] + applied[:-1]) * np.diff(run.time)))
    assert change == pytest.approx(sampled, rel=1e-9)
    impulse = 12 * 0.75 * q * (math.pi / 2) / w0 * (2 / math.pi)
    assert change == pytest.approx(-impulse, rel=2e-3)


def test_peaks_do_not_depend_on_the_samples_kept():
    """The extremes come from every step: keeping 50 samples or every one gives the same."""
    line = _line()
    event = StepTorque("engine", 500.0, start=0.05, rise_time=0.02)
    full = event_response(line, event, duration=1.0, max_samples=1_000_000)
    few = event_response(line, event, duration=1.0, max_samples=50)
    assert few.time.size <= 50 + 3 and few.stride > 1
    assert np.array_equal(few.max_torque, full.max_torque)
    assert np.array_equal(few.min_torque, full.min_torque)
    assert few.memory_bound < full.memory_bound


def test_a_speed_ramp_follows_its_profile_and_the_mean_torque():
    """A ramp with an unlimited governor: the mean speed follows the set speed exactly and the
    shafts carry the torque that accelerates the masses beyond them (J Omega')."""
    line = _line()
    event = SpeedChange("ramp", 10.0, 30.0, ramp_time=2.0, hold=0.5)
    run = event_response(line, event, duration=3.0)
    set_speed = event.set_speed(run.time)
    assert np.max(np.abs(run.speed - set_speed)) < 1e-3
    # in the ramp, the shaft to the propeller carries J_p a = 30 x 10 = 300 N m on average
    inside = (run.time > 1.0) & (run.time < 2.4)
    assert np.mean(run.torque[inside, 1]) == pytest.approx(300.0, rel=2e-2)


def test_emergency_stop_coasts_to_its_end_speed_under_a_brake():
    line = _line()
    event = SpeedChange("emergency stop", 30.0, 10.0, brake_torque=440.0)
    run = event_response(line, event)
    # no load law: the brake alone decelerates J = 44 kg m^2 at 10 rad/s^2 -> 2 s
    assert run.duration == pytest.approx(2.0, rel=1e-6)
    assert run.speed[-1] == pytest.approx(10.0, abs=0.05)
    assert run.severity == "exceptional"


# ---- readers ---------------------------------------------------------------------------------
def test_torque_history_errors_name_file_and_line(tmp_path):
    bad = tmp_path / "kick.csv"
    bad.write_text("time_s,torque\n0,0\n1,2\n")
    with pytest.raises(InputError, match="torque column must name its unit") as err:
        read_torque_history(bad)
    assert err.value.file is not None and "kick.csv" in err.value.file
    bad.write_text("time_s,torque_N*m\n0,0\n0.2,1\n0.1,2\n")
    with pytest.raises(InputError, match="must increase") as err:
        read_torque_history(bad)
    assert err.value.key == "line 4"
    good = tmp_path / "good.csv"
    good.write_text("# a kick\ntime_ms,torque_kN*m\n0,0\n10,-5\n20,0\n")
    event = TabulatedTorque.from_file(good, "propeller")
    run = event_response(_line(), event, duration=0.5)
    assert run.event == good.name or run.event.endswith("good.csv")


def test_event_tables_check_keys_and_take_the_model_defaults():
    with pytest.raises(InputError, match='did you mean "rise_time"'):
        event_from_table(
            {"kind": "step", "at": "engine", "torque": 1.0, "rise_tim": 1.0}, model=_line()
        )
    with pytest.raises(InputError, match="no mass named"):
        event_from_table({"kind": "step", "at": "engin", "torque": 1.0}, model=_line())
    clutch = event_from_table(
        {
            "kind": "clutch",
            "between": "engine,flywheel",
            "torque": "2 kN*m",
            "rise_time": "0.2 s",
            "speeds": ["300 rpm", "0 rpm"],
        },
        model=_line(),
    )
    assert clutch.speeds == pytest.approx((300 / RPM, 0.0))


@lru_cache(maxsize=1)
def _genset():
    from crankdyn.io.catalogue import resolve_model_and_engine
    from crankdyn.session import Analysis

    _model, engine = resolve_model_and_engine("genset-1500")
    session = Analysis(engine)
    return session


def test_genset_three_phase_short_circuit_against_its_coupling():
    """The genset line through a three-phase short circuit (rated torque from the
    alternator's load law), with the engine's harmonic torques: the coupling's row."""
    session = _genset()
    model = session.loaded_model
    event = event_from_table(
        {
            "kind": "short-circuit",
            "line_frequency": "50 Hz",
            "xd2": 0.12,
            "xd1": 0.25,
            "xd": 2.2,
            "td2": "15 ms",
            "td1": "0.35 s",
            "ta": "40 ms",
        },
        model=model,
    )
    assert event.rated_torque == pytest.approx(565e3 / (1500 / RPM))
    run = event_response(
        model, event, speed=1500 / RPM, excitation=session.excitation(), orders=session.orders
    )
    # judged by the installation's checks, the TVC's one evaluation
    run = judge_event(model, run, session.tvc_spec, 1500 / RPM)
    rows = {v.quantity.split(" vs ")[-1]: v for v in run.summary().verdicts}
    assert {v.component for v in rows.values()} == {"elastic coupling"}
    assert rows["T_Kmax"].limit == 16e3 and rows["T_Kmax"].passed
    # an exceptional event: T_Kmax2 of the catalogue (25 kN m), not T_Kmax1
    assert rows["T_Kmax2"].limit == 25e3 and "T_Kmax1" not in rows
    assert run.largest(("coupling",))[0] > abs(run.initial_torque[7])
