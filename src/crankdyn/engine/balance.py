"""Engine balance: free forces and free moments of the mass forces, and the overturning moment.

Seed 000 section 2.2 separates the forces of the crank train by where they go: the gas force
stays inside the engine; the reciprocating inertia force P_j = -m_j a and the centrifugal force
P_r = m_r R w^2 of the rotating masses leave it through the mounts as *free forces* and, acting
at different places along the crankshaft, as *free moments*; the side thrust and the main-bearing
reaction form the *overturning (reaction) moment*, equal and opposite to the engine torque.

Coordinates (docs/conventions.md). Seen from the free end: x horizontal (to the right), y
vertical (up), z along the crankshaft toward the flywheel. Cylinder i's axis points along
u_i = (sin alpha_i, cos alpha_i), alpha_i its angle from the vertical, clockwise (0 in-line,
-gamma/2 bank A, +gamma/2 bank B); its crank angle is phi_i = theta - psi_i.

Reciprocating masses. The piston acceleration (positive toward the crank) is the Fourier series
a = R w^2 sum_n (C_n cos(n phi) + S_n sin(n phi)), from the lambda-series of
:func:`crankdyn.crank.kinematics.series_coefficients` carried to convergence (C_1 = 1, C_2 =
lambda + lambda^3/4 + 15 lambda^5/128 + ..., C_4 = -(lambda^3/4 + 3 lambda^5/16 + ...),
C_6 = 9 lambda^5/128 + ...; an offset adds S_n and odd orders). The inertia force on the engine,
m_j a u_i, summed over the cylinders, has the order-n part

    F_n(theta) = R w^2 (Re[X_n e^(j n theta)], Re[Y_n e^(j n theta)]),
    X_n = (C_n - j S_n) sum_i m_j,i e^(-j n psi_i) sin(alpha_i),
    Y_n = (C_n - j S_n) sum_i m_j,i e^(-j n psi_i) cos(alpha_i),

and, with z_i the axial position of cylinder i's rod from the middle of the engine (halfway
between the first and last throw), the moment M = sum_i z_i e_z x F_i, i.e.
M_x = -sum z_i F_y,i (pitching, the moment in the vertical plane) and M_y = sum z_i F_x,i
(yawing, in the horizontal plane), whose phasors X_n^z, Y_n^z carry the extra factor z_i.
The two-mass rod model gives the rod's centre-of-gravity force exactly, so these are the free
forces of the whole crank train.

Rotating masses. Throw t's pin points at alpha_1 + p_t + theta (p_t its crank-end-view
position) and carries m_r,t = the big-end masses of its rods plus the throw's own unbalance m_k
(seed 000: m_r = m_k + m_CB per cylinder); a counterweight of m_cw,t = c m_r,t + b sum m_j
(c the counterweight balance ratio, b the share of the reciprocating mass balanced) sits
opposite it. Their first-order phasors are X_r = sum (m_r,t - m_cw,t)(-j) e^(j c_t),
Y_r = sum (m_r,t - m_cw,t) e^(j c_t), c_t = alpha_1 + p_t.

Amplitudes. Over a revolution a phasor pair traces an ellipse, the sum of two vectors turning
with and against the crank, of lengths |X - jY|/2 and |X + jY|/2; the largest magnitude (the
amplitude reported) is their sum, the vertical and horizontal parts are |Y| and |X|.

Power-related unbalance (engine builders' figure, e.g. MAN Energy Solutions' project guides):
the free moment divided by the engine power, in N m/kW.
"""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, NamedTuple, TypeAlias, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import DEG, RPM
from crankdyn.crank.kinematics import series_coefficients
from crankdyn.crank.masses import equivalent_mass_model, equivalent_masses
from crankdyn.engine.firing import crank_end_view
from crankdyn.engine.model import BalanceInputs
from crankdyn.errors import InputError
from crankdyn.results import Result, column, freeze, scalar
from crankdyn.summary import SummaryColumn, SummaryTable, derived

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.crank.masses import Masses
    from crankdyn.engine.model import Cylinders, Engine
    from crankdyn.engine.torque import TorqueResult

__all__ = [
    "BALANCE_METHODS",
    "BalanceInputs",
    "BalanceResult",
    "OrderBalance",
    "OverturningMoment",
    "Phasors",
    "engine_balance",
    "harmonic_phasors",
    "overturning_moment",
    "phasor_amplitude",
    "piston_harmonics",
    "rotating_masses",
]

BALANCE_METHODS = ("exact", "approx")
"""The harmonics of the piston acceleration: the converged lambda-series, or seed 000's
second-order formula."""
DEFAULT_ORDERS = (1, 2, 4, 6)
OFFSET_ORDERS = (1, 2, 3, 4, 5, 6)

Phasor: TypeAlias = "complex | NDArray[np.complex128]"
"""A complex amplitude, or a batch of them."""


# ---- numeric core -------------------------------------------------------------------------------


def piston_harmonics(
    lam: float, k: float = 0.0, orders: ArrayLike = DEFAULT_ORDERS, method: str = "exact"
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Fourier coefficients of the piston acceleration a/(R w^2) = sum C_n cos(n phi) +
    S_n sin(n phi) (dimensionless).

    ``"exact"``: the lambda-series of :func:`crankdyn.crank.kinematics.series_coefficients`, carried
    until its next term, of size (lambda (1 + |k|))^(2N), is below 1e-17 (the series converges
    to the exact motion because lambda (1 + |k|) < 1 whenever the crank turns).
    ``"approx"``: seed 000's second-order formula a = R w^2 (cos phi + lambda cos 2 phi +
    lambda k sin phi), i.e. C_1 = 1, C_2 = lambda, S_1 = lambda k, all else 0.

    Parameters
    ----------
    lam : float
        Crank-rod ratio lambda = R/L (dimensionless).
    k : float
        Relative offset k = e/R (dimensionless); default 0.
    orders : array_like of int
        Harmonic orders n (>= 1); default 1, 2, 4, 6.
    method : str
        ``"exact"`` (default) or ``"approx"``.

    Returns
    -------
    C, S : numpy.ndarray
        Coefficients for each of ``orders`` (dimensionless).

    Raises
    ------
    ValueError
        If the method is unknown (a programming error; the callers check it).

    Examples
    --------
    C_2 = lambda + lambda^3/4 + 15 lambda^5/128 + ... (module docstring), and at TDC the
    harmonics add up to the exact a/(R w^2) = 1 + lambda:

    >>> c, s = piston_harmonics(0.25, orders=[2])
    >>> round(float(c[0]), 4), round(0.25 + 0.25**3 / 4 + 15 * 0.25**5 / 128, 4)
    (0.254, 0.254)
    >>> c, s = piston_harmonics(0.25, orders=range(1, 41))
    >>> round(float(c.sum()), 12)
    1.25
    """
    orders = np.asarray(orders, dtype=int)
    if method == "approx":
        c = np.where(orders == 1, 1.0, np.where(orders == 2, lam, 0.0))
        s = np.where(orders == 1, lam * k, 0.0)
        return c, s
    if method != "exact":
        raise ValueError(f"unknown method {method!r}; expected one of {BALANCE_METHODS}")
    ratio = lam * (1.0 + abs(k))
    terms = math.ceil(math.log(1e-17) / (2.0 * math.log(ratio))) + 1 if ratio > 0 else 1
    top = 2 * max(terms, (int(orders.max()) + 1) // 2 + 1, 2)
    cos_c, sin_c = series_coefficients(lam, k, top)
    m = np.arange(cos_c.size)
    big_c, big_s = -(m**2) * cos_c, -(m**2) * sin_c
    return big_c[orders].astype(np.float64), big_s[orders].astype(np.float64)


class Phasors(NamedTuple):
    """Complex amplitudes of a harmonic force and moment: F = (Re[x e^(j n theta)],
    Re[y e^(j n theta)]), M = (-Re[yz e^(j n theta)], Re[xz e^(j n theta)]) (module docstring).

    Attributes
    ----------
    x, y : complex or numpy.ndarray
        Force phasors, horizontal and vertical (the unit of the weights, times R w^2 for N).
    xz, yz : complex or numpy.ndarray or None
        Moment phasors (the force unit times the unit of the axial positions), or None without
        axial positions.
    """

    x: Phasor
    y: Phasor
    xz: Phasor | None
    yz: Phasor | None


def harmonic_phasors(
    throw_angles: ArrayLike,
    axis_angles: ArrayLike,
    weights: ArrayLike,
    order: int,
    axial: ArrayLike | None = None,
) -> Phasors:
    """Order-n phasors of unit harmonic forces along the cylinder axes (module docstring):
    x = sum_i w_i e^(-j n psi_i) sin(alpha_i), y = ... cos(alpha_i), and with the axial positions
    z_i the moment phasors xz, yz.

    Parameters
    ----------
    throw_angles : array_like
        psi_i (rad), shape (Z,) or a batch (..., Z).
    axis_angles : array_like
        alpha_i (rad), (Z,).
    weights : array_like
        Mass (kg, or any weight) of every cylinder, scalar or (Z,).
    order : int
        n.
    axial : array_like or None
        z_i (m, or pitches), (Z,); None for no moments.

    Returns
    -------
    Phasors
        x, y in the unit of the weights; xz, yz times the unit of z (None without ``axial``);
        complex scalars, or arrays of the batch shape.

    Examples
    --------
    The inline-4 with a flat crank: no first-order free force, a second-order force of four
    times one cylinder's.

    >>> psi = np.radians([0, 180, 180, 0])
    >>> [round(abs(complex(harmonic_phasors(psi, np.zeros(4), 1.0, n).y)), 9) for n in (1, 2)]
    [0.0, 4.0]
    """
    psi = np.asarray(throw_angles, dtype=float)
    alpha = np.asarray(axis_angles, dtype=float)
    w = np.broadcast_to(np.asarray(weights, dtype=float), alpha.shape)
    rot = np.exp(-1j * order * psi)
    x = rot @ (w * np.sin(alpha))
    y = rot @ (w * np.cos(alpha))
    if axial is None:
        return Phasors(x, y, None, None)
    z = np.asarray(axial, dtype=float)
    return Phasors(x, y, rot @ (w * z * np.sin(alpha)), rot @ (w * z * np.cos(alpha)))


def phasor_amplitude(x: ArrayLike, y: ArrayLike) -> NDArray[np.float64]:
    """Largest magnitude over a period of the vector (Re[x e^(jt)], Re[y e^(jt)]).

    The ellipse's semi-major axis (|x + jy| + |x - jy|) / 2 (module docstring).

    Parameters
    ----------
    x, y : array_like
        Complex phasors of the horizontal and vertical parts (any unit).

    Returns
    -------
    numpy.ndarray
        The amplitude, in the phasors' unit, of their broadcast shape.

    Examples
    --------
    A force turning with the crank has the same size in every direction:

    >>> float(phasor_amplitude(-1j, 1.0))
    1.0
    """
    x = np.asarray(x)
    y = np.asarray(y)
    return 0.5 * (np.abs(x + 1j * y) + np.abs(x - 1j * y))


def rotation_split(x: ArrayLike, y: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The parts turning with the crank (clockwise seen from the free end) and against it.

    Parameters
    ----------
    x, y : array_like
        Complex phasors of the horizontal and vertical parts (any unit).

    Returns
    -------
    forward, backward : numpy.ndarray
        Magnitudes |x - jy|/2 (with the crank) and |x + jy|/2 (against it), in the phasors'
        unit (module docstring).
    """
    return 0.5 * np.abs(np.asarray(x) - 1j * np.asarray(y)), 0.5 * np.abs(
        np.asarray(x) + 1j * np.asarray(y)
    )


def rotating_masses(
    masses: Masses, rod_length: float, throws: Sequence[int]
) -> NDArray[np.float64]:
    """Rotating mass of every cylinder at the crank radius, seed 000 section 2.1.

    m_r = m_k / n + m_CB with n rods on the cylinder's throw (a V engine's throw carries its
    unbalance m_k once, shared by its two rods), or the directly given ``rotating`` mass
    (:func:`crankdyn.crank.masses.equivalent_mass_model`). A throw's rotating mass is the sum
    over its cylinders.

    Parameters
    ----------
    masses : crankdyn.crank.masses.Masses
        The crank-train masses of one cylinder.
    rod_length : float
        Rod length L (m).
    throws : sequence of int
        The throw (1-based) of every cylinder.

    Returns
    -------
    numpy.ndarray
        m_r of every cylinder (kg).
    """
    throws = list(throws)
    counts = {t: throws.count(t) for t in set(throws)}
    return np.array([equivalent_mass_model(masses, rod_length, counts[t]).rotating for t in throws])


# ---- results -----------------------------------------------------------------------------------


@dataclass(frozen=True)
class OrderBalance(Result):
    """Free force and free moment of one order (or of the rotating masses).

    Parameters
    ----------
    phasors : Phasors or None
        The order's phasors (N and N m; not exported), for the polar plots.
    speed : float
        Crank speed (rad/s; not exported).
    """

    title = "Free force and moment"
    order: int = scalar("order", "Order", "")
    source: str = scalar("source", "Masses", "")
    free_force: float = scalar("free_force_N", "Free force", "N")
    free_force_vertical: float = scalar("free_force_vertical_N", "Vertical part", "N")
    free_force_horizontal: float = scalar("free_force_horizontal_N", "Horizontal part", "N")
    free_force_with_crank: float = scalar(
        "free_force_forward_N", "Part turning with the crank", "N"
    )
    free_force_against_crank: float = scalar(
        "free_force_backward_N", "Part turning against the crank", "N"
    )
    free_moment: float | None = scalar("free_moment_Nm", "Free moment", "N·m")
    free_moment_vertical: float | None = scalar(
        "free_moment_vertical_plane_Nm", "Moment in the vertical plane (pitch)", "N·m"
    )
    free_moment_horizontal: float | None = scalar(
        "free_moment_horizontal_plane_Nm", "Moment in the horizontal plane (yaw)", "N·m"
    )
    free_moment_with_crank: float | None = scalar(
        "free_moment_forward_Nm", "Moment turning with the crank", "N·m"
    )
    free_moment_against_crank: float | None = scalar(
        "free_moment_backward_Nm", "Moment turning against the crank", "N·m"
    )
    force_coefficient: float | None = scalar(
        "free_force_coefficient", "Free force / (m_j R ω²)", "", fmt=".6g"
    )
    moment_coefficient: float | None = scalar(
        "free_moment_coefficient", "Free moment / (m_j R ω² a)", "", fmt=".6g"
    )
    power_related_unbalance: float | None = scalar(
        "power_related_unbalance_Nm_kW", "Free moment per kW", "N·m/kW", 1e3
    )
    phasors: Phasors | None = field(default=None, repr=False, compare=False)
    speed: float = field(default=1.0, repr=False, compare=False)

    @property
    def name(self) -> str:
        """The row's name in every balance table: the order, ``1 (rotating)`` for the rotating
        masses with their counterweights, ``1 (total)`` for the first order of both."""
        if self.source == "reciprocating":
            return str(self.order)
        return f"{self.order} ({self.source})"


def _order_balance(
    order: int,
    source: str,
    ph: Phasors,
    scale: float,
    unit_force: float,
    pitch: float,
    power: float | None,
    floors: tuple[float, float],
) -> OrderBalance:
    """One row of the balance table from scaled phasors; parts smaller than ``floors`` (force
    and moment phasors, round-off of sums that vanish exactly) are set to zero."""
    ph = _snap(ph, floors)
    f_amp = scale * float(phasor_amplitude(ph.x, ph.y))
    fwd, bwd = rotation_split(ph.x, ph.y)
    moment = vert = horiz = mfwd = mbwd = None
    if ph.xz is not None and ph.yz is not None:
        moment = scale * float(phasor_amplitude(ph.xz, ph.yz))
        vert, horiz = scale * float(np.abs(ph.yz)), scale * float(np.abs(ph.xz))
        a, b = rotation_split(ph.xz, ph.yz)
        mfwd, mbwd = scale * float(a), scale * float(b)
    return OrderBalance(
        order=order,
        source=source,
        free_force=f_amp,
        free_force_vertical=scale * float(np.abs(ph.y)),
        free_force_horizontal=scale * float(np.abs(ph.x)),
        free_force_with_crank=scale * float(fwd),
        free_force_against_crank=scale * float(bwd),
        free_moment=moment,
        free_moment_vertical=vert,
        free_moment_horizontal=horiz,
        free_moment_with_crank=mfwd,
        free_moment_against_crank=mbwd,
        force_coefficient=f_amp / unit_force if unit_force > 0 else None,
        moment_coefficient=(
            moment / (unit_force * pitch) if moment is not None and unit_force > 0 else None
        ),
        power_related_unbalance=moment / power if moment is not None and power else None,
        phasors=_scaled(ph, scale),
    )


def _scaled(ph: Phasors, factor: complex) -> Phasors:
    return Phasors(
        factor * ph.x,
        factor * ph.y,
        None if ph.xz is None else factor * ph.xz,
        None if ph.yz is None else factor * ph.yz,
    )


def _snap(ph: Phasors, floors: tuple[float, float]) -> Phasors:
    f_floor, m_floor = floors

    def clean(p: Phasor, floor: float) -> Phasor:
        return complex(0.0) if np.abs(p) < floor else p

    return Phasors(
        clean(ph.x, f_floor),
        clean(ph.y, f_floor),
        None if ph.xz is None else clean(ph.xz, m_floor),
        None if ph.yz is None else clean(ph.yz, m_floor),
    )


@dataclass(frozen=True)
class OverturningMoment(Result):
    """The reaction of the engine torque on the engine block (seed 000 section 2.2): equal and
    opposite to the torque, a steady part -M_mean and a fluctuating part -(M - M_mean)."""

    title = "Overturning moment"
    crank_angle: NDArray[np.float64] = column("crank_angle_deg", "Crank angle θ", "deg", DEG)
    moment: NDArray[np.float64] = column("overturning_moment_Nm", "Overturning moment", "N·m")
    mean: float = scalar("mean_overturning_moment_Nm", "Steady part", "N·m")
    amplitude: float = scalar(
        "overturning_moment_amplitude_Nm", "Largest fluctuation |M - M_mean|", "N·m"
    )
    peak_to_peak: float = scalar("overturning_moment_peak_to_peak_Nm", "Peak to peak", "N·m")
    orders: NDArray[np.float64] = scalar("harmonic_orders", "Orders", "", fmt=".3g", summary=False)
    harmonic_amplitudes: NDArray[np.float64] = scalar(
        "harmonic_amplitudes_Nm", "Harmonic amplitudes", "N·m", fmt=".4g", summary=False
    )


def overturning_moment(
    angle: ArrayLike, torque: ArrayLike, cycle_angle: float, max_order: float = 12.0
) -> OverturningMoment:
    """The overturning (reaction) moment from an engine torque curve.

    Parameters
    ----------
    angle : array_like
        Crankshaft angles (rad), uniformly spaced over one cycle; a closing point one cycle
        after the first is allowed and dropped.
    torque : array_like
        Engine torque at those angles (N m).
    cycle_angle : float
        Cycle length (rad): 4 pi four-stroke, 2 pi two-stroke.
    max_order : float
        Highest order of the harmonic table (dimensionless); default 12.

    Returns
    -------
    OverturningMoment
        The reaction -M(theta), its steady part, the largest fluctuation, and the amplitudes of
        its orders n = k 2 pi / cycle_angle (0.5, 1, 1.5, ... four-stroke) from the discrete
        Fourier transform.

    Raises
    ------
    InputError
        If the curve has fewer than 4 points, its angles are not uniformly spaced over one
        cycle, or a torque is not finite.

    Examples
    --------
    A pure fourth-order torque of 100 N m about a mean of 50 N m:

    >>> theta = np.linspace(0.0, 4 * np.pi, 720, endpoint=False)
    >>> m = overturning_moment(theta, 50 + 100 * np.cos(4 * theta), 4 * np.pi)
    >>> round(m.mean, 9), round(m.amplitude, 9)
    (-50.0, 100.0)
    >>> float(m.orders[np.argmax(m.harmonic_amplitudes)])
    4.0
    """
    theta, m = _one_cycle(angle, torque, cycle_angle)
    mean = float(np.mean(m))
    fluct = m - mean
    spectrum = np.fft.rfft(fluct) / m.size
    amps = 2.0 * np.abs(spectrum)
    k = np.arange(amps.size)
    orders = k * (2.0 * math.pi / cycle_angle)
    keep = (k >= 1) & (orders <= max_order + 1e-9)
    if m.size % 2 == 0:
        amps[-1] /= 2.0  # the Nyquist term is not doubled
    return OverturningMoment(
        crank_angle=freeze(theta),
        moment=freeze(-m),
        mean=-mean,
        amplitude=float(np.max(np.abs(fluct))),
        peak_to_peak=float(np.ptp(m)),
        orders=freeze(orders[keep]),
        harmonic_amplitudes=freeze(amps[keep]),
    )


def _one_cycle(
    angle: ArrayLike, values: ArrayLike, cycle_angle: float
) -> tuple[np.ndarray, np.ndarray]:
    theta = np.asarray(angle, dtype=float)
    v = np.asarray(values, dtype=float)
    if theta.ndim != 1 or theta.shape != v.shape or theta.size < 4:
        raise InputError("expected matching 1-D arrays of angle and torque (4 points or more)")
    if abs(theta[-1] - theta[0] - cycle_angle) < 1e-9 * cycle_angle:
        theta, v = theta[:-1], v[:-1]
    steps = np.diff(theta)
    if np.any(steps <= 0.0) or np.ptp(steps) > 1e-6 * steps.mean():
        raise InputError("the torque curve needs uniformly spaced, increasing angles")
    if abs(theta.size * steps.mean() - cycle_angle) > 1e-6 * cycle_angle:
        raise InputError(
            f"the torque curve must cover one cycle of {math.degrees(cycle_angle):.0f} deg"
        )
    if not np.all(np.isfinite(v)):
        raise InputError("the torque curve holds values that are not finite")
    return theta, v


BALANCE_ORDERS = (1, 2, 4, 6)
"""The reciprocating orders whose free force and moment are key figures of their own (for
parameter studies)."""


def _largest(
    result: BalanceResult, name: str, rows: Sequence[OrderBalance] | None = None, scale: float = 1.0
) -> tuple[float, str] | None:
    """The largest value of an OrderBalance field over the balance table's rows (or ``rows``),
    with the row's name; None when no row has one."""
    found = [(getattr(r, name), r) for r in (result.rows() if rows is None else rows)]
    found = [(v, r) for v, r in found if v is not None]
    if not found:
        return None
    value, row = max(found, key=lambda p: p[0])
    return value * scale, (f"order {row.name}" if value else "balanced")


def _of_order(n: int, name: str) -> Callable[[BalanceResult], float | None]:
    """``f(result)``: an OrderBalance field of reciprocating order ``n`` (None without it)."""

    def value(result: BalanceResult) -> float | None:
        row = next((o for o in result.orders if o.order == n), None)
        return None if row is None else getattr(row, name)

    return value


@dataclass(frozen=True)
class BalanceResult(Result):
    """Free forces and moments of an engine at one speed (:func:`engine_balance`; module
    docstring).

    Parameters
    ----------
    axis_angles : numpy.ndarray or None
        Cylinder axis angles alpha_i (rad; not exported), for the polar plots.
    """

    title = "Engine balance"
    engine: str = scalar("engine", "Engine", "")
    speed: float = scalar("speed_rpm", "Speed", "rpm", RPM)
    method: str = scalar("method", "Harmonics", "")
    reciprocating_mass: float = scalar("reciprocating_mass_kg", "Reciprocating mass m_j", "kg")
    rotating_mass: float = scalar(
        "rotating_mass_per_throw_kg", "Rotating mass per throw (mean)", "kg"
    )
    counterweight_ratio: float = scalar("counterweight_ratio", "Counterweight ratio c", "")
    reciprocating_balance_ratio: float = scalar(
        "reciprocating_balance_ratio", "Reciprocating share balanced b", ""
    )
    crank_radius: float = scalar("crank_radius_m", "Crank radius R", "m", summary=False)
    pitch: float | None = scalar("pitch_m", "Cylinder pitch a", "m")
    power: float | None = scalar("power_kW", "Power (for the power-related unbalance)", "kW", 1e-3)
    orders: tuple[OrderBalance, ...] = scalar("orders", "Reciprocating masses by order", "")
    rotating: OrderBalance = scalar(
        "rotating", "Rotating masses and counterweights", "", summary=False
    )
    first_order_total: OrderBalance = scalar(
        "first_order_total", "First order, reciprocating and rotating", "", summary=False
    )
    overturning: OverturningMoment | None = scalar("overturning", "Overturning moment", "")
    notes: tuple[str, ...] = scalar("notes", "Notes", "")
    axis_angles: NDArray[np.float64] | None = field(default=None, repr=False, compare=False)

    FIGURES = (
        derived(
            "max_free_force", "max_free_force_N", "Largest free force", "N",
            lambda r: _largest(r, "free_force"), reduction="max over the table's rows",
            better="min", headline=True,
        ),
        derived(
            "max_free_moment", "max_free_moment_Nm", "Largest free moment", "N·m",
            lambda r: _largest(r, "free_moment"), reduction="max over the table's rows",
            better="min", headline=True,
        ),
        derived(
            "power_related_unbalance", "power_related_unbalance_Nm_kW",
            "Power-related unbalance (reciprocating orders)", "N·m/kW",
            lambda r: _largest(r, "power_related_unbalance", rows=r.orders, scale=1e3),
            reduction="max over the orders",
        ),
        *(
            figure
            for n in BALANCE_ORDERS
            for figure in (
                derived(
                    f"free_force_{n}", f"free_force_{n}_N",
                    f"Free force, order {n} (reciprocating masses)", "N",
                    _of_order(n, "free_force"), better="min",
                    description=f"Largest free force of the reciprocating masses of order {n} "
                    "over a revolution",
                ),
                derived(
                    f"free_moment_{n}", f"free_moment_{n}_Nm",
                    f"Free moment, order {n} (reciprocating masses)", "N·m",
                    _of_order(n, "free_moment"), better="min",
                    description=f"Largest free moment of the reciprocating masses of order {n} "
                    "about the middle of the engine (needs [cylinders] pitch)",
                ),
            )
        ),
        derived(
            "rotating_free_force", "rotating_free_force_N",
            "Free force of the rotating masses and counterweights", "N",
            lambda r: r.rotating.free_force, better="min",
        ),
        derived(
            "rotating_free_moment", "rotating_free_moment_Nm",
            "Free moment of the rotating masses and counterweights", "N·m",
            lambda r: r.rotating.free_moment, better="min",
        ),
        derived(
            "first_order_free_moment", "first_order_free_moment_Nm",
            "First-order free moment, reciprocating and rotating", "N·m",
            lambda r: r.first_order_total.free_moment, better="min",
        ),
    )  # fmt: skip

    def summary_tables(self) -> list[SummaryTable]:
        """The free forces and moments by order (every row of :meth:`rows`), round-off next to
        the unit force m_j R ω² (and the moment m_j R ω² a) shown as 0."""
        unit_force = self.reciprocating_mass * self.crank_radius * self.speed**2
        moment_ref = unit_force * (self.pitch or 1.0)
        spec = [
            ("free_force_N", "Free force", "N", "free_force", unit_force, 1.0),
            ("free_force_vertical_N", "Free force, vertical", "N", "free_force_vertical",
             unit_force, 1.0),
            ("free_force_horizontal_N", "Free force, horizontal", "N", "free_force_horizontal",
             unit_force, 1.0),
            ("free_moment_Nm", "Free moment", "N·m", "free_moment", moment_ref, 1.0),
            ("free_moment_vertical_plane_Nm", "Free moment, vertical plane", "N·m",
             "free_moment_vertical", moment_ref, 1.0),
            ("free_moment_horizontal_plane_Nm", "Free moment, horizontal plane", "N·m",
             "free_moment_horizontal", moment_ref, 1.0),
            ("free_force_coefficient", "Free force per m_j R ω²", "", "force_coefficient",
             1.0, 1.0),
            ("free_moment_coefficient", "Free moment per m_j R ω² a", "", "moment_coefficient",
             1.0, 1.0),
        ]  # fmt: skip
        if self.power:
            spec.append(
                (
                    "power_related_unbalance_Nm_kW", "Moment per power", "N·m/kW",
                    "power_related_unbalance", moment_ref / self.power * 1e3, 1e3,
                )
            )  # fmt: skip
        columns = [SummaryColumn("order", "Order")]
        columns += [SummaryColumn(k, label, u) for k, label, u, *_ in spec]
        rows = tuple(
            (
                r.name,
                *(
                    None if getattr(r, name) is None else getattr(r, name) * scale
                    for _k, _l, _u, name, _ref, scale in spec
                ),
            )
            for r in self.rows()
        )
        return [
            SummaryTable(
                "balance",
                f"Free forces and moments at {self.speed * RPM:.0f} rpm",
                tuple(columns),
                rows,
                caption="Largest magnitude over a revolution, by order; moments about the middle "
                "of the engine; 1 (rotating): the rotating masses with the counterweights; "
                "1 (total): the first order of both (seed 000 §2.2).",
                reference=(None, *(ref for *_r, ref, _s in spec)),
            )
        ]

    def rows(self) -> list[OrderBalance]:
        """Every line of the balance table.

        Returns
        -------
        list of OrderBalance
            The orders, the rotating masses, the first-order total.
        """
        return [*self.orders, self.rotating, self.first_order_total]

    def to_csv(self) -> str:
        """The balance table as CSV text.

        Returns
        -------
        str
            One row per order and for the rotating masses and the first-order total: forces
            (N), moments (N m), coefficients (dimensionless), power-related unbalance (N m/kW).
        """
        keys = [
            "order",
            "source",
            "free_force_N",
            "free_force_vertical_N",
            "free_force_horizontal_N",
            "free_moment_Nm",
            "free_moment_vertical_plane_Nm",
            "free_moment_horizontal_plane_Nm",
            "free_force_coefficient",
            "free_moment_coefficient",
            "power_related_unbalance_Nm_kW",
        ]
        buffer = io.StringIO()
        writer = csv.writer(buffer, lineterminator="\n")
        writer.writerow(keys)
        for row in self.rows():
            d = row.to_dict()
            writer.writerow([_csv_cell(d.get(k)) for k in keys])
        return buffer.getvalue()

    def plot(self, fig: Figure | None = None) -> Figure:
        """Polar plots of the free force and moment of every order.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.balance import plot_balance

        return plot_balance(self, fig=fig)


def _csv_cell(value: object) -> str:
    if value is None:
        return ""
    return f"{value:.10g}" if isinstance(value, float) else str(value)


# ---- the analysis ----------------------------------------------------------------------------


def _axial_positions(cylinders: Cylinders, rod_offset: float) -> tuple[np.ndarray, np.ndarray]:
    """Axial positions (m) from the middle of the engine: rods (Z,) and throws (T,)."""
    pitch = cylinders.pitch
    if pitch is None:
        raise ValueError("axial positions need the cylinder pitch")
    throws = np.asarray(cylinders.throws, dtype=int)
    n_throws = int(throws.max())
    throw_z = (np.arange(n_throws) - (n_throws - 1) / 2.0) * pitch
    rod_z = throw_z[throws - 1].copy()
    shared = np.bincount(throws, minlength=n_throws + 1)[throws] > 1
    side = np.where(np.asarray(cylinders.banks) == "A", -0.5, 0.5)
    rod_z = rod_z + np.where(shared, side * rod_offset, 0.0)
    return rod_z, throw_z


def engine_balance(
    engine: Engine,
    speed: float,
    *,
    orders: Sequence[int] | None = None,
    method: str = "exact",
    inputs: BalanceInputs | None = None,
    torque: TorqueResult | tuple[ArrayLike, ArrayLike] | None = None,
) -> BalanceResult:
    """Free forces and moments of an engine's mass forces at a speed (module docstring).

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine (masses required; the cylinder pitch for moments).
    speed : float
        Crank speed w (rad/s).
    orders : sequence of int or None
        Orders of the reciprocating masses (default 1, 2, 4, 6; 1 to 6 for an offset engine,
        whose piston acceleration has odd harmonics too).
    method : str
        ``"exact"`` (converged lambda-series, default) or ``"approx"`` (seed 000's second-order
        formula).
    inputs : BalanceInputs or None
        Counterweights, rod offset and power; default ``engine.balance`` or no counterweights.
    torque : crankdyn.engine.torque.TorqueResult or (array_like, array_like) or None
        The engine torque over one cycle, for the overturning moment: a torque result (whose
        power also serves the power-related unbalance when ``inputs`` gives none: the effective
        power if the mechanical efficiency is known, else the indicated power) or a pair
        (angles in rad, torque in N m); None leaves it out.

    Returns
    -------
    BalanceResult
        Free forces (N) and moments (N m) of every order, of the rotating masses and
        counterweights, and of the whole first order; their coefficients; the overturning
        moment when a torque is given.

    Raises
    ------
    InputError
        If the engine has no masses, the method is unknown, the speed is not positive or an
        order is outside 1 to 64.

    Examples
    --------
    The inline-4 (VAZ-2108, flat crank): the first-order force and every moment balance, the
    second-order force is free, 4 m_j R w^2 C_2 (seed 000 section 2.2).

    >>> import crankdyn
    >>> engine = crankdyn.Engine.example("vaz2108")
    >>> w = 4900 * math.pi / 30
    >>> b = engine_balance(engine, w)
    >>> [(o.order, round(o.free_force, 1), o.free_moment) for o in b.orders[:2]]
    [(1, 0.0, 0.0), (2, 6022.7, 0.0)]
    >>> c2 = piston_harmonics(engine.geometry.lam, orders=[2])[0][0]
    >>> round(float(4 * b.reciprocating_mass * engine.geometry.crank_radius * w**2 * c2), 1)
    6022.7
    """
    if engine.masses is None:
        raise InputError(
            "the balance needs the crank-train masses: add a [masses] table", file=engine.source
        )
    if method not in BALANCE_METHODS:
        raise InputError(
            f"expected one of {', '.join(BALANCE_METHODS)}", key="--method", value=method
        )
    w = float(speed)
    if not (math.isfinite(w) and w > 0.0):
        raise InputError("the speed must be positive", key="speed", value=speed)
    if inputs is None:
        inputs = getattr(engine, "balance", None) or BalanceInputs()
    geo, cyl = engine.geometry, engine.cylinders
    if orders is None:
        orders = OFFSET_ORDERS if geo.offset != 0.0 else DEFAULT_ORDERS
    orders = tuple(int(n) for n in orders)
    if not orders or any(n < 1 or n > 64 for n in orders):
        raise InputError("orders must be whole numbers from 1 to 64", key="orders", value=orders)
    m_j = equivalent_masses(engine.masses, geo.rod_length)[0]
    m_rot = rotating_masses(engine.masses, geo.rod_length, cyl.throws)
    r = geo.crank_radius
    scale = r * w * w
    unit_force = m_j * scale
    psi = np.asarray(cyl.throw_angles)
    alpha = np.asarray(cyl.bank_axis_angles)
    throws = np.asarray(cyl.throws, dtype=int)
    notes = []
    if cyl.pitch is None:
        rod_z = throw_z = None
        if cyl.throw_count > 1:
            notes.append("no [cylinders] pitch: free moments not computed")
    else:
        rod_z, throw_z = _axial_positions(cyl, inputs.rod_offset)
    if inputs.rod_offset and cyl.layout != "V":
        notes.append("rod_offset applies to V engines only; ignored")
    pitch = cyl.pitch if cyl.pitch is not None else math.nan
    power = inputs.power
    torque_curve: tuple[ArrayLike, ArrayLike] | None = None
    if torque is not None:
        if hasattr(torque, "total_torque"):
            torque = cast("TorqueResult", torque)
            torque_curve = (torque.crank_angle, torque.total_torque)
            if power is None:
                effective = getattr(torque, "effective_power", None)
                power = effective if effective else torque.indicated_power
                kind = "effective" if effective else "indicated"
                notes.append(
                    f"power-related unbalance per kW of {kind} power from the torque analysis "
                    f"({power / 1e3:.4g} kW)"
                )
        else:
            torque_curve = torque
        if power is not None and not power > 0.0:
            power = None
    coeff_c, coeff_s = piston_harmonics(geo.lam, geo.k, orders, method)

    # round-off floor: sums that vanish exactly come out near 1e-16 of their terms
    length = 1.0 if rod_z is None else max(float(np.max(np.abs(rod_z))), 1e-300)
    total_mass = throws.size * m_j + float(m_rot.sum())
    total_mass *= 1.0 + inputs.counterweight_ratio + inputs.reciprocating_balance_ratio
    floors = (1e-12 * total_mass, 1e-12 * total_mass * length)

    def recip(n: int, c_n: float, s_n: float) -> Phasors:
        return _scaled(harmonic_phasors(psi, alpha, m_j, n, rod_z), c_n - 1j * s_n)

    results = [
        _order_balance(
            n, "reciprocating", recip(n, c_n, s_n), scale, unit_force, pitch, power, floors
        )
        for n, c_n, s_n in zip(orders, coeff_c, coeff_s, strict=True)
    ]

    # rotating masses and counterweights, first order
    c_t = alpha[0] + crank_end_view(psi, throws, alpha)
    e_t = np.exp(1j * c_t)
    m_rec_throw = np.bincount(throws - 1, weights=np.full(throws.size, m_j))
    m_rot_throw = np.bincount(throws - 1, weights=m_rot)
    m_cw = (
        inputs.counterweight_ratio * m_rot_throw + inputs.reciprocating_balance_ratio * m_rec_throw
    )
    # the rotating masses at the rods' axial positions (the share of a V throw's own unbalance
    # with each rod: symmetric about the throw's middle, so as if at the middle), the
    # counterweights at the throw's middle
    e_cyl = e_t[throws - 1]
    y_rot = np.sum(m_rot * e_cyl) - np.sum(m_cw * e_t)
    yz_rot = None
    if rod_z is not None and throw_z is not None:
        yz_rot = np.sum(m_rot * rod_z * e_cyl) - np.sum(m_cw * throw_z * e_t)
    rot_ph = Phasors(-1j * y_rot, y_rot, None if yz_rot is None else -1j * yz_rot, yz_rot)
    rotating = replace(
        _order_balance(1, "rotating", rot_ph, scale, unit_force, pitch, power, floors),
        force_coefficient=None,
        moment_coefficient=None,
    )
    c1, s1 = piston_harmonics(geo.lam, geo.k, (1,), method)
    ph1 = recip(1, c1[0], s1[0])
    total_ph = Phasors(
        ph1.x + rot_ph.x,
        ph1.y + rot_ph.y,
        None if rot_ph.xz is None or ph1.xz is None else ph1.xz + rot_ph.xz,
        None if rot_ph.yz is None or ph1.yz is None else ph1.yz + rot_ph.yz,
    )
    total = _order_balance(
        1, "first order total", total_ph, scale, unit_force, pitch, power, floors
    )
    overturning = None
    if torque_curve is not None:
        overturning = overturning_moment(torque_curve[0], torque_curve[1], engine.cycle_angle)
    return BalanceResult(
        engine=engine.name,
        speed=w,
        method=method,
        reciprocating_mass=m_j,
        rotating_mass=float(np.mean(m_rot_throw)),
        counterweight_ratio=inputs.counterweight_ratio,
        reciprocating_balance_ratio=inputs.reciprocating_balance_ratio,
        crank_radius=r,
        pitch=cyl.pitch,
        power=power,
        orders=tuple(results),
        rotating=rotating,
        first_order_total=total,
        overturning=overturning,
        notes=tuple(notes),
        axis_angles=freeze(alpha),
    )
