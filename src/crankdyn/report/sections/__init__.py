"""Section builders: one module per analysis, each with ``build(ctx) -> Section`` taking its numbers
from the analysis session ``ctx.analysis`` (:class:`crankdyn.session.Analysis`).

A builder raises :class:`NotApplicable` (with the reason) when its analysis does not apply to the
engine (no pressure, no torsional model...); the reason is listed in the report. The order of
:data:`BUILDERS` is the order of the report.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from crankdyn.engine.model import Engine
from crankdyn.session import Analysis

if TYPE_CHECKING:
    from crankdyn.report.model import Section

__all__ = ["BUILDERS", "Context", "NotApplicable", "NotRequested", "builders"]

BUILDERS = (
    "kinematics",
    "pressure",
    "forces",
    "torque",
    "firing",
    "balance",
    "flywheel",
    "torsion_model",
    "torsion_modes",
    "torsion_response",
    "crankshaft",
    "crankshaft_beam",
    "measurement",
)


class NotApplicable(Exception):
    """The analysis does not apply to this engine; the message says why."""


class NotRequested(NotApplicable):
    """An optional section the user did not ask for (no note in the report)."""


@dataclass
class Context:
    """What the builders share: the analysis session (every number of the report comes from
    it, so the report agrees with the command line, the study runner and notebooks) and the
    optional inputs the user gave (a measurement).

    Parameters
    ----------
    analysis : crankdyn.session.Analysis
        The analysis session of the engine at its operating point (SI units).
    measurement : crankdyn.report.sections.measurement.MeasurementInput or None
        A measured torsiograph signal to hold against the model, or None.
    """

    analysis: Analysis
    measurement: Any = None  # sections.measurement.MeasurementInput, or None

    @property
    def engine(self) -> Engine:
        """The engine the report is about (every report is of an engine)."""
        engine = self.analysis.engine
        assert engine is not None  # build_report makes the session of an engine
        return engine

    @property
    def speed(self) -> float:
        """The operating point (rad/s)."""
        return self.analysis.speed


def builders() -> list[tuple[str, Callable[[Context], Section]]]:
    """The section builders in report order (:data:`BUILDERS`).

    Returns
    -------
    list of (str, callable)
        Each section's name and its ``build(ctx)`` function, which returns a
        :class:`~crankdyn.report.model.Section` or raises :class:`NotApplicable`.

    Examples
    --------
    >>> [name for name, _ in builders()][:3]
    ['kinematics', 'pressure', 'forces']
    """
    return [
        (name, importlib.import_module(f"crankdyn.report.sections.{name}").build)
        for name in BUILDERS
    ]
