"""The verdict on implausible inputs (issue 32, item 2): the wording is declared once
(crankdyn.summary.verdict_text) and every result the analysis session computes from an engine or
a model whose file carries input warnings carries them first, so no verdict, figure status or
JSON of it reads a clean "passed". The front ends: tests/cli/test_input_warnings_cli.py."""

from __future__ import annotations

import dataclasses

import pytest

from crankdyn.io.catalogue import resolve_model_and_engine
from crankdyn.io.engine_file import parse_engine
from crankdyn.io.examples import example_path
from crankdyn.io.files import load_toml
from crankdyn.plausibility import InputWarning, PlausibilityWarning
from crankdyn.session import Analysis
from crankdyn.summary import Summary, Verdict, verdict_status, verdict_text

WARNING = InputWarning(
    key="input:a",
    quantity="shaft diameters",
    value=180.0,
    unit="m",
    low=0.003,
    high=3.0,
    source="test rigs to the largest engines",
    message="line.toml: [[shaft]] #3 outer_diameter = 180: 180 m is outside ...",
    file="line.toml",
    input_key="[[shaft]] #3 outer_diameter",
    written=180,
)
OWN = PlausibilityWarning("imep", "IMEP", 19e6, "Pa", 1.2e6, 3.8e6, "Heywood", "IMEP 19 MPa")
ROW = Verdict("shaft", "normal firing", "stress", 1e6, 40e6, "Pa", True, "IACS UR M68", "M68.4")


@pytest.mark.parametrize(
    "passed, count, text, status",
    [
        (True, 0, "passed", "pass"),
        (True, 1, "passed, with 1 input warning", "warn"),
        (True, 3, "passed, with 3 input warnings", "warn"),
        (False, 0, "FAILED", "fail"),
        (False, 2, "FAILED, with 2 input warnings", "fail"),
        (None, 1, None, None),
    ],
)
def test_the_wording(passed, count, text, status):
    assert verdict_text(passed, count) == text
    assert verdict_status(text) == status


def test_the_summary_counts_only_input_warnings():
    summary = Summary("t", warnings=(WARNING, OWN), verdicts=(ROW,))
    assert summary.input_warnings == (WARNING,)
    assert summary.verdict == "passed, with 1 input warning"
    data = summary.to_dict()
    assert [w["check"] for w in data["input_warnings"]] == ["input"]
    assert [w["check"] for w in data["warnings"]] == ["imep"]
    assert data["verdict"] == "passed, with 1 input warning" and data["passed"] is True
    assert Summary("t", warnings=(OWN,), verdicts=(ROW,)).verdict == "passed"


@pytest.fixture(scope="module")
def warned():
    """The marine propulsion engine with a bare 300 for the [torsion.tvc.crankshaft] diameter
    (300 m for 300 mm): its crank spans' nominal stress falls a million-fold, so it passes."""
    data = load_toml(example_path("marine-propulsion"))
    data["torsion"]["tvc"]["crankshaft"]["diameter"] = 300
    base = example_path("marine-propulsion").parent
    return parse_engine(data, file="mp.toml", base_dir=base)


def test_the_engine_and_its_model_carry_the_warning(warned):
    (w,) = warned.input_warnings
    assert w.input_key == "[torsion.tvc.crankshaft] diameter" and w.written == 300
    assert warned.torsion is not None and warned.torsion.input_warnings == (w,)


def test_every_session_result_carries_it_first(warned):
    session = Analysis(warned)
    assert session.input_warnings == warned.input_warnings
    judged = session.judged()
    assert judged is not None and judged.warnings[:1] == warned.input_warnings
    summary = judged.summary()
    assert summary.verdict == "passed, with 1 input warning"
    figure = summary.figure("condition_passed")
    assert (figure.value, figure.status) == (True, "warn")
    assert figure.display() == "yes, with 1 input warning"
    assert session.modes.warnings == warned.input_warnings
    key = warned.input_warnings[0].input_key
    assert session.response().to_dict()["input_warnings"][0]["key"] == key
    forces = session.forces()
    assert forces.warnings[: len(warned.input_warnings)] == warned.input_warnings


def test_a_tvc_holds_it_in_every_condition(warned):
    import dataclasses

    session = Analysis(warned)
    # the running conditions (the example's clutch-in event fails its gear row by design)
    result = session.tvc(passage=False, spec=dataclasses.replace(session.tvc_spec, events=()))
    assert result.summary().verdict == "passed, with 1 input warning"
    assert result.summary().figure("verdict").status == "warn"
    assert result.to_dict()["verdict"] == "passed, with 1 input warning"
    for condition in result.condition_results:
        assert condition.warnings[:1] == warned.input_warnings
        assert condition.summary().verdict.startswith("passed, with 1 input warning")
    assert result.conditions == result.condition_results  # still the same objects
    assert all(a is b for a, b in zip(result.conditions, result.condition_results, strict=True))
    assert result.modes is not None and result.modes.warnings == warned.input_warnings


def test_the_same_line_without_the_warning_passes_cleanly():
    _model, engine = resolve_model_and_engine("marine-propulsion")
    session = Analysis(engine)
    assert session.input_warnings == ()
    judged = session.judged()
    assert judged is not None and judged.summary().verdict == "passed"
    assert "input_warnings" not in judged.to_dict()


def test_the_crankshaft_check_carries_the_engine_files_warnings():
    from crankdyn.crankshaft.strength import crankshaft_strength

    data = load_toml(example_path("marine-propulsion"))
    data["crankshaft"]["web_width"] = 480  # 480 m for 480 mm
    engine = parse_engine(data, file="mp.toml", base_dir=example_path("marine-propulsion").parent)
    summary = crankshaft_strength(engine).summary()
    assert [w.input_key for w in summary.input_warnings] == ["[crankshaft] web_width"]
    assert summary.verdict is not None and summary.verdict.endswith(", with 1 input warning")


def test_warnings_do_not_change_what_a_result_equals(warned):
    """The warnings are carried, not compared: the same numbers are the same result."""
    result = Analysis(warned).modes
    assert dataclasses.replace(result, warnings=()) == result
