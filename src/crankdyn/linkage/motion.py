"""The motion of a planar mechanism at a set of crank angles, and the kinematics result of
every link and point (results of :mod:`crankdyn.linkage.planar`).

The coordinates q, their derivatives per unit crank speed q' and q'' and the crank's speed
omega and acceleration alpha give the velocities and accelerations q_dot = omega q' and
q_ddot = omega^2 q'' + alpha q' (:mod:`crankdyn.linkage.solver`; Nikravesh 1988, ch. 3-4).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import DEG
from crankdyn.linkage.elements import GROUND
from crankdyn.results import Result, column, freeze, scalar

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.linkage.planar import Mechanism

__all__ = ["LinkageKinematicsResult", "MechanismMotion", "linkage_kinematics"]


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
    >>> from crankdyn.linkage.planar import Mechanism
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
