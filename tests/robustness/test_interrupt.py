"""Ctrl-C and SIGTERM during a long run leave no partial output (issue 17, point 6; no data
loss). The signal tests are deterministic: the child stops at the step under test and waits
until the test has sent its signal (tests.robustness.blocking); it sets its own signal
dispositions, so a suite started as a background job (SIGINT ignored) tests the same thing."""

from __future__ import annotations

import os
import signal
import stat
import sys

import pytest

from crankdyn.report import sections
from tests.robustness import blocking

posix = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
SIGNALS = pytest.mark.parametrize(
    ("signum", "status", "line"),
    [
        (signal.SIGINT, 130, "crankdyn: error: interrupted; nothing was written"),
        (
            getattr(signal, "SIGTERM", 15),
            143,
            "crankdyn: error: terminated (SIGTERM); nothing was written",
        ),
    ],
    ids=["SIGINT", "SIGTERM"],
)


def test_interrupt_during_analysis_writes_nothing(cli, tmp_path, monkeypatch):
    def interrupted(ctx):
        raise KeyboardInterrupt

    from crankdyn.report import build

    real = sections.builders
    monkeypatch.setattr(build, "builders", lambda: [*real()[:1], ("boom", interrupted)])
    out = tmp_path / "report"
    run = cli("analyze", "vaz2108", "--output", out)
    assert run.status == 130
    assert run.err.strip() == "crankdyn: error: interrupted; nothing was written"
    assert list(tmp_path.iterdir()) == []


def test_interrupt_while_writing_keeps_the_old_report(cli, tmp_path, monkeypatch):
    from crankdyn.report import build

    real = sections.builders
    monkeypatch.setattr(build, "builders", lambda: real()[:1])
    out = tmp_path / "report"
    assert cli("analyze", "vaz2108", "--output", out).status == 0
    before = sorted(p.name for p in out.rglob("*"))
    from crankdyn.report import write as write_module

    def boom(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(write_module, "render_html", boom)
    run = cli("analyze", "vaz2108", "--output", out, "--force")
    assert run.status == 130
    assert sorted(p.name for p in out.rglob("*")) == before
    assert [p.name for p in tmp_path.iterdir()] == ["report"]


# ---- real signals, sent while the child is stopped at the step ---------------------------------


def lines(err: str) -> list[str]:
    return [line for line in err.splitlines() if line.strip()]


@posix
@SIGNALS
def test_signal_while_the_report_is_written(tmp_path, signum, status, line):
    """SIGINT or SIGTERM while the report's temporary folder holds its plots (the child stops
    at the HTML page): exit 130 or 143, one line, no report and no temporary folder (SIGTERM
    used to leave `.rep.XXXX.tmp/`)."""
    work = tmp_path / "work"
    work.mkdir()
    child = blocking.start(
        ["analyze", "v8-crossplane", "--output", "rep"],
        target="crankdyn.report.write:render_html",
        fifo=tmp_path / "ready",
        cwd=work,
    )
    assert [p.name for p in work.iterdir() if p.name.startswith(".rep.")]  # mid-write
    code, _out, err = child.signal(signum)
    assert (code, lines(err)) == (status, [line]), err
    assert list(work.iterdir()) == []


@posix
@SIGNALS
def test_signal_while_replacing_a_report_keeps_the_old_one(tmp_path, signum, status, line):
    work = tmp_path / "work"
    (work / "rep").mkdir(parents=True)
    (work / "rep" / "index.html").write_text("the old report")
    (work / "rep" / ".crankdyn-output").write_text("")  # a folder crankdyn wrote
    child = blocking.start(
        ["analyze", "vaz2108", "--output", "rep", "--force"],
        target="crankdyn.report.write:render_html",
        fifo=tmp_path / "ready",
        cwd=work,
    )
    code, _out, err = child.signal(signum)
    assert (code, lines(err)) == (status, [line]), err
    assert [p.name for p in work.iterdir()] == ["rep"]
    assert sorted(p.name for p in (work / "rep").iterdir()) == [".crankdyn-output", "index.html"]
    assert (work / "rep" / "index.html").read_text() == "the old report"


@posix
@SIGNALS
def test_signal_while_a_file_is_written(tmp_path, signum, status, line):
    """`-o FILE`: the child stops with the temporary file written and not yet moved."""
    work = tmp_path / "work"
    work.mkdir()
    child = blocking.start(
        ["forces", "vaz2108", "--format", "json", "-o", "forces.json"],
        target="crankdyn.io.output:_sync",
        fifo=tmp_path / "ready",
        cwd=work,
    )
    assert [p.name for p in work.iterdir() if p.name.startswith(".forces.json.")]
    code, _out, err = child.signal(signum)
    assert (code, lines(err)) == (status, [line]), err
    assert list(work.iterdir()) == []


# ---- permissions: outputs take the user's umask ---------------------------------------------


@posix
@pytest.mark.parametrize("umask", [0o022, 0o077])
def test_outputs_take_the_umask(cli, tmp_path, monkeypatch, umask):
    """Files written with -o and by `crankdyn example`, and report folders, got 0600 and 0700
    whatever the umask (from mkstemp): now 0666 and 0777 less the umask, as any file the user
    makes."""
    from crankdyn.report import build

    real = sections.builders
    monkeypatch.setattr(build, "builders", lambda: real()[:1])
    monkeypatch.chdir(tmp_path)
    old = os.umask(umask)
    try:
        assert cli("example", "inline6-diesel").status == 0  # the engine file and its trace
        assert cli("kinematics", "vaz2108", "-o", "k.csv", "--format", "csv").status == 0
        assert cli("analyze", "vaz2108", "--output", "rep").status == 0
    finally:
        os.umask(old)
    files = [
        tmp_path / "inline6-diesel.toml",
        tmp_path / "mendes2008_pressure.csv",
        tmp_path / "k.csv",
        tmp_path / "rep" / "index.html",
        *(tmp_path / "rep" / "plots").iterdir(),
    ]
    for path in files:
        assert stat.S_IMODE(path.stat().st_mode) == 0o666 & ~umask, path
    for path in (tmp_path / "rep", tmp_path / "rep" / "plots", tmp_path / "rep" / "data"):
        assert stat.S_IMODE(path.stat().st_mode) == 0o777 & ~umask, path
