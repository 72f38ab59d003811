"""The equivalent system of an engine's crank throws; Carter's formula; closed forms."""

import math

import numpy as np
import pytest

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.masses import Masses, equivalent_masses
from crankdyn.engine.model import Cylinders, Engine
from crankdyn.errors import InputError
from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.closed_form import single_mass, three_mass, two_mass, uniform_chain
from crankdyn.torsion.elements import shaft_stiffness
from crankdyn.torsion.equivalent import (
    CrankThrowGeometry,
    ThrowSpec,
    carter_throw_stiffness,
    equivalent_system,
    throw_inertias,
)

GEOMETRY = CrankGeometry(bore=0.105, crank_radius=0.0685, rod_length=0.207)
CARTER = CrankThrowGeometry(
    journal_diameter=0.085,
    journal_length=0.035,
    pin_diameter=0.070,
    pin_length=0.040,
    web_thickness=0.022,
    web_width=0.120,
    shear_modulus=8.0e10,
    journal_bore=0.020,
)


def test_throw_inertia_of_an_inline_engine():
    masses = Masses(reciprocating=2.521, rotating=3.2)
    cylinders = Cylinders(count=6, firing_order=(1, 5, 3, 6, 2, 4))
    j = throw_inertias(GEOMETRY, cylinders, masses, crank_inertia=0.012)
    expected = (3.2 + 2.521 / 2) * 0.0685**2 + 0.012
    assert j.tolist() == pytest.approx([expected] * 6, rel=1e-15)


def test_v_engine_throw_counts_the_crank_unbalance_once():
    engine = Engine.example("v8-crossplane")  # two cylinders per throw, masses by components
    masses, geometry = engine.masses, engine.geometry
    m_j, m_r = equivalent_masses(masses, geometry.rod_length)
    m_cb = m_r - masses.crank_unbalance
    j = throw_inertias(geometry, engine.cylinders, masses, crank_inertia=0.0)
    expected = geometry.crank_radius**2 * (masses.crank_unbalance + 2 * m_cb + 2 * m_j / 2)
    assert j.tolist() == pytest.approx([expected] * 4, rel=1e-14)


def test_carter_formula_by_hand():
    g, r = CARTER, 0.0685
    compliance = (
        (0.035 + 0.8 * 0.022) / (0.085**4 - 0.020**4)
        + 0.75 * 0.040 / 0.070**4
        + 1.5 * r / (0.022 * 0.120**3)
    )
    assert carter_throw_stiffness(r, g) == pytest.approx(math.pi * 8e10 / 32 / compliance)


def test_carter_formula_reduces_to_a_plain_shaft_without_webs():
    """With the pin the journal's size and an (almost) rigid web, Carter's span is a plain
    shaft of length l_j + 0.8 h + 0.75 l_p."""
    g = CrankThrowGeometry(
        journal_diameter=0.08,
        journal_length=0.03,
        pin_diameter=0.08,
        pin_length=0.04,
        web_thickness=0.02,
        web_width=1.0e3,
        shear_modulus=8e10,
    )
    plain = shaft_stiffness(0.03 + 0.8 * 0.02 + 0.75 * 0.04, 0.08, 0.0, 8e10)
    assert carter_throw_stiffness(0.05, g) == pytest.approx(plain, rel=1e-9)


def test_equivalent_system_layout():
    masses = Masses(reciprocating=2.521, rotating=3.2)
    cylinders = Cylinders(count=4, firing_order=(1, 3, 4, 2))
    spec = ThrowSpec(crank_inertia=0.01, geometry=CARTER, damping=2.0, loss_factor=0.03)
    others = (Mass("damper", 0.05), Mass("pulley", 0.02), Mass("flywheel", 1.5))
    shafts = (
        Shaft(("damper", "pulley"), 1e5, damping=50.0),
        Shaft(("pulley", "throw 1"), 2e6),
        Shaft(("throw 4", "flywheel"), 2.5e6),
    )
    model = equivalent_system(
        GEOMETRY, cylinders, masses, spec, other_masses=others, shafts=shafts, name="i4"
    )
    assert model.mass_names == (
        "damper",
        "pulley",
        "throw 1",
        "throw 2",
        "throw 3",
        "throw 4",
        "flywheel",
    )
    assert model.is_chain and model.is_free
    assert [m.cylinders for m in model.masses[2:6]] == [(1,), (2,), (3,), (4,)]
    k = carter_throw_stiffness(GEOMETRY.crank_radius, CARTER)
    assert model.chain.stiffness.tolist() == pytest.approx([1e5, 2e6, k, k, k, 2.5e6])
    assert model.masses[3].damping == 2.0
    spans = [s for s in model.shafts if s.between[0].startswith("throw")][:3]
    assert all(s.loss_factor == 0.03 for s in spans)
    assert spans[0].geometry.outer_diameter == 0.085


def test_throws_first_when_no_mass_precedes_them():
    masses = Masses(reciprocating=1.0, rotating=1.0)
    cylinders = Cylinders(count=2, firing_order=(1, 2), cycle="two-stroke")
    model = equivalent_system(
        GEOMETRY,
        cylinders,
        masses,
        ThrowSpec(crank_inertia=0.0, stiffness=1e6),
        other_masses=(Mass("flywheel", 1.0),),
        shafts=(Shaft(("throw 2", "flywheel"), 1e6),),
    )
    assert model.mass_names == ("throw 1", "throw 2", "flywheel")


def test_throw_spec_needs_exactly_one_stiffness():
    with pytest.raises(InputError, match="not both or neither"):
        ThrowSpec(crank_inertia=0.0)
    with pytest.raises(InputError, match="not both or neither"):
        ThrowSpec(crank_inertia=0.0, stiffness=1e6, geometry=CARTER)


def test_engine_checks_the_model_cylinders():
    geometry = GEOMETRY
    model = TorsionModel(
        masses=(Mass("a", 1.0, cylinders=(1,)), Mass("b", 1.0, cylinders=(3,))),
        shafts=(Shaft(("a", "b"), 1.0),),
    )
    with pytest.raises(InputError, match="engine has 2 cylinders"):
        Engine(
            name="e",
            geometry=geometry,
            cylinders=Cylinders(count=2, firing_order=(1, 2), cycle="two-stroke"),
            torsion=model,
        )


# ---- closed forms --------------------------------------------------------------------------
def test_closed_forms_against_the_frequency_equations():
    assert single_mass(2.0, 8.0) == 2.0
    omega, ratio, node = two_mass(1.0, 3.0, 12.0)
    assert omega == pytest.approx(4.0)
    assert ratio == pytest.approx(-1 / 3)
    assert node == pytest.approx(0.75)
    j, k = (1.0, 2.0, 3.0), (4.0, 5.0)
    w, shapes = three_mass(*j, *k)
    # both roots satisfy det(K - w^2 M) = 0, and the shapes the equations of motion
    kk = np.array([[4.0, -4.0, 0.0], [-4.0, 9.0, -5.0], [0.0, -5.0, 5.0]])
    for omega, phi in zip(w, shapes, strict=True):
        assert np.linalg.det(kk - omega**2 * np.diag(j)) == pytest.approx(0.0, abs=1e-10)
        assert np.allclose(kk @ phi, omega**2 * np.array(j) * phi)


def test_uniform_chain_formula_needs_known_ends():
    with pytest.raises(ValueError, match="ends"):
        uniform_chain(3, 1.0, 1.0, "pinned")
