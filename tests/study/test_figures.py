"""The figures of the registry: closed forms for the kinematic ones, and identities between
independent computations for the torque and load figures."""

from __future__ import annotations

import math

import numpy as np
import pytest

from crankdyn.bearings import bearing_loads
from crankdyn.io.engine_file import example_files, load_example
from crankdyn.io.files import load_toml
from crankdyn.study.docpath import parse_path
from crankdyn.study.figures import FIGURES, AnalysisSettings, CaseContext, Figure, register_figure
from crankdyn.study.worker import Payload, evaluate_case
from crankdyn.torque import engine_torque

STEP = math.radians(1.0)


def figures_of(engine, names, speed=None):
    values = [] if speed is None else [("speed", speed)]
    ctx = CaseContext(engine, AnalysisSettings((*values, ("step", STEP))))
    return {name: FIGURES[name].evaluate(ctx) for name in names}


@pytest.fixture(scope="module")
def vaz():
    return load_example("vaz2108")


def test_max_piston_acceleration_is_r_omega2_one_plus_lambda(vaz):
    """Central slider-crank: the largest |a| is at TDC, R w^2 (1 + lambda) (seed 000 section 1;
    also for lambda > 1/4, where the BDC minimum splits in two)."""
    g = vaz.geometry
    assert g.offset == 0.0 and g.lam > 0.25
    w = vaz.speed
    got = figures_of(vaz, ["max_piston_acceleration"])["max_piston_acceleration"]
    assert got == pytest.approx(g.crank_radius * w * w * (1.0 + g.lam), rel=1e-12)


def test_piston_speeds(vaz):
    """Mean piston speed c_m = S n / 30 = S w / pi (seed 002 eq. 9); the largest |v| against a
    dense evaluation of the exact velocity, v = R w (sin phi + lambda sin phi cos phi /
    sqrt(1 - lambda^2 sin^2 phi)), on a 0.0001 deg grid (its error there is below 1e-9
    relative, second order in the step at the maximum)."""
    g, w = vaz.geometry, vaz.speed
    got = figures_of(vaz, ["mean_piston_speed", "max_piston_speed"])
    assert got["mean_piston_speed"] == pytest.approx(g.stroke * w / math.pi, rel=1e-12)
    phi = np.linspace(0.0, math.pi, 1_800_001)
    s = np.sin(phi)
    v = g.crank_radius * w * (s + g.lam * s * np.cos(phi) / np.sqrt(1 - (g.lam * s) ** 2))
    assert got["max_piston_speed"] == pytest.approx(v.max(), rel=1e-9)


def test_power_and_imep_agree_with_the_mean_torque(vaz):
    """Indicated power P = M w exactly; and M Theta = Z W_i (the mean of the torque curve over
    the cycle angle Theta against the p dV work of one cylinder, two different integrations:
    agreement to 1e-5)."""
    got = figures_of(vaz, ["mean_torque", "indicated_power", "imep"])
    assert got["indicated_power"] == pytest.approx(got["mean_torque"] * vaz.speed, rel=1e-14)
    z, vd = vaz.cylinders.count, vaz.geometry.swept_volume
    assert got["imep"] == pytest.approx(got["mean_torque"] * 4 * math.pi / (z * vd), rel=1e-5)


def test_torque_nonuniformity_and_loads_from_the_curves():
    engine = load_example("inline6-diesel")
    w = engine.speed
    got = figures_of(
        engine,
        ["torque_nonuniformity", "max_main_bearing_load", "max_crank_pin_load", "max_torque"],
    )
    torque = engine_torque(engine, w, step=STEP)
    curve = torque.total_torque
    expected = (curve.max() - curve.min()) / torque.mean_torque
    assert got["torque_nonuniformity"] == pytest.approx(expected, rel=1e-14)
    assert got["max_torque"] == pytest.approx(curve.max(), rel=1e-14)
    loads = bearing_loads(engine, w, step=STEP)
    assert got["max_main_bearing_load"] == pytest.approx(loads.bearing_load.max(), rel=1e-14)
    assert got["max_crank_pin_load"] == pytest.approx(loads.pin_load.max(), rel=1e-14)


def test_the_analysis_speed_overrides_the_engines(vaz):
    slow = figures_of(vaz, ["max_piston_acceleration"], speed=vaz.speed / 2)
    fast = figures_of(vaz, ["max_piston_acceleration"])
    assert slow["max_piston_acceleration"] == pytest.approx(fast["max_piston_acceleration"] / 4)


def test_a_case_without_a_speed_fails_with_one_line(tmp_path):
    path = example_files("vaz2108")[0]
    document = load_toml(path)
    del document["operating"]
    payload = Payload(
        kind="engine",
        document=document,
        source="vaz2108.toml",
        base_dir=str(path.parent),
        remove=(),
        paths=(parse_path("masses.piston_group"),),
        settings=AnalysisSettings(),
        figures=("mean_torque",),
        modules=("crankdyn.study.figures",),
    )
    record = evaluate_case(payload, "x", {"masses.piston_group": "0.5 kg"})
    assert record["status"] == "failed"
    assert record["error"] == (
        "vaz2108.toml: no speed: give [analysis] speed in the study file or [operating] speed "
        "in the engine file"
    )


def test_the_registry():
    keys = [f.key for f in FIGURES.values()]
    assert len(keys) == len(set(keys))
    for f in FIGURES.values():
        assert f.si_unit is not None and f.better in (None, "min", "max")
    with pytest.raises(ValueError, match="already registered"):
        register_figure(FIGURES["mean_torque"])
    with pytest.raises(ValueError, match="needs its si_unit"):
        Figure("x", "x_kN", "x", "kN", function=lambda c: 0.0, scale=1e-3)
