"""The report's measurement section (crankdyn analyze --measurement), built directly."""

import math

import pytest

from crankdyn.engine.model import Engine
from crankdyn.measure.examples import example_signal
from crankdyn.measure.orders import order_analysis
from crankdyn.report.sections import Context, NotApplicable
from crankdyn.report.sections.measurement import MeasurementInput, build
from crankdyn.session import Analysis


@pytest.fixture(scope="module")
def engine():
    return Engine.example("inline6-diesel")


def test_not_applicable_without_a_measurement(engine):
    with pytest.raises(NotApplicable, match="--measurement SIGNAL"):
        build(Context(Analysis(engine)))


def test_steady_measurement_against_the_engines_model(engine):
    measured = order_analysis(example_signal("inline6-2000rpm"))
    ctx = Context(Analysis(engine), measurement=MeasurementInput(measured, "pulley"))
    section = build(ctx)
    assert section.key == "measurement"
    (figure,) = section.figures
    assert figure.key == "measured_synthesized_amplitude_rad"
    assert figure.value == pytest.approx(measured.synthesized)
    assert "model" in figure.display and f"{2000:.0f} rpm" in figure.display
    assert [p.name for p in section.plots] == ["measurement_orders", "measurement_trace"]
    (table,) = section.tables
    header = table.csv_text().splitlines()[0]
    assert header.endswith("model_amplitude_rad,model_phase_deg")
    assert "uniform (rectangular) over 1 cycle" in section.intro
    assert math.isfinite(figure.value)
    # the comparison comes from the report's analysis session (its excitation, its model)
    assert "measurement" in ctx.analysis.computed()
    assert ctx.analysis.measurement(measured, "pulley").comparison is not None
