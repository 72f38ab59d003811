"""Friction in the joints: friction circles and Coulomb friction, solved iteratively.

Seed 004 sec. 3.5 ("考虑摩擦时机构的力分析"): in a revolute joint of journal radius r and friction
coefficient f_v the total reaction is tangent to the friction circle of radius rho = f_v r, on
the side that makes its moment about the pin centre oppose the relative rotation; in a prismatic
joint the total reaction leans from the normal by the friction angle phi = arctan f against the
relative sliding. Equivalently, added to the frictionless equations of :mod:`.kinetostatics`:

- revolute joint between links i (first) and j (second) with reaction R (force of i on j): a
  friction couple -rho |R| sgn(omega_j - omega_i) on j and the opposite on i;
- prismatic joint with normal force N: a friction force -f |N| sgn(v_rel) t on the slider j at
  its point (t the guide direction, v_rel the slider's velocity relative to the guide along t)
  and the opposite on the guide link i. The couple of the prismatic reaction is carried by the
  guide without extra friction (a short slider's edge loads are not modelled).

The directions of relative motion come from the kinematics (per unit crank speed, times the sign
of the crank speed; a crank at rest is taken as about to turn counter-clockwise), the magnitudes
from the reactions, so the system is solved by fixed-point iteration
R_{k+1} = C^-1 (D P - F_friction(R_k)) from the frictionless solution, all positions at once
(one LU factorisation of C, reused by every step),
until the largest change is below 1e-12 of the largest reaction. Where a relative motion is at
rest (a rocker's reversal) its friction is taken as zero.

Instantaneous efficiency (the ratio of the ideal to the actual driving torque; seed 004,
Zhukovsky's principle with and without friction): eta = M_0 / M where both drive the crank
(M, M_0 > 0 for a counter-clockwise crank), eta = M / M_0 where the mechanism drives the crank
back (both negative), NaN where the two differ in sign (power passes through zero).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError
from crankdyn.linkage.elements import GROUND, Joint
from crankdyn.linkage.joints import cross_arm, driving_torque_of, joint_geometry, sign_of_speed
from crankdyn.linkage.motion import MechanismMotion
from crankdyn.linkage.planar import Mechanism

if TYPE_CHECKING:  # pragma: no cover
    from crankdyn.linkage.kinetostatics import KinetostaticSystem

# (kind, joint, column of its reactions, sign of the relative motion, point, guide direction)
_Term = tuple[str, Joint, int, np.ndarray, np.ndarray | None, np.ndarray | None]

__all__ = ["efficiency", "has_friction", "solve_with_friction"]

_MAX_ITER = 200


def has_friction(mech: Mechanism) -> bool:
    """Whether any joint has friction.

    Parameters
    ----------
    mech : crankdyn.linkage.planar.Mechanism
        The mechanism.

    Returns
    -------
    bool
        A prismatic joint with f > 0, or a revolute one with f r > 0.
    """
    return any(
        j.friction > 0.0 and (j.kind == "prismatic" or j.journal_radius > 0.0) for j in mech.joints
    )


def _friction_terms(motion: MechanismMotion) -> list[_Term]:
    """Per joint: (rows/columns needed to add its friction) as closures over the kinematics."""
    mech = motion.mechanism
    direction = sign_of_speed(motion.speed)
    terms: list[_Term] = []
    col = 0
    for joint in mech.joints:
        first, second = joint.links
        if joint.kind == "revolute" and joint.friction > 0.0 and joint.journal_radius > 0.0:
            w_i = 0.0 if first == GROUND else motion.link_state(first, "qp")[:, 2]
            w_j = 0.0 if second == GROUND else motion.link_state(second, "qp")[:, 2]
            rel = np.sign(np.round((w_j - w_i) * direction, 12))
            terms.append(("revolute", joint, col, rel, None, None))
        elif joint.kind == "prismatic" and joint.friction > 0.0:
            r, _nrm, t = joint_geometry(motion, joint)
            assert t is not None  # a prismatic joint has its guide
            v_j = motion.point(joint.point, link=second, which="qp")
            if first == GROUND:
                v_i = np.zeros_like(v_j)
            else:  # the guide's material point now under the slider point r
                q = motion.link_state(first)
                w = motion.link_state(first, "qp")
                arm = r - q[:, :2]
                v_i = np.stack(
                    [w[:, 0] - w[:, 2] * arm[:, 1], w[:, 1] + w[:, 2] * arm[:, 0]], axis=1
                )
            rel = np.sign(np.round(np.sum((v_j - v_i) * t, axis=1) * direction, 12))
            terms.append(("prismatic", joint, col, rel, r, t))
        col += 2
    return terms


def _friction_vector(
    motion: MechanismMotion, terms: list[_Term], R: np.ndarray, n_eq: int
) -> np.ndarray:
    """F_friction (N, 3n): the friction loads on every link equation for reactions R."""
    mech = motion.mechanism
    model = mech._model
    out = np.zeros((R.shape[0], n_eq))
    G = {link.name: motion.link_state(link.name)[:, :2] for link in mech.links}
    for kind, joint, col, rel, r, t in terms:
        first, second = joint.links
        if kind == "revolute":
            mag = joint.friction * joint.journal_radius * np.hypot(R[:, col], R[:, col + 1])
            couple_on_second = -mag * rel
            for sign, link in ((1.0, second), (-1.0, first)):
                if link != GROUND:
                    k = 3 * (model.index[link] - 1)
                    out[:, k + 2] += sign * couple_on_second
        else:
            assert r is not None and t is not None  # a prismatic term carries its guide
            mag = joint.friction * np.abs(R[:, col])
            fx, fy = -mag * rel * t[:, 0], -mag * rel * t[:, 1]
            for sign, link in ((1.0, second), (-1.0, first)):
                if link != GROUND:
                    k = 3 * (model.index[link] - 1)
                    mx, my = cross_arm(r - G[link])
                    out[:, k] += sign * fx
                    out[:, k + 1] += sign * fy
                    out[:, k + 2] += sign * (mx * fx + my * fy)
    return out


def solve_with_friction(
    motion: MechanismMotion,
    system: KinetostaticSystem,
    R0: np.ndarray,
    *,
    source: str | None = None,
) -> tuple[np.ndarray, np.ndarray, dict[str, np.ndarray]]:
    """Reactions with friction by fixed-point iteration from the frictionless ones (module
    docstring; seed 004 sec. 3.5).

    Parameters
    ----------
    motion : crankdyn.linkage.motion.MechanismMotion
        The mechanism's motion (N positions).
    system : crankdyn.linkage.kinetostatics.KinetostaticSystem
        Its matrix equation (with the factors of C).
    R0 : numpy.ndarray
        (N, 3n) frictionless reactions (N, N m).
    source : str or None
        The mechanism's file, for messages.

    Returns
    -------
    R : numpy.ndarray
        (N, 3n) reactions with friction (N, N m).
    efficiency : numpy.ndarray
        (N,) instantaneous efficiency (dimensionless; NaN where power passes through zero).
    friction_forces : dict of str to numpy.ndarray
        The prismatic joints' friction forces (:func:`prismatic_friction_forces`).

    Raises
    ------
    InputError
        If the iteration does not converge (a self-locking position), naming the crank angle.
    """
    terms = _friction_terms(motion)
    n_eq = system.C.shape[1]
    lu = system.lu  # the factors of C from the frictionless solve
    base = np.einsum("nij,nj->ni", system.D, system.P)
    R = R0
    scale = max(float(np.max(np.abs(R0))), 1e-300)
    for _ in range(_MAX_ITER):
        fric = _friction_vector(motion, terms, R, n_eq)
        R_new = lu.solve(base - fric)
        change = np.max(np.abs(R_new - R), axis=1)
        R = R_new
        if np.all(change <= 1e-12 * scale):
            break
    else:
        i = int(np.argmax(change))
        raise InputError(
            f"the friction iteration does not converge at crank angle "
            f"{math.degrees(motion.crank_angle[i]):.6g} deg: the mechanism is self-locking "
            "there (friction too large for the crank to drive it)",
            file=source,
        )
    torque0, _f0 = driving_torque_of(motion, R0)
    torque, _f = driving_torque_of(motion, R)
    return R, efficiency(torque0, torque, motion.speed), prismatic_friction_forces(terms, R)


def prismatic_friction_forces(terms: list[_Term], R: np.ndarray) -> dict[str, np.ndarray]:
    """{prismatic joint: (N, 2) friction force of the guide on the slider (N)}: the part of the
    total reaction along the guide, -f |N| sgn(v_rel) t."""
    out = {}
    for kind, joint, col, rel, _r, t in terms:
        if kind == "prismatic":
            assert t is not None  # a prismatic term carries its guide
            mag = joint.friction * np.abs(R[:, col])
            out[joint.name] = -(mag * rel)[:, None] * t
    return out


def efficiency(ideal: ArrayLike, actual: ArrayLike, speed: float = 1.0) -> NDArray[np.float64]:
    """Instantaneous efficiency from the ideal and actual driving torques (module docstring;
    seed 004).

    Parameters
    ----------
    ideal : array_like
        Driving torque M_0 without friction (N m).
    actual : array_like
        Driving torque M with friction (N m), of ideal's shape.
    speed : float
        Crank speed (rad/s): its sign is the sense of the crank's rotation; default 1.

    Returns
    -------
    numpy.ndarray
        eta (dimensionless): M_0 / M where both drive the crank, M / M_0 where the mechanism
        drives it back, NaN where they differ in sign.

    Examples
    --------
    >>> efficiency([8.0, -5.0, 1.0], [10.0, -4.0, -1.0]).tolist()
    [0.8, 0.8, nan]
    """
    s = sign_of_speed(speed)
    m0, m = np.asarray(ideal) * s, np.asarray(actual) * s
    out = np.full(m.shape, np.nan)
    tiny = 1e-12 * max(float(np.max(np.abs(m), initial=0.0)), 1e-300)
    drive = (m > tiny) & (m0 > tiny)
    back = (m < -tiny) & (m0 < -tiny)
    out[drive] = m0[drive] / m[drive]
    out[back] = m[back] / m0[back]
    return out
