"""Every error names its target (issue 33, "Silent nonsense and unnamed errors"): extreme gear
ratios refused at the gear with the file and key (no numpy warning first), a cylinder number
beyond the engine's named at the mass, openTorsion models validated as they are converted."""

from __future__ import annotations

import re
import warnings
from importlib import resources

import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from crankdyn.errors import InputError
from crankdyn.torsion.elements import GEAR_RATIO_LIMIT, Gear, Mass, Shaft
from crankdyn.torsion.model import TorsionModel
from tests.conftest import fuzz_examples

EXAMPLES = resources.files("crankdyn") / "examples"
MARINE = (EXAMPLES / "torsion" / "marine-shaft-line.toml").read_text(encoding="utf-8")


def with_teeth(folder, teeth: str):
    path = folder / "line.toml"
    path.write_text(re.sub(r"(?m)^teeth = \[25, 80\]", f"teeth = {teeth}", MARINE), "utf-8")
    return path


@pytest.mark.parametrize("command", [["torsion", "modes"], ["torsion", "response"], ["tvc"]])
def test_extreme_gear_ratio_refused_at_the_gear(cli, tmp_path, command):
    """``teeth = [1, 1000000000000]`` before a propeller: four numpy RuntimeWarnings, then
    "orders = 0.0: orders must be positive" naming neither file nor key (issue 33)."""
    path = with_teeth(tmp_path, "[1, 1000000000000]")
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no warning of any kind on the way
        run = cli(*command, str(path))
    assert run.status == 2
    assert run.err == (
        f"crankdyn: error: {path}: [[gear]] #1 teeth = [1, 1000000000000]: a speed ratio of "
        "1e-12 lies beyond the 1:1000 to 1000:1 of one gear mesh (the largest built are about "
        "300:1); check the tooth numbers, or give a gear train as its stages\n"
    )


def test_gear_ratio_bounds():
    """Within 1/1000..1000 a mesh is accepted (the edges included); a ratio beyond is refused
    under ``ratio``, on gears and on elastic meshes given as shafts; meshes in series are held
    to 1e-6..1e6 of the reference speed (``gear``)."""
    assert Gear(("a", "b"), GEAR_RATIO_LIMIT).ratio == 1000.0
    assert Gear(("a", "b"), teeth=(1, 1000)).ratio == 1e-3
    with pytest.raises(InputError, match=r"^ratio = 1000\.1: a speed ratio of 1e\+03 lies"):
        Gear(("a", "b"), 1000.1)
    with pytest.raises(InputError, match=r"^ratio = 0\.0001: a speed ratio of 0\.0001"):
        Shaft(("a", "b"), 1e5, ratio=1e-4, direction=-1)
    masses = tuple(Mass(n, 1.0, cylinders=(1,) if n == "a" else ()) for n in "abcd")
    gears = (Gear(("a", "b"), 1000.0), Gear(("b", "c"), 1000.0), Gear(("c", "d"), 2.0))
    with pytest.raises(InputError) as info:
        TorsionModel(masses=masses, shafts=(), gears=gears)
    assert str(info.value) == (
        'gear = 2000000.0: "d" turns at 2e+06 times the speed of "a" through the gears, '
        "beyond the 1e-6 to 1e6 crankdyn resolves; check the gear ratios"
    )


@settings(max_examples=fuzz_examples(30))
@given(a=st.integers(1, 10**13), b=st.integers(1, 10**13))
@example(a=1, b=10**12)
@example(a=10**12, b=1)
def test_fuzz_tooth_numbers(tmp_path_factory, a, b):
    """Any tooth numbers: the model's modes, or one line at the gear; no warning."""
    path = with_teeth(tmp_path_factory.mktemp("gear"), f"[{a}, {b}]")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            model = TorsionModel.from_file(path)
        except InputError as exc:
            assert str(exc).startswith(f"{path}: [[gear]] #1 teeth = [{a}, {b}]: "), str(exc)
            assert 1e-3 <= a / b <= 1e3 or "lies beyond" in str(exc)
            return
        from crankdyn.torsion.modal import natural_modes

        assert natural_modes(model).natural_frequency.size == model.dof_count


def test_a_cylinder_beyond_the_firing_order_is_named_at_its_mass(cli, tmp_path):
    """``cylinders = [7]`` on a mass of a 6-cylinder model blamed the firing order (issue 33);
    on an engine's [torsion] mass it names the engine's count, as it did."""
    line = (EXAMPLES / "torsion" / "verdict-geared-line.toml").read_text(encoding="utf-8")
    path = tmp_path / "m7.toml"
    path.write_text(line.replace("cylinders = [6]", "cylinders = [7]"), encoding="utf-8")
    run = cli("torsion", "modes", str(path))
    assert run.status == 2
    assert run.err == (
        f"crankdyn: error: {path}: [[mass]] #7 cylinders = [7]: the [excitation] firing_order "
        "names 6 cylinders (1..6)\n"
    )
    engine = (EXAMPLES / "inline6-diesel.toml").read_text(encoding="utf-8")
    path = tmp_path / "e7.toml"
    path.write_text(engine.replace("cylinders = [6]", "cylinders = [7]"), encoding="utf-8")
    (tmp_path / "mendes2008_pressure.csv").write_bytes(
        (EXAMPLES / "mendes2008_pressure.csv").read_bytes()
    )
    run = cli("torsion", "modes", str(path))
    assert run.err == (
        f"crankdyn: error: {path}: [[torsion.mass]] #8 cylinders = [7]: the engine has 6 "
        "cylinders (1..6)\n"
    )


# ---- openTorsion conversion ---------------------------------------------------------------------


def assembly(node=1, radius=2.0, inertia=0.7, parent_radius=1.0):
    """An openTorsion-like assembly (the attributes from_opentorsion reads): two disks on a
    shaft, and a pair of rigid gears at nodes 1 and 2."""
    from types import SimpleNamespace as Element

    pinion = Element(node=1, I=0.1, R=parent_radius, parent=None)
    wheel = Element(node=2, I=0.3, R=radius, parent=pinion)
    return Element(
        shaft_elements=[Element(nl=0, nr=node, k=1e4, c=0.0, mass=0.0, odl=None)],
        disk_elements=[Element(node=0, I=0.4, c=0.0, k=0.0), Element(node=2, I=inertia, c=0, k=0)],
        gear_elements=[pinion, wheel],
    )


@pytest.mark.parametrize(
    ("kw", "message"),
    [
        ({"radius": 0}, "gear_elements[1].R = 0: a gear's radius must be positive"),
        ({"parent_radius": 0.0}, "gear_elements[1].parent.R = 0.0: a gear's radius must be"),
        ({"node": 1.5}, "shaft_elements[0].nr = 1.5: expected a node number, a whole number"),
        ({"node": -1}, "shaft_elements[0].nr = -1: expected a node number, a whole number >= 0"),
        ({"node": "1"}, 'shaft_elements[0].nr = "1": expected a node number'),
        ({"node": True}, "shaft_elements[0].nr = true: expected a node number"),
        ({"inertia": float("nan")}, "disk_elements[1].I = nan: the value is not finite"),
        ({"inertia": -0.7}, "disk_elements[1].I = -0.7: must not be negative"),
        ({"radius": 1e5}, "gear_elements[1]: ratio = 1e-05: a speed ratio of 1e-05 lies beyond"),
    ],
)
def test_opentorsion_conversion_validates_what_it_reads(kw, message):
    """A Gear with R = 0 raised ZeroDivisionError; node 1.5 was silently node 1 (issue 33)."""
    with pytest.raises(InputError) as info:
        TorsionModel.from_opentorsion(assembly(**kw))
    assert str(info.value).startswith(message), str(info.value)


def test_opentorsion_numpy_numbers_are_accepted():
    import numpy as np

    model = TorsionModel.from_opentorsion(assembly(node=np.int64(1), radius=np.float64(2.0)))
    assert model.mass_names == ("node 0", "node 1", "node 2")
    with pytest.raises(InputError, match=r"^shaft_elements\[0\]\.nr = 1\.5:"):
        TorsionModel.from_opentorsion(assembly(node=np.float64(1.5)))


values = st.one_of(
    st.integers(-3, 5),
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([None, "x", True, 0, 0.0, 1.5, -1]),
)


@settings(max_examples=fuzz_examples(60))
@given(node=values, radius=values, inertia=values, parent_radius=values)
def test_fuzz_opentorsion_elements(node, radius, inertia, parent_radius):
    """Any element values: a model, or one line naming the element."""
    try:
        TorsionModel.from_opentorsion(
            assembly(node=node, radius=radius, inertia=inertia, parent_radius=parent_radius)
        )
    except InputError as exc:
        assert "\n" not in str(exc)
