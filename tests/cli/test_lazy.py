"""The lazy command group: a command imports only what it runs (issue 16, start-up).

No timing here: the tests check what the start-up imports, which is what makes it slow."""

from __future__ import annotations

import importlib
import json
import subprocess
import sys

import click
import pytest

from crankdyn.cli import COMMAND_MODULES, COMMAND_SUMMARIES

HEAVY = (
    "matplotlib",
    "scipy.optimize",
    "dask",
    "pyarrow",
    "pint",
    "distributed",
    "pandas",
    "rich",  # the tables of a command whose output is not a terminal are plain text
    "crankdyn.torsion.modal",
    "crankdyn.torsion.mode_blocks",
    "crankdyn.torsion.nodes",
    "crankdyn.torsion.response",
    "crankdyn.torsion.solvers",
    "crankdyn.torsion.sweep",
    "crankdyn.linkage",
    "crankdyn.report",
    "crankdyn.plots",
)


def test_the_index_is_what_the_modules_register():
    """COMMAND_MODULES names, for each module, the top-level commands its register() adds."""
    for module, names in COMMAND_MODULES.items():
        group = click.Group()
        importlib.import_module(f"crankdyn.cli.{module}").register(group)
        if group.commands:  # torsion_response adds its commands to the torsion group itself
            assert set(group.commands) == set(names), module
        else:
            assert set(names) <= {n for m, ns in COMMAND_MODULES.items() if m != module for n in ns}


def test_every_command_resolves():
    from crankdyn.cli import cli

    ctx = click.Context(cli)
    for name in cli.list_commands(ctx):
        assert cli.get_command(ctx, name) is not None, name
    assert set(cli.commands) == set(cli.list_commands(ctx))


def _imported_after(code: str) -> set[str]:
    script = f"import sys, json\n{code}\nprint(json.dumps(sorted(sys.modules)))"
    out = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True, timeout=120
    )
    return set(json.loads(out.stdout.strip().splitlines()[-1]))


def _heavy(modules: set[str]) -> list[str]:
    return sorted(h for h in HEAVY if h in modules)


@pytest.mark.parametrize(
    "code",
    [
        "import crankdyn.cli",
        "from crankdyn.cli import main\nimport contextlib, io\n"
        "with contextlib.redirect_stdout(io.StringIO()): main(['--help'])",
        "from crankdyn.cli import main\nimport contextlib, io\n"
        "with contextlib.redirect_stdout(io.StringIO()): main(['kinematics', 'vaz2108'])",
        "from crankdyn.cli import main\nimport contextlib, io\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    main(['kinematics', 'vaz2108', '--format', 'json'])\n"
        "    main(['kinematics', 'vaz2108', '--format', 'csv'])\n"
        "    main(['kinematics', 'vaz2108', '--step', '5'])",
    ],
    ids=["import", "help", "kinematics", "kinematics-formats"],
)
def test_start_up_imports_nothing_heavy(code):
    assert _heavy(_imported_after(code)) == []


def test_a_command_imports_only_its_own_module():
    modules = _imported_after(
        "from crankdyn.cli import main\nimport contextlib, io\n"
        "with contextlib.redirect_stdout(io.StringIO()): main(['kinematics', 'vaz2108'])"
    )
    assert "crankdyn.cli.kinematics" in modules
    assert not {"crankdyn.cli.study", "crankdyn.cli.measure", "crankdyn.cli.analyze"} & modules


def test_help_imports_no_command_module_nor_numpy():
    """``crankdyn --help`` lists the commands from COMMAND_SUMMARIES."""
    modules = _imported_after(
        "from crankdyn.cli import main\nimport contextlib, io\n"
        "with contextlib.redirect_stdout(io.StringIO()): main(['--help'])"
    )
    assert not {m for m in modules if m.startswith("crankdyn.cli.")}
    assert "numpy" not in modules


def _first_sentence(help_text: str) -> str:
    """The help up to the first word ending a sentence, in its first paragraph."""
    words = []
    for word in help_text.split("\n\n")[0].split():
        words.append(word)
        if word.endswith("."):
            break
    return " ".join(words)


def test_the_summaries_are_the_commands_first_sentences():
    """COMMAND_SUMMARIES holds each top-level command's first sentence, which gives the same
    short help as the command at every width (the listing never shows more)."""
    from crankdyn.cli import cli

    ctx = click.Context(cli)
    names = cli.list_commands(ctx)
    assert set(COMMAND_SUMMARIES) == set(names)
    for name in names:
        cmd = cli.get_command(ctx, name)
        assert cmd is not None and not cmd.hidden and not cmd.deprecated, name
        assert not cmd.short_help, name  # the listing is made from the help
        assert COMMAND_SUMMARIES[name] == _first_sentence(cmd.help or ""), name
        stand_in = click.Command(name, help=COMMAND_SUMMARIES[name])
        for limit in range(10, 200):
            assert stand_in.get_short_help_str(limit) == cmd.get_short_help_str(limit), name


def test_help_from_the_summaries_is_the_help_of_the_commands():
    """The group's help at several widths: listed from the summaries (nothing loaded), then
    with every command module loaded; the same text."""
    script = (
        "import click, json\n"
        "from crankdyn.cli import cli\n"
        "def helps():\n"
        "    return [cli.get_help(click.Context(cli, info_name='crankdyn', terminal_width=w,\n"
        "        max_content_width=100)) for w in (40, 60, 80, 100, 120, 200)]\n"
        "lazy = helps()\n"
        "cli.commands  # loads every command module\n"
        "print(json.dumps([lazy, helps()]))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, check=True, timeout=120
    )
    lazy, loaded = json.loads(out.stdout.strip().splitlines()[-1])
    assert lazy == loaded
    assert all("kinematics" in text and "torsion" in text for text in lazy)
