"""The crankshaft beam model (crankdyn.crankshaft.beam_model, beam_elements, beam_stiffness):
the assembled matrices against hand sums (mass, inertia about the axis), rigid-body motions
against the stiffness, and a single throw's static stiffness against the closed-form frame
(Castigliano's theorem on the statically determinate cantilever throw: an independent method)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.crankshaft.beam_elements import (
    BeamMaterial,
    BeamSection,
    element_frames,
    global_element_matrices,
    local_element_matrices,
    offset_matrices,
    point_mass_matrix,
)
from crankdyn.crankshaft.beam_model import (
    CrankshaftBeamGeometry,
    EndMass,
    MainBearings,
    ThrowDimensions,
    ThrowMasses,
    TorsionalDamper,
    build_beam_model,
)
from crankdyn.crankshaft.beam_stiffness import throw_stiffness
from crankdyn.errors import InputError

STEEL = BeamMaterial(210e9, 0.3, 7850.0)
THROW = ThrowDimensions(0.1, 0.05, 0.08, 0.04, 0.025, 0.12, 0.06, journal_bore=0.02)


def _rigid(model, translation=(0.0, 0.0, 0.0), rotation=(0.0, 0.0, 0.0)):
    """A rigid motion of every beam node as a displacement vector."""
    r = model.node_xyz
    u = np.asarray(translation) + np.cross(np.asarray(rotation), r)
    per_node = np.concatenate([u, np.tile(rotation, (r.shape[0], 1))], axis=1)
    out = np.zeros(model.size)
    idx = model.dof_index
    out[idx[idx >= 0]] = per_node[idx >= 0]
    return out


@pytest.mark.parametrize("theory", ["timoshenko", "euler-bernoulli"])
def test_rigid_motions_store_no_strain_energy(theory):
    g = CrankshaftBeamGeometry(THROW, (0.0, 2.0, 4.5), STEEL)
    m = build_beam_model(g, theory=theory, web_rigid_fraction=0.3)
    scale = abs(m.stiffness).max()
    for t, w in (
        ((1, 0, 0), (0, 0, 0)),
        ((0, 1, 0), (0, 0, 0)),
        ((0, 0, 1), (0, 0, 0)),
        ((0, 0, 0), (1, 0, 0)),
        ((0, 0, 0), (0, 1, 0)),
        ((0, 0, 0), (0, 0, 1)),
    ):
        assert np.max(np.abs(m.stiffness @ _rigid(m, t, w))) < 1e-9 * scale
    assert abs(m.stiffness - m.stiffness.T).max() < 1e-14 * scale
    assert abs(m.mass - m.mass.T).max() < 1e-15 * abs(m.mass).max()


def test_element_is_frame_invariant_and_offsets_are_rigid_links():
    sec = BeamSection.rectangular(0.12, 0.03, 0.3)
    k, _ = local_element_matrices([0.2], STEEL, sec)
    axis = np.array([[0.3, -0.4, 0.866]])
    frames = element_frames(axis, [[1.0, 0.0, 0.0]])
    ea, eb = np.array([0.01, 0.02, -0.03]), np.array([0.0, -0.05, 0.02])
    offs = offset_matrices([ea], [eb])
    kg = global_element_matrices(k, frames, offs)[0]
    # node a at the origin, its end at ea; end b 0.2 m along the axis, node b at end b - eb
    node_b = ea + 0.2 * frames[0, 0] - eb
    # rigid motions of the two nodes (the offsets are rigid links) store no energy
    for w in np.eye(3):
        for t in np.eye(3):
            u = np.concatenate([t, w, t + np.cross(w, node_b), w])
            assert np.max(np.abs(kg @ u)) < 1e-9 * np.abs(kg).max()
    # eigenvalues do not depend on the frame (orthogonal transformation without offsets)
    plain = global_element_matrices(k, frames)[0]
    np.testing.assert_allclose(
        np.linalg.eigvalsh(plain), np.linalg.eigvalsh(k[0]), rtol=1e-9, atol=1e-6 * np.abs(k).max()
    )


def test_point_mass_parallel_axis():
    m = point_mass_matrix([3.0], [[0.1, -0.2, 0.05]], [np.diag([0.1, 0.2, 0.3])])[0]
    # inertia about the node = J_c + m (|e|^2 I - e e^T)
    e = np.array([0.1, -0.2, 0.05])
    expected = np.diag([0.1, 0.2, 0.3]) + 3.0 * (e @ e * np.eye(3) - np.outer(e, e))
    np.testing.assert_allclose(m[3:, 3:], expected, rtol=1e-14)
    np.testing.assert_allclose(m[:3, :3], 3.0 * np.eye(3))


def test_mass_and_axial_inertia_against_hand_sums():
    masses = ThrowMasses(
        rotating_mass=1.5, reciprocating_mass=1.2, counterweight_mass=2.0, counterweight_radius=0.05
    )
    g = CrankshaftBeamGeometry(
        THROW,
        (0.0, math.pi),
        STEEL,
        MainBearings(1e9),
        masses=masses,
        free_end=EndMass(5.0, 0.05, 0.03, 0.04),
        flywheel=EndMass(20.0, 0.8, 0.4, 0.0),
    )
    m = build_beam_model(g, elements=3)
    t, rho = THROW, STEEL.density
    aj = math.pi / 4 * (t.journal_diameter**2 - t.journal_bore**2)
    ap = math.pi / 4 * t.pin_diameter**2
    aw = t.web_width * t.web_thickness
    lj = 2 * (t.journal_length + t.web_thickness) + 0.04  # two throws' journal halves, stub
    lp = 2 * (t.pin_length + t.web_thickness)
    lw = 4 * t.crank_radius
    steel = rho * (aj * lj + ap * lp + aw * lw)
    x = _rigid(m, (1.0, 0.0, 0.0))
    z = _rigid(m, (0.0, 0.0, 1.0))
    # across: rod m_r + m_j / 2; along the axis m_r only (module docstring)
    attached = 5.0 + 20.0 + 2 * 2.0
    assert x @ m.mass @ x == pytest.approx(steel + attached + 2 * (1.5 + 0.6), rel=1e-12)
    assert z @ m.mass @ z == pytest.approx(steel + attached + 2 * 1.5, rel=1e-12)
    # inertia about the axis: journals and pins' own, pins' R^2, webs' (A R^3 / 3 + I_z' R)
    jp = math.pi / 32 * (t.journal_diameter**4 - t.journal_bore**4)
    pp = math.pi / 32 * t.pin_diameter**4
    R = t.crank_radius
    web = aw * R**3 / 3 + t.web_thickness * t.web_width**3 / 12 * R
    shaft = rho * (jp * lj + lp * (pp + ap * R**2) + 4 * web)
    bodies = 0.05 + 0.8 + 2 * (1.5 + 0.6) * R**2 + 2 * 2.0 * 0.05**2
    r = m.rigid_rotation()
    assert r @ m.mass @ r == pytest.approx(shaft + bodies, rel=1e-12)


def test_geometry_of_nodes():
    g = CrankshaftBeamGeometry(THROW, (0.3, -1.2), STEEL)
    m = build_beam_model(g, elements=2)
    R = THROW.crank_radius
    for node, alpha in zip(m.pin_nodes, (0.3, -1.2), strict=True):
        x, y, _ = m.node_xyz[node]
        assert (x, y) == pytest.approx((R * math.cos(alpha), R * math.sin(alpha)), abs=1e-15)
    np.testing.assert_allclose(m.node_xyz[m.journal_nodes, 2], [0.0, THROW.span, 2 * THROW.span])
    assert "2 per journal half" in m.mesh_note


def _cantilever_torsion(t, mat, fraction=0.0):
    """Closed-form twist per unit torque of the cantilever throw: journals and pin in torsion,
    webs in in-plane bending under the constant moment T (no shear force)."""
    j = BeamSection.circular(t.journal_diameter, t.journal_bore, mat.poisson_ratio)
    p = BeamSection.circular(t.pin_diameter, t.pin_bore, mat.poisson_ratio)
    w = BeamSection.rectangular(t.web_width, t.web_thickness, mat.poisson_ratio)
    G, E = mat.shear_modulus, mat.youngs_modulus
    web = t.crank_radius - fraction * 0.5 * (t.journal_diameter + t.pin_diameter)
    return (
        (t.journal_length + t.web_thickness) / (G * j.torsion_constant)
        + (t.pin_length + t.web_thickness) / (G * p.torsion_constant)
        + 2 * web / (E * w.second_moment_z)
    )


def _cantilever_axial(t, mat, shear=True):
    """Closed-form deflection per unit axial force (Castigliano): journals and pin in tension,
    the pin bent by the constant moment R F, the webs by x F (x from the axis) and sheared by F."""
    j = BeamSection.circular(t.journal_diameter, t.journal_bore, mat.poisson_ratio)
    p = BeamSection.circular(t.pin_diameter, t.pin_bore, mat.poisson_ratio)
    w = BeamSection.rectangular(t.web_width, t.web_thickness, mat.poisson_ratio)
    G, E, R = mat.shear_modulus, mat.youngs_modulus, t.crank_radius
    lp = t.pin_length + t.web_thickness
    out = (
        (t.journal_length + t.web_thickness) / (E * j.area)
        + lp / (E * p.area)
        + lp * R**2 / (E * p.second_moment_y)
        + 2 * R**3 / (3 * E * w.second_moment_y)
    )
    if shear:
        out += 2 * R / (w.shear_coefficient * G * w.area)
    return out


@pytest.mark.parametrize("theory", ["timoshenko", "euler-bernoulli"])
@pytest.mark.parametrize("fraction", [0.0, 0.4])
def test_throw_torsional_stiffness_closed_form_frame(theory, fraction):
    s = throw_stiffness(
        THROW, STEEL, supported=False, elements=1, theory=theory, web_rigid_fraction=fraction
    )
    assert s.torsional == pytest.approx(1.0 / _cantilever_torsion(THROW, STEEL, fraction), rel=1e-9)
    # held in its bearings the symmetric throw twists the same (the pin's sideways motion
    # through one web is undone by the other)
    held = throw_stiffness(
        THROW, STEEL, supported=True, elements=1, theory=theory, web_rigid_fraction=fraction
    )
    assert held.torsional == pytest.approx(s.torsional, rel=1e-9)


@pytest.mark.parametrize("theory", ["timoshenko", "euler-bernoulli"])
def test_throw_axial_stiffness_closed_form_frame(theory):
    s = throw_stiffness(THROW, STEEL, supported=False, elements=1, theory=theory)
    expected = 1.0 / _cantilever_axial(THROW, STEEL, shear=theory == "timoshenko")
    assert s.axial == pytest.approx(expected, rel=1e-9)


def test_damper_and_shaft_line_are_torsional_only():
    g = CrankshaftBeamGeometry(
        THROW,
        (0.0,),
        STEEL,
        MainBearings(1e9),
        damper=TorsionalDamper(0.05, 1e4, 10.0),
        shaft_line=((1.0, 5e5), (2.0, 3e5)),
    )
    m = build_beam_model(g)
    assert len(m.extra_nodes) == 3
    for node in m.extra_nodes:
        assert (m.dof_index[node] >= 0).tolist() == [False] * 5 + [True]
    assert m.damping is not None
    assert m.damping[m.dof(m.extra_nodes[0], 5), m.dof(m.free_end_node, 5)] == -10.0


@pytest.mark.parametrize(
    "make,key",
    [
        (lambda: ThrowDimensions(0.1, 0.05, 0.08, 0.04, 0.025, 0.12, -0.06), "crank_radius"),
        (
            lambda: ThrowDimensions(0.1, 0.05, 0.08, 0.04, 0.025, 0.12, 0.06, pin_bore=0.08),
            "pin_bore",
        ),
        (lambda: MainBearings(-1.0), "radial_stiffness"),
        (lambda: MainBearings(1.0, thrust_journal=0), "thrust_journal"),
        (lambda: CrankshaftBeamGeometry(THROW, (), STEEL), "pin_angles"),
        (
            lambda: CrankshaftBeamGeometry(
                THROW, (0.0,), STEEL, MainBearings(1.0, thrust_journal=3)
            ),
            "thrust_journal",
        ),
        (
            lambda: CrankshaftBeamGeometry(
                THROW, (0.0,), STEEL, masses=(ThrowMasses(), ThrowMasses())
            ),
            "masses",
        ),
        (lambda: BeamMaterial(210e9, 0.5, 7850.0), "poisson_ratio"),
        (
            lambda: build_beam_model(CrankshaftBeamGeometry(THROW, (0.0,), STEEL), elements=0),
            "elements",
        ),
        (
            lambda: build_beam_model(CrankshaftBeamGeometry(THROW, (0.0,), STEEL), theory="x"),
            "theory",
        ),
        (
            lambda: build_beam_model(
                CrankshaftBeamGeometry(THROW, (0.0,), STEEL), web_rigid_fraction=2.0
            ),
            "web_rigid_fraction",
        ),
    ],
)
def test_bad_input_names_its_key(make, key):
    with pytest.raises(InputError) as err:
        make()
    assert err.value.key == key
