"""The beam model of an engine's crankshaft from its engine file, and the pin forces that excite
it (crankdyn.crankshaft.beam_engine)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import crankdyn
from crankdyn.crank.pressure_model import default_pressure
from crankdyn.crankshaft.beam_elements import BeamSection
from crankdyn.crankshaft.beam_engine import (
    disc_of_inertia,
    engine_beam_model,
    pin_force_harmonics,
    throw_dimensions,
)
from crankdyn.crankshaft.beam_inputs import BeamInputs
from crankdyn.crankshaft.beam_stiffness import throw_stiffness
from crankdyn.engine.forces import crank_train, engine_masses
from crankdyn.errors import InputError
from tests.crankshaft.test_beam_model import _rigid


@pytest.fixture(scope="module")
def marine():
    return crankdyn.Engine.example("marine-propulsion")


@pytest.fixture(scope="module")
def beam(marine):
    return engine_beam_model(marine)


def _with_beam(engine, **inputs):
    shaft = dataclasses.replace(engine.crankshaft, beam=BeamInputs(**inputs))
    return dataclasses.replace(engine, crankshaft=shaft)


def test_a_throw_from_the_m53_geometry(marine):
    g = marine.crankshaft.geometry
    t = throw_dimensions(marine)
    # L_1 = l_j / 2 + W / 2 and L_3 = l_j + 2 W + l_p (UR M53 Fig. 1)
    assert t.journal_length / 2 + t.web_thickness / 2 == pytest.approx(g.web_centre_distance)
    assert t.span == pytest.approx(marine.cylinders.pitch)
    assert (t.pin_diameter, t.journal_diameter, t.web_width) == (0.26, 0.3, 0.48)
    assert t.crank_radius == pytest.approx(0.2)
    thin = dataclasses.replace(g, web_centre_distance=0.05)  # 2 L_1 < W: no journal
    shaft = dataclasses.replace(marine.crankshaft, geometry=thin)
    with pytest.raises(InputError, match="no journal") as info:
        throw_dimensions(marine, shaft)
    assert info.value.key == "[crankshaft] web_centre_distance"


def test_disc_estimate_has_the_inertia_it_came_from():
    m, jd = disc_of_inertia(420.0, 7850.0)
    d = (4.0 * m / (0.2 * math.pi * 7850.0)) ** (1.0 / 3.0)  # m = pi rho (D / 5) D^2 / 4
    assert m * d * d / 8.0 == pytest.approx(420.0, rel=1e-12)  # solid disc J = m D^2 / 8
    assert jd == pytest.approx(m * (d * d / 16.0 + (0.2 * d) ** 2 / 12.0), rel=1e-12)
    assert disc_of_inertia(0.0, 7850.0) == (0.0, 0.0)


def test_the_rods_and_pistons_are_the_engines(marine, beam):
    """The engine's rods and pistons add m_CB + m_j / 2 per cylinder across the shaft and m_CB
    along it (crankdyn.crankshaft.beam_model), the crank's own unbalance not at all."""
    none = dataclasses.replace(marine, masses=dataclasses.replace(marine.masses, piston_group=0.0,
                                                                   rod=0.0))  # fmt: skip
    bare = engine_beam_model(none).model
    full = beam.model
    x_full, x_bare = _rigid(full, (1.0, 0.0, 0.0)), _rigid(bare, (1.0, 0.0, 0.0))
    z_full, z_bare = _rigid(full, (0.0, 0.0, 1.0)), _rigid(bare, (0.0, 0.0, 1.0))
    masses = engine_masses(marine)
    across = sum(m.rod_big_end + 0.5 * m.reciprocating for m in masses)
    along = sum(m.rod_big_end for m in masses)
    assert x_full @ full.mass @ x_full - x_bare @ bare.mass @ x_bare == pytest.approx(across)
    assert z_full @ full.mass @ z_full - z_bare @ bare.mass @ z_bare == pytest.approx(along)


def test_the_whole_torsional_line_is_attached(marine, beam):
    chain = marine.torsion.chain
    g = beam.model.geometry
    assert beam.whole_line
    assert g.free_end.polar_inertia == chain.inertia[0]  # "free end"
    assert g.flywheel.polar_inertia == chain.inertia[7]  # flywheel + coupling primary
    assert len(g.shaft_line) == chain.size - 8
    assert g.shaft_line[0] == (chain.inertia[8], chain.stiffness[7])
    assert g.damper.ring_inertia == 30.0 and g.damper.damping == 12e3
    assert g.bearings.thrust_journal == 7  # the last journal: next to the flywheel
    assert [round(a, 12) for a in g.pin_angles] == [
        round(a, 12) for a in marine.cylinders.throw_positions
    ]


def test_the_flywheel_stub_matches_the_lumped_shaft(marine, beam):
    """The stub G J / L in series with half a throw (2 k_t) is the lumped model's 120 MN m/rad."""
    g = beam.model.geometry
    kt = throw_stiffness(g.throw, g.material).torsional
    gj = g.material.shear_modulus * BeamSection.circular(0.3, 0.0, 0.3).torsion_constant
    series = 1.0 / (g.flywheel.distance / gj + 0.5 / kt)
    assert series == pytest.approx(120e6, rel=1e-9)
    assert g.free_end.distance == pytest.approx(g.throw.span)  # capped at one span (the note)
    assert any("one bearing span long" in n for n in beam.notes)


def test_given_inputs_replace_the_estimates(marine):
    engine = _with_beam(
        marine, bearing_radial_stiffness=2e9, thrust_axial_stiffness=1e9, thrust_journal=1,
        free_end_mass=100.0, flywheel_mass=1500.0, free_end_distance=0.1, flywheel_distance=0.2,
        counterweight_mass=50.0,
    )  # fmt: skip
    built = engine_beam_model(engine)
    g = built.model.geometry
    assert (g.bearings.radial_stiffness, g.bearings.axial_stiffness) == (2e9, 1e9)
    assert g.bearings.thrust_journal == 1
    assert (g.free_end.mass, g.flywheel.mass) == (100.0, 1500.0)
    assert (g.free_end.distance, g.flywheel.distance) == (0.1, 0.2)
    assert g.throw_masses[0].counterweight_mass == 50.0
    assert g.throw_masses[0].counterweight_radius == pytest.approx(0.2)  # the crank radius
    assert not any("estimated" in n or "rigid" in n for n in built.notes)


def test_without_a_torsional_model(marine):
    built = engine_beam_model(dataclasses.replace(marine, torsion=None))
    g = built.model.geometry
    assert not built.whole_line and g.free_end is None and g.flywheel is None
    assert any("no [torsion] model" in n for n in built.notes)


@pytest.mark.parametrize("scale", [1.0, 0.4])
def test_pin_forces_synthesise_the_crank_train(marine, scale):
    """Independent of the FFT: the harmonics summed at 60 angles equal the crank train's pin
    loads there (seed 000 section 2.2, evaluated directly), less their mean and the constant
    big-end centrifugal force; under a load scale s, the train of the trace scaled by s."""
    speed = 600 * math.pi / 30
    orders = np.arange(0.5, 600.0, 0.5)
    z, t = pin_force_harmonics(marine, [speed], orders, load_factor=[scale])
    theta = np.linspace(0.0, 4 * math.pi, 60, endpoint=False)
    trace = default_pressure(marine).scaled(scale)
    train = crank_train(marine, speed, theta, pressure=trace)
    t_pin, z_pin = train.pin_loads()
    basis = np.exp(1j * orders[:, None] * theta[None, :])
    for harmonics, direct in ((z[0], z_pin), (t[0], t_pin)):
        synthesised = np.real(harmonics.T @ basis)  # (throws, angles)
        fluctuation = direct - direct.mean(axis=1, keepdims=True)
        peak = np.max(np.abs(fluctuation))
        assert np.max(np.abs(synthesised - fluctuation)) < 2e-4 * peak
