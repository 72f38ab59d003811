"""Dampers (Den Hartog's optima), the M68 limits, critical speeds, and the time domain."""

import dataclasses
import math

import numpy as np
import pytest

from crankdyn.errors import InputError
from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
from crankdyn.torsion.campbell import campbell, with_dampers
from crankdyn.torsion.dampers import (
    Damper,
    design_damper,
    equivalent_single_mass,
    optimum_tuned,
    optimum_viscous,
)
from crankdyn.torsion.excitation import UniformExcitation
from crankdyn.torsion.modal import natural_modes
from crankdyn.torsion.rules import (
    RuleSet,
    ShaftLimit,
    permissible_continuous,
    permissible_transient,
    size_factor,
)
from crankdyn.torsion.sweep import forced_response
from crankdyn.tvc import TvcSpec
from crankdyn.tvc.analysis import judge

J, K = 1.0, 1.0e6  # the main system: one mass on a grounded shaft


def _main():
    return TorsionModel(masses=(Mass("m", J, cylinders=(1,)),), shafts=(Shaft(("ground", "m"), K),))


def _peak(damper, span=(0.6, 1.4)):
    w0 = math.sqrt(K / J)
    w = np.linspace(span[0] * w0, span[1] * w0, 4001)
    r = forced_response(
        _main(), UniformExcitation(1.0, [0.0], "two-stroke"), w, [1.0], dampers=(damper,)
    )
    return np.max(r.amplitude[:, 0, 0]) * K  # magnification x / x_static


def _closed_form_peak(mu: float, f: float, zeta: float, span=(0.3, 1.7)) -> float:
    """The largest magnification x/x_static of an undamped main system with a damped absorber
    (Den Hartog 1956, section 3.9, eq. (3.29)): mass ratio mu, tuning f = omega_a/omega_n,
    damping ratio zeta = c/(2 m_a omega_n), found on a 2e6-point grid of g = omega/omega_n (its
    step, 7e-7, leaves the peak exact to about 1e-12)."""
    g = np.linspace(span[0], span[1], 2_000_001)
    num = (2 * zeta * g) ** 2 + (g * g - f * f) ** 2
    den = (2 * zeta * g) ** 2 * (g * g - 1 + mu * g * g) ** 2 + (
        mu * f * f * g * g - (g * g - 1) * (g * g - f * f)
    ) ** 2
    return float(np.max(np.sqrt(num / den)))


# The response sweeps of _peak take 4001 speeds over 0.8 (tuned) or 1.2 (viscous) times the
# natural frequency: next to a peak of these widths the sampled maximum is below the true one by
# less than 1e-6 of it, hence rel=1e-5 against the closed form.
SWEEP = 1e-5


@pytest.mark.parametrize("mu", [0.05, 0.2])
def test_den_hartog_tuned_optimum(mu):
    """Den Hartog's optimum (section 3.9): tuning 1/(1 + mu) and (c/c_c)^2 = 3 mu/(8 (1 + mu)^3).
    The response equals the closed form's; its peak lies just above the height of the two fixed
    points, sqrt(1 + 2/mu), because the optimum damping averages the two conditions that would
    each make the curve flat at one fixed point: by the closed form 0.08 % above at mu = 0.05 and
    0.33 % at mu = 0.2 (less than 0.4 %). Damping off the optimum raises the peak."""
    design = design_damper(_main(), "m", 1, mu * J, "tuned")
    assert design.tuning_ratio == pytest.approx(1 / (1 + mu), rel=1e-15)
    assert design.damping_ratio == pytest.approx(math.sqrt(3 * mu / (8 * (1 + mu) ** 3)), rel=1e-15)
    peak = _peak(design.damper())
    exact = _closed_form_peak(mu, 1 / (1 + mu), design.damping_ratio)
    assert peak == pytest.approx(exact, rel=SWEEP)
    fixed = math.sqrt(1 + 2 / mu)
    assert fixed < exact < fixed * 1.004
    for f in (0.7, 1.4):
        other = Damper("d", "m", mu * J, design.stiffness, f * design.damping)
        assert _peak(other) > peak


@pytest.mark.parametrize("mu", [0.1, 0.5])
def test_den_hartog_viscous_optimum(mu):
    """Untuned viscous damper (Den Hartog 1956, section 3.10): the optimum c makes the curve
    flat at its fixed point, so the peak is the fixed point's height 1 + 2/mu exactly (the
    closed form gives it to 1e-11); the sweep finds it to its sampling, rel=1e-5."""
    design = design_damper(_main(), "m", 1, mu * J, "viscous")
    assert design.stiffness == 0.0
    peak = _peak(design.damper(), (0.3, 1.5))
    assert _closed_form_peak(mu, 0.0, design.damping_ratio) == pytest.approx(1 + 2 / mu, rel=1e-9)
    assert peak == pytest.approx(1 + 2 / mu, rel=SWEEP)
    for f in (0.6, 1.6):
        other = Damper("d", "m", mu * J, 0.0, f * design.damping)
        assert _peak(other, (0.3, 1.5)) > peak * 0.999
    ratio, zeta, _ = optimum_viscous(mu)
    assert ratio == pytest.approx(math.sqrt(2 / (2 + mu)))
    assert zeta == pytest.approx(1 / math.sqrt(2 * (1 + mu) * (2 + mu)))
    assert optimum_tuned(mu)[2] == pytest.approx(math.sqrt(1 + 2 / mu))


def test_equivalent_single_mass_of_a_two_mass_system():
    """Two free masses: mode 1 (the elastic mode; the rigid-body mode is 0) seen at mass 1 has
    J_e = J1 + J2 (J1/J2)^2."""
    model = TorsionModel.chain_of([2.0, 0.5], [1e5])
    j_e, omega = equivalent_single_mass(model, "1", 1)
    assert j_e == pytest.approx(2.0 + 0.5 * (2.0 / 0.5) ** 2)
    assert omega == pytest.approx(math.sqrt(1e5 * 2.5 / 1.0))
    with pytest.raises(InputError, match="rigid-body mode"):
        equivalent_single_mass(model, "1", 0)
    with pytest.raises(InputError, match="modes 1 to 1"):
        equivalent_single_mass(model, "1", 2)


def test_damper_validation():
    with pytest.raises(InputError, match="needs damping"):
        Damper("d", "m", 0.1)
    with pytest.raises(InputError, match='no mass named "pully"'):
        TorsionModel(masses=(Mass("pulley", 1.0),), dampers=(Damper("d", "pully", 0.1, damping=1),))


def test_tuned_damper_in_the_natural_frequencies():
    base = TorsionModel.example("seed003-v6")
    model = TorsionModel(masses=base.masses[1:], shafts=base.shafts[1:])
    ring = Damper("damper ring", "pulley", 0.1670, 160e3, 70.0)
    full = with_dampers(dataclasses.replace(model, dampers=(ring,)))
    assert natural_modes(full).natural_frequency == pytest.approx(
        natural_modes(base).natural_frequency, rel=1e-9, abs=1e-6
    )


def test_m68_formulas_by_hand():
    """sigma_B = 600 N/mm^2, d = 200 mm, C_K = 1: C_D = 0.35 + 0.93 * 200^-0.2 = 0.6190...,
    tau_C(0.5) = 760/18 * C_D * 2.5, tau_C(1.0) = 760/18 * C_D * 1.38, tau_T = 1.7 tau_C."""
    c_d = 0.35 + 0.93 * 200**-0.2
    assert size_factor(0.2) == pytest.approx(c_d)
    tau = permissible_continuous(np.array([0.5, 0.95, 1.0, 1.1]), 600e6, 1.0, 0.2)
    assert tau[0] == pytest.approx(760 / 18 * c_d * 2.5 * 1e6)
    assert tau[1] == tau[2] == pytest.approx(760 / 18 * c_d * 1.38 * 1e6)
    assert math.isnan(tau[3])
    t = permissible_transient(np.array([0.5, 0.85]), tau[:2], 0.6)
    assert t[0] == pytest.approx(1.7 * tau[0] / math.sqrt(0.6))
    assert math.isnan(t[1])
    with pytest.raises(InputError, match="0 < C_K <= 1"):
        ShaftLimit(("a", "b"), 600e6, 1.2)


@pytest.mark.parametrize(("torque", "permitted"), [(60.0, True), (100.0, False)])
def test_rule_check_flags_barred_ranges(torque, permitted):
    """An engine and a propeller on a 60 mm shaft with its order-3 resonance at 598 rpm =
    0.6 n_0: the stress passes tau_C there, a barred range; permitted while the stress stays
    under tau_T, not once it exceeds it."""
    masses = (Mass("engine", 2.0, damping=5.0, cylinders=(1,)), Mass("propeller", 6.0))
    shafts = (Shaft(("engine", "propeller"), 5.3e4, geometry=ShaftGeometry(0.06)),)
    limit = ShaftLimit(("engine", "propeller"), 600e6)
    rules = RuleSet(rated_speed=1000 * math.pi / 30, shafts=(limit,))
    model = TorsionModel(masses=masses, shafts=shafts, rules=rules)
    ex = UniformExcitation(torque, [0.0], "two-stroke")
    w = np.linspace(200, 1050, 400) * math.pi / 30
    r = forced_response(model, ex, w, [3.0])
    verdicts, ranges = judge(model, r, TvcSpec(tachometer_tolerance=0.0))  # as found
    critical = math.sqrt(5.3e4 * 8.0 / 12.0) / 3 * 30 / math.pi  # rpm
    assert len(ranges) == 1
    barred = ranges[0]
    assert barred.start * 30 / math.pi < critical < barred.end * 30 / math.pi
    assert barred.permitted is permitted
    assert all(v.passed for v in verdicts) is permitted
    tau_c = permissible_continuous(r.speed / rules.rated_speed, 600e6, 1.0, 0.06)
    stress = r.synthesized_shaft_stress[:, 0]
    inside = (r.speed >= barred.start) & (r.speed <= barred.end)
    assert np.all(stress[inside] > tau_c[inside])
    assert np.all(stress[~inside] <= tau_c[~inside])


def test_critical_speeds_are_natural_frequency_over_order():
    model = TorsionModel.example("seed003-v6")
    modes = natural_modes(model)
    result = campbell(model, [1.5, 3.0, 4.5, 6.0], (1000 * math.pi / 30, 2000 * math.pi / 30))
    assert result.critical_speeds
    for c in result.critical_speeds:
        assert c.speed == pytest.approx(modes.natural_frequency[modes.index(c.mode)] / c.order)
        assert c.frequency_hz == pytest.approx(c.natural_frequency / (2 * math.pi))
        assert 1000 <= c.speed * 30 / math.pi <= 2000
    speeds = [c.speed for c in result.critical_speeds]
    assert speeds == sorted(speeds)
    d = result.to_dict()["critical_speeds"][0]
    assert set(d) >= {"mode", "order", "speed_rpm", "major"}
    with pytest.raises(InputError, match="no speed range"):
        campbell(model, [3.0])


@pytest.mark.parametrize(
    "settings", [{}, {"method": "DOP853", "rtol": 1e-9, "atol": 1e-13}], ids=["modal", "DOP853"]
)
def test_time_domain_steady_state_matches_the_frequency_domain(settings):
    """Two masses with viscous and hysteretic damping at constant speed: after the transient
    has decayed, the last cycle equals the sum of the orders' steady states (both integrators:
    the modal one and solve_ivp's)."""
    from crankdyn.torsion.transient import transient_response

    model = TorsionModel(
        masses=(Mass("a", 0.4, damping=20.0, cylinders=(1,)), Mass("b", 1.2, damping=5.0)),
        shafts=(Shaft(("a", "b"), 2e5, damping=15.0, loss_factor=0.05),),
    )
    ex = UniformExcitation(50.0, [0.0])
    orders = [0.5, 1.0, 3.0, 4.5]
    w = 1500 * math.pi / 30
    run = transient_response(model, ex, orders, speed=w, cycles=25, **settings)
    steady = forced_response(model, ex, [w], orders, hysteretic_frequency=run.hysteretic_frequency)
    last = run.last_cycle(4 * math.pi)
    phi = run.crank_angle[last]
    expected = np.real(np.exp(1j * np.outer(phi, orders)) @ steady.mass_response[0])
    assert run.angle[last] == pytest.approx(expected, abs=1e-6 * np.abs(expected).max())
    torque = np.real(np.exp(1j * np.outer(phi, orders)) @ steady.shaft_response[0])
    assert run.shaft_torque[last] == pytest.approx(torque, abs=1e-6 * np.abs(torque).max())


def test_damper_modes_command_with_two_stages(cli, tmp_path):
    """Two [[damper]] stages on one hub (a multi-stage damper): the command lists the modes, the
    rings' shares and the damper modes' critical speeds (seed 003)."""
    import json

    text = """
name = "two stages"
[[mass]]
name = "hub"
inertia = "1 kg*m^2"
cylinders = [1]
[[shaft]]
between = ["ground", "hub"]
stiffness = "1e6 N*m/rad"
[[damper]]
name = "stage 1"
at = "hub"
kind = "tuned"
inertia = "0.05 kg*m^2"
stiffness = "45351.47 N*m/rad"
damping = "10 N*m*s/rad"
[[damper]]
name = "stage 2"
at = "hub"
kind = "tuned"
inertia = "0.02 kg*m^2"
stiffness = "135200 N*m/rad"
damping = "5 N*m*s/rad"
[excitation]
cycle = "two-stroke"
torque = "100 N*m"
"""
    path = tmp_path / "two.toml"
    path.write_text(text, encoding="utf-8")
    run = cli("torsion", "damper-modes", path, "--speeds", "1000:30000", "--orders", "1,2",
              "--format", "json")  # fmt: skip
    assert run.status == 0, run
    data = json.loads(run.out)
    assert data["rings"] == ["stage 1", "stage 2"]
    assert len(data["natural_frequency_hz"]) == 3 and data["damper_mode"][-1] == "yes"
    assert data["added_resonances"] == len(data["resonances"]["speed_rpm"]) > 0
    table = cli("torsion", "damper-modes", path, "--speeds", "1000:30000", "--orders", "1,2")
    assert table.status == 0 and "Resonances of the damper modes" in table.out
