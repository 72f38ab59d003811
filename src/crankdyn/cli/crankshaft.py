"""``crankdyn crankshaft``: the crankshaft's fatigue strength by IACS UR M53 (``crankdyn
crankshaft ENGINE``, the same as ``crankdyn crankshaft strength ENGINE``), the coupled modes of
its beam model (``crankshaft modes``) and its forced response (``crankshaft response``); the
numbers come from the analysis session (:meth:`crankdyn.Analysis.crankshaft`,
:meth:`~crankdyn.Analysis.crankshaft_modes`, :meth:`~crankdyn.Analysis.crankshaft_response`).

``crankshaft strength`` ends with exit status 1 when a verdict fails, 0 with ``--no-fail``
(:func:`crankdyn.cli.common.verdict_status`, the one place that says so)."""

from __future__ import annotations

from typing import Any

import click

from crankdyn.cli.common import (
    check_plot_path,
    engine_argument,
    no_fail_option,
    orders_option,
    parse_speed,
    plot_option,
    save_figure,
    speed_option,
    speed_sweep,
    speeds_option,
    verdict_status,
)
from crankdyn.cli.writer import Output, output_options, summary_blocks
from crankdyn.crankshaft.beam_inputs import ADDITIONAL_STRESS_SOURCES
from crankdyn.errors import InputError
from crankdyn.io.catalogue import resolve_engine
from crankdyn.session import Analysis

__all__ = ["crankshaft_group", "register"]

DEFAULT_COMMAND = "strength"
"""The command ``crankdyn crankshaft ENGINE`` runs."""

_ORDERS_HELP = (
    "Orders of the harmonic synthesis, e.g. 0.5:12 (default 0.5:12 four-stroke, 1:12 "
    "two-stroke; UR M53 asks for 0.5:12 and 1:15)."
)
_SPEEDS_HELP = (
    "The speed range of the forced responses (rpm for bare numbers); default the torsional "
    "model's operating range every 10 rpm."
)


class _DefaultGroup(click.Group):
    """A group whose first argument, when it names none of its commands, is the default
    command's (:data:`DEFAULT_COMMAND`): ``crankdyn crankshaft ENGINE``."""

    def parse_args(self, ctx: click.Context, args: list[str]) -> list[str]:
        """As :meth:`click.Group.parse_args`, the default command's name put first when the
        first argument names no command (and asks for no help).

        Parameters
        ----------
        ctx
            The group's context.
        args
            The arguments after the group's name.

        Returns
        -------
        list of str
            What is left for the command.
        """
        if args and args[0] not in self.commands and args[0] not in ctx.help_option_names:
            args = [DEFAULT_COMMAND, *args]
        return super().parse_args(ctx, args)


@click.group("crankshaft", cls=_DefaultGroup)
def crankshaft_group() -> None:
    """The crankshaft: its fatigue strength by IACS UR M53 and the coupled vibration of its
    beam model.

    ``crankdyn crankshaft ENGINE`` is ``crankdyn crankshaft strength ENGINE``. ENGINE needs a
    [crankshaft] section (crankdyn docs crankshaft).
    """


def _session(engine: str, speed: str | None, speeds: str | None, orders: str | None) -> Analysis:
    """The analysis session of ENGINE with the --speed, --speeds and --orders given."""
    from crankdyn.cli.common import parse_orders

    eng = resolve_engine(engine)
    options: dict[str, Any] = {"speed": parse_speed(speed), "speeds": speed_sweep(speeds)}
    if orders is not None:
        options["orders"] = parse_orders(orders, eng.cycle)
    return Analysis(eng, **options)


@crankshaft_group.command(DEFAULT_COMMAND)
@engine_argument
@speed_option("The speed of the maximum continuous rating (rpm for a bare number); default the "
              "engine's [operating] speed.")  # fmt: skip
@speeds_option(_SPEEDS_HELP)
@orders_option(_ORDERS_HELP)
@click.option(
    "--additional-stress",
    type=click.Choice(ADDITIONAL_STRESS_SOURCES),
    default=None,
    help="Where the additional bending stress of vibration comes from: the rule's values "
    "(M53.4) or the beam model's forced response (M53.4(3)); default the engine file's "
    "(beam when it has [crankshaft.beam]).",
)
@no_fail_option
@output_options
def strength_command(
    engine: str,
    speed: str | None,
    speeds: str | None,
    orders: str | None,
    additional_stress: str | None,
    no_fail: bool,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """The fatigue strength of ENGINE's crankshaft by IACS UR M53: Q of the crankpin fillet, the
    journal fillet and the oil bore of every throw with the nominal stresses, stress concentration
    factors, equivalent stresses and fatigue strengths, each with its clause; the nominal
    torsional stress from the forced torsional response over the speed range (the one the TVC
    judges, barred ranges left out). CSV: every quantity with its unit and clause. Exit status:
    0 when every verdict passed, 1 when one failed (the analysis ran and its output is written),
    2 on an error; --no-fail gives 0 whatever the verdict.
    """
    out = Output(fmt, output_path, force)
    out.check()
    session = _session(engine, speed, speeds, orders)
    try:
        result = session.crankshaft(additional_stress=additional_stress)
    except InputError as exc:
        if exc.key != "additional_stress":
            raise
        raise InputError(
            exc.message, file=exc.file, key="--additional-stress", value=additional_stress
        ) from None
    name = session.engine.name if session.engine is not None else engine
    out.write(
        blocks=summary_blocks(result, f"{name}: crankshaft strength (IACS UR M53)"),
        json_data=result,
        csv_text=result.quantities_table().csv_text(),
    )
    return verdict_status(result.summary().passed, no_fail)


@crankshaft_group.command("modes")
@engine_argument
@click.option(
    "--modes",
    "count",
    type=click.IntRange(min=1, max=500),
    default=None,
    metavar="N",
    help="The lowest N modes (default [crankshaft.beam] modes, 24).",
)
@plot_option("Also write the mode shapes in three projections (.png, .svg or .pdf).")
@click.option(
    "--plot-modes",
    default=None,
    metavar="LIST",
    help="Mode numbers to plot, e.g. 3,4,5 (from 1, as the table lists them; default: the first "
    "four elastic modes).",
)
@output_options
def modes_command(
    engine: str,
    count: int | None,
    plot_path: str | None,
    plot_modes: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """The coupled modes of ENGINE's crankshaft as a beam structure (journals, webs and pins as
    3-D beams, the rods' and pistons' masses, main bearings, the flywheel, damper and shaft
    line attached): natural frequencies classified as torsional, axial, bending or coupled by
    their kinetic energy, a throw's torsional and axial stiffness, and the torsional modes
    beside the lumped model's.
    """
    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    chosen = _mode_list(plot_modes)
    session = _session(engine, None, None, None)
    result = session.crankshaft_modes(count)
    if chosen is not None:
        bad = [m for m in chosen if not 1 <= m <= result.mode.size]
        if bad:
            raise InputError(
                f"expected modes from 1 to {result.mode.size}", key="--plot-modes", value=plot_modes
            )
    name = session.engine.name if session.engine is not None else engine
    out.write(
        blocks=summary_blocks(result, f"{name}: crankshaft beam model, modes"),
        json_data=result,
        csv_text=result.to_csv(),
    )
    if plot_path:
        save_figure(result.plot(chosen), plot_path, force)
    return 0


@crankshaft_group.command("response")
@engine_argument
@speeds_option(_SPEEDS_HELP)
@plot_option("Also write the axial vibration and the webs' bending stress against speed.")
@output_options
def response_command(
    engine: str,
    speeds: str | None,
    plot_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """The forced response of ENGINE's crankshaft beam model to the gas and inertia forces on
    its pins over the speed range: axial vibration at the free end, torsional vibration,
    bending moments at the main bearings, the webs' bending stress and the part of it that
    vibration adds (UR M53's additional stress). The critical speeds of the beam's modes are
    added to the speed grid.
    """
    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    session = _session(engine, None, speeds, None)
    result = session.crankshaft_response()
    name = session.engine.name if session.engine is not None else engine
    out.write(
        blocks=summary_blocks(result, f"{name}: crankshaft beam model, forced response"),
        json_data=result,
        csv_text=result.to_csv(),
    )
    if plot_path:
        save_figure(result.plot(), plot_path, force)
    return 0


def _mode_list(text: str | None) -> list[int] | None:
    """--plot-modes as mode numbers, or None."""
    if text is None:
        return None
    try:
        values = [int(t) for t in text.split(",") if t.strip()]
    except ValueError:
        values = []
    if not values:
        raise InputError(
            "expected mode numbers separated by commas, e.g. 3,4,5", key="--plot-modes", value=text
        )
    return values


def register(group: click.Group) -> None:
    """Add ``crankshaft`` to the command ``group``."""
    group.add_command(crankshaft_group)
