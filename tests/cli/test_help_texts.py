"""The command line's documentation is each command's click help (and the CLI reference the
documentation site generates from it): every command of the lazy group, hidden ones included,
has help; every option has help text; every argument is named in its command's help; and every
option that takes a quantity says the unit of a bare number and its default.

The walk goes through ``cli.commands``, which loads every module of
:data:`crankdyn.cli.COMMAND_MODULES` (tests/cli/test_lazy.py holds that index to what the modules
register), so a command added to any module is checked here without listing it.
"""

from __future__ import annotations

import re

import click
import pytest

from crankdyn.cli import COMMAND_MODULES, cli


def _walk(group: click.Group, path: tuple[str, ...] = ()):
    """(command path, command) for the group and everything under it, hidden ones too."""
    yield " ".join(path) or "crankdyn", group
    for name, cmd in sorted(group.commands.items()):
        if isinstance(cmd, click.Group):
            yield from _walk(cmd, (*path, name))
        else:
            yield " ".join((*path, name)), cmd


COMMANDS = dict(_walk(cli))

UNITS = {
    "RPM": "rpm",
    "LOW:HIGH[:STEP]": "rpm",
    "LOW:HIGH": "rpm",
    "START:END": "rpm",
    "DEG": "deg",
    "MM": "mm",
    "P,Q": "mm",
    "KW": "kW",
    "KGM2": "kg·m²",
    "NM": "N·m",
    "S": "s",
    "HZ": "Hz",
    "RAD/S": "rad/s",
    "RAD/S2": "rad/s²",
}
"""The metavars that name a quantity (docs/cli.md: options whose metavar names a unit take that
unit for bare numbers), and the unit the help text must name."""

KNOWN_GAPS: dict[tuple[str, str], str] = {}
"""Help texts found lacking in modules this change does not edit; fix them there and remove
the entry."""


def _unit_named(unit: str, text: str) -> bool:
    """Whether ``unit`` appears in ``text`` as a unit (not inside a word: "s" is not the s of
    "speeds")."""
    return re.search(rf"(?<![\w·/]){re.escape(unit)}(?![\w²/])", text) is not None


def _visible_options(cmd: click.Command) -> list[click.Option]:
    """The options ``--help`` shows: retired names stay as hidden aliases that print a
    deprecation line when used (test_vocabulary.py holds them to that)."""
    return [p for p in cmd.params if isinstance(p, click.Option) and not p.hidden]


def test_the_walk_reaches_every_module():
    names = {name.split()[0] for name in COMMANDS if name != "crankdyn"}
    for module, registered in COMMAND_MODULES.items():
        assert set(registered) <= names, module
    # the modules that add to a group another module makes (torsion_response to torsion) loaded
    assert {"torsion modes", "torsion response", "linkage fourbar", "linkage animate"} <= set(
        COMMANDS
    )


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_every_command_has_help(name):
    cmd = COMMANDS[name]
    assert cmd.help and cmd.help.strip(), f"{name}: no help"
    assert "Parameters\n" not in cmd.help, f"{name}: numpydoc sections show in --help"


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_every_argument_is_named_in_the_help(name):
    cmd = COMMANDS[name]
    for arg in (p for p in cmd.params if isinstance(p, click.Argument)):
        metavar = (arg.metavar or arg.name or "").strip("[]").rstrip(".")
        assert metavar and metavar in (cmd.help or ""), f"{name}: {metavar} is not in the help"


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_every_option_has_help(name):
    for option in _visible_options(COMMANDS[name]):
        long = max(option.opts, key=len)
        assert option.help and option.help.strip(), f"{name} {long}: no help text"


def _quantity_problems(name: str, cmd: click.Command) -> list[str]:
    """What the help texts of ``cmd``'s quantity options lack: the unit, the default."""
    problems = []
    for option in _visible_options(cmd):
        long = max(option.opts, key=len)
        unit = UNITS.get(option.metavar or "")
        if unit is None or (name, long) in KNOWN_GAPS:
            continue
        text = option.help or ""
        if not _unit_named(unit, text):
            problems.append(f"{long}: the help does not name the unit of a bare number ({unit})")
        if not (option.required or option.show_default or "default" in text.lower()):
            problems.append(f"{long}: the help does not say the default")
    return problems


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_quantities_name_their_unit_and_default(name):
    problems = _quantity_problems(name, COMMANDS[name])
    assert not problems, f"{name}: " + "; ".join(problems)


def test_the_quantity_check_finds_what_is_missing():
    @click.command("probe")
    @click.option("--speed", metavar="RPM", help="Crank speed.")
    @click.option("--step", metavar="DEG", help="Crank-angle step (deg).")
    @click.option("--length", metavar="MM", required=True, help="A length (mm).")
    @click.option("--time", metavar="S", default="1 s", show_default=True, help="Time (s).")
    def probe(speed: str, step: str, length: str, time: str) -> None:
        """A probe."""

    assert _quantity_problems("probe", probe) == [
        "--speed: the help does not name the unit of a bare number (rpm)",
        "--speed: the help does not say the default",
        "--step: the help does not say the default",
    ]


def test_the_unit_check_reads_units_not_letters():
    assert _unit_named("s", "Simulated time (s, or with a unit)")
    assert not _unit_named("s", "Speed range of the speeds")
    assert _unit_named("rpm", "Speed bin of order tracking (rpm); default 10.")
    assert not _unit_named("rad/s", "Crank angular acceleration (rad/s² for a bare number)")
    assert _unit_named("rad/s²", "Crank angular acceleration (rad/s² for a bare number)")


def test_known_gaps_name_real_options():
    for (name, long), _why in KNOWN_GAPS.items():
        assert name in COMMANDS, name
        assert any(long in o.opts for o in _visible_options(COMMANDS[name])), (name, long)
