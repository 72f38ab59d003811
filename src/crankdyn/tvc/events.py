"""Transient events in the torsional vibration calculation (analysis): every ``[[tvc.event]]``
run through the line (:func:`crankdyn.torsion.event_run.event_response`) and judged by the
installation's own checks (:func:`crankdyn.tvc.checks.model_checks`, evaluated by
:func:`crankdyn.tvc.evaluate.evaluate_event`): the shafts' vibratory stress against tau_T, the
crank spans' against the builder's transient limit, the couplings' torque against T_Kmax and
T_Kmax1 or T_Kmax2 by the event's severity, the gear meshes' torque reversals, each row with
the time spent above its limit (docs/events.md).

How a run is set up: the line runs at ``speed`` (default the rated speed n_0) before the event
(a clutch, a start or a stop have their own speeds), under its load laws, with the engine's and
the sources' harmonic torques at the TVC's orders (``harmonics``, default true; a clutch
engagement without them), for ``duration`` (default the event's own). The integration resolves
in time the natural modes up to :data:`EVENT_MODE_FACTOR` times the highest excitation
frequency (the highest order at the run's top speed, or the event's own frequency), the modes
above quasi-statically: the modal truncation of :mod:`crankdyn.torsion.integrator`, its bound
reported with the run (:mod:`crankdyn.torsion.event_run`).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from crankdyn.constants import RPM
from crankdyn.defaults import DEFAULTS
from crankdyn.errors import InputError
from crankdyn.tvc.checks import Check, model_checks
from crankdyn.tvc.evaluate import evaluate_event
from crankdyn.tvc.result import EventCondition, EventCurve, truncation_fields

if TYPE_CHECKING:
    from crankdyn.summary import Verdict
    from crankdyn.torsion.event_result import EventResult
    from crankdyn.torsion.excitation import Excitation
    from crankdyn.torsion.model import TorsionModel
    from crankdyn.tvc.spec import TvcEvent, TvcSpec

__all__ = [
    "CUTOFF_STEPS",
    "EVENT_MODE_FACTOR",
    "EVENT_TRUNCATION_DOFS",
    "decided",
    "event_conditions",
    "event_curves",
    "judge_event",
    "truncates",
]

EVENT_MODE_FACTOR = float(DEFAULTS["event_mode_factor"].value)
"""The natural modes an event's run resolves in time: up to this factor times the highest
excitation frequency."""
EVENT_TRUNCATION_DOFS = int(DEFAULTS["event_truncation_dofs"].value)
"""From this many degrees of freedom on, the modes above the cut-off are integrated
quasi-statically (modal truncation); a smaller model's runs integrate every mode."""


def truncates(model: TorsionModel) -> bool:
    """Whether the TVC's runs (events, passages) on ``model`` truncate its modes at their
    cut-off (:data:`EVENT_TRUNCATION_DOFS`).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model.

    Returns
    -------
    bool
        True for a model of at least that many degrees of freedom.
    """
    return model.dof_count >= EVENT_TRUNCATION_DOFS


def judge_event(
    model: TorsionModel,
    run: EventResult,
    spec: TvcSpec,
    rated: float,
    *,
    checks: Sequence[Check] | None = None,
) -> EventResult:
    """An event's run with its verdict rows: the installation's checks evaluated on it
    (module docstring).

    Parameters
    ----------
    model : TorsionModel
        The line the run is of (its limits: ``[rules]``, couplings, gears).
    run : crankdyn.torsion.event_result.EventResult
        The run.
    spec : TvcSpec
        The TVC settings (the crankshaft's limit).
    rated : float
        The rated speed n_0 (rad/s), for the shafts' speed ratio.
    checks : sequence of Check or None
        The checks; None: :func:`crankdyn.tvc.checks.model_checks` of the model.

    Returns
    -------
    crankdyn.torsion.event_result.EventResult
        The run with ``verdicts``.
    """
    if checks is None:
        checks = model_checks(model, spec, rated, model.dampers)[0]
    rows = evaluate_event(run, run.event, checks)
    return dataclasses.replace(run, verdicts=tuple(rows))


def event_curves(run: EventResult, checks: Sequence[Check]) -> tuple[EventCurve, ...]:
    """Every checked quantity over the run's kept samples, with its governing (smallest) limit
    at each sample's speed (the limits evaluated on 41 speeds across the run and interpolated),
    for the event's plot.

    Parameters
    ----------
    run : crankdyn.torsion.event_result.EventResult
        The run.
    checks : sequence of Check
        The line's checks.

    Returns
    -------
    tuple of EventCurve
        One per check with an event reading.
    """
    out = []
    grid = np.linspace(float(np.min(run.speed)), float(np.max(run.speed)), 41)
    for check in checks:
        reading = check.event
        if reading is None:
            continue
        idx = [k if isinstance(k, int) else run.element_index(tuple(k)) for k in reading.elements]
        if reading.reversal:
            _drop, mean, _w, _t, _n = run.reversal(idx[0])
            sign = 1.0 if mean >= 0.0 else -1.0
            value = sign * (mean - np.asarray(run.torque)[:, idx[0]])
            out.append(
                EventCurve(
                    check.component,
                    "drop of the mesh torque below its mean",
                    "N·m",
                    value,
                    np.full(value.size, abs(mean)),
                    "|mean torque|",
                )
            )
            continue
        if reading.limits is None:
            continue
        factors = reading.factors or (1.0,) * len(idx)
        samples = [run.samples(i, vibratory=reading.vibratory) for i in idx]
        value = np.max([f * x for x, f in zip(samples, factors, strict=True)], axis=0)
        levels = np.array(
            [min((lim.value for lim in reading.limits(w, run.severity)), default=math.nan)
             for w in grid]
        )  # fmt: skip
        names = [lim.name for lim in reading.limits(float(grid[-1]), run.severity)]
        if not names:
            continue
        limit = np.interp(run.speed, grid, levels) if grid[-1] > grid[0] else levels[0]
        out.append(
            EventCurve(
                check.component,
                reading.what,
                check.unit,
                value,
                np.broadcast_to(limit, value.shape).copy(),
                "/".join(names),
                torque=not reading.vibratory and check.unit == "N·m",
            )
        )
    return tuple(out)


def _top_speed(te: TvcEvent, speed: float | None) -> float:
    """The highest reference speed of an event's run (rad/s): a start's or stop's larger end,
    a clutch's faster half, else the speed before the event."""
    event: Any = te.event
    if hasattr(event, "start_speed"):
        return max(float(event.start_speed), float(event.end_speed))
    if hasattr(event, "speeds"):
        return max(abs(float(v)) for v in event.speeds)
    return float(speed or 0.0)


CUTOFF_STEPS: tuple[float | None, ...] = (1.0, 4.0, None)
"""The cut-offs a truncated run of the TVC is tried at, as multiples of its own (the modes up
to :data:`EVENT_MODE_FACTOR` times the highest excitation frequency), until no row is
undecided: its own, four times it, then every mode (None). On a line subdivided into 1000
masses the bound fell by four orders of magnitude from the first cut-off to the second (the
shafts' element modes begin just above the first), for about twice the run's time."""


def decided(
    model: TorsionModel,
    run_with: Callable[[float | None], EventResult],
    judge: Callable[[EventResult], list[Verdict]],
) -> tuple[EventResult, list[Verdict]]:
    """A run of the TVC (an event's, a passage's) and its verdict rows, no row left to the
    modal truncation: a large line's run truncates (:func:`truncates`) at its cut-off, and
    while the truncation's bound could overturn one of its rows (:attr:`crankdyn.summary.
    Verdict.undecided`: the row's worst value within the bound of its limit) it is run again
    at the next of :data:`CUTOFF_STEPS`, the last with every mode, exactly; the rows are those
    of the last run (its notes say why it was run again).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The line.
    run_with : callable
        ``run_with(scale)`` -> the run with its cut-off times ``scale``, or with every mode
        (``scale`` None).
    judge : callable
        ``judge(run)`` -> its verdict rows.

    Returns
    -------
    run : crankdyn.torsion.event_result.EventResult
        The run the rows stand on.
    rows : list of crankdyn.summary.Verdict
        Its verdict rows.
    """
    steps = CUTOFF_STEPS if truncates(model) else (None,)
    why: list[str] = []
    for k, scale in enumerate(steps):
        run = run_with(scale)
        rows = judge(run)
        undecided = [v for v in rows if v.undecided]
        if not undecided or k == len(steps) - 1:
            break
        first, following = undecided[0], steps[k + 1]
        how = "with every mode" if following is None else f"with {following:g} times its cut-off"
        why.append(
            f"run again {how}: the modal truncation's bound could overturn {len(undecided)} "
            f"row(s) ({first.component}: {first.worst:.6g} against {first.limit:.6g} "
            f"{first.unit}, bound {first.error_bound:.3g})"
        )
    if why:
        run = dataclasses.replace(run, notes=(*run.notes, *why))
    return run, rows


def _run(
    model: TorsionModel,
    te: TvcEvent,
    rated: float,
    excitation: Excitation | None,
    orders: NDArray[np.float64],
    truncate: bool | None = None,
    scale: float = 1.0,
) -> EventResult:
    """One event's run (module docstring), truncated at ``scale`` times its cut-off or with
    every mode (``truncate`` None: as :func:`truncates` says of the line)."""
    from crankdyn.torsion.event_run import event_response
    from crankdyn.torsion.events import ClutchEngagement, SpeedChange

    event = te.event
    own = isinstance(event, (ClutchEngagement, SpeedChange))
    speed = te.speed if te.speed is not None else (None if own else rated)
    harmonic = te.harmonics and excitation is not None and not isinstance(event, ClutchEngagement)
    top = _top_speed(te, speed)
    highest = float(np.max(orders)) * top if harmonic and orders.size else 0.0
    try:
        own_frequency = float(getattr(event, "frequency", lambda: 0.0)())
    except InputError:  # an ice sequence laid out on the run's speed: below the orders'
        own_frequency = 0.0
    max_frequency = scale * EVENT_MODE_FACTOR * max(highest, own_frequency, 2.0 * math.pi * 50.0)
    return event_response(
        model,
        event,
        speed=speed,
        duration=te.duration,
        excitation=excitation if harmonic else None,
        orders=orders if harmonic else None,
        max_frequency=max_frequency,
        truncate=truncates(model) if truncate is None else truncate,
    )


def event_conditions(
    model: TorsionModel,
    spec: TvcSpec,
    rated: float,
    excitation: Excitation | None,
    orders: NDArray[np.float64],
    checks: Sequence[Check],
) -> list[EventCondition]:
    """Every ``[[tvc.event]]`` of the settings, run and judged (module docstring).

    Parameters
    ----------
    model : TorsionModel
        The installation (with its load law's excitation).
    spec : TvcSpec
        The settings (``events``).
    rated : float
        The rated speed n_0 (rad/s).
    excitation : Excitation or None
        The normal-firing excitation (the harmonic torques of the runs), or None.
    orders : numpy.ndarray
        The TVC's orders.
    checks : sequence of Check
        The installation's checks (with its own dampers).

    Returns
    -------
    list of EventCondition
        In the order of the settings.

    Raises
    ------
    InputError
        As :func:`crankdyn.torsion.event_run.event_response` (an unknown mass, a clutch
        between masses no element joins, orders the model cannot take).
    """
    out = []
    for te in spec.events:

        def run_with(scale: float | None, te: TvcEvent = te) -> EventResult:
            return _run(model, te, rated, excitation, orders, scale is not None, scale or 1.0)

        found, rows = decided(model, run_with, lambda r: evaluate_event(r, r.event, checks))
        run = dataclasses.replace(found, verdicts=tuple(rows))
        event: Any = te.event
        if hasattr(event, "speeds"):  # a clutch: the engine's half
            speed = float(event.speeds[0])
        elif hasattr(event, "start_speed"):
            speed = float(event.start_speed)
        else:
            speed = te.speed or rated
        out.append(
            EventCondition(
                name=te.name,
                kind=run.kind,
                severity=run.severity,
                description=(
                    f"{run.kind} ({run.severity} transient condition) from "
                    f"{speed * RPM:.6g} rpm, {run.duration:.4g} s run; "
                    f"{run.source}" + _governed(event)
                ),
                speed=speed,
                duration=run.duration,
                source=run.source,
                verdicts=run.verdicts,
                run=run,
                curves=event_curves(run, checks),
                **truncation_fields(run),
            )
        )
    return out


def _governed(event: object) -> str:
    """The engine's governor of a clutch event, in words for its description ("" without)."""
    governor = getattr(event, "governor", None)
    if governor is None:
        return ""
    return (
        f"; the engine on its governor: {governor.source} (k_p = {governor.gain:.4g}, "
        f"T_i = {governor.integral_time:.4g} s, droop {governor.droop:.4g})"
    )
