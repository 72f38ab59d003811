"""Multi-stage dampers (seed 003, "装多级扭转减振器的发动机曲轴系统扭振分析": several rubber
stages on one hub, and the resonances they add) against the closed form of a main mass with two
absorbers (J. P. Den Hartog, Mechanical Vibrations, 4th ed. 1956, sec. 3.2, the undamped absorber,
and sec. 3.3, the damped one, extended to two stages on one mass).

Main mass J on a spring k to the ground, stages J_i on complex stiffnesses k_i' = k_i + i (omega
c_i + eta_i k_i) at it. Each stage's equation gives theta_i = k_i' theta / (k_i' - omega^2 J_i), so
the hub's receptance is

    theta / T = 1 / (k - omega^2 J + sum_i k_i' (-omega^2 J_i) / (k_i' - omega^2 J_i)),

and without damping the natural frequencies are the roots in lambda = omega^2 of the cubic
(k + k_1 + k_2 - lambda J)(k_1 - lambda J_1)(k_2 - lambda J_2) - k_1^2 (k_2 - lambda J_2)
- k_2^2 (k_1 - lambda J_1) = 0. The tolerances are round-off (1e-9 relative)."""

import math

import numpy as np
import pytest

from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.dampers import Damper, damper_modes
from crankdyn.torsion.excitation import UniformExcitation
from crankdyn.torsion.sweep import forced_response

J, K = 1.0, 1.0e6  # main system: omega_0 = 1000 rad/s
J1, W1 = 0.05, 1000.0 / 1.05  # stage 1: Den Hartog's tuning 1/(1 + mu) for the main mode
J2, W2 = 0.02, 2600.0  # stage 2: tuned well above, as a second stage for a higher order
K1, K2 = J1 * W1**2, J2 * W2**2


def _model(c1=0.0, c2=0.0, eta=0.0):
    return TorsionModel(
        masses=(Mass("hub", J, cylinders=(1,)),),
        shafts=(Shaft(("ground", "hub"), K),),
        dampers=(
            Damper("stage 1", "hub", J1, stiffness=K1, damping=c1, loss_factor=eta),
            Damper("stage 2", "hub", J2, stiffness=K2, damping=c2, loss_factor=eta),
        ),
    )


def _cubic_roots():
    p = np.poly1d([-J, K + K1 + K2])
    a, b = np.poly1d([-J1, K1]), np.poly1d([-J2, K2])
    cubic = p * a * b - K1**2 * b - K2**2 * a
    return np.sort(np.sqrt(np.real(cubic.roots)))


def test_two_stage_natural_frequencies_and_ring_shares():
    result = damper_modes(_model(), [1.0, 2.0], (100.0, 3000.0))
    omega = np.asarray(result.natural_frequency)
    assert omega == pytest.approx(_cubic_roots(), rel=1e-9)
    # the rings' energy share in each mode, from the closed-form mode shape
    lam = omega**2
    th1, th2 = K1 / (K1 - lam * J1), K2 / (K2 - lam * J2)  # per unit hub angle
    share = (J1 * th1**2 + J2 * th2**2) / (J + J1 * th1**2 + J2 * th2**2)
    assert np.asarray(result.ring_share) == pytest.approx(share, rel=1e-9)
    # stage 1 splits the main mode in two (tuned below it, the ring holds most of the lower
    # one); stage 2 adds a mode of its own far above (the seed's "resonance at another speed, in
    # essence the damper's own natural vibration"), held almost wholly by its ring
    flags = ["yes" if x > 0.5 else "no" for x in share]
    assert [str(d) for d in result.damper_mode] == flags == ["yes", "no", "yes"]
    assert share[2] > 0.9
    roots = _cubic_roots()
    assert result.lowest_damper_mode == pytest.approx(roots[0], rel=1e-9)
    # the critical speeds of the damper modes inside 100-3000 rad/s, orders 1 and 2
    expected = sorted(
        w / q for w in (roots[0], roots[2]) for q in (1.0, 2.0) if 100 <= w / q <= 3000
    )
    speeds = sorted(float(s) for s in result.resonances.speed)
    assert speeds == pytest.approx(expected, rel=1e-9)
    assert result.added_resonances == len(expected) == 4


@pytest.mark.parametrize("eta", [0.0, 0.1])
def test_two_stage_hub_response_against_the_closed_form(eta):
    c1, c2 = 2 * 0.12 * J1 * W1, 2 * 0.05 * J2 * W2
    model = _model(c1, c2, eta)
    torque = 100.0
    excitation = UniformExcitation(torque, [0.0], "two-stroke")
    speeds = np.linspace(600.0, 3000.0, 97)  # order 1: omega = speed
    response = forced_response(model, excitation, speeds, [1.0], resolve=False)
    hub = response.mass_index("hub")
    got = np.abs(response.amplitude[:, 0, hub])
    w = speeds
    k1 = K1 + 1j * (w * c1 + eta * K1)
    k2 = K2 + 1j * (w * c2 + eta * K2)
    dyn = (
        K
        - w**2 * J
        + k1 * (-(w**2) * J1) / (k1 - w**2 * J1)
        + k2 * (-(w**2) * J2) / (k2 - w**2 * J2)
    )
    assert got == pytest.approx(np.abs(torque / dyn), rel=1e-9)


def test_undamped_stage_is_an_antiresonance_of_the_hub():
    # at omega = sqrt(k_2 / J_2) the stage holds the hub still (Den Hartog sec. 3.2)
    model = _model(1e-9, 1e-9)
    excitation = UniformExcitation(100.0, [0.0], "two-stroke")
    response = forced_response(model, excitation, [W2], [1.0], resolve=False)
    static = 100.0 / K
    assert abs(response.amplitude[0, 0, response.mass_index("hub")]) < 1e-9 * static
    assert math.isclose(W2, math.sqrt(K2 / J2))
