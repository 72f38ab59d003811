"""Plausible ranges of input values by their role: the one table the file readers check every
number against (:data:`ROLES`), and the check of a speed range against the rated speed.

A bare number in a file is SI (docs/engine-file.md), so ``outer_diameter = 180`` is a 180 m
shaft: legal, computable, and wrong by a factor of 1000. Every quantity and every number a file
gives (:class:`crankdyn.io.schema.Table`, and the cells of the mass-elastic CSV) is held to the
range of its role here; outside it the reader records a
:class:`crankdyn.plausibility.InputWarning` naming the file, the key, the value as written and
the range (``outer_diameter = 180: 180 m is outside the 0.003-3 m of shaft diameters ...; did
you mean 180 mm?``). The warnings travel with the domain objects (``input_warnings`` of
:class:`~crankdyn.engine.model.Engine` and :class:`~crankdyn.torsion.model.TorsionModel`) into
every result the session computes from them, and a verdict whose inputs carry one reads
"passed, with N input warnings" (:func:`crankdyn.summary.verdict_text`).

The ranges are wide on purpose: they span the machines crankdyn is for, from laboratory test
rigs and model engines to the largest two-stroke marine engines and their propellers, so that a
warning means a unit slip or a typo (a factor of 10 to 1000), not an unusual design. Each row
says why (the machines at its two ends). The table is printed in the input pages
(docs/engine-file.md, docs/torsion-file.md) by :func:`roles_markdown`, and
``tests/io/test_plausibility_docs.py`` holds the pages to it.

Sources of the ends (public data): the largest two-stroke engines (bore 0.98 m, stroke about
3.2 m, cylinder pitch about 1.75 m, crank journals about 1 m, speeds down to about 60 rpm;
makers' project guides of the 98 cm bore class); propellers of the largest ships (about 100 t,
inertias with entrained water to about 1e6 kg m^2); model engines and test rigs (bores and
shafts of a few millimetres); material data of steels, cast irons, aluminium and titanium
(shear moduli 26-80 GPa, tensile strengths 200-2000 MPa); rubber couplings (relative damping
psi 0.4-2, DIN 740-2 catalogues: loss factor psi / 2 pi up to about 0.3).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from crankdyn.constants import RPM
from crankdyn.display import number
from crankdyn.io.units import COMMON_UNITS, KINDS
from crankdyn.plausibility import InputWarning

__all__ = [
    "RATED_SPEED_RANGE",
    "ROLES",
    "Role",
    "check_input",
    "check_speed_range",
    "role_of",
    "roles_markdown",
    "section_of",
]


@dataclass(frozen=True)
class Role:
    """What a value is for, and the range such values take.

    Parameters
    ----------
    name : str
        The role for people, plural (``"shaft diameters"``).
    kind : str
        The kind of quantity (a key of :data:`crankdyn.io.units.KINDS`; ``"ratio"`` for the
        plain numbers of :meth:`crankdyn.io.schema.Table.number`).
    keys : tuple of str
        The keys (TOML keys, CSV columns) the role applies to; empty: every key of the kind
        that no other role names (the kind's fallback).
    low, high : float
        The plausible range of the magnitude (SI, in the kind's unit); 0 is never checked
        (it means "none" wherever a file accepts it).
    reason : str
        Why: the machines at the two ends.
    sections : tuple of str
        The tables the role applies in (the last part of the section's name: ``"shaft"`` for
        ``[[torsion.shaft]]``); empty: every table.
    shown : tuple of (str, float)
        The display unit and the factor from SI to it (``("rpm", RPM)``); default the SI unit.
    hints : tuple of str
        Units tried for "did you mean" (the number as written, in each unit, lying in the
        range); empty: the kind's (:data:`HINTS`).
    hint : str
        A fixed hint instead (e.g. a loss factor given as the relative damping psi).
    """

    name: str
    kind: str
    keys: tuple[str, ...]
    low: float
    high: float
    reason: str
    sections: tuple[str, ...] = ()
    shown: tuple[str, float] | None = None
    hints: tuple[str, ...] = ()
    hint: str = ""

    def unit(self) -> tuple[str, float]:
        """The display unit and the factor from SI to it.

        Returns
        -------
        tuple of (str, float)
            E.g. ``("m", 1.0)``, ``("rpm", 9.549...)``, ``("MPa", 1e-6)``.
        """
        if self.shown is not None:
            return self.shown
        return KINDS[self.kind].si_unit if self.kind in KINDS else "", 1.0

    def range_text(self) -> str:
        """The range in the display unit: ``"0.003-3 m"``, ``"1e-7 to 1e7 kg*m^2"``.

        Returns
        -------
        str
            The two ends and the unit.
        """
        unit, scale = self.unit()
        low, high = _g(self.low * scale), _g(self.high * scale)
        sep = " to " if "e" in low + high else "-"
        return f"{low}{sep}{high} {unit}".rstrip()

    def holds(self, value: float) -> bool:
        """Whether a value (SI) lies in the range (its magnitude; 0 always does).

        Parameters
        ----------
        value : float
            The value (SI).

        Returns
        -------
        bool
            True inside the range or for 0.
        """
        magnitude = abs(value)
        return magnitude == 0.0 or self.low <= magnitude <= self.high


def _g(x: float) -> str:
    """About three significant digits as people write them (``45000``, ``0.003``), powers of
    ten for very large and very small magnitudes, without padding (``1e7``, ``2e-5``)."""
    text = f"{x:.3g}"
    if "e" not in text or 1e-4 <= abs(float(text)) < 1e6:
        return number(float(text), 3)
    mantissa, exponent = text.split("e")
    return f"{mantissa}e{int(exponent)}"


HINTS: dict[str, tuple[str, ...]] = {
    "length": ("mm", "cm", "m"),
    "mass": ("g", "kg", "t"),
    "inertia": ("kg*m^2", "kg*cm^2", "t*m^2"),
    "torsional_stiffness": ("N*m/rad", "kN*m/rad", "MN*m/rad"),
    "torsional_damping": ("N*m*s/rad", "kN*m*s/rad"),
    "stiffness": ("N/mm", "kN/mm", "MN/m"),
    "pressure": ("MPa", "bar", "kPa", "GPa", "Pa"),
    "torque": ("N*m", "kN*m", "MN*m"),
    "power": ("W", "kW", "MW"),
    "force": ("N", "kN", "MN"),
    "angle": ("deg", "rad"),
    "time": ("ms", "s"),
    "density": ("kg/m^3", "g/cm^3"),
    "speed": ("rpm", "rad/s"),
}
"""The units a "did you mean" tries for a kind, in order (units of
:data:`crankdyn.io.units.COMMON_UNITS`)."""

_M = 1e-3  # mm in m
_MPA = ("MPa", 1e-6)
_GPA = ("GPa", 1e-9)
_LARGEST = "the largest two-stroke engines"

ROLES: tuple[Role, ...] = (
    # ---- lengths ---------------------------------------------------------------------------
    Role(
        "flywheel diameters", "length", ("max_diameter", "inner_diameter"), 0.02, 6.0,
        "a small engine's flywheel to the flywheels of " + _LARGEST, sections=("flywheel",),
    ),
    Role(
        "shaft diameters", "length",
        ("outer_diameter", "inner_diameter", "journal_diameter", "pin_diameter",
         "web_outer_diameter", "journal_bore", "pin_bore"),
        3 * _M, 3.0, "the few-millimetre shafts of test rigs to the crank journals of "
        + _LARGEST + " (about 1 m)",
    ),
    Role(
        "shaft diameters", "length", ("diameter",), 3 * _M, 3.0,
        "the few-millimetre shafts of test rigs to the crank journals of " + _LARGEST,
        sections=("crankshaft", "shrink_fit"),
    ),
    Role(
        "cylinder bores", "length", ("bore",), 5 * _M, 1.2,
        "model engines (a few mm) to " + _LARGEST + " (0.98 m)",
    ),
    Role(
        "strokes", "length", ("stroke",), 5 * _M, 4.0,
        "model engines to " + _LARGEST + " (about 3.2 m)",
    ),
    Role(
        "crank radii", "length", ("crank_radius",), 2.5 * _M, 2.0,
        "half the strokes: model engines to " + _LARGEST,
    ),
    Role(
        "connecting-rod lengths", "length", ("rod_length",), 10 * _M, 10.0,
        "model engines to " + _LARGEST + " (rods of about 3 m)",
    ),
    Role(
        "cylinder pitches", "length", ("pitch",), 10 * _M, 3.0,
        "model engines to " + _LARGEST + " (about 1.75 m)", sections=("cylinders",),
    ),
    Role(
        "crank offsets", "length", ("offset", "rod_offset"), 0.0, 0.5,
        "a fraction of the crank radius (desaxe and V-engine rod offsets)",
    ),
    Role(
        "shaft lengths", "length", ("length",), 1 * _M, 60.0,
        "a coupling's short shaft to a large ship's whole intermediate shaft line as one shaft",
        sections=("shaft",),
    ),
    Role(
        "crankshaft dimensions", "length",
        ("pin_fillet_radius", "journal_fillet_radius", "web_thickness", "web_width",
         "web_centre_distance", "overlap", "pin_recess", "journal_recess", "oil_bore_diameter",
         "bearing_span", "journal_length", "pin_length", "oversize"),
        1e-5, 4.0, "fits of hundredths of a millimetre and fillets of a model engine to the "
        "webs and bearing spans of " + _LARGEST + " (about 2 m)",
    ),
    Role(
        "lengths", "length", (), 1e-5, 1e3,
        "fillet radii and fits of hundredths of a millimetre to shaft lines of a few hundred m",
    ),
    # ---- masses and inertias ---------------------------------------------------------------
    Role("masses", "mass", (), 1e-4, 1e5, "a model engine's piston to the crossheads, pistons "
         "and rods of " + _LARGEST + " (several tonnes)"),
    Role(
        "moments of inertia", "inertia", (), 1e-7, 1e7,
        "a test rig's hub to the propellers of the largest ships with their entrained water "
        "(about 1e6 kg m^2)",
    ),
    # ---- stiffnesses and damping -----------------------------------------------------------
    Role(
        "torsional stiffnesses", "torsional_stiffness", (), 1.0, 1e11,
        "a soft coupling of a small machine to the crank spans and shafts of " + _LARGEST,
    ),
    Role(
        "torsional dampings", "torsional_damping", (), 0.0, 1e8,
        "absolute dampers and couplings up to the viscous dampers of " + _LARGEST,
    ),
    Role(
        "mesh stiffnesses", "stiffness", (), 1e4, 1e12,
        "gear meshes (about 1e10 N/m per metre of face width)",
    ),
    # ---- pressures, stresses, material data ------------------------------------------------
    Role(
        "mean effective pressures", "pressure", ("imep",), 0.05e6, 6e6,
        "part load of small engines to the most highly rated diesels (about 3-4 MPa)",
        shown=_MPA,
    ),
    Role(
        "peak cylinder pressures", "pressure", ("peak_pressure",), 1e6, 40e6,
        "motored small engines to heavy-duty diesels (about 25-30 MPa)", shown=_MPA,
    ),
    Role(
        "gas-exchange pressures", "pressure",
        ("intake_pressure", "exhaust_pressure", "crankcase_pressure"), 0.01e6, 1.5e6,
        "absolute pressures from throttled intakes to high-pressure turbocharging",
        shown=_MPA,
    ),
    Role(
        "shear moduli", "pressure", ("shear_modulus",), 1e9, 200e9,
        "composite shafts to steels (80 GPa); aluminium 26 GPa, titanium 44 GPa",
        shown=_GPA,
    ),
    Role(
        "Young's moduli", "pressure", ("youngs_modulus",), 10e9, 450e9,
        "aluminium alloys (70 GPa) to steels (210 GPa)", shown=_GPA,
    ),
    Role(
        "material strengths", "pressure",
        ("tensile_strength", "yield_strength", "tensile_strength_cap", "pin_yield_strength",
         "web_yield_strength"),
        100e6, 3000e6, "cast irons and light alloys to high-strength forged steels",
        shown=_MPA,
    ),
    Role(
        "stresses", "pressure",
        ("permissible_stress", "transient_stress", "axial_vibration_stress"),
        0.1e6, 2000e6, "permissible vibratory stresses of a few MPa to steels' strengths",
        shown=_MPA,
    ),
    Role("pressures", "pressure", (), 100.0, 1e11, "the kind's widest engineering range",
         shown=_MPA),
    # ---- torques, powers, forces -----------------------------------------------------------
    Role(
        "torques", "torque", (), 1e-3, 1e8,
        "a test rig's motor to the propulsion lines of " + _LARGEST + " (about 10 MN m)",
    ),
    Role("powers", "power", (), 0.1, 2e8,
         "small machines to the largest propulsion plants (about 100 MW)"),
    Role("forces", "force", (), 1e-3, 1e9, "small linkages to the largest engines' gas forces"),
    # ---- speeds, times, frequencies, angles ------------------------------------------------
    Role(
        "speed steps", "speed", ("speed_step",), 0.001 / RPM, 1000.0 / RPM,
        "a thousandth of a rpm to 1000 rpm", shown=("rpm", RPM),
    ),
    Role(
        "rotational speeds", "speed", (), 1.0 / RPM, 60000.0 / RPM,
        "dead-slow propellers and " + _LARGEST + " (tens of rpm) to racing engines and "
        "high-speed machines", shown=("rpm", RPM),
    ),
    Role("frequencies", "frequency", (), 0.01, 1e5, "slow transients to acoustic frequencies"),
    Role("times", "time", (), 1e-6, 1e5, "a microsecond to a day"),
    Role(
        "angles", "angle", (), 0.0, 4.0 * math.pi,
        "within a working cycle (720 deg); a bare angle is radians", shown=("deg", 180 / math.pi),
    ),
    Role("densities", "density", (), 100.0, 25000.0, "polymers to tungsten (19300 kg/m^3)"),
    Role("angular accelerations", "angular_acceleration", (), 0.0, 1e7,
         "the kind's engineering range"),
    # ---- plain numbers ---------------------------------------------------------------------
    Role(
        "loss factors", "ratio", ("loss_factor",), 0.0, 0.5,
        "steels about 0.001-0.05, rubber couplings up to about 0.3 (psi / 2 pi)",
        hint="a loss factor is psi / 2 pi: was the relative damping psi given?",
    ),
    Role(
        "relative dampings psi", "ratio", ("relative_damping",), 0.05, 3.0,
        "steel-spring couplings to natural-rubber couplings (psi 0.4-2, DIN 740-2)",
    ),
    Role("damping ratios", "ratio", ("damping_ratio",), 0.0, 0.5,
         "lightly damped steel to heavily damped couplings (psi / 4 pi)"),
    Role("gear ratios", "ratio", ("ratio",), 0.01, 100.0, "speed ratios of gear stages and "
         "multi-stage gearboxes", sections=("gear",)),
    Role("gear ratios", "ratio", ("gear_ratio",), 0.01, 100.0,
         "speed ratios of gear stages and multi-stage gearboxes"),
    Role("crank-rod ratios", "ratio", ("rod_ratio",), 0.1, 0.6,
         "lambda = R/L of production engines, about 0.2-0.35"),
    Role("compression ratios", "ratio", ("compression_ratio",), 4.0, 30.0,
         "two-stroke petrol engines to diesels of about 23"),
    Role("degrees of cyclic irregularity", "ratio", ("delta",), 1e-4, 0.2,
         "generator sets (1/300) to pumps and compressors (1/20)"),
    Role("balance ratios", "ratio", ("counterweight_ratio", "reciprocating_balance_ratio"),
         0.0, 2.0, "no counterweight to full and over-balance"),
    Role("temperature factors", "ratio", ("temperature_factor", "damping_temperature_factor"),
         0.2, 2.0, "rubber couplings' catalogue factors at their operating temperatures"),
    Role("skirt friction coefficients", "ratio", ("skirt_friction",), 0.0, 0.4,
         "lubricated piston skirts (about 0.01-0.1) to dry steel on cast iron (about 0.2-0.4)"),
    Role("mechanical efficiencies", "ratio", ("mechanical_efficiency",), 0.3, 1.0,
         "idle to full load (Heywood sec. 2.5: 0.75-0.9 at full load)"),
)  # fmt: skip
"""Every role's plausible range, in lookup order: a role naming the key (and the section, where
it names sections) before the kind's fallback (no keys)."""

RATED_SPEED_RANGE = (0.1, 1.5)
"""The plausible upper end of a speed range as a fraction of the rated speed n_0: a TVC runs to
the overspeed (about 1.05-1.2 n_0); a range ending above 1.5 n_0 or below 0.1 n_0 has a speed
in the wrong unit (Hz for rpm: x 60, rad/s read as rpm: / 9.55)."""


def section_of(name: str) -> str:
    """The last part of a table's name as roles name sections.

    Parameters
    ----------
    name : str
        The table's name as messages show it (``"[[torsion.shaft]] #2"``, ``"[geometry]"``).

    Returns
    -------
    str
        ``"shaft"``, ``"geometry"``; ``""`` for the top level.

    Examples
    --------
    >>> section_of("[[torsion.shaft]] #2"), section_of("[torsion.tvc.crankshaft]"), section_of("")
    ('shaft', 'crankshaft', '')
    """
    return name.split(" ")[0].strip("[]").rpartition(".")[2]


def role_of(kind: str, key: str, section: str = "") -> Role | None:
    """The role of a key of a kind in a table.

    Parameters
    ----------
    kind : str
        The kind of quantity (``"ratio"`` for a plain number).
    key : str
        The key (the last part: ``"outer_diameter"``).
    section : str
        The table (:func:`section_of`).

    Returns
    -------
    Role or None
        The first role of :data:`ROLES` naming the key in that section, else the kind's
        fallback; None for a plain number no role names.

    Examples
    --------
    >>> role_of("length", "outer_diameter", "shaft").name
    'shaft diameters'
    >>> role_of("length", "inner_diameter", "flywheel").name
    'flywheel diameters'
    """
    index = (kind, key, section)
    if index not in _ROLE_INDEX:
        _ROLE_INDEX[index] = next(
            (
                r
                for r in ROLES
                if r.kind == kind
                and (key in r.keys or not r.keys)
                and (not r.sections or section in r.sections)
            ),
            None,
        )
    return _ROLE_INDEX[index]


_ROLE_INDEX: dict[tuple[str, str, str], Role | None] = {}
"""The roles looked up so far (every file reads the same few keys)."""


def check_input(
    value: float,
    kind: str,
    key: str,
    *,
    section: str = "",
    label: str | None = None,
    file: str | None = None,
    written: Any = None,
) -> InputWarning | None:
    """The warning for a value outside the plausible range of its role, or None.

    Parameters
    ----------
    value : float
        The value (SI, in the kind's unit).
    kind : str
        Its kind (a key of :data:`crankdyn.io.units.KINDS`, or ``"ratio"``).
    key : str
        Its key (the last part, for the role).
    section : str
        Its table (:func:`section_of`).
    label : str or None
        The key as messages name it (``"[[shaft]] #3 outer_diameter"``); default ``key``.
    file : str or None
        The file, as messages name it.
    written : object
        The value as written (default the SI value).

    Returns
    -------
    crankdyn.plausibility.InputWarning or None
        The warning (file, key, value as written, the value, the range, why, a hint).

    Examples
    --------
    >>> w = check_input(180.0, "length", "outer_diameter", section="shaft",
    ...                 label="[[shaft]] #3 outer_diameter", file="line.toml", written=180)
    >>> print(w.message)  # doctest: +NORMALIZE_WHITESPACE
    line.toml: [[shaft]] #3 outer_diameter = 180: 180 m is outside the 0.003-3 m of shaft
    diameters (the few-millimetre shafts of test rigs to the crank journals of the largest
    two-stroke engines (about 1 m)); did you mean 180 mm?
    >>> check_input(0.29, "length", "outer_diameter") is None
    True
    """
    if not math.isfinite(value):
        return None
    role = role_of(kind, key, section)
    if role is None or role.holds(value):
        return None
    unit, scale = role.unit()
    shown = f"{_g(value * scale)} {unit}".rstrip()
    hint = role.hint or _did_you_mean(role, written if written is not None else value)
    return _warning(role, value, shown, role.range_text(), hint, label or key, file, written)


def _warning(
    role: Role,
    value: float,
    shown: str,
    span: str,
    hint: str,
    label: str,
    file: str | None,
    written: Any,
) -> InputWarning:
    """The warning in one pattern: where, the value, the range of the role, why, a hint."""
    as_written = _written_text(written if written is not None else value)
    where = f"{file}: {label}" if file else label
    text = f"{where} = {as_written}: {shown} is outside the {span} of {role.name} ({role.reason})"
    message = f"{text}; {hint}" if hint else text
    return InputWarning(
        key=f"input:{message}",
        quantity=role.name,
        value=float(value),
        unit=KINDS[role.kind].si_unit if role.kind in KINDS else "",
        low=role.low,
        high=role.high,
        source=role.reason,
        message=message,
        file=file,
        input_key=label,
        written=written,
        value_shown=shown,
        range_shown=span,
    )


def _written_text(written: Any) -> str:
    """The value as written, as messages quote it (strings in double quotes, as TOML)."""
    import json

    if isinstance(written, str):
        return json.dumps(written, ensure_ascii=False)
    if isinstance(written, float) and written.is_integer():
        return f"{written:g}"
    return str(written)


def _did_you_mean(role: Role, written: Any) -> str:
    """``did you mean 180 mm?``: the number as written, in the first unit of the kind's hints
    (other than its own) that brings it into the role's range; ``""`` when none does."""
    from crankdyn.io.units import split_quantity

    try:
        parsed = split_quantity(written)
    except Exception:  # a value a reader accepted; a hint is only a courtesy
        return ""
    if parsed is None:
        return ""
    magnitude, unit_text = parsed
    own = unit_text or (KINDS[role.kind].si_unit if role.kind in KINDS else "")
    for hint in role.hints or HINTS.get(role.kind, ()):
        if hint == own:
            continue
        factor = COMMON_UNITS[hint][0]  # speeds: rpm and rad/s, whose factor is to rad/s
        if magnitude != 0.0 and role.holds(magnitude * factor):
            return f"did you mean {_g(magnitude)} {hint}?"
    return ""


def check_speed_range(
    high: float,
    rated: float,
    *,
    label: str,
    file: str | None = None,
    written: Any = None,
) -> InputWarning | None:
    """The warning for a speed range whose upper end lies outside :data:`RATED_SPEED_RANGE`
    times the rated speed n_0 (a speed in the wrong unit), or None.

    Parameters
    ----------
    high : float
        The range's upper end (rad/s).
    rated : float
        The rated speed n_0 (rad/s).
    label : str
        The range's key as messages name it.
    file : str or None
        The file.
    written : object
        The range as written.

    Returns
    -------
    crankdyn.plausibility.InputWarning or None
        The warning, naming the file, the key, the range as written, the ratio and n_0.

    Examples
    --------
    >>> w = check_speed_range(1000 * 2 * math.pi, 750 / RPM, label="[operating] speed_range",
    ...                       file="m.toml", written=["350 Hz", "1000 Hz"])
    >>> print(w.message)  # doctest: +NORMALIZE_WHITESPACE
    m.toml: [operating] speed_range = ["350 Hz", "1000 Hz"]: the range ends at 60000 rpm, 80
    times the rated speed 750 rpm; ranges end at 0.1-1.5 n_0 (a TVC runs to the overspeed,
    about 1.05-1.2 n_0): check the unit (Hz is revolutions per second)
    """
    low_f, high_f = RATED_SPEED_RANGE
    if not (math.isfinite(high) and math.isfinite(rated) and rated > 0.0):
        return None
    ratio = high / rated
    if low_f <= ratio <= high_f:
        return None
    import json

    shown = json.dumps(written, ensure_ascii=False) if written is not None else f"{high:g}"
    where = f"{file}: {label}" if file else label
    message = (
        f"{where} = {shown}: the range ends at {_g(high * RPM)} rpm, {_g(ratio)} times the "
        f"rated speed {_g(rated * RPM)} rpm; ranges end at {low_f:g}-{high_f:g} n_0 (a TVC "
        "runs to the overspeed, about 1.05-1.2 n_0): check the unit (Hz is revolutions per "
        "second)"
    )
    return InputWarning(
        key=f"input:{message}",
        quantity="speed ranges against the rated speed",
        value=float(high),
        unit="rad/s",
        low=low_f * rated,
        high=high_f * rated,
        source="a TVC runs to the overspeed, about 1.05-1.2 n_0",
        message=message,
        file=file,
        input_key=label,
        written=written,
        value_shown=f"{_g(high * RPM)} rpm",
        range_shown=f"{_g(low_f * rated * RPM)}-{_g(high_f * rated * RPM)} rpm",
    )


def roles_markdown() -> str:
    """The plausibility table as the input pages print it (one row per role, in lookup
    order), generated from :data:`ROLES` so the pages never fall behind it.

    Returns
    -------
    str
        A Markdown table: role, keys, tables, plausible range, why.
    """
    lines = ["| role | keys | in | plausible range | why |", "|---|---|---|---|---|"]
    for r in ROLES:
        keys = ", ".join(f"`{k}`" for k in r.keys) or f"any other {KINDS_WORDS.get(r.kind, r.kind)}"
        where = ", ".join(f"`{s}`" for s in r.sections) or "any"
        lines.append(f"| {r.name} | {keys} | {where} | `{r.range_text()}` | {r.reason} |")
    low, high = RATED_SPEED_RANGE
    lines.append(
        "| speed ranges against the rated speed | `speed_range`, `speed_ranges.*` | "
        f"`operating`, `tvc` | upper end `{low:g}-{high:g} n_0` | a TVC runs to the "
        "overspeed, about 1.05-1.2 n_0 |"
    )
    return "\n".join(lines) + "\n"


KINDS_WORDS = {key: kind.name.split(" ", 1)[1] for key, kind in KINDS.items()}
"""The kinds in words without their article (``"length"``, ``"torsional stiffness"``)."""
KINDS_WORDS["ratio"] = "plain number"
