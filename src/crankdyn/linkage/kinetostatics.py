"""Kinetostatics of planar mechanisms by the matrix method [C]{R} = [D]{P} (seed 004).

D'Alembert's principle (seed 004, sec. 2 "动态静力分析"): with the inertia force -m a_G at the
centre of gravity and the inertia couple -I_G alpha added to the applied loads, every link is in
equilibrium. For each moving link the seed writes sum F_x = 0, sum F_y = 0 and the moment sum
about a point, with the moment of a force P at point I about point K

    M_K = (x_I - x_K) P_y - (y_I - y_K) P_x                                            (1)

(counter-clockwise positive; seed 004 sec. 3.2 "力矩的统一表达式"). Here the moments are taken
about each link's centre of gravity. Unknowns {R}: two per lower pair (a revolute's R_x, R_y,
the force of the joint's first link on its second, seed 004's R_ij; a prismatic joint's normal
force N along the guide normal and its couple M, i.e. magnitude and point of application), and
the balancing (driving) torque M_b on the crank (or a balancing force at a crank point along a
given direction). For a one-degree-of-freedom mechanism of n moving links and p_l lower pairs,
3n = 2 p_l + 1, so [C] is square (seed 004 sec. 3.2 "可解性分析": nine equations and nine
unknowns for the four-bar). Known loads {P}: per link (P_x, P_y) at the centre of gravity and a
couple M (inertia, gravity, applied couples), then each applied force at a point. With
{R} on the left and {P} on the right, C R + L P = 0 and D = -L.

All positions are assembled into stacked arrays C (N, 3n, 3n), D (N, 3n, p). C is factorised
once, all positions at once (:mod:`crankdyn.linkage.linsolve`: batched LU with partial
pivoting); a position where C is singular (a pivot below 1e-10 of its column's largest entry,
about a condition number of 1e10) is named in an InputError, and the factors serve every
right-hand side: the frictionless reactions and each step of the friction iteration.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any

import numpy as np

from crankdyn.constants import DEG
from crankdyn.errors import InputError
from crankdyn.linkage.elements import GROUND
from crankdyn.linkage.joints import cross_arm, driving_torque_of, joint_geometry, sign_of_speed
from crankdyn.linkage.linsolve import LU, lu_factor
from crankdyn.linkage.motion import MechanismMotion
from crankdyn.results import Result, column, freeze, scalar

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "KinetostaticSystem",
    "KinetostaticsResult",
    "KnownLoads",
    "build_system",
    "kinetostatics",
    "known_loads",
    "solve_system",
]


@dataclass(frozen=True, eq=False)
class KnownLoads:
    """The known loads {P} at every position and where they act.

    Parameters
    ----------
    names : tuple of str
        Label of every entry of P (e.g. ``"coupler Fx at G"``).
    P : numpy.ndarray
        (N, p) values (N or N m).
    L : numpy.ndarray
        (N, 3n, p) contribution of each entry to each link equation (sum F_x, sum F_y, sum M_G;
        dimensionless for the forces, m for their moments).
    W : numpy.ndarray
        (N, p) virtual velocity of each entry per unit crank speed: the velocity component of
        its point for a force component, the link's angular velocity for a couple (m/rad, -).
    """

    names: tuple[str, ...]
    P: np.ndarray
    L: np.ndarray
    W: np.ndarray


def known_loads(motion: MechanismMotion) -> KnownLoads:
    """Inertia (D'Alembert), gravity and applied loads of every link at every position (module
    docstring; seed 004 sec. 2).

    Per link the inertia force -m a_G (N) and couple -I_G alpha (N m) with the weight m g and
    the applied couples at G, then each applied force at its point (a resistance opposes the
    point's velocity).

    Parameters
    ----------
    motion : crankdyn.linkage.motion.MechanismMotion
        The mechanism's motion (N positions).

    Returns
    -------
    KnownLoads
        {P} (N, N m), where each entry acts, and its virtual velocity.
    """
    mech = motion.mechanism
    model = mech._model
    N = motion.crank_angle.size
    n = model.n
    links = mech.links
    entries = 3 * n + 2 * len(mech.forces)
    P = np.zeros((N, entries))
    L = np.zeros((N, 3 * n, entries))
    W = np.zeros((N, entries))
    names: list[str] = []
    gx, gy = mech.gravity
    direction = sign_of_speed(motion.speed)
    for k, link in enumerate(links):
        acc = motion.link_state(link.name, "qdd")
        vel = motion.link_state(link.name, "qp")
        torque = -link.inertia * acc[:, 2]
        for t in mech.torques:
            if t.link == link.name:
                if t.torque is not None:
                    torque = torque + t.torque
                else:
                    assert t.resistance is not None  # Torque requires one of the two
                    w = vel[:, 2] * direction
                    torque = torque - t.resistance * np.sign(np.round(w, 12))
        P[:, 3 * k] = -link.mass * acc[:, 0] + link.mass * gx
        P[:, 3 * k + 1] = -link.mass * acc[:, 1] + link.mass * gy
        P[:, 3 * k + 2] = torque
        for c in range(3):
            L[:, 3 * k + c, 3 * k + c] = 1.0
            W[:, 3 * k + c] = vel[:, c]
        names += [f"{link.name} Fx at G", f"{link.name} Fy at G", f"{link.name} couple"]
    for f_index, f in enumerate(mech.forces):
        col = 3 * n + 2 * f_index
        k = model.index[f.link] - 1
        r = motion.point(f.point, link=f.link)
        g = motion.link_state(f.link)[:, :2]
        v = motion.point(f.point, link=f.link, which="qp")
        if f.force is not None:
            fx = np.full(N, f.force[0])
            fy = np.full(N, f.force[1])
        else:
            assert f.resistance is not None  # Force requires one of the two
            vv = v * direction
            speed = np.hypot(vv[:, 0], vv[:, 1])
            moving = speed > 1e-12 * mech.length_scale
            if f.working_direction is not None:
                u = np.array([math.cos(f.working_direction), math.sin(f.working_direction)])
                moving &= vv @ u > 1e-12 * mech.length_scale
            with np.errstate(invalid="ignore", divide="ignore"):
                fx = np.where(moving, -f.resistance * vv[:, 0] / speed, 0.0)
                fy = np.where(moving, -f.resistance * vv[:, 1] / speed, 0.0)
        P[:, col], P[:, col + 1] = fx, fy
        mx, my = cross_arm(r - g)
        L[:, 3 * k, col] = 1.0
        L[:, 3 * k + 1, col + 1] = 1.0
        L[:, 3 * k + 2, col] = mx
        L[:, 3 * k + 2, col + 1] = my
        W[:, col], W[:, col + 1] = v[:, 0], v[:, 1]
        names += [f"force on {f.link} at {f.point} Fx", f"force on {f.link} at {f.point} Fy"]
    return KnownLoads(tuple(names), P, L, W)


@dataclass(frozen=True, eq=False)
class KinetostaticSystem:
    """The matrix equation [C]{R} = [D]{P} at every position (seed 004 sec. 3.2).

    Parameters
    ----------
    C : numpy.ndarray
        (N, 3n, 3n) coefficients of the unknowns (dimensionless for forces, m for their
        moments).
    D : numpy.ndarray
        (N, 3n, p) coefficients of the known loads (likewise).
    P : numpy.ndarray
        (N, p) known loads (N, N m).
    unknowns : tuple of str
        Names of the unknowns in {R}, e.g. ``"B Rx"``, ``"S N"``, ``"driving torque"``.
    equations : tuple of str
        Names of the rows, e.g. ``"coupler sum Fx"``, ``"coupler sum M about G"``.
    loads : KnownLoads
        The known loads behind P and D.
    """

    C: np.ndarray
    D: np.ndarray
    P: np.ndarray
    unknowns: tuple[str, ...]
    equations: tuple[str, ...]
    loads: KnownLoads

    @cached_property
    def lu(self) -> LU:
        """LU factors of C at every position (:func:`crankdyn.linkage.linsolve.lu_factor`),
        computed once and reused by every solve."""
        return lu_factor(self.C)

    def matrices(self, index: int) -> dict[str, Any]:
        """C, D, P and the names at one position, as plain lists (for JSON).

        Parameters
        ----------
        index : int
            The position (0-based).

        Returns
        -------
        dict of str to list
            ``unknowns``, ``equations``, ``known_loads`` (names) and ``C``, ``D``, ``P``
            (nested lists; N, N m, m).
        """
        return {
            "unknowns": list(self.unknowns),
            "equations": list(self.equations),
            "known_loads": list(self.loads.names),
            "C": self.C[index].tolist(),
            "D": self.D[index].tolist(),
            "P": self.P[index].tolist(),
        }


def build_system(motion: MechanismMotion, loads: KnownLoads | None = None) -> KinetostaticSystem:
    """Assemble C, D, P at every position (seed 004's matrix method, sec. 3.2; module
    docstring).

    Parameters
    ----------
    motion : crankdyn.linkage.motion.MechanismMotion
        The mechanism's motion (N positions).
    loads : KnownLoads or None
        The known loads; default :func:`known_loads` of ``motion``.

    Returns
    -------
    KinetostaticSystem
        The stacked matrix equation.

    Examples
    --------
    A slider-crank: three moving links, four lower pairs and the driving torque, nine
    equations in nine unknowns (seed 004 sec. 3.2).

    >>> from crankdyn.linkage.planar import slider_crank_mechanism
    >>> system = build_system(slider_crank_mechanism(0.05, 0.2).motion([1.0]))
    >>> system.C.shape, system.unknowns[-3:]
    ((1, 9, 9), ('S N', 'S M', 'driving torque'))
    """
    mech = motion.mechanism
    model = mech._model
    N = motion.crank_angle.size
    n = model.n
    if loads is None:
        loads = known_loads(motion)
    C = np.zeros((N, 3 * n, 3 * n))
    unknowns: list[str] = []
    col = 0
    G = {link.name: motion.link_state(link.name)[:, :2] for link in mech.links}

    def put(link: str, cx: Any, cy: Any, cm_x: Any, cm_y: Any, c: int) -> None:
        """Add a force with unit components (cx, cy) at point r to link's rows, column c."""
        if link == GROUND:
            return
        k = 3 * (model.index[link] - 1)
        C[:, k, c] += cx
        C[:, k + 1, c] += cy
        C[:, k + 2, c] += cm_x * cx + cm_y * cy

    for joint in mech.joints:
        first, second = joint.links
        r, nrm, _t = joint_geometry(motion, joint)
        if joint.kind == "revolute":
            for sign, link in ((1.0, second), (-1.0, first)):
                if link == GROUND:
                    continue
                mx, my = cross_arm(r - G[link])
                put(link, sign, 0.0, mx, my, col)
                put(link, 0.0, sign, mx, my, col + 1)
            unknowns += [f"{joint.name} Rx", f"{joint.name} Ry"]
        else:
            assert nrm is not None  # a prismatic joint has its guide
            for sign, link in ((1.0, second), (-1.0, first)):
                if link == GROUND:
                    continue
                mx, my = cross_arm(r - G[link])
                put(link, sign * nrm[:, 0], sign * nrm[:, 1], mx, my, col)
                k = 3 * (model.index[link] - 1)
                C[:, k + 2, col + 1] += sign
            unknowns += [f"{joint.name} N", f"{joint.name} M"]
        col += 2
    d = mech.driver
    crank = mech.crank
    k = 3 * (model.index[crank] - 1)
    if d.balancing_point is None:
        C[:, k + 2, col] = 1.0
        unknowns.append("driving torque")
    else:
        r = motion.point(d.balancing_point, link=crank)
        mx, my = cross_arm(r - G[crank])
        u = d.balancing_unit(motion.crank_angle)
        put(crank, u[:, 0], u[:, 1], mx, my, col)
        unknowns.append("balancing force")
    equations = []
    for moving in mech.links:
        name = moving.name
        equations += [f"{name} sum Fx", f"{name} sum Fy", f"{name} sum M about G"]
    return KinetostaticSystem(
        C=C,
        D=-loads.L,
        P=loads.P,
        unknowns=tuple(unknowns),
        equations=tuple(equations),
        loads=loads,
    )


def check_singular(
    system: KinetostaticSystem, crank_angle: np.ndarray, source: str | None = None
) -> None:
    """Raise InputError naming the first position where C is singular (from its LU pivots)."""
    bad = system.lu.singular
    if np.any(bad):
        i = int(np.argmax(bad))
        raise InputError(
            f"the kinetostatic matrix [C] is singular at crank angle "
            f"{math.degrees(crank_angle[i]):.6g} deg (position {i + 1}): the mechanism is at a "
            "dead point there and the crank cannot balance it",
            file=source,
        )


def solve_system(system: KinetostaticSystem, extra: np.ndarray | None = None) -> np.ndarray:
    """The reactions {R} from C R = D P (- extra), with the factors of C
    (:attr:`KinetostaticSystem.lu`).

    Parameters
    ----------
    system : KinetostaticSystem
        The matrix equation.
    extra : numpy.ndarray or None
        (N, 3n) loads moved to the left-hand side (friction, N and N m), or None.

    Returns
    -------
    numpy.ndarray
        (N, 3n) reactions (N; N m for a prismatic joint's couple and the driving torque).
    """
    rhs = np.einsum("nij,nj->ni", system.D, system.P)
    if extra is not None:
        rhs = rhs - extra
    return system.lu.solve(rhs)


# ---- result ----------------------------------------------------------------------------------


@dataclass(frozen=True)
class KinetostaticsResult(Result):
    """Joint reactions and driving torque over the crank angles (seed 004; :func:`kinetostatics`).

    Parameters
    ----------
    system : KinetostaticSystem or None
        The matrix equation (not exported).
    motion : crankdyn.linkage.motion.MechanismMotion or None
        The motion it was built on (not exported).
    reactions : numpy.ndarray or None
        (N, 3n) the solved {R} (N, N m), in the order of ``system.unknowns``.
    """

    title = "Kinetostatics"
    mechanism_name: str = scalar("mechanism", "Mechanism", "")
    crank_speed: float = scalar("crank_speed_rad_s", "Crank speed", "rad/s")
    crank_acceleration: float = scalar("crank_acceleration_rad_s2", "Crank acceleration", "rad/s²")
    with_friction: bool = scalar("friction", "Friction included", "")
    max_driving_torque: float = scalar("max_driving_torque_Nm", "Max driving torque", "N·m")
    min_driving_torque: float = scalar("min_driving_torque_Nm", "Min driving torque", "N·m")
    mean_driving_torque: float = scalar("mean_driving_torque_Nm", "Mean driving torque", "N·m")
    method_difference: float = scalar(
        "max_method_difference_Nm",
        "Max |matrix - virtual work| (frictionless)",
        "N·m",
        fmt=".3g",
    )
    mean_efficiency: float | None = scalar("mean_efficiency", "Cycle efficiency", "", fmt=".4g")
    crank_angle: np.ndarray = column("crank_angle_deg", "Crank angle", "deg", DEG)
    driving_torque: np.ndarray = column("driving_torque_Nm", "Driving torque", "N·m")
    driving_torque_virtual_work: np.ndarray = column(
        "driving_torque_virtual_work_Nm", "Driving torque, virtual work", "N·m"
    )
    driving_torque_frictionless: np.ndarray | None = column(
        "driving_torque_frictionless_Nm", "Driving torque, no friction", "N·m"
    )
    efficiency: np.ndarray | None = column("efficiency", "Instantaneous efficiency", "")
    balancing_force: np.ndarray | None = column("balancing_force_N", "Balancing force", "N")
    joint_forces: dict | None = column("joint_forces_N", "Joint force", "N")
    joint_moments: dict | None = column("joint_moments_Nm", "Prismatic joint couple", "N·m")
    system: KinetostaticSystem | None = field(default=None, repr=False)
    motion: MechanismMotion | None = field(default=None, repr=False)
    reactions: np.ndarray | None = field(default=None, repr=False)

    def joint_force(self, name: str) -> np.ndarray:
        """The force of a joint's first link on its second.

        Parameters
        ----------
        name : str
            The joint.

        Returns
        -------
        numpy.ndarray
            (N, 2) force (N): a prismatic joint's normal force plus its friction force.
        """
        assert self.joint_forces is not None  # kinetostatics fills it
        f = self.joint_forces[name]
        return np.stack([f["x"], f["y"]], axis=1)

    def plot(self, fig: Figure | None = None) -> Figure:
        """Driving torque (both methods) and joint force magnitudes over the cycle.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; default a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.linkage import plot_kinetostatics

        return plot_kinetostatics(self, fig=fig)


def _joint_outputs(
    system: KinetostaticSystem,
    motion: MechanismMotion,
    R: np.ndarray,
    friction_forces: dict[str, np.ndarray] | None = None,
) -> tuple[dict[str, dict[str, np.ndarray]], dict[str, np.ndarray]]:
    """Total joint forces {joint: {"x", "y"}} (a prismatic joint's normal force plus its
    friction force) and the prismatic joints' couples."""
    mech = motion.mechanism
    forces: dict[str, dict[str, np.ndarray]] = {}
    moments: dict[str, np.ndarray] = {}
    friction_forces = friction_forces or {}
    col = 0
    for joint in mech.joints:
        if joint.kind == "revolute":
            fx, fy = R[:, col], R[:, col + 1]
        else:
            _r, nrm, _t = joint_geometry(motion, joint)
            assert nrm is not None  # a prismatic joint has its guide
            fx, fy = R[:, col] * nrm[:, 0], R[:, col] * nrm[:, 1]
            if joint.name in friction_forces:
                fx = fx + friction_forces[joint.name][:, 0]
                fy = fy + friction_forces[joint.name][:, 1]
            moments[joint.name] = freeze(R[:, col + 1])
        forces[joint.name] = {"x": freeze(fx), "y": freeze(fy)}
        col += 2
    return forces, moments


def _work(torque: np.ndarray, theta: np.ndarray) -> float:
    """Work of the crank torque over the crank angles (J per unit of crank angle sense):
    trapezoidal integral; a single position gives its torque."""
    torque, theta = np.asarray(torque), np.asarray(theta)
    if torque.size < 2:
        return float(torque[0]) if torque.size else 0.0
    return float(np.sum(0.5 * (torque[1:] + torque[:-1]) * np.diff(theta)))


def _mean(torque: np.ndarray, theta: np.ndarray) -> float:
    """Mean torque over the span of crank angles (N m); the value itself at one position."""
    span = float(np.ptp(theta)) if np.size(theta) > 1 else 0.0
    return _work(torque, theta) / span if span > 0.0 else float(np.mean(torque))


def kinetostatics(
    motion: MechanismMotion, *, friction: bool = True, source: str | None = None
) -> KinetostaticsResult:
    """Joint reactions and driving torque at every position of ``motion``.

    The frictionless matrix solution is checked against the independent Zhukovsky-lever /
    virtual-power driving torque (:mod:`crankdyn.linkage.virtual_power`). With ``friction`` and
    any joint with a friction coefficient, friction circles and Coulomb friction are added
    iteratively (:mod:`crankdyn.linkage.friction`) and the instantaneous efficiency is reported.

    Parameters
    ----------
    motion : crankdyn.linkage.motion.MechanismMotion
        The mechanism's motion (N positions, its crank speed and acceleration).
    friction : bool
        Include the joints' friction; default True.
    source : str or None
        The mechanism's file, for messages; default the mechanism's source.

    Returns
    -------
    KinetostaticsResult
        Driving torque (N m) by both methods, joint forces (N), prismatic couples (N m),
        balancing force (N), efficiency.

    Raises
    ------
    InputError
        At a dead point (C singular) or a self-locking position, naming the crank angle.

    Examples
    --------
    A central slider-crank (R = 50 mm, L = 200 mm) at 90 deg with 100 N pushing the slider:
    the crank balances it with P R = 5 N m, and the rod, inclined by arcsin(R/L), carries
    P tan(arcsin(R/L)) = 25.8 N across the guide:

    >>> from crankdyn.linkage.elements import Force
    >>> from crankdyn.linkage.planar import slider_crank_mechanism
    >>> mech = slider_crank_mechanism(0.05, 0.2, forces=[Force("slider", "C", force=(100.0, 0.0))])
    >>> result = kinetostatics(mech.motion([math.pi / 2]))
    >>> round(float(result.driving_torque[0]), 9), round(float(result.method_difference), 9)
    (5.0, 0.0)
    >>> [round(float(v), 4) for v in result.joint_force("C")[0]]
    [-100.0, 25.8199]
    >>> round(100.0 * math.tan(math.asin(0.25)), 4)
    25.8199
    """
    from crankdyn.linkage.friction import has_friction, solve_with_friction
    from crankdyn.linkage.virtual_power import virtual_power_driving_torque

    mech = motion.mechanism
    source = source or mech.source
    system = build_system(motion)
    check_singular(system, motion.crank_angle, source)
    R0 = solve_system(system)
    torque0, force0 = driving_torque_of(motion, R0)
    virtual, _vf = virtual_power_driving_torque(motion, system.loads)
    difference = float(np.max(np.abs(torque0 - virtual))) if torque0.size else 0.0
    use_friction = friction and has_friction(mech)
    slide = None
    if use_friction:
        R, efficiency, slide = solve_with_friction(motion, system, R0, source=source)
        torque, force = driving_torque_of(motion, R)
    else:
        R, efficiency, torque, force = R0, None, torque0, force0
    forces, moments = _joint_outputs(system, motion, R, slide)
    mean_eff = None
    if efficiency is not None:
        work0, work = _work(torque0, motion.crank_angle), _work(torque, motion.crank_angle)
        if work > 0.0 and work0 > 0.0:
            mean_eff = float(work0 / work)
    return KinetostaticsResult(
        mechanism_name=mech.name,
        crank_speed=motion.speed,
        crank_acceleration=motion.acceleration,
        with_friction=use_friction,
        max_driving_torque=float(np.max(torque)),
        min_driving_torque=float(np.min(torque)),
        mean_driving_torque=_mean(torque, motion.crank_angle),
        method_difference=difference,
        mean_efficiency=mean_eff,
        crank_angle=freeze(motion.crank_angle),
        driving_torque=freeze(torque),
        driving_torque_virtual_work=freeze(virtual),
        driving_torque_frictionless=freeze(torque0) if use_friction else None,
        efficiency=freeze(efficiency) if efficiency is not None else None,
        balancing_force=freeze(force) if force is not None else None,
        joint_forces=forces,
        joint_moments=moments or None,
        system=system,
        motion=motion,
        reactions=freeze(R),
    )
