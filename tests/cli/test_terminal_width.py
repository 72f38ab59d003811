"""Terminal tables take the terminal's width (issue 33): a command run in a terminal 100 (or
60) columns wide prints no line wider than it; a pipe or a file gets 120 columns."""

from __future__ import annotations

import os
import re
import subprocess
import sys

import pytest

from crankdyn.cli import common

pty = pytest.importorskip("pty")
fcntl = pytest.importorskip("fcntl")
termios = pytest.importorskip("termios")

_STYLE = re.compile(r"\x1b\[[0-9;?]*[A-Za-z]")


def run_in_terminal(args: list[str], columns: int) -> tuple[int, list[str]]:
    """``crankdyn ARGS`` with its standard output on a pseudo-terminal ``columns`` wide:
    (status, the lines printed, styles removed)."""
    import struct

    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 50, columns, 0, 0))
    env = {
        k: v
        for k, v in os.environ.items()
        if k not in ("COLUMNS", "LINES", "FORCE_COLOR", "TTY_COMPATIBLE", "NO_COLOR")
    }
    env["TERM"] = "xterm"
    process = subprocess.Popen(
        [sys.executable, "-m", "crankdyn", *args],
        stdin=subprocess.DEVNULL,
        stdout=slave,
        stderr=subprocess.PIPE,
        env=env,
    )
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 1 << 16)
        except OSError:  # the child closed the terminal (Linux: EIO)
            break
        if not data:
            break
        chunks.append(data)
    os.close(master)
    assert process.wait(timeout=300) == 0, process.stderr.read() if process.stderr else ""
    text = _STYLE.sub("", b"".join(chunks).decode("utf-8"))
    return process.returncode, text.replace("\r", "").split("\n")


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX pseudo-terminals")
@pytest.mark.parametrize(
    ("args", "columns"),
    [(["examples"], 100), (["examples"], 60), (["kinematics", "vaz2108"], 100)],
)
def test_tables_fit_the_terminal(args, columns):
    """No line runs past the terminal's right edge (``crankdyn examples`` was 120 columns
    wide whatever the terminal, its right border cut in a 100-column one)."""
    status, lines = run_in_terminal(args, columns)
    assert status == 0
    assert max(len(line) for line in lines) <= columns
    assert any(line.startswith("┏") for line in lines)  # a table was printed


def test_a_pipe_gets_the_file_width(monkeypatch):
    """Not a terminal: 120 columns (or COLUMNS where wider)."""
    monkeypatch.delenv("COLUMNS", raising=False)
    monkeypatch.setattr(sys, "stdout", open(os.devnull, "w"))  # noqa: SIM115
    try:
        assert common.stdout_width() == common.PIPE_WIDTH == 120
        monkeypatch.setenv("COLUMNS", "200")
        assert common.stdout_width() == 200
        monkeypatch.setenv("COLUMNS", "80")
        assert common.stdout_width() == 120
    finally:
        sys.stdout.close()
