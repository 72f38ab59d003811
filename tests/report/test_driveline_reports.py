"""The engineering report on the built-in marine and genset lines: the torsion sections run on
the joined model (engine, coupling, gearbox, propeller or alternator) with the propeller's
orders."""

from __future__ import annotations

import pytest

from crankdyn.engine.model import Engine
from crankdyn.report.build import build_report


@pytest.mark.parametrize("name", ["marine-propulsion", "genset-1500"])
def test_report_builds_the_torsion_sections(name):
    engine = Engine.example(name)
    report = build_report(engine)
    keys = [s.key for s in report.sections]
    assert "torsion-modes" in keys and "torsion-response" in keys, report.notes
    summary = report.summary()
    assert summary["key_figures"]["max_vibratory_shaft_torque_Nm"] > 0.0
    section = next(s for s in report.sections if s.key == "torsion-response")
    text = " ".join(f.display for f in section.figures)
    assert "damper ring" not in text  # the output end is the model's, not a damper ring
