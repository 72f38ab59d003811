"""A design search tables its best designs' verdict rows as its workers kept them in their
journal records (issue 39, item 5: what a candidate's evaluation computed is not computed
again): the rows read back from the records equal those of the candidate analysed afresh in
this process (every field, through the journal's JSON), for the normal-firing rows and for
the whole TVC's."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from crankdyn.io.design_file import load_design
from crankdyn.io.study_file import parse_base
from crankdyn.study.figures import CaseContext, case_verdicts
from crankdyn.study.run.design import candidate_document, run_design

DATA = Path(__file__).resolve().parents[2] / "validation" / "data"


def _fresh(space, case):
    """The candidate's verdict rows analysed here, from its document."""
    base = space.study.base
    document = candidate_document(space, case)
    subject = parse_base(base.kind, document, file=base.source, base_dir=base.base_dir)
    ctx = CaseContext(subject, space.study.settings, base.kind)
    return case_verdicts(ctx, space.study.figures)


@pytest.mark.parametrize("verdicts", ["normal", "all"])
def test_the_best_designs_rows_are_the_workers_and_equal_a_fresh_analysis(tmp_path, verdicts):
    for name in ("small_coupling_line.toml", "small_couplings.csv", "small_coupling_design.toml"):
        shutil.copy(DATA / name, tmp_path / name)
    path = tmp_path / "small_coupling_design.toml"
    text = path.read_text(encoding="utf-8").replace("max_candidates = 60", "max_candidates = 6")
    if verdicts == "all":
        text += '\n[constraints]\nverdicts = "all"\n'
    path.write_text(text, encoding="utf-8")
    space = load_design(path)
    assert space.study.verdict_rows
    result = run_design(space, tmp_path / "out", workers=1)
    records = [
        json.loads(line)
        for line in (tmp_path / "out" / "journal.jsonl").read_text(encoding="utf-8").splitlines()
    ]
    assert records and all(r["verdicts"] for r in records if r["status"] == "ok")
    assert result.best_verdicts
    for rows, candidate in zip(result.best_verdicts, result.ranked(), strict=False):
        fresh = _fresh(space, candidate.case)
        assert rows == fresh and len(rows) > 0
        assert all(a.kind == b.kind for a, b in zip(rows, fresh, strict=True))
    if verdicts == "all":  # the whole TVC's rows: its verdict follows them
        assert "failed_rows" in space.study.figures
        assert result.tvc is None  # not computed again for the table
        assert result.tvc_passed is all(v.passed for v in result.best_verdicts[0])
