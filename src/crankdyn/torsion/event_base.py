"""Shared checks of the transient events' data (domain helpers of
:mod:`crankdyn.torsion.events` and :mod:`crankdyn.torsion.event_drives`)."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from crankdyn.errors import InputError

__all__ = [
    "SEVERITIES",
    "SPEED_KINDS",
    "finite",
    "linear_rise",
    "mass_name",
    "nonnegative",
    "positive",
    "severity_of",
]

SEVERITIES = ("normal", "exceptional")
"""How often an event occurs in service: ``normal`` transient conditions (T_Kmax1 of a coupling)
or ``exceptional`` ones (T_Kmax2)."""

SPEED_KINDS = ("start", "stop", "emergency stop", "ramp")
"""The kinds of :class:`crankdyn.torsion.event_drives.SpeedChange`."""


def positive(name: str, value: float) -> float:
    """``value`` as a positive finite float, else an InputError naming ``name``.

    Parameters
    ----------
    name : str
        The key named in an error.
    value : float
        The value (any unit).

    Returns
    -------
    float
        The value.
    """
    v = float(value)
    if not (math.isfinite(v) and v > 0.0):
        raise InputError("must be a positive number", key=name, value=value)
    return v


def nonnegative(name: str, value: float) -> float:
    """``value`` as a finite float >= 0, else an InputError naming ``name``.

    Parameters
    ----------
    name : str
        The key named in an error.
    value : float
        The value (any unit).

    Returns
    -------
    float
        The value.
    """
    v = float(value)
    if not (math.isfinite(v) and v >= 0.0):
        raise InputError("must not be negative", key=name, value=value)
    return v


def finite(name: str, value: float) -> float:
    """``value`` as a finite float, else an InputError naming ``name``.

    Parameters
    ----------
    name : str
        The key named in an error.
    value : float
        The value (any unit).

    Returns
    -------
    float
        The value.
    """
    v = float(value)
    if not math.isfinite(v):
        raise InputError("must be a finite number", key=name, value=value)
    return v


def severity_of(value: str) -> str:
    """``value`` when it is a severity (:data:`SEVERITIES`), else an InputError.

    Parameters
    ----------
    value : str
        The severity.

    Returns
    -------
    str
        The value.
    """
    if value not in SEVERITIES:
        raise InputError("expected normal or exceptional", key="severity", value=value)
    return value


def mass_name(value: object) -> str:
    """``value`` when it is a non-empty name, else an InputError (key ``at``).

    Parameters
    ----------
    value : object
        The name.

    Returns
    -------
    str
        The name.
    """
    if not isinstance(value, str) or not value.strip():
        raise InputError("expected a mass name", key="at", value=value)
    return value


def linear_rise(t: NDArray[np.float64], start: float, rise_time: float) -> NDArray[np.float64]:
    """The fraction of a torque that rises linearly from ``start`` over ``rise_time``.

    Parameters
    ----------
    t : numpy.ndarray
        Times (s).
    start : float
        The start of the rise (s).
    rise_time : float
        Its length (s), >= 0 (0: a step at ``start``).

    Returns
    -------
    numpy.ndarray
        0 before ``start``, 1 after ``start + rise_time``, linear between.

    Examples
    --------
    >>> linear_rise(np.array([0.0, 1.5, 2.0, 3.0]), 1.0, 1.0).tolist()
    [0.0, 0.5, 1.0, 1.0]
    >>> linear_rise(np.array([0.5, 1.0]), 1.0, 0.0).tolist()
    [0.0, 1.0]
    """
    t = np.asarray(t, dtype=float)
    if rise_time == 0.0:
        return np.where(t >= start, 1.0, 0.0)
    return np.clip((t - start) / rise_time, 0.0, 1.0)
