"""``crankdyn kinematics`` and ``crankdyn coefficients``."""

from __future__ import annotations

import math

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
from crankdyn.crank.kinematics import METHODS, coefficient_table, piston_kinematics
from crankdyn.errors import InputError


def check_order(method: str, order: int) -> None:
    if method == "series" and (order < 2 or order % 2 or order > 64):
        raise InputError(
            "the series order must be an even number from 2 to 64", key="--order", value=order
        )


@click.command("kinematics")
@engine_argument
@speed_option()
@step_option()
@click.option(
    "--method",
    type=click.Choice(METHODS),
    default="exact",
    show_default=True,
    help="Exact formulas, the seeds' second-order approximation, or the λ-series.",
)
@click.option(
    "--order",
    type=int,
    default=4,
    show_default=True,
    help="Highest harmonic of the λ-series (--method series).",
)
@format_option()
@output_options
def kinematics_command(engine, speed, step, method, order, fmt, output, force) -> int:
    """Piston and connecting-rod kinematics of ENGINE over one revolution."""
    eng = load_engine_arg(engine)
    w = speed_of(eng, speed)
    check_order(method, order)
    phi = angle_grid(step, fmt)
    result = piston_kinematics(eng.geometry, w, phi, method=method, order=order, fuel=eng.fuel)
    emit(result, fmt, output, force, summary=result.summary)
    return 0


def _parse_lambda(text: str) -> float:
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
    help="k = e/R, the same for every λ.",
)
@click.option(
    "--step",
    metavar="DEG",
    default=None,
    help="Crank-angle step (deg); default 10 for tables, 1 otherwise.",
)
@click.option("--method", type=click.Choice(METHODS), default="exact", show_default=True)
@click.option("--order", type=int, default=4, show_default=True)
@format_option()
@output_options
def coefficients_command(lambdas, offset_ratio, step, method, order, fmt, output, force) -> int:
    """The seeds' dimensionless tables: A = x/R, B = v/(Rω), C = a/(Rω²) vs crank angle."""
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
    emit(table, fmt, output, force)
    return 0


def register(group: click.Group) -> None:
    group.add_command(kinematics_command)
    group.add_command(coefficients_command)
