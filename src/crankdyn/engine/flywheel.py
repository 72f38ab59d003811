"""Speed fluctuation and flywheel sizing (seed 000 section 2.4).

Seed 000 section 2.4, with the crankshaft taken as rigid and the load torque steady and equal to
the engine's mean torque M_m:

- torque non-uniformity mu = (M_max - M_min) / M_m;
- the excess work W(theta) = integral from theta_0 to theta of (M - M_m) dtheta; the largest
  excess work (energy swing) Delta E = max W - min W is the work done between the slowest and
  the fastest crank position; the excess-work coefficient xi = Delta E / E, E = M_m Theta the
  work of one cycle (Theta = 720 deg four-stroke, 360 deg two-stroke);
- with I dw/dt = M - M_m and dw/dt = w dw/dtheta, (1/2) I (w_max^2 - w_min^2) = Delta E, i.e.
  I w_m^2 delta = Delta E with w_m = (w_max + w_min)/2: the degree of cyclic irregularity
  delta = (w_max - w_min)/w_m = Delta E / (I w_m^2), and for a target delta the total inertia
  I_0 = Delta E / (delta w_m^2);
- I_0 = I_F + Z (I_1 + I_2) + I_3: the flywheel I_F, the rotating masses m_r R^2 and the
  reciprocating masses m_j R^2 / 2 of each cylinder (the mean of m_j (dx/dphi)^2), and any other
  parts turning with the crankshaft I_3 (damper, pulley, gears);
- the flywheel moment GD^2 = 4 g I_F (N m^2); a rim of width b between the diameters D_1 and D_2
  of a material of density rho has I = pi rho b (D_1^4 - D_2^4) / 32, i.e.
  GD^2 = pi rho g b (D_1^4 - D_2^4) / 8 (a solid disc: D_2 = 0).

The instantaneous crank speed follows from the same energy equation without linearising:
(1/2) I w(theta)^2 = (1/2) I w_0^2 + W(theta), with w_0 set so that the time-mean speed
Theta / integral dtheta / w equals the given speed. Its delta agrees with Delta E / (I w_m^2) to
first order in delta. A thin rim turning at peripheral speed v carries the hoop stress rho v^2
(Timoshenko and Goodier, *Theory of Elasticity*, 3rd ed., McGraw-Hill, 1970, rotating disks,
in the thin-ring limit).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import DEG, RPM
from crankdyn.crank.masses import equivalent_masses
from crankdyn.engine.balance import rotating_masses
from crankdyn.engine.model import FlywheelInputs
from crankdyn.errors import InputError
from crankdyn.results import Result, column, freeze, scalar
from crankdyn.roots import brentq
from crankdyn.summary import derived

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.crank.geometry import CrankGeometry
    from crankdyn.crank.masses import Masses
    from crankdyn.engine.model import Engine
    from crankdyn.engine.torque import TorqueResult

__all__ = [
    "ExcessWork",
    "FlywheelInputs",
    "FlywheelResult",
    "G",
    "crank_train_inertia",
    "engine_flywheel",
    "excess_work",
    "flywheel_analysis",
    "instantaneous_speed",
    "rim_width",
]

G = 9.80665
"""Standard gravity (m/s^2), for the flywheel moment GD^2 = 4 g I."""

# ---- numeric core -------------------------------------------------------------------------------


class ExcessWork(NamedTuple):
    """Excess work over one cycle of a torque curve (SI; :func:`excess_work`).

    Attributes
    ----------
    angle : numpy.ndarray
        The grid (rad), one cycle, no closing point.
    work : numpy.ndarray
        W(theta) = integral of (M - M_m) from the first angle (J).
    mean_torque : float
        M_m (N m).
    swing : float
        Delta E = max W - min W (J).
    angle_of_min : float
        Slowest crank position (rad).
    angle_of_max : float
        Fastest crank position (rad).
    """

    angle: NDArray[np.float64]
    work: NDArray[np.float64]
    mean_torque: float
    swing: float
    angle_of_min: float
    angle_of_max: float


def _cycle_grid(
    angle: ArrayLike, torque: ArrayLike, period: float
) -> tuple[np.ndarray, np.ndarray]:
    theta = np.asarray(angle, dtype=float)
    m = np.asarray(torque, dtype=float)
    if theta.ndim != 1 or theta.shape != m.shape or theta.size < 4:
        raise InputError("expected matching 1-D arrays of angle and torque (4 points or more)")
    if not (np.all(np.isfinite(theta)) and np.all(np.isfinite(m))):
        raise InputError("the torque curve holds values that are not finite")
    if not (math.isfinite(period) and period > 0.0):
        raise InputError("the cycle angle must be positive", key="period", value=period)
    if abs(theta[-1] - theta[0] - period) < 1e-9 * period:
        theta, m = theta[:-1], m[:-1]  # a closing point one cycle on repeats the first
    if np.any(np.diff(theta) <= 0.0) or theta[-1] - theta[0] >= period:
        raise InputError("the torque curve's angles must increase within one cycle")
    return theta, m


def excess_work(angle: ArrayLike, torque: ArrayLike, period: float) -> ExcessWork:
    """Excess work of a periodic torque curve (module docstring).

    The curve is taken as linear between its points and periodic (the last point joins the
    first one cycle later), so the mean torque and W(theta) are the trapezoid-rule integrals,
    exact for that curve; W returns to 0 after one cycle.

    Parameters
    ----------
    angle : array_like
        Crankshaft angles (rad), increasing, within one cycle (a closing point one cycle after
        the first is allowed and dropped).
    torque : array_like
        Engine torque M at those angles (N m).
    period : float
        Cycle angle Theta (rad).

    Returns
    -------
    ExcessWork
        W(theta) (J), the mean torque (N m), the swing Delta E (J) and where the crank is
        slowest and fastest (rad).

    Raises
    ------
    InputError
        If the curve has fewer than 4 points, holds values that are not finite, or its angles
        do not increase within one cycle.

    Examples
    --------
    M = M_m + A sin(theta) gives W = A (1 - cos(theta)) and Delta E = 2 A:

    >>> theta = np.linspace(0.0, 2 * np.pi, 3600, endpoint=False)
    >>> ew = excess_work(theta, 100.0 + 40.0 * np.sin(theta), 2 * np.pi)
    >>> round(ew.mean_torque, 9), round(ew.swing, 4), round(math.degrees(ew.angle_of_max), 1)
    (100.0, 80.0, 180.0)
    """
    theta, m = _cycle_grid(angle, torque, period)
    h = np.diff(np.append(theta, theta[0] + period))
    nxt = np.roll(m, -1)
    mean = float(np.sum(h * (m + nxt)) / (2.0 * period))
    f = m - mean
    steps = h * (f + np.roll(f, -1)) / 2.0
    work = np.concatenate([[0.0], np.cumsum(steps[:-1])])
    i_min, i_max = int(np.argmin(work)), int(np.argmax(work))
    return ExcessWork(
        angle=theta,
        work=work,
        mean_torque=mean,
        swing=float(work[i_max] - work[i_min]),
        angle_of_min=float(theta[i_min]),
        angle_of_max=float(theta[i_max]),
    )


def instantaneous_speed(
    angle: ArrayLike, work: ArrayLike, period: float, inertia: float, mean_speed: float
) -> NDArray[np.float64]:
    """Crank speed w(theta) of a rigid crankshaft from its excess work (seed 000 section 2.4).

    (1/2) I w^2 = (1/2) I w_0^2 + W, with w_0 such that the time-mean speed
    Theta / integral dtheta/w is ``mean_speed`` (module docstring). The time integral takes
    the speed at the middle of each step (W linear between the points), which stays finite
    when the slowest point nearly stops.

    Parameters
    ----------
    angle : array_like
        Crankshaft angles (rad), one cycle, no closing point.
    work : array_like
        Excess work W(theta) (J) at those angles.
    period : float
        Cycle angle Theta (rad).
    inertia : float
        Moment of inertia I of everything turning with the crankshaft (kg m^2).
    mean_speed : float
        Time-mean crank speed (rad/s).

    Returns
    -------
    numpy.ndarray
        w(theta) (rad/s).

    Raises
    ------
    InputError
        If the inertia is too small to carry the crankshaft through the cycle (it would stop).
    """
    theta = np.asarray(angle, dtype=float)
    w_work = np.asarray(work, dtype=float)
    h = np.diff(np.append(theta, theta[0] + period))
    w_mid = (w_work + np.roll(w_work, -1)) / 2.0
    lowest = -2.0 * float(w_work.min()) / inertia  # w_0^2 at which the slowest point stops

    def speed(c: float, values: np.ndarray) -> np.ndarray:
        return np.sqrt(np.maximum(c + 2.0 * values / inertia, 0.0))

    def excess_mean(c: float) -> float:
        mid = np.maximum(speed(c, w_mid), 1e-300)
        return period / float(np.sum(h / mid)) - mean_speed

    if excess_mean(lowest) > 0.0:
        raise InputError(
            f"the inertia ({inertia:.4g} kg*m^2) is too small to carry the crankshaft through "
            "the cycle at this speed: it would stop",
            key="inertia",
            value=inertia,
        )
    top = mean_speed**2 + 4.0 * float(np.max(np.abs(w_work))) / inertia + 1.0
    c = brentq(excess_mean, lowest, top, xtol=1e-15 * top, rtol=1e-15, maxiter=200)
    return speed(c, w_work)


def crank_train_inertia(
    masses: Masses, geometry: CrankGeometry, throws: Sequence[int]
) -> tuple[float, float]:
    """Inertias of the crank train about the crankshaft axis, seed 000 section 2.4.

    The rotating masses sum m_r R^2 (big ends of the rods, and the throws' unbalance once per
    throw) and the reciprocating masses sum m_j R^2 / 2 (the mean of m_j (dx/dphi)^2).

    Parameters
    ----------
    masses : crankdyn.crank.masses.Masses
        The crank-train masses of one cylinder.
    geometry : crankdyn.crank.geometry.CrankGeometry
        The crank geometry.
    throws : sequence of int
        The throw (1-based) of every cylinder.

    Returns
    -------
    rotating, reciprocating : float
        Z m_r R^2 and Z m_j R^2 / 2 (kg m^2).
    """
    r = geometry.crank_radius
    m_rot = rotating_masses(masses, geometry.rod_length, throws)
    m_j = equivalent_masses(masses, geometry.rod_length)[0]
    return float(m_rot.sum() * r * r), len(throws) * m_j * r * r / 2.0


def rim_width(inertia: float, density: float, outer: float, inner: float = 0.0) -> float:
    """Width of a rim (or a solid disc) of a given moment of inertia, seed 000 section 2.4.

    b = 32 I / (pi rho (D_1^4 - D_2^4)) (module docstring).

    Parameters
    ----------
    inertia : float
        Moment of inertia I (kg m^2).
    density : float
        Material density rho (kg/m^3).
    outer : float
        Outer diameter D_1 (m).
    inner : float
        Inner diameter D_2 (m); 0 (default) for a solid disc.

    Returns
    -------
    float
        The width b (m).

    Examples
    --------
    A steel disc of 0.4 m for 1 kg m^2:

    >>> round(rim_width(1.0, 7850.0, 0.4) * 1e3, 2)  # mm
    50.68
    """
    return 32.0 * inertia / (math.pi * density * (outer**4 - inner**4))


# ---- result -------------------------------------------------------------------------------------


@dataclass(frozen=True)
class FlywheelResult(Result):
    """Speed fluctuation of an engine and the flywheel it needs (:func:`flywheel_analysis`,
    :func:`engine_flywheel`; module docstring).

    Parameters
    ----------
    cycle_angle : float
        Crank angle of the cycle (rad; not exported).
    """

    title = "Speed fluctuation and flywheel"
    crank_angle: NDArray[np.float64] = column("crank_angle_deg", "Crank angle θ", "deg", DEG)
    torque: NDArray[np.float64] = column("torque_Nm", "Engine torque M", "N·m")
    excess_work_curve: NDArray[np.float64] = column(
        "excess_work_curve_J", "Excess work W = ∫(M − M_m)dθ", "J"
    )
    crank_speed: NDArray[np.float64] = column("crank_speed_rpm", "Crank speed", "rpm", RPM)
    engine: str = scalar("engine", "Engine", "", summary=False)
    speed: float = scalar("speed_rpm", "Speed", "rpm", RPM)
    mean_torque: float = scalar("mean_torque_Nm", "Mean torque M_m", "N·m", summary=False)
    max_torque: float = scalar("max_torque_Nm", "Max torque", "N·m", summary=False)
    min_torque: float = scalar("min_torque_Nm", "Min torque", "N·m", summary=False)
    torque_nonuniformity: float | None = scalar(
        "torque_nonuniformity", "Torque non-uniformity μ = (M_max − M_min)/M_m", "", fmt=".4g",
        better="min",
    )  # fmt: skip
    excess_work: float = scalar(
        "excess_work_J", "Largest excess work ΔE", "J", better="min", headline=True,
        description="Energy swing of the torque curve",
    )  # fmt: skip
    excess_work_coefficient: float | None = scalar(
        "excess_work_coefficient", "Excess-work coefficient ξ = ΔE/(M_m Θ)", "", fmt=".4g",
        better="min",
    )  # fmt: skip
    angle_of_min_speed: float = scalar("angle_of_min_speed_deg", "Slowest at θ", "deg", DEG)
    angle_of_max_speed: float = scalar("angle_of_max_speed_deg", "Fastest at θ", "deg", DEG)
    rotating_inertia: float = scalar("rotating_inertia_kgm2", "Rotating masses Σ m_r R²", "kg·m²")
    reciprocating_inertia: float = scalar(
        "reciprocating_inertia_kgm2", "Reciprocating masses Σ m_j R²/2", "kg·m²"
    )
    other_inertia: float = scalar("other_inertia_kgm2", "Other inertias I₃", "kg·m²")
    target_delta: float | None = scalar("target_delta", "Target δ", "", fmt=".4g")
    required_inertia: float | None = scalar(
        "required_inertia_kgm2", "Required total inertia I₀ = ΔE/(δ ω²)", "kg·m²"
    )
    flywheel_inertia: float = scalar(
        "flywheel_inertia_kgm2", "Flywheel inertia I_F", "kg·m²", better="min", headline=True,
        description="Flywheel needed for the target degree of cyclic irregularity (or the "
        "engine's own)",
    )  # fmt: skip
    total_inertia: float = scalar("total_inertia_kgm2", "Total inertia", "kg·m²")
    gd2: float = scalar("gd2_Nm2", "Flywheel moment GD² = 4 g I_F", "N·m²")
    speed_fluctuation: float = scalar(
        "speed_fluctuation", "δ = (ω_max − ω_min)/ω_m achieved", "", fmt=".5g",
        name="cyclic_irregularity", better="min", headline=True,
        description="Degree of cyclic irregularity with the engine's flywheel or the one sized "
        "for the target",
    )  # fmt: skip
    speed_fluctuation_linear: float = scalar(
        "speed_fluctuation_linear", "δ = ΔE/(I ω_m²)", "", fmt=".5g"
    )
    min_speed: float = scalar("min_speed_rpm", "Min speed", "rpm", RPM)
    max_speed: float = scalar("max_speed_rpm", "Max speed", "rpm", RPM)
    density: float | None = scalar(
        "density_kg_m3", "Flywheel density", "kg/m³", name="flywheel_density"
    )
    outer_diameter: float | None = scalar(
        "outer_diameter_m", "Outer diameter D₁", "m", name="flywheel_outer_diameter"
    )
    disc_width: float | None = scalar("disc_width_m", "Solid disc: width", "m")
    disc_mass: float | None = scalar("disc_mass_kg", "Solid disc: mass", "kg")
    inner_diameter: float | None = scalar(
        "inner_diameter_m", "Rim: inner diameter D₂", "m", name="flywheel_inner_diameter"
    )
    rim_width: float | None = scalar("rim_width_m", "Rim: width", "m")
    rim_mass: float | None = scalar("rim_mass_kg", "Rim: mass", "kg")
    rim_speed: float | None = scalar("rim_speed_m_s", "Peripheral speed at D₁", "m/s")
    hoop_stress: float | None = scalar("rim_hoop_stress_Pa", "Thin-rim hoop stress ρv²", "Pa")
    notes: tuple[str, ...] = scalar("notes", "Notes", "")
    cycle_angle: float = field(default=4.0 * math.pi, repr=False)

    FIGURES = (
        derived(
            "flywheel_share", "flywheel_share", "Flywheel share of the total inertia I_F/I₀", "",
            lambda r: _share(r),
            description="The flywheel's part of the total inertia; seed 000 section 2.4's "
            "shortcut I_F ≈ (0.8-0.9) I₀",
        ),
        derived(
            "shortcut_flywheel_inertia", "shortcut_flywheel_inertia_kgm2",
            "Shortcut flywheel I_F ≈ 0.85 I₀", "kg·m²", lambda r: _shortcut(r),
            description="Seed 000 section 2.4's estimate of the flywheel from the required "
            "total inertia, I_F ≈ (0.8-0.9) I₀ (mid value; the exact sizing above)",
            unavailable="no target δ: no required total inertia I₀",
        ),
    )  # fmt: skip

    def plot(self, fig: Figure | None = None) -> Figure:
        """Torque, excess work (energy swing) and instantaneous speed.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.flywheel import plot_flywheel

        return plot_flywheel(self, fig=fig)


SHORTCUT_SHARE = (0.8, 0.9)
"""Seed 000 section 2.4: the flywheel is usually 0.8-0.9 of the engine's total inertia, a
shortcut for its size from the required total inertia I_0 (the exact sizing subtracts the crank
train's inertias)."""


def _share(r: FlywheelResult) -> tuple[float, str] | None:
    if not r.total_inertia > 0.0:
        return None
    share = r.flywheel_inertia / r.total_inertia
    low, high = SHORTCUT_SHARE
    inside = "within" if low <= share <= high else "outside"
    return share, f"{inside} the seed's {low:g}-{high:g}"


def _shortcut(r: FlywheelResult) -> tuple[float, str] | None:
    if r.required_inertia is None:
        return None
    low, high = (f * r.required_inertia for f in SHORTCUT_SHARE)
    mid = 0.5 * (low + high)
    return mid, f"range {low:.4g}-{high:.4g} kg·m², exact {r.flywheel_inertia:.4g} kg·m²"


def flywheel_analysis(
    angle: ArrayLike,
    torque: ArrayLike,
    speed: float,
    cycle_angle: float,
    *,
    rotating_inertia: float = 0.0,
    reciprocating_inertia: float = 0.0,
    inputs: FlywheelInputs | None = None,
    delta: float | None = None,
    inertia: float | None = None,
    engine: str = "",
) -> FlywheelResult:
    """Speed fluctuation and flywheel from a torque curve (module docstring).

    Parameters
    ----------
    angle : array_like
        Crankshaft angles of the torque curve over one cycle (rad).
    torque : array_like
        The engine torque at those angles (N m), at constant speed.
    speed : float
        Mean crank speed w_m (rad/s).
    cycle_angle : float
        Theta (rad): 4 pi four-stroke, 2 pi two-stroke.
    rotating_inertia, reciprocating_inertia : float
        Z m_r R^2 and Z m_j R^2 / 2 of the crank train (kg m^2), :func:`crank_train_inertia`.
    inputs : FlywheelInputs or None
        Flywheel inputs (target delta, given flywheel, other inertias, material, diameters).
    delta : float or None
        Target degree of cyclic irregularity (dimensionless); overrides ``inputs.delta``.
    inertia : float or None
        A given flywheel's inertia (kg m^2), to find its delta; overrides ``inputs.inertia``.
        With both a target delta and a flywheel, the flywheel for the target is sized and the
        given one ignored.
    engine : str
        Name for the result.

    Returns
    -------
    FlywheelResult
        Torque (N m), excess work (J) and crank speed (rad/s) over the cycle; mu, Delta E, xi,
        the inertias (kg m^2), GD^2 (N m^2), the achieved delta and, with a material and
        diameters, the disc or rim (m, kg) and its peripheral speed (m/s) and hoop stress (Pa).

    Raises
    ------
    InputError
        If the speed is not positive, neither a target delta nor a flywheel is given, there is
        no inertia at all, the torque curve is invalid, or the inertia is too small to carry
        the crankshaft through the cycle.

    Examples
    --------
    M = 100 + 40 sin(theta) N m at 100 rad/s, sized for delta = 1/100:
    I_0 = Delta E / (delta w^2) = 80 / (0.01 x 100^2) = 0.8 kg m^2.

    >>> theta = np.linspace(0.0, 2 * np.pi, 3600, endpoint=False)
    >>> f = flywheel_analysis(theta, 100 + 40 * np.sin(theta), 100.0, 2 * np.pi, delta=0.01)
    >>> round(f.required_inertia, 6), round(f.speed_fluctuation, 4)
    (0.8, 0.01)
    """
    inputs = inputs or FlywheelInputs()
    w = float(speed)
    if not (math.isfinite(w) and w > 0.0):
        raise InputError("the speed must be positive", key="speed", value=speed)
    if delta is not None:
        inputs = replace(inputs, delta=delta)
    if inertia is not None:
        inputs = replace(inputs, inertia=inertia)
    if inputs.delta is None and inputs.inertia is None:
        raise InputError(
            "give a target degree of cyclic irregularity (--delta or [flywheel] delta) or a "
            "flywheel inertia (--inertia or [flywheel] inertia)",
            key="delta",
        )
    ew = excess_work(angle, torque, cycle_angle)
    m = np.asarray(torque, dtype=float)[: ew.angle.size]
    notes: list[str] = []
    mean = ew.mean_torque
    crank = rotating_inertia + reciprocating_inertia + inputs.other_inertia
    if inputs.delta is not None:
        required = ew.swing / (inputs.delta * w * w)
        flywheel = required - crank
        if flywheel <= 0.0:
            notes.append(
                f"the crank train's own inertia ({crank:.4g} kg*m^2) already meets the target "
                "delta: no flywheel needed"
            )
            flywheel = 0.0
        if inputs.inertia is not None:
            notes.append("a target delta is given: the flywheel is sized, the given one ignored")
    else:
        required = None
        assert inputs.inertia is not None  # checked above: a delta or an inertia is given
        flywheel = inputs.inertia
    total = flywheel + crank
    if total <= 0.0:
        raise InputError(
            "no inertia at all: give the masses, other_inertia or a flywheel", key="inertia"
        )
    omega = instantaneous_speed(ew.angle, ew.work, cycle_angle, total, w)
    nonuniformity = coefficient = None
    if mean > 0.0:
        nonuniformity = float((m.max() - m.min()) / mean)
        coefficient = ew.swing / (mean * cycle_angle)
    else:
        notes.append("mean torque not positive: no non-uniformity or excess-work coefficient")
    sizing = _sizing(flywheel, inputs, w, notes)
    return FlywheelResult(
        crank_angle=freeze(ew.angle),
        torque=freeze(m),
        excess_work_curve=freeze(ew.work),
        crank_speed=freeze(omega),
        engine=engine,
        speed=w,
        mean_torque=mean,
        max_torque=float(m.max()),
        min_torque=float(m.min()),
        torque_nonuniformity=nonuniformity,
        excess_work=ew.swing,
        excess_work_coefficient=coefficient,
        angle_of_min_speed=ew.angle_of_min,
        angle_of_max_speed=ew.angle_of_max,
        rotating_inertia=rotating_inertia,
        reciprocating_inertia=reciprocating_inertia,
        other_inertia=inputs.other_inertia,
        target_delta=inputs.delta,
        required_inertia=required,
        flywheel_inertia=flywheel,
        total_inertia=total,
        gd2=4.0 * G * flywheel,
        speed_fluctuation=float((omega.max() - omega.min()) / w),
        speed_fluctuation_linear=ew.swing / (total * w * w),
        min_speed=float(omega.min()),
        max_speed=float(omega.max()),
        notes=tuple(notes),
        cycle_angle=cycle_angle,
        **sizing,
    )


def _sizing(
    flywheel: float, inputs: FlywheelInputs, w: float, notes: list[str]
) -> dict[str, float | None]:
    out: dict[str, float | None] = dict.fromkeys(
        (
            "density",
            "outer_diameter",
            "disc_width",
            "disc_mass",
            "inner_diameter",
            "rim_width",
            "rim_mass",
            "rim_speed",
            "hoop_stress",
        )
    )
    rho, d1, d2 = inputs.density, inputs.max_diameter, inputs.inner_diameter
    if rho is None or d1 is None:
        if flywheel > 0.0:
            notes.append("no [flywheel] density and max_diameter: the flywheel is not sized")
        return out
    if flywheel <= 0.0:
        return out
    v = w * d1 / 2.0
    out.update(density=rho, outer_diameter=d1, rim_speed=v, hoop_stress=rho * v * v)
    b = rim_width(flywheel, rho, d1)
    out.update(disc_width=b, disc_mass=rho * b * math.pi * d1 * d1 / 4.0)
    if d2 is not None:
        b = rim_width(flywheel, rho, d1, d2)
        out.update(
            inner_diameter=d2, rim_width=b, rim_mass=rho * b * math.pi * (d1 * d1 - d2 * d2) / 4.0
        )
    return out


def engine_flywheel(
    engine: Engine,
    speed: float,
    *,
    delta: float | None = None,
    inertia: float | None = None,
    inputs: FlywheelInputs | None = None,
    step: float = math.radians(0.5),
    torque: TorqueResult | None = None,
) -> FlywheelResult:
    """Speed fluctuation and flywheel of an engine at a speed (module docstring).

    The torque is the engine's total (gas and inertia) torque over a cycle at constant speed
    from :func:`crankdyn.engine.torque.engine_torque` (the engine's pressure trace, or its synthetic
    model); the load takes the mean torque.

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine (masses required for the torque).
    speed : float
        Mean crank speed (rad/s).
    delta : float or None
        Target degree of cyclic irregularity (dimensionless); overrides the engine's
        ``[flywheel]`` inputs.
    inertia : float or None
        A given flywheel's inertia (kg m^2); overrides the engine's ``[flywheel]`` inputs.
    inputs : FlywheelInputs or None
        Flywheel inputs; default ``engine.flywheel``.
    step : float
        Crank-angle step of the torque curve (rad); default 0.5 deg.
    torque : crankdyn.engine.torque.TorqueResult or None
        The torque already computed at this speed, to reuse.

    Returns
    -------
    FlywheelResult
        As :func:`flywheel_analysis`; the largest and smallest torque and the non-uniformity
        are the torque analysis's refined ones.

    Raises
    ------
    InputError
        If the engine has no masses, or as :func:`flywheel_analysis`.

    Examples
    --------
    >>> import crankdyn
    >>> engine = crankdyn.Engine.example("inline6-diesel")
    >>> f = engine_flywheel(engine, 2200 * math.pi / 30, delta=1 / 200)
    >>> round(f.speed_fluctuation_linear, 6)  # Delta E / (I w_m^2) with the sized inertia
    0.005
    """
    from crankdyn.engine.torque import engine_torque

    if engine.masses is None:
        raise InputError(
            "the flywheel needs the engine torque, hence the crank-train masses: add [masses]",
            file=engine.source,
        )
    if torque is None:
        torque = engine_torque(engine, speed, step=step)
    rotating, reciprocating = crank_train_inertia(
        engine.masses, engine.geometry, engine.cylinders.throws
    )
    result = flywheel_analysis(
        torque.crank_angle,
        torque.total_torque,
        speed,
        engine.cycle_angle,
        rotating_inertia=rotating,
        reciprocating_inertia=reciprocating,
        inputs=inputs if inputs is not None else (engine.flywheel or FlywheelInputs()),
        delta=delta,
        inertia=inertia,
        engine=engine.name,
    )
    # the torque's own extrema are refined between the grid points (crankdyn.engine.torque):
    # the largest and smallest torque and the non-uniformity are the same numbers everywhere
    changes: dict[str, Any] = {"max_torque": torque.max_torque, "min_torque": torque.min_torque}
    if result.torque_nonuniformity is not None and torque.mean_torque > 0.0:
        changes["torque_nonuniformity"] = (
            torque.max_torque - torque.min_torque
        ) / torque.mean_torque
    if torque.notes:
        changes["notes"] = tuple(torque.notes) + result.notes
    return replace(result, **changes)
