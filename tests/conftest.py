"""Shared test fixtures."""

from __future__ import annotations

import os

import matplotlib
import pytest

matplotlib.use("Agg")
os.environ.setdefault("COLUMNS", "160")


class CliRun:
    """Result of an in-process CLI run."""

    def __init__(self, status: int, out: str, err: str):
        self.status, self.out, self.err = status, out, err

    def __repr__(self) -> str:
        return f"CliRun(status={self.status}, out={self.out[:200]!r}, err={self.err!r})"


@pytest.fixture
def cli(capsys):
    """Run ``crankdyn ARGS`` in process: returns CliRun(status, stdout, stderr)."""
    from crankdyn.cli import main

    def run(*args: str) -> CliRun:
        capsys.readouterr()
        status = main([str(a) for a in args])
        captured = capsys.readouterr()
        return CliRun(status, captured.out, captured.err)

    return run


@pytest.fixture
def write(tmp_path):
    """Write a text file in a temporary folder and return its path."""

    def _write(name: str, text: str):
        path = tmp_path / name
        path.write_text(text, encoding="utf-8")
        return path

    return _write
