"""Transient events of a shaft line: the torques (or the constraint) they put on its masses
(domain objects).

Each event is a frozen dataclass naming the mass it acts on and giving its torque as a function
of time, in the mass's own sense of rotation (positive drives the rotation: a load or a brake
is negative), with its source in its docstring; :func:`crankdyn.torsion.event_run.
event_response` integrates the line's response (:mod:`crankdyn.torsion.integrator`):

- :class:`StepTorque`: a torque applied suddenly (or rising linearly) at a mass;
- :class:`TabulatedTorque`: a torque-time history (a CSV file: :meth:`TabulatedTorque.
  from_file`);
- :class:`ShortCircuit`: a generator's two- or three-phase short circuit
  (:mod:`crankdyn.torsion.short_circuit`);
- :class:`IceImpact`: a propeller's ice milling sequence (Finnish-Swedish Ice Class Rules 2017,
  IACS UR I3: :mod:`crankdyn.torsion.ice`);
- :class:`ClutchEngagement`: a friction clutch closing with slip, then locked (a constraint:
  the element between its halves is replaced by the friction torque while they slip);
- :class:`SpeedChange`: a start (the engine's torque curve and its governor), a stop, an
  emergency stop (fuel cut, the line coasting down under its load) or a prescribed speed ramp,
  through the barred speed ranges.

Every event has a ``severity``: ``"normal"`` for the transient conditions of service (a start,
a stop, a clutch engagement, ice impacts) and ``"exceptional"`` for the rare ones (a short
circuit, an emergency stop): a coupling maker's catalogue gives T_Kmax1 for the first and
T_Kmax2 for the second (the TVC's checks, :mod:`crankdyn.tvc.checks`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError
from crankdyn.torsion.event_base import (
    SEVERITIES,
    SPEED_KINDS,
    finite,
    linear_rise,
    mass_name,
    nonnegative,
    positive,
    severity_of,
)
from crankdyn.torsion.event_drives import ClutchEngagement, SpeedChange
from crankdyn.torsion.ice import (
    ICE_CASES,
    design_ice_torque,
    ice_thickness,
    ice_torque,
    milling_revolutions,
)
from crankdyn.torsion.short_circuit import short_circuit_torque

__all__ = [
    "SEVERITIES",
    "SPEED_KINDS",
    "ClutchEngagement",
    "Event",
    "IceImpact",
    "ShortCircuit",
    "SpeedChange",
    "StepTorque",
    "TabulatedTorque",
    "TorqueEvent",
]


@dataclass(frozen=True)
class StepTorque:
    """A torque applied suddenly at ``start`` (or rising linearly over ``rise_time``) and held.

    The undamped response of a line to a step is the classic one: a suddenly applied torque
    twists a shaft to twice its static twist (e.g. W. T. Thomson, *Theory of Vibration with
    Applications*, 4th ed., 1993, sec. 4.2, the response to a step: x = (F/k)(1 - cos wt)).

    Parameters
    ----------
    at : str
        The mass (its name in the model).
    value : float
        The torque (N m, own sense: positive drives the rotation).
    start : float
        When it is applied (s), >= 0.
    rise_time : float
        The time over which it rises linearly from 0 (s), >= 0 (0: a step).
    name : str
        The event's name (the verdicts' condition).
    severity : str
        ``"normal"`` or ``"exceptional"`` (:data:`SEVERITIES`).
    source : str
        Where the event comes from, for reports.

    Examples
    --------
    >>> e = StepTorque("flywheel", 1e3, start=0.1, rise_time=0.1)
    >>> e.torque(np.array([0.0, 0.15, 1.0])).tolist(), e.breakpoints()
    ([0.0, 500.0, 1000.0], (0.1, 0.2))
    """

    at: str
    value: float
    start: float = 0.0
    rise_time: float = 0.0
    name: str = "suddenly applied torque"
    severity: str = "normal"
    source: str = field(default="a suddenly applied torque", repr=False)

    if TYPE_CHECKING:

        def __init__(
            self,
            at: str,
            value: float,
            start: float = 0.0,
            rise_time: float = 0.0,
            name: str = "suddenly applied torque",
            severity: str = "normal",
            source: str = "a suddenly applied torque",
        ) -> None: ...

    def __post_init__(self) -> None:
        mass_name(self.at)
        object.__setattr__(self, "value", finite("value", self.value))
        object.__setattr__(self, "start", nonnegative("start", self.start))
        object.__setattr__(self, "rise_time", nonnegative("rise_time", self.rise_time))
        severity_of(self.severity)

    def torque(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """The torque (N m) at times t (s).

        Parameters
        ----------
        t : numpy.ndarray
            Times (s).

        Returns
        -------
        numpy.ndarray
            0 before ``start``, the torque after ``start + rise_time``, linear between.
        """
        return self.value * linear_rise(t, self.start, self.rise_time)

    def breakpoints(self) -> tuple[float, ...]:
        """The start and the end of the rise (s).

        Returns
        -------
        tuple of float
            Times (s).
        """
        if self.rise_time == 0.0:
            return (self.start,)
        return (self.start, self.start + self.rise_time)

    def frequency(self) -> float:
        """0: a step holds no frequency of its own (the step rule follows the model's modes).

        Returns
        -------
        float
            0 (rad/s).
        """
        return 0.0

    def default_duration(self) -> float | None:
        """None: the run lasts 20 periods of the line's lowest mode after the rise.

        Returns
        -------
        None
            The run chooses.
        """
        return None

    def prepared(self, speed: float) -> StepTorque:
        """This event (it does not depend on the speed).

        Parameters
        ----------
        speed : float
            The nominal speed of its mass (rad/s).

        Returns
        -------
        StepTorque
            Itself.
        """
        return self


@dataclass(frozen=True)
class TabulatedTorque:
    """A torque-time history at a mass, interpolated linearly between its points (the first
    value held before them, the last after).

    Parameters
    ----------
    at : str
        The mass.
    time : numpy.ndarray
        (P,) times (s), increasing.
    values : numpy.ndarray
        (P,) torques (N m, own sense).
    name : str
        The event's name.
    severity : str
        ``"normal"`` or ``"exceptional"``.
    source : str
        Where the history comes from (the file).

    Examples
    --------
    >>> e = TabulatedTorque("propeller", [0.0, 0.1, 0.2], [0.0, -5e3, 0.0])
    >>> e.torque(np.array([0.05, 0.3])).tolist()
    [-2500.0, 0.0]
    """

    at: str
    time: NDArray[np.float64]
    values: NDArray[np.float64]
    name: str = "tabulated torque"
    severity: str = "normal"
    source: str = "a tabulated torque-time history"

    if TYPE_CHECKING:

        def __init__(
            self,
            at: str,
            time: ArrayLike,
            values: ArrayLike,
            name: str = "tabulated torque",
            severity: str = "normal",
            source: str = "a tabulated torque-time history",
        ) -> None: ...

    def __post_init__(self) -> None:
        mass_name(self.at)
        t = np.array(self.time, dtype=float).ravel()
        v = np.array(self.values, dtype=float).ravel()
        if t.size < 2 or t.size != v.size:
            raise InputError("expected at least two times and as many torques", key="time")
        if not (np.all(np.isfinite(t)) and np.all(np.isfinite(v))):
            raise InputError("expected finite times and torques", key="time")
        if np.any(np.diff(t) <= 0.0) or t[0] < 0.0:
            raise InputError("the times must increase from 0 or later", key="time")
        t.setflags(write=False)
        v.setflags(write=False)
        object.__setattr__(self, "time", t)
        object.__setattr__(self, "values", v)
        severity_of(self.severity)

    @classmethod
    def from_file(
        cls, path: str | Path, at: str, *, name: str | None = None, severity: str = "normal"
    ) -> TabulatedTorque:
        """The history in a CSV file with a time and a torque column, units in the header
        (``time_s,torque_kN*m``; :func:`crankdyn.io.event_tables.read_torque_history`).

        Parameters
        ----------
        path : str or pathlib.Path
            The file.
        at : str
            The mass the torque acts on.
        name : str or None
            The event's name; default the file's name.
        severity : str
            ``"normal"`` or ``"exceptional"``.

        Returns
        -------
        TabulatedTorque
            The event.

        Raises
        ------
        InputError
            For a file that cannot be read, naming the file, line and column.
        """
        from crankdyn.io.event_tables import read_torque_history

        time, torque, shown = read_torque_history(path)
        return cls(at, time, torque, name or shown, severity, source=f"torque history {shown}")

    def torque(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """The torque (N m) at times t (s), linear between the points.

        Parameters
        ----------
        t : numpy.ndarray
            Times (s).

        Returns
        -------
        numpy.ndarray
            The torques (N m).
        """
        return np.interp(np.asarray(t, dtype=float), self.time, self.values)

    def breakpoints(self) -> tuple[float, ...]:
        """The table's times (s), when there are at most 2000 of them (a denser table is
        followed by the step: :meth:`frequency`).

        Returns
        -------
        tuple of float
            Times (s).
        """
        if self.time.size > 2000:
            return (float(self.time[0]), float(self.time[-1]))
        return tuple(float(v) for v in self.time)

    def frequency(self) -> float:
        """The table's own resolution: pi over its median interval for a table of more than
        2000 points (the step then samples every interval), else 0.

        Returns
        -------
        float
            (rad/s).
        """
        if self.time.size <= 2000:
            return 0.0
        return math.pi / float(np.median(np.diff(self.time)))

    def default_duration(self) -> float | None:
        """The table's last time (s).

        Returns
        -------
        float
            (s).
        """
        return float(self.time[-1])

    def prepared(self, speed: float) -> TabulatedTorque:
        """This event (it does not depend on the speed).

        Parameters
        ----------
        speed : float
            The nominal speed of its mass (rad/s).

        Returns
        -------
        TabulatedTorque
            Itself.
        """
        return self


@dataclass(frozen=True)
class ShortCircuit:
    """A generator's sudden short circuit: the air-gap torque on its rotor
    (:mod:`crankdyn.torsion.short_circuit`: IEC 60034-4-1:2018's short-circuit current
    components, the classic constant-flux-linkage torque; two- and three-phase).

    The torque adds to the running condition (the generator's mean load stays, a conservative
    simplification: the fault takes little active power); it acts against the rotation.

    Parameters
    ----------
    at : str
        The generator's rotor (a mass of the model).
    rated_torque : float
        T_r, the generator's rated torque (N m), > 0 (rated active power over the mechanical
        speed).
    line_frequency : float
        The electrical frequency f (Hz), > 0.
    xd2, xd1, xd : float
        X''_d <= X'_d <= X_d (per unit).
    td2, td1, ta : float
        T''_d, T'_d, T_a (s).
    phases : {2, 3}
        A two-phase (line-to-line) or three-phase fault.
    power_factor : float
        cos(phi_r), 0 < cos(phi_r) <= 1 (default 0.8): the torque base is T_r / cos(phi_r).
    voltage : float
        The internal EMF before the fault (per unit), default 1 (IEC 60909-0: c_max = 1.1).
    angle : float
        The fault instant on the line-to-line EMF (rad), two-phase only; 0 gives the largest
        torque.
    start : float
        When the fault occurs (s), >= 0.
    clearing_time : float or None
        The fault's duration until the breaker clears it (s), or None (not cleared in the
        run).
    name : str or None
        The event's name; default "two-phase short circuit" or "three-phase short circuit".
    severity : str
        Default ``"exceptional"``.
    source : str
        The event's source, for reports (the standards above).

    Examples
    --------
    >>> sc = ShortCircuit("alternator", rated_torque=3600.0, line_frequency=50.0, xd2=0.12,
    ...                   xd1=0.25, xd=2.0, td2=0.02, td1=0.4, ta=0.05)
    >>> sc.name, round(float(sc.torque(np.array([0.005]))[0]))  # against the rotation
    ('three-phase short circuit', -29851)
    """

    at: str
    rated_torque: float
    line_frequency: float
    xd2: float
    xd1: float
    xd: float
    td2: float
    td1: float
    ta: float
    phases: int = 3
    power_factor: float = 0.8
    voltage: float = 1.0
    angle: float = 0.0
    start: float = 0.0
    clearing_time: float | None = None
    name: str = ""
    severity: str = "exceptional"
    source: str = field(
        default="air-gap torque of the constant-flux-linkage analysis from the machine's "
        "IEC 60034-4-1:2018 quantities (X''d, X'd, Xd, T''d, T'd, Ta; the standard not read: "
        "crankdyn.torsion.short_circuit)",
        repr=False,
    )

    def __post_init__(self) -> None:
        mass_name(self.at)
        if self.phases not in (2, 3):
            raise InputError("expected 2 or 3", key="phases", value=self.phases)
        pf = float(self.power_factor)
        if not (math.isfinite(pf) and 0.0 < pf <= 1.0):
            raise InputError("expected 0 < cos phi <= 1", key="power_factor", value=pf)
        object.__setattr__(self, "start", nonnegative("start", self.start))
        if self.clearing_time is not None:
            positive("clearing_time", self.clearing_time)
        if not self.name:
            words = "two-phase" if self.phases == 2 else "three-phase"
            object.__setattr__(self, "name", f"{words} short circuit")
        severity_of(self.severity)
        self.torque(np.zeros(1))  # the machine data checked once (one-line errors)

    def torque(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """The air-gap torque on the rotor (N m, own sense: negative brakes) at times t (s).

        Parameters
        ----------
        t : numpy.ndarray
            Times (s).

        Returns
        -------
        numpy.ndarray
            0 before the fault and after its clearing.
        """
        t = np.asarray(t, dtype=float)
        tau = t - self.start
        out = -short_circuit_torque(
            tau,
            phases=self.phases,
            frequency=2.0 * math.pi * self.line_frequency,
            base_torque=self.rated_torque / self.power_factor,
            xd2=self.xd2,
            xd1=self.xd1,
            xd=self.xd,
            td2=self.td2,
            td1=self.td1,
            ta=self.ta,
            voltage=self.voltage,
            angle=self.angle,
        )
        if self.clearing_time is not None:
            out = np.where(tau > self.clearing_time, 0.0, out)
        return out

    def breakpoints(self) -> tuple[float, ...]:
        """The fault and its clearing (s).

        Returns
        -------
        tuple of float
            Times (s).
        """
        if self.clearing_time is None:
            return (self.start,)
        return (self.start, self.start + self.clearing_time)

    def frequency(self) -> float:
        """The line's angular frequency, twice it for a two-phase fault (rad/s).

        Returns
        -------
        float
            (rad/s).
        """
        return 2.0 * math.pi * self.line_frequency * (2.0 if self.phases == 2 else 1.0)

    def default_duration(self) -> float | None:
        """The fault and 10 armature time constants, at least 0.3 s after the fault (s).

        Returns
        -------
        float
            (s).
        """
        return self.start + max(10.0 * self.ta, 0.3)

    def prepared(self, speed: float) -> ShortCircuit:
        """This event (the line frequency is the machine's).

        Parameters
        ----------
        speed : float
            The nominal speed of its mass (rad/s).

        Returns
        -------
        ShortCircuit
            Itself.
        """
        return self


@dataclass(frozen=True)
class IceImpact:
    """A propeller's ice milling sequence (:mod:`crankdyn.torsion.ice`: the Finnish-Swedish Ice
    Class Rules 2017 and IACS UR I3, the torque excitation for the shaft line's dynamic
    analysis): half-sine blade impacts of C_q Q_max over alpha_i of each blade's rotation, the
    blades 360 / Z apart, during N_Q revolutions, against the rotation.

    The impacts are laid out on the propeller's nominal speed (the speed drop during the
    sequence is computed, but does not move them).

    Parameters
    ----------
    at : str
        The propeller (a mass of the model).
    q_max : float
        Q_max (N m), > 0 (:func:`crankdyn.torsion.ice.design_ice_torque`, or
        :meth:`from_rule`).
    blades : int
        Z, >= 1.
    case : {1, 2, 3, 4}
        The excitation case (:data:`crankdyn.torsion.ice.ICE_CASES`).
    revolutions : float
        N_Q (:func:`crankdyn.torsion.ice.milling_revolutions`), > 0.
    start : float
        The first impact (s), >= 0.
    speed : float or None
        The propeller's speed (rad/s); None: its nominal speed in the run.
    name : str or None
        The event's name; default "ice impact, case <case>".
    severity : str
        Default ``"normal"``.
    source : str
        The event's source, for reports (the rules above).

    Examples
    --------
    >>> ice = IceImpact("propeller", q_max=1e5, blades=4, case=1, revolutions=3.0,
    ...                 speed=2 * np.pi)
    >>> round(float(ice.torque(np.array([0.125]))[0]), 6)  # 45 deg: -0.75 Q_max
    -75000.0
    """

    at: str
    q_max: float
    blades: int
    case: int = 1
    revolutions: float = 3.0
    start: float = 0.0
    speed: float | None = None
    name: str = ""
    severity: str = "normal"
    source: str = field(
        default="Finnish-Swedish Ice Class Rules 2017 (TRAFI/494131/03.04.01.00/2016) ch. 6 and "
        "IACS UR I3 Rev.1 2007: torque excitation for shaft line dynamic analysis (not verified "
        "against the texts: crankdyn.torsion.ice)",
        repr=False,
    )

    def __post_init__(self) -> None:
        mass_name(self.at)
        positive("q_max", self.q_max)
        if self.case not in ICE_CASES:
            raise InputError("expected an ice case 1, 2, 3 or 4", key="case", value=self.case)
        if isinstance(self.blades, bool) or int(self.blades) != self.blades or self.blades < 1:
            raise InputError("expected a whole number of blades", key="blades", value=self.blades)
        positive("revolutions", self.revolutions)
        object.__setattr__(self, "start", nonnegative("start", self.start))
        if self.speed is not None:
            positive("speed", self.speed)
        if not self.name:
            object.__setattr__(self, "name", f"ice impact, case {self.case}")
        severity_of(self.severity)

    @classmethod
    def from_rule(
        cls,
        at: str,
        *,
        ice_class: str,
        diameter: float,
        hub_diameter: float,
        pitch: float,
        thickness: float,
        speed: float,
        blades: int,
        case: int = 1,
        ducted: bool = False,
        start: float = 0.0,
    ) -> IceImpact:
        """The sequence of an ice class: Q_max from the propeller's data and N_Q = 2 H_ice
        (:func:`crankdyn.torsion.ice.design_ice_torque`, :func:`~crankdyn.torsion.ice.
        milling_revolutions`).

        Parameters
        ----------
        at : str
            The propeller.
        ice_class : str
            ``"IA Super"``, ``"IA"``, ``"IB"``, ``"IC"``, ``"PC1"`` ... ``"PC7"``.
        diameter, hub_diameter, pitch, thickness : float
            D, d, P_0.7, t_0.7 (m).
        speed : float
            The propeller's speed at the bollard condition (rad/s): Q_max's n.
        blades : int
            Z.
        case : int
            The excitation case.
        ducted : bool
            A ducted propeller.
        start : float
            The first impact (s).

        Returns
        -------
        IceImpact
            The event (its speed None: the run's nominal speed lays out the impacts).

        Examples
        --------
        >>> e = IceImpact.from_rule("propeller", ice_class="IA", diameter=4.0,
        ...                         hub_diameter=1.2, pitch=3.2, thickness=0.08,
        ...                         speed=4 * np.pi, blades=4)
        >>> round(e.q_max / 1e3, 3), e.revolutions
        (41.431, 3.0)
        """
        h = ice_thickness(ice_class)
        q = design_ice_torque(
            diameter=diameter,
            hub_diameter=hub_diameter,
            pitch=pitch,
            thickness=thickness,
            speed=speed,
            ice_thickness=h,
            ducted=ducted,
        )
        return cls(
            at,
            q_max=q,
            blades=blades,
            case=case,
            revolutions=milling_revolutions(h),
            start=start,
            name=f"ice impact {ice_class}, case {case}",
        )

    def _speed(self) -> float:
        if self.speed is None:
            raise InputError("the ice sequence needs the propeller's speed", key="speed")
        return float(self.speed)

    def torque(self, t: NDArray[np.float64]) -> NDArray[np.float64]:
        """The ice torque (N m, own sense: negative, against the rotation) at times t (s).

        Parameters
        ----------
        t : numpy.ndarray
            Times (s).

        Returns
        -------
        numpy.ndarray
            The torque (N m).
        """
        angle = self._speed() * (np.asarray(t, dtype=float) - self.start)
        return -ice_torque(
            angle,
            q_max=self.q_max,
            case=self.case,
            blades=self.blades,
            revolutions=self.revolutions,
        )

    def breakpoints(self) -> tuple[float, ...]:
        """The start and end of every blade impact (s).

        Returns
        -------
        tuple of float
            Times (s), sorted.
        """
        w = self._speed()
        _cq, alpha, blocks = ICE_CASES[self.case]
        z = int(self.blades)
        shifts = [0.0] if blocks == 1 else [0.0, 360.0 / (2 * z)]
        out = []
        passes = math.ceil(self.revolutions)
        for j in range(passes):
            for k in range(z):
                for s in shifts:
                    first = j * 360.0 + k * 360.0 / z + s
                    if first < self.revolutions * 360.0:
                        out.append(self.start + math.radians(first) / w)
                        out.append(self.start + math.radians(first + alpha) / w)
        return tuple(sorted(out))

    def frequency(self) -> float:
        """The half sine's angular frequency, speed x 180 / alpha_i (rad/s).

        Returns
        -------
        float
            (rad/s).
        """
        return self._speed() * 180.0 / ICE_CASES[self.case][1]

    def default_duration(self) -> float | None:
        """The sequence and two revolutions after it (s).

        Returns
        -------
        float
            (s).
        """
        return self.start + (self.revolutions + 2.0) * 2.0 * math.pi / self._speed()

    def prepared(self, speed: float) -> IceImpact:
        """The sequence laid out on ``speed`` when it names none.

        Parameters
        ----------
        speed : float
            The propeller's nominal speed (rad/s).

        Returns
        -------
        IceImpact
            With its speed.
        """
        return self if self.speed is not None else replace(self, speed=positive("speed", speed))


TorqueEvent = StepTorque | TabulatedTorque | ShortCircuit | IceImpact
"""An event that is a torque at one mass (:func:`crankdyn.torsion.event_run.event_response`
asks of it ``torque(t)``, ``breakpoints()``, ``frequency()``, ``default_duration()`` and
``prepared(speed)``)."""

Event = StepTorque | TabulatedTorque | ShortCircuit | IceImpact | ClutchEngagement | SpeedChange
"""Any event of the library."""
