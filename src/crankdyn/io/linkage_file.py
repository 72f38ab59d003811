"""Linkage description files (TOML) and the built-in linkage examples; see docs/linkage-file.md."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any, overload

from crankdyn.errors import did_you_mean
from crankdyn.io.files import display_name, load_toml
from crankdyn.io.schema import Table
from crankdyn.io.units import parse_quantity
from crankdyn.linkage.elements import GROUND, JOINT_KINDS, Driver, Force, Joint, Link, Torque
from crankdyn.linkage.planar import Mechanism

__all__ = [
    "load_linkage",
    "parse_linkage",
]


def load_linkage(path: str | Path) -> Mechanism:
    """Load a linkage file (TOML; format in docs/linkage-file.md, ``crankdyn docs
    linkage-file``).

    Parameters
    ----------
    path
        The linkage file.

    Returns
    -------
    Mechanism
        The planar mechanism, every quantity in SI (lengths m, masses kg, inertias kg m^2,
        forces N, torques N m, speeds rad/s).

    Raises
    ------
    InputError
        On an unreadable or malformed file, a missing or unknown key, a value of the wrong
        unit or sign, or an inconsistent mechanism; naming the file, the key and the value.
    """
    return _load(Path(path), display_name(path))


def _load(path: Path, name: str) -> Mechanism:
    data = load_toml(path, what="linkage file")
    return parse_linkage(data, file=name)


# for the type checker: the callers give no default only for a key the table holds
@overload
def _pair(t: Table, key: str, kind: str) -> tuple[float, float]: ...


@overload
def _pair(t: Table, key: str, kind: str, default: tuple[float, float]) -> tuple[float, float]: ...


@overload
def _pair(t: Table, key: str, kind: str, default: None) -> tuple[float, float] | None: ...


def _pair(
    t: Table, key: str, kind: str, default: tuple[float, float] | None = None
) -> tuple[float, float] | None:
    value = t.raw(key, default, expected=f'a pair such as ["10 {_UNIT[kind]}", "0 {_UNIT[kind]}"]')
    if value is default and key not in t.data:
        return default
    if not isinstance(value, list) or len(value) != 2:
        raise t.error(
            key, f'expected a pair such as ["10 {_UNIT[kind]}", "0 {_UNIT[kind]}"]', value
        )
    x, y = (parse_quantity(v, kind, key=t.label(key), file=t.file) for v in value)
    return x, y


_UNIT = {"length": "mm", "force": "N", "acceleration": "m/s^2"}


def parse_linkage(data: dict[str, Any], *, file: str | None = None) -> Mechanism:
    """Build a Mechanism from a parsed linkage document (a dict as from tomllib).

    Keys: ``name``, ``gravity`` (pair, m/s^2; default [0, 0]), ``[points]`` (NAME = [x, y],
    lengths), ``[[links]]`` (``name``, ``points``, ``mass`` kg, ``inertia`` kg m^2, ``cg``),
    ``[[joints]]``, ``[driver]``, ``[[forces]]`` (N) and ``[[torques]]`` (N m); quantities as
    strings with units (``"10 mm"``) or bare SI numbers (docs/linkage-file.md).

    Parameters
    ----------
    data
        The parsed document.
    file
        The file's name for messages (None: the document came from elsewhere).

    Returns
    -------
    Mechanism
        The planar mechanism, every quantity in SI.

    Raises
    ------
    InputError
        On a missing or unknown key or table, a value of the wrong unit, kind or sign, a
        reference to an unknown point or link, or an inconsistent mechanism; naming the
        file, the key and the value.
    """
    root = Table(data, file=file)
    name = root.string("name")
    gravity = _pair(root, "gravity", "acceleration", (0.0, 0.0))
    pts = root.table("points", required=True)
    points = {}
    for key in list(pts.data):
        points[key] = _pair(pts, key, "length")
    if not points:
        raise pts.error(None, "no points; give each point as NAME = [x, y]")
    pts.finish()
    links = [_link(t, points) for t in root.tables("links", required=True)]
    joints = [_joint(t) for t in root.tables("joints", required=True)]
    driver = _driver(root.table("driver", required=True), points)
    forces = [_force(t) for t in root.tables("forces")]
    torques = [_torque(t) for t in root.tables("torques")]
    with root.context():
        mechanism = Mechanism(
            name=name,
            points=points,
            links=tuple(links),
            joints=tuple(joints),
            driver=driver,
            forces=tuple(forces),
            torques=tuple(torques),
            gravity=gravity,
            source=file,
        )
    root.finish()
    return mechanism


def _link(t: Table, points: dict) -> Link:
    name = t.string("name")
    pts = t.string_list("points")
    mass = t.quantity("mass", "mass", 0.0, check="nonnegative")
    inertia = t.quantity("inertia", "inertia", 0.0, check="nonnegative")
    cg = None
    if t.has("cg"):
        raw = t.data["cg"]
        if isinstance(raw, str):
            if raw not in points:
                raise t.error("cg", f"no point of that name{did_you_mean(raw, points)}", raw)
            cg = points[raw]
        else:
            cg = _pair(t, "cg", "length")
    with t.context():
        link = Link(name=name, points=pts, mass=mass, inertia=inertia, cg=cg)
    t.finish()
    return link


def _joint(t: Table) -> Joint:
    name = t.string("name")
    kind = t.string("type", "revolute", choices=JOINT_KINDS)
    links = t.string_list("links", length=2)
    point = t.string("point", name)
    axis = t.quantity("axis", "angle", None)
    radius = t.quantity("journal_radius", "length", 0.0, check="nonnegative")
    friction = t.number("friction", 0.0, check="nonnegative")
    if kind == "prismatic" and axis is None:
        raise t.error("axis", 'missing; a prismatic joint needs its guide direction, e.g. "0 deg"')
    if kind == "revolute" and axis is not None:
        raise t.error("axis", "only a prismatic joint has an axis", t.data["axis"])
    if kind == "prismatic" and t.has("journal_radius"):
        raise t.error(
            "journal_radius", "a prismatic joint has no journal", t.data["journal_radius"]
        )
    with t.context():
        joint = Joint(
            name=name,
            kind=kind,
            links=links,
            point=point,
            axis=axis,
            journal_radius=radius,
            friction=friction,
        )
    t.finish()
    return joint


def _driver(t: Table, points: dict) -> Driver:
    joint = t.string("joint")
    point = t.string("point")
    zero = 0.0
    if t.has("zero"):
        raw = t.data["zero"]
        if isinstance(raw, str) and raw in points:
            pivot_name = t.string("pivot", joint)
            if pivot_name not in points:
                raise t.error(
                    "pivot", "no point of that name; give the crank pivot's point", pivot_name
                )
            p0, p1 = points[pivot_name], points[raw]
            if p0 == p1:
                raise t.error("zero", "the zero line needs a point away from the pivot", raw)
            zero = math.atan2(p1[1] - p0[1], p1[0] - p0[0])
        else:
            # a direction: whole turns beyond one are dropped (a zero line of 1e10 deg would
            # have the motion march through millions of turns from the drawn position)
            zero = math.fmod(t.quantity("zero", "angle"), 2.0 * math.pi)
    speed = t.quantity("speed", "speed", 1.0)
    acceleration = t.quantity("acceleration", "angular_acceleration", 0.0)
    bp = t.string("balancing_point", None)
    bd = t.quantity("balancing_direction", "angle", None)
    relative = t.boolean("balancing_relative_to_crank", False)
    with t.context():
        driver = Driver(
            joint=joint,
            point=point,
            zero=zero,
            speed=speed,
            acceleration=acceleration,
            balancing_point=bp,
            balancing_direction=bd,
            balancing_relative=relative,
        )
    t.finish(also_known=("pivot",))
    return driver


def _force(t: Table) -> Force:
    link = t.string("link")
    point = t.string("point")
    if link == GROUND:
        raise t.error("link", "a force on the ground does not load the mechanism", link)
    force = _pair(t, "force", "force", None)
    resistance = t.quantity("resistance", "force", None, check="nonnegative")
    direction = t.quantity("working_direction", "angle", None)
    if (force is None) == (resistance is None):
        raise t.error("force", "give either force = [Fx, Fy] or resistance")
    with t.context():
        f = Force(
            link=link,
            point=point,
            force=force,
            resistance=resistance,
            working_direction=direction,
        )
    t.finish()
    return f


def _torque(t: Table) -> Torque:
    link = t.string("link")
    torque = t.quantity("torque", "torque", None)
    resistance = t.quantity("resistance", "torque", None, check="nonnegative")
    if (torque is None) == (resistance is None):
        raise t.error("torque", "give either torque or resistance")
    with t.context():
        out = Torque(link=link, torque=torque, resistance=resistance)
    t.finish()
    return out
