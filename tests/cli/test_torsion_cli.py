"""``crankdyn torsion modes | holzer | examples`` in process."""

import json

import numpy as np
import pytest

from crankdyn.cli import main

MODEL = """
[[mass]]
name = "a"
inertia = "0.2 kg*m^2"
[[mass]]
name = "b"
inertia = "1.3 kg*m^2"
[[shaft]]
between = ["a", "b"]
stiffness = "400 kN*m/rad"
"""


def run(capsys, *args):
    status = main(list(args))
    out, err = capsys.readouterr()
    return status, out, err


def one_line_error(capsys, *args):
    status, out, err = run(capsys, *args)
    assert status == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("crankdyn: error: ")
    return lines[0]


def test_modes_json_of_a_model_file(tmp_path, capsys):
    path = tmp_path / "two.toml"
    path.write_text(MODEL, encoding="utf-8")
    status, out, _ = run(capsys, "torsion", "modes", str(path), "--format", "json")
    assert status == 0
    data = json.loads(out)
    f = data["natural_frequencies_hz"]
    assert f[0] == 0.0
    omega = np.sqrt(4e5 * 1.5 / (0.2 * 1.3))
    assert f[1] == pytest.approx(omega / (2 * np.pi), rel=1e-12)
    assert data["mode_shapes"][1] == pytest.approx([1.0, -0.2 / 1.3])
    assert data["masses"] == ["a", "b"]
    assert data["nodes"][1][0] == {
        "shaft": ["a", "b"],
        "fraction_from_first": pytest.approx(1.3 / 1.5),
        "determined": True,
    }
    assert data["mode"] == [0, 1]  # the rigid-body mode 0, the elastic mode 1
    assert data["nodes_resolved"] == [True, True] and data["roundoff_regions"] == [[], []]


@pytest.mark.parametrize("name", ["seed003-v6", "seed003-three-disc", "inline6-diesel"])
def test_modes_json_of_built_ins(capsys, name):
    status, out, _ = run(capsys, "torsion", "modes", name, "--format", "json")
    assert status == 0
    data = json.loads(out)
    f = data["natural_frequencies_hz"]
    assert f == sorted(f) and f[0] == 0.0
    shapes = np.array(data["mode_shapes"])
    assert shapes.shape == (len(f), len(data["masses"]))
    assert np.allclose(np.max(np.abs(shapes), axis=1), 1.0)


@pytest.mark.parametrize("solver", ["holzer", "transfer"])
def test_modes_solvers_agree_through_the_cli(capsys, solver):
    _, base, _ = run(capsys, "torsion", "modes", "seed003-v6", "--format", "json")
    _, other, _ = run(
        capsys, "torsion", "modes", "seed003-v6", "--format", "json", "--solver", solver
    )
    a = np.array(json.loads(base)["natural_frequencies_hz"][1:])
    b = np.array(json.loads(other)["natural_frequencies_hz"][1:])
    assert np.allclose(a, b, rtol=1e-9)


def test_modes_table_and_csv(capsys):
    status, out, _ = run(capsys, "torsion", "modes", "seed003-three-disc")
    assert status == 0
    assert "rigid-body mode" in out and "Mode shapes" in out and "disc 2 - disc 3 at 0.411" in out
    status, out, _ = run(capsys, "torsion", "modes", "seed003-three-disc", "--format", "csv")
    lines = out.splitlines()
    assert lines[0].startswith("mode,natural_frequencies_hz,")
    assert len(lines) == 4


def test_modes_writes_files(tmp_path, capsys):
    out_json = tmp_path / "modes.json"
    fig = tmp_path / "modes.png"
    status, out, err = run(
        capsys,
        "torsion",
        "modes",
        "seed003-v6",
        "--format",
        "json",
        "-o",
        str(out_json),
        "--plot",
        str(fig),
        "--plot-modes",
        "2,3",
    )
    assert status == 0 and out == ""
    assert json.loads(out_json.read_text())["natural_frequencies_hz"][0] == 0.0
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "wrote" in err
    # no overwrite without --force
    line = one_line_error(capsys, "torsion", "modes", "seed003-v6", "--plot", str(fig))
    assert "already exists" in line


def test_modes_schematic_svg(capsys, tmp_path):
    """--schematic: the mass-elastic system drawn from the model, every mass named in it."""
    fig = tmp_path / "system.svg"
    status, _out, err = run(
        capsys, "torsion", "modes", "marine-propulsion", "--schematic", str(fig)
    )
    assert status == 0 and f"wrote {fig}" in err
    svg = fig.read_text(encoding="utf-8")
    assert svg.startswith("<?xml") and "propeller" in svg and "flywheel" in svg
    line = one_line_error(capsys, "torsion", "modes", "seed003-v6", "--schematic", str(fig))
    assert "already exists" in line


def test_holzer_table_json(capsys):
    status, out, _ = run(
        capsys,
        "torsion",
        "holzer",
        "seed003-three-disc",
        "--frequency",
        "7.0561",
        "--format",
        "json",
    )
    assert status == 0
    data = json.loads(out)
    assert data["frequency_hz"] == pytest.approx(7.0561)
    assert data["mass"] == ["disc 1", "disc 2", "disc 3"]
    assert data["angle"][0] == 1.0
    assert data["twist"][-1] is None
    # near a natural frequency the residual is small against the inertia torques
    assert abs(data["residual_torque_Nm_per_rad"]) < 1e-3 * max(
        abs(t) for t in data["inertia_torque_Nm_per_rad"]
    )


def test_holzer_table_text_units_and_plot(tmp_path, capsys):
    fig = tmp_path / "residual.svg"
    status, out, _ = run(
        capsys,
        "torsion",
        "holzer",
        "inline6-diesel",
        "--frequency",
        "13000 rpm",
        "--plot",
        str(fig),
    )
    assert status == 0
    assert "Holzer's table" in out and "cylinder 6" in out and "216.67" in out
    assert fig.read_text().lstrip().startswith("<?xml")


def test_examples_list(capsys):
    status, out, _ = run(capsys, "torsion", "examples")
    assert status == 0
    assert "seed003-v6" in out and "seed003-three-disc" in out


@pytest.mark.parametrize(
    ("args", "text"),
    [
        (("torsion", "modes", "nosuch"), "no such file, built-in model"),
        (("torsion", "modes", "v8-crossplane"), "no [torsion] section"),
        (("torsion", "modes", "seed003-v6", "--solver", "closed-form"), "closed forms exist"),
        (("torsion", "holzer", "seed003-v6", "--frequency", "-5"), "must not be negative"),
        (("torsion", "holzer", "seed003-v6", "--frequency", "5 kg"), "expected a frequency"),
        (("torsion", "holzer", "seed003-v6"), "Missing option '--frequency'"),
        (("torsion", "modes", "seed003-v6", "--plot", "x.gif"), "must end in .png, .svg, .pdf"),
        (("torsion", "modes", "seed003-v6", "--schematic", "x.gif"), '--schematic = "x.gif"'),
        (("torsion", "modes", "seed003-v6", "--plot-modes", "2,x"), "mode numbers"),
        (("torsion", "modes", "seed003-v6", "--plot-modes", "12"), "modes 1 to 8 and the rigid"),
    ],
)
def test_bad_input_is_one_line(capsys, args, text):
    assert text in one_line_error(capsys, *args)


def test_bad_model_file_is_one_line(tmp_path, capsys):
    path = tmp_path / "bad.toml"
    path.write_text(MODEL.replace('"0.2 kg*m^2"', '"0 kg*m^2"'), encoding="utf-8")
    line = one_line_error(capsys, "torsion", "modes", str(path))
    assert line.endswith('bad.toml: [[mass]] #1 inertia = "0 kg*m^2": must be positive')
    branched = MODEL + '[[mass]]\nname = "c"\ninertia = 1\n[[mass]]\nname = "d"\ninertia = 1\n'
    branched += '[[shaft]]\nbetween = ["a", "c"]\nstiffness = 1\n'
    branched += '[[shaft]]\nbetween = ["a", "d"]\nstiffness = 1\n'
    path.write_text(branched, encoding="utf-8")
    line = one_line_error(capsys, "torsion", "holzer", str(path), "--frequency", "10")
    assert "needs an unbranched chain" in line and '(it branches at "a")' in line


def test_names_with_brackets_are_shown_as_written(tmp_path, capsys):
    path = tmp_path / "b.toml"
    path.write_text(MODEL.replace('"b"', '"wheel [big]"'), encoding="utf-8")
    status, out, _ = run(capsys, "torsion", "modes", str(path))
    assert status == 0
    assert "wheel [big]" in out and "a - wheel [big] at" in out
    status, out, _ = run(capsys, "torsion", "holzer", str(path), "--frequency", "10")
    assert status == 0 and "wheel [big]" in out


def test_holzer_overflow_names_the_option(capsys):
    # beyond the computable range the option is refused before any arithmetic
    line = one_line_error(capsys, "torsion", "holzer", "seed003-v6", "--frequency", "1e95")
    assert '--frequency = "1e95": 1e+95 Hz lies outside the range crankdyn computes with' in line


def test_a_large_chain_tables_its_lowest_modes_and_says_what_it_leaves_out(tmp_path, capsys):
    """Issue 16: --modes N lists the lowest N modes, at most ten mode shapes, and notes what is
    left out and where it is; JSON and CSV hold every mode."""
    n = 40
    rng = np.random.default_rng(16)
    masses = ",\n".join(
        f'{{name="m{i}",inertia={j:.4g}}}' for i, j in enumerate(rng.uniform(0.05, 2, n))
    )
    shafts = ",\n".join(
        f'{{between=["m{i}","m{i + 1}"],stiffness={k:.4g}}}'
        for i, k in enumerate(rng.uniform(2e5, 5e6, n - 1))
    )
    path = tmp_path / "chain.toml"
    path.write_text(f'name = "chain"\nmass = [\n{masses}\n]\nshaft = [\n{shafts}\n]\n', "utf-8")
    status, out, _ = run(capsys, "torsion", "modes", str(path), "--modes", "12")
    assert status == 0
    text = " ".join(out.split())
    # a free chain: the rigid-body mode 0 and the elastic modes 1 to 39
    assert "Modes 12 to 39 (up to" in text and "--modes 40 lists them" in text
    assert "Mode shapes of modes 10 to 11 are not shown" in text
    assert "11 nodes" in text  # mode 11: a count, not eleven locations
    status, out, _ = run(capsys, "torsion", "modes", str(path), "--format", "json")
    data = json.loads(out)
    assert len(data["natural_frequencies_hz"]) == n and len(data["mode_shapes"]) == n
    assert [len(m) for m in data["nodes"]] == data["node_counts"]
    status, out, _ = run(capsys, "torsion", "modes", str(path), "--format", "csv")
    assert len(out.strip().splitlines()) == n + 1
    status, out, _ = run(capsys, "torsion", "modes", str(path), "--modes", "40")
    assert "not listed" not in " ".join(out.split())
