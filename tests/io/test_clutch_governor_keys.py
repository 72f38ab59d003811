"""The clutch event's governor keys (crankdyn.io.event_spec): the governor on where a torque
curve is known (the event's, or the model's [tvc] engine_torque_curve), its defaults from
crankdyn.defaults, and the one-line errors of a governor without a curve or a setting without
a governor."""

from __future__ import annotations

import pytest

from crankdyn.constants import RPM
from crankdyn.defaults import DEFAULTS
from crankdyn.errors import InputError
from crankdyn.io.catalogue import resolve_engine
from crankdyn.io.event_spec import event_from_table
from crankdyn.session import Analysis

CLUTCH = {
    "kind": "clutch",
    "between": ["a", "b"],
    "torque": "60 kN*m",
    "rise_time": "0.5 s",
    "speeds": ["350 rpm", "0 rpm"],
}


def test_a_torque_curve_puts_the_engine_on_its_governor_with_the_default_settings():
    curve = [["300 rpm", "14 kN*m"], ["750 rpm", "38.2 kN*m"]]
    event = event_from_table({**CLUTCH, "torque_curve": curve, "governor_droop": 0.04})
    g = event.governor
    assert g is not None and g.droop == 0.04 and g.set_speed is None
    assert g.gain == DEFAULTS["governor_gain"].value
    assert g.integral_time == DEFAULTS["governor_integral_time"].value
    assert g.sample_time == DEFAULTS["governor_sample_time"].value
    assert g.rated_speed == pytest.approx(750 / RPM) and g.rated_torque == pytest.approx(38.2e3)


def test_without_a_curve_there_is_no_governor_and_asking_for_one_is_an_error():
    assert event_from_table(CLUTCH).governor is None
    with pytest.raises(InputError, match="never unlimited") as err:
        event_from_table({**CLUTCH, "governor": True})
    assert "\n" not in str(err.value) and "torque_curve" in str(err.value)
    with pytest.raises(InputError, match="without a governor"):
        event_from_table({**CLUTCH, "governor": False, "governor_gain": 5})


def test_the_marine_tvc_clutch_takes_the_engine_torque_curve_of_its_tvc():
    model = Analysis(resolve_engine("marine-propulsion")).model
    assert model is not None and model.tvc is not None
    clutch = model.tvc.events[0].event
    g = clutch.governor
    assert g is not None
    assert g.torque_curve[1].max() == pytest.approx(38.2e3)
    assert g.max_torque(350 / RPM) == pytest.approx(14e3 + (20e3 - 14e3) * 0.5)
