"""The built-in design space ``marine-propulsion-design``: its best design passes every
normal-firing verdict row with a wider worst margin than the built-in design's, and the chosen
design written to best.toml reads back as the same design (the same verdict rows and margin)."""

from __future__ import annotations

import csv
import dataclasses

import pytest

from crankdyn.io.catalogue import load_example, resolve_engine
from crankdyn.session import Analysis


@pytest.mark.slow
def test_the_marine_example_finds_a_wider_margin_than_the_built_in_design(tmp_path, cli):
    # the first population of the differential evolution (20 candidates) suffices here; the
    # file's own budget (120) is for the command line
    result = cli(
        "design", "marine-propulsion-design", "-o", tmp_path / "out", "--workers", "1",
        "--max-candidates", "20", "--no-report",
    )  # fmt: skip
    assert result.status == 0, result
    built_in = Analysis(resolve_engine("marine-propulsion")).judged()
    assert built_in is not None and built_in.passed
    base_margin = min(v.margin for v in built_in.verdicts)
    chosen = Analysis(resolve_engine(str(tmp_path / "out" / "best.toml"))).judged()
    assert chosen is not None and chosen.passed
    chosen_margin = min(v.margin for v in chosen.verdicts)
    assert chosen_margin > base_margin + 0.05
    with open(tmp_path / "out" / "results.csv", encoding="utf-8") as f:
        margins = [
            float(r["condition_worst_margin"]) for r in csv.DictReader(f) if r["feasible"] == "true"
        ]
    assert max(margins) == chosen_margin  # best.toml is the best candidate, read back


def test_the_example_space(tmp_path):
    space = load_example("marine-propulsion-design", "design")
    assert [space.name_of(k) for k in space.choices] == ["coupling", "firing order"]
    coupling = space.parameter(space.choices[0])
    assert coupling.bundle and len(coupling.values or ()) >= 6
    orders = space.parameter(space.choices[1]).names
    assert orders is not None and "1-5-3-6-2-4" in orders and len(orders) == 4
    assert space.method() == "differential-evolution"
    assert dataclasses.replace(space.search).seed == 2024
