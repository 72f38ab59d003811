"""The finer equivalent system of the crank throws (seed 003: each journal and web as two inertias
and a spring; crankdyn.torsion.equivalent.ThrowParts): the series stiffness of a span equals the
one-mass system's (Carter), the inertia is the same, the natural frequencies match a closed form
and converge to the one-mass system's as the parts' inertia vanishes; the engine-file keys."""

import math

import numpy as np
import pytest

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.masses import Masses
from crankdyn.engine.model import Cylinders
from crankdyn.errors import InputError
from crankdyn.torsion import Mass, Shaft
from crankdyn.torsion.equivalent import (
    CrankThrowGeometry,
    ThrowParts,
    ThrowSpec,
    carter_part_stiffnesses,
    carter_throw_stiffness,
    equivalent_system,
    journal_names,
    throw_inertias,
)
from crankdyn.torsion.modal import natural_modes

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
MASSES = Masses(reciprocating=2.521, rotating=3.2)
SIX = Cylinders(count=6, firing_order=(1, 5, 3, 6, 2, 4))
J_CRANK = 0.012


def _line(spec, cylinders=SIX):
    n = cylinders.throw_count
    return equivalent_system(
        GEOMETRY,
        cylinders,
        MASSES,
        spec,
        other_masses=(Mass("pulley", 0.05), Mass("flywheel", 1.5)),
        shafts=(
            Shaft(("pulley", "throw 1"), 8.0e5),
            Shaft((f"throw {n}", "flywheel"), 2.0e6),
        ),
    )


def test_carter_terms_add_up_to_the_span_by_hand():
    r, factor = 0.0685, 32.0 / (math.pi * 8.0e10)
    c_j = factor * (0.035 + 0.8 * 0.022) / (0.085**4 - 0.020**4)
    c_w = factor * (0.75 * r / (0.022 * 0.120**3) + 0.375 * 0.040 / 0.070**4)
    k_j, k_w = carter_part_stiffnesses(r, CARTER)
    assert (k_j, k_w) == pytest.approx((1 / c_j, 1 / c_w), rel=1e-14)
    assert 1 / (1 / k_j + 2 / k_w) == pytest.approx(carter_throw_stiffness(r, CARTER), rel=1e-14)


def test_the_finer_span_is_as_stiff_and_as_heavy_as_the_one_mass_span():
    parts = ThrowParts(journal_inertia=0.003, web_inertia=0.002)
    fine = _line(ThrowSpec(J_CRANK, geometry=CARTER, parts=parts))
    coarse = _line(ThrowSpec(J_CRANK, geometry=CARTER))
    assert sum(m.inertia for m in fine.masses) == pytest.approx(
        sum(m.inertia for m in coarse.masses), rel=1e-14
    )
    # the springs between throw 2 and throw 3 in series: the one-mass span's Carter stiffness
    front, rear = journal_names(3)
    chain = [("throw 2", front), (front, rear), (rear, "throw 3")]
    springs = {tuple(s.between): s.stiffness for s in fine.shafts}
    compliance = sum(1.0 / springs[c] for c in chain)
    assert 1.0 / compliance == pytest.approx(carter_throw_stiffness(0.0685, CARTER), rel=1e-13)
    # statically: a rigid rotation strains nothing; a unit twist across a span is carried whole
    k = fine.stiffness_matrix()
    assert np.allclose(k @ np.ones(k.shape[0]), 0.0, atol=1e-6)
    assert [m.name for m in fine.masses][:5] == ["pulley", "throw 1", *journal_names(2), "throw 2"]


def test_a_two_throw_crank_against_its_closed_form():
    """Throws a, journal halves b, b, throws a; springs k_w, k_j, k_w: a free symmetric chain.
    Symmetric modes leave k_j unstrained: omega^2 = k_w (1/a + 1/b) (and 0); antisymmetric modes
    have a node at the journal's middle (half of k_j is 2 k_j to it): the roots of
    a b w^4 - (a (k_w + 2 k_j) + b k_w) w^2 + 2 k_w k_j = 0."""
    two = Cylinders(count=2, firing_order=(1, 2), throw_angles=(0.0, math.pi))
    parts = ThrowParts(journal_inertia=0.004, web_inertia=0.002)
    spec = ThrowSpec(J_CRANK, geometry=CARTER, parts=parts)
    model = equivalent_system(GEOMETRY, two, MASSES, spec)
    k_j, k_w = carter_part_stiffnesses(GEOMETRY.crank_radius, CARTER)
    running = float(throw_inertias(GEOMETRY, two, MASSES, 0.0)[0])
    pin = J_CRANK - 0.004 - 2 * 0.002
    a = running + pin + 0.002 / 2 + (0.002 + 0.004 / 2)  # one refined web half, the end parts
    b = 0.002 / 2 + 0.004 / 2
    assert [m.inertia for m in model.masses] == pytest.approx([a, b, b, a], rel=1e-14)
    symmetric = k_w * (1 / a + 1 / b)
    disc = (a * (k_w + 2 * k_j) + b * k_w) ** 2 - 8 * a * b * k_w * k_j
    anti = [((a * (k_w + 2 * k_j) + b * k_w) + sgn * math.sqrt(disc)) / (2 * a * b)
            for sgn in (-1, 1)]  # fmt: skip
    expected = np.sqrt(sorted([0.0, symmetric, *anti]))
    got = natural_modes(model).natural_frequency
    assert np.asarray(got) == pytest.approx(expected, rel=1e-10, abs=1e-6)


def test_frequencies_converge_to_the_one_mass_system_as_the_parts_lighten():
    coarse = natural_modes(_line(ThrowSpec(J_CRANK, geometry=CARTER))).natural_frequency[1:4]
    errors = []
    for share in (1e-2, 1e-3, 1e-4):
        parts = ThrowParts(journal_inertia=share * J_CRANK, web_inertia=share * J_CRANK / 2)
        fine = natural_modes(_line(ThrowSpec(J_CRANK, geometry=CARTER, parts=parts)))
        errors.append(np.max(np.abs(fine.natural_frequency[1:4] / coarse - 1.0)))
    # the first elastic modes approach the one-mass system's linearly in the parts' share
    assert errors[0] < 1e-2
    assert errors[1] == pytest.approx(errors[0] / 10, rel=0.05)
    assert errors[2] == pytest.approx(errors[1] / 10, rel=0.05)


def test_given_part_stiffnesses_and_the_checks():
    parts = ThrowParts(0.003, 0.002, journal_stiffness=3e6, web_stiffness=4e6)
    spec = ThrowSpec(J_CRANK, parts=parts)
    assert spec.span_stiffness(0.0685) == pytest.approx(1 / (1 / 3e6 + 2 / 4e6))
    with pytest.raises(InputError, match="outweigh"):
        ThrowSpec(0.005, geometry=CARTER, parts=ThrowParts(0.003, 0.002))
    with pytest.raises(InputError, match="not the span's"):
        ThrowSpec(J_CRANK, stiffness=1e6, parts=parts)
    with pytest.raises(InputError, match="or neither"):
        ThrowParts(0.003, 0.002, journal_stiffness=3e6)
    with pytest.raises(InputError, match="not both or neither"):
        ThrowSpec(J_CRANK, geometry=CARTER, parts=parts)


def test_engine_file_keys(tmp_path):
    from crankdyn.engine.model import Engine

    text = """
name = "parts"
[geometry]
bore = "105 mm"
stroke = "137 mm"
rod_length = "207 mm"
[cylinders]
count = 6
firing_order = [1, 5, 3, 6, 2, 4]
[masses]
reciprocating = "2.521 kg"
rotating = "3.2 kg"
[torsion.throws]
inertia = "0.012 kg*m^2"
model = "parts"
journal_inertia = "0.003 kg*m^2"
web_inertia = "0.002 kg*m^2"
journal_stiffness = "3 MN*m/rad"
web_stiffness = "4 MN*m/rad"
loss_factor = 0.03
[[torsion.mass]]
name = "flywheel"
inertia = "1.5 kg*m^2"
[[torsion.shaft]]
between = ["throw 6", "flywheel"]
stiffness = "2 MN*m/rad"
"""
    path = tmp_path / "e.toml"
    path.write_text(text, encoding="utf-8")
    model = Engine.from_file(path).torsion
    assert len(model.masses) == 6 + 2 * 5 + 1
    journals = [s for s in model.shafts if s.role == "crankshaft"]
    assert len(journals) == 5 and all(s.stiffness == 3e6 for s in journals)
    assert all(s.loss_factor == 0.03 for s in model.shafts if s.between[1] != "flywheel")
    path.write_text(text.replace('model = "parts"\n', ""), encoding="utf-8")
    with pytest.raises(InputError, match='applies with model = "parts"'):
        Engine.from_file(path)
    path.write_text(text.replace('journal_stiffness = "3 MN*m/rad"', 'stiffness = "1 MN*m/rad"'))
    with pytest.raises(InputError, match="stiffness"):
        Engine.from_file(path)
