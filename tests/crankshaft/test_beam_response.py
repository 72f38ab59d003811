"""Forced response of the crankshaft beam model (crankdyn.crankshaft.beam_response): modal
superposition with the residual against one sparse solve per frequency, the moment recovery
against statically determinate frames, the load matrix against the torque it must give, and a
resonance where a mode says it is."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import scipy.sparse.linalg as spla

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
from crankdyn.crankshaft.beam_modes import beam_modes
from crankdyn.crankshaft.beam_response import beam_response, load_matrix, recovery_matrices
from crankdyn.errors import InputError

STEEL = BeamMaterial(210e9, 0.3, 7850.0)
THROW = ThrowDimensions(0.1, 0.05, 0.08, 0.04, 0.025, 0.12, 0.06)
SIX = tuple(-k * 2 * math.pi / 3 for k in (0, 2, 1, 1, 2, 0))


def _six(**kw):
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
    return build_beam_model(g)


def _forces(orders, throws=6, seed=3):
    rng = np.random.default_rng(seed)
    shape = (orders, throws)
    z = 1e3 * (rng.normal(size=shape) + 1j * rng.normal(size=shape))
    t = 1e3 * (rng.normal(size=shape) + 1j * rng.normal(size=shape))
    return z, t


def test_modal_with_residual_matches_direct_solves():
    model = _six(damper=TorsionalDamper(0.02, 2e4, 20.0), axial_damping=2e3)
    speeds = np.linspace(100.0, 600.0, 6)
    orders = np.array([0.5, 1.0, 1.5, 2.0, 3.0])
    z, t = _forces(orders.size)
    direct = beam_response(model, speeds, orders, z, t, damping_ratio=0.0, method="direct")
    errors = []
    for modes in (30, 60):
        modal = beam_response(model, speeds, orders, z, t, damping_ratio=0.0, modes=modes)
        err = max(
            float(
                np.max(np.abs(getattr(modal, f) - getattr(direct, f)))
                / np.max(np.abs(getattr(direct, f)))
            )
            for f in ("free_end_axial", "free_end_torsion", "twist", "bearing_moment", "web_moment")
        )
        errors.append(err)
    # mode truncation with the static residual: the error falls with the modes kept
    assert errors[1] < errors[0] < 5e-3, errors
    assert errors[1] < 5e-4, errors


def test_load_matrix_gives_the_torque_of_a_tangential_force():
    model = _six()
    b = load_matrix(model).toarray()
    r = model.rigid_rotation()
    torque = r @ b  # virtual work of the unit forces in a unit rotation
    np.testing.assert_allclose(torque[1::2], THROW.crank_radius, rtol=1e-14)
    np.testing.assert_allclose(torque[0::2], 0.0, atol=1e-15)


def _cantilever(model, load_dof):
    """Static displacement of a single throw clamped at its first journal."""
    a = int(model.journal_nodes[0])
    fixed = [model.dof(a, d) for d in range(6)]
    free = np.setdiff1d(np.arange(model.size), fixed)
    f = np.zeros(model.size)
    f[load_dof] = 1.0
    u = np.zeros(model.size)
    u[free] = spla.spsolve(model.stiffness[free][:, free].tocsc(), f[free])
    return u


def test_web_moments_of_an_axial_force_are_r_times_f():
    # a unit axial force at the free journal bends each web with the moment x F at x from the
    # axis (Castigliano's frame, tests/crankshaft/test_beam_model.py): 0 at the journal end,
    # R F at the pin end; the journals carry no moment
    model = build_beam_model(CrankshaftBeamGeometry(THROW, (0.4,), STEEL), elements=3)
    b = int(model.journal_nodes[1])
    u = _cantilever(model, model.dof(b, 2))
    bearings, webs = recovery_matrices(model)
    np.testing.assert_allclose(np.abs(webs @ u), [0.0, 0.06, 0.0, 0.06], atol=1e-9)
    np.testing.assert_allclose(bearings @ u, 0.0, atol=1e-9)


def test_bearing_moment_of_a_lateral_force_is_f_times_span():
    model = build_beam_model(CrankshaftBeamGeometry(THROW, (0.0,), STEEL), elements=2)
    b = int(model.journal_nodes[1])
    u = _cantilever(model, model.dof(b, 1))  # unit force along y at the far journal
    bearings, _ = recovery_matrices(model)
    m = (bearings @ u).reshape(2, 2)
    # at the clamped journal the moment about x is F times the span; at the loaded one 0
    assert abs(m[0, 0]) == pytest.approx(THROW.span, rel=1e-9)
    assert abs(m[0, 1]) < 1e-9 and np.all(np.abs(m[1]) < 1e-9)


def test_resonance_of_the_lowest_axial_mode():
    model = _six()
    modes = beam_modes(model, 6)
    axial = next(i for i, m in enumerate(modes.motion) if m == "axial")
    w = modes.natural_frequency[axial]
    speeds = w * np.linspace(0.8, 1.2, 201)  # order 1 sweeps through it
    z = np.ones((1, 6)) * 1e3
    zeta = 0.01
    r = beam_response(model, speeds, [1.0], z, 0.0 * z, damping_ratio=zeta)
    peak = speeds[np.argmax(r.free_end_axial)]
    # within the mode's half-power band (the neighbouring modes shift the peak a little)
    assert peak == pytest.approx(w, abs=zeta * w)
    assert r.summary().figure("max_free_end_axial_m").where.startswith("at ")


def test_synthesis_of_two_orders():
    # the synthesised amplitude is the largest |sum| over the cycle: for one order it is |c|
    model = _six()
    z, t = _forces(2)
    one = beam_response(model, [300.0], [1.0], z[:1], t[:1])
    np.testing.assert_allclose(one.free_end_axial, one.free_end_axial_orders[:, 0], rtol=1e-3)
    both = beam_response(model, [300.0], [1.0, 2.0], z, t)
    amps = both.free_end_axial_orders[0]
    assert max(amps) <= both.free_end_axial[0] <= amps.sum() * (1 + 1e-9)


def test_result_exports():
    r = beam_response(_six(), [200.0, 300.0], [1.0, 2.0], *_forces(2))
    data = json.loads(r.to_json())
    assert data["speed_rpm"] == pytest.approx([200 * 30 / math.pi, 300 * 30 / math.pi])
    assert np.shape(data["bearing_moment_Nm"]) == (2, 7)
    assert np.shape(data["web_stress_Pa"]) == (2, 12)
    keys = {f.key for f in r.summary().figures}
    assert {"max_free_end_axial_m", "max_bearing_moment_Nm", "max_web_stress_Pa"} <= keys


@pytest.mark.parametrize(
    "kw,key",
    [
        ({"speeds": [0.0]}, "speeds"),
        ({"orders": [-1.0]}, "orders"),
        ({"method": "x"}, "method"),
        ({"method": "direct"}, "damping_ratio"),
        ({"radial": np.ones((3, 6))}, "radial"),
    ],
)
def test_bad_arguments(kw, key):
    args = {
        "speeds": [100.0],
        "orders": [1.0],
        "radial": np.ones((1, 6)),
        "tangential": np.ones((1, 6)),
    }
    args.update(kw)
    with pytest.raises(InputError) as err:
        beam_response(_six(), **args)
    assert err.value.key == key


def test_vibration_part_by_modes_matches_direct_solves():
    """The webs' bending from vibration (the moments less their quasi-static part) by modal
    superposition against one sparse solve per frequency, as the totals above."""
    model = _six(damper=TorsionalDamper(0.02, 2e4, 20.0), axial_damping=2e3)
    speeds = np.linspace(100.0, 600.0, 6)
    orders = np.array([0.5, 1.0, 1.5, 2.0, 3.0])
    z, t = _forces(orders.size)
    direct = beam_response(model, speeds, orders, z, t, damping_ratio=0.0, method="direct")
    modal = beam_response(model, speeds, orders, z, t, damping_ratio=0.0, modes=60)
    scale = np.max(direct.web_vibration_stress)
    assert np.max(np.abs(modal.web_vibration_stress - direct.web_vibration_stress)) < 5e-4 * scale


def test_vibration_part_vanishes_below_the_modes():
    """Far below the lowest elastic mode omega_1 the response is quasi-static: the part that
    vibration adds falls as (omega / omega_1)^2 (one degree of freedom: 1 / (1 - r^2) - 1 =
    r^2 / (1 - r^2))."""
    model = _six()
    modes = beam_modes(model, 3)
    w1 = modes.natural_frequency[1]  # mode 0: the rigid rotation
    z, t = _forces(1)
    r = beam_response(model, [0.01 * w1], [1.0], z, t, damping_ratio=0.0)
    ratio = np.max(r.web_vibration_stress) / np.max(r.web_stress)
    assert ratio < 5 * 0.01**2  # every mode above omega_1, each with r^2 <= 1e-4


def test_vibration_part_carries_the_axial_resonance():
    """At the lowest axial mode the webs' bending is almost all from vibration (amplified by
    about 1 / (2 zeta) over the quasi-static bending)."""
    model = _six()
    modes = beam_modes(model, 6)
    axial = next(i for i, m in enumerate(modes.motion) if m == "axial")
    w = modes.natural_frequency[axial]
    z = np.ones((1, 6)) * 1e3
    r = beam_response(model, [w], [1.0], z, 0.0 * z, damping_ratio=0.01)
    assert np.max(r.web_vibration_stress) > 0.9 * np.max(r.web_stress)
    keys = {f.key for f in r.summary().figures}
    assert "max_web_vibration_stress_Pa" in keys
