"""General planar mechanisms: links, revolute and prismatic joints, a crank driver; positions,
velocities and accelerations in closed form for mechanisms of dyads, else by Newton-Raphson with
branch control and the constraint Jacobian.

Formulation (absolute coordinates; Nikravesh 1988, Computer-Aided Analysis of Mechanical Systems,
ch. 3-4; Haug 1989, Computer-Aided Kinematics and Dynamics of Mechanical Systems, ch. 3)
---------------------------------------------------------------------------------------------
Every moving link i carries the coordinates q_i = (x_i, y_i, phi_i): the position of its
reference point G_i (its centre of gravity) and its rotation phi_i from the drawn configuration.
A point with drawn position p on link i is at r = G_i + A(phi_i) s_i, s_i = p - G_i(drawn), with
A the rotation matrix; B = dA/dphi = A R90. The ground is fixed (G = 0, phi = 0).

- Revolute joint between links i and j at a point: two equations
  Phi = G_i + A_i s_i - G_j - A_j s_j = 0,  gamma = A_i s_i phi_i'^2 - A_j s_j phi_j'^2.
- Prismatic joint, the guide on link i (direction fixed in i, unit normal n' in i's frame), the
  slider j: phi_i - phi_j = 0 and n_i . (G_j + A_j s_j - G_i) - n' . s_i = 0 with n_i = A_i n',
  gamma = n_i.e phi_i'^2 - 2 (B_i n' phi_i').e' + n_i.(A_j s_j) phi_j'^2, e = G_j + A_j s_j - G_i.
- Driver: phi_k = theta - theta_drawn for the crank k turning about a ground pivot.

The mechanism has F = 3n - 2 p_l degrees of freedom (Gruebler-Chebyshev, seed 004: each lower
pair removes two); crankdyn needs F = 1 so that the driver closes the system (3n equations).

**Closed form.** When every link group (:meth:`Mechanism.link_groups`) is a dyad (RRR, RRP, RPR,
PRP, RPP), the mechanism is solved group by group in closed form, vectorised over all crank
angles (:mod:`crankdyn.linkage.dyads`), on the drawn assembly branch, with the rotations
continued along the crank angles from the drawn one (:meth:`_Model._solve_closed`). Everything
else, and any path that passes a dead point, an assembly gap or a singular position, goes to the
general solver below, which reports such positions.

**General solver.** Positions: Newton-Raphson, Phi_q dq = -Phi, continued from the drawn
configuration in small crank steps with a second-order predictor q + q' dtheta + q'' dtheta^2 / 2.
**Branch control**: a step is accepted only when Newton converges quickly and its correction is
small against the step's own motion; otherwise the step is halved. The assembly branch is
therefore the one drawn, kept through the cycle; a mechanism that cannot reach a requested crank
angle stops at its dead point with a message naming both angles. Velocities and accelerations
then follow from one LU factorisation of Phi_q per position (batched over blocks of angles,
:mod:`crankdyn.linkage.linsolve`) used for both Phi_q q' = e_driver and Phi_q q'' = gamma(q, q'),
per unit crank speed, so that q_dot = omega q' and q_ddot = omega^2 q'' + alpha q'; a position
whose factorisation has a pivot below 1e-10 of its column is singular and named in the error.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import DEG
from crankdyn.crank.geometry import check_finite
from crankdyn.errors import InputError, did_you_mean
from crankdyn.linkage.dyads import GROUND
from crankdyn.linkage.linsolve import lu_factor
from crankdyn.results import Result, column, freeze, scalar

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "GROUND",
    "JOINT_KINDS",
    "Driver",
    "Force",
    "Joint",
    "Link",
    "LinkGroup",
    "LinkageKinematicsResult",
    "Mechanism",
    "MechanismMotion",
    "Torque",
    "degrees_of_freedom",
    "is_statically_determinate",
    "linkage_kinematics",
    "slider_crank_mechanism",
]

JOINT_KINDS = ("revolute", "prismatic")
"""The lower pairs crankdyn models."""
TWO_PI = 2.0 * math.pi
_MAX_STEP = math.radians(3.0)  # largest continuation step of the crank
_MIN_STEP = 1e-9  # rad; below this a step that still fails marks a dead point
_COND_LIMIT = 1e10  # condition number above which the drawn configuration counts as singular
_BLOCK = 4096  # crank angles per block of the general solver's batched Jacobians (bounded memory)
_PATH_BLOCK = 8192  # crank angles per block of the closed-form solution
_MAX_TURN = 0.5 * math.pi  # largest rotation of a link the closed form follows between samples


def degrees_of_freedom(moving_links: int, lower_pairs: int, higher_pairs: int = 0) -> int:
    """Gruebler-Chebyshev mobility F = 3n - 2 p_l - p_h of a planar mechanism (seed 004).

    Parameters
    ----------
    moving_links : int
        n, the moving links.
    lower_pairs : int
        p_l, revolute and prismatic joints.
    higher_pairs : int
        p_h, cam and gear contacts; default 0.

    Returns
    -------
    int
        F (dimensionless).

    Examples
    --------
    A four-bar: three moving links, four revolute joints.

    >>> degrees_of_freedom(3, 4)
    1
    """
    return 3 * moving_links - 2 * lower_pairs - higher_pairs


def is_statically_determinate(links: int, lower_pairs: int, higher_pairs: int = 0) -> bool:
    """Static determinacy of a link group (seed 004, sec. 1 "构件组的静定条件"): its n links give
    3n equilibrium equations and each lower pair brings two unknown reaction components (a
    revolute: magnitude and direction; a prismatic: magnitude and point of application), each
    higher pair one, so the group is determinate when 3n = 2 p_l + p_h.

    Parameters
    ----------
    links : int
        n, the links of the group.
    lower_pairs : int
        p_l, its lower pairs (to each other and to the rest).
    higher_pairs : int
        p_h, its higher pairs; default 0.

    Returns
    -------
    bool
        Whether 3n = 2 p_l + p_h.

    Examples
    --------
    A dyad (two links, three joints) is determinate:

    >>> is_statically_determinate(2, 3)
    True
    """
    return 3 * links == 2 * lower_pairs + higher_pairs


def _xy(name: str, value: Any) -> tuple[float, float]:  # Any: the user's value, as given
    try:
        x, y = value
    except (TypeError, ValueError):
        raise InputError("expected a pair [x, y]", key=name, value=value) from None
    return check_finite(name, x), check_finite(name, y)


def _nonnegative(name: str, value: float, what: str) -> float:
    number = check_finite(name, value)
    if number < 0.0:
        raise InputError(f"{what} must not be negative", key=name, value=value)
    return number


@dataclass(frozen=True)
class Link:
    """A rigid link (domain object).

    Parameters
    ----------
    name : str
        Unique name; ``"ground"`` is reserved for the frame.
    points : sequence of str
        Names of the points on the link (drawing, joint checks, centroid).
    mass : float
        Mass (kg), >= 0; default 0.
    inertia : float
        Moment of inertia about the centre of gravity (kg m^2), >= 0; default 0.
    cg : (float, float) or None
        Centre of gravity in the drawn configuration (m); default the centroid of the points.

    Raises
    ------
    InputError
        If the name is empty or ``"ground"``, there are no points, or the mass, inertia or
        centre of gravity is invalid.
    """

    name: str
    points: tuple[str, ...]
    mass: float = 0.0
    inertia: float = 0.0
    cg: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip():
            raise InputError("a link needs a name", key="name", value=self.name)
        if self.name == GROUND:
            raise InputError(
                '"ground" is the frame, not a moving link', key="name", value=self.name
            )
        object.__setattr__(self, "points", tuple(self.points))
        if not self.points:
            raise InputError("a link needs at least one point", key="points", value=[])
        object.__setattr__(self, "mass", _nonnegative("mass", self.mass, "a mass"))
        object.__setattr__(
            self, "inertia", _nonnegative("inertia", self.inertia, "a moment of inertia")
        )
        if self.cg is not None:
            object.__setattr__(self, "cg", _xy("cg", self.cg))


@dataclass(frozen=True)
class Joint:
    """A lower pair between two links (domain object).

    Parameters
    ----------
    name : str
        Unique name (used for the reactions).
    kind : str
        ``"revolute"`` or ``"prismatic"``.
    links : (str, str)
        (first, second): the reaction reported is the force of the first link on the second
        (seed 004's R_ij, the force of link i on link j). For a prismatic joint the guide is on
        the first link, the slider is the second.
    point : str
        The joint's point: a revolute's pin centre; a prismatic joint's slider point, which lies
        on the guide line in the drawn configuration.
    axis : float or None
        Prismatic only: direction of the guide in the drawn configuration (rad, counter-clockwise
        from x), fixed to the first link.
    journal_radius : float
        Revolute: pin (journal) radius r (m) for the friction circle rho = f r; default 0.
    friction : float
        Friction coefficient f (dimensionless, >= 0): a revolute's journal coefficient (seed
        004's f_v), a prismatic joint's Coulomb coefficient; default 0.

    Raises
    ------
    InputError
        If the name is empty, the kind unknown, the links not two different ones, the axis
        missing (prismatic) or given (revolute), or the radius or coefficient negative.
    """

    name: str
    kind: str
    links: tuple[str, str]
    point: str
    axis: float | None = None
    journal_radius: float = 0.0
    friction: float = 0.0

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name.strip():
            raise InputError("a joint needs a name", key="name", value=self.name)
        if self.kind not in JOINT_KINDS:
            raise InputError(
                f"expected one of {', '.join(JOINT_KINDS)}", key="type", value=self.kind
            )
        links = tuple(self.links)
        if len(links) != 2 or links[0] == links[1]:
            raise InputError("a joint connects two different links", key="links", value=list(links))
        object.__setattr__(self, "links", links)
        if self.kind == "prismatic":
            if self.axis is None:
                raise InputError("a prismatic joint needs the direction of its guide", key="axis")
            object.__setattr__(self, "axis", check_finite("axis", self.axis))
        elif self.axis is not None:
            raise InputError("only a prismatic joint has an axis", key="axis", value=self.axis)
        object.__setattr__(
            self,
            "journal_radius",
            _nonnegative("journal_radius", self.journal_radius, "a journal radius"),
        )
        object.__setattr__(
            self, "friction", _nonnegative("friction", self.friction, "a friction coefficient")
        )


@dataclass(frozen=True)
class Driver:
    """The input crank: a revolute joint to the ground, turned at a given speed.

    Parameters
    ----------
    joint : str
        The crank's revolute joint with the ground.
    point : str
        A point on the crank; the crank angle is the angle of the line joint -> point.
    zero : float
        Direction (rad, counter-clockwise from x) from which the crank angle is measured;
        default 0.
    speed : float
        Crank angular velocity (rad/s, counter-clockwise positive); default 1.
    acceleration : float
        Crank angular acceleration (rad/s^2); default 0.
    balancing_point : str or None
        Optional: balance the mechanism by a force at this crank point instead of a torque
        (seed 004's balancing force P_b); the driving torque is then its moment about the crank
        pivot.
    balancing_direction : float or None
        The balancing force's direction (rad); given with ``balancing_point``.
    balancing_relative : bool
        Whether ``balancing_direction`` is measured from the crank line (joint -> point) and
        turns with the crank (e.g. 90 deg: perpendicular to the crank), instead of from x.

    Raises
    ------
    InputError
        If an angle, speed or acceleration is not finite, or only one of the balancing point
        and direction is given.
    """

    joint: str
    point: str
    zero: float = 0.0
    speed: float = 1.0
    acceleration: float = 0.0
    balancing_point: str | None = None
    balancing_direction: float | None = None
    balancing_relative: bool = False

    def balancing_unit(self, crank_angle: ArrayLike) -> NDArray[np.float64]:
        """Unit vectors of the balancing force at crank angles.

        Parameters
        ----------
        crank_angle : array_like
            Crank angles (rad), N of them.

        Returns
        -------
        numpy.ndarray
            (N, 2) unit vectors (dimensionless).

        Raises
        ------
        ValueError
            If the driver has no balancing force (a programming error).
        """
        if self.balancing_direction is None:
            raise ValueError("the driver balances with a torque, not a force")
        theta = np.atleast_1d(np.asarray(crank_angle, dtype=float))
        ang = self.balancing_direction + (
            self.zero + theta if self.balancing_relative else np.zeros_like(theta)
        )
        return np.stack([np.cos(ang), np.sin(ang)], axis=1)

    def __post_init__(self) -> None:
        object.__setattr__(self, "zero", check_finite("zero", self.zero))
        object.__setattr__(self, "speed", check_finite("speed", self.speed))
        object.__setattr__(self, "acceleration", check_finite("acceleration", self.acceleration))
        if (self.balancing_point is None) != (self.balancing_direction is None):
            raise InputError(
                "a balancing force needs both its point and its direction",
                key="balancing_point" if self.balancing_point is None else "balancing_direction",
            )
        if self.balancing_direction is not None:
            object.__setattr__(
                self,
                "balancing_direction",
                check_finite("balancing_direction", self.balancing_direction),
            )


@dataclass(frozen=True)
class Force:
    """An external force on a link at one of its points.

    Either a fixed ``force`` (Fx, Fy) in N in the ground frame, or a ``resistance`` (N): a force
    of that magnitude opposing the point's velocity (a production resistance), acting only while
    the point moves with a positive component along ``working_direction`` (rad) when given.

    Parameters
    ----------
    link : str
        The moving link it acts on.
    point : str
        The point of that link it acts at.
    force : (float, float) or None
        A fixed force (Fx, Fy) (N), ground frame.
    resistance : float or None
        Or the magnitude of a resistance (N), >= 0.
    working_direction : float or None
        With a resistance: the direction (rad) the point must move along for it to act.

    Raises
    ------
    InputError
        If not exactly one of ``force`` and ``resistance`` is given, or a value is invalid.
    """

    link: str
    point: str
    force: tuple[float, float] | None = None
    resistance: float | None = None
    working_direction: float | None = None

    def __post_init__(self) -> None:
        if (self.force is None) == (self.resistance is None):
            raise InputError("give either force or resistance", key="force")
        if self.force is not None:
            object.__setattr__(self, "force", _xy("force", self.force))
        if self.resistance is not None:
            object.__setattr__(
                self, "resistance", _nonnegative("resistance", self.resistance, "a resistance")
            )
        if self.working_direction is not None:
            if self.resistance is None:
                raise InputError(
                    "working_direction applies to a resistance only", key="working_direction"
                )
            object.__setattr__(
                self,
                "working_direction",
                check_finite("working_direction", self.working_direction),
            )


@dataclass(frozen=True)
class Torque:
    """An external couple on a link: a fixed ``torque`` (N m, counter-clockwise positive) or a
    ``resistance`` (N m) opposing the link's angular velocity.

    Parameters
    ----------
    link : str
        The moving link it acts on.
    torque : float or None
        A fixed couple (N m, counter-clockwise positive).
    resistance : float or None
        Or the magnitude of a resisting couple (N m), >= 0.

    Raises
    ------
    InputError
        If not exactly one of ``torque`` and ``resistance`` is given, or a value is invalid.
    """

    link: str
    torque: float | None = None
    resistance: float | None = None

    def __post_init__(self) -> None:
        if (self.torque is None) == (self.resistance is None):
            raise InputError("give either torque or resistance", key="torque")
        if self.torque is not None:
            object.__setattr__(self, "torque", check_finite("torque", self.torque))
        if self.resistance is not None:
            object.__setattr__(
                self, "resistance", _nonnegative("resistance", self.resistance, "a resistance")
            )


@dataclass(frozen=True)
class LinkGroup:
    """A statically determinate link group (Assur group) of seed 004: links, joints, class.

    Parameters
    ----------
    links : tuple of str
        The group's links.
    joints : tuple of str
        Its joints (to each other and to the rest of the mechanism).
    kind : str
        ``"driver"``, ``"RRR dyad"``, ``"RRP dyad"``, ..., or ``"group of n links"``.
    """

    links: tuple[str, ...]
    joints: tuple[str, ...]
    kind: str


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
        points = tuple((str(n), _xy(f'point "{n}"', xy)) for n, xy in pts)
        object.__setattr__(self, "points", points)
        object.__setattr__(self, "links", tuple(self.links))
        object.__setattr__(self, "joints", tuple(self.joints))
        object.__setattr__(self, "forces", tuple(self.forces))
        object.__setattr__(self, "torques", tuple(self.torques))
        object.__setattr__(self, "gravity", _xy("gravity", self.gravity))
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
    def _model(self) -> _Model:
        return _Model(self)

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
        """Positions, velocities and accelerations at crank angles (module docstring).

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


# ---- the numeric model -----------------------------------------------------------------------


def _rot(phi: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """cos, sin of rotation angles (arrays)."""
    return np.cos(phi), np.sin(phi)


def _apply(c: np.ndarray, s: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A(phi) v for arrays c, s of shape (N, k) and local vectors v of shape (k, 2)."""
    x = c * v[:, 0] - s * v[:, 1]
    y = s * v[:, 0] + c * v[:, 1]
    return x, y


def _guide_normal(joint: Joint) -> tuple[float, float]:
    """The unit normal of a prismatic joint's guide in the drawn configuration."""
    if joint.axis is None:  # Joint requires it of a prismatic joint
        raise ValueError(f"joint {joint.name!r} has no guide")
    return -math.sin(joint.axis), math.cos(joint.axis)


class _Locked(Exception):
    """The continuation cannot pass crank angle ``theta`` (a dead point); ``q`` is there."""

    def __init__(self, q, theta):
        super().__init__(theta)
        self.q, self.theta = q, theta


class _Model:
    """Index arrays and batched constraint functions of a Mechanism (internal)."""

    def __init__(self, mech: Mechanism) -> None:
        self.mech = mech
        names = list(mech.link_names)
        self.index = {GROUND: 0, **{n: i + 1 for i, n in enumerate(names)}}
        self.n = len(names)
        pm = mech.point_map
        cg = mech.cg_drawn
        self.g0 = np.vstack([np.zeros(2), *[cg[n] for n in names]])  # (n+1, 2), ground = origin

        def local(link_name: str, point: str) -> np.ndarray:
            return pm[point] - self.g0[self.index[link_name]]

        rev = [j for j in mech.joints if j.kind == "revolute"]
        pri = [j for j in mech.joints if j.kind == "prismatic"]
        self.rev_i = np.array([self.index[j.links[0]] for j in rev], dtype=int)
        self.rev_j = np.array([self.index[j.links[1]] for j in rev], dtype=int)
        self.rev_si = np.array([local(j.links[0], j.point) for j in rev]).reshape(-1, 2)
        self.rev_sj = np.array([local(j.links[1], j.point) for j in rev]).reshape(-1, 2)
        self.pri_i = np.array([self.index[j.links[0]] for j in pri], dtype=int)
        self.pri_j = np.array([self.index[j.links[1]] for j in pri], dtype=int)
        self.pri_si = np.array([local(j.links[0], j.point) for j in pri]).reshape(-1, 2)
        self.pri_sj = np.array([local(j.links[1], j.point) for j in pri]).reshape(-1, 2)
        self.pri_n = np.array([_guide_normal(j) for j in pri]).reshape(-1, 2)
        self.rev_names = [j.name for j in rev]
        self.pri_names = [j.name for j in pri]
        self.crank = self.index[mech.crank]
        self.m = 2 * len(rev) + 2 * len(pri) + 1
        self.nq = 3 * self.n
        self.q0 = np.concatenate([np.r_[self.g0[i], 0.0] for i in range(1, self.n + 1)])
        self.theta0 = mech.crank_angle_drawn
        self.scale = mech.length_scale
        # weights for norms: rotations count as arcs of the mechanism's size
        self.weights = np.tile([1.0, 1.0, self.scale], self.n)

    # q (N, nq) -> bodies (N, n+1, 3) with the ground first
    def bodies(self, q):
        q = np.asarray(q)
        out = np.zeros((q.shape[0], self.n + 1, 3), dtype=q.dtype)
        out[:, 1:, :] = q.reshape(q.shape[0], self.n, 3)
        out[:, 0, :2] = 0.0
        return out

    def constraints(self, q, theta):
        """Phi (N, m)."""
        b = self.bodies(q)
        parts = []
        if len(self.rev_i):
            bi, bj = b[:, self.rev_i], b[:, self.rev_j]
            xi, yi = _apply(*_rot(bi[..., 2]), self.rev_si)
            xj, yj = _apply(*_rot(bj[..., 2]), self.rev_sj)
            parts += [bi[..., 0] + xi - bj[..., 0] - xj, bi[..., 1] + yi - bj[..., 1] - yj]
        if len(self.pri_i):
            bi, bj = b[:, self.pri_i], b[:, self.pri_j]
            ci, si = _rot(bi[..., 2])
            nx, ny = _apply(ci, si, self.pri_n)
            xj, yj = _apply(*_rot(bj[..., 2]), self.pri_sj)
            ex, ey = bj[..., 0] + xj - bi[..., 0], bj[..., 1] + yj - bi[..., 1]
            const = np.sum(self.pri_n * self.pri_si, axis=1)
            parts += [bi[..., 2] - bj[..., 2], nx * ex + ny * ey - const]
        drive = b[:, self.crank, 2] - (np.asarray(theta) - self.theta0)
        return self._assemble(parts, drive)

    def _assemble(self, parts, drive):
        """Stack joint rows in the order: revolute (x, y) per joint, prismatic (angle, normal)
        per joint, then the driver."""
        cols = []
        nr, npr = len(self.rev_i), len(self.pri_i)
        if nr:
            px, py = parts[0], parts[1]
            cols.append(np.stack([px, py], axis=2).reshape(px.shape[0], 2 * nr))
        if npr:
            pa, pn = parts[-2], parts[-1]
            cols.append(np.stack([pa, pn], axis=2).reshape(pa.shape[0], 2 * npr))
        cols.append(drive[:, None])
        return np.concatenate(cols, axis=1)

    def jacobian(self, q):
        """Phi_q (N, m, nq)."""
        q = np.asarray(q)
        N = q.shape[0]
        b = self.bodies(q)
        jac = np.zeros((N, self.m, 3 * (self.n + 1)))
        nr = len(self.rev_i)
        rows = np.arange(nr)
        if nr:
            bi, bj = b[:, self.rev_i], b[:, self.rev_j]
            xi, yi = _apply(*_rot(bi[..., 2]), self.rev_si)
            xj, yj = _apply(*_rot(bj[..., 2]), self.rev_sj)
            rx, ry = 2 * rows, 2 * rows + 1
            ci, cj = 3 * self.rev_i, 3 * self.rev_j
            jac[:, rx, ci] += 1.0
            jac[:, ry, ci + 1] += 1.0
            jac[:, rx, ci + 2] += -yi  # B s = (-y, x) of A s
            jac[:, ry, ci + 2] += xi
            jac[:, rx, cj] -= 1.0
            jac[:, ry, cj + 1] -= 1.0
            jac[:, rx, cj + 2] -= -yj
            jac[:, ry, cj + 2] -= xj
        npr = len(self.pri_i)
        if npr:
            prow = np.arange(npr)
            ra, rn = 2 * nr + 2 * prow, 2 * nr + 2 * prow + 1
            bi, bj = b[:, self.pri_i], b[:, self.pri_j]
            ci_, si_ = _rot(bi[..., 2])
            nx, ny = _apply(ci_, si_, self.pri_n)
            xj, yj = _apply(*_rot(bj[..., 2]), self.pri_sj)
            ex, ey = bj[..., 0] + xj - bi[..., 0], bj[..., 1] + yj - bi[..., 1]
            ci, cj = 3 * self.pri_i, 3 * self.pri_j
            jac[:, ra, ci + 2] += 1.0
            jac[:, ra, cj + 2] -= 1.0
            jac[:, rn, ci] -= nx
            jac[:, rn, ci + 1] -= ny
            jac[:, rn, ci + 2] += -ny * ex + nx * ey  # (B_i n') . e, B n = (-ny, nx)
            jac[:, rn, cj] += nx
            jac[:, rn, cj + 1] += ny
            jac[:, rn, cj + 2] += nx * -yj + ny * xj  # n . (B_j s_j)
        jac[:, self.m - 1, 3 * self.crank + 2] = 1.0
        return jac[:, :, 3:]  # drop the ground's columns

    def gamma(self, q, qp):
        """Right-hand side gamma (N, m) of Phi_q q'' = gamma for rates qp (driver row 0)."""
        b = self.bodies(q)
        v = self.bodies(qp)
        v[:, 0, :] = 0.0
        out = np.zeros((b.shape[0], self.m))
        nr = len(self.rev_i)
        if nr:
            bi, bj = b[:, self.rev_i], b[:, self.rev_j]
            wi, wj = v[:, self.rev_i, 2], v[:, self.rev_j, 2]
            xi, yi = _apply(*_rot(bi[..., 2]), self.rev_si)
            xj, yj = _apply(*_rot(bj[..., 2]), self.rev_sj)
            out[:, 0 : 2 * nr : 2] = xi * wi**2 - xj * wj**2
            out[:, 1 : 2 * nr : 2] = yi * wi**2 - yj * wj**2
        npr = len(self.pri_i)
        if npr:
            bi, bj = b[:, self.pri_i], b[:, self.pri_j]
            vi, vj = v[:, self.pri_i], v[:, self.pri_j]
            wi, wj = vi[..., 2], vj[..., 2]
            ci_, si_ = _rot(bi[..., 2])
            nx, ny = _apply(ci_, si_, self.pri_n)
            xj, yj = _apply(*_rot(bj[..., 2]), self.pri_sj)
            ex, ey = bj[..., 0] + xj - bi[..., 0], bj[..., 1] + yj - bi[..., 1]
            dex = vj[..., 0] - yj * wj - vi[..., 0]
            dey = vj[..., 1] + xj * wj - vi[..., 1]
            ndot_x, ndot_y = -ny * wi, nx * wi
            val = (nx * ex + ny * ey) * wi**2 - 2.0 * (ndot_x * dex + ndot_y * dey)
            val += (nx * xj + ny * yj) * wj**2
            out[:, 2 * nr + 1 : 2 * nr + 2 * npr : 2] = val
        return out

    # ---- solvers ------------------------------------------------------------------------------
    def _newton(self, q, theta, max_iter=12):
        """Newton-Raphson at one crank angle; returns (q, converged, iterations)."""
        tol = 1e-14 * self.scale
        for it in range(max_iter):
            phi = self.constraints(q[None, :], np.array([theta]))[0]
            if np.max(np.abs(phi)) <= tol:
                return q, True, it
            jac = self.jacobian(q[None, :])[0]
            try:
                dq = np.linalg.solve(jac, -phi)
            except np.linalg.LinAlgError:
                return q, False, it
            q = q + dq
            if not np.all(np.isfinite(q)):
                return q, False, it
        phi = self.constraints(q[None, :], np.array([theta]))[0]
        return q, bool(np.max(np.abs(phi)) <= tol), max_iter

    def _unit_rates(self, q):
        """q' and q'' per unit crank speed at one configuration (for the predictor), from one
        inverse of the Jacobian."""
        inv = np.linalg.inv(self.jacobian(q[None, :])[0])
        qp = inv[:, -1].copy()  # Phi_q q' = e_driver
        qpp = inv @ self.gamma(q[None, :], qp[None, :])[0]
        return qp, qpp

    def _march(self, q, theta, target, step0=_MAX_STEP):
        """Continue from (q, theta) to target; return q at target or raise InputError."""
        size = step0
        while theta != target:
            remaining = target - theta
            step = math.copysign(min(size, abs(remaining)), remaining)
            while True:
                try:
                    qp, qpp = self._unit_rates(q)
                except np.linalg.LinAlgError:
                    qp = qpp = np.zeros_like(q)
                pred = q + qp * step + 0.5 * qpp * step * step
                new_theta = target if step == remaining else theta + step
                new, ok, _it = self._newton(pred, new_theta)
                if ok:
                    correction = np.max(np.abs((new - pred) * self.weights))
                    motion = np.max(np.abs((pred - q) * self.weights))
                    if correction <= 0.25 * motion + 1e-9 * self.scale:
                        break
                step /= 2.0
                remaining = None  # a halved step never lands on the target exactly
                if abs(step) < _MIN_STEP:
                    raise _Locked(q, theta)
            q, theta = new, new_theta
            size = min(_MAX_STEP, 2.0 * abs(step))
        return q

    def _dead_point(self, q: np.ndarray, theta: float, target: float) -> InputError:
        jac = self.jacobian(q[None, :])[0]
        cond = np.linalg.cond(jac)
        where = (
            f"the mechanism locks at crank angle {math.degrees(theta):.6g} deg, a dead point "
            "(links in line)"
            if cond > 1e3
            else f"the position solver stopped at crank angle {math.degrees(theta):.6g} deg"
        )
        return InputError(
            f"the links cannot be assembled at crank angle {math.degrees(target):.6g} deg: "
            f"moving from the drawn position ({math.degrees(self.theta0):.6g} deg) on its "
            f"branch, {where}",
            file=self.mech.source,
        )

    def _anchors(self, start: float, lo: float, hi: float) -> tuple[np.ndarray, np.ndarray]:
        """Continuation anchors every <= _MAX_STEP from start up to hi and down to lo."""
        up = np.linspace(start, hi, max(math.ceil((hi - start) / _MAX_STEP), 0) + 1)
        down = np.linspace(start, lo, max(math.ceil((start - lo) / _MAX_STEP), 0) + 1)
        return up[1:] if hi > start else up[:0], down[1:] if lo < start else down[:0]

    def solve_positions(self, theta):
        """q (N, nq) at crank angles theta (rad), continued from the drawn configuration.

        The branch is followed by marching (Newton-Raphson with a second-order predictor and
        step halving) through anchors at most 3 deg apart, up from the drawn angle to the
        largest requested angle and down to the smallest (angles are not reduced modulo a turn:
        0 and 360 deg are reached from opposite sides). Every requested angle is then solved in
        one batched Newton iteration from its nearest anchor's Taylor predictor, and accepted
        under the same branch test; the few that fail it are marched to one by one.
        """
        theta = np.asarray(theta, dtype=float)
        lo, hi = float(theta.min()), float(theta.max())
        start, q_start = self.theta0, self.q0.copy()
        if not lo <= start <= hi:  # begin at the drawn position moved by whole turns
            shifted = start + round(((lo + hi) / 2 - start) / TWO_PI) * TWO_PI
            q_start = self._march_or_raise(q_start, start, shifted, theta)
            start = shifted
        up, down = self._anchors(start, lo, hi)
        anchor_t, anchor_q = [start], [q_start]
        for seq in (up, down):
            q, t = q_start, start
            for target in seq:
                q = self._march_or_raise(q, t, float(target), theta)
                t = float(target)
                anchor_t.append(t)
                anchor_q.append(q)
        anchors_t = np.array(anchor_t)
        anchors_q = np.array(anchor_q)
        # batched Newton from the nearest anchor
        nearest = np.argmin(np.abs(theta[:, None] - anchors_t[None, :]), axis=1)
        q_a, t_a = anchors_q[nearest], anchors_t[nearest]
        qp, qpp = self._batch_unit_rates(q_a)
        dt = (theta - t_a)[:, None]
        pred = q_a + qp * dt + 0.5 * qpp * dt * dt
        q, ok = self._batch_newton(pred, theta)
        correction = np.max(np.abs((q - pred) * self.weights), axis=1)
        motion = np.max(np.abs((pred - q_a) * self.weights), axis=1)
        ok &= correction <= 0.25 * motion + 1e-9 * self.scale
        for i in np.flatnonzero(~ok):
            q[i] = self._march_or_raise(q_a[i], float(t_a[i]), float(theta[i]), theta)
        return q

    def _march_or_raise(self, q, theta, target, requested):
        try:
            return self._march(q, theta, target)
        except _Locked as lock:
            # name the first requested angle beyond the lock, in the direction of the march
            beyond = requested[(requested - lock.theta) * (target - theta) > 0]
            first = beyond[np.argmin(np.abs(beyond - lock.theta))] if beyond.size else target
            raise self._dead_point(lock.q, lock.theta, float(first)) from None

    def _batch_unit_rates(self, q):
        """q', q'' (N, nq) for the predictors, block by block from one LU factorisation of the
        Jacobian each; zero at singular positions."""
        qp = np.zeros_like(q)
        qpp = np.zeros_like(q)
        for sl in _blocks(q.shape[0], _BLOCK):
            fact, a, b = self._block_rates(q[sl])
            a[fact.singular] = 0.0
            b[fact.singular] = 0.0
            qp[sl], qpp[sl] = a, b
        return qp, qpp

    def _block_rates(self, q):
        """(LU factors of Phi_q, q', q'') at positions q (B, nq): one factorisation for both
        right-hand sides, Phi_q q' = e_driver and Phi_q q'' = gamma(q, q')."""
        fact = lu_factor(self.jacobian(q))
        rhs = np.zeros((q.shape[0], self.m))
        rhs[:, -1] = 1.0
        qp = fact.solve(rhs)
        qpp = fact.solve(self.gamma(q, qp))
        return fact, qp, qpp

    def _batch_newton(self, q, theta, max_iter=8):
        """Newton-Raphson at all angles at once, in blocks of angles; returns (q, converged
        mask). A position whose Jacobian is singular (from its LU pivots) does not converge."""
        out = np.empty_like(q)
        ok = np.empty(q.shape[0], dtype=bool)
        for sl in _blocks(q.shape[0], _BLOCK):
            out[sl], ok[sl] = self._block_newton(q[sl], theta[sl], max_iter)
        return out, ok

    def _block_newton(self, q, theta, max_iter):
        tol = 1e-14 * self.scale
        failed = np.zeros(q.shape[0], dtype=bool)
        for _ in range(max_iter):
            phi = self.constraints(q, theta)
            ok = np.max(np.abs(phi), axis=1) <= tol
            if np.all(ok | failed):
                break
            fact = lu_factor(self.jacobian(q))
            failed |= fact.singular
            dq = fact.solve(-phi)
            dq[ok | failed] = 0.0
            q = q + dq
            bad = ~np.all(np.isfinite(q), axis=1)
            if np.any(bad):
                q[bad] = 0.0
                failed |= bad
        else:
            phi = self.constraints(q, theta)
            ok = np.max(np.abs(phi), axis=1) <= tol
        return q, ok & ~failed

    def rates(self, q, theta):
        """Unit-speed rates q' and q'' (N, nq), batched in blocks of angles, one LU
        factorisation of the Jacobian per position for both; raises InputError at singular
        positions (a pivot below 1e-10 of its column, :mod:`.linsolve`)."""
        qp = np.empty_like(q)
        qpp = np.empty_like(q)
        for sl in _blocks(q.shape[0], _BLOCK):
            fact, qp[sl], qpp[sl] = self._block_rates(q[sl])
            if np.any(fact.singular):
                i = sl.start + int(np.argmax(fact.singular))
                raise self._singular(theta[i])
        return qp, qpp

    def _singular(self, theta: float) -> InputError:
        return InputError(
            f"the constraint Jacobian is singular at crank angle "
            f"{math.degrees(theta):.6g} deg (a dead point or change point: links in "
            "line); velocities are indeterminate there",
            file=self.mech.source,
        )

    # ---- the solution: closed form where the link groups allow it ------------------------------
    @cached_property
    def closed(self):
        """The closed-form plan (:mod:`.dyads`), or None when a group has none."""
        from crankdyn.linkage.dyads import closed_form

        return closed_form(self.mech, self)

    def solve(
        self, theta: np.ndarray, method: str = "auto"
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """q, q', q'' (N, nq) at crank angles theta (rad).

        ``"auto"``: in closed form (:mod:`.dyads`) when every link group is a dyad with one and
        every position on the path from the drawn angle is regular; otherwise, and with
        ``"newton"``, by the general solver (:meth:`solve_positions`, :meth:`rates`), which
        also reports dead points and singular positions.
        """
        theta = np.asarray(theta, dtype=float)
        if (
            method == "auto"
            and theta.size
            and self.closed is not None
            and np.all(np.isfinite(theta))
        ):
            from crankdyn.linkage.dyads import NoClosedForm

            try:
                return self._solve_closed(theta)
            except NoClosedForm:
                pass
        q = self.solve_positions(theta)
        qp, qpp = self.rates(q, theta)
        return q, qp, qpp

    def _path(self, theta):
        """The path of crank angles the closed form is continued along: the requested angles
        in increasing order, the drawn angle, and anchors in every gap wider than 3 deg (the
        general solver's continuation step). Returns (angles, source) with source the index of
        the requested angle, -1 for an anchor, -2 for the drawn angle."""
        n = theta.shape[0]
        if n > 1 and (theta[1:] < theta[:-1]).any():
            order = np.argsort(theta, kind="stable")
            ts = theta[order]
        else:  # already in order (the common case): no sort, no gather
            order = np.arange(n)
            ts = theta
        k0 = int(np.searchsorted(ts, self.theta0))
        pt = np.concatenate((ts[:k0], [self.theta0], ts[k0:]))
        src = np.concatenate((order[:k0], [-2], order[k0:]))
        gaps = pt[1:] - pt[:-1]
        # a gap needs anchors when gap / _MAX_STEP > 1, i.e. (the division being monotonic and
        # exact at 1) when the gap exceeds _MAX_STEP: one reduction in the common case of none
        if gaps.max() > _MAX_STEP:
            need = np.maximum(np.ceil(gaps / _MAX_STEP).astype(int) - 1, 0)
            counts = np.append(need + 1, 1)
            first = np.cumsum(counts) - counts
            j = np.arange(int(counts.sum())) - np.repeat(first, counts)
            step = np.repeat(np.append(gaps / (need + 1), 0.0), counts)
            pt = np.repeat(pt, counts) + j * step
            src = np.where(j == 0, np.repeat(src, counts), -1)
        return pt, src

    def _solve_closed(self, theta):
        """The closed form at the requested angles, continued along the path from the drawn
        angle (:meth:`_path`), block by block.

        The rotations of the dyad links are continued from sample to sample along the path:
        the whole turns added to a wrapped increment are those that bring it nearest the
        increment predicted from the rates (the corrected trapezoidal rule,
        h (phi'_0 + phi'_1)/2 + h^2 (phi''_0 - phi''_1)/12), and every step must then agree with
        that prediction as the general solver's steps must (deviation at most a quarter of the
        step's motion, here the crank's rotation); the drawn angle has rotation 0. A predicted
        rotation above 90 deg in one step (a link far faster than the crank, near a dead point),
        a step that does not agree (an assembly gap or a branch change between two samples) and
        a dyad whose determinant changes sign or nears zero (:mod:`.dyads`) raise NoClosedForm.
        Each block of the path is one gather of its rotations in path order (with the last
        sample of the block before it) and one test of all its steps (:func:`_turns`).
        Returns (q, q', q''), each (N, nq), transposed views of one (3, nq, N + anchors)
        array.
        """
        cf = self.closed
        n = theta.shape[0]
        pt, src = self._path(theta)
        extra = src < 0
        n_extra = int(np.count_nonzero(extra))
        # the other path angles (the drawn one, anchors) are solved with the requested ones,
        # unless there are many (a few requested angles far from the drawn one): then block by
        # block, so that memory stays bounded
        inline = n_extra <= 8 * _PATH_BLOCK
        every = np.concatenate([theta, pt[extra]]) if inline else theta
        whole = np.empty((3, self.nq, every.shape[0]))
        for sl in _blocks(every.shape[0], _PATH_BLOCK):
            cf.evaluate(every[sl], out=whole[:, :, sl])
        if cf.rotation_rows is None:  # no rotation to continue (the dyads checked themselves)
            out = whole[:, :, :n]
            return out[0].T, out[1].T, out[2].T
        rotations = whole[:, cf.rotation_rows, :]  # (3, links, ...): phi, phi', phi''
        k = rotations.shape[1]
        if inline:  # the column of ``whole`` of every path angle
            column = src.copy()
            column[extra] = np.arange(n, n + n_extra)
        drawn = int(np.argmin(src))  # the drawn angle's place on the path (its source is -2)
        prev = None  # the last path angle of the block before: (3, k, 1) values, (k,) turns
        turns_drawn = None
        for sl in _blocks(pt.shape[0], _PATH_BLOCK):
            sb = src[sl]
            if inline:
                cols = column[sl]
                angles = _gather(rotations, cols)
            else:
                mine = sb >= 0
                cols = sb[mine]
                angles = np.empty((3, k, sb.shape[0]))
                angles[:, :, mine] = rotations[:, :, cols]
                if not np.all(mine):
                    angles[:, :, ~mine] = cf.evaluate(pt[sl][~mine])[:, cf.rotation_rows, :]
            if prev is None:  # the path's first angle: no turn
                turns = self._continue(pt[sl], angles, None)
                if turns is not None:
                    turns = np.concatenate([np.zeros((k, 1)), turns], axis=1)
            else:
                steps = pt[sl.start - 1 : sl.stop]
                turns = self._continue(steps, np.concatenate([prev[0], angles], axis=2), prev[1])
            # (a copy: ``angles`` may be a view of the rotations, which the turns then change)
            prev = (angles[:, :, -1:].copy(), np.zeros(k) if turns is None else turns[:, -1])
            if turns is not None and turns.any():
                rotations[0][:, cols] += TWO_PI * (turns if inline else turns[:, mine])
            if sl.start <= drawn < sl.stop and turns is not None:
                turns_drawn = turns[:, drawn - sl.start]
        if turns_drawn is not None and turns_drawn.any():
            rotations[0] -= TWO_PI * turns_drawn[:, None]
        out = whole[:, :, :n]
        return out[0].T, out[1].T, out[2].T

    @staticmethod
    def _continue(t, angles, carry):
        """Whole turns (k, L) at the path angles t[1:] of wrapped rotations ``angles``
        (3, k, L + 1: values, first and second derivatives, along the path angles t, L >= 0),
        given the turns ``carry`` (k,) at t[0] (None: none); None when every turn is zero.
        Raises NoClosedForm where a step disagrees with its prediction
        (:meth:`_solve_closed`)."""
        jumps = _turns(t[1:] - t[:-1], angles[:, :, :-1], angles[:, :, 1:])
        if jumps is None:
            if carry is None or not carry.any():
                return None
            return np.broadcast_to(carry[:, None], (angles.shape[1], t.shape[0] - 1))
        turns = np.cumsum(jumps, axis=1)
        if carry is not None:
            turns += carry[:, None]
        return turns


def _gather(rotations, cols):
    """rotations[:, :, cols] (3, k, B) for a block of the path: its runs of consecutive
    columns (sorted requested angles around the drawn one) as one view or one concatenation of
    views, many short runs (anchors) by one gather (never a copy of all the rotations)."""
    starts = np.flatnonzero(cols[1:] - cols[:-1] != 1) + 1
    if starts.size > 8:
        return rotations[:, :, cols]
    bounds = [0, *starts.tolist(), cols.shape[0]]
    runs = [rotations[:, :, cols[i] : cols[i] + j - i] for i, j in itertools.pairwise(bounds)]
    return runs[0] if len(runs) == 1 else np.concatenate(runs, axis=2)


def _turns(h, lo, hi):
    """Whole turns added to each step lo -> hi of wrapped rotations (3, k, L each: values,
    first and second derivatives; steps h, rad, at most about :data:`_MAX_STEP` as on the
    path),
    None when there are none; raises NoClosedForm where a step disagrees with its prediction
    (:meth:`_Model._solve_closed`)."""
    from crankdyn.linkage.dyads import NoClosedForm

    if h.shape[0] == 0:
        return None
    pred = (0.5 * h) * (hi[1] + lo[1])
    pred += (h * h / 12.0) * (lo[2] - hi[2])
    # |pred| <= _MAX_TURN everywhere (NaN fails), by the two extremes of pred
    if not (pred.max() <= _MAX_TURN and pred.min() >= -_MAX_TURN):
        raise NoClosedForm("a rotation too fast to follow from one sample to the next")
    miss = hi[0] - lo[0]
    miss -= pred  # the step's deviation from its prediction, before whole turns
    # the general solver's test, with the crank's own rotation as the step's motion (every
    # coordinate's deviation within a quarter of it)
    tol = 0.25 * np.abs(h) + 1e-9
    if (np.abs(miss).max(axis=0) <= tol).all():  # within a quarter step (<= 0.8 deg): far
        return None  # from half a turn, so no whole turn (rint gives 0) and the test passes
    jumps = np.rint(miss * (-1.0 / TWO_PI))
    if not jumps.any():
        raise NoClosedForm("a step along the path disagrees with its prediction")
    miss += TWO_PI * jumps
    if not (np.abs(miss) <= tol).all():
        raise NoClosedForm("a step along the path disagrees with its prediction")
    return jumps


def _blocks(n: int, size: int) -> list[slice]:
    """Slices of at most ``size`` covering range(n)."""
    return [slice(i, min(i + size, n)) for i in range(0, n, size)]


# ---- motion result ---------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class MechanismMotion:
    """Motion of a mechanism at a set of crank angles (SI arrays; N positions).

    ``q``, ``qp``, ``qpp`` hold (x_G, y_G, phi) of every moving link and their derivatives with
    respect to the crank angle (per unit crank speed); time derivatives are
    q_dot = omega q' and q_ddot = omega^2 q'' + alpha q'. Made by :meth:`Mechanism.motion`.

    Parameters
    ----------
    mechanism : Mechanism
        The mechanism.
    crank_angle : numpy.ndarray
        (N,) crank angles (rad).
    speed : float
        Crank speed omega (rad/s).
    acceleration : float
        Crank angular acceleration alpha (rad/s^2).
    q : numpy.ndarray
        (N, 3n) x_G (m), y_G (m), phi (rad, from the drawn configuration) of every moving link.
    qp, qpp : numpy.ndarray
        (N, 3n) first and second derivatives of q with respect to the crank angle (m/rad and
        m/rad^2; dimensionless and 1/rad for the rotations).
    """

    mechanism: Mechanism
    crank_angle: NDArray[np.float64]
    speed: float
    acceleration: float
    q: NDArray[np.float64]
    qp: NDArray[np.float64]
    qpp: NDArray[np.float64]

    @property
    def qd(self) -> NDArray[np.float64]:
        """Time derivative of q (N, nq)."""
        return self.speed * self.qp

    @property
    def qdd(self) -> NDArray[np.float64]:
        """Second time derivative of q (N, nq)."""
        return self.speed**2 * self.qpp + self.acceleration * self.qp

    def _slot(self, link: str) -> int:
        return 3 * (self.mechanism._model.index[link] - 1)

    def link_state(self, link: str, which: str = "q") -> NDArray[np.float64]:
        """The coordinates of a moving link, or their derivatives.

        Parameters
        ----------
        link : str
            The moving link.
        which : str
            ``"q"`` (default; m, m, rad), ``"qd"`` (m/s, rad/s), ``"qdd"`` (m/s^2, rad/s^2),
            ``"qp"`` or ``"qpp"`` (per unit crank speed).

        Returns
        -------
        numpy.ndarray
            (N, 3) x_G, y_G, phi or their rates.
        """
        k = self._slot(link)
        return getattr(self, which)[:, k : k + 3]

    def link_angle(self, link: str) -> NDArray[np.float64]:
        """Absolute angle of a link.

        Parameters
        ----------
        link : str
            The moving link.

        Returns
        -------
        numpy.ndarray
            (N,) the drawn angle of the line from its first to its second point (0 for a
            one-point link) plus its rotation (rad).
        """
        mech = self.mechanism
        pts = mech.link(link).points
        base = 0.0
        if len(pts) >= 2:
            pm = mech.point_map
            v = pm[pts[1]] - pm[pts[0]]
            base = math.atan2(v[1], v[0])
        return base + self.link_state(link)[:, 2]

    def point(self, name: str, link: str | None = None, which: str = "q") -> NDArray[np.float64]:
        """Position, velocity or acceleration of a named point.

        Parameters
        ----------
        name : str
            The point.
        link : str or None
            The link that carries it (default its owner, :attr:`Mechanism.point_owner`).
        which : str
            ``"q"`` position (m, default), ``"qd"`` velocity (m/s), ``"qdd"`` acceleration
            (m/s^2), or the unit-speed coefficients ``"qp"``, ``"qpp"``.

        Returns
        -------
        numpy.ndarray
            (N, 2) x, y.
        """
        mech = self.mechanism
        link = link or mech.point_owner[name]
        n = self.crank_angle.shape[0]
        if link == GROUND:
            p = mech.point_map[name]
            return np.tile(p, (n, 1)) if which == "q" else np.zeros((n, 2))
        s = mech.point_map[name] - mech.cg_drawn[link]
        return self.body_point(link, s, which)

    def body_point(self, link: str, s: ArrayLike, which: str = "q") -> NDArray[np.float64]:
        """Kinematics of a point given by its drawn offset from the link's centre of gravity.

        Parameters
        ----------
        link : str
            The moving link.
        s : array_like
            (2,) the point's offset from the centre of gravity in the drawn configuration (m).
        which : str
            As :meth:`point`.

        Returns
        -------
        numpy.ndarray
            (N, 2) position (m), velocity (m/s), acceleration (m/s^2) or the unit-speed
            coefficients.
        """
        s = np.asarray(s, dtype=float)
        q = self.link_state(link, "q")
        c, si = np.cos(q[:, 2]), np.sin(q[:, 2])
        ax, ay = c * s[0] - si * s[1], si * s[0] + c * s[1]  # A s
        if which == "q":
            return np.stack([q[:, 0] + ax, q[:, 1] + ay], axis=1)
        if which in ("qd", "qp"):
            v = self.link_state(link, which)
            return np.stack([v[:, 0] - v[:, 2] * ay, v[:, 1] + v[:, 2] * ax], axis=1)
        first = "qd" if which == "qdd" else "qp"
        v = self.link_state(link, first)
        acc = self.link_state(link, which)
        w, e = v[:, 2], acc[:, 2]
        return np.stack([acc[:, 0] - e * ay - w * w * ax, acc[:, 1] + e * ax - w * w * ay], axis=1)

    def all_points(self, which: str = "q") -> dict[str, NDArray[np.float64]]:
        """Every named point's kinematics.

        Parameters
        ----------
        which : str
            As :meth:`point`.

        Returns
        -------
        dict of str to numpy.ndarray
            {point: (N, 2)} in the unit of ``which``.
        """
        return {n: self.point(n, which=which) for n, _xy in self.mechanism.points}

    def angular_velocity(self, link: str) -> NDArray[np.float64]:
        """Angular velocity of a link.

        Parameters
        ----------
        link : str
            The moving link.

        Returns
        -------
        numpy.ndarray
            (N,) omega (rad/s, counter-clockwise positive).
        """
        return self.link_state(link, "qd")[:, 2]

    def angular_acceleration(self, link: str) -> NDArray[np.float64]:
        """Angular acceleration of a link.

        Parameters
        ----------
        link : str
            The moving link.

        Returns
        -------
        numpy.ndarray
            (N,) alpha (rad/s^2).
        """
        return self.link_state(link, "qdd")[:, 2]


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


# ---- analysis result ---------------------------------------------------------------------------


@dataclass(frozen=True)
class LinkageKinematicsResult(Result):
    """Motion of every link and point over the crank angles (SI; angles exported in deg;
    :func:`linkage_kinematics`).

    Parameters
    ----------
    motion : MechanismMotion or None
        The motion behind the arrays (not exported), for the plot.
    """

    title = "Linkage kinematics"
    mechanism_name: str = scalar("mechanism", "Mechanism", "")
    crank_speed: float = scalar("crank_speed_rad_s", "Crank speed", "rad/s")
    crank_acceleration: float = scalar("crank_acceleration_rad_s2", "Crank acceleration", "rad/s²")
    degrees_of_freedom: int = scalar("degrees_of_freedom", "Degrees of freedom", "")
    link_groups: tuple = scalar("link_groups", "Link groups (force-analysis order)", "")
    crank_angle: NDArray[np.float64] = column("crank_angle_deg", "Crank angle", "deg", DEG)
    link_angle: dict = column("link_angle_deg", "Angle", "deg", DEG)
    link_angular_velocity: dict = column("link_angular_velocity_rad_s", "ω", "rad/s")
    link_angular_acceleration: dict = column("link_angular_acceleration_rad_s2", "α", "rad/s²")
    point_position: dict = column("point_position_m", "Position", "m")
    point_velocity: dict = column("point_velocity_m_s", "Velocity", "m/s")
    point_acceleration: dict = column("point_acceleration_m_s2", "Acceleration", "m/s²")
    motion: MechanismMotion | None = field(default=None, repr=False)

    def plot(self, fig: Figure | None = None) -> Figure:
        """Paths (coupler curves) of the points with the mechanism drawn.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.

        Raises
        ------
        ValueError
            If the result holds no motion.
        """
        if self.motion is None:
            raise ValueError("this result holds no motion to draw")
        from crankdyn.plots.linkage import plot_paths

        return plot_paths(self.motion, fig=fig)


def linkage_kinematics(motion: MechanismMotion) -> LinkageKinematicsResult:
    """The kinematics of a mechanism's motion as a result object.

    Parameters
    ----------
    motion : MechanismMotion
        The motion (:meth:`Mechanism.motion`).

    Returns
    -------
    LinkageKinematicsResult
        Link angles (rad), angular velocities (rad/s) and accelerations (rad/s^2), and the
        positions (m), velocities (m/s) and accelerations (m/s^2) of the moving points.

    Examples
    --------
    >>> mech = Mechanism.example("fourbar-seed004")
    >>> k = linkage_kinematics(mech.motion(np.radians([0.0, 90.0])))
    >>> sorted(k.link_angle)
    ['coupler', 'crank', 'rocker']
    """
    mech = motion.mechanism
    moving = [n for n, _xy in mech.points if mech.point_owner[n] != GROUND]

    def xy(arr: np.ndarray) -> dict[str, NDArray[np.float64]]:
        return {"x": freeze(arr[:, 0]), "y": freeze(arr[:, 1])}

    groups = tuple(f"{g.kind}: {'-'.join(g.links)}" for g in mech.link_groups())
    return LinkageKinematicsResult(
        mechanism_name=mech.name,
        crank_speed=motion.speed,
        crank_acceleration=motion.acceleration,
        degrees_of_freedom=mech.degrees_of_freedom,
        link_groups=groups,
        crank_angle=freeze(motion.crank_angle),
        link_angle={n: freeze(motion.link_angle(n)) for n in mech.link_names},
        link_angular_velocity={n: freeze(motion.angular_velocity(n)) for n in mech.link_names},
        link_angular_acceleration={
            n: freeze(motion.angular_acceleration(n)) for n in mech.link_names
        },
        point_position={n: xy(motion.point(n)) for n in moving},
        point_velocity={n: xy(motion.point(n, which="qd")) for n in moving},
        point_acceleration={n: xy(motion.point(n, which="qdd")) for n in moving},
        motion=motion,
    )
