"""The optional forces of seed 000 section 2 (crankdyn.engine.force_model): gravity against the
parts' potential energy, the piston's friction against its own law and a hand-worked angle."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.engine.force_model import ForceModel, G
from crankdyn.engine.forces import crank_tangential, crank_train
from crankdyn.errors import InputError
from crankdyn.io.engine_file import parse_engine
from crankdyn.session import Analysis

RPM_ = math.pi / 30


def _doc(forces: dict | None, *, layout: str = "V") -> dict:
    doc = {
        "name": "twin",
        "geometry": {"bore": "90 mm", "stroke": "80 mm", "rod_length": "150 mm",
                     "offset": "2 mm"},
        "cylinders": {"count": 2, "layout": layout, "firing_order": [1, 2],
                      "bank_angle": "70 deg", "banks": ["A", "B"], "throws": [1, 1],
                      "throw_angles": ["0 deg", "70 deg"]},
        "masses": {"piston_group": "0.6 kg", "rod": "0.7 kg", "rod_cg_from_big_end": "40 mm",
                   "crank_unbalance": "0.5 kg"},
        "operating": {"speed": "600 rpm"},
    }  # fmt: skip
    if forces is not None:
        doc["forces"] = forces
    return doc


def test_gravity_torque_is_minus_the_potential_energys_derivative():
    """With gravity on, the torque changes by -dV/dtheta, V = g sum (m_j h_pin + m_r h_crank):
    the piston pin at s = R cos(phi) + L cos(beta) along the axis (height s cos(alpha) - e
    sin(alpha)), the crank pin at R cos(chi), chi = alpha + phi (the two-mass rod keeps the
    rod's centre-of-gravity height). V is differentiated numerically (central differences,
    h = 1e-5 rad: relative error ~1e-10); a V twin so that alpha != 0 on both banks."""
    plain = parse_engine(_doc(None), file="e.toml")
    heavy = parse_engine(_doc({"gravity": True}), file="e.toml")
    theta = np.linspace(0.0, 4 * math.pi, 181)
    w = 600 * RPM_
    g = plain.geometry
    dm = crank_train(heavy, w, theta).tangential - crank_train(plain, w, theta).tangential
    torque = dm.sum(axis=0) * g.crank_radius
    eq = crank_train(plain, w, theta).masses
    alpha = np.asarray(plain.cylinders.bank_axis_angles)[:, None]
    psi = np.asarray(plain.cylinders.throw_angles)[:, None]
    m_j = np.array([m.reciprocating for m in eq])[:, None]
    m_r = np.array([m.rotating for m in eq])[:, None]

    def potential(th):
        phi = th[None, :] - psi
        s = g.crank_radius * np.cos(phi) + np.sqrt(
            g.rod_length**2 - (g.crank_radius * np.sin(phi) - g.offset) ** 2
        )
        h_pin = s * np.cos(alpha) - g.offset * np.sin(alpha)
        h_crank = g.crank_radius * np.cos(alpha + phi)
        return G * (m_j * h_pin + m_r * h_crank).sum(axis=0)

    h = 1e-5
    expected = -(potential(theta + h) - potential(theta - h)) / (2 * h)
    scale = float(np.max(np.abs(expected)))
    np.testing.assert_allclose(torque, expected, atol=1e-8 * scale)
    # the weights' torque does no work over a revolution; the tangential force alone agrees
    np.testing.assert_array_equal(
        crank_tangential(heavy, w, theta), crank_train(heavy, w, theta).tangential
    )


def test_gravity_loads_the_bearings_with_the_whole_weight():
    """The throw forces gain the weights: summed over a revolution (rigid crank, even grid) the
    mean vertical force changes by -(m_j + m_r) g per cylinder (the piston's weight reaches the
    crank through the rod, its part across the axis through the liner is not the crank's)."""
    plain = parse_engine(_doc(None, layout="inline") | {"cylinders": {"count": 1}}, file="e.toml")
    heavy = parse_engine(
        _doc({"gravity": True}, layout="inline") | {"cylinders": {"count": 1}}, file="e.toml"
    )
    theta = np.linspace(0.0, 4 * math.pi, 1441)[:-1]
    w = 600 * RPM_
    _, fy0 = crank_train(plain, w, theta).throw_forces()
    _, fy1 = crank_train(heavy, w, theta).throw_forces()
    eq = crank_train(plain, w, theta).masses[0]
    # upright single cylinder: the whole weight goes down through the crank, on average
    assert float(np.mean(fy1 - fy0)) == pytest.approx(-(eq.reciprocating + eq.rotating) * G,
                                                      rel=2e-3)  # fmt: skip


def test_piston_friction_obeys_its_law_and_a_hand_worked_angle():
    """F_f = -sgn(v) (F_ring + mu |N|) at every angle with N the final side force; at phi = 90
    deg (moving toward the crank) by hand: P = (P_0 - F_ring) / (1 + mu tan(beta))."""
    doc = _doc({"ring_friction": "60 N", "skirt_friction": 0.08}, layout="inline")
    doc["cylinders"] = {"count": 1}
    doc["geometry"] = {"bore": "90 mm", "stroke": "80 mm", "rod_length": "150 mm"}
    engine = parse_engine(doc, file="e.toml")
    plain = parse_engine({**doc, "forces": {}}, file="e.toml")
    theta = np.radians(np.arange(0.0, 720.0, 0.5))
    w = 1500 * RPM_
    t = crank_train(engine, w, theta)
    v = t.motion.velocity
    law = -np.sign(v) * (60.0 + 0.08 * np.abs(t.side))
    np.testing.assert_allclose(t.friction, law, rtol=1e-12, atol=1e-9)
    p0 = crank_train(plain, w, theta).piston
    k = int(np.argmin(np.abs(theta - math.pi / 2)))
    lam = 0.040 / 0.150
    tan_beta = lam / math.sqrt(1 - lam**2)
    assert t.piston[0, k] == pytest.approx((p0[0, k] - 60.0) / (1 + 0.08 * tan_beta), rel=1e-12)
    # friction only takes work out of the crank: the mean torque falls
    assert float(np.mean(t.tangential)) < float(np.mean(crank_train(plain, w, theta).tangential))


def test_forces_output_and_file_errors():
    engine = parse_engine(_doc({"gravity": True, "ring_friction": "40 N"}), file="e.toml")
    forces = Analysis(engine).forces()
    d = forces.to_dict()
    assert "weight_force_N" in d and "friction_force_N" in d
    assert any("gravity; piston friction" in n for n in forces.notes)
    assert (
        "weight_force_N" not in Analysis(parse_engine(_doc(None), file="e.toml")).forces().to_dict()
    )
    with pytest.raises(InputError) as info:
        parse_engine(_doc({"skirt_friction": 1.5}), file="e.toml")
    assert str(info.value).startswith("e.toml: [forces] skirt_friction")
    no_masses = _doc({"gravity": True})
    del no_masses["masses"]
    with pytest.raises(InputError, match="give \\[masses\\]"):
        parse_engine(no_masses, file="e.toml")
    assert ForceModel().active is False
