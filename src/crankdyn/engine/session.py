"""One analysis session: every analysis of an engine (or of a stand-alone torsional model),
computed once and cached, with the defaults of every front end in one place.

The command line, the HTML report, the study runner and notebooks all take their numbers from an
:class:`Analysis`, so the same quantity is the same number everywhere:

>>> import crankdyn
>>> a = crankdyn.Analysis(crankdyn.Engine.example("inline6-diesel"))   # doctest: +SKIP
>>> a.torque.mean_torque, a.forces().max_gas_force  # doctest: +SKIP
>>> a.modes.frequencies_hz[a.modes.index(1)]  # elastic mode 1  # doctest: +SKIP

Defaults (module constants, used by every front end):

- the crank-angle step of the cycle analyses, :data:`STEP` (1 deg); summaries (maxima, minima,
  means) always come from this analysis grid, refined at the extrema, never from a coarser
  display grid: a front end that shows fewer rows asks for them with ``angles=`` and gets the
  rows at those angles with the summary of the full-resolution analysis;
- the speed step of the torsional sweeps over the operating range, :data:`SPEED_STEP` (10 rpm);
- the orders of the torsional analyses: the cycle's fundamental order to :data:`MAX_ORDER` (12);
- the target degree of cyclic irregularity when the engine file names neither a target nor a
  flywheel, :data:`DELTA` (0.01, seed 000 section 2.4);
- the λ-series order of the kinematics, :data:`SERIES_ORDER`;
- the shaft a stress or torque plot shows: the most stressed (most loaded) shaft.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Hashable, Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, Any, TypeVar, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import RPM
from crankdyn.crank.geometry import check_step
from crankdyn.crank.kinematics import SERIES_ORDER
from crankdyn.docs import ref
from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.results import freeze
from crankdyn.torsion.model import TorsionModel

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.crank.indicated import PressureResult
    from crankdyn.crank.kinematics import KinematicsResult, KinematicsSummary
    from crankdyn.engine.balance import BalanceResult
    from crankdyn.engine.bearings import BearingsResult
    from crankdyn.engine.firing_search import FiringCandidate, FiringOrderRanking
    from crankdyn.engine.flywheel import FlywheelResult
    from crankdyn.engine.forces import CrankTrain, ForcesResult
    from crankdyn.engine.model import BalanceInputs
    from crankdyn.engine.torque import TorqueResult
    from crankdyn.measure.orders import OrderSpectrum, OrderTracking
    from crankdyn.results import Result
    from crankdyn.torsion.campbell import CampbellResult
    from crankdyn.torsion.damped import DampedModalResult
    from crankdyn.torsion.dampers import Damper, DamperDesign
    from crankdyn.torsion.excitation import (
        Excitation,
        HarmonicResult,
    )
    from crankdyn.torsion.holzer import HolzerTable, ResidualCurve
    from crankdyn.torsion.modal import ModalResult
    from crankdyn.torsion.response import Peak, RelativeAngle, ResponseResult
    from crankdyn.torsion.transient import TransientResult
    from crankdyn.tvc import TvcResult, TvcSpec

_T = TypeVar("_T")
_R = TypeVar("_R", bound="Result")

__all__ = ["DELTA", "MAX_ORDER", "SERIES_ORDER", "SPEED_STEP", "STEP", "Analysis", "speed_grid"]

STEP = math.radians(1.0)
"""Crank-angle step of every cycle analysis (rad)."""

SPEED_STEP = 10.0 / RPM
"""Speed step of the torsional sweeps over the operating range (rad/s): 10 rpm."""

MAX_SPEEDS = 100_000
"""The most speeds of a speed grid (``--speeds``, ``[tvc] speed_step``): checked before the
grid is made."""

MAX_ORDER = 12.0
"""Highest excitation order of the torsional analyses."""

DELTA = 0.01
"""Target degree of cyclic irregularity when the engine file gives no [flywheel] delta or
inertia (seed 000 section 2.4: 1/100 to 1/300 for most engines)."""


def speed_grid(low: float, high: float, step: float = SPEED_STEP) -> NDArray[np.float64]:
    """Speeds low, low + step, ... up to high.

    The end is included when the step divides the range, to a relative 1e-12. Each speed is
    the nearest multiple of the step in rpm when the ends and the step are round numbers in
    rpm, so that grids read 6000, not 6000.000000000001.

    Parameters
    ----------
    low, high : float
        The ends (rad/s), 0 < low <= high.
    step : float
        The step (rad/s); default :data:`SPEED_STEP` (10 rpm).

    Returns
    -------
    numpy.ndarray
        The speeds (rad/s), ascending.

    Raises
    ------
    InputError
        If the ends or the step are not positive or out of order, or there would be more than
        100000 speeds.

    Examples
    --------
    >>> (speed_grid(1000 / RPM, 1030 / RPM) * RPM).round(9).tolist()
    [1000.0, 1010.0, 1020.0, 1030.0]
    """
    if not (step > 0.0 and high >= low > 0.0):
        raise InputError(
            "expected 0 < LOW <= HIGH and a positive step",
            key="speeds",
            value=[low * RPM, high * RPM, step * RPM],
        )
    count = math.floor((high - low) / step * (1 + 1e-12)) + 1
    if count > MAX_SPEEDS:
        raise InputError(f"too many speeds (more than {MAX_SPEEDS})", key="speeds")
    rpm = low * RPM + step * RPM * np.arange(count)
    rounded = np.round(rpm, 9)
    return rounded / RPM


def _with_summary(rows: _R, full: _R) -> _R:
    """``rows`` (a result on a display grid) with every scalar figure of ``full``."""
    return rows.with_summary_of(full)


class Analysis:
    """The analyses of an engine, or of a torsional model without an engine, computed once.

    Parameters
    ----------
    subject : Engine or TorsionModel
        An :class:`~crankdyn.engine.Engine` or a :class:`~crankdyn.torsion.TorsionModel`.
    speed : float or None
        Operating speed (rad/s) of the one-speed analyses; default the engine's [operating]
        speed (a torsional model: its rated speed).
    speeds : array_like or None
        Speeds (rad/s) of the torsional sweeps; default the torsional model's operating range
        every :data:`SPEED_STEP`.
    orders : array_like or None
        Excitation orders (per revolution) of the torsional analyses; default the cycle's
        fundamental order to :data:`MAX_ORDER`.
    step : float or None
        Crank-angle step (rad) of the cycle analyses; default :data:`STEP`. It must divide the
        working cycle (the library does not round it).
    engine : Engine or None
        With a torsional model as ``subject``: the engine whose cylinders excite it (its
        pressure and masses), if any.
    speed_hint, speeds_hint : str
        How the front end names the speed and the speed range in its error messages.

    Attributes are the analyses: properties for those without options (``torque``,
    ``modes``...), methods with keyword options for the others (``forces(cylinder=2)``,
    ``flywheel(delta=0.005)``); each is computed once per set of options.

    Raises
    ------
    InputError
        If the subject is neither, the speed or the speeds are not positive, or the step does
        not divide the engine's working cycle.

    Examples
    --------
    A stand-alone torsional model has no cylinders, so no cycle analyses:

    >>> a = Analysis(Engine.example("inline6-diesel").torsion)
    >>> a.engine is None, a.cycle, a.computed()
    (True, 'four-stroke', [])
    """

    def __init__(
        self,
        subject: Engine | TorsionModel,
        *,
        speed: float | None = None,
        speeds: ArrayLike | None = None,
        orders: ArrayLike | None = None,
        step: float | None = None,
        engine: Engine | None = None,
        speed_hint: str = "--speed RPM",
        speeds_hint: str = "--speeds LOW:HIGH[:STEP]",
    ) -> None:
        if isinstance(subject, Engine):
            self.engine: Engine | None = subject
            self.model: TorsionModel | None = subject.torsion
        elif isinstance(subject, TorsionModel):
            self.engine = engine
            self.model = subject
        else:
            raise InputError(
                "expected an Engine or a TorsionModel", key="subject", value=type(subject).__name__
            )
        self.subject = subject
        if speed is not None and not (math.isfinite(speed) and speed > 0.0):
            raise InputError("the speed must be positive", key="speed", value=speed * RPM)
        self._speed = None if speed is None else float(speed)
        self._speeds: NDArray[np.float64] | None = None
        if speeds is not None:
            s = np.atleast_1d(np.asarray(speeds, dtype=float))
            if s.ndim != 1 or s.size == 0 or not np.all(np.isfinite(s) & (s > 0.0)):
                raise InputError("speeds must be positive", key="speeds")
            self._speeds = s
        self._orders = None if orders is None else np.asarray(orders, dtype=float)
        self.step = STEP if step is None else float(step)
        if self.engine is not None:
            check_step(self.step, self.engine.cycle_angle)
        self._hints = (speed_hint, speeds_hint)
        self._memo: dict[Any, Any] = {}

    def __repr__(self) -> str:
        what = self.engine.name if self.engine is not None else self._need_model().name
        speed = f", {self._speed * RPM:.6g} rpm" if self._speed is not None else ""
        return f"Analysis({what!r}{speed}, {len(self._memo)} analyses computed)"

    def computed(self) -> list[str]:
        """The names of the analyses computed so far.

        Returns
        -------
        list of str
            One name each time an analysis was computed (a name repeats for each set of
            options).
        """
        return [k[0] if isinstance(k, tuple) else k for k in self._memo]

    def _cached(self, key: Hashable, compute: Callable[[], _T]) -> _T:
        if key not in self._memo:
            self._memo[key] = compute()
        return self._memo[key]

    # ---- what the session analyses ----------------------------------------------------------
    def _need_engine(self, what: str) -> Engine:
        if self.engine is None:
            raise InputError(f"{what} needs an engine (a torsional model alone has no cylinders)")
        return self.engine

    def _need_masses(self, what: str) -> Engine:
        engine = self._need_engine(what)
        if engine.masses is None:
            raise InputError(
                f"the engine has no [masses]: {what} needs the reciprocating and rotating masses "
                "(give reciprocating and rotating, or the components)",
                file=engine.source,
            )
        return engine

    def _need_model(self) -> TorsionModel:
        if self.model is None:
            source = self.engine.source if self.engine is not None else None
            raise InputError(
                f"the engine has no [torsion] section ({ref('torsion-file')})", file=source
            )
        return self.model

    @property
    def speed(self) -> float:
        """The operating speed (rad/s): given, else the engine's [operating] speed, else the
        torsional model's rated speed."""
        if self._speed is not None:
            return self._speed
        if self.engine is not None and self.engine.speed is not None:
            return self.engine.speed
        operating = getattr(self.model, "operating", None) if self.model is not None else None
        if operating is not None and operating.rated is not None:
            return operating.rated
        source = (
            self.engine.source if self.engine is not None else getattr(self.model, "source", None)
        )
        raise InputError(
            f"no speed: give {self._hints[0]} or [operating] speed in the engine file", file=source
        )

    @property
    def speed_range(self) -> tuple[float, float]:
        """(low, high) of the torsional sweeps (rad/s): the given speeds' ends, else the
        model's operating range."""
        if self._speeds is not None:
            return float(self._speeds[0]), float(self._speeds[-1])
        model = self._need_model()
        if model.operating is None:
            raise InputError(
                f"no speed range: give {self._hints[1]} or [operating] "
                "speed_range in the torsional model",
                file=model.source,
                key="speeds",
            )
        operating: Any = model.operating  # an OperatingRange
        return operating.low, operating.high

    @property
    def speeds(self) -> np.ndarray:
        """Speeds of the torsional sweeps (rad/s): given, else the operating range every
        :data:`SPEED_STEP`."""
        if self._speeds is not None:
            return self._speeds
        low, high = self.speed_range
        return self._cached("speeds", lambda: speed_grid(low, high, SPEED_STEP))

    @property
    def cycle(self) -> str:
        """``"four-stroke"`` or ``"two-stroke"``: the engine's, else the model's excitation."""
        if self.engine is not None:
            return self.engine.cycle
        spec = getattr(self.model, "excitation", None)
        return spec.cycle if spec is not None else "four-stroke"

    @property
    def orders(self) -> np.ndarray:
        """Excitation orders of the torsional analyses: given, else the fundamental order to
        :data:`MAX_ORDER`, with the orders of the torsional model's excitation sources (a
        propeller's blade orders, a machine's harmonics) where it has any
        (:func:`crankdyn.torsion.sources.default_orders`). Given orders must be harmonics of
        the cycle or orders of the model's sources."""
        model = self.model
        if model is None or not getattr(model, "sources", ()):
            return self.engine_orders
        from crankdyn.torsion.sources import check_model_orders, default_orders

        def compute():
            ex = self.excitation()
            if self._orders is not None:
                return check_model_orders(model, ex, self._orders)
            return default_orders(model, self.cycle, engine=ex.cylinder_count > 0, last=MAX_ORDER)

        return self._cached("orders", compute)

    @property
    def engine_orders(self) -> np.ndarray:
        """The orders of the engine's cylinder torque alone (harmonics of the cycle): given,
        else the fundamental order to :data:`MAX_ORDER`."""
        from crankdyn.torsion.excitation import check_orders, fundamental_order, order_grid

        if self._orders is not None:
            return check_orders(self._orders, self.cycle)
        base = fundamental_order(self.cycle)
        return order_grid(base, MAX_ORDER, base, self.cycle)

    def cycle_angles(self, step: float | None = None) -> NDArray[np.float64]:
        """Crankshaft angles over one working cycle, 0..cycle inclusive.

        Parameters
        ----------
        step : float or None
            The step (rad), which must divide the cycle; default the session's.

        Returns
        -------
        numpy.ndarray
            The angles (rad).

        Raises
        ------
        InputError
            Without an engine, or if the step does not divide the cycle.
        """
        engine = self._need_engine("a cycle grid")
        h = self.step if step is None else float(step)
        count = check_step(h, engine.cycle_angle)
        return np.linspace(0.0, engine.cycle_angle, count + 1)

    # ---- one cylinder's mechanism ----------------------------------------------------------
    def _rows(
        self, step: float | None, key: Hashable, full: _R, compute_rows: Callable[[], _R]
    ) -> _R:
        """``full`` (on the session's grid) or, with a display ``step`` (rad), the rows every
        ``step`` with the summary of ``full``."""
        if step is None or abs(step - self.step) <= 1e-12 * self.step:
            return full
        return self._cached((key, "rows", float(step)), lambda: _with_summary(compute_rows(), full))

    def kinematics(
        self, *, method: str = "exact", order: int = SERIES_ORDER, step: float | None = None
    ) -> KinematicsResult:
        """Piston and rod kinematics over one revolution with the exact extrema
        (:func:`crankdyn.crank.kinematics.piston_kinematics`).

        Parameters
        ----------
        method : str
            ``"exact"`` (default), ``"approx"`` or ``"series"`` (the lambda series;
            :data:`crankdyn.crank.kinematics.METHODS`).
        order : int
            Order of the lambda series; default :data:`SERIES_ORDER`.
        step : float or None
            Crank-angle step of the rows (rad); default the session's. The summary is always
            that of the session's grid.

        Returns
        -------
        crankdyn.crank.kinematics.KinematicsResult
            Displacement (m), velocity (m/s), acceleration (m/s^2) and the rod's angles.
        """
        from crankdyn.crank.kinematics import piston_kinematics

        engine = self._need_engine("the kinematics")

        def compute(h: float, summary: KinematicsSummary | None = None) -> KinematicsResult:
            check_step(h, 2.0 * math.pi)
            return piston_kinematics(
                engine.geometry,
                self.speed,
                step=h,
                method=method,
                order=order,
                fuel=engine.fuel,
                summary=summary,
            )

        full = self._cached(("kinematics", method, order), lambda: compute(self.step))
        return self._rows(  # the rows carry the full grid's summary: not computed again
            step,
            ("kinematics", method, order),
            full,
            lambda: compute(cast(float, step), full.summary),
        )

    @property
    def pressure(self) -> PressureResult:
        """The cylinder pressure over the cycle with the indicated work, IMEP and peak pressure
        (the engine's trace, or the synthetic Wiebe model)."""
        return self.pressure_rows()

    def pressure_rows(self, step: float | None = None) -> PressureResult:
        """:attr:`pressure` with its rows every ``step``.

        Parameters
        ----------
        step : float or None
            Crank-angle step of the rows (rad); default the session's.

        Returns
        -------
        crankdyn.crank.indicated.PressureResult
            Pressure (Pa) over the cycle, indicated work (J), IMEP and peak pressure (Pa).
        """
        from crankdyn.crank.indicated import pressure_analysis
        from crankdyn.crank.pressure_model import default_pressure

        engine = self._need_engine("the cylinder pressure")
        trace = self._cached("trace", lambda: default_pressure(engine))

        def compute(h: float) -> PressureResult:
            check_step(h, engine.cycle_angle)
            return pressure_analysis(
                trace, engine.geometry, h, fuel=engine.fuel, aspiration=engine.aspiration
            )

        full = self._cached("pressure", lambda: compute(self.step))
        return self._rows(step, "pressure", full, lambda: compute(cast(float, step)))

    # ---- the engine: forces, torque, balance, flywheel ------------------------------------
    def _train(self) -> CrankTrain:
        from crankdyn.engine.forces import crank_train

        engine = self._need_masses("the forces")
        return self._cached("train", lambda: crank_train(engine, self.speed, self.cycle_angles()))

    def forces(self, cylinder: int = 1, *, step: float | None = None) -> ForcesResult:
        """Forces of one cylinder over the working cycle
        (:func:`crankdyn.engine.forces.engine_forces`).

        Parameters
        ----------
        cylinder : int
            The cylinder (1-based); default 1.
        step : float or None
            Crank-angle step of the rows (rad); default the session's. The summary is always
            that of the session's grid.

        Returns
        -------
        crankdyn.engine.forces.ForcesResult
            Gas, inertia, rod, side and crank forces (N).
        """
        from crankdyn.engine.forces import engine_forces

        engine = self._need_masses("the forces")

        def compute(h: float) -> ForcesResult:
            return engine_forces(engine, self.speed, cylinder=cylinder, step=h)

        full = self._cached(
            ("forces", cylinder),
            lambda: engine_forces(
                engine, self.speed, cylinder=cylinder, step=self.step, train=self._train()
            ),
        )
        return self._rows(step, ("forces", cylinder), full, lambda: compute(cast(float, step)))

    def bearings(self, *, step: float | None = None) -> BearingsResult:
        """Crank-pin and main-bearing loads over the cycle
        (:func:`crankdyn.engine.bearings.engine_bearings`).

        Parameters
        ----------
        step : float or None
            Crank-angle step of the rows (rad); default the session's.

        Returns
        -------
        crankdyn.engine.bearings.BearingsResult
            The loads (N).
        """
        from crankdyn.engine.bearings import engine_bearings

        engine = self._need_masses("the bearing loads")
        full = self._cached(
            "bearings",
            lambda: engine_bearings(engine, self.speed, step=self.step, train=self._train()),
        )
        return self._rows(
            step,
            "bearings",
            full,
            lambda: engine_bearings(engine, self.speed, step=cast(float, step)),
        )

    @property
    def torque(self) -> TorqueResult:
        """Cylinder, total, journal and crank-pin torques with mean torque and power
        (:func:`crankdyn.engine.torque.engine_torque`)."""
        return self.torque_rows()

    def torque_rows(
        self, step: float | None = None, *, mechanical_efficiency: float | None = None
    ) -> TorqueResult:
        """:attr:`torque` with rows every ``step`` and/or another mechanical efficiency.

        Parameters
        ----------
        step : float or None
            Crank-angle step of the rows (rad); default the session's.
        mechanical_efficiency : float or None
            Mechanical efficiency (dimensionless, 0..1); default the engine's.

        Returns
        -------
        crankdyn.engine.torque.TorqueResult
            Torques (N m), mean torque (N m) and power (W).
        """
        from crankdyn.engine.torque import engine_torque

        engine = self._need_masses("the torque")
        full = self._cached(
            ("torque", mechanical_efficiency),
            lambda: engine_torque(
                engine,
                self.speed,
                step=self.step,
                mechanical_efficiency=mechanical_efficiency,
                train=self._train(),
            ),
        )
        return self._rows(
            step,
            ("torque", mechanical_efficiency),
            full,
            lambda: engine_torque(
                engine,
                self.speed,
                step=cast(float, step),
                mechanical_efficiency=mechanical_efficiency,
            ),
        )

    @property
    def firing(self) -> FiringCandidate:
        """The engine's own crank arrangement and firing order with its criteria
        (:func:`crankdyn.engine.firing_search.arrangement`)."""
        from crankdyn.engine.firing_search import arrangement

        engine = self._need_engine("the firing order")
        return self._cached("firing", lambda: arrangement(engine.cylinders))

    def firing_orders(
        self,
        *,
        any_crankshaft: bool = False,
        include_uneven: bool | None = None,
        mode_shape: ArrayLike | None = None,
        orders: Sequence[float] | None = None,
        exhaust_groups: Sequence[Sequence[int]] | None = None,
        priority: Sequence[str] | None = None,
        top: int | None = None,
    ) -> FiringOrderRanking:
        """The firing orders the crankshaft allows (or any crankshaft of the layout), ranked
        (:func:`crankdyn.engine.firing_search.firing_order_search`).

        Parameters
        ----------
        any_crankshaft : bool
            Search every crankshaft of the layout, not only the engine's; default False.
        include_uneven : bool or None
            Include unevenly firing orders; default the search's.
        mode_shape : array_like or None
            The first torsional mode's relative amplitudes at the cylinders (dimensionless);
            default that of the engine's [torsion] model when it has one.
        orders : sequence of float or None
            The torsional orders (per revolution) of the criterion; default the search's.
        exhaust_groups : sequence of sequence of int or None
            Cylinders (1-based) sharing an exhaust manifold.
        priority : sequence of str or None
            The criteria in order of importance; default the search's.
        top : int or None
            Keep the best this many; default the search's.

        Returns
        -------
        crankdyn.engine.firing_search.FiringOrderRanking
            The ranked firing orders with their criteria.
        """
        from crankdyn.engine.firing_search import firing_order_search, first_mode_shape

        engine = self._need_engine("the firing orders")
        torsion = engine.torsion
        if mode_shape is None and torsion is not None:
            mode_shape = self._cached(
                "first_mode_shape",
                lambda: first_mode_shape(torsion, engine.cylinders.count),
            )
        key = (
            "firing_orders",
            any_crankshaft,
            include_uneven,
            None if mode_shape is None else tuple(np.asarray(mode_shape, dtype=float)),
            None if orders is None else tuple(orders),
            None if exhaust_groups is None else tuple(map(tuple, exhaust_groups)),
            None if priority is None else tuple(priority),
            top,
        )
        return self._cached(
            key,
            lambda: firing_order_search(
                engine.cylinders,
                search="any-crankshaft" if any_crankshaft else "crankshaft",
                include_uneven=include_uneven,
                mode_shape=mode_shape,
                torsion_orders=orders,
                exhaust_groups=exhaust_groups,
                priority=priority,
                top=top,
                name=engine.name,
            ),
        )

    def balance(
        self,
        *,
        orders: Sequence[int] | None = None,
        method: str = "exact",
        inputs: BalanceInputs | None = None,
        overturning: bool = True,
    ) -> BalanceResult:
        """Free forces and moments by order, counterweights and the overturning moment
        (:func:`crankdyn.engine.balance.engine_balance`).

        Parameters
        ----------
        orders : sequence of int or None
            The orders (per revolution); default the balance's.
        method : str
            ``"exact"`` (default) or ``"approx"`` (:data:`crankdyn.engine.balance.BALANCE_METHODS`).
        inputs : crankdyn.engine.model.BalanceInputs or None
            Override the engine's [balance].
        overturning : bool
            Include the overturning moment (from :attr:`torque`); default True.

        Returns
        -------
        crankdyn.engine.balance.BalanceResult
            Free forces (N) and moments (N m) by order, counterweights, overturning moment
            (N m).
        """
        from crankdyn.engine.balance import engine_balance

        engine = self._need_masses("the balance")
        key = ("balance", None if orders is None else tuple(orders), method, inputs, overturning)
        return self._cached(
            key,
            lambda: engine_balance(
                engine,
                self.speed,
                orders=orders,
                method=method,
                inputs=inputs,
                torque=self.torque if overturning else None,
            ),
        )

    def flywheel(
        self,
        *,
        delta: float | None = None,
        inertia: float | None = None,
        step: float | None = None,
    ) -> FlywheelResult:
        """Speed fluctuation and the flywheel (:func:`crankdyn.engine.flywheel.engine_flywheel`)
        on the session's torque curve.

        Parameters
        ----------
        delta : float or None
            Target degree of cyclic irregularity (dimensionless).
        inertia : float or None
            Or the flywheel's moment of inertia (kg m^2); neither: the engine's [flywheel],
            else the target :data:`DELTA`.
        step : float or None
            Crank-angle step of the curves' rows (rad, interpolated on the analysis grid);
            default the session's. Every figure is that of the full-resolution analysis.

        Returns
        -------
        crankdyn.engine.flywheel.FlywheelResult
            Excess work (J), speed fluctuation and the flywheel's inertia (kg m^2).
        """
        from crankdyn.engine.flywheel import engine_flywheel
        from crankdyn.engine.model import FlywheelInputs

        engine = self._need_masses("the flywheel")
        inputs = engine.flywheel or FlywheelInputs()
        if delta is None and inertia is None and inputs.delta is None and inputs.inertia is None:
            delta = DELTA
        full = self._cached(
            ("flywheel", delta, inertia),
            lambda: engine_flywheel(
                engine, self.speed, delta=delta, inertia=inertia, inputs=inputs, torque=self.torque
            ),
        )
        if step is None or abs(step - self.step) <= 1e-12 * self.step:
            return full
        # rows of the curves at the display step, interpolated on the analysis grid (exact at
        # its points); every figure stays that of the full-resolution analysis
        count = check_step(step, engine.cycle_angle)
        rows = np.linspace(0.0, engine.cycle_angle, count + 1)[:-1]
        period = engine.cycle_angle
        grid = np.append(full.crank_angle, full.crank_angle[0] + period)

        def at(values: ArrayLike) -> NDArray[np.float64]:
            values = np.asarray(values, dtype=float)
            return freeze(np.interp(rows, grid, np.append(values, values[0])))

        return replace(
            full,
            crank_angle=freeze(rows),
            torque=at(full.torque),
            excess_work_curve=at(full.excess_work_curve),
            crank_speed=at(full.crank_speed),
        )

    def flywheel_default_delta(self) -> bool:
        """Whether :meth:`flywheel` without options uses the default target :data:`DELTA`.

        Returns
        -------
        bool
            True when the engine file gives no [flywheel] delta or inertia.
        """
        engine = self._need_engine("the flywheel")
        inputs = engine.flywheel
        return inputs is None or (inputs.delta is None and inputs.inertia is None)

    # ---- torsional vibration -----------------------------------------------------------------
    @property
    def modes(self) -> ModalResult:
        """Natural frequencies, mode shapes and nodes of the torsional model
        (:func:`crankdyn.torsion.modal.natural_modes`, the structured eigen solver)."""
        return self.modes_by()

    def modes_by(self, solver: str = "eigen", count: int | None = None) -> ModalResult:
        """:attr:`modes` by another solver, or the lowest modes only.

        Parameters
        ----------
        solver : str
            ``"eigen"`` (default), ``"holzer"``, ``"transfer"`` or ``"closed-form"``.
        count : int or None
            The lowest ``count`` modes only (the whole result when the model has no more);
            None for every mode.

        Returns
        -------
        crankdyn.torsion.modal.ModalResult
            Natural frequencies (rad/s), mode shapes and nodes.
        """
        from crankdyn.torsion.modal import natural_modes

        model = self._need_model()
        if count is not None and count >= model.dof_inertia.size:
            count = None
        return self._cached(("modes", solver, count), lambda: natural_modes(model, solver, count))

    def damped_modes(self, *, modal_damping: ArrayLike | None = None) -> DampedModalResult:
        """Damped (complex) modes, numbered as the undamped modes (elastic from 1)
        (:func:`crankdyn.torsion.damped.damped_modes`).

        Parameters
        ----------
        modal_damping : float, array_like or None
            Damping ratios (dimensionless) of the elastic modes added to the model's own
            damping: one for all, or one per mode; None for none.

        Returns
        -------
        crankdyn.torsion.damped.DampedModalResult
            Damped frequencies (rad/s), damping ratios, logarithmic decrements and complex
            mode shapes.
        """
        from crankdyn.torsion.damped import damped_modes

        model = self._need_model()
        key = (
            "damped_modes",
            None if modal_damping is None else tuple(np.atleast_1d(modal_damping)),
        )
        return self._cached(key, lambda: damped_modes(model, modal_damping=modal_damping))

    def holzer(self, frequency: float) -> HolzerTable:
        """Holzer's table at a trial frequency (:func:`crankdyn.torsion.holzer.holzer_table`).

        Parameters
        ----------
        frequency : float
            The trial frequency (rad/s).

        Returns
        -------
        crankdyn.torsion.holzer.HolzerTable
            The table and its residual torque.
        """
        from crankdyn.torsion.holzer import holzer_table

        return holzer_table(self._need_model(), frequency)

    def residual_curve(self, max_frequency: float | None = None) -> ResidualCurve:
        """Holzer's residual torque against frequency
        (:func:`crankdyn.torsion.holzer.residual_curve`).

        Parameters
        ----------
        max_frequency : float or None
            The highest frequency (rad/s); default the curve's.

        Returns
        -------
        crankdyn.torsion.holzer.ResidualCurve
            Residual torque against frequency (rad/s).
        """
        from crankdyn.torsion.holzer import residual_curve

        return residual_curve(self._need_model(), max_frequency)

    def excitation(self, *, misfire: Sequence[int] = (), torque: float | None = None) -> Excitation:
        """The excitation of the torsional model: the engine's cylinder torques, or a uniform
        torque per order, with the model's excitation sources (a propeller, an electric
        machine, further engines); a shaft line without cylinders: its sources alone
        (:func:`crankdyn.torsion.excitation.excitation_for`).

        Parameters
        ----------
        misfire : sequence of int
            Cylinders (1-based) motored instead of fired; default none.
        torque : float or None
            A uniform torque per order (N m) instead of the engine's cylinder torques.

        Returns
        -------
        UniformExcitation or EngineExcitation
            The excitation.

        Raises
        ------
        InputError
            Without an excitation point, or a uniform torque without cylinder masses.
        """
        from crankdyn.torsion.excitation import EngineExcitation, excitation_for

        key = ("excitation", tuple(misfire), torque)
        model = self.model
        if model is not None and not model.cylinder_dofs and model.sources:
            return self._cached(
                key, lambda: excitation_for(model, self.engine, misfire=misfire, torque=torque)
            )
        if model is not None and self.engine is None and not model.cylinder_dofs:
            excitation_for(model)  # raises: the model has no excitation point
        if model is None or not model.cylinder_dofs:
            engine = self._need_engine("the excitation")
            if torque is not None:
                raise InputError(
                    "a uniform torque needs a torsional model with cylinder masses", key="torque"
                )
            spec = model.excitation if model is not None else None
            return self._cached(key, lambda: EngineExcitation(engine, spec, tuple(misfire)))
        return self._cached(
            key, lambda: excitation_for(model, self.engine, misfire=misfire, torque=torque)
        )

    def harmonics(
        self, *, orders: ArrayLike | None = None, misfire: Sequence[int] = ()
    ) -> HarmonicResult:
        """Harmonic analysis of the cylinder torque at the session's speed
        (:func:`crankdyn.torsion.excitation.harmonic_analysis`).

        Parameters
        ----------
        orders : array_like or None
            The orders (per revolution); default the session's.
        misfire : sequence of int
            Cylinders (1-based) motored instead of fired; default none.

        Returns
        -------
        crankdyn.torsion.excitation.HarmonicResult
            Per order the gas, inertia and total amplitude (N m), the phase-vector sums (major
            orders) and, with a torsional model, the relative amplitude sums.
        """
        from crankdyn.torsion.excitation import harmonic_analysis

        ex = self.excitation(misfire=misfire)
        q = self.engine_orders if orders is None else orders
        modes = model = None
        if self.model is not None and self.model.cylinder_dofs:
            modes, model = self.modes, self.model
        key = ("harmonics", tuple(np.asarray(q, dtype=float)), tuple(misfire))
        return self._cached(key, lambda: harmonic_analysis(ex, self.speed, q, modes, model))

    def response(
        self,
        *,
        dampers: tuple[Damper, ...] | None = None,
        misfire: Sequence[int] = (),
        torque: float | None = None,
    ) -> ResponseResult:
        """Steady-state forced response over the session's speeds and orders
        (:func:`crankdyn.torsion.response.forced_response`), resolved: the critical speeds are
        added to the grid and every resonance refined until each peak is resolved (the
        result's ``added_speeds`` and ``added_reasons`` say where and why).

        Parameters
        ----------
        dampers : tuple of crankdyn.torsion.dampers.Damper or None
            None: the model's own; ``()``: none; or these dampers.
        misfire : sequence of int
            Cylinders (1-based) motored instead of fired; default none.
        torque : float or None
            A uniform torque per order (N m) instead of the engine's cylinder torques.

        Returns
        -------
        crankdyn.torsion.response.ResponseResult
            Amplitudes (rad), shaft torques (N m) and stresses (Pa) per speed and order, and
            synthesised.
        """
        from crankdyn.torsion.response import forced_response

        model = self._need_model()
        ex = self.excitation(misfire=misfire, torque=torque)
        key = ("response", dampers, tuple(misfire), torque)
        return self._cached(
            key, lambda: forced_response(model, ex, self.speeds, self.orders, dampers=dampers)
        )

    def response_at(
        self,
        speeds: ArrayLike,
        orders: ArrayLike | None = None,
        *,
        dampers: tuple[Damper, ...] | None = None,
    ) -> ResponseResult:
        """The forced response at exactly ``speeds`` (no speed added) and/or other orders than
        the session's sweep (e.g. at the speed of a measurement), with the session's excitation.

        Parameters
        ----------
        speeds : array_like
            The speeds (rad/s).
        orders : array_like or None
            The orders (per revolution); default the session's.
        dampers : tuple of crankdyn.torsion.dampers.Damper or None
            As for :meth:`response`.

        Returns
        -------
        crankdyn.torsion.response.ResponseResult
            The response.
        """
        from crankdyn.torsion.response import forced_response

        model = self._need_model()
        s = np.atleast_1d(np.asarray(speeds, dtype=float))
        q = self.orders if orders is None else np.asarray(orders, dtype=float)
        key = ("response_at", tuple(s), tuple(q), dampers)
        return self._cached(
            key,
            lambda: forced_response(model, self.excitation(), s, q, dampers=dampers, resolve=False),
        )

    def measurement(
        self, measured: OrderSpectrum | OrderTracking, at: str
    ) -> OrderSpectrum | OrderTracking:
        """A measured order analysis held against the torsional model, with the session's
        excitation (:func:`crankdyn.measure.compare.compare_with_model`).

        Parameters
        ----------
        measured : OrderSpectrum or OrderTracking
            The measured orders (:func:`crankdyn.measure.orders.order_analysis`).
        at : str
            The mass that carries the measured wheel.

        Returns
        -------
        OrderSpectrum or OrderTracking
            ``measured`` with the comparison attached: the model's forced response at exactly
            the measured speeds and orders (rad), the resonance peaks and the identified damping.
        """
        model = self._need_model()
        excitation = self.excitation()
        key = ("measurement", id(measured), at)
        # the measured result is kept with its comparison, so its id is not reused
        return self._cached(key, lambda: (measured, measured.with_model(model, excitation, at)))[1]

    def tvc(self, *, spec: TvcSpec | None = None, passage: bool = True) -> TvcResult:
        """The torsional vibration calculation of the installation (:func:`crankdyn.tvc.tvc`):
        every running condition (normal, each misfire, damper out of order) against every
        component's limit, the barred speed ranges and their passage, with the session's
        orders.

        Parameters
        ----------
        spec
            The TVC settings; None: the model's ``[tvc]`` (or the defaults).
        passage
            Whether to run the time-domain passage through the barred ranges.

        Returns
        -------
        crankdyn.tvc.TvcResult
            The verdict rows, barred speed ranges (rad/s), passages, the conditions with their
            responses, the modes and the Campbell diagram.
        """
        from crankdyn.tvc import tvc

        model = self._need_model()
        return self._cached(
            ("tvc", repr(spec), passage),
            lambda: tvc(model, self.engine, spec, passage=passage, orders=self.orders),
        )

    @property
    def rule_check(self) -> Result | None:
        """The rule check of the forced response (IACS UR M68), or None without [rules]."""
        return self.response().rule_check

    def campbell(self) -> CampbellResult:
        """Critical speeds in the speed range with the major orders marked (undetermined
        without firing angles), what excites each order, and the Campbell diagram's data
        (:func:`crankdyn.torsion.campbell.campbell`).

        Returns
        -------
        crankdyn.torsion.campbell.CampbellResult
            The critical speeds (rad/s) and the diagram's lines.
        """
        from crankdyn.torsion.campbell import campbell

        model = self._need_model()
        excited = bool(model.cylinder_dofs) or bool(model.sources)
        ex = self.excitation() if excited else None
        return self._cached(
            "campbell",
            lambda: campbell(model, self.orders, self.speed_range, excitation=ex, cycle=self.cycle),
        )

    def relative_angle(
        self,
        a: str | None = None,
        b: str | None = None,
        response: ResponseResult | None = None,
    ) -> RelativeAngle:
        """The relative angle between two masses over the sweep, its peaks resolved as the
        response's (:meth:`crankdyn.torsion.response.ResponseResult.relative_angle`).

        Parameters
        ----------
        a, b : str or None
            The masses; default the first and the last mass of the model.
        response : crankdyn.torsion.response.ResponseResult or None
            The response; default :meth:`response`.

        Returns
        -------
        crankdyn.torsion.response.RelativeAngle
            The relative angle (rad) per speed and order, and synthesised.
        """
        names = self._need_model().mass_names
        pair = (a or names[0], b or names[-1])
        result = self.response() if response is None else response
        key = ("relative_angle", pair, id(result))
        # the response is kept with its relative angle, so its id is not reused
        return self._cached(key, lambda: (result, result.relative_angle(*pair)))[1]

    def model_shafts(self, response: ResponseResult | None = None) -> list[int]:
        """Indices of the model's own shafts in a response.

        Parameters
        ----------
        response : crankdyn.torsion.response.ResponseResult or None
            The response (its damper couplings follow the model's shafts).

        Returns
        -------
        list of int
            0 .. the model's shafts - 1.
        """
        return list(range(len(self._need_model().shafts)))

    def most_stressed_shaft(self, response: ResponseResult | None = None) -> tuple[str, str]:
        """The shaft with the largest synthesised shear stress over the resolved sweep (among
        those with diameters; :meth:`~crankdyn.torsion.response.ResponseResult.peak`); the
        shaft a stress plot shows by default.

        Parameters
        ----------
        response : crankdyn.torsion.response.ResponseResult or None
            The response; default :meth:`response`.

        Returns
        -------
        (str, str)
            The shaft's two masses.

        Raises
        ------
        InputError
            If no shaft has diameters.
        """
        result = self.response() if response is None else response
        if result.section_modulus is None or not np.any(np.isfinite(result.section_modulus)):
            raise InputError(
                "no shaft of the torsional model has diameters (outer_diameter): no stress",
                key="stress",
            )
        shaft = result.shafts[
            result.shaft_index(_shaft_of(result.peak("synthesized_shaft_stress")))
        ]
        return cast("tuple[str, str]", tuple(shaft))

    def most_loaded_shaft(self, response: ResponseResult | None = None) -> tuple[str, str]:
        """The shaft with the largest synthesised vibratory torque over the resolved sweep
        (:meth:`~crankdyn.torsion.response.ResponseResult.peak`); the shaft a torque plot
        shows by default.

        Parameters
        ----------
        response : crankdyn.torsion.response.ResponseResult or None
            The response; default :meth:`response`.

        Returns
        -------
        (str, str)
            The shaft's two masses.
        """
        result = self.response() if response is None else response
        shaft = result.shafts[
            result.shaft_index(_shaft_of(result.peak("synthesized_shaft_torque")))
        ]
        return cast("tuple[str, str]", tuple(shaft))

    def plot_response(
        self,
        quantity: str = "torque",
        item: Any = None,
        response: ResponseResult | None = None,
        **kw: Any,
    ) -> Figure:
        """The response against speed (per order and synthesised) with the command line's
        defaults.

        Parameters
        ----------
        quantity : str
            ``"torque"`` (default), ``"stress"``, ``"amplitude"`` or ``"relative"``.
        item : str or (str, str) or None
            The mass, the shaft (its two masses) or the pair of masses; default the most
            loaded shaft for ``"torque"``, the most stressed one (with diameters) for
            ``"stress"``, the first mass for ``"amplitude"``, the first and the last mass for
            ``"relative"``.
        response : crankdyn.torsion.response.ResponseResult or None
            The response; default :meth:`response`.
        **kw
            Passed to the response's ``plot``.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        result = self.response() if response is None else response
        if item is None:
            if quantity == "torque":
                item = self.most_loaded_shaft(result)
            elif quantity == "stress":
                item = self.most_stressed_shaft(result)
            elif quantity == "relative":
                names = self._need_model().mass_names
                item = (names[0], names[-1])
        return result.plot(quantity, item, **kw)

    def peak(
        self,
        quantity: str,
        item: Any = None,
        response: ResponseResult | None = None,
    ) -> tuple[float, float]:
        """The peak of a synthesised response quantity over the resolved sweep
        (:meth:`~crankdyn.torsion.response.ResponseResult.peak`).

        Parameters
        ----------
        quantity : str
            ``"amplitude"`` of mass ``item``, ``"torque"`` or ``"stress"`` of shaft ``item``,
            ``"relative"`` between masses ``item = (a, b)``.
        item : str or (str, str)
            The mass, the shaft (its two masses) or the pair of masses.
        response : crankdyn.torsion.response.ResponseResult or None
            The response; default :meth:`response`.

        Returns
        -------
        value : float
            The peak (rad, N m or Pa).
        speed : float
            Its speed (rad/s).

        Raises
        ------
        InputError
            For an unknown quantity.
        """
        result = self.response() if response is None else response
        if quantity == "relative":
            a, b = item
            found = self.relative_angle(a, b, response=result).peak("synthesized")
        else:
            name = _PEAK_QUANTITIES.get(quantity)
            if name is None:
                raise InputError(
                    "expected amplitude, torque, stress or relative", key="quantity", value=quantity
                )
            found = result.peak(name, item)
        return float(found.value), float(found.speed)

    def damper(self, at: str, mode: int, inertia: float, kind: str = "tuned") -> DamperDesign:
        """The optimum damper (Den Hartog) for one mode
        (:func:`crankdyn.torsion.dampers.design_damper`).

        Parameters
        ----------
        at : str
            The mass it is fitted to.
        mode : int
            The elastic mode it is designed for (1 the first).
        inertia : float
            Its ring's moment of inertia (kg m^2).
        kind : str
            ``"tuned"`` (default) or ``"viscous"`` (untuned).

        Returns
        -------
        crankdyn.torsion.dampers.DamperDesign
            The optimum design.
        """
        from crankdyn.torsion.dampers import design_damper

        model = self._need_model()
        return self._cached(
            ("damper", at, mode, inertia, kind),
            lambda: design_damper(model, at, mode, inertia, kind, modes=None),
        )

    def damper_comparison(self, design: DamperDesign) -> tuple[ResponseResult, ResponseResult]:
        """The responses with and without a designed damper over the session's sweep.

        Parameters
        ----------
        design : crankdyn.torsion.dampers.DamperDesign
            The damper (:meth:`damper`).

        Returns
        -------
        with_damper : crankdyn.torsion.response.ResponseResult
            The response with the damper added to the model's own.
        without : crankdyn.torsion.response.ResponseResult
            The response without any damper.
        """
        model = self._need_model()
        ring = _ring_name(model)
        with_damper = self.response(dampers=(*model.dampers, design.damper(ring)))
        return with_damper, self.response(dampers=())

    def transient(
        self,
        *,
        speed: float | None = None,
        run_up: tuple[float, float] | None = None,
        duration: float | None = None,
        cycles: float | None = None,
    ) -> TransientResult:
        """Time-domain response at a constant speed or in a run-up
        (:func:`crankdyn.torsion.transient.transient_response`).

        Parameters
        ----------
        speed : float or None
            The constant speed (rad/s); default the session's when there is no run-up.
        run_up : (float, float) or None
            Start and end speeds of a run-up (rad/s).
        duration : float or None
            Length of the simulation (s).
        cycles : float or None
            Or its length in working cycles; default 30 unless a duration is given.

        Returns
        -------
        crankdyn.torsion.transient.TransientResult
            Angles (rad) and shaft torques (N m) against time (s).
        """
        from crankdyn.torsion.transient import transient_response

        model = self._need_model()
        if run_up is None and speed is None:
            speed = self.speed
        return transient_response(
            model,
            self.excitation(),
            self.orders,
            speed=speed,
            run_up=run_up,
            duration=duration,
            cycles=None if duration is not None else (cycles or 30.0),
        )


_PEAK_QUANTITIES = {
    "amplitude": "synthesized_amplitude",
    "torque": "synthesized_shaft_torque",
    "stress": "synthesized_shaft_stress",
}
"""The session's names of the synthesised quantities -> :data:`crankdyn.torsion.response.
QUANTITIES`."""


def _shaft_of(peak: Peak) -> str:
    """The shaft a per-shaft peak was found on (``"a - b"``); a per-shaft quantity's peak
    always names it."""
    if peak.item is None:
        raise ValueError(f"the peak of {peak.quantity} names no shaft")
    return peak.item


def _ring_name(model: TorsionModel) -> str:
    name, k = "damper ring", 1
    taken = set(model.mass_names) | {d.name for d in model.dampers}
    while name in taken:
        k += 1
        name = f"damper ring {k}"
    return name
