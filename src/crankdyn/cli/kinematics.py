"""``crankdyn kinematics`` and ``crankdyn coefficients``."""

from __future__ import annotations

import math

import click

from crankdyn.cli.common import (
    angle_grid,
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
from crankdyn.crank.kinematics import METHODS, coefficient_table
from crankdyn.errors import InputError
from crankdyn.io.catalogue import resolve_engine
from crankdyn.session import SERIES_ORDER, Analysis


def check_order(method: str, order: int) -> None:
    """Refuse a --order of the λ-series that is not even, from 2 to 64 (``--method series``).

    Parameters
    ----------
    method
        The --method (``exact``, ``approx`` or ``series``); only ``series`` reads the order.
    order
        The --order, the highest harmonic of the series.

    Raises
    ------
    InputError
        On a bad order with ``--method series``, naming ``--order`` and the value.
    """
    if method == "series" and (order < 2 or order % 2 or order > 64):
        raise InputError(
            "the series order must be an even number from 2 to 64", key="--order", value=order
        )


_METHOD = click.option(
    "--method",
    type=click.Choice(METHODS),
    default="exact",
    show_default=True,
    help="Exact formulas, the seeds' second-order approximation, or the λ-series.",
)
_ORDER = click.option(
    "--order",
    type=int,
    default=SERIES_ORDER,
    show_default=True,
    metavar="N",
    help="Highest harmonic of the λ-series (--method series); the library's default too.",
)

KINEMATICS_TABLE = (
    "crank_angle_deg",
    "displacement_m",
    "velocity_m_s",
    "acceleration_m_s2",
    "rod_angle_deg",
    "rod_angular_velocity_rad_s",
    "rod_angular_acceleration_rad_s2",
)


@click.command("kinematics")
@engine_argument
@speed_option()
@step_option()
@_METHOD
@_ORDER
@plot_option("Also write the kinematics figure (.png, .svg or .pdf).")
@output_options
def kinematics_command(
    engine: str,
    speed: str | None,
    step: str | None,
    method: str,
    order: int,
    plot_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Piston and connecting-rod kinematics of ENGINE over one revolution."""
    out = Output(fmt, output_path, force)
    check_plot_path(plot_path, force)
    check_order(method, order)
    h = display_step(step, fmt, 2.0 * math.pi)
    session = Analysis(resolve_engine(engine), speed=parse_speed(speed))
    result = session.kinematics(method=method, order=order, step=h)
    out.write(
        blocks=[
            result_table(result, KINEMATICS_TABLE, title="Piston and rod kinematics"),
            summary_table(result.extrema, "Summary (exact extrema)"),
        ],
        json_data=result,
        csv_text=result.to_csv(),
    )
    if plot_path:  # from the full-resolution analysis, whatever --step the rows use
        save_figure(session.kinematics(method=method, order=order).plot(), plot_path, force)
    return 0


def _parse_lambda(text: str) -> float:
    """One --lambda value, a number or a fraction such as 1/3.8, between 0 and 1."""
    try:
        parts = [float(p) for p in text.split("/")]
        if len(parts) > 2:
            raise ValueError
        value = parts[0] / parts[1] if len(parts) == 2 else parts[0]
    except (ValueError, ZeroDivisionError):
        raise InputError(
            "expected a number or a fraction such as 1/3.8", key="--lambda", value=text
        ) from None
    if not 0.0 < value < 1.0:
        raise InputError("λ = R/L must lie between 0 and 1", key="--lambda", value=text)
    return value


@click.command("coefficients")
@click.option(
    "--lambda",
    "lambdas",
    default="1/4,0.26,1/3.8,0.28,0.3,1/3.2",
    show_default=True,
    metavar="LIST",
    help="Comma-separated λ = R/L values (fractions allowed).",
)
@click.option(
    "--offset-ratio",
    default=0.0,
    type=float,
    show_default=True,
    metavar="K",
    help="k = e/R, the same for every λ.",
)
@step_option("Crank-angle step (deg for a bare number); default 10 for tables, 1 otherwise.")
@_METHOD
@_ORDER
@output_options
def coefficients_command(
    lambdas: str,
    offset_ratio: float,
    step: str | None,
    method: str,
    order: int,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """The seeds' dimensionless tables: A = x/R, B = v/(Rω), C = a/(Rω²) vs crank angle."""
    out = Output(fmt, output_path, force)
    values = [_parse_lambda(t) for t in lambdas.split(",") if t.strip()]
    if not values:
        raise InputError("give at least one λ value", key="--lambda", value=lambdas)
    if not math.isfinite(offset_ratio):
        raise InputError(
            "the offset ratio must be finite", key="--offset-ratio", value=offset_ratio
        )
    for lam in values:
        if abs(offset_ratio) >= 1.0 / lam - 1.0:
            raise InputError(
                f"with λ = {lam:.4g} the offset ratio must satisfy |k| < 1/λ - 1 = "
                f"{1 / lam - 1:.4g} for the crank to turn",
                key="--offset-ratio",
                value=offset_ratio,
            )
    check_order(method, order)
    phi = angle_grid(step, fmt, span=math.pi if offset_ratio == 0.0 else 2 * math.pi)
    table = coefficient_table(values, phi, offset_ratio=offset_ratio, method=method, order=order)
    out.write(blocks=[result_table(table)], json_data=table, csv_text=table.to_csv())
    return 0


def register(group: click.Group) -> None:
    """Add ``kinematics`` and ``coefficients`` to the command ``group``."""
    group.add_command(kinematics_command)
    group.add_command(coefficients_command)
