"""The time-domain run in truncated modal coordinates (crankdyn.torsion.modal_run, the default
integrator of crankdyn.torsion.transient): against the closed form of an undamped two-mass
line driven from rest, against scipy's DOP853 on a damped chain in a run-up (all modes, and
modes truncated with the reported error estimate), and its one-line input errors."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.errors import InputError
from crankdyn.torsion import Mass, Shaft, TorsionModel
from crankdyn.torsion.excitation import UniformExcitation
from crankdyn.torsion.modal_run import harmonic_run, truncated_system
from crankdyn.torsion.solvers import linear_system
from crankdyn.torsion.transient import transient_response


def test_two_masses_driven_from_rest_follow_the_closed_form():
    """Free-free masses J_a = 1, J_b = 3 kg m^2 on k = 1e5 N m/rad, T cos(nu t) on a from rest:
    the twist delta = theta_b - theta_a obeys delta'' + omega_n^2 delta = -T cos(nu t) / J_a,
    so delta = -(T / J_a) (cos nu t - cos omega_n t) / (omega_n^2 - nu^2), and the rigid motion
    r = (J_a theta_a + J_b theta_b) / J = T (1 - cos nu t) / (J nu^2) (undamped single-degree
    and rigid-body solutions from rest, e.g. Thomson and Dahl, Theory of Vibration with
    Applications, 5th ed., sec. 3.1). Tolerance: the cubic hold's 1e-8 (rtol) of the peak."""
    ja, jb, k, torque, nu = 1.0, 3.0, 1e5, 100.0, 200.0
    model = TorsionModel((Mass("a", ja), Mass("b", jb)), (Shaft(("a", "b"), k),))
    duration = 0.2
    run = harmonic_run(
        linear_system(model), [[[torque + 0j, 0j]]], [nu], [1.0], (nu, nu), duration, 1.0,
        "rest", 4000,
    )  # fmt: skip
    t = np.linspace(0.0, duration, 4001)
    wn2 = k * (1.0 / ja + 1.0 / jb)
    delta = -(torque / ja) * (np.cos(nu * t) - np.cos(math.sqrt(wn2) * t)) / (wn2 - nu * nu)
    rigid = torque * (1.0 - np.cos(nu * t)) / ((ja + jb) * nu * nu)
    total = ja + jb
    assert run.modes == 2
    twist = run.angles[:, 1] - run.angles[:, 0]
    assert twist == pytest.approx(delta, abs=1e-8 * np.abs(delta).max())
    expected_a = rigid - jb / total * delta
    assert run.angles[:, 0] == pytest.approx(expected_a, abs=1e-8 * np.abs(expected_a).max())


def _chain() -> tuple[TorsionModel, UniformExcitation, list[float]]:
    """Eight damped masses (six cylinders) with natural frequencies 959 ... 4662 rad/s."""
    n = 8
    masses = tuple(
        Mass(f"m{i}", 0.5 + 0.1 * i, damping=3.0, cylinders=(i + 1,) if i < 6 else ())
        for i in range(n)
    )
    shafts = tuple(
        Shaft((f"m{i}", f"m{i + 1}"), 3e6 * (1 + 0.2 * i), damping=2.0, loss_factor=0.02)
        for i in range(n - 1)
    )
    excitation = UniformExcitation(100.0, np.radians([0, 120, 240, 360, 480, 600]))
    return TorsionModel(masses=masses, shafts=shafts), excitation, [0.5, 1.0, 1.5, 3.0]


RUN = {"run_up": (300.0, 600.0), "duration": 0.04, "start": "steady"}


@pytest.fixture(scope="module")
def reference():
    """The chain's run-up by scipy's DOP853 at tight tolerances (every degree of freedom)."""
    model, excitation, orders = _chain()
    return transient_response(
        model, excitation, orders, method="DOP853", rtol=1e-11, atol=1e-14, **RUN
    )


def test_modal_run_matches_solve_ivp(reference):
    """Default cut-off (8 x 3 x 600 rad/s, above every mode): the shaft torques equal
    DOP853's to 1e-7 of the largest (the hold's rtol 1e-8, DOP853's 1e-11)."""
    model, excitation, orders = _chain()
    run = transient_response(model, excitation, orders, **RUN)
    top = np.abs(reference.shaft_torque).max()
    assert run.modes_integrated == 8
    assert run.modal_cutoff == pytest.approx(8 * 3.0 * 600.0)
    assert run.time == pytest.approx(reference.time, abs=1e-15)
    assert run.shaft_torque == pytest.approx(reference.shaft_torque, abs=1e-7 * top)
    assert run.truncation_error < 1e-7


@pytest.mark.parametrize("cutoff", [3000.0, 2000.0])
def test_truncated_run_error_within_its_estimate(reference, cutoff):
    """Modes above the cut-off taken quasi-steadily (4 and 3 of 8 integrated): the shaft torques
    differ from DOP853's (all modes) by less than the reported estimate, and that estimate
    stays a fraction of the torque (the highest excitation frequency 1800 rad/s lies below
    the cut-off)."""
    model, excitation, orders = _chain()
    run = transient_response(model, excitation, orders, max_frequency=cutoff, **RUN)
    top = np.abs(reference.shaft_torque).max()
    error = np.abs(run.shaft_torque - reference.shaft_torque).max() / top
    assert run.modes_integrated < 8
    assert error <= run.truncation_error
    assert run.truncation_error < 0.2


def test_truncated_system_keeps_the_modes_below_the_cutoff():
    """The chain's retained frequencies equal the dense generalised eigenproblem's up to the
    cut-off (scipy.linalg.eigh of (K, M), an independent solver), 1e-9 relative."""
    import scipy.linalg

    model, _, _ = _chain()
    system = linear_system(model)
    reduced = truncated_system(system, 3000.0, 1000.0)
    lam = scipy.linalg.eigh(system.stiffness, np.diag(system.inertia), eigvals_only=True)
    dense = np.sqrt(np.maximum(lam, 0.0))
    expected = dense[dense <= 3000.0]
    assert reduced.natural_frequency == pytest.approx(expected, rel=1e-9, abs=1e-6)
    mass = reduced.modes.T @ (system.inertia[:, None] * reduced.modes)
    assert mass == pytest.approx(np.eye(reduced.count), abs=1e-12)


@pytest.mark.parametrize(
    ("settings", "key"),
    [
        ({"method": "Euler"}, "method"),
        ({"rtol": 2.0}, "rtol"),
        ({"atol": 1e-9}, "atol"),
        ({"max_frequency": -1.0}, "max_frequency"),
        ({"method": "DOP853", "max_frequency": 1e3}, "max_frequency"),
    ],
)
def test_bad_integration_settings_are_one_line_errors(settings, key):
    model, excitation, orders = _chain()
    with pytest.raises(InputError) as err:
        transient_response(model, excitation, orders, speed=400.0, cycles=1.0, **settings)
    assert err.value.key == key
    assert "\n" not in str(err.value)
