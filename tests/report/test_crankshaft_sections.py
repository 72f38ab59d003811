"""The report's crankshaft sections (UR M53; the beam model with the lumped-vs-beam rows) render
the session's results, and an engine without [crankshaft] leaves them out without a note."""

from __future__ import annotations

import pytest

from crankdyn.engine.model import Engine
from crankdyn.report.sections import Context, NotRequested
from crankdyn.report.sections.crankshaft import build as build_m53
from crankdyn.report.sections.crankshaft_beam import build as build_beam
from crankdyn.session import Analysis


@pytest.fixture(scope="module")
def ctx():
    return Context(analysis=Analysis(Engine.example("marine-propulsion")))


def test_the_m53_section_is_the_results_summary(ctx):
    section = build_m53(ctx)
    result = ctx.analysis.crankshaft()
    figures = {f.key: f.value for f in section.figures}
    assert figures["min_acceptability_factor"] == result.smallest_q()[0]
    assert [v.to_dict() for v in section.verdicts] == [
        v.to_dict() for v in result.summary_verdicts()
    ]
    names = [t.name for t in section.tables]
    assert names[0] == "crankshaft-verdicts"
    assert {"m53_nominal", "m53_locations", "m53_validity", "m53_quantities"} <= set(names)
    assert section.json["crankshaft"]["quantities"]


def test_the_beam_section_holds_the_lumped_comparison(ctx):
    section = build_beam(ctx)
    keys = {f.key for f in section.figures}
    assert {"lumped_model_largest_difference", "max_free_end_axial_m",
            "max_web_vibration_stress_Pa", "beam_lowest_axial_frequency_hz"} <= keys  # fmt: skip
    assert "lumped_comparison" in [t.name for t in section.tables]
    assert [p.name for p in section.plots] == [
        "crankshaft_mode_shapes",
        "crankshaft_axial_response",
    ]


def test_no_crankshaft_no_section():
    plain = Context(analysis=Analysis(Engine.example("inline6-diesel")))
    for build in (build_m53, build_beam):
        with pytest.raises(NotRequested):
            build(plain)
