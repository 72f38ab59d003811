"""``crankdyn analyze ENGINE`` and ``crankdyn demo``: the engineering report."""

from __future__ import annotations

import math
from pathlib import Path

import click
from rich.console import Console
from rich.progress import BarColumn, Progress, SpinnerColumn, TextColumn, TimeElapsedColumn
from rich.table import Table as RichTable

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
from crankdyn.report.build import build_report
from crankdyn.report.sections import builders
from crankdyn.report.write import write_report

DEMO_ENGINE = "inline6-diesel"
_BADGE = {"pass": "[green]pass[/]", "warn": "[yellow]warn[/]", "fail": "[red]fail[/]", None: ""}


def run_report(
    engine: Engine, out: Path, *, speed: float | None, speeds, force: bool, measurement=None
) -> int:
    """Build and write the report with a progress bar, then print the summary table."""
    if out.exists() and not force:  # fail before the long work
        raise InputError("already exists; not overwritten without --force", file=str(out))
    con = console()
    err = Console(stderr=True)
    with Progress(
        SpinnerColumn(),
        TextColumn("{task.description}"),
        BarColumn(),
        TextColumn("{task.completed}/{task.total}"),
        TimeElapsedColumn(),
        console=err,
        transient=True,
    ) as progress:
        task = progress.add_task("Analysing", total=len(builders()))

        def step(name):
            progress.update(task, description=f"Analysing: {name}", advance=1)

        report = build_report(
            engine, speed=speed, speeds=speeds, progress=step, measurement=measurement
        )
        plots = sum(len(s.plots) for s in report.sections)
        task2 = progress.add_task("Writing plots", total=plots)

        def plot_step(name):
            progress.update(task2, description=f"Writing plots: {name}", advance=1)

        write_report(report, out, force=force, progress=plot_step)
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
        con.print(f"[dim]Not analysed: {note}[/]")
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
@click.option(
    "--measurement",
    default=None,
    metavar="SIGNAL",
    help="A torsiograph signal to hold against the model (crankdyn measure; needs --teeth for "
    "pulse times and --at).",
)
@click.option("--teeth", type=int, default=None, metavar="N", help="Pulses per revolution.")
@click.option("--at", "mass", default=None, metavar="MASS", help="The mass that carries the wheel.")
@click.option("--force", is_flag=True, help="Replace an existing report folder.")
def analyze_command(engine, out, speed, speeds, measurement, teeth, mass, force) -> int:
    """Run every analysis that applies to ENGINE and write an HTML report with its data."""
    eng = load_engine_arg(engine)
    signal = _measurement(eng, measurement, teeth, mass)
    w = option_quantity(speed, "speed", "--speed", "rpm")
    if w is not None and not w > 0:
        raise InputError("the speed must be positive", key="--speed", value=speed)
    sweep = speed_range(speeds)
    stem = Path(engine).stem if engine.endswith(".toml") else engine
    target = Path(out) if out else Path(f"{stem}-report")
    return run_report(eng, target, speed=w, speeds=sweep, force=force, measurement=signal)


def _measurement(engine: Engine, signal, teeth, mass):
    """--measurement SIGNAL --teeth N --at MASS, analysed before the report's long work."""
    if signal is None:
        if teeth is not None or mass is not None:
            raise InputError("--teeth and --at go with --measurement SIGNAL", key="--measurement")
        return None
    if mass is None:
        raise InputError("give --at MASS, the mass that carries the wheel", key="--at")
    if engine.torsion is not None:
        try:
            engine.torsion.index(mass)
        except InputError as exc:
            raise InputError(exc.message, key="--at", value=mass) from None
    from crankdyn.cli.measure import load_measurement
    from crankdyn.report.sections.measurement import MeasurementInput

    return MeasurementInput(load_measurement(signal, teeth, cycle=engine.cycle), mass)


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
