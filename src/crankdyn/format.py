"""Numbers for people: engineering units, sensible digits, round-off shown as 0.

One helper for every place that shows a number to a person (the HTML report, the terminal
tables of the command line); files for machines (JSON, CSV) keep SI values at full precision.

- :func:`number`: a plain number with ``digits`` significant digits, never an exponent for
  ordinary magnitudes (``12345``, not ``1.234e+04``), and 0 for round-off next to a reference
  magnitude (``scale``): ``1.393e-14`` beside values of order 1 is shown as ``0``.
- :func:`quantity`: an SI value with the unit prefix engineers read (``1.894 MPa``, not
  ``1.89441e+06 Pa``; ``130.3 kN``; ``137 mm``).
- :func:`column`: one display unit and factor for a whole column of values, so that a table's
  header carries the unit and its cells only numbers.
- :func:`clean`: a float without representation artefacts (``6000.000000000001`` -> ``6000.0``)
  for grid values written to JSON.

Everything here is pure (no I/O, no boundary imports), so the command line, the report, the
plots and the messages of the analyses (plausibility warnings) all format numbers alike.
"""

from __future__ import annotations

import math
from collections.abc import Iterable

__all__ = [
    "ROUNDOFF",
    "clean",
    "column",
    "display_unit",
    "number",
    "quantity",
    "unit_label",
]

ROUNDOFF = 1e-9
"""A value smaller than ROUNDOFF x the reference magnitude of its quantity is round-off (the
solvers work to about 1e-12 relative; 1e-9 leaves margin) and is shown as 0."""

# Display units by SI unit: (factor from SI, unit), largest first. The first unit whose factor
# does not exceed |value| is taken; the last is the floor (so small lengths stay in mm and small
# pressures in kPa rather than going to µm or Pa).
_PREFIXED: dict[str, tuple[tuple[float, str], ...]] = {
    "Pa": ((1e9, "GPa"), (1e6, "MPa"), (1e3, "kPa"), (1.0, "Pa")),
    "N": ((1e6, "MN"), (1e3, "kN"), (1.0, "N")),
    "N·m": ((1e6, "MN·m"), (1e3, "kN·m"), (1.0, "N·m")),
    "W": ((1e6, "MW"), (1e3, "kW"), (1.0, "W")),
    "J": ((1e6, "MJ"), (1e3, "kJ"), (1.0, "J")),
    "N·m/rad": ((1e6, "MN·m/rad"), (1e3, "kN·m/rad"), (1.0, "N·m/rad")),
    "N·m·s/rad": ((1e3, "kN·m·s/rad"), (1.0, "N·m·s/rad")),
    "Hz": ((1e3, "kHz"), (1.0, "Hz")),
    "m": ((1.0, "m"), (1e-3, "mm")),
}
_ALIASES = {"Nm": "N·m", "N*m": "N·m", "N m": "N·m", "Nm/rad": "N·m/rad", "Nms/rad": "N·m·s/rad"}


def _canonical(unit: str) -> str:
    return _ALIASES.get(unit, unit)


def number(value, digits: int = 4, *, scale: float | None = None) -> str:
    """``value`` with ``digits`` significant digits, as people write numbers.

    Parameters
    ----------
    value
        The number (any unit); None, NaN and inf are shown as ``-``.
    digits
        Significant digits (>= 1). Integer digits are never rounded away: 12345.6 with 4 digits
        is ``12346``.
    scale
        Reference magnitude of the quantity (e.g. the largest |value| of its column, same unit):
        a value below :data:`ROUNDOFF` x scale is round-off and is shown as ``0``.

    Returns
    -------
    str
        ``"0"``, ``"-"`` or the digits; an exponent only outside 1e-4 <= |value| < 1e15
        (``"3.2e-07"``).
    """
    if value is None:
        return "-"
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int) or (hasattr(value, "dtype") and value.dtype.kind in "iu"):
        return str(int(value))
    if isinstance(value, str):
        return value
    x = float(value)
    if not math.isfinite(x):
        return "-"
    if x == 0.0 or (scale is not None and abs(x) <= ROUNDOFF * abs(scale)):
        return "0"
    magnitude = abs(x)
    if magnitude < 1e-4 or magnitude >= 1e15:
        mantissa, _, power = f"{x:.{max(digits - 1, 0)}e}".partition("e")
        if "." in mantissa:
            mantissa = mantissa.rstrip("0").rstrip(".")
        return f"{mantissa}e{power}"
    exponent = math.floor(math.log10(magnitude))
    decimals = max(digits - 1 - exponent, 0)
    text = f"{x:.{decimals}f}"
    if float(text) == 0.0:
        return "0"
    if "." in text:  # 2 significant digits of 0.0500 read 0.05, trailing zeros are noise
        text = text.rstrip("0").rstrip(".")
    if text in ("-0", "+0"):
        return "0"
    return text


def display_unit(value: float, unit: str) -> tuple[float, str]:
    """(factor, unit) to show ``value`` (SI, in ``unit``) in: the engineering unit that puts its
    magnitude at 1 or above (``1.89e6 Pa`` -> ``(1e6, "MPa")``); units without prefixes come
    back unchanged with factor 1."""
    choices = _PREFIXED.get(_canonical(unit))
    if not choices:
        return 1.0, unit
    magnitude = abs(value) if value is not None and math.isfinite(value) else 0.0
    for factor, name in choices:
        if magnitude >= factor:
            return factor, name
    return choices[-1]


def quantity(
    value, unit: str = "", digits: int = 4, *, scale: float | None = None, to: str | None = None
) -> str:
    """An SI value with its engineering unit: ``quantity(1.89441e6, "Pa")`` -> ``"1.894 MPa"``.

    Parameters
    ----------
    value
        The SI value (in ``unit``).
    unit
        Its SI unit (``"Pa"``, ``"N"``, ``"N·m"``, ``"W"``, ``"J"``, ``"m"``, ``"Hz"``,
        ``"N·m/rad"``...); other units are shown as they are (``"rpm"``, ``"kg·m²"``).
    digits
        Significant digits.
    scale
        Reference magnitude for round-off (see :func:`number`), in ``unit``.
    to
        A display unit to use instead of the automatic choice (e.g. ``"bar"`` or ``"kPa"``).
    """
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    if to is not None:
        factor = _FACTORS.get(to)
        if factor is None:
            raise ValueError(f"unknown display unit {to!r}")
        name = to
    else:  # the unit follows the reference magnitude when there is one (a column's unit)
        factor, name = display_unit(float(scale) if scale else float(value), unit)
    text = number(
        float(value) / factor, digits, scale=None if scale is None else abs(scale) / factor
    )
    return f"{text} {name}".rstrip()


_FACTORS = {name: factor for choices in _PREFIXED.values() for factor, name in choices}
_FACTORS.update({"bar": 1e5, "deg": 1.0, "rpm": 1.0})


def column(values: Iterable, unit: str = "") -> tuple[float, str, float]:
    """One display unit for a column: (factor, display unit, scale in display units), chosen
    from the column's largest finite magnitude; divide each SI value by factor and format it with
    :func:`number` and ``scale`` (so round-off reads 0 and every row has the same unit)."""
    finite = [abs(float(v)) for v in values if v is not None and math.isfinite(float(v))]
    largest = max(finite, default=0.0)
    factor, name = display_unit(largest, unit)
    return factor, name, largest / factor


def unit_label(label: str, unit: str) -> str:
    """A column header: ``"Stiffness (MN·m/rad)"``; a label alone when there is no unit."""
    return f"{label} ({unit})" if unit else label


def clean(value: float, digits: int = 12) -> float:
    """``value`` rounded to ``digits`` significant digits, dropping the binary representation
    artefacts of grid arithmetic (``1000 + 20 x 250.00000000000003`` -> ``6000.0``). For grid
    values and other numbers that are round by construction, never for computed results."""
    x = float(value)
    if x == 0.0 or not math.isfinite(x):
        return x
    return float(f"{x:.{digits}g}")
