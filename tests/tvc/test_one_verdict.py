"""One verdict per check (issue 31): ``crankdyn torsion response`` and ``crankdyn tvc`` give the
same normal-firing verdict, the same declared barred ranges and the same reason for the same
file with default options, on a lightly damped marine line whose stress range lies just below
0.8 n_0 and is widened above it by the tachometer tolerance (tests/tvc/data/below-08-line.toml).
The found range (698.9-705.0 rpm) and the 2 % widening are checked by hand against the found
ends: start x 0.98 and end x 1.02 (IACS UR M68.4, the tachometer tolerance as [tvc] gives it)."""

from __future__ import annotations

import contextlib
import io
import json
import math
from pathlib import Path

import pytest

from crankdyn.cli import main

LINE = str(Path(__file__).parent / "data" / "below-08-line.toml")
SHAFT = "intermediate shaft (thrust collar - propeller)"
N0 = 889.0  # rpm, the file's rated speed


def _run(*args: str) -> tuple[int, str, str]:
    stdout, stderr = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(stdout), contextlib.redirect_stderr(stderr):
        status = main(list(args))
    return status, stdout.getvalue(), stderr.getvalue()


def _block(text: str, title: str) -> str:
    """The terminal's block from ``title`` up to the next notes, whitespace folded."""
    start = text.index(title)
    end = text.find("Note:", start)
    return " ".join(text[start : end if end > 0 else None].split())


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    target = tmp_path_factory.mktemp("tvc") / "out"
    tvc = _run("tvc", LINE, "-o", str(target), "--no-pdf", "--no-passage")
    summary = json.loads((target / "summary.json").read_text(encoding="utf-8"))
    response = _run("torsion", "response", LINE)
    response_json = json.loads(_run("torsion", "response", LINE, "--format", "json")[1])
    return tvc, summary, response, response_json


def test_same_verdict_and_exit_status(runs):
    (t_status, t_out, t_err), summary, (r_status, r_out, r_err), _ = runs
    assert t_status == r_status == 1, (t_err, r_err)
    assert "Verdict: FAILED" in t_out and "Verdict: FAILED" in r_out
    failed = {v["component"] for v in summary["verdicts"] if not v["passed"]}
    assert SHAFT in failed


def test_same_declared_ranges_found_and_declared_with_the_reason(runs):
    (_, t_out, _), summary, (_, r_out, _), response_json = runs
    # the terminal shows the same table of ranges, as found and as declared, with why
    assert _block(t_out, "Barred speed ranges") == _block(r_out, "Barred speed ranges")
    ranges = response_json["judged"]["barred_speed_ranges"]
    (shaft,) = [b for b in ranges if b["component"] == SHAFT]
    ours = {(b["component"], b["condition"]): b for b in ranges}
    for b in summary["barred_speed_ranges"]:
        if b["condition"] != "normal firing":
            continue
        r = ours[(b["component"], b["condition"])]
        assert b["permitted"] == r["permitted"]
        assert math.isclose(b["start_rpm"], r["start_rpm"], rel_tol=1e-9)
        assert math.isclose(b["end_rpm"], r["end_rpm"], rel_tol=1e-9)
    # found just below 0.8 n_0, declared above it by the 2 % tachometer tolerance
    assert 698.5 < shaft["exceeds_from_rpm"] < shaft["exceeds_to_rpm"] < 0.8 * N0
    assert shaft["start_rpm"] == pytest.approx(shaft["exceeds_from_rpm"] * 0.98, rel=1e-9)
    assert shaft["end_rpm"] == pytest.approx(shaft["exceeds_to_rpm"] * 1.02, rel=1e-9)
    assert shaft["end_rpm"] > 0.8 * N0 and not shaft["permitted"]
    reason = shaft["reason"]
    # the ends once, from the range (its columns): the reason says how, without speeds
    assert "widened by the 2 % tachometer tolerance" in reason
    assert "685.0" not in reason and "719.1" not in reason
    assert "above 0.8 n_0 = 711.2 rpm" in reason
    # found and declared, each end once, in the table's columns
    assert "698.9 │ 705.0 │ 685.0 │ 719.1" in _block(t_out, "Barred speed ranges")
