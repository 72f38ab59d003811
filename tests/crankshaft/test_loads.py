"""The throw loads of UR M53.2.1.1 against an independent method: the bending moments of the
simply supported throw found by the direct stiffness method of Euler-Bernoulli beam elements
(no use of the closed form), and the half-ranges against a fine grid."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import crankdyn
from crankdyn.crankshaft.loads import rod_positions, simply_supported_moment, throw_loads
from crankdyn.engine.forces import crank_train
from crankdyn.engine.model import BalanceInputs

SPAN = 0.53
WEB = 0.135


def beam_moments(span, loads, sections):
    """Bending moments (sagging positive for loads in +v) at ``sections`` of a beam on two
    supports at 0 and ``span`` under point loads [(position, force)], by the direct stiffness
    method with cubic Hermite elements between every load and section (EI = 1)."""
    xs = sorted({0.0, span, *[a for a, _ in loads], *sections})
    n = len(xs)
    k = np.zeros((2 * n, 2 * n))
    for e in range(n - 1):
        h = xs[e + 1] - xs[e]
        ke = (
            np.array(
                [
                    [12, 6 * h, -12, 6 * h],
                    [6 * h, 4 * h * h, -6 * h, 2 * h * h],
                    [-12, -6 * h, 12, -6 * h],
                    [6 * h, 2 * h * h, -6 * h, 4 * h * h],
                ]
            )
            / h**3
        )
        dofs = [2 * e, 2 * e + 1, 2 * e + 2, 2 * e + 3]
        k[np.ix_(dofs, dofs)] += ke
    f = np.zeros(2 * n)
    for a, force in loads:
        f[2 * xs.index(a)] += force
    free = [i for i in range(2 * n) if i not in (0, 2 * (n - 1))]  # v = 0 at both supports
    u = np.zeros(2 * n)
    u[free] = np.linalg.solve(k[np.ix_(free, free)], f[free])
    out = []
    for x in sections:
        e = xs.index(x)
        e = min(e, n - 2)
        h = xs[e + 1] - xs[e]
        v1, t1, v2, t2 = u[2 * e : 2 * e + 4]
        s = (x - xs[e]) / h  # 0 at the element's start, 1 at its end
        curvature = (
            (-6 + 12 * s) / h**2 * v1
            + (-4 + 6 * s) / h * t1
            + (6 - 12 * s) / h**2 * v2
            + (-2 + 6 * s) / h * t2
        )
        out.append(-curvature)  # upward loads hog the beam: v'' < 0
    return np.array(out)


def pin_forces(engine, speed, theta):
    """F_R (toward the axis) and F_T of every cylinder's rod on its pin."""
    train = crank_train(engine, speed, theta)
    big_end = np.array([m.rod_big_end or 0.0 for m in train.masses])[:, None]
    radial = train.radial - big_end * speed**2 * engine.geometry.crank_radius
    return radial, train.tangential


def test_closed_form_against_the_stiffness_method():
    """Statics: the closed form M(x) of a point load equals the beam elements' moment."""
    for a in (0.1, 0.265, 0.4):
        for x in (0.05, 0.2, 0.265, 0.45):
            fe = beam_moments(SPAN, [(a, 1000.0)], [x])[0]
            assert float(simply_supported_moment(1000.0, a, x, SPAN)) == pytest.approx(fe, rel=1e-9)


def test_inline_web_and_oil_bore_moments_of_the_statically_determinate_throw():
    """UR M53.2.1.1: the web moment M_BRF at L_1 and the oil bore's M_BO at mid-pin of a
    throw simply supported on its bearings, at several crank angles of a real crank train."""
    engine = crankdyn.Engine.example("marine-propulsion")
    speed = 750 * math.pi / 30
    psi = math.radians(30.0)
    loads = throw_loads(
        engine, speed, bearing_span=SPAN, web_centre_distance=WEB, oil_bore_angle=psi
    )
    idx = [0, 17, 183, 371, 500]  # angles of the 1 deg grid, firing TDC among them
    radial, tangential = pin_forces(engine, speed, loads.theta[idx])
    throws = engine.cylinders.throws
    for i, t in enumerate(throws):
        for k, j in enumerate(idx):
            m_r = beam_moments(SPAN, [(SPAN / 2, radial[i, k])], [WEB, SPAN / 2])
            m_t = beam_moments(SPAN, [(SPAN / 2, tangential[i, k])], [SPAN / 2])[0]
            scale = abs(radial[i]).max() * SPAN
            assert loads.web_moment[t - 1, j] == pytest.approx(m_r[0], abs=1e-9 * scale)
            oil = m_t * math.cos(psi) + m_r[1] * math.sin(psi)
            assert loads.oil_bore_moment[t - 1, j] == pytest.approx(oil, abs=1e-9 * scale)
            # the web's radial force is the free-end bearing's reaction, F_R / 2
            assert loads.web_force[t - 1, j] == pytest.approx(radial[i, k] / 2, rel=1e-12)


def test_v_engine_rods_superposed_by_position():
    """UR M53.2.1.1 (Fig. 2): two rods on one pin, each at its own L_2 (half the rod offset
    either side of the pin's middle), the moment diagrams superposed according to phase."""
    engine = crankdyn.Engine.example("v8-crossplane")
    engine = dataclasses.replace(engine, balance=BalanceInputs(rod_offset=0.03))
    span, web = 0.12, 0.03
    speed = 5000 * math.pi / 30
    positions = rod_positions(engine, span)
    cyl = engine.cylinders
    assert positions[[i for i, b in enumerate(cyl.banks) if b == "A"]] == pytest.approx(0.045)
    assert positions[[i for i, b in enumerate(cyl.banks) if b == "B"]] == pytest.approx(0.075)
    loads = throw_loads(engine, speed, bearing_span=span, web_centre_distance=web)
    idx = [0, 90, 400]
    radial, _ = pin_forces(engine, speed, loads.theta[idx])
    for t in range(1, cyl.throw_count + 1):
        on = [i for i in range(cyl.count) if cyl.throws[i] == t]
        for k, j in enumerate(idx):
            forces = [(positions[i], radial[i, k]) for i in on]
            expected = beam_moments(span, forces, [web])[0]
            assert loads.web_moment[t - 1, j] == pytest.approx(
                expected, abs=1e-9 * abs(radial).max() * span
            )


def test_half_ranges_against_a_fine_grid():
    """The half-ranges (largest - smallest)/2 of M53.2.1.2 are found on the 1 deg grid and
    refined: they bound those of a 0.01 deg grid from above, by less than its resolution."""
    engine = crankdyn.Engine.example("marine-propulsion")
    speed = 750 * math.pi / 30
    loads = throw_loads(engine, speed, bearing_span=SPAN, web_centre_distance=WEB)
    theta = np.linspace(0.0, engine.cycle_angle, 72001)
    radial, _ = pin_forces(engine, speed, theta)
    web = radial * 0.5 * WEB  # the inline throw: M_BRF = F_R / 2 L_1 (statics, test above)
    for i, t in enumerate(engine.cylinders.throws):
        fine = 0.5 * (web[i].max() - web[i].min())
        assert loads.moment_half_range[t - 1] >= fine * (1 - 1e-12)
        assert loads.moment_half_range[t - 1] == pytest.approx(fine, rel=2e-6)
        fine_q = 0.5 * (radial[i].max() - radial[i].min()) / 2
        assert loads.force_half_range[t - 1] == pytest.approx(fine_q, rel=2e-6)


def test_journal_torque_is_the_sum_of_the_cylinders_from_the_free_end():
    """The quasi-static torque through the journal after throw k: the tangential forces of
    throws 1..k times R; its largest magnitude over the cycle (the shrink fit's M_max)."""
    engine = crankdyn.Engine.example("marine-propulsion")
    speed = 750 * math.pi / 30
    loads = throw_loads(engine, speed, bearing_span=SPAN, web_centre_distance=WEB)
    theta = np.linspace(0.0, engine.cycle_angle, 14401)
    train = crank_train(engine, speed, theta)
    order = np.argsort(engine.cylinders.throws)
    through = np.cumsum(train.tangential[order], axis=0) * engine.geometry.crank_radius
    fine = np.abs(through).max()
    assert loads.max_journal_torque >= fine * (1 - 1e-12)
    assert loads.max_journal_torque == pytest.approx(fine, rel=1e-4)
