"""Every command follows docs/cli.md: one name, one metavar and one unit per concept, help text
on every option, --plot on every analysis with a figure, -o/--output everywhere, the old names
as hidden aliases that say they are deprecated."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import click
import pytest

from crankdyn.cli import cli as root

DOCS = Path(__file__).parents[2] / "docs" / "cli.md"

SHARED = {
    "--speed": "RPM",
    "--speeds": "LOW:HIGH[:STEP]",
    "--orders": "LIST",
    "--step": "DEG",
    "--angle": "DEG",
    "--plot": "FILE",
}
"""The shared options and their one metavar (docs/cli.md, Vocabulary)."""

METAVAR = re.compile(r"^[A-Z][A-Z0-9_]*(,[A-Z]+)?$|^LOW:HIGH\[:STEP\]$|^RAD/S2?$|^KEY=VALUE$")
RETIRED = {"--range", "--run-up", "--torsion-orders", "--out", "--crank-speed"}

WITH_FIGURES = {
    "kinematics",
    "pressure",
    "forces",
    "bearings",
    "torque",
    "firing-orders",
    "balance",
    "flywheel",
    "torsion modes",
    "torsion holzer",
    "torsion excitation",
    "torsion response",
    "torsion campbell",
    "torsion damper",
    "torsion transient",
    "linkage fourbar",
    "linkage forces",
    "measure",
    "crankshaft modes",
    "crankshaft response",
}
"""The analysis commands with a figure (in the report, or of their own)."""


def _commands(group=root, path=()):
    for name, cmd in sorted(group.commands.items()):
        if getattr(cmd, "hidden", False):
            continue
        if isinstance(cmd, click.Group):
            yield from _commands(cmd, (*path, name))
        else:
            yield " ".join((*path, name)), cmd


COMMANDS = dict(_commands())


def _options(cmd):
    return [p for p in cmd.params if isinstance(p, click.Option)]


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_options_follow_the_vocabulary(name):
    cmd = COMMANDS[name]
    assert cmd.help, name
    for option in _options(cmd):
        long = max(option.opts, key=len)
        if option.hidden:
            assert long in RETIRED, f"{name} {long}: a hidden option is a retired name"
            continue
        assert long not in RETIRED, f"{name} {long}"
        assert option.help, f"{name} {long}: no help text"
        if long in SHARED:
            assert option.metavar == SHARED[long], f"{name} {long}: {option.metavar}"
        if option.is_flag or isinstance(option.type, click.Choice):
            continue
        if option.metavar is not None:
            assert METAVAR.match(option.metavar), f"{name} {long}: metavar {option.metavar}"


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_outputs_and_figures(name):
    opts = {max(o.opts, key=len): o for o in _options(COMMANDS[name])}
    writes = "--format" in opts or name in ("analyze", "demo", "study", "example")
    if writes or name.startswith(("linkage draw", "linkage animate")):
        assert "-o" in opts.get("--output", click.Option(["--x"])).opts, name
    if name in WITH_FIGURES:
        assert "--plot" in opts, name


def test_every_command_and_shared_option_is_documented():
    text = DOCS.read_text(encoding="utf-8")
    for name in COMMANDS:
        assert f"`{name}" in text or f" {name.split()[-1]} " in text, name
    for option, metavar in SHARED.items():
        assert f"`{option} {metavar}`" in text, option
    for old in RETIRED:
        assert old in text, old


def test_retired_names_still_work_and_say_so(cli):
    run = cli("torsion", "campbell", "inline6-diesel", "--range", "1000:2500", "--format", "json")
    assert run.status == 0, run
    assert "crankdyn: warning: --range is deprecated; use --speeds" in run.err
    new = cli("torsion", "campbell", "inline6-diesel", "--speeds", "1000:2500", "--format", "json")
    assert json.loads(run.out) == json.loads(new.out)
    both = cli("torsion", "campbell", "inline6-diesel", "--speeds", "1000:2500", "--range", "1:2")
    assert both.status == 2 and "not both" in both.err


def test_a_bare_linkage_speed_is_rpm(cli):
    """`linkage forces --speed 300` is 300 rpm, as in every command (it read rad/s before)."""

    def torque(speed):
        run = cli(
            "linkage", "forces", "fourbar-seed004", "--angle", "30", "--format", "json",
            "--speed", speed,
        )  # fmt: skip
        assert run.status == 0, run
        return json.loads(run.out)["driving_torque_Nm"]

    assert torque("300") == pytest.approx(torque(f"{300 * math.pi / 30!r} rad/s"), rel=1e-12)
    assert torque("300") != pytest.approx(torque("300 rad/s"), rel=1e-3)


def test_the_engines_speed_is_the_default(cli):
    run = cli("torsion", "excitation", "inline6-diesel", "--format", "json")
    assert run.status == 0, run
    assert json.loads(run.out)["speed_rpm"] == pytest.approx(2200.0)


def test_the_driveline_options_speak_the_vocabulary(cli, tmp_path):
    """The drivelines' options (docs/cli.md): --orders takes a source's orders in every torsion
    command that takes orders, modes are numbered from 1 in every option, MODEL_OR_ENGINE may be
    a mass-elastic table, and the new outputs follow -o/--output and --force."""
    for command in ("response", "campbell", "transient"):
        extra = ("--cycles", "2") if command == "transient" else ("--speeds", "300:750:150")
        run = cli(
            "torsion", command, "marine-propulsion", "--orders", "1.25,3", *extra, "--format",
            "json",
        )  # fmt: skip
        assert run.status == 0, (command, run)
        assert json.loads(run.out)["orders"] == [1.25, 3.0], command
    for mode, text in (("0", "the rigid-body mode cannot be damped"), ("99", "modes 1 to")):
        run = cli("torsion", "damper", "inline6-diesel", "--at", "pulley", "--mode", mode,
                  "--inertia", "0.01")  # fmt: skip
        assert run.status == 2 and f"--mode = {mode}: " in run.err and text in run.err, run
    table = tmp_path / "genset.csv"
    assert cli("torsion", "table", "genset-1500", "-o", table).status == 0
    again = cli("torsion", "table", "genset-1500", "-o", table)
    assert again.status == 2 and "--force" in again.err
    damped = cli("torsion", "modes", table, "--damped", "--modal-damping", "0.02", "-o",
                 tmp_path / "damped.json", "--format", "json")  # fmt: skip
    assert damped.status == 0, damped
    data = json.loads((tmp_path / "damped.json").read_text(encoding="utf-8"))
    assert data["mode"][:2] == [0, 1] and data["damping_ratios"][0] is None
