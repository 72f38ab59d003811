"""Closed-form kinematics of mechanisms built from dyads (Assur groups of class II).

A mechanism whose link groups (:meth:`~crankdyn.linkage.planar.Mechanism.link_groups`, seed 004)
are all dyads is solved group by group in the kinematic order (the crank, then the groups in the
reverse of the force-analysis order), each dyad from the links already known, in closed form and
vectorised over all crank angles at once; velocities and accelerations per unit crank speed
follow from the derivatives of the same closure equations.

Formulation (Norton 2012, Design of Machinery, 5th ed., ch. 4, 6, 7: the vector-loop closure and its
derivatives; Nikravesh 1988, Computer-Aided Analysis of Mechanical Systems, sec. 3.6 and 4.1 for
the absolute coordinates and the prismatic-joint equations used by :mod:`.planar`)
---------------------------------------------------------------------------------------------
Notation: J v = (-v_y, v_x) (the rotation by +90 deg), a x b = a_x b_y - a_y b_x; primes are
derivatives with respect to the crank angle. A rotating world vector v = A(phi) v_0 has
v' = omega J v and v'' = alpha J v - omega^2 v. The material point of a known link K drawn at p
is r = G_K + A(phi_K)(p - G_K,drawn), with r' = G_K' + omega_K J (r - G_K) and
r'' = G_K'' + alpha_K J (r - G_K) - omega_K^2 (r - G_K).

A dyad has links a and b, an inner joint between them and one outer joint from each to a known
link K_a, K_b. Its unknowns are one coordinate x_X per link X:

- outer revolute at point o: X turns about the known pin P = r_K(o); x_X = phi_X, and a point of
  X drawn at p is at P + A(phi_X)(p - o);
- outer prismatic: X keeps the rotation of K (phi_X = phi_K) and slides by u along the guide
  direction d = A(phi_K) d_0; x_X = u, and a point of X drawn at p is at r_K(p) + u d.

Inner revolute at Q (RRR, RRP, PRP): Q_a(x_a) = Q_b(x_b) with Q_X = P + r_X (|r_X| = |q - o|, a
circle) or Q_X = C + u d (C = r_K(q), a line). Positions: circle-circle intersection
Q = P_a + f w + sigma g J w with w = P_b - P_a, f = (L_a^2 - L_b^2 + |w|^2) / (2 |w|^2),
g = sqrt(L_a^2 / |w|^2 - f^2); circle-line u = -beta + sigma sqrt(beta^2 - gamma),
beta = d . (C - P), gamma = |C - P|^2 - L^2; line-line by Cramer's rule. Rates: differentiating
Q_a = Q_b gives the 2 x 2 system [e_a, -e_b] (x_a', x_b') = k_b - k_a with e_X = J r_X
(revolute end) or d (prismatic end), k_X = P' or C' + u d'; the second derivative has the same
matrix and k_X = P'' - omega_X^2 r_X or C'' + 2 u' d' + u d''. Both are solved by Cramer's rule
with the one determinant e_a x (-e_b).

Inner prismatic at p (normal n = A(phi) n_0, guide on the joint's first link):
phi_a = phi_b and n . (r_slider(p) - r_guide(p)) = 0.

- RPR (both outer joints revolute, pivots P_g of the guide and P_s of the slider,
  w = P_s - P_g): n . w = c with c = n_0 . (o_s - o_g), i.e. A cos phi + B sin phi = c with
  A = n_0 . w, B = n_0 x w, so cos phi = (A c + h B) / |w|^2, sin phi = (B c - h A) / |w|^2,
  h = sigma sqrt(|w|^2 - c^2); omega = -(n . w') / (n x w),
  alpha = (omega^2 n . w - 2 omega n x w' - n . w'') / (n x w).
- RPP (the revolute end turns with the prismatic end's known link): with m = r_K(p) - r_R(p) and
  v = m + u d, n . v = 0 is linear, u = -(n . m)/(n . d), u' = -(n' . v + n . (m' + u d'))/(n . d),
  u'' = -(n'' . v + 2 n' . v' + n . (m'' + 2 u' d' + u d''))/(n . d).

**Assembly branch.** The signs sigma are taken from the drawn configuration, so every position
is on the drawn branch: sigma changes only where the dyad is singular (its determinant, e.g.
r_a x r_b of an RRR dyad, vanishes: links in line), which the crank cannot pass without locking.
Rotations are continued along the path of crank angles from the drawn one (unwrapped from one
sample to the next with the increment predicted from the rates, see :mod:`.planar`).

**What has no closed form here** (a group of more than two links, a dyad of three prismatic
joints, a dyad whose joints are not one inner and one outer per link) and **positions where
a dyad is infeasible or nearly singular** (an imaginary intersection, a normalised determinant
below :data:`DET_LIMIT` or of the other sign than drawn: a singular position passed between two
samples) raise :class:`NoClosedForm`: the caller then uses the general
Newton-Raphson solver, which reports dead points and singular positions.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike

from crankdyn.linkage.elements import GROUND

if TYPE_CHECKING:
    from crankdyn.linkage.planar import Mechanism
    from crankdyn.linkage.solver import KinematicModel

__all__ = ["DET_LIMIT", "ClosedForm", "NoClosedForm", "closed_form"]

DET_LIMIT = 1e-7
"""Smallest normalised dyad determinant (the sine of the angle between its directions) solved
in closed form."""

# A link's state (gx, gy, c, s, phi, gx', gy', omega, gx'', gy'', alpha), each entry a number
# or an array over the crank angles (numbers where they are constant, e.g. for the ground)
_State = tuple[Any, ...]
_States = dict[int, _State]
# scalars for the ground
_GROUND_STATE = (0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


class NoClosedForm(Exception):
    """The mechanism, or a requested position, needs the general solver."""


def _mul(a, b):
    """a * b, without an array operation when either factor is the number 0 or 1 (the crank
    turns at unit speed without acceleration, the ground stands still: their rates are plain
    numbers)."""
    if type(a) is float:
        if a == 0.0:
            return 0.0
        if a == 1.0:
            return b
    if type(b) is float:
        if b == 0.0:
            return 0.0
        if b == 1.0:
            return a
    return a * b


def _add(a, b):
    """a + b, without an array operation when either is the number 0."""
    if type(a) is float and a == 0.0:
        return b
    if type(b) is float and b == 0.0:
        return a
    return a + b


def _sub(a, b):
    """a - b, without an array operation when b is the number 0."""
    if type(b) is float and b == 0.0:
        return a
    return a - b


def _zero(a: Any) -> bool:
    """Whether a is the number 0 (a product with it is the number 0, :func:`_mul`)."""
    return type(a) is float and a == 0.0


def _vec(p: np.ndarray, g0: np.ndarray) -> tuple[float, float]:
    """p - g0 of two drawn points as plain numbers (a constant offset on a link)."""
    return float(p[0] - g0[0]), float(p[1] - g0[1])


def _put(row, value):
    """Write a value (a number or an array over the crank angles) into its row of the output
    and return what a link's state holds: the number, or the row (the state's arrays are the
    rows of the output, written once)."""
    row[...] = value
    return value if type(value) is float else row


def _plus_to(row, a, b):
    """a + b into ``row`` (:func:`_put`); numbers stay numbers."""
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.add(a, b, out=row)
    return _put(row, a + b)


def _add_to(row, a, b):
    """:func:`_add` into ``row`` (:func:`_put`)."""
    if type(a) is float and a == 0.0:
        return _put(row, b)
    if type(b) is float and b == 0.0:
        return _put(row, a)
    return _plus_to(row, a, b)


def _sub_to(row, a, b):
    """:func:`_sub` into ``row`` (:func:`_put`)."""
    if type(b) is float and b == 0.0:
        return _put(row, a)
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.subtract(a, b, out=row)
    return _put(row, a - b)


def _material(state, v):
    """Position, first and second derivative of the material point of a link at the drawn
    offset v = p - G_drawn (plain numbers) from its centre of gravity, for the link's state
    (module docstring). Returns ((x, y), (x', y'), (x'', y''))."""
    gx, gy, c, s, _phi, gxp, gyp, w, gxpp, gypp, al = state
    vx, vy = v
    ax = c * vx - s * vy
    ay = s * vx + c * vy
    w2 = _mul(w, w)
    return (
        (gx + ax, gy + ay),
        (_sub(gxp, _mul(w, ay)), _add(gyp, _mul(w, ax))),
        (
            _sub(_sub(gxpp, _mul(al, ay)), _mul(w2, ax)),
            _sub(_add(gypp, _mul(al, ax)), _mul(w2, ay)),
        ),
    )


def _direction(state, d0):
    """A(phi) d0 of a link's state and its two derivatives."""
    _gx, _gy, c, s, _phi, _gxp, _gyp, w, _gxpp, _gypp, al = state
    dx = c * float(d0[0]) - s * float(d0[1])
    dy = s * float(d0[0]) + c * float(d0[1])
    w2 = _mul(w, w)
    return (
        (dx, dy),
        (-_mul(w, dy), _mul(w, dx)),
        (-_add(_mul(al, dy), _mul(w2, dx)), _sub(_mul(al, dx), _mul(w2, dy))),
    )


def _pose_about(pin, c, s, w, al, v, rows, w2=None):
    """State of a link turning about a pin: pin = (P, P', P''), rotation (c, s, omega, alpha),
    v = drawn centre of gravity minus drawn pin point (plain numbers); written into the link's
    ``rows`` of the output ((3, 3, B): x, y, phi and their derivatives; the caller writes phi)
    as the state's arrays. ``w2``: omega^2 when the caller has it."""
    (px, py), (p1x, p1y), (p2x, p2y) = pin
    vx, vy = v
    ax = c * vx - s * vy
    ay = s * vx + c * vy
    if w2 is None:
        w2 = _mul(w, w)
    return (
        _plus_to(rows[0, 0], px, ax),
        _plus_to(rows[0, 1], py, ay),
        c,
        s,
        None,
        _sub_to(rows[1, 0], p1x, _mul(w, ay)),
        _add_to(rows[1, 1], p1y, _mul(w, ax)),
        _put(rows[1, 2], w),
        _sub_to(rows[2, 0], _sub(p2x, _mul(al, ay)), _mul(w2, ax)),
        _sub_to(rows[2, 1], _add(p2y, _mul(al, ax)), _mul(w2, ay)),
        _put(rows[2, 2], al),
    )


def _pose_sliding(known, v, d, u, rows):
    """State of a link translating by u (with u', u'') along d (with d', d'') from the pose it
    would have moving with the known link (v: the link's drawn centre of gravity minus the
    known link's), written into the link's ``rows`` of the output (:func:`_pose_about`)."""
    (mx, my), (m1x, m1y), (m2x, m2y) = _material(known, v)
    (dx, dy), (d1x, d1y), (d2x, d2y) = d
    u0, u1, u2 = u
    u12 = 0.0 if _zero(d1x) and _zero(d1y) else 2.0 * u1  # 2 u', needed where the guide turns
    return (
        _plus_to(rows[0, 0], mx, _mul(u0, dx)),
        _plus_to(rows[0, 1], my, _mul(u0, dy)),
        known[2],
        known[3],
        _put(rows[0, 2], known[4]),
        _add_to(rows[1, 0], _add(m1x, _mul(u1, dx)), _mul(u0, d1x)),
        _add_to(rows[1, 1], _add(m1y, _mul(u1, dy)), _mul(u0, d1y)),
        _put(rows[1, 2], known[7]),
        _add_to(rows[2, 0], _add(_add(m2x, _mul(u2, dx)), _mul(u12, d1x)), _mul(u0, d2x)),
        _add_to(rows[2, 1], _add(_add(m2y, _mul(u2, dy)), _mul(u12, d1y)), _mul(u0, d2y)),
        _put(rows[2, 2], known[10]),
    )


def _least(x):
    """The smallest value of a number or an array (NaN if any is NaN)."""
    return x.min() if isinstance(x, np.ndarray) else x


def _check(margin: Any) -> None:
    """Feasibility: a negative margin is an imaginary intersection (the links do not reach);
    NaN fails the test too."""
    if not _least(margin) >= 0.0:
        raise NoClosedForm("a dyad cannot be assembled")


def _check_det(det: Any, sign: float, scale: float = 1.0) -> None:
    """Regularity: the normalised determinant det * scale (scale > 0) keeps its drawn sign and
    stays away from zero (a sign change between two samples is a singular position passed
    between them). The extreme is scaled after the reduction: rounding x * scale is monotonic
    in x, so min(det * scale) = min(det) * scale to the bit."""
    if sign > 0.0:
        ok = _least(det) * scale >= DET_LIMIT
    else:
        ok = (det.max() if isinstance(det, np.ndarray) else det) * scale <= -DET_LIMIT
    if not ok:
        raise NoClosedForm("a dyad is at or near a singular position")


def _solve2(ea, eb, rhs, det):
    """(x1, x2) of x1 e_a - x2 e_b = rhs by Cramer's rule; det = e_a x (-e_b)."""
    (eax, eay), (ebx, eby), (rx, ry) = ea, eb, rhs
    x1 = (ry * ebx - rx * eby) / det  # rhs x (-e_b)
    x2 = (eax * ry - eay * rx) / det  # e_a x rhs
    return x1, x2


class _Outer:
    """An outer joint of a dyad link: kind "R" or "P", the known link's index and drawn centre
    of gravity, the joint's drawn point, the guide's drawn direction (prismatic)."""

    __slots__ = ("d0", "k", "kg0", "kind", "point")

    def __init__(self, kind, k, kg0, point, d0=None):
        self.kind, self.k, self.kg0, self.point, self.d0 = kind, k, kg0, point, d0


class _Dyad:
    """One dyad of the plan (module docstring): links (ia, ib) with drawn centres of gravity,
    their outer joints, the inner joint (kind, drawn point, normal, guide end) and the drawn
    branch sign."""

    def __init__(self, links, g0, outer, inner_kind, inner_point, inner_normal=None, guide=0):
        self.links, self.g0, self.outer = links, g0, outer
        self.inner_kind, self.q0 = inner_kind, inner_point
        self.n0, self.guide = inner_normal, guide
        kinds = "".join(o.kind for o in outer)
        if inner_kind == "P" and kinds == "PP":
            raise NoClosedForm("a dyad of three prismatic joints")
        self.kinds = kinds
        self.sigma = self._drawn_sign()
        self.det_sign = self._drawn_det_sign()
        # per end: (q - o)/|q - o|^2 of a turning end (its rotation from r . r0, r0 x r), and
        # 1/(|e_a| |e_b|) of an inner revolute's determinant
        self.r0_scaled: list[Any] = [None, None]
        norm = 1.0
        for X, o in enumerate(outer):
            if inner_kind == "R" and o.kind == "R":
                r0 = inner_point - o.point
                l2 = float(r0 @ r0)
                if not l2 > 0.0:
                    raise NoClosedForm("a dyad link with its two joints at one point")
                self.r0_scaled[X] = (float(r0[0] / l2), float(r0[1] / l2))
                norm *= math.sqrt(l2)
        self.inv_norm = 1.0 / norm
        # constant offsets (plain numbers), computed once: of each end's joint point on its
        # known link (the inner point q for a prismatic end) from that link's centre of gravity,
        # of each link's centre of gravity from its outer point (a turning link) or from the
        # known link's (a sliding link), and of q from each link's centre of gravity
        self.end_v = [_vec(o.point if o.kind == "R" else inner_point, o.kg0) for o in outer]
        self.pose_v = [
            _vec(g0[X], o.point if o.kind == "R" else o.kg0) for X, o in enumerate(outer)
        ]
        self.q_v = [_vec(inner_point, g0[X]) for X in (0, 1)]
        # squared lengths |q - o|^2 of the turning ends (circles)
        self.l2 = [float(np.sum((inner_point - o.point) ** 2)) for o in outer]
        if inner_kind == "P":
            g, sl = outer[guide], outer[1 - guide]
            self.c0 = float(inner_normal @ (sl.point - g.point))

    def _drawn_sign(self) -> float:
        """Branch sign sigma of the drawn configuration (module docstring)."""
        q0 = self.q0
        oa, ob = self.outer
        if self.inner_kind == "R":
            if self.kinds == "RR":
                w = ob.point - oa.point
                value = w[0] * (q0[1] - oa.point[1]) - w[1] * (q0[0] - oa.point[0])
            elif self.kinds == "PP":
                return 1.0  # a line-line intersection has one solution
            else:
                r_end, p_end = (oa, ob) if self.kinds == "RP" else (ob, oa)
                value = float(np.dot(p_end.d0, q0 - r_end.point))
        else:
            if self.kinds != "RR":
                return 1.0  # linear in the slide
            g, s = self.outer[self.guide], self.outer[1 - self.guide]
            w = s.point - g.point
            value = self.n0[0] * w[1] - self.n0[1] * w[0]
        if not abs(value) > 0.0:
            raise NoClosedForm("the drawn dyad is singular")
        return math.copysign(1.0, value)

    def _drawn_det_sign(self) -> float:
        """Sign of the dyad's determinant in the drawn configuration (module docstring)."""
        q0 = self.q0
        if self.inner_kind == "R":
            e = []
            for o in self.outer:
                if o.kind == "R":
                    r = q0 - o.point
                    e.append((-r[1], r[0]))
                else:
                    e.append(o.d0)
            value = e[1][0] * e[0][1] - e[1][1] * e[0][0]
        elif self.kinds == "RR":
            w = self.outer[1 - self.guide].point - self.outer[self.guide].point
            value = self.n0[0] * w[1] - self.n0[1] * w[0]
        else:
            value = float(self.n0 @ self.outer[0 if self.kinds == "PR" else 1].d0)
        if not abs(value) > 0.0:
            raise NoClosedForm("the drawn dyad is singular")
        return math.copysign(1.0, value)

    def _end(self, states: _States, X: int) -> tuple[Any, ...]:
        """Known data of end X: ("R", pin) or ("P", C, d) as (value, ', '') triples."""
        o = self.outer[X]
        known = states[o.k]
        if o.kind == "R":
            return ("R", _material(known, self.end_v[X]))
        return ("P", _material(known, self.end_v[X]), _direction(known, o.d0))

    def solve(self, states: _States, out: np.ndarray) -> None:
        """Add the states of both links to ``states`` (dict index -> state), their arrays
        written into their rows of ``out`` ((3, 3n, B), :meth:`ClosedForm.evaluate`)."""
        rows = [out[:, 3 * (i - 1) : 3 * i] for i in self.links]
        if self.inner_kind == "R":
            self._inner_revolute(states, rows)
        elif self.kinds == "RR":
            self._rpr(states, rows)
        else:
            self._rpp(states, rows)

    # ---- inner revolute: RRR, RRP, PRP -----------------------------------------------------
    def _inner_revolute(self, states: _States, rows: list[np.ndarray]) -> None:
        ends = [self._end(states, 0), self._end(states, 1)]
        sig = self.sigma
        u: list[Any] = [None, None]
        if self.kinds == "RR":
            (pa, _pa1, _pa2), (pb, _pb1, _pb2) = ends[0][1], ends[1][1]
            la2, lb2 = self.l2
            wx, wy = pb[0] - pa[0], pb[1] - pa[1]
            d2 = wx * wx + wy * wy
            f = 0.5 * (la2 - lb2 + d2) / d2
            g2 = la2 / d2 - f * f
            _check(g2)
            g = sig * np.sqrt(g2)
            qx = pa[0] + f * wx - g * wy
            qy = pa[1] + f * wy + g * wx
        elif self.kinds == "PP":
            (_, (ca, _ca1, _ca2), da), (_, (cb, _cb1, _cb2), db) = ends
            ea, eb = da[0], db[0]
            det = eb[0] * ea[1] - eb[1] * ea[0]  # e_a x (-e_b)
            _check_det(det, self.det_sign)
            rhs = (cb[0] - ca[0], cb[1] - ca[1])
            ua, ub = _solve2(ea, eb, rhs, det)
            u = [ua, ub]
            qx, qy = ca[0] + ua * ea[0], ca[1] + ua * ea[1]
        else:
            ir = 0 if self.kinds == "RP" else 1
            ip = 1 - ir
            (p, _p1, _p2) = ends[ir][1]
            (c, _c1, _c2), (d, _d1, _d2) = ends[ip][1], ends[ip][2]
            l2 = self.l2[ir]
            vx, vy = c[0] - p[0], c[1] - p[1]
            beta = d[0] * vx + d[1] * vy
            disc = beta * beta - (vx * vx + vy * vy - l2)
            _check(disc)
            up = sig * np.sqrt(disc) - beta
            u[ip] = up
            qx, qy = c[0] + up * d[0], c[1] + up * d[1]
        # directions e_X and the known parts of the rates
        e: list[Any] = []
        k1: list[Any] = []
        r: list[Any] = [None, None]
        for X, end in enumerate(ends):
            if end[0] == "R":
                (p, p1, _p2) = end[1]
                rx, ry = qx - p[0], qy - p[1]
                r[X] = (rx, ry)
                e.append((-ry, rx))
                k1.append(p1)
            else:
                (_c, c1, _c2), (d, d1, _d2) = end[1], end[2]
                e.append(d)
                k1.append((_add(c1[0], _mul(u[X], d1[0])), _add(c1[1], _mul(u[X], d1[1]))))
        ea, eb = e
        det = eb[0] * ea[1] - eb[1] * ea[0]
        if self.kinds != "PP":  # |e_X| is the constant |q - o| of a turning end, 1 of a slide
            _check_det(det, self.det_sign, self.inv_norm)
        x1 = _solve2(ea, eb, (_sub(k1[1][0], k1[0][0]), _sub(k1[1][1], k1[0][1])), det)
        k2 = []
        w2: list[Any] = [None, None]
        for X, end in enumerate(ends):
            if end[0] == "R":
                (_p, _p1, p2) = end[1]
                w2[X] = x1[X] * x1[X]
                k2.append((p2[0] - w2[X] * r[X][0], p2[1] - w2[X] * r[X][1]))
            else:
                (_c, _c1, c2), (_d, d1, d2) = end[1], end[2]
                u2 = 0.0 if _zero(d1[0]) and _zero(d1[1]) else 2.0 * x1[X]  # 2 u' (d' turns)
                k2.append(
                    (
                        _add(_add(c2[0], _mul(u2, d1[0])), _mul(u[X], d2[0])),
                        _add(_add(c2[1], _mul(u2, d1[1])), _mul(u[X], d2[1])),
                    )
                )
        x2 = _solve2(ea, eb, (_sub(k2[1][0], k2[0][0]), _sub(k2[1][1], k2[0][1])), det)
        for X, end in enumerate(ends):
            o, link = self.outer[X], self.links[X]
            if end[0] == "R":
                u0x, u0y = self.r0_scaled[X]  # (q - o) / |q - o|^2
                rx, ry = r[X]
                c = rx * u0x + ry * u0y
                s = ry * u0x - rx * u0y
                st = _pose_about(end[1], c, s, x1[X], x2[X], self.pose_v[X], rows[X], w2[X])
                states[link] = (*st[:4], np.arctan2(s, c, out=rows[X][0, 2]), *st[5:])
            else:
                states[link] = _pose_sliding(
                    states[o.k], self.pose_v[X], end[2], (u[X], x1[X], x2[X]), rows[X]
                )

    # ---- inner prismatic, both outer joints revolute: RPR ------------------------------------
    def _rpr(self, states: _States, rows: list[np.ndarray]) -> None:
        gi, si = self.guide, 1 - self.guide
        (pg, pg1, pg2) = self._end(states, gi)[1]
        (ps, ps1, ps2) = self._end(states, si)[1]
        n0 = self.n0
        c0 = self.c0
        wx, wy = ps[0] - pg[0], ps[1] - pg[1]
        a = n0[0] * wx + n0[1] * wy
        b = n0[0] * wy - n0[1] * wx
        r2 = a * a + b * b
        h2 = r2 - c0 * c0
        _check(h2)
        h = self.sigma * np.sqrt(h2)
        c = (a * c0 + h * b) / r2
        s = (b * c0 - h * a) / r2
        nx, ny = c * n0[0] - s * n0[1], s * n0[0] + c * n0[1]
        det = nx * wy - ny * wx  # n x w
        _check_det(det / np.sqrt(r2), self.det_sign)
        w1x, w1y = ps1[0] - pg1[0], ps1[1] - pg1[1]
        w2x, w2y = ps2[0] - pg2[0], ps2[1] - pg2[1]
        omega = -(nx * w1x + ny * w1y) / det
        omega2 = omega * omega
        alpha = (
            omega2 * (nx * wx + ny * wy)
            - 2.0 * omega * (nx * w1y - ny * w1x)
            - (nx * w2x + ny * w2y)
        ) / det
        phi = np.arctan2(s, c, out=rows[0][0, 2])
        for X in (0, 1):
            pin = (pg, pg1, pg2) if gi == X else (ps, ps1, ps2)
            st = _pose_about(pin, c, s, omega, alpha, self.pose_v[X], rows[X], omega2)
            states[self.links[X]] = (*st[:4], _put(rows[X][0, 2], phi), *st[5:])

    # ---- inner prismatic, one outer prismatic: RPP -------------------------------------------
    def _rpp(self, states: _States, rows: list[np.ndarray]) -> None:
        ir = 0 if self.kinds == "RP" else 1
        ip = 1 - ir
        o_p = self.outer[ip]
        known = states[o_p.k]  # both links turn with it
        _gx, _gy, c, s, phi, _gxp, _gyp, w, _gxpp, _gypp, al = known
        pin = self._end(states, ir)[1]
        st = _pose_about(pin, c, s, w, al, self.pose_v[ir], rows[ir])
        states[self.links[ir]] = (*st[:4], _put(rows[ir][0, 2], phi), *st[5:])
        (kx, ky), (k1x, k1y), (k2x, k2y) = _material(known, self.end_v[ip])
        (rx, ry), (r1x, r1y), (r2x, r2y) = _material(states[self.links[ir]], self.q_v[ir])
        mx, my, m1x, m1y, m2x, m2y = kx - rx, ky - ry, k1x - r1x, k1y - r1y, k2x - r2x, k2y - r2y
        (nx, ny), (n1x, n1y), (n2x, n2y) = _direction(known, self.n0)
        d = _direction(known, o_p.d0)
        (dx, dy), (d1x, d1y), (d2x, d2y) = d
        nd = nx * dx + ny * dy
        _check_det(nd, self.det_sign)
        u0 = -(nx * mx + ny * my) / nd
        vx, vy = mx + u0 * dx, my + u0 * dy
        u1 = -(n1x * vx + n1y * vy + nx * (m1x + u0 * d1x) + ny * (m1y + u0 * d1y)) / nd
        v1x, v1y = m1x + u1 * dx + u0 * d1x, m1y + u1 * dy + u0 * d1y
        u2 = (
            -(
                n2x * vx
                + n2y * vy
                + 2.0 * (n1x * v1x + n1y * v1y)
                + nx * (m2x + 2.0 * u1 * d1x + u0 * d2x)
                + ny * (m2y + 2.0 * u1 * d1y + u0 * d2y)
            )
            / nd
        )
        states[self.links[ip]] = _pose_sliding(known, self.pose_v[ip], d, (u0, u1, u2), rows[ip])


class ClosedForm:
    """The closed-form plan of a mechanism: the crank, then its dyads in kinematic order.

    :meth:`evaluate` gives q, q', q'' (per unit crank speed) at crank angles, with the rotations
    of the dyad links wrapped to (-pi, pi] (the caller continues them along its path), or raises
    :class:`NoClosedForm` where a position needs the general solver.

    Parameters
    ----------
    mech : crankdyn.linkage.planar.Mechanism
        The mechanism.
    model : crankdyn.linkage.solver.KinematicModel
        Its coordinates in the drawn configuration (``mech._model``).

    Raises
    ------
    NoClosedForm
        If a link group has no closed form here (module docstring).

    Examples
    --------
    A central slider-crank (R = 50 mm, L = 200 mm) drawn at 30 deg: at 90 deg the slider
    (link 3) is at sqrt(L^2 - R^2) = 0.193649 m.

    >>> from crankdyn.linkage.planar import slider_crank_mechanism
    >>> mech = slider_crank_mechanism(0.05, 0.2)
    >>> q = ClosedForm(mech, mech._model).evaluate(np.array([math.pi / 2]))[0]
    >>> round(float(q[6, 0]), 6)
    0.193649
    """

    def __init__(self, mech: Mechanism, model: KinematicModel) -> None:
        index = model.index
        g0 = model.g0
        joints = {j.name: j for j in mech.joints}
        crank = index[mech.crank]
        self.n = model.n
        self.crank = crank
        self.theta0 = model.theta0
        self.crank_g0 = g0[crank]
        self.pivot = mech.point_map[joints[mech.driver.joint].point]
        self.pivot_pin = ((float(self.pivot[0]), float(self.pivot[1])), (0.0, 0.0), (0.0, 0.0))
        self.crank_v = _vec(self.crank_g0, self.pivot)
        known = {0, crank}
        self.dyads: list[_Dyad] = []
        pm = mech.point_map
        for group in reversed(mech.link_groups()[:-1]):
            if len(group.links) != 2:
                raise NoClosedForm(f"{group.kind} has no closed form")
            a, b = group.links
            js = [joints[n] for n in group.joints]
            inner = [j for j in js if set(j.links) == {a, b}]
            outer = []
            for link in (a, b):
                mine = [j for j in js if link in j.links and set(j.links) != {a, b}]
                if len(mine) != 1 or len(inner) != 1:
                    raise NoClosedForm("not a dyad of one inner and two outer joints")
                j = mine[0]
                other = j.links[0] if j.links[1] == link else j.links[1]
                k = 0 if other == GROUND else index[other]
                if k not in known:
                    raise NoClosedForm("a dyad attached to a link not yet known")
                d0 = None
                if j.kind == "prismatic":
                    assert j.axis is not None  # a prismatic joint has its guide
                    d0 = np.array([math.cos(j.axis), math.sin(j.axis)])
                kind = "R" if j.kind == "revolute" else "P"
                outer.append(_Outer(kind, k, g0[k], pm[j.point], d0))
            ij = inner[0]
            ia, ib = index[a], index[b]
            normal, guide = None, 0
            if ij.kind == "prismatic":
                assert ij.axis is not None  # a prismatic joint has its guide
                normal = np.array([-math.sin(ij.axis), math.cos(ij.axis)])
                guide = 0 if ij.links[0] == a else 1
            dyad = _Dyad(
                (ia, ib),
                (g0[ia], g0[ib]),
                outer,
                "R" if ij.kind == "revolute" else "P",
                pm[ij.point],
                normal,
                guide,
            )
            self.dyads.append(dyad)
            known |= {ia, ib}
        if len(known) != self.n + 1:
            raise NoClosedForm("some links are in no dyad")
        # links whose rotation comes out of an arctangent, wrapped to (-pi, pi] (or is copied
        # from such a link): the caller continues them along its path; their rows in q are
        # ``rotation_rows`` (a slice over the span of them; links in between are continued too,
        # harmlessly). None when there is none (only PRP and RPP dyads after the crank).
        wrapped: set[int] = set()
        for d in self.dyads:
            if d.inner_kind == "R":
                for X, o in enumerate(d.outer):
                    if o.kind == "R" or o.k in wrapped:
                        wrapped.add(d.links[X])
            elif d.kinds == "RR" or d.outer[0 if d.kinds == "PR" else 1].k in wrapped:
                wrapped |= set(d.links)
        self.rotation_rows = None
        if wrapped:
            lo, hi = min(wrapped), max(wrapped)
            self.rotation_rows = slice(3 * lo - 1, 3 * hi, 3)

    def evaluate(self, theta: ArrayLike, out: np.ndarray | None = None) -> np.ndarray:
        """q, q', q'' (per unit crank speed) at crank angles.

        Parameters
        ----------
        theta : array_like
            (B,) crank angles (rad).
        out : numpy.ndarray or None
            A (3, 3n, B) array to write into, or None.

        Returns
        -------
        numpy.ndarray
            (3, 3n, B): q, q', q'', each the rows x_G, y_G (m; m/rad, m/rad^2), phi (rad;
            dimensionless, 1/rad) of every moving link (the transpose of the (B, 3n) layout of
            :class:`~crankdyn.linkage.motion.MechanismMotion`). Rotations of dyad links are
            wrapped to (-pi, pi].

        Raises
        ------
        NoClosedForm
            Where a dyad is infeasible or nearly singular.
        """
        theta = np.asarray(theta, dtype=float)
        if out is None:
            out = np.empty((3, 3 * self.n, theta.shape[0]))
        rows = out[:, 3 * (self.crank - 1) : 3 * self.crank]
        phi = np.subtract(theta, self.theta0, out=rows[0, 2])
        c, s = np.cos(phi), np.sin(phi)
        st = _pose_about(self.pivot_pin, c, s, 1.0, 0.0, self.crank_v, rows)
        states = {0: _GROUND_STATE, self.crank: (*st[:4], phi, *st[5:])}
        for dyad in self.dyads:  # each writes its links' rows of ``out`` once
            dyad.solve(states, out)
        return out


def closed_form(mech: Mechanism, model: KinematicModel) -> ClosedForm | None:
    """The closed-form plan of a mechanism.

    Parameters
    ----------
    mech : crankdyn.linkage.planar.Mechanism
        The mechanism.
    model : crankdyn.linkage.solver.KinematicModel
        Its coordinates in the drawn configuration.

    Returns
    -------
    ClosedForm or None
        The plan; None when a group has no closed form.
    """
    try:
        return ClosedForm(mech, model)
    except NoClosedForm:
        return None
