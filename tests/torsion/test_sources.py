"""Excitation at any mass and order: order conversion through the gears, validation of the
orders, the common period of the synthesis, default orders, mean torque along the line, general
and machine sources, engine sources and source-only models."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.torsion import Gear, Mass, Shaft, TorsionModel
from crankdyn.torsion.campbell import campbell
from crankdyn.torsion.excitation import UniformExcitation, excitation_for
from crankdyn.torsion.sources import (
    HarmonicSource,
    LoadLaw,
    SourceExcitation,
    check_model_orders,
    default_orders,
    electric_machine,
    mean_torques,
    propeller,
    synthesis_index,
    synthesize,
)
from crankdyn.torsion.sweep import forced_response
from crankdyn.torsion.synthesis import half_range


def _line(**source):
    masses = (
        Mass("engine", 2.0, cylinders=(1,)),
        Mass("pinion", 0.1, role="gear"),
        Mass("wheel", 1.0, role="gear"),
        Mass("prop", 30.0, role="propeller"),
    )
    shafts = (
        Shaft(("engine", "pinion"), 2e5, loss_factor=0.02),
        Shaft(("wheel", "prop"), 5e5, loss_factor=0.02),
    )
    gears = (Gear(("pinion", "wheel"), teeth=(20, 64)),)
    src = propeller("prop", 4, fractions=[0.08, 0.02], load=LoadLaw(5000.0, 50.0, 2.0), **source)
    return TorsionModel(masses=masses, shafts=shafts, gears=gears, sources=(src,))


def test_blade_orders_are_converted_to_the_reference_speed():
    model = _line()
    ex = UniformExcitation(10.0, [0.0])
    assert default_orders(model, "four-stroke")[:5] == pytest.approx([0.5, 1.0, 1.25, 1.5, 2.0])
    q = check_model_orders(model, ex, [1.25, 2.5, 3.0])
    assert list(q) == [1.25, 2.5, 3.0]
    with pytest.raises(
        InputError,
        match=r"order 1.3 does not fit the four-stroke cycle \(multiples of 0.5\) and is no "
        r"order of the propeller",
    ) as info:
        check_model_orders(model, ex, [1.3])
    assert info.value.key == "orders" and info.value.value == 1.3
    with pytest.raises(InputError, match="orders must be positive"):
        check_model_orders(model, ex, [0.0])
    with pytest.raises(InputError, match="orders must be positive"):
        check_model_orders(model, ex, [-1.25])


def test_propeller_harmonic_acts_at_its_order_with_the_speed_ratio():
    """A torque T at order p of a mass turning at r enters as r T at order p r (virtual work),
    so the response to the propeller alone is that of a reflected torque."""
    model = _line()
    speeds = np.array([300.0, 800.0]) / RPM
    r = forced_response(model, SourceExcitation(), speeds, [1.25])
    # the same with the torque put by hand on the reflected model (UniformExcitation at the prop)
    plain = dataclasses.replace(
        model,
        masses=tuple(
            dataclasses.replace(m, cylinders=(1,) if m.name == "prop" else ()) for m in model.masses
        ),
        sources=(),
    )
    q = 5000.0 * (0.3125 * speeds / 50.0) ** 2 * 0.08  # actual torque amplitude (N m)
    for s, w in enumerate(speeds):
        # the reference is now the prop (first cylinder mass): its speed is the reference
        one = forced_response(plain, UniformExcitation(q[s], [0.0]), [0.3125 * w], [4.0])
        assert r.amplitude[s, 0] == pytest.approx(one.amplitude[0, 0], rel=1e-9)


def test_synthesis_over_the_common_period():
    assert list(synthesis_index([0.5, 1.0, 1.5], "four-stroke")) == [1, 2, 3]
    assert list(synthesis_index([0.5, 1.25, 3.0], "four-stroke")) == [2, 5, 12]
    assert synthesis_index([0.5, math.pi], "four-stroke") is None
    c = np.array([1.0 + 0.5j, 0.3 - 0.2j, 0.1j])
    top, low = synthesize(c, [0.5, 1.25, 3.0], "four-stroke")
    theta = np.linspace(0.0, 8 * math.pi, 400_001)  # the common period of 0.25: 8 pi
    x = np.real(c[None, :] * np.exp(1j * np.outer(theta, [0.5, 1.25, 3.0]))).sum(axis=1)
    assert top == pytest.approx(x.max(), abs=1e-8)
    assert low == pytest.approx(x.min(), abs=1e-8)
    bound, neg = synthesize(c, [0.5, math.pi, 3.0], "four-stroke")
    assert bound == pytest.approx(np.abs(c).sum()) and neg == pytest.approx(-np.abs(c).sum())
    # the engine orders alone keep the usual index
    top2, low2 = synthesize(c, [0.5, 1.0, 3.0], "four-stroke")
    ref_top, ref_low = half_range(c, [1, 2, 6])
    assert float(top2) == pytest.approx(float(ref_top)) and float(low2) == pytest.approx(
        float(ref_low)
    )


def test_mean_torque_along_the_line_from_the_propeller_law():
    model = _line()
    r = mean_torques(model, [50.0 / 0.3125, 25.0 / 0.3125])
    # the propeller's 5000 N m at 50 rad/s (its speed), 1250 N m at half speed
    assert r.mean_torque[:, 1] == pytest.approx([5000.0, 1250.0], rel=1e-12)
    # the engine side carries r Q: power is conserved through the (lossless) gear
    assert r.mean_torque[:, 0] == pytest.approx([5000.0 * 0.3125, 1250.0 * 0.3125], rel=1e-12)


def test_mean_torque_of_the_built_in_marine_line():
    engine = Engine.example("marine-propulsion")
    model = engine.torsion
    w = 750.0 / RPM
    r = mean_torques(model, [w])
    names = [tuple(s.between) for s in model.shafts]
    coupling = names.index(("coupling primary", "coupling secondary"))
    assert r.mean_torque[0, coupling] == pytest.approx(2900e3 / w, rel=1e-12)
    span = names.index(("throw 3", "throw 4"))  # half the cylinders drive behind it
    assert r.mean_torque[0, span] == pytest.approx(0.5 * 2900e3 / w, rel=1e-12)
    prop_shaft = [
        i for i, s in enumerate(model.shafts) if s.segment_of == ("stern tube flange", "propeller")
    ]
    assert r.mean_torque[0, prop_shaft] == pytest.approx(2900e3 / (w * 25 / 80), rel=1e-12)


def test_no_load_law_is_a_one_line_error():
    model = TorsionModel.example("seed003-v6")
    with pytest.raises(InputError, match="no load law"):
        mean_torques(model, [100.0])


def test_machine_and_tabulated_sources():
    m = electric_machine("gen", 2, [2, 6], torques=[10.0, 5.0])
    assert list(m.orders) == [4.0, 12.0]
    table = HarmonicSource(
        "gen",
        orders=[1.0, 2.0],
        amplitude=[[0.0, 10.0], [100.0, 30.0]],
        phase=[[0.0, 0.0], [math.pi / 2, 0.0]],
        speed=[10.0, 20.0],
    )
    c = table.coefficients([15.0, 5.0, 30.0])
    assert np.abs(c[:, 0]) == pytest.approx([50.0, 0.0, 100.0])
    assert np.abs(c[:, 1]) == pytest.approx([20.0, 10.0, 30.0])
    assert np.angle(c[2, 0]) == pytest.approx(math.pi / 2)
    with pytest.raises(InputError, match="fractions of the mean torque need the load law"):
        HarmonicSource("gen", orders=[1.0], fraction=[0.1])
    with pytest.raises(InputError, match="orders must be positive"):
        HarmonicSource("gen", orders=[0.0], amplitude=[1.0])


def test_source_only_model_and_campbell_marks_what_excites():
    masses = (Mass("motor", 1.0), Mass("load", 3.0))
    src = HarmonicSource("load", orders=[3.0], amplitude=[20.0], name="pump")
    model = TorsionModel(masses=masses, shafts=(Shaft(("motor", "load"), 1e5),), sources=(src,))
    ex = excitation_for(model)
    assert isinstance(ex, SourceExcitation) and ex.cylinder_count == 0
    r = forced_response(model, ex, np.linspace(10.0, 100.0, 5), [3.0])
    assert np.all(r.amplitude > 0.0) and not np.any(r.major)
    c = campbell(model, [3.0], (10.0, 200.0))
    assert c.critical_speeds and all(cs.excited_by == "pump" for cs in c.critical_speeds)
    assert all(cs.major is False and cs.relative_amplitude_sum is None for cs in c.critical_speeds)


def test_campbell_of_the_marine_line_has_engine_and_propeller_orders():
    engine = Engine.example("marine-propulsion")
    model = engine.torsion
    orders = default_orders(model, "four-stroke")
    c = campbell(model, orders, excitation=excitation_for(model, engine))
    assert 1.25 in list(c.orders)  # the first blade order (4 x 25/80)
    excited = {cs.order: cs.excited_by for cs in c.critical_speeds}
    assert excited[3.0] == "engine"
    assert excited[2.5] == "engine, propeller"  # an engine order and the second blade order
    wide = campbell(
        model, [1.25], (150.0 / RPM, 800.0 / RPM), excitation=excitation_for(model, engine)
    )
    assert [cs.excited_by for cs in wide.critical_speeds] == ["propeller", "propeller"]
