"""``crankdyn examples`` and ``crankdyn example NAME``."""

from __future__ import annotations

import math
from pathlib import Path

import click
from rich.table import Table as RichTable

from crankdyn.cli.common import console
from crankdyn.errors import InputError
from crankdyn.io.engine_file import example_files, example_names, load_example
from crankdyn.io.output import check_writable, write_bytes


@click.command("examples")
def examples_command() -> int:
    """List the built-in example engines."""
    table = RichTable(title="Built-in examples", header_style="bold")
    for col in (
        "Name",
        "Engine",
        "Cylinders",
        "Bore x stroke (mm)",
        "λ",
        "Speed (rpm)",
        "Pressure",
    ):
        table.add_column(col)
    for name in example_names():
        e = load_example(name)
        c = e.cylinders
        layout = f"{c.count} {c.layout}" + (
            f" {math.degrees(c.bank_angle):.0f}°" if c.layout == "V" else ""
        )
        table.add_row(
            name,
            e.name,
            f"{layout}, {e.cycle}",
            f"{e.geometry.bore * 1e3:g} x {e.geometry.nominal_stroke * 1e3:g}",
            f"{e.geometry.lam:.3f}",
            f"{e.speed * 30 / math.pi:.0f}" if e.speed else "-",
            "trace" if e.pressure is not None else "-",
        )
    console().print(table)
    return 0


@click.command("example")
@click.argument("name")
@click.option(
    "-o",
    "--output",
    default=None,
    metavar="PATH",
    help="File (NAME.toml by default) or folder to write to; '-' prints the file.",
)
@click.option("--force", is_flag=True, help="Overwrite existing files.")
def example_command(name: str, output: str | None, force: bool) -> int:
    """Write the built-in example NAME (and any pressure trace it uses) to a file."""
    files = example_files(name)
    main_file = files[0]
    if output == "-":
        click.echo(main_file.read_text(encoding="utf-8"), nl=False)
        return 0
    target = Path(output) if output else Path(f"{name}.toml")
    if target.is_dir():
        target = target / f"{name}.toml"
    if target.suffix != ".toml":
        raise InputError("the output file name must end in .toml", key="--output", value=output)
    destinations = [(main_file, target)] + [(f, target.parent / f.name) for f in files[1:]]
    for _src, dst in destinations:
        check_writable(dst, force=force)
    for src, dst in destinations:
        click.echo(f"wrote {write_bytes(dst, src.read_bytes(), force=force)}", err=True)
    return 0


def register(group: click.Group) -> None:
    group.add_command(examples_command)
    group.add_command(example_command)
