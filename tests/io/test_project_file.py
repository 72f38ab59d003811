"""The [project] section (issue 32): the document control of a TVC read from a model file, its
errors one line naming the file and the key."""

from __future__ import annotations

from pathlib import Path

import pytest

import crankdyn
from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.torsion.model import TorsionModel

LINE = (
    Path(crankdyn.__file__).parent / "examples" / "torsion" / "verdict-geared-line.toml"
).read_text(encoding="utf-8")

PROJECT = """
[project]
project = "MV Example"
document = "TVC-42"
yard = "Yard"
hull = "H-7"
engine_type = "6L32"
mcr_power = "3000 kW"
mcr_speed = "750 rpm"
prepared = "A. Author"
date = 2026-02-01

[[project.revision]]
revision = 0
date = 2026-01-01
description = "first issue"

[[project.revision]]
revision = "A"
description = "comments of the society"
by = "A. Author"
"""


def _model(tmp_path: Path, extra: str) -> TorsionModel:
    path = tmp_path / "line.toml"
    path.write_text(LINE + extra, encoding="utf-8")
    return TorsionModel.from_file(path)


def test_project_read_from_a_model_file(tmp_path):
    p = _model(tmp_path, PROJECT).project
    assert p is not None and p.project == "MV Example" and p.document == "TVC-42"
    assert p.mcr_power == pytest.approx(3.0e6) and p.mcr_speed == pytest.approx(750 / RPM)
    assert [r.revision for r in p.revisions] == ["0", "A"] and p.revision == "A"
    assert p.date == "2026-02-01" and p.revisions[0].date == "2026-01-01"
    assert ("Yard / hull", "Yard / hull H-7") in p.rows()
    assert p.signatures()[0] == ("Prepared", "A. Author") and p.signatures()[1] == ("Checked", "")


def test_no_project_section_is_none(tmp_path):
    assert _model(tmp_path, "").project is None


@pytest.mark.parametrize(
    ("extra", "key"),
    [
        ('[project]\nprojekt = "x"\n', "projekt"),
        ('[project]\nmcr_speed = "3000 kW"\n', "mcr_speed"),
        ('[project]\nmcr_power = "-3 kW"\n', "mcr_power"),
        ("[project]\nprepared = 3\n", "prepared"),
        ('[project]\n[[project.revision]]\ndescription = "no mark"\n', "revision"),
    ],
)
def test_bad_project_keys_are_one_line_errors(tmp_path, extra, key):
    with pytest.raises(InputError) as err:
        _model(tmp_path, extra)
    text = str(err.value)
    assert "\n" not in text and "line.toml" in text and key in text
