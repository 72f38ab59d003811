"""``crankdyn analyze ENGINE`` and ``crankdyn demo``: the engineering report."""

from __future__ import annotations

import math
from pathlib import Path

import click
from rich.progress import BarColumn, Progress, SpinnerColumn, TextColumn, TimeElapsedColumn
from rich.table import Table as RichTable
from rich.text import Text

from crankdyn.cli.common import (
    console,
    load_engine_arg,
    option_quantity,
    speed_option,
    speed_range,
)
from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.io.engine_file import load_example
from crankdyn.io.output import check_output_dir
from crankdyn.report.build import build_report
from crankdyn.report.sections import builders
from crankdyn.report.write import write_report

DEMO_ENGINE = "inline6-diesel"
_BADGE = {
    "pass": Text("pass", style="green"),
    "warn": Text("warn", style="yellow"),
    "fail": Text("fail", style="red"),
    None: "",
}


def run_report(engine: Engine, out: Path, *, speed: float | None, speeds, force: bool) -> int:
    """Build and write the report with a progress bar, then print the summary table."""
    check_output_dir(out, force=force)  # fail before the long work
    con = console()
    err = console(stderr=True)
    with Progress(
        SpinnerColumn(),
        TextColumn("{task.description}", markup=False),
        BarColumn(),
        TextColumn("{task.completed}/{task.total}"),
        TimeElapsedColumn(),
        console=err,
        transient=True,
    ) as progress:
        task = progress.add_task("Analysing", total=len(builders()))

        def step(name):
            progress.update(task, description=f"Analysing: {name}", advance=1)

        report = build_report(engine, speed=speed, speeds=speeds, progress=step)
        plots = sum(len(s.plots) for s in report.sections)
        task2 = progress.add_task("Writing plots", total=plots)

        def plot_step(name):
            progress.update(task2, description=f"Writing plots: {name}", advance=1)

        out = write_report(report, out, force=force, progress=plot_step)
    table = RichTable(title=f"{engine.name}: key figures", header_style="bold")
    table.add_column("Quantity")
    table.add_column("Value", justify="right")
    table.add_column("Status")
    for f in report.key_figures():
        table.add_row(f.label, f.display, _BADGE[f.status])
    con.print(table)
    failed = [c for c in report.checks() if not c.passed]
    if report.checks():
        con.print(
            f"Cross-checks: {len(report.checks()) - len(failed)} of {len(report.checks())} passed."
        )
    for note in report.notes:
        con.print(Text(f"Not analysed: {note}", style="dim"))
    con.print(f"Report: {out / 'index.html'}")
    return 0


@click.command("analyze")
@click.argument("engine", metavar="ENGINE")
@click.option(
    "--out", default=None, metavar="DIR", help="Report folder (default: <engine name>-report)."
)
@speed_option("Operating speed (rpm or with a unit); default: the engine's [operating] speed.")
@click.option(
    "--speeds",
    metavar="A:B:STEP",
    default=None,
    help="Speed range of the sweeps (rpm), e.g. 1000:2500:25.",
)
@click.option("--force", is_flag=True, help="Replace an existing report folder.")
def analyze_command(engine, out, speed, speeds, force) -> int:
    """Run every analysis that applies to ENGINE and write an HTML report with its data."""
    eng = load_engine_arg(engine)
    w = option_quantity(speed, "speed", "--speed", "rpm")
    if w is not None and not w > 0:
        raise InputError("the speed must be positive", key="--speed", value=speed)
    sweep = speed_range(speeds)
    stem = Path(engine).stem if engine.endswith(".toml") else engine
    target = Path(out) if out else Path(f"{stem}-report")
    return run_report(eng, target, speed=w, speeds=sweep, force=force)


@click.command("demo")
@click.option(
    "--out", default="crankdyn-demo", show_default=True, metavar="DIR", help="Report folder."
)
@click.option("--force", is_flag=True, help="Replace an existing DIR.")
def demo_command(out: str, force: bool) -> int:
    """The full report on the built-in inline-6 diesel (crankdyn analyze inline6-diesel)."""
    engine = load_example(DEMO_ENGINE)
    speed = engine.speed if engine.speed else 2000 * math.pi / 30
    return run_report(engine, Path(out), speed=speed, speeds=None, force=force)


def register(group: click.Group) -> None:
    group.add_command(analyze_command)
    group.add_command(demo_command)
