"""Section builders: one module per analysis, each with ``build(ctx) -> Section``.

A builder raises :class:`NotApplicable` (with the reason) when its analysis does not apply to the
engine (no pressure, no torsional model...); the reason is listed in the report. The order of
:data:`BUILDERS` is the order of the report.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from crankdyn.engine.model import Engine

__all__ = ["BUILDERS", "Context", "NotApplicable", "NotRequested", "builders"]

BUILDERS = (
    "kinematics",
    "pressure",
    "forces",
    "torque",
    "firing",
    "balance",
    "flywheel",
    "torsion_modes",
    "torsion_response",
    "measurement",
)


class NotApplicable(Exception):
    """The analysis does not apply to this engine; the message says why."""


class NotRequested(NotApplicable):
    """An optional section the user did not ask for (no note in the report)."""


@dataclass
class Context:
    """What the builders share: the engine, the speeds, and a cache of computed results."""

    engine: Engine
    speed: float  # rad/s, the operating point
    speeds: np.ndarray | None = None  # rad/s, for speed sweeps (torsional response)
    measurement: Any = None  # sections.measurement.MeasurementInput, or None
    cache: dict[str, Any] = field(default_factory=dict)

    def get(self, key: str, compute):
        """The cached value for key, computed once."""
        if key not in self.cache:
            self.cache[key] = compute()
        return self.cache[key]


def builders():
    """(name, build function) in report order."""
    return [
        (name, importlib.import_module(f"crankdyn.report.sections.{name}").build)
        for name in BUILDERS
    ]
