"""The results table (Parquet and CSV agree, columns, units, order) and the HTML summary."""

from __future__ import annotations

import csv
import json
import math
import random

import numpy as np
import pytest

from crankdyn.io.study_file import load_study
from crankdyn.study.cases import expand
from crankdyn.study.run.journal import read_journal
from crankdyn.study.run.results import CaseTable, read_table, write_outputs
from crankdyn.study.run.runner import run_study
from tests.study.helpers import write_study


@pytest.fixture(scope="module")
def grid(tmp_path_factory):
    folder = tmp_path_factory.mktemp("grid")
    study = write_study(folder, ratios=(0.24, 0.26, 1.5))  # 1.5: two failed cases
    spec = load_study(study)
    run_study(spec, folder / "out", workers=1)
    return spec, folder / "out"


def test_parquet_columns_types_and_units(grid):
    spec, out = grid
    table = read_table(out / "results.parquet")
    assert table.column_names == [
        "case",
        "case_id",
        "status",
        "geometry.rod_ratio",
        "masses.piston_group_kg",
        "mean_torque_Nm",
        "max_main_bearing_load_N",
        "max_piston_acceleration_m_s2",
        "error",
        "elapsed_s",
    ]
    schema = table.schema
    assert str(schema.field("case").type) == "int64"
    assert str(schema.field("masses.piston_group_kg").type) == "double"
    meta = {
        k.decode(): v.decode() for k, v in schema.field("max_main_bearing_load_N").metadata.items()
    }
    assert meta == {
        "label": "Max main-bearing load",
        "unit": "N",
        "role": "figure",
        "key": "max_main_bearing_load",
    }
    param = {
        k.decode(): v.decode() for k, v in schema.field("masses.piston_group_kg").metadata.items()
    }
    assert param["unit"] == "kg" and param["key"] == "masses.piston_group"
    study = json.loads(schema.metadata[b"crankdyn"])
    assert study["fingerprint"] == spec.fingerprint() and study["study"] == "test grid"
    data = table.to_pydict()
    assert data["case"] == [1, 2, 3, 4, 5, 6]
    assert data["status"] == ["ok", "ok", "ok", "ok", "failed", "failed"]
    assert (
        data["error"][:4] == [None] * 4 and "rod ratio R/L must be less than 1" in data["error"][4]
    )
    assert data["mean_torque_Nm"][4] is None or math.isnan(data["mean_torque_Nm"][4])


def test_csv_and_parquet_hold_the_same_numbers(grid):
    _, out = grid
    parquet = read_table(out / "results.parquet").to_pydict()
    with (out / "results.csv").open(encoding="utf-8") as handle:
        rows = list(csv.DictReader(handle))
    for name in ("masses.piston_group_kg", "max_main_bearing_load_N", "elapsed_s"):
        from_csv = [float(r[name]) if r[name] else math.nan for r in rows]
        from_parquet = [math.nan if v is None else v for v in parquet[name]]
        np.testing.assert_array_equal(from_csv, from_parquet)  # exact: shortest round-trip text
    assert [r["case_id"] for r in rows] == parquet["case_id"]


def test_rows_follow_the_case_order_whatever_the_finishing_order(grid):
    spec, out = grid
    records, _ = read_journal(out / "journal.jsonl")
    shuffled = list(records.items())
    random.Random(1).shuffle(shuffled)
    table = CaseTable.build(spec, expand(spec), dict(shuffled))
    assert table.data["case"] == [1, 2, 3, 4, 5, 6]
    assert table.to_csv() == (out / "results.csv").read_text(encoding="utf-8")


def test_the_summary(grid):
    _, out = grid
    html = (out / "summary" / "index.html").read_text(encoding="utf-8")
    for text in (
        "Study: test grid",
        "Best cases",
        "Max main-bearing load: lowest",
        "Sensitivity",
        "Failed cases",
        "rod ratio R/L must be less than 1",
        "The same in every case (to 1 part in a million): Mean indicated torque",
    ):
        assert text in html, text
    assert (out / "summary" / "plots" / "sensitivity.png").is_file()
    summary = json.loads((out / "summary" / "summary.json").read_text())
    assert summary["key_figures"]["failed"] == 2 and summary["key_figures"]["ok"] == 4


def test_monte_carlo_tables_have_the_sample_and_distributions(tmp_path):
    study = write_study(
        tmp_path,
        ratios=(0.26,),
        figures=["max_main_bearing_load"],
        extra=(
            "[monte_carlo]\nsamples = 6\nseed = 3\n"
            '[[parameter]]\nkey = "geometry.bore"\ndistribution = "normal"\n'
            'mean = "76 mm"\nstd = "0.5 mm"\n'
        ),
    )
    spec = load_study(study)
    run = run_study(spec, tmp_path / "out", workers=1)
    assert run.ok == 12
    data = read_table(tmp_path / "out" / "results.parquet").to_pydict()
    assert data["sample"] == [0, 1, 2, 3, 4, 5] * 2
    assert data["geometry.bore_mm"][:6] == data["geometry.bore_mm"][6:]
    assert (tmp_path / "out" / "summary" / "plots" / "distributions.png").is_file()


def test_a_summary_without_the_marker_is_replaced(grid, tmp_path):
    """A study folder written before output folders carried crankdyn's marker (issue 33): its
    summary is the study's own (a derived file) and is replaced when the results are written
    again, the marker added."""
    import shutil

    from crankdyn.io.output import MARKER

    spec, out = grid
    copy = tmp_path / "out"
    shutil.copytree(out, copy)
    (copy / "summary" / MARKER).unlink()
    (copy / "summary" / "index.html").write_text("old", encoding="utf-8")
    records, _ = read_journal(copy / "journal.jsonl")
    write_outputs(spec, CaseTable.build(spec, expand(spec), records), copy)
    assert "Study: test grid" in (copy / "summary" / "index.html").read_text(encoding="utf-8")
    assert (copy / "summary" / MARKER).is_file()
