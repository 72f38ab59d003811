"""The engineering report's torsion sections on the built-in marine and genset lines: they run
on the joined model (engine, coupling, gearbox, propeller or alternator) with the propeller's
orders (the other sections do not depend on the line)."""

from __future__ import annotations

import pytest

from crankdyn.engine.model import Engine
from crankdyn.report.sections import Context, builders
from crankdyn.session import Analysis


@pytest.mark.parametrize("name", ["marine-propulsion", "genset-1500"])
def test_report_torsion_sections(name):
    engine = Engine.example(name)
    ctx = Context(analysis=Analysis(engine))
    built = {key: build(ctx) for key, build in builders() if key.startswith("torsion")}
    assert set(built) == {"torsion_model", "torsion_modes", "torsion_response"}
    response = built["torsion_response"]
    figures = {f.key: f for f in response.figures}
    assert figures["max_vibratory_shaft_torque_Nm"].value > 0.0
    text = " ".join(f.display for f in response.figures)
    assert "damper ring" not in text  # the output end is the model's, not a damper ring
    if name == "marine-propulsion":  # the blade orders are among the response's orders
        assert 1.25 in list(ctx.analysis.response().orders)
