"""``crankdyn forces``, ``crankdyn bearings``, ``crankdyn torque`` and ``crankdyn pressure``."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import click

from crankdyn.cli.common import (
    check_plot_path,
    display_step,
    engine_argument,
    parse_speed,
    plot_option,
    save_figure,
    speed_option,
    step_option,
)
from crankdyn.cli.writer import Output, output_options, result_table, summary_table
from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.io.catalogue import resolve_engine
from crankdyn.session import Analysis

FORCE_TABLE = (  # the columns `crankdyn forces` shows
    "crank_angle_deg",
    "gas_force_N",
    "inertia_force_N",
    "piston_force_N",
    "side_force_N",
    "rod_force_N",
    "tangential_force_N",
    "radial_force_N",
    "crank_pin_load_N",
    "torque_Nm",
)


def _session(engine: str, speed: str | None) -> tuple[Engine, Analysis]:
    """The ENGINE argument's engine and its analysis session at --speed."""
    eng = resolve_engine(engine)
    return eng, Analysis(eng, speed=parse_speed(speed))


def _write(
    out: Output,
    result: Any,
    keys: Sequence[str],
    title: str,
    plot_path: str | None,
    force: bool,
    full: Any,
) -> None:
    """The rows (at the display step) as table, CSV or JSON; the figure from ``full``, the
    session's full-resolution analysis, whatever --step the rows use.

    Parameters
    ----------
    out
        The command's output.
    result
        The result at the display step (a :class:`crankdyn.results.Result`).
    keys
        The columns the table shows (CSV and JSON hold them all).
    title
        The table's title.
    plot_path
        The --plot file, or None.
    force
        Whether an existing figure file may be replaced.
    full
        The full-resolution result, whose ``plot()`` is the figure.
    """
    out.write(
        blocks=[result_table(result, keys, title=title), summary_table(result)],
        json_data=result,
        csv_text=result.to_csv(),
    )
    if plot_path:
        save_figure(full.plot(), plot_path, force)


@click.command("forces")
@engine_argument
@speed_option()
@step_option()
@click.option(
    "--cylinder",
    type=int,
    default=1,
    show_default=True,
    metavar="N",
    help="Cylinder number (from the free end).",
)
@plot_option("Also write the forces figure (.png, .svg or .pdf).")
@output_options
def forces_command(
    engine: str,
    speed: str | None,
    step: str | None,
    cylinder: int,
    plot_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Gas, inertia, rod, side, tangential and radial forces and the crank-pin load of one
    cylinder of ENGINE over the working cycle."""
    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    eng, session = _session(engine, speed)
    if not 1 <= cylinder <= eng.cylinders.count:
        raise InputError(
            f"the engine has cylinders 1 to {eng.cylinders.count}", key="--cylinder", value=cylinder
        )
    h = display_step(step, fmt, eng.cycle_angle)
    result = session.forces(cylinder, step=h)
    _write(
        out,
        result,
        FORCE_TABLE,
        f"Cylinder {cylinder} forces",
        plot_path,
        force,
        session.forces(cylinder),
    )
    return 0


@click.command("bearings")
@engine_argument
@speed_option()
@step_option()
@plot_option("Also write the polar diagrams of the bearing loads (.png, .svg or .pdf).")
@output_options
def bearings_command(
    engine: str,
    speed: str | None,
    step: str | None,
    plot_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Crank-pin loads (crank frame) of every throw and main-bearing loads (engine frame) of
    ENGINE over the working cycle."""
    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    eng, session = _session(engine, speed)
    result = session.bearings(step=display_step(step, fmt, eng.cycle_angle))
    keys = (
        "crank_angle_deg",
        *(k for k in result.columns() if k.startswith(("crank_pin_load_N", "main_bearing_load_N"))),
    )
    _write(
        out, result, keys, "Crank-pin and main-bearing loads", plot_path, force, session.bearings()
    )
    return 0


@click.command("torque")
@engine_argument
@speed_option()
@step_option()
@click.option(
    "--mechanical-efficiency",
    type=float,
    default=None,
    metavar="ETA",
    help="Mechanical efficiency (0 < ETA <= 1) for the effective torque and power; default the "
    "engine file's.",
)
@plot_option("Also write the torque figure (.png, .svg or .pdf).")
@output_options
def torque_command(
    engine: str,
    speed: str | None,
    step: str | None,
    mechanical_efficiency: float | None,
    plot_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Cylinder, total, main-journal and crank-pin torques of ENGINE over the working cycle,
    with mean torque, power, IMEP and peak pressure."""
    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    eta = mechanical_efficiency
    if eta is not None and not (math.isfinite(eta) and 0.0 < eta <= 1.0):
        raise InputError(
            "the mechanical efficiency must lie in 0 < ETA <= 1",
            key="--mechanical-efficiency",
            value=eta,
        )
    eng, session = _session(engine, speed)
    result = session.torque_rows(
        display_step(step, fmt, eng.cycle_angle), mechanical_efficiency=eta
    )
    n = result.journal_torque.shape[0]
    keys = (
        "crank_angle_deg",
        "total_torque_Nm",
        "total_gas_torque_Nm",
        "total_inertia_torque_Nm",
        "cylinder_torque_Nm" if eng.cylinders.count == 1 else "cylinder_torque_Nm_1",
        "journal_torque_Nm" if n == 1 else f"journal_torque_Nm_{n}",
    )
    full = session.torque_rows(mechanical_efficiency=eta)
    _write(out, result, keys, "Engine torque", plot_path, force, full)
    return 0


@click.command("pressure")
@engine_argument
@step_option()
@plot_option("Also write the p-φ and p-V diagrams (.png, .svg or .pdf).")
@output_options
def pressure_command(
    engine: str,
    step: str | None,
    plot_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Cylinder pressure of ENGINE over the cycle (its trace, or the synthetic Wiebe model) with
    the indicated work, IMEP and peak pressure."""
    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    eng = resolve_engine(engine)
    session = Analysis(eng)
    result = session.pressure_rows(display_step(step, fmt, eng.cycle_angle))
    _write(
        out,
        result,
        ("crank_angle_deg", "pressure_Pa", "volume_m3"),
        "Cylinder pressure",
        plot_path,
        force,
        session.pressure,
    )
    return 0


def register(group: click.Group) -> None:
    """Add ``forces``, ``bearings``, ``torque`` and ``pressure`` to the command ``group``."""
    group.add_command(forces_command)
    group.add_command(bearings_command)
    group.add_command(torque_command)
    group.add_command(pressure_command)
