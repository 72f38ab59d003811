"""Inputs that cannot pass silently (issue 32, item 2): a bare speed in a file is refused, a unit
of the wrong dimension for its key is refused (a torque for a torsional stiffness), and every
other value outside the plausible range of its role is a warning naming the file, the key, the
value as written and the range (crankdyn.io.plausibility), carried by the domain objects."""

from __future__ import annotations

import math

import pytest

from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.io.catalogue import load_example, resolve_model_and_engine
from crankdyn.io.engine_file import parse_engine
from crankdyn.io.examples import example_names, example_path
from crankdyn.io.files import load_toml
from crankdyn.io.mass_elastic import read_mass_elastic
from crankdyn.io.plausibility import ROLES, check_input, role_of
from crankdyn.io.torsion_file import parse_torsion_model
from crankdyn.io.units import BARE_SPEED, parse_quantity
from crankdyn.plausibility import InputWarning

LINE = """name = "test line"
[operating]
speed_range = ["300 rpm", "750 rpm"]
rated_speed = "750 rpm"
[[mass]]
name = "engine"
inertia = "400 kg*m^2"
[[mass]]
name = "propeller"
inertia = "900 kg*m^2"
[[shaft]]
between = ["engine", "propeller"]
name = "line shaft"
stiffness = "10 MN*m/rad"
outer_diameter = "200 mm"
loss_factor = 0.01
"""


def _model(text: str, file: str = "line.toml"):
    import tomllib

    return parse_torsion_model(tomllib.loads(text), file=file)


def _one_line(exc: pytest.ExceptionInfo[InputError]) -> str:
    text = str(exc.value)
    assert "\n" not in text
    return text


# ---- bare speeds are refused ---------------------------------------------------------------
@pytest.mark.parametrize(
    "old, new, key, value",
    [
        (
            'speed_range = ["300 rpm", "750 rpm"]',
            'speed_range = ["350", "1000"]',
            "[operating] speed_range",
            '"350"',
        ),
        ('rated_speed = "750 rpm"', "rated_speed = 750", "[operating] rated_speed", "750"),
        (
            'rated_speed = "750 rpm"',
            'rated_speed = "750 rpm"\n[tvc]\nengine_torque_curve = [[300, "20 kN*m"]]',
            "[tvc] engine_torque_curve",
            "300",
        ),
        (
            'rated_speed = "750 rpm"',
            'rated_speed = "750 rpm"\n[tvc]\nspeed_step = 5',
            "[tvc] speed_step",
            "5",
        ),
    ],
)
def test_a_bare_speed_in_a_model_file_is_refused(old, new, key, value):
    """The same text on the command line (--speeds 350:1000) is rpm; in a file it would be
    read as rad/s (3342-9549 rpm): refused in one line naming file, key and value."""
    with pytest.raises(InputError) as exc:
        _model(LINE.replace(old, new))
    text = _one_line(exc)
    assert text == f"line.toml: {key} = {value}: {BARE_SPEED}"


def test_a_bare_speed_in_an_engine_file_is_refused():
    data = load_toml(example_path("vaz2108"))
    data["operating"]["speed"] = 5600
    with pytest.raises(InputError) as exc:
        parse_engine(data, file="vaz.toml", base_dir=example_path("vaz2108").parent)
    assert _one_line(exc) == f"vaz.toml: [operating] speed = 5600: {BARE_SPEED}"


def test_a_speed_with_its_unit_and_a_bare_zero_are_read():
    assert parse_quantity("750 rpm", "speed") == pytest.approx(750 / RPM)
    assert parse_quantity("78.54 rad/s", "speed") == pytest.approx(78.54)
    assert parse_quantity(0, "speed") == 0.0  # 0 is 0 in any unit
    assert parse_quantity("750", "speed", default_unit="rpm") == pytest.approx(750 / RPM)


def test_a_load_curve_speed_column_without_unit_is_refused(tmp_path):
    from crankdyn.io.torsion_tables import read_load_curve

    path = tmp_path / "load.csv"
    path.write_text("speed,load_factor\n300,0.2\n750,1\n", encoding="utf-8")
    with pytest.raises(InputError) as exc:
        read_load_curve(path, "load.csv")
    text = _one_line(exc)
    assert text.startswith('load.csv: header = "speed": ') and BARE_SPEED in text


@pytest.mark.parametrize(
    "body, key, value",
    [
        (
            '[[parameter]]\nkey = "operating.speed"\nvalues = [1000, 2000]\n',
            "[[parameter]] #1 values",
            "[1000, 2000]",
        ),
        (
            '[[parameter]]\nkey = "operating.speed"\nrange = [1000, 3000]\nsteps = 3\n',
            "[[parameter]] #1 range",
            "[1000, 3000]",
        ),
        (
            '[[parameter]]\nkey = "geometry.bore"\nvalues = ["75 mm", "76 mm"]\n'
            "[analysis]\nspeed = 3000\n",
            "[analysis] speed",
            "3000",
        ),
    ],
)
def test_a_bare_speed_in_a_study_file_is_refused(tmp_path, body, key, value):
    """A study varying the engine's speed with bare numbers (or giving its own speed bare) is
    refused before any case runs, naming the study file, the key and the values."""
    from crankdyn.io.study_file import load_study
    from tests.study.helpers import ENGINE

    (tmp_path / "engine.toml").write_text(ENGINE.format(name="e"), encoding="utf-8")
    analysis = "" if "[analysis]" in body else "[analysis]\n"
    text = 'engine = "engine.toml"\n' + body + analysis + 'figures = ["mean_torque"]\n'
    (tmp_path / "study.toml").write_text(text, encoding="utf-8")
    with pytest.raises(InputError) as exc:
        load_study(tmp_path / "study.toml")
    assert _one_line(exc).endswith(f"study.toml: {key} = {value}: {BARE_SPEED}")


# ---- units of the wrong dimension for their key ----------------------------------------------
def test_a_torque_unit_as_a_stiffness_is_refused():
    """pint counts the radian as dimensionless, so N*m and N*m/rad have one dimension: the kind
    says whether the unit must be per angle."""
    text = LINE.replace('stiffness = "10 MN*m/rad"', 'stiffness = "95 MN*m"')
    with pytest.raises(InputError) as exc:
        _model(text)
    assert _one_line(exc) == (
        'line.toml: [[shaft]] #1 stiffness = "95 MN*m": expected a torsional stiffness '
        '(e.g. "160 kN*m/rad"), got a torque'
    )


@pytest.mark.parametrize(
    "value, kind, got",
    [
        ("95 MN*m", "torsional_stiffness", "a torque"),
        ("12 kN*m", "torsional_stiffness", "a torque"),  # the pint-free path of COMMON_UNITS
        ("3 kJ", "torsional_stiffness", "a torque"),
        ("50 kN*m/rad", "torque", "a torsional stiffness"),
        ("10 N*m/deg", "torque", "a torsional stiffness"),
        ("70 N*m*s", "torsional_damping", "a quantity of dimension"),
    ],
)
def test_per_angle_units_are_told_from_torques(value, kind, got):
    with pytest.raises(InputError, match=f"got {got}"):
        parse_quantity(value, kind, key="k", file="f.toml")


def test_stiffness_and_torque_units_still_read():
    assert parse_quantity("95 MN*m/rad", "torsional_stiffness") == 95e6
    assert parse_quantity("2 kN*m/deg", "torsional_stiffness") == pytest.approx(2e3 * 180 / math.pi)
    assert parse_quantity("95 MN*m", "torque") == 95e6
    assert parse_quantity("70 kN*m*s/rad", "torsional_damping") == 70e3


# ---- implausible values are listed warnings ---------------------------------------------------
def test_a_bare_180_for_a_shaft_diameter_is_a_warning():
    model = _model(LINE.replace('outer_diameter = "200 mm"', "outer_diameter = 180"))
    (w,) = model.input_warnings
    assert isinstance(w, InputWarning)
    assert (w.file, w.input_key, w.written, w.value) == (
        "line.toml",
        "[[shaft]] #1 outer_diameter",
        180,
        180.0,
    )
    assert w.message.startswith(
        "line.toml: [[shaft]] #1 outer_diameter = 180: 180 m is outside the 0.003-3 m of "
        "shaft diameters ("
    )
    assert w.message.endswith("; did you mean 180 mm?")
    assert "\n" not in w.message
    assert (w.low, w.high) == (0.003, 3.0)


def test_a_loss_factor_of_2_is_a_warning():
    """A shaft's loss factor eta = psi / 2 pi; 2 is the relative damping psi of a rubber
    coupling typed into the wrong key."""
    model = _model(LINE.replace("loss_factor = 0.01", "loss_factor = 2"))
    (w,) = model.input_warnings
    assert w.message.startswith(
        "line.toml: [[shaft]] #1 loss_factor = 2: 2 is outside the 0-0.5 of loss factors ("
    )
    assert w.message.endswith("was the relative damping psi given?")


def test_a_unit_slip_with_a_unit_is_a_warning_too():
    """A propeller of 90000 kg m^2 typed with tonnes: 9e7 kg m^2."""
    model = _model(LINE.replace('inertia = "900 kg*m^2"', 'inertia = "90000 t*m^2"'))
    (w,) = model.input_warnings
    assert w.input_key == "[[mass]] #2 inertia" and w.written == "90000 t*m^2"
    assert '= "90000 t*m^2": 9e7 kg*m^2 is outside the 1e-7 to 1e7 kg*m^2' in w.message
    assert w.message.endswith("did you mean 90000 kg*m^2?")


def test_an_engine_files_implausible_number_is_a_warning():
    """A skirt friction coefficient of 0.5 (the model takes any mu < 1) is warned, and the
    engine carries the warning."""
    data = load_toml(example_path("vaz2108"))
    data["forces"] = {"ring_friction": "40 N", "skirt_friction": 0.5}
    engine = parse_engine(data, file="vaz.toml", base_dir=example_path("vaz2108").parent)
    (w,) = engine.input_warnings
    assert w.message.startswith(
        "vaz.toml: [forces] skirt_friction = 0.5: 0.5 is outside the 0-0.4 of skirt friction "
        "coefficients"
    )


def test_a_speed_range_far_from_the_rated_speed_is_a_warning():
    """Hz for rpm: the range ends at 60 times the rated speed."""
    model = _model(LINE.replace('["300 rpm", "750 rpm"]', '["300 Hz", "750 Hz"]'))
    (w,) = model.input_warnings
    assert w.input_key == "[operating] speed_range"
    assert "the range ends at 45000 rpm, 60 times the rated speed 750 rpm" in w.message


def test_every_implausible_item_of_a_list_is_listed():
    text = LINE.replace(
        'name = "line shaft"',
        'name = "line shaft"\nkind = "coupling"\nstiffness_table = [["0 kN*m", "190 kN*m/rad"], '
        '["15 kN*m", "240 kN*m/rad"]]\nrelative_damping = 0.01',
    )
    text = text.replace('stiffness = "10 MN*m/rad"\n', "").replace("loss_factor = 0.01\n", "")
    model = _model(text)
    assert [w.input_key for w in model.input_warnings] == ["[[shaft]] #1 relative_damping"]


def test_warnings_of_a_shaft_line_reach_the_engine_that_joins_it(tmp_path):
    line = tmp_path / "line.toml"
    source = example_path("marine-shaft-line", "model").read_text(encoding="utf-8")
    line.write_text(source.replace('outer_diameter = "330 mm"', "outer_diameter = 330", 1))
    data = load_toml(example_path("marine-propulsion"))
    data["torsion"]["shaft_line"] = str(line)
    engine = parse_engine(data, file="e.toml", base_dir=example_path("marine-propulsion").parent)
    assert len(engine.input_warnings) == 1
    assert engine.torsion is not None and engine.torsion.input_warnings == engine.input_warnings
    assert "line.toml: [[shaft]] #" in engine.input_warnings[0].message


def test_the_mass_elastic_table_warns_naming_file_line_and_column(tmp_path):
    path = tmp_path / "me.csv"
    path.write_text(
        "name,inertia [kg*m^2],stiffness [N*m/rad],outer_diameter [mm],loss_factor\n"
        "engine,400,1e7,0.2,0.01\npropeller,900,,,\n",
        encoding="utf-8",
    )
    model = read_mass_elastic(path, "me.csv")
    (w,) = model.input_warnings
    assert w.message.startswith(
        'me.csv: line 2 outer_diameter = "0.2 mm": 0.0002 m is outside the 0.003-3 m of '
        "shaft diameters"
    )
    assert w.message.endswith("did you mean 0.2 m?")


# ---- the table -------------------------------------------------------------------------------
@pytest.mark.parametrize("kind", ["ratio", "inertia", "length", "speed"])
def test_roles_are_found_by_key_and_table(kind):
    assert role_of("length", "inner_diameter", "flywheel").name == "flywheel diameters"
    assert role_of("length", "inner_diameter", "shaft").name == "shaft diameters"
    assert role_of("ratio", "share", "engine") is None  # a plain number no role names
    assert role_of(kind, "a_key_no_role_names", "x") is (
        None if kind == "ratio" else next(r for r in ROLES if r.kind == kind and not r.keys)
    )


def test_every_role_is_well_formed():
    from crankdyn.io.units import KINDS

    for role in ROLES:
        assert role.kind in KINDS and 0.0 <= role.low < role.high, role
        assert role.reason and role.name
        assert role.holds(0.0) and role.holds(role.low or role.high) and role.holds(role.high)
        assert not role.holds(role.high * 1.01) and not role.holds(-role.high * 1.01)


def test_zero_is_never_implausible():
    assert check_input(0.0, "length", "inner_diameter") is None


@pytest.mark.parametrize("kind", ["engine", "model"])
def test_the_built_in_examples_carry_no_warnings(kind):
    """The examples are plausible: no value of theirs lies outside its role's range."""
    for name in example_names(kind):
        subject = load_example(name, kind)
        assert subject.input_warnings == (), name
        if kind == "engine" and subject.torsion is not None:
            assert subject.torsion.input_warnings == (), name
        if kind == "model" or subject.torsion is not None:
            model, _engine = resolve_model_and_engine(name)
            assert model.input_warnings == (), name
