"""Engine torque: single-cylinder, total, main-journal and crank-pin torques, mean torque and
power (seed 000 sections 2.2-2.3).

- Cylinder torque M_i = T_i R (gas part P_g and inertia part P_j; over a cycle at constant
  speed the inertia part does no work, since oint -m_j a dx = -m_j [v^2/2] = 0, so it averages
  to zero).
- Total torque M(theta) = sum_i M_i, each cylinder at its own crank angle theta - psi_i and
  cycle phase theta - Phi_i (throw angles and firing angles from the firing order, inline and
  V engines).
- Main-journal torques, accumulated from the free end (seed 000): the journal behind throw j
  carries M_J,j = sum of the torques of throws 1..j; the last is the engine's output torque.
- Crank-pin torques: with each throw simply supported on its two main bearings (half of its
  tangential force reacted at each), the pin of throw j twists under
  M_P,j = M_J,j-1 + M_throw,j / 2.
- Mean indicated torque M_i = (1/Theta) oint M dtheta over the cycle angle Theta; since
  M dtheta = P dx, M_i Theta = Z W_i (Z cylinders, W_i indicated work per cylinder and cycle).
  Mean effective torque M_e = eta_m M_i with the mechanical efficiency eta_m; indicated and
  effective power P = M w (seed 000: P = M n / 9550 in kW with n in rpm).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import DEG, RPM
from crankdyn.crank.indicated import indicated_work
from crankdyn.crank.pressure import PressureTrace
from crankdyn.engine.forces import (
    SUMMARY_STEP,
    CrankTrain,
    crank_tangential,
    crank_train,
    cycle_grid,
    refined_extrema,
    reuse_train,
    throw_sums,
)
from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.plausibility import PlausibilityWarning
from crankdyn.results import Result, column, freeze, scalar

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["EngineTorque", "TorqueResult", "engine_torque", "journal_torques"]


_MEAN_STEP = math.radians(0.1)


def _mean_torque(engine: Engine, train: CrankTrain) -> float:
    """Mean of the total torque over the cycle by the rectangle rule on a 0.1 deg grid (the
    trace's kinks make the rule second-order), whatever grid the rows use."""
    if train.theta.size > 1 and np.allclose(np.diff(train.theta), _MEAN_STEP, atol=1e-12, rtol=0):
        return float(np.mean(train.tangential[:, :-1].sum(axis=0))) * engine.geometry.crank_radius
    fine = cycle_grid(engine, _MEAN_STEP)[:-1]
    dense = crank_tangential(engine, train.speed, fine, pressure=train.trace)
    return float(np.mean(dense.sum(axis=0))) * engine.geometry.crank_radius


def _torque_extrema(engine: Engine, train: CrankTrain) -> tuple[float, float]:
    """(max, min) of the total torque over the whole cycle: on the summary grid, refined
    (:func:`crankdyn.engine.forces.refined_extrema`), whatever grid the rows use."""
    r = engine.geometry.crank_radius
    if not (
        train.theta.size > 1 and np.allclose(np.diff(train.theta), SUMMARY_STEP, atol=1e-12, rtol=0)
    ):
        train = train.summary_train()  # shared with the bearing loads of the same train
    total = train.tangential.sum(axis=0) * r
    sign = np.array([[1.0], [-1.0]])  # the largest torque, and the largest of its negative

    def f(angles: NDArray[np.float64]) -> NDArray[np.float64]:
        """Row 0 the total torque at row 0's angles, row 1 its negative at row 1's."""
        local = crank_train(engine, train.speed, angles.reshape(-1), pressure=train.trace)
        both = local.tangential.sum(axis=0) * r
        return sign * both.reshape(angles.shape)

    peaks = refined_extrema(f, train.theta, sign * total, period=engine.cycle_angle)[0]
    top, low = float(peaks[0]), -float(peaks[1])
    return top, low


def journal_torques(
    throw_torque: ArrayLike,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Main-journal and crank-pin torques from the throw torques (seed 000 section 2.2).

    The journal behind throw j carries the sum over throws 1..j (from the free end); the pin of
    throw j the journal before it plus half of its own torque (module docstring).

    Parameters
    ----------
    throw_torque : array_like
        Torque of every throw (N m), shape (throws, angles).

    Returns
    -------
    journal, pin : numpy.ndarray
        Main-journal and crank-pin torques (N m), shape (throws, angles).

    Examples
    --------
    >>> journal, pin = journal_torques([[100.0], [50.0], [-30.0]])
    >>> journal.ravel(), pin.ravel()
    (array([100., 150., 120.]), array([ 50., 125., 135.]))
    """
    m = np.asarray(throw_torque, dtype=float)
    journal = np.cumsum(m, axis=0)
    pin = journal - 0.5 * m
    return journal, pin


@dataclass(frozen=True)
class TorqueResult(Result):
    """Torque of every cylinder, the total, main-journal and crank-pin torques over one cycle,
    with mean torque and power (:func:`engine_torque`; module docstring).

    Parameters
    ----------
    cycle_angle : float
        Crank angle of the cycle (rad; not exported).
    throws : tuple of int
        Throw (1-based) of every cylinder (not exported).
    warnings : tuple of crankdyn.plausibility.PlausibilityWarning
        Plausibility warnings of the engine at this speed.
    """

    title = "Engine torque"
    crank_angle: NDArray[np.float64] = column("crank_angle_deg", "Crank angle θ", "deg", DEG)
    cylinder_torque: NDArray[np.float64] = column("cylinder_torque_Nm", "Cylinder", "N·m")
    total_torque: NDArray[np.float64] = column("total_torque_Nm", "Total torque", "N·m")
    gas_torque: NDArray[np.float64] = column("total_gas_torque_Nm", "Total gas torque", "N·m")
    inertia_torque: NDArray[np.float64] = column(
        "total_inertia_torque_Nm", "Total inertia torque", "N·m"
    )
    journal_torque: NDArray[np.float64] = column("journal_torque_Nm", "Journal behind throw", "N·m")
    pin_torque: NDArray[np.float64] = column("crank_pin_torque_Nm", "Pin torque, throw", "N·m")
    mean_torque: float = scalar(
        "mean_torque_Nm", "Mean indicated torque", "N·m", headline=True, better="max"
    )
    mean_effective_torque: float | None = scalar(
        "mean_effective_torque_Nm", "Mean effective torque", "N·m"
    )
    mechanical_efficiency: float | None = scalar(
        "mechanical_efficiency", "Mechanical efficiency", "", fmt=".4g"
    )
    indicated_power: float = scalar(
        "indicated_power_kW", "Indicated power", "kW", 1e-3, headline=True, better="max"
    )
    effective_power: float | None = scalar("effective_power_kW", "Effective power", "kW", 1e-3)
    max_torque: float = scalar("max_torque_Nm", "Max total torque", "N·m", headline=True)
    min_torque: float = scalar("min_torque_Nm", "Min total torque", "N·m", headline=True)
    indicated_work: float = scalar(
        "indicated_work_J", "Indicated work per cylinder", "J", headline=True
    )
    imep: float = scalar(
        "imep_Pa", "IMEP", "Pa", checked="imep", headline=True, better="max",
        description="Indicated mean effective pressure",
    )  # fmt: skip
    peak_pressure: float = scalar(
        "peak_pressure_Pa", "Peak pressure", "Pa", checked="peak_pressure", headline=True,
        better="min",
    )  # fmt: skip
    peak_angle: float = scalar(
        "peak_pressure_angle_deg", "Peak pressure after firing TDC", "deg", DEG
    )
    speed: float = scalar("speed_rpm", "Speed", "rpm", RPM)
    cylinders: int = scalar("cylinders", "Cylinders", "")
    firing_angles: NDArray[np.float64] = scalar(
        "firing_angles_deg", "Firing angles", "deg", DEG, fmt=".5g"
    )
    pressure_source: str = scalar("pressure_source", "Pressure from", "")
    notes: tuple[str, ...] | None = scalar("notes", "Notes", "")
    cycle_angle: float = field(default=4.0 * math.pi, repr=False)
    throws: tuple[int, ...] = field(default=(), repr=False)
    warnings: tuple[PlausibilityWarning, ...] = field(default=(), repr=False, compare=False)

    def plot(self, fig: Figure | None = None) -> Figure:
        """Single-cylinder and total torque, journal torques.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.forces import plot_torque

        return plot_torque(self, fig=fig)


def engine_torque(
    engine: Engine,
    speed: float,
    *,
    step: float = math.radians(1.0),
    mechanical_efficiency: float | None = None,
    pressure: PressureTrace | None = None,
    train: CrankTrain | None = None,
) -> TorqueResult:
    """Torques of an engine over one cycle every ``step`` (module docstring; seed 000
    sections 2.2-2.3).

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine (masses required).
    speed : float
        Crank speed w (rad/s).
    step : float
        Crank-angle step (rad) of the rows; must divide the cycle angle. Default 1 deg. The
        summary does not depend on it: the mean is taken over the cycle with the rectangle rule
        on a 0.1 deg grid (exact for trigonometric polynomials of low enough order,
        second-order accurate otherwise), the largest and smallest torque on the summary grid
        and refined.
    mechanical_efficiency : float or None
        eta_m (dimensionless, 0 < eta_m <= 1) for the effective torque and power; default the
        engine's [operating] mechanical_efficiency; None there too leaves them out.
    pressure : PressureTrace or None
        Pressure trace; default the engine's own or its synthetic model.
    train : CrankTrain or None
        The crank train of this engine at this speed over the same cycle grid
        (``crank_train(engine, speed, cycle_grid(engine, step))``), when already computed, e.g.
        for :func:`crankdyn.engine.bearings.bearing_loads`; default: evaluated here.

    Returns
    -------
    TorqueResult
        Torques (N m) over the crank angle (rad), the mean indicated and effective torque
        (N m), the indicated and effective power (W), the extremes (N m), the indicated work
        (J) and IMEP (Pa).

    Raises
    ------
    InputError
        If the efficiency is out of range, the speed not positive, the step does not divide
        the cycle, or the engine has no masses.

    Examples
    --------
    The mean torque is the indicated work of the cylinders over the cycle angle,
    M_i Theta = Z W_i (module docstring):

    >>> import crankdyn
    >>> engine = crankdyn.Engine.example("inline6-diesel")
    >>> t = engine_torque(engine, 2200 * math.pi / 30)
    >>> round(t.mean_torque, 1), round(6 * t.indicated_work / (4 * math.pi), 1)
    (1073.0, 1073.0)
    """
    if mechanical_efficiency is None:
        mechanical_efficiency = engine.mechanical_efficiency
    if mechanical_efficiency is not None and not 0.0 < mechanical_efficiency <= 1.0:
        raise InputError(
            "the mechanical efficiency must lie in 0 < eta <= 1",
            key="mechanical_efficiency",
            value=mechanical_efficiency,
        )
    theta = cycle_grid(engine, step)
    train = reuse_train(train, engine, speed, theta, pressure)
    r = engine.geometry.crank_radius
    cyl = engine.cylinders
    per_cylinder = train.tangential * r
    throw_torque = throw_sums(per_cylinder, cyl.throws, cyl.throw_count)
    journal, pin = journal_torques(throw_torque)
    total = per_cylinder.sum(axis=0)
    mean = _mean_torque(engine, train)
    top, low = _torque_extrema(engine, train)
    work = (  # shared with the train's plausibility warnings
        train.indicated_work()
        if train.engine.geometry is engine.geometry
        else indicated_work(train.trace, engine.geometry)
    )
    peak, at = train.trace.peak
    effective = None if mechanical_efficiency is None else mechanical_efficiency * mean
    notes = []
    if engine.pressure is None:
        notes.append("no pressure trace: synthetic Wiebe model with default parameters")
    return TorqueResult(
        crank_angle=freeze(theta),
        cylinder_torque=freeze(per_cylinder),
        total_torque=freeze(total),
        gas_torque=freeze((train.gas_tangential * r).sum(axis=0)),
        inertia_torque=freeze((train.inertia_tangential * r).sum(axis=0)),
        journal_torque=freeze(journal),
        pin_torque=freeze(pin),
        mean_torque=mean,
        mean_effective_torque=effective,
        mechanical_efficiency=mechanical_efficiency,
        indicated_power=mean * train.speed,
        effective_power=None if effective is None else effective * train.speed,
        max_torque=top,
        min_torque=low,
        indicated_work=work,
        imep=work / engine.geometry.swept_volume,
        peak_pressure=peak,
        peak_angle=at,
        speed=train.speed,
        cylinders=cyl.count,
        firing_angles=freeze(cyl.firing_angles),
        pressure_source=train.trace.source or "",
        notes=tuple(notes) or None,
        cycle_angle=engine.cycle_angle,
        throws=tuple(cyl.throws),
        warnings=train.warnings(),
    )


EngineTorque = TorqueResult
"""The former name of :class:`TorqueResult` (kept as an alias)."""
