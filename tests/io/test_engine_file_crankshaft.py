"""The engine file's [crankshaft] section (docs/engine-file.md): every key, its units and
defaults, and one-line errors naming file, section, key and value."""

from __future__ import annotations

import math

import pytest

from crankdyn.errors import InputError
from crankdyn.io.engine_file import load_engine

BASE = """
name = "crankshaft engine"
[geometry]
bore = "320 mm"
stroke = "400 mm"
rod_length = "900 mm"
[cylinders]
count = 2
firing_order = [1, 2]
throw_angles = ["0 deg", "180 deg"]
pitch = "530 mm"
[masses]
reciprocating = "150 kg"
rotating = "120 kg"
[operating]
speed = "750 rpm"
[crankshaft]
pin_diameter = "260 mm"
pin_fillet_radius = "13 mm"
journal_diameter = "300 mm"
journal_fillet_radius = "15 mm"
web_thickness = "115 mm"
web_width = "480 mm"
web_centre_distance = "135 mm"
tensile_strength = "850 MPa"
"""

FULL = """
engine_type = "crosshead"
construction = "semi-built"
pin_bore = "60 mm"
journal_bore = "50 mm"
overlap = "80 mm"
pin_recess = "2 mm"
journal_recess = "1 mm"
oil_bore_diameter = "20 mm"
oil_bore_angle = "30 deg"
bearing_span = "530 mm"
yield_strength = "650 MPa"
manufacture = "continuous-grain-flow"
surface_treatment = "nitrided"
surface_factor = 1.1
youngs_modulus = "210 GPa"
axial_vibration_stress = "15 MPa"
[crankshaft.shrink_fit]
diameter = "420 mm"
length = "200 mm"
web_outer_diameter = "700 mm"
oversize = "0.55 mm"
friction = 0.18
slip_safety = 2.5
pin_yield_strength = "600 MPa"
web_yield_strength = "500 MPa"
[crankshaft.factors]
alpha_b = 2.4
beta_q = 3.9
source = "FE report 17"
"""


def test_minimal_section_and_defaults(write):
    shaft = load_engine(write("e.toml", BASE)).crankshaft
    g, m = shaft.geometry, shaft.material
    assert (g.pin_diameter, g.journal_diameter, g.web_thickness) == (0.26, 0.3, 0.115)
    assert g.web_centre_distance == pytest.approx(0.135)
    assert (g.pin_bore, g.journal_bore, g.pin_recess, g.journal_recess) == (0, 0, 0, 0)
    assert g.overlap is None and g.bearing_span is None and g.oil_bore_diameter is None
    assert g.oil_bore_angle == 0.0
    assert m.tensile_strength == 850e6 and m.yield_strength is None
    assert (m.manufacture, m.surface_treatment, m.surface_factor) == ("free-form", "none", 1.0)
    assert m.youngs_modulus == 2.05e11  # Annex 5-3 Appendix III 2(2)
    assert (shaft.engine_type, shaft.construction) == ("trunk-piston", "solid")
    assert shaft.shrink_fit is None and shaft.factors is None
    assert shaft.axial_vibration_stress is None


def test_every_key(write):
    text = BASE.replace("[geometry]", 'cycle = "two-stroke"\n[geometry]')
    shaft = load_engine(write("e.toml", text + FULL)).crankshaft
    g, m, fit, f = shaft.geometry, shaft.material, shaft.shrink_fit, shaft.factors
    assert (g.pin_bore, g.journal_bore, g.overlap) == pytest.approx((0.06, 0.05, 0.08))
    assert (g.pin_recess, g.journal_recess) == pytest.approx((0.002, 0.001))
    assert g.oil_bore_diameter == pytest.approx(0.02)
    assert g.oil_bore_angle == pytest.approx(math.radians(30))
    assert g.bearing_span == pytest.approx(0.53)
    assert (m.yield_strength, m.manufacture, m.factor_k) == (650e6, "continuous-grain-flow", 1.05)
    assert (m.surface_treatment, m.surface_factor, m.youngs_modulus) == ("nitrided", 1.1, 210e9)
    assert (shaft.engine_type, shaft.construction) == ("crosshead", "semi-built")
    assert shaft.axial_vibration_stress == 15e6
    assert (fit.diameter, fit.length, fit.web_outer_diameter) == pytest.approx((0.42, 0.2, 0.7))
    assert fit.oversize == pytest.approx(0.55e-3)
    assert (fit.friction, fit.slip_safety) == (0.18, 2.5)
    assert (fit.pin_yield_strength, fit.web_yield_strength) == (600e6, 500e6)
    assert (f.alpha_b, f.beta_q, f.alpha_t, f.source) == (2.4, 3.9, None, "FE report 17")


def _err(write, text):
    with pytest.raises(InputError) as info:
        load_engine(write("bad.toml", text))
    message = str(info.value)
    assert "\n" not in message and "bad.toml: " in message
    return message


@pytest.mark.parametrize(
    ("old", "new", "expected"),
    [
        ('pin_diameter = "260 mm"', 'pin_diameter = "260 kg"', "[crankshaft] pin_diameter"),
        ('pin_diameter = "260 mm"', 'pin_diameter = "-260 mm"', "must be positive"),
        ('pin_diameter = "260 mm"\n', "", "[crankshaft] pin_diameter: missing"),
        ('web_width = "480 mm"', 'web_widht = "480 mm"', 'did you mean "web_width"'),
        ('tensile_strength = "850 MPa"', 'tensile_strength = "850 mm"', "expected a pressure"),
        (
            'web_centre_distance = "135 mm"',
            'web_centre_distance = "300 mm"',
            '[crankshaft] web_centre_distance = "300 mm": the web centre must lie within half',
        ),
        (
            'tensile_strength = "850 MPa"',
            'tensile_strength = "850 MPa"\nmanufacture = "forged"',
            "[crankshaft] manufacture",
        ),
        (
            'tensile_strength = "850 MPa"',
            'tensile_strength = "850 MPa"\npin_bore = "300 mm"',
            '[crankshaft] pin_bore = "300 mm": the bore must be smaller',
        ),
        (
            'tensile_strength = "850 MPa"',
            'tensile_strength = "850 MPa"\nsurface_factor = 1.2',
            "needs the surface treatment",
        ),
        (
            'tensile_strength = "850 MPa"',
            'tensile_strength = "850 MPa"\nconstruction = "semi-built"',
            "[crankshaft] shrink_fit: a semi-built crankshaft needs its shrink fit",
        ),
        (
            'tensile_strength = "850 MPa"',
            'tensile_strength = "850 MPa"\naxial_vibration_stress = "10 MPa"',
            "crosshead",
        ),
        (
            'tensile_strength = "850 MPa"',
            'tensile_strength = "850 MPa"\n[crankshaft.factors]\nsource = "x"',
            "[crankshaft.factors]: give at least one of alpha_b",
        ),
        (
            'tensile_strength = "850 MPa"',
            'tensile_strength = "850 MPa"\n[crankshaft.factors]\nalpha_b = 0.5',
            "[crankshaft.factors] alpha_b = 0.5: a stress concentration factor is at least 1",
        ),
    ],
)
def test_bad_input_one_line(write, old, new, expected):
    assert old in BASE
    assert expected in _err(write, BASE.replace(old, new, 1))


def test_shrink_fit_errors(write):
    semi = BASE.replace(
        'tensile_strength = "850 MPa"',
        'tensile_strength = "850 MPa"\nyield_strength = "650 MPa"\nconstruction = "semi-built"',
    )
    fit = '[crankshaft.shrink_fit]\ndiameter = "420 mm"\nlength = "200 mm"\n'
    message = _err(write, semi + fit + 'web_outer_diameter = "400 mm"\n')
    assert "[crankshaft.shrink_fit] web_outer_diameter" in message
    message = _err(write, semi + fit)
    assert "[crankshaft.shrink_fit] web_outer_diameter: missing" in message
    assert load_engine(write("ok.toml", semi + fit + 'web_outer_diameter = "700 mm"\n'))
