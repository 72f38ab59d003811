"""The engine's speed governor in a transient event: a sampled (digital) PI governor with an
optional speed droop, its output held between samples and limited to the engine's available
torque at the sensed speed (domain object and numeric core of
:mod:`crankdyn.torsion.event_run`).

The law, at every sample instant t_k = k Delta (Delta the governor's sample time), from the
sensed engine speed w_k (the speed of the engine's masses weighted as they share its torque,
at the reference shaft)::

    e_k = w_s - w_k - delta w_ref T_(k-1) / T_ref            (speed error with droop)
    I_k = I_(k-1) + (K_p / T_i) e_k Delta                    (integral, frozen while the
                                                              output is limited and e_k
                                                              drives it further: anti-windup)
    T_k = clip(K_p e_k + I_k, 0, T_max(w_k))                 (held until t_(k+1))

K_p = k_p T_ref / w_ref (k_p the gain in per unit: the fraction of T_ref per fraction of w_ref
of speed error), T_i the integral time, delta the droop, and (w_ref, T_ref) the engine's rated
point: the torque curve's highest speed and its largest torque. In steady state e = 0, so the
speed settles delta w_ref T / T_ref below the set speed: the droop characteristic of ISO
3046-4:2009 (Reciprocating internal combustion engines, Performance, Part 4: Speed governing,
the steady-state speed droop as a fraction of the rated speed from no load to rated load);
delta = 0 is the isochronous governor. The PI structure with a proportional gain and an
integral time acting on the speed error, the engine's torque following the fuel index, is the
marine engine speed control model of Kurihara et al. (the PI governor of the training ship
Shioji-maru, Tokyo University of Mercantile Marine; Nippon Foundation report 2000, sec. 2.3)
and of Altosole et al., "A diesel engine modelling approach for ship propulsion real-time
simulators", J. Mar. Sci. Eng. 7 (2019) 138 (the governor's PI on the speed error, the fuel
limited by the engine's torque limiter); the zero-order hold over a sample is the digital
governor's update cycle (electronic governors of medium-speed engines compute every few
milliseconds to tens of milliseconds). The torque limit T_max(w) is the engine's torque-speed
curve (the load diagram's torque or fuel limit), never unlimited: a governed engine cannot give
more than its cylinders can.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.defaults import DEFAULTS
from crankdyn.errors import InputError
from crankdyn.torsion.event_base import finite, nonnegative, positive

__all__ = [
    "GOVERNOR_DROOP",
    "GOVERNOR_GAIN",
    "GOVERNOR_INTEGRAL_TIME",
    "GOVERNOR_SAMPLE_TIME",
    "Governor",
    "GovernorRun",
]

GOVERNOR_GAIN = float(DEFAULTS["governor_gain"].value)
"""The governor's proportional gain k_p (per unit torque per unit speed error)."""
GOVERNOR_INTEGRAL_TIME = float(DEFAULTS["governor_integral_time"].value)
"""The governor's integral time T_i (s)."""
GOVERNOR_DROOP = float(DEFAULTS["governor_droop"].value)
"""The governor's speed droop delta (fraction of the rated speed at rated torque)."""
GOVERNOR_SAMPLE_TIME = float(DEFAULTS["governor_sample_time"].value)
"""The governor's sample time Delta (s)."""


@dataclass(frozen=True)
class Governor:
    """An engine's speed governor during a transient event (module docstring).

    Parameters
    ----------
    torque_curve : (array_like, array_like)
        The engine's largest torque (N m, at the reference shaft) against its speed (rad/s,
        increasing; at least two points), interpolated linearly and held at its ends; its
        highest speed and largest torque are the rated point (w_ref, T_ref) of the per-unit
        gain and the droop.
    set_speed : float or None
        w_s (rad/s, reference shaft), > 0; None: the engine's speed when the event starts.
    gain : float
        k_p (per unit), > 0; default :data:`GOVERNOR_GAIN`.
    integral_time : float
        T_i (s), > 0; default :data:`GOVERNOR_INTEGRAL_TIME`.
    droop : float
        delta (dimensionless, 0 <= delta < 0.2); default :data:`GOVERNOR_DROOP` (isochronous).
    sample_time : float
        Delta (s), > 0; default :data:`GOVERNOR_SAMPLE_TIME`.
    source : str
        The model's source, for reports.

    Raises
    ------
    InputError
        Naming the key: a curve that is not increasing in speed or has negative torques, a gain,
        integral time or sample time that is not positive, a droop out of range.

    Examples
    --------
    >>> g = Governor(([30.0, 80.0], [1e4, 4e4]), droop=0.04)
    >>> round(g.proportional, 3), g.max_torque(np.array([55.0, 100.0])).tolist()
    (5000.0, [25000.0, 40000.0])
    """

    torque_curve: tuple[NDArray[np.float64], NDArray[np.float64]]
    set_speed: float | None = None
    gain: float = GOVERNOR_GAIN
    integral_time: float = GOVERNOR_INTEGRAL_TIME
    droop: float = GOVERNOR_DROOP
    sample_time: float = GOVERNOR_SAMPLE_TIME
    source: str = field(
        default="sampled PI speed governor (Altosole et al. 2019; ISO 3046-4:2009 speed droop), "
        "its torque limited by the engine's torque-speed curve",
        repr=False,
    )

    if TYPE_CHECKING:

        def __init__(
            self,
            torque_curve: tuple[ArrayLike, ArrayLike],
            set_speed: float | None = None,
            gain: float = GOVERNOR_GAIN,
            integral_time: float = GOVERNOR_INTEGRAL_TIME,
            droop: float = GOVERNOR_DROOP,
            sample_time: float = GOVERNOR_SAMPLE_TIME,
            source: str = "",
        ) -> None: ...

    def __post_init__(self) -> None:
        curve = self.torque_curve
        if not isinstance(curve, (list, tuple)) or len(curve) != 2:
            raise InputError("expected (speeds, torques)", key="torque_curve")
        w, q = (np.array(v, dtype=float).ravel() for v in curve)
        if w.size < 2 or w.size != q.size or np.any(np.diff(w) <= 0.0) or w[0] < 0.0:
            raise InputError("expected increasing speeds and as many torques", key="torque_curve")
        if not (np.all(np.isfinite(q)) and np.all(q >= 0.0) and np.max(q) > 0.0):
            raise InputError("the torques must not be negative", key="torque_curve")
        object.__setattr__(self, "torque_curve", (w, q))
        if self.set_speed is not None:
            object.__setattr__(self, "set_speed", positive("set_speed", self.set_speed))
        for key in ("gain", "integral_time", "sample_time"):
            object.__setattr__(self, key, positive(key, getattr(self, key)))
        droop = nonnegative("droop", self.droop)
        if droop >= 0.2:
            raise InputError("expected a droop below 0.2 (20 %)", key="droop", value=droop)
        object.__setattr__(self, "droop", droop)

    @property
    def rated_speed(self) -> float:
        """w_ref: the torque curve's highest speed (rad/s)."""
        return float(self.torque_curve[0][-1])

    @property
    def rated_torque(self) -> float:
        """T_ref: the torque curve's largest torque (N m)."""
        return float(np.max(self.torque_curve[1]))

    @property
    def proportional(self) -> float:
        """K_p = k_p T_ref / w_ref (N m s/rad)."""
        return self.gain * self.rated_torque / self.rated_speed

    def max_torque(self, speed: ArrayLike) -> NDArray[np.float64]:
        """T_max at speeds (rad/s): the torque curve, held at its ends (N m).

        Parameters
        ----------
        speed : array_like
            Speeds (rad/s).

        Returns
        -------
        numpy.ndarray
            (N m), the shape of ``speed``.
        """
        w, q = self.torque_curve
        return np.interp(np.asarray(speed, dtype=float), w, q)

    def start(self, speed: float, torque: float) -> GovernorRun:
        """The governor's run from an engine at ``speed`` giving ``torque`` at t = 0.

        Parameters
        ----------
        speed : float
            The sensed engine speed at t = 0 (rad/s).
        torque : float
            The engine's torque at t = 0 (N m), within [0, T_max(speed)].

        Returns
        -------
        GovernorRun
            Its state, to be sampled along the run.

        Raises
        ------
        InputError
            If ``torque`` is outside [0, T_max(speed)] (key ``drive_torque``).
        """
        top = float(self.max_torque(speed))
        if not -1e-9 * top <= finite("drive_torque", torque) <= top * (1.0 + 1e-9):
            raise InputError(
                f"the engine's torque before the event must lie within 0 and its torque "
                f"curve's {top:.6g} N m at {speed:.6g} rad/s",
                key="drive_torque",
                value=torque,
            )
        set_speed = float(speed) if self.set_speed is None else float(self.set_speed)
        return GovernorRun(self, set_speed, float(torque))


@dataclass(eq=False)
class GovernorRun:
    """A governor's state along a run: its samples (instants, held torques) and its integral
    (module docstring). Built by :meth:`Governor.start`.

    Parameters
    ----------
    governor : Governor
        The settings.
    set_speed : float
        w_s (rad/s).
    initial_torque : float
        The torque held before the first sample (N m).
    times : list of float
        The sample instants so far (s).
    held : list of float
        The torque held from each (N m).
    integral : float
        The integral part I_k (N m); NaN before the first sample.
    """

    governor: Governor
    set_speed: float
    initial_torque: float
    times: list[float] = field(default_factory=list)
    held: list[float] = field(default_factory=list)
    integral: float = math.nan

    def sample(self, t: float, speed: float) -> float:
        """Take the sample at t of the sensed speed and hold the new torque (module docstring).

        Parameters
        ----------
        t : float
            The sample instant (s).
        speed : float
            The sensed engine speed (rad/s).

        Returns
        -------
        float
            The torque held from t (N m).
        """
        g = self.governor
        last = self.held[-1] if self.held else self.initial_torque
        error = self.set_speed - speed - g.droop * g.rated_speed * last / g.rated_torque
        kp = g.proportional
        if math.isnan(self.integral):  # the first sample: the output continues the torque
            self.integral = self.initial_torque - kp * error
        step = kp / g.integral_time * error * g.sample_time
        top = float(g.max_torque(speed))
        want = kp * error + self.integral + step
        if not ((want > top and error > 0.0) or (want < 0.0 and error < 0.0)):
            self.integral += step  # anti-windup: frozen while limited in the error's direction
        torque = min(max(kp * error + self.integral, 0.0), top)
        self.times.append(float(t))
        self.held.append(torque)
        return torque

    def torque(self, t: ArrayLike) -> NDArray[np.float64]:
        """The held torque at times t (s), any time of the run so far (N m).

        Parameters
        ----------
        t : array_like
            Times (s).

        Returns
        -------
        numpy.ndarray
            The torque of the last sample at or before each time (the initial torque before
            the first), the shape of ``t``.
        """
        t = np.asarray(t, dtype=float)
        values = np.array([self.initial_torque, *self.held])
        index = np.searchsorted(np.array(self.times), t, side="right")
        return values[index]
