"""The torsional analyses: modes (undamped, damped, Holzer), excitation, the forced response,
the TVC, the Campbell diagram, dampers, the time domain and measurements held against the model
(:class:`TorsionAnalyses`, part of :class:`crankdyn.session.Analysis`)."""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from numpy.typing import ArrayLike

from crankdyn.errors import InputError
from crankdyn.session.core import SessionCore, with_parameters
from crankdyn.torsion.model import TorsionModel

if TYPE_CHECKING:
    from crankdyn.measure.orders import OrderSpectrum, OrderTracking
    from crankdyn.torsion.campbell import CampbellResult
    from crankdyn.torsion.damped import DampedModalResult
    from crankdyn.torsion.dampers import Damper, DamperDesign
    from crankdyn.torsion.excitation import Excitation
    from crankdyn.torsion.harmonics import HarmonicResult
    from crankdyn.torsion.holzer import HolzerTable, ResidualCurve
    from crankdyn.torsion.modal import ModalResult
    from crankdyn.torsion.mode_table import ModeTable
    from crankdyn.torsion.response import RelativeAngle, ResponseResult
    from crankdyn.torsion.transient import TransientResult
    from crankdyn.tvc import ConditionResult, TvcResult, TvcSpec

__all__ = ["TorsionAnalyses"]


@with_parameters
class TorsionAnalyses(SessionCore):
    """The torsional analyses of the model, each computed once per set of options."""

    # ---- torsional vibration -----------------------------------------------------------------
    @property
    def orders(self) -> np.ndarray:
        """Excitation orders of the torsional analyses: given, else the fundamental order to
        :attr:`max_order`, with the orders of the torsional model's excitation sources (a
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
            return default_orders(
                model, self.cycle, engine=ex.cylinder_count > 0, last=self.max_order
            )

        return self._cached("orders", compute)

    @property
    def engine_orders(self) -> np.ndarray:
        """The orders of the engine's cylinder torque alone (harmonics of the cycle): given,
        else the fundamental order to :attr:`max_order`."""
        from crankdyn.torsion.orders import check_orders, fundamental_order, order_grid

        if self._orders is not None:
            return check_orders(self._orders, self.cycle)
        base = fundamental_order(self.cycle)
        return order_grid(base, self.max_order, base, self.cycle)

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
        model = self.loaded_model
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
        from crankdyn.torsion.harmonics import harmonic_analysis

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
        (:func:`crankdyn.torsion.sweep.forced_response`), resolved: the critical speeds are
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
        from crankdyn.torsion.sweep import forced_response

        self._need_model()
        model = cast(TorsionModel, self.loaded_model)
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
        from crankdyn.torsion.sweep import forced_response

        self._need_model()
        model = cast(TorsionModel, self.loaded_model)
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
        self._need_model()
        model = cast(TorsionModel, self.loaded_model)
        excitation = self.excitation()
        key = ("measurement", id(measured), at)
        # the measured result is kept with its comparison, so its id is not reused
        return self._cached(key, lambda: (measured, measured.with_model(model, excitation, at)))[1]

    # ---- the verdicts: the installation's checks (crankdyn.tvc), evaluated in one place -------
    @property
    def tvc_spec(self) -> TvcSpec:
        """The settings that shape a verdict: the model's ``[tvc]`` (the rule set, the
        tachometer tolerance, the speed ranges...), else the defaults; the session's ``rules``
        (``--rules``) replaces the file's rule set."""
        from crankdyn.tvc import TvcSpec

        spec = getattr(self._need_model(), "tvc", None) or TvcSpec()
        if self.rules is not None and self.rules != spec.rules:
            spec = dataclasses.replace(spec, rules=self.rules)
        if self.barred_band is not None:
            spec = dataclasses.replace(spec, barred_band=self.barred_band)
        return spec

    @property
    def loaded_model(self) -> TorsionModel | None:
        """The torsional model as every torsional analysis excites it: with its load law's
        excitation (the propeller law, or full load for a generating set:
        :func:`crankdyn.tvc.analysis.tvc_model`), so that ``torsion response`` and ``tvc`` judge
        the same response; the model itself where it has no rated speed."""
        model = self.model
        if model is None:
            return None

        def compute() -> TorsionModel:
            from crankdyn.tvc.analysis import tvc_model

            try:
                return tvc_model(model, self.engine, self.tvc_spec)[0]
            except InputError:  # no rated speed: no load law to apply
                return model

        return self._cached("loaded_model", compute)

    def tvc(
        self,
        *,
        spec: TvcSpec | None = None,
        passage: bool = True,
        conditions: Sequence[str] | None = None,
        progress: Callable[[str], None] | None = None,
    ) -> TvcResult:
        """The torsional vibration calculation of the installation (:func:`crankdyn.tvc.tvc`):
        every running condition (normal, each misfire, damper out of order, overspeed,
        declutched and idle where a clutch is modelled) and every transient event of its
        ``[tvc]`` against every component's limit, the barred speed ranges and their passage,
        with the session's orders; each condition's response is the session's own where its
        speeds are the session's (:meth:`response`), so its verdicts are :meth:`judged`'s.

        Parameters
        ----------
        spec
            The TVC settings; None: :attr:`tvc_spec` (the model's ``[tvc]`` with the
            session's ``rules``).
        passage
            Whether to run the time-domain passage through the barred ranges.
        conditions
            The kinds of condition (:data:`crankdyn.tvc.spec.CONDITION_KINDS`); None: all.
        progress
            Told each step the calculation begins (:func:`crankdyn.tvc.tvc`), for a progress
            display; not called when the result is the session's cached one.

        Returns
        -------
        crankdyn.tvc.TvcResult
            The verdict rows, barred speed ranges (rad/s), passages, the conditions with their
            responses, the modes and the Campbell diagram.
        """
        from crankdyn.tvc import tvc
        from crankdyn.tvc.spec import CONDITION_KINDS

        model = self._need_model()
        kinds = tuple(CONDITION_KINDS if conditions is None else conditions)
        spec = spec or self.tvc_spec
        return self._cached(
            ("tvc", repr(spec), passage, kinds),
            lambda: tvc(
                model,
                self.engine,
                spec,
                passage=passage,
                orders=self.orders,
                conditions=kinds,
                response_of=self._condition_response,
                progress=progress,
            ),
        )

    def _condition_response(
        self, model: TorsionModel, cond: Any, speeds: ArrayLike, orders: ArrayLike
    ) -> ResponseResult:
        """A TVC condition's response: the session's own (cached) where the speeds and orders
        are the session's, else computed for the condition."""
        from crankdyn.torsion.sweep import forced_response

        same = (
            model is self.loaded_model
            and np.array_equal(np.asarray(speeds), self.speeds)
            and np.array_equal(np.asarray(orders), self.orders)
        )
        if same and cond.kind == "normal":
            return self.response()
        if same and cond.kind == "misfire" and cond.misfire is not None:
            # :meth:`response`'s computation, not kept in the cache: the TVC keeps only the
            # worst cylinder's response (issue 33: one misfire response held, not one per
            # cylinder); the same numbers as ``response(misfire=...)``
            misfired = self.excitation(misfire=(cond.misfire,))
            return forced_response(model, misfired, self.speeds, self.orders, dampers=None)
        if same and cond.kind == "damper-out":
            return self.response(dampers=())
        return forced_response(model, cond.excitation, speeds, orders, dampers=cond.dampers)

    def judged(
        self,
        *,
        dampers: tuple[Damper, ...] | None = None,
        misfire: Sequence[int] = (),
        torque: float | None = None,
    ) -> ConditionResult | None:
        """The forced response (:meth:`response` with the same options) judged by the
        installation's checks (:func:`crankdyn.tvc.checks.model_checks`, evaluated by
        :func:`crankdyn.tvc.evaluate.evaluate_condition`, the TVC's one evaluation): verdict
        rows and barred speed ranges as found and as declared. With default options these are
        exactly the TVC's normal-firing rows.

        Parameters
        ----------
        dampers, misfire, torque
            As for :meth:`response`.

        Returns
        -------
        crankdyn.tvc.ConditionResult or None
            The condition judged; None when the model has no rated speed or no component with
            a limit.
        """
        from crankdyn.tvc.analysis import load_of, rated_speed
        from crankdyn.tvc.checks import model_checks
        from crankdyn.tvc.evaluate import evaluate_condition
        from crankdyn.tvc.installation import installation_verdicts
        from crankdyn.tvc.result import ConditionResult

        self._need_model()
        model = cast(TorsionModel, self.loaded_model)
        r = self.response(dampers=dampers, misfire=misfire, torque=torque)
        try:
            rated = rated_speed(model, self.engine)
        except InputError:
            return None
        spec = self.tvc_spec
        load = load_of(model, spec)
        used = model.dampers if dampers is None else dampers
        checks, _notes = model_checks(model, spec, rated, used, engine=self.engine, load=load)
        if not checks:
            return None
        if torque is not None:
            name, kind = f"uniform torque {torque:g} N·m per order", "uniform"
        elif misfire:
            name = f"misfire cylinder{'s' if len(misfire) > 1 else ''} "
            name += ", ".join(str(c) for c in misfire)
            kind = "misfire"
        elif dampers is not None and tuple(dampers) != tuple(model.dampers):
            name, kind = ("damper out of order" if not dampers else "other dampers"), "damper-out"
        else:
            name, kind = "normal firing", "normal"
        key = ("judged", dampers, tuple(misfire), torque)

        def compute() -> ConditionResult:
            verdicts, barred = evaluate_condition(r, name, checks, spec, rated)
            if kind == "normal":  # as the TVC's normal-firing condition
                verdicts += installation_verdicts(model, spec, rated, engine=self.engine, load=load)
            low, high = self.speed_range
            return ConditionResult(
                name=name,
                kind=kind,
                low=low,
                high=high,
                description="the forced response judged by the installation's checks",
                verdicts=tuple(verdicts),
                barred_ranges=tuple(barred),
                passages=(),
                response=r,
                curves={(c.component, c.quantity): c for c in checks},
            )

        return self._cached(key, compute)

    def mode_table(self) -> ModeTable:
        """The lowest elastic modes' relative amplitudes per mass and nodes, and the relative
        vector sums of the engine's orders with its firing order
        (:func:`crankdyn.torsion.mode_table.excited_mode_table`; Ker Wilson vol. 2, Nestorides
        1958 ch. 7): the tables of a TVC's modes section.

        Returns
        -------
        crankdyn.torsion.mode_table.ModeTable
            The tables (no vector sums where the model has no cylinders or their firing
            angles are unknown).
        """
        from crankdyn.torsion.mode_table import excited_mode_table, mode_table

        model = self._need_model()

        def compute() -> ModeTable:
            if not model.cylinder_dofs:
                return mode_table(self.modes, model, self.orders)
            return excited_mode_table(self.modes, model, self.excitation(), self.orders)

        return self._cached("mode_table", compute)

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

        self._need_model()
        model = cast(TorsionModel, self.loaded_model)
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
        default = self.relative or (names[0], names[-1])
        pair = (a or default[0], b or default[1])
        result = self.response() if response is None else response
        key = ("relative_angle", pair, id(result))

        def compute() -> tuple[ResponseResult, RelativeAngle]:
            try:
                return result, result.relative_angle(*pair)
            except InputError as exc:
                if a is None and b is None and self.relative is not None:  # the setting's
                    raise InputError(exc.message, key="relative", value=list(pair)) from None
                raise

        # the response is kept with its relative angle, so its id is not reused
        return self._cached(key, compute)[1]

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

        self._need_model()
        model = cast(TorsionModel, self.loaded_model)
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


def _ring_name(model: TorsionModel) -> str:
    name, k = "damper ring", 1
    taken = set(model.mass_names) | {d.name for d in model.dampers}
    while name in taken:
        k += 1
        name = f"damper ring {k}"
    return name
