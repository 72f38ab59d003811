"""No control character in any output (issue 33): user text with ESC, BEL, BS, CR or LF
reaches neither the terminal (titles, cells, notes, errors, warnings), nor an HTML page (and the
PDF printed from it), an SVG, or a CSV file (fields quoted as RFC 4180 requires); a name a round
trip could not keep exactly (a mass name with a control character or white space at its ends)
is refused at input, and the others come back from ``torsion table`` exactly."""

from __future__ import annotations

import itertools
import json
import re
import unicodedata
from importlib import resources

import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from crankdyn.errors import InputError
from crankdyn.io.mass_elastic import mass_elastic_csv, read_mass_elastic
from crankdyn.torsion.model import Mass, Shaft, TorsionModel
from tests.conftest import fuzz_examples

EXAMPLE = resources.files("crankdyn") / "examples" / "torsion" / "verdict-geared-line.toml"
LINE = EXAMPLE.read_text(encoding="utf-8")
CONTROLS = "".join(chr(c) for c in (*range(0x20), 0x7F, 0x85, 0x9B)) + "\u2028"


def controls_in(text: str) -> set[str]:
    """The control characters of an output's text, line ends aside."""
    return {ch for ch in text.replace("\n", "") if unicodedata.category(ch) == "Cc"} | (
        set(text) & {"\u2028", "\u2029"}
    )


def toml_string(text: str) -> str:
    return json.dumps(text, ensure_ascii=True)  # \\u escapes: TOML reads them as JSON does


def model_file(folder, name: str, mass: str = "front end"):
    text = re.sub(r'(?m)^name = ".*"$', lambda _m: f"name = {toml_string(name)}", LINE, count=1)
    text = text.replace('"front end"', toml_string(mass))
    path = folder / "line.toml"
    path.write_text(text, encoding="utf-8")
    return path


hostile = st.text(
    alphabet=st.sampled_from(CONTROLS + "ab [/]$,\"'#é"), min_size=1, max_size=16
).filter(lambda s: s.strip() and any(ch in CONTROLS for ch in s))


@settings(
    max_examples=fuzz_examples(6),
    suppress_health_check=[HealthCheck.function_scoped_fixture],
)
@given(name=hostile)
@example(name="Line \x1b[31mRED\x07\x08\r\nX")
def test_model_names_reach_no_terminal_or_csv_raw(cli, tmp_path_factory, name):
    """A model name with control characters: the terminal titles (a table, its parts), CSV
    and JSON outputs hold none of them raw; the name is shown with its escapes."""
    path = model_file(tmp_path_factory.mktemp("ctl"), name)
    for args in (
        ("torsion", "modes", path),
        ("torsion", "modes", path, "--format", "csv"),
        ("torsion", "modes", path, "--format", "json"),
        ("torsion", "table", path),
    ):
        run = cli(*args)
        assert run.status == 0, (args, run)
        assert not controls_in(run.out), (args, controls_in(run.out))
        assert not controls_in(run.err), (args, run.err)


def test_report_folder_holds_no_control_character(cli, tmp_path):
    """``tvc -o``: index.html (and so the PDF printed from it), the SVG figures, summary.json
    and the data/*.csv files: ESC, BEL and BS reached index.html raw, and a name's CR split
    the rows of five CSV files (issue 33)."""
    name = 'Line \x1b[31mRED\x07\x08\r\nX, "quoted"'
    path = model_file(tmp_path, name, mass='front, "end" #1')
    run = cli("tvc", path, "-o", tmp_path / "rep", "--no-pdf")  # the PDF prints this HTML
    assert run.status in (0, 1), run  # the verdict's exit status; the report is written either way
    assert not controls_in(run.out) and not controls_in(run.err)  # the verdict table's title
    for file in (tmp_path / "rep").rglob("*"):
        if file.suffix in (".html", ".svg", ".json", ".csv"):
            text = file.read_text(encoding="utf-8")
            assert not controls_in(text), (file.name, controls_in(text))
    page = (tmp_path / "rep" / "index.html").read_text(encoding="utf-8")
    assert "Line \\x1b[31mRED\\x07\\x08\\r\\nX" in page
    import csv

    masses = (tmp_path / "rep" / "data" / "torsion_masses.csv").read_text(encoding="utf-8")
    rows = list(csv.reader(masses.splitlines()))
    assert rows[1][1] == 'front, "end" #1'
    assert len({len(row) for row in rows}) == 1  # every row as wide as the header


@settings(max_examples=fuzz_examples(40))
@given(name=hostile)
def test_mass_names_that_a_table_cannot_keep_are_refused(name):
    """Control characters in a mass name, or white space at its ends: refused at input, in one
    line, under ``name`` (a round trip through ``torsion table`` changed them)."""
    with pytest.raises(InputError) as info:
        Mass(name, 1.0)
    assert str(info.value).startswith("name = ") and "\n" not in str(info.value)
    for spaced in (f" {name.strip()}", f"{name.strip()}\t"):
        with pytest.raises(InputError):
            Mass(spaced, 1.0)


names = st.text(
    alphabet=st.characters(blacklist_categories=("Cc", "Cs", "Zl", "Zp")), min_size=1, max_size=12
).filter(lambda s: s == s.strip() and s)


@settings(max_examples=fuzz_examples(60))
@given(chosen=st.lists(names, min_size=2, max_size=5, unique=True))
@example(chosen=["#1", 'a, "b"', " ".join(["x", "y"]), "=1+1", "ü"])
def test_torsion_table_keeps_names_exactly(tmp_path_factory, chosen):
    """Every name a model accepts comes back from the mass-elastic table exactly: commas and
    quotes quoted (RFC 4180), a leading ``#`` quoted (not a comment)."""
    if "ground" in chosen:
        return
    model = TorsionModel(
        masses=tuple(Mass(n, 1.0) for n in chosen),
        shafts=tuple(Shaft((a, b), 1e4) for a, b in itertools.pairwise(chosen)),
    )
    path = tmp_path_factory.mktemp("table") / "t.csv"
    path.write_text(mass_elastic_csv(model), encoding="utf-8")
    assert read_mass_elastic(path).mass_names == tuple(chosen)


def test_error_lines_hold_no_control_character(cli, tmp_path):
    """An error quoting a name with ESC (an unknown mass) is one line without it."""
    text = LINE.replace('between = ["front end", "cylinder 1"]', 'between = ["\\u001b[2J", "x"]')
    path = tmp_path / "bad.toml"
    path.write_text(text, encoding="utf-8")
    run = cli("torsion", "modes", path)
    assert run.status == 2 and run.err.count("\n") == 1
    assert not controls_in(run.err) and "\\x1b[2J" in run.err
