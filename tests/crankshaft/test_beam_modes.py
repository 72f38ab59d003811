"""Modes of the crankshaft beam model (crankdyn.crankshaft.beam_modes): the sparse shift-invert
solver against a dense generalized eigensolver, the energy classification on motions whose type
is known, rigid-body modes, mesh convergence and the result's summary."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import scipy.linalg

from crankdyn.crankshaft.beam_elements import BeamMaterial
from crankdyn.crankshaft.beam_model import (
    CrankshaftBeamGeometry,
    EndMass,
    MainBearings,
    ThrowDimensions,
    ThrowMasses,
    TorsionalDamper,
    build_beam_model,
)
from crankdyn.crankshaft.beam_modes import (
    beam_modes,
    compare_torsional_modes,
    energy_fractions,
    solve_lowest_modes,
)
from crankdyn.errors import InputError

STEEL = BeamMaterial(210e9, 0.3, 7850.0)
THROW = ThrowDimensions(0.1, 0.05, 0.08, 0.04, 0.025, 0.12, 0.06)
SIX = tuple(-k * 2 * math.pi / 3 for k in (0, 2, 1, 1, 2, 0))


def _six(elements=2, **kw):
    g = CrankshaftBeamGeometry(
        THROW,
        SIX,
        STEEL,
        MainBearings(5e8, 1e6, 5e8, thrust_journal=4),
        masses=ThrowMasses(1.5, 1.2, 2.0, 0.05),
        free_end=EndMass(5.0, 0.05, 0.03, 0.05),
        flywheel=EndMass(20.0, 0.8, 0.4, 0.05),
        **kw,
    )
    return build_beam_model(g, elements=elements)


def test_sparse_shift_invert_equals_dense_eigh():
    model = _six()
    assert model.size > 120  # the sparse path
    lam, phi = solve_lowest_modes(model.stiffness, model.mass, 16)
    dense = scipy.linalg.eigh(
        model.stiffness.toarray(), model.mass.toarray(), eigvals_only=True, subset_by_index=[0, 15]
    )
    assert lam[0] == 0.0 and abs(dense[0]) < 1e-6 * dense[-1]
    np.testing.assert_allclose(lam[1:], dense[1:], rtol=1e-9)
    # mass-normalised and K-orthogonal
    np.testing.assert_allclose(phi.T @ (model.mass @ phi), np.eye(16), atol=1e-9)
    np.testing.assert_allclose(phi.T @ (model.stiffness @ phi), np.diag(lam), atol=1e-6 * lam[-1])


def test_energy_fractions_of_known_motions():
    model = _six()
    idx = model.dof_index
    active = idx >= 0

    def field(per_node):
        out = np.zeros(model.size)
        out[idx[active]] = per_node[active]
        return out

    r = model.node_xyz
    rotation = model.rigid_rotation()
    lateral = field(np.tile([1.0, 0, 0, 0, 0, 0], (r.shape[0], 1)))
    axial = field(np.tile([0, 0, 1.0, 0, 0, 0], (r.shape[0], 1)))
    tilt = np.zeros((r.shape[0], 6))
    tilt[:, :3] = np.cross([1.0, 0, 0], r)
    tilt[:, 3] = 1.0
    f = energy_fractions(model, np.stack([rotation, lateral, axial, field(tilt)], axis=1))
    np.testing.assert_allclose(f[0], [1, 0, 0], atol=1e-12)
    np.testing.assert_allclose(f[1], [0, 0, 1], atol=1e-12)
    np.testing.assert_allclose(f[2], [0, 1, 0], atol=1e-12)
    assert f[3][2] > 0.5  # a tilt: bending, with the axial motion of the off-axis masses
    np.testing.assert_allclose(f.sum(axis=1), 1.0)


def test_free_crankshaft_has_six_rigid_modes():
    g = CrankshaftBeamGeometry(THROW, SIX[:3], STEEL)
    r = beam_modes(build_beam_model(g), 8)
    labels = list(r.motion[:6])
    assert labels.count("rigid torsional") == 1
    assert labels.count("rigid axial") == 1
    assert labels.count("rigid bending") == 4
    assert not r.motion[6].startswith("rigid")
    assert np.all(r.natural_frequency[:6] == 0.0)


def test_a_viscous_dampers_free_ring_is_its_own_rigid_mode():
    # k = 0: undamped, the ring turns alone (a second zero mode), named so and kept out of the
    # elastic modes; its shape is the ring's unit rotation, the shaft's rigid mode leaves it
    model = _six(damper=TorsionalDamper(0.4, 0.0, 300.0))
    r = beam_modes(model, 10)
    ring = int(model.dof_index[model.extra_nodes[0]].max())
    labels = [str(m) for m in r.motion]
    assert labels[:2] == ["rigid torsional", "rigid damper ring"]
    shape = r.shapes[:, 1]
    assert abs(abs(shape[ring]) - 1 / math.sqrt(0.4)) < 1e-9
    assert np.max(np.abs(np.delete(shape, ring))) < 1e-9
    assert abs(r.shapes[ring, 0]) < 1e-9
    np.testing.assert_allclose(r.shapes.T @ (model.mass @ r.shapes), np.eye(10), atol=1e-9)
    # the elastic modes are those of the model without the ring
    bare = beam_modes(_six(), 9)
    np.testing.assert_allclose(r.natural_frequency[2:], bare.natural_frequency[1:], rtol=1e-8)


def test_mesh_convergence_of_the_lowest_modes():
    f = {n: beam_modes(_six(n), 10).frequencies_hz[1:] for n in (1, 2, 4, 8)}
    # stated mesh error of the default (2 elements per part) against 8: below 2e-4
    assert np.max(np.abs(f[2] / f[8] - 1.0)) < 2e-4
    assert np.max(np.abs(f[4] / f[8] - 1.0)) < np.max(np.abs(f[2] / f[8] - 1.0))
    assert np.max(np.abs(f[1] / f[8] - 1.0)) < 5e-3


def test_result_summary_table_and_json():
    r = beam_modes(_six(), 12)
    summary = r.summary()
    keys = [fig.key for fig in summary.figures]
    assert "beam_lowest_natural_frequency_hz" in keys
    assert "beam_lowest_torsional_frequency_hz" in keys
    assert summary.figure("beam_lowest_natural_frequency_hz").value == pytest.approx(
        r.frequencies_hz[1]
    )
    table = summary.tables[0]
    assert len(table.rows) == 12 and table.rows[0][2] == "rigid torsional"
    data = json.loads(r.to_json())
    assert len(data["natural_frequencies_hz"]) == 12
    assert r.node_displacements(2).shape == (r.model.node_xyz.shape[0], 6)
    with pytest.raises(InputError):
        r.node_displacements(13)


def test_compare_torsional_modes_pairs_in_order():
    r = beam_modes(_six(), 12)
    torsional = r.natural_frequency[(r.torsional_fraction >= 0.3) & (r.natural_frequency > 0)]
    assert torsional.size >= 2
    c = compare_torsional_modes(r, [0.0, *(1.1 * torsional)], minimum=0.3)
    np.testing.assert_allclose(c.difference, 0.1, rtol=1e-12)
    assert c.summary().figure("lumped_model_largest_difference").value == pytest.approx(0.1)
    # the default counts a mode as torsional from half its kinetic energy
    strict = compare_torsional_modes(r, [0.0, *(1.1 * torsional)])
    assert np.all(r.torsional_fraction[strict.beam_mode - 1] >= 0.5)


def test_compare_torsional_modes_pairs_by_shape_whatever_the_order():
    # lumped modes made from the beam's own torsional shapes at the web centres' theta_z, listed
    # in reverse with 10 % higher frequencies: the MAC assignment finds every pair (MAC 1),
    # where the k-th with the k-th pairs them crosswise
    model = _six()
    r = beam_modes(model, 12)
    rows = [model.dof(int(n), 5) for n in model.web_axis_nodes.ravel()]
    use = np.flatnonzero((r.torsional_fraction >= 0.3) & (r.natural_frequency > 0))
    assert use.size >= 2
    at = r.shapes[rows]
    flipped = use[::-1]
    lumped = [0.0, *(1.1 * r.natural_frequency[flipped])]
    shapes = np.column_stack([np.ones(len(rows)), -3.0 * at[:, flipped]])
    c = compare_torsional_modes(r, lumped, shapes=(at, shapes), minimum=0.3)
    np.testing.assert_array_equal(c.beam_mode, r.mode[use])
    np.testing.assert_allclose(c.difference, 0.1, rtol=1e-12)
    np.testing.assert_allclose(c.mac, 1.0, rtol=1e-12)
    assert "MAC" in c.pairing
    (table,) = c.summary().tables
    assert table.columns[-1].label == "MAC" and table.caption == c.pairing
    # the lower beam mode's shape at a lumped frequency above the higher one's: order pairs
    # them crosswise, the shapes do not
    a, b = r.mode[use[:2]]
    fb = r.natural_frequency[use[1]]
    swapped = [fb, 2.0 * fb]
    c = compare_torsional_modes(r, swapped, shapes=(at, at[:, use[1::-1]]), minimum=0.3)
    assert dict(zip(c.beam_mode.tolist(), c.lumped_frequency, strict=True)) == {b: fb, a: 2 * fb}
    crossed = compare_torsional_modes(r, swapped, minimum=0.3)
    assert crossed.mac is None and crossed.beam_mode[0] == a and crossed.lumped_frequency[0] == fb


@pytest.mark.parametrize("kw,key", [({"count": 0}, "count"), ({"threshold": 0.4}, "threshold")])
def test_bad_arguments(kw, key):
    with pytest.raises(InputError) as err:
        beam_modes(_six(1), **kw)
    assert err.value.key == key
