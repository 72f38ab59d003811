"""Shared checks of the transient events' data (domain helpers of
:mod:`crankdyn.torsion.events` and :mod:`crankdyn.torsion.event_drives`)."""

from __future__ import annotations

import math

from crankdyn.errors import InputError

__all__ = [
    "SEVERITIES",
    "SPEED_KINDS",
    "finite",
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
