"""One quantity, one declaration (issue 31): every key figure of every analysis of every
built-in engine, as its result declares it (:meth:`crankdyn.results.Result.summary`), is the
same label, unit and value in the command line's table and JSON, the report (summary.json, the
key-figure CSV and the section's figures), the study's figure registry and a notebook's view,
since every front end renders the one summary of one :class:`crankdyn.Analysis`."""

from __future__ import annotations

import csv
import html
import io
import json
import math

import pytest

import crankdyn
from crankdyn.errors import InputError
from crankdyn.io.examples import example_names
from crankdyn.report.build import build_report
from crankdyn.session import ANALYSES
from crankdyn.study.figures import FIGURES, AnalysisSettings, CaseContext

pytestmark = pytest.mark.slow  # long: started first (tests/conftest.py)

COMMANDS = {  # the command that shows each analysis (the engine's name follows)
    "kinematics": ("kinematics",),
    "pressure": ("pressure",),
    "forces": ("forces",),
    "bearings": ("bearings",),
    "torque": ("torque",),
    "balance": ("balance",),
    "flywheel": ("flywheel",),
    "modes": ("torsion", "modes"),
    "response": ("torsion", "response"),
    "relative_angle": ("torsion", "response"),
    "judged": ("torsion", "response"),
    "crankshaft": ("crankshaft",),
    "crankshaft_modes": ("crankshaft", "modes"),
    "crankshaft_response": ("crankshaft", "response"),
}
JSON_PART = {"relative_angle": "relative_angle", "judged": "judged"}  # where the JSON holds it


def _find(data, key):
    """The value under ``key`` in a JSON document (depth first: a nested result's figures sit
    in its own object, as the kinematics' summary)."""
    if isinstance(data, dict):
        if key in data:
            return data[key]
        for value in data.values():
            found = _find(value, key)
            if found is not _MISSING:
                return found
    return _MISSING


_MISSING = object()


def _same(got, want):
    if isinstance(want, float):
        return isinstance(got, (int, float)) and (got == want or (math.isnan(want) and got is None))
    return got == want


def _results(session):
    """(analysis, result) of every analysis that applies to the session's subject."""
    out = []
    for analysed in ANALYSES:
        try:
            result = analysed.of(session)
        except InputError:  # e.g. no [torsion] model, no speed range
            continue
        if result is not None:
            out.append((analysed.name, result))
    return out


@pytest.mark.parametrize("name", example_names("engine"))
def test_every_key_figure_is_the_same_in_every_front_end(cli, name):
    engine = crankdyn.Engine.example(name)
    notebook = crankdyn.Analysis(engine)
    report = build_report(engine)
    report_figures = {f.key: f for f in report.key_figures()}
    summary_json = report.summary()["key_figures"]
    key_csv = {r["key"]: r for r in csv.DictReader(io.StringIO(report.key_figures_csv()))}
    case = CaseContext(engine, AnalysisSettings())
    runs: dict = {}
    for analysis, result in _results(notebook):
        command = COMMANDS[analysis]
        extra = ()
        if analysis in ("response", "relative_angle", "judged"):
            first, last = notebook.model.mass_names[0], notebook.model.mass_names[-1]
            extra = ("--relative", f"{first},{last}")
        if command not in runs:  # one run of each command, table and JSON
            table = cli(*command, name, *extra)
            data = cli(*command, name, *extra, "--format", "json")
            assert table.status in (0, 1) and data.status in (0, 1), (table, data)
            runs[command] = (table.out, json.loads(data.out))
        table, data = runs[command]
        data = data[JSON_PART[analysis]] if analysis in JSON_PART else data
        page = result._repr_html_()
        lines = table.splitlines()
        for f in result.summary().figures:
            where = (name, analysis, f.key)
            # JSON: the value under its key
            assert _same(_find(data, f.key), f.value), where
            # the table: the label and the value, in one row
            digits, unit = f.text()
            if len(digits) <= 40:
                row = [ln for ln in lines if f.label in ln and digits in ln]
                assert row, where
                assert not unit or unit in row[0], where
            # the report: summary.json, its CSV and the section's figure
            assert _same(summary_json[f.key], f.value), where
            shown = report_figures[f.key]
            assert (shown.label, shown.unit) == (f.label, f.unit), where
            assert key_csv[f.key]["label"] == f.label and key_csv[f.key]["unit"] == f.unit
            # the study: the same figure under its name
            figure = FIGURES.get(f.name)
            if figure is not None and figure.key == f.key:
                assert (figure.label, figure.unit) == (f.label, f.unit), where
                if isinstance(f.value, (int, float)) and not isinstance(f.value, bool):
                    got = figure.evaluate(case)
                    assert got == pytest.approx(f.value, rel=1e-15, nan_ok=True), where
            # a notebook: the result's own view
            assert html.escape(f.label) in page and html.escape(digits) in page, where


def test_the_response_and_the_tvc_agree(cli):
    """One verdict per check: ``torsion response`` and ``tvc``'s normal-firing condition judge
    the same response with the same checks: the same rows and the same barred ranges, as found
    and as declared."""
    session = crankdyn.Analysis(crankdyn.Engine.example("marine-propulsion"))
    judged = session.judged()
    tvc = session.tvc(passage=False, conditions=("normal",))
    (normal,) = tvc.conditions
    assert [v.to_dict() for v in normal.verdicts] == [v.to_dict() for v in judged.verdicts]
    assert [b.to_dict() for b in normal.barred_ranges] == [
        b.to_dict() for b in judged.barred_ranges
    ]
