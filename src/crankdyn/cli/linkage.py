"""``crankdyn linkage ...``: four-bar quick analysis and general planar mechanisms (files)."""

from __future__ import annotations

import math
from collections.abc import Callable, Collection
from typing import TYPE_CHECKING, Any, TypeVar

import click
import numpy as np
from numpy.typing import NDArray

from crankdyn.cli.common import (
    angle_grid,
    check_plot_path,
    deprecated_alias,
    merge_alias,
    option_quantity,
    parse_speed,
    plot_option,
    save_figure,
    speed_option,
    step_option,
)
from crankdyn.cli.examples import example_alias, examples_alias
from crankdyn.cli.writer import (
    Output,
    TextTable,
    output_options,
    result_table,
    summary_blocks,
)
from crankdyn.display import column_text
from crankdyn.errors import InputError
from crankdyn.io.catalogue import resolve_linkage
from crankdyn.io.output import check_writable, write_bytes
from crankdyn.linkage.fourbar import BRANCHES, FourBar, fourbar_analysis
from crankdyn.linkage.kinetostatics import kinetostatics
from crankdyn.linkage.motion import linkage_kinematics
from crankdyn.results import Result

if TYPE_CHECKING:
    from crankdyn.linkage.kinetostatics import KinetostaticsResult
    from crankdyn.linkage.planar import Mechanism, MechanismMotion

F = TypeVar("F", bound=Callable[..., Any])
R = TypeVar("R", bound=Result)

TWO_PI = 2.0 * math.pi
PLOT_POINTS = 1441
"""Crank positions of a plotted revolution (every 0.25 deg): plots are drawn from an analysis at
this resolution whatever --step the table uses, so a load step is drawn as a step."""


def _plot_angles(start: float) -> NDArray[np.float64]:
    """A full crank revolution from ``start`` (rad) at the plot resolution."""
    return start + np.linspace(0.0, TWO_PI, PLOT_POINTS)


def _angles(
    angle: str | None, step: str | None, fmt: str, start: float = 0.0
) -> NDArray[np.float64]:
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
    return angle_grid(step, fmt, TWO_PI, start=start)


MAX_TURNS = 10
"""The largest --angle, in turns (the motion is followed from the drawn position)."""


ANALYSIS_STEP = np.radians(1.0)
"""The analysis grid of a full turn: a table's coarser rows show its summary."""


def _full_turn(theta: NDArray[np.float64], start: float = 0.0) -> NDArray[np.float64] | None:
    """The 1 deg full turn the summary comes from, when ``theta`` is another full-turn grid."""
    if theta.size < 2:
        return None
    full = start + np.linspace(0.0, TWO_PI, 361)
    if theta.size == full.size and np.allclose(theta, full):
        return None
    return full


def _single(data: dict[str, Any], keys: Collection[str]) -> dict[str, Any]:
    """For one --angle: the per-angle lists of length one become plain numbers."""

    def squeeze(v: Any) -> Any:
        """A list of one number as the number, inside dicts too."""
        if isinstance(v, list) and len(v) == 1 and not isinstance(v[0], (list, dict)):
            return v[0]
        if isinstance(v, dict):
            return {k: squeeze(x) for k, x in v.items()}
        return v

    return {k: (squeeze(v) if k in keys else v) for k, v in data.items()}


def _json(result: Result, *, single: bool, extra: dict[str, Any] | None = None) -> dict[str, Any]:
    """A result's JSON data (one --angle: plain numbers, :func:`_single`), with ``extra``."""
    data = result.to_dict()
    if single:
        data = _single(data, set(result.columns()) | {k.split(".")[0] for k in result.columns()})
    if extra:
        data.update(extra)
    return data


def _length(value: str, option: str) -> float:
    """A link length option (mm for a bare number) in m; it must be positive."""
    number = option_quantity(value, "length", option, "mm")
    if not number > 0.0:
        raise InputError("a link length must be positive", key=option, value=value)
    return number


@click.group("linkage")
def linkage_group() -> None:
    """Planar linkages: four-bar, slider-crank and general mechanisms (kinematics, forces).

    LINKAGE arguments take a linkage file (TOML, `crankdyn docs linkage-file`) or a built-in example
    (`crankdyn examples`). Angles are counter-clockwise from the ground line, with the
    crank pivot at the origin (`crankdyn docs theory-linkage`).
    """


@linkage_group.command("fourbar")
@click.option(
    "--crank", required=True, metavar="MM", help="Crank AB, the input (mm, or with a unit)."
)
@click.option("--coupler", required=True, metavar="MM", help="Coupler BC (mm, or with a unit).")
@click.option(
    "--rocker", required=True, metavar="MM", help="Rocker DC, the output (mm, or with a unit)."
)
@click.option(
    "--ground", required=True, metavar="MM", help="Ground AD, the frame (mm, or with a unit)."
)
@speed_option(
    "Crank speed, counter-clockwise positive (rpm for a bare number, or with a unit); "
    "default 1 rad/s."
)
@deprecated_alias("--crank-speed", "--speed", "crank_speed", "RAD/S")
@click.option(
    "--crank-acceleration",
    default="0rad/s^2",
    show_default=True,
    metavar="RAD/S2",
    help="Crank angular acceleration (rad/s² for a bare number, or with a unit).",
)
@click.option(
    "--angle",
    default=None,
    metavar="DEG",
    help="One crank angle from A->D (deg for a bare number, or with a unit); default: a full "
    "turn every --step.",
)
@step_option(
    "Crank-angle step over a full turn (deg for a bare number); default 10 for tables, 1 "
    "otherwise. Summaries always come from the 1 deg analysis."
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
    help="Coupler point: P along B->C and Q to its left (mm for bare numbers), e.g. 60mm,40mm; "
    "default: none.",
)
@plot_option("Also write the four-bar figure (.png, .svg or .pdf).")
@output_options
def fourbar_command(
    crank: str,
    coupler: str,
    rocker: str,
    ground: str,
    speed: str | None,
    crank_speed: str | None,
    crank_acceleration: str,
    angle: str | None,
    step: str | None,
    branch: str,
    coupler_point: str | None,
    plot_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Four-bar kinematics in closed form: Grashof type, limits, link angles and rates."""
    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    a, b, c, d = (
        _length(v, o)
        for v, o in (
            (crank, "--crank"),
            (coupler, "--coupler"),
            (rocker, "--rocker"),
            (ground, "--ground"),
        )
    )
    point = None
    if coupler_point is not None:
        parts = coupler_point.split(",")
        if len(parts) != 2:
            raise InputError(
                "expected P,Q such as 60mm,40mm", key="--coupler-point", value=coupler_point
            )
        p, q = (option_quantity(part.strip(), "length", "--coupler-point", "mm") for part in parts)
        point = (p, q)
    merge_alias(speed, crank_speed, "--speed", "--crank-speed")
    if crank_speed is not None:  # the older option read rad/s for a bare number
        w = option_quantity(crank_speed, "speed", "--crank-speed", "rad/s")
    elif speed is not None:
        w = option_quantity(speed, "speed", "--speed", "rpm")
    else:
        w = 1.0
    e = option_quantity(
        crank_acceleration, "angular_acceleration", "--crank-acceleration", "rad/s^2"
    )
    try:
        fb = FourBar(a, b, c, d, branch=branch, coupler_point=point)
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
    full = None
    if angle is None and (grid := _full_turn(theta)) is not None:
        full = fourbar_analysis(fb, grid, w, e)
        result = result.with_summary_of(full)
    out.write(
        blocks=[result_table(result, title="Four-bar kinematics"), *summary_blocks(result.limits)],
        json_data=_json(result, single=angle is not None),
        csv_text=result.to_csv(),
        warnings=[result],
    )
    if plot_path:  # a full revolution at the plot resolution, whatever --step or --angle
        fine = fourbar_analysis(fb, _plot_angles(theta[0]), w, e) if fb.crank_rotates else result
        save_figure(fine.plot(), plot_path, force)
    return 0


def _speed(mech: Mechanism, speed: str | None) -> float | None:
    """--speed (rpm for a bare number), else the linkage file's [driver] speed (rad/s)."""
    if speed is None:
        return mech.driver.speed
    return parse_speed(speed)


_SPEED_HELP = (
    "Crank speed (rpm for a bare number, or with a unit); default: the file's [driver] speed."
)


def _linkage_options(f: F) -> F:
    """--speed, --step and --angle of the linkage commands that analyse a turn or a position."""
    f = speed_option(_SPEED_HELP)(f)
    f = step_option(
        "Crank-angle step over a full turn (deg for a bare number); default 10 for tables, 1 "
        "otherwise. Summaries always come from the 1 deg analysis."
    )(f)
    return click.option(
        "--angle",
        default=None,
        metavar="DEG",
        help="One crank angle (deg for a bare number, or with a unit); default: a full turn "
        "every --step.",
    )(f)


def _analysed(
    mech: Mechanism,
    theta: NDArray[np.float64],
    speed: str | None,
    angle: str | None,
    analyse: Callable[[MechanismMotion], R],
) -> tuple[R, R | None]:
    """(result at the rows, the full-turn result or None): a coarser table's summary is the
    full turn's."""
    w = _speed(mech, speed)
    result = analyse(mech.motion(theta, w))
    full = None
    if angle is None and (grid := _full_turn(theta, float(theta[0]))) is not None:
        full = analyse(mech.motion(grid, w))
        result = result.with_summary_of(full)
    return result, full


@linkage_group.command("kinematics")
@click.argument("linkage", metavar="LINKAGE")
@_linkage_options
@output_options
def kinematics_command(
    linkage: str,
    angle: str | None,
    step: str | None,
    speed: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Positions, velocities and accelerations of every link and point of LINKAGE."""
    out = Output(fmt, output_path, force)
    out.check()
    mech = resolve_linkage(linkage)
    theta = _angles(angle, step, fmt)
    result, _full = _analysed(mech, theta, speed, angle, linkage_kinematics)
    out.write(
        blocks=[result_table(result, title=f"{mech.name}: kinematics")],
        json_data=_json(result, single=angle is not None),
        csv_text=result.to_csv(),
    )
    return 0


@linkage_group.command("forces")
@click.argument("linkage", metavar="LINKAGE")
@_linkage_options
@click.option("--no-friction", is_flag=True, help="Ignore the joints' friction.")
@click.option(
    "--matrices",
    is_flag=True,
    help="Add the matrices C, D and P of [C]{R} = [D]{P} at every position (JSON).",
)
@plot_option("Also write the driving-torque and joint-force figure (.png, .svg or .pdf).")
@output_options
def forces_command(
    linkage: str,
    angle: str | None,
    step: str | None,
    speed: str | None,
    no_friction: bool,
    matrices: bool,
    plot_path: str | None,
    fmt: str,
    output_path: str | None,
    force: bool,
) -> int:
    """Joint reactions and driving torque of LINKAGE (matrix method and virtual work)."""
    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    mech = resolve_linkage(linkage)
    theta = _angles(angle, step, fmt)
    if matrices and fmt != "json":
        raise InputError("--matrices needs --format json", key="--matrices")
    result, _full = _analysed(
        mech, theta, speed, angle, lambda m: kinetostatics(m, friction=not no_friction)
    )
    extra: dict[str, Any] | None = None
    if matrices:
        system = result.system
        assert system is not None  # kinetostatics() keeps its system of equations
        extra = {"matrices": [system.matrices(i) for i in range(theta.size)]}
        if angle is not None:
            extra = {"matrices": extra["matrices"][0]}
    out.write(
        blocks=[_forces_table(result), *summary_blocks(result)],
        json_data=_json(result, single=angle is not None, extra=extra),
        csv_text=result.to_csv(),
        warnings=[result],
    )
    if plot_path:  # a full revolution at the plot resolution, whatever --step or --angle
        fine = mech.motion(_plot_angles(theta[0]), _speed(mech, speed))
        save_figure(kinetostatics(fine, friction=not no_friction).plot(), plot_path, force)
    return 0


def _forces_table(result: KinetostaticsResult) -> TextTable:
    """The driving torque by both methods and the joint force magnitudes."""
    cols = [
        ("Crank angle", "deg", np.degrees(result.crank_angle)),
        ("Driving torque", "N·m", result.driving_torque),
        ("Driving torque by virtual work, no friction", "N·m", result.driving_torque_virtual_work),
    ]
    if result.efficiency is not None:
        cols.append(("Efficiency", "", result.efficiency))
    assert result.joint_forces is not None  # a kinetostatics result carries its forces
    for name, f in result.joint_forces.items():
        cols.append((f"Force in joint {name}", "N", np.hypot(f["x"], f["y"])))
    header, columns = [], []
    for label, unit, values in cols:
        if unit == "deg":
            texts, shown = [f"{v:.6g}" for v in values], unit
        else:
            texts, shown = column_text(values, unit)
        header.append(f"{label} ({shown})" if shown else label)
        columns.append(texts)
    return TextTable(
        f"{result.mechanism_name}: kinetostatics",
        header,
        [list(r) for r in zip(*columns, strict=True)],
    )


@linkage_group.command("check")
@click.argument("linkage", metavar="LINKAGE")
@output_options
def check_command(linkage: str, fmt: str, output_path: str | None, force: bool) -> int:
    """Structure of LINKAGE: mobility, link groups and their static determinacy (seed 004)."""
    out = Output(fmt, output_path, force)
    out.check()
    mech = resolve_linkage(linkage)
    n, p = len(mech.links), len(mech.joints)
    line = (
        f"{mech.name}: {n} moving links, {p} lower pairs, "
        f'F = 3n - 2p_l = {mech.degrees_of_freedom}; crank "{mech.crank}" driven at '
        f'joint "{mech.driver.joint}"; drawn at crank angle '
        f"{math.degrees(mech.crank_angle_drawn):.6g} deg"
    )
    rows, groups = [], []
    for g in mech.link_groups():
        pl = len(g.joints)
        extra = 1 if g.kind == "driver" else 0
        determinate = 3 * len(g.links) == 2 * pl + extra
        rows.append(
            [
                g.kind,
                ", ".join(g.links),
                ", ".join(g.joints),
                str(3 * len(g.links)),
                str(2 * pl) + (" + 1 (driving torque)" if extra else ""),
                "yes" if determinate else "no",
            ]
        )
        groups.append(
            {
                "kind": g.kind,
                "links": list(g.links),
                "joints": list(g.joints),
                "determinate": determinate,
            }
        )
    table = TextTable(
        "Link groups, in the order of the force analysis",
        [
            "Group",
            "Links",
            "Joints",
            "Equations 3n",
            "Unknowns 2p_l",
            "Statically determinate",
        ],
        rows,
        text_columns={0, 1, 2, 4, 5},
    )
    data = {
        "name": mech.name,
        "moving_links": n,
        "lower_pairs": p,
        "degrees_of_freedom": mech.degrees_of_freedom,
        "crank": mech.crank,
        "driver_joint": mech.driver.joint,
        "crank_angle_drawn_deg": math.degrees(mech.crank_angle_drawn),
        "link_groups": groups,
    }
    out.write(blocks=[line, table], json_data=data)
    return 0


def _one_angle(angle: str | None, mech: Mechanism) -> float:
    """--angle (deg for a bare number) in rad, else the drawn position's crank angle."""
    if angle is None:
        return mech.crank_angle_drawn
    return option_quantity(angle, "angle", "--angle", "deg")


@linkage_group.command("draw")
@click.argument("linkage", metavar="LINKAGE")
@click.option(
    "--angle",
    default=None,
    metavar="DEG",
    help="Crank angle (deg for a bare number, or with a unit); default: the drawn position.",
)
@speed_option(_SPEED_HELP)
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
def draw_command(
    linkage: str,
    angle: str | None,
    speed: str | None,
    show_forces: bool,
    paths: bool,
    output: str,
    force: bool,
) -> int:
    """Draw LINKAGE at one crank angle with its joint forces (or its point paths)."""
    from crankdyn.plots.linkage import plot_mechanism, plot_paths

    mech = resolve_linkage(linkage)
    check_writable(output, force=force)
    theta0 = _one_angle(angle, mech)
    theta = _plot_angles(theta0)
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
    metavar="N",
    help="Frames per crank revolution (4 to 720).",
)
@click.option(
    "--fps",
    default=20,
    show_default=True,
    type=click.IntRange(1, 50),
    metavar="N",
    help="Frames per second (1 to 50).",
)
@speed_option(_SPEED_HELP)
@click.option(
    "--forces/--no-forces",
    "show_forces",
    default=True,
    show_default=True,
    help="Draw the joint forces.",
)
@click.option("-o", "--output", required=True, metavar="FILE", help="The GIF to write (.gif).")
@click.option("--force", is_flag=True, help="Overwrite an existing file.")
def animate_command(
    linkage: str,
    frames: int,
    fps: int,
    speed: str | None,
    show_forces: bool,
    output: str,
    force: bool,
) -> int:
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


@linkage_group.command("polygon")
@click.argument("linkage", metavar="LINKAGE")
@click.option(
    "--angle",
    default=None,
    metavar="DEG",
    help="Crank angle (deg for a bare number, or with a unit); default: the drawn position.",
)
@speed_option(_SPEED_HELP)
@click.option("--no-friction", is_flag=True, help="Ignore the joints' friction.")
@click.option("-o", "--output", required=True, metavar="FILE", help="PNG, SVG or PDF to write.")
@click.option("--force", is_flag=True, help="Overwrite an existing file.")
def polygon_command(
    linkage: str,
    angle: str | None,
    speed: str | None,
    no_friction: bool,
    output: str,
    force: bool,
) -> int:
    """The force polygon of every link group of LINKAGE at one crank angle (seed 004's
    graphical kinetostatics), drawn from the matrix method's solution."""
    from crankdyn.linkage.polygon import force_polygons
    from crankdyn.plots.linkage_statics import plot_force_polygons

    mech = resolve_linkage(linkage)
    check_writable(output, force=force)
    theta0 = _one_angle(angle, mech)
    result = kinetostatics(mech.motion([theta0], _speed(mech, speed)), friction=not no_friction)
    title = f"{mech.name}: force polygons at crank angle {math.degrees(theta0):.4g} deg"
    save_figure(plot_force_polygons(force_polygons(result), title), output, force)
    return 0


@linkage_group.command("truss")
@click.argument("truss_file", metavar="FILE")
@plot_option("Also write the truss with its member forces (.png, .svg or .pdf).")
@output_options
def truss_command(
    truss_file: str, plot_path: str | None, fmt: str, output_path: str | None, force: bool
) -> int:
    """Member forces of the plane truss in FILE by the method of joints and by the method of
    sections, checked against each other (seed 004; `crankdyn docs linkage-file`)."""
    from crankdyn.io.truss_file import load_truss
    from crankdyn.linkage.truss import truss_analysis

    out = Output(fmt, output_path, force)
    out.check()
    check_plot_path(plot_path, force)
    result = truss_analysis(load_truss(truss_file))
    out.write(
        blocks=[
            result_table(result),
            result_table(result.reactions),
            *summary_blocks(result),
        ],
        json_data=result,
        csv_text=result.to_csv(),
    )
    if plot_path:
        save_figure(result.plot(), plot_path, force)
    return 0


linkage_group.add_command(examples_alias("linkage", "linkage"))
linkage_group.add_command(example_alias("linkage"))


def register(group: click.Group) -> None:
    """Add the ``linkage`` group to the command ``group``."""
    group.add_command(linkage_group)
