"""Consistency of the crankshaft beam model with crankdyn's lumped torsional chain: with the
crank throws made rigid, the beam model's torsional modes approach those of the chain built from
it (crankdyn.crankshaft.beam_stiffness.lumped_torsional_chain, solved by crankdyn's
TorsionModel.chain_of and natural_modes, an independent solver).

The chain is exact in the limit where (a) the inertia sits in the throws (the rods' and the
counterweights' masses; the shaft's own inertia negligible: density 1/1000 of steel's), (b) the
bearings hold the journal centres (radial and axial stiffness 1e13 N/m), (c) each throw is
balanced (counterweights with the rods' m r), so that its torsional inertia forces have no
resultant across the shaft, and (d) the webs and the pins do not deform, so that the shaft twists
only in its journals, on the axis. The webs' and pins' E and G are scaled by 100 and 1e4: the
difference chain / beam - 1 of the five lowest torsional modes falls with the scale, to below
2e-4 at 1e4 (1.5e-6 for the first mode).

What stiffening only the webs does (stated, and checked to hold): the chain's torsional
frequencies then lie 8-33 % below the beam model's (webs scaled by 1e4). A pin offset by R
from the axis must bend as well as twist when the webs on either side of it turn relative to
each other (its ends move apart by R times the angle), and with the journals held by their
bearings that bending stiffens the throw; the chain's throw stiffness is that of one throw free
to tilt in its two bearings (crankdyn.crankshaft.beam_stiffness.throw_stiffness), which lets the
pin twist alone. With flexible webs and pins the two effects nearly cancel on this crankshaft
(1-2 %).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.crankshaft.beam_elements import BeamMaterial
from crankdyn.crankshaft.beam_model import (
    CrankshaftBeamGeometry,
    EndMass,
    MainBearings,
    ThrowDimensions,
    ThrowMasses,
    build_beam_model,
)
from crankdyn.crankshaft.beam_modes import beam_modes
from crankdyn.crankshaft.beam_stiffness import lumped_chain_comparison, lumped_torsional_chain

LIGHT = BeamMaterial(210e9, 0.3, 7.85)
THROW = ThrowDimensions(0.1, 0.05, 0.08, 0.04, 0.025, 0.12, 0.06)
ANGLES = tuple(-k * 2 * math.pi / 3 for k in (0, 2, 1, 1, 2, 0))  # an in-line six
BALANCED = ThrowMasses(rotating_mass=5.5, counterweight_mass=5.5, counterweight_radius=0.06)


def _comparison(web, pin):
    g = CrankshaftBeamGeometry(
        THROW,
        ANGLES,
        LIGHT,
        MainBearings(1e13, 0.0, 1e13, thrust_journal=1),
        masses=BALANCED,
        free_end=EndMass(2.0, 0.05),
        flywheel=EndMass(20.0, 0.8),
    )
    model = build_beam_model(g, web_stiffness_scale=web, pin_stiffness_scale=pin)
    return lumped_chain_comparison(model, beam_modes(model, 24))


def test_rigid_throws_make_the_beam_a_lumped_chain():
    diffs = []
    for scale in (1e2, 1e4):
        c = _comparison(scale, scale)
        assert c.difference.size >= 5
        diffs.append(np.abs(c.difference[:5]))
    assert np.all(diffs[1] < diffs[0]), diffs
    assert np.max(diffs[1]) < 2e-4, diffs[1]
    assert diffs[1][0] < 1e-5


def test_rigid_webs_alone_leave_the_pins_offset_coupling():
    c = _comparison(1e4, 1.0)
    assert c.difference.size >= 3
    # the beam is stiffer than the chain of free-to-tilt throws (module docstring)
    assert np.all(c.difference[:3] < -0.05), c.difference


def test_chain_inertias_are_the_beam_models():
    g = CrankshaftBeamGeometry(
        THROW,
        ANGLES,
        BeamMaterial(210e9, 0.3, 7850.0),
        MainBearings(1e9),
        masses=ThrowMasses(1.5, 1.2, 2.0, 0.05),
        free_end=EndMass(5.0, 0.05, 0.0, 0.04),
        flywheel=EndMass(20.0, 0.8),
    )
    model = build_beam_model(g)
    chain = lumped_torsional_chain(model)
    r = model.rigid_rotation()
    assert chain.inertias.sum() == pytest.approx(r @ model.mass @ r, rel=1e-12)
    assert chain.names[0] == "free end" and chain.names[-1] == "flywheel"
    # the flywheel's own inertia goes whole to its mass, with half the last journal's
    assert 0.8 < chain.inertias[-1] < 0.8 + 0.5 * chain.inertias[3]
    # the middle throws are alike
    np.testing.assert_allclose(chain.inertias[2:6], chain.inertias[3], rtol=1e-12)
