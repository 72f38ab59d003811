"""One analysis session: every analysis of an engine (or of a stand-alone torsional model),
computed once and cached, with the defaults of every front end in one registry.

The command line, the HTML report, the TVC, the study runner and notebooks all take their
numbers from an :class:`Analysis`, so the same quantity is the same number everywhere:

>>> import crankdyn
>>> a = crankdyn.Analysis(crankdyn.Engine.example("inline6-diesel"))   # doctest: +SKIP
>>> a.torque.mean_torque, a.forces().max_gas_force  # doctest: +SKIP
>>> a.modes.frequencies_hz[a.modes.index(1)]  # elastic mode 1  # doctest: +SKIP

The defaults (crank-angle step, speed grid, orders, the flywheel's target, the tachometer
tolerance) are in :data:`crankdyn.defaults.DEFAULTS`; summaries (maxima, minima, means)
always come from the session's analysis grid, refined at the extrema, never from a coarser
display grid: a front end that shows fewer rows asks for them with ``step=`` and gets the rows
with the summary of the full-resolution analysis. The session holds no presentation: results
declare their summaries (:mod:`crankdyn.summary`) and front ends render them.

Modules: :mod:`crankdyn.defaults` (the registry and the speed grid, at the package's top),
:mod:`~crankdyn.session.core` (subject, speeds, orders, cache), :mod:`~crankdyn.session.engine`
(the cycle analyses), :mod:`~crankdyn.session.torsion` (the torsional analyses) and
:mod:`~crankdyn.session.crankshaft` (UR M53 and the crankshaft's beam model).
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from typing import Any

from crankdyn.crank.kinematics import SERIES_ORDER
from crankdyn.defaults import DEFAULTS, DELTA, MAX_ORDER, SPEED_STEP, STEP, speed_grid
from crankdyn.session.core import with_parameters
from crankdyn.session.crankshaft import CrankshaftAnalyses
from crankdyn.session.engine import EngineAnalyses

__all__ = [
    "ANALYSES",
    "DEFAULTS",
    "DELTA",
    "MAX_ORDER",
    "SERIES_ORDER",
    "SPEED_STEP",
    "STEP",
    "Analysed",
    "Analysis",
    "speed_grid",
]


@with_parameters
class Analysis(EngineAnalyses, CrankshaftAnalyses):
    """The analyses of an engine, or of a torsional model without an engine, computed once.

    Attributes are the analyses: properties for those without options (``torque``,
    ``modes``...), methods with keyword options for the others (``forces(cylinder=2)``,
    ``flywheel(delta=0.005)``); each is computed once per set of options.

    Examples
    --------
    A stand-alone torsional model has no cylinders, so no cycle analyses:

    >>> from crankdyn.engine.model import Engine
    >>> a = Analysis(Engine.example("inline6-diesel").torsion)
    >>> a.engine is None, a.cycle, a.computed()
    (True, 'four-stroke', [])
    """


@dataclass(frozen=True)
class Analysed:
    """An analysis of the session that needs no options, whose key figures a parameter study
    can keep (:mod:`crankdyn.study.figures` registers them all).

    Parameters
    ----------
    name : str
        The session's property or method (called without arguments).
    result : str
        The dotted path of its result class (imported when a study lists its figures).
    subjects : tuple of str
        What it applies to: ``"engine"``, ``"model"`` (a torsional model alone).
    """

    name: str
    result: str
    subjects: tuple[str, ...] = ("engine",)

    def result_class(self) -> Any:
        """The result class.

        Returns
        -------
        type
            The class named by :attr:`result`.
        """
        module, _, name = self.result.rpartition(".")
        return getattr(importlib.import_module(module), name)

    def of(self, analysis: Analysis) -> Any:
        """The result of this analysis in a session (computed once there).

        Parameters
        ----------
        analysis : Analysis
            The session.

        Returns
        -------
        crankdyn.results.Result
            The analysis's result.
        """
        value = getattr(analysis, self.name)
        return value() if callable(value) else value


ANALYSES: tuple[Analysed, ...] = (
    Analysed("kinematics", "crankdyn.crank.kinematics.KinematicsResult"),
    Analysed("pressure", "crankdyn.crank.indicated.PressureResult"),
    Analysed("forces", "crankdyn.engine.forces.ForcesResult"),
    Analysed("bearings", "crankdyn.engine.bearings.BearingsResult"),
    Analysed("torque", "crankdyn.engine.torque.TorqueResult"),
    Analysed("balance", "crankdyn.engine.balance.BalanceResult"),
    Analysed("flywheel", "crankdyn.engine.flywheel.FlywheelResult"),
    Analysed("modes", "crankdyn.torsion.modal.ModalResult", ("engine", "model")),
    Analysed("response", "crankdyn.torsion.response.ResponseResult", ("engine", "model")),
    Analysed("relative_angle", "crankdyn.torsion.response.RelativeAngle", ("engine", "model")),
    Analysed("judged", "crankdyn.tvc.result.ConditionResult", ("engine", "model")),
    Analysed("crankshaft", "crankdyn.crankshaft.result.CrankshaftResult"),
    Analysed("crankshaft_modes", "crankdyn.crankshaft.beam_modes.BeamModesResult"),
    Analysed("crankshaft_response", "crankdyn.crankshaft.beam_response.BeamResponseResult"),
)
"""The analyses whose key figures every front end (the study among them) takes, in report
order."""
