"""The conditions a surveyor expects (issue 32 item 5): misfire from the engine builder's table
of a model without an engine, the passage driven by the engine's torque-speed curve (never the
rated torque at low speed unless asked), overspeed to the rule's top speed, declutched and idle
running where a clutch is modelled."""

from __future__ import annotations

import dataclasses
import tomllib

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.io.catalogue import resolve_model_and_engine
from crankdyn.io.torsion_file import parse_torsion_model
from crankdyn.tvc import TvcSpec, rulesets, tvc
from crankdyn.tvc.conditions import (
    IDLE_BAND,
    conditions,
    declutched_model,
    overspeed_ratio,
    unloaded_model,
)
from crankdyn.tvc.passage import engine_torque


@pytest.fixture(scope="module")
def builder():
    model, _engine = resolve_model_and_engine("marine-builder-line")
    return model


@pytest.fixture(scope="module")
def marine():
    from crankdyn.session import Analysis

    _model, engine = resolve_model_and_engine("marine-propulsion")
    return Analysis(engine).loaded_model, engine


def test_builder_table_gives_every_misfire(builder):
    notes: list[str] = []
    conds = conditions(builder, None, builder.tvc, 750 / RPM, notes, ("normal", "misfire"))
    misfires = [c for c in conds if c.kind == "misfire"]
    assert [c.misfire for c in misfires] == [1, 2, 3, 4, 5, 6]
    assert all("marine-builder-harmonics.csv" in c.description for c in misfires)
    # the misfiring cylinder takes the table's misfire coefficients, the others fire
    orders = [0.5, 1.0, 3.0]
    normal = conds[0].excitation.harmonics([60.0], orders)
    third = misfires[2].excitation.harmonics([60.0], orders)
    table = builder.excitation.cylinder_harmonics
    assert np.abs(third[0, :, 2]) == pytest.approx(
        np.abs(table.at([60.0], orders, misfiring=True)[0]), rel=1e-12
    )
    others = [0, 1, 3, 4, 5]
    assert third[0][:, others] == pytest.approx(normal[0][:, others], rel=1e-15)


def test_overspeed_to_the_rule_sets_top_speed():
    ratio, source = overspeed_ratio(TvcSpec())
    iacs = rulesets.get("iacs-m68").overspeed
    assert ratio == iacs.value == 1.05 and source == iacs.clause.cite()
    assert overspeed_ratio(TvcSpec(overspeed_limit=1.1)) == (1.1, "[tvc] overspeed_limit")
    with pytest.raises(InputError, match="overspeed_limit"):
        TvcSpec(overspeed_limit=0.9)
    model, _ = resolve_model_and_engine("verdict-geared-line")  # n_0 = 1000 rpm
    notes: list[str] = []
    conds = conditions(model, None, TvcSpec(), 1000 / RPM, notes, ("normal", "overspeed"))
    (over,) = [c for c in conds if c.kind == "overspeed"]
    assert (over.low * RPM, over.high * RPM) == pytest.approx((1000.0, 1050.0), rel=1e-12)
    assert "1.05 n_0" in over.description and "IACS UR M68" in over.description
    # a normal range reaching past 1.05 n_0 needs no overspeed condition: a note says so
    spec = TvcSpec(speed_range=(400 / RPM, 1100 / RPM))
    conds = conditions(model, None, spec, 1000 / RPM, notes, ("normal", "overspeed"))
    assert [c.kind for c in conds] == ["normal"] and "no separate condition" in notes[-1]
    res = tvc(model, spec=TvcSpec(misfire=False), passage=False, conditions=("normal", "overspeed"))
    assert {v.condition for v in res.verdicts} >= {"normal firing", "overspeed"}


def test_declutched_line_is_the_engines_side(builder):
    line = declutched_model(builder, ("coupling secondary", "pinion"))
    kept = ["free end", *(f"throw {i}" for i in range(1, 7)), "flywheel", "coupling secondary"]
    assert list(line.mass_names) == kept
    assert not line.gears and not line.sources and line.rules is None
    assert all(set(s.between) <= set(kept) for s in line.shafts)
    with pytest.raises(InputError, match="no shaft or coupling joins"):
        declutched_model(builder, ("free end", "flywheel"))


def test_idle_and_declutched_run_without_load(marine):
    model, engine = marine
    line, how = unloaded_model(model, engine)
    # no load: the propeller's load and excitation gone, the pressure at 1 - eta_m
    assert not [s for s in line.sources if getattr(s, "load", None) is not None]
    curve = line.excitation.load_curve
    assert curve.kind == "load_factor" and curve.value[0] == pytest.approx(1 - 0.92)
    assert "1 - eta_m" in how and "propeller" in how
    spec = dataclasses.replace(model.tvc, clutch=("coupling secondary", "pinion"))
    notes: list[str] = []
    conds = conditions(model, engine, spec, 750 / RPM, notes, ("normal", "declutched", "idle"))
    declutched, idle = conds[1], conds[2]
    assert declutched.kind == "declutched" and "propeller" not in declutched.model.mass_names
    assert idle.kind == "idle" and idle.model.mass_names == model.mass_names
    low = spec.range_of("normal", model)[0]  # no idle_speed: the range's lowest speed
    assert (idle.low, idle.high) == pytest.approx((low * (1 - IDLE_BAND), low * (1 + IDLE_BAND)))
    # the same inertia torques, the gas torques of the unloaded pressure
    loaded = conds[0].excitation.parts([350 / RPM], [3.0])
    unloaded = idle.excitation.parts([350 / RPM], [3.0])
    assert unloaded[1] == pytest.approx(loaded[1], rel=1e-12)
    assert np.abs(unloaded[0]).max() < np.abs(loaded[0]).max()


def test_builder_tvc_runs_every_condition(builder):
    spec = dataclasses.replace(builder.tvc, misfire=False)  # misfire: the test above
    res = tvc(builder, spec=spec, passage=False)
    kinds = [c.kind for c in res.conditions]
    assert kinds == ["normal", "overspeed", "declutched", "idle"]
    declutched = [v for v in res.verdicts if v.condition == "declutched"]
    assert declutched and not any("shaft (" in v.component for v in declutched)
    assert any("keeps its excitation's coefficients" in n for n in res.notes)


def test_passage_torque_is_the_curve_never_the_rated_torque_unless_asked():
    text = """
name = "line"
[operating]
speed_range = ["400 rpm", "1000 rpm"]
rated_speed = "1000 rpm"
[excitation]
torque = "1 kN*m"
[tvc]
passage_torque = "rated"
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
    assert model.tvc.passage_torque == "rated"
    torque, words = engine_torque(TvcSpec(), model, 100.0)
    assert torque is None and "engine_torque_curve" in words and "rated" in words
    curve = TvcSpec(engine_torque_curve=([40.0, 100.0], [2e4, 4e4]))
    torque, words = engine_torque(curve, model, 100.0)
    assert torque([70.0]).tolist() == [3e4] and "torque-speed curve" in words
    # no load law here: the rated torque is not known either
    assert engine_torque(TvcSpec(passage_torque="rated"), model, 100.0)[0] is None
    with pytest.raises(InputError, match="passage_torque"):
        TvcSpec(passage_torque="rated", engine_torque=1e4)
    bad = text.replace('passage_torque = "rated"', 'passage_torque = "full"')
    with pytest.raises(InputError, match="passage_torque"):
        parse_torsion_model(tomllib.loads(bad), file="line.toml")


def test_passage_rows_say_which_torque(marine):
    """The geared line's permitted barred range is passed with the engine's torque curve and
    its rows say so; without the curve no passage is calculated; the rated torque (the marine
    line's propeller law at n_0) only when asked."""
    geared, _ = resolve_model_and_engine("verdict-geared-line")
    base = TvcSpec(tachometer_tolerance=0.0, misfire=False, overspeed=False)
    curve = dataclasses.replace(base, engine_torque_curve=([40.0, 110.0], [2e4, 4e4]))
    res = tvc(geared, spec=curve, conditions=("normal",))
    rows = [v for v in res.verdicts if v.quantity.startswith("transient peak passing")]
    assert res.passages and rows and all("engine_torque_curve" in v.note for v in rows)
    assert all("none (run up unloaded)" in p.note for p in res.passages)
    none = tvc(geared, spec=base, conditions=("normal",))
    assert not none.passages and any("not calculated" in n for n in none.notes)
    model, _engine = marine
    torque, words = engine_torque(TvcSpec(passage_torque="rated"), model, 750 / RPM)
    from crankdyn.tvc.passage import load_torque

    rated = float(load_torque(model, [750 / RPM])[0])
    assert torque([300 / RPM, 500 / RPM]).tolist() == [rated, rated]
    assert 'passage_torque = "rated"' in words and f"{rated / 1e3:.6g} kN·m" in words
