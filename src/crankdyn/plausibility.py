"""Plausibility warnings: inputs that are legal but unlikely for the machine they describe.

An error (:class:`crankdyn.errors.InputError`) stops a run; a warning does not. A
:class:`PlausibilityWarning` says which quantity lies outside the range such machines reach,
its value, that range and where the range comes from, so the user can check a unit or a typo
(an IMEP of 19 MPa is usually 1.9 MPa typed with a wrong exponent) or confirm an unusual design.
An :class:`InputWarning` says the same of a value read from a file, against the plausible range
of its role (:mod:`crankdyn.io.plausibility`, where the ranges are declared), naming the file,
the key and the value as written.
The checks are pure functions of SI numbers; the analyses attach their warnings to their result
objects (``result.warnings``; an engine's together: :func:`crankdyn.engine.forces.
engine_warnings`), the command line's writer prints them (``crankdyn: warning: ...``) and lists
them in the JSON (a ``warnings`` list), the report lists them in its summary (status ``warn``).

Ranges and their sources
------------------------
- **IMEP** at full load, by engine type. Heywood (1988), *Internal Combustion Engine
  Fundamentals*, sec. 2.7, gives the maximum brake mean effective pressure of production
  engines: naturally aspirated spark-ignition 0.85-1.05 MPa, turbocharged spark-ignition
  1.25-1.7 MPa, naturally aspirated four-stroke diesels 0.7-0.9 MPa, turbocharged four-stroke
  diesels 1.0-1.2 MPa (1.4 MPa aftercooled), large two-stroke diesels about 1.6 MPa;
  IMEP = bmep / eta_m with the mechanical efficiency eta_m of 0.75-0.9 at full load (Heywood
  sec. 2.5). Engines built since reach higher mean pressures (downsized turbocharged petrol
  engines and heavy-duty and medium-speed diesels with bmep of 2.5-3 MPa), so the upper ends
  below allow for them: a value above them is outside anything the engine type reaches in
  service.
- **Peak cylinder pressure**, by engine type: knock limits spark-ignition engines (Heywood
  ch. 9: typically 3-7 MPa naturally aspirated, about twice that turbocharged), the structure
  limits diesels (Heywood ch. 10: 6-10 MPa naturally aspirated; turbocharged engines of today
  up to about 25 MPa).
- **Maximum piston acceleration**: seed 000 sec. 1 ("actual engines": petrol 500-1500 g,
  diesel 200-800 g).
- **Mean piston speed**: seed 002 Table 1 classes (low-speed 5-6 m/s, medium 6-9, high 9-12,
  very high above 12 m/s); the highest production and racing engines reach about 25 m/s
  (Heywood sec. 2.2 gives 8-15 m/s at rated speed for production engines), which bounds the
  top class.
- **Four-bar transmission angle**: the worst min(mu, 180 deg - mu) over the motion should stay
  above about 40 deg for the coupler to drive the output well (Norton, *Design of Machinery*,
  ch. 3, and the transmission angle of ch. 4, eq. 4.32).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from crankdyn.display import quantity

__all__ = [
    "IMEP_RANGES",
    "MEAN_PISTON_SPEED_RANGE",
    "PEAK_PRESSURE_RANGES",
    "PISTON_ACCELERATION_G",
    "TRANSMISSION_ANGLE_MIN",
    "InputWarning",
    "PlausibilityWarning",
    "check_imep",
    "check_mean_piston_speed",
    "check_peak_pressure",
    "check_piston_acceleration",
    "check_transmission_angle",
    "engine_type_text",
    "input_warnings",
    "kinematics_warnings",
    "merge_warnings",
    "pressure_warnings",
]

G = 9.80665
"""Standard gravity (m/s^2), for accelerations in g."""

IMEP_RANGES: dict[tuple[str, str], tuple[float, float]] = {
    ("petrol", "natural"): (0.9e6, 1.8e6),
    ("petrol", "turbocharged"): (1.4e6, 3.3e6),
    ("diesel", "natural"): (0.8e6, 1.4e6),
    ("diesel", "turbocharged"): (1.2e6, 3.8e6),
}
"""(fuel, aspiration): (typical low, upper end) of the IMEP at full load (Pa); module
docstring."""
IMEP_SOURCE = "Heywood 1988 sec. 2.7, bmep / eta_m, raised to current engines"

PEAK_PRESSURE_RANGES: dict[tuple[str, str], tuple[float, float]] = {
    ("petrol", "natural"): (3e6, 10e6),
    ("petrol", "turbocharged"): (5e6, 15e6),
    ("diesel", "natural"): (6e6, 12e6),
    ("diesel", "turbocharged"): (8e6, 25e6),
}
"""(fuel, aspiration): (typical low, upper end) of the peak cylinder pressure (Pa, absolute);
module docstring."""
PEAK_PRESSURE_SOURCE = "Heywood 1988 ch. 9-10, raised to current engines"

PISTON_ACCELERATION_G: dict[str, tuple[float, float]] = {
    "petrol": (500.0, 1500.0),
    "diesel": (200.0, 800.0),
}
"""fuel: (low, high) of the largest piston acceleration (in g = 9.80665 m/s^2), seed 000
sec. 1."""
PISTON_ACCELERATION_SOURCE = "seed 000 sec. 1"

MEAN_PISTON_SPEED_RANGE = (5.0, 25.0)
"""(low, high) of the mean piston speed (m/s): seed 002 Table 1 and the fastest engines."""
MEAN_PISTON_SPEED_SOURCE = "seed 002 Table 1; Heywood 1988 sec. 2.2"

TRANSMISSION_ANGLE_MIN = math.radians(40.0)
"""Smallest good transmission angle of a four-bar (rad), 40 deg (Norton, ch. 3)."""
TRANSMISSION_ANGLE_SOURCE = "Norton, Design of Machinery, ch. 3"


@dataclass(frozen=True)
class PlausibilityWarning:
    """A legal but unlikely input value.

    Parameters
    ----------
    key : str
        Stable identifier of the check (``"imep"``, ``"peak_pressure"``,
        ``"piston_acceleration"``, ``"mean_piston_speed"``, ``"transmission_angle"``).
    quantity : str
        What is checked, for people (``"IMEP"``).
    value : float
        The value (SI, in ``unit``).
    unit : str
        SI unit of ``value``, ``low`` and ``high`` (``"Pa"``, ``"m/s^2"``, ``"m/s"``, ``"rad"``).
    low, high : float
        The typical range (SI, in ``unit``).
    source : str
        Where the range comes from.
    message : str
        One line for people: the value, the range, the engine type.
    """

    key: str
    quantity: str
    value: float
    unit: str
    low: float
    high: float
    source: str
    message: str

    def to_dict(self) -> dict[str, Any]:
        """The warning as a JSON-ready dict.

        Returns
        -------
        dict
            ``check``, ``quantity``, ``value``, ``unit``, ``typical_low``, ``typical_high``,
            ``source``, ``message``: SI values, the unit stated once (``unit``).
        """
        return {
            "check": self.key,
            "quantity": self.quantity,
            "value": self.value,
            "unit": self.unit,
            "typical_low": self.low,
            "typical_high": self.high,
            "source": self.source,
            "message": self.message,
        }

    @property
    def value_text(self) -> str:
        """The value for people: ``"19 MPa"``, ``"2001 g (19620 m/s²)"``, ``"26.4 deg"``."""
        return _value_text(self.value, self.unit)

    @property
    def range_text(self) -> str:
        """The typical range for people: ``"1.2-3.8 MPa"``, ``"200-800 g"``, ``"40-90 deg"``."""
        return _range_text(self.low, self.high, self.unit)


@dataclass(frozen=True)
class InputWarning(PlausibilityWarning):
    """An input value outside the plausible range of its role (a shaft diameter of 180 m: a
    bare number is SI, and 180 mm was meant), found where the file is read
    (:mod:`crankdyn.io.plausibility`) and carried by the domain objects read from the file
    (``input_warnings``) into every result computed from them. A result whose inputs carry
    one cannot show a clean "passed" (:func:`crankdyn.summary.verdict_text`).

    Parameters
    ----------
    key : str
        Unique per input (``"input:"`` and the message), so that each is listed once.
    quantity : str
        The role of the value (``"shaft diameter"``).
    value : float
        The value (SI, in ``unit``).
    unit : str
        Its SI unit.
    low, high : float
        The plausible range of the role (SI, in ``unit``).
    source : str
        Why the range is plausible (the machines it spans).
    message : str
        One line: file, key, value as written, the value, the range, a hint.
    file : str or None
        The file, as named in messages.
    input_key : str
        The key as messages name it (``"[[shaft]] #3 outer_diameter"``, ``"line 4 inertia"``).
    written : object
        The value as written in the file.
    value_shown, range_shown : str
        The value and the range as the message shows them, in the role's display unit
        (``"3342 rpm"``, ``"1-60000 rpm"``).
    """

    file: str | None = None
    input_key: str = ""
    written: Any = None
    value_shown: str = ""
    range_shown: str = ""

    @property
    def value_text(self) -> str:
        """The value for people, in the role's display unit (``"180 m"``, ``"3342 rpm"``)."""
        return self.value_shown or super().value_text

    @property
    def range_text(self) -> str:
        """The plausible range for people, in the role's display unit (``"0.003-3 m"``)."""
        return self.range_shown or super().range_text

    def to_dict(self) -> dict[str, Any]:
        """The warning as a JSON-ready dict.

        Returns
        -------
        dict
            ``check`` (``"input"``), ``file``, ``key``, ``value_as_written``, ``role``,
            ``value``, ``unit``, ``plausible_low``, ``plausible_high`` (SI), ``reason`` and
            ``message``.
        """
        written = self.written
        if not isinstance(written, (str, int, float, bool)) and written is not None:
            written = str(written)
        return {
            "check": "input",
            "file": self.file,
            "key": self.input_key,
            "value_as_written": written,
            "role": self.quantity,
            "value": self.value,
            "unit": self.unit,
            "plausible_low": self.low,
            "plausible_high": self.high,
            "reason": self.source,
            "message": self.message,
        }


def input_warnings(warnings: Any) -> tuple[InputWarning, ...]:
    """The input warnings among ``warnings`` (the others are the analyses' plausibility
    warnings).

    Parameters
    ----------
    warnings : iterable of PlausibilityWarning
        The warnings of a result or a summary.

    Returns
    -------
    tuple of InputWarning
        Those that are :class:`InputWarning`, in order.
    """
    return tuple(w for w in warnings if isinstance(w, InputWarning))


def merge_warnings(*groups: Any) -> tuple[PlausibilityWarning, ...]:
    """The warnings of several groups, each once (by message), in the order first met.

    Parameters
    ----------
    *groups : iterable of PlausibilityWarning
        The groups (an engine's and its model's input warnings, a result's own).

    Returns
    -------
    tuple of PlausibilityWarning
        The warnings, each message once.

    Examples
    --------
    >>> w = PlausibilityWarning("imep", "IMEP", 19e6, "Pa", 1.2e6, 3.8e6, "Heywood", "too high")
    >>> merge_warnings((w,), (w,)) == (w,)
    True
    """
    seen: dict[str, PlausibilityWarning] = {}
    for group in groups:
        for w in group or ():
            seen.setdefault(w.message, w)
    return tuple(seen.values())


def _engine_type(fuel: str | None, aspiration: str | None) -> list[tuple[str, str]]:
    fuels = (fuel,) if fuel else ("petrol", "diesel")
    airs = (aspiration,) if aspiration else ("natural", "turbocharged")
    return [(f, a) for f in fuels for a in airs]


def engine_type_text(fuel: str | None, aspiration: str | None) -> str:
    """The engine type for people.

    Parameters
    ----------
    fuel : str or None
        ``"petrol"``, ``"diesel"`` or None (not stated).
    aspiration : str or None
        ``"natural"``, ``"turbocharged"`` or None (not stated).

    Returns
    -------
    str
        ``"turbocharged diesel engines"``, ``"petrol engines"`` or ``"piston engines"``.

    Examples
    --------
    >>> engine_type_text("diesel", "turbocharged")
    'turbocharged diesel engines'
    """
    air = {"natural": "naturally aspirated ", "turbocharged": "turbocharged "}.get(
        aspiration or "", ""
    )
    return f"{air}{fuel or 'piston'} engines"


def _range(
    table: dict[tuple[str, str], tuple[float, float]], fuel: str | None, aspiration: str | None
) -> tuple[float, float]:
    pairs = [table[t] for t in _engine_type(fuel, aspiration)]
    return min(p[0] for p in pairs), max(p[1] for p in pairs)


def _warning(
    key: str,
    what: str,
    value: float,
    unit: str,
    low: float,
    high: float,
    source: str,
    kind: str,
    hint: str,
) -> PlausibilityWarning:
    """The warning, its message in one pattern: what, value, the typical range of the kind of
    machine, the source, and what to check."""
    side = "below" if value < low else "above"
    return PlausibilityWarning(
        key=key,
        quantity=what,
        value=float(value),
        unit=unit,
        low=float(low),
        high=float(high),
        source=source,
        message=(
            f"{what} {_value_text(value, unit)} is {side} the {_range_text(low, high, unit)} "
            f"typical of {kind} ({source}); {hint}"
        ),
    )


def _range_text(low: float, high: float, unit: str) -> str:
    if unit == "rad":
        return f"{math.degrees(low):.0f}-{math.degrees(high):.0f} deg"
    if unit == "m/s^2":
        return f"{low / G:.0f}-{high / G:.0f} g"
    if unit == "m/s":
        return f"{low:g}-{high:g} m/s"
    return f"{quantity(low, unit, reference=high).split()[0]}-{quantity(high, unit)}"


def _value_text(value: float, unit: str) -> str:
    if unit == "rad":
        return f"{math.degrees(value):.3g} deg"
    if unit == "m/s^2":
        return f"{value / G:.0f} g ({value:.0f} m/s²)"
    if unit == "m/s":
        return f"{value:.3g} m/s"
    return quantity(value, unit)


def check_imep(
    imep: float, fuel: str | None = None, aspiration: str | None = None
) -> list[PlausibilityWarning]:
    """A warning when the IMEP (Pa) is above what engines of the type reach at full load.

    Parameters
    ----------
    imep : float
        Indicated mean effective pressure (Pa).
    fuel, aspiration : str or None
        The engine type (``"petrol"``/``"diesel"``, ``"natural"``/``"turbocharged"``); None
        for not stated (the widest range of the types it may be).

    Returns
    -------
    list of PlausibilityWarning
        Empty, or one warning.

    Examples
    --------
    An IMEP of 19 MPa typed for 1.9 MPa:

    >>> for w in check_imep(19e6, "diesel", "turbocharged"):
    ...     print(w.message)  # doctest: +ELLIPSIS
    IMEP 19 MPa is above the 1.2-3.8 MPa typical of turbocharged diesel engines at full load ...
    """
    low, high = _range(IMEP_RANGES, fuel, aspiration)
    if not math.isfinite(imep) or imep <= high:
        return []
    kind = engine_type_text(fuel, aspiration) + " at full load"
    hint = "check the pressure's unit and the load"
    return [_warning("imep", "IMEP", imep, "Pa", low, high, IMEP_SOURCE, kind, hint)]


def check_peak_pressure(
    peak: float, fuel: str | None = None, aspiration: str | None = None
) -> list[PlausibilityWarning]:
    """A warning when the peak cylinder pressure is above what engines of the type reach.

    Parameters
    ----------
    peak : float
        Peak cylinder pressure (Pa, absolute).
    fuel, aspiration : str or None
        The engine type, as :func:`check_imep`.

    Returns
    -------
    list of PlausibilityWarning
        Empty, or one warning.
    """
    low, high = _range(PEAK_PRESSURE_RANGES, fuel, aspiration)
    if not math.isfinite(peak) or peak <= high:
        return []
    kind = engine_type_text(fuel, aspiration)
    hint = "check the pressure's unit"
    what = "peak cylinder pressure"
    return [
        _warning("peak_pressure", what, peak, "Pa", low, high, PEAK_PRESSURE_SOURCE, kind, hint)
    ]


def check_piston_acceleration(
    max_acceleration: float, fuel: str | None = None
) -> list[PlausibilityWarning]:
    """A warning when the largest piston acceleration exceeds seed 000's range for the fuel.

    Seed 000 sec. 1: petrol 500-1500 g, diesel 200-800 g; the widest, 200-1500 g, when the fuel
    is not stated.

    Parameters
    ----------
    max_acceleration : float
        The largest piston acceleration (m/s^2; its magnitude is checked).
    fuel : str or None
        ``"petrol"``, ``"diesel"`` or None (not stated).

    Returns
    -------
    list of PlausibilityWarning
        Empty, or one warning.
    """
    fuels = (fuel,) if fuel else tuple(PISTON_ACCELERATION_G)
    low = min(PISTON_ACCELERATION_G[f][0] for f in fuels) * G
    high = max(PISTON_ACCELERATION_G[f][1] for f in fuels) * G
    a = abs(max_acceleration)
    if not math.isfinite(a) or a <= high:
        return []
    kind = f"{fuel} engines" if fuel else "petrol and diesel engines"
    return [
        _warning(
            "piston_acceleration",
            "max piston acceleration",
            a,
            "m/s^2",
            low,
            high,
            PISTON_ACCELERATION_SOURCE,
            kind,
            "check the speed and the stroke",
        )
    ]


def check_mean_piston_speed(mean_piston_speed: float) -> list[PlausibilityWarning]:
    """A warning when the mean piston speed is above the fastest engines' (about 25 m/s).

    The fastest class of seed 002 Table 1 (above 12 m/s), bounded by what production and
    racing engines reach (Heywood 1988 sec. 2.2).

    Parameters
    ----------
    mean_piston_speed : float
        c_m = S n / 30 (m/s).

    Returns
    -------
    list of PlausibilityWarning
        Empty, or one warning.
    """
    low, high = MEAN_PISTON_SPEED_RANGE
    if not math.isfinite(mean_piston_speed) or mean_piston_speed <= high:
        return []
    return [
        _warning(
            "mean_piston_speed",
            "mean piston speed",
            mean_piston_speed,
            "m/s",
            low,
            high,
            MEAN_PISTON_SPEED_SOURCE,
            "piston engines",
            "check the speed (rpm) and the stroke",
        )
    ]


def check_transmission_angle(worst: float) -> list[PlausibilityWarning]:
    """A warning when a four-bar's worst transmission angle is below 40 deg (Norton, ch. 3).

    Parameters
    ----------
    worst : float
        The worst transmission angle min(mu, 180 deg - mu) over the motion (rad).

    Returns
    -------
    list of PlausibilityWarning
        Empty, or one warning.
    """
    if not math.isfinite(worst) or worst >= TRANSMISSION_ANGLE_MIN:
        return []
    return [
        _warning(
            "transmission_angle",
            "worst transmission angle",
            worst,
            "rad",
            TRANSMISSION_ANGLE_MIN,
            math.pi / 2.0,
            TRANSMISSION_ANGLE_SOURCE,
            "well-designed linkages",
            "the coupler drives the output poorly there (large joint forces, friction may lock it)",
        )
    ]


def kinematics_warnings(
    mean_piston_speed: float, max_acceleration: float, fuel: str | None = None
) -> tuple[PlausibilityWarning, ...]:
    """The warnings of an engine's piston motion.

    Parameters
    ----------
    mean_piston_speed : float
        c_m (m/s), :func:`check_mean_piston_speed`.
    max_acceleration : float
        The largest piston acceleration (m/s^2), :func:`check_piston_acceleration`.
    fuel : str or None
        ``"petrol"``, ``"diesel"`` or None.

    Returns
    -------
    tuple of PlausibilityWarning
        The warnings of both checks (none when both values are typical).
    """
    return (
        *check_mean_piston_speed(mean_piston_speed),
        *check_piston_acceleration(max_acceleration, fuel),
    )


def pressure_warnings(
    imep: float, peak_pressure: float, fuel: str | None = None, aspiration: str | None = None
) -> tuple[PlausibilityWarning, ...]:
    """The warnings of a cylinder pressure.

    Parameters
    ----------
    imep : float
        Indicated mean effective pressure (Pa), :func:`check_imep`.
    peak_pressure : float
        Peak cylinder pressure (Pa, absolute), :func:`check_peak_pressure`.
    fuel, aspiration : str or None
        The engine type, as :func:`check_imep`.

    Returns
    -------
    tuple of PlausibilityWarning
        The warnings of both checks.
    """
    return (
        *check_imep(imep, fuel, aspiration),
        *check_peak_pressure(peak_pressure, fuel, aspiration),
    )
