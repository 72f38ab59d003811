"""docs/seeds.md lists every item of the four seeds with the capability that does it and the test
that checks it (issue 34). This test reads the table: every row names a capability (a module,
function or command of crankdyn that exists) and tests that exist (a test file and a function
defined in it), its status is present, partial or pending, and the only pending rows are the
engine results' second round, each with its reason."""

from __future__ import annotations

import ast
import importlib
import re
from functools import cache
from pathlib import Path

import pytest

ROOT = Path(__file__).parents[1]
TABLE = ROOT / "docs" / "seeds.md"
STATUSES = ("present", "partial", "pending")
SECOND_ROUND = "second round: engine results"
PENDING: dict[str, str] = {}
"""The rows allowed to be pending, each with a word its 'what the seed says' cell holds: none
(the engine results' second round of issue 34 did the last seven)."""
TEST_REF = re.compile(r"(tests/[\w/]+\.py)::(\w+)")
DOTTED = re.compile(r"`(crankdyn(?:\.\w+)+)`")
COMMAND = re.compile(r"`crankdyn [a-z]")


def _rows() -> list[dict[str, str]]:
    rows = []
    for number, line in enumerate(TABLE.read_text(encoding="utf-8").splitlines(), 1):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if not line.startswith("| ") or not re.fullmatch(r"00[0-4]-\d\d", cells[0]):
            continue
        assert len(cells) == 6, f"docs/seeds.md line {number}: expected 6 cells, got {len(cells)}"
        rows.append(
            dict(
                zip(("id", "section", "says", "capability", "test", "status"), cells, strict=True),
                line=str(number),
            )
        )
    return rows


ROWS = _rows()


@cache
def _defined(path: str) -> frozenset[str]:
    """The names of the functions a test file defines (at module level or in classes)."""
    tree = ast.parse((ROOT / path).read_text(encoding="utf-8"))
    return frozenset(
        node.name
        for node in ast.walk(tree)
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))
    )


def _resolves(dotted: str) -> bool:
    """A dotted name is a crankdyn module, or an attribute reached from the longest module."""
    parts = dotted.split(".")
    for cut in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:cut]))
        except ImportError:
            continue
        for name in parts[cut:]:
            if not hasattr(obj, name):
                return False
            obj = getattr(obj, name)
        return True
    return False


def test_the_table_lists_the_four_seeds():
    ids = [r["id"] for r in ROWS]
    assert len(ids) == len(set(ids)), "an ID is given twice"
    assert len(ids) >= 75, len(ids)
    assert {i[:3] for i in ids} == {"000", "002", "003", "004"}


@pytest.mark.parametrize("row", ROWS, ids=[r["id"] for r in ROWS])
def test_every_row_names_a_capability_and_existing_tests(row):
    where = f"docs/seeds.md line {row['line']} ({row['id']})"
    status = row["status"].split(":")[0].strip()
    assert status in STATUSES, f"{where}: status {row['status']!r}"
    capability = row["capability"]
    named = DOTTED.findall(capability)
    assert named or COMMAND.search(capability) or "docs/" in capability, (
        f"{where}: no capability (a `crankdyn.module.name`, a `crankdyn command` or a docs page)"
    )
    for dotted in named:
        assert _resolves(dotted), f"{where}: {dotted} does not exist"
    tests = TEST_REF.findall(row["test"])
    if status == "pending":
        assert row["id"] in PENDING, f"{where}: only the second round's items may be pending"
        assert SECOND_ROUND in row["status"], f"{where}: a pending row says why ({SECOND_ROUND})"
        assert PENDING[row["id"]] in row["says"], f"{where}: not the item the second round holds"
        return
    assert tests, f"{where}: no test named (tests/path.py::function)"
    for path, name in tests:
        assert (ROOT / path).is_file(), f"{where}: no test file {path}"
        assert name.startswith("test_"), f"{where}: {name} is not a test"
        assert name in _defined(path), f"{where}: {path} defines no {name}"


def test_nothing_is_pending():
    pending = {r["id"] for r in ROWS if r["status"].startswith("pending")}
    assert pending == set(PENDING)


def test_the_table_counts():
    """The counts the issue reports: present, partial and pending rows."""
    counts = {s: sum(r["status"].split(":")[0].strip() == s for r in ROWS) for s in STATUSES}
    assert sum(counts.values()) == len(ROWS)
    assert counts["pending"] == len(PENDING)
