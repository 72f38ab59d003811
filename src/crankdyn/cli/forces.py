"""``crankdyn forces``, ``crankdyn bearings``, ``crankdyn torque`` and ``crankdyn pressure``."""

from __future__ import annotations

import math
from dataclasses import dataclass

import click

from crankdyn.cli.common import (
    angle_grid,
    emit,
    engine_argument,
    format_option,
    load_engine_arg,
    output_options,
    speed_of,
    speed_option,
    step_option,
)
from crankdyn.crank.indicated import pressure_analysis
from crankdyn.crank.pressure_model import default_pressure
from crankdyn.engine.bearings import bearing_loads
from crankdyn.engine.forces import cylinder_forces
from crankdyn.engine.torque import engine_torque
from crankdyn.errors import InputError
from crankdyn.results import Result


@dataclass(frozen=True)
class ColumnView(Result):
    """A few columns of a result, for the terminal table (CSV and JSON keep every field)."""

    base: Result
    keys: tuple[str, ...]
    title: str = ""

    def columns(self):
        cols = self.base.columns()
        return {k: cols[k] for k in self.keys if k in cols}

    def column_labels(self):
        labels = self.base.column_labels()
        return {k: labels[k] for k in self.keys if k in labels}


def _emit(result: Result, fmt: str, output, force, table_keys: tuple[str, ...]) -> None:
    if fmt == "table":
        view = ColumnView(result, table_keys, getattr(result, "title", ""))
        emit(view, fmt, output, force, summary=result)
    else:
        emit(result, fmt, output, force)


def _step(engine, step, fmt) -> float:
    grid = angle_grid(step, fmt, span=engine.cycle_angle)
    return float(grid[1] - grid[0])


_SPEED = speed_option()
_STEP = step_option(
    "Crank-angle step (deg, or with a unit); must divide the cycle; "
    "default 10 for tables, 1 otherwise."
)

FORCE_TABLE = (
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


@click.command("forces")
@engine_argument
@_SPEED
@_STEP
@click.option(
    "--cylinder",
    type=int,
    default=1,
    show_default=True,
    metavar="N",
    help="Cylinder number (from the free end).",
)
@format_option()
@output_options
def forces_command(engine, speed, step, cylinder, fmt, output, force) -> int:
    """Gas, inertia, rod, side, tangential and radial forces and the crank-pin load of one
    cylinder of ENGINE over the working cycle."""
    eng = load_engine_arg(engine)
    w = speed_of(eng, speed)
    if not 1 <= cylinder <= eng.cylinders.count:
        raise InputError(
            f"the engine has cylinders 1 to {eng.cylinders.count}", key="--cylinder", value=cylinder
        )
    result = cylinder_forces(eng, w, cylinder=cylinder, step=_step(eng, step, fmt))
    _emit(result, fmt, output, force, FORCE_TABLE)
    return 0


@click.command("bearings")
@engine_argument
@_SPEED
@_STEP
@format_option()
@output_options
def bearings_command(engine, speed, step, fmt, output, force) -> int:
    """Crank-pin loads (crank frame) of every throw and main-bearing loads (engine frame) of
    ENGINE over the working cycle."""
    eng = load_engine_arg(engine)
    w = speed_of(eng, speed)
    result = bearing_loads(eng, w, step=_step(eng, step, fmt))
    keys = (
        "crank_angle_deg",
        *(k for k in result.columns() if k.startswith(("crank_pin_load_N", "main_bearing_load_N"))),
    )
    _emit(result, fmt, output, force, keys)
    return 0


@click.command("torque")
@engine_argument
@_SPEED
@_STEP
@click.option(
    "--mechanical-efficiency",
    type=float,
    default=None,
    metavar="ETA",
    help="Mechanical efficiency (0 < ETA <= 1) for the effective torque and power.",
)
@format_option()
@output_options
def torque_command(engine, speed, step, mechanical_efficiency, fmt, output, force) -> int:
    """Cylinder, total, main-journal and crank-pin torques of ENGINE over the working cycle,
    with mean torque, power, IMEP and peak pressure."""
    eng = load_engine_arg(engine)
    w = speed_of(eng, speed)
    eta = mechanical_efficiency
    if eta is not None and not (math.isfinite(eta) and 0.0 < eta <= 1.0):
        raise InputError(
            "the mechanical efficiency must lie in 0 < ETA <= 1",
            key="--mechanical-efficiency",
            value=eta,
        )
    result = engine_torque(eng, w, step=_step(eng, step, fmt), mechanical_efficiency=eta)
    n = result.journal_torque.shape[0]
    keys = (
        "crank_angle_deg",
        "total_torque_Nm",
        "total_gas_torque_Nm",
        "total_inertia_torque_Nm",
        "cylinder_torque_Nm" if eng.cylinders.count == 1 else "cylinder_torque_Nm_1",
        "journal_torque_Nm" if n == 1 else f"journal_torque_Nm_{n}",
    )
    _emit(result, fmt, output, force, keys)
    return 0


@click.command("pressure")
@engine_argument
@_STEP
@format_option()
@output_options
def pressure_command(engine, step, fmt, output, force) -> int:
    """Cylinder pressure of ENGINE over the cycle (its trace, or the synthetic Wiebe model) with
    the indicated work, IMEP and peak pressure."""
    eng = load_engine_arg(engine)
    result = pressure_analysis(
        default_pressure(eng),
        eng.geometry,
        _step(eng, step, fmt),
        fuel=eng.fuel,
        aspiration=eng.aspiration,
    )
    _emit(result, fmt, output, force, ("crank_angle_deg", "pressure_Pa", "volume_m3"))
    return 0


def register(group: click.Group) -> None:
    group.add_command(forces_command)
    group.add_command(bearings_command)
    group.add_command(torque_command)
    group.add_command(pressure_command)
