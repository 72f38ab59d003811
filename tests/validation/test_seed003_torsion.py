"""Seed 003 (crankshaft torsional vibration): the three-disc example and the V6 engine model.

The three-disc example ("4、三盘解例") gives only the data in the extracted text: three solid
discs of 1 m diameter and 500, 1000, 1500 kg on two shafts of 75 cm length and 12 cm diameter,
G = 8e9 N/m^2 as printed (steel's G is about ten times that; the test keeps the seed's value).
The seed's frequencies are not printed in the text, so the reference is the seed's own frequency
equation (eq. 4-13 and the equation after it) evaluated on those data, solved here by numpy's
polynomial roots, independently of crankdyn's closed forms.
"""

import math

import numpy as np
import pytest

from crankdyn.torsion import TorsionModel
from crankdyn.torsion.modal import natural_modes

SOLVERS = ("eigen", "holzer", "transfer", "closed-form")


def test_seed003_three_disc_data():
    model = TorsionModel.example("seed003-three-disc")
    assert [m.inertia for m in model.masses] == pytest.approx(
        [m * 1.0**2 / 8 for m in (500.0, 1000.0, 1500.0)], rel=1e-15
    )
    k = 8e9 * math.pi * 0.12**4 / 32 / 0.75
    assert [s.stiffness for s in model.shafts] == pytest.approx([k, k], rel=1e-14)
    assert model.is_free and model.is_chain


def test_seed003_three_disc_frequencies():
    model = TorsionModel.example("seed003-three-disc")
    (j1, j2, j3), k = (m.inertia for m in model.masses), model.shafts[0].stiffness
    # J1 J2 J3 w^4 - [k J3 (J1 + J2) + k J1 (J2 + J3)] w^2 + k^2 (J1 + J2 + J3) = 0
    lam = np.sort(
        np.roots([j1 * j2 * j3, -(k * j3 * (j1 + j2) + k * j1 * (j2 + j3)), k * k * (j1 + j2 + j3)])
    )
    expected = np.concatenate([[0.0], np.sqrt(lam)])
    for solver in SOLVERS:
        omega = natural_modes(model, solver).natural_frequency
        assert omega[0] == 0.0
        assert omega[1:] == pytest.approx(expected[1:], rel=1e-9), solver
    # the values, for readers: 44.33 and 78.37 rad/s (7.056 and 12.47 Hz)
    assert expected[1:] == pytest.approx([44.335, 78.366], abs=5e-4)


def test_seed003_three_disc_mode_shapes_satisfy_the_equations_of_motion():
    model = TorsionModel.example("seed003-three-disc")
    r = natural_modes(model)
    k, m = model.stiffness_matrix(), model.mass_matrix()
    for w, phi in zip(r.natural_frequency, r.mode_shapes, strict=True):
        assert np.allclose(k @ phi, w**2 * m @ phi, atol=1e-9 * np.max(np.abs(k @ phi)) + 1e-9)


TABLE2_INERTIA = [0.1670, 0.0893, 0.1052, 0.0577, 0.1052, 0.1052, 0.0577, 0.1052, 2.7146]
TABLE2_STIFFNESS = [160e3, 3345.7e3, 2194.1e3, 2194.1e3, 2194.1e3, 2194.1e3, 2194.1e3, 3243.7e3]


def test_seed003_v6_model_is_table2():
    """Yu Xuehua 2008, Table 2 (../shared/reference/README.md), as the built-in model."""
    model = TorsionModel.example("seed003-v6")
    assert [m.inertia for m in model.masses] == pytest.approx(TABLE2_INERTIA, rel=1e-15)
    assert model.chain.stiffness.tolist() == pytest.approx(TABLE2_STIFFNESS, rel=1e-15)
    assert model.shafts[0].damping == 70.0  # Cd
    assert [m.damping for m in model.masses] == [0.0, 0.0] + [4.5] * 6 + [0.0]  # Ce
    assert [m.cylinders for m in model.masses[2:8]] == [(i,) for i in range(1, 7)]


def test_seed003_v6_solvers_agree():
    model = TorsionModel.example("seed003-v6")
    base = natural_modes(model).natural_frequency
    for solver in ("holzer", "transfer"):
        other = natural_modes(model, solver).natural_frequency
        assert other[0] == base[0] == 0.0
        assert other[1:] == pytest.approx(base[1:], rel=1e-9)


def test_seed003_v6_fig7_two_resonances_below_400_hz():
    """The paper's Fig. 7 ("曲轴系统扭转振动的共振频率") shows the first and second modes on a
    0-400 Hz axis; the model of its Table 2 has exactly two elastic modes there. (The figure's
    values are not printed, so this checks only that range.)"""
    r = natural_modes(TorsionModel.example("seed003-v6"))
    elastic = r.frequencies_hz[1:]
    assert np.sum(elastic < 400.0) == 2
