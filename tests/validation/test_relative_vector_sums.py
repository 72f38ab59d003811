"""Relative vector sums of an in-line six, four-stroke, firing 1-5-3-6-2-4, worked by hand
(Ker Wilson, *Practical Solution of Torsional Vibration Problems*, vol. 2; Nestorides, *A
Handbook on Torsional Vibration*, BICERA 1958, ch. 7: R_q = |sum_k beta_k exp(i q Phi_k)|).

The model is six equal cylinder masses J on five equal shafts k, free at both ends. Its mode
shapes are known in closed form (the uniform free-free chain: phi_j = cos((j - 1/2) r pi / N),
j = 1..N, omega_r^2 = 4 k/J sin^2(r pi / 2N)), so the relative amplitudes beta are
independent of the eigen-solver. Mode 1, normalised to the largest cylinder amplitude 1:

    beta = cos(15, 45, 75, 105, 135, 165 deg) / cos 15 deg
         = 1, sqrt(3) - 1, 2 - sqrt(3), -(2 - sqrt(3)), -(sqrt(3) - 1), -1
         = 1, 0.73205, 0.26795, -0.26795, -0.73205, -1.

Firing 1-5-3-6-2-4 every 120 deg: Phi = 0 (cyl 1), 480 (2), 240 (3), 600 (4), 120 (5), 360 (6).

- Order 1.5: 1.5 Phi = 0, 720, 360, 900, 180, 540 deg: cylinders 1-3 in phase, 4-6 opposite:
  R = b1 + b2 + b3 - b4 - b5 - b6 = 2 (1 + 0.73205 + 0.26795) = 4.
- Order 3 (major): every 3 Phi a multiple of 360 deg: R = |sum beta| = 0 (the mode is
  antisymmetric).
- Order 0.5: 0.5 Phi = 0, 240, 120, 300, 60, 180 deg:
  Re = 1 - 0.5 (0.73205) - 0.5 (0.26795) - 0.5 (0.26795) - 0.5 (0.73205) + 1 = 1,
  Im = (sqrt 3 / 2)(-0.73205 + 0.26795 + 0.26795 - 0.73205) = -0.80385,
  R = sqrt(1 + 0.64617) = 1.2830.
- Order 1: Phi modulo 360 = 0, 120, 240, 240, 120, 0 deg:
  Re = 1 - 0.5 (0.73205) - 0.5 (0.26795) + 0.5 (0.26795) + 0.5 (0.73205) - 1 = 0,
  Im = (sqrt 3 / 2)(0.73205 - 0.26795 + 0.26795 - 0.73205) = 0: R = 0.

The printed digits are five significant: tolerance 5e-5 absolute on sums of order 1.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.modal import natural_modes
from crankdyn.torsion.mode_table import mode_table

FIRING = np.radians([0.0, 480.0, 240.0, 600.0, 120.0, 360.0])  # 1-5-3-6-2-4, cylinders 1..6
J, K = 20.0, 80e6  # kg m^2, N m/rad


@pytest.fixture(scope="module")
def table():
    masses = tuple(Mass(f"throw {i}", J, cylinders=(i,)) for i in range(1, 7))
    shafts = tuple(Shaft((f"throw {i}", f"throw {i + 1}"), K) for i in range(1, 6))
    model = TorsionModel(masses, shafts, name="uniform in-line six")
    return mode_table(natural_modes(model), model, [0.5, 1.0, 1.5, 3.0], FIRING)


def test_mode_1_relative_amplitudes_are_the_closed_form(table):
    r3 = math.sqrt(3.0)
    want = [1.0, r3 - 1.0, 2.0 - r3, r3 - 2.0, 1.0 - r3, -1.0]
    assert table.cylinder_amplitudes[0] == pytest.approx(want, abs=5e-6)
    # omega_1^2 = 4 k / J sin^2(pi / 12)
    assert table.natural_frequency[0] == pytest.approx(
        2.0 * math.sqrt(K / J) * math.sin(math.pi / 12.0), rel=1e-9
    )


def test_mode_1_vector_sums_by_hand(table):
    sums = dict(zip(table.orders.tolist(), table.vector_sums[0].tolist(), strict=True))
    assert sums[1.5] == pytest.approx(4.0, abs=5e-5)
    assert sums[3.0] == pytest.approx(0.0, abs=5e-5)
    assert sums[0.5] == pytest.approx(1.2830, abs=5e-5)
    assert sums[1.0] == pytest.approx(0.0, abs=5e-5)
    assert table.major.tolist() == [False, False, False, True]


def test_the_table_reports_them(table):
    tables = {t.key: t for t in table.summary().tables}
    header, rows = tables["relative_vector_sums"].cells()
    assert header[:3] == [
        "Order",
        "Major",
        f"Mode 1, {table.natural_frequency[0] / 2 / math.pi:.4g} Hz",
    ]
    row = next(r for r in rows if r[0] == "1.5")
    assert float(row[2]) == pytest.approx(4.0, abs=5e-5)
    figure = table.summary().figure("max_relative_vector_sum_mode_1")
    assert figure.value == pytest.approx(4.0, abs=5e-5) and figure.where == "order 1.5, mode 1"
    shapes = tables["mode_shapes"]
    assert [r[0] for r in shapes.rows] == [*(f"throw {i}" for i in range(1, 7)), "Nodes"]
    assert "throw 3 - throw 4 at 0.500" in shapes.rows[-1][1]
