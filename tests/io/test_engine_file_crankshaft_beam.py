"""The engine file's [crankshaft.beam] table and [crankshaft] additional_stress
(docs/engine-file.md): every key with its unit and default, and one-line errors."""

from __future__ import annotations

import pytest

from crankdyn.crankshaft.beam_inputs import BeamInputs
from crankdyn.errors import InputError
from crankdyn.io.engine_file import load_engine
from tests.io.test_engine_file_crankshaft import BASE

BEAM = """
[crankshaft.beam]
poisson_ratio = 0.29
density = "7.8 g/cm^3"
bearing_radial_stiffness = "2 GN/m"
bearing_tilting_stiffness = "5 MN*m/rad"
thrust_axial_stiffness = "1.5 GN/m"
thrust_journal = 1
counterweight_mass = "120 kg"
counterweight_radius = "180 mm"
free_end_mass = "300 kg"
flywheel_mass = "2 t"
free_end_distance = "250 mm"
flywheel_distance = "150 mm"
axial_damping = "2 MN*s/m"
elements = 3
theory = "euler-bernoulli"
web_rigid_fraction = 0.2
modes = 30
damping_ratio = 0.03
"""


def test_no_table_means_the_defaults_and_the_rule(write):
    shaft = load_engine(write("e.toml", BASE)).crankshaft
    assert shaft.beam is None and shaft.beam_inputs == BeamInputs()
    assert shaft.additional_stress_source == "rule"
    b = shaft.beam_inputs
    assert (b.poisson_ratio, b.density, b.elements, b.modes) == (0.3, 7850.0, 2, 24)
    assert b.bearing_radial_stiffness is None and b.thrust_axial_stiffness is None


def test_every_key_with_its_unit(write):
    shaft = load_engine(write("e.toml", BASE + BEAM)).crankshaft
    b = shaft.beam
    assert b.poisson_ratio == 0.29 and b.density == pytest.approx(7800.0)
    assert (b.bearing_radial_stiffness, b.bearing_tilting_stiffness) == pytest.approx((2e9, 5e6))
    assert (b.thrust_axial_stiffness, b.thrust_journal) == (pytest.approx(1.5e9), 1)
    assert (b.counterweight_mass, b.counterweight_radius) == pytest.approx((120.0, 0.18))
    assert (b.free_end_mass, b.flywheel_mass) == pytest.approx((300.0, 2000.0))
    assert (b.free_end_distance, b.flywheel_distance) == pytest.approx((0.25, 0.15))
    assert b.axial_damping == pytest.approx(2e6)
    assert (b.elements, b.theory, b.web_rigid_fraction) == (3, "euler-bernoulli", 0.2)
    assert (b.modes, b.damping_ratio) == (30, 0.03)
    assert b.defaulted() == ()
    # the table given: the additional stress comes from the beam model unless said otherwise
    assert shaft.additional_stress_source == "beam"
    text = BASE.replace('tensile_strength = "850 MPa"', 'tensile_strength = "850 MPa"\n'
                        'additional_stress = "rule"') + BEAM  # fmt: skip
    assert load_engine(write("r.toml", text)).crankshaft.additional_stress_source == "rule"


@pytest.mark.parametrize(
    ("old", "new", "expected"),
    [
        ("elements = 3", "elements = 0", "[crankshaft.beam] elements"),
        ("elements = 3", "elements = 2.5", "[crankshaft.beam] elements"),
        ('theory = "euler-bernoulli"', 'theory = "bernoulli"', "[crankshaft.beam] theory"),
        ("poisson_ratio = 0.29", "poisson_ratio = 0.5", "[crankshaft.beam] poisson_ratio"),
        ('density = "7.8 g/cm^3"', 'density = "7.8 kg"', "[crankshaft.beam] density"),
        ("thrust_journal = 1", "thrust_journal = 0", "[crankshaft.beam] thrust_journal"),
        ('flywheel_mass = "2 t"', 'flywhel_mass = "2 t"', 'did you mean "flywheel_mass"'),
        (
            'bearing_radial_stiffness = "2 GN/m"',
            'bearing_radial_stiffness = "-2 GN/m"',
            "[crankshaft.beam] bearing_radial_stiffness",
        ),
    ],
)
def test_errors_name_the_key(write, old, new, expected):
    assert old in BEAM
    with pytest.raises(InputError) as info:
        load_engine(write("bad.toml", BASE + BEAM.replace(old, new)))
    message = str(info.value)
    assert "\n" not in message and "bad.toml: " in message and expected in message


def test_the_rule_or_the_beam_not_both(write):
    text = BASE.replace(
        'tensile_strength = "850 MPa"',
        'tensile_strength = "850 MPa"\nengine_type = "crosshead"\n'
        'axial_vibration_stress = "12 MPa"\nadditional_stress = "beam"',
    )
    with pytest.raises(InputError) as info:
        load_engine(write("bad.toml", text))
    assert "[crankshaft] axial_vibration_stress" in str(info.value)
    bad = BASE.replace('tensile_strength = "850 MPa"', 'tensile_strength = "850 MPa"\n'
                       'additional_stress = "fe"')  # fmt: skip
    with pytest.raises(InputError) as info:
        load_engine(write("bad.toml", bad))
    assert "[crankshaft] additional_stress" in str(info.value)


THROWS = '[torsion]\n[torsion.throws]\ninertia = "9.5 kg*m^2"\nstiffness = "beam"\n'


def test_the_lumped_models_span_stiffness_from_the_beam(write):
    # [torsion.throws] stiffness = "beam": the crank span of the lumped model is the beam
    # model's throw (the stiffness crankdyn crankshaft modes reports), with [crankshaft.beam]'s
    # mesh and web stiffening; the stiffness itself is validated in tests/validation
    # (test_beam_throw_stiffness.py: Carter, Ker Wilson; Castigliano's frame)
    from crankdyn.crankshaft.beam_elements import BeamMaterial
    from crankdyn.crankshaft.beam_engine import throw_dimensions
    from crankdyn.crankshaft.beam_stiffness import throw_stiffness

    engine = load_engine(write("e.toml", BASE + THROWS))
    (shaft,) = engine.torsion.shafts
    expected = throw_stiffness(
        throw_dimensions(engine), BeamMaterial(205e9, 0.3, 7850.0), elements=2
    ).torsional
    assert shaft.between == ("throw 1", "throw 2")
    assert shaft.stiffness == pytest.approx(expected, rel=1e-12)
    stiff = load_engine(
        write("s.toml", BASE + THROWS + "[crankshaft.beam]\nweb_rigid_fraction = 0.5\n")
    )
    assert stiff.torsion.shafts[0].stiffness > 1.05 * shaft.stiffness


def test_beam_span_stiffness_needs_the_crankshaft(write):
    text = BASE.split("[crankshaft]")[0] + THROWS
    with pytest.raises(InputError) as info:
        load_engine(write("bad.toml", text))
    message = str(info.value)
    assert "\n" not in message and "[torsion.throws] stiffness" in message
    assert "[crankshaft]" in message
    with pytest.raises(InputError) as info:
        load_engine(write("bad.toml", BASE + THROWS.replace('"beam"', '"bean"')))
    assert "[torsion.throws] stiffness" in str(info.value)
