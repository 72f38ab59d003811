"""Equivalent masses: two- and three-mass rod models (seed 000 section 2.1)."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.kinematics import slider_crank_exact
from crankdyn.crank.masses import Masses, equivalent_mass_model, rod_three_mass, rod_two_mass
from crankdyn.errors import InputError
from crankdyn.io.engine_file import parse_engine


def test_two_mass_keeps_mass_and_centre_of_gravity():
    m_c, length, lb = 0.62, 0.1365, 0.035
    small, big = rod_two_mass(m_c, length, lb)
    assert small + big == pytest.approx(m_c, rel=1e-15)
    assert small * (length - lb) == pytest.approx(big * lb, rel=1e-14)  # moments about the CG


def test_three_mass_keeps_mass_centre_and_inertia():
    m_c, length, lb, inertia = 0.62, 0.1365, 0.035, 2.1e-3
    la = length - lb
    a, b, g = rod_three_mass(m_c, length, lb, inertia)
    assert a + b + g == pytest.approx(m_c, rel=1e-14)
    assert a * la == pytest.approx(b * lb, rel=1e-14)
    assert a * la**2 + b * lb**2 == pytest.approx(inertia, rel=1e-14)


def test_inertia_error_is_seed000_formula():
    """dI = m_CA l_A^2 + m_CB l_B^2 - I_C (seed 000) equals m_C l_A l_B - I_C."""
    masses = Masses(piston_group=0.45, rod=0.62, rod_cg_from_big_end=0.035, rod_inertia=2.1e-3)
    length = 0.1365
    eq = equivalent_mass_model(masses, length)
    la, lb = length - 0.035, 0.035
    assert eq.inertia_error == pytest.approx(
        eq.rod_small_end * la**2 + eq.rod_big_end * lb**2 - 2.1e-3, rel=1e-12
    )
    assert eq.reciprocating == pytest.approx(0.45 + 0.62 * lb / length)


def test_v_engine_shares_crank_unbalance():
    masses = Masses(piston_group=0.7, rod=0.6, rod_cg_from_big_end=0.04, crank_unbalance=0.5)
    one = equivalent_mass_model(masses, 0.145, rods_per_throw=1)
    two = equivalent_mass_model(masses, 0.145, rods_per_throw=2)
    big = 0.6 * (0.145 - 0.04) / 0.145
    assert one.rotating == pytest.approx(0.5 + big)
    assert 2 * two.rotating == pytest.approx(0.5 + 2 * big)  # the throw's rotating mass


def test_given_equivalent_masses_take_precedence():
    eq = equivalent_mass_model(Masses(reciprocating=2.521, rotating=3.2), 0.207)
    assert (eq.reciprocating, eq.rotating) == (2.521, 3.2)
    assert not eq.pin_mass_known
    assert eq.source == "given reciprocating and rotating"


@settings(max_examples=40, deadline=None)
@given(
    st.floats(0.05, 0.5),  # L
    st.floats(0.1, 0.9),  # l_B / L
    st.floats(0.1, 3.0),  # m_C
    st.floats(0.05, 1.0),  # I_C / (m_C l_A l_B)
    st.floats(0.1, 3.0),  # phi
)
def test_rod_kinetic_energy_two_vs_three_mass(length, frac, m_c, ratio, phi):
    """Koenig: a rod on its pins has T = m_C v_G^2/2 + I_C w_L^2/2. The three-mass model gives
    exactly that; the two-mass model exceeds it by (m_C l_A l_B - I_C) w_L^2 / 2."""
    r = 0.3 * length
    lb = frac * length
    la = length - lb
    inertia = ratio * m_c * la * lb
    w = 100.0
    m = slider_crank_exact(np.array([phi]), r, length, 0.0, w)
    v_a = m.velocity[0]  # small end moves along the axis
    v_b = np.array([r * w * math.cos(phi), -r * w * math.sin(phi)])  # crank pin (lateral, axial)
    v_a_vec = np.array([0.0, -v_a])
    v_g = (la * v_b + lb * v_a_vec) / length
    true = 0.5 * m_c * v_g @ v_g + 0.5 * inertia * m.rod_angular_velocity[0] ** 2
    a, b, g = rod_three_mass(m_c, length, lb, inertia)
    three = 0.5 * (a * v_a**2 + b * v_b @ v_b + g * v_g @ v_g)
    small, big = rod_two_mass(m_c, length, lb)
    two = 0.5 * (small * v_a**2 + big * v_b @ v_b)
    assert three == pytest.approx(true, rel=1e-10)
    expected = 0.5 * (m_c * la * lb - inertia) * m.rod_angular_velocity[0] ** 2
    assert two - true == pytest.approx(expected, rel=1e-8, abs=1e-9 * true)


def _engine(masses: dict):
    doc = {
        "name": "t",
        "geometry": {"bore": "80 mm", "stroke": "80 mm", "rod_length": "140 mm"},
        "masses": masses,
    }
    return parse_engine(doc, file="e.toml")


@pytest.mark.parametrize(
    ("masses", "message"),
    [
        (
            {"piston_group": "0.4 kg", "rod": "0.5 kg", "rod_cg_from_big_end": "150 mm"},
            'e.toml: [masses] rod_cg_from_big_end = "150 mm": the rod\'s centre of gravity',
        ),
        (
            {"piston_group": "-0.4 kg", "rod": "0.5 kg", "rod_cg_from_big_end": "40 mm"},
            'e.toml: [masses] piston_group = "-0.4 kg": must not be negative',
        ),
        (
            {
                "piston_group": "0.4 kg",
                "rod": "0.5 kg",
                "rod_cg_from_big_end": "40 mm",
                "rod_inertia": "0.01 kg*m^2",
            },
            'e.toml: [masses] rod_inertia = "0.01 kg*m^2": the rod\'s moment of inertia exceeds',
        ),
        (
            {"piston_group": "0.4 kg", "rod": "0.5 kg"},
            "e.toml: [masses] rod_cg_from_big_end: the rod's centre of gravity is needed",
        ),
        (
            {"piston_group": "0.4 kg", "rod": "0.5 kg", "rod_cg_from_big_end": "0 mm"},
            'e.toml: [masses] rod_cg_from_big_end = "0 mm": must be positive',
        ),
    ],
)
def test_impossible_masses_are_one_line_errors(masses, message):
    with pytest.raises(InputError) as info:
        _engine(masses)
    text = str(info.value)
    assert "\n" not in text
    assert text.startswith(message)


def test_geometry_check_happens_for_direct_construction():
    with pytest.raises(InputError, match="centre of gravity"):
        equivalent_mass_model(
            Masses(piston_group=0.3, rod=0.3, rod_cg_from_big_end=0.2),
            CrankGeometry(0.08, 0.04, 0.15).rod_length,
        )


def test_crank_unbalance_from_its_parts_seed000():
    """Seed 000 section 2.1: m_k = m_z + 2 m_w rho / R. By hand for R = 40 mm (stroke 80 mm):
    m_z = 0.30 kg, m_w = 0.25 kg at rho = 30 mm: 0.30 + 2 x 0.25 x 30/40 = 0.675 kg."""
    engine = _engine(
        {
            "piston_group": "0.4 kg",
            "rod": "0.5 kg",
            "rod_cg_from_big_end": "40 mm",
            "crank_pin": "0.30 kg",
            "crank_web": "0.25 kg",
            "crank_web_radius": "30 mm",
        }
    )
    assert engine.masses.crank_unbalance == pytest.approx(0.675, rel=1e-15)
    eq = equivalent_mass_model(engine.masses, engine.geometry.rod_length)
    assert eq.crank == pytest.approx(0.675, rel=1e-15)
    assert eq.rotating == pytest.approx(0.675 + 0.5 * 100 / 140, rel=1e-14)  # m_k + m_CB


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        ({"crank_pin": "0.3 kg"}, "also needs crank_web, crank_web_radius"),
        (
            {
                "crank_pin": "0.3 kg",
                "crank_web": "0.2 kg",
                "crank_web_radius": "30 mm",
                "crank_unbalance": "0.5 kg",
            },
            "give crank_unbalance or its parts",
        ),
        ({"rod_split": "halves"}, "rod_split"),
    ],
)
def test_crank_parts_and_rod_split_errors_are_one_line(extra, message):
    with pytest.raises(InputError) as info:
        _engine(
            {"piston_group": "0.4 kg", "rod": "0.5 kg", "rod_cg_from_big_end": "40 mm", **extra}
        )
    text = str(info.value)
    assert "\n" not in text and text.startswith("e.toml: [masses]") and message in text


def test_rod_thirds_rule_seed002():
    """Seed 002 eq. 15: P_j = m_j j with m_j = m_piston + m_rod/3 (the rest of the rod rotates).
    By hand: m_p = 0.4 kg, m_rod = 0.6 kg: m_j = 0.6 kg, m_r = m_k + 0.4 kg; no centre of gravity
    is needed for this split."""
    engine = _engine({"piston_group": "0.4 kg", "rod": "0.6 kg", "rod_split": "thirds",
                      "crank_unbalance": "0.1 kg"})  # fmt: skip
    eq = equivalent_mass_model(engine.masses, engine.geometry.rod_length)
    assert eq.reciprocating == pytest.approx(0.6, rel=1e-15)
    assert eq.rotating == pytest.approx(0.5, rel=1e-15)
    assert "m_rod/3" in eq.source
    assert eq.three_mass_centre is None  # the 3-mass model is a centre-of-gravity model
