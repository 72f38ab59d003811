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
    figures = {f.key: f for f in section.figures}
    figure = figures["measured_synthesized_amplitude_rad"]
    assert figure.headline
    assert figures["teeth"].value == measured.teeth  # as the result declares them
    assert figure.value == pytest.approx(measured.synthesized)
    assert "model" in figure.display and f"{2000:.0f} rpm" in figure.display
    assert [p.name for p in section.plots] == ["measurement_orders", "measurement_trace"]
    (table,) = section.tables
    header = table.csv_text().splitlines()[0]
    assert header.endswith("model_amplitude_rad,model_phase_deg")
    assert "uniform (rectangular) over 1 cycle" in figures["window"].display
    assert math.isfinite(figure.value)
    # the comparison comes from the report's analysis session (its excitation, its model)
    assert "measurement" in ctx.analysis.computed()
    assert ctx.analysis.measurement(measured, "pulley").comparison is not None


def test_run_up_declares_its_resonance_and_damping(engine):
    """A run-up's key figures and resonance table are the order tracking's own declarations:
    the largest window (not a speed bin), the largest fitted resonance and its damping ratio,
    with the model's peak of the same order beside it."""
    measured = order_analysis(example_signal("inline6-runup"))
    ctx = Context(Analysis(engine), measurement=MeasurementInput(measured, "pulley"))
    section = build(ctx)
    figures = {f.key: f for f in section.figures}
    largest = figures["measured_synthesized_amplitude_rad"]
    assert largest.value == pytest.approx(float(measured.window_synthesized.max()))
    assert "model there" in largest.display
    top = max(measured.resonances, key=lambda f: f.peak_amplitude)
    peak = figures["measured_resonance_peak_rad"]
    assert peak.value == pytest.approx(top.peak_amplitude)
    assert f"order {top.order:g}" in peak.display and "model" in peak.display
    assert figures["measured_damping_ratio"].value == pytest.approx(top.damping)
    table = next(t for t in section.tables if t.name == "measurement_resonances")
    header = table.csv_text().splitlines()[0].split(",")
    assert {"order", "measured_speed_rpm", "model_speed_rpm", "damping_ratio"} <= set(header)
    # the same figures reach the command line's summary (one declaration)
    compared = ctx.analysis.measurement(measured, "pulley")
    keys = [f.key for f in compared.key_figures()]
    assert "measured_resonance_peak_rad" in keys and "measured_damping_ratio" in keys
