"""The command line, in process."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.kinematics import dead_centres, slider_crank_exact

KIN_KEYS = (
    "crank_angle_deg",
    "displacement_m",
    "velocity_m_s",
    "acceleration_m_s2",
    "rod_angle_deg",
    "rod_angular_velocity_rad_s",
    "rod_angular_acceleration_rad_s2",
)
SUMMARY_KEYS = (
    "stroke_m",
    "tdc_crank_angle_deg",
    "bdc_crank_angle_deg",
    "mean_piston_speed_m_s",
    "max_velocity_m_s",
    "crank_angle_at_max_velocity_deg",
    "max_acceleration_m_s2",
    "min_acceleration_m_s2",
)


def test_help_and_version(cli):
    run = cli("--help")
    assert run.status == 0 and "kinematics" in run.out
    assert cli("--version").status == 0
    assert cli("kinematics", "--help").status == 0


def test_kinematics_json_central(cli):
    run = cli("kinematics", "vaz2108", "--format", "json", "--step", "5")
    assert run.status == 0, run
    data = json.loads(run.out)
    for key in KIN_KEYS:
        assert len(data[key]) == 73
    for key in SUMMARY_KEYS:
        assert isinstance(data["summary"][key], float)
    # independent calculation at 90 deg: x = R + L (1 - cos beta), a = -R w^2 tan(beta)
    r, lam, w = 0.0355, 0.26, 4900 * math.pi / 30
    beta = math.asin(lam)
    i = data["crank_angle_deg"].index(90.0)
    assert data["displacement_m"][i] == pytest.approx(r + r / lam * (1 - math.cos(beta)))
    assert data["velocity_m_s"][i] == pytest.approx(r * w)
    assert data["acceleration_m_s2"][i] == pytest.approx(-r * w * w * math.tan(beta))
    assert data["summary"]["stroke_m"] == pytest.approx(0.071)
    assert data["summary"]["max_acceleration_m_s2"] == pytest.approx(r * w * w * (1 + lam))


def test_kinematics_json_offset(cli, write):
    path = write(
        "off.toml",
        """
name = "offset single"
[geometry]
bore = "80 mm"
crank_radius = "40 mm"
rod_length = "140 mm"
offset = "4 mm"
[operating]
speed = "3000 rpm"
""",
    )
    run = cli("kinematics", path, "--format", "json", "--step", "1")
    assert run.status == 0, run
    data = json.loads(run.out)
    tdc, bdc, stroke = dead_centres(0.04, 0.14, 0.004)
    s = data["summary"]
    assert s["tdc_crank_angle_deg"] == pytest.approx(math.degrees(tdc))
    assert s["bdc_crank_angle_deg"] == pytest.approx(math.degrees(bdc))
    assert s["stroke_m"] == pytest.approx(stroke)
    assert s["mean_piston_speed_m_s"] == pytest.approx(stroke * 3000 / 30)
    # independent: piston position from the triangle geometry at 40 deg
    phi = math.radians(40.0)
    pin = np.array([0.04 * math.sin(phi), 0.04 * math.cos(phi)])
    y = pin[1] + math.sqrt(0.14**2 - (0.004 - pin[0]) ** 2)
    x = math.sqrt(0.18**2 - 0.004**2) - y
    assert data["displacement_m"][40] == pytest.approx(x, rel=1e-12)


def test_kinematics_approx_and_series(cli):
    exact = json.loads(cli("kinematics", "vaz2108", "--format", "json").out)
    approx = json.loads(cli("kinematics", "vaz2108", "--format", "json", "--method", "approx").out)
    series = json.loads(
        cli("kinematics", "vaz2108", "--format", "json", "--method", "series", "--order", "20").out
    )
    r, w = 0.0355, 4900 * math.pi / 30
    phi = np.radians(approx["crank_angle_deg"])
    np.testing.assert_allclose(
        approx["acceleration_m_s2"], r * w * w * (np.cos(phi) + 0.26 * np.cos(2 * phi)), atol=1e-9
    )
    np.testing.assert_allclose(series["acceleration_m_s2"], exact["acceleration_m_s2"], atol=1e-6)
    assert approx["summary"]["method"] == "approx"


def test_kinematics_speed_option_and_csv(cli):
    run = cli("kinematics", "vaz2108", "--speed", "3000", "--format", "csv", "--step", "90")
    lines = run.out.strip().splitlines()
    assert lines[0].split(",")[:3] == ["crank_angle_deg", "displacement_m", "velocity_m_s"]
    assert len(lines) == 6
    v90 = float(lines[2].split(",")[2])
    assert v90 == pytest.approx(0.0355 * 3000 * math.pi / 30, rel=1e-9)
    run = cli("kinematics", "vaz2108", "--speed", "50 Hz", "--format", "json", "--step", "90")
    assert json.loads(run.out)["summary"]["speed_rpm"] == pytest.approx(3000)


def test_kinematics_table_format(cli):
    run = cli("kinematics", "vaz2108")
    assert run.status == 0
    assert "velocity" in run.out and "Max piston speed" in run.out
    assert "e-15" not in run.out  # round-off next to large values prints as 0


def test_output_file_is_not_overwritten(cli, tmp_path):
    out = tmp_path / "k.json"
    assert cli("kinematics", "vaz2108", "--format", "json", "-o", out).status == 0
    first = out.read_text()
    run = cli("kinematics", "vaz2108", "--format", "json", "-o", out, "--speed", "1000")
    assert run.status == 2 and "already exists" in run.err
    assert out.read_text() == first
    assert (
        cli(
            "kinematics", "vaz2108", "--format", "json", "-o", out, "--speed", "1000", "--force"
        ).status
        == 0
    )
    assert json.loads(out.read_text())["summary"]["speed_rpm"] == pytest.approx(1000)


@pytest.mark.parametrize(
    "args, fragment",
    [
        (("kinematics", "vaz2108", "--speed", "76 kg"), '--speed = "76 kg": expected a rotational'),
        (("kinematics", "vaz2108", "--speed", "-5"), "--speed"),
        (("kinematics", "vaz2108", "--step", "7"), "must divide 360 deg evenly"),
        (("kinematics", "vaz2108", "--step", "0"), "--step"),
        (("kinematics", "vaz2109"), 'did you mean "vaz2108"'),
        (("kinematics", "missing.toml"), "missing.toml: no such engine file"),
        (("kinematics", "vaz2108", "--spede", "3"), "No such option"),
        (("kinematics", "vaz2108", "--method", "magic"), "Invalid value for '--method'"),
        (("kinematics", "vaz2108", "--method", "series", "--order", "3"), "--order"),
        (("kinematics",), "Missing argument"),
        (("coefficients", "--lambda", "1.5"), "λ = R/L must lie between 0 and 1"),
        (("coefficients", "--lambda", "0.3", "--offset-ratio", "5"), "offset ratio"),
        (("example", "nope"), "no built-in example"),
        (("frobnicate",), "No such command"),
    ],
)
def test_errors_one_line_status_2(cli, args, fragment):
    run = cli(*args)
    assert run.status == 2, run
    lines = run.err.strip().splitlines()
    assert len(lines) == 1, run.err
    assert lines[0].startswith("crankdyn: error: ")
    assert fragment in lines[0]
    assert "Traceback" not in run.err


def test_kinematics_speed_missing(cli, write):
    path = write(
        "e.toml", 'name = "x"\n[geometry]\nbore = 0.08\nstroke = 0.08\nrod_length = 0.14\n'
    )
    run = cli("kinematics", path)
    assert run.status == 2 and "no speed" in run.err


def test_coefficients_table(cli):
    run = cli("coefficients", "--lambda", "1/3.8,0.26", "--format", "json", "--step", "30")
    data = json.loads(run.out)
    assert data["lambda"] == pytest.approx([1 / 3.8, 0.26])
    assert data["crank_angle_deg"] == [0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0]
    np.testing.assert_allclose(data["acceleration_coefficient"][1][0], 1.26)
    m = slider_crank_exact(np.radians(30.0), 1.0, 3.8)
    assert data["velocity_coefficient"][0][1] == pytest.approx(float(m.velocity))
    csv_head = cli("coefficients", "--lambda", "0.25", "--format", "csv").out.splitlines()[0]
    assert csv_head == "crank_angle_deg,A_0.25,B_0.25,C_0.25"


def test_examples_and_example(cli, tmp_path, monkeypatch):
    run = cli("examples")
    assert run.status == 0 and "inline6-diesel" in run.out and "v8-crossplane" in run.out
    monkeypatch.chdir(tmp_path)
    assert cli("example", "inline6-diesel").status == 0
    assert (tmp_path / "inline6-diesel.toml").exists()
    assert (tmp_path / "mendes2008_pressure.csv").exists()
    # the written file is a working engine file (its trace is found next to it)
    run = cli("kinematics", "inline6-diesel.toml", "--format", "json", "--step", "90")
    assert run.status == 0
    again = cli("example", "inline6-diesel")
    assert again.status == 2 and "already exists" in again.err
    assert cli("example", "vaz2108", "-o", "-").out.startswith("#")
    assert cli("example", "vaz2108", "-o", tmp_path / "sub" / "x.toml").status == 2


def test_geometry_from_stroke_alternatives():
    g = CrankGeometry.from_stroke(0.076, 0.071, rod_ratio=0.26)
    assert g.rod_length == pytest.approx(0.0355 / 0.26)


def test_the_console_entry_freezes_the_objects_before_the_interpreter_exits(monkeypatch):
    """``crankdyn`` (and ``python -m crankdyn``) ends with its objects frozen, so that the
    interpreter's last collection does not traverse them (issue 16's process speed), and exits
    with the command's status."""
    import crankdyn.cli as cli_module

    calls: list[str] = []
    monkeypatch.setattr(cli_module, "main", lambda: calls.append("main") or 3)
    monkeypatch.setattr(cli_module.gc, "freeze", lambda: calls.append("freeze"))
    with pytest.raises(SystemExit) as exited:
        cli_module.run()
    assert exited.value.code == 3
    assert calls == ["main", "freeze"]
