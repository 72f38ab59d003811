"""The firing, balance and flywheel report sections: they build, and a report that lists them
(as the lead's BUILDERS will) writes its plots, data and summary."""

from __future__ import annotations

import importlib
import json

import pytest

import crankdyn.report.sections as sections
from crankdyn.engine.model import Engine
from crankdyn.report.build import build_report
from crankdyn.report.sections import Context, NotApplicable
from crankdyn.report.write import write_report
from crankdyn.session import Analysis

OURS = ("firing", "balance", "flywheel")


@pytest.mark.parametrize("name", ["v8-crossplane", "inline3-petrol"])
def test_sections_build(name):
    e = Engine.example(name)
    ctx = Context(Analysis(e))
    for key in OURS:
        section = importlib.import_module(f"crankdyn.report.sections.{key}").build(ctx)
        assert section.key == key and section.figures and section.plots
    # the torque, balance and flywheel sections share one torque run
    assert ctx.analysis.computed().count("torque") == 1


def test_sections_not_applicable_without_masses():
    base = Engine.example("vaz2108")
    e = Engine(name="bare", geometry=base.geometry, cylinders=base.cylinders, speed=base.speed)
    ctx = Context(Analysis(e))
    for key in ("balance", "flywheel"):
        with pytest.raises(NotApplicable):
            importlib.import_module(f"crankdyn.report.sections.{key}").build(ctx)
    assert importlib.import_module("crankdyn.report.sections.firing").build(ctx).figures


def test_report_with_the_sections(tmp_path, monkeypatch):
    monkeypatch.setattr(sections, "BUILDERS", OURS)  # the others have their own tests
    engine = Engine.example("v8-flatplane")
    out = write_report(build_report(engine), tmp_path / "r")
    summary = json.loads((out / "summary.json").read_text())
    figures = summary["key_figures"]
    assert figures["adjacent_consecutive"] == 4  # each bank an in-line four: 3-4 and 2-1
    assert figures["max_free_force_N"] > 0  # the flat-plane V8's horizontal second order
    assert figures["flywheel_inertia_kgm2"] > 0
    for plot in ("firing", "balance", "flywheel"):
        assert (out / "plots" / f"{plot}.png").exists()
    assert (out / "data" / "balance.csv").read_text().startswith("Order,")
    assert (out / "data" / "flywheel.csv").read_text().startswith("crank_angle_deg,")


def test_build_report_hands_over_each_section_as_it_is_made():
    """``built`` sees every section of the report, in order, as it is made (the command line
    starts drawing its figures then)."""
    seen = []
    report = build_report(Engine.example("vaz2108"), built=lambda s: seen.append(s.key))
    assert seen == [s.key for s in report.sections] and seen
