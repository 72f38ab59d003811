"""Values as the exports write them: SI values scaled to the unit of their key (degrees,
rpm), and any data as strict JSON (numpy types as Python ones, NaN and inf as None). A pure
module: :mod:`crankdyn.results` and :mod:`crankdyn.summary` both write through it."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from crankdyn.constants import DEG, RPM

__all__ = ["jsonable", "scaled", "scaled_value", "to_jsonable"]


def scaled(value: Any, scale: float) -> Any:
    """value x scale; angles converted to degrees are rounded to 1e-10 deg and speeds converted
    to rpm to 1e-9 rpm, so that grid values read as the round numbers they are (30.0, not
    29.999999999999996; 6000.0, not 6000.000000000001).

    Parameters
    ----------
    value : float or numpy.ndarray
        SI value(s).
    scale : float
        The factor to the exported unit (1, :data:`~crankdyn.constants.DEG`,
        :data:`~crankdyn.constants.RPM`, ...).

    Returns
    -------
    float or numpy.ndarray
        The exported value(s).
    """
    if scale == 1.0:
        return value
    out = value * scale
    if scale == DEG:
        return np.round(out, 10)
    if scale == RPM:
        return np.round(out, 9)
    return out


def scaled_value(value: float, scale: float) -> float:
    """A float in the unit a field is exported in (SI x scale, rounded as the exports round
    it: degrees to 1e-10, rpm to 1e-9).

    Parameters
    ----------
    value : float
        The SI value.
    scale : float
        The field's factor from SI to its exported unit.

    Returns
    -------
    float
        The exported value.

    Examples
    --------
    >>> from crankdyn.constants import RPM
    >>> scaled_value(6000 / RPM, RPM)
    6000.0
    """
    return float(scaled(float(value), scale))


def jsonable(value: Any) -> Any:
    """``value`` as JSON data: numpy types as Python ones, NaN and inf as None (strict JSON),
    results (and anything else with ``to_dict``) as their ``to_dict()``.

    Parameters
    ----------
    value : object
        Results, dicts, lists, tuples, arrays and numbers nested in any way.

    Returns
    -------
    object
        The same data as dicts (string keys), lists, bools, ints, floats, None and text.

    Examples
    --------
    >>> jsonable({"speeds": np.array([1.0, np.nan]), 2: (np.int64(3), np.True_)})
    {'speeds': [1.0, None], '2': [3, True]}
    """
    return to_jsonable(value, 1.0)


def to_jsonable(value: Any, scale: float) -> Any:
    """:func:`jsonable` of a value exported with a field's scale (numbers and arrays scaled
    by :func:`scaled`).

    Parameters
    ----------
    value : object
        The value.
    scale : float
        The field's factor to its exported unit.

    Returns
    -------
    object
        JSON data.
    """
    if hasattr(value, "to_dict") and not isinstance(value, type):  # results, verdicts, warnings
        return value.to_dict()
    if isinstance(value, np.ndarray):
        if value.dtype.kind in "fc":
            out = scaled(value, scale)
            finite = np.isfinite(out)
            if not finite.all():  # NaN and inf as None (strict JSON), whole arrays at a time
                out = np.where(finite, out.astype(object), None)
            return out.tolist()  # nested lists of Python floats, in one pass
        if value.dtype.kind in "iub":
            return value.tolist()
        return [to_jsonable(v, scale) for v in value.tolist()]
    if isinstance(value, (list, tuple)):
        return [to_jsonable(v, scale) for v in value]
    if isinstance(value, dict):
        return {str(k): to_jsonable(v, scale) for k, v in value.items()}
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        number = float(scaled(float(value), scale))
        return number if math.isfinite(number) else None
    return value
