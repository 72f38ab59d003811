"""The model held against a measurement: conventions and refusals."""

import math

import numpy as np
import pytest

from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.measure.compare import with_shaft_loss_factor
from crankdyn.measure.orders import order_analysis
from crankdyn.measure.synthetic import PrescribedMotion, synthetic_pulses
from crankdyn.torsion import Gear, Mass, Shaft, TorsionModel
from crankdyn.torsion.excitation import UniformExcitation, excitation_for
from crankdyn.torsion.orders import order_grid
from crankdyn.torsion.sweep import forced_response

RPM = 30.0 / math.pi


def test_measured_phases_follow_the_models_crank_angle():
    """The pulley of the inline-6 moving exactly as the model predicts at 1700 rpm, measured
    with the reference mark at cylinder 1's firing TDC: measured over model is 1 and the
    phases agree (the same crank-angle origin and sign on both sides)."""
    engine = Engine.example("inline6-diesel")
    model, ex = engine.torsion, excitation_for(engine.torsion, engine)
    orders = order_grid(0.5, 12.0, 0.5, ex.cycle)
    speed = 1700 / RPM
    x = forced_response(model, ex, [speed], orders).mass_response[0, :, 0]
    motion = PrescribedMotion(speed, 0.0, orders, x)
    measured = order_analysis(synthetic_pulses(motion, 60, 1.5, reference_every=2))
    cmp = measured.with_model(model, ex, "pulley").comparison
    big = np.abs(x) > 1e-4
    assert np.allclose(measured.amplitude[big] / cmp.amplitude[0, big], 1.0, atol=2e-3)
    phase = np.degrees(np.abs(np.angle(np.exp(1j * (measured.phase - cmp.phase[0])))))
    assert np.max(phase[big]) < 0.1
    assert measured.synthesized == pytest.approx(float(cmp.synthesized[0]), rel=2e-3)


def test_a_geared_mass_is_refused():
    model = TorsionModel(
        masses=(Mass("engine", 1.0, cylinders=(1,)), Mass("pinion", 0.1), Mass("load", 2.0)),
        shafts=(Shaft(("engine", "pinion"), 1e5), Shaft(("load", "ground"), 1e5)),
        gears=(Gear(("pinion", "load"), 2.0),),
    )
    motion = PrescribedMotion(1500 / RPM, 0.0, np.array([1.0]), np.array([1e-3]))
    measured = order_analysis(
        synthetic_pulses(motion, 60, 1.0, reference_every=2), orders=[1.0], cycle="two-stroke"
    )
    with pytest.raises(InputError, match="turns at 2 times the crankshaft speed"):
        measured.with_model(model, UniformExcitation(1.0, [0.0], "two-stroke"), "load")


def test_cycle_mismatch_is_refused():
    motion = PrescribedMotion(1500 / RPM, 0.0, np.array([1.0]), np.array([1e-3]))
    measured = order_analysis(synthetic_pulses(motion, 60, 1.0, reference_every=2), orders=[1.0])
    model = TorsionModel(
        masses=(Mass("disc", 1.0, cylinders=(1,)),), shafts=(Shaft(("ground", "disc"), 1e5),)
    )
    with pytest.raises(InputError, match="analysed as four-stroke, the model's excitation is"):
        measured.with_model(model, UniformExcitation(1.0, [0.0], "two-stroke"), "disc")


def test_with_shaft_loss_factor_changes_only_the_loss_factors():
    model = Engine.example("inline6-diesel").torsion
    new = with_shaft_loss_factor(model, 0.08)
    assert {s.loss_factor for s in new.shafts} == {0.08}
    assert [s.stiffness for s in new.shafts] == [s.stiffness for s in model.shafts]
    assert new.masses == model.masses
