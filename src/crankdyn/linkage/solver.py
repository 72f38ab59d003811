"""Positions, velocities and accelerations of a planar mechanism at any crank angles: the
kinematic model of a :class:`~crankdyn.linkage.planar.Mechanism` (numeric core).

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

**Closed form.** When every link group (:meth:`~crankdyn.linkage.planar.Mechanism.link_groups`)
is a dyad (RRR, RRP, RPR, PRP, RPP), the mechanism is solved group by group in closed form,
vectorised over all crank angles (:mod:`crankdyn.linkage.dyads`), on the drawn assembly branch,
with the rotations continued along the crank angles from the drawn one
(:meth:`KinematicModel._solve_closed`). Everything else, and any path that passes a dead point,
an assembly gap or a singular position, goes to the general solver below, which reports such
positions.

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
from functools import cached_property
from typing import TYPE_CHECKING

import numpy as np

from crankdyn.errors import InputError
from crankdyn.linkage.elements import GROUND, Joint
from crankdyn.linkage.linsolve import lu_factor

if TYPE_CHECKING:
    from crankdyn.linkage.planar import Mechanism

__all__: list[str] = []

TWO_PI = 2.0 * math.pi
_MAX_STEP = math.radians(3.0)  # largest continuation step of the crank
_MIN_STEP = 1e-9  # rad; below this a step that still fails marks a dead point
_BLOCK = 4096  # crank angles per block of the general solver's batched Jacobians (bounded memory)
_PATH_BLOCK = 8192  # crank angles per block of the closed-form solution
_MAX_TURN = 0.5 * math.pi  # largest rotation of a link the closed form follows between samples


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


class KinematicModel:
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
    (:meth:`KinematicModel._solve_closed`)."""
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
