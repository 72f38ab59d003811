"""The forces, bearings, torque and pressure commands, run in-process."""

import json
import math

import pytest

from crankdyn.cli import main

ENGINE = """
name = "test single"
[geometry]
bore = "80 mm"
stroke = "80 mm"
rod_length = "140 mm"
[masses]
reciprocating = "0.5 kg"
rotating = "0.6 kg"
"""


def run(capsys, *args):
    status = main(list(args))
    out, err = capsys.readouterr()
    return status, out, err


def test_forces_json_keys(capsys):
    status, out, err = run(capsys, "forces", "vaz2108", "--format", "json", "--step", "5")
    assert status == 0, err
    d = json.loads(out)
    for key in (
        "crank_angle_deg",
        "gas_force_N",
        "inertia_force_N",
        "piston_force_N",
        "side_force_N",
        "rod_force_N",
        "tangential_force_N",
        "radial_force_N",
        "crank_pin_load_N",
    ):
        assert len(d[key]) == 145, key
    assert d["crank_angle_deg"][-1] == pytest.approx(720.0)
    assert set(d["masses"]) >= {"reciprocating_kg", "rotating_kg"}
    assert d["speed_rpm"] == pytest.approx(4900.0)


def test_forces_cylinder_option_and_speed(capsys):
    status, out, err = run(
        capsys, "forces", "v8-crossplane", "--cylinder", "2", "--speed", "3000", "--format", "json"
    )
    assert status == 0, err
    d = json.loads(out)
    assert d["cylinder"] == 2 and d["bank"] == "A" and d["rods_on_pin"] == 2
    assert d["speed_rpm"] == pytest.approx(3000.0)
    assert len(d["crank_angle_deg"]) == 721  # 1 deg default for data formats


def test_torque_json_keys(capsys):
    status, out, err = run(capsys, "torque", "inline6-diesel", "--format", "json", "--step", "2")
    assert status == 0, err
    d = json.loads(out)
    assert len(d["crank_angle_deg"]) == 361
    assert len(d["cylinder_torque_Nm"]) == 6 and len(d["cylinder_torque_Nm"][0]) == 361
    assert len(d["journal_torque_Nm"]) == 6
    assert len(d["total_torque_Nm"]) == 361
    for key in ("mean_torque_Nm", "indicated_power_W", "imep_Pa", "peak_pressure_Pa"):
        assert isinstance(d[key], float)
    assert d["indicated_power_W"] == pytest.approx(
        d["mean_torque_Nm"] * 2200 * math.pi / 30, rel=1e-9
    )
    assert d["peak_pressure_Pa"] == pytest.approx(15.2e6, rel=0.01)


def test_torque_csv_and_table(capsys):
    status, out, _ = run(capsys, "torque", "vaz2108", "--format", "csv", "--step", "10")
    assert status == 0
    header = out.splitlines()[0].split(",")
    assert header[0] == "crank_angle_deg"
    assert "cylinder_torque_Nm_4" in header and "journal_torque_Nm_1" in header
    assert len(out.splitlines()) == 1 + 73
    status, out, _ = run(capsys, "torque", "vaz2108", "--mechanical-efficiency", "0.85")
    assert status == 0
    assert "Mean effective torque" in out and "Effective power" in out
    assert "no pressure trace" in out.lower()  # the default model is announced


def test_bearings_and_pressure_commands(capsys, tmp_path):
    status, out, err = run(capsys, "bearings", "v8-crossplane", "--format", "json", "--step", "10")
    assert status == 0, err
    d = json.loads(out)
    assert len(d["crank_pin_load_N"]) == 4 and len(d["main_bearing_load_N"]) == 5
    target = tmp_path / "p.csv"
    status, out, err = run(
        capsys, "pressure", "inline6-diesel", "--format", "csv", "-o", str(target)
    )
    assert status == 0, err
    assert target.read_text().startswith("crank_angle_deg,pressure_Pa,volume_m3")
    status, out, _ = run(capsys, "pressure", "vaz2108")
    assert status == 0 and "IMEP" in out


def _error(capsys, *args):
    status, _out, err = run(capsys, *args)
    assert status == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("crankdyn: error: ")
    return lines[0]


def test_cli_errors(capsys, tmp_path):
    assert "--cylinder = 9: the engine has cylinders 1 to 4" in _error(
        capsys, "forces", "vaz2108", "--cylinder", "9"
    )
    assert "--step" in _error(capsys, "torque", "vaz2108", "--step", "7")
    assert "--mechanical-efficiency" in _error(
        capsys, "torque", "vaz2108", "--mechanical-efficiency", "1.5"
    )
    engine = tmp_path / "e.toml"
    engine.write_text(
        ENGINE.replace('[masses]\nreciprocating = "0.5 kg"\nrotating = "0.6 kg"\n', "")
    )
    line = _error(capsys, "torque", str(engine), "--speed", "3000")
    assert "the engine has no [masses]" in line
    engine.write_text(ENGINE)
    assert "no speed" in _error(capsys, "forces", str(engine))


TRACE_ENGINE = (
    ENGINE
    + """
[pressure]
file = "trace.csv"
firing_tdc = "360 deg"
"""
)


def _trace_lines(n=80, unit="MPa", value=lambda i: 0.1 + i * 0.01):
    rows = [f"crank_angle_deg,pressure_{unit}"]
    rows += [f"{720 * i / n:.4f},{value(i)}" for i in range(n)]
    return "\n".join(rows) + "\n"


@pytest.mark.parametrize(
    ("trace", "expected"),
    [
        (
            "\n".join(["crank_angle_deg,pressure_MPa"] + [f"{i},{1.0}" for i in range(0, 300, 10)]),
            "the trace does not cover the cycle",
        ),
        (_trace_lines().replace("0.15", "abc", 1), "not a number in column"),
        (_trace_lines(value=lambda i: 0.5 - 0.01 * i), "absolute pressure must be positive"),
        (_trace_lines(unit="furlongs"), "unknown pressure unit"),
        (_trace_lines().replace("pressure_MPa", "pressure"), "must name its unit"),
    ],
)
def test_bad_traces_are_one_line_errors(capsys, tmp_path, trace, expected):
    (tmp_path / "trace.csv").write_text(trace)
    engine = tmp_path / "e.toml"
    engine.write_text(TRACE_ENGINE)
    line = _error(capsys, "torque", str(engine), "--speed", "3000")
    assert expected in line
    assert "trace.csv" in line


def test_synthetic_pressure_in_engine_file(capsys, tmp_path):
    engine = tmp_path / "e.toml"
    engine.write_text(
        ENGINE
        + '[pressure]\nmodel = "wiebe"\ncompression_ratio = 17\npeak_pressure = "12 MPa"\n'
        + 'combustion_start = "-5 deg"\ncrankcase_pressure = "1 bar"\n'
    )
    status, out, err = run(capsys, "torque", str(engine), "--speed", "2000", "--format", "json")
    assert status == 0, err
    d = json.loads(out)
    assert d["peak_pressure_Pa"] == pytest.approx(12e6, rel=1e-9)
    assert "Wiebe model" in d["pressure_source"]
    engine.write_text(ENGINE + '[pressure]\nfile = "x.csv"\ncompression_ratio = 17\nimep = 1\n')
    assert "imep" in _error(capsys, "torque", str(engine), "--speed", "2000")
    engine.write_text(ENGINE + '[pressure]\nmodel = "wiebe"\nimep = "1 MPa"\npeak_pressure = 9e6\n')
    assert "give only one of" in _error(capsys, "torque", str(engine), "--speed", "2000")


@pytest.mark.parametrize("command", ["forces", "bearings", "torque", "pressure", "kinematics"])
def test_the_figure_does_not_follow_the_table_step(capsys, monkeypatch, command):
    """A table every 30 deg plots the session's 1 deg analysis (issue 14, point 8)."""
    import crankdyn.cli.forces as forces_cli
    import crankdyn.cli.kinematics as kinematics_cli

    figures = []
    for module in (forces_cli, kinematics_cli):
        monkeypatch.setattr(module, "save_figure", lambda fig, *a, **k: figures.append(fig))
    status, _out, err = run(capsys, command, "vaz2108", "--step", "30", "--plot", "p.png")
    assert status == 0, err
    points = max(len(line.get_xdata()) for ax in figures[0].axes for line in ax.get_lines())
    assert points >= 361
