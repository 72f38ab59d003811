"""Plausibility warnings (issue 14, point 7): each check fires outside its typical range and only
there, the built-in examples where the values are plausible stay quiet, and the warnings reach
the command line (stderr), the JSON (a ``warnings`` list) and the report's summary."""

from __future__ import annotations

import dataclasses
import json
import math

import pytest

import crankdyn.report.sections as sections
from crankdyn.engine.torque import engine_torque
from crankdyn.errors import InputError
from crankdyn.io.engine_file import load_example, parse_engine
from crankdyn.linkage.fourbar import FourBar, fourbar_analysis
from crankdyn.plausibility import (
    G,
    check_imep,
    check_mean_piston_speed,
    check_peak_pressure,
    check_piston_acceleration,
    check_transmission_angle,
)
from crankdyn.report.build import build_report
from crankdyn.report.write import write_report

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


def _fast(name="vaz2108", rpm=11000.0):
    """A plausible engine driven too fast: mean piston speed 26 m/s, 2700 g."""
    return dataclasses.replace(load_example(name), speed=rpm * math.pi / 30.0)


def test_cli_prints_warnings_and_json_lists_them(cli, tmp_path):
    quiet = cli("kinematics", "vaz2108", "--format", "json")
    assert quiet.status == 0 and "warning" not in quiet.err
    assert "warnings" not in json.loads(quiet.out)
    loud = cli("kinematics", "vaz2108", "--speed", "11000", "--format", "json")
    assert loud.status == 0
    lines = [line for line in loud.err.splitlines() if line.startswith("crankdyn: warning: ")]
    assert len(lines) == 2 and any("mean piston speed 26" in line for line in lines)
    listed = json.loads(loud.out)["warnings"]
    assert {w["check"] for w in listed} == {"mean_piston_speed", "piston_acceleration"}
    assert all({"value", "unit", "typical_low", "typical_high", "source"} <= set(w) for w in listed)
    table = cli("torque", "vaz2108", "--speed", "11000")
    assert table.status == 0 and table.err.count("crankdyn: warning: ") == 2


def test_cli_pressure_warning_follows_the_engine_type(cli, write):
    engine = write(
        "hot.toml",
        'name = "hot"\nfuel = "petrol"\naspiration = "natural"\n'
        '[geometry]\nbore = "80 mm"\nstroke = "80 mm"\nrod_length = "140 mm"\n'
        '[pressure]\nmodel = "wiebe"\nimep = "2.2 MPa"\n',
    )
    run = cli("pressure", engine, "--format", "json")
    assert run.status == 0, run
    assert "crankdyn: warning: IMEP 2.2 MPa is above the 0.9-1.8 MPa" in run.err
    assert json.loads(run.out)["warnings"][0]["check"] == "imep"


def test_report_summary_shows_warnings(tmp_path, monkeypatch):
    monkeypatch.setattr(sections, "BUILDERS", ("kinematics", "pressure"))
    out = write_report(build_report(_fast()), tmp_path / "r")
    summary = json.loads((out / "summary.json").read_text())
    assert {w["check"] for w in summary["warnings"]} == {"mean_piston_speed", "piston_acceleration"}
    assert summary["status"]["max_piston_acceleration_m_s2"] == "warn"
    assert summary["status"]["mean_piston_speed_m_s"] == "warn"
    html = (out / "index.html").read_text()
    summary_part = html[html.index("id='summary'") : html.index("id='inputs'")]
    assert "Plausibility: Mean piston speed" in summary_part
    assert summary_part.count('<span class="badge warn">warn</span>') >= 2
