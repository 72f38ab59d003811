"""The figures of the registry: closed forms for the kinematic ones, and identities between
independent computations for the torque and load figures."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from crankdyn.engine.bearings import bearing_loads
from crankdyn.engine.torque import engine_torque
from crankdyn.errors import InputError
from crankdyn.io.catalogue import load_example
from crankdyn.io.examples import example_files
from crankdyn.io.files import load_toml
from crankdyn.session import ANALYSES
from crankdyn.study.docpath import parse_path
from crankdyn.study.figures import (
    FIGURES,
    TVC,
    AnalysisSettings,
    CaseContext,
    register_figure,
)
from crankdyn.study.run.worker import Payload, evaluate_case
from crankdyn.torsion.rules import permissible_continuous

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
    """The figures are the analyses' own summaries: the extrema of the whole cycle, refined
    between the points of the 1 deg grid (so at least the grid's largest value and within a
    few per mille of it)."""
    engine = load_example("inline6-diesel")
    w = engine.speed
    got = figures_of(
        engine,
        ["torque_nonuniformity", "max_main_bearing_load", "max_crank_pin_load", "max_torque"],
    )
    torque = engine_torque(engine, w, step=STEP)
    curve = torque.total_torque
    expected = (torque.max_torque - torque.min_torque) / torque.mean_torque
    assert got["torque_nonuniformity"] == pytest.approx(expected, rel=1e-14)
    assert got["max_torque"] == pytest.approx(torque.max_torque, rel=1e-14)
    assert curve.max() <= got["max_torque"] <= curve.max() * (1 + 1e-3)
    loads = bearing_loads(engine, w, step=STEP)
    assert got["max_main_bearing_load"] == pytest.approx(loads.max_bearing_load.max(), rel=1e-14)
    assert got["max_crank_pin_load"] == pytest.approx(loads.max_pin_load.max(), rel=1e-14)
    grid_max = loads.bearing_load.max()  # the firing peak falls between grid points: 0.2 % low
    assert grid_max <= got["max_main_bearing_load"] <= grid_max * (1 + 1e-2)


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
        targets=(("masses.piston_group", (parse_path("masses.piston_group"),)),),
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
    # one declaration: every figure is a key figure of a result class, its label and unit
    declared = {
        s.key: (s.name, s.label, s.unit)
        for a in (*ANALYSES, TVC)
        for s in a.result_class().figure_specs()
    }
    for name, f in FIGURES.items():
        # (tests register figures of their own)
        if f.module.startswith("crankdyn."):
            assert declared[f.key] == (name, f.label, f.unit), name
    # the names study files used before the figures were declared by the results
    old = [
        "mean_torque",
        "indicated_power",
        "imep",
        "peak_pressure",
        "max_torque",
        "min_torque",
        "torque_nonuniformity",
        "max_crank_pin_load",
        "max_mean_crank_pin_load",
        "max_main_bearing_load",
        "max_mean_main_bearing_load",
        "max_side_force",
        "max_rod_compression",
        "max_rod_tension",
        "mean_piston_speed",
        "max_piston_speed",
        "max_piston_acceleration",
        "free_force_1",
        "free_moment_1",
        "free_force_2",
        "free_moment_2",
        "free_force_4",
        "free_moment_4",
        "free_force_6",
        "free_moment_6",
        "rotating_free_force",
        "rotating_free_moment",
        "first_order_free_moment",
        "excess_work",
        "excess_work_coefficient",
        "flywheel_inertia",
        "cyclic_irregularity",
        "natural_frequency_1",
        "natural_frequency_2",
        "natural_frequency_3",
        "max_relative_angle",
        "max_free_end_amplitude",
        "max_shaft_torque",
        "max_shaft_stress",
        "max_stress_ratio",
        "max_damper_power",
    ]
    assert set(old) <= set(FIGURES)


def test_inline4_balance_figures_against_the_series():
    """Inline-4 with a flat crank: first-order forces and all moments cancel; the second-order
    free force is 4 m_j R w^2 times the second harmonic of the piston acceleration,
    F_2 = m_j R w^2 (4 lam + lam^3 + 15 lam^5/32 + 35 lam^7/128 + 735 lam^9/4096 + ...): the
    binomial series of sqrt(1 - lam^2 sin^2 phi) in the exact piston displacement, each
    sin^2n phi contributing -C(2n, n-1)/2^(2n-1) cos 2 phi. Seed 000 gives the first term,
    4 lam m_j R w^2; the first term left out, 0.127 lam^11, is 5e-8 of the sum at
    lam = 0.26."""
    from crankdyn.crank.masses import equivalent_masses

    engine = load_example("vaz2108")
    names = ["free_force_1", "free_force_2", "free_moment_1", "free_moment_2", "free_force_4"]
    got = figures_of(engine, names)
    g, w = engine.geometry, engine.speed
    m_j = equivalent_masses(engine.masses, g.rod_length)[0]
    lam = g.lam
    unit = m_j * g.crank_radius * w * w
    series = 4 * lam + lam**3 + 15 * lam**5 / 32 + 35 * lam**7 / 128 + 735 * lam**9 / 4096
    assert got["free_force_2"] == pytest.approx(unit * series, rel=1e-7)
    assert got["free_force_1"] <= 1e-9 * unit
    assert got["free_moment_1"] <= 1e-9 * unit and got["free_moment_2"] <= 1e-9 * unit
    assert got["free_force_4"] > 0.0


def test_flywheel_figures(vaz):
    """For a target delta: the flywheel inertia is Delta E / (delta w^2) less the crank train's
    own (seed 000 section 2.4), and the delta achieved with it (exact energy equation) equals
    the target to first order in delta."""
    from crankdyn.engine.flywheel import crank_train_inertia

    delta = 0.01
    ctx = CaseContext(vaz, AnalysisSettings((("step", STEP), ("delta", delta))))
    got = {
        n: FIGURES[n].evaluate(ctx)
        for n in ("excess_work", "flywheel_inertia", "cyclic_irregularity")
    }
    w = vaz.speed
    rotating, reciprocating = crank_train_inertia(vaz.masses, vaz.geometry, vaz.cylinders.throws)
    expected = got["excess_work"] / (delta * w * w) - rotating - reciprocating
    assert got["flywheel_inertia"] == pytest.approx(expected, rel=1e-12)
    assert got["cyclic_irregularity"] == pytest.approx(delta, rel=2 * delta)


def test_natural_frequencies_of_a_two_mass_model_study(tmp_path):
    """A study on a torsional model file: two discs on a shaft whose stiffness varies; the
    only elastic mode is f = sqrt(k (J1 + J2)/(J1 J2)) / (2 pi) (seed 003, two-mass system),
    and there is no second one."""
    from crankdyn.io.study_file import load_study
    from crankdyn.study.run.results import read_table
    from crankdyn.study.run.runner import run_study

    (tmp_path / "model.toml").write_text(
        'name = "two discs"\n'
        '[[mass]]\nname = "a"\ninertia = "2 kg*m^2"\n'
        '[[mass]]\nname = "b"\ninertia = "6 kg*m^2"\n'
        '[[shaft]]\nbetween = ["a", "b"]\nstiffness = "1e5 N*m/rad"\n',
        encoding="utf-8",
    )
    (tmp_path / "study.toml").write_text(
        'model = "model.toml"\n'
        '[[parameter]]\nkey = "shaft[1].stiffness"\n'
        'range = ["1 kN*m/rad", "1000 kN*m/rad"]\nsteps = 4\nspacing = "log"\n'
        '[analysis]\nfigures = ["natural_frequency_1", "natural_frequency_2"]\n',
        encoding="utf-8",
    )
    spec = load_study(tmp_path / "study.toml")
    assert spec.base.kind == "model"
    run = run_study(spec, tmp_path / "out", workers=1, summary=False)
    assert run.ok == 4
    data = read_table(tmp_path / "out" / "results.parquet").to_pydict()
    k = np.asarray(data["shaft[1].stiffness_kN_m_per_rad"]) * 1e3
    np.testing.assert_allclose(k, [1e3, 1e4, 1e5, 1e6], rtol=1e-12)
    expected = np.sqrt(k * (2 + 6) / (2 * 6)) / (2 * math.pi)
    np.testing.assert_allclose(data["natural_frequency_1_hz"], expected, rtol=1e-10)
    assert all(v is None or math.isnan(v) for v in data["natural_frequency_2_hz"])


def test_one_parameter_sets_two_keys(tmp_path):
    """The built-in flywheel study sets the flywheel's inertia in the torsional model and in
    [flywheel] with one parameter: the natural frequency and the speed fluctuation both move
    (delta ~ 1 / (J_F + I_crank + I_other) at a fixed excess work)."""
    from crankdyn.io.catalogue import resolve_study
    from crankdyn.study.cases import expand
    from crankdyn.study.run.runner import payload_of

    spec = resolve_study("inline6-flywheel-and-pulley-shaft")
    flywheel = spec.parameters[0]
    assert [p.text for p in flywheel.paths] == ["torsion.mass[9].inertia", "flywheel.inertia"]
    payload = payload_of(spec)
    cases = [
        c
        for c in expand(spec)
        if c.params["torsion.shaft[1].stiffness"] == c.params["torsion.shaft[1].stiffness"]
        and c.index % 4 == 0
    ][:2]
    records = [evaluate_case(payload, c.case_id, c.params) for c in cases]
    assert [r["status"] for r in records] == ["ok", "ok"]
    j = [c.numbers["torsion.mass[9].inertia"] for c in cases]
    engine = load_example("inline6-diesel")
    from crankdyn.engine.flywheel import crank_train_inertia

    crank = sum(crank_train_inertia(engine.masses, engine.geometry, engine.cylinders.throws))
    crank += engine.flywheel.other_inertia
    ratio = (
        records[0]["figures"]["cyclic_irregularity"] / records[1]["figures"]["cyclic_irregularity"]
    )
    assert ratio == pytest.approx((j[1] + crank) / (j[0] + crank), rel=0.01)
    assert (
        records[0]["figures"]["natural_frequency_1"] != records[1]["figures"]["natural_frequency_1"]
    )


SHAFT_LINE = Path(__file__).parent / "data" / "shaft-line.toml"


def test_forced_response_figures_of_an_engine():
    """The inline-6's response figures are those of the torsion response at the model's
    operating range every 10 rpm and orders 0.5 to 12 (the session's defaults, as
    `crankdyn torsion response` and the report), the
    relative angle between the first and the last mass (pulley and flywheel) by default."""
    from crankdyn.torsion.excitation import excitation_for
    from crankdyn.torsion.sweep import forced_response

    engine = load_example("inline6-diesel")
    got = figures_of(engine, ["max_relative_angle", "max_free_end_amplitude", "max_shaft_torque"])
    model = engine.torsion
    speeds = np.arange(1000, 2501, 10) * math.pi / 30
    result = forced_response(model, excitation_for(model, engine), speeds, np.arange(1, 25) * 0.5)
    relative = result.relative_angle("pulley", "flywheel").synthesized
    assert got["max_relative_angle"] == pytest.approx(relative.max(), rel=1e-12)
    assert got["max_free_end_amplitude"] == pytest.approx(
        result.synthesized_amplitude[:, 0].max(), rel=1e-12
    )
    assert got["max_shaft_torque"] == pytest.approx(
        result.synthesized_shaft_torque.max(), rel=1e-12
    )


def test_shaft_stress_rules_and_damper_figures_of_a_model():
    """A shaft line with a 50 mm solid shaft: the nominal shear stress is the torque over the
    polar section modulus pi D^3 / 16 (Timoshenko, Strength of Materials), the rule figure is
    the stress over tau_C, and a viscous damper dissipates power."""
    from crankdyn.io.catalogue import load_torsion_model

    model = load_torsion_model(SHAFT_LINE)
    ctx = CaseContext(model, AnalysisSettings(), "model")
    names = ["max_shaft_torque", "max_shaft_stress", "max_stress_ratio", "max_damper_power"]
    got = {n: FIGURES[n].evaluate(ctx) for n in names}
    assert got["max_shaft_stress"] == pytest.approx(
        got["max_shaft_torque"] / (math.pi * 0.05**3 / 16), rel=1e-12
    )
    result = ctx.analysis.response()
    # the largest stress over tau_C of M68.4 (torsion.rules), written out for the line's shafts
    ratios = []
    for limit in model.rules.shafts:
        shaft = next(s for s in model.shafts if s.between == limit.between)
        tau_c = permissible_continuous(
            result.speed / model.rules.rated_speed,
            limit.strength_used,
            limit.design_factor,
            shaft.geometry.outer_diameter,
        )
        stress = result.synthesized_shaft_stress[:, result.shaft_index(limit.between)]
        ratios.append(np.max(stress / tau_c))
    assert got["max_stress_ratio"] == pytest.approx(max(ratios), rel=1e-12)
    assert got["max_damper_power"] > 0.0
    ranged = CaseContext(
        model,
        AnalysisSettings((("speed_range", (100.0, 120.0)), ("speed_step", 10.0))),
        "model",
    )
    swept = ranged.analysis.response()
    # the grid, and speeds added to resolve the peaks (listed apart in added_speeds)
    np.testing.assert_allclose(swept.speed[swept.on_grid], [100.0, 110.0, 120.0])


@pytest.mark.parametrize(
    ("figure", "message"),
    [
        ("max_shaft_stress", "no shaft of the torsional model has diameters"),
        ("max_stress_ratio", "the torsional model has no [rules]"),
        ("max_damper_power", "the torsional model has no damper"),
    ],
)
def test_response_figures_a_model_cannot_give(figure, message):
    engine = load_example("inline6-diesel")
    ctx = CaseContext(engine, AnalysisSettings((("step", STEP),)))
    with pytest.raises(InputError, match=message.replace("[", r"\[")):
        FIGURES[figure].evaluate(ctx)


def test_relative_angle_between_unknown_masses():
    engine = load_example("inline6-diesel")
    ctx = CaseContext(engine, AnalysisSettings((("relative", ("pulley", "flywhel")),)))
    with pytest.raises(InputError) as info:
        FIGURES["max_relative_angle"].evaluate(ctx)
    assert str(info.value).startswith('[analysis] relative = ["pulley", "flywhel"]: no mass')
