"""Case: four-bar positions, velocities and accelerations at 3600 crank angles.

The seed 004 crank-rocker (crank AB = 73.4 mm, coupler BC = 125.36 mm, rocker DC = 103.4 mm,
ground AD = 103.52 mm; open branch) turning at omega2 = 10 rad/s with alpha2 = 5 rad/s^2, one
crank turn in 3600 steps of 0.1 deg.

crankdyn: ``FourBar.motion`` (closed form, vectorised over the angles: circle intersection,
Norton's velocity and acceleration equations). pylinkage 1.3.0: the same linkage from its
``Ground``, ``Crank`` and ``RRRDyad`` components in a ``Linkage``, with
``set_input_velocity(crank, omega, alpha)``, stepped through one turn by
``step_with_derivatives`` (pure Python, one step at a time) and, with numba installed, by
``step_fast_with_kinematics`` (numba-compiled; its one-off compilation happens in the warm-up
call). pylinkage returns joint positions, velocities and accelerations; the agreement check turns
them into link angles and rates (theta = atan2 of the link vector, omega = (r x v)/|r|^2,
alpha = (r x a)/|r|^2 for a link turning about a fixed or moving end) outside the clock, and
evaluates crankdyn at pylinkage's own crank angles (it advances the crank by repeated rotation).

Agreement: angles to 1e-9 rad, angular velocities and accelerations to 1e-9 of their largest
magnitude.
"""

from __future__ import annotations

import math

import numpy as np

from bench.harness import CRANKDYN, AgreementError, Case, Contender, Deviation, Target
from crankdyn.linkage.fourbar import FourBar

KEY = "fourbar"
TITLE = "Four-bar kinematics (seed 004 crank-rocker)"
SIZES = {"full": 3600, "tiny": 36}
LENGTHS = (0.0734, 0.12536, 0.1034, 0.10352)  # a, b, c, d (m)
OMEGA2 = 10.0  # rad/s
ALPHA2 = 5.0  # rad/s^2
TOLERANCE = 1e-9
SLOW = "pylinkage step_with_derivatives"
FAST = "pylinkage step_fast_with_kinematics (numba)"


def crank_angles(n: int) -> np.ndarray:
    """The n crank angles pylinkage visits from 0: one step, then every step (rad)."""
    return np.arange(1, n + 1) * (2.0 * math.pi / n)


def _pylinkage(n: int):
    """(linkage, crank) of pylinkage, or None when it is not installed."""
    try:
        import pylinkage as pl
        from pylinkage.simulation import Linkage
    except ImportError:
        return None
    a, b, c, d = LENGTHS
    ground_a = pl.Ground(0.0, 0.0, name="A")
    ground_d = pl.Ground(d, 0.0, name="D")
    crank = pl.Crank(anchor=ground_a, radius=a, angular_velocity=2.0 * math.pi / n, name="B")
    # start C on crankdyn's open branch (pylinkage then follows the nearest intersection)
    m = FourBar(*LENGTHS).motion(np.array([0.0]))
    cx, cy = d + c * math.cos(m.theta4[0]), c * math.sin(m.theta4[0])
    joint_c = pl.RRRDyad(crank.output, ground_d, distance1=b, distance2=c, x=cx, y=cy, name="C")
    linkage = Linkage([ground_a, ground_d, crank, joint_c], name="seed 004 four-bar")
    linkage.set_input_velocity(crank, omega=OMEGA2, alpha=ALPHA2)
    return linkage


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


def link_motion(pos, vel, acc):
    """Angles, angular velocities and accelerations of the coupler and rocker from joint
    arrays of shape (steps, joints [A, D, B, C], 2)."""
    out = {}
    for name, (i, j) in {"coupler": (2, 3), "rocker": (1, 3)}.items():
        r = pos[:, j] - pos[:, i]
        v = vel[:, j] - vel[:, i]
        a = acc[:, j] - acc[:, i]
        r2 = np.sum(r * r, axis=1)
        out[name] = (
            np.arctan2(r[:, 1], r[:, 0]),
            (r[:, 0] * v[:, 1] - r[:, 1] * v[:, 0]) / r2,
            (r[:, 0] * a[:, 1] - r[:, 1] * a[:, 0]) / r2,
        )
    crank = pos[:, 2] - pos[:, 0]
    return np.arctan2(crank[:, 1], crank[:, 0]), out


def _angle_gap(x, y) -> float:
    return float(np.max(np.abs(np.remainder(x - y + math.pi, 2.0 * math.pi) - math.pi)))


def _check_crankdyn(m) -> None:
    """Independent checks of crankdyn's result: the loop closes (eq. 1) and the rates match
    the loop's derivatives, a e^{i t2} w2 i + b e^{i t3} w3 i = c e^{i t4} w4 i."""
    a, b, c, d = LENGTHS
    e2, e3, e4 = np.exp(1j * m.theta2), np.exp(1j * m.theta3), np.exp(1j * m.theta4)
    loop = a * e2 + b * e3 - d - c * e4
    rate = 1j * (a * m.omega2 * e2 + b * m.omega3 * e3 - c * m.omega4 * e4)
    scale = max(LENGTHS)
    if np.max(np.abs(loop)) > 1e-12 * scale or np.max(np.abs(rate)) > 1e-12 * scale * OMEGA2:
        raise AgreementError("crankdyn: the four-bar loop or its derivative does not close")


def _check(outputs: dict) -> dict[str, Deviation]:
    mine = outputs[CRANKDYN]
    _check_crankdyn(mine)
    out = {}
    linkage = FourBar(*LENGTHS)
    for name, value in outputs.items():
        if name == CRANKDYN:
            continue
        pos, vel, acc = (np.asarray(x, dtype=float) for x in value)
        theta2, links = link_motion(pos, vel, acc)
        ref = linkage.motion(theta2, OMEGA2, ALPHA2)  # at pylinkage's own crank angles
        worst = 0.0
        for link, (t, w, al) in links.items():
            t_ref = ref.theta3 if link == "coupler" else ref.theta4
            w_ref = ref.omega3 if link == "coupler" else ref.omega4
            a_ref = ref.alpha3 if link == "coupler" else ref.alpha4
            worst = max(
                worst,
                _angle_gap(t, t_ref),
                float(np.max(np.abs(w - w_ref)) / np.max(np.abs(w_ref))),
                float(np.max(np.abs(al - a_ref)) / np.max(np.abs(a_ref))),
            )
        out[name] = Deviation(worst, TOLERANCE, "angles (rad); rates relative to their peak")
    return out


def cases(size: str = "full") -> list[Case]:
    n = SIZES[size]
    theta2 = crank_angles(n)
    linkage = FourBar(*LENGTHS)
    pl_linkage = _pylinkage(n)
    missing = None if pl_linkage is not None else "pylinkage not installed"
    no_numba = missing or _numba_available()
    contenders = (
        Contender(CRANKDYN, lambda: linkage.motion(theta2, OMEGA2, ALPHA2)),
        Contender(SLOW, _slow_run(pl_linkage, n) if not missing else None, missing=missing),
        Contender(FAST, _fast_run(pl_linkage, n) if not no_numba else None, missing=no_numba),
    )
    return [
        Case(
            key=KEY,
            title=TITLE,
            size=f"{n} crank angles",
            contenders=contenders,
            check=_check,
            targets=(
                Target(SLOW, 30.0, ">= 30x step_with_derivatives"),
                Target(FAST, 1.0, "not slower than the numba path"),
            ),
            repeats=15,
            interleave=True,  # a ratio of a few milliseconds to numba's: both under the same load
        )
    ]
