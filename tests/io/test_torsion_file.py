"""Torsional model files, the engine file's [torsion] section and the built-in models."""

import math
import tomllib

import pytest

from crankdyn.errors import InputError
from crankdyn.io.catalogue import load_torsion_model, resolve_torsion
from crankdyn.io.engine_file import parse_engine
from crankdyn.io.examples import example_names
from crankdyn.io.torsion_file import parse_torsion_model
from crankdyn.torsion import TorsionModel

MODEL = """
name = "test rig"

[[mass]]
name = "motor"
inertia = "0.5 kg*m^2"
damping = "1.5 N*m*s/rad"

[[mass]]
name = "pinion"
inertia = "200 kg*cm^2"

[[mass]]
name = "wheel"
inertia = "0.08 kg*m^2"

[[mass]]
name = "load"
inertia = "2 kg*m^2"

[[shaft]]
between = ["motor", "pinion"]
length = "400 mm"
outer_diameter = "40 mm"
inner_diameter = "10 mm"
shear_modulus = "80 GPa"
loss_factor = 0.02

[[shaft]]
between = ["wheel", "load"]
stiffness = "50 kN*m/rad"
damping = "10 N*m*s/rad"
outer_diameter = "50 mm"

[[shaft]]
between = ["load", "ground"]
stiffness = "5 kN*m/rad"

[[gear]]
between = ["pinion", "wheel"]
ratio = 0.25
"""

ENGINE = """
name = "test engine"
[geometry]
bore = "105 mm"
stroke = "137 mm"
rod_length = "207 mm"
[cylinders]
count = 4
firing_order = [1, 3, 4, 2]
[masses]
reciprocating = "2.5 kg"
rotating = "3.2 kg"
"""

THROWS = """
[torsion.throws]
inertia = "0.012 kg*m^2"
stiffness = "1.25 MN*m/rad"
damping = "2 N*m*s/rad"
loss_factor = 0.035

[[torsion.mass]]
name = "pulley"
inertia = "0.017 kg*m^2"

[[torsion.mass]]
name = "flywheel"
inertia = "2.0 kg*m^2"

[[torsion.shaft]]
between = ["pulley", "throw 1"]
stiffness = "1.1 MN*m/rad"

[[torsion.shaft]]
between = ["throw 4", "flywheel"]
stiffness = "2 MN*m/rad"
"""


def parse(text, file="m.toml"):
    return parse_torsion_model(tomllib.loads(text), file=file)


def error_of(text, engine=False):
    with pytest.raises(InputError) as info:
        if engine:
            parse_engine(tomllib.loads(text), file="e.toml")
        else:
            parse(text)
    message = str(info.value)
    assert "\n" not in message
    return message


def test_model_file_is_read_in_si():
    m = parse(MODEL)
    assert m.name == "test rig"
    assert m.masses[1].inertia == pytest.approx(0.02)
    assert m.masses[0].damping == 1.5
    k = 80e9 * math.pi * (0.04**4 - 0.01**4) / 32 / 0.4
    assert m.shafts[0].stiffness == pytest.approx(k)
    assert m.shafts[0].loss_factor == 0.02
    assert m.shafts[1].geometry.outer_diameter == pytest.approx(0.05)
    assert m.gears[0].ratio == 0.25
    assert not m.is_free
    assert m.dof_names == ("motor", "pinion + wheel", "load")
    assert m.dof_inertia[2] == pytest.approx(2.0 * 0.25**2)


def test_model_name_defaults_to_the_file_name(tmp_path):
    path = tmp_path / "rig.toml"
    path.write_text(MODEL.replace('name = "test rig"', ""), encoding="utf-8")
    assert load_torsion_model(path).name == "rig"


def test_built_in_models_and_engines_resolve():
    assert {"seed003-three-disc", "seed003-v6"} <= set(example_names("model"))
    assert resolve_torsion("seed003-v6").mass_count == 9
    mendes = resolve_torsion("inline6-diesel")
    assert mendes.mass_count == 9 and mendes.masses[2].cylinders == (1,)
    assert TorsionModel.example("seed003-three-disc").mass_count == 3


def test_engine_file_is_a_model_source(tmp_path):
    path = tmp_path / "engine.toml"
    path.write_text(ENGINE + THROWS, encoding="utf-8")
    m = load_torsion_model(path)
    assert m.name == "test engine"
    assert m.mass_names == ("pulley", "throw 1", "throw 2", "throw 3", "throw 4", "flywheel")
    j = (3.2 + 2.5 / 2) * 0.0685**2 + 0.012
    assert m.masses[1].inertia == pytest.approx(j)
    assert m.chain.stiffness.tolist() == pytest.approx([1.1e6, 1.25e6, 1.25e6, 1.25e6, 2e6])
    assert m.cylinder_dofs == {1: 1, 2: 2, 3: 3, 4: 4}


def test_engine_torsion_by_carter_geometry():
    text = ENGINE + THROWS.replace(
        'stiffness = "1.25 MN*m/rad"',
        """journal_diameter = "85 mm"
journal_bore = "20 mm"
journal_length = "35 mm"
pin_diameter = "70 mm"
pin_length = "40 mm"
web_thickness = "22 mm"
web_width = "120 mm"
shear_modulus = "80 GPa\"""",
    )
    engine = parse_engine(tomllib.loads(text), file="e.toml")
    spans = engine.torsion.chain.stiffness[1:4]
    compliance = (
        (0.035 + 0.8 * 0.022) / (0.085**4 - 0.020**4)
        + 0.75 * 0.040 / 0.070**4
        + 1.5 * 0.0685 / (0.022 * 0.120**3)
    )
    assert spans.tolist() == pytest.approx([math.pi * 80e9 / 32 / compliance] * 3)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        (
            '[[mass]]\nname = "a"\ninertia = "0 kg*m^2"',
            'm.toml: [[mass]] #1 inertia = "0 kg*m^2": must be positive',
        ),
        (
            '[[mass]]\nname = "a"\ninertia = -2',
            "m.toml: [[mass]] #1 inertia = -2: must be positive",
        ),
        (
            '[[mass]]\nname = "a"\ninertia = 1\n[[mass]]\nname = "b"\ninertia = 1\n'
            '[[shaft]]\nbetween = ["a", "b"]\nstiffness = "-1 kN*m/rad"',
            'm.toml: [[shaft]] #1 stiffness = "-1 kN*m/rad": must be positive',
        ),
        (
            '[[mass]]\nname = "a"\ninertia = 1\n[[mass]]\nname = "b"\ninertia = 1\n'
            '[[shaft]]\nbetween = ["a", "x"]\nstiffness = 1',
            'm.toml: [[shaft]] #1 between = ["a", "x"]: no mass named "x"',
        ),
        (
            '[[mass]]\nname = "a"\ninertia = 1\n[[mass]]\nname = "b"\ninertia = 1',
            'm.toml: the model is disconnected: no shaft or gear joins "b" to "a"',
        ),
        (
            '[[mass]]\nname = "a"\ninertia = 1\n[[mass]]\nname = "b"\ninertia = 1\n'
            '[[gear]]\nbetween = ["a", "b"]\nratio = 0',
            "m.toml: [[gear]] #1 ratio = 0.0: a gear ratio cannot be zero",
        ),
        ('name = "x"', "m.toml: missing [[mass]] entries"),
        (
            '[[mass]]\nname = "a"\ninertia = 1\n[[mass]]\nname = "a"\ninertia = 2\n',
            'm.toml: [[mass]] #2 name = "a": another mass has this name already',
        ),
        (
            '[[mass]]\nname = "a"\ninertia = 1\nintertia = 2',
            'm.toml: [[mass]] #1 intertia = 2: unknown key (did you mean "inertia"?)',
        ),
        (
            '[[mass]]\nname = "a"\ninertia = 1\n[[shaft]]\nbetween = ["a", "ground"]\n'
            'length = "1 m"\nouter_diameter = "10 mm"',
            "m.toml: [[shaft]] #1 shear_modulus: missing; give the stiffness, or the length",
        ),
        (
            '[[mass]]\nname = "a"\ninertia = 1\n[[shaft]]\nbetween = ["a", "ground"]\n'
            'stiffness = 1\nlength = "1 m"',
            'm.toml: [[shaft]] #1 length = "1 m": give the stiffness or the shaft',
        ),
        (
            '[[mass]]\nname = "a"\ninertia = 1\n[throws]\ninertia = 1\nstiffness = 1',
            "m.toml: throws: crank throws are generated from an engine",
        ),
        (
            '[[mass]]\nname = "a"\ninertia = 1\n[[gear]]\nbetween = ["a", "ground"]\nratio = 2',
            'm.toml: [[gear]] #1 between = ["a", "ground"]: a gear cannot mesh with "ground"',
        ),
    ],
)
def test_bad_model_files_fail_in_one_line(text, expected):
    assert error_of(text).startswith(expected)


@pytest.mark.parametrize(
    ("extra", "expected"),
    [
        (
            '[[torsion.mass]]\nname = "a"\ninertia = 1\ncylinders = [5]\n'
            '[[torsion.mass]]\nname = "b"\ninertia = 1\n'
            '[[torsion.shaft]]\nbetween = ["a", "b"]\nstiffness = 1',
            "e.toml: [[torsion.mass]] #1 cylinders = [5]: the engine has 4 cylinders",
        ),
        (
            THROWS.replace('name = "flywheel"', 'name = "throw 2"'),
            'e.toml: [[torsion.mass]] #2 name = "throw 2": a generated crank throw has this name',
        ),
        (
            THROWS.replace('stiffness = "1.25 MN*m/rad"\n', ""),
            "e.toml: [torsion.throws] stiffness: missing; give the crank span's stiffness",
        ),
        (
            THROWS.replace('"throw 4"', '"throw 5"'),
            'e.toml: [[torsion.shaft]] #2 between = ["throw 5", "flywheel"]: no mass named '
            '"throw 5" (did you mean "throw 4"?)',
        ),
    ],
)
def test_bad_torsion_sections_fail_in_one_line(extra, expected):
    assert error_of(ENGINE + extra, engine=True).startswith(expected)


def test_throws_need_the_engine_masses():
    text = ENGINE.replace('[masses]\nreciprocating = "2.5 kg"\nrotating = "3.2 kg"\n', "")
    message = error_of(text + THROWS, engine=True)
    assert message.startswith("e.toml: [torsion.throws]: the crank throws need the engine's")


def test_v_engine_cylinders_of_one_throw_share_a_mass():
    text = """
name = "v2"
[geometry]
bore = "80 mm"
stroke = "70 mm"
rod_length = "130 mm"
[cylinders]
count = 2
layout = "V"
bank_angle = "90 deg"
firing_order = [1, 2]
throw_angles = ["0 deg", "90 deg"]
[[torsion.mass]]
name = "a"
inertia = 1
cylinders = [1]
[[torsion.mass]]
name = "b"
inertia = 1
cylinders = [2]
[[torsion.shaft]]
between = ["a", "b"]
stiffness = 1
"""
    message = error_of(text, engine=True)
    assert "cylinders 1 and 2 share crank throw 1, so they belong on the same mass" in message


def test_unknown_model_name():
    with pytest.raises(InputError, match="no such file, built-in model"):
        resolve_torsion("seed003-v7")
    with pytest.raises(InputError, match="no \\[torsion\\] section"):
        resolve_torsion("v8-crossplane")


# ---- plain entries (bare SI numbers) read directly: the same model and the same errors ----------
PLAIN = """
[[mass]]
name = "a"
inertia = 0.5
damping = 2
[[mass]]
name = "b"
inertia = 1.25
[[shaft]]
between = ["a", "b"]
stiffness = 2.5e6
damping = 1.5
loss_factor = 0.02
[[shaft]]
between = ["b", "ground"]
stiffness = 4e5
"""

WITH_UNITS = PLAIN.replace("0.5\n", '"0.5 kg*m^2"\n').replace("2.5e6", '"2.5 MN*m/rad"')


def test_plain_entries_read_as_the_table_reader_reads_them():
    plain = parse_torsion_model(tomllib.loads(PLAIN), file="p.toml")
    units = parse_torsion_model(tomllib.loads(WITH_UNITS), file="u.toml")
    assert plain.masses == units.masses and plain.shafts == units.shafts
    assert [m.inertia for m in plain.masses] == [0.5, 1.25]
    assert plain.masses[0].damping == 2.0 and isinstance(plain.masses[0].damping, float)
    assert plain.shafts[0].stiffness == 2.5e6 and plain.shafts[0].loss_factor == 0.02


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        ("inertia = 0.5", "inertia = -0.5", "inertia"),
        ("inertia = 0.5", "inertia = true", "inertia"),
        ("inertia = 0.5", "inertia = 1e15", "outside the range"),
        ("inertia = 0.5", "inertia = nan", "not finite"),
        ("damping = 2", "damping = -2", "damping"),
        ("stiffness = 2.5e6", "stiffness = 0", "stiffness"),
        ("loss_factor = 0.02", "loss_factor = inf", "not finite"),
        ('between = ["a", "b"]', 'between = ["a", "c"]', "c"),
        ('between = ["a", "b"]', 'between = ["a", 3]', "between"),
        ('name = "b"', 'name = "a"', "a"),
    ],
)
def test_plain_entries_refused_with_the_table_readers_message(old, new, message):
    text = PLAIN.replace(old, new, 1)
    assert text != PLAIN
    with pytest.raises(InputError, match=message) as info:
        parse_torsion_model(tomllib.loads(text), file="p.toml")
    assert "p.toml" in str(info.value)


@pytest.mark.parametrize(
    ("old", "new", "key"),
    [
        ("inertia = 0.5", "inertia = 5e8", "inertia"),
        ("stiffness = 2.5e6", "stiffness = 0.5", "stiffness"),
        ("loss_factor = 0.02", "loss_factor = 0.9", "loss_factor"),
    ],
)
def test_plain_entries_keep_the_table_readers_plausibility_warnings(old, new, key):
    """An implausible bare number in a plain entry goes through the Table reader: the model
    carries its warning, as for the same entry with any other key."""
    assert not parse_torsion_model(tomllib.loads(PLAIN), file="p.toml").input_warnings
    model = parse_torsion_model(tomllib.loads(PLAIN.replace(old, new, 1)), file="p.toml")
    assert len(model.input_warnings) == 1 and key in model.input_warnings[0].message
