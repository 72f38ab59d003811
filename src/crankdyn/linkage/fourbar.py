"""Four-bar linkage in closed form: Grashof class, limits, positions, velocities, accelerations.

Numeric core and domain object, vectorized over the crank angle (no loop over angles).

Conventions (docs/theory-linkage.md)
------------------------------------
Crank pivot A at the origin, rocker pivot D at (d, 0): every angle is measured counter-clockwise
from the ground line A->D. Crank AB = a (input, angle theta2), coupler BC = b (theta3, the angle
of B->C), rocker DC = c (theta4, the angle of D->C), ground AD = d. Angular speeds are positive
counter-clockwise. The loop closure is

    a e^{i theta2} + b e^{i theta3} = d + c e^{i theta4}                      (1)

Positions (circle intersection). With B = a e^{i theta2}, f = |D - B| and u = (D - B)/f, the
joint C lies on the circles |C - B| = b and |C - D| = c:

    C = B + g u + s h (i u),   g = (b^2 - c^2 + f^2) / (2 f),   h = sqrt(b^2 - g^2)       (2)

where s = +1 or -1 picks the assembly branch: **open** (s = +1) puts C to the left of the
directed line B->D, which is the convex, uncrossed quadrilateral ABCD whenever the crank is above
the ground line (0 < theta2 < 180 deg); **crossed** (s = -1) is its mirror image in BD. The
branch is kept for every crank angle (Norton 2012, Design of Machinery, 5th ed., sec. 4.5, the
"open" and "crossed" circuits of eq. 4.10). The links assemble only when |b - c| <= f <= b + c.

At a change point (s + l = p + q) the two branches meet when all four links are collinear
(f = b + c or |b - c| at theta2 = 0 or 180 deg, h = 0 with a double root). When this happens at
both 0 and 180 deg (parallelogram and antiparallelogram linkages) the smooth motion continues on
the mirror sign, so s flips for 180 < theta2 < 360 deg and a parallelogram linkage stays a
parallelogram all round. With a single in-line position per turn the smooth motion would need
two turns to close, so the geometric sign is kept and the motion has a kink there. Velocities are
indeterminate exactly at in-line positions (the mechanism can bifurcate) and are returned as NaN
with the ``singular`` mask set.

Velocities: differentiating (1), multiplying by e^{-i theta4} and e^{-i theta3} and taking
imaginary parts (Norton eq. 6.18; Freudenstein's vector-loop method):

    omega3 = a omega2 sin(theta4 - theta2) / (b sin(theta3 - theta4))
    omega4 = a omega2 sin(theta2 - theta3) / (c sin(theta4 - theta3))                (3)

Accelerations: differentiating again, with K = a (i alpha2 - omega2^2) e^{i theta2}
- b omega3^2 e^{i theta3} + c omega4^2 e^{i theta4} (the known part) (Norton eq. 7.12):

    alpha3 = Re(K e^{-i theta4}) / (b sin(theta3 - theta4))
    alpha4 = -Re(K e^{-i theta3}) / (c sin(theta4 - theta3))                        (4)

Transmission angle mu: the interior angle BCD between coupler and rocker, by the cosine rule
cos mu = (b^2 + c^2 - f^2)/(2 b c) with f^2 = a^2 + d^2 - 2 a d cos theta2 (Norton eq. 4.32);
its extremes for a turning crank are at theta2 = 0 (f = |d - a|) and 180 deg (f = d + a).

Grashof condition (Norton sec. 2.12, Table 2-4; seed 004 sec. 1.2 "杆长条件"): with s, l the
shortest and longest links and p, q the others, s + l < p + q gives a Grashof linkage, in which
the shortest link turns fully relative to its neighbours: a double-crank (drag link) when the
shortest is the ground, a crank-rocker when it is the input crank, a rocker-crank when it is the
output, a double-rocker when it is the coupler. s + l = p + q is a change-point linkage;
s + l > p + q a non-Grashof triple rocker (no link turns fully).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import DEG
from crankdyn.crank.geometry import check_finite, check_length
from crankdyn.errors import InputError
from crankdyn.linkage.elements import GROUND, Driver, Joint, Link
from crankdyn.linkage.planar import Mechanism
from crankdyn.plausibility import PlausibilityWarning, check_transmission_angle
from crankdyn.results import Result, column, freeze, scalar

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.linkage.elements import Force, Torque

__all__ = [
    "BRANCHES",
    "GRASHOF_TYPES",
    "FourBar",
    "FourBarLimits",
    "FourBarMotion",
    "FourBarResult",
    "fourbar_analysis",
    "fourbar_mechanism",
    "fourbar_motion",
    "fourbar_positions",
    "grashof_type",
    "transmission_angle",
]

TWO_PI = 2.0 * math.pi
BRANCHES = ("open", "crossed")
"""The assembly branches (module docstring)."""
GRASHOF_TYPES = (
    "crank-rocker",
    "double-crank",
    "rocker-crank",
    "double-rocker",
    "change-point",
    "triple-rocker",
)
"""The Grashof classes :func:`grashof_type` returns."""
_REL_TOL = 1e-12  # relative tolerance of length comparisons (change point, collinearity)
_SINGULAR_TOL = 1e-9  # |sin(theta3 - theta4)| below which a position counts as singular


def grashof_type(a: float, b: float, c: float, d: float) -> str:
    """Grashof class of a four-bar.

    Norton (2012) sec. 2.12 and Table 2-4; seed 004 ("杆长条件": shortest + longest <= sum of the
    other two, the shortest link a side link gives a crank-rocker).

    Parameters
    ----------
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths (any one unit, e.g. m).

    Returns
    -------
    str
        ``"crank-rocker"`` (shortest = crank), ``"double-crank"`` (shortest = ground),
        ``"rocker-crank"`` (shortest = rocker: the output turns, the input rocks),
        ``"double-rocker"`` (shortest = coupler), ``"change-point"`` (s + l = p + q) or
        ``"triple-rocker"`` (non-Grashof, s + l > p + q).

    Examples
    --------
    Seed 004's first measured link set (sec. 1.2, mm): s + l = 198.76 < p + q = 206.92, the
    shortest link the crank.

    >>> grashof_type(0.0734, 0.12536, 0.1034, 0.10352)
    'crank-rocker'
    >>> grashof_type(0.12536, 0.1034, 0.10352, 0.0734)  # the shortest link as the ground
    'double-crank'
    """
    lengths = [float(a), float(b), float(c), float(d)]
    ordered = sorted(lengths)
    s, p, q, l = ordered
    excess = (s + l) - (p + q)
    if abs(excess) <= _REL_TOL * l * 4:
        return "change-point"
    if excess > 0.0:
        return "triple-rocker"
    shortest = lengths.index(s)
    return ("crank-rocker", "double-rocker", "rocker-crank", "double-crank")[shortest]


def transmission_angle(
    theta2: ArrayLike, a: float, b: float, c: float, d: float
) -> NDArray[np.float64]:
    """Transmission angle mu, the interior angle BCD between coupler and rocker.

    cos mu = (b^2 + c^2 - a^2 - d^2 + 2 a d cos theta2)/(2 b c) (Norton eq. 4.32).

    Parameters
    ----------
    theta2 : array_like
        Crank angles (rad).
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths (m).

    Returns
    -------
    numpy.ndarray
        mu (rad) in [0, pi]; NaN where the links cannot be assembled.

    Examples
    --------
    A parallelogram linkage at 90 deg: the coupler and the rocker meet at right angles.

    >>> round(float(np.degrees(transmission_angle(np.pi / 2, 1.0, 2.0, 1.0, 2.0))), 9)
    90.0
    """
    theta2 = np.asarray(theta2, dtype=float)
    f2 = a * a + d * d - 2.0 * a * d * np.cos(theta2)
    cos_mu = (b * b + c * c - f2) / (2.0 * b * c)
    out = np.full(theta2.shape, np.nan)
    ok = np.abs(cos_mu) <= 1.0 + 1e-12
    out[ok] = np.arccos(np.clip(cos_mu[ok], -1.0, 1.0))
    return out


def _singular_crank_angles(a: float, b: float, c: float, d: float) -> list[float]:
    """Crank angles (0 and/or pi) at which a change-point linkage is all in line."""
    out = []
    scale = max(a, b, c, d)
    for theta, f in ((0.0, abs(d - a)), (math.pi, d + a)):
        if min(abs(f - (b + c)), abs(f - abs(b - c))) <= 4 * _REL_TOL * scale:
            out.append(theta)
    return out


def _branch_sign(theta2: ArrayLike, sign: float, singular: list[float]) -> np.ndarray:
    """Branch sign s(theta2): constant, except that a change-point linkage in line at both 0
    and 180 deg continues smoothly onto the mirror sign for 180 < theta2 < 360 deg."""
    theta2 = np.asarray(theta2, dtype=float)
    s = np.full(theta2.shape, float(sign))
    if len(singular) == 2:
        lower_half = np.mod(theta2, TWO_PI) > math.pi
        s[lower_half] = -s[lower_half]
    return s


def fourbar_positions(
    theta2: ArrayLike, a: float, b: float, c: float, d: float, branch: str = "open"
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Coupler and rocker angles of a four-bar by circle intersection, eq. (2) above.

    Parameters
    ----------
    theta2 : array_like
        Crank angles (rad) from the ground line A->D, counter-clockwise.
    a, b, c, d : float
        Crank, coupler, rocker and ground lengths (m).
    branch : str
        ``"open"`` (default) or ``"crossed"`` (module docstring).

    Returns
    -------
    theta3, theta4 : numpy.ndarray
        Coupler angle (of B->C) and rocker angle (of D->C) in rad, in (-pi, pi]; NaN where the
        links cannot be assembled.

    Examples
    --------
    A parallelogram stays one on the open branch: the coupler parallel to the ground, the
    rocker parallel to the crank.

    >>> t3, t4 = fourbar_positions(np.radians([60.0]), 1.0, 2.0, 1.0, 2.0)
    >>> round(float(np.degrees(t3[0])), 9), round(float(np.degrees(t4[0])), 9)
    (0.0, 60.0)
    """
    theta2 = np.asarray(theta2, dtype=float)
    sign = 1.0 if branch == "open" else -1.0
    s = _branch_sign(theta2, sign, _singular_crank_angles(a, b, c, d))
    bx, by = a * np.cos(theta2), a * np.sin(theta2)
    ux, uy = d - bx, -by
    f = np.hypot(ux, uy)
    # B on D (f -> 0) makes g overflow: no intersection there unless b = c, reported as NaN
    with np.errstate(invalid="ignore", divide="ignore", over="ignore"):
        ux, uy = ux / f, uy / f
        g = (b * b - c * c + f * f) / (2.0 * f)
        h2 = b * b - g * g
        tol = 4 * _REL_TOL * max(a, b, c, d) ** 2
        h = np.where(h2 >= -tol, np.sqrt(np.maximum(h2, 0.0)), np.nan)
        cx = bx + g * ux - s * h * uy
        cy = by + g * uy + s * h * ux
        theta3 = np.arctan2(cy - by, cx - bx)
        theta4 = np.arctan2(cy, cx - d)
    bad = ~np.isfinite(h)
    theta3[bad] = np.nan
    theta4[bad] = np.nan
    return theta3, theta4


@dataclass(frozen=True, eq=False, slots=True)
class FourBarMotion:
    """Angles, angular velocities and accelerations of a four-bar at a set of crank angles;
    arrays of one shape (:func:`fourbar_motion`).

    Parameters
    ----------
    theta2, theta3, theta4 : numpy.ndarray
        Crank, coupler (B->C) and rocker (D->C) angles (rad).
    omega2, omega3, omega4 : numpy.ndarray
        Their angular velocities (rad/s), counter-clockwise positive.
    alpha2, alpha3, alpha4 : numpy.ndarray
        Their angular accelerations (rad/s^2).
    singular : numpy.ndarray
        Bool: the coupler and rocker are in line (velocities indeterminate, NaN).
    """

    theta2: NDArray[np.float64]
    theta3: NDArray[np.float64]
    theta4: NDArray[np.float64]
    omega2: NDArray[np.float64]
    omega3: NDArray[np.float64]
    omega4: NDArray[np.float64]
    alpha2: NDArray[np.float64]
    alpha3: NDArray[np.float64]
    alpha4: NDArray[np.float64]
    singular: NDArray[np.bool_]


def fourbar_motion(
    theta2: ArrayLike,
    a: float,
    b: float,
    c: float,
    d: float,
    omega2: ArrayLike = 1.0,
    alpha2: ArrayLike = 0.0,
    branch: str = "open",
) -> FourBarMotion:
    """Positions, angular velocities and accelerations of all links, eqs. (2)-(4) above
    (Norton 2012, eqs. 4.10, 6.18, 7.12).

    Parameters
    ----------
    theta2 : array_like
        Crank angles (rad).
    a, b, c, d : float
        Link lengths (m).
    omega2 : array_like
        Crank angular velocity (rad/s), a scalar or an array like theta2; default 1.
    alpha2 : array_like
        Crank angular acceleration (rad/s^2), likewise; default 0.
    branch : str
        ``"open"`` (default) or ``"crossed"``.

    Returns
    -------
    FourBarMotion
        Angles (rad), angular velocities (rad/s) and accelerations (rad/s^2); NaN where the
        links do not assemble or are singular.
    """
    theta2 = np.asarray(theta2, dtype=float)
    theta3, theta4 = fourbar_positions(theta2, a, b, c, d, branch)
    w2 = np.broadcast_to(np.asarray(omega2, dtype=float), theta2.shape)
    e2 = np.broadcast_to(np.asarray(alpha2, dtype=float), theta2.shape)
    s34 = np.sin(theta3 - theta4)
    singular = np.abs(s34) < _SINGULAR_TOL
    with np.errstate(invalid="ignore", divide="ignore"):
        den = np.where(singular, np.nan, s34)
        w3 = a * w2 * np.sin(theta4 - theta2) / (b * den)
        w4 = a * w2 * np.sin(theta2 - theta3) / (c * -den)
        e_i2, e_i3, e_i4 = np.exp(1j * theta2), np.exp(1j * theta3), np.exp(1j * theta4)
        k = a * (1j * e2 - w2 * w2) * e_i2 - b * w3 * w3 * e_i3 + c * w4 * w4 * e_i4
        e3 = np.real(k / e_i4) / (b * den)
        e4 = -np.real(k / e_i3) / (c * -den)
    return FourBarMotion(
        theta2=theta2,
        theta3=theta3,
        theta4=theta4,
        omega2=np.array(w2),
        omega3=w3,
        omega4=w4,
        alpha2=np.array(e2),
        alpha3=e3,
        alpha4=e4,
        singular=singular & np.isfinite(theta3),
    )


# ---- the domain object ------------------------------------------------------------------------


def _length(name: str, value: object) -> float:
    number = check_finite(name, value)
    if number <= 0.0:
        raise InputError("a link length must be positive", key=name, value=value)
    return check_length(name, number, "a link length")


@dataclass(frozen=True)
class FourBarLimits(Result):
    """Closed-form characteristics of a four-bar on one branch, no sampling
    (:attr:`FourBar.limits`)."""

    title = "Four-bar characteristics"
    grashof_type: str = scalar("grashof_type", "Grashof type", "")
    grashof_sum: float = scalar("grashof_excess_m", "s + l - (p + q)", "m")
    crank_rotates: bool = scalar("crank_rotates", "Crank turns fully", "")
    crank_ranges: tuple[tuple[float, float], ...] = scalar(
        "crank_angle_ranges_deg", "Crank angle ranges", "deg", DEG
    )
    transmission_angle_min: float = scalar(
        "transmission_angle_min_deg", "Min transmission angle", "deg", DEG, fmt=".5g"
    )
    transmission_angle_max: float = scalar(
        "transmission_angle_max_deg", "Max transmission angle", "deg", DEG, fmt=".5g"
    )
    transmission_angle_worst: float = scalar(
        "transmission_angle_worst_deg", "Worst transmission angle min(μ, 180°-μ)", "deg", DEG
    )
    rocker_angle_min: float | None = scalar(
        "rocker_angle_min_deg", "Min rocker angle", "deg", DEG, fmt=".5g"
    )
    rocker_angle_max: float | None = scalar(
        "rocker_angle_max_deg", "Max rocker angle", "deg", DEG, fmt=".5g"
    )
    rocker_swing: float | None = scalar("rocker_swing_deg", "Rocker swing", "deg", DEG, fmt=".5g")
    toggle_crank_angles: tuple[float, ...] = scalar(
        "toggle_crank_angles_deg", "Crank angles at crank-coupler toggles", "deg", DEG
    )
    dead_point_crank_angles: tuple[float, ...] = scalar(
        "dead_point_crank_angles_deg", "Crank angles at coupler-rocker dead points", "deg", DEG
    )
    time_ratio: float | None = scalar("time_ratio", "Time ratio (slow/fast stroke)", "", fmt=".5g")
    forward_stroke_crank_angle: float | None = scalar(
        "forward_stroke_crank_angle_deg", "Crank angle, stroke 1 (max->min rocker)", "deg", DEG
    )


@dataclass(frozen=True)
class FourBar:
    """A four-bar linkage (domain object); all lengths in m.

    Parameters
    ----------
    crank, coupler, rocker, ground : float
        Link lengths a = AB, b = BC, c = DC, d = AD (m), positive.
    branch : str
        Assembly branch, ``"open"`` (default) or ``"crossed"`` (see the module docstring).
    coupler_point : (float, float) or None
        Optional coupler point P as (p, q) (m): p along B->C and q perpendicular to it, to the
        left (counter-clockwise); P = B + (p + i q) e^{i theta3}.

    Raises
    ------
    InputError
        If a length is not a positive length, the branch is unknown, the coupler point is not
        two numbers, or one link is not shorter than the other three together.

    Examples
    --------
    Seed 004's first measured link set (sec. 1.2), AB = 73.4, BC = 125.36, DC = 103.4,
    AD = 103.52 mm, a crank-rocker; its smallest transmission angle is at theta2 = 0, where
    cos mu = (b^2 + c^2 - (d - a)^2) / (2 b c) (Norton eq. 4.32):

    >>> fb = FourBar(0.0734, 0.12536, 0.1034, 0.10352)
    >>> fb.grashof_type, fb.crank_rotates
    ('crank-rocker', True)
    >>> round(math.degrees(fb.limits.transmission_angle_min), 6)
    10.388635
    >>> a, b, c, d = fb.lengths
    >>> round(math.degrees(math.acos((b * b + c * c - (d - a) ** 2) / (2 * b * c))), 6)
    10.388635
    """

    crank: float
    coupler: float
    rocker: float
    ground: float
    branch: str = "open"
    coupler_point: tuple[float, float] | None = None
    _limits: FourBarLimits | None = field(default=None, init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        for name in ("crank", "coupler", "rocker", "ground"):
            object.__setattr__(self, name, _length(name, getattr(self, name)))
        if self.branch not in BRANCHES:
            raise InputError(
                f"expected one of {', '.join(BRANCHES)}", key="branch", value=self.branch
            )
        if self.coupler_point is not None:
            try:
                p, q = (check_finite("coupler_point", v) for v in self.coupler_point)
            except (TypeError, ValueError):
                raise InputError(
                    "expected two distances (along and across the coupler)",
                    key="coupler_point",
                    value=self.coupler_point,
                ) from None
            object.__setattr__(self, "coupler_point", (p, q))
        a, b, c, d = self.lengths
        if a + b + c <= d or a + b + d <= c or a + c + d <= b or b + c + d <= a:
            longest = max(self.lengths)
            name = ("crank", "coupler", "rocker", "ground")[self.lengths.index(longest)]
            raise InputError(
                f"the links cannot be assembled at any crank angle: the {name} "
                f"({longest * 1e3:.6g} mm) is not shorter than the other three together "
                f"({(sum(self.lengths) - longest) * 1e3:.6g} mm)",
                key=name,
                value=longest,
            )

    @property
    def lengths(self) -> tuple[float, float, float, float]:
        """(a, b, c, d) = crank, coupler, rocker, ground (m)."""
        return (self.crank, self.coupler, self.rocker, self.ground)

    @property
    def grashof_type(self) -> str:
        """The Grashof class (:func:`grashof_type`)."""
        return grashof_type(*self.lengths)

    # ---- feasibility -------------------------------------------------------------------------
    def _cos_bounds(self) -> tuple[float, float]:
        """cos(theta2) must lie in [lo, hi] for |b - c| <= f <= b + c."""
        a, b, c, d = self.lengths
        lo = (a * a + d * d - (b + c) ** 2) / (2 * a * d)
        hi = (a * a + d * d - (b - c) ** 2) / (2 * a * d)
        return lo, hi

    def crank_ranges(self) -> tuple[tuple[float, float], ...]:
        """Intervals of crank angle in which the links assemble.

        Returns
        -------
        tuple of (float, float)
            (start, end) with start < end, in (-pi, 2 pi) (rad); ((0, 2 pi),) when the crank
            turns fully.
        """
        lo, hi = self._cos_bounds()
        eps = 1e-12
        if lo <= -1.0 + eps and hi >= 1.0 - eps:
            return ((0.0, TWO_PI),)
        t_small = math.acos(min(hi, 1.0))  # smallest |theta2|
        t_large = math.acos(max(lo, -1.0))  # largest |theta2|
        if hi >= 1.0 - eps:  # the range contains theta2 = 0
            return ((-t_large, t_large),)
        if lo <= -1.0 + eps:  # the range contains theta2 = pi
            return ((t_small, TWO_PI - t_small),)
        return ((t_small, t_large), (TWO_PI - t_large, TWO_PI - t_small))

    @property
    def crank_rotates(self) -> bool:
        """Whether the input crank turns through a full revolution."""
        return self.crank_ranges() == ((0.0, TWO_PI),)

    def assembly_error(self, theta2: float, key: str = "crank angle") -> InputError:
        """An error saying why the links cannot be assembled at a crank angle.

        Parameters
        ----------
        theta2 : float
            The crank angle (rad).
        key : str
            The key or option for the message; default ``"crank angle"``.

        Returns
        -------
        InputError
            The error (not raised): the distance B-D against the coupler and rocker, and the
            crank angles at which the linkage assembles.
        """
        a, b, c, d = self.lengths
        f = math.sqrt(max(a * a + d * d - 2 * a * d * math.cos(theta2), 0.0))
        if f > b + c:
            why = (
                f"B and D are {f * 1e3:.6g} mm apart, more than coupler + rocker = "
                f"{(b + c) * 1e3:.6g} mm"
            )
        else:
            why = (
                f"B and D are {f * 1e3:.6g} mm apart, less than |coupler - rocker| = "
                f"{abs(b - c) * 1e3:.6g} mm"
            )
        ranges = ", ".join(
            f"{math.degrees(lo):.4g} to {math.degrees(hi):.4g} deg"
            for lo, hi in self.crank_ranges()
        )
        return InputError(
            f"the links cannot be assembled at crank angle {math.degrees(theta2):.6g} deg: "
            f"{why} (a {self.grashof_type} linkage assembles for crank angles {ranges})",
            key=key,
        )

    # ---- closed-form characteristics --------------------------------------------------------
    @property
    def limits(self) -> FourBarLimits:
        """Grashof type, transmission-angle extremes, toggle and dead points, rocker limits and
        time ratio on this branch, in closed form."""
        if self._limits is None:
            limits = self._compute_limits()
            object.__setattr__(self, "_limits", limits)
            return limits
        return self._limits

    def _toggles(self) -> list[tuple[str, float, float]]:
        """Crank-coupler toggle positions on this branch: (kind, theta2, theta4) with kind
        "extended" (AC = a + b) or "folded" (AC = |b - a|), from the triangle ACD."""
        a, b, c, d = self.lengths
        sing = _singular_crank_angles(a, b, c, d)
        out = []
        for kind, r in (("extended", a + b), ("folded", abs(b - a))):
            if r <= 1e-15 * (a + b):
                continue
            # C on the circles |C| = r and |C - D| = c
            x = (r * r - c * c + d * d) / (2 * d)
            y2 = r * r - x * x
            if y2 < -4 * _REL_TOL * max(r, d) ** 2:
                continue
            y = math.sqrt(max(y2, 0.0))
            for cy in {y, -y}:
                theta_c = math.atan2(cy, x)
                theta2 = theta_c if (kind == "extended" or a > b) else theta_c + math.pi
                theta2 = math.remainder(theta2, TWO_PI) % TWO_PI
                bx, by = a * math.cos(theta2), a * math.sin(theta2)
                cross = (d - bx) * (cy - by) - (0.0 - by) * (x - bx)
                s = float(
                    _branch_sign(np.array([theta2]), 1.0 if self.branch == "open" else -1.0, sing)[
                        0
                    ]
                )
                if cross * s < -1e-12 * max(a, b, c, d) ** 2:
                    continue  # this toggle belongs to the other branch
                out.append((kind, theta2, math.atan2(cy, x - d)))
        return out

    def _compute_limits(self) -> FourBarLimits:
        a, b, c, d = self.lengths
        kind = self.grashof_type
        ordered = sorted(self.lengths)
        excess = ordered[0] + ordered[3] - ordered[1] - ordered[2]
        ranges = self.crank_ranges()
        rotates = ranges == ((0.0, TWO_PI),)
        # transmission angle: monotone in f, f monotone in |theta2| on [0, pi]
        lo, hi = self._cos_bounds()
        cos_t = np.array([min(hi, 1.0), max(lo, -1.0)])  # cos theta2 at the ends of the range
        mu = transmission_angle(np.arccos(cos_t), a, b, c, d)
        mu_min, mu_max = float(np.nanmin(mu)), float(np.nanmax(mu))
        worst = min(mu_min, math.pi - mu_max)
        # dead points for a crank drive: coupler and rocker in line (mu = 0 or pi): the ends of
        # the crank's ranges
        dead = () if rotates else tuple(sorted({t % TWO_PI for r in ranges for t in r}))
        toggles = self._toggles()
        toggle_angles = tuple(sorted(t for _k, t, _r in toggles))
        # rocker limits: where d theta4 / d theta2 = 0 (crank and coupler in line) or at the ends
        # of the crank's range; none when the rocker turns fully
        candidates = [t4 for _k, _t2, t4 in toggles]
        if not rotates:
            ends = np.array(sorted({t for r in ranges for t in r}))
            _t3, t4 = fourbar_positions(ends, a, b, c, d, self.branch)
            candidates += [float(v) for v in t4 if np.isfinite(v)]
        # (none either for a double-rocker's two separate circuits: see docs/theory-linkage.md)
        rocker_min = rocker_max = swing = None
        rocker_turns = FourBar(c, b, a, d).crank_rotates  # the rocker as the input

        if candidates and not rocker_turns and len(ranges) == 1:
            rocker_min, rocker_max = _angle_span(candidates)
            swing = rocker_max - rocker_min
        time_ratio = stroke = None
        if (
            rotates
            and not rocker_turns
            and len(toggles) == 2
            and {k for k, _t, _r in toggles} == {"extended", "folded"}
        ):
            (_k1, t1, r1), (_k2, t2, r2) = toggles
            # crank rotation (counter-clockwise) from the toggle at the max rocker angle to the
            # one at the min rocker angle
            t_at_max, t_at_min = (t1, t2) if math.remainder(r1 - r2, TWO_PI) > 0 else (t2, t1)
            stroke = (t_at_min - t_at_max) % TWO_PI
            time_ratio = max(stroke, TWO_PI - stroke) / min(stroke, TWO_PI - stroke)
        return FourBarLimits(
            grashof_type=kind,
            grashof_sum=excess,
            crank_rotates=rotates,
            crank_ranges=tuple((float(lo_), float(hi_)) for lo_, hi_ in ranges),
            transmission_angle_min=mu_min,
            transmission_angle_max=mu_max,
            transmission_angle_worst=worst,
            rocker_angle_min=rocker_min,
            rocker_angle_max=rocker_max,
            rocker_swing=swing,
            toggle_crank_angles=toggle_angles,
            dead_point_crank_angles=dead,
            time_ratio=time_ratio,
            forward_stroke_crank_angle=stroke,
        )

    # ---- motion --------------------------------------------------------------------------------
    def check_assembly(self, theta2: ArrayLike) -> None:
        """Check that the links assemble at every crank angle.

        Parameters
        ----------
        theta2 : array_like
            Crank angles (rad).

        Raises
        ------
        InputError
            Naming the first crank angle at which the links do not assemble.
        """
        theta2 = np.atleast_1d(np.asarray(theta2, dtype=float))
        _t3, t4 = fourbar_positions(theta2, *self.lengths, self.branch)
        bad = ~np.isfinite(t4)
        if np.any(bad):
            raise self.assembly_error(float(theta2[np.argmax(bad)]))

    def motion(
        self, theta2: ArrayLike, omega2: ArrayLike = 1.0, alpha2: ArrayLike = 0.0
    ) -> FourBarMotion:
        """Angles, angular velocities and accelerations at crank angles (:func:`fourbar_motion`).

        Parameters
        ----------
        theta2 : array_like
            Crank angles (rad).
        omega2 : array_like
            Crank speed (rad/s); default 1.
        alpha2 : array_like
            Crank angular acceleration (rad/s^2); default 0.

        Returns
        -------
        FourBarMotion
            Angles (rad), angular velocities (rad/s) and accelerations (rad/s^2).

        Raises
        ------
        InputError
            Where the links do not assemble.
        """
        self.check_assembly(theta2)
        return fourbar_motion(theta2, *self.lengths, omega2, alpha2, self.branch)

    def coupler_point_motion(
        self, m: FourBarMotion
    ) -> tuple[NDArray[np.complex128], NDArray[np.complex128], NDArray[np.complex128]]:
        """Position, velocity and acceleration of the coupler point (Norton 2012, sec. 4.6).

        P = B + z e^{i theta3}, z = p + i q, so
        dP/dt = i a omega2 e^{i theta2} + i z omega3 e^{i theta3} and
        d2P/dt2 = a (i alpha2 - omega2^2) e^{i theta2} + z (i alpha3 - omega3^2) e^{i theta3}.

        Parameters
        ----------
        m : FourBarMotion
            The linkage's motion.

        Returns
        -------
        position, velocity, acceleration : numpy.ndarray
            Complex arrays x + i y (m, m/s, m/s^2).

        Raises
        ------
        ValueError
            If the four-bar has no coupler point.
        """
        if self.coupler_point is None:
            raise ValueError("this four-bar has no coupler point")
        z = complex(*self.coupler_point)
        a = self.crank
        e2, e3 = np.exp(1j * m.theta2), np.exp(1j * m.theta3)
        pos = a * e2 + z * e3
        vel = 1j * a * m.omega2 * e2 + 1j * z * m.omega3 * e3
        acc = a * (1j * m.alpha2 - m.omega2**2) * e2 + z * (1j * m.alpha3 - m.omega3**2) * e3
        return pos, vel, acc

    def joint_positions(self, m: FourBarMotion) -> dict[str, NDArray[np.complex128]]:
        """Positions of the joints.

        Parameters
        ----------
        m : FourBarMotion
            The linkage's motion.

        Returns
        -------
        dict of str to numpy.ndarray
            A, B, C, D as complex arrays x + i y (m).
        """
        a, _b, c, d = self.lengths
        shape = np.shape(m.theta2)
        return {
            "A": np.zeros(shape, dtype=complex),
            "B": a * np.exp(1j * m.theta2),
            "C": d + c * np.exp(1j * m.theta4),
            "D": np.full(shape, d, dtype=complex),
        }

    def to_mechanism(self, theta2: float = math.radians(60.0), **kw: Any) -> Mechanism:
        """The same linkage as a general planar mechanism, drawn at a crank angle on this branch.

        Parameters
        ----------
        theta2 : float
            Crank angle of the drawing (rad); default 60 deg.
        **kw
            Passed to :func:`fourbar_mechanism` (masses, loads...).

        Returns
        -------
        crankdyn.linkage.planar.Mechanism
            The mechanism.

        Raises
        ------
        InputError
            If the links do not assemble at ``theta2``.
        """
        return fourbar_mechanism(self, theta2, **kw)


def _angle_span(angles: Sequence[float]) -> tuple[float, float]:
    """(min, max) of angles (rad) on an arc shorter than a turn, written without a wrap:
    in [-pi, pi) when possible, else in [0, 2 pi)."""
    arr = np.asarray(angles, dtype=float)
    for values in (np.remainder(arr + math.pi, TWO_PI) - math.pi, np.mod(arr, TWO_PI)):
        lo, hi = float(values.min()), float(values.max())
        if hi - lo < math.pi + 1e-9 or len(values) < 2:
            return lo, hi
    # a swing of more than 180 deg: take the representation with the smaller spread
    a = np.remainder(arr + math.pi, TWO_PI) - math.pi
    b = np.mod(arr, TWO_PI)
    pick = a if np.ptp(a) <= np.ptp(b) else b
    return float(pick.min()), float(pick.max())


# ---- analysis: result object -----------------------------------------------------------------


@dataclass(frozen=True)
class FourBarResult(Result):
    """Four-bar motion over a set of crank angles, with its closed-form characteristics
    (:func:`fourbar_analysis`).

    Parameters
    ----------
    linkage : FourBar or None
        The linkage (not exported), for the plot.
    warnings : tuple of crankdyn.plausibility.PlausibilityWarning
        A worst transmission angle under 40 deg.
    """

    title = "Four-bar kinematics"
    grashof_type: str = scalar("grashof_type", "Grashof type", "")
    branch: str = scalar("branch", "Branch", "")
    crank: float = scalar("crank_m", "Crank AB", "m")
    coupler: float = scalar("coupler_m", "Coupler BC", "m")
    rocker: float = scalar("rocker_m", "Rocker DC", "m")
    ground: float = scalar("ground_m", "Ground AD", "m")
    crank_speed: float = scalar("crank_speed_rad_s", "Crank speed", "rad/s")
    crank_acceleration: float = scalar("crank_acceleration_rad_s2", "Crank acceleration", "rad/s²")
    transmission_angle_min: float = scalar(
        "transmission_angle_min_deg", "Min transmission angle", "deg", DEG, fmt=".5g"
    )
    transmission_angle_max: float = scalar(
        "transmission_angle_max_deg", "Max transmission angle", "deg", DEG, fmt=".5g"
    )
    rocker_angle_min: float | None = scalar(
        "rocker_angle_min_deg", "Min rocker angle", "deg", DEG, fmt=".5g"
    )
    rocker_angle_max: float | None = scalar(
        "rocker_angle_max_deg", "Max rocker angle", "deg", DEG, fmt=".5g"
    )
    limits: FourBarLimits = scalar("limits", "Characteristics", "")
    crank_angle: NDArray[np.float64] = column("crank_angle_deg", "Crank angle θ2", "deg", DEG)
    coupler_angle: NDArray[np.float64] = column("coupler_angle_deg", "Coupler angle θ3", "deg", DEG)
    rocker_angle: NDArray[np.float64] = column("rocker_angle_deg", "Rocker angle θ4", "deg", DEG)
    transmission: NDArray[np.float64] = column(
        "transmission_angle_deg", "Transmission angle μ", "deg", DEG
    )
    coupler_angular_velocity: NDArray[np.float64] = column(
        "coupler_angular_velocity_rad_s", "Coupler ω3", "rad/s"
    )
    rocker_angular_velocity: NDArray[np.float64] = column(
        "rocker_angular_velocity_rad_s", "Rocker ω4", "rad/s"
    )
    coupler_angular_acceleration: NDArray[np.float64] = column(
        "coupler_angular_acceleration_rad_s2", "Coupler α3", "rad/s²"
    )
    rocker_angular_acceleration: NDArray[np.float64] = column(
        "rocker_angular_acceleration_rad_s2", "Rocker α4", "rad/s²"
    )
    coupler_point_x: NDArray[np.float64] | None = column(
        "coupler_point_x_m", "Coupler point x", "m", default=None
    )
    coupler_point_y: NDArray[np.float64] | None = column(
        "coupler_point_y_m", "Coupler point y", "m", default=None
    )
    coupler_point_vx: NDArray[np.float64] | None = column(
        "coupler_point_velocity_x_m_s", "Coupler point vx", "m/s", default=None
    )
    coupler_point_vy: NDArray[np.float64] | None = column(
        "coupler_point_velocity_y_m_s", "Coupler point vy", "m/s", default=None
    )
    coupler_point_ax: NDArray[np.float64] | None = column(
        "coupler_point_acceleration_x_m_s2", "Coupler point ax", "m/s²", default=None
    )
    coupler_point_ay: NDArray[np.float64] | None = column(
        "coupler_point_acceleration_y_m_s2", "Coupler point ay", "m/s²", default=None
    )
    linkage: FourBar | None = field(default=None, repr=False)
    warnings: tuple[PlausibilityWarning, ...] = field(default=(), repr=False, compare=False)

    def plot(self, fig: Figure | None = None) -> Figure:
        """Mechanism, coupler curve, transmission angle and angular velocities.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.linkage import plot_fourbar

        return plot_fourbar(self, fig=fig)


def fourbar_analysis(
    linkage: FourBar,
    angles: ArrayLike,
    crank_speed: float = 1.0,
    crank_acceleration: float = 0.0,
) -> FourBarResult:
    """Four-bar kinematics at a set of crank angles (module docstring).

    Parameters
    ----------
    linkage : FourBar
        The four-bar.
    angles : array_like
        Crank angles (rad).
    crank_speed : float
        Crank speed (rad/s); default 1.
    crank_acceleration : float
        Crank angular acceleration (rad/s^2); default 0.

    Returns
    -------
    FourBarResult
        Angles (rad), angular velocities (rad/s) and accelerations (rad/s^2), the transmission
        angle (rad), the coupler point's motion (m, m/s, m/s^2) and the closed-form limits;
        ``warnings`` holds a worst transmission angle under 40 deg
        (:func:`crankdyn.plausibility.check_transmission_angle`).

    Raises
    ------
    InputError
        If the links do not assemble at an angle.

    Examples
    --------
    >>> fb = FourBar(0.0734, 0.12536, 0.1034, 0.10352)
    >>> r = fourbar_analysis(fb, np.radians([0, 90, 180]))
    >>> np.round(np.degrees(r.transmission), 3)
    array([ 10.389,  66.583, 100.882])
    >>> [w.key for w in r.warnings]  # worst transmission angle under 40 deg
    ['transmission_angle']
    """
    theta2 = np.asarray(angles, dtype=float)
    m = linkage.motion(theta2, crank_speed, crank_acceleration)
    lim = linkage.limits
    point: dict[str, NDArray[np.float64]] = {}
    if linkage.coupler_point is not None:
        pos, vel, acc = linkage.coupler_point_motion(m)
        point = {
            "coupler_point_x": freeze(pos.real),
            "coupler_point_y": freeze(pos.imag),
            "coupler_point_vx": freeze(vel.real),
            "coupler_point_vy": freeze(vel.imag),
            "coupler_point_ax": freeze(acc.real),
            "coupler_point_ay": freeze(acc.imag),
        }
    return FourBarResult(
        grashof_type=lim.grashof_type,
        branch=linkage.branch,
        crank=linkage.crank,
        coupler=linkage.coupler,
        rocker=linkage.rocker,
        ground=linkage.ground,
        crank_speed=float(crank_speed),
        crank_acceleration=float(crank_acceleration),
        transmission_angle_min=lim.transmission_angle_min,
        transmission_angle_max=lim.transmission_angle_max,
        rocker_angle_min=lim.rocker_angle_min,
        rocker_angle_max=lim.rocker_angle_max,
        limits=lim,
        crank_angle=freeze(theta2),
        coupler_angle=freeze(m.theta3),
        rocker_angle=freeze(m.theta4),
        transmission=freeze(transmission_angle(theta2, *linkage.lengths)),
        coupler_angular_velocity=freeze(m.omega3),
        rocker_angular_velocity=freeze(m.omega4),
        coupler_angular_acceleration=freeze(m.alpha3),
        rocker_angular_acceleration=freeze(m.alpha4),
        linkage=linkage,
        warnings=tuple(check_transmission_angle(lim.transmission_angle_worst)),
        **point,
    )


# ---- the four-bar as a general planar mechanism ---------------------------------------------


def fourbar_mechanism(
    fourbar: FourBar,
    theta2: float = math.radians(60.0),
    *,
    masses: tuple[float, float, float] = (0.0, 0.0, 0.0),
    inertias: tuple[float, float, float] = (0.0, 0.0, 0.0),
    cgs: tuple[float, float, float] | None = None,
    speed: float = 1.0,
    acceleration: float = 0.0,
    gravity: Sequence[float] = (0.0, 0.0),
    forces: Sequence[Force] = (),
    torques: Sequence[Torque] = (),
    name: str = "four-bar",
) -> Mechanism:
    """A four-bar as a general planar mechanism, drawn at a crank angle on its branch.

    Points A (origin), B, C, D (ground, d, 0) and the coupler point P if any; links crank
    (A, B), coupler (B, C[, P]), rocker (D, C); joints A, B, C, D.

    Parameters
    ----------
    fourbar : FourBar
        The four-bar.
    theta2 : float
        Crank angle of the drawing (rad); default 60 deg.
    masses : (float, float, float)
        Masses of crank, coupler and rocker (kg); default 0.
    inertias : (float, float, float)
        Their moments of inertia about their centres of gravity (kg m^2); default 0.
    cgs : (float, float, float) or None
        Each link's centre of gravity as the fraction along its line (crank from A, coupler
        from B, rocker from D), dimensionless; default the midpoints.
    speed : float
        Crank speed (rad/s); default 1.
    acceleration : float
        Crank angular acceleration (rad/s^2); default 0.
    gravity : (float, float)
        Gravitational acceleration (m/s^2); default (0, 0).
    forces : sequence of crankdyn.linkage.elements.Force
        External forces.
    torques : sequence of crankdyn.linkage.elements.Torque
        External couples.
    name : str
        The mechanism's name.

    Returns
    -------
    crankdyn.linkage.planar.Mechanism
        The mechanism.

    Raises
    ------
    InputError
        If the links do not assemble at ``theta2``.
    """
    a, b, c, d = fourbar.lengths
    t3, t4 = fourbar_positions(np.array([theta2]), a, b, c, d, fourbar.branch)
    if not np.isfinite(t4[0]):
        raise fourbar.assembly_error(theta2)
    pa = np.array([0.0, 0.0])
    pb = a * np.array([math.cos(theta2), math.sin(theta2)])
    pd = np.array([d, 0.0])
    pc = pd + c * np.array([math.cos(t4[0]), math.sin(t4[0])])
    points = {"A": pa, "B": pb, "C": pc, "D": pd}
    coupler_pts = ["B", "C"]
    if fourbar.coupler_point is not None:
        p, qq = fourbar.coupler_point
        u = np.array([math.cos(t3[0]), math.sin(t3[0])])
        points["P"] = pb + p * u + qq * np.array([-u[1], u[0]])
        coupler_pts.append("P")
    fr = cgs or (0.5, 0.5, 0.5)
    ends = ((pa, pb), (pb, pc), (pd, pc))
    cg = [tuple(s + f * (e - s)) for f, (s, e) in zip(fr, ends, strict=True)]
    links = (
        Link("crank", ("A", "B"), masses[0], inertias[0], cg[0]),
        Link("coupler", tuple(coupler_pts), masses[1], inertias[1], cg[1]),
        Link("rocker", ("D", "C"), masses[2], inertias[2], cg[2]),
    )
    joints = (
        Joint("A", "revolute", (GROUND, "crank"), "A"),
        Joint("B", "revolute", ("crank", "coupler"), "B"),
        Joint("C", "revolute", ("coupler", "rocker"), "C"),
        Joint("D", "revolute", (GROUND, "rocker"), "D"),
    )
    return Mechanism(
        name=name,
        points={k: tuple(v) for k, v in points.items()},
        links=links,
        joints=joints,
        driver=Driver("A", "B", 0.0, speed, acceleration),
        forces=tuple(forces),
        torques=tuple(torques),
        gravity=gravity,
    )
