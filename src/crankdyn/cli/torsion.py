"""``crankdyn torsion``: lumped torsional models and their free vibration."""

from __future__ import annotations

import math

import click
from rich.table import Table as RichTable

from crankdyn.cli.common import (
    check_plot_path,
    console,
    emit,
    format_option,
    option_quantity,
    output_options,
    plot_option,
    save_figure,
)
from crankdyn.errors import InputError
from crankdyn.io.output import write_text
from crankdyn.io.torsion_file import load_torsion_example, resolve_torsion, torsion_example_names
from crankdyn.torsion.holzer import holzer_table, residual_curve
from crankdyn.torsion.modal import SOLVERS, natural_modes

_MODEL_HELP = (
    "MODEL_OR_ENGINE is a torsional model file, an engine file with a [torsion] section, the "
    "name of a built-in model (`crankdyn torsion examples`) or of a built-in engine."
)


@click.group("torsion")
def torsion_group() -> None:
    """Crankshaft torsional vibration: lumped models and free vibration.

    Models are TOML files of masses, shafts and gears (docs/torsion-file.md).
    """


def _print_tables(tables: list[RichTable], output: str | None, force: bool) -> None:
    if not output or output == "-":
        con = console()
        for table in tables:
            con.print(table)
        return
    con = console(record=True)
    for table in tables:
        con.print(table)
    path = write_text(output, con.export_text(), force=force)
    click.echo(f"wrote {path}", err=True)


def _g(value: float) -> str:
    return f"{value:.6g}" if math.isfinite(value) else "-"


def _modes_tables(result) -> list[RichTable]:
    summary = RichTable(title=result.model_name, header_style="bold")
    summary.add_column("Mode", justify="right")
    summary.add_column("Frequency\n(Hz)", justify="right")
    summary.add_column("ω\n(rad/s)", justify="right")
    summary.add_column("Modal inertia\n(kg·m²)", justify="right")
    summary.add_column("Modal stiffness\n(N·m/rad)", justify="right")
    summary.add_column("Nodes", justify="left")
    for r in range(result.mode.size):
        nodes = result.nodes[r]
        where = (
            "rigid-body mode" if result.free and r == 0 else "; ".join(n.describe() for n in nodes)
        )
        summary.add_row(
            str(int(result.mode[r])),
            _g(result.frequencies_hz[r]),
            _g(result.natural_frequency[r]),
            _g(result.modal_inertia[r]),
            _g(result.modal_stiffness[r]),
            where,
        )
    summary.caption = (
        f"{result.structure}, {'free' if result.free else 'grounded'}; solver: {result.solver}"
    )
    shapes = RichTable(title="Mode shapes", header_style="bold")
    shapes.caption = "largest amplitude 1"
    shapes.add_column("Mass", justify="left")
    for r in range(result.mode.size):
        shapes.add_column(
            f"{int(result.mode[r])}\n{result.frequencies_hz[r]:.4g} Hz", justify="right"
        )
    for i, name in enumerate(result.masses):
        shapes.add_row(name, *(f"{v:.4f}" for v in result.mode_shapes[:, i]))
    return [summary, shapes]


@torsion_group.command("modes")
@click.argument("model", metavar="MODEL_OR_ENGINE")
@click.option(
    "--solver",
    type=click.Choice(SOLVERS),
    default="eigen",
    show_default=True,
    help="Structured eigen solver (any model); Holzer or transfer matrices (chains); the closed "
    "forms (one grounded mass, two or three free masses).",
)
@plot_option("Also write the mode-shape figure (.png, .svg or .pdf).")
@click.option(
    "--plot-modes",
    default=None,
    metavar="LIST",
    help="Mode numbers to plot, e.g. 2,3,4 (default: the first six elastic modes).",
)
@format_option()
@output_options
def modes_command(model, solver, plot_path, plot_modes, fmt, output, force) -> int:
    """Natural frequencies, mode shapes, nodes and modal inertias of MODEL_OR_ENGINE.

    Every mode is listed, ascending; a free model's rigid-body mode is 0.0 Hz. Mode shapes are
    normalised to a largest absolute amplitude of 1.
    """
    chosen = _mode_list(plot_modes)
    check_plot_path(plot_path, force)
    torsion = resolve_torsion(model)
    result = natural_modes(torsion, solver)
    if chosen is not None:
        bad = [m for m in chosen if not 1 <= m <= result.mode.size]
        if bad:
            raise InputError(
                f"the model has modes 1..{result.mode.size}", key="--plot-modes", value=plot_modes
            )
    if plot_path:
        save_figure(result.plot(modes=chosen), plot_path, force)
    if fmt == "table":
        _print_tables(_modes_tables(result), output, force)
    else:
        emit(result, fmt, output, force)
    return 0


def _mode_list(text: str | None) -> list[int] | None:
    if text is None:
        return None
    try:
        values = [int(t) for t in text.split(",") if t.strip()]
    except ValueError:
        raise InputError(
            "expected mode numbers separated by commas, e.g. 2,3,4",
            key="--plot-modes",
            value=text,
        ) from None
    if not values:
        raise InputError("expected at least one mode number", key="--plot-modes", value=text)
    return values


@torsion_group.command("holzer")
@click.argument("model", metavar="MODEL_OR_ENGINE")
@click.option(
    "--frequency",
    required=True,
    metavar="HZ",
    help="Trial frequency (Hz, or with a unit: '120 Hz', '7200 rpm').",
)
@plot_option("Also write the residual-torque curve with its zeros (.png, .svg or .pdf).")
@click.option(
    "--max-frequency",
    default=None,
    metavar="HZ",
    help="Upper end of the plotted curve (default: 1.15 x the highest natural frequency).",
)
@format_option()
@output_options
def holzer_command(model, frequency, plot_path, max_frequency, fmt, output, force) -> int:
    """Holzer's table of MODEL_OR_ENGINE (a chain) at a trial frequency.

    Per mass: the angle (the first mass's is 1), the inertia torque J ω² θ, the accumulated
    torque and the twist of the shaft to the next mass. The residual torque after the last mass
    vanishes at a natural frequency.
    """
    f = option_quantity(frequency, "frequency", "--frequency", "Hz")
    if f < 0.0:
        raise InputError("the frequency must not be negative", key="--frequency", value=frequency)
    f_max = option_quantity(max_frequency, "frequency", "--max-frequency", "Hz")
    if f_max is not None and not f_max > 0.0:
        raise InputError(
            "the frequency must be positive", key="--max-frequency", value=max_frequency
        )
    check_plot_path(plot_path, force)
    torsion = resolve_torsion(model)
    try:
        table = holzer_table(torsion, 2.0 * math.pi * f)
    except InputError as exc:
        if exc.key != "frequency":
            raise
        raise InputError(exc.message, key="--frequency", value=frequency) from None
    if plot_path:
        curve = residual_curve(torsion, None if f_max is None else 2.0 * math.pi * f_max)
        save_figure(curve.plot(), plot_path, force)
    emit(table, fmt, output, force, summary=table)
    return 0


@torsion_group.command("examples")
def examples_command() -> int:
    """List the built-in torsional models (engines with a [torsion] section work too)."""
    table = RichTable(title="Built-in torsional models", header_style="bold")
    for col in ("Name", "Model", "Masses", "Structure", "Ends"):
        table.add_column(col)
    for name in torsion_example_names():
        m = load_torsion_example(name)
        table.add_row(
            name,
            m.name,
            str(m.mass_count),
            "chain" if m.is_chain else "branched",
            "free" if m.is_free else "grounded",
        )
    console().print(table)
    return 0


torsion_group.help = (torsion_group.help or "") + "\n\n" + _MODEL_HELP


def register(group: click.Group) -> None:
    group.add_command(torsion_group)
