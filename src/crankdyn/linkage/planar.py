"""General planar mechanisms: links, revolute and prismatic joints and a crank driver joined
into a :class:`Mechanism` (domain), and its motion at any crank angles.

The mechanism has F = 3n - 2 p_l degrees of freedom (Gruebler-Chebyshev, seed 004: each lower
pair removes two); crankdyn needs F = 1 so that the driver closes the system (3n equations).

The parts are :mod:`crankdyn.linkage.elements` (links, joints, the driver, external loads);
positions, velocities and accelerations come from :mod:`crankdyn.linkage.solver` (in closed form
for mechanisms of dyads, else by Newton-Raphson with branch control and the constraint Jacobian;
Nikravesh 1988, Haug 1989) as a :class:`~crankdyn.linkage.motion.MechanismMotion`.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from crankdyn.errors import InputError, did_you_mean
from crankdyn.linkage.elements import (
    GROUND,
    Driver,
    Force,
    Joint,
    Link,
    LinkGroup,
    Torque,
    check_xy,
    degrees_of_freedom,
    is_statically_determinate,
)
from crankdyn.linkage.motion import MechanismMotion
from crankdyn.linkage.solver import KinematicModel

__all__ = ["Mechanism", "slider_crank_mechanism"]

_COND_LIMIT = 1e10  # condition number above which the drawn configuration counts as singular


def _key(kind: str, name: str, field_name: str) -> str:
    return f'{kind} "{name}" {field_name}'


@dataclass(frozen=True)
class Mechanism:
    """A planar mechanism of rigid links, revolute and prismatic joints and one crank driver.

    Parameters
    ----------
    name : str
        Name for reports.
    points : mapping or sequence of (str, (float, float))
        Named points and their coordinates (m) in the drawn (assembled) configuration, as a
        mapping or a sequence of (name, (x, y)) pairs; held as a tuple of pairs. The drawing
        fixes every link's geometry and the assembly branch.
    links : sequence of Link
        The moving links.
    joints : sequence of Joint
        The joints (lower pairs).
    driver : Driver
        The input crank.
    forces : sequence of Force
        External forces; default none.
    torques : sequence of Torque
        External couples; default none.
    gravity : (float, float)
        Gravitational acceleration vector (m/s^2), e.g. (0, -9.81); (0, 0) (default) ignores
        weight.
    source : str or None
        The file the mechanism came from, for messages.

    Raises
    ------
    InputError
        If a name is repeated or unknown, a joint's point is not on its links, the mobility is
        not F = 1, a link is not connected to the ground, the driver is not a revolute joint to
        the ground, or the drawn configuration is singular (each message names the key).

    Examples
    --------
    >>> mech = slider_crank_mechanism(0.05, 0.2)
    >>> mech.degrees_of_freedom, [g.kind for g in mech.link_groups()]
    (1, ['RRP dyad', 'driver'])
    """

    name: str
    points: tuple[tuple[str, tuple[float, float]], ...]
    links: tuple[Link, ...]
    joints: tuple[Joint, ...]
    driver: Driver
    forces: tuple[Force, ...] = ()
    torques: tuple[Torque, ...] = ()
    gravity: tuple[float, float] = (0.0, 0.0)
    source: str | None = field(default=None, compare=False)

    if TYPE_CHECKING:  # what the constructor accepts; the fields hold the normalised values

        def __init__(
            self,
            name: str,
            points: Mapping[str, Sequence[float]] | Sequence[tuple[str, Sequence[float]]],
            links: Sequence[Link],
            joints: Sequence[Joint],
            driver: Driver,
            forces: Sequence[Force] = (),
            torques: Sequence[Torque] = (),
            gravity: Sequence[float] = (0.0, 0.0),
            source: str | None = None,
        ) -> None: ...

    def __post_init__(self) -> None:
        pts = self.points.items() if isinstance(self.points, Mapping) else self.points
        points = tuple((str(n), check_xy(f'point "{n}"', xy)) for n, xy in pts)
        object.__setattr__(self, "points", points)
        object.__setattr__(self, "links", tuple(self.links))
        object.__setattr__(self, "joints", tuple(self.joints))
        object.__setattr__(self, "forces", tuple(self.forces))
        object.__setattr__(self, "torques", tuple(self.torques))
        object.__setattr__(self, "gravity", check_xy("gravity", self.gravity))
        self._validate()

    # ---- validation ---------------------------------------------------------------------------
    def _validate(self) -> None:
        names = [n for n, _xy_ in self.points]
        if len(set(names)) != len(names):
            dup = next(n for n in names if names.count(n) > 1)
            raise InputError("a point is defined twice", key="points", value=dup)
        point_set = set(names)
        link_names = [link.name for link in self.links]
        if not link_names:
            raise InputError("the mechanism has no moving links", key="links")
        if len(set(link_names)) != len(link_names):
            dup = next(n for n in link_names if link_names.count(n) > 1)
            raise InputError("two links have the same name", key="links", value=dup)
        all_links = {*link_names, GROUND}
        for link in self.links:
            for p in link.points:
                if p not in point_set:
                    raise InputError(
                        f"no point of that name{did_you_mean(p, names)}",
                        key=_key("link", link.name, "points"),
                        value=p,
                    )
        joint_names = [j.name for j in self.joints]
        if len(set(joint_names)) != len(joint_names):
            dup = next(n for n in joint_names if joint_names.count(n) > 1)
            raise InputError("two joints have the same name", key="joints", value=dup)
        by_name = {link.name: link for link in self.links}
        for j in self.joints:
            for ln in j.links:
                if ln not in all_links:
                    raise InputError(
                        f"no link of that name{did_you_mean(ln, sorted(all_links))}",
                        key=_key("joint", j.name, "links"),
                        value=ln,
                    )
            if j.point not in point_set:
                raise InputError(
                    f"no point of that name{did_you_mean(j.point, names)}",
                    key=_key("joint", j.name, "point"),
                    value=j.point,
                )
            on = j.links if j.kind == "revolute" else j.links[1:]
            for ln in on:
                if ln != GROUND and j.point not in by_name[ln].points:
                    raise InputError(
                        f'the joint\'s point "{j.point}" is not a point of link "{ln}"',
                        key=_key("joint", j.name, "point"),
                        value=j.point,
                    )
        # mobility
        n_links, n_joints = len(self.links), len(self.joints)
        dof = degrees_of_freedom(n_links, n_joints)
        if dof != 1:
            raise InputError(
                f"the mechanism has F = 3n - 2p = 3*{n_links} - 2*{n_joints} = {dof} degrees of "
                "freedom; "
                "crankdyn analyses mechanisms with exactly one, driven by the crank",
                key="joints",
            )
        connected = {GROUND}
        changed = True
        while changed:
            changed = False
            for j in self.joints:
                a, b = j.links
                if (a in connected) != (b in connected):
                    connected |= {a, b}
                    changed = True
        loose = [ln for ln in link_names if ln not in connected]
        if loose:
            raise InputError(
                "the link is not connected to the ground through joints",
                key=_key("link", loose[0], "name"),
                value=loose[0],
            )
        # driver
        d = self.driver
        joints = {j.name: j for j in self.joints}
        if d.joint not in joints:
            raise InputError(
                f"no joint of that name{did_you_mean(d.joint, joint_names)}",
                key="driver joint",
                value=d.joint,
            )
        dj = joints[d.joint]
        if dj.kind != "revolute" or GROUND not in dj.links:
            raise InputError(
                "the driver must be a revolute joint between the ground and the crank "
                "(linear actuators are not supported yet)",
                key="driver joint",
                value=d.joint,
            )
        crank = self.crank
        if d.point not in by_name[crank].points or d.point == dj.point:
            raise InputError(
                f'expected a point of the crank "{crank}" other than its pivot "{dj.point}"',
                key="driver point",
                value=d.point,
            )
        if d.balancing_point is not None and d.balancing_point not in by_name[crank].points:
            raise InputError(
                f'expected a point of the crank "{crank}"',
                key="driver balancing_point",
                value=d.balancing_point,
            )
        for f in self.forces:
            if f.link not in by_name:
                raise InputError(
                    f"no moving link of that name{did_you_mean(f.link, link_names)}",
                    key="force link",
                    value=f.link,
                )
            if f.point not in by_name[f.link].points:
                raise InputError(
                    f'not a point of link "{f.link}"', key="force point", value=f.point
                )
        for t in self.torques:
            if t.link not in by_name:
                raise InputError(
                    f"no moving link of that name{did_you_mean(t.link, link_names)}",
                    key="torque link",
                    value=t.link,
                )
        # (a prismatic joint's guide is the line through its point along its axis, so the
        # drawn configuration satisfies it by construction)
        if self.length_scale <= 0.0:
            raise InputError("all points coincide", key="points")
        # the drawn configuration must not be singular
        model = self._model
        jac = model.jacobian(model.q0[None, :])[0]
        if np.linalg.cond(jac) > _COND_LIMIT:
            raise InputError(
                "the drawn configuration is singular (links in line at a dead point, or "
                "redundant joints); draw the mechanism at another crank angle",
                key="points",
            )

    # ---- derived structure --------------------------------------------------------------------
    @property
    def point_map(self) -> dict[str, np.ndarray]:
        """{point name: drawn position (m)}."""
        return {n: np.array(xy) for n, xy in self.points}

    @cached_property
    def length_scale(self) -> float:
        """Largest distance between two points (m): the scale of tolerances."""
        xy = np.array([p for _n, p in self.points])
        return float(np.max(np.ptp(xy, axis=0))) if len(xy) > 1 else 0.0

    @property
    def crank(self) -> str:
        """Name of the driven crank link."""
        j = next(j for j in self.joints if j.name == self.driver.joint)
        return j.links[1] if j.links[0] == GROUND else j.links[0]

    @property
    def link_names(self) -> tuple[str, ...]:
        """Names of the moving links, in order."""
        return tuple(link.name for link in self.links)

    def link(self, name: str) -> Link:
        """A moving link by name.

        Parameters
        ----------
        name : str
            The link's name.

        Returns
        -------
        Link
            The link.

        Raises
        ------
        StopIteration
            If there is no such link (the names are checked on construction).
        """
        return next(link for link in self.links if link.name == name)

    def joint(self, name: str) -> Joint:
        """A joint by name.

        Parameters
        ----------
        name : str
            The joint's name.

        Returns
        -------
        Joint
            The joint.

        Raises
        ------
        StopIteration
            If there is no such joint.
        """
        return next(j for j in self.joints if j.name == name)

    @cached_property
    def cg_drawn(self) -> dict[str, np.ndarray]:
        """Centre of gravity of every moving link in the drawn configuration (m)."""
        pm = self.point_map
        out = {}
        for link in self.links:
            if link.cg is not None:
                out[link.name] = np.array(link.cg)
            else:
                out[link.name] = np.mean([pm[p] for p in link.points], axis=0)
        return out

    @cached_property
    def point_owner(self) -> dict[str, str]:
        """The link that carries each point (its motion is the point's motion); a point on no
        moving link belongs to the ground."""
        owner: dict[str, str] = {}
        for link in self.links:
            for p in link.points:
                owner.setdefault(p, link.name)
        for n, _ in self.points:
            owner.setdefault(n, GROUND)
        return owner

    @cached_property
    def crank_angle_drawn(self) -> float:
        """Crank angle of the drawn configuration (rad), from the driver's zero line."""
        pm = self.point_map
        pivot = pm[self.joint(self.driver.joint).point]
        v = pm[self.driver.point] - pivot
        return math.atan2(v[1], v[0]) - self.driver.zero

    @cached_property
    def _model(self) -> KinematicModel:
        return KinematicModel(self)

    # ---- structure (seed 004) ------------------------------------------------------------------
    @property
    def degrees_of_freedom(self) -> int:
        """F = 3n - 2 p_l (all joints are lower pairs)."""
        return degrees_of_freedom(len(self.links), len(self.joints))

    def link_groups(self) -> tuple[LinkGroup, ...]:
        """Decompose the mechanism into statically determinate link groups (Assur groups, seed
        004: each satisfies 3n = 2 p_l) and the driver, in the order of the force analysis.

        Groups are peeled off from the end of the chain: a group is a connected set of links
        (not the crank) whose joints, to each other and to the rest, number 3n/2; removing it
        leaves a mechanism of the same mobility. Forces are then found group by group in this
        order, starting from the group farthest from the crank (seed 004: the conveyor's group
        4-5 before 2-3), and the kinematics in the reverse order.

        Returns
        -------
        tuple of LinkGroup
            The groups in the order of the force analysis, the driver last.
        """
        remaining = [ln for ln in self.link_names if ln != self.crank]
        joints = [j for j in self.joints if j.name != self.driver.joint]
        groups = []
        while remaining:
            found = None
            for size in range(1, len(remaining) + 1):
                for subset in itertools.combinations(remaining, size):
                    s = set(subset)
                    touching = [j for j in joints if s & set(j.links)]
                    if is_statically_determinate(size, len(touching)) and _connected(s, touching):
                        found = (subset, touching)
                        break
                if found:
                    break
            if found is None:  # cannot happen for F = 1, but never loop forever
                groups.append(LinkGroup(tuple(remaining), (), "indeterminate"))
                break
            subset, touching = found
            kind = f"group of {len(subset)} links"
            if len(subset) == 2:
                kind = _dyad_class(subset, touching) + " dyad"
            groups.append(LinkGroup(tuple(subset), tuple(j.name for j in touching), kind))
            remaining = [ln for ln in remaining if ln not in subset]
            joints = [j for j in joints if j not in touching]
        groups.append(LinkGroup((self.crank,), (self.driver.joint,), "driver"))
        return tuple(groups)

    # ---- analyses ---------------------------------------------------------------------------
    def motion(
        self,
        crank_angles: ArrayLike,
        speed: float | None = None,
        acceleration: float | None = None,
    ) -> MechanismMotion:
        """Positions, velocities and accelerations at crank angles
        (:mod:`crankdyn.linkage.solver`).

        Parameters
        ----------
        crank_angles : array_like
            Crank angles (rad) from the driver's zero line.
        speed : float or None
            Crank speed (rad/s); default the driver's.
        acceleration : float or None
            Crank angular acceleration (rad/s^2); default the driver's.

        Returns
        -------
        MechanismMotion
            Link coordinates and their derivatives at every angle.

        Raises
        ------
        InputError
            If the mechanism cannot reach an angle on its drawn branch (a dead point) or is
            singular there.

        Examples
        --------
        A central slider-crank (R = 50 mm, L = 200 mm) at 90 deg: the slider moves at -R w.

        >>> mech = slider_crank_mechanism(0.05, 0.2)
        >>> m = mech.motion([math.pi / 2], speed=10.0)
        >>> [round(float(v), 9) for v in m.point("C", which="qd")[0]]
        [-0.5, 0.0]
        """
        theta = np.atleast_1d(np.asarray(crank_angles, dtype=float))
        w = self.driver.speed if speed is None else float(speed)
        e = self.driver.acceleration if acceleration is None else float(acceleration)
        q, qp, qpp = self._model.solve(theta)
        return MechanismMotion(
            mechanism=self, crank_angle=theta, speed=w, acceleration=e, q=q, qp=qp, qpp=qpp
        )

    @classmethod
    def from_file(cls, path: str | Path) -> Mechanism:
        """Load a linkage file (TOML; ``crankdyn docs linkage-file``).

        Parameters
        ----------
        path : str or pathlib.Path
            The linkage file.

        Returns
        -------
        Mechanism
            The mechanism.

        Raises
        ------
        InputError
            If the file cannot be read or holds a mistake.
        """
        from crankdyn.io.linkage_file import load_linkage

        return load_linkage(path)

    def _repr_html_(self) -> str:
        """The links (masses, inertias) and joints (notebooks)."""
        from crankdyn.display import mechanism_html

        return mechanism_html(self)

    @classmethod
    def example(cls, name: str) -> Mechanism:
        """A built-in example linkage by name (``crankdyn linkage examples`` lists them).

        Parameters
        ----------
        name : str
            The example's name, e.g. ``"fourbar-seed004"``.

        Returns
        -------
        Mechanism
            The mechanism.

        Raises
        ------
        InputError
            If there is no linkage example of that name.
        """
        from crankdyn.io.catalogue import load_example

        return load_example(name, "linkage")


def _connected(links: set[str], joints: Sequence[Joint]) -> bool:
    if len(links) == 1:
        return True
    start = next(iter(links))
    seen = {start}
    changed = True
    while changed:
        changed = False
        for j in joints:
            a, b = j.links
            if a in links and b in links and (a in seen) != (b in seen):
                seen |= {a, b}
                changed = True
    return seen == links


def _dyad_class(subset: tuple[str, ...], touching: Sequence[Joint]) -> str:
    a, b = subset
    inner = [j for j in touching if set(j.links) == {a, b}]
    outer_a = [j for j in touching if a in j.links and b not in j.links]
    outer_b = [j for j in touching if b in j.links and a not in j.links]
    if len(inner) != 1 or len(outer_a) != 1 or len(outer_b) != 1:
        return "RRR"
    letters = [j.kind[0].upper() for j in (outer_a[0], inner[0], outer_b[0])]
    text = "".join(letters)
    return max(text, text[::-1])


# ---- constructors of common mechanisms ----------------------------------------------------


def slider_crank_mechanism(
    crank: float,
    rod: float,
    offset: float = 0.0,
    theta: float = math.radians(30.0),
    *,
    masses: tuple[float, float, float] = (0.0, 0.0, 0.0),
    inertias: tuple[float, float] = (0.0, 0.0),
    cg_fractions: tuple[float, float] = (0.5, 0.5),
    speed: float = 1.0,
    acceleration: float = 0.0,
    gravity: Sequence[float] = (0.0, 0.0),
    forces: Sequence[Force] = (),
    torques: Sequence[Torque] = (),
    friction: Mapping[str, tuple[float, float]] | None = None,
    name: str = "slider-crank",
) -> Mechanism:
    """An (offset) slider-crank as a general planar mechanism.

    Drawn at crank angle theta: crank pivot A at the origin, the slider's guide along +x at
    height ``offset``, crank AB, rod BC. Links crank (A, B), rod (B, C), slider (C); joints A,
    B, C (revolute) and S (prismatic, on the ground).

    Parameters
    ----------
    crank : float
        Crank length AB (m).
    rod : float
        Rod length BC (m).
    offset : float
        Height of the guide above the crank pivot (m); default 0.
    theta : float
        Crank angle of the drawing (rad, from +x); default 30 deg.
    masses : (float, float, float)
        Masses of crank, rod and slider (kg); default 0.
    inertias : (float, float)
        Moments of inertia of crank and rod about their centres of gravity (kg m^2).
    cg_fractions : (float, float)
        Centres of gravity of crank and rod as fractions along A->B and B->C; default
        midpoints.
    speed : float
        Crank speed (rad/s); default 1.
    acceleration : float
        Crank angular acceleration (rad/s^2); default 0.
    gravity : (float, float)
        Gravitational acceleration (m/s^2); default (0, 0).
    forces : sequence of Force
        External forces.
    torques : sequence of Torque
        External couples.
    friction : mapping or None
        Joint name to (journal radius (m) or 0, friction coefficient (dimensionless)).
    name : str
        The mechanism's name.

    Returns
    -------
    Mechanism
        The slider-crank.

    Raises
    ------
    InputError
        If the rod cannot reach the guide at ``theta``, or as :class:`Mechanism`.
    """
    pb = crank * np.array([math.cos(theta), math.sin(theta)])
    dy = offset - pb[1]
    if abs(dy) >= rod:
        raise InputError("the rod cannot reach the guide at this crank angle", key="rod")
    pc = np.array([pb[0] + math.sqrt(rod * rod - dy * dy), offset])
    fr = friction or {}

    def jf(name: str) -> dict[str, float]:
        r, f = fr.get(name, (0.0, 0.0))
        return {"journal_radius": r, "friction": f}

    links = (
        Link("crank", ("A", "B"), masses[0], inertias[0], tuple(cg_fractions[0] * pb)),
        Link(
            "rod",
            ("B", "C"),
            masses[1],
            inertias[1],
            tuple(pb + cg_fractions[1] * (pc - pb)),
        ),
        Link("slider", ("C",), masses[2], 0.0, tuple(pc)),
    )
    joints = (
        Joint("A", "revolute", (GROUND, "crank"), "A", **jf("A")),
        Joint("B", "revolute", ("crank", "rod"), "B", **jf("B")),
        Joint("C", "revolute", ("rod", "slider"), "C", **jf("C")),
        Joint("S", "prismatic", (GROUND, "slider"), "C", axis=0.0, friction=jf("S")["friction"]),
    )
    return Mechanism(
        name=name,
        points={"A": (0.0, 0.0), "B": tuple(pb), "C": tuple(pc)},
        links=links,
        joints=joints,
        driver=Driver("A", "B", 0.0, speed, acceleration),
        forces=tuple(forces),
        torques=tuple(torques),
        gravity=gravity,
    )
