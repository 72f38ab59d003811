"""Benchmark cases, one module per case; each has KEY, TITLE and ``cases(size)``."""

from __future__ import annotations

import importlib

MODULES = ("chain_modes", "forced_response", "fourbar", "engine_cycle", "analyze")


def load(name: str):
    """The case module ``bench.cases.<name>``."""
    return importlib.import_module(f"bench.cases.{name}")
