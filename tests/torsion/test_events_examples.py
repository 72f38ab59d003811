"""The built-in marine line through a clutch engagement, a start through its speed range and an
ice-impact sequence, each with its verdict rows (issue 36's "done when")."""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.io.event_spec import event_from_table
from crankdyn.torsion.event_run import event_response
from crankdyn.tvc.events import EVENT_MODE_FACTOR, judge_event


@lru_cache(maxsize=1)
def _marine():
    from crankdyn.io.catalogue import resolve_model_and_engine
    from crankdyn.session import Analysis

    _model, engine = resolve_model_and_engine("marine-propulsion")
    return Analysis(engine)


def _rows(run):
    """The run's rows by (component's name, limit), judged by the installation's checks."""
    session = _marine()
    run = judge_event(session.loaded_model, run, session.tvc_spec, 750 / RPM)
    return {
        (v.component.split(" (")[0], v.quantity.split(" vs ")[-1]): v
        for v in run.summary().verdicts
    }


def test_marine_clutch_engagement():
    """The gearbox's clutch (on its input shaft) closes with the engine at 350 rpm and the
    propeller at rest: one slip -> stick switch, the coupling against T_Kmax, the shafts
    against tau_T, the gear mesh's reversals."""
    model = _marine().loaded_model
    event = event_from_table(
        {
            "kind": "clutch",
            "between": ["coupling secondary", "pinion"],
            "torque": "60 kN*m",
            "rise_time": "0.5 s",
            "speeds": ["350 rpm", "0 rpm"],
        },
        model=model,
    )
    run = event_response(model, event, duration=2.0)
    assert len(run.switches) == 1 and "slip -> locked" in run.switches[0]
    # after the lock both halves turn together
    a, b = run.masses.index("coupling secondary"), run.masses.index("pinion")
    assert abs(run.mass_speed[-1, a] - run.mass_speed[-1, b]) < 0.5 / RPM
    rows = _rows(run)
    assert rows[("highly elastic coupling", "T_Kmax")].limit == 125e3
    assert ("intermediate shaft", "τ_T") in rows
    assert any("reversal" in quantity for _c, quantity in rows)


def test_marine_start_through_the_speed_range():
    """A start from 280 to 560 rpm in 4 s with the engine's harmonic torques: the mean speed
    passes the range, the shafts' vibratory stresses stay within tau_T."""
    session = _marine()
    model = session.loaded_model
    event = event_from_table(
        {
            "kind": "start",
            "start_speed": "280 rpm",
            "end_speed": "560 rpm",
            "ramp_time": "4 s",
            "governor_time": "0.3 s",
        },
        model=model,
    )
    # the TVC's time resolution: the modes up to EVENT_MODE_FACTOR times the highest order's
    # frequency at the top speed (the modes above it quasi-statically: the modal truncation)
    top = EVENT_MODE_FACTOR * float(np.max(session.orders)) * 560.0 / RPM
    run = event_response(
        model, event, excitation=session.excitation(), orders=session.orders, max_frequency=top
    )
    assert run.speed[0] * RPM == pytest.approx(280.0, abs=2.0)
    assert run.speed[-1] * RPM == pytest.approx(560.0, abs=2.0)
    rows = _rows(run)
    shaft = rows[("propeller shaft", "τ_T")]
    assert shaft.passed and np.isfinite(shaft.worst) and shaft.worst > 0.0


def test_marine_ice_impact_sequence():
    """Case 1 on the 4-blade propeller at 750 rpm of the engine: the propeller slows, the
    sequence's torque reaches the shafts."""
    session = _marine()
    model = session.loaded_model
    event = event_from_table({"kind": "ice", "q_max": "120 kN*m", "case": 1}, model=model)
    assert event.blades == 4  # the propeller source's blade order
    run = event_response(
        model, event, speed=750 / RPM, excitation=session.excitation(), orders=session.orders
    )
    assert run.speed[-1] < run.speed[0]
    rows = _rows(run)
    assert rows[("intermediate shaft", "τ_T")].worst > 0.0
    assert rows[("highly elastic coupling", "T_Kmax")].passed
