"""``crankdyn torsion response | campbell | damper | excitation | transient`` in process."""

import json

import numpy as np
import pytest

from crankdyn.cli import main

MODEL = """
name = "engine and propeller"

[excitation]
cycle = "two-stroke"
torque = "60 N*m"

[operating]
speed_range = ["300 rpm", "1000 rpm"]
rated_speed = "1000 rpm"

[[mass]]
name = "engine"
inertia = "2 kg*m^2"
damping = "5 N*m*s/rad"
cylinders = [1]

[[mass]]
name = "propeller"
inertia = "6 kg*m^2"

[[shaft]]
between = ["engine", "propeller"]
stiffness = "53 kN*m/rad"
outer_diameter = "60 mm"

[rules]
[[rules.shaft]]
between = ["engine", "propeller"]
tensile_strength = "600 MPa"
design_factor = 1.0
"""


def run(capsys, *args):
    status = main(list(args))
    out, err = capsys.readouterr()
    return status, out, err


def one_line_error(capsys, *args):
    status, out, err = run(capsys, *args)
    assert status == 2, err
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("crankdyn: error: "), err
    return lines[0]


def test_response_json_keys_and_shapes(capsys):
    status, out, _ = run(
        capsys,
        "torsion",
        "response",
        "inline6-diesel",
        "--speeds",
        "1000:2500:25",
        "--orders",
        "0.5:12",
        "--format",
        "json",
    )
    assert status == 0
    data = json.loads(out)
    speed = np.array(data["speed_rpm"])
    grid = np.array(data["on_grid"])
    s, q, m = speed.size, 24, 9
    assert speed[grid] == pytest.approx(np.arange(1000, 2501, 25))
    # the critical speeds and the refinement points, each with a reason
    added = np.array(data["added_speeds_rpm"])
    assert added.size == s - 61 == len(data["added_speed_reasons"])
    assert np.min(np.abs(added - 2165.8)) < 0.1  # mode 1 x order 6
    assert "critical speed: mode 1 x order 6" in data["added_speed_reasons"]
    peak = next(
        p
        for p in data["peaks"]
        if p["quantity"] == "shaft_torque" and p["item"] == "cylinder 6 - flywheel"
    )
    assert peak["value_Nm"] == pytest.approx(np.max(np.array(data["shaft_torque_Nm"])[:, 7]))
    assert data["orders"] == pytest.approx(np.arange(1, 25) * 0.5)
    assert np.shape(data["amplitude_rad"]) == (s, q, m)
    assert np.shape(data["synthesized_amplitude_rad"]) == (s, m)
    assert np.shape(data["shaft_torque_Nm"]) == (s, 8)
    assert np.shape(data["shaft_stress_Pa"]) == (s, 8)
    assert data["shaft_stress_Pa"][0][0] is None  # no diameters in the Mendes model
    torque = np.array(data["shaft_torque_Nm"])
    assert torque[:, 7].max() == pytest.approx(9.5e3, rel=0.05)
    assert data["masses"][0] == "pulley" and data["shafts"][7] == ["cylinder 6", "flywheel"]


def test_response_with_rules_relative_angle_and_plots(tmp_path, capsys):
    path = tmp_path / "m.toml"
    path.write_text(MODEL, encoding="utf-8")
    fig, stress = tmp_path / "r.png", tmp_path / "s.png"
    status, out, err = run(
        capsys,
        "torsion",
        "response",
        str(path),
        "--speeds",
        "300:1000:5",
        "--orders",
        "1:6",
        "--relative",
        "engine,propeller",
        "--format",
        "json",
        "--plot",
        str(fig),
        "--plot-quantity",
        "stress",
        "--plot-stress",
        str(stress),
    )
    assert status == 1, err  # a verdict failed: the output is written, exit status 1
    data = json.loads(out)
    # the verdicts of the installation's checks, the TVC's own evaluation (one verdict per check)
    judged = data["judged"]
    m68 = [v for v in judged["verdicts"] if v["source"].startswith("IACS UR M68")]
    assert m68 and judged["condition_passed"] is False  # the resonance at 898 rpm > 0.8 n_0
    barred = judged["barred_speed_ranges"]
    assert barred[1]["permitted"] is True
    assert barred[1]["start_rpm"] < barred[1]["exceeds_from_rpm"] < barred[1]["exceeds_to_rpm"]
    assert not barred[-1]["permitted"] and "above 0.8 n_0" in barred[-1]["reason"]
    assert data["relative_angle"]["between"] == ["engine", "propeller"]
    assert all(v is not None for v in data["shaft_stress_Pa"][0])
    assert fig.stat().st_size > 10_000 and stress.stat().st_size > 10_000
    status, out, _ = run(capsys, "torsion", "response", str(path), "--orders", "1:6", "--no-fail")
    assert status == 0 and "IACS UR M68" in out and "Barred speed ranges" in out
    assert "Declared" in out and "Found" in out


def test_response_table_and_csv(capsys):
    status, out, _ = run(
        capsys,
        "torsion",
        "response",
        "seed003-v6",
        "--speeds",
        "1000:2000:100",
        "--orders",
        "1.5,3,4.5,6",
    )
    assert status == 0 and "Vibratory torque" in out and "Speeds added to resolve" in out
    assert "critical speed: mode 1 x order 6" in out
    status, out, _ = run(
        capsys,
        "torsion",
        "response",
        "seed003-v6",
        "--speeds",
        "1000:2000:100",
        "--orders",
        "1.5,3",
        "--format",
        "csv",
    )
    lines = out.strip().splitlines()
    assert status == 0 and len(lines) == 12  # 11 speeds: no resonance of 1.5 or 3 in the range
    assert lines[0].startswith("speed_rpm,on_grid,synthesized_amplitude_rad.damper ring")
    assert sum(line.split(",")[1] == "1" for line in lines[1:]) == 11


def test_campbell_json(capsys, tmp_path):
    fig = tmp_path / "c.png"
    status, out, _ = run(
        capsys, "torsion", "campbell", "inline6-diesel", "--format", "json", "--plot", str(fig)
    )
    assert status == 0 and fig.exists()
    data = json.loads(out)
    rows = data["critical_speeds"]
    sixth = next(r for r in rows if r["order"] == 6.0)
    assert sixth["speed_rpm"] == pytest.approx(2165.8, abs=0.1)
    assert sixth["major"] is True and sixth["mode"] == 1  # elastic modes from 1
    assert {r["major"] for r in rows if r["order"] == 5.5} == {False}
    status, out, _ = run(capsys, "torsion", "campbell", "seed003-v6", "--range", "1000:2000")
    assert (status == 0 and "Critical" in out) or "critical" in out


def test_damper_excitation_transient(capsys, tmp_path):
    status, out, _ = run(
        capsys,
        "torsion",
        "damper",
        "inline6-diesel",
        "--at",
        "pulley",
        "--mode",
        "1",
        "--inertia",
        "0.01 kg*m^2",
        "--speeds",
        "1800:2500:10",
        "--plot",
        str(tmp_path / "d.png"),
    )
    assert status == 0 and "with damper" in out and (tmp_path / "d.png").exists()
    status, out, _ = run(
        capsys,
        "torsion",
        "damper",
        "inline6-diesel",
        "--at",
        "pulley",
        "--mode",
        "1",
        "--inertia",
        "0.01",
        "--format",
        "json",
    )
    design = json.loads(out)
    assert design["kind"] == "tuned" and design["mass_ratio"] > 0
    status, out, _ = run(
        capsys, "torsion", "excitation", "inline6-diesel", "--speed", "2000", "--orders", "0.5:6"
    )
    assert status == 0 and "Major" in out
    status, out, _ = run(
        capsys,
        "torsion",
        "transient",
        "seed003-v6",
        "--speed",
        "1500",
        "--cycles",
        "3",
        "--orders",
        "3,6",
        "--format",
        "csv",
    )
    assert status == 0 and out.startswith("time_s,speed_rpm,crank_angle_deg")


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--speeds", "2500:1000:25"], "the range is empty"),
        (["--speeds", "-100:1000:25"], "speeds must be positive"),
        (["--orders", "0.25:12"], "does not fit the four-stroke cycle"),
        (["--orders", "0.5:12:0.3"], "does not fit the four-stroke cycle"),
        (["--relative", "pulley,flywhel"], 'no mass named "flywhel" (did you mean "flywheel"?)'),
        (["--misfire", "9"], "the engine has cylinders 1 to 6"),
    ],
)
def test_response_bad_input_one_line(capsys, args, message):
    line = one_line_error(capsys, "torsion", "response", "inline6-diesel", *args)
    assert message in line


def test_model_without_excitation_point(capsys, tmp_path):
    path = tmp_path / "bare.toml"
    path.write_text(
        '[[mass]]\nname = "a"\ninertia = 1.0\n[[mass]]\nname = "b"\ninertia = 2.0\n'
        '[[shaft]]\nbetween = ["a", "b"]\nstiffness = 1e5\n',
        encoding="utf-8",
    )
    line = one_line_error(capsys, "torsion", "response", str(path), "--speeds", "100:200:10")
    assert "no excitation point" in line
    line = one_line_error(capsys, "torsion", "response", "seed003-v6")
    assert "no speed range" in line


def test_misfire_without_compression_ratio_is_one_line(tmp_path, capsys):
    """A trace without [pressure] compression_ratio cannot give a misfiring cylinder's motored
    pressure: one clear line."""
    import shutil

    from crankdyn.cli import main
    from crankdyn.io.examples import example_files

    for f in example_files("inline6-diesel"):
        shutil.copy(f, tmp_path / f.name)
    engine = tmp_path / "inline6-diesel.toml"
    text = engine.read_text(encoding="utf-8")
    engine.write_text(
        "\n".join(line for line in text.splitlines() if not line.startswith("compression_ratio")),
        encoding="utf-8",
    )
    capsys.readouterr()
    status = main(
        ["torsion", "response", str(engine), "--misfire", "3", "--speeds", "2000:2100:100"]
    )
    err = capsys.readouterr().err.strip().splitlines()
    assert status == 2 and len(err) == 1 and "compression ratio" in err[0]


def test_transient_table_from_the_result(capsys):
    """The terminal's shaft-torque table is the result's summary table; its half ranges over
    the last cycle and largest |T| agree with the exported arrays (JSON)."""
    import json

    import numpy as np

    from crankdyn.display import column_text

    args = ["torsion", "transient", "seed003-v6", "--speed", "1500", "--cycles", "3"]
    args += ["--orders", "3,6"]
    status, text, _ = run(capsys, *args)
    assert status == 0 and "last cycle" in text and "Half range" in text
    status, json_text, _ = run(capsys, *args, "--format", "json")
    data = json.loads(json_text)
    angle = np.array(data["crank_angle_deg"])
    torque = np.array(data["shaft_torque_Nm"])
    last = angle >= angle[-1] - data["cycle_angle_deg"] * (1 - 1e-12)
    half = 0.5 * (torque[last].max(axis=0) - torque[last].min(axis=0))
    largest = np.abs(torque).max(axis=0)
    flat = " ".join(text.split())
    for values in (half, largest):
        cells, _unit = column_text(list(values), "N·m")
        assert all(cell in flat for cell in cells)
