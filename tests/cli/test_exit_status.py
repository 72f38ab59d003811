"""The exit status of the commands that print a verdict (docs/errors.md): 0 when every verdict
passed, 1 when one failed (the analysis ran and its output is written), 2 on an error;
``--no-fail`` gives 0. ``crankdyn tvc`` and ``crankdyn torsion response`` give the same
verdict (the same normal-firing rows) for the same options and rules, on the class-flip line
(tests/tvc/data/class-flip-line.toml: passed under LR, failed under KR)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from crankdyn.cli import main
from crankdyn.cli.common import EXIT_STATUS_HELP

LINE = str(Path(__file__).parents[1] / "tvc" / "data" / "class-flip-line.toml")


def run(capsys, *args):
    status = main([str(a) for a in args])
    out, err = capsys.readouterr()
    return status, out, err


def _rows(verdicts):
    return {
        (v["component"], v["quantity"]): (v["worst"], v["limit"], v["passed"], v["clause"])
        for v in verdicts
        if v["condition"] == "normal firing"
    }


@pytest.fixture(scope="module")
def tvc_runs(tmp_path_factory):
    """``crankdyn tvc LINE --rules KEY`` under LR and KR (report folders, no PDF)."""
    import contextlib
    import io

    out = {}
    for key in ("lr", "kr"):
        target = tmp_path_factory.mktemp("tvc") / key
        stdout, stderr = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
            status = main(["tvc", LINE, "--rules", key, "-o", str(target), "--no-pdf"])
        summary = json.loads((target / "summary.json").read_text(encoding="utf-8"))
        out[key] = (status, stdout.getvalue(), stderr.getvalue(), summary)
    return out


def test_tvc_exit_status_follows_the_verdict(tvc_runs):
    status, out, err, summary = tvc_runs["lr"]
    assert status == 0, err
    assert "Verdict: passed" in out
    status, out, err, summary = tvc_runs["kr"]
    assert status == 1, err  # the report is written all the same
    assert "Verdict: FAILED" in out and "crankdyn: error" not in err
    assert not all(v["passed"] for v in summary["verdicts"])


def test_tvc_no_fail_and_bad_input(capsys, tmp_path):
    status, out, err = run(
        capsys, "tvc", LINE, "--rules", "kr", "-o", tmp_path / "r", "--no-pdf", "--no-fail"
    )
    assert status == 0, err
    assert "Verdict: FAILED" in out and (tmp_path / "r" / "index.html").is_file()
    status, out, err = run(capsys, "tvc", LINE, "--rules", "krr", "-o", tmp_path / "x")
    assert status == 2 and out == "" and not (tmp_path / "x").exists()
    assert err.strip() == (
        'crankdyn: error: --rules = "krr": expected one of iacs-m68, lr, kr, dnv, abs, bv '
        '(did you mean "kr"?)'
    )
    status, _, err = run(capsys, "tvc", "no-such-line", "-o", tmp_path / "y", "--no-fail")
    assert status == 2 and err.count("\n") == 1


def test_torsion_response_gives_the_tvcs_verdict(capsys, tvc_runs):
    """The same rows (the normal-firing condition, every value and clause) and the same exit
    status from ``torsion response`` as from ``tvc``, under LR and under KR."""
    for key, expected in (("lr", 0), ("kr", 1)):
        status, out, err = run(
            capsys, "torsion", "response", LINE, "--rules", key, "--format", "json"
        )
        assert status == expected == tvc_runs[key][0], err
        judged = json.loads(out)["judged"]
        ours = _rows(judged["verdicts"])
        theirs = _rows(tvc_runs[key][3]["verdicts"])
        assert ours.keys() == theirs.keys()
        for row, (worst, limit, passed, clause) in ours.items():
            t_worst, t_limit, t_passed, t_clause = theirs[row]
            assert (passed, clause) == (t_passed, t_clause), row
            for a, b in ((worst, t_worst), (limit, t_limit)):
                assert (a is None and b is None) or math.isclose(a, b, rel_tol=1e-12), row
    status, _, err = run(capsys, "torsion", "response", LINE, "--rules", "kr", "--no-fail")
    assert status == 0, err
    status, out, err = run(capsys, "torsion", "response", LINE, "--rules", "nope")
    assert status == 2 and out == "" and err.count("\n") == 1 and "--rules" in err


@pytest.mark.parametrize("command", [("tvc",), ("torsion", "response"), ("torsion", "transient")])
def test_verdict_commands_document_their_exit_status(capsys, command):
    status, out, _ = run(capsys, *command, "--help")
    assert status == 0
    text = " ".join(out.split())
    assert "Exit status: 0" in text and "--no-fail" in text
    assert " ".join(EXIT_STATUS_HELP.split()[:4]) in text
