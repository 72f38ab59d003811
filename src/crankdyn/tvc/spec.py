"""The inputs of a torsional vibration calculation besides the model (domain): which running
conditions, the speed range of each, the load law, the classification society's rule set (the
limits, the barred-range rules and margins, each with its clause: :mod:`crankdyn.tvc.rulesets`),
the tachometer tolerance, the crankshaft's limit, the data of the passage through barred ranges,
the clutch and idle speed of the declutched and idle conditions, and the transient events
(docs/tvc.md)."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import RPM
from crankdyn.crank.geometry import check_positive
from crankdyn.defaults import RULES, SPEED_STEP
from crankdyn.errors import InputError
from crankdyn.tvc.limits import CrankshaftLimit
from crankdyn.tvc.rulesets import get as get_rules
from crankdyn.tvc.rulesets import tachometer_tolerance

if TYPE_CHECKING:
    from crankdyn.torsion.events import Event
    from crankdyn.torsion.model import TorsionModel
    from crankdyn.tvc.rulesets import RuleSet

__all__ = ["CONDITION_KINDS", "DEFAULT_STEP", "LOADS", "PASSAGE_TORQUES", "TvcEvent", "TvcSpec"]

LOADS = ("propeller", "constant-speed")
"""Load laws of a TVC: ``"propeller"`` (mean torque ~ n^2: the model's load curve and
propeller law) or ``"constant-speed"`` (a generating set: full load at every speed of the range,
run up without load)."""

CONDITION_KINDS = ("normal", "misfire", "damper-out", "overspeed", "declutched", "idle")
"""Kinds of running condition: ``"normal"`` firing, ``"misfire"`` (each cylinder not firing in
turn), ``"damper-out"`` (the damper out of order), ``"overspeed"`` (normal firing above the
normal range to the rule's top speed), ``"declutched"`` and ``"idle"`` (where a clutch is
modelled: :mod:`crankdyn.tvc.conditions`); the keys of :attr:`TvcSpec.ranges`."""

PASSAGE_TORQUES = ("curve", "rated")
"""What drives the passage through a barred range where neither ``engine_torque_curve`` nor
``engine_torque`` is given: ``"curve"`` (the default: the engine's torque-speed curve, so none
given means no passage is calculated) or ``"rated"`` (asked for: the load law's torque at n_0,
the rated torque, at every speed)."""

DEFAULT_STEP = SPEED_STEP
"""Speed step of the user grid of every condition's sweep (rad/s, 10 rpm: the analyses' default,
:data:`crankdyn.defaults.SPEED_STEP`); the peaks, barred ranges and verdicts come from the
resolved curves, whatever the step."""


@dataclass(frozen=True)
class TvcEvent:
    """A transient event of the TVC (a ``[[tvc.event]]`` table): the event and how the line
    runs into it (:mod:`crankdyn.tvc.events`).

    Parameters
    ----------
    event : Event
        The event (:mod:`crankdyn.torsion.events`).
    speed : float or None
        The reference speed before the event (rad/s); None: the rated speed n_0 (a clutch, a
        start, a stop have their own speeds).
    duration : float or None
        The run's duration (s); None: the event's own.
    harmonics : bool
        Whether the engine's and the sources' harmonic torques act during the run (default
        True; a clutch engagement runs without them).

    Raises
    ------
    InputError
        Naming ``speed`` or ``duration`` where it is not positive.

    Examples
    --------
    >>> from crankdyn.torsion.events import StepTorque
    >>> TvcEvent(StepTorque("propeller", -1e4), duration=0.5).duration
    0.5
    """

    event: Event
    speed: float | None = None
    duration: float | None = None
    harmonics: bool = True

    def __post_init__(self) -> None:
        for key in ("speed", "duration"):
            if getattr(self, key) is not None:
                check_positive(key, getattr(self, key), f"the event's {key}")

    @property
    def name(self) -> str:
        """The event's name (the verdict rows' condition)."""
        return str(self.event.name)


@dataclass(frozen=True)
class TvcSpec:
    """TVC settings (``[tvc]`` of a model or engine file; every field has a default).

    Parameters
    ----------
    speed_range : tuple of float or None
        (low, high) speeds (rad/s) of every condition; None: the model's operating range.
    ranges : dict or None
        Per-condition speed ranges overriding ``speed_range``: a dict from a condition kind
        (:data:`CONDITION_KINDS`) to (low, high) (rad/s); held as a dict (empty: none).
    step : float
        Speed step of the user grid (rad/s, default :data:`DEFAULT_STEP`, 10 rpm).
    load : str or None
        :data:`LOADS`, or None: ``"propeller"`` when the model has a propeller, else
        ``"constant-speed"``.
    misfire : bool
        Whether each single-cylinder misfire is a condition (default True where the engine's
        pressure is known).
    damper_out : bool
        Whether "damper out of order" is a condition (default True where there is a damper).
    tachometer_tolerance : float or None
        Relative accuracy of the speed indication (dimensionless, 0 <= tolerance < 0.2),
        widening every barred range on both sides; None: the rule set's value where its text
        states one, else :data:`crankdyn.defaults.TACHOMETER_TOLERANCE` (0.02;
        :attr:`tolerance`).
    rules : str
        The classification society's rule set, a key of
        :data:`crankdyn.tvc.rulesets.RULESETS` (default :data:`crankdyn.defaults.RULES`,
        ``"iacs-m68"``): the shaft limits and the caps on sigma_B, the C_K table, the barred-range
        rules and the least range around a critical speed, generating sets, crankshafts, each
        value with its clause (:attr:`ruleset`).
    crankshaft : CrankshaftLimit or None
        The engine builder's crankshaft limit (:class:`CrankshaftLimit`), or None.
    engine_torque : float or None
        Torque (N m, reference shaft) the engine delivers while passing a barred range; None: the
        mean load torque at the rated speed (the torque limit at rated load).
    engine_torque_curve : tuple of array_like or None
        Instead of ``engine_torque``: the engine's torque-speed curve, (speeds (rad/s,
        increasing), torques (N m, > 0)), interpolated linearly and held at its ends; held as
        two float arrays.
    passage_load : str or None
        ``"law"``: the load follows its law while passing; ``"none"``: no load (a generating set
        runs up before it is loaded). Default from ``load``.
    passage_torque : str
        :data:`PASSAGE_TORQUES`: where neither ``engine_torque_curve`` nor ``engine_torque``
        is given, ``"curve"`` (default) calculates no passage (the engine's curve is needed),
        ``"rated"`` passes with the rated torque at every speed.
    overspeed : bool
        Whether "overspeed" is a condition (default True: to the rule's top speed where the
        normal range stops below it).
    overspeed_limit : float or None
        The overspeed condition's top, n/n_0 (dimensionless, 1 < ratio <= 1.5); None: the rule
        set's (IACS UR M68.4: 1.05).
    clutch : tuple of str or None
        The clutch's element, (the engine's half, the other half): two masses of the model;
        None: no clutch (no declutched or idle condition).
    declutched, idle : bool
        Whether declutched and idle running are conditions where a clutch is given (default
        True).
    idle_speed : float or None
        The engine's idle speed (rad/s, reference shaft); None: the lowest speed of the normal
        range.
    events : tuple of TvcEvent
        The transient events (``[[tvc.event]]``).
    source : str or None
        Where these settings come from, for reports.
    barred_band : (float, float) or None
        A speed band (rad/s, low < high) where no barred range is wanted (the design search's
        constraint): the TVC's key figure ``barred_width_in_band``; None: none.

    Raises
    ------
    InputError
        Naming the key (``speed_range``, ``speed_ranges.<kind>``, ``step``, ``load``,
        ``tachometer_tolerance``, ``rules``, ``engine_torque``, ``engine_torque_curve``,
        ``passage_load``, ``passage_torque``, ``overspeed_limit``, ``clutch``, ``idle_speed``)
        and its value where a setting is unknown, not positive, out of range or an empty speed
        range, or where two of ``engine_torque``, ``engine_torque_curve`` and
        ``passage_torque = "rated"`` are given.

    Examples
    --------
    >>> from crankdyn.constants import RPM
    >>> spec = TvcSpec(speed_range=(300 / RPM, 600 / RPM))
    >>> round(spec.step * RPM, 6), spec.tolerance, spec.rules
    (10.0, 0.02, 'iacs-m68')
    >>> TvcSpec(rules="KR").ruleset.title
    'Korean Register (KR)'
    >>> TvcSpec(load="hybrid")
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: load = "hybrid": expected one of propeller, constant-speed
    """

    speed_range: tuple[float, float] | None = None
    # None on input: an empty dict after __post_init__ (the __init__ below tells the type checker)
    ranges: dict[str, tuple[float, float]] = None  # type: ignore[assignment]
    step: float = DEFAULT_STEP
    load: str | None = None
    misfire: bool = True
    damper_out: bool = True
    tachometer_tolerance: float | None = None
    rules: str = RULES
    crankshaft: CrankshaftLimit | None = None
    engine_torque: float | None = None
    engine_torque_curve: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None
    passage_load: str | None = None
    passage_torque: str = "curve"
    overspeed: bool = True
    overspeed_limit: float | None = None
    clutch: tuple[str, str] | None = None
    declutched: bool = True
    idle: bool = True
    idle_speed: float | None = None
    events: tuple[TvcEvent, ...] = ()
    source: str | None = None
    barred_band: tuple[float, float] | None = None

    if TYPE_CHECKING:  # what the constructor accepts; the fields hold the normalised values

        def __init__(
            self,
            speed_range: Sequence[float] | None = None,
            ranges: Mapping[str, Sequence[float]] | None = None,
            step: float = DEFAULT_STEP,
            load: str | None = None,
            misfire: bool = True,
            damper_out: bool = True,
            tachometer_tolerance: float | None = None,
            rules: str = RULES,
            crankshaft: CrankshaftLimit | None = None,
            engine_torque: float | None = None,
            engine_torque_curve: tuple[ArrayLike, ArrayLike] | None = None,
            passage_load: str | None = None,
            passage_torque: str = "curve",
            overspeed: bool = True,
            overspeed_limit: float | None = None,
            clutch: Sequence[str] | None = None,
            declutched: bool = True,
            idle: bool = True,
            idle_speed: float | None = None,
            events: Sequence[TvcEvent] = (),
            source: str | None = None,
            barred_band: Sequence[float] | None = None,
        ) -> None: ...

    def __post_init__(self) -> None:
        if self.speed_range is not None:
            object.__setattr__(self, "speed_range", _range(self.speed_range, "speed_range"))
        if self.barred_band is not None:
            object.__setattr__(self, "barred_band", _range(self.barred_band, "barred_band"))
        ranges = dict(self.ranges or {})
        for kind, pair in ranges.items():
            if kind not in CONDITION_KINDS:
                raise InputError(
                    f"expected one of {', '.join(CONDITION_KINDS)}", key="speed_ranges", value=kind
                )
            ranges[kind] = _range(pair, f"speed_ranges.{kind}")
        object.__setattr__(self, "ranges", ranges)
        object.__setattr__(self, "step", check_positive("step", self.step, "the speed step"))
        if self.load is not None and self.load not in LOADS:
            raise InputError(f"expected one of {', '.join(LOADS)}", key="load", value=self.load)
        if self.tachometer_tolerance is not None:
            tol = float(self.tachometer_tolerance)
            if not (math.isfinite(tol) and 0.0 <= tol < 0.2):
                raise InputError(
                    "the tachometer tolerance is a fraction of the speed, 0 <= tolerance < 0.2",
                    key="tachometer_tolerance",
                    value=self.tachometer_tolerance,
                )
            object.__setattr__(self, "tachometer_tolerance", tol)
        object.__setattr__(self, "rules", get_rules(self.rules).key)
        if self.engine_torque is not None:
            object.__setattr__(
                self,
                "engine_torque",
                check_positive("engine_torque", self.engine_torque, "the engine torque"),
            )
        if self.engine_torque_curve is not None:
            if self.engine_torque is not None:
                raise InputError(
                    "give engine_torque or engine_torque_curve, not both",
                    key="engine_torque_curve",
                )
            try:
                w, q = (np.asarray(v, dtype=float) for v in self.engine_torque_curve)
            except (TypeError, ValueError):
                raise InputError("expected speeds and torques", key="engine_torque_curve") from None
            ok = (
                w.ndim == 1
                and w.shape == q.shape
                and w.size >= 1
                and np.all(np.isfinite(w))
                and np.all(np.isfinite(q))
                and np.all(w > 0.0)
                and np.all(np.diff(w) > 0.0)
                and np.all(q > 0.0)
            )
            if not ok:
                raise InputError(
                    "the engine's torque-speed curve needs increasing positive speeds and "
                    "positive torques",
                    key="engine_torque_curve",
                )
            object.__setattr__(self, "engine_torque_curve", (w, q))
        if self.passage_load is not None and self.passage_load not in ("law", "none"):
            raise InputError("expected law or none", key="passage_load", value=self.passage_load)
        self._check_conditions()

    def _check_conditions(self) -> None:
        """The passage torque, the overspeed limit, the clutch, the idle speed, the events."""
        if self.passage_torque not in PASSAGE_TORQUES:
            raise InputError(
                f"expected one of {', '.join(PASSAGE_TORQUES)}",
                key="passage_torque",
                value=self.passage_torque,
            )
        given = self.engine_torque is not None or self.engine_torque_curve is not None
        if self.passage_torque == "rated" and given:
            raise InputError(
                'give engine_torque, engine_torque_curve or passage_torque = "rated", not two',
                key="passage_torque",
                value=self.passage_torque,
            )
        if self.overspeed_limit is not None:
            ratio = float(self.overspeed_limit)
            if not (math.isfinite(ratio) and 1.0 < ratio <= 1.5):
                raise InputError(
                    "the overspeed limit is a speed ratio n/n_0 above 1 (at most 1.5)",
                    key="overspeed_limit",
                    value=self.overspeed_limit,
                )
            object.__setattr__(self, "overspeed_limit", ratio)
        if self.clutch is not None:
            pair = tuple(self.clutch)
            if (
                len(pair) != 2
                or not all(isinstance(v, str) and v for v in pair)
                or (pair[0] == pair[1])
            ):
                raise InputError("expected two mass names", key="clutch", value=self.clutch)
            object.__setattr__(self, "clutch", (pair[0], pair[1]))
        if self.idle_speed is not None:
            object.__setattr__(
                self, "idle_speed", check_positive("idle_speed", self.idle_speed, "the idle speed")
            )
        object.__setattr__(self, "events", tuple(self.events))
        names = [e.name for e in self.events]
        if len(set(names)) != len(names):
            twice = next(n for n in names if names.count(n) > 1)
            raise InputError(
                "two events have this name: give each its own name", key="event", value=twice
            )

    @property
    def ruleset(self) -> RuleSet:
        """The classification society's rule set (:func:`crankdyn.tvc.rulesets.get` of
        :attr:`rules`): every value of the verdicts with its clause."""
        return get_rules(self.rules)

    @property
    def tolerance(self) -> float:
        """The tachometer tolerance a declared barred range is widened by (fraction of the
        speed): ``tachometer_tolerance`` where given, else the rule set's stated value, else
        :data:`crankdyn.defaults.TACHOMETER_TOLERANCE`
        (:func:`crankdyn.tvc.rulesets.tachometer_tolerance`)."""
        return tachometer_tolerance(self.ruleset, self.tachometer_tolerance)

    def engine_torque_at(self, speeds: ArrayLike, default: float) -> NDArray[np.float64]:
        """The engine's torque while passing a barred range, at given speeds.

        Parameters
        ----------
        speeds : array_like
            Reference-shaft speeds (rad/s), any shape.
        default : float
            The torque (N m) where neither ``engine_torque_curve`` nor ``engine_torque`` is given
            (the TVC passes the mean load torque at the rated speed).

        Returns
        -------
        numpy.ndarray
            Torque (N m), the shape of ``speeds``: ``engine_torque_curve`` interpolated linearly
            (held at its ends), else ``engine_torque``, else ``default``.

        Examples
        --------
        >>> spec = TvcSpec(engine_torque_curve=([20.0, 40.0, 60.0], [1e4, 2e4, 2e4]))
        >>> spec.engine_torque_at([10.0, 30.0, 70.0], 5e3)
        array([10000., 15000., 20000.])
        >>> TvcSpec().engine_torque_at([10.0, 30.0], 5e3)
        array([5000., 5000.])
        """
        w = np.asarray(speeds, dtype=float)
        if self.engine_torque_curve is not None:
            cw, cq = self.engine_torque_curve
            return np.interp(w, cw, cq)
        value = self.engine_torque if self.engine_torque is not None else default
        return np.full(w.shape, float(value))

    def range_of(self, kind: str, model: TorsionModel | None) -> tuple[float, float]:
        """The speed range of a condition kind.

        Parameters
        ----------
        kind : str
            A condition kind (:data:`CONDITION_KINDS`).
        model : TorsionModel or None
            The model whose ``[operating]`` speed range is the last resort.

        Returns
        -------
        low, high : float
            The kind's own range from ``ranges``, else ``speed_range``, else the model's
            operating range (rad/s).

        Raises
        ------
        InputError
            Naming the model's file and the key ``speed_range`` where none of them is given.

        Examples
        --------
        >>> from crankdyn.constants import RPM
        >>> spec = TvcSpec(speed_range=(300 / RPM, 600 / RPM), ranges={"misfire": (30.0, 50.0)})
        >>> spec.range_of("misfire", None)
        (30.0, 50.0)
        >>> [round(w * RPM, 6) for w in spec.range_of("normal", None)]
        [300.0, 600.0]
        """
        if kind in self.ranges:
            return self.ranges[kind]
        if self.speed_range is not None:
            return self.speed_range
        operating = getattr(model, "operating", None)
        if operating is None:
            raise InputError(
                "the TVC needs a speed range: give [tvc] speed_range or [operating] speed_range",
                file=getattr(model, "source", None),
                key="speed_range",
            )
        return operating.low, operating.high


def _range(pair: Sequence[float], key: str) -> tuple[float, float]:
    try:
        low, high = (float(v) for v in pair)
    except (TypeError, ValueError):
        raise InputError("expected two speeds", key=key, value=pair) from None
    low = check_positive(key, low, "the lowest speed")
    high = check_positive(key, high, "the highest speed")
    if high <= low:
        raise InputError(
            "the speed range is empty: its end is not above its start",
            key=key,
            value=[low * RPM, high * RPM],
        )
    return low, high
