"""The mass-elastic table as CSV: written and read back to the same model, and one-line errors."""

from __future__ import annotations

import numpy as np
import pytest

from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.io.catalogue import resolve_torsion
from crankdyn.io.mass_elastic import mass_elastic_csv, read_mass_elastic
from crankdyn.torsion import Gear, Mass, Shaft, ShaftGeometry, TorsionModel
from crankdyn.torsion.modal import natural_modes


def _roundtrip(model, tmp_path):
    path = tmp_path / "table.csv"
    path.write_text(mass_elastic_csv(model), encoding="utf-8")
    return read_mass_elastic(path)


@pytest.mark.parametrize("name", ["genset-1500", "marine-propulsion"])
def test_built_in_lines_roundtrip(name, tmp_path):
    model = Engine.example(name).torsion
    back = _roundtrip(model, tmp_path)
    assert back.mass_names == model.mass_names
    assert natural_modes(back).natural_frequency == pytest.approx(
        natural_modes(model).natural_frequency, rel=1e-9, abs=1e-9
    )
    assert back.cylinder_dofs == model.cylinder_dofs
    assert np.array_equal(back.rotation, model.rotation)
    assert back.hysteretic_matrix() == pytest.approx(model.hysteretic_matrix(), rel=1e-9)


def test_elastic_mesh_grounded_shaft_and_diameters_roundtrip(tmp_path):
    model = TorsionModel(
        masses=(Mass("a", 1.0, damping=3.0, cylinders=(1, 2)), Mass("b", 0.2), Mass("c", 4.0)),
        shafts=(
            Shaft(("ground", "a"), 5e3),
            Shaft(("a", "b"), 2e5, damping=7.0, geometry=ShaftGeometry(0.05, 0.01)),
        ),
        gears=(Gear(("b", "c"), teeth=(17, 51), stiffness=8e5, direction="same"),),
    )
    back = _roundtrip(model, tmp_path)
    assert back.stiffness_matrix() == pytest.approx(model.stiffness_matrix())
    assert back.damping_matrix() == pytest.approx(model.damping_matrix())
    assert back.shafts[1].geometry.inner_diameter == pytest.approx(0.01)
    mesh = next(s for s in back.shafts if s.is_mesh)
    assert mesh.ratio == pytest.approx(1 / 3) and mesh.direction == 1


def test_a_table_is_a_model_argument(tmp_path):
    path = tmp_path / "t.csv"
    path.write_text(mass_elastic_csv(TorsionModel.example("seed003-v6")), encoding="utf-8")
    model = resolve_torsion(str(path))
    assert model.mass_count == TorsionModel.example("seed003-v6").mass_count


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("name,inertia [kg*m^2]\na,1\n", "expected a column 'stiffness'"),
        ("name,inertia,stiffness [N*m/rad]\na,1,5\nb,2,\n", "the column must name its unit"),
        (
            "name,inertia [kg*m^2],stiffness [N*m/rad],colour\na,1,5,red\n",
            "unknown column",
        ),
        (
            "name,inertia [kg*m^2],stiffness [N*m/rad]\na,1,\nb,2,\n",
            "line 2 stiffness: missing; give the stiffness (or gear_ratio) to the next mass",
        ),
        (
            "name,inertia [kg*m^2],stiffness [N*m/rad]\na,1,1e5\nb,x,\n",
            'line 3 inertia = "x": not a number',
        ),
        (
            "name,inertia [kg*m^2],stiffness [N*m/rad]\na,1,1e5\nb,2,3e4\n",
            "the last row has no next mass",
        ),
        (
            "name,inertia [kg*m^2],stiffness [N*m/rad],gear_ratio,gear_direction\n"
            "a,1,,0,\nb,2,,,\n",
            "a gear ratio cannot be zero",
        ),
        # issue 33: the SI range check of the TOML reader, with the line, column and value
        (
            "name,inertia [kg*m^2],stiffness [N*m/rad]\na,1,1e5\nb,1e-15,\n",
            "bad.csv: line 3 inertia = \"1e-15\": 1e-15 kg*m^2 in column 'inertia [kg*m^2]' lies "
            "outside the range crankdyn computes with (1e-12 to 1e12 in SI units, or 0); check "
            "the unit",
        ),
        (
            "name,inertia [kg*m^2],stiffness [N*m/rad]\na,1e300,1e5\nb,1,\n",
            "bad.csv: line 2 inertia = \"1e300\": 1e+300 kg*m^2 in column 'inertia [kg*m^2]' "
            "lies outside the range crankdyn computes with (1e-12 to 1e12 in SI units, or 0)",
        ),
        (
            "name,inertia [kg*m^2],stiffness [kN*m/rad],loss_factor\na,1,1e10,1e-13\nb,1,,\n",
            "bad.csv: line 2 stiffness = \"1e10\": 1e+13 N*m/rad in column 'stiffness [kN*m/rad]' "
            "lies outside",
        ),
        (
            "name,inertia [kg*m^2],stiffness [N*m/rad],loss_factor\na,1,1e5,1e-13\nb,1,,\n",
            "bad.csv: line 2 loss_factor = \"1e-13\": 1e-13 in column 'loss_factor' lies outside",
        ),
    ],
)
def test_errors_are_one_line(tmp_path, text, expected):
    path = tmp_path / "bad.csv"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(InputError) as info:
        read_mass_elastic(path, "bad.csv")
    message = str(info.value)
    assert "\n" not in message and message.startswith("bad.csv") and expected in message, message


def test_branched_models_have_no_table():
    model = TorsionModel(
        masses=tuple(Mass(n, 1.0) for n in "abcd"),
        shafts=(Shaft(("a", "b"), 1.0), Shaft(("b", "c"), 1.0), Shaft(("b", "d"), 1.0)),
    )
    with pytest.raises(InputError, match='branches at "b"'):
        mass_elastic_csv(model)


def test_a_branched_model_file_is_named(cli, tmp_path):
    """``torsion table`` on a branched model named the model, not its file (issue 33)."""
    path = tmp_path / "branched.toml"
    path.write_text(
        'name = "Y"\n'
        + "".join(f'[[mass]]\nname = "{n}"\ninertia = "1 kg*m^2"\n' for n in "abcd")
        + "".join(
            f'[[shaft]]\nbetween = ["{a}", "{b}"]\nstiffness = "1 N*m/rad"\n'
            for a, b in ("ab", "bc", "bd")
        ),
        encoding="utf-8",
    )
    run = cli("torsion", "table", str(path))
    assert run.status == 2
    assert run.err == (
        f'crankdyn: error: {path}: model = "Y": the mass-elastic table holds a chain and the '
        'model branches at "b"\n'
    )
