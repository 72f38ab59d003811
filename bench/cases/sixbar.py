"""Case: six-bar (the built-in reciprocating conveyor of seed 004) at 3600 crank angles.

The mechanism is crankdyn's built-in ``conveyor-seed004``: the crank-rocker A-B-C-D (an RRR
dyad), the point E on the rocker, the link EF and the slider F on the horizontal guide
y = 420 mm (an RRP dyad); crank speed 12 rad/s, crank acceleration 5 rad/s^2, one crank turn in
3600 steps of 0.1 deg.

Contenders:

- crankdyn: ``Mechanism.motion`` (every link's position, velocity and acceleration: the dyads in
  closed form, vectorised over all angles, :mod:`crankdyn.linkage.dyads`).
- pylinkage 1.3.0, the same mechanism from its components: ``Ground`` A, D and two points of the
  guide, ``Crank`` B, ``RRRDyad`` C, ``FixedDyad`` E (on the rocker, at a fixed distance and
  angle from D relative to D->C), ``RRPDyad`` F (circle about E, line through the guide points),
  with ``set_input_velocity(crank, omega, alpha)``; stepped through one turn by
  ``step_with_derivatives`` (pure Python) and, with numba, by ``step_fast_with_kinematics``
  (compiled in the warm-up call). Its joints C and F start from crankdyn's positions at crank
  angle 0, so that it follows the same assembly branch.
- the limit: the same closed forms written as bare numpy in this file (:func:`bare_sixbar`:
  circle-circle for C, a rigid rotation for E, circle-line for F, their velocity and
  acceleration equations by dot and cross products), returning the three points only, with
  nothing validated and no result object.

All return joint positions, velocities and accelerations (or, for crankdyn, every link's state);
the agreement check compares the points C, E and F outside the clock, at pylinkage's own crank
angles for pylinkage (it advances the crank by repeated rotation): positions to 1e-9 of the
mechanism's size, velocities and accelerations to 1e-9 of their peak. crankdyn's own result is
also checked against the loop closure (link lengths, the guide) before anything is compared.
"""

from __future__ import annotations

import math

import numpy as np

from bench.harness import CRANKDYN, AgreementError, Case, Contender, Deviation, Target
from crankdyn.linkage.planar import Mechanism

KEY = "sixbar"
TITLE = "Six-bar kinematics (conveyor-seed004)"
SIZES = {"full": 3600, "tiny": 36}
EXAMPLE = "conveyor-seed004"
OMEGA = 12.0  # rad/s
ALPHA = 5.0  # rad/s^2
TOLERANCE = 1e-9
SLOW = "pylinkage step_with_derivatives"
FAST = "pylinkage step_fast_with_kinematics (numba)"
BARE = "bare numpy closed-form dyads (the limit)"
POINTS = ("C", "E", "F")


def crank_angles(n: int) -> np.ndarray:
    """The n crank angles pylinkage visits from 0: one step, then every step (rad)."""
    return np.arange(1, n + 1) * (2.0 * math.pi / n)


def mechanism() -> Mechanism:
    return Mechanism.example(EXAMPLE)


def geometry(mech: Mechanism) -> dict:
    """Drawn points, lengths and branch signs of the conveyor for the bare version."""
    p = {k: np.array(v) for k, v in mech.point_map.items()}
    out = {k: p[k] for k in ("A", "B", "C", "D", "E", "F")}
    out["crank"] = float(np.linalg.norm(p["B"] - p["A"]))
    out["BC"] = float(np.linalg.norm(p["C"] - p["B"]))
    out["DC"] = float(np.linalg.norm(p["C"] - p["D"]))
    out["EF"] = float(np.linalg.norm(p["F"] - p["E"]))
    w, r = p["D"] - p["B"], p["C"] - p["B"]
    out["sign_C"] = math.copysign(1.0, w[0] * r[1] - w[1] * r[0])
    out["sign_F"] = math.copysign(1.0, p["F"][0] - p["E"][0])
    out["guide_y"] = float(p["F"][1])
    return out


def bare_sixbar(theta, g, omega=OMEGA, alpha=ALPHA):
    """Positions, velocities, accelerations (each (N, 3, 2): C, E, F) of the conveyor in closed
    form (module docstring), crank angle theta from x (rad)."""
    ct, st = np.cos(theta), np.sin(theta)
    a = g["crank"]
    bx, by = a * ct, a * st
    vbx, vby = -a * omega * st, a * omega * ct
    abx = -a * (alpha * st + omega * omega * ct)
    aby = a * (alpha * ct - omega * omega * st)
    dx, dy = g["D"]
    # C: circle about B (BC) and about D (DC)
    wx, wy = dx - bx, dy - by
    w2 = wx * wx + wy * wy
    f = 0.5 * (g["BC"] ** 2 - g["DC"] ** 2 + w2) / w2
    h = g["sign_C"] * np.sqrt(g["BC"] ** 2 / w2 - f * f)
    cx, cy = bx + f * wx - h * wy, by + f * wy + h * wx
    r3x, r3y = cx - bx, cy - by
    r4x, r4y = cx - dx, cy - dy
    cross = r3x * r4y - r3y * r4x
    w3 = -(vbx * r4x + vby * r4y) / cross
    w4 = -(vbx * r3x + vby * r3y) / cross
    kx = abx - w3 * w3 * r3x + w4 * w4 * r4x
    ky = aby - w3 * w3 * r3y + w4 * w4 * r4y
    a4 = -(kx * r3x + ky * r3y) / cross
    vcx, vcy = -w4 * r4y, w4 * r4x
    acx, acy = -a4 * r4y - w4 * w4 * r4x, a4 * r4x - w4 * w4 * r4y
    # E: fixed on the rocker D-C-E
    e0 = g["E"] - g["D"]
    c0 = g["C"] - g["D"]
    l4 = float(c0 @ c0)
    cr = (r4x * c0[0] + r4y * c0[1]) / l4
    sr = (c0[0] * r4y - c0[1] * r4x) / l4
    ex_, ey_ = cr * e0[0] - sr * e0[1], sr * e0[0] + cr * e0[1]
    ex, ey = dx + ex_, dy + ey_
    vex, vey = -w4 * ey_, w4 * ex_
    aex, aey = -a4 * ey_ - w4 * w4 * ex_, a4 * ex_ - w4 * w4 * ey_
    # F: circle about E (EF) and the line y = guide_y
    fy = g["guide_y"]
    r5y = fy - ey
    r5x = g["sign_F"] * np.sqrt(g["EF"] ** 2 - r5y * r5y)
    fx = ex + r5x
    w5 = -vey / r5x
    vfx = vex - w5 * r5y
    a5 = (w5 * w5 * r5y - aey) / r5x
    afx = aex - a5 * r5y - w5 * w5 * r5x
    zero = np.zeros_like(theta)
    pos = np.stack(
        [np.stack([cx, cy], -1), np.stack([ex, ey], -1), np.stack([fx, fy + zero], -1)], 1
    )
    vel = np.stack(
        [np.stack([vcx, vcy], -1), np.stack([vex, vey], -1), np.stack([vfx, zero], -1)], 1
    )
    acc = np.stack(
        [np.stack([acx, acy], -1), np.stack([aex, aey], -1), np.stack([afx, zero], -1)], 1
    )
    return pos, vel, acc


def _pylinkage(n: int, mech: Mechanism):
    """pylinkage's conveyor (module docstring), or None when pylinkage is not installed."""
    try:
        import pylinkage as pl
        from pylinkage.simulation import Linkage
    except ImportError:
        return None
    g = geometry(mech)
    start = mech.motion(np.array([0.0]))  # crankdyn's branch at pylinkage's first crank angle
    c0, f0 = start.point("C")[0], start.point("F")[0]
    ground_a = pl.Ground(*g["A"], name="A")
    ground_d = pl.Ground(*g["D"], name="D")
    guide_1 = pl.Ground(0.0, g["guide_y"], name="guide 1")
    guide_2 = pl.Ground(1.0, g["guide_y"], name="guide 2")
    crank = pl.Crank(anchor=ground_a, radius=g["crank"], angular_velocity=2 * math.pi / n, name="B")
    joint_c = pl.RRRDyad(
        crank.output, ground_d, distance1=g["BC"], distance2=g["DC"], x=c0[0], y=c0[1], name="C"
    )
    e0, dc0 = g["E"] - g["D"], g["C"] - g["D"]
    angle = math.atan2(e0[1], e0[0]) - math.atan2(dc0[1], dc0[0])
    joint_e = pl.FixedDyad(ground_d, joint_c, distance=float(np.hypot(*e0)), angle=angle, name="E")
    joint_f = pl.RRPDyad(joint_e, guide_1, guide_2, distance=g["EF"], x=f0[0], y=f0[1], name="F")
    linkage = Linkage(
        [ground_a, ground_d, guide_1, guide_2, crank, joint_c, joint_e, joint_f],
        name="conveyor (seed 004)",
    )
    linkage.set_input_velocity(crank, omega=OMEGA, alpha=ALPHA)
    return linkage


# joints of pylinkage's linkage: A, D, guide 1, guide 2, B, C, E, F
_PL_CRANK, _PL_POINTS = 4, (5, 6, 7)


def _numba_available() -> str | None:
    try:
        import numba  # noqa: F401
    except ImportError:
        return "numba not installed: pylinkage's compiled path not measured"
    return None


def _slow_run(linkage, n):
    def run():
        steps = list(linkage.step_with_derivatives(iterations=n))
        pos = np.array([s[0] for s in steps], dtype=float)
        vel = np.array([s[1] for s in steps], dtype=float)
        acc = np.array([s[2] for s in steps], dtype=float)
        return pos, vel, acc

    return run


def _fast_run(linkage, n):
    def run():
        return linkage.step_fast_with_kinematics(iterations=n)

    return run


def crankdyn_points(motion) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(N, 3, 2) positions, velocities, accelerations of C, E, F from crankdyn's motion."""
    return tuple(
        np.stack([motion.point(p, which=which) for p in POINTS], axis=1)
        for which in ("q", "qd", "qdd")
    )


def _check_crankdyn(motion, g) -> None:
    """Independent checks of crankdyn's result: the loop closes (link lengths, the slider on
    its guide) and the points move as their rates say (centred differences of the rates agree
    with the rates of the rates on the uniform grid)."""
    pos, vel, _acc = crankdyn_points(motion)
    b = motion.point("B")
    scale = motion.mechanism.length_scale
    gaps = (
        np.hypot(*(pos[:, 0] - b).T) - g["BC"],
        np.hypot(*(pos[:, 0] - g["D"]).T) - g["DC"],
        np.hypot(*(pos[:, 2] - pos[:, 1]).T) - g["EF"],
        pos[:, 2, 1] - g["guide_y"],
        vel[:, 2, 1],
    )
    if max(float(np.max(np.abs(x))) for x in gaps[:4]) > 1e-12 * scale:
        raise AgreementError("crankdyn: the conveyor's loop does not close")
    if float(np.max(np.abs(gaps[4]))) > 1e-12 * scale * OMEGA:
        raise AgreementError("crankdyn: the slider leaves its guide")


def _deviation(mine, theirs, scale) -> float:
    pos, vel, acc = mine
    p, v, a = theirs
    return max(
        float(np.max(np.abs(p - pos))) / scale,
        float(np.max(np.abs(v - vel)) / np.max(np.abs(vel))),
        float(np.max(np.abs(a - acc)) / np.max(np.abs(acc))),
    )


def _check_factory(mech, theta):
    g = geometry(mech)
    scale = mech.length_scale

    def check(outputs: dict) -> dict[str, Deviation]:
        motion = outputs[CRANKDYN]
        _check_crankdyn(motion, g)
        what = "positions (of the size); rates (of their peak)"
        out = {}
        if BARE in outputs:
            dev = _deviation(crankdyn_points(motion), outputs[BARE], scale)
            out[BARE] = Deviation(dev, TOLERANCE, what)
        for name in (SLOW, FAST):
            if name not in outputs:
                continue
            pos, vel, acc = (np.asarray(x, dtype=float) for x in outputs[name])
            b = pos[:, _PL_CRANK]
            angles = np.unwrap(np.arctan2(b[:, 1], b[:, 0]))
            ref = crankdyn_points(mech.motion(angles, OMEGA, ALPHA))  # at pylinkage's angles
            pts = list(_PL_POINTS)
            theirs = (pos[:, pts], vel[:, pts], acc[:, pts])
            out[name] = Deviation(_deviation(ref, theirs, scale), TOLERANCE, what)
        return out

    return check


def cases(size: str = "full") -> list[Case]:
    n = SIZES[size]
    theta = crank_angles(n)
    mech = mechanism()
    g = geometry(mech)
    pl_linkage = _pylinkage(n, mech)
    missing = None if pl_linkage is not None else "pylinkage not installed"
    no_numba = missing or _numba_available()
    contenders = (
        Contender(CRANKDYN, lambda: mech.motion(theta, OMEGA, ALPHA)),
        Contender(SLOW, _slow_run(pl_linkage, n) if not missing else None, missing=missing),
        Contender(FAST, _fast_run(pl_linkage, n) if not no_numba else None, missing=no_numba),
        Contender(BARE, lambda: bare_sixbar(theta, g)),
    )
    return [
        Case(
            key=KEY,
            title=TITLE,
            size=f"{n} crank angles",
            contenders=contenders,
            check=_check_factory(mech, theta),
            targets=(
                Target(SLOW, 30.0, ">= 30x step_with_derivatives"),
                Target(FAST, 1.0, "not slower than the numba path"),
            ),
            repeats=15,
            interleave=True,  # a ratio of a few milliseconds to numba's: both under the same load
        )
    ]
