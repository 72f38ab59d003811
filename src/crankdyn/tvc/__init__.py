"""The torsional vibration calculation (TVC) a classification society accepts: running
conditions (:mod:`crankdyn.tvc.conditions`), per-component limits, barred speed ranges and
their passage, transient events (:mod:`crankdyn.tvc.events`) (docs/tvc.md).

:func:`tvc` runs it (:mod:`crankdyn.tvc.analysis`) with the settings of a :class:`TvcSpec`
(:mod:`crankdyn.tvc.spec`) against the rule set it names (:mod:`crankdyn.tvc.rulesets`: IACS UR
M68, Lloyd's Register, KR, DNV, ABS, BV, every value with its clause) and the makers' limits,
and returns a :class:`TvcResult` (:mod:`crankdyn.tvc.result`).

Examples
--------
The settings' defaults: a 10 rpm user grid (the verdicts come from the resolved curves
whatever the step), a 2 % tachometer tolerance, IACS UR M68 (no added margin):

>>> from crankdyn.constants import RPM
>>> spec = TvcSpec()
>>> round(spec.step * RPM, 6), spec.tolerance, spec.rules
(10.0, 0.02, 'iacs-m68')
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
