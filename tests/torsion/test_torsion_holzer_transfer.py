"""Holzer's table and residual curve; the transfer-matrix method and its damped form."""

import math

import numpy as np
import pytest

from crankdyn.errors import InputError
from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.holzer import holzer_residual, holzer_table, residual_curve
from crankdyn.torsion.modal import natural_modes
from crankdyn.torsion.transfer import chain_transfer_matrix


def model_with_ground():
    inertia = [0.17, 0.09, 0.11, 0.06, 0.11, 2.7]
    stiffness = [1.6e5, 3.3e6, 2.2e6, 2.2e6, 3.2e6]
    return TorsionModel.chain_of(inertia, stiffness, ground_right=5e5)


def test_holzer_table_identities():
    model = model_with_ground()
    omega = 2 * math.pi * 150.0
    t = holzer_table(model, omega)
    lam = omega**2
    J = model.dof_inertia
    assert t.angle[0] == 1.0
    assert np.allclose(t.inertia_omega2, J * lam)
    assert np.allclose(t.inertia_torque, J * lam * t.angle)
    assert np.allclose(t.accumulated_torque, np.cumsum(t.inertia_torque + t.ground_torque))
    assert np.allclose(t.twist[:-1], t.accumulated_torque[:-1] / model.chain.stiffness)
    assert np.allclose(t.angle[1:], t.angle[:-1] - t.twist[:-1])
    assert math.isnan(t.twist[-1]) and math.isnan(t.stiffness[-1])
    assert t.ground_torque[-1] == pytest.approx(-5e5 * t.angle[-1])
    assert t.residual_torque == t.accumulated_torque[-1]


def test_residual_is_the_scaled_frequency_determinant():
    """T_n(omega) = -det(K - omega^2 M) / (k_1 ... k_{n-1}) (the Sturm/Holzer link)."""
    model = model_with_ground()
    omegas = np.array([0.0, 300.0, 1234.5, 5000.0])
    residual = holzer_residual(model, omegas)
    k, m = model.stiffness_matrix(), model.mass_matrix()
    det = np.array([np.linalg.det(k - w**2 * m) for w in omegas])
    expected = -det / np.prod(model.chain.stiffness)
    assert np.allclose(residual, expected, rtol=1e-9)


def test_residual_vanishes_at_the_natural_frequencies():
    model = model_with_ground()
    natural = natural_modes(model).natural_frequency
    for w in natural:
        table = holzer_table(model, w)
        scale = np.max(np.abs(table.inertia_torque))
        assert abs(table.residual_torque) < 1e-8 * scale


def test_residual_curve_changes_sign_at_each_natural_frequency():
    model = TorsionModel.example("seed003-three-disc")
    curve = residual_curve(model)
    f = curve.frequency
    r = curve.residual_torque
    crossings = f[1:][np.sign(r[1:]) * np.sign(r[:-1]) < 0]
    elastic = curve.natural_frequencies[1:]
    assert len(crossings) == len(elastic)
    assert np.allclose(crossings, elastic, rtol=1e-3)
    assert set(curve.to_dict()) == {
        "frequency_hz",
        "residual_torque_Nm_per_rad",
        "natural_frequencies_hz",
        "model",
    }


def test_holzer_rejects_a_negative_frequency():
    with pytest.raises(InputError, match="trial frequency"):
        holzer_table(model_with_ground(), -1.0)


def test_transfer_matrix_is_unimodular_and_matches_holzer():
    model = model_with_ground()
    omegas = np.array([10.0, 400.0, 2500.0])
    u = chain_transfer_matrix(model, omegas)
    assert np.allclose(np.linalg.det(u), 1.0)
    # starting free (theta = 1, T = 0), T_n^R = U_21 is minus Holzer's residual
    assert np.allclose(u[:, 1, 0], -holzer_residual(model, omegas), rtol=1e-10)


def test_damped_transfer_matrix_gives_the_dynamic_compliance():
    """A torque M at the first mass of a damped free chain: theta_1 from the transfer matrix
    (T^L_1 = -M, T^R_n = 0, so theta_1 = U_22 M / U_21) equals the solution of
    (K + iH + i omega C - omega^2 M) theta = M e_1."""
    masses = (
        Mass("a", 0.17, damping=2.0),
        Mass("b", 0.09),
        Mass("c", 0.11, damping=4.5),
        Mass("d", 2.7),
    )
    shafts = (
        Shaft(("a", "b"), 1.6e5, damping=70.0),
        Shaft(("b", "c"), 3.3e6, loss_factor=0.035),
        Shaft(("c", "d"), 2.2e6, loss_factor=0.02, damping=3.0),
    )
    model = TorsionModel(masses=masses, shafts=shafts)
    for w in (120.0, 900.0, 4000.0):
        u = chain_transfer_matrix(model, w, damped=True)
        theta_tm = u[1, 1] / u[1, 0]
        z = (
            model.stiffness_matrix()
            + 1j * model.hysteretic_matrix()
            + 1j * w * model.damping_matrix()
            - w**2 * model.mass_matrix()
        )
        rhs = np.zeros(4, dtype=complex)
        rhs[0] = 1.0
        theta = np.linalg.solve(z, rhs)
        assert theta_tm == pytest.approx(theta[0], rel=1e-10)


def test_holzer_table_refuses_an_overflowing_trial_frequency():
    with pytest.raises(InputError, match="Holzer's table overflows"):
        holzer_table(model_with_ground(), 1e95)
    with pytest.raises(InputError, match="too high"):
        holzer_table(model_with_ground(), 1e150)


def test_residual_of_a_long_chain_may_overflow_quietly():
    model = TorsionModel.chain_of([1.0] * 400, [1.0] * 399)
    curve = residual_curve(model, points=201)
    assert np.isfinite(curve.residual_torque[:10]).all()
    assert curve.to_json()  # infinite values are written as null
