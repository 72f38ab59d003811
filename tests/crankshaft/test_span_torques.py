"""M_TN of every throw from a forced torsional response (crankdyn.crankshaft.span_torques) and
the additional stress of UR M53.4 by source (crankdyn.crankshaft.strength.additional_stress_of),
on responses and crankshafts whose answers are known by construction."""

from __future__ import annotations

import dataclasses
from types import SimpleNamespace

import numpy as np
import pytest

import crankdyn
from crankdyn.constants import RPM
from crankdyn.crankshaft.span_torques import nominal_torques
from crankdyn.crankshaft.strength import additional_stress_of
from crankdyn.errors import InputError


@pytest.fixture(scope="module")
def marine():
    return crankdyn.Engine.example("marine-propulsion")


def _response(model, speeds_rpm, torque, orders=(0.5, 12.0)):
    """A response-like object: the synthesised shaft torques given (speed x shaft)."""
    shafts = tuple(s.between for s in model.shafts)
    return SimpleNamespace(
        speed=np.asarray(speeds_rpm, dtype=float) / RPM,
        synthesized_shaft_torque=np.asarray(torque, dtype=float),
        shafts=shafts,
        orders=np.asarray(orders),
    )


def test_each_throw_takes_the_larger_span_beside_it(marine):
    model = marine.torsion
    shafts = [s.between for s in model.shafts]
    torque = np.zeros((3, len(shafts)))
    span = shafts.index(("throw 3", "throw 4"))
    torque[1, span] = 7e4  # at 500 rpm, between throws 3 and 4
    torque[2, shafts.index(("free end", "throw 1"))] = 2e4  # at 600 rpm
    torque[0, shafts.index(("throw 6", "flywheel"))] = 3e4  # at 400 rpm
    m_tn, where, notes = nominal_torques(marine, model, _response(model, [400, 500, 600], torque))
    assert m_tn.tolist() == [2e4, 0.0, 7e4, 7e4, 0.0, 3e4]
    assert where[2] == where[3] == "throw 3 - throw 4 at 500 rpm"
    assert where[0] == "free end - throw 1 at 600 rpm"
    assert not any("orders" in n for n in notes)  # 0.5 to 12: the rule's for four-stroke


def test_barred_ranges_are_left_out(marine):
    model = marine.torsion
    shafts = [s.between for s in model.shafts]
    torque = np.zeros((3, len(shafts)))
    torque[:, shafts.index(("throw 1", "throw 2"))] = [1e4, 9e4, 2e4]
    response = _response(model, [400, 500, 600], torque)
    barred = [(480 / RPM, 520 / RPM)]
    m_tn, where, notes = nominal_torques(marine, model, response, barred)
    assert m_tn[0] == m_tn[1] == 2e4 and where[0].endswith("at 600 rpm")
    assert any("barred" in n and "480-520 rpm" in n for n in notes)
    with pytest.raises(InputError, match="barred"):
        nominal_torques(marine, model, response, [(300 / RPM, 700 / RPM)])


def test_orders_short_of_the_rules_are_said(marine):
    model = marine.torsion
    response = _response(model, [400], np.ones((1, len(model.shafts))), orders=(0.5, 6.0))
    notes = nominal_torques(marine, model, response)[2]
    assert any("UR M53 asks for 0.5 to 12" in n for n in notes)


def test_additional_stress_by_source(marine):
    trunk = marine.crankshaft
    cross = dataclasses.replace(trunk, engine_type="crosshead")
    # the rule (M53.4 [Annex 5-3 4(1)]): +-10 trunk piston, +-30 crosshead
    assert additional_stress_of(trunk)[0] == 10e6 and additional_stress_of(cross)[0] == 30e6
    # crosshead: the calculated axial part replaces the 20 (4(3)), the 10 of misalignment kept
    value, source = additional_stress_of(cross, 4e6, "web 3 at 700 rpm")
    assert value == 14e6 and "M53.4(3)" in source and "web 3 at 700 rpm" in source
    given = dataclasses.replace(cross, axial_vibration_stress=12e6)
    assert additional_stress_of(given)[0] == 22e6
    # trunk piston: the rule's 10 unless the vibration alone exceeds it (crankdyn's choice)
    assert additional_stress_of(trunk, 4e6)[0] == 10e6
    value, source = additional_stress_of(trunk, 12e6)
    assert value == 12e6 and "crankdyn takes the larger" in source
