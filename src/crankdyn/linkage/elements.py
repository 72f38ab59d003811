"""The parts of a planar mechanism: links, revolute and prismatic joints, the crank driver,
external forces and couples, link groups; the mobility of a mechanism (domain objects and
numeric core of :mod:`crankdyn.linkage.planar`).

The mechanism has F = 3n - 2 p_l degrees of freedom (Gruebler-Chebyshev, seed 004: each lower
pair removes two); crankdyn needs F = 1 so that the driver closes the system (3n equations).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.crank.geometry import check_finite
from crankdyn.errors import InputError

__all__ = [
    "GROUND",
    "JOINT_KINDS",
    "Driver",
    "Force",
    "Joint",
    "Link",
    "LinkGroup",
    "Torque",
    "degrees_of_freedom",
    "is_statically_determinate",
]

GROUND = "ground"
"""The name of the frame (ground) link."""

JOINT_KINDS = ("revolute", "prismatic")
"""The lower pairs crankdyn models."""


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


def check_xy(name: str, value: Any) -> tuple[float, float]:  # Any: the user's value, as given
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
            object.__setattr__(self, "cg", check_xy("cg", self.cg))


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
            object.__setattr__(self, "force", check_xy("force", self.force))
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
