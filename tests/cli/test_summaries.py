"""Summaries come from the full-resolution analysis, never from a display grid: for every command
the figures of the table, the JSON (at any --step) and the analysis session a notebook uses are
the same numbers (the table shows them rounded by crankdyn.display, the JSON exactly)."""

from __future__ import annotations

import csv
import io
import json
import math

import numpy as np
import pytest

from crankdyn.engine.model import Engine
from crankdyn.results import Result
from crankdyn.session import Analysis

ENGINE = "inline6-diesel"


@pytest.fixture(scope="module")
def session():
    return Analysis(Engine.example(ENGINE))


def _flat(data, prefix=""):
    """The scalar numbers of a JSON document, by dotted key."""
    out = {}
    if isinstance(data, dict):
        for k, v in data.items():
            out.update(_flat(v, f"{prefix}{k}."))
    elif isinstance(data, (int, float)) and not isinstance(data, bool):
        out[prefix[:-1]] = data
    return out


def _scalars(result: Result) -> dict:
    """The JSON of a result's scalar figures (nested results included), columns left out."""
    keys = {meta["key"] for _f, meta, _v in result._fields("column", "array")}
    return _flat({k: v for k, v in result.to_dict().items() if k not in keys})


def _table_shows(out: str, result: Result) -> None:
    """Every summary row of the session's result is a row of the printed table."""
    lines = out.splitlines()
    for label, value, unit in result.summary_rows():
        if len(value) > 40 or not value or label in ("Engine", "Notes"):
            continue  # the flywheel's table names the engine in its title
        head = label[:24]
        matching = [ln for ln in lines if head in ln and f" {value} " in ln]
        assert matching, (label, value, unit)
        if unit:
            assert any(unit in ln for ln in matching), (label, value, unit)


COMMANDS = {
    "kinematics": lambda s: s.kinematics().summary,
    "pressure": lambda s: s.pressure,
    "forces": lambda s: s.forces(),
    "bearings": lambda s: s.bearings(),
    "torque": lambda s: s.torque,
    "flywheel": lambda s: s.flywheel(),
}


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_table_json_and_session_agree(cli, session, command):
    expected = COMMANDS[command](session)
    full = cli(command, ENGINE, "--format", "json")
    coarse = cli(command, ENGINE, "--format", "json", "--step", "10")
    assert full.status == 0 and coarse.status == 0, (full, coarse)
    got_full = _flat(json.loads(full.out))
    got_coarse = _flat(json.loads(coarse.out))
    want = _scalars(expected)
    prefix = "summary." if command == "kinematics" else ""
    for key, value in want.items():
        assert got_full[prefix + key] == value, key  # exactly: JSON round-trips floats
        assert got_coarse[prefix + key] == value, key  # the display step changes no figure
    table = cli(command, ENGINE)  # a 10 deg table
    assert table.status == 0, table
    _table_shows(table.out, expected)


def test_the_coarse_grid_alone_would_read_low(session):
    """The reason for the above: on the 10 deg display grid the gas force peak reads about 2 %
    low (the issue's 127.8 kN against 130.3 kN); the summary is the refined maximum."""
    forces = session.forces(step=math.radians(10.0))
    assert forces.max_gas_force == session.forces().max_gas_force
    assert np.max(forces.gas_force) < 0.99 * forces.max_gas_force


def test_csv_rows_are_the_json_columns(cli):
    as_json = json.loads(cli("torque", ENGINE, "--format", "json").out)
    rows = list(csv.DictReader(io.StringIO(cli("torque", ENGINE, "--format", "csv").out)))
    assert len(rows) == len(as_json["crank_angle_deg"])
    np.testing.assert_array_equal(
        [float(r["total_torque_Nm"]) for r in rows],
        np.array([float(f"{v:.10g}") for v in as_json["total_torque_Nm"]]),
    )


def test_balance_and_modes_agree(cli, session):
    data = json.loads(cli("balance", ENGINE, "--format", "json").out)
    balance = session.balance()
    assert [o["free_force_N"] for o in data["orders"]] == [o.free_force for o in balance.orders]
    table = cli("balance", ENGINE).out
    assert "e-1" not in table  # round-off next to the unit force reads 0
    modes = json.loads(cli("torsion", "modes", ENGINE, "--format", "json").out)
    assert modes["natural_frequencies_hz"] == pytest.approx(
        list(session.modes.frequencies_hz), rel=0, abs=0
    )


def test_response_peaks_agree(cli, session):
    """The response table's peaks are the session's (resolved at resonances when the result
    resolves them), and the JSON's curves hold them."""
    data = json.loads(cli("torsion", "response", ENGINE, "--format", "json").out)
    result = session.response()
    np.testing.assert_array_equal(data["speed_rpm"], np.round(result.speed * 30 / math.pi, 9))
    shaft = session.most_loaded_shaft()
    value, speed = session.peak("torque", shaft)
    s = result.shaft_index(shaft)
    assert max(row[s] for row in data["synthesized_shaft_torque_Nm"]) == value
    from crankdyn.display import format_value

    table = cli("torsion", "response", ENGINE).out
    text, _unit = format_value(value, "N·m")
    line = next(ln for ln in table.splitlines() if f"{shaft[0]} - {shaft[1]}" in ln)
    assert f" {text} " in line or text in line
    assert f"{speed * 30 / math.pi:.1f}" in line


@pytest.mark.parametrize(
    "args",
    [
        ("linkage", "forces", "fourbar-seed004"),
        (
            "linkage",
            "fourbar",
            "--crank",
            "20",
            "--coupler",
            "70",
            "--rocker",
            "50",
            "--ground",
            "60",
        ),
    ],
)
def test_linkage_summaries_do_not_depend_on_the_rows(cli, args):
    """A 10 deg table and the 1 deg JSON give the same figures: the table's summary is the
    full-turn analysis's."""
    fine = _flat(json.loads(cli(*args, "--format", "json").out))
    coarse = _flat(json.loads(cli(*args, "--format", "json", "--step", "10").out))
    assert fine and {k: v for k, v in coarse.items() if k in fine} == {
        k: v for k, v in fine.items() if k in coarse
    }


def test_the_other_torsion_commands_are_the_sessions(cli, session):
    ex = json.loads(cli("torsion", "excitation", ENGINE, "--format", "json").out)
    assert ex["amplitude_Nm"] == list(session.harmonics().amplitude)
    camp = json.loads(cli("torsion", "campbell", ENGINE, "--format", "json").out)
    assert camp == json.loads(json.dumps(session.campbell().to_dict()))
    damper = json.loads(
        cli(
            "torsion", "damper", ENGINE, "--at", "pulley", "--mode", "2", "--inertia", "0.01",
            "--format", "json",
        ).out
    )  # fmt: skip
    design = session.damper("pulley", 2, 0.01)
    assert {k: v for k, v in damper.items() if "damper" not in k or k == "dampers"} == {
        k: v for k, v in json.loads(json.dumps(design.to_dict())).items()
    }
    firing = json.loads(cli("firing-orders", ENGINE, "--format", "json").out)
    assert firing == json.loads(json.dumps(session.firing_orders().ranked_list()))
