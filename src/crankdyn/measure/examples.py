"""Built-in example signals: simulated torsiograph records of the built-in inline-6 diesel.

``inline6-runup`` is a run-up from 1800 to 2500 rpm at 50 rpm/s measured at the pulley with a
60-tooth wheel and a cam-shaft reference at cylinder 1's firing TDC (once per cycle), through a
10 MHz counter with 50 ns of timing jitter. The engine "as built" is the model of the built-in
``inline6-diesel`` (Mendes et al. 2008) with a shaft loss factor of 0.05 instead of the model's
0.035: analysed with the model, the run-up shows the model's resonance too high and too sharp,
and the identified loss factor comes out at 0.05. The pulley's motion is the steady-state
response at the instantaneous speed (a quasi-static sweep, :mod:`crankdyn.measure.synthetic`),
every order from 0.5 to 12. ``inline6-2000rpm`` is the same engine at a steady 2000 rpm for
2 s.
"""

from __future__ import annotations

from functools import lru_cache
from typing import TYPE_CHECKING, Any

import numpy as np

from crankdyn.constants import RPM
from crankdyn.errors import InputError, did_you_mean
from crankdyn.measure.signals import PulseTrain
from crankdyn.measure.synthetic import PrescribedMotion, synthetic_pulses

if TYPE_CHECKING:
    from crankdyn.torsion.response import ResponseResult

__all__ = ["EXAMPLES", "TRUE_LOSS_FACTOR", "example_motion", "example_signal"]

TRUE_LOSS_FACTOR = 0.05
"""Shaft loss factor of the simulated engine "as built" (the model says 0.035)."""
ENGINE = "inline6-diesel"
"""The built-in engine the examples simulate."""
MASS = "pulley"
"""The mass of its shaft line the wheel sits on."""
TEETH = 60
"""Teeth of the simulated wheel at the pulley."""

EXAMPLES: dict[str, dict[str, Any]] = {
    "inline6-runup": {
        "speed": 1800.0 / RPM,
        "acceleration": 50.0 / RPM,
        "duration": 14.0,
        "description": "inline-6 diesel run-up 1800-2500 rpm at 50 rpm/s, 60 teeth at the pulley",
    },
    "inline6-2000rpm": {
        "speed": 2000.0 / RPM,
        "acceleration": 0.0,
        "duration": 2.0,
        "description": "inline-6 diesel at a steady 2000 rpm, 60 teeth at the pulley",
    },
}
"""The built-in signals: initial speed (rad/s), acceleration (rad/s^2), duration (s) and a
one-line description, by name."""


def example_motion(name: str) -> PrescribedMotion:
    """The prescribed motion of the pulley in an example (its exact order amplitudes).

    Parameters
    ----------
    name : str
        The example's name, a key of :data:`EXAMPLES`.

    Returns
    -------
    PrescribedMotion
        The pulley's mean rotation and its order amplitudes X_q (rad) at the mean speed.

    Raises
    ------
    InputError
        If there is no example of that name.
    """
    spec = _spec(name)
    return _motion(spec["speed"], spec["acceleration"], spec["duration"])


@lru_cache(maxsize=4)
def _motion(speed: float, acceleration: float, duration: float) -> PrescribedMotion:
    from crankdyn.engine.model import Engine
    from crankdyn.measure.compare import with_shaft_loss_factor
    from crankdyn.torsion.excitation import excitation_for
    from crankdyn.torsion.orders import order_grid
    from crankdyn.torsion.sweep import forced_response

    engine = Engine.example(ENGINE)
    if engine.torsion is None:  # the built-in engine carries its shaft line
        raise ValueError(f"the built-in {ENGINE} has no torsional model")
    model = with_shaft_loss_factor(engine.torsion, TRUE_LOSS_FACTOR)
    excitation = excitation_for(engine.torsion, engine)
    orders = order_grid(0.5, 12.0, 0.5, excitation.cycle)
    end = speed + acceleration * duration
    lo, hi = min(speed, end) - 20.0 / RPM, max(speed, end) + 20.0 / RPM
    if acceleration == 0.0:
        steady = forced_response(model, excitation, [speed], orders, resolve=False)
        x = _mass_response(steady)[0, :, steady.mass_index(MASS)]
        return PrescribedMotion(speed, 0.0, orders, x)
    grid = np.arange(lo, hi + 2.0 / RPM, 2.0 / RPM)  # every 2 rpm (the spline is smooth)
    response = forced_response(model, excitation, grid, orders, resolve=False)  # on the grid
    from scipy.interpolate import CubicSpline  # imported here: keeps the start-up light

    spline = CubicSpline(grid, _mass_response(response)[:, :, response.mass_index(MASS)], axis=0)
    return PrescribedMotion(speed, acceleration, orders, spline)


def _mass_response(response: ResponseResult) -> np.ndarray:
    if response.mass_response is None:  # forced_response keeps it
        raise ValueError("the forced response holds no mass response")
    return response.mass_response


def _spec(name: str) -> dict[str, Any]:
    if name not in EXAMPLES:
        raise InputError(
            f"no built-in signal named {name!r}{did_you_mean(name, EXAMPLES)} (built-in: "
            f"{', '.join(EXAMPLES)})",
            key="SIGNAL",
            value=name,
        )
    return EXAMPLES[name]


def example_signal(name: str) -> PulseTrain:
    """A built-in example signal (module docstring) as a pulse train.

    Parameters
    ----------
    name : str
        The example's name, a key of :data:`EXAMPLES`.

    Returns
    -------
    PulseTrain
        Pulse and reference times (s), 60 teeth, counted by a 10 MHz clock with 50 ns of
        jitter.

    Raises
    ------
    InputError
        If there is no example of that name.
    """
    spec = _spec(name)
    motion = example_motion(name)
    return synthetic_pulses(
        motion,
        TEETH,
        spec["duration"],
        reference_every=2,
        reference_angle=0.0,
        jitter=50e-9,
        clock=1e-7,
        seed=20,
        source=f"{name} (built-in example)",
    )
