"""A verdict row no computation's error can overturn (issue 37's modal truncation; "nothing
passes silently"): a row states the bound of its worst value's error, a row within it of its
limit is undecided (never a clean "passed"), and the TVC runs an event or a passage again with
every mode when its truncation's bound could overturn one of its rows."""

from __future__ import annotations

import dataclasses
from functools import lru_cache

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.summary import Verdict, verdict_cells, verdict_of, verdict_text


def _row(worst: float, limit: float, bound: float, passed: bool | None = None) -> Verdict:
    return Verdict(
        "intermediate shaft", "ice impact", "peak vs τ_T", worst, limit, "Pa",
        worst <= limit if passed is None else passed, "IACS UR M68", error_bound=bound,
    )  # fmt: skip


@pytest.mark.parametrize(
    ("worst", "limit", "bound", "undecided"),
    [
        (40e6, 41e6, 1e6, True),  # passed by the bound exactly: could fail
        (40e6, 41e6, 0.999e6, False),
        (42e6, 41e6, 1e6, True),  # failed by the bound: could pass
        (42e6, 41e6, 0.5e6, False),
        (40e6, 41e6, 0.0, False),  # no bound stated
        (40e6, float("nan"), 5e6, False),  # no limit
        (float("nan"), 41e6, 5e6, False),
    ],
)
def test_a_row_within_its_error_bound_of_its_limit_is_undecided(worst, limit, bound, undecided):
    row = _row(worst, limit, bound)
    assert row.undecided is undecided
    data = row.to_dict()
    assert data.get("undecided", False) is undecided
    assert data.get("error_bound", 0.0) == bound
    cell = verdict_cells([row])[1][0][8]
    assert cell == ("passed" if row.passed else "FAILED") + (" (undecided)" if undecided else "")


def test_the_verdict_counts_the_undecided_rows_and_input_warnings():
    from crankdyn.plausibility import InputWarning

    sure, open_ = _row(30e6, 41e6, 1e6), _row(40.5e6, 41e6, 1e6)
    assert verdict_of([sure]) == "passed"
    assert verdict_of([sure, open_]) == "passed, with 1 undecided row"
    assert verdict_of([sure, open_, open_]) == "passed, with 2 undecided rows"
    assert verdict_of([_row(41.5e6, 41e6, 1e6)]) == "FAILED, with 1 undecided row"
    assert verdict_of([]) is None
    warning = InputWarning(
        "stiffness", "Shaft stiffness", 1e12, "N·m/rad", 1e3, 1e9, "crankdyn", "check the unit",
        file="line.toml", written="1e12",
    )  # fmt: skip
    assert verdict_of([open_], [warning]) == "passed, with 1 input warning and 1 undecided row"
    assert verdict_text(True, 0, 0) == "passed"


def test_a_result_and_its_report_give_the_verdict_with_its_undecided_rows():
    """The result's summary, its JSON and the report's section take the verdict from one
    place (:func:`crankdyn.summary.verdict_of`)."""
    from crankdyn.report.model import Section
    from crankdyn.summary import Summary

    summary = Summary("TVC", verdicts=(_row(30e6, 41e6, 1e6), _row(40.5e6, 41e6, 1e6)))
    assert summary.verdict == "passed, with 1 undecided row"
    assert summary.to_dict()["verdict"] == summary.verdict
    section = Section.of("tvc", "TVC", [summary])
    assert section.verdict == summary.verdict


def test_the_run_is_decided_again_at_a_higher_cutoff_then_with_every_mode(monkeypatch):
    """:func:`crankdyn.tvc.events.decided`: a truncated run whose rows are all decided stands;
    one with an undecided row is run again at four times its cut-off, then with every mode
    while a row stays undecided, and the rows are the last run's; a small line runs every
    mode at once."""
    from crankdyn.tvc.events import decided

    @dataclasses.dataclass(frozen=True)
    class Run:
        scale: float | None
        notes: tuple[str, ...] = ()

    class Line:
        dof_count = 10

    monkeypatch.setattr("crankdyn.tvc.events.EVENT_TRUNCATION_DOFS", 5)
    asked: list[float | None] = []

    def run_with(scale: float | None) -> Run:
        asked.append(scale)
        return Run(scale)

    def judge(bounds: dict):
        return lambda run: [_row(40e6, 41e6, bounds.get(run.scale, 0.0))]

    run, rows = decided(Line(), run_with, judge({1.0: 0.5e6}))
    assert asked == [1.0] and run.scale == 1.0 and rows[0].error_bound == 0.5e6
    assert run.notes == ()
    asked.clear()
    run, rows = decided(Line(), run_with, judge({1.0: 2e6, 4.0: 0.1e6}))
    assert asked == [1.0, 4.0] and rows[0].error_bound == 0.1e6
    assert run.notes == (
        "run again with 4 times its cut-off: the modal truncation's bound could overturn "
        "1 row(s) (intermediate shaft: 4e+07 against 4.1e+07 Pa, bound 2e+06)",
    )
    asked.clear()
    run, rows = decided(Line(), run_with, judge({1.0: 2e6, 4.0: 1.5e6}))
    assert asked == [1.0, 4.0, None] and run.scale is None
    assert rows == [_row(40e6, 41e6, 0.0)]
    assert len(run.notes) == 2 and run.notes[1].startswith("run again with every mode")
    monkeypatch.setattr("crankdyn.tvc.events.EVENT_TRUNCATION_DOFS", 50)
    asked.clear()
    decided(Line(), run_with, judge({1.0: 2e6}))
    assert asked == [None]  # a small line: every mode at once, nothing undecided


@lru_cache(maxsize=1)
def _marine():
    from crankdyn.io.catalogue import resolve_model_and_engine
    from crankdyn.session import Analysis

    _model, engine = resolve_model_and_engine("marine-propulsion")
    return Analysis(engine)


def test_marine_ice_impact_rows_within_their_bounds_and_decided_with_every_mode(monkeypatch):
    """The marine TVC's ice impact, truncated (the threshold lowered: the 38-mass line
    integrates every mode in the TVC): every verdict row's worst value lies within the row's
    stated bound of the all-mode run's (the bound validated against the independent
    computation with every mode). The bound decides every row of the example (the truncated
    run stands); with every limit moved to within the bound of its row's worst value,
    :func:`~crankdyn.tvc.events.decided` runs it again with every mode and its rows stand on
    the all-mode run."""
    from crankdyn.tvc.events import _run, decided, judge_event

    monkeypatch.setattr("crankdyn.tvc.events.EVENT_TRUNCATION_DOFS", 1)
    session = _marine()
    model, spec, rated = session.loaded_model, session.tvc_spec, 750 / RPM
    te = spec.events[2]  # the ice impact
    assert "ice" in te.name

    def run_with(scale):
        return _run(model, te, rated, session.excitation(), session.orders, scale is not None)

    def judge(run):
        return list(judge_event(model, run, spec, rated).verdicts)

    cut, exact = judge(run_with(1.0)), judge(run_with(None))
    assert len(cut) == len(exact) > 3
    bounded = [v for v in cut if v.error_bound > 0.0]
    assert len(bounded) == len(cut)
    for a, b in zip(cut, exact, strict=True):
        assert (a.component, a.quantity) == (b.component, b.quantity)
        assert abs(a.worst - b.worst) <= a.error_bound, (a.component, a.quantity)
        assert b.error_bound == 0.0 and not b.undecided
    assert not any(v.undecided for v in cut)  # the bound decides every row here: no rerun
    run, rows = decided(model, run_with, judge)
    assert rows == cut and run.cutoff_frequency is not None

    def close(run):  # every limit moved to within half the row's bound of its worst value
        return [dataclasses.replace(v, limit=v.worst + 0.5 * v.error_bound) for v in judge(run)]

    # (run_with gives the first cut-off at every truncated step: the rows stay undecided
    # until the run with every mode)

    run, rows = decided(model, run_with, close)
    assert run.cutoff_frequency is None and "run again with every mode" in run.notes[-1]
    from crankdyn.tvc.result import truncation_fields

    assert "run again with every mode" in truncation_fields(run)["truncation"]  # exported
    assert [v.worst for v in rows] == [v.worst for v in exact]
    assert all(v.error_bound == 0.0 and not v.undecided for v in rows)
    np.testing.assert_array_equal([v.limit for v in rows], [v.worst for v in exact])
