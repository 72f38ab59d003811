"""`crankdyn linkage ...` in process: outputs, files and one-line errors."""

import json
import math

import numpy as np
import pytest

from crankdyn.cli import main

FOURBAR = [
    "linkage",
    "fourbar",
    "--crank",
    "73.4mm",
    "--coupler",
    "125.36mm",
    "--rocker",
    "103.4mm",
    "--ground",
    "103.52mm",
]


def run(capsys, *args):
    status = main(list(args))
    out, err = capsys.readouterr()
    return status, out, err


def test_fourbar_one_angle_json_has_the_documented_keys(capsys):
    status, out, _err = run(
        capsys, *FOURBAR, "--crank-speed", "10rad/s", "--angle", "60deg", "--format", "json"
    )
    assert status == 0
    data = json.loads(out)
    assert data["grashof_type"] == "crank-rocker"
    assert data["crank_angle_deg"] == pytest.approx(60.0)
    for key in (
        "transmission_angle_min_deg",
        "transmission_angle_max_deg",
        "rocker_angle_min_deg",
        "rocker_angle_max_deg",
        "coupler_angle_deg",
        "rocker_angle_deg",
        "coupler_angular_velocity_rad_s",
        "rocker_angular_velocity_rad_s",
        "coupler_angular_acceleration_rad_s2",
        "rocker_angular_acceleration_rad_s2",
    ):
        assert isinstance(data[key], float), key
    # closed-form check of the rocker angle at 60 deg (loop closure, by hand)
    a, b, c, d = 73.4, 125.36, 103.4, 103.52
    t2, t3, t4 = (
        math.radians(data[k]) for k in ("crank_angle_deg", "coupler_angle_deg", "rocker_angle_deg")
    )
    gap = complex(
        a * math.cos(t2) + b * math.cos(t3) - d - c * math.cos(t4),
        a * math.sin(t2) + b * math.sin(t3) - c * math.sin(t4),
    )
    assert abs(gap) < 1e-9


def test_fourbar_step_gives_lists_over_a_full_turn(capsys):
    status, out, _ = run(
        capsys, *FOURBAR, "--step", "1deg", "--branch", "crossed", "--format", "json"
    )
    assert status == 0
    data = json.loads(out)
    assert len(data["crank_angle_deg"]) == 361
    assert data["branch"] == "crossed"


def test_fourbar_table_and_csv(capsys):
    status, out, _ = run(capsys, *FOURBAR)
    assert status == 0 and "Grashof type" in out and "crank-rocker" in out
    status, out, _ = run(capsys, *FOURBAR, "--format", "csv", "--coupler-point", "60mm,40mm")
    assert status == 0
    assert out.splitlines()[0].startswith("crank_angle_deg,coupler_angle_deg")
    assert "coupler_point_x_m" in out.splitlines()[0]


def test_fourbar_full_turn_of_a_crank_that_cannot_rotate(capsys):
    status, _out, err = run(
        capsys,
        "linkage",
        "fourbar",
        "--crank",
        "30mm",
        "--coupler",
        "35mm",
        "--rocker",
        "40mm",
        "--ground",
        "50mm",
        "--step",
        "1deg",
    )
    assert status == 2
    assert err.count("\n") == 1
    assert "triple-rocker" in err and "cannot turn through a full revolution" in err
    assert "-137.9 to 137.9 deg" in err


def test_fourbar_angle_where_links_do_not_assemble(capsys):
    status, _out, err = run(
        capsys,
        "linkage",
        "fourbar",
        "--crank",
        "30mm",
        "--coupler",
        "35mm",
        "--rocker",
        "40mm",
        "--ground",
        "50mm",
        "--angle",
        "170deg",
    )
    assert status == 2
    assert '--angle = "170deg"' in err
    assert "cannot be assembled at crank angle 170 deg" in err
    assert "more than coupler + rocker" in err


@pytest.mark.parametrize("option", ["--crank", "--coupler", "--rocker", "--ground"])
def test_fourbar_negative_length(capsys, option):
    args = list(FOURBAR)
    args[args.index(option) + 1] = "-5mm"
    status, _out, err = run(capsys, *args)
    assert status == 2
    assert f'{option} = "-5mm": a link length must be positive' in err


def test_fourbar_bad_unit(capsys):
    args = list(FOURBAR)
    args[args.index("--crank") + 1] = "73.4kg"
    status, _out, err = run(capsys, *args)
    assert status == 2 and "expected a length" in err and "got a mass" in err


def test_forces_json(capsys):
    status, out, _ = run(
        capsys, "linkage", "forces", "fourbar-seed004", "--format", "json", "--step", "30deg"
    )
    assert status == 0
    data = json.loads(out)
    assert len(data["crank_angle_deg"]) == 13
    assert set(data["joint_forces_N"]) == {"A", "B", "C", "D"}
    assert set(data["joint_forces_N"]["B"]) == {"x", "y"}
    for a, b in zip(data["driving_torque_Nm"], data["driving_torque_virtual_work_Nm"], strict=True):
        assert a == pytest.approx(b, abs=1e-9)


def test_forces_one_angle_with_matrices(capsys):
    status, out, _ = run(
        capsys,
        "linkage",
        "forces",
        "conveyor-seed004",
        "--angle",
        "100deg",
        "--format",
        "json",
        "--matrices",
    )
    assert status == 0
    data = json.loads(out)
    assert isinstance(data["driving_torque_Nm"], float)
    assert isinstance(data["joint_forces_N"]["guide"]["y"], float)
    m = data["matrices"]
    assert len(m["C"]) == 15 and len(m["C"][0]) == 15
    assert m["unknowns"][-1] == "driving torque"


def test_forces_table_and_friction_switch(capsys):
    status, out, _ = run(capsys, "linkage", "forces", "slider-crank-friction", "--step", "90deg")
    assert status == 0 and "Efficiency" in out and "Cycle efficiency" in out
    status, out, _ = run(
        capsys,
        "linkage",
        "forces",
        "slider-crank-friction",
        "--step",
        "90deg",
        "--no-friction",
        "--format",
        "json",
    )
    assert "efficiency" not in json.loads(out)


def test_kinematics_and_check(capsys):
    status, out, _ = run(
        capsys, "linkage", "kinematics", "conveyor-seed004", "--format", "csv", "--step", "90deg"
    )
    assert status == 0 and "point_position_m.F.x" in out.splitlines()[0]
    status, out, _ = run(capsys, "linkage", "check", "conveyor-seed004")
    assert status == 0 and "RRP dyad" in out and "F = 3n - 2p_l = 1" in out


def test_examples_and_example(capsys, tmp_path):
    status, out, _ = run(capsys, "linkage", "examples")
    assert status == 0 and "conveyor-seed004" in out
    target = tmp_path / "c.toml"
    assert run(capsys, "linkage", "example", "conveyor-seed004", "-o", str(target))[0] == 0
    status, out, _ = run(
        capsys, "linkage", "forces", str(target), "--angle", "0", "--format", "json"
    )
    assert status == 0
    status, _out, err = run(capsys, "linkage", "example", "conveyor-seed004", "-o", str(target))
    assert status == 2 and "not overwritten without --force" in err


def test_draw_and_animate_write_files_and_refuse_to_overwrite(capsys, tmp_path):
    png = tmp_path / "m.png"
    assert (
        run(capsys, "linkage", "draw", "fourbar-seed004", "--angle", "30deg", "-o", str(png))[0]
        == 0
    )
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    status, _out, err = run(capsys, "linkage", "draw", "fourbar-seed004", "-o", str(png))
    assert status == 2 and "--force" in err
    gif = tmp_path / "a.gif"
    assert (
        run(capsys, "linkage", "animate", "slider-crank-friction", "--frames", "6", "-o", str(gif))[
            0
        ]
        == 0
    )
    assert gif.read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    status, _out, err = run(
        capsys, "linkage", "animate", "fourbar-seed004", "-o", str(tmp_path / "a.png")
    )
    assert status == 2 and "must end in .gif" in err


def test_fourbar_plot_option(capsys, tmp_path):
    png = tmp_path / "fb.png"
    status, _out, _err = run(
        capsys, *FOURBAR, "--format", "json", "--coupler-point", "60mm,40mm", "--plot", str(png)
    )
    assert status == 0 and png.stat().st_size > 1000


def test_missing_linkage_file(capsys):
    status, _out, err = run(capsys, "linkage", "forces", "nothere.toml")
    assert status == 2 and "nothere.toml: no such linkage file" in err


def test_unknown_example_suggests(capsys):
    status, _out, err = run(capsys, "linkage", "forces", "conveyor-seed04")
    assert status == 2 and 'did you mean "conveyor-seed004"' in err


# ---- plots at their own resolution, whatever --step (issue 14, point 8) ----------------------


@pytest.fixture
def captured(monkeypatch):
    """The figures the linkage commands save (instead of writing them)."""
    import crankdyn.cli.linkage as linkage_cli

    figures = []
    monkeypatch.setattr(linkage_cli, "save_figure", lambda fig, path, force: figures.append(fig))
    return figures


def _torque_line(fig):
    ax = next(ax for ax in fig.axes if ax.get_ylabel() == "Driving torque (N·m)")
    return next(line for line in ax.get_lines() if line.get_label().startswith("matrix method"))


def test_linkage_forces_plot_does_not_follow_the_table_step(cli, captured, tmp_path):
    for step in ("10", "30"):
        run = cli("linkage", "forces", "slider-crank-friction", "--step", step, "--plot", "f.png")
        assert run.status == 0, run
    coarse, coarser = (_torque_line(fig) for fig in captured)
    assert len(coarse.get_xdata()) == len(coarser.get_xdata()) >= 1441
    np.testing.assert_array_equal(coarse.get_ydata(), coarser.get_ydata())
    # the slider's resistance reverses at the dead centre: the plotted torque falls there within
    # one plot step (0.25 deg), not over the 10 deg of the table grid
    x, y = coarse.get_xdata(), coarse.get_ydata()
    near = (x > 170.0) & (x < 180.0)
    assert np.max(y[near]) > 10 * np.min(np.abs(y[(x > 179.0) & (x < 181.0)])) + 1.0


def test_fourbar_plot_does_not_follow_the_table_step(cli, captured):
    args = ("linkage", "fourbar", "--crank", "73.4mm", "--coupler", "125.36mm")
    args += ("--rocker", "103.4mm", "--ground", "103.52mm", "--plot", "f.png")
    for step in ("10", "45"):
        assert cli(*args, "--step", step).status == 0
    assert cli(*args, "--angle", "30").status == 0
    sizes = {
        len(
            next(ax for ax in fig.axes if "Transmission" in ax.get_ylabel())
            .get_lines()[0]
            .get_xdata()
        )
        for fig in captured
    }
    assert sizes == {1441}


def test_truss_command_table_json_and_plot(cli, tmp_path):
    from pathlib import Path

    data = Path(__file__).parents[1] / "validation" / "data" / "beer_johnston_truss.toml"
    run = cli("linkage", "truss", data)
    assert run.status == 0, run
    assert "Truss member forces" in run.out and "Support reactions" in run.out
    run = cli("linkage", "truss", data, "--format", "json", "--plot", tmp_path / "truss.png")
    assert run.status == 0, run
    out = json.loads(run.out)
    ef = out["member"].index("E-F")
    assert out["force_N"][ef] == pytest.approx(out["force_sections_N"][ef])
    assert out["reactions"]["component"] == ["B x", "B y", "J"]
    assert (tmp_path / "truss.png").stat().st_size > 0
    bad = tmp_path / "bad.toml"
    bad.write_text(
        '[nodes]\nA = ["0 m", "0 m"]\nB = ["1 m", "0 m"]\n[[members]]\nbetween = ["A", "Z"]\n'
        '[[supports]]\nnode = "A"\n',
        encoding="utf-8",
    )
    run = cli("linkage", "truss", bad)
    assert run.status == 2 and "bad.toml" in run.err and '"Z"' in run.err


def test_polygon_command_writes_the_figure(cli, tmp_path):
    run = cli("linkage", "polygon", "conveyor-seed004", "--angle", "30", "-o", tmp_path / "p.png")
    assert run.status == 0, run
    assert (tmp_path / "p.png").stat().st_size > 0
