"""The lumped torsional model: validation, structure, reflection through gears, matrices."""

import math

import numpy as np
import pytest

from crankdyn.errors import InputError
from crankdyn.torsion import GROUND, Gear, Mass, Shaft, ShaftGeometry, TorsionModel
from crankdyn.torsion.elements import shaft_stiffness


def chain3(**kw):
    masses = (Mass("a", 1.0, damping=0.5, cylinders=(1,)), Mass("b", 2.0), Mass("c", 3.0))
    shafts = (
        Shaft(("a", "b"), 10.0, damping=0.1, loss_factor=0.02),
        Shaft(("b", "c"), 20.0),
    )
    return TorsionModel(masses=masses, shafts=shafts, **kw)


def test_chain_is_detected_and_ordered():
    m = chain3()
    assert m.is_chain and m.is_free
    assert m.dof_names == ("a", "b", "c")
    assert m.chain.stiffness.tolist() == [10.0, 20.0]
    assert m.cylinder_dofs == {1: 0}


def test_chain_mass_normalised_matrix_is_made_once_and_read_only():
    """ChainArrays.normalised against the dense M^-1/2 K M^-1/2 built from the model's own K
    (an independent assembly), with sqrt(J), the total inertia and the smallest sqrt(J); the
    same object at every call, read-only, and left as it was by the modal solve that uses it."""
    from crankdyn.torsion.modal import natural_modes

    m = TorsionModel.chain_of([0.5, 2.0, 8.0, 1.0], [3e5, 1e6, 2e5], ground_right=4e4)
    a = m.chain.normalised
    root = np.sqrt(m.dof_inertia)
    dense = m.stiffness_matrix() / np.outer(root, root)
    np.testing.assert_allclose(a.diagonal, np.diag(dense), rtol=1e-15)
    np.testing.assert_allclose(a.off_diagonal, np.diag(dense, 1), rtol=1e-15)
    assert a.root_inertia.tolist() == root.tolist()
    assert a.total_inertia == 11.5 and a.least_root_inertia == math.sqrt(0.5)
    assert m.chain.normalised is a
    before = [arr.copy() for arr in (a.diagonal, a.off_diagonal, a.root_inertia)]
    for arr in (a.diagonal, a.off_diagonal, a.root_inertia):
        assert not arr.flags.writeable
    natural_modes(m)
    natural_modes(m, count=2)
    for arr, old in zip((a.diagonal, a.off_diagonal, a.root_inertia), before, strict=True):
        assert arr.tolist() == old.tolist()


def test_chain_order_follows_the_shafts_not_the_listing():
    masses = (Mass("a", 1.0), Mass("c", 3.0), Mass("b", 2.0))
    shafts = (Shaft(("a", "b"), 10.0), Shaft(("c", "b"), 20.0))
    m = TorsionModel(masses=masses, shafts=shafts)
    assert m.is_chain
    assert m.dof_names == ("a", "b", "c")
    # outputs stay in listing order: mass "c" is listed second, dof 2
    assert m.mass_dof.tolist() == [0, 2, 1]


def test_stiffness_matrix_is_symmetric_with_zero_row_sums_when_free():
    m = chain3()
    k = m.stiffness_matrix()
    assert np.allclose(k, k.T)
    assert np.allclose(k.sum(axis=1), 0.0)
    diag, off = m.chain.stiffness_diagonals()
    assert np.allclose(np.diag(k), diag)
    assert np.allclose(np.diag(k, 1), off)


def test_damping_matrices_hold_absolute_and_relative_parts():
    m = chain3()
    c = m.damping_matrix()
    assert c[0, 0] == pytest.approx(0.5 + 0.1)
    assert c[0, 1] == pytest.approx(-0.1)
    h = m.hysteretic_matrix()
    assert h[0, 0] == pytest.approx(0.02 * 10.0)
    assert m.chain.ground_damping.tolist() == [0.5, 0.0, 0.0]


def test_grounded_shaft_adds_to_the_diagonal_only():
    masses = (Mass("a", 1.0), Mass("b", 2.0))
    shafts = (Shaft((GROUND, "a"), 5.0), Shaft(("a", "b"), 10.0))
    m = TorsionModel(masses=masses, shafts=shafts)
    assert not m.is_free
    assert m.stiffness_matrix().tolist() == [[15.0, -10.0], [-10.0, 10.0]]
    assert m.chain.ground_stiffness.tolist() == [5.0, 0.0]


def test_gear_reflects_inertia_and_stiffness_by_the_ratio_squared():
    # engine (1 kg m^2) - shaft 100 - gear pair (0.1 and 0.2) at ratio 3 - shaft 50 - load 4
    masses = (
        Mass("engine", 1.0, cylinders=(1,)),
        Mass("pinion", 0.1),
        Mass("wheel", 0.2),
        Mass("load", 4.0),
    )
    shafts = (Shaft(("engine", "pinion"), 100.0), Shaft(("wheel", "load"), 50.0))
    gears = (Gear(("pinion", "wheel"), 3.0),)
    m = TorsionModel(masses=masses, shafts=shafts, gears=gears)
    assert m.is_chain and m.dof_count == 3
    assert m.speed_ratios.tolist() == [1.0, 1.0, 3.0, 3.0]
    assert m.dof_names == ("engine", "pinion + wheel", "load")
    assert np.allclose(m.dof_inertia, [1.0, 0.1 + 0.2 * 9, 4.0 * 9])
    assert np.allclose(m.chain.stiffness, [100.0, 50.0 * 9])


def test_branched_model_is_not_a_chain():
    masses = tuple(Mass(n, 1.0) for n in "abcd")
    shafts = (Shaft(("a", "b"), 1.0), Shaft(("b", "c"), 1.0), Shaft(("b", "d"), 1.0))
    m = TorsionModel(masses=masses, shafts=shafts)
    assert not m.is_chain
    assert m.chain is None
    assert m.junction == "b"


def test_parallel_shafts_still_make_a_chain():
    masses = (Mass("a", 1.0), Mass("b", 1.0))
    m = TorsionModel(masses=masses, shafts=(Shaft(("a", "b"), 1.0), Shaft(("b", "a"), 2.0)))
    assert m.is_chain
    assert m.chain.stiffness.tolist() == [3.0]


def test_shaft_stiffness_from_geometry():
    g = ShaftGeometry(outer_diameter=0.12, inner_diameter=0.04, length=0.75, shear_modulus=8e10)
    expected = 8e10 * math.pi * (0.12**4 - 0.04**4) / 32 / 0.75
    assert g.stiffness == pytest.approx(expected, rel=1e-15)
    assert shaft_stiffness(0.75, 0.12, 0.04, 8e10) == pytest.approx(expected, rel=1e-15)
    assert Shaft(("a", "b"), geometry=g).stiffness == pytest.approx(expected, rel=1e-15)
    assert g.section_modulus == pytest.approx(g.polar_moment / 0.06)


@pytest.mark.parametrize(
    ("build", "key", "text"),
    [
        (lambda: Mass("a", 0.0), "inertia", "must be positive"),
        (lambda: Mass("a", -1.0), "inertia", "must be positive"),
        (lambda: Mass(GROUND, 1.0), "name", "reserved"),
        (lambda: Mass("a", 1.0, damping=-1.0), "damping", "must not be negative"),
        (lambda: Mass("a", 1.0, cylinders=(0,)), "cylinders", "from 1 up"),
        (lambda: Shaft(("a", "b"), 0.0), "stiffness", "must be positive"),
        (lambda: Shaft(("a", "b"), -3.0), "stiffness", "must be positive"),
        (lambda: Shaft(("a", "a"), 1.0), "between", "two different masses"),
        (lambda: Shaft(("a", "b")), "stiffness", "missing"),
        (lambda: Shaft(("a", "b"), 1.0, loss_factor=-0.1), "loss_factor", "negative"),
        (lambda: Gear(("a", "b"), 0.0), "ratio", "cannot be zero"),
        (lambda: Gear(("a", "b"), -2.0), "ratio", "positive"),
        (lambda: Gear(("a", GROUND), 2.0), "between", "ground"),
        (lambda: ShaftGeometry(0.1, 0.1), "inner_diameter", "smaller"),
    ],
)
def test_bad_parts_raise_one_line_errors(build, key, text):
    with pytest.raises(InputError) as info:
        build()
    assert info.value.key == key
    assert text in str(info.value)
    assert "\n" not in str(info.value)


def test_unknown_mass_in_a_shaft():
    with pytest.raises(InputError, match='no mass named "x"'):
        TorsionModel(masses=(Mass("a", 1.0),), shafts=(Shaft(("a", "x"), 1.0),))


def test_disconnected_model():
    with pytest.raises(InputError, match='disconnected: no shaft or gear joins "c"'):
        TorsionModel(
            masses=(Mass("a", 1.0), Mass("b", 1.0), Mass("c", 1.0)),
            shafts=(Shaft(("a", "b"), 1.0),),
        )


def test_duplicate_names_and_cylinders():
    with pytest.raises(InputError, match="two masses are named"):
        TorsionModel(masses=(Mass("a", 1.0), Mass("a", 1.0)), shafts=(Shaft(("a", "a2"), 1),))
    with pytest.raises(InputError, match="cylinder 1 is on two masses"):
        TorsionModel(
            masses=(Mass("a", 1.0, cylinders=(1,)), Mass("b", 1.0, cylinders=(1,))),
            shafts=(Shaft(("a", "b"), 1.0),),
        )


def test_gear_loop_with_disagreeing_ratios():
    masses = tuple(Mass(n, 1.0) for n in "abc")
    with pytest.raises(InputError, match="gear ratios disagree"):
        TorsionModel(
            masses=masses,
            shafts=(Shaft(("a", "b"), 1.0),),
            gears=(Gear(("b", "c"), 2.0), Gear(("a", "c"), 3.0)),
        )


def test_shaft_across_a_gear_mesh_is_refused():
    masses = (Mass("a", 1.0), Mass("b", 1.0))
    with pytest.raises(InputError, match="already ties together"):
        TorsionModel(
            masses=masses, shafts=(Shaft(("a", "b"), 1.0),), gears=(Gear(("a", "b"), 1.0),)
        )


def test_single_free_mass_is_a_model():
    m = TorsionModel(masses=(Mass("a", 2.0),))
    assert m.is_chain and m.is_free and m.dof_count == 1


def test_chain_of_needs_matching_counts():
    with pytest.raises(InputError, match="needs 2 stiffnesses"):
        TorsionModel.chain_of([1, 1, 1], [1])


def test_magnitudes_that_would_overflow_are_refused():
    with pytest.raises(InputError, match="beyond 1e\\+50 rad/s; check their units"):
        TorsionModel.chain_of([1e-200, 1.0], [1e200])


def test_magnitudes_beyond_any_machine_are_refused():
    """A distributed shaft of a diameter in km (a unit mistake) has a fine omega^2 bound but
    inertias and stiffnesses near overflow in the solvers' products: refused in one line."""
    from crankdyn.torsion import ShaftGeometry

    with pytest.raises(InputError, match="beyond 1e\\+20; check their units"):
        TorsionModel(
            masses=(Mass("a", 1.0), Mass("b", 1.0)),
            shafts=(
                Shaft(("a", "b"), geometry=ShaftGeometry(1.2e4, 0.0, 7.0, 80e9), inertia=1e25),
            ),
        )


def test_chain_of_builds_the_masses_and_shafts_its_constructors_build():
    """chain_of's quick constructors (every field written at once, the numbers checked
    together) give the objects Mass and Shaft give, field for field."""
    import dataclasses

    from crankdyn.torsion.elements import Mass as M
    from crankdyn.torsion.elements import Shaft as S

    quick = TorsionModel.chain_of([1.0, 2.5, 0.25], [1e5, 3e6])
    plain = TorsionModel(
        masses=(M("1", 1.0), M("2", 2.5), M("3", 0.25)),
        shafts=(S(("1", "2"), 1e5), S(("2", "3"), 3e6)),
        name="chain",
    )
    pairs = [
        *zip(quick.masses, plain.masses, strict=True),
        *zip(quick.shafts, plain.shafts, strict=True),
    ]
    for mine, theirs in pairs:
        assert vars(mine) == vars(theirs)
        assert set(vars(mine)) == {f.name for f in dataclasses.fields(mine)}
        assert hash(mine) == hash(theirs)
