"""Joint geometry shared by the kinetostatic matrix method (:mod:`crankdyn.linkage.kinetostatics`)
and the friction iteration (:mod:`crankdyn.linkage.friction`): the direction of motion, moment
arms, the point and guide of a joint, and the driving torque from the last unknown (seed 004)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from crankdyn.linkage.elements import GROUND, Joint
from crankdyn.linkage.motion import MechanismMotion

__all__ = ["cross_arm", "driving_torque_of", "joint_geometry", "sign_of_speed"]


def sign_of_speed(speed: float) -> float:
    """Direction of motion for velocity-dependent loads.

    That of the crank; counter-clockwise when the crank stands still (a quasi-static analysis).

    Parameters
    ----------
    speed : float
        Crank speed (rad/s).

    Returns
    -------
    float
        -1.0 or 1.0.
    """
    return -1.0 if speed < 0.0 else 1.0


def cross_arm(arm: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Moment coefficients of a force's components about G, seed 004 eq. (1).

    M_G = (x - x_G) F_y - (y - y_G) F_x (:mod:`crankdyn.linkage.kinetostatics`).

    Parameters
    ----------
    arm : numpy.ndarray
        (..., 2) offset r - G of the force's point from G (m).

    Returns
    -------
    of_fx, of_fy : numpy.ndarray
        The moments per unit F_x and per unit F_y (m), shape (...).
    """
    return -arm[..., 1], arm[..., 0]


def joint_geometry(
    motion: MechanismMotion, joint: Joint
) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
    """The current point of a joint and, for a prismatic joint, its guide's directions.

    Parameters
    ----------
    motion : crankdyn.linkage.motion.MechanismMotion
        The mechanism's motion (N positions).
    joint : crankdyn.linkage.elements.Joint
        The joint.

    Returns
    -------
    point : numpy.ndarray
        (N, 2) the joint's point (m).
    normal, direction : numpy.ndarray or None
        (N, 2) unit normal and direction of a prismatic joint's guide (dimensionless); None for
        a revolute joint.
    """
    r = motion.point(joint.point, link=joint.links[1])
    if joint.kind == "revolute":
        return r, None, None
    first = joint.links[0]
    rot = 0.0 if first == GROUND else motion.link_state(first)[:, 2]
    ang = (joint.axis or 0.0) + rot  # a prismatic joint has its axis (Joint checks it)
    t = np.stack(np.broadcast_arrays(np.cos(ang), np.sin(ang)), axis=-1).reshape(-1, 2)
    t = np.broadcast_to(t, r.shape)
    nrm = np.stack([-t[:, 1], t[:, 0]], axis=1)
    return r, nrm, t


def driving_torque_of(
    motion: MechanismMotion, R: np.ndarray
) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """The driving torque from the last unknown of the reactions {R} (seed 004).

    Parameters
    ----------
    motion : crankdyn.linkage.motion.MechanismMotion
        The mechanism's motion.
    R : numpy.ndarray
        (N, 3n) reactions, the driving torque (N m) or balancing force (N) last.

    Returns
    -------
    torque : numpy.ndarray
        (N,) driving torque (N m).
    force : numpy.ndarray or None
        (N,) the balancing force (N), or None when the driver balances with a torque.
    """
    mech = motion.mechanism
    d = mech.driver
    last = R[:, -1]
    if d.balancing_point is None:
        return last, None
    pivot = motion.point(mech.joint(d.joint).point, link=mech.crank)
    r = motion.point(d.balancing_point, link=mech.crank)
    u = d.balancing_unit(motion.crank_angle)
    arm = r - pivot
    return last * (arm[:, 0] * u[:, 1] - arm[:, 1] * u[:, 0]), last
