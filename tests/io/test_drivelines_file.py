"""Driveline files: a shaft line joined to an engine ([torsion] shaft_line, [[torsion.line]]),
engines joined to a line ([[engine]]), and the new [[shaft]], [[gear]], [[mass]] and
[[excitation.*]] keys, with their one-line errors."""

from __future__ import annotations

import math
import textwrap
import tomllib

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.io.catalogue import load_torsion_model
from crankdyn.io.engine_file import load_engine
from crankdyn.io.torsion_file import parse_torsion_model
from crankdyn.torsion.excitation import excitation_for
from crankdyn.torsion.modal import natural_modes
from crankdyn.torsion.sources import EngineSource
from crankdyn.torsion.sweep import forced_response

ENGINE = """
name = "test engine"
[geometry]
bore = "120 mm"
stroke = "140 mm"
rod_length = "260 mm"
[cylinders]
count = 4
firing_order = [1, 3, 4, 2]
[masses]
reciprocating = "2 kg"
rotating = "2.5 kg"
[operating]
speed = "1800 rpm"
[torsion]
{line}
[torsion.throws]
inertia = "0.05 kg*m^2"
stiffness = "1.2 MN*m/rad"
[[torsion.mass]]
name = "flywheel"
inertia = "1.5 kg*m^2"
[[torsion.shaft]]
between = ["throw 4", "flywheel"]
stiffness = "2 MN*m/rad"
"""

LINE = """
name = "line"
input = "hub"
[operating]
speed_range = ["800 rpm", "2000 rpm"]
rated_speed = "1800 rpm"
[[mass]]
name = "hub"
inertia = "0.4 kg*m^2"
[[mass]]
name = "pinion"
inertia = "0.02 kg*m^2"
role = "gear"
[[mass]]
name = "wheel"
inertia = "0 kg*m^2"
role = "gear"
[[mass]]
name = "load"
inertia = "3 kg*m^2"
role = "propeller"
[[shaft]]
between = ["hub", "pinion"]
kind = "coupling"
dynamic_stiffness = "40 kN*m/rad"
relative_damping = 1.0
nominal_torque = "1.2 kN*m"
[[gear]]
between = ["pinion", "wheel"]
teeth = [20, 50]
[[shaft]]
between = ["wheel", "load"]
length = "1.5 m"
outer_diameter = "60 mm"
shear_modulus = "80 GPa"
density = "7850 kg/m^3"
elements = 3
role = "propulsion shaft"
[[excitation.propeller]]
at = "load"
blades = 3
fractions = [0.05]
power = "100 kW"
"""


def _write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text), encoding="utf-8")
    return path


@pytest.fixture
def files(tmp_path):
    _write(tmp_path, "line.toml", LINE)
    engine = _write(tmp_path, "engine.toml", ENGINE.format(line='shaft_line = "line.toml"'))
    return tmp_path, engine


def test_engine_with_a_shaft_line(files):
    tmp_path, path = files
    engine = load_engine(path)
    model = engine.torsion
    # engine masses, then the line's; the line's hub joined rigidly to the flywheel
    assert model.mass_names[:6] == ("throw 1", "throw 2", "throw 3", "throw 4", "flywheel", "hub")
    assert "flywheel + hub" in model.dof_names and "pinion + wheel" in model.dof_names
    assert model.is_chain and model.is_free
    assert [s.kind for s in model.sources] == ["propeller"]
    assert model.speed_ratios[model.index("load")] == pytest.approx(0.4)
    assert model.rotation[model.index("load")] == -1.0  # an external mesh reverses
    # the subdivided propulsion shaft: 3 elements, 2 generated masses
    assert [s.segment_of for s in model.shafts].count(("wheel", "load")) == 3
    # the propeller's speed defaulted to the line's rated speed times its ratio
    load = model.sources[0].load
    assert load.speed == pytest.approx(1800.0 / RPM * 0.4)
    assert load.torque * load.speed == pytest.approx(100e3)
    # the line alone is a model of its own (free, excited by its propeller only)
    line = load_torsion_model(tmp_path / "line.toml")
    assert line.is_free and not line.cylinder_dofs and line.sources
    ex = excitation_for(model, engine)
    r = forced_response(model, ex, np.linspace(800.0, 2000.0, 13) / RPM, [0.5, 1.2, 2.0])
    assert np.all(np.isfinite(r.synthesized_shaft_torque))


def test_an_engine_drives_two_copies_of_one_line(tmp_path):
    _write(tmp_path, "line.toml", LINE)
    two = (
        'shaft_line = "line.toml"\n[[torsion.line]]\nfile = "line.toml"\nat = "throw 2"\n'
        'prefix = "PTO "'
    )
    # shaft_line and [[torsion.line]] together: the main line at the flywheel, a PTO at throw 2
    path = _write(tmp_path, "e2.toml", ENGINE.format(line=two))
    model = load_engine(path).torsion
    assert "PTO hub" in model.mass_names and "hub" in model.mass_names
    assert not model.is_chain  # the PTO branches off throw 2
    assert len(model.sources) == 2


def test_twin_input_gearbox_with_two_engines(tmp_path):
    _write(tmp_path, "engine.toml", ENGINE.format(line=""))
    twin = """
    name = "twin input"
    [operating]
    speed_range = ["800 rpm", "2000 rpm"]
    rated_speed = "1800 rpm"
    [[mass]]
    name = "input A"
    inertia = "0.1 kg*m^2"
    role = "gear"
    [[mass]]
    name = "input B"
    inertia = "0.1 kg*m^2"
    role = "gear"
    [[mass]]
    name = "bull gear"
    inertia = "2 kg*m^2"
    role = "gear"
    [[mass]]
    name = "propeller"
    inertia = "40 kg*m^2"
    [[gear]]
    between = ["input A", "bull gear"]
    teeth = [25, 100]
    stiffness = "3 MN*m/rad"
    [[gear]]
    between = ["input B", "bull gear"]
    teeth = [25, 100]
    stiffness = "3 MN*m/rad"
    [[shaft]]
    between = ["bull gear", "propeller"]
    stiffness = "1.5 MN*m/rad"
    [[excitation.propeller]]
    at = "propeller"
    blades = 4
    fractions = [0.05]
    power = "200 kW"
    [[engine]]
    file = "engine.toml"
    name = "port"
    at = "input A"
    [[engine]]
    file = "engine.toml"
    name = "starboard"
    at = "input B"
    phase = "90 deg"
    share = 1.0
    """
    model = load_torsion_model(_write(tmp_path, "twin.toml", twin))
    assert "port: throw 1" in model.mass_names and "starboard: throw 1" in model.mass_names
    assert model.engine is not None and model.cylinder_dofs  # the port engine's cylinders
    engines = [s for s in model.sources if isinstance(s, EngineSource)]
    assert len(engines) == 1 and engines[0].phase == pytest.approx(math.pi / 2)
    assert not model.is_chain
    ex = excitation_for(model)  # the first engine's excitation, from the model
    speeds = np.linspace(900.0, 1900.0, 6) / RPM
    r = forced_response(model, ex, speeds, [0.5, 1.0, 2.0])
    assert np.all(np.isfinite(r.amplitude))
    # the load is shared: each input pinion carries half the propeller's reflected torque
    from crankdyn.torsion.sources import mean_torques

    mt = mean_torques(model, [1800.0 / RPM])
    meshes = [i for i, s in enumerate(model.shafts) if s.kind == "mesh"]
    assert mt.mean_torque[0, meshes] == pytest.approx([0.5 * 200e3 / (1800 / RPM)] * 2, rel=1e-9)
    assert natural_modes(model).natural_frequency[0] == 0.0


@pytest.mark.parametrize(
    ("line", "expected"),
    [
        ('shaft_line = "nope.toml"', 'shaft_line = "nope.toml": no such shaft-line file'),
        (
            'shaft_line = "line.toml"\nconnect_at = "flywhel"',
            'connect_at = "flywhel": no mass named "flywhel" (did you mean "flywheel"?)',
        ),
        ('connect_at = "flywheel"', 'connect_at = "flywheel": applies with shaft_line'),
    ],
)
def test_engine_line_errors(tmp_path, line, expected):
    _write(tmp_path, "line.toml", LINE)
    path = _write(tmp_path, "e.toml", ENGINE.format(line=line))
    with pytest.raises(InputError) as info:
        load_engine(path)
    text = str(info.value)
    assert "\n" not in text and expected in text and "e.toml" in text


def test_a_line_that_does_not_connect(tmp_path):
    broken = LINE.replace('[[gear]]\nbetween = ["pinion", "wheel"]\nteeth = [20, 50]\n', "")
    _write(tmp_path, "line.toml", broken)
    path = _write(tmp_path, "e.toml", ENGINE.format(line='shaft_line = "line.toml"'))
    with pytest.raises(InputError, match=r'disconnected: no shaft or gear joins "wheel"') as info:
        load_engine(path)
    assert "line.toml: " in str(info.value) and "\n" not in str(info.value)


@pytest.mark.parametrize(
    ("old", "new", "expected"),
    [
        ("teeth = [20, 50]", "ratio = 0", "ratio = 0.0: a gear ratio cannot be zero"),
        (
            "teeth = [20, 50]",
            "teeth = [0, 50]",
            "teeth = [0, 50]: tooth numbers must be at least 1",
        ),
        (
            "teeth = [20, 50]",
            'teeth = [20, 50]\ndirection = "reverse"',
            'direction = "reverse": expected one of',
        ),
        (
            "relative_damping = 1.0",
            "relative_damping = 12.0",
            "relative_damping = 12.0: the relative damping psi",
        ),
        (
            'dynamic_stiffness = "40 kN*m/rad"',
            'stiffness = "40 kN*m/rad"',
            'stiffness = "40 kN*m/rad": a coupling\'s stiffness',
        ),
        ("fractions = [0.05]", "fractions = [0.05]\norders = [2]", "orders = [2]: unknown key"),
        (
            'power = "100 kW"',
            'power = "100 kW"\nmean_torque = "1 kN*m"',
            "give power or mean_torque, not both",
        ),
        ('at = "load"', 'at = "lood"', 'at = "lood": no mass named "lood"'),
        (
            'inertia = "0 kg*m^2"\nrole = "gear"',
            'inertia = "0 kg*m^2"',
            'inertia = "0 kg*m^2": must be positive',
        ),
        ("elements = 3", "elements = 0", "elements = 0: must be at least 1"),
        (
            'density = "7850 kg/m^3"',
            'density = "7850 kg/m^3"\ninertia = "1 kg*m^2"',
            "give the density (with the geometry) or the shaft's inertia, not both",
        ),
    ],
)
def test_line_key_errors(tmp_path, old, new, expected):
    assert old in LINE
    doc = tomllib.loads(LINE.replace(old, new, 1))
    with pytest.raises(InputError) as info:
        parse_torsion_model(doc, file="line.toml")
    text = str(info.value)
    assert "\n" not in text and text.startswith("line.toml") and expected in text, text


def test_both_wheels_without_inertia_are_refused():
    lumped = LINE.replace('density = "7850 kg/m^3"\nelements = 3\n', "")
    doc = tomllib.loads(
        lumped.replace(
            'inertia = "0.02 kg*m^2"\nrole = "gear"', 'inertia = "0 kg*m^2"\nrole = "gear"'
        )
    )
    with pytest.raises(
        InputError, match='the gear wheels "pinion", "wheel" have no inertia together'
    ):
        parse_torsion_model(doc, file="line.toml")


def test_elastic_mesh_from_the_line_of_action(tmp_path):
    text = LINE.replace(
        "teeth = [20, 50]",
        'teeth = [20, 50]\nmesh_stiffness = "1.5e9 N/m"\nbase_diameter = "80 mm"\n'
        'damping = "5 N*m*s/rad"',
    ).replace('inertia = "0 kg*m^2"', 'inertia = "0.1 kg*m^2"')
    model = parse_torsion_model(tomllib.loads(text), file="line.toml")
    mesh = next(s for s in model.shafts if s.kind == "mesh")
    assert mesh.stiffness == pytest.approx(1.5e9 * 0.04**2)
    assert mesh.ratio == pytest.approx(0.4) and mesh.direction == -1
    assert mesh.gear is not None and mesh.gear.teeth == (20, 50)
    assert not model.gears


def test_mass_limits_are_kept():
    text = LINE.replace(
        'name = "load"\ninertia = "3 kg*m^2"\nrole = "propeller"',
        'name = "load"\ninertia = "3 kg*m^2"\nrole = "alternator"\n[mass.limits]\n'
        'vibratory_torque = "2 kN*m"\nangular_acceleration = "1500 rad/s^2"\nsource = "maker"',
    )
    model = parse_torsion_model(tomllib.loads(text), file="line.toml")
    m = model.masses[model.index("load")]
    assert m.role == "alternator"
    assert (m.limits.vibratory_torque, m.limits.angular_acceleration, m.limits.source) == (
        2000.0,
        1500.0,
        "maker",
    )
