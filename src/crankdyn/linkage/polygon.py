"""Force polygons of a mechanism's link groups from the analytic kinetostatic solution
(analysis; seed 004 sec. 2).

Seed 004 sec. 2 ("用图解法作机构的动态静力分析", the reciprocating conveyor 往复式运输机) finds the
joint reactions graphically: the inertia forces are added to each link as external loads
(D'Alembert), the mechanism is split into statically determinate link groups, and for each group,
starting with the one farthest from the crank (the conveyor's group 4-5, then 2-3), the vector
equation of its forces is closed as a polygon drawn to scale, e.g. for the slider 5::

    P_r + G_5 + F_I5 + R_45 + R_65 = 0,

whose closing sides give the unknown reactions. Here the reactions come from the matrix method
(:func:`crankdyn.linkage.kinetostatics.kinetostatics`); this module lays every group's forces
head to tail in the seed's order (known loads first, then the reactions from the other links and
the ground) so that the polygon can be drawn, and reports how well it closes (the identity the
graphical method rests on): every force on the group from outside it, the group's internal joints
cancelling. Each group's polygon is of forces only: the couples (inertia couples, the driving
torque, prismatic joints' couples) enter the moment equation and not the polygon.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError
from crankdyn.linkage.kinetostatics import KinetostaticsResult, known_loads

__all__ = ["ForcePolygon", "force_polygons"]


@dataclass(frozen=True, eq=False)
class ForcePolygon:
    """The forces on one link group at one position, in drawing order (module docstring).

    Parameters
    ----------
    group : str
        The group's kind and links (``"RRP dyad: link, slider"``).
    labels : tuple of str
        A label per force (``"weight of slider"``, ``"R guide (ground on slider)"``).
    forces : numpy.ndarray
        (k, 2) force vectors (N).
    known : numpy.ndarray
        (k,) True for the known loads (inertia, weight, applied), False for the reactions.
    """

    group: str
    labels: tuple[str, ...]
    forces: NDArray[np.float64]
    known: NDArray[np.bool_]

    @property
    def vertices(self) -> NDArray[np.float64]:
        """(k + 1, 2) the polygon's corners: 0, then the forces summed head to tail (N)."""
        return np.vstack([np.zeros(2), np.cumsum(self.forces, axis=0)])

    @property
    def closure(self) -> float:
        """|sum of the forces| (N): 0 for a group in equilibrium."""
        return float(np.hypot(*np.sum(self.forces, axis=0)))

    @property
    def scale(self) -> float:
        """The largest force's magnitude (N), for relative closure."""
        return float(np.max(np.hypot(self.forces[:, 0], self.forces[:, 1]), initial=0.0))


def force_polygons(result: KinetostaticsResult, index: int = 0) -> tuple[ForcePolygon, ...]:
    """The force polygon of every link group at one position (seed 004 sec. 2; module
    docstring).

    Parameters
    ----------
    result : crankdyn.linkage.kinetostatics.KinetostaticsResult
        The kinetostatic solution (joint forces in N) with its motion.
    index : int
        The position (index into the result's crank angles).

    Returns
    -------
    tuple of ForcePolygon
        One per link group, in the order of the force analysis (the driver last).

    Raises
    ------
    crankdyn.errors.InputError
        A position index outside the result (key ``index``).

    Examples
    --------
    The seed's conveyor at its drawn position: every group's polygon closes.

    >>> from crankdyn.linkage.kinetostatics import kinetostatics
    >>> from crankdyn.linkage.planar import Mechanism
    >>> mech = Mechanism.example("conveyor-seed004")
    >>> result = kinetostatics(mech.motion([mech.crank_angle_drawn]))
    >>> [(p.group, p.closure < 1e-9 * p.scale) for p in force_polygons(result)]
    [('RRP dyad: link, slider', True), ('RRR dyad: coupler, rocker', True), ('driver: crank', True)]
    """
    motion = result.motion
    assert motion is not None and result.joint_forces is not None  # kinetostatics keeps both
    count = motion.crank_angle.size
    if isinstance(index, bool) or not -count <= int(index) < count:
        raise InputError(f"expected a position from 0 to {count - 1}", key="index", value=index)
    i = int(index) % count
    mech = motion.mechanism
    loads = known_loads(motion)
    gx, gy = mech.gravity
    n = len(mech.links)
    out = []
    for group in mech.link_groups():
        members = set(group.links)
        labels: list[str] = []
        vectors: list[tuple[float, float]] = []
        known: list[bool] = []
        for k, link in enumerate(mech.links):
            if link.name not in members:
                continue
            px, py = loads.P[i, 3 * k], loads.P[i, 3 * k + 1]
            wx, wy = link.mass * gx, link.mass * gy
            if wx or wy:
                labels.append(f"weight of {link.name}")
                vectors.append((wx, wy))
                known.append(True)
            if abs(px - wx) + abs(py - wy) > 0.0:
                labels.append(f"inertia force of {link.name}")
                vectors.append((px - wx, py - wy))
                known.append(True)
        for f_index, f in enumerate(mech.forces):
            if f.link in members:
                col = 3 * n + 2 * f_index
                fx, fy = loads.P[i, col], loads.P[i, col + 1]
                if fx or fy:
                    labels.append(f"applied force on {f.link} at {f.point}")
                    vectors.append((fx, fy))
                    known.append(True)
        for joint in mech.joints:
            first, second = joint.links
            force = result.joint_forces[joint.name]
            fx, fy = force["x"][i], force["y"][i]
            if second in members and first not in members:
                labels.append(f"R {joint.name} ({first} on {second})")
                vectors.append((float(fx), float(fy)))
                known.append(False)
            elif first in members and second not in members:
                labels.append(f"R {joint.name} ({second} on {first})")
                vectors.append((-float(fx), -float(fy)))
                known.append(False)
        if group.kind == "driver" and result.balancing_force is not None:
            u = mech.driver.balancing_unit(motion.crank_angle[i : i + 1])[0]
            labels.append("balancing force")
            vectors.append(tuple(float(result.balancing_force[i]) * u))
            known.append(False)
        out.append(
            ForcePolygon(
                group=f"{group.kind}: {', '.join(group.links)}",
                labels=tuple(labels),
                forces=np.array(vectors, dtype=float).reshape(-1, 2),
                known=np.array(known, dtype=bool),
            )
        )
    return tuple(out)
