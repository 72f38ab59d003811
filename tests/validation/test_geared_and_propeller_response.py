"""A geared line against its equivalent single-speed system, and the propeller-order response
of the built-in marine line against an independent dense solve.

Equivalent system (W. Ker Wilson, *Practical Solution of Torsional Vibration Problems*, vol. 1,
ch. 3): everything beyond a gear of speed ratio r enters with inertia, stiffness and damping
times r^2 and its angles divided by r (the kinetic and strain energies unchanged); a torque T
on a mass turning at r times the reference speed enters as r T, and an order p of its own speed
is the order p r of the reference speed. Beyond a reversing (external) mesh the actual angles and
torques change sign.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.engine.model import Engine
from crankdyn.torsion import Gear, Mass, Shaft, TorsionModel
from crankdyn.torsion.excitation import UniformExcitation
from crankdyn.torsion.modal import natural_modes
from crankdyn.torsion.sources import HarmonicSource
from crankdyn.torsion.sweep import forced_response

R = 0.3125  # n_wheel / n_pinion (25:80 teeth)
K1, KM, K2 = 4e5, 9e5, 6e5  # N m/rad (the mesh stiffness referred to the pinion)
JC, JP, JW, JL = 1.2, 0.05, 0.9, 14.0
CL, ETA = 35.0, 0.02


def geared(direction: str, elastic: bool) -> TorsionModel:
    masses = [
        Mass("crank", JC, cylinders=(1,)),
        Mass("pinion", JP, role="gear"),
        Mass("wheel", JW, role="gear"),
        Mass("load", JL, damping=CL),
    ]
    shafts = [
        Shaft(("crank", "pinion"), K1, loss_factor=ETA),
        Shaft(("wheel", "load"), K2, loss_factor=ETA),
    ]
    gear = Gear(
        ("pinion", "wheel"), teeth=(25, 80), direction=direction, stiffness=KM if elastic else None
    )
    source = HarmonicSource("load", orders=[3.0], amplitude=[40.0], phase=[0.7])
    return TorsionModel(
        masses=tuple(masses), shafts=tuple(shafts), gears=(gear,), sources=(source,)
    )


def equivalent(elastic: bool) -> TorsionModel:
    r2 = R * R
    if elastic:
        masses = (
            Mass("crank", JC, cylinders=(1,)),
            Mass("pinion", JP),
            Mass("wheel", JW * r2),
            Mass("load", JL * r2, damping=CL * r2),
        )
        shafts = (
            Shaft(("crank", "pinion"), K1, loss_factor=ETA),
            Shaft(("pinion", "wheel"), KM),
            Shaft(("wheel", "load"), K2 * r2, loss_factor=ETA),
        )
    else:
        masses = (
            Mass("crank", JC, cylinders=(1,)),
            Mass("gears", JP + JW * r2),
            Mass("load", JL * r2, damping=CL * r2),
        )
        shafts = (
            Shaft(("crank", "gears"), K1, loss_factor=ETA),
            Shaft(("gears", "load"), K2 * r2, loss_factor=ETA),
        )
    # the source: order 3 of the load's speed = order 3 R of the crank's, torque R T
    source = HarmonicSource("load", orders=[3.0 * R], amplitude=[40.0 * R], phase=[0.7])
    return TorsionModel(masses=masses, shafts=shafts, sources=(source,))


@pytest.mark.parametrize("elastic", [False, True])
@pytest.mark.parametrize(("direction", "sign"), [("opposite", -1.0), ("same", 1.0)])
def test_geared_line_equals_its_single_speed_equivalent(elastic, direction, sign):
    a, b = geared(direction, elastic), equivalent(elastic)
    assert natural_modes(a).natural_frequency == pytest.approx(
        natural_modes(b).natural_frequency, rel=1e-12, abs=1e-9
    )
    ex = UniformExcitation(250.0, [0.0], "four-stroke")
    speeds = np.linspace(200.0, 3000.0, 57) / RPM
    orders = [0.5, 1.0, 3.0 * R, 2.0]
    ra = forced_response(a, ex, speeds, orders, resolve=False)
    rb = forced_response(b, ex, speeds, orders, resolve=False)
    load_a, load_b = ra.mass_index("load"), rb.mass_index("load")
    assert ra.mass_response[:, :, load_a] == pytest.approx(
        sign * R * rb.mass_response[:, :, load_b], rel=1e-9, abs=1e-18
    )
    # the load shaft: actual torque k2 (actual twist) = (k2 r^2 reflected twist) / (sign r)
    ta = ra.shaft_response[:, :, ra.shaft_index(("wheel", "load"))]
    tb = rb.shaft_response[:, :, -1]
    assert ta == pytest.approx(sign * tb / R, rel=1e-9, abs=1e-12)
    assert ra.synthesized_shaft_torque[:, 1] == pytest.approx(
        rb.synthesized_shaft_torque[:, -1] / R, rel=1e-9
    )
    if elastic:  # the mesh spring's torque, referred to the pinion
        tm = ra.shaft_response[:, :, ra.shaft_index(("pinion", "wheel"))]
        assert tm == pytest.approx(rb.shaft_response[:, :, 1], rel=1e-9, abs=1e-12)


def test_marine_propeller_orders_against_a_dense_solve():
    """Order 1.25 of the engine speed (blade order 4 at the propeller, which turns at 25/80 of
    it; no harmonic of the engine's cycle) excites only through the propeller: the response
    (with the coupling's stiffness at each speed's mean torque, r Q(n) on the engine side, read
    off its table by hand) equals the dense
    solution of (K + iH - omega^2 M + i omega C) X = F with F at the propeller's degree of
    freedom = (25/80) x fraction x Q0 (n_p / n_0)^2 (the propeller law), solved here with
    numpy's dense solver, independently of the chain solver."""
    engine = Engine.example("marine-propulsion")
    model = engine.torsion
    from crankdyn.torsion.excitation import excitation_for

    speeds = np.linspace(300.0, 750.0, 31) / RPM
    orders = np.array([1.25])
    r = forced_response(
        model, excitation_for(model, engine), speeds, orders, dampers=(), resolve=False
    )
    prop = model.index("propeller")
    ratio = model.speed_ratios[prop]
    assert ratio == pytest.approx(25 / 80)
    source = next(s for s in model.sources if s.kind == "propeller")
    q0, n0 = source.load.torque, source.load.speed
    assert q0 * n0 == pytest.approx(2900e3, rel=1e-12)  # 2900 kW at 234.375 rpm
    k, m = model.stiffness_matrix(), model.mass_matrix()
    c, h = model.damping_matrix(), model.hysteretic_matrix()
    dof = model.mass_dof[prop]
    # the coupling (at engine speed): its table in the line file, psi = 1.13
    table_t = np.array([0.0, 15e3, 30e3, 50e3, 75e3])
    table_c = np.array([190e3, 240e3, 285e3, 330e3, 360e3])
    i, o = (model.mass_dof[model.index(n)] for n in ("coupling primary", "coupling secondary"))
    unit = np.zeros_like(k)
    unit[[i, o], [i, o]] = 1.0
    unit[i, o] = unit[o, i] = -1.0
    k_model = np.interp(38e3, table_t, table_c)  # its reference torque
    for j, (q, fraction) in enumerate(zip(orders, source.fraction[:1], strict=True)):
        for s, w in enumerate(speeds):
            omega = q * w
            delta = np.interp(ratio * q0 * (ratio * w / n0) ** 2, table_t, table_c) - k_model
            kk = k + delta * unit
            hh = h + 1.13 / (2 * math.pi) * delta * unit
            f = np.zeros(model.dof_count, dtype=complex)
            f[dof] = ratio * fraction * q0 * (ratio * w / n0) ** 2
            x = np.linalg.solve(kk + 1j * hh - omega**2 * m + 1j * omega * c, f)
            actual = x[dof] * model.signed_speed_ratios[prop]
            assert r.mass_response[s, j, prop] == pytest.approx(actual, rel=1e-9)
    assert math.isfinite(float(np.max(r.synthesized_amplitude)))


def test_engine_source_phase_shifts_the_second_engines_harmonics():
    """A second engine (EngineSource) with firing phase phi: its order-p harmonics are those of
    the same engine at phase 0 times exp(i p phi) (its crank angle is phi when the first
    engine's cylinder 1 fires), checked by the linearity of the response."""
    from crankdyn.torsion.excitation import excitation_for
    from crankdyn.torsion.sources import EngineSource

    masses = (
        Mass("A1", 0.3, cylinders=(1,)),
        Mass("A fw", 1.0),
        Mass("box", 2.0),
        Mass("B fw", 1.0),
        Mass("B1", 0.3),
    )
    shafts = (
        Shaft(("A1", "A fw"), 2e5),
        Shaft(("A fw", "box"), 5e4, loss_factor=0.05),
        Shaft(("box", "B fw"), 5e4, loss_factor=0.05),
        Shaft(("B fw", "B1"), 2e5),
    )
    ex_b = UniformExcitation(100.0, [0.0], "four-stroke")
    base = TorsionModel(masses=masses, shafts=shafts)
    speeds = np.linspace(500.0, 2000.0, 7) / RPM
    orders = [0.5, 1.0, 1.5]

    def with_b(phase):
        src = EngineSource("engine B", ex_b, ((1, "B1"),), phase=phase)
        return dataclasses.replace(base, sources=(src,))

    ex_a = excitation_for(base)
    r0 = forced_response(with_b(0.0), ex_a, speeds, orders, resolve=False)
    rp = forced_response(with_b(1.1), ex_a, speeds, orders, resolve=False)
    only_a = forced_response(base, ex_a, speeds, orders, resolve=False)
    part_b = r0.mass_response - only_a.mass_response
    expected = only_a.mass_response + part_b * np.exp(1j * np.asarray(orders) * 1.1)[None, :, None]
    assert rp.mass_response == pytest.approx(expected, rel=1e-9, abs=1e-15)
