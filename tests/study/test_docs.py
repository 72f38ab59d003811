"""docs/study-file.md stays true: its figure table names every registered figure, and its
example study files are the built-in ones."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

from crankdyn.io.examples import example_path
from crankdyn.io.files import load_toml
from crankdyn.study.figures import FIGURES, SETTINGS, figures_markdown

DOC = (Path(__file__).parents[2] / "docs" / "study-file.md").read_text(encoding="utf-8")


def _section(title: str) -> str:
    start = DOC.index(f"## {title}\n")
    end = DOC.find("\n## ", start + 1)
    return DOC[start:end]


def test_the_figure_table_names_every_figure():
    """The page's table is the one generated from the results' declarations (regenerate it
    with crankdyn.study.figures.figures_markdown())."""
    table = _section("Figures")
    assert figures_markdown() in table
    rows = [line for line in table.splitlines() if line.startswith("| `")]
    named = {name for row in rows for name in re.findall(r"`([a-z0-9_]+)`", row.split("|")[1])}
    assert named == {n for n, f in FIGURES.items() if f.module.startswith("crankdyn.")}


def test_the_analysis_table_names_every_setting():
    table = _section("`[analysis]`")
    named = set(re.findall(r"^\| `([a-z_]+)` \|", table, flags=re.M))
    assert named == {"figures", *SETTINGS}


def test_the_examples_are_the_built_in_studies():
    blocks = [tomllib.loads(b) for b in re.findall(r"```toml\n(.*?)```", DOC, flags=re.S)]
    for name in ("inline4-rod-and-firing", "inline6-tolerances"):
        assert load_toml(example_path(name, "study")) in blocks, name
