"""``crankdyn examples`` and ``crankdyn example NAME``: the one catalogue of built-in examples
(engines, torsional models, linkages, studies)."""

from __future__ import annotations

from pathlib import Path

import click

from crankdyn.cli.writer import Output, TextTable
from crankdyn.errors import InputError
from crankdyn.io.catalogue import catalogue
from crankdyn.io.examples import EXAMPLE_KINDS, example_files, example_kind
from crankdyn.io.output import check_writable, write_bytes

_KIND_CHOICE = click.Choice(tuple(EXAMPLE_KINDS))


def print_examples(kind: str | None = None) -> None:
    """The catalogue as one table (or the examples of one kind)."""
    table = TextTable(
        "Built-in examples",
        ["Name", "Kind", "Title", "What"],
        [[ex.name, EXAMPLE_KINDS[ex.kind][1], ex.title, ex.description] for ex in catalogue(kind)],
        text_columns={0, 1, 2, 3},
    )
    Output("table").write(
        blocks=[
            table,
            "Use a name wherever a file is expected (ENGINE, MODEL_OR_ENGINE, LINKAGE, STUDY); "
            "`crankdyn example NAME` writes the file to edit.",
        ]
    )


@click.command("examples")
@click.option(
    "--kind",
    type=_KIND_CHOICE,
    default=None,
    help="Only the examples of one kind (default: all).",
)
def examples_command(kind: str | None) -> int:
    """List the built-in examples: engines, torsional models, linkages and studies."""
    print_examples(kind)
    return 0


def write_example(name: str, output: str | None, force: bool, kind: str | None = None) -> None:
    """Write the example NAME (and the files it names) to OUTPUT (a file or a folder)."""
    files = example_files(name, kind)
    main_file = files[0]
    if output == "-":
        click.echo(main_file.read_text(encoding="utf-8"), nl=False)
        return
    target = Path(output) if output else Path(f"{name}.toml")
    if target.is_dir():
        target = target / f"{name}.toml"
    if target.suffix != ".toml":
        raise InputError("the output file name must end in .toml", key="--output", value=output)
    # the files it names keep their place relative to it (e.g. torsion/<line>.toml)
    destinations = [(main_file, target)] + [
        (f, target.parent / _relative(f, main_file.parent)) for f in files[1:]
    ]
    check_writable(target, force=force)
    for _src, dst in destinations:
        if dst.exists() and not force:
            check_writable(dst, force=force)
        for folder in dst.parents:
            if folder == target.parent:
                break
            if folder.exists() and not folder.is_dir():
                raise InputError("is a file, not a folder", file=str(folder))
    for src, dst in destinations:
        dst.parent.mkdir(parents=True, exist_ok=True)
        click.echo(f"wrote {write_bytes(dst, src.read_bytes(), force=force)}", err=True)


def _relative(path: Path, folder: Path) -> Path:
    """``path`` relative to ``folder``, or its bare name when it lies outside."""
    try:
        return path.relative_to(folder)
    except ValueError:  # outside the example's folder: beside the written file
        return Path(path.name)


@click.command("example")
@click.argument("name", metavar="NAME")
@click.option(
    "-o",
    "--output",
    default=None,
    metavar="PATH",
    help="File (NAME.toml by default) or folder to write to; '-' prints the file.",
)
@click.option("--force", is_flag=True, help="Overwrite existing files.")
def example_command(name: str, output: str | None, force: bool) -> int:
    """Write the built-in example NAME (engine, torsional model, linkage or study, with any file
    it names, such as a pressure trace) to a file to edit."""
    write_example(name, output, force)
    return 0


def examples_alias(kind: str, group_name: str) -> click.Command:
    """``crankdyn GROUP examples``: the catalogue's examples of one kind (kept for scripts)."""

    @click.command("examples", hidden=True)
    def alias() -> int:
        print_examples(kind)
        return 0

    alias.help = f"List the built-in {EXAMPLE_KINDS[kind][1]} examples (crankdyn examples)."
    return alias


def example_alias(kind: str) -> click.Command:
    """``crankdyn GROUP example NAME``: ``crankdyn example NAME`` for one kind."""

    @click.command("example", hidden=True)
    @click.argument("name", metavar="NAME")
    @click.option("-o", "--output", default=None, metavar="PATH", help="File or folder.")
    @click.option("--force", is_flag=True, help="Overwrite existing files.")
    def alias(name: str, output: str | None, force: bool) -> int:
        found = example_kind(name)
        if found is not None and found != kind:
            raise InputError(
                f"{name} is a built-in {EXAMPLE_KINDS[found][1]}, not a "
                f"{EXAMPLE_KINDS[kind][1]} (crankdyn example {name} writes it)",
                key="example",
                value=name,
            )
        write_example(name, output, force, kind)
        return 0

    alias.help = f"Write the built-in {EXAMPLE_KINDS[kind][1]} NAME (crankdyn example NAME)."
    return alias


def register(group: click.Group) -> None:
    """Add ``examples`` and ``example`` to the command ``group``."""
    group.add_command(examples_command)
    group.add_command(example_command)
