"""Crank-pin and main-bearing loads of an engine (seed 000 section 2.2: R_B and R_K).

Crank-pin load R_B of every throw: the force of its rod(s) on the pin plus the big ends'
centrifugal force, in the crank frame (components along the crank toward the centre and
tangential, positive in the direction of rotation); on a V engine's shared pin the two rods,
each at its own bank's crank angle, are added in that frame.

Main-bearing loads R_K: every throw is taken as a beam simply supported on the main bearings
either side of it (a main bearing between every two throws and at both ends: throws + 1
bearings, numbered from the free end), loaded at mid-span by its rods' forces and the
centrifugal force of its rotating masses m_r R w^2, so each adjacent bearing carries half of
it (the statically determinate "split crankshaft" method; e.g. Kolchin and Demidov, *Design of
Automotive Engines*, Mir 1984, ch. on bearing loads). A bearing's load is the sum of the halves
of its two throws, added as vectors in the engine frame (horizontal positive to the right seen
from the free end, vertical positive toward the cylinder heads of an inline engine): the force
of the journal on the bearing.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import DEG, RPM
from crankdyn.crank.pressure import PressureTrace
from crankdyn.engine.forces import (
    SUMMARY_STEP,
    CrankTrain,
    crank_train,
    cycle_grid,
    load_angle,
    refined_extrema,
    reuse_train,
)
from crankdyn.engine.model import Engine
from crankdyn.plausibility import PlausibilityWarning
from crankdyn.results import Result, column, freeze, scalar
from crankdyn.summary import reduced

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "BearingLoads",
    "BearingsResult",
    "bearing_loads",
    "engine_bearings",
    "main_bearing_loads",
]


def main_bearing_loads(
    throw_x: ArrayLike, throw_y: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Main-bearing loads from the throw forces by the simply supported split.

    Bearing b (0-based from the free end, throws + 1 of them) carries half of throw b - 1 and
    half of throw b (module docstring; Kolchin and Demidov 1984).

    Parameters
    ----------
    throw_x, throw_y : array_like
        Horizontal and vertical force of every throw on the crankshaft (N), shape
        (throws, angles).

    Returns
    -------
    bearing_x, bearing_y : numpy.ndarray
        Horizontal and vertical load of every main bearing (N), shape (throws + 1, angles).

    Examples
    --------
    >>> bx, by = main_bearing_loads([[0.0], [0.0]], [[100.0], [-40.0]])
    >>> by.ravel()
    array([ 50.,  30., -20.])
    """
    hx = np.asarray(throw_x, dtype=float)
    hy = np.asarray(throw_y, dtype=float)
    zero = np.zeros((1, hx.shape[1]))
    bx = 0.5 * (np.vstack([hx, zero]) + np.vstack([zero, hx]))
    by = 0.5 * (np.vstack([hy, zero]) + np.vstack([zero, hy]))
    return bx, by


@dataclass(frozen=True)
class BearingsResult(Result):
    """Crank-pin loads (one row per throw) and main-bearing loads (one row per bearing) over
    the cycle (:func:`engine_bearings`; module docstring for frames and signs).

    Parameters
    ----------
    warnings : tuple of crankdyn.plausibility.PlausibilityWarning
        Plausibility warnings of the engine at this speed.
    """

    title = "Crank-pin and main-bearing loads"
    crank_angle: NDArray[np.float64] = column("crank_angle_deg", "Crank angle θ", "deg", DEG)
    pin_load: NDArray[np.float64] = column("crank_pin_load_N", "Pin load", "N")
    pin_load_angle: NDArray[np.float64] = column(
        "crank_pin_load_angle_deg", "Pin load angle", "deg", DEG
    )
    pin_tangential: NDArray[np.float64] = column(
        "crank_pin_load_tangential_N", "Pin tangential", "N"
    )
    pin_radial: NDArray[np.float64] = column("crank_pin_load_radial_N", "Pin radial", "N")
    bearing_load: NDArray[np.float64] = column("main_bearing_load_N", "Main bearing", "N")
    bearing_load_angle: NDArray[np.float64] = column(
        "main_bearing_load_angle_deg", "Main bearing angle", "deg", DEG
    )
    bearing_horizontal: NDArray[np.float64] = column(
        "main_bearing_load_horizontal_N", "Main bearing horiz.", "N"
    )
    bearing_vertical: NDArray[np.float64] = column(
        "main_bearing_load_vertical_N", "Main bearing vert.", "N"
    )
    max_pin_load: NDArray[np.float64] = scalar(
        "max_crank_pin_load_per_throw_N", "Max crank-pin load per throw", "N"
    )
    mean_pin_load: NDArray[np.float64] = scalar(
        "mean_crank_pin_load_per_throw_N", "Mean crank-pin load per throw", "N"
    )
    max_bearing_load: NDArray[np.float64] = scalar(
        "max_main_bearing_load_per_bearing_N", "Max main-bearing load per bearing", "N"
    )
    mean_bearing_load: NDArray[np.float64] = scalar(
        "mean_main_bearing_load_per_bearing_N", "Mean main-bearing load per bearing", "N"
    )
    speed: float = scalar("speed_rpm", "Speed", "rpm", RPM)
    pressure_source: str = scalar("pressure_source", "Pressure from", "")
    notes: tuple[str, ...] | None = scalar("notes", "Notes", "")
    warnings: tuple[PlausibilityWarning, ...] = field(default=(), repr=False, compare=False)

    FIGURES = (
        reduced(
            "max_pin_load", "max", over="throw", name="max_crank_pin_load",
            key="max_crank_pin_load_N", label="Max crank-pin load", better="min", headline=True,
        ),
        reduced(
            "mean_pin_load", "max", over="throw", name="max_mean_crank_pin_load",
            key="max_mean_crank_pin_load_N", label="Largest mean crank-pin load", better="min",
        ),
        reduced(
            "max_bearing_load", "max", over="bearing", name="max_main_bearing_load",
            key="max_main_bearing_load_N", label="Max main-bearing load", better="min",
            headline=True,
        ),
        reduced(
            "mean_bearing_load", "max", over="bearing", name="max_mean_main_bearing_load",
            key="max_mean_main_bearing_load_N", label="Largest mean main-bearing load",
            better="min",
        ),
    )  # fmt: skip

    def plot(self, fig: Figure | None = None) -> Figure:
        """Polar diagrams of the crank-pin loads (crank frame) and main-bearing loads (engine
        frame).

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.forces import plot_bearing_polars

        return plot_bearing_polars(self, fig=fig)


def engine_bearings(
    engine: Engine,
    speed: float,
    angles: ArrayLike | None = None,
    *,
    step: float = math.radians(1.0),
    pressure: PressureTrace | None = None,
    train: CrankTrain | None = None,
) -> BearingsResult:
    """Crank-pin and main-bearing loads of an engine over one cycle (module docstring).

    Parameters
    ----------
    engine : crankdyn.engine.Engine
        The engine (masses required).
    speed : float
        Crank speed w (rad/s).
    angles : array_like or None
        Crankshaft angles (rad); default one cycle every ``step``.
    step : float
        Angle step of the default grid (rad); it must divide the cycle. Default 1 deg.
    pressure : PressureTrace or None
        Pressure trace; default the engine's own or its synthetic model.
    train : CrankTrain or None
        The crank train at exactly these angles, speed and pressure when already computed
        (e.g. shared with :func:`crankdyn.engine.torque.engine_torque`); default: evaluated
        here.

    Returns
    -------
    BearingsResult
        Loads (N) and their directions (rad) over the crank angle, one row per throw or
        bearing; the summary (largest and mean load of every throw and bearing, N) is that of
        the whole cycle on the :data:`~crankdyn.engine.forces.SUMMARY_STEP` grid, the maxima
        refined, whatever grid the rows use.

    Raises
    ------
    InputError
        If the speed is not positive, the step does not divide the cycle, or the engine has no
        masses.

    Examples
    --------
    >>> import crankdyn
    >>> engine = crankdyn.Engine.example("inline6-diesel")
    >>> b = engine_bearings(engine, 2200 * math.pi / 30)
    >>> b.max_pin_load.shape, b.max_bearing_load.shape  # 6 throws, 7 main bearings
    ((6,), (7,))
    """
    theta = cycle_grid(engine, step) if angles is None else np.asarray(angles, dtype=float)
    train = reuse_train(train, engine, speed, theta, pressure)
    t_pin, z_pin = train.pin_loads()
    hx, hy = train.throw_forces()
    bx, by = main_bearing_loads(hx, hy)
    pin = np.hypot(t_pin, z_pin)
    bearing = np.hypot(bx, by)
    max_pin, mean_pin, max_bearing, mean_bearing = _load_summary(engine, train, full=angles is None)
    notes = []
    if not all(m.pin_mass_known for m in train.masses):
        notes.append(
            "rod big-end mass unknown: the crank-pin loads leave out its centrifugal force "
            "(the main-bearing loads include the whole rotating mass)"
        )
    if engine.pressure is None:
        notes.append("no pressure trace: synthetic Wiebe model with default parameters")
    return BearingsResult(
        crank_angle=freeze(theta),
        pin_load=freeze(pin),
        pin_load_angle=freeze(load_angle(-z_pin, t_pin)),
        pin_tangential=freeze(t_pin),
        pin_radial=freeze(z_pin),
        bearing_load=freeze(bearing),
        bearing_load_angle=freeze(load_angle(by, bx)),
        bearing_horizontal=freeze(bx),
        bearing_vertical=freeze(by),
        max_pin_load=freeze(max_pin),
        mean_pin_load=freeze(mean_pin),
        max_bearing_load=freeze(max_bearing),
        mean_bearing_load=freeze(mean_bearing),
        speed=train.speed,
        pressure_source=train.trace.source or "",
        notes=tuple(notes) or None,
        warnings=train.warnings(),
    )


def _load_summary(
    engine: Engine, train: CrankTrain, *, full: bool
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Largest and mean crank-pin and main-bearing loads over the whole cycle: on the summary
    grid (the maxima refined, :func:`crankdyn.engine.forces.refined_extremum`), whatever grid
    ``train`` holds."""
    on_grid = (
        full
        and train.theta.size > 1
        and np.allclose(np.diff(train.theta), SUMMARY_STEP, atol=1e-12, rtol=0.0)
    )
    if not on_grid:
        train = train.summary_train()  # shared with the torque of the same train

    def loads(theta: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        local = crank_train(engine, train.speed, np.asarray(theta), pressure=train.trace)
        t_pin, z_pin = local.pin_loads()
        bx, by = main_bearing_loads(*local.throw_forces())
        return np.hypot(t_pin, z_pin), np.hypot(bx, by)

    pin, bearing = loads(train.theta)
    rows = np.vstack([pin, bearing])  # every throw's pin, then every main bearing

    def row_loads(angles: NDArray[np.float64]) -> NDArray[np.float64]:
        """Row k's load at row k's angles: one crank train over every row's samples."""
        count, samples = angles.shape
        both = np.vstack(loads(angles.reshape(-1)))  # (rows, rows x samples)
        return both.reshape(count, count, samples)[np.arange(count), np.arange(count)]

    peaks = refined_extrema(row_loads, train.theta, rows, period=engine.cycle_angle)[0]
    max_pin, max_bearing = peaks[: pin.shape[0]], peaks[pin.shape[0] :]
    body = slice(0, -1)  # the cycle's end repeats its start
    return (
        max_pin,
        pin[:, body].mean(axis=1),
        max_bearing,
        bearing[:, body].mean(axis=1),
    )


BearingLoads = BearingsResult
"""The former name of :class:`BearingsResult` (kept as an alias)."""


bearing_loads = engine_bearings
"""The former name of :func:`engine_bearings` (kept as an alias)."""
