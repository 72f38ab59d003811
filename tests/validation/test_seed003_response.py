"""Seed 003 (crankshaft torsional vibration): damped forced response.

- Single mass, "单质量有阻尼强迫扭转振动": J phi'' + C phi' + k phi = M sin(p t), i.e.
  phi'' + 2 n phi' + w^2 phi = h sin(p t) with 2n = C/J, w^2 = k/J, h = M/J, has the steady state
  B sin(p t - psi), B = h / sqrt((w^2 - p^2)^2 + 4 n^2 p^2), tan psi = 2 n p / (w^2 - p^2)
  (the seed's formulas, garbled in the extracted text, rederived), and B / B0 =
  1 / sqrt((1 - (p/w)^2)^2 + (2 zeta p/w)^2) with B0 = h / w^2.
- The V6 engine of Yu Xuehua (2008), Table 2: the dynamic-stiffness method of the paper (its
  eqs. 2 and 6, {T}_n = [K(n w)] {theta}_n, matrix entries K11 = -w^2 Jd + Kd + j w Cd, ...)
  assembled here by hand from the table and solved densely, against crankdyn's chain solver, at
  the orders the paper computes (1.5, 3, 4.5 and 6) between 1000 and 2000 rpm, with the
  relative angle pulley - flywheel (the paper's criterion). The paper prints no numbers for its
  curves (Figs. 5, 6), so the reference is its own method on its own data.
"""

import math

import numpy as np
import pytest

from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.excitation import UniformExcitation
from crankdyn.torsion.sweep import forced_response

J, K, C, T = 0.8, 2.0e5, 40.0, 150.0


def _single():
    return TorsionModel(
        masses=(Mass("disc", J, damping=C, cylinders=(1,)),),
        shafts=(Shaft(("ground", "disc"), K),),
    )


@pytest.mark.parametrize("ratio", [0.2, 0.7, 0.95, 1.0, 1.05, 1.6, 3.0])
def test_seed003_single_mass_amplitude_and_phase(ratio):
    w = math.sqrt(K / J)
    p = ratio * w
    n, h = C / (2 * J), T / J
    amplitude = h / math.sqrt((w * w - p * p) ** 2 + 4 * n * n * p * p)
    lag = math.atan2(2 * n * p, w * w - p * p)
    # order 1 at speed p: the response to T cos(p t) is B cos(p t - psi)
    r = forced_response(_single(), UniformExcitation(T, [0.0], "two-stroke"), [p], [1.0])
    x = r.mass_response[0, 0, 0]
    assert abs(x) == pytest.approx(amplitude, rel=1e-12)
    assert -np.angle(x) == pytest.approx(lag, abs=1e-12)
    zeta = C / (2 * math.sqrt(K * J))
    b0 = h / (w * w)
    assert abs(x) / b0 == pytest.approx(
        1 / math.sqrt((1 - ratio**2) ** 2 + (2 * zeta * ratio) ** 2), rel=1e-12
    )


TABLE2 = {
    "J": [0.1670, 0.0893, 0.1052, 0.0577, 0.1052, 0.1052, 0.0577, 0.1052, 2.7146],
    "K": [160e3, 3345.7e3, 2194.1e3, 2194.1e3, 2194.1e3, 2194.1e3, 2194.1e3, 3243.7e3],
    "Cd": 70.0,
    "Ce": 4.5,
}


def _paper_matrix(w):
    """Eq. 2 of the paper: the 9 x 9 dynamic stiffness at w, from Table 2 by hand."""
    j, k = TABLE2["J"], TABLE2["K"]
    d = np.zeros((9, 9), dtype=complex)
    links = [k[0] + 1j * w * TABLE2["Cd"], *k[1:]]
    for i, kk in enumerate(links):
        d[i, i] += kk
        d[i + 1, i + 1] += kk
        d[i, i + 1] -= kk
        d[i + 1, i] -= kk
    for i in range(9):
        d[i, i] -= w * w * j[i]
    for i in range(2, 8):
        d[i, i] += 1j * w * TABLE2["Ce"]
    return d


@pytest.mark.parametrize("order", [1.5, 3.0, 4.5, 6.0])
def test_seed003_v6_dynamic_stiffness_orders(order):
    model = TorsionModel.example("seed003-v6")
    speeds = np.linspace(1000.0, 2000.0, 41) * math.pi / 30
    angles = np.radians([0, 120, 240, 360, 480, 600])  # an even-firing V6, for the test
    ex = UniformExcitation(1.0, angles)
    r = forced_response(model, ex, speeds, [order], resolve=False)  # the paper's method, on a grid
    rel = r.relative_angle("pulley", "flywheel")
    t = np.zeros(9, dtype=complex)
    t[2:8] = np.exp(-1j * order * angles)
    for s, omega in enumerate(speeds):
        theta = np.linalg.solve(_paper_matrix(order * omega), t)
        assert r.mass_response[s, 0] == pytest.approx(theta, rel=1e-10, abs=1e-14)
        assert rel.amplitude[s, 0] == pytest.approx(abs(theta[1] - theta[8]), rel=1e-10)
        # eq. 6: {T}_n = [K(n w)] {theta}_n
        assert _paper_matrix(order * omega) @ r.mass_response[s, 0] == pytest.approx(t, abs=1e-9)


def test_seed003_v6_relative_angle_peaks_at_critical_speeds():
    """The relative angle pulley - flywheel of an order peaks where the order meets a natural
    frequency (within the damping's shift)."""
    from crankdyn.torsion.modal import natural_modes

    model = TorsionModel.example("seed003-v6")
    f = natural_modes(model).natural_frequency[1]  # the first elastic mode (rad/s)
    order = 6.0
    critical = f / order * 30 / math.pi
    speeds = np.arange(critical - 200, critical + 200, 2.0) * math.pi / 30
    r = forced_response(model, UniformExcitation(1.0, np.zeros(6)), speeds, [order])
    peak = r.relative_angle("pulley", "flywheel").peak("amplitude", order=order)
    assert peak.speed * 30 / math.pi == pytest.approx(critical, rel=0.01)
