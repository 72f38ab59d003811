"""Benchmark cases, one module per case; each has KEY, TITLE and ``cases(size)``."""

from __future__ import annotations

import importlib
import importlib.util

MODULES = (
    "chain_modes",
    "damped_modes",
    "forced_response",
    "branched_response",
    "fourbar",
    "sixbar",
    "engine_cycle",
    "process",
    "baseline",
    "crankshaft_beam",
    "records",
    "tvc_scaling",
)


def available() -> tuple[str, ...]:
    """The case modules present in this checkout, in table order."""
    return tuple(m for m in MODULES if importlib.util.find_spec(f"bench.cases.{m}") is not None)


def load(name: str):
    """The case module ``bench.cases.<name>``."""
    return importlib.import_module(f"bench.cases.{name}")
