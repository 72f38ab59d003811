"""Result objects of a torsional vibration calculation (analysis): verdict rows, barred speed
ranges, passages through them, one result per running condition, one per transient event and
the whole TVC."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np

from crankdyn.constants import RPM
from crankdyn.results import Result, scalar
from crankdyn.summary import (
    SummaryColumn,
    SummaryTable,
    Verdict,
    derived,
    verdict_of,
    verdict_status,
)

_HZ = 1.0 / (2.0 * math.pi)
"""rad/s to Hz."""

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.engine.model import Engine
    from crankdyn.plausibility import PlausibilityWarning
    from crankdyn.torsion.campbell import CampbellResult
    from crankdyn.torsion.event_result import EventResult
    from crankdyn.torsion.modal import ModalResult
    from crankdyn.torsion.mode_table import ModeTable
    from crankdyn.torsion.model import TorsionModel
    from crankdyn.torsion.response import ResponseResult
    from crankdyn.tvc.checks import Check
    from crankdyn.tvc.spec import TvcSpec

__all__ = [
    "BarredSpeedRange",
    "ConditionResult",
    "EventCondition",
    "EventCurve",
    "Passage",
    "TvcResult",
    "Verdict",
    "truncation_fields",
]


@dataclass(frozen=True)
class BarredSpeedRange(Result):
    """A barred speed range of one component in one condition (rad/s; exported in rpm).

    ``exceeds_start``/``exceeds_end`` where the response exceeds the continuous limit (ends
    bisected to 0.01 rpm, :func:`crankdyn.torsion.rules.exceedances`), ``start``/``end`` the
    declared range after the rule set's least range (:func:`crankdyn.tvc.limits.barred_limits`)
    and the tachometer tolerance; ``permitted`` whether the rule allows a barred range there
    (IACS UR M68.4: below 0.8 n_0 and under tau_T; a coupling under T_Kmax, DIN 740-2);
    ``source`` and ``clause`` the rule text with its edition and the clauses the range's
    permission and margins come from (:func:`crankdyn.tvc.evaluate.margins`).

    Examples
    --------
    >>> from crankdyn.constants import RPM
    >>> b = BarredSpeedRange(component="intermediate shaft", condition="normal firing",
    ...                      start=280 / RPM, end=320 / RPM, permitted=True,
    ...                      exceeds_start=290 / RPM, exceeds_end=310 / RPM,
    ...                      critical_speed=300 / RPM, worst_ratio=1.2, reason="", margins="")
    >>> b.to_dict()["start_rpm"], b.to_dict()["end_rpm"]
    (280.0, 320.0)
    """

    component: str = scalar("component", "Component", "")
    condition: str = scalar("condition", "Condition", "")
    start: float = scalar("start_rpm", "From", "rpm", RPM)
    end: float = scalar("end_rpm", "To", "rpm", RPM)
    permitted: bool = scalar("permitted", "Permitted", "")
    exceeds_start: float = scalar("exceeds_from_rpm", "Limit exceeded from", "rpm", RPM)
    exceeds_end: float = scalar("exceeds_to_rpm", "Limit exceeded to", "rpm", RPM)
    critical_speed: float = scalar("critical_speed_rpm", "Largest response at", "rpm", RPM)
    worst_ratio: float = scalar("worst_to_limit", "Largest value / continuous limit", "")
    reason: str = scalar("reason", "Why", "")
    margins: str = scalar("margins", "Margins", "")
    source: str = scalar("source", "Rule", "", default="")
    clause: str = scalar("clause", "Clause", "", default="")


BARRED_COLUMNS = (
    SummaryColumn("component", "Component"),
    SummaryColumn("condition", "Condition"),
    SummaryColumn("exceeds_from_rpm", "Found from", "rpm"),
    SummaryColumn("exceeds_to_rpm", "Found to", "rpm"),
    SummaryColumn("start_rpm", "Declared from", "rpm"),
    SummaryColumn("end_rpm", "Declared to", "rpm"),
    SummaryColumn("permitted", "Permitted"),
    SummaryColumn("reason", "Why"),
    SummaryColumn("clause", "Rule clause"),
)
"""The columns of a barred-range table, in every front end: each range as found (where the
limit is exceeded) and as declared (widened), permitted or not and why."""


def barred_table(
    ranges: tuple[BarredSpeedRange, ...], title: str = "Barred speed ranges"
) -> SummaryTable:
    """The barred ranges as a summary table (:data:`BARRED_COLUMNS`), speeds in rpm to 0.1 rpm
    (their ends are bisected to 0.01 rpm; one value per end, from the range itself)."""
    rows = tuple(
        (
            b.component,
            b.condition,
            round(b.exceeds_start * RPM, 1),
            round(b.exceeds_end * RPM, 1),
            round(b.start * RPM, 1),
            round(b.end * RPM, 1),
            "yes" if b.permitted else "no",
            b.reason,
            f"{b.source}, {b.clause}" if b.clause else b.source,
        )
        for b in ranges
    )
    return SummaryTable("barred_speed_ranges", title, BARRED_COLUMNS, rows)


_TRUNCATION_SCALARS: dict[str, tuple[tuple[Any, ...], Any]] = {
    "modes_kept": (("modes_kept", "Elastic modes integrated in time", ""), 0),
    "cutoff_frequency": (("cutoff_frequency_hz", "Modal cut-off frequency", "Hz", _HZ), None),
    "truncation_error": (
        ("truncation_error_Nm", "Truncation error bound of the element torques", "N·m"),
        0.0,
    ),
    "truncation": (("truncation", "Modal truncation", ""), ""),
}
"""The modal truncation's fields of a run of the TVC (:class:`Passage`, :class:`EventCondition`;
:func:`truncation_fields`): key, label, unit (and display scale), and the default of a run that
carried every mode."""


def _truncation_scalar(name: str) -> Any:
    """The declaration of the truncation field ``name`` (:data:`_TRUNCATION_SCALARS`): one
    declaration for the passages and the events."""
    args, default = _TRUNCATION_SCALARS[name]
    return scalar(*args, default=default)


@dataclass(frozen=True)
class Passage(Result):
    """A time-domain run-up through a barred range: the time spent in it (s) and the run's
    speeds (rad/s; exported in rpm).

    The time in the range is the integral of J dOmega / (T_engine - T_load) over it (Newton's
    second law of the whole line; module docstring of :mod:`crankdyn.tvc.analysis`).

    Parameters
    ----------
    transient : EventResult or None
        The time-domain run (:func:`crankdyn.torsion.event_run.event_response`, a speed ramp;
        not exported).
    elements : tuple of int
        The model's shaft indices of the component whose barred range this is (for plots).
    modes_kept, cutoff_frequency, truncation_error, truncation
        The run's modal truncation (:func:`truncation_fields`).
    """

    condition: str = scalar("condition", "Condition", "")
    start: float = scalar("start_rpm", "From", "rpm", RPM)
    end: float = scalar("end_rpm", "To", "rpm", RPM)
    time_in_range: float = scalar("time_in_range_s", "Time in the range", "s")
    acceleration_torque: float = scalar(
        "least_acceleration_torque_Nm", "Least acceleration torque", "N·m"
    )
    run_from: float = scalar("run_from_rpm", "Run from", "rpm", RPM)
    run_to: float = scalar("run_to_rpm", "Run to", "rpm", RPM)
    duration: float = scalar("duration_s", "Duration of the run", "s")
    note: str = scalar("note", "How", "")
    transient: EventResult | None = field(default=None, repr=False, compare=False)
    elements: tuple[int, ...] = field(default=(), repr=False, compare=False)
    modes_kept: int = _truncation_scalar("modes_kept")
    cutoff_frequency: float | None = _truncation_scalar("cutoff_frequency")
    truncation_error: float = _truncation_scalar("truncation_error")
    truncation: str = _truncation_scalar("truncation")


def truncation_fields(run: EventResult) -> dict[str, Any]:
    """The modal truncation of an event's or a passage's run as the fields of
    :class:`EventCondition` and :class:`Passage` (:mod:`crankdyn.torsion.integrator`, "Modal
    truncation"; the note of the run).

    Parameters
    ----------
    run : EventResult
        The run.

    Returns
    -------
    dict
        ``modes_kept``, ``cutoff_frequency`` (rad/s or None), ``truncation_error`` (N m) and
        ``truncation`` (words: the run's truncation, and why it was run again at a higher
        cut-off or with every mode, :func:`crankdyn.tvc.events.decided`; "" for neither).
    """
    found = [n for n in run.notes if n.startswith("modal truncation")][:1]
    words = "; ".join(found + [n for n in run.notes if n.startswith("run again")])
    return {
        "modes_kept": int(run.modes_kept),
        "cutoff_frequency": run.cutoff_frequency,
        "truncation_error": float(run.truncation_error),
        "truncation": words,
    }


_TRUNCATION_COLUMNS = (
    SummaryColumn("modes_kept", "Modes integrated"),
    SummaryColumn("cutoff_frequency_hz", "Modal cut-off", "Hz"),
    SummaryColumn("truncation_error_Nm", "Truncation bound", "N·m"),
)
"""The modal truncation's columns of the events' and the passages' tables."""


def _truncation_columns(items: Sequence[EventCondition | Passage]) -> tuple[SummaryColumn, ...]:
    """:data:`_TRUNCATION_COLUMNS` where one of the runs truncated its modes (none where every
    run integrated every mode: a model below :data:`crankdyn.tvc.events.EVENT_TRUNCATION_DOFS`
    degrees of freedom)."""
    truncated = any(item.cutoff_frequency is not None for item in items)
    return _TRUNCATION_COLUMNS if truncated else ()


def _truncation_cells(
    item: EventCondition | Passage, columns: tuple[SummaryColumn, ...]
) -> tuple[Any, ...]:
    """The cells of the truncation's ``columns`` (:func:`_truncation_columns`) of an event or a
    passage (SI values but the cut-off, in Hz as its column says)."""
    if not columns:
        return ()
    cutoff = item.cutoff_frequency
    return (item.modes_kept, None if cutoff is None else cutoff * _HZ, item.truncation_error)


def _largest_m68_ratio(condition: Any) -> tuple[float, str] | None:
    """The largest synthesised stress / tau_C of the IACS UR M68 shafts over the condition's
    resolved response (every speed), with the shaft and speed; None without an M68 check."""
    r = condition.response
    found = None
    for check in condition.curves.values():
        if not check.m68 or r is None:
            continue
        speeds = np.asarray(r.speed, dtype=float)
        with np.errstate(invalid="ignore", divide="ignore"):
            ratio = np.asarray(check.curve(r)) / np.asarray(check.limit(speeds))
        if not np.isfinite(ratio).any():
            continue
        k = int(np.nanargmax(ratio))
        if found is None or ratio[k] > found[0]:
            found = (float(ratio[k]), f"{check.component} at {speeds[k] * RPM:.6g} rpm")
    return found


@dataclass(frozen=True)
class ConditionResult(Result):
    """One running condition: its response, verdicts and barred ranges (speeds in rad/s,
    exported in rpm).

    Parameters
    ----------
    response : ResponseResult or None
        The condition's resolved forced response
        (:func:`crankdyn.torsion.sweep.forced_response`; for the misfire conditions the
        worst cylinder's); not exported.
    curves : dict
        The checks plotted, {(component, quantity): :class:`crankdyn.tvc.analysis.Check`}; not
        exported.
    warnings : tuple of crankdyn.plausibility.PlausibilityWarning
        The input warnings of the model's file(s) (:mod:`crankdyn.io.plausibility`), given by
        the analysis session (not exported as a field: ``to_dict`` lists them under
        ``input_warnings``).
    """

    name: str = scalar("condition", "Condition", "")
    kind: str = scalar("kind", "Kind", "")
    low: float = scalar("from_rpm", "Speed range from", "rpm", RPM, summary=False)
    high: float = scalar("to_rpm", "Speed range to", "rpm", RPM, summary=False)
    description: str = scalar("description", "Description", "")
    verdicts: tuple[Verdict, ...] = scalar("verdicts", "Verdicts", "", summary=False)
    barred_ranges: tuple[BarredSpeedRange, ...] = scalar(
        "barred_speed_ranges", "Barred speed ranges", "", summary=False
    )
    passages: tuple[Passage, ...] = scalar("passages", "Passages", "", summary=False)
    response: ResponseResult | None = field(default=None, repr=False, compare=False)
    curves: dict[tuple[str, str], Check] = field(default_factory=dict, repr=False, compare=False)
    warnings: tuple[PlausibilityWarning, ...] = field(default=(), repr=False, compare=False)

    FIGURES = (
        derived(
            "condition_passed", "condition_passed", "Every check passed", "",
            lambda c: all(v.passed for v in c.verdicts) if c.verdicts else None,
            status=lambda passed: "pass" if passed else "fail", headline=True,
        ),
        derived(
            "max_stress_ratio", "max_stress_ratio",
            "Largest shaft stress / permissible τ_C (the rule set's)", "",
            _largest_m68_ratio, reduction="max over the M68 shafts and the resolved speeds",
            better="min", unavailable="the torsional model has no [rules] (crankdyn docs "
            "torsion-file): no IACS UR M68 check",
        ),
        derived(
            "condition_worst_margin", "condition_worst_margin",
            "Smallest margin of the condition's verdict rows", "",
            lambda c: _worst(c), reduction="min over the verdict rows", better="max",
        ),
    )  # fmt: skip

    @property
    def passed(self) -> bool:
        """Whether every verdict row of the condition passed (False without a row: nothing was
        checked)."""
        return bool(self.verdicts) and all(v.passed for v in self.verdicts)

    def summary_verdicts(self) -> list[Verdict]:
        """The condition's verdict rows.

        Returns
        -------
        list of crankdyn.summary.Verdict
            The rows.
        """
        return list(self.verdicts)

    def summary_tables(self) -> list[SummaryTable]:
        """The condition's barred speed ranges, as found and as declared, and why.

        Returns
        -------
        list of crankdyn.summary.SummaryTable
            The tables.
        """
        return [barred_table(self.barred_ranges)] if self.barred_ranges else []

    def plot(self, fig: Figure | None = None) -> Figure:
        """Every checked quantity as a fraction of its limit against speed, the barred ranges
        shaded.

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.tvc import plot_condition

        return plot_condition(self, fig=fig)

    def plot_orders(self, fig: Figure | None = None) -> Figure:
        """Every component that bars speeds: its quantity per order and synthesised against
        its limits (:func:`crankdyn.plots.tvc.plot_condition_orders`).

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.tvc import plot_condition_orders

        return plot_condition_orders(self, fig=fig)

    def plot_stress_limits(self, fig: Figure | None = None) -> Figure:
        """The shafts checked by IACS UR M68: stress against tau_C and tau_T with the barred
        ranges (:func:`crankdyn.plots.torsion_response.plot_stress_limits`).

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.torsion_response import plot_stress_limits

        return plot_stress_limits(self, fig=fig)


@dataclass(frozen=True)
class EventCurve:
    """One check's quantity over a transient event's kept samples, and its limit there (for the
    event's plot; :mod:`crankdyn.tvc.events`).

    Parameters
    ----------
    component : str
        The component.
    quantity : str
        What is drawn (``"vibratory shear stress"``, ``"torque"``, ``"drop below the mean"``).
    unit : str
        The unit of ``value`` and ``limit`` (SI).
    value : numpy.ndarray
        (time,) the quantity at the run's kept samples.
    limit : numpy.ndarray
        (time,) the governing (smallest) limit at each sample's speed.
    limit_name : str
        The limit's name (``"τ_T"``, ``"T_Kmax"``).
    torque : bool
        Whether ``value`` is an element's torque (drawn in the torque panel with its limit).
    """

    component: str
    quantity: str
    unit: str
    value: np.ndarray
    limit: np.ndarray
    limit_name: str
    torque: bool = False


@dataclass(frozen=True)
class EventCondition(Result):
    """A transient event of the TVC (``[[tvc.event]]``): its run through the line and its
    verdict rows, every check with an event reading against its limits
    (:func:`crankdyn.tvc.evaluate.evaluate_event`; speeds in rad/s, exported in rpm).

    Parameters
    ----------
    run : EventResult or None
        The run (:func:`crankdyn.torsion.event_run.event_response`; not exported).
    modes_kept, cutoff_frequency, truncation_error, truncation
        The run's modal truncation (:func:`truncation_fields`): the modes integrated, the
        cut-off (rad/s; exported in Hz), the bound of the element torques' error (N m), in
        words.
    curves : tuple of EventCurve
        Every checked quantity over the run, with its limit (for the plot; not exported).
    """

    title = "Transient event"
    name: str = scalar("condition", "Condition", "")
    kind: str = scalar("event_kind", "Kind of event", "")
    severity: str = scalar("severity", "Severity", "")
    description: str = scalar("description", "Description", "")
    speed: float = scalar("speed_before_rpm", "Speed before the event", "rpm", RPM, summary=False)
    duration: float = scalar("duration_s", "Duration of the run", "s", summary=False)
    source: str = scalar("source", "Source of the event", "", summary=False)
    verdicts: tuple[Verdict, ...] = scalar("verdicts", "Verdicts", "", summary=False)
    run: EventResult | None = field(default=None, repr=False, compare=False)
    curves: tuple[EventCurve, ...] = field(default=(), repr=False, compare=False)
    modes_kept: int = _truncation_scalar("modes_kept")
    cutoff_frequency: float | None = _truncation_scalar("cutoff_frequency")
    truncation_error: float = _truncation_scalar("truncation_error")
    truncation: str = _truncation_scalar("truncation")

    FIGURES = (
        derived(
            "condition_passed", "condition_passed", "Every check passed", "",
            lambda c: all(v.passed for v in c.verdicts) if c.verdicts else None,
            status=lambda passed: "pass" if passed else "fail", headline=True,
        ),
        derived(
            "condition_worst_margin", "condition_worst_margin",
            "Smallest margin of the event's verdict rows", "",
            lambda c: _worst(c), reduction="min over the verdict rows", better="max",
        ),
    )  # fmt: skip

    def summary_verdicts(self) -> list[Verdict]:
        """The event's verdict rows.

        Returns
        -------
        list of crankdyn.summary.Verdict
            The rows.
        """
        return list(self.verdicts)

    def plot(self, fig: Figure | None = None) -> Figure:
        """The event's time history with its limits: every checked quantity as a fraction of
        its limit, the couplings' and gear meshes' torques with their limits, and the speeds
        (:func:`crankdyn.plots.events.plot_event_checks`).

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            A figure to draw into; None makes a new one.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.events import plot_event_checks

        return plot_event_checks(self, fig=fig)


@dataclass(frozen=True)
class TvcResult(Result):
    """A torsional vibration calculation (:func:`crankdyn.tvc.tvc`): the installation, modes,
    every condition's verdicts and barred ranges, and the overall verdict.

    ``to_dict`` carries every verdict row in ``verdicts`` and every barred range in
    ``barred_speed_ranges``. The fields below are not exported.

    Parameters
    ----------
    model : TorsionModel or None
        The model as calculated (with the load law's excitation).
    engine : Engine or None
        The engine whose cylinders excite it, or None.
    modes : ModalResult or None
        The model's natural modes (:func:`crankdyn.torsion.modal.natural_modes`).
    mode_table : ModeTable or None
        The lowest modes' relative amplitudes and the relative vector sums per order
        (:func:`crankdyn.torsion.mode_table.excited_mode_table`).
    campbell : CampbellResult or None
        The Campbell diagram over the conditions' speeds
        (:func:`crankdyn.torsion.campbell.campbell`), None where it could not be drawn.
    spec : TvcSpec or None
        The settings the calculation ran with.
    condition_results : tuple of ConditionResult
        Every condition, with its response (the same objects as ``conditions``).
    warnings : tuple of crankdyn.plausibility.PlausibilityWarning
        The input warnings of the model's file(s) (:mod:`crankdyn.io.plausibility`), given by
        the analysis session (not exported as a field: ``to_dict`` lists them under
        ``input_warnings``).

    Examples
    --------
    >>> from crankdyn.constants import RPM
    >>> row = dict(condition="normal firing", passed=True, speed=300 / RPM)
    >>> shaft = Verdict(component="intermediate shaft", quantity="stress", worst=30e6,
    ...                 limit=40e6, unit="Pa", margin=0.25, source="IACS UR M68.4", **row)
    >>> row["passed"] = False
    >>> coupling = Verdict(component="coupling C1", quantity="torque vs T_KW", worst=12e3,
    ...                    limit=10e3, unit="N·m", margin=-0.2, source="DIN 740-2", **row)
    >>> result = TvcResult(model_name="demo", rated_speed=500 / RPM, load="propeller",
    ...                    passed=False, verdicts=(shaft, coupling), barred_ranges=(),
    ...                    passages=(), conditions=(), notes=(), tachometer_tolerance=0.02,
    ...                    rules="iacs-m68")
    >>> [v.component for v in result.failed()], result.worst_margin()
    (['coupling C1'], -0.2)
    >>> result.to_dict()["rated_speed_rpm"]
    500.0
    """

    title = "Torsional vibration calculation"
    model_name: str = scalar("model", "Installation", "")
    rated_speed: float = scalar("rated_speed_rpm", "Rated speed n_0", "rpm", RPM)
    load: str = scalar("load", "Load", "")
    passed: bool = scalar("passed", "Passed", "", summary=False)
    verdicts: tuple[Verdict, ...] = scalar("verdicts", "Verdicts", "", summary=False)
    barred_ranges: tuple[BarredSpeedRange, ...] = scalar(
        "barred_speed_ranges", "Barred speed ranges", "", summary=False
    )
    passages: tuple[Passage, ...] = scalar(
        "passages", "Passages through barred ranges", "", summary=False
    )
    conditions: tuple[ConditionResult, ...] = scalar("conditions", "Conditions", "", summary=False)
    notes: tuple[str, ...] = scalar("notes", "Notes", "")
    tachometer_tolerance: float = scalar("tachometer_tolerance", "Tachometer tolerance", "")
    rules: str = scalar("rules", "Rule set", "")
    events: tuple[EventCondition, ...] = scalar(
        "events", "Transient events", "", summary=False, default=()
    )
    model: TorsionModel | None = field(default=None, repr=False, compare=False)
    engine: Engine | None = field(default=None, repr=False, compare=False)
    modes: ModalResult | None = field(default=None, repr=False, compare=False)
    mode_table: ModeTable | None = field(default=None, repr=False, compare=False)
    campbell: CampbellResult | None = field(default=None, repr=False, compare=False)
    spec: TvcSpec | None = field(default=None, repr=False, compare=False)
    condition_results: tuple[ConditionResult, ...] = field(default=(), repr=False, compare=False)
    warnings: tuple[PlausibilityWarning, ...] = field(default=(), repr=False, compare=False)

    def to_dict(self) -> dict[str, Any]:
        """The result as a JSON-ready dict (:meth:`crankdyn.results.Result.to_dict`).

        Returns
        -------
        dict
            Every exported field (speeds in rpm, the unit in the key); the verdict rows and
            barred ranges once, in ``verdicts`` and ``barred_speed_ranges``, not again under
            each of ``conditions`` and ``events``.
        """
        out = super().to_dict()
        for key in ("conditions", "events"):
            out[key] = [
                {k: v for k, v in c.items() if k not in ("verdicts", "barred_speed_ranges")}
                for c in out.get(key, [])
            ]
        return out

    FIGURES = (
        derived(
            "verdict", "verdict", "Verdict", "", lambda r: r.summary_verdict(),
            status=verdict_status, headline=True,
        ),
        derived(
            "worst_margin", "worst_margin", "Smallest margin of the verdict rows", "",
            lambda r: _worst(r), reduction="min over the verdict rows", better="max",
            headline=True,
        ),
        derived(
            "failed_rows", "failed_rows", "Verdict rows failed", "",
            lambda r: len(r.failed()), better="min",
        ),
        derived(
            "barred_width_in_band", "barred_width_in_band_rad_s",
            "Width of the TVC's barred speed ranges inside [analysis] barred_band", "rad/s",
            lambda r: _in_band(r), better="min",
            reduction="sum over the barred ranges of their part inside the band",
            description="the barred speed ranges of every condition of crankdyn tvc, the part "
            "of each inside [analysis] barred_band",
            unavailable="the figure needs [analysis] barred_band",
        ),
    )  # fmt: skip

    def summary_verdict(self) -> str | None:
        """The overall verdict in words (:func:`crankdyn.summary.verdict_text`): ``passed``
        or ``FAILED``, with the number of input warnings it stands on.

        Returns
        -------
        str or None
            The verdict; None without verdict rows.
        """
        return verdict_of(self.verdicts, self.warnings)

    def summary_verdicts(self) -> list[Verdict]:
        """Every verdict row (every component x condition).

        Returns
        -------
        list of crankdyn.summary.Verdict
            The rows.
        """
        return list(self.verdicts)

    def summary_tables(self) -> list[SummaryTable]:
        """The conditions (speed range, verdict rows, failed, smallest margin and where, barred
        ranges), the barred speed ranges (as found and as declared, and why), the transient
        events and the passages.

        Returns
        -------
        list of crankdyn.summary.SummaryTable
            The tables.
        """
        out = [_conditions_table(self.conditions)] if self.conditions else []
        out += [barred_table(self.barred_ranges)] if self.barred_ranges else []
        events = self.event_table()
        if events is not None:
            out.append(events)
        if self.passages:
            shown = _truncation_columns(self.passages)
            out.append(
                SummaryTable(
                    "passages",
                    "Passages through the barred ranges",
                    (
                        SummaryColumn("condition", "Condition"),
                        SummaryColumn("start_rpm", "From", "rpm"),
                        SummaryColumn("end_rpm", "To", "rpm"),
                        SummaryColumn("time_in_range_s", "Time in the range", "s"),
                        SummaryColumn("note", "How"),
                        *shown,
                    ),
                    tuple(
                        (
                            p.condition,
                            round(p.start * RPM, 1),
                            round(p.end * RPM, 1),
                            p.time_in_range,
                            p.note,
                            *_truncation_cells(p, shown),
                        )
                        for p in self.passages
                    ),
                )
            )
        return out

    def event_table(self) -> SummaryTable | None:
        """The transient events: each one's kind, severity, the speed before it, the run's
        duration and the smallest margin of its rows (None without events).

        Returns
        -------
        crankdyn.summary.SummaryTable or None
            The table.
        """
        if not self.events:
            return None
        shown = _truncation_columns(self.events)
        return SummaryTable(
            "events",
            "Transient events",
            (
                SummaryColumn("condition", "Event"),
                SummaryColumn("event_kind", "Kind"),
                SummaryColumn("severity", "Severity"),
                SummaryColumn("speed_before_rpm", "Speed before", "rpm"),
                SummaryColumn("duration_s", "Run", "s"),
                SummaryColumn("worst_margin", "Smallest margin"),
                SummaryColumn("passed", "Passed"),
                *shown,
            ),
            tuple(
                (
                    e.name,
                    e.kind,
                    e.severity,
                    round(e.speed * RPM, 1),
                    e.duration,
                    w[0] if (w := _worst(e)) is not None else None,
                    "yes" if all(v.passed for v in e.verdicts) else "no",
                    *_truncation_cells(e, shown),
                )
                for e in self.events
            ),
        )

    def with_verdicts(self, rows: tuple[Verdict, ...], notes: tuple[str, ...] = ()) -> TvcResult:
        """This calculation with further verdict rows made elsewhere (the crankshaft's check by
        UR M53, :meth:`crankdyn.session.Analysis.tvc`): rendered with the others, never
        recomputed here.

        Parameters
        ----------
        rows : tuple of Verdict
            The rows, appended.
        notes : tuple of str
            Notes, appended.

        Returns
        -------
        TvcResult
            A copy; passed only if it passed and every row added passes.
        """
        from dataclasses import replace

        return replace(
            self,
            verdicts=(*self.verdicts, *rows),
            passed=bool(self.passed and all(v.passed for v in rows)),
            notes=(*self.notes, *notes),
        )

    @property
    def rule_title(self) -> str:
        """The rule set's name (:data:`crankdyn.tvc.rulesets.RULESETS`), e.g. ``"Korean
        Register (KR)"``."""
        from crankdyn.tvc.rulesets import get

        return get(self.rules).title

    def unverified_table(self) -> SummaryTable | None:
        """The clauses of the rule set that could not be verified against its text (the rows
        citing them say "not verified against the text"), or None where every clause was read.

        Returns
        -------
        crankdyn.summary.SummaryTable or None
            Columns: the value, the clause cited, where the value is taken from instead.
        """
        from crankdyn.tvc.rulesets import get, unverified

        rows = tuple(
            (name, clause.cite(), clause.value_as or clause.note)
            for name, clause in unverified(get(self.rules))
        )
        if not rows:
            return None
        return SummaryTable(
            "unverified_clauses",
            f"{self.rule_title}: values not verified against the text",
            (
                SummaryColumn("value", "Value"),
                SummaryColumn("clause", "Clause cited"),
                SummaryColumn("value_as", "Value taken as"),
            ),
            rows,
        )

    def failed(self) -> tuple[Verdict, ...]:
        """The verdict rows that did not pass.

        Returns
        -------
        tuple of Verdict
            The rows with ``passed`` False, in table order.
        """
        return tuple(v for v in self.verdicts if not v.passed)

    def worst_margin(self) -> float:
        """The smallest finite margin of all verdict rows.

        Returns
        -------
        float
            min(1 - worst / limit) over the rows (dimensionless; negative where a limit is
            exceeded), NaN when there is no row with a finite margin.
        """
        margins = [v.margin for v in self.verdicts if np.isfinite(v.margin)]
        return min(margins) if margins else float("nan")


def _conditions_table(conditions: tuple[ConditionResult, ...]) -> SummaryTable:
    """One row per condition: its speed range (rpm), verdict rows, rows failed, smallest
    margin and its component, barred ranges declared."""
    rows = []
    for c in conditions:
        worst = _worst(c)
        rows.append(
            (
                c.name,
                round(c.low * RPM, 1),
                round(c.high * RPM, 1),
                len(c.verdicts),
                sum(1 for v in c.verdicts if not v.passed),
                None if worst is None else worst[0],
                "-" if worst is None else worst[1].rsplit(", ", 1)[0],
                len(c.barred_ranges),
            )
        )
    return SummaryTable(
        "conditions",
        "Conditions",
        (
            SummaryColumn("condition", "Condition"),
            SummaryColumn("from_rpm", "From", "rpm"),
            SummaryColumn("to_rpm", "To", "rpm"),
            SummaryColumn("rows", "Verdict rows"),
            SummaryColumn("failed", "Failed"),
            SummaryColumn("smallest_margin", "Smallest margin"),
            SummaryColumn("where", "Smallest margin at"),
            SummaryColumn("barred_ranges", "Barred ranges"),
        ),
        tuple(rows),
        "Every running condition: its rows of the verdict table; margin = 1 - worst / limit.",
    )


def band_overlap(ranges: Any, low: float, high: float) -> float:
    """The total width of the parts of speed ranges inside a band.

    Parameters
    ----------
    ranges : iterable of (float, float)
        (start, end) of each range (rad/s).
    low, high : float
        The band (rad/s).

    Returns
    -------
    float
        Sum over the ranges of max(0, min(end, high) - max(start, low)) (rad/s).

    Examples
    --------
    >>> band_overlap([(10.0, 20.0), (30.0, 50.0)], 15.0, 40.0)
    15.0
    """
    return float(sum(max(0.0, min(e, high) - max(s, low)) for s, e in ranges))


def _in_band(result: TvcResult) -> float | None:
    """The width of the result's barred ranges inside its settings' ``barred_band`` (rad/s),
    None without a band."""
    band = None if result.spec is None else result.spec.barred_band
    if band is None:
        return None
    return band_overlap(((b.start, b.end) for b in result.barred_ranges), band[0], band[1])


def _worst(result: TvcResult | ConditionResult | EventCondition) -> tuple[float, str] | None:
    """The smallest finite margin of the verdict rows, with the row's component and condition."""
    rows = [v for v in result.verdicts if np.isfinite(v.margin)]
    if not rows:
        return None
    v = min(rows, key=lambda v: v.margin)
    return float(v.margin), f"{v.component}, {v.condition}"
