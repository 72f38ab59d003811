"""``crankdyn torsion transient MODEL --event KIND -p KEY=VALUE``: one event, its summary and
verdicts, its histories as CSV and JSON, its figure, and one-line errors."""

from __future__ import annotations

import csv
import io
import json

SHORT_CIRCUIT = (
    "torsion", "transient", "genset-1500", "--event", "short-circuit",
    "-p", "xd2=0.12", "-p", "xd1=0.25", "-p", "xd=2.2", "-p", "td2=15 ms", "-p", "td1=0.35 s",
    "-p", "ta=40 ms", "-p", "line_frequency=50 Hz", "--duration", "0.1",
)  # fmt: skip


def test_short_circuit_json_holds_the_verdicts(cli):
    run = cli(*SHORT_CIRCUIT, "--format", "json")
    assert run.status == 0, run
    data = json.loads(run.out)
    assert data["event"] == "three-phase short circuit" and data["severity"] == "exceptional"
    rows = {v["quantity"].split(" vs ")[-1]: v for v in data["verdicts"]}
    assert rows["T_Kmax"]["component"] == "elastic coupling"
    assert rows["T_Kmax"]["limit"] == 16000.0 and rows["T_Kmax"]["passed"]
    assert rows["T_Kmax2"]["limit"] == 25000.0  # a short circuit is exceptional
    assert data["duration_s"] == 0.1


def test_short_circuit_table_csv_and_plot(cli, tmp_path):
    table = cli(*SHORT_CIRCUIT)
    assert table.status == 0, table
    assert "Largest coupling torque" in table.out and "T_Kmax" in table.out
    out = tmp_path / "sc.csv"
    figure = tmp_path / "sc.png"
    run = cli(*SHORT_CIRCUIT, "--format", "csv", "-o", out, "--plot", figure)
    assert run.status == 0, run
    header = next(csv.reader(io.StringIO(out.read_text(encoding="utf-8"))))
    assert header[:2] == ["time_s", "speed_rpm"]
    assert "torque_Nm.coupling primary - coupling secondary" in header
    assert figure.stat().st_size > 10_000


def test_bad_event_keys_end_in_one_line(cli):
    run = cli("torsion", "transient", "genset-1500", "--event", "short-circut")
    assert run.status == 2 and 'did you mean "short-circuit"' in run.err
    assert run.err.count("\n") == 1
    run = cli(*SHORT_CIRCUIT, "-p", "clearing=0.1 s")
    assert run.status == 2 and "clearing" in run.err and run.err.count("\n") == 1
    run = cli("torsion", "transient", "genset-1500", "-p", "xd=2.2")
    assert run.status == 2 and "-p" in run.err
