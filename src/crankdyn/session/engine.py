"""The analyses of an engine's cycle: kinematics, pressure, forces, bearing loads, torque,
firing orders, balance and the flywheel (:class:`EngineAnalyses`, part of
:class:`crankdyn.session.Analysis`)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.crank.geometry import check_step
from crankdyn.crank.kinematics import SERIES_ORDER
from crankdyn.defaults import DELTA
from crankdyn.results import freeze
from crankdyn.session.core import SessionCore

if TYPE_CHECKING:
    from crankdyn.crank.indicated import PressureResult
    from crankdyn.crank.kinematics import KinematicsResult, KinematicsSummary
    from crankdyn.engine.balance import BalanceResult
    from crankdyn.engine.bearings import BearingsResult
    from crankdyn.engine.firing_search import FiringCandidate, FiringOrderRanking
    from crankdyn.engine.flywheel import FlywheelResult
    from crankdyn.engine.forces import CrankTrain, ForcesResult
    from crankdyn.engine.model import BalanceInputs
    from crankdyn.engine.torque import TorqueResult

__all__ = ["EngineAnalyses"]


class EngineAnalyses(SessionCore):
    """The cycle analyses of an engine, each computed once per set of options."""

    # ---- one cylinder's mechanism ----------------------------------------------------------
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
            lambda: compute(cast(float, step), full.extrema),
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
            else the session's target (its ``delta``, default
            :data:`~crankdyn.defaults.DELTA`).
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
            delta = DELTA if self.delta is None else self.delta
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
