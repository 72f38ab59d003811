"""``crankdyn crankshaft``: the UR M53 check (the default command, ``strength``), the beam
model's modes and response; tables, JSON, CSV, figures, the exit status of a failed verdict,
one-line errors."""

from __future__ import annotations

import csv
import io
import json

import pytest

from tests.io.test_engine_file_crankshaft import BASE

WEAK = (
    BASE.replace('web_thickness = "115 mm"', 'web_thickness = "60 mm"')
    .replace('web_width = "480 mm"', 'web_width = "300 mm"')
    .replace('web_centre_distance = "135 mm"', 'web_centre_distance = "100 mm"')
    .replace('tensile_strength = "850 MPa"', 'tensile_strength = "400 MPa"')
    + '[crankshaft.factors]\nalpha_b = 5.0\nsource = "assumed for the test"\n'
)
"""Two throws without a torsional model (bending alone), a crankpin fillet factor that fails."""

FAST = ("--speeds", "550:750:50")
"""A coarser sweep than the default 10 rpm (the resolved response adds its critical speeds)."""


@pytest.fixture(scope="module")
def marine_json():
    from crankdyn.cli import main

    buffer = io.StringIO()
    import contextlib

    with contextlib.redirect_stdout(buffer):
        status = main(["crankshaft", "marine-propulsion", *FAST, "--format", "json"])
    return status, json.loads(buffer.getvalue())


def test_the_check_of_every_fillet_and_oil_bore(cli, marine_json):
    status, data = marine_json
    assert status == 0
    run = cli("crankshaft", "marine-propulsion", *FAST)
    assert run.status == 0, run.err
    for label in ("Smallest acceptability factor Q", "Fillets and oil bores (UR M53.3 to M53.7)",
                  "Nominal alternating stresses (UR M53.2)", "M_TN from (2.2.2)"):  # fmt: skip
        assert label in run.out, label
    for throw in range(1, 7):
        for location in ("crankpin fillet", "journal fillet", "oil bore"):
            assert f"throw {throw} {location}" in run.out
    # JSON: every quantity with unit and clause, the verdicts, where M_TN comes from
    rows = data["quantities"]
    assert {r["location"] for r in rows} == {"throw", "crankpin fillet", "journal fillet",
                                             "oil bore"}  # fmt: skip
    q = [r for r in rows if r["symbol"] == "Q"]
    assert len(q) == 18 and all(r["clause"] == "M53.7" for r in q)
    assert min(r["value"] for r in q) == pytest.approx(data["min_acceptability_factor"])
    assert len(data["verdicts"]) == 18 and len(data["nominal_torque_from"]) == 6


def test_the_explicit_command_and_the_csv(cli, marine_json):
    table = cli("crankshaft", "strength", "marine-propulsion", *FAST, "--format", "csv")
    assert table.status == 0
    rows = list(csv.DictReader(io.StringIO(table.out)))
    assert list(rows[0]) == ["throw", "location", "quantity", "symbol", "value", "unit", "clause"]
    sigma_v = [r for r in rows if r["symbol"] == "σ_V"]
    assert len(sigma_v) == 18 and all(r["unit"] == "Pa" and r["clause"] == "M53.5" for r in sigma_v)
    json_q = {
        (r["throw"], r["location"], r["symbol"]): r["value"] for r in marine_json[1]["quantities"]
    }
    for r in rows:
        if r["value"]:
            key = (int(r["throw"]), r["location"], r["symbol"])
            assert float(r["value"]) == pytest.approx(json_q[key], rel=1e-9)


def test_a_failed_verdict_ends_with_status_1(cli, write):
    path = write("weak.toml", WEAK)
    run = cli("crankshaft", path)
    assert run.status == 1, run.err
    assert "FAILED" in run.out or "failed" in run.out
    data = json.loads(cli("crankshaft", path, "--format", "json").out)
    passed = {v["component"]: v["passed"] for v in data["verdicts"]}
    assert not passed["throw 1 crankpin fillet"] and passed["throw 1 journal fillet"]
    assert any("no torsional stress" in n for n in data["notes"])
    # the shared --no-fail (cli/common.py): the same output, status 0
    kept = cli("crankshaft", path, "--no-fail")
    assert kept.status == 0, kept.err
    assert kept.out == run.out


def test_modes_command(cli, tmp_path):
    figure = tmp_path / "shapes.png"
    run = cli("crankshaft", "modes", "marine-propulsion", "--modes", "8", "--plot", figure,
              "--plot-modes", "3,5")  # fmt: skip
    assert run.status == 0, run.err
    assert "Torsional modes: how well the lumped model holds" in run.out
    assert "Lowest axial mode of the beam model" in run.out
    assert figure.stat().st_size > 0
    data = json.loads(cli("crankshaft", "modes", "marine-propulsion", "--modes", "8",
                          "--format", "json").out)  # fmt: skip
    assert len(data["natural_frequencies_hz"]) == 8 and "lumped_frequency_hz" in data
    bad = cli("crankshaft", "modes", "marine-propulsion", "--plot-modes", "3,x")
    assert bad.status == 2 and "--plot-modes" in bad.err and "\n" not in bad.err.strip()


def test_response_command(cli, tmp_path):
    figure = tmp_path / "axial.svg"
    run = cli("crankshaft", "response", "marine-propulsion", "--speeds", "600:750:50",
              "--plot", figure)  # fmt: skip
    assert run.status == 0, run.err
    assert "Largest web bending stress from vibration" in run.out
    assert "critical speeds" in run.out
    assert figure.stat().st_size > 0
    data = json.loads(cli("crankshaft", "response", "marine-propulsion", "--speeds",
                          "600:750:50", "--format", "json").out)  # fmt: skip
    assert data["speed_rpm"][0] == pytest.approx(600.0) and data["speed_rpm"][-1] == 750.0


def test_errors_are_one_line(cli, write):
    run = cli("crankshaft", "inline6-diesel")
    assert run.status == 2 and "[crankshaft]" in run.err and run.err.count("\n") == 1
    run = cli("crankshaft", "marine-propulsion", "--additional-stress", "fe")
    assert run.status == 2 and "--additional-stress" in run.err
    run = cli("crankshaft", write("weak.toml", WEAK), "--additional-stress", "beam")
    assert run.status == 2 and "[torsion]" in run.err and run.err.count("\n") == 1
