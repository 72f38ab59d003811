"""The command line has glibc's malloc keep the memory freed arrays leave (crankdyn.allocator):
arrays of a few megabytes allocated again after they are freed take no new pages (no page
faults), where without the settings the freed heap is given back and faulted in again; the
user's own settings win."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from crankdyn.allocator import _glibc, keep_freed_memory

glibc = pytest.mark.skipif(not _glibc(), reason="glibc only")

_FAULTS = """
import resource, sys
import numpy as np
from crankdyn.allocator import _glibc, keep_freed_memory
set_ = keep_freed_memory() if sys.argv[1] == "1" else False
def faults():
    return resource.getrusage(resource.RUSAGE_SELF).ru_minflt
def block():  # eight arrays of 10 MB held together, then all freed (a block of speeds)
    held = [np.ones(1_250_000) for _ in range(8)]
    del held
block()  # warm up: the heap grown once
before = faults()
for _ in range(10):
    block()
print(int(set_), faults() - before)
"""


def _run(keep: bool) -> tuple[int, int]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("MALLOC_")}
    env.pop("GLIBC_TUNABLES", None)
    out = subprocess.run(
        [sys.executable, "-c", _FAULTS, "1" if keep else "0"],
        capture_output=True,
        text=True,
        check=True,
        env=env,
    ).stdout.split()
    return int(out[0]), int(out[1])


@glibc
def test_freed_arrays_memory_is_used_again_without_page_faults():
    made, faults = _run(True)
    assert made == 1
    # without the settings glibc gives the 80 MB freed at the top of its heap back (beyond its
    # trim threshold, twice the largest block freed so far) and faults it in again each time:
    # thousands of pages (or, with transparent huge pages, dozens of 2 MiB pages) a block
    assert faults < 50, faults
    _, faults_default = _run(False)
    # (at least 10 a block even where every page is a 2 MiB one: 40 of them a block)
    assert faults_default >= 100 > faults, (faults_default, faults)


def test_the_users_own_settings_win():
    assert keep_freed_memory({"MALLOC_TRIM_THRESHOLD_": "0"}) is False
    assert keep_freed_memory({"GLIBC_TUNABLES": "glibc.malloc.trim_threshold=0"}) is False
