"""Speed fluctuation and flywheel (seed 000 section 2.4) against closed-form torque curves,
identities of the energy equation, the sizing formulas, engine files and bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.engine.flywheel import (
    FlywheelInputs,
    G,
    crank_train_inertia,
    engine_flywheel,
    excess_work,
    flywheel_analysis,
    instantaneous_speed,
    rim_width,
)
from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.io.engine_file import load_engine

FOUR = 4 * math.pi
W = 1500 * math.pi / 30
H = math.radians(0.25)
THETA = np.linspace(0.0, FOUR, round(FOUR / H) + 1)


def _trapezoid_rel(order):
    """Relative error bound of the swing of a harmonic of this order on THETA: the trapezoid
    rule's cumulative integral of sin(n theta) has the amplitude factor 1 - (n h)^2/12, and the
    grid can miss each extreme by half a step, 1 - cos(n h/2) ~ (n h)^2/8."""
    return (order * H) ** 2 * (1 / 12 + 1 / 8)


def test_single_harmonic_closed_form():
    """M = M0 + A sin(n theta + c): W = (A/n)(cos c - cos(n theta + c)), Delta E = 2 A / n,
    mu = 2 A / M0, xi = Delta E / (M0 Theta); I0 = Delta E / (delta w^2)."""
    m0, a, n, c = 650.0, 1200.0, 3.0, 0.4
    torque = m0 + a * np.sin(n * THETA + c)
    ew = excess_work(THETA, torque, FOUR)
    assert ew.mean_torque == pytest.approx(m0, rel=1e-12)
    assert ew.swing == pytest.approx(2 * a / n, rel=_trapezoid_rel(n))
    exact_w = (a / n) * (math.cos(c) - np.cos(n * ew.angle + c))
    np.testing.assert_allclose(ew.work, exact_w, atol=2 * a / n * _trapezoid_rel(n))
    # slowest where n theta + c = 0 (mod 2 pi), fastest half a period later (to the grid point:
    # half a step off at most)
    off = (n * H) ** 2 / 8
    assert math.cos(n * ew.angle_of_min + c) == pytest.approx(1.0, abs=off)
    assert math.cos(n * ew.angle_of_max + c) == pytest.approx(-1.0, abs=off)
    r = flywheel_analysis(THETA, torque, W, FOUR, delta=0.01)
    assert r.torque_nonuniformity == pytest.approx(2 * a / m0, rel=off)  # sampled extremes
    rel = _trapezoid_rel(n)
    assert r.excess_work_coefficient == pytest.approx(2 * a / n / (m0 * FOUR), rel=rel)
    assert r.required_inertia == pytest.approx(2 * a / n / (0.01 * W * W), rel=rel)


def test_two_harmonics_closed_form():
    """M = M0 + A sin 2 theta + B sin 4 theta: W = A/2 (1 - cos 2t) + B/4 (1 - cos 4t); its
    extremes found on a fine analytic grid."""
    m0, a, b = 300.0, 900.0, 350.0
    torque = m0 + a * np.sin(2 * THETA) + b * np.sin(4 * THETA)
    t = np.linspace(0, FOUR, 400001)
    w = a / 2 * (1 - np.cos(2 * t)) + b / 4 * (1 - np.cos(4 * t))
    ew = excess_work(THETA, torque, FOUR)
    assert ew.swing == pytest.approx(np.ptp(w), rel=_trapezoid_rel(4))


def test_flywheel_from_the_required_inertia():
    """I_F = I_0 - (rotating + reciprocating + other); GD^2 = 4 g I_F (seed 000 2.4)."""
    torque = 500.0 + 800.0 * np.sin(2 * THETA)
    inputs = FlywheelInputs(delta=0.02, other_inertia=0.03)
    r = flywheel_analysis(
        THETA,
        torque,
        W,
        FOUR,
        rotating_inertia=0.05,
        reciprocating_inertia=0.02,
        inputs=inputs,
    )
    assert r.flywheel_inertia == pytest.approx(r.required_inertia - 0.1)
    assert r.total_inertia == pytest.approx(r.required_inertia)
    assert r.gd2 == pytest.approx(4 * G * r.flywheel_inertia)
    assert r.speed_fluctuation_linear == pytest.approx(0.02)
    # the exact speed swing agrees with the linearised delta to first order in delta
    assert r.speed_fluctuation == pytest.approx(0.02, abs=0.02**2)
    d = r.to_dict()
    for key in (
        "torque_nonuniformity",
        "excess_work_J",
        "excess_work_coefficient",
        "required_inertia_kgm2",
        "flywheel_inertia_kgm2",
        "gd2_Nm2",
        "speed_fluctuation",
    ):
        assert isinstance(d[key], float), key


def test_seed_shortcut_beside_the_exact_sizing():
    """Seed 000 section 2.4: the flywheel is usually I_F = (0.8-0.9) I_0. By hand for the
    single-harmonic case above: I_0 = Delta E / (delta w^2) with Delta E = 2 x 800 / 2 = 800 J
    (the swing of 800 sin(2 theta) integrated: 800/2 from crest to trough, twice), and the exact
    I_F = I_0 - 0.1 kg m^2; the shortcut is 0.85 I_0 and the share I_F / I_0."""
    torque = 500.0 + 800.0 * np.sin(2 * THETA)
    inputs = FlywheelInputs(delta=0.02, other_inertia=0.03)
    r = flywheel_analysis(
        THETA, torque, W, FOUR, rotating_inertia=0.05, reciprocating_inertia=0.02, inputs=inputs
    )
    rel = _trapezoid_rel(2)  # the swing on the grid (test_single_harmonic_closed_form)
    i0 = 800.0 / (0.02 * W**2)
    assert r.required_inertia == pytest.approx(i0, rel=rel)
    figures = {f.key: f for f in r.key_figures()}
    shortcut = figures["shortcut_flywheel_inertia_kgm2"]
    assert shortcut.value == pytest.approx(0.85 * i0, rel=rel)
    assert shortcut.where.startswith("range ")
    assert figures["flywheel_share"].value == pytest.approx((i0 - 0.1) / i0, rel=rel)
    assert "flywheel_share" in r.to_dict()
    given = flywheel_analysis(
        THETA,
        torque,
        W,
        FOUR,
        rotating_inertia=0.05,
        reciprocating_inertia=0.02,
        inputs=FlywheelInputs(inertia=0.4),
    )
    assert "shortcut_flywheel_inertia_kgm2" not in {f.key for f in given.key_figures()}


def test_no_flywheel_needed():
    torque = 500.0 + 10.0 * np.sin(6 * THETA)
    r = flywheel_analysis(THETA, torque, W, FOUR, rotating_inertia=1.0, delta=0.01)
    assert r.flywheel_inertia == 0.0 and r.gd2 == 0.0
    assert r.speed_fluctuation < 0.01
    assert any("no flywheel needed" in n for n in r.notes)


def test_given_flywheel_gives_its_delta():
    torque = 500.0 + 800.0 * np.sin(2 * THETA)
    r = flywheel_analysis(THETA, torque, W, FOUR, inertia=2.0)
    assert r.required_inertia is None
    assert r.speed_fluctuation_linear == pytest.approx(r.excess_work / (2.0 * W * W))


def test_instantaneous_speed_energy_identity_and_mean():
    """(1/2) I (w^2 - w_0^2) = W(theta) at every point, and the time-mean speed is w_m."""
    torque = 400.0 + 1500.0 * np.sin(2 * THETA + 1.0)
    ew = excess_work(THETA, torque, FOUR)
    inertia = 0.15
    w = instantaneous_speed(ew.angle, ew.work, FOUR, inertia, W)
    energy = 0.5 * inertia * w**2 - ew.work
    np.testing.assert_allclose(energy, energy[0], rtol=1e-12)
    h = np.diff(np.append(ew.angle, FOUR))
    w_mid = np.sqrt(w[0] ** 2 + 2 * ((ew.work + np.roll(ew.work, -1)) / 2 - ew.work[0]) / inertia)
    assert FOUR / np.sum(h / w_mid) == pytest.approx(W, rel=1e-12)
    with pytest.raises(InputError, match="would stop"):
        instantaneous_speed(ew.angle, ew.work, FOUR, 1e-4, W)


def test_rim_and_disc_sizing():
    """I = pi rho b (D1^4 - D2^4) / 32, checked by integrating r^2 dm over the rim."""
    rho, d1, d2, inertia = 7200.0, 0.4, 0.3, 1.7
    b = rim_width(inertia, rho, d1, d2)
    r = np.linspace(d2 / 2, d1 / 2, 200001)
    integrand = r**2 * rho * b * 2 * math.pi * r
    by_integral = np.sum((integrand[1:] + integrand[:-1]) / 2 * np.diff(r))
    assert by_integral == pytest.approx(inertia, rel=1e-9)
    torque = 500.0 + 800.0 * np.sin(2 * THETA)
    inputs = FlywheelInputs(delta=0.01, density=rho, max_diameter=d1, inner_diameter=d2)
    res = flywheel_analysis(THETA, torque, W, FOUR, inputs=inputs)
    assert res.rim_width == pytest.approx(rim_width(res.flywheel_inertia, rho, d1, d2))
    assert res.disc_width == pytest.approx(rim_width(res.flywheel_inertia, rho, d1))
    assert res.disc_mass == pytest.approx(rho * res.disc_width * math.pi * d1**2 / 4)
    # GD^2 = pi rho g b (D1^4 - D2^4) / 8 (seed 000 2.4)
    assert res.gd2 == pytest.approx(math.pi * rho * G * res.rim_width * (d1**4 - d2**4) / 8)
    assert res.rim_speed == pytest.approx(W * d1 / 2)
    assert res.hoop_stress == pytest.approx(rho * (W * d1 / 2) ** 2)


def test_crank_train_inertia_seed_formula():
    e = Engine.example("vaz2108")
    rot, rec = crank_train_inertia(e.masses, e.geometry, e.cylinders.throws)
    m = e.masses
    l_len, r = e.geometry.rod_length, e.geometry.crank_radius
    m_cb = m.rod * (l_len - m.rod_cg_from_big_end) / l_len
    m_ca = m.rod - m_cb
    assert rot == pytest.approx(4 * (m.crank_unbalance + m_cb) * r * r)
    assert rec == pytest.approx(4 * (m.piston_group + m_ca) * r * r / 2)


def test_engine_flywheel_uses_the_engine_torque():
    from crankdyn.engine.torque import engine_torque

    e = Engine.example("inline6-diesel")
    t = engine_torque(e, e.speed, step=math.radians(0.5))
    r = engine_flywheel(e, e.speed, delta=0.01, torque=t)
    assert r.mean_torque == pytest.approx(t.mean_torque, rel=1e-4)
    assert r.max_torque == pytest.approx(t.max_torque)
    assert r.speed_fluctuation == pytest.approx(0.01, abs=1e-4)


FILE = """
name = "single"
[geometry]
bore = "72 mm"
stroke = "61.2 mm"
rod_length = "110 mm"
[masses]
reciprocating = "0.3 kg"
rotating = "0.35 kg"
[flywheel]
delta = 0.02
other_inertia = "0.004 kg*m^2"
density = "7850 kg/m^3"
max_diameter = "200 mm"
inner_diameter = "150 mm"
[operating]
speed = "3000 rpm"
"""


def test_flywheel_table_in_the_engine_file(write):
    e = load_engine(write("e.toml", FILE))
    assert e.flywheel == FlywheelInputs(
        delta=0.02, other_inertia=0.004, density=7850.0, max_diameter=0.2, inner_diameter=0.15
    )
    r = engine_flywheel(e, e.speed)
    assert r.target_delta == 0.02 and r.rim_width > 0 and r.other_inertia == 0.004


@pytest.mark.parametrize(
    ("old", "new", "fragment"),
    [
        ("delta = 0.02", "delta = 2.0", "small fraction"),
        ("delta = 0.02", "delta = -0.02", "must be positive"),
        ('inner_diameter = "150 mm"', 'inner_diameter = "250 mm"', "smaller than max_diameter"),
        ('density = "7850 kg/m^3"', 'density = "7850 kg"', "expected a density"),
        ('other_inertia = "0.004 kg*m^2"', 'other_inertia = "-1 kg*m^2"', "must not be negative"),
        ("delta = 0.02", "delt = 0.02", "unknown key"),
    ],
)
def test_flywheel_file_errors(write, old, new, fragment):
    with pytest.raises(InputError) as info:
        load_engine(write("e.toml", FILE.replace(old, new)))
    assert fragment in str(info.value) and "[flywheel]" in str(info.value)


def test_flywheel_bad_input():
    torque = 500.0 + 800.0 * np.sin(2 * THETA)
    with pytest.raises(InputError, match="give a target"):
        flywheel_analysis(THETA, torque, W, FOUR)
    with pytest.raises(InputError, match="speed"):
        flywheel_analysis(THETA, torque, 0.0, FOUR, delta=0.01)
    with pytest.raises(InputError, match="within one cycle"):
        flywheel_analysis(THETA * 2, torque, W, FOUR, delta=0.01)
    with pytest.raises(InputError, match="matching"):
        flywheel_analysis(THETA, torque[:-3], W, FOUR, delta=0.01)
    with pytest.raises(InputError, match="not finite"):
        flywheel_analysis(THETA, np.full_like(THETA, np.nan), W, FOUR, delta=0.01)
    with pytest.raises(InputError, match="masses"):
        engine_flywheel(
            Engine(
                name="x",
                geometry=Engine.example("vaz2108").geometry,
                cylinders=Engine.example("vaz2108").cylinders,
            ),
            W,
            delta=0.01,
        )
