"""The four front ends give the same numbers: for every built-in engine at its own speed, the
command line (JSON), the report (summary.json's key figures), the study runner (the figures of a
case) and a notebook (the analysis session) agree exactly, since all take them from one
:class:`crankdyn.Analysis`: the cycle's figures, the natural frequency of elastic mode 1 (the
numbering of crankdyn docs conventions) and, for the engines with a forced response (the
drivelines marine-propulsion and genset-1500 among them), its resolved peaks."""

from __future__ import annotations

import json
import math

import pytest

import crankdyn
from crankdyn.io.examples import example_names
from crankdyn.report.build import build_report
from crankdyn.study.figures import FIGURES, AnalysisSettings, CaseContext

# (command, JSON key, report key, study figure, notebook) for each quantity
QUANTITIES = [
    (
        ("torque",),
        "mean_torque_Nm",
        "mean_torque_Nm",
        "mean_torque",
        lambda a: a.torque.mean_torque,
    ),
    (
        ("forces",),
        "max_side_force_N",
        "max_side_force_N",
        "max_side_force",
        lambda a: a.forces().max_side_force,
    ),
    (
        ("forces",),
        "max_rod_compression_N",
        "max_rod_compression_N",
        "max_rod_compression",
        lambda a: a.forces().max_rod_compression,
    ),
    (
        ("bearings",),
        "max_main_bearing_load_N",
        "max_main_bearing_load_N",
        "max_main_bearing_load",
        lambda a: float(max(a.bearings().max_bearing_load)),
    ),
    (
        ("kinematics",),
        "summary.max_acceleration_m_s2",
        "max_piston_acceleration_m_s2",
        "max_piston_acceleration",
        lambda a: a.kinematics().extrema.max_acceleration,
    ),
    (
        ("pressure",),
        "imep_Pa",
        "imep_Pa",
        "imep",
        lambda a: a.pressure.imep,
    ),
    (
        ("flywheel",),
        "flywheel_inertia_kgm2",
        "flywheel_inertia_kgm2",
        None,  # the study's flywheel figure takes its target from [analysis] delta
        lambda a: a.flywheel().flywheel_inertia,
    ),
]


def _cli_value(cli, command, engine, key, runs):
    if command not in runs:  # one run per command
        run = cli(*command, engine, "--format", "json")
        assert run.status == 0, run
        runs[command] = json.loads(run.out)
    data = runs[command]
    for part in key.split("."):
        data = data[part]
    return max(data) if isinstance(data, list) else data


@pytest.mark.parametrize("name", example_names("engine"))
def test_cli_report_study_and_notebook_agree(cli, name):
    engine = crankdyn.Engine.example(name)
    notebook = crankdyn.Analysis(engine)
    report = build_report(engine).summary()["key_figures"]
    case = CaseContext(engine, AnalysisSettings())
    runs: dict = {}
    for command, key, report_key, figure, value_of in QUANTITIES:
        expected = value_of(notebook)
        assert _cli_value(cli, command, name, key, runs) == expected, (name, key)
        assert report[report_key] == expected, (name, report_key)
        if figure is not None:
            got = FIGURES[figure].evaluate(case)
            assert got == pytest.approx(abs(expected), rel=1e-15), (name, figure)
    model = engine.torsion
    if model is not None:
        modes = json.loads(cli("torsion", "modes", name, "--format", "json").out)
        f1 = float(notebook.modes.frequencies_hz[notebook.modes.index(1)])  # elastic mode 1
        assert modes["natural_frequencies_hz"][modes["mode"].index(1)] == f1
        assert report["natural_frequency_1_hz"] == f1
        assert FIGURES["natural_frequency_1"].evaluate(case) == pytest.approx(f1, rel=1e-15)
    if model is not None and model.operating is not None and model.cylinder_dofs:
        _response_agrees(cli, name, notebook, report, case)


def _response_agrees(cli, name, notebook, report, case):
    """The resolved peaks of the forced response: the most loaded shaft's synthesised torque and
    the relative angle between the model's ends."""
    first, last = notebook.model.mass_names[0], notebook.model.mass_names[-1]
    run = cli(
        "torsion", "response", name, "--relative", f"{first},{last}", "--format", "json"
    )  # fmt: skip
    assert run.status == 0, run
    data = json.loads(run.out)
    shaft = notebook.most_loaded_shaft()
    torque, speed = notebook.peak("torque", shaft)
    (peak,) = [
        p
        for p in data["peaks"]
        if p["quantity"] == "synthesized_shaft_torque" and p["item"] == " - ".join(shaft)
    ]
    assert peak["value_Nm"] == torque
    # JSON speeds read as round numbers (12 significant digits)
    assert peak["speed_rpm"] == pytest.approx(speed * 30.0 / math.pi, rel=1e-11)
    assert max(data["synthesized_shaft_torque_Nm"], key=max) == max(
        notebook.response().synthesized_shaft_torque.tolist(), key=max
    )
    assert report["max_vibratory_shaft_torque_Nm"] == torque
    assert FIGURES["max_shaft_torque"].evaluate(case) == pytest.approx(torque, rel=1e-15)
    angle, _ = notebook.peak("relative", (first, last))
    assert max(data["relative_angle"]["synthesized_amplitude_rad"]) == angle
    assert report["max_relative_angle_rad"] == angle
    assert FIGURES["max_relative_angle"].evaluate(case) == pytest.approx(angle, rel=1e-15)
