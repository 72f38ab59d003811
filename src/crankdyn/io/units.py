"""Unit parsing at the boundary (the only module that imports pint).

Files and command-line options accept a quantity as a unit string (``"76 mm"``, ``"4900 rpm"``,
``"0.167 kg*m^2"``) or as a bare number. A bare number is taken in SI (m, kg, s, rad, N, Pa...)
unless the caller names a different default unit, as the command line does for options whose
metavar names a unit (``--speed RPM``, ``--step DEG``). A bare rotational speed is the exception:
on the command line it is rpm, so in a file (no default unit) it would mean rad/s silently;
:func:`parse_quantity` refuses it (:data:`BARE_SPEED`) unless it is 0. Everything below this
layer works on SI floats.

Notes on angles: pint treats the radian as dimensionless, so a bare 1/time unit cannot tell
"rad/s" from "rev/s". crankdyn resolves it by kind: for a rotational ``speed`` a pure frequency
(``Hz``, ``1/s``) means revolutions per second; for a ``frequency`` an angular unit (``rpm``,
``rad/s``) is turned into cycles per second.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from functools import lru_cache
from typing import TYPE_CHECKING, Any

from crankdyn.errors import InputError

if TYPE_CHECKING:  # pint is imported on first use only (start-up time)
    import pint

__all__ = [
    "BARE_SPEED",
    "COMMON_UNITS",
    "KINDS",
    "Kind",
    "convert_magnitude",
    "parse_quantity",
    "registry",
    "split_quantity",
]


@dataclass(frozen=True)
class Kind:
    """A physical kind of quantity: its pint dimensionality, SI unit and an example.

    Parameters
    ----------
    name
        The kind in words with its article (``"a length"``), used in messages.
    dimensionality
        pint dimensionality expression (``"[length]"``); ``""`` for a dimensionless kind
        (angles, ratios).
    si_unit
        The SI unit of the values crankdyn works in (``"m"``, ``"rad/s"``, ``"N*m/rad"``).
    example
        A quantity of this kind as a user writes it (``"76 mm"``), quoted in messages.
    per_angle
        For the kinds pint cannot tell apart because it counts the radian as dimensionless:
        True when the unit must be per angle (a torsional stiffness in N*m/rad, a torsional
        damping in N*m*s/rad), False when it must not be (a torque in N*m, an energy in J);
        None when the angle is not checked.
    """

    name: str  # "a length", used in messages
    dimensionality: str  # pint dimensionality expression, e.g. "[length]"; "" = dimensionless
    si_unit: str  # unit of the SI value crankdyn works in
    example: str  # "76 mm"
    per_angle: bool | None = None  # the unit per radian (True), without an angle (False)


_T = "[time]"
KINDS: dict[str, Kind] = {
    "length": Kind("a length", "[length]", "m", "76 mm"),
    "mass": Kind("a mass", "[mass]", "kg", "0.45 kg"),
    "angle": Kind("an angle", "", "rad", "180 deg"),
    "speed": Kind("a rotational speed", f"1/{_T}", "rad/s", "4900 rpm"),
    "frequency": Kind("a frequency", f"1/{_T}", "Hz", "120 Hz"),
    "time": Kind("a time", _T, "s", "0.1 s"),
    "inertia": Kind("a moment of inertia", "[mass]*[length]**2", "kg*m^2", "0.167 kg*m^2"),
    "torsional_stiffness": Kind(
        "a torsional stiffness", f"[mass]*[length]**2/{_T}**2", "N*m/rad", "160 kN*m/rad", True
    ),
    "torsional_damping": Kind(
        "a torsional damping", f"[mass]*[length]**2/{_T}", "N*m*s/rad", "70 N*m*s/rad", True
    ),
    "stiffness": Kind("a linear stiffness", f"[mass]/{_T}**2", "N/m", "2 MN/m"),
    "damping": Kind("a linear damping", f"[mass]/{_T}", "N*s/m", "100 N*s/m"),
    "pressure": Kind("a pressure", f"[mass]/[length]/{_T}**2", "Pa", "15 MPa"),
    "force": Kind("a force", f"[mass]*[length]/{_T}**2", "N", "1200 N"),
    "torque": Kind("a torque", f"[mass]*[length]**2/{_T}**2", "N*m", "250 N*m", False),
    "energy": Kind("an energy", f"[mass]*[length]**2/{_T}**2", "J", "1.2 kJ", False),
    "power": Kind("a power", f"[mass]*[length]**2/{_T}**3", "W", "95 kW"),
    "density": Kind("a density", "[mass]/[length]**3", "kg/m^3", "7850 kg/m^3"),
    "velocity": Kind("a velocity", f"[length]/{_T}", "m/s", "12 m/s"),
    "acceleration": Kind("an acceleration", f"[length]/{_T}**2", "m/s^2", "9.81 m/s^2"),
    "angular_acceleration": Kind("an angular acceleration", f"1/{_T}**2", "rad/s^2", "100 rad/s^2"),
    "area": Kind("an area", "[length]**2", "m^2", "45 cm^2"),
    "volume": Kind("a volume", "[length]**3", "m^3", "0.5 L"),
    "ratio": Kind("a ratio", "", "", "0.26"),
}
# kinds used to name a wrong dimension in messages ("got a mass"), first match wins
_DESCRIBE_ORDER = (
    "length",
    "mass",
    "speed",
    "time",
    "inertia",
    "torque",
    "torsional_stiffness",
    "torsional_damping",
    "stiffness",
    "damping",
    "pressure",
    "force",
    "power",
    "density",
    "velocity",
    "acceleration",
    "angular_acceleration",
    "area",
    "volume",
)


BARE_SPEED = "give rpm or rad/s (a bare speed is rpm on the command line)"
"""Why a bare number for a rotational speed is refused in a file: the command line reads a bare
speed as rpm (``--speed 1500``), a file would read it as SI (rad/s), so the same text would
mean two speeds a factor 9.55 apart. One vocabulary: bare is rpm where a unit is implied
(options), and a file names its unit."""

SI_RANGE = (1e-12, 1e12)
"""Magnitudes crankdyn accepts for a quantity in SI units (besides exactly 0): from 1e-12 to 1e12
covers every engineering value (a marine shaft's 1e10 N*m/rad, a steel's 2e11 Pa, a gear's
1e-6 kg*m^2); beyond it the input is a unit mistake, and products of such values would leave
the range of floating point."""


def check_si_range(value: float) -> bool:
    """Whether a finite SI value lies in SI_RANGE (or is 0).

    Parameters
    ----------
    value
        A value in SI units (any kind).

    Returns
    -------
    bool
        True when its magnitude is 0 or lies in :data:`SI_RANGE`.

    Examples
    --------
    >>> check_si_range(2.1e11), check_si_range(0.0), check_si_range(1e-15)
    (True, True, False)
    """
    magnitude = abs(value)
    return magnitude == 0.0 or SI_RANGE[0] <= magnitude <= SI_RANGE[1]


_NUMBER = re.compile(r"^\s*([-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")
_UNIT_TOKEN = re.compile(r"[A-Za-zµμΩ°%_]+|\d+(?:\.\d+)?|\*\*|[\^*/()\-\s.]")
_SUPERSCRIPTS = str.maketrans({"²": "^2", "³": "^3", "·": "*", "⋅": "*", "−": "-"})
_MAX_UNIT_CHARS = 40


@lru_cache(maxsize=1)
def registry() -> pint.UnitRegistry:
    """The shared pint registry (created on first use; creating it takes a fraction of a second).

    Returns
    -------
    pint.UnitRegistry
        pint's default registry with ``r_per_min`` (revolutions per minute) defined.
    """
    import pint

    ureg: pint.UnitRegistry = pint.UnitRegistry()
    ureg.define("r_per_min = revolution / minute")
    return ureg


@lru_cache(maxsize=64)
def _dimensionality(expr: str) -> Any:
    ureg = registry()
    if not expr:
        return ureg.dimensionless.dimensionality
    return ureg.get_dimensionality(expr)


def _describe_dimension(dim: Any, radians: int = 0) -> str:
    """The kind a dimension (and a power of the radian in the unit) is, for messages."""
    if not dim:
        return "a dimensionless number"
    for key in _DESCRIBE_ORDER:
        kind = KINDS[key]
        if kind.per_angle is not None and kind.per_angle != (radians == -1):
            continue
        if _dimensionality(kind.dimensionality) == dim:
            return kind.name
    return f"a quantity of dimension {dim}"


def _radian_power(units: Any) -> int:
    """The power of the radian in a pint unit's root units (-1 for N*m/rad and N*m/deg, 0 for
    N*m, 1 for rpm): pint counts the radian as dimensionless, so the dimension alone cannot tell
    a torsional stiffness from a torque."""
    root = registry().get_root_units(units)[1]
    power: Any = dict(root._units).get("radian", 0)  # a number of pint's UnitsContainer
    return int(power)


def _check_unit_text(text: str) -> bool:
    """Accept only plain unit expressions: unit names, * / ^ ** ( ) and small literal exponents."""
    if len(text) > _MAX_UNIT_CHARS:
        return False
    tokens = _UNIT_TOKEN.findall(text)
    if "".join(tokens) != text:
        return False
    previous = ""
    for i, tok in enumerate(tokens):
        if tok[0].isdigit():
            after_power = previous in ("^", "**") or (
                previous == "-" and i >= 2 and tokens[i - 2] in ("^", "**")
            )
            one_over = tok == "1" and i + 1 < len(tokens) and tokens[i + 1].strip() in ("/", "")
            if after_power:
                if float(tok) > 12:
                    return False
            elif not one_over:
                return False
        if not tok.isspace():
            previous = tok
    return True


COMMON_UNITS: dict[str, tuple[float, tuple[str, ...]]] = {
    "m": (1.0, ("length",)),
    "mm": (0.001, ("length",)),
    "cm": (0.01, ("length",)),
    "um": (1e-06, ("length",)),
    "µm": (1e-06, ("length",)),
    "km": (1000.0, ("length",)),
    "in": (0.0254, ("length",)),
    "ft": (0.30479999999999996, ("length",)),
    "kg": (1.0, ("mass",)),
    "g": (0.001, ("mass",)),
    "t": (1000.0, ("mass",)),
    "s": (1.0, ("time",)),
    "ms": (0.001, ("time",)),
    "min": (60.0, ("time",)),
    "h": (3600.0, ("time",)),
    "rpm": (0.10471975511965977, ("speed", "frequency")),
    "rad/s": (1.0, ("speed", "frequency")),
    "Hz": (1.0, ("speed", "frequency")),
    "kHz": (1000.0, ("speed", "frequency")),
    "1/s": (1.0, ("speed", "frequency")),
    "deg": (0.017453292519943295, ("angle", "ratio")),
    "rad": (1.0, ("angle", "ratio")),
    "°": (0.017453292519943295, ("angle", "ratio")),
    "N": (1.0, ("force",)),
    "kN": (1000.0, ("force",)),
    "MN": (1000000.0, ("force",)),
    "N*m": (1.0, ("torque", "energy")),
    "kN*m": (1000.0, ("torque", "energy")),
    "MN*m": (1000000.0, ("torque", "energy")),
    "Pa": (1.0, ("pressure",)),
    "kPa": (1000.0, ("pressure",)),
    "MPa": (1000000.0, ("pressure",)),
    "GPa": (1000000000.0, ("pressure",)),
    "bar": (100000.0, ("pressure",)),
    "kg*m^2": (1.0, ("inertia",)),
    "g*cm^2": (1.0000000000000001e-07, ("inertia",)),
    "kg*cm^2": (0.0001, ("inertia",)),
    "kg*mm^2": (1e-06, ("inertia",)),
    "t*m^2": (1000.0, ("inertia",)),
    "N*m/rad": (1.0, ("torsional_stiffness",)),
    "kN*m/rad": (1000.0, ("torsional_stiffness",)),
    "MN*m/rad": (1000000.0, ("torsional_stiffness",)),
    "N*m/deg": (57.29577951308232, ("torsional_stiffness",)),
    "kN*m/deg": (57295.77951308232, ("torsional_stiffness",)),
    "N*m*s/rad": (1.0, ("torsional_damping",)),
    "kN*m*s/rad": (1000.0, ("torsional_damping",)),
    "N*m*s/deg": (57.29577951308232, ("torsional_damping",)),
    "N/m": (1.0, ("stiffness",)),
    "kN/m": (1000.0, ("stiffness",)),
    "MN/m": (1000000.0, ("stiffness",)),
    "N/mm": (1000.0, ("stiffness",)),
    "kN/mm": (1000000.0, ("stiffness",)),
    "N*s/m": (1.0, ("damping",)),
    "kN*s/m": (1000.0, ("damping",)),
    "J": (1.0, ("torque", "energy")),
    "kJ": (1000.0, ("torque", "energy")),
    "W": (1.0, ("power",)),
    "kW": (1000.0, ("power",)),
    "MW": (1000000.0, ("power",)),
    "hp": (745.6998715822701, ("power",)),
    "kg/m^3": (1.0, ("density",)),
    "g/cm^3": (999.9999999999999, ("density",)),
    "m/s": (1.0, ("velocity",)),
    "km/h": (0.2777777777777778, ("velocity",)),
    "m/s^2": (1.0, ("acceleration",)),
    "rad/s^2": (1.0, ("angular_acceleration",)),
    "m^2": (1.0, ("area",)),
    "cm^2": (0.0001, ("area",)),
    "mm^2": (1e-06, ("area",)),
    "m^3": (1.0, ("volume",)),
    "cm^3": (1.0000000000000002e-06, ("volume",)),
    "mm^3": (1e-09, ("volume",)),
    "L": (0.0010000000000000002, ("volume",)),
    "l": (0.0010000000000000002, ("volume",)),
    "cc": (1.0000000000000002e-06, ("volume",)),
    "%": (0.01, ("angle", "ratio")),
}
"""Units written as here convert without importing pint (which, with its registry, takes most of a
second of a command's start-up): unit text -> (the magnitude of one such unit in the SI unit of
its kinds, or in rad/s or Hz for a speed or a frequency; the kinds of :data:`KINDS` it measures).
Computed with pint and held to it by ``tests/io/test_units.py`` (which shows how to extend it)."""
_ANGULAR = frozenset({"rpm", "rad/s"})  # the speed units above whose root unit holds a radian


def _to_si(kind_key: str, angular: bool, x: float) -> float:
    """The SI value of a kind from ``x``, the quantity's magnitude in rad/s (``angular``) or Hz
    for a speed or a frequency, in the kind's SI unit otherwise (module docstring)."""
    if kind_key == "speed":
        # a pure frequency (Hz, 1/s) for a rotational speed means revolutions per second
        return x if angular else x * 2 * math.pi
    if kind_key == "frequency":
        # an angular unit (rpm, rad/s) for a frequency is turned into cycles per second
        return x / (2 * math.pi) if angular else x
    return float(x)


def _unit_value(magnitude: float, unit_text: str, kind_key: str) -> float:
    """Convert magnitude * unit to the SI value of kind; raise ValueError with a reason.

    The units of :data:`COMMON_UNITS` convert without pint (the same arithmetic, so the same
    number); any other unit, and any unit of the wrong dimension, goes through pint."""
    common = COMMON_UNITS.get(unit_text)
    if common is not None and kind_key in common[1]:
        return _to_si(kind_key, unit_text in _ANGULAR, magnitude * common[0])
    ureg = registry()
    kind = KINDS[kind_key]
    try:
        units = ureg.parse_units(unit_text)
    except Exception as exc:  # pint raises several types (UndefinedUnitError, syntax errors)
        raise ValueError(f"unknown unit {unit_text!r}") from exc
    expected = _dimensionality(kind.dimensionality)
    got = units.dimensionality
    radians = _radian_power(units) if kind.per_angle is not None or got != expected else 0
    if got != expected or (kind.per_angle is not None and kind.per_angle != (radians == -1)):
        raise ValueError(
            f'expected {kind.name} (e.g. "{kind.example}"), got {_describe_dimension(got, radians)}'
        )
    angular = "radian" in str(ureg.get_root_units(units)[1])
    quantity = ureg.Quantity(magnitude, units)
    if kind_key in ("speed", "frequency"):
        return _to_si(kind_key, angular, quantity.to("rad/s" if angular else "Hz").magnitude)
    return float(quantity.to(kind.si_unit or "dimensionless").magnitude)


def parse_quantity(
    value: object,
    kind: str,
    *,
    key: str | None = None,
    file: str | None = None,
    default_unit: str | None = None,
) -> float:
    """Parse a user quantity into an SI float.

    Parameters
    ----------
    value
        A number (taken in ``default_unit``, or SI when that is None; a rotational speed has
        no SI default: a bare speed other than 0 is refused, :data:`BARE_SPEED`) or a string
        such as ``"76 mm"``; a string holding only a number is treated like a number.
    kind
        A key of :data:`KINDS` (``"length"``, ``"mass"``, ``"angle"``, ``"speed"``...).
    key, file
        Where the value came from, for the error message.
    default_unit
        Unit of bare numbers (e.g. ``"rpm"`` for a ``--speed`` option); SI when None.

    Returns
    -------
    float
        The value in the SI unit of ``kind`` (``KINDS[kind].si_unit``).

    Raises
    ------
    InputError
        For a value that is not a number or quantity, has an unknown unit, the wrong dimension
        (a torque for a torsional stiffness among them), is not finite, lies outside
        :data:`SI_RANGE` in SI units, or is a bare speed without ``default_unit``; it names
        ``file``, ``key`` and ``value``.
    KeyError
        For a ``kind`` not in :data:`KINDS` (a programming error, not a user's).

    Examples
    --------
    >>> parse_quantity("76 mm", "length")
    0.076
    >>> round(parse_quantity("4900 rpm", "speed"), 4)
    513.1268
    >>> parse_quantity(180, "angle", default_unit="deg") == math.pi
    True
    >>> parse_quantity("12 kg", "length", key="bore", file="e.toml")
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: e.toml: bore = "12 kg": expected a length (e.g. "76 mm"), got a mass
    >>> parse_quantity("350", "speed", key="speed_range", file="m.toml")
    Traceback (most recent call last):
    ...
    crankdyn.errors.InputError: m.toml: speed_range = "350": give rpm or rad/s (a bare speed is \
rpm on the command line)
    """
    if kind not in KINDS:
        raise KeyError(f"unknown quantity kind {kind!r}")
    spec = KINDS[kind]

    def fail(message: str) -> InputError:
        return InputError(message, file=file, key=key, value=value)

    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise fail(f'expected {spec.name} such as "{spec.example}"')
    if isinstance(value, (int, float)):
        magnitude, unit_text = float(value), ""
    else:
        text = value.translate(_SUPERSCRIPTS)
        match = _NUMBER.match(text)
        if not match:
            raise fail(
                f'expected a number with a unit, such as "{spec.example}"'
                if text.strip()
                else f'empty value; expected {spec.name} such as "{spec.example}"'
            )
        magnitude, unit_text = float(match.group(1)), match.group(2)
    if not math.isfinite(magnitude):
        raise fail("the value is not finite")
    if not unit_text:
        if default_unit is None:
            if kind == "speed" and magnitude != 0.0:
                raise fail(BARE_SPEED)
            if not check_si_range(magnitude):
                raise fail(
                    f"{magnitude:.3g} {spec.si_unit} lies outside the range crankdyn computes "
                    "with (1e-12 to 1e12 in SI units); check the unit"
                )
            return magnitude
        unit_text = default_unit
    elif not _check_unit_text(unit_text):
        raise fail(f"unknown unit {unit_text!r}")
    try:
        result = _unit_value(magnitude, unit_text, kind)
    except ValueError as exc:
        raise fail(str(exc)) from None
    if not math.isfinite(result):
        raise fail("the value is not finite in SI units")
    if not check_si_range(result):
        raise fail(
            f"{result:.3g} {spec.si_unit} lies outside the range crankdyn computes with "
            "(1e-12 to 1e12 in SI units); check the unit"
        )
    return result


def split_quantity(
    value: object, *, key: str | None = None, file: str | None = None
) -> tuple[float, str] | None:
    """A number, or a number with a unit of any dimension, as ``(magnitude, unit_text)``.

    ``unit_text`` is ``""`` for a bare number (or a string holding only a number). Used where
    the kind of a quantity is not known in advance (the parameters of a study file, whose
    values are checked later by the file they are written into). Returns None for a value that
    is not a number or a number-with-unit string (a bool, a list, other text).

    Parameters
    ----------
    value
        A number or a string such as ``"76 mm"``, as read from a file.
    key, file
        Where the value came from, for the error message.

    Returns
    -------
    tuple of (float, str), or None
        The magnitude (in ``unit_text``, not converted) and the unit as written; None for a
        value that is neither a number nor a number with a unit.

    Raises
    ------
    InputError
        For a number-with-unit string whose unit is not known, or a non-finite number, naming
        ``file``, ``key`` and ``value``.

    Examples
    --------
    >>> split_quantity("76 mm"), split_quantity(3), split_quantity("fast")
    ((76.0, 'mm'), (3.0, ''), None)
    """
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        return None
    if isinstance(value, (int, float)):
        magnitude, unit_text = float(value), ""
    else:
        match = _NUMBER.match(value.translate(_SUPERSCRIPTS))
        if not match:
            return None
        magnitude, unit_text = float(match.group(1)), match.group(2)
    if not math.isfinite(magnitude):
        raise InputError("the value is not finite", file=file, key=key, value=value)
    if unit_text:
        if not _check_unit_text(unit_text):
            raise InputError(f"unknown unit {unit_text!r}", file=file, key=key, value=value)
        try:
            if unit_text not in COMMON_UNITS:
                registry().parse_units(unit_text)
        except Exception:  # pint raises several types (UndefinedUnitError, syntax errors)
            raise InputError(
                f"unknown unit {unit_text!r}", file=file, key=key, value=value
            ) from None
    return magnitude, unit_text


def convert_magnitude(
    magnitude: float,
    from_unit: str,
    to_unit: str,
    *,
    key: str | None = None,
    file: str | None = None,
    value: object = None,
) -> float:
    """``magnitude`` in ``from_unit`` expressed in ``to_unit`` (units as accepted by
    :func:`split_quantity`; ``""`` for a bare number, which converts only to itself).

    Units of the same dimension convert; an angular unit (rpm, rad/s, deg) and a non-angular
    one (Hz, 1/s, a bare ratio) do not, because crankdyn reads a bare frequency as revolutions
    per second for a speed but pint as radians per second (module docstring).

    Parameters
    ----------
    magnitude
        The number, in ``from_unit``.
    from_unit
        Its unit as written (``"mm"``; ``""`` for a bare number).
    to_unit
        The unit wanted (``""`` for a bare number).
    key, file
        Where the value came from, for the error message.
    value
        The value as the user wrote it, for the message (default: magnitude and unit).

    Returns
    -------
    float
        The magnitude in ``to_unit``.

    Raises
    ------
    InputError
        When the units differ in dimension or in being angular, or only one of them is bare;
        it names ``file``, ``key`` and ``value``.

    Examples
    --------
    >>> convert_magnitude(1500, "rpm", "rad/s") * 60 / (2 * math.pi)
    1500.0
    >>> convert_magnitude(25.4, "mm", "in")
    1.0
    """
    if from_unit == to_unit:
        return float(magnitude)

    def fail(reason: str) -> InputError:
        shown = value if value is not None else f"{magnitude:g} {from_unit}".strip()
        return InputError(reason, file=file, key=key, value=shown)

    if not from_unit or not to_unit:
        raise fail(
            f"give every value with a unit, as {to_unit!r}"
            if to_unit
            else "give every value as a bare number, as the first one"
        )
    ureg = registry()
    a, b = ureg.parse_units(from_unit), ureg.parse_units(to_unit)
    angular_a = "radian" in str(ureg.get_root_units(a)[1])
    angular_b = "radian" in str(ureg.get_root_units(b)[1])
    if a.dimensionality != b.dimensionality or angular_a != angular_b:
        raise fail(f"{from_unit!r} does not convert to {to_unit!r}, the unit of the first value")
    return float(ureg.Quantity(magnitude, a).to(b).magnitude)
