"""The one writer: tables that never cut a number, engineering units, clean JSON grids."""

from __future__ import annotations

import io
import json
import math
import random

import numpy as np
import pytest
from rich.cells import cell_len
from rich.console import Console

from crankdyn.cli import writer
from crankdyn.cli.writer import (
    Output,
    TextTable,
    plain_console,
    plain_text,
    render,
    result_table,
    summary_table,
)
from crankdyn.display import column_text, format_value
from crankdyn.engine.model import Engine
from crankdyn.session import Analysis, speed_grid


def _render(blocks, width: int) -> str:
    buffer = io.StringIO()
    render(blocks, Console(file=buffer, width=width, soft_wrap=False, highlight=False))
    return buffer.getvalue()


@pytest.mark.parametrize("width", [50, 80, 120])
def test_a_wide_table_is_split_never_cut(width):
    """Twelve columns of long numbers on a narrow console: every number appears whole, in
    parts that repeat the first column."""
    rng = np.random.default_rng(1)
    values = rng.uniform(-1e6, 1e6, size=(5, 12))
    rows = [[f"row {i}", *(f"{v:.6f}" for v in r)] for i, r in enumerate(values)]
    table = TextTable(
        "Wide", ["Name", *(f"Quantity number {c} (N·m)" for c in range(12))], rows, {0}
    )
    out = _render([table], width)
    assert "…" not in out
    for row in rows:
        for cell in row[1:]:
            assert cell in out, cell
    assert out.count("row 0") >= 2  # the key column repeats in every part
    assert max(len(line) for line in out.splitlines()) <= width


def test_the_bearing_loads_of_a_v12_print_whole():
    result = Analysis(Engine.example("v12-60")).bearings(step=np.radians(30.0))
    table = result_table(result)
    out = _render([table], 100)
    assert "…" not in out
    for row in table.rows:
        for cell in row:
            assert cell in out


def test_engineering_units_and_round_off():
    assert format_value(1.89441e6, "Pa") == ("1.8944", "MPa")
    assert format_value(130733.0, "N") == ("130.73", "kN")
    assert format_value(1.393e-14, "N", reference=5e4) == ("0", "kN")
    texts, unit = column_text([0.0, 1.2e-12, 130733.2, -5000.0], "N")
    assert unit == "kN" and texts == ["0", "0", "130.73", "-5.00"]
    texts, unit = column_text(np.arange(0.0, 40.0, 10.0), "deg")
    assert texts == ["0", "10", "20", "30"] and unit == "deg"


def test_json_grids_read_round(capsys):
    """A sweep built in rad/s reads as round rpm in JSON (6000, not 6000.000000000001); the
    speeds added to resolve the peaks are listed beside the grid (``on_grid`` false)."""
    speeds = speed_grid(5000 * np.pi / 30, 6000 * np.pi / 30, 100 * np.pi / 30)
    result = Analysis(Engine.example("inline6-diesel"), speeds=speeds).response()
    Output("json").write(json_data=result)
    data = json.loads(capsys.readouterr().out)
    grid = [s for s, on in zip(data["speed_rpm"], data["on_grid"], strict=True) if on]
    assert grid == [5000.0 + 100.0 * k for k in range(11)]


# ---- the plain text written without rich is rich's own text ------------------------------------
def _rich_text(blocks, width: int) -> str:
    """What :func:`render` prints through rich on a plain console ``width`` columns wide."""
    buffer = io.StringIO()
    con = Console(
        file=buffer, width=width, soft_wrap=False, highlight=False, markup=False, emoji=False
    )
    render(blocks, con)
    return buffer.getvalue()


def _kinematics_blocks():
    from crankdyn.cli.kinematics import KINEMATICS_TABLE

    result = Analysis(Engine.example("vaz2108")).kinematics(step=math.radians(10.0))
    return [
        result_table(result, KINEMATICS_TABLE, title="Piston and rod kinematics"),
        summary_table(result.extrema, "Summary (exact extrema)"),
    ]


@pytest.mark.parametrize("width", [120, 160, 250])
def test_plain_text_of_a_command_is_rich_text(width):
    """The kinematics command's tables (headers over four lines, units such as m/s², text and
    number columns) and the bearing loads of a V12 (split into parts at 120), as plain text."""
    bearings = result_table(
        Analysis(Engine.example("v12-60")).bearings(step=np.radians(30.0)), title="Bearings"
    )
    for blocks in (_kinematics_blocks(), [bearings, "a note", TextTable("", ["x"], [], set())]):
        text = plain_text(blocks, width)
        assert text is not None
        assert text == _rich_text(blocks, width)


_WORDS = [*"abcXYZ019.-+ ()/", "²", "·", "λ", "°", "µ", "Ω", "\xa0", "é", "Ж"]
_ODD = ["–", "…", "\t", "\n", "中", "\u0301", "\x1b"]  # not one column each: rich's layout


def _word(r: random.Random, n: int) -> str:
    return "".join(
        r.choice(_WORDS[:16] if r.random() < 0.97 else _WORDS + _ODD)
        for _ in range(r.randint(0, n))
    )


def test_plain_text_is_rich_text_or_none():
    """Tables of every shape (text and number columns, headers of several lines or none,
    leading, trailing and no-break spaces, empty cells, no rows, titles, captions, notes,
    splits into parts) on consoles of several widths: the plain text is rich's to the
    character, or None where rich's layout is needed (too wide, wrapped, odd characters)."""
    r = random.Random(16)
    plain = 0
    for _ in range(600):
        ncol = r.randint(1, 9)
        header = [" ".join(_word(r, 8) for _ in range(r.randint(0, 4))) for _ in range(ncol)]
        text_columns = {c for c in range(ncol) if r.random() < 0.3}
        rows = [
            [_word(r, r.choice([3, 8, 30]) if c in text_columns else 12) for c in range(ncol)]
            for _ in range(r.randint(0, 6))
        ]
        title = r.choice(["", "Title", _word(r, 40), " padded  "])
        caption = r.choice(["", "", "a caption", _word(r, 50)])
        blocks: list = [TextTable(title, header, rows, text_columns, caption)]
        if r.random() < 0.5:
            blocks.append(r.choice(["note", _word(r, 30), "", None, "x" * 130]))
        width = r.choice([40, 60, 80, 120, 200])
        text = plain_text(blocks, width)
        if text is not None:
            plain += 1
            assert text == _rich_text(blocks, width), (blocks, width)
    assert plain > 200  # the comparison covered many layouts


@pytest.mark.parametrize(
    "blocks",
    [
        [TextTable("T", ["A (m)", "B (m)"], [["1" * 70, "2" * 70]], set())],  # wider than 120
        [TextTable("T", ["Name"], [["a\tb"]], {0})],
        [TextTable("T", ["Name"], [["two\nlines"]], {0})],
        [TextTable("T", ["Name"], [["中文"]], {0})],
        [TextTable("A title much longer than the narrow table below it", ["x"], [["1"]], set())],
        ["a note longer than the console " * 5],
        [TextTable("", [], [], set())],
    ],
)
def test_plain_text_leaves_what_needs_rich_to_rich(blocks):
    assert plain_text(blocks, 120) is None
    _rich_text(blocks, 120)  # rich prints it


def test_one_cell_characters_are_one_cell_to_rich():
    for c in writer._ONE_CELL:
        assert cell_len(c) == 1, hex(ord(c))


class _Stream(io.StringIO):
    def __init__(self, tty: bool, encoding: str = "utf-8") -> None:
        super().__init__()
        self._tty, self._encoding = tty, encoding

    def isatty(self) -> bool:
        return self._tty

    @property
    def encoding(self) -> str:  # type: ignore[override]
        return self._encoding


@pytest.mark.parametrize(
    ("tty", "encoding", "env", "plain"),
    [
        (False, "utf-8", {}, True),
        (True, "utf-8", {}, False),
        (False, "latin-1", {}, False),
        (False, "utf-8", {"FORCE_COLOR": "1"}, False),
        (False, "utf-8", {"FORCE_COLOR": ""}, True),
        (True, "utf-8", {"FORCE_COLOR": ""}, True),
        (False, "utf-8", {"TTY_COMPATIBLE": "1"}, False),
        (True, "utf-8", {"TTY_COMPATIBLE": "0"}, True),
        (True, "utf-8", {"TTY_COMPATIBLE": "0", "FORCE_COLOR": "1"}, True),
    ],
)
def test_plain_console_is_where_rich_prints_no_styles(monkeypatch, tty, encoding, env, plain):
    """plain_console agrees with rich: no colour system and a Unicode box, or not plain."""
    for name in ("FORCE_COLOR", "TTY_COMPATIBLE"):
        monkeypatch.delenv(name, raising=False)
    for name, value in env.items():
        monkeypatch.setenv(name, value)
    stream = _Stream(tty, encoding)
    assert plain_console(stream) is plain
    con = Console(file=stream, width=120)
    assert (con.color_system is None and con.encoding.startswith("utf")) is plain


def test_no_standard_output_is_left_to_rich():
    """Standard output closed (None): rich discards what it prints."""
    assert plain_console(None) is False


class _Recorder(io.StringIO):
    """A standard output that records its writes and flushes."""

    def __init__(self) -> None:
        super().__init__()
        self.calls: list[tuple[str, ...]] = []

    def write(self, text: str) -> int:
        self.calls.append(("write", text))
        return super().write(text)

    def flush(self) -> None:
        self.calls.append(("flush",))
        super().flush()


def test_standard_output_is_written_as_rich_writes_it(monkeypatch):
    """The same writes and flushes (one write and a flush per table part and note, as rich
    prints them): a pipe closed half-way fails at the same point."""
    blocks = [*_kinematics_blocks(), "a note"]

    def calls(plain: bool) -> list[tuple[str, ...]]:
        monkeypatch.setattr(writer, "plain_console", lambda _file: plain)
        recorder = _Recorder()
        monkeypatch.setattr("sys.stdout", recorder)
        Output("table").write(blocks=blocks)
        return recorder.calls

    assert calls(True) == calls(False)


@pytest.mark.parametrize("output", [None, "table.txt"])
def test_the_table_output_is_the_same_with_rich(monkeypatch, capsys, tmp_path, output):
    """Output.write (standard output, a file): the plain text is what rich writes."""
    path = None if output is None else str(tmp_path / output)

    def written(plain: bool) -> str:
        monkeypatch.setattr(writer, "plain_console", lambda _file: plain)
        if path is not None:
            Output("table", path, force=True).write(blocks=_kinematics_blocks())
            return (tmp_path / output).read_text(encoding="utf-8")
        Output("table").write(blocks=_kinematics_blocks())
        return capsys.readouterr().out

    assert written(True) == written(False)


def test_a_split_verdict_table_repeats_component_and_condition():
    """Issue 32: every part of a verdict table split to fit the console names the component
    and the condition, so its rows can be matched."""
    from crankdyn.cli.writer import _titled_parts, summary_blocks
    from crankdyn.summary import Summary, Verdict

    v = Verdict("intermediate shaft (thrust collar - stern tube flange)", "misfire cylinder 3",
                "synthesised vibratory shear stress (half range)", 30e6, 40e6, "Pa", True,
                "IACS UR M68 (Corr.2 Nov 2012, Aug 2014 text)", "M68.4", speed=70.0)  # fmt: skip
    table, verdict = summary_blocks(Summary("tvc", verdicts=(v,)))
    assert verdict == "Verdict: passed"
    parts = _titled_parts(table, 80)
    assert len(parts) > 1
    for _title, columns in parts:
        assert columns[:2] == [0, 1]
