"""The torsional vibration calculation (TVC) a classification society accepts: running
conditions (:mod:`crankdyn.tvc.conditions`), per-component limits, barred speed ranges and
their passage, transient events (:mod:`crankdyn.tvc.events`) (docs/tvc.md).

:func:`tvc` runs it (:mod:`crankdyn.tvc.analysis`) with the settings of a :class:`TvcSpec`
(:mod:`crankdyn.tvc.spec`) against the limits of :mod:`crankdyn.tvc.limits` (IACS UR M68.4,
the makers' limits, the barred-range widening of Lloyd's Register), and returns a
:class:`TvcResult` (:mod:`crankdyn.tvc.result`).

Examples
--------
The settings' defaults: a 10 rpm user grid (the verdicts come from the resolved curves
whatever the step), a 2 % tachometer tolerance, IACS UR M68 without added margins:

>>> from crankdyn.constants import RPM
>>> spec = TvcSpec()
>>> round(spec.step * RPM, 6), spec.tachometer_tolerance, spec.widening
(10.0, 0.02, 'none')
"""

from crankdyn.tvc.analysis import Check, tvc
from crankdyn.tvc.limits import CrankshaftLimit
from crankdyn.tvc.result import (
    BarredSpeedRange,
    ConditionResult,
    EventCondition,
    Passage,
    TvcResult,
    Verdict,
)
from crankdyn.tvc.spec import TvcEvent, TvcSpec

__all__ = [
    "BarredSpeedRange",
    "Check",
    "ConditionResult",
    "CrankshaftLimit",
    "EventCondition",
    "Passage",
    "TvcEvent",
    "TvcResult",
    "TvcSpec",
    "Verdict",
    "tvc",
]
