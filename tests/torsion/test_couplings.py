"""Elastic couplings from catalogue data: psi and the loss factor, the resonance factor,
stiffness tables against the mean torque (and the load-dependent forced response), temperature
factors, the permissible torques kept for the rule checks, and catalogue-range errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.io.torsion_file import parse_torsion_model
from crankdyn.torsion import Coupling, Mass, Shaft, TorsionModel
from crankdyn.torsion.coupling import loss_factor_from_psi, psi_from_damping_ratio
from crankdyn.torsion.excitation import UniformExcitation, excitation_for
from crankdyn.torsion.loaded import model_at_speed
from crankdyn.torsion.sources import LoadLaw, propeller
from crankdyn.torsion.sweep import forced_response


def test_psi_is_two_pi_times_the_loss_factor():
    """psi = A_D / A_el = 2 pi eta (DIN 740-2; Renold: psi = 2 pi / M, M = 1 / tan delta)."""
    assert loss_factor_from_psi(2 * math.pi * 0.17) == pytest.approx(0.17, rel=1e-15)
    assert psi_from_damping_ratio(0.05) == pytest.approx(4 * math.pi * 0.05, rel=1e-15)
    c = Coupling(stiffness=2e5, relative_damping=1.13)
    assert c.loss_factor == pytest.approx(1.13 / (2 * math.pi), rel=1e-15)
    assert c.resonance_factor == pytest.approx(2 * math.pi / 1.13, rel=1e-15)


def test_damping_work_per_cycle_is_psi_times_the_strain_energy():
    """A hysteretic coupling twisted theta sin(omega t) dissipates pi eta C theta^2 per cycle,
    psi times the strain energy C theta^2 / 2: the definition psi = A_D / A_el, checked by
    integrating the damping torque over a cycle."""
    c = Coupling(stiffness=3e5, relative_damping=0.9)
    k, eta, theta = c.model_stiffness, c.loss_factor, 0.004
    t = np.linspace(0.0, 2 * math.pi, 200_001)
    rate = theta * np.cos(t)  # d(twist)/d(omega t)
    damping_torque = eta * k * theta * np.cos(t)  # eta k x twist, a quarter period ahead
    work = np.trapezoid(damping_torque * rate, t)
    assert work / (0.5 * k * theta**2) == pytest.approx(c.psi, rel=1e-8)


def test_single_mass_on_a_coupling_resonates_at_the_catalogues_resonance_factor():
    """One mass on a coupling to ground, excited at its natural frequency: the angle is
    V_R = 2 pi / psi times the static twist T/C (the catalogues' resonance factor)."""
    coupling = Coupling(stiffness=2.4e5, relative_damping=1.13)
    j = 6.0
    model = TorsionModel(
        masses=(Mass("hub", j, cylinders=(1,)),),
        shafts=(Shaft(("ground", "hub"), coupling=coupling),),
    )
    wn = math.sqrt(coupling.model_stiffness / j)
    r = forced_response(model, UniformExcitation(100.0, [0.0], "two-stroke"), [wn], [1.0])
    static = 100.0 / coupling.model_stiffness
    assert r.amplitude[0, 0, 0] / static == pytest.approx(coupling.resonance_factor, rel=1e-12)


def test_stiffness_table_temperature_factor_and_model_torque():
    c = Coupling(
        table_torque=[0.0, 10e3, 20e3],
        table_stiffness=[1e5, 2e5, 2.5e5],
        relative_damping=1.0,
        temperature_factor=0.8,
        damping_temperature_factor=0.9,
        nominal_torque=20e3,
        maximum_torque=50e3,
        vibratory_torque=5e3,
        power_loss=800.0,
    )
    assert c.load_dependent
    assert c.model_torque == 20e3  # T_KN by default
    assert c.model_stiffness == pytest.approx(2.5e5 * 0.8)
    assert c.stiffness_at([5e3, -15e3]) == pytest.approx([1.5e5 * 0.8, 2.25e5 * 0.8])
    assert c.psi == pytest.approx(0.9)
    assert c.limits() == {
        "nominal_torque_Nm": 20e3,
        "maximum_torque_Nm": 50e3,
        "vibratory_torque_Nm": 5e3,
        "maximum_torque_1_Nm": None,
        "maximum_torque_2_Nm": None,
        "power_loss_W": 800.0,
    }
    with pytest.raises(InputError, match="outside the coupling's stiffness table"):
        c.stiffness_at([25e3])


@pytest.mark.parametrize(
    ("kwargs", "key", "text"),
    [
        ({"stiffness": 1e5, "relative_damping": 7.0}, "relative_damping", "between 0 and 2 pi"),
        ({"stiffness": 1e5, "damping_ratio": 0.7}, "damping_ratio", "between 0 and 0.5"),
        ({"stiffness": 1e5}, "relative_damping", "missing"),
        (
            {"stiffness": 1e5, "relative_damping": 1.0, "damping_ratio": 0.1},
            "damping_ratio",
            "not both",
        ),
        (
            {
                "stiffness": 1e5,
                "relative_damping": 1,
                "nominal_torque": 10e3,
                "maximum_torque": 5e3,
            },
            "maximum_torque",
            "below the nominal torque",
        ),
        (
            {
                "stiffness": 1e5,
                "relative_damping": 1,
                "nominal_torque": 10e3,
                "vibratory_torque": 20e3,
            },
            "vibratory_torque",
            "out of any catalogue's range",
        ),
        (
            {
                "table_torque": [0, 60e3],
                "table_stiffness": [1e5, 2e5],
                "relative_damping": 1,
                "maximum_torque": 50e3,
            },
            "stiffness_table_torque",
            "beyond the maximum torque",
        ),
        (
            {
                "table_torque": [0, 5e3],
                "table_stiffness": [1e5, 2e5],
                "relative_damping": 1,
                "reference_torque": 8e3,
            },
            "reference_torque",
            "outside the coupling's stiffness table",
        ),
        (
            {"table_torque": [5e3, 0.0], "table_stiffness": [1e5, 2e5], "relative_damping": 1},
            "stiffness_table_torque",
            "increase strictly",
        ),
    ],
)
def test_catalogue_range_errors(kwargs, key, text):
    with pytest.raises(InputError, match=text) as info:
        Coupling(**kwargs)
    assert info.value.key == key
    assert "\n" not in str(info.value)


COUPLED = """
name = "coupled"
[[mass]]
name = "engine"
inertia = "40 kg*m^2"
cylinders = [1]
[[mass]]
name = "sec"
inertia = "10 kg*m^2"
[[mass]]
name = "prop"
inertia = "300 kg*m^2"
role = "propeller"
[[shaft]]
between = ["engine", "sec"]
kind = "coupling"
stiffness_table = [
    ["0 kN*m", "60 kN*m/rad"], ["10 kN*m", "90 kN*m/rad"], ["20 kN*m", "110 kN*m/rad"]
]
relative_damping = 1.0
nominal_torque = "20 kN*m"
maximum_torque = "50 kN*m"
vibratory_torque = "5 kN*m"
power_loss = "1 kW"
[[shaft]]
between = ["sec", "prop"]
stiffness = "2 MN*m/rad"
[[excitation.propeller]]
at = "prop"
blades = 3
fractions = [0.05]
mean_torque = "18 kN*m"
speed = "600 rpm"
"""


def test_load_dependent_coupling_in_the_forced_response():
    """At every speed the coupling takes the stiffness of that speed's mean torque (propeller
    law): the response at each speed equals the response of the model evaluated at that speed
    (model_at_speed, then the ordinary chain solver)."""
    model = parse_torsion_model(__import__("tomllib").loads(COUPLED), file="c.toml")
    assert model.shafts[0].kind == "coupling"
    assert model.shafts[0].stiffness == pytest.approx(1.1e5)  # at T_KN
    ex = excitation_for(model)
    speeds = np.array([200.0, 400.0, 590.0]) / RPM
    orders = [1.0, 3.0]
    r = forced_response(model, ex, speeds, orders, resolve=False)
    for s, w in enumerate(speeds):
        at = model_at_speed(model, w)
        q = 18e3 * (w * RPM / 600.0) ** 2
        assert at.shafts[0].stiffness == pytest.approx(at.shafts[0].coupling.stiffness_at(q)[()])
        one = forced_response(at, ex, [w], orders)
        assert r.mass_response[s] == pytest.approx(one.mass_response[0], rel=1e-9, abs=1e-18)
        assert r.shaft_response[s] == pytest.approx(one.shaft_response[0], rel=1e-9, abs=1e-12)


def test_mean_torque_beyond_the_table_is_refused_with_the_speed():
    text = COUPLED.replace('mean_torque = "18 kN*m"', 'mean_torque = "30 kN*m"')
    model = parse_torsion_model(__import__("tomllib").loads(text), file="c.toml")
    with pytest.raises(InputError, match="outside its stiffness table") as info:
        forced_response(model, excitation_for(model), [600.0 / RPM], [1.0])
    assert "600 rpm" in str(info.value)


def test_propeller_source_fraction_of_the_propeller_law():
    src = propeller("p", 4, fractions=[0.1, 0.02], load=LoadLaw(1000.0, 10.0, 2.0))
    c = src.coefficients([5.0, 10.0])
    assert np.abs(c) == pytest.approx(np.array([[25.0, 5.0], [100.0, 20.0]]))
    assert list(src.orders) == [4.0, 8.0]
