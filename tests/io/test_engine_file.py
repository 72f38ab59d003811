"""Engine files: every documented key, the examples, and one-line errors for bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.errors import InputError
from crankdyn.io.catalogue import load_example, resolve_engine
from crankdyn.io.engine_file import load_engine
from crankdyn.io.examples import example_names

BASE = """
name = "test engine"
cycle = "four-stroke"
[geometry]
bore = "76 mm"
stroke = "71 mm"
rod_length = "136.5 mm"
offset = "0 mm"
[cylinders]
count = 4
layout = "inline"
firing_order = [1, 3, 4, 2]
throw_angles = ["0 deg", "180 deg", "180 deg", "0 deg"]
pitch = "86 mm"
[masses]
piston_group = "0.45 kg"
rod = "0.62 kg"
rod_cg_from_big_end = "35 mm"
rod_inertia = "2.1e-3 kg*m^2"
crank_unbalance = "0.4 kg"
[operating]
speed = "4900 rpm"
"""


def test_issue_example_file_loads(write):
    e = load_engine(write("e.toml", BASE))
    g = e.geometry
    assert (g.bore, g.crank_radius, g.rod_length, g.offset) == pytest.approx(
        (0.076, 0.0355, 0.1365, 0.0)
    )
    assert e.cylinders.firing_order == (1, 3, 4, 2)
    np.testing.assert_allclose(np.degrees(e.cylinders.throw_angles), [0, 180, 180, 0])
    np.testing.assert_allclose(np.degrees(e.cylinders.firing_angles), [0, 540, 180, 360])
    assert e.cylinders.pitch == pytest.approx(0.086)
    assert e.masses.rod_inertia == pytest.approx(2.1e-3)
    assert e.speed == pytest.approx(4900 * math.pi / 30)


def test_bare_si_numbers_and_alternative_keys(write):
    text = (
        BASE.replace('stroke = "71 mm"', "crank_radius = 0.0355")
        .replace('rod_length = "136.5 mm"', "rod_ratio = 0.26")
        .replace('speed = "4900 rpm"', 'speed = "513.1268 rad/s"')  # a bare speed is refused
    )
    e = load_engine(write("e.toml", text))
    assert e.geometry.crank_radius == 0.0355
    assert e.geometry.rod_length == pytest.approx(0.0355 / 0.26)
    assert e.speed == pytest.approx(513.1268)


def test_throw_angles_derived_from_firing_order(write):
    e = load_engine(
        write(
            "e.toml", BASE.replace('throw_angles = ["0 deg", "180 deg", "180 deg", "0 deg"]\n', "")
        )
    )
    np.testing.assert_allclose(np.degrees(e.cylinders.throw_angles), [0, 180, 180, 0])


@pytest.mark.parametrize("name", ["inline6-diesel", "single-cylinder", "v8-crossplane", "vaz2108"])
def test_examples_load(name):
    e = load_example(name)
    assert e.name and e.geometry.lam < 0.5
    assert resolve_engine(name) == e


def test_example_list():
    assert {"inline6-diesel", "single-cylinder", "v8-crossplane", "vaz2108"} <= set(
        example_names("engine")
    )


def test_inline6_example_is_mendes2008():
    e = load_example("inline6-diesel")
    assert e.geometry.bore == pytest.approx(0.105)
    assert e.geometry.crank_radius == pytest.approx(0.0685)
    assert e.geometry.rod_length == pytest.approx(0.207)
    assert e.cylinders.firing_order == (1, 5, 3, 6, 2, 4)
    np.testing.assert_allclose(np.degrees(e.cylinders.firing_angles), [0, 480, 240, 600, 120, 360])
    peak, at = e.pressure.peak
    assert peak == pytest.approx(15.199226e6)
    assert math.degrees(at) == pytest.approx(367.682927 - 360)


def test_v8_crossplane_arrangement():
    """Cross-plane crank: throws at 0, 90, 270, 180 deg; firing every 90 deg."""
    c = load_example("v8-crossplane").cylinders
    np.testing.assert_allclose(np.degrees(c.throw_positions), [0, 90, 270, 180], atol=1e-9)
    fired = np.sort(np.degrees(c.firing_angles))
    np.testing.assert_allclose(fired, np.arange(0, 720, 90), atol=1e-9)


def _err(write, text, name="bad.toml"):
    with pytest.raises(InputError) as info:
        load_engine(write(name, text))
    message = str(info.value)
    assert "\n" not in message
    assert f"{name}: " in message
    return message


@pytest.mark.parametrize(
    "old, new, expected",
    [
        (
            'bore = "76 mm"',
            'bore = "76 kg"',
            '[geometry] bore = "76 kg": expected a length (e.g. "76 mm"), got a mass',
        ),
        ('bore = "76 mm"', 'bore = "-76 mm"', '[geometry] bore = "-76 mm": must be positive'),
        ('bore = "76 mm"', 'bore = "76 s"', "got a time"),
        ('bore = "76 mm"', 'bore = "76 mmm"', "unknown unit"),
        ('bore = "76 mm"', 'bore = "nan mm"', "[geometry] bore"),
        ('bore = "76 mm"', "bore = inf", "not finite"),
        ('bore = "76 mm"\n', "", "[geometry] bore: missing"),
        ('bore = "76 mm"', 'boer = "76 mm"', 'did you mean "bore"'),
        ('rod_length = "136.5 mm"', 'rod_length = "30 mm"', "must be longer than the crank radius"),
        ('rod_length = "136.5 mm"', "rod_ratio = 1.2", "rod ratio R/L must be less than 1"),
        ('offset = "0 mm"', 'offset = "110 mm"', "offset stops the crank from turning"),
        (
            "firing_order = [1, 3, 4, 2]",
            "firing_order = [1, 3, 3, 2]",
            "must name each of the 4 cylinders",
        ),
        (
            "firing_order = [1, 3, 4, 2]",
            "firing_order = [1, 2, 3, 4]",
            "does not fit the throw angles",
        ),
        (
            'throw_angles = ["0 deg", "180 deg", "180 deg", "0 deg"]',
            "throw_angles = [0, 180, 180, 0]",
            'did you mean "180 deg"',
        ),
        ('layout = "inline"', 'layout = "W"', "expected one of 'inline', 'V'"),
        ('layout = "inline"', 'layout = "V"', "bank_angle: missing"),
        ('cycle = "four-stroke"', 'cycle = "fourstroke"', 'did you mean "four-stroke"'),
        ('piston_group = "0.45 kg"', 'piston_group = "-0.45 kg"', "must not be negative"),
        (
            'rod_cg_from_big_end = "35 mm"',
            'rod_cg_from_big_end = "150 mm"',
            "centre of gravity must lie between the pin centres",
        ),
        ('rod_inertia = "2.1e-3 kg*m^2"', 'rod_inertia = "0.1 kg*m^2"', "3-mass rod model"),
        ('speed = "4900 rpm"', 'speed = "4900 m"', "expected a rotational speed"),
        ("count = 4", "count = 4.5", "expected a whole number"),
        ('name = "test engine"', "name = 3", "[name|expected a string]"),
        ("[operating]", "[operatin]", 'unknown key (did you mean "operating"?)'),
    ],
)
def test_bad_input_one_line(write, old, new, expected):
    assert old in BASE
    message = _err(write, BASE.replace(old, new, 1))
    if expected.startswith("[") and "|" in expected:
        assert all(part in message for part in expected.strip("[]").split("|"))
    else:
        assert expected in message


def test_missing_name_and_geometry(write):
    assert "name: missing" in _err(write, "[geometry]\nbore = 0.1\n")
    assert "missing table [geometry]" in _err(write, 'name = "x"\n')


def test_invalid_toml_and_files(write, tmp_path):
    assert "invalid TOML" in _err(write, "name = \n")
    with pytest.raises(InputError, match="no such engine file"):
        load_engine(tmp_path / "nope.toml")
    path = tmp_path / "latin1.toml"
    path.write_bytes('name = "Mot\xf6r"\n'.encode("latin-1"))
    with pytest.raises(InputError, match="not UTF-8"):
        load_engine(path)
    with pytest.raises(InputError, match="is a directory"):
        load_engine(tmp_path)


def test_huge_file_bounded(tmp_path):
    path = tmp_path / "huge.toml"
    path.write_bytes(b"#" * (2 << 20))
    with pytest.raises(InputError, match="larger than"):
        load_engine(path)


TRACE = "crank_angle_deg,pressure_MPa\n" + "".join(
    f"{a},{0.1 + 5.0 * math.exp(-(((a - 360) / 30) ** 2)):.6f}\n" for a in range(0, 721, 20)
)


def test_pressure_trace_relative_to_engine_file(tmp_path, write):
    sub = tmp_path / "engines"
    sub.mkdir()
    (sub / "trace.csv").write_text(TRACE, encoding="utf-8")
    text = BASE + '[pressure]\nfile = "trace.csv"\nfiring_tdc = "360 deg"\n'
    (sub / "e.toml").write_text(text, encoding="utf-8")
    e = load_engine(sub / "e.toml")
    peak, at = e.pressure.peak
    assert peak == pytest.approx(5.1e6) and at == pytest.approx(0.0)
    assert e.pressure.at(np.array([4 * math.pi])) == pytest.approx(5.1e6)
    assert e.crankcase_pressure == pytest.approx(101325.0)


@pytest.mark.parametrize(
    "trace, expected",
    [
        (TRACE.replace("pressure_MPa", "pressure"), "must name its unit"),
        (TRACE.replace("pressure_MPa", "pressure_MPaa"), "unknown pressure unit"),
        (TRACE.replace("crank_angle_deg,", "crank_angle_kg,"), "unknown crank-angle unit"),
        (TRACE.replace("\n100,", "\n100,abc\n999,", 1), "not a number"),
        (TRACE.replace(",0.100", ",-0.100", 1), "absolute pressure must be positive"),
        ("crank_angle_deg,pressure_MPa\n0,1\n10,2\n20,3\n", "does not cover the cycle"),
        ("0,1\n10,2\n", "header naming the units"),
        ("", "empty"),
    ],
)
def test_bad_traces(tmp_path, trace, expected):
    (tmp_path / "t.csv").write_text(trace, encoding="utf-8")
    (tmp_path / "e.toml").write_text(BASE + '[pressure]\nfile = "t.csv"\n', encoding="utf-8")
    with pytest.raises(InputError) as info:
        load_engine(tmp_path / "e.toml")
    assert expected in str(info.value)
    assert "\n" not in str(info.value)


def test_missing_trace_names_engine_key(tmp_path):
    (tmp_path / "e.toml").write_text(BASE + '[pressure]\nfile = "none.csv"\n', encoding="utf-8")
    with pytest.raises(InputError, match=r'\[pressure\] file = "none.csv": no such pressure'):
        load_engine(tmp_path / "e.toml")


def test_v_engine_throw_consistency(write):
    v8 = """
name = "v"
[geometry]
bore = "100 mm"
stroke = "90 mm"
rod_length = "150 mm"
[cylinders]
count = 8
layout = "V"
bank_angle = "90 deg"
firing_order = [1, 5, 4, 8, 6, 3, 7, 2]
"""
    # default numbering (1-4 bank A, 5-8 bank B, i and i+4 on throw i): 1-5-4-8-6-3-7-2 is the
    # cross-plane order of that numbering, throws at 0, 90, 270, 180 deg
    c = load_engine(write("v8.toml", v8)).cylinders
    np.testing.assert_allclose(np.degrees(c.throw_positions), [0, 90, 270, 180], atol=1e-9)
    # cylinders 1 and 5 share a throw, so 5 must reach TDC 90 deg after 1; in 1-2-...-8 it is 360
    message = _err(write, v8.replace("[1, 5, 4, 8, 6, 3, 7, 2]", "[1, 2, 3, 4, 5, 6, 7, 8]"))
    assert "cylinders 1 (bank A) and 5 (bank B) share throw 1" in message
    assert "give throw_angles" in message
