"""The linear algebra's threads (crankdyn.threads): the processors not already busy, the user's
settings first, and a bad CRANKDYN_THREADS as one line and status 2."""

from __future__ import annotations

import numpy as np
import pytest
from threadpoolctl import threadpool_info, threadpool_limits

from crankdyn.cli import main
from crankdyn.threads import LIBRARY_VARIABLES, VARIABLE, blas_threads, limit_blas_threads


@pytest.mark.parametrize(
    ("cores", "load", "expected"),
    [(2, 0.0, 2), (2, 0.4, 2), (2, 0.6, 1), (2, 9.0, 1), (8, 2.6, 5), (4, float("nan"), 4)],
)
def test_threads_are_the_processors_not_busy(cores, load, expected):
    """max(1, min(cores, round(cores - load))), worked by hand for each row."""
    assert blas_threads(cores, load) == expected


@pytest.fixture
def restore_threads():
    """Put the loaded libraries' thread counts back after the test."""
    np.dot(np.ones((2, 2)), np.ones((2, 2)))  # numpy's BLAS loaded
    before = {i["filepath"]: i["num_threads"] for i in threadpool_info()}
    yield
    for info in threadpool_info():
        if info["filepath"] in before:
            threadpool_limits(limits=before[info["filepath"]], user_api=info["user_api"])


def test_crankdyn_threads_limits_the_loaded_libraries(monkeypatch, restore_threads):
    for variable in LIBRARY_VARIABLES:
        monkeypatch.delenv(variable, raising=False)
    monkeypatch.setenv(VARIABLE, "1")
    assert limit_blas_threads() == 1
    blas = [i for i in threadpool_info() if i["user_api"] == "blas"]
    assert blas
    assert all(i["num_threads"] == 1 for i in blas)
    import os

    assert all(os.environ[v] == "1" for v in LIBRARY_VARIABLES)  # for libraries loaded later


def test_the_users_library_variables_are_left_alone(monkeypatch):
    monkeypatch.delenv(VARIABLE, raising=False)
    monkeypatch.setenv("OPENBLAS_NUM_THREADS", "3")
    assert limit_blas_threads() is None


@pytest.mark.parametrize("value", ["0", "two", "-1"])
def test_a_bad_thread_count_is_one_line(monkeypatch, capsys, value):
    monkeypatch.setenv(VARIABLE, value)
    assert main(["--help"]) == 2
    err = capsys.readouterr().err.strip()
    assert VARIABLE in err
    assert "\n" not in err
