"""The input pages stay true to the plausibility table: docs/engine-file.md and
docs/torsion-file.md print the table generated from crankdyn.io.plausibility.ROLES (regenerate it
with roles_markdown()) and say that a bare speed is refused, with the message the reader gives."""

from __future__ import annotations

from pathlib import Path

import pytest

from crankdyn.io.plausibility import ROLES, roles_markdown
from crankdyn.io.units import BARE_SPEED

DOCS = Path(__file__).parents[2] / "docs"


@pytest.mark.parametrize("page", ["engine-file.md", "torsion-file.md"])
def test_the_input_pages_print_the_table_and_the_bare_speed_rule(page):
    text = (DOCS / page).read_text(encoding="utf-8")
    start = text.index("## Bare numbers and plausible values\n")
    section = text[start : text.find("\n## ", start + 1)]
    assert roles_markdown() in section
    assert BARE_SPEED in section and "A bare speed is refused" in section
    rows = [line for line in section.splitlines() if line.startswith("| ") and "---" not in line]
    assert len(rows) == len(ROLES) + 2  # the header, every role, the speed range against n_0
