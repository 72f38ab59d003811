"""Signal files read in chunks (crankdyn.io.csv_chunks, crankdyn.io.signals.open_signal): the
same pulses, lines, marks and messages as the line-by-line table reader
(crankdyn.io.csv_tables.read_csv_table), whatever the chunks' size; NumPy files a chunk of
values at a time, their headers checked first."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import crankdyn.io.csv_chunks as chunks
import crankdyn.io.signals as signals
from crankdyn.errors import InputError
from crankdyn.io.csv_chunks import sparse_column
from crankdyn.io.csv_tables import read_csv_table, split_header_unit, unit_factor
from crankdyn.io.signals import open_signal, read_signal
from crankdyn.measure.records import PulseRecord
from tests.conftest import fuzz_examples


def _by_lines(path):
    """The pulse times (s), lines, marks (s) and their lines of a signal CSV read by the table
    reader, cell by cell (the reference of the chunked reader)."""
    table = read_csv_table(path, what="signal file")
    cols = {}
    for i, cell in enumerate(table.header):
        label, unit = split_header_unit(cell)
        cols[label.strip().lower()] = (
            i,
            unit_factor(cell, unit, "time", "f", missing="", unknown=""),
        )
    times = table.column(cols["time"][0], cols["time"][1], kind="time")
    lines = np.array([n for n, _ in table.rows])
    marks = mark_lines = None
    if "reference" in cols:
        marks, mark_lines = sparse_column(table, *cols["reference"])
    return times, lines, marks, mark_lines


cells = st.one_of(
    st.floats(1e-6, 1e4, allow_nan=False).map(lambda x: f"{x:.9f}"),
    st.floats(1e-6, 1e4, allow_nan=False).map(repr),
    st.floats(1e-6, 1e4, allow_nan=False).map(lambda x: f"{x:.6e}"),
    st.integers(1, 10**6).map(str),
    st.floats(1e-3, 1e3, allow_nan=False).map(lambda x: f"  {x:.5f} "),
)


@st.composite
def csv_files(draw):
    """A signal CSV: a header (units s or ms, a reference column or not, a comment before it),
    rows with times in any format, the reference column shorter, blank and comment lines,
    trailing commas, LF or CRLF, a byte-order mark."""
    unit = draw(st.sampled_from(["s", "ms"]))
    reference = draw(st.booleans())
    rows = draw(st.lists(cells, min_size=1, max_size=60))
    marks = draw(st.lists(cells, max_size=len(rows))) if reference else []
    lines = ["# a record", f"time [{unit}],reference [{unit}]" if reference else f"time_{unit}"]
    for i, cell in enumerate(rows):
        if draw(st.integers(0, 9)) == 0:
            lines.append(draw(st.sampled_from(["", "   ", "# comment", ",,", "  # indented"])))
        if reference:
            lines.append(f"{cell},{marks[i] if i < len(marks) else ''}")
        else:
            lines.append(cell + draw(st.sampled_from(["", ""])))
    ending = draw(st.sampled_from(["\n", "\r\n"]))
    text = ending.join(lines) + draw(st.sampled_from([ending, ""]))
    bom = draw(st.sampled_from(["", "\ufeff"]))
    return (bom + text).encode("utf-8")


@settings(max_examples=fuzz_examples(60))
@given(data=csv_files(), size=st.integers(8, 400))
@example(data=b"time [s],reference [s]\n1,0.5\n2,\n3,\n", size=8)
@example(data=b"time [s]\r\n1\r\n2\r\n3", size=9)
def test_chunked_csv_reads_what_the_table_reader_reads(tmp_path_factory, data, size):
    path = tmp_path_factory.mktemp("csv") / "s.csv"
    path.write_bytes(data)
    try:
        expected = _by_lines(path)
    except InputError as exc:  # (a value out of range: the same message in chunks)
        with pytest.raises(InputError) as err:
            _read(path, size)
        assert str(err.value) == str(exc)
        return
    times, lines, marks, mark_lines = _read(path, size)
    np.testing.assert_array_equal(times, expected[0])  # the same floats, to the bit
    np.testing.assert_array_equal(lines, expected[1])
    if expected[2] is not None and expected[2].size:
        np.testing.assert_array_equal(marks, expected[2])
        np.testing.assert_array_equal(mark_lines, expected[3])
    else:
        assert marks.size == 0


def _read(path, size):
    """The chunks of a signal CSV read with chunks of ``size`` bytes, joined."""
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(chunks, "CHUNK_BYTES", size)
        record = open_signal(path, 60)
        assert isinstance(record, PulseRecord)
        parts = list(record.chunks())
    join = lambda key: np.concatenate(  # noqa: E731
        [np.asarray(getattr(c, key)) for c in parts if getattr(c, key) is not None] or [[]]
    )
    return join("times"), join("lines"), join("reference"), join("reference_lines")


def _column(n, start=0.001, step=1e-3):
    return "".join(f"{start + step * k:.9f}\n" for k in range(n))


@pytest.mark.parametrize("size", [64, 1000, 1 << 22])
def test_errors_beyond_the_first_chunk_name_their_line(tmp_path, size, monkeypatch):
    monkeypatch.setattr(chunks, "CHUNK_BYTES", size)
    body = _column(3000).splitlines()
    cases = {
        "x": ("line 2501 = \"x\": not a number in column 'time [s]'"),
        "1,5": ('line 2501 = "1,5": 2 cells, but the header names 1 columns: column 2 has no name'),
        "0.0001": ("times must increase: line 2501 has 0.0001 s after 2.499 s"),
        "1e300": ("line 2501 = \"1e300\": 1e+300 s in column 'time [s]' lies outside"),
    }
    for bad, message in cases.items():
        lines = [*body[:2499], bad, *body[2500:]]
        path = tmp_path / "bad.csv"
        path.write_text("time [s]\n" + "\n".join(lines) + "\n", encoding="utf-8")
        with pytest.raises(InputError) as err:
            read_signal(path, 60)
        assert message in str(err.value) and str(err.value).startswith(str(path))
    path.write_bytes(b"time [s]\n" + _column(3000).encode() + b"\xff\n")
    with pytest.raises(InputError, match=r"not UTF-8 text \(byte 0xff on line 3002\)"):
        read_signal(path, 60)


def test_quoted_cells_and_odd_line_breaks_are_read_line_by_line(tmp_path, monkeypatch):
    monkeypatch.setattr(chunks, "CHUNK_BYTES", 32)
    path = tmp_path / "q.csv"
    path.write_bytes(b'time [s]\n"0.001"\n0.002\r0.003\r\n"0.004"\n')
    train = read_signal(path, 60)
    np.testing.assert_array_equal(train.times, [0.001, 0.002, 0.003, 0.004])
    np.testing.assert_array_equal(train.lines, [2, 3, 4, 5])


def test_a_header_only_file_and_a_huge_line(tmp_path, monkeypatch):
    path = tmp_path / "h.csv"
    path.write_text("# nothing\ntime [s]\n\n", encoding="utf-8")
    with pytest.raises(InputError, match="the signal file holds no data"):
        read_signal(path, 60)
    monkeypatch.setattr(chunks, "MAX_LINE_BYTES", 100)
    monkeypatch.setattr(chunks, "CHUNK_BYTES", 16)
    path.write_text("time [s]\n" + "1" * 200, encoding="utf-8")
    with pytest.raises(InputError, match="a line longer than"):
        read_signal(path, 60)


def test_pulse_times_need_teeth_before_any_reading(tmp_path):
    path = tmp_path / "p.csv"
    path.write_text("time [s]\n" + _column(10), encoding="utf-8")
    with pytest.raises(InputError, match="pulse times need --teeth N"):
        open_signal(path, None)


def test_a_record_expected_longer_than_the_cache_is_read_again_not_kept(tmp_path, monkeypatch):
    """A text file's expected pulses: its size over its first lines' length (exact for a file
    shorter than the sample). Over the limit of :meth:`PulseRecord.cached`, every reading reads
    the file (the first is not kept, to be dropped when it grows too long); under it, the first
    reading's times are replayed. The pulses read are the same either way."""
    path = tmp_path / "p.csv"
    times = np.cumsum(np.full(5000, 1e-3))
    path.write_text("time [s]\n" + "".join(f"{t:.6f}\n" for t in times), encoding="utf-8")
    assert open_signal(path, 60).expected == 5001  # the whole file sampled: its lines
    monkeypatch.setattr(signals, "SAMPLE_BYTES", 1000)
    record = open_signal(path, 60)
    assert abs(record.expected - 5001) <= 5001 * 0.1  # lines of 9 to 12 characters
    reads = []

    def counted():
        reads.append(1)
        return record.chunks()

    counting = PulseRecord(counted, 60, "p.csv", record.expected)
    for limit, readings in ((10_000, 1), (1_000, 3)):
        reads.clear()
        kept = counting.cached(limit)
        got = [np.concatenate([c.times for c in kept.chunks()]) for _ in range(3)]
        assert len(reads) == readings
        for g in got:
            np.testing.assert_array_equal(g, read_signal(path, 60).times)


# ---- NumPy files ------------------------------------------------------------------------------


def test_npy_and_npz_read_in_chunks(tmp_path, monkeypatch):
    monkeypatch.setattr(signals, "CHUNK_VALUES", 777)
    t = np.cumsum(np.full(10_000, 1e-3))
    ref = t[::120] + 3e-4
    np.save(tmp_path / "p.npy", t.astype(">f8"))
    np.savez_compressed(tmp_path / "p.npz", time=t, reference=ref)
    for name in ("p.npy", "p.npz"):
        record = open_signal(tmp_path / name, 60)
        assert isinstance(record, PulseRecord)
        assert [c.times.size for c in record.chunks()][:3] == [777, 777, 777]
        train = record.train()
        np.testing.assert_array_equal(train.times, t)
    np.testing.assert_array_equal(read_signal(tmp_path / "p.npz", 60).reference, ref)


def test_npy_values_checked_chunk_by_chunk(tmp_path, monkeypatch):
    monkeypatch.setattr(signals, "CHUNK_VALUES", 1000)
    t = np.cumsum(np.full(5000, 1e-3))
    bad = t.copy()
    bad[3333] = math.inf
    np.save(tmp_path / "inf.npy", bad)
    with pytest.raises(InputError, match=r"array = inf: not a finite number .* at index 3333"):
        read_signal(tmp_path / "inf.npy", 60)
    back = t.copy()
    back[3000] = back[2998]
    np.save(tmp_path / "back.npy", back)
    with pytest.raises(InputError, match=r"times must increase: sample 3001 has"):
        read_signal(tmp_path / "back.npy", 60)
    (tmp_path / "cut.npy").write_bytes((tmp_path / "back.npy").read_bytes()[:-8])
    with pytest.raises(InputError, match=r"the header claims shape \(5000,\) .* \(truncated\?\)"):
        open_signal(tmp_path / "cut.npy", 60)
