"""The analysis session's core: the subject, its speeds, orders and crank-angle grid, the
defaults and the cache (:class:`SessionCore`); the analyses themselves are in
:mod:`crankdyn.session.engine` and :mod:`crankdyn.session.torsion`."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Hashable
from typing import Any, TypeVar, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import RPM
from crankdyn.crank.geometry import check_step
from crankdyn.defaults import MAX_ORDER, SPEED_STEP, STEP, speed_grid
from crankdyn.docs import ref
from crankdyn.engine.model import Engine
from crankdyn.errors import InputError
from crankdyn.plausibility import PlausibilityWarning, merge_warnings
from crankdyn.results import Result
from crankdyn.torsion.model import TorsionModel

__all__ = ["SESSION_PARAMETERS", "SessionCore", "with_parameters"]

_T = TypeVar("_T")
_R = TypeVar("_R", bound=Result)


SESSION_PARAMETERS = """
    Parameters
    ----------
    subject : Engine or TorsionModel
        An :class:`~crankdyn.engine.Engine` or a :class:`~crankdyn.torsion.TorsionModel`.
    speed : float or None
        Operating speed (rad/s) of the one-speed analyses; default the engine's [operating]
        speed (a torsional model: its rated speed).
    speeds : array_like or None
        Speeds (rad/s) of the torsional sweeps; default ``speed_range`` every ``speed_step``.
    speed_range : (float, float) or None
        Or the range (rad/s) of the sweeps; default the torsional model's operating range.
    speed_step : float or None
        The step (rad/s) of the sweeps; default :data:`~crankdyn.defaults.SPEED_STEP`.
    orders : array_like or None
        Excitation orders (per revolution) of the torsional analyses; default the cycle's
        fundamental order to ``max_order``, with the orders of the model's sources.
    max_order : float or None
        The highest order of the default orders; default
        :data:`~crankdyn.defaults.MAX_ORDER`.
    step : float or None
        Crank-angle step (rad) of the cycle analyses; default
        :data:`~crankdyn.defaults.STEP`. It must divide the working cycle (the library
        does not round it).
    engine : Engine or None
        With a torsional model as ``subject``: the engine whose cylinders excite it (its
        pressure and masses), if any.
    delta : float or None
        The flywheel's target degree of cyclic irregularity (dimensionless) when the engine
        file gives neither a target nor a flywheel; default
        :data:`~crankdyn.defaults.DELTA`.
    relative : (str, str) or None
        The two masses of the relative angle; default the model's first and last.
    rules : str or None
        The classification society's rule set of the verdicts (a key of
        :data:`crankdyn.tvc.rulesets.RULESETS`); default the model's ``[tvc] rules``, else
        :data:`~crankdyn.defaults.RULES`.
    barred_band : (float, float) or None
        A speed band (rad/s) where no barred range is wanted: the TVC's key figure
        ``barred_width_in_band`` (its settings' ``barred_band``); default none.

    Attributes are the analyses: properties for those without options (``torque``,
    ``modes``...), methods with keyword options for the others (``forces(cylinder=2)``,
    ``flywheel(delta=0.005)``); each is computed once per set of options.

    Raises
    ------
    InputError
        If the subject is neither, the speed or the speeds are not positive, the step does
        not divide the engine's working cycle, or the rule set is unknown.

"""
"""The parameters of every session class (:class:`crankdyn.session.Analysis` and its parts),
documented once."""


class SessionCore:
    """What every analysis of a session shares: the subject, its speeds, orders and crank-angle
    grid, the defaults (:data:`crankdyn.defaults.DEFAULTS`) and the cache (its parameters:
    :data:`SESSION_PARAMETERS`).

    """

    def __init__(
        self,
        subject: Engine | TorsionModel,
        *,
        speed: float | None = None,
        speeds: ArrayLike | None = None,
        speed_range: tuple[float, float] | None = None,
        speed_step: float | None = None,
        orders: ArrayLike | None = None,
        max_order: float | None = None,
        step: float | None = None,
        engine: Engine | None = None,
        delta: float | None = None,
        relative: tuple[str, str] | None = None,
        rules: str | None = None,
        barred_band: tuple[float, float] | None = None,
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
        if speed_range is not None:
            low, high = (float(v) for v in speed_range)
            if not (math.isfinite(low) and math.isfinite(high) and high > low > 0.0):
                raise InputError(
                    "the speed range is empty: its end is not above its start",
                    key="speed_range",
                    value=[low * RPM, high * RPM],
                )
        self._speed_range = speed_range
        self._speed_step = None if speed_step is None else float(speed_step)
        self._orders = None if orders is None else np.asarray(orders, dtype=float)
        self.max_order = MAX_ORDER if max_order is None else float(max_order)
        self.step = STEP if step is None else float(step)
        if self.engine is not None:
            check_step(self.step, self.engine.cycle_angle)
        self.delta = None if delta is None else float(delta)
        self.relative = None if relative is None else (str(relative[0]), str(relative[1]))
        self.barred_band = None if barred_band is None else tuple(barred_band)
        self.rules: str | None = None
        if rules is not None:
            from crankdyn.tvc.rulesets import get

            self.rules = get(rules).key
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

    @property
    def input_warnings(self) -> tuple[PlausibilityWarning, ...]:
        """The input warnings of the subject (the engine's and the torsional model's, each
        once: values of their files outside the plausible range of their role,
        :mod:`crankdyn.io.plausibility`); every result the session computes carries them."""
        engine = self.engine.input_warnings if self.engine is not None else ()
        model = self.model.input_warnings if self.model is not None else ()
        return merge_warnings(engine, model)

    def _cached(self, key: Hashable, compute: Callable[[], _T]) -> _T:
        if key not in self._memo:
            self._memo[key] = self.with_input_warnings(compute())
        return self._memo[key]

    def with_input_warnings(self, value: _T) -> _T:
        """A result (one with a ``warnings`` field) carrying the subject's input warnings
        first, then its own, and so the results it holds (a TVC's conditions, their
        responses, its modes): whatever the inputs' values, a verdict computed from them says
        so (:func:`crankdyn.summary.verdict_text`). Every analysis of the session goes through
        it; a front end that computes from the session's model passes its result here.

        Parameters
        ----------
        value : object
            A result (anything else is returned as it is).

        Returns
        -------
        object
            ``value`` with :attr:`input_warnings` added to its ``warnings``.
        """
        found = self.input_warnings
        if not found:
            return value
        return cast(_T, _carrying(value, found, {}))

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
            "no speed: none was given and the file has no [operating] speed",
            file=source,
            key="speed",
        )

    @property
    def speed_range(self) -> tuple[float, float]:
        """(low, high) of the torsional sweeps (rad/s): the given speeds' ends or range, else
        the model's [tvc] speed range of normal firing, else its operating range."""
        if self._speeds is not None:
            return float(self._speeds[0]), float(self._speeds[-1])
        if self._speed_range is not None:
            return float(self._speed_range[0]), float(self._speed_range[1])
        model = self._need_model()
        spec: Any = getattr(model, "tvc", None)  # a TvcSpec: the line's verdict settings
        if spec is not None and (spec.speed_range is not None or "normal" in spec.ranges):
            return spec.range_of("normal", model)
        if model.operating is None:
            raise InputError(
                "no speed range: none was given and the torsional model has no [operating] "
                "speed_range",
                file=model.source,
                key="speeds",
            )
        operating: Any = model.operating  # an OperatingRange
        return operating.low, operating.high

    @property
    def speeds(self) -> np.ndarray:
        """Speeds of the torsional sweeps (rad/s): given, else :attr:`speed_range` every
        :attr:`speed_step` (:func:`~crankdyn.defaults.speed_grid`)."""
        if self._speeds is not None:
            return self._speeds
        low, high = self.speed_range
        return self._cached("speeds", lambda: speed_grid(low, high, self.speed_step))

    @property
    def speed_step(self) -> float:
        """The step of the torsional sweeps (rad/s): given, else the model's [tvc] step, else
        :data:`~crankdyn.defaults.SPEED_STEP`."""
        if self._speed_step is not None:
            return self._speed_step
        spec: Any = getattr(self.model, "tvc", None) if self.model is not None else None
        return float(spec.step) if spec is not None else SPEED_STEP

    @property
    def cycle(self) -> str:
        """``"four-stroke"`` or ``"two-stroke"``: the engine's, else the model's excitation."""
        if self.engine is not None:
            return self.engine.cycle
        spec = getattr(self.model, "excitation", None)
        return spec.cycle if spec is not None else "four-stroke"

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

    def _rows(
        self, step: float | None, key: Hashable, full: _R, compute_rows: Callable[[], _R]
    ) -> _R:
        """``full`` (on the session's grid) or, with a display ``step`` (rad), the rows every
        ``step`` with the summary of ``full``."""
        if step is None or abs(step - self.step) <= 1e-12 * self.step:
            return full
        return self._cached(
            (key, "rows", float(step)), lambda: compute_rows().with_summary_of(full)
        )


def _carrying(value: Any, found: tuple[PlausibilityWarning, ...], done: dict[int, Any]) -> Any:
    """``value`` with the input warnings ``found`` first in its ``warnings``, and in those of
    the results it holds (a TVC's conditions, their responses, its modes): the same object
    held twice stays one object (``done``, by identity)."""
    if id(value) in done:
        return done[id(value)]
    out = value
    if isinstance(value, tuple) and value and isinstance(value[0], Result):
        out = tuple(_carrying(v, found, done) for v in value)
    elif isinstance(value, Result) and dataclasses.is_dataclass(value):
        names = {f.name for f in dataclasses.fields(value)}
        changes: dict[str, Any] = {}
        for name in names - {"warnings"}:
            held = getattr(value, name)
            if isinstance(held, Result) or (
                isinstance(held, tuple) and held and isinstance(held[0], Result)
            ):
                new = _carrying(held, found, done)
                if new is not held:
                    changes[name] = new
        if "warnings" in names:
            merged = merge_warnings(found, value.warnings)
            if merged != tuple(value.warnings):
                changes["warnings"] = merged
        if changes:
            out = dataclasses.replace(value, **changes)
    done[id(value)] = out
    return out


def with_parameters(klass: type) -> type:
    """``klass`` with the session's parameters (:data:`SESSION_PARAMETERS`) appended to its
    docstring, written once for every session class.

    Parameters
    ----------
    klass : type
        A session class.

    Returns
    -------
    type
        The same class.
    """
    klass.__doc__ = (klass.__doc__ or "").rstrip() + "\n" + SESSION_PARAMETERS
    return klass


with_parameters(SessionCore)
