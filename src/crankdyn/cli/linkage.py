"""``crankdyn linkage ...``: four-bar quick analysis and general planar mechanisms (files)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import click
import numpy as np
from rich.table import Table as RichTable

from crankdyn.cli.common import (
    angle_grid,
    console,
    emit,
    format_option,
    option_quantity,
    output_options,
    plot_option,
    save_figure,
)
from crankdyn.errors import InputError
from crankdyn.io.linkage_file import (
    linkage_example_names,
    linkage_example_path,
    load_linkage_example,
    resolve_linkage,
)
from crankdyn.io.output import check_writable, write_bytes, write_text
from crankdyn.linkage.fourbar import BRANCHES, FourBar, fourbar_analysis
from crankdyn.linkage.kinetostatics import kinetostatics
from crankdyn.linkage.planar import linkage_kinematics

TWO_PI = 2.0 * math.pi


def _angles(angle: str | None, step: str | None, fmt: str, start: float = 0.0) -> np.ndarray:
    """--angle (one position) or --step (a full turn from ``start``); deg for bare numbers."""
    if angle is not None and step is not None:
        raise InputError("give --angle or --step, not both", key="--angle", value=angle)
    if angle is not None:
        value = option_quantity(angle, "angle", "--angle", "deg")
        if abs(value) > MAX_TURNS * TWO_PI:  # the motion is followed from the drawn position
            raise InputError(
                f"the crank angle must lie within ±{MAX_TURNS * 360} deg ({MAX_TURNS} turns); "
                "positions repeat every turn",
                key="--angle",
                value=angle,
            )
        return np.array([value])
    return angle_grid(step, fmt, TWO_PI, start=start, max_points=100_000)


MAX_TURNS = 10


def _single(data: dict, keys) -> dict:
    """For one --angle: the per-angle lists of length one become plain numbers."""

    def squeeze(v):
        if isinstance(v, list) and len(v) == 1 and not isinstance(v[0], (list, dict)):
            return v[0]
        if isinstance(v, dict):
            return {k: squeeze(x) for k, x in v.items()}
        return v

    return {k: (squeeze(v) if k in keys else v) for k, v in data.items()}


def _emit(result, fmt, output, force, *, single: bool, summary=None, extra=None):
    """emit() with --angle squeezing and optional extra JSON members."""
    if fmt == "json" and (single or extra):
        data = result.to_dict()
        if single:
            data = _single(
                data, set(result.columns()) | {k.split(".")[0] for k in result.columns()}
            )
        if extra:
            data.update(extra)
        text = json.dumps(data, indent=2, allow_nan=False) + "\n"
        if output and output != "-":
            click.echo(f"wrote {write_text(output, text, force=force)}", err=True)
        else:
            click.echo(text, nl=False)
        return
    emit(result, fmt, output, force, summary=summary)


def _length(value: str, option: str) -> float:
    number = option_quantity(value, "length", option, "mm")
    if not number > 0.0:
        raise InputError("a link length must be positive", key=option, value=value)
    return number


@click.group("linkage")
def linkage_group() -> None:
    """Planar linkages: four-bar, slider-crank and general mechanisms (kinematics, forces).

    LINKAGE arguments take a linkage file (TOML, docs/linkage-file.md) or a built-in example
    (`crankdyn linkage examples`). Angles are counter-clockwise from the ground line, with the
    crank pivot at the origin (docs/theory-linkage.md).
    """


@linkage_group.command("fourbar")
@click.option("--crank", required=True, metavar="MM", help="Crank AB (input), e.g. 73.4mm.")
@click.option("--coupler", required=True, metavar="MM", help="Coupler BC.")
@click.option("--rocker", required=True, metavar="MM", help="Rocker DC (output).")
@click.option("--ground", required=True, metavar="MM", help="Ground AD (frame).")
@click.option(
    "--crank-speed",
    default="1rad/s",
    show_default=True,
    metavar="RAD/S",
    help="Crank angular velocity, counter-clockwise positive.",
)
@click.option(
    "--crank-acceleration",
    default="0rad/s^2",
    show_default=True,
    metavar="RAD/S2",
    help="Crank angular acceleration.",
)
@click.option("--angle", default=None, metavar="DEG", help="One crank angle (from A->D).")
@click.option(
    "--step",
    default=None,
    metavar="DEG",
    help="Crank-angle step over a full turn; default 10 for tables, 1 otherwise.",
)
@click.option(
    "--branch",
    type=click.Choice(BRANCHES),
    default="open",
    show_default=True,
    help="Assembly branch: open (C left of B->D) or crossed.",
)
@click.option(
    "--coupler-point",
    default=None,
    metavar="P,Q",
    help="Coupler point: P along B->C and Q to its left (mm), e.g. 60mm,40mm.",
)
@plot_option("Also write the four-bar plot (PNG, SVG or PDF).", "plot_file")
@format_option()
@output_options
def fourbar_command(
    crank,
    coupler,
    rocker,
    ground,
    crank_speed,
    crank_acceleration,
    angle,
    step,
    branch,
    coupler_point,
    plot_file,
    fmt,
    output,
    force,
) -> int:
    """Four-bar kinematics in closed form: Grashof type, limits, link angles and rates."""
    lengths = [
        _length(v, o)
        for v, o in (
            (crank, "--crank"),
            (coupler, "--coupler"),
            (rocker, "--rocker"),
            (ground, "--ground"),
        )
    ]
    point = None
    if coupler_point is not None:
        parts = coupler_point.split(",")
        if len(parts) != 2:
            raise InputError(
                "expected P,Q such as 60mm,40mm", key="--coupler-point", value=coupler_point
            )
        point = tuple(option_quantity(p.strip(), "length", "--coupler-point", "mm") for p in parts)
    w = option_quantity(crank_speed, "speed", "--crank-speed", "rad/s")
    e = option_quantity(
        crank_acceleration, "angular_acceleration", "--crank-acceleration", "rad/s^2"
    )
    try:
        fb = FourBar(*lengths, branch=branch, coupler_point=point)
    except InputError as exc:
        raise InputError(
            exc.message,
            key=f"--{exc.key}" if exc.key else None,
            value=exc.value if exc.has_value else None,
        ) from None
    theta = _angles(angle, step, fmt)
    if angle is None and not fb.crank_rotates:
        ranges = ", ".join(
            f"{math.degrees(a):.4g} to {math.degrees(b):.4g} deg" for a, b in fb.crank_ranges()
        )
        raise InputError(
            f"this {fb.grashof_type} linkage's crank cannot turn through a full revolution "
            f"(it assembles only for crank angles {ranges}); give --angle for one position",
            key="--step",
            value=step if step is not None else "full turn",
        )
    try:
        fb.check_assembly(theta)
    except InputError as exc:
        raise InputError(
            exc.message,
            key="--angle" if angle is not None else "--step",
            value=angle if angle is not None else step,
        ) from None
    result = fourbar_analysis(fb, theta, w, e)
    _emit(result, fmt, output, force, single=angle is not None, summary=result.limits)
    if plot_file:
        if angle is not None:
            full = (
                fourbar_analysis(fb, np.linspace(0, TWO_PI, 361) + theta[0], w, e)
                if fb.crank_rotates
                else result
            )
            save_figure(full.plot(), plot_file, force)
        else:
            save_figure(result.plot(), plot_file, force)
    return 0


def _speed(mech, speed):
    if speed is None:
        return mech.driver.speed
    return option_quantity(speed, "speed", "--speed", "rad/s")


_SPEED_HELP = "Crank speed (rad/s when bare; rpm with a unit); default: the file's [driver] speed."


@linkage_group.command("kinematics")
@click.argument("linkage", metavar="LINKAGE")
@click.option("--angle", default=None, metavar="DEG", help="One crank angle.")
@click.option("--step", default=None, metavar="DEG", help="Crank-angle step over a full turn.")
@click.option("--speed", default=None, metavar="RAD/S", help=_SPEED_HELP)
@format_option()
@output_options
def kinematics_command(linkage, angle, step, speed, fmt, output, force) -> int:
    """Positions, velocities and accelerations of every link and point of LINKAGE."""
    mech = resolve_linkage(linkage)
    theta = _angles(angle, step, fmt)
    motion = mech.motion(theta, _speed(mech, speed))
    result = linkage_kinematics(motion)
    _emit(result, fmt, output, force, single=angle is not None)
    return 0


@linkage_group.command("forces")
@click.argument("linkage", metavar="LINKAGE")
@click.option("--angle", default=None, metavar="DEG", help="One crank angle.")
@click.option("--step", default=None, metavar="DEG", help="Crank-angle step over a full turn.")
@click.option("--speed", default=None, metavar="RAD/S", help=_SPEED_HELP)
@click.option("--no-friction", is_flag=True, help="Ignore the joints' friction.")
@click.option(
    "--matrices",
    is_flag=True,
    help="Add the matrices C, D and P of [C]{R} = [D]{P} at every position (JSON).",
)
@plot_option("Also write the driving-torque and joint-force plot (PNG, SVG or PDF).", "plot_file")
@format_option()
@output_options
def forces_command(
    linkage, angle, step, speed, no_friction, matrices, plot_file, fmt, output, force
) -> int:
    """Joint reactions and driving torque of LINKAGE (matrix method and virtual work)."""
    mech = resolve_linkage(linkage)
    theta = _angles(angle, step, fmt)
    if matrices and fmt != "json":
        raise InputError("--matrices needs --format json", key="--matrices")
    motion = mech.motion(theta, _speed(mech, speed))
    result = kinetostatics(motion, friction=not no_friction)
    extra = None
    if matrices:
        extra = {"matrices": [result.system.matrices(i) for i in range(theta.size)]}
        if angle is not None:
            extra = {"matrices": extra["matrices"][0]}
    if fmt == "table":
        _forces_table(result, output, force)
    else:
        _emit(result, fmt, output, force, single=angle is not None, extra=extra)
    if plot_file:
        save_figure(result.plot(), plot_file, force)
    return 0


def _forces_table(result, output, force) -> None:
    """A readable table: driving torque by both methods and the joint force magnitudes."""
    from crankdyn.cli.common import summary_table

    table = RichTable(title=f"{result.mechanism_name}: kinetostatics", header_style="bold")
    cols = [("Crank angle\n(deg)", np.degrees(result.crank_angle))]
    cols.append(("Driving torque\n(N·m)", result.driving_torque))
    cols.append(("Virtual work,\nno friction (N·m)", result.driving_torque_virtual_work))
    if result.efficiency is not None:
        cols.append(("Efficiency", result.efficiency))
    for name, f in result.joint_forces.items():
        cols.append((f"|F| {name}\n(N)", np.hypot(f["x"], f["y"])))
    for label, _v in cols:
        table.add_column(label, justify="right")
    for row in zip(*(v for _l, v in cols), strict=True):
        table.add_row(*(f"{x:.6g}" if np.isfinite(x) else "-" for x in row))
    con = console(record=True) if output else console()
    con.print(table)
    con.print(summary_table(result))
    if output:
        click.echo(f"wrote {write_text(output, con.export_text(), force=force)}", err=True)


@linkage_group.command("check")
@click.argument("linkage", metavar="LINKAGE")
def check_command(linkage) -> int:
    """Structure of LINKAGE: mobility, link groups and their static determinacy (seed 004)."""
    mech = resolve_linkage(linkage)
    con = console()
    n, p = len(mech.links), len(mech.joints)
    con.print(
        f"{mech.name}: {n} moving links, {p} lower pairs, "
        f'F = 3n - 2p_l = {mech.degrees_of_freedom}; crank "{mech.crank}" driven at '
        f'joint "{mech.driver.joint}"; drawn at crank angle '
        f"{math.degrees(mech.crank_angle_drawn):.6g} deg"
    )
    table = RichTable(title="Link groups, in the order of the force analysis", header_style="bold")
    for col in ("Group", "Links", "Joints", "3n", "2p_l", "Determinate"):
        table.add_column(col)
    for g in mech.link_groups():
        pl = len(g.joints)
        extra = 1 if g.kind == "driver" else 0
        table.add_row(
            g.kind,
            ", ".join(g.links),
            ", ".join(g.joints),
            str(3 * len(g.links)),
            str(2 * pl) + (" + 1 (driving torque)" if extra else ""),
            "yes" if 3 * len(g.links) == 2 * pl + extra else "no",
        )
    con.print(table)
    return 0


def _one_angle(angle: str | None, mech) -> float:
    if angle is None:
        return mech.crank_angle_drawn
    return option_quantity(angle, "angle", "--angle", "deg")


@linkage_group.command("draw")
@click.argument("linkage", metavar="LINKAGE")
@click.option(
    "--angle", default=None, metavar="DEG", help="Crank angle; default: the drawn position."
)
@click.option("--speed", default=None, metavar="RAD/S", help=_SPEED_HELP)
@click.option(
    "--forces/--no-forces",
    "show_forces",
    default=True,
    show_default=True,
    help="Draw the joint forces.",
)
@click.option("--paths", is_flag=True, help="Draw the point paths (coupler curves) instead.")
@click.option("-o", "--output", required=True, metavar="FILE", help="PNG, SVG or PDF to write.")
@click.option("--force", is_flag=True, help="Overwrite an existing file.")
def draw_command(linkage, angle, speed, show_forces, paths, output, force) -> int:
    """Draw LINKAGE at one crank angle with its joint forces (or its point paths)."""
    from crankdyn.plots.linkage import plot_mechanism, plot_paths

    mech = resolve_linkage(linkage)
    check_writable(output, force=force)
    theta0 = _one_angle(angle, mech)
    theta = theta0 + np.linspace(0.0, TWO_PI, 181)
    motion = mech.motion(theta, _speed(mech, speed))
    if paths:
        fig = plot_paths(motion)
    else:
        result = kinetostatics(motion) if show_forces else None
        fig = plot_mechanism(motion, 0, forces=result)
    save_figure(fig, output, force)
    return 0


@linkage_group.command("animate")
@click.argument("linkage", metavar="LINKAGE")
@click.option(
    "--frames",
    default=72,
    show_default=True,
    type=click.IntRange(4, 720),
    help="Frames per crank revolution.",
)
@click.option(
    "--fps", default=20, show_default=True, type=click.IntRange(1, 50), help="Frames per second."
)
@click.option("--speed", default=None, metavar="RAD/S", help=_SPEED_HELP)
@click.option(
    "--forces/--no-forces",
    "show_forces",
    default=True,
    show_default=True,
    help="Draw the joint forces.",
)
@click.option("-o", "--output", required=True, metavar="FILE.gif", help="GIF to write.")
@click.option("--force", is_flag=True, help="Overwrite an existing file.")
def animate_command(linkage, frames, fps, speed, show_forces, output, force) -> int:
    """An animated GIF of LINKAGE through a full crank revolution."""
    from crankdyn.plots.linkage import animate_mechanism

    if not output.lower().endswith(".gif"):
        raise InputError("the animation file must end in .gif", key="--output", value=output)
    mech = resolve_linkage(linkage)
    check_writable(output, force=force)
    theta = mech.crank_angle_drawn + np.linspace(0.0, TWO_PI, frames, endpoint=False)
    motion = mech.motion(theta, _speed(mech, speed))
    result = kinetostatics(motion) if show_forces else None
    data = animate_mechanism(motion, result, fps=fps)
    click.echo(f"wrote {write_bytes(output, data, force=force)}", err=True)
    return 0


@linkage_group.command("examples")
def examples_command() -> int:
    """List the built-in example linkages."""
    table = RichTable(title="Built-in linkages", header_style="bold")
    for col in ("Name", "Mechanism", "Links", "Joints", "Groups"):
        table.add_column(col)
    for name in linkage_example_names():
        m = load_linkage_example(name)
        groups = "; ".join(f"{g.kind} {'-'.join(g.links)}" for g in m.link_groups())
        table.add_row(name, m.name, str(len(m.links)), str(len(m.joints)), groups)
    console().print(table)
    return 0


@linkage_group.command("example")
@click.argument("name")
@click.option(
    "-o",
    "--output",
    default=None,
    metavar="PATH",
    help="File (NAME.toml by default) or folder; '-' prints the file.",
)
@click.option("--force", is_flag=True, help="Overwrite an existing file.")
def example_command(name, output, force) -> int:
    """Write the built-in linkage NAME to a file, to edit."""
    src = linkage_example_path(name)
    if output == "-":
        click.echo(src.read_text(encoding="utf-8"), nl=False)
        return 0
    target = Path(output) if output else Path(f"{name}.toml")
    if target.is_dir():
        target = target / f"{name}.toml"
    click.echo(f"wrote {write_bytes(target, src.read_bytes(), force=force)}", err=True)
    return 0


def register(group: click.Group) -> None:
    group.add_command(linkage_group)
