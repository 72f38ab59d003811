"""Plausibility warnings (issue 14, point 7): each check fires outside its typical range and only
there, the built-in examples where the values are plausible stay quiet, the results carry them
(the session's too, whatever the display grid). How they reach people: the command line in
tests/cli/test_warnings_cli.py, the report in tests/report/test_report.py."""

from __future__ import annotations

import dataclasses
import math

import pytest

from crankdyn.engine.torque import engine_torque
from crankdyn.errors import InputError
from crankdyn.io.catalogue import load_example
from crankdyn.io.engine_file import parse_engine
from crankdyn.linkage.fourbar import FourBar, fourbar_analysis
from crankdyn.plausibility import (
    G,
    check_imep,
    check_mean_piston_speed,
    check_peak_pressure,
    check_piston_acceleration,
    check_transmission_angle,
)
from crankdyn.session import Analysis

EXAMPLES = (
    "inline6-diesel",
    "vaz2108",
    "inline3-petrol",
    "single-cylinder",
    "v8-crossplane",
    "v8-flatplane",
    "v12-60",
)


@pytest.mark.parametrize(
    ("fuel", "aspiration", "quiet", "loud"),
    [
        ("petrol", "natural", 1.7e6, 1.9e6),
        ("petrol", "turbocharged", 3.2e6, 3.4e6),
        ("diesel", "natural", 1.3e6, 1.5e6),
        ("diesel", "turbocharged", 3.7e6, 3.9e6),
        (None, None, 3.7e6, 3.9e6),  # not stated: the widest range of the types
        ("petrol", None, 3.2e6, 3.4e6),
    ],
)
def test_imep_warning(fuel, aspiration, quiet, loud):
    assert check_imep(quiet, fuel, aspiration) == []
    (w,) = check_imep(loud, fuel, aspiration)
    assert w.key == "imep" and w.value == loud and w.unit == "Pa"
    assert w.low < w.high < loud
    assert "Heywood 1988" in w.source and "Heywood 1988" in w.message
    assert w.message.startswith(f"IMEP {w.value_text} is above the ")
    assert "MPa" in w.message and "e+06" not in w.message


@pytest.mark.parametrize(
    ("fuel", "aspiration", "quiet", "loud"),
    [
        ("petrol", "natural", 9e6, 11e6),
        ("petrol", "turbocharged", 14e6, 16e6),
        ("diesel", "natural", 11e6, 13e6),
        ("diesel", "turbocharged", 24e6, 26e6),
        (None, None, 24e6, 26e6),
    ],
)
def test_peak_pressure_warning(fuel, aspiration, quiet, loud):
    assert check_peak_pressure(quiet, fuel, aspiration) == []
    (w,) = check_peak_pressure(loud, fuel, aspiration)
    assert w.key == "peak_pressure" and w.high < loud


def test_piston_acceleration_warning_uses_seed000_ranges():
    # seed 000 sec. 1: petrol 500-1500 g, diesel 200-800 g
    assert check_piston_acceleration(900 * G, "petrol") == []
    (w,) = check_piston_acceleration(900 * G, "diesel")
    assert (w.low, w.high) == pytest.approx((200 * G, 800 * G))
    assert "seed 000" in w.message and "200-800 g" in w.message
    assert check_piston_acceleration(1400 * G) == []
    assert check_piston_acceleration(-1600 * G)  # the magnitude counts
    assert check_piston_acceleration(1501 * G, "petrol")


def test_mean_piston_speed_warning():
    assert check_mean_piston_speed(24.9) == []
    (w,) = check_mean_piston_speed(26.0)
    assert "seed 002" in w.source and w.high == 25.0


def test_transmission_angle_warning():
    assert check_transmission_angle(math.radians(40.0)) == []
    (w,) = check_transmission_angle(math.radians(30.0))
    assert w.key == "transmission_angle" and "Norton" in w.message
    assert "30 deg is below the 40-90 deg" in w.message


def test_fourbar_result_carries_the_transmission_warning():
    # cos mu = (b² + c² - a² - d² + 2 a d cos θ) / (2 b c) (Norton eq. 4.32): 0.68 at θ = 0,
    # the worst angle: mu = acos(0.68) = 47.2 deg
    good = FourBar(0.02, 0.1, 0.1, 0.1)
    assert good.limits.transmission_angle_worst == pytest.approx(math.acos(0.68))
    assert fourbar_analysis(good, [0.0, 1.0]).warnings == ()
    bad = FourBar(0.0734, 0.12536, 0.1034, 0.10352)  # seed 004 link set 1: 10.4 deg
    result = fourbar_analysis(bad, [0.0, 1.0])
    assert [w.key for w in result.warnings] == ["transmission_angle"]
    assert result.to_dict()["warnings"][0]["check"] == "transmission_angle"


@pytest.mark.parametrize("name", EXAMPLES)
def test_builtin_examples_are_plausible(name):
    engine = load_example(name)
    keys = {w.key for w in engine_torque(engine, engine.speed).warnings}
    assert not keys & {"imep", "peak_pressure", "mean_piston_speed"}
    if name in ("inline6-diesel", "vaz2108"):
        assert not keys  # within seed 000's ranges too
    if name == "v8-flatplane":  # 3737 g at 8000 rpm: beyond seed 000's 500-1500 g for petrol
        assert keys == {"piston_acceleration"}


def test_engine_file_states_the_type():
    data = {"name": "e", "fuel": "diesel", "aspiration": "turbocharged", "geometry": {}}
    data["geometry"] = {"bore": "100 mm", "stroke": "120 mm", "rod_length": "240 mm"}
    engine = parse_engine(data, file="e.toml")
    assert (engine.fuel, engine.aspiration) == ("diesel", "turbocharged")
    with pytest.raises(InputError, match="fuel"):
        parse_engine({**data, "fuel": "kerosene"}, file="e.toml")


def test_the_session_passes_the_engine_type_and_keeps_the_full_analysis_warnings():
    """The session's kinematics and pressure are checked against the engine's own type, and
    rows at a coarse display step carry the warnings of the full-resolution analysis."""
    fast = dataclasses.replace(load_example("vaz2108"), speed=11000.0 * math.pi / 30.0)
    a = Analysis(fast)
    full = a.kinematics()
    assert {w.key for w in full.warnings} == {"mean_piston_speed", "piston_acceleration"}
    assert a.kinematics(step=math.radians(30.0)).warnings == full.warnings
    hot = dataclasses.replace(
        load_example("vaz2108"), fuel="petrol", aspiration="natural"
    )  # the vaz2108 trace: its IMEP is plausible for a naturally aspirated petrol engine
    assert Analysis(hot).pressure.warnings == ()
    assert Analysis(hot).pressure_rows(math.radians(30.0)).warnings == ()
