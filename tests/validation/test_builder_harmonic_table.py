"""The engine builder's table of one cylinder's harmonic torques (issue 32 item 5): a model file
without an engine gets normal firing and each misfire from it.

- Hand-built: a cylinder torque T(theta) = 300 sin(theta/2 + 0.3) + 120 cos(theta)
  - 50 sin(1.5 theta) N m (misfiring: 80 sin(theta/2) N m), its coefficients written by hand
  (sin(x + p) = sin x cos p + cos x sin p), read from a CSV in both forms (sine and cosine;
  amplitude and phase); the three cylinders' torque synthesised from the table equals the sum
  of the cylinders' torques evaluated directly, T(phi - Phi_i), at every crank angle (to
  rounding: the formulas are exact).
- The pressure-trace route: the marine-propulsion engine's coefficients of cylinder 1, firing
  and motored, from its pressure (the FFT of the cylinder torque), written to a CSV at two
  speeds and read back: the table route gives every cylinder's harmonics (phased by the
  firing order) and every misfire's, and the same forced response of the engine's line, to
  the digits written (12 significant).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.io.torsion_tables import read_cylinder_harmonics
from crankdyn.torsion.excitation import EngineExcitation, TabulatedExcitation, excitation_for
from crankdyn.torsion.excitation_spec import ExcitationSpec
from crankdyn.torsion.sweep import forced_response

ANGLES = np.radians([0.0, 240.0, 480.0])  # three cylinders, even firing over 720 deg


def _torque(theta):
    return 300.0 * np.sin(theta / 2 + 0.3) + 120.0 * np.cos(theta) - 50.0 * np.sin(1.5 * theta)


def _misfire(theta):
    return 80.0 * np.sin(theta / 2)


HAND_SIN_COS = (
    "order,normal_sin_N*m,normal_cos_N*m,misfire_sin_N*m,misfire_cos_N*m\n"
    f"0.5,{300 * math.cos(0.3)!r},{300 * math.sin(0.3)!r},80,0\n"
    "1.0,0,120,0,0\n"
    "1.5,-50,0,0,0\n"
)
HAND_POLAR = (
    "order,normal_amplitude_N*m,normal_phase_rad,misfire_amplitude_N*m,misfire_phase_rad\n"
    "0.5,300,0.3,80,0\n"
    f"1.0,120,{math.pi / 2!r},0,0\n"
    f"1.5,50,{math.pi!r},0,0\n"
)


@pytest.mark.parametrize("text", [HAND_SIN_COS, HAND_POLAR], ids=["sin-cos", "amplitude-phase"])
def test_hand_built_table_synthesises_the_cylinders_torques(tmp_path, text):
    path = tmp_path / "table.csv"
    path.write_text(text, encoding="utf-8")
    table = read_cylinder_harmonics(path)
    phi = np.linspace(0.0, 4 * math.pi, 721)
    orders = [0.5, 1.0, 1.5, 2.0]  # order 2 is not in the table: 0
    for misfire in ((), (2,)):
        exc = TabulatedExcitation(table, ANGLES, misfire=misfire)
        c = exc.harmonics([50.0], orders)[0]  # (orders, cylinders)
        synthesised = np.real(np.exp(1j * np.outer(phi, orders)) @ c.sum(axis=1))
        direct = sum((_misfire if k + 1 in misfire else _torque)(phi - ANGLES[k]) for k in range(3))
        assert synthesised == pytest.approx(direct, abs=1e-9)


def test_table_errors_are_one_line(tmp_path):
    bad = tmp_path / "bad.csv"
    bad.write_text("order,normal_sin_N*m\n0.5,1\n", encoding="utf-8")
    with pytest.raises(InputError, match="normal_cos"):
        read_cylinder_harmonics(bad)
    bad.write_text("order,normal_amplitude_N*m,normal_phase_deg\n0.7,1,0\n", encoding="utf-8")
    table = read_cylinder_harmonics(bad)
    with pytest.raises(InputError, match="four-stroke"):  # 0.7 is no order of the cycle
        TabulatedExcitation(table, ANGLES)
    bad.write_text("order,normal_amplitude_N*m,normal_phase_deg\n1.0,1,0\n", encoding="utf-8")
    with pytest.raises(InputError, match="misfiring"):  # no misfire columns
        TabulatedExcitation(read_cylinder_harmonics(bad), ANGLES, misfire=(1,))
    bad.write_text("speed_rpm,order,normal_sin_N*m,normal_cos_N*m\n300,0.5,1,0\n400,1,1,0\n")
    with pytest.raises(InputError, match="every order at every speed"):
        read_cylinder_harmonics(bad)


@pytest.fixture(scope="module")
def marine_route(tmp_path_factory):
    """The marine engine's cylinder-1 coefficients at two speeds of the propeller law, firing
    and motored, written to a CSV (12 significant digits) and read back."""
    from crankdyn.io.catalogue import resolve_model_and_engine
    from crankdyn.session import Analysis

    _model, engine = resolve_model_and_engine("marine-propulsion")
    model = Analysis(engine).loaded_model
    speeds = np.array([450.0, 600.0]) / RPM
    orders = np.arange(1, 25) * 0.5
    firing = EngineExcitation(engine, model.excitation).harmonics(speeds, orders)[:, :, 0]
    motored = EngineExcitation(engine, model.excitation, (1,)).harmonics(speeds, orders)[:, :, 0]
    rows = ["speed_rpm,order,normal_sin_N*m,normal_cos_N*m,misfire_sin_N*m,misfire_cos_N*m"]
    for i, w in enumerate(speeds):
        for j, q in enumerate(orders):
            c, m = firing[i, j], motored[i, j]
            cells = (-c.imag, c.real, -m.imag, m.real)
            rows.append(f"{w * RPM:.12g},{q:g}," + ",".join(f"{x:.12g}" for x in cells))
    path = tmp_path_factory.mktemp("table") / "marine.csv"
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return model, engine, read_cylinder_harmonics(path), speeds, orders


def test_pressure_route_and_table_route_give_the_same_harmonics(marine_route):
    model, engine, table, speeds, orders = marine_route
    angles = np.asarray(engine.cylinders.firing_angles)
    for misfire in ((), (1,), (4,)):
        route = EngineExcitation(engine, model.excitation, misfire).harmonics(speeds, orders)
        got = TabulatedExcitation(table, angles, misfire=misfire).harmonics(speeds, orders)
        scale = np.max(np.abs(route))
        assert np.max(np.abs(got - route)) <= 1e-11 * scale


def test_model_without_engine_responds_as_the_engine_line(marine_route):
    """The engine's line with its excitation replaced by the table (no engine): the same
    synthesised shaft torques at the table's speeds, firing and with cylinder 3 misfiring."""
    model, engine, table, speeds, orders = marine_route
    angles = tuple(float(a) for a in engine.cylinders.firing_angles)
    spec = ExcitationSpec(firing_angles=angles, cylinder_harmonics=table)
    bare = dataclasses.replace(model, engine=None, excitation=spec)
    for misfire in ((), (3,)):
        exc = excitation_for(bare, misfire=misfire)
        assert isinstance(exc, TabulatedExcitation)
        got = forced_response(bare, exc, speeds, orders, resolve=False)
        ref = forced_response(
            model, excitation_for(model, engine, misfire=misfire), speeds, orders, resolve=False
        )
        assert np.asarray(got.synthesized_shaft_torque) == pytest.approx(
            np.asarray(ref.synthesized_shaft_torque), rel=1e-9
        )
