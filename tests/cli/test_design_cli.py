"""``crankdyn design``: the outputs, the exit status (0 found, 1 none feasible, 2 bad input),
the chosen design as a file ``crankdyn tvc`` reads, and the built-in example listing."""

from __future__ import annotations

import re
import shutil
from pathlib import Path

DATA = Path(__file__).resolve().parents[1] / "validation" / "data"


def copy_design(tmp_path: Path, extra: str = "") -> Path:
    for name in ("small_coupling_line.toml", "small_couplings.csv", "small_coupling_design.toml"):
        shutil.copy(DATA / name, tmp_path / name)
    path = tmp_path / "small_coupling_design.toml"
    if extra:
        path.write_text(path.read_text(encoding="utf-8") + extra, encoding="utf-8")
    return path


def test_design_writes_the_table_the_chosen_design_and_its_tvc_report(tmp_path, cli):
    space = copy_design(tmp_path)
    out = tmp_path / "out"
    result = cli("design", space, "-o", out, "--workers", "1")
    assert result.status == 0, result
    assert "Chosen design" in result.out and "coupling = S-10" in result.out
    assert "Margin of every verdict row" in result.out
    assert "Sensitivity of the" in result.out and "Spearman" in result.out
    # the chosen design was checked against the whole TVC (every condition) and passes it
    assert re.search(r"Chosen design passes every row of crankdyn tvc\s*│\s*yes", result.out)
    assert "evaluating candidates on a 1 process" in result.err
    rows = (out / "results.csv").read_text(encoding="utf-8").splitlines()
    assert rows[0].startswith("candidate,case_id,status,coupling,firing_order,")
    assert len(rows) == 13  # 12 candidates and the header
    assert (out / "tvc" / "index.html").is_file()
    page = (out / "summary" / "index.html").read_text(encoding="utf-8")
    assert "Best designs" in page and "Margin of every verdict row" in page
    assert (out / "summary" / "plots" / "candidates.png").is_file()
    # the chosen design is a model file crankdyn reads (its TVC passes: it was feasible)
    tvc = cli("tvc", out / "best.toml", "-o", tmp_path / "tvc", "--no-pdf", "--no-passage")
    assert tvc.status == 0, tvc
    again = cli("design", space, "-o", out, "--workers", "1", "--no-report")
    assert again.status == 0
    assert "13 candidates evaluated in an earlier run are kept" in again.err


def test_no_feasible_design_exits_1(tmp_path, cli):
    space = copy_design(
        tmp_path, '\n[[constraints.figure]]\nname = "condition_worst_margin"\nmin = 0.99\n'
    )
    result = cli("design", space, "-o", tmp_path / "out", "--workers", "1")
    assert result.status == 1, result
    assert "none feasible" in result.out
    assert not (tmp_path / "out" / "best.toml").exists()


def test_bad_input_is_one_line_and_exit_2(tmp_path, cli):
    space = copy_design(tmp_path)
    text = space.read_text(encoding="utf-8")
    space.write_text(text.replace('shaft = "elastic coupling"', 'shaft = "elastic coupler"'))
    result = cli("design", space, "-o", tmp_path / "out")
    assert result.status == 2
    line = result.err.strip()
    assert "\n" not in line
    assert '[[choice]] #1 shaft = "elastic coupler": no shaft of this name' in line
    assert 'did you mean "elastic coupling"' in line


def test_list_shows_the_built_in_design_spaces(cli):
    result = cli("design", "--list")
    assert result.status == 0
    assert "marine-propulsion-design" in result.out
