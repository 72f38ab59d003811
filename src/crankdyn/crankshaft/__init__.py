"""The crankshaft's fatigue strength by IACS UR M53, "Calculation of crankshafts for I.C.
engines" (docs/crankshaft.md).

- :mod:`crankdyn.crankshaft.geometry`: the domain objects of the engine file's ``[crankshaft]``
  (:class:`Crankshaft`, :class:`CrankshaftGeometry`, :class:`CrankshaftMaterial`,
  :class:`ShrinkFit`, :class:`StressFactors`);
- :mod:`crankdyn.crankshaft.m53`: the rule's formulas, each with its clause;
- :mod:`crankdyn.crankshaft.loads`: the throw's bending moments and forces over the cycle by the
  statically determinate method;
- :mod:`crankdyn.crankshaft.strength`: :func:`crankshaft_strength`, the check of an engine;
- :mod:`crankdyn.crankshaft.result`: :class:`CrankshaftResult`, its summary and verdicts;
- the crankshaft as a structure (a 3-D beam model of the throws: coupled torsional, axial and
  bending vibration): :mod:`crankdyn.crankshaft.beam_elements`, :mod:`~crankdyn.crankshaft.
  beam_model`, :mod:`~crankdyn.crankshaft.beam_modes`, :mod:`~crankdyn.crankshaft.beam_stiffness`,
  :mod:`~crankdyn.crankshaft.beam_response`.

The domain objects are imported here; the analysis on first use (the engine model imports this
package, and the analysis imports the engine model).
"""

from typing import Any

from crankdyn.crankshaft.geometry import (
    Crankshaft,
    CrankshaftGeometry,
    CrankshaftMaterial,
    ShrinkFit,
    StressFactors,
)

__all__ = [
    "Crankshaft",
    "CrankshaftGeometry",
    "CrankshaftMaterial",
    "CrankshaftResult",
    "ShrinkFit",
    "StressFactors",
    "crankshaft_strength",
]


def __getattr__(name: str) -> Any:
    """The analysis and its result, imported on first use (module docstring)."""
    if name == "crankshaft_strength":
        from crankdyn.crankshaft.strength import crankshaft_strength

        return crankshaft_strength
    if name == "CrankshaftResult":
        from crankdyn.crankshaft.result import CrankshaftResult

        return CrankshaftResult
    raise AttributeError(f"module 'crankdyn.crankshaft' has no attribute {name!r}")
