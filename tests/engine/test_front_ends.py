"""The four front ends give the same numbers: for every built-in engine at its own speed, the
command line (JSON), the report (summary.json's key figures), the study runner (the figures of a
case) and a notebook (the analysis session) agree exactly, since all take them from one
:class:`crankdyn.Analysis`."""

from __future__ import annotations

import json

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
        lambda a: a.kinematics().summary.max_acceleration,
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
    if engine.torsion is not None:
        modes = json.loads(cli("torsion", "modes", name, "--format", "json").out)
        f1 = float(notebook.modes.frequencies_hz[1])
        assert modes["natural_frequencies_hz"][1] == f1
        assert report["natural_frequency_1_hz"] == f1
        assert FIGURES["natural_frequency_1"].evaluate(case) == pytest.approx(f1, rel=1e-15)
