"""Shared test fixtures."""

from __future__ import annotations

import os

# One linear-algebra thread per test process: `make test` runs two xdist workers on two cores,
# and a threaded OpenBLAS in each (its threads spinning while they wait) oversubscribes them:
# the damped-mode tests of 400-mass chains took 30-60 s of CPU instead of 3 s. Set before numpy
# loads OpenBLAS; crankdyn's own rule (crankdyn.threads) leaves a set variable alone.
for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_variable, "1")

import matplotlib  # noqa: E402
import pytest  # noqa: E402
from hypothesis import HealthCheck, settings  # noqa: E402

matplotlib.use("Agg")
try:  # numpy and scipy loaded before this file (by a plugin) follow through threadpoolctl
    from threadpoolctl import threadpool_limits

    threadpool_limits(1)
except ImportError:  # pragma: no cover - threadpoolctl is a dependency
    pass
os.environ.setdefault("COLUMNS", "160")

# Hypothesis profiles: "ci" (default) keeps the normal suite bounded; "fuzz" is the long campaign
# of `make fuzz` (docs/robustness.md). Tests that set max_examples themselves keep them in "ci".
settings.register_profile("ci", deadline=None, suppress_health_check=[HealthCheck.too_slow])
settings.register_profile(
    "fuzz",
    max_examples=int(os.environ.get("CRANKDYN_FUZZ_EXAMPLES", "5000")),
    deadline=None,
    suppress_health_check=list(HealthCheck),
)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci"))
FUZZ = os.environ.get("HYPOTHESIS_PROFILE") == "fuzz"


def fuzz_examples(normal: int) -> int:
    """Examples for a fuzz test: ``normal`` in the suite, the profile's count under make fuzz."""
    return settings().max_examples if FUZZ else normal


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


def pytest_collection_modifyitems(config, items):
    """The tests marked ``slow`` run first (stable order otherwise): with ``pytest -n 2`` the
    workers start on the long ones and finish together, instead of one worker running a long
    test alone at the end (the longest-processing-time-first rule of scheduling)."""
    items.sort(key=lambda item: item.get_closest_marker("slow") is None)
