"""The defaults of every analysis, in one registry (:data:`DEFAULTS`).

The analysis session (:class:`crankdyn.session.Analysis`) and the TVC (:mod:`crankdyn.tvc`) read
them; the command line, the report, the study runner and notebooks never restate them. A pure
module (numbers and the speed grid), importable from every layer. Each :class:`Default` says its
value (SI), its unit, what it does and where it comes from.

Examples
--------
>>> from crankdyn.constants import RPM
>>> round(DEFAULTS["speed_step"].value * RPM, 9), DEFAULTS["max_order"].value
(10.0, 12.0)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from crankdyn.constants import RPM
from crankdyn.errors import InputError

__all__ = [
    "DEFAULTS",
    "DELTA",
    "MAX_ORDER",
    "MAX_SPEEDS",
    "RESPONSE_BLOCK_MEMORY",
    "RULES",
    "SPEED_STEP",
    "STEP",
    "TACHOMETER_TOLERANCE",
    "Default",
    "speed_grid",
]


@dataclass(frozen=True)
class Default:
    """One default of the analyses.

    Parameters
    ----------
    name : str
        Its name (the session's keyword, the study file's ``[analysis]`` key where there is one).
    value : object
        The value, SI.
    unit : str
        The SI unit of the value (``""`` for numbers).
    help : str
        What it sets, for people.
    source : str
        Where the value comes from (a seed, a rule, a convention).
    """

    name: str
    value: Any
    unit: str
    help: str
    source: str = "crankdyn convention"


DEFAULTS: dict[str, Default] = {
    d.name: d
    for d in (
        Default(
            "step",
            math.radians(1.0),
            "rad",
            "crank-angle step of every cycle analysis; summaries (maxima, minima, means) come "
            "from this grid refined at the extrema, never from a coarser display grid",
        ),
        Default(
            "speed_step",
            10.0 / RPM,
            "rad/s",
            "speed step of the torsional sweeps over the operating range (the verdicts come "
            "from the resolved curves whatever the step)",
        ),
        Default(
            "max_order",
            12.0,
            "",
            "highest excitation order of the torsional analyses (from the cycle's fundamental "
            "order: 0.5 four-stroke, 1 two-stroke)",
        ),
        Default(
            "delta",
            0.01,
            "",
            "target degree of cyclic irregularity when the engine file gives no [flywheel] "
            "delta or inertia",
            "seed 000 section 2.4 (1/100 to 1/300 for most engines)",
        ),
        Default(
            "tachometer_tolerance",
            0.02,
            "",
            "the tachometer's tolerance by which a barred speed range is widened on both sides, "
            "where neither the model file ([tvc] tachometer_tolerance) nor the rule set states one",
            "crankdyn convention: no rule text read states a value (KR 2025 Pt 5 Ch 4 206.3 asks "
            "for the tachometer's accuracy to be regarded, without a number)",
        ),
        Default(
            "rules",
            "iacs-m68",
            "",
            "the classification society's rule set of the verdicts (limits, barred-range rules, "
            "each value with its clause; a [tvc] rules or --rules overrides it)",
            "IACS UR M68, which every IACS member society implements (crankdyn docs tvc)",
        ),
        Default(
            "idle_band",
            0.05,
            "",
            "the TVC's idle condition sweeps the idle speed +- this fraction (a governor's band "
            "around the set speed; a [tvc.speed_ranges] idle overrides it)",
            "crankdyn convention (an assumption: no rule text read states a band)",
        ),
        Default(
            "event_mode_factor",
            4.0,
            "",
            "the TVC's transient events integrate in time the natural modes up to this factor "
            "times the highest excitation frequency (the highest order at the top speed), the "
            "modes above quasi-statically (residual flexibility, the truncation's bound "
            "reported with the run)",
            "crankdyn convention",
        ),
        Default(
            "event_truncation_dofs",
            150,
            "",
            "the TVC's transient events and passages integrate the modes above the cut-off "
            "quasi-statically (modal truncation, its bound reported) from this many degrees of "
            "freedom on; a smaller model integrates every mode, exactly (it costs little there)",
            "crankdyn convention",
        ),
        Default(
            "response_block_memory",
            256.0 * 2**20,
            "B",
            "memory budget of the working arrays of one block of speeds of a forced response "
            "(the solve and the synthesis of every speed x order x degree of freedom): the "
            "speeds are evaluated in blocks that fit it, so the working memory of a sweep does "
            "not grow with its number of speeds; the block size never changes a number",
            "crankdyn convention (crankdyn docs benchmarks: the bound it gives)",
        ),
        Default(
            "governor_gain",
            10.0,
            "",
            "proportional gain k_p of the engine's speed governor in a transient event (per "
            "unit: the fraction of the rated torque per fraction of the rated speed of speed "
            "error; crankdyn.torsion.event_governor)",
            "crankdyn convention: an assumed setting of the usual order (a 1 % speed error "
            "asks for 10 % of the rated torque), to be replaced by the governor maker's",
        ),
        Default(
            "governor_integral_time",
            1.0,
            "s",
            "integral time T_i of the engine's speed governor in a transient event",
            "crankdyn convention: an assumed setting of the usual order, to be replaced by the "
            "governor maker's",
        ),
        Default(
            "governor_droop",
            0.0,
            "",
            "speed droop of the engine's speed governor in a transient event (fraction of the "
            "rated speed at rated torque; 0: isochronous)",
            "ISO 3046-4:2009 (speed droop); isochronous: a propulsion engine alone on its shaft",
        ),
        Default(
            "governor_sample_time",
            0.01,
            "s",
            "sample time of the engine's (digital) speed governor in a transient event: its "
            "torque is held between samples",
            "crankdyn convention: the update cycle of an electronic governor (milliseconds to "
            "tens of milliseconds)",
        ),
        Default(
            "max_speeds",
            100_000,
            "",
            "the largest number of speeds a sweep may have (a larger grid is refused before any "
            "work)",
        ),
    )
}
"""Every default, by name."""

STEP = float(DEFAULTS["step"].value)
"""Crank-angle step of every cycle analysis (rad)."""
SPEED_STEP = float(DEFAULTS["speed_step"].value)
"""Speed step of the torsional sweeps over the operating range (rad/s): 10 rpm."""
MAX_ORDER = float(DEFAULTS["max_order"].value)
"""Highest excitation order of the torsional analyses."""
DELTA = float(DEFAULTS["delta"].value)
"""Target degree of cyclic irregularity when the engine file gives no [flywheel] delta or
inertia (seed 000 section 2.4: 1/100 to 1/300 for most engines)."""
TACHOMETER_TOLERANCE = float(DEFAULTS["tachometer_tolerance"].value)
"""The tachometer's tolerance (fraction of the speed) a barred range is widened by."""
MAX_SPEEDS = int(DEFAULTS["max_speeds"].value)
"""The largest number of speeds of a sweep."""
RESPONSE_BLOCK_MEMORY = float(DEFAULTS["response_block_memory"].value)
"""Memory budget (bytes) of one block of speeds of a forced response's evaluation."""
RULES = str(DEFAULTS["rules"].value)
"""The rule set of the verdicts (:data:`crankdyn.tvc.rulesets.RULESETS`)."""


def speed_grid(low: float, high: float, step: float = SPEED_STEP) -> NDArray[np.float64]:
    """Speeds low, low + step, ... up to high: the one speed grid of every sweep (the command
    line, the report, the TVC and the study).

    The end is always included (after the last whole step when the step does not divide the
    range, to a relative 1e-12): a sweep covers its whole range. Each speed is the nearest
    multiple of the step in rpm when the ends and the step are round numbers in rpm, so that
    grids read 6000, not 6000.000000000001. Verdicts never depend on it: the analyses add the
    critical speeds and refine every resonance.

    Parameters
    ----------
    low, high : float
        The ends (rad/s), 0 < low <= high.
    step : float
        The step (rad/s); default :data:`SPEED_STEP` (10 rpm).

    Returns
    -------
    numpy.ndarray
        The speeds (rad/s), ascending.

    Raises
    ------
    InputError
        If the ends or the step are not positive or out of order, or there would be more than
        :data:`MAX_SPEEDS` speeds.

    Examples
    --------
    >>> (speed_grid(1000 / RPM, 1030 / RPM) * RPM).round(9).tolist()
    [1000.0, 1010.0, 1020.0, 1030.0]
    >>> (speed_grid(1000 / RPM, 1025 / RPM) * RPM).round(9).tolist()
    [1000.0, 1010.0, 1020.0, 1025.0]
    """
    if not (step > 0.0 and high >= low > 0.0):
        raise InputError(
            "expected 0 < LOW <= HIGH and a positive step",
            key="speeds",
            value=[low * RPM, high * RPM, step * RPM],
        )
    count = math.floor((high - low) / step * (1 + 1e-12)) + 1
    short = low + step * (count - 1) < high * (1.0 - 1e-12)  # the end after the last step
    if count + short > MAX_SPEEDS:
        raise InputError(
            f"too many speeds ({count + short}, more than {MAX_SPEEDS}): give a larger step",
            key="speeds",
            value=[low * RPM, high * RPM, step * RPM],
        )
    rpm = low * RPM + step * RPM * np.arange(count)
    if short:
        rpm = np.append(rpm, high * RPM)
    rounded = np.round(rpm, 9)
    return rounded / RPM
