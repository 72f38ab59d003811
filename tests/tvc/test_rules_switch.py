"""Switching the rule set of the TVC's checks (``[tvc] rules``, ``--rules``): every verdict row
and barred range cites its rule, edition and clause (and says so where the clause could not be
verified); a switch between the six societies changes exactly the rows whose rule values differ
(:func:`crankdyn.tvc.rulesets.differences`), and between societies whose values are the same
only the citations.

Two lines: the class-flip line (tests/tvc/data/class-flip-line.toml: engine, elastic
coupling, 3:1 gearbox, propeller; an 800 N/mm^2 carbon-steel intermediate shaft whose order-3
resonance at 0.94 n_0 lies between KR's and LR's tau_C) and the built-in verdict-geared-line
(barred ranges of two shafts near 0.79 n_0: the least range and LR's 500 N/mm^2 show)."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest

from crankdyn.constants import RPM
from crankdyn.io.catalogue import resolve_model_and_engine
from crankdyn.session import Analysis
from crankdyn.torsion.model import TorsionModel
from crankdyn.tvc import rulesets as R
from crankdyn.tvc.analysis import judge
from crankdyn.tvc.checks import model_checks, shaft_label
from crankdyn.tvc.spec import TvcSpec

LINE = Path(__file__).parent / "data" / "class-flip-line.toml"
KEYS = R.RULESET_KEYS
BARRED_KINDS = {
    "barred range end",
    "barred range at n_0",
    "barred range steady state",
    "barred range without a transient limit",
    "least tensile strength",
    "keyway with a barred range",
}
"""The rows a barred range brings (evaluate.py, checks.py)."""


def _judged_all(model: TorsionModel) -> dict:
    """{key: (verdicts, barred)} of one response judged under every rule set."""
    response = Analysis(model).response()
    base = model.tvc or TvcSpec()
    return {k: judge(model, response, dataclasses.replace(base, rules=k)) for k in KEYS}


@pytest.fixture(scope="module")
def lines():
    flip = TorsionModel.from_file(LINE)
    geared, _ = resolve_model_and_engine("verdict-geared-line")
    return {"flip": (flip, _judged_all(flip)), "geared": (geared, _judged_all(geared))}


def _rows(verdicts):
    """{(component, kind): (quantity, worst, limit, passed)}: a row's identity is its component
    and what it checks, whatever range it covers."""
    out = {}
    for v in verdicts:
        key = (v.component, v.kind or v.quantity)
        assert key not in out, key
        out[key] = (v.quantity, v.worst, v.limit, v.passed)
    return out


def _same(a, b) -> bool:
    qa, wa, la, pa = a
    qb, wb, lb, pb = b
    close = all(
        (math.isnan(x) and math.isnan(y)) or x == pytest.approx(y, rel=1e-12)
        for x, y in ((wa, wb), (la, lb))
    )
    return qa == qb and pa == pb and close


def _shafts_of(model, material: str, kind: str) -> set[str]:
    """The components of the [rules] shafts of a material and kind."""
    out = set()
    for limit in model.rules.shafts:
        if (limit.material, limit.kind) == (material, kind):
            s = next(sh for sh in model.shafts if tuple(sh.between) == tuple(limit.between))
            out.add(shaft_label(s))
    return out


ROWS_OF_VALUE = {
    "widening": lambda component, kind: kind in BARRED_KINDS,
    "min_strength_transient": lambda component, kind: kind == "least tensile strength",
    "keyways": lambda component, kind: kind == "keyway with a barred range",
    "major_criticals": lambda component, kind: kind.startswith("major critical"),
    "crankshaft": lambda component, kind: component.startswith(("crank span", "alternator")),
    "genset": lambda component, kind: component.startswith(("crank span", "alternator")),
}
"""The rows a value of a rule set (named as in :func:`crankdyn.tvc.rulesets.differences`, up
to its first space) may change, besides the caps (the rows of the shafts they cap)."""


def _explained(model, names, key, barred_changed: bool) -> bool:
    """Whether a change of the row ``key`` follows from the values ``names`` that differ."""
    component, kind = key
    for name in names:
        head, _, rest = name.partition(" ")
        if head == "strength_caps":
            material, shaft_kind = rest.split("/")
            if component in _shafts_of(model, material, shaft_kind):
                return True
        elif head in ROWS_OF_VALUE and ROWS_OF_VALUE[head](component, kind):
            return True
    # a barred range that moved changes the speeds of continuous running of every check
    continuous = not kind.startswith(("major critical", "transient")) and kind not in BARRED_KINDS
    return barred_changed and continuous


@pytest.mark.parametrize("line", ["flip", "geared"])
def test_switching_rules_changes_exactly_the_rows_whose_values_differ(lines, line):
    model, judged = lines[line]
    for a in KEYS:
        for b in KEYS:
            names = R.differences(R.get(a), R.get(b))
            rows_a, rows_b = _rows(judged[a][0]), _rows(judged[b][0])
            ranges_a = [(r.component, r.start, r.end) for r in judged[a][1]]
            ranges_b = [(r.component, r.start, r.end) for r in judged[b][1]]
            changed = {
                k
                for k in rows_a.keys() | rows_b.keys()
                if k not in rows_a or k not in rows_b or not _same(rows_a[k], rows_b[k])
            }
            unexplained = [
                k for k in changed if not _explained(model, names, k, ranges_a != ranges_b)
            ]
            assert not unexplained, (a, b, names, unexplained)
            # where a limit is exceeded (the ranges as found) changes only with the limit:
            # the least range and the tachometer move the declared ends, never the found ones
            found_a = {(r.component, r.exceeds_start, r.exceeds_end) for r in judged[a][1]}
            found_b = {(r.component, r.exceeds_start, r.exceeds_end) for r in judged[b][1]}
            for component, *_ in found_a ^ found_b:
                assert _explained(model, names, (component, "limit"), False), (a, b, component)
            if not names:  # the same values: the same rows, only the citations switch
                assert not changed and ranges_a == ranges_b, (a, b)


def test_the_switches_that_matter_change_their_rows(lines):
    """The values that differ do change the rows they name: KR's 600 N/mm^2 cap the flip
    line's shaft limit by (600 + 160)/(760 + 160); LR's 500 N/mm^2 row appears with LR's
    barred ranges; the least range moves the declared ends; KR's window adds its rows."""
    flip_model, flip = lines["flip"]
    speeds = np.linspace(0.5, 1.05, 12) * 750 / RPM
    limits = {}
    for key in ("lr", "kr"):
        spec = dataclasses.replace(flip_model.tvc, rules=key)
        (check, *_), _notes = model_checks(flip_model, spec, 750 / RPM, ())
        assert check.component == "intermediate shaft (thrust collar - propeller)"
        limits[key] = check.limit(speeds)
    np.testing.assert_allclose(limits["kr"] / limits["lr"], 760 / 920, rtol=1e-12)
    lr, kr = _rows(flip["lr"][0]), _rows(flip["kr"][0])
    assert {k for k in kr if k[1].startswith("major critical")}
    assert not {k for k in lr if k[1].startswith("major critical")}
    _, geared = lines["geared"]
    least = {k for k in _rows(geared["lr"][0]) if k[1] == "least tensile strength"}
    assert least and not {k for k in _rows(geared["iacs-m68"][0]) if k[1] in least}
    ends = {key: [(b.start, b.end) for b in geared[key][1]] for key in ("iacs-m68", "lr")}
    assert len(ends["lr"]) == len(ends["iacs-m68"]) and ends["lr"] != ends["iacs-m68"]
    for (s_lr, e_lr), (s_m68, e_m68) in zip(ends["lr"], ends["iacs-m68"], strict=True):
        assert s_lr <= s_m68 and e_lr >= e_m68  # the least range widens, never narrows


@pytest.mark.parametrize("key", KEYS)
def test_every_row_cites_rule_edition_and_clause(lines, key):
    society = R.get(key)
    for line in ("flip", "geared"):
        model, judged = lines[line]
        verdicts, barred = judged[key]
        assert verdicts
        for v in verdicts:
            assert v.source and v.clause, v
        shafts = {shaft_label(sh) for sh in model.shafts if sh.geometry is not None}
        for v in verdicts:
            if v.component not in shafts or v.kind == "least tensile strength":
                continue
            formula = society.transient_formula if "steady state" in v.quantity else None
            if v.kind.startswith("synthesised vibratory shear stress"):
                formula = society.shaft_formula
            if formula is None:  # the barred-range rows cite the barred-range rule
                formula = society.barred_upper.clause
            assert v.source.startswith(formula.source), (v.source, formula.source)
            assert formula.row() in v.clause, (formula.row(), v.clause)
            if not formula.verified:
                assert "not verified against the text" in v.clause
        for b in barred:
            assert b.source.startswith(society.barred_upper.clause.source)
            assert society.widening.clause.row() in b.clause
            assert society.barred_upper.clause.row() in b.clause


def test_unverified_values_say_where_they_come_from(lines):
    """DNV, ABS and BV rows cite their own rule text, "not verified against the text: value as
    IACS UR M68"; KR's rows cite clauses read in the text, with no such mark."""
    _, judged = lines["flip"]
    for key in ("dnv", "abs", "bv"):
        row = next(v for v in judged[key][0] if v.kind.startswith("synthesised vibratory shear"))
        assert row.source.startswith(R.get(key).shaft_formula.rule)
        assert "not verified against the text: value as IACS UR M68" in row.clause
    row = next(v for v in judged["kr"][0] if v.kind.startswith("synthesised vibratory shear"))
    assert "not verified" not in row.clause
    assert row.clause.startswith("τ_C: Pt 5 Ch 4 202.1(1); σ_B cap: Pt 5 Ch 4 202.1(1)")


def test_session_rules_and_the_file_key(lines):
    """``Analysis(rules=...)`` (``--rules``) replaces the file's ``[tvc] rules``; the judged
    condition and the TVC's normal-firing condition give the same rows."""
    model, judged = lines["flip"]
    for key in ("lr", "kr"):
        session = Analysis(model, rules=key)
        assert session.tvc_spec.rules == key
        rows = _rows(session.judged().verdicts)
        assert rows.keys() == _rows(judged[key][0]).keys()
        assert all(_same(rows[k], _rows(judged[key][0])[k]) for k in rows)
        normal = session.tvc(passage=False).conditions[0]
        assert normal.name == "normal firing"
        assert _rows(normal.verdicts).keys() == rows.keys()
        assert all(_same(rows[k], _rows(normal.verdicts)[k]) for k in rows)
        assert normal.passed == session.judged().passed == (key == "lr")
