"""Firing order, throw angles and firing angles (seed 000 section 2.3).

Conventions (docs/conventions.md): the throw angle psi_i of cylinder i is the crankshaft rotation
from cylinder 1's TDC to cylinder i's TDC, 0 <= psi_i < 360 deg; the firing angle Phi_i is the
crankshaft angle at which cylinder i fires, 0 <= Phi_i < cycle angle (720 deg four-stroke,
360 deg two-stroke), Phi_1 = 0, and for a four-stroke engine Phi_i = psi_i or psi_i + 360 deg.
"""

from __future__ import annotations

import math

import numpy as np

from crankdyn.errors import InputError

__all__ = [
    "CYCLE_ANGLE",
    "check_firing_order",
    "even_firing_interval",
    "even_firing_throw_angles",
    "firing_angles",
]

TWO_PI = 2.0 * math.pi
CYCLE_ANGLE = {"four-stroke": 2.0 * TWO_PI, "two-stroke": TWO_PI}
_TOL = 1e-9


def even_firing_interval(cylinders: int, cycle: str) -> float:
    """Even firing interval (rad): 720/Z deg four-stroke, 360/Z deg two-stroke (seed 000 2.3)."""
    return CYCLE_ANGLE[cycle] / cylinders


def check_firing_order(order, cylinders: int, key: str = "firing_order") -> tuple[int, ...]:
    """Validate a firing order (a permutation of 1..Z) and rotate it to start at cylinder 1."""
    try:
        items = [int(c) for c in order]
        if any(int(c) != c for c in order):
            raise ValueError
    except (TypeError, ValueError):
        raise InputError("expected a list of cylinder numbers", key=key, value=order) from None
    if sorted(items) != list(range(1, cylinders + 1)):
        raise InputError(
            f"the firing order must name each of the {cylinders} cylinders (1..{cylinders}) once",
            key=key,
            value=list(order),
        )
    start = items.index(1)
    return tuple(items[start:] + items[:start])


def even_firing_throw_angles(order, cycle: str) -> np.ndarray:
    """Throw angles psi_i (rad, indexed by cylinder - 1) of an evenly firing engine.

    The k-th cylinder of the firing order fires at k times the even interval; its TDC angle is
    that firing angle taken modulo one revolution.
    """
    interval = CYCLE_ANGLE[cycle] / len(order)
    psi = np.empty(len(order))
    for position, cylinder in enumerate(order):
        psi[cylinder - 1] = np.mod(position * interval, TWO_PI)
    return psi


def firing_angles(order, throw_angles, cycle: str, key: str = "firing_order") -> np.ndarray:
    """Firing angles Phi_i (rad, indexed by cylinder - 1) from a firing order and throw angles.

    Walking the firing order from cylinder 1 (which fires at 0), each cylinder fires at the first
    of its TDCs after the previous cylinder fired (a four-stroke cylinder reaches TDC at psi_i and
    psi_i + 360 deg). The order fits the crankshaft when the last cylinder fires before the cycle
    ends; otherwise InputError.
    """
    cycle_angle = CYCLE_ANGLE[cycle]
    psi = np.mod(np.asarray(throw_angles, dtype=float), TWO_PI)
    phi = np.empty(len(order))
    previous = -1.0
    for cylinder in order:
        candidate = psi[cylinder - 1]
        while candidate <= previous + _TOL:
            candidate += TWO_PI
        phi[cylinder - 1] = candidate
        previous = candidate
    if previous >= cycle_angle - _TOL:
        raise InputError(
            f"the firing order does not fit the throw angles: cylinder {order[-1]} would fire "
            f"at {math.degrees(previous):.6g} deg, after the {math.degrees(cycle_angle):.0f} deg "
            "cycle",
            key=key,
            value=list(order),
        )
    return phi
