"""``crankdyn analyze ENGINE`` and ``crankdyn demo``: the engineering report."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import click
from rich.progress import BarColumn, Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

from crankdyn.cli.common import (
    at_option,
    console,
    deprecated_alias,
    merge_alias,
    parse_speed,
    speed_option,
    speed_sweep,
    speeds_option,
    teeth_option,
)
from crankdyn.cli.writer import Output, TextTable
from crankdyn.constants import RPM
from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.io.catalogue import load_example, resolve_engine
from crankdyn.io.output import check_output_dir
from crankdyn.plots.render import Renderer, collector_paused
from crankdyn.report.build import build_report
from crankdyn.report.sections import builders
from crankdyn.report.write import write_report

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import NDArray

    from crankdyn.report.model import Section
    from crankdyn.report.sections.measurement import MeasurementInput

DEMO_ENGINE = "inline6-diesel"
"""The built-in engine of ``crankdyn demo``."""


def run_report(
    engine: Engine,
    out: Path,
    *,
    speed: float | None,
    speeds: NDArray[np.float64] | None,
    force: bool,
    measurement: MeasurementInput | None = None,
) -> int:
    """Build and write the report with a progress bar, then print the summary table.

    Parameters
    ----------
    engine
        The engine.
    out
        The report folder (checked before the work, :func:`crankdyn.io.output.check_output_dir`).
    speed
        The operating speed (rad/s); None: the engine's own.
    speeds
        The speeds of the sweeps (rad/s); None: the session's default range.
    force
        Whether an existing folder may be replaced.
    measurement
        A torsiograph signal to hold against the torsional model (the measurement section).

    Returns
    -------
    int
        The exit status, 0.

    Raises
    ------
    InputError
        When the folder cannot be written, naming it and the reason.
    """
    check_output_dir(out, force=force)  # fail before the long work
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

        def step(name: str) -> None:
            """Advance the bar past the report section ``name``."""
            progress.update(task, description=f"Analysing: {name}", advance=1)

        # each section's figures drawn while the next is made; no collector passes over the
        # figures kept to the end
        with collector_paused(), Renderer() as renderer:
            renderer.busy()

            def built(section: Section) -> None:
                """Start drawing the figures of ``section``."""
                for plot in section.plots:
                    renderer.submit(plot.figure)

            report = build_report(
                engine,
                speed=speed,
                speeds=speeds,
                progress=step,
                measurement=measurement,
                built=built,
            )
            plots = sum(len(s.plots) for s in report.sections)
            task2 = progress.add_task("Writing plots", total=plots)

            def plot_step(name: str) -> None:
                """Advance the bar past the plot ``name``."""
                progress.update(task2, description=f"Writing plots: {name}", advance=1)

            # the folder written: a numbered sibling when ``out`` appeared while the report
            # was built
            out = write_report(report, out, force=force, progress=plot_step, renderer=renderer)
    table = TextTable(
        f"{engine.name}: key figures",
        ["Quantity", "Value", "Status"],
        [[f.label, f.display, f.status or ""] for f in report.key_figures()],
        text_columns={0, 1, 2},
    )
    lines: list = [table]
    failed = [c for c in report.checks() if not c.passed]
    if report.checks():
        lines.append(
            f"Cross-checks: {len(report.checks()) - len(failed)} of {len(report.checks())} passed."
        )
    lines.extend(f"Not analysed: {note}" for note in report.notes)
    lines.append(f"Report: {out / 'index.html'}")
    Output("table").write(blocks=lines, warnings=report.warnings())
    return 0


_OUTPUT_HELP = "Report folder (default: <engine name>-report); built aside and moved into place."


@click.command("analyze")
@click.argument("engine", metavar="ENGINE")
@click.option("-o", "--output", "output_dir", default=None, metavar="DIR", help=_OUTPUT_HELP)
@deprecated_alias("--out", "--output", "out", "DIR")
@speed_option("Operating speed (rpm for a bare number, or with a unit); default: the engine's own.")
@speeds_option(
    "Speed range of the sweeps (rpm for bare numbers), e.g. 1000:2500 or 1000:2500:25; default "
    "the torsional model's operating range every 10 rpm."
)
@click.option(
    "--measurement",
    default=None,
    metavar="SIGNAL",
    help="A torsiograph signal (file or built-in name, as `crankdyn measure`) to hold against "
    "the engine's torsional model: adds the measurement section; needs --at (and --teeth for "
    "pulse times).",
)
@teeth_option()
@at_option()
@click.option("--force", is_flag=True, help="Replace an existing report folder.")
def analyze_command(
    engine: str,
    output_dir: str | None,
    out: str | None,
    speed: str | None,
    speeds: str | None,
    measurement: str | None,
    teeth: int | None,
    mass: str | None,
    force: bool,
) -> int:
    """Run every analysis that applies to ENGINE and write an HTML report with its data."""
    output_dir = merge_alias(output_dir, out, "--output", "--out")
    eng = resolve_engine(engine)
    signal = _measurement(eng, measurement, teeth, mass)
    w = parse_speed(speed)
    sweep = speed_sweep(speeds)
    stem = Path(engine).stem if engine.endswith(".toml") else engine
    target = Path(output_dir) if output_dir else Path(f"{stem}-report")
    return run_report(eng, target, speed=w, speeds=sweep, force=force, measurement=signal)


def _measurement(
    engine: Engine, signal: str | None, teeth: int | None, mass: str | None
) -> MeasurementInput | None:
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
    "-o",
    "--output",
    "output_dir",
    default="crankdyn-demo",
    show_default=True,
    metavar="DIR",
    help="Report folder.",
)
@deprecated_alias("--out", "--output", "out", "DIR")
@click.option("--force", is_flag=True, help="Replace an existing report folder.")
def demo_command(output_dir: str, out: str | None, force: bool) -> int:
    """The full report on the built-in inline-6 diesel (crankdyn analyze inline6-diesel)."""
    target = out if out is not None else output_dir
    engine = load_example(DEMO_ENGINE, "engine")
    speed = engine.speed if engine.speed else 2000 / RPM
    return run_report(engine, Path(target), speed=speed, speeds=None, force=force)


def register(group: click.Group) -> None:
    """Add ``analyze`` and ``demo`` to the command ``group``."""
    group.add_command(analyze_command)
    group.add_command(demo_command)
