"""Transient events that change the line's drive or its constraints: a friction clutch
closing, and a start, stop, emergency stop or speed ramp (domain objects; the library is
:mod:`crankdyn.torsion.events`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError
from crankdyn.torsion.event_base import (
    SPEED_KINDS,
    finite,
    linear_rise,
    nonnegative,
    positive,
    severity_of,
)
from crankdyn.torsion.event_governor import Governor

__all__ = ["ClutchEngagement", "SpeedChange"]


@dataclass(frozen=True)
class ClutchEngagement:
    """A friction clutch closing: its friction torque rises linearly from 0 to ``max_torque``
    over ``rise_time`` (the filling of a hydraulic multi-plate clutch) and acts between the two
    halves, against their slip, until their speeds meet; then the halves are locked (a
    constraint: the element between them, in the model, carries the torque).

    The model (VDI 2241 Blatt 1, "Schaltbare fremdbetaetigte Reibkupplungen und -bremsen",
    1982, the engagement of a friction clutch with a rising clutch torque; Coulomb friction: the
    transmitted torque is the friction torque while the halves slip): the element ``between``
    of the model (the clutch's shaft or coupling) is taken out while the halves slip (it is in
    series with the slipping plates and carries the friction torque) and put back when their
    speeds meet, carrying the friction torque of that instant (no jump in the transmitted
    torque). Locked, the halves slip again when the torque the element carries exceeds the
    friction torque (event detection both ways, :mod:`crankdyn.torsion.event_run`).

    The engine: with a ``governor`` (:class:`crankdyn.torsion.event_governor.Governor`) it is
    on its speed governor, as a real engine is during clutch-in: its torque, shared by its
    cylinders as the mean torques are (:mod:`crankdyn.torsion.event_line`), follows the
    governor from ``drive_torque`` and never exceeds the engine's torque-speed curve. Without
    one, ``drive_torque`` is held at ``drive_at`` whatever the speed (an engine off its
    governor: the clutch drags it down).

    Parameters
    ----------
    between : (str, str)
        The two masses of the clutch's element (a shaft or coupling of the model): the first
        half and the second.
    max_torque : float
        The friction torque when fully engaged (N m), > 0.
    rise_time : float
        The time the friction torque takes to rise from 0 (s), >= 0.
    speeds : (float, float)
        The halves' speeds when the clutch starts to close (rad/s, own sense), e.g. the engine
        at idle and the propeller at rest.
    start : float
        When the friction torque starts to rise (s), >= 0.
    drive_torque : float
        A torque held at ``drive_at`` during the run (N m, own sense), e.g. the engine's at
        idle; default 0.
    drive_at : str or None
        Its mass without a governor; default the model's first crank throw, or its first mass.
    governor : crankdyn.torsion.event_governor.Governor or None
        The engine's speed governor (its set speed defaults to the engine's speed when the
        clutch starts to close); None: none.
    name : str
        The event's name.
    severity : str
        Default ``"normal"``.
    source : str
        The event's source, for reports (VDI 2241).

    Examples
    --------
    >>> c = ClutchEngagement(("engine", "gearbox"), 2e4, 0.5, speeds=(60.0, 0.0))
    >>> c.friction(np.array([0.25, 1.0])).tolist()
    [10000.0, 20000.0]
    """

    between: tuple[str, str]
    max_torque: float
    rise_time: float
    speeds: tuple[float, float]
    start: float = 0.0
    drive_torque: float = 0.0
    drive_at: str | None = None
    governor: Governor | None = None
    name: str = "clutch engagement"
    severity: str = "normal"
    source: str = field(
        default="VDI 2241 Blatt 1 (1982): friction clutch engaging with a rising clutch torque "
        "(Coulomb friction while slipping, locked when the speeds meet)",
        repr=False,
    )

    def __post_init__(self) -> None:
        ends = tuple(self.between) if isinstance(self.between, (list, tuple)) else ()
        if len(ends) != 2 or not all(isinstance(e, str) and e for e in ends) or ends[0] == ends[1]:
            raise InputError("expected two mass names", key="between", value=self.between)
        object.__setattr__(self, "between", (ends[0], ends[1]))
        positive("max_torque", self.max_torque)
        object.__setattr__(self, "rise_time", nonnegative("rise_time", self.rise_time))
        speeds = tuple(self.speeds) if isinstance(self.speeds, (list, tuple)) else ()
        if len(speeds) != 2:
            raise InputError("expected the two halves' speeds", key="speeds", value=self.speeds)
        w = (finite("speeds", speeds[0]), finite("speeds", speeds[1]))
        if w[0] == w[1]:
            raise InputError("the halves turn at the same speed: nothing slips", key="speeds")
        object.__setattr__(self, "speeds", w)
        object.__setattr__(self, "start", nonnegative("start", self.start))
        object.__setattr__(self, "drive_torque", finite("drive_torque", self.drive_torque))
        if self.governor is not None and not isinstance(self.governor, Governor):
            raise InputError("expected a Governor", key="governor", value=self.governor)
        severity_of(self.severity)

    def friction(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """The friction torque the clutch can transmit at times t (s) (N m, >= 0).

        Parameters
        ----------
        t : numpy.ndarray
            Times (s).

        Returns
        -------
        numpy.ndarray
            0 before ``start``, ``max_torque`` after the rise, linear between.
        """
        return self.max_torque * linear_rise(t, self.start, self.rise_time)

    def breakpoints(self) -> tuple[float, ...]:
        """The start and the end of the rise (s).

        Returns
        -------
        tuple of float
            Times (s).
        """
        return (self.start, self.start + self.rise_time)


@dataclass(frozen=True)
class SpeedChange:
    """A start, a stop, an emergency stop or a speed ramp through the speed range: the line's
    mean speed Omega(t) from its rigid-body equation, the engine's harmonic torques at that
    speed and the mean torques that drive it.

    The mean speed obeys J Omega' = T_e - T_L(Omega) - T_brake (the rigid-body equation of the
    line reflected to the reference speed, as the TVC's passage through a barred range:
    :mod:`crankdyn.tvc.analysis`; J the line's total reflected inertia, T_L the load laws of the
    model's sources). The engine's torque follows a speed governor with the time constant
    ``governor_time`` toward the set speed Omega_s(t), which moves linearly from
    ``start_speed`` to ``end_speed`` over ``ramp_time`` after ``hold``:

        T_e = clip(T_L(Omega) + J (Omega_s' + (Omega_s - Omega) / tau), 0, T_max(Omega)),

    T_max the engine's torque curve (none: not limited); an unlimited governor makes the speed
    follow the set speed exactly (a prescribed ramp). After the fuel cut of an emergency stop
    T_e = 0 and the line coasts down under its load (and ``brake_torque``); the cylinders'
    harmonic torques stop with the fuel (their inertia torques' harmonics are left out).

    Parameters
    ----------
    kind : str
        ``"start"``, ``"stop"``, ``"emergency stop"`` or ``"ramp"``
        (:data:`crankdyn.torsion.event_base.SPEED_KINDS`).
    start_speed, end_speed : float
        Speeds of the reference mass (rad/s), >= 0.
    ramp_time : float
        The set speed's travel time (s), >= 0 (0: a step of the set speed, the torque curve
        limiting).
    governor_time : float
        tau (s), > 0; default 0.5.
    torque_curve : (array_like, array_like) or None
        The engine's largest torque (N m, at the reference speed) against the speed (rad/s),
        interpolated linearly; None: not limited.
    hold : float
        The time before the set speed moves (s), >= 0; the fuel cut of an emergency stop.
    brake_torque : float
        A braking torque after the fuel cut (N m at the reference), >= 0.
    load : bool
        Whether the model's load laws act (False: an idle start, no load).
    name : str or None
        The event's name; default the kind.
    severity : str or None
        Default ``"exceptional"`` for an emergency stop, else ``"normal"``.
    source : str
        The event's source, for reports.

    Examples
    --------
    >>> s = SpeedChange("ramp", 30.0, 80.0, ramp_time=10.0)
    >>> s.set_speed(np.array([0.0, 5.0, 20.0])).tolist(), s.name
    ([30.0, 55.0, 80.0], 'ramp')
    """

    kind: str
    start_speed: float
    end_speed: float
    ramp_time: float = 0.0
    governor_time: float = 0.5
    torque_curve: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None
    hold: float = 0.0
    brake_torque: float = 0.0
    load: bool = True
    name: str = ""
    severity: str = ""
    source: str = field(
        default="rigid-body equation J dOmega/dt = T_e - T_L(Omega) with the engine's torque "
        "curve and a speed governor (as the TVC's passage, crankdyn.tvc.analysis)",
        repr=False,
    )

    if TYPE_CHECKING:

        def __init__(
            self,
            kind: str,
            start_speed: float,
            end_speed: float,
            ramp_time: float = 0.0,
            governor_time: float = 0.5,
            torque_curve: tuple[ArrayLike, ArrayLike] | None = None,
            hold: float = 0.0,
            brake_torque: float = 0.0,
            load: bool = True,
            name: str = "",
            severity: str = "",
            source: str = "",
        ) -> None: ...

    def __post_init__(self) -> None:
        if self.kind not in SPEED_KINDS:
            raise InputError(
                f"expected one of {', '.join(SPEED_KINDS)}", key="kind", value=self.kind
            )
        for key in ("start_speed", "end_speed", "ramp_time", "hold", "brake_torque"):
            object.__setattr__(self, key, nonnegative(key, getattr(self, key)))
        object.__setattr__(self, "governor_time", positive("governor_time", self.governor_time))
        if self.torque_curve is not None:
            w, q = (np.array(v, dtype=float).ravel() for v in self.torque_curve)
            if w.size < 2 or w.size != q.size or np.any(np.diff(w) <= 0.0):
                raise InputError(
                    "expected increasing speeds and as many torques", key="torque_curve"
                )
            if not (np.all(np.isfinite(q)) and np.all(q >= 0.0)):
                raise InputError("the torques must not be negative", key="torque_curve")
            object.__setattr__(self, "torque_curve", (w, q))
        if self.kind == "start" and self.end_speed <= self.start_speed:
            raise InputError("a start ends above its start speed", key="end_speed")
        if self.kind in ("stop", "emergency stop") and self.end_speed >= self.start_speed:
            raise InputError("a stop ends below its start speed", key="end_speed")
        if not self.name:
            object.__setattr__(self, "name", self.kind)
        if not self.severity:
            default = "exceptional" if self.kind == "emergency stop" else "normal"
            object.__setattr__(self, "severity", default)
        severity_of(self.severity)

    @property
    def fuel_cut(self) -> float | None:
        """The time of the fuel cut (s): ``hold`` for an emergency stop, else None."""
        return self.hold if self.kind == "emergency stop" else None

    def set_speed(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """The governor's set speed Omega_s at times t (s) (rad/s).

        Parameters
        ----------
        t : numpy.ndarray
            Times (s).

        Returns
        -------
        numpy.ndarray
            (rad/s).
        """
        t = np.asarray(t, dtype=float)
        if self.ramp_time == 0.0:
            return np.where(t >= self.hold, self.end_speed, self.start_speed)
        frac = np.clip((t - self.hold) / self.ramp_time, 0.0, 1.0)
        return self.start_speed + (self.end_speed - self.start_speed) * frac

    def set_rate(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """Omega_s' at times t (s) (rad/s^2).

        Parameters
        ----------
        t : numpy.ndarray
            Times (s).

        Returns
        -------
        numpy.ndarray
            (rad/s^2).
        """
        t = np.asarray(t, dtype=float)
        if self.ramp_time == 0.0:
            return np.zeros(t.shape)
        inside = (t >= self.hold) & (t < self.hold + self.ramp_time)
        return np.where(inside, (self.end_speed - self.start_speed) / self.ramp_time, 0.0)

    def max_torque(self, speed: NDArray[np.float64]) -> NDArray[np.float64]:
        """The engine's torque curve at speeds (rad/s) (N m); inf without one.

        Parameters
        ----------
        speed : numpy.ndarray
            Speeds (rad/s).

        Returns
        -------
        numpy.ndarray
            (N m).
        """
        speed = np.asarray(speed, dtype=float)
        if self.torque_curve is None:
            return np.full(speed.shape, np.inf)
        w, q = self.torque_curve
        return np.interp(speed, w, q)

    def breakpoints(self) -> tuple[float, ...]:
        """The hold's end and the ramp's (s).

        Returns
        -------
        tuple of float
            Times (s).
        """
        return tuple(sorted({self.hold, self.hold + self.ramp_time}))
