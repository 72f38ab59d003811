"""Judging one running condition's forced response by the installation's checks: the barred
speed ranges (as found and as declared) and the verdict rows (analysis).

This is the one place a check is evaluated: ``crankdyn torsion response`` judges its response
here, ``crankdyn tvc`` every condition's and every transient event's (:func:`evaluate_event`),
``crankdyn torsion transient`` its event's, so two commands never answer the same question
differently.

Barred speed ranges. Where a component's synthesised response exceeds its continuous limit the
range *as found* is bisected to 0.01 rpm on the resolved curve
(:func:`crankdyn.torsion.rules.exceedances`); the range *as declared* is that range widened to
the selected rule set's least range around the critical speed where its text states one (KR
2025 Pt 5 Ch 4 206.1(1), which bars ranges where the stresses exceed the tau_1 of 201-203:
applied to the ranges of the rules' limits, not to a maker's limit such as a coupling's;
:func:`crankdyn.tvc.limits.barred_limits`) and by the tachometer tolerance on both sides (``[tvc]
tachometer_tolerance``, else the rule set's, else crankdyn's 2 %). A range is *permitted* when
the rule allows one there: below the highest speed ratio the check's rule gives (a propulsion
shaft 0.8 n_0: IACS UR M68.4, KR 202.1(2); a generating set's crankshaft and alternator shaft
0.9 n_0: KR 203; the declared range, margins included) and only while the response stays
below the transient limit (tau_T, the society's or the builder's transient crankshaft limit;
for a coupling T_Kmax; none given: no barred range permitted); never where it holds the rated
speed. Every barred range and every row cites its rule, edition and clause. Continuous limits
(heat, gear hammering, generator, damper) are checked over the speeds of continuous running:
the condition's range less its declared barred ranges (their ends, bisected to 0.01 rpm,
widened by that accuracy: a range declared as found, with no margin, leaves no sample of the
crossing itself in continuous running).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

import crankdyn.tvc.curves as cv
from crankdyn.constants import RPM
from crankdyn.summary import Verdict
from crankdyn.torsion.event_result import time_above
from crankdyn.torsion.rules import SPEED_TOLERANCE, exceedances
from crankdyn.tvc.limits import barred_limits
from crankdyn.tvc.result import BarredSpeedRange
from crankdyn.tvc.rulesets import cite_row

if TYPE_CHECKING:
    from crankdyn.torsion.event_result import EventResult
    from crankdyn.torsion.response import ResponseResult
    from crankdyn.torsion.rules import Exceedance
    from crankdyn.tvc.checks import Check, EventReading
    from crankdyn.tvc.spec import TvcSpec

__all__ = [
    "Found",
    "evaluate_condition",
    "evaluate_event",
    "margins",
    "merge_intervals",
    "truncation_bound",
]


@dataclass(frozen=True)
class Found:
    """A check's exceedance of its continuous limit, with the range declared for it.

    Parameters
    ----------
    check : Check
        The check.
    exceedance : crankdyn.torsion.rules.Exceedance
        Where its curve exceeds its continuous limit (the range as found).
    start, end : float
        The range as declared (rad/s): widened by the rule and the tachometer tolerance.
    """

    check: Check
    exceedance: Exceedance
    start: float
    end: float


def merge_intervals(intervals: Iterable[tuple[float, float]]) -> list[tuple[float, float]]:
    """Overlapping intervals merged, sorted.

    Parameters
    ----------
    intervals : iterable of (float, float)
        The intervals (start <= end).

    Returns
    -------
    list of (float, float)
        The merged intervals, in order.

    Examples
    --------
    >>> merge_intervals([(3.0, 4.0), (1.0, 2.0), (1.5, 2.5)])
    [(1.0, 2.5), (3.0, 4.0)]
    """
    out: list[list[float]] = []
    for a, b in sorted(intervals):
        if out and a <= out[-1][1]:
            out[-1][1] = max(out[-1][1], b)
        else:
            out.append([a, b])
    return [(a, b) for a, b in out]


def _column(
    func: Callable[[Any], NDArray[np.float64]],
) -> Callable[[Any], NDArray[np.float64]]:
    """``func`` with its result as one column (speeds x 1), the layout
    :func:`~crankdyn.torsion.rules.exceedances` reads."""
    return lambda x: func(x)[:, None]


def margins(spec: TvcSpec, rule_limit: bool = True) -> tuple[str, str, str]:
    """How a declared barred range is widened, in words, with the source and clauses: the rule
    set's least range around a critical speed (for a rule's limit only: KR 2025 Pt 5 Ch 4 206.1
    bars ranges where the stresses exceed the tau_1 of 201-203, not a maker's limit) and the
    tachometer tolerance.

    Parameters
    ----------
    spec : TvcSpec
        The settings (the rule set, the tachometer tolerance).
    rule_limit : bool
        Whether the range is a rule limit's (a shaft's, the society's crankshaft or generator
        shaft limit: the least range applies), or a maker's (a coupling's, the engine
        builder's: the range where the limit is exceeded).

    Returns
    -------
    text, source, clause : str
        ``"least range: 16 n_c/(18-λ_c) ≤ n ≤ (18-λ_c) n_c/16; tachometer tolerance ±2 %"``,
        and the rule texts and clauses (:func:`crankdyn.tvc.rulesets.cite_row`).

    Examples
    --------
    >>> from crankdyn.tvc.spec import TvcSpec
    >>> text, source, clause = margins(TvcSpec(rules="kr", tachometer_tolerance=0.01))
    >>> text
    'least range 16 n_c/(18-λ_c) ≤ n ≤ (18-λ_c) n_c/16; tachometer tolerance ±1 % (as given)'
    >>> clause
    'least range: Pt 5 Ch 4 206.1(1)'
    """
    society = spec.ruleset
    widening = society.widening
    parts = [("least range", widening.clause)]
    if not rule_limit:
        parts = []
        text = "a maker's limit: the range where it is exceeded (no society's least range)"
    elif widening.value == "none":
        text = "no least range around the critical speed (the range where the limit is exceeded)"
    else:
        text = "least range 16 n_c/(18-λ_c) ≤ n ≤ (18-λ_c) n_c/16"
    tol = spec.tolerance
    if spec.tachometer_tolerance is not None:
        how = "as given"
    elif society.tachometer.value is not None:
        how = "the rule set's"
        parts.append(("tachometer", society.tachometer.clause))
    else:
        how = "crankdyn's default: no text read states one"
    text += f"; tachometer tolerance ±{tol * 100:g} % ({how})"
    source, clause = cite_row(parts) if parts else ("", "")
    return text, source, clause


def _found(r: ResponseResult, checks: Sequence[Check], spec: TvcSpec, n0: float) -> list[Found]:
    """Every exceedance of a check that bars speeds, with its declared range: widened by the
    rule set's least range (a rule's limit: the check states its highest barred speed ratio)
    and by the tachometer tolerance on both sides."""
    tol = spec.tolerance
    out = []
    for check in checks:
        if not check.barred or not check.steady:
            continue
        widening = spec.ruleset.widening.value if check.barred_upper is not None else "none"
        for ex in exceedances(r, _column(check.curve), _column(check.limit)):
            lo, hi = barred_limits(ex.peak_speed, n0, widening)
            start = min(ex.start, lo) * (1.0 - tol)
            end = max(ex.end, hi) * (1.0 + tol)
            out.append(Found(check, ex, start, end))
    return out


def _declared_how(found: Found, spec: TvcSpec) -> str:
    """How the found range became the declared one, in words without its ends (the table's
    columns give them once, from the range itself): ``declared: the range found, widened by the
    2 % tachometer tolerance``."""
    society = spec.ruleset
    widened = []
    if society.widening.value != "none" and found.check.barred_upper is not None:
        widened.append(f"to {society.title}'s least range ({society.widening.clause.clause})")
    if spec.tolerance:
        widened.append(f"by the {spec.tolerance * 100:g} % tachometer tolerance")
    if widened:
        return f"declared: the range found, widened {' and '.join(widened)}"
    return "declared: the range found"


def _barred_range(
    r: ResponseResult, found: Found, condition: str, spec: TvcSpec, n0: float
) -> BarredSpeedRange:
    """The barred range of one exceedance: permitted or not, and why in words, with the rule
    that permits it or not."""
    check, ex = found.check, found.exceedance
    start, end = found.start, found.end
    how = _declared_how(found, spec)
    text, m_source, m_clause = margins(spec, check.barred_upper is not None)
    reasons = []
    permitted = True
    upper = check.barred_upper
    if upper is not None and end > upper * n0:
        permitted = False
        reasons.append(
            f"{how}, above {upper:g} n_0 = {upper * n0 * RPM:.1f} rpm, where {check.barred_source}"
            f" ({check.barred_clause}) permits no barred range"
        )
    if start <= n0 <= end:
        permitted = False
        reasons.append(f"{how}, which holds the rated speed n_0 = {n0 * RPM:.1f} rpm")
    if check.transient_limit is None:
        permitted = False
        reasons.append("no transient limit is given for this component")
    else:
        w = cv.resolved_worst(r, check.curve, check.transient_limit, low=ex.start, high=ex.end)
        if w is None or w[0] > w[1]:
            permitted = False
            reasons.append("the steady-state response exceeds the transient limit")
    if ex.open_start or ex.open_end:
        reasons.append("reaches an end of the swept range: sweep further")
    if permitted:
        reasons.append(
            f"{how}; limit exceeded only where a barred range is permitted: pass quickly"
        )
    sources = (
        [m_source or check.source.split(":")[0]]
        if upper is None
        else [check.barred_source, m_source]
    )
    clauses = [m_clause or check.clause] if upper is None else [check.barred_clause, m_clause]
    return BarredSpeedRange(
        component=check.component,
        condition=condition,
        start=start,
        end=end,
        permitted=permitted,
        exceeds_start=ex.start,
        exceeds_end=ex.end,
        critical_speed=ex.peak_speed,
        worst_ratio=ex.peak_ratio,
        reason="; ".join(reasons),
        margins=text,
        source=" / ".join(dict.fromkeys(sources)),
        clause="; ".join(dict.fromkeys(clauses)),
    )


def _continuous_verdicts(
    r: ResponseResult,
    checks: Sequence[Check],
    condition: str,
    excluded: Sequence[tuple[float, float]],
) -> list[Verdict]:
    """Every check's worst value over the speeds of continuous running against its limit."""
    out = []
    for check in checks:
        if not check.steady:
            continue
        worst = cv.resolved_worst(r, check.curve, check.limit, excluded)
        if worst is None:
            continue
        value, limit, speed = worst
        out.append(
            Verdict(
                component=check.component,
                condition=condition,
                quantity=check.quantity + (" (continuous running)" if excluded else ""),
                worst=value,
                limit=limit,
                unit=check.unit,
                passed=bool(value <= limit),
                source=check.source,
                clause=check.clause,
                speed=speed,
                margin=1.0 - value / limit,
                kind=check.quantity,
            )
        )
    return out


def _barred_verdicts(
    r: ResponseResult, found: Found, b: BarredSpeedRange, condition: str, n0: float
) -> list[Verdict]:
    """The verdict rows of one barred range: its end against the highest speed ratio the rule
    permits (0.8 n_0 for a propulsion shaft), the rated speed outside it, the steady state in
    it against the transient limit, and the rows a rule attaches to it."""
    check, ex = found.check, found.exceedance
    label = f"barred range {b.start * RPM:.1f}-{b.end * RPM:.1f} rpm"
    out = []
    upper = check.barred_upper
    if upper is not None:  # no barred range above upper n_0 (the declared range, margins included)
        out.append(
            Verdict(
                component=check.component,
                condition=condition,
                quantity=f"end of the declared {label} (λ = n/n_0)",
                worst=b.end / n0,
                limit=upper,
                unit="",
                passed=bool(b.end <= upper * n0),
                source=f"{b.source}: barred speed ranges only below λ = {upper:g}; margins: "
                f"{b.margins}",
                clause=b.clause,
                speed=b.end,
                note=b.reason,
                margin=1.0 - b.end / n0 / upper,
                kind="barred range end",
            )
        )
    if b.start <= n0 <= b.end:
        out.append(
            Verdict(
                component=check.component,
                condition=condition,
                quantity=f"start of the declared {label} vs the rated speed (n/n_0)",
                worst=1.0,
                limit=b.start / n0,
                unit="",
                passed=False,
                source=f"{b.source}: the rated speed cannot lie in a barred range",
                clause=b.clause,
                speed=n0,
                margin=1.0 - n0 / b.start,
                kind="barred range at n_0",
            )
        )
    if check.transient_limit is None:
        out.append(
            Verdict(
                component=check.component,
                condition=condition,
                quantity=f"{label}: no transient limit given",
                worst=ex.peak,
                limit=float(check.limit(np.array([ex.peak_speed]))[0]),
                unit=check.unit,
                passed=False,
                source=check.source,
                clause=check.clause,
                speed=ex.peak_speed,
                note="a barred range needs the component's transient limit",
                margin=1.0 - ex.peak_ratio,
                kind="barred range without a transient limit",
            )
        )
        return out
    w = cv.resolved_worst(r, check.curve, check.transient_limit, low=ex.start, high=ex.end)
    value, limit, speed = w if w is not None else (ex.peak, math.nan, ex.peak_speed)
    out.append(
        Verdict(
            component=check.component,
            condition=condition,
            quantity=f"steady state in the {label} vs the transient limit",
            worst=value,
            limit=limit,
            unit=check.unit,
            passed=bool(np.isfinite(limit) and value <= limit),
            source=check.transient_source,
            clause=check.transient_clause,
            speed=speed,
            margin=1.0 - value / limit if np.isfinite(limit) else -math.inf,
            kind="barred range steady state",
        )
    )
    if check.barred_rows is not None:
        out += check.barred_rows(b)
    return out


def evaluate_condition(
    r: ResponseResult, condition: str, checks: Sequence[Check], spec: TvcSpec, n0: float
) -> tuple[list[Verdict], list[BarredSpeedRange]]:
    """The verdict rows and barred speed ranges of one condition's resolved response (module
    docstring).

    Parameters
    ----------
    r : ResponseResult
        The condition's forced response (resolved: every peak refined).
    condition : str
        The condition's name, for the rows.
    checks : sequence of Check
        The installation's checks (:func:`crankdyn.tvc.checks.model_checks`).
    spec : TvcSpec
        The settings: the rule set (the least range around a critical speed) and the
        tachometer tolerance.
    n0 : float
        The rated speed (rad/s).

    Returns
    -------
    verdicts : list of crankdyn.summary.Verdict
        Every check's continuous verdict, then each barred range's rows.
    barred : list of BarredSpeedRange
        The barred ranges, as found and as declared, permitted or not and why.
    """
    found = _found(r, checks, spec, n0)
    barred = [_barred_range(r, f, condition, spec, n0) for f in found]
    # the ends are bisected to SPEED_TOLERANCE: continuous running starts that far outside
    excluded = merge_intervals(
        [(b.start - SPEED_TOLERANCE, b.end + SPEED_TOLERANCE) for b in barred]
    )
    verdicts = _continuous_verdicts(r, checks, condition, excluded)
    for f, b in zip(found, barred, strict=True):
        verdicts += _barred_verdicts(r, f, b, condition, n0)
    return verdicts, barred


def truncation_bound(run: EventResult, reading: EventReading | None) -> float:
    """The bound of the error a run's modal truncation leaves in a check's event quantity
    (its unit): the largest over the check's elements of the factor times the element's bound
    (:attr:`crankdyn.torsion.event_result.EventResult.truncation_torque`; the quantity is
    the largest of the factored element torques, so its error is at most the largest of
    their bounds; :mod:`crankdyn.torsion.integrator`, "Modal truncation"); 0 for a run that
    carried every mode.

    Parameters
    ----------
    run : crankdyn.torsion.event_result.EventResult
        The run.
    reading : EventReading or None
        How the check reads it (:attr:`crankdyn.tvc.checks.Check.event`).

    Returns
    -------
    float
        The bound (0 without truncation or reading).
    """
    per = run.truncation_torque
    if per is None or reading is None:
        return 0.0
    idx = [_element(run, key) for key in reading.elements]
    factors = reading.factors or (1.0,) * len(idx)
    return float(max(abs(f) * float(per[e]) for e, f in zip(idx, factors, strict=True)))


def _element(run: EventResult, key: int | tuple[str, str]) -> int:
    """The run's element of a check's key: a model shaft's index, or a rigid gear's ends."""
    return key if isinstance(key, int) else run.element_index(tuple(key))


def _event_reversal(run: EventResult, check: Check, condition: str, e: int) -> Verdict:
    """A gear mesh's torque reversal in an event: its largest drop below the run's mean
    against that mean (:meth:`crankdyn.torsion.event_result.EventResult.reversal`)."""
    drop, mean, when, reversed_time, count = run.reversal(e)
    return Verdict(
        component=check.component,
        condition=condition,
        quantity="largest drop of the mesh torque below its mean vs the mean (torque reversal)",
        worst=drop,
        limit=abs(mean),
        unit="N·m",
        passed=bool(drop < abs(mean)),
        source=check.source,
        speed=float(np.interp(when, run.time, run.speed)),
        note=(
            f"lowest at t = {when:.4g} s; reversed {reversed_time:.3g} s in all, {count} "
            f"reversal(s); mean {mean / 1e3:.6g} kN·m over the run"
            + (f" from the lock at {run.loaded_from:.4g} s" if run.loaded_from > 0.0 else "")
        ),
        margin=1.0 - drop / abs(mean) if mean != 0.0 else -math.inf,
        kind="event torque reversal",
        # drop < |mean| is the mesh torque's least value against 0: the element's own bound
        error_bound=truncation_bound(run, check.event),
    )


def evaluate_event(run: EventResult, condition: str, checks: Sequence[Check]) -> list[Verdict]:
    """The verdict rows of a transient event's run: every check with an event reading
    (:class:`crankdyn.tvc.checks.EventReading`) against its limits at the speed of its peak
    and the event's severity; the time above each limit in the row's note.

    The peak is the run's extreme of the check's elements (refined between the integration
    steps, :mod:`crankdyn.torsion.event_run`) times the check's factor (1/W_p for a stress);
    the time above a limit comes from the kept samples (resolution: the kept interval).

    Parameters
    ----------
    run : crankdyn.torsion.event_result.EventResult
        The event's run on the checks' line.
    condition : str
        The event's name, for the rows.
    checks : sequence of Check
        The line's checks (:func:`crankdyn.tvc.checks.model_checks`).

    Returns
    -------
    list of crankdyn.summary.Verdict
        One row per check and limit (a reversal row per gear mesh), in the checks' order.
    """
    out = []
    for check in checks:
        reading = check.event
        if reading is None:
            continue
        idx = [_element(run, key) for key in reading.elements]
        if reading.reversal:
            out.append(_event_reversal(run, check, condition, idx[0]))
            continue
        if reading.limits is None:
            continue
        factors = reading.factors or (1.0,) * len(idx)
        bound = truncation_bound(run, reading)
        peak = run.vibratory_peak if reading.vibratory else run.peak
        values = [f * peak(e) for e, f in zip(idx, factors, strict=True)]
        k = int(np.argmax(values))
        e, worst = idx[k], float(values[k])
        when = run.vibratory_peak_time(e) if reading.vibratory else run.peak_time(e)
        speed = float(np.interp(when, run.time, run.speed))
        samples = [run.samples(i, vibratory=reading.vibratory) for i in idx]
        series = np.max([f * x for x, f in zip(samples, factors, strict=True)], axis=0)
        for limit in reading.limits(speed, run.severity):
            above = time_above(run.time, series, limit.value) if limit.value > 0 else 0.0
            note = f"peak at t = {when:.4g} s ({run.element_names[e]}); {above:.3g} s above"
            out.append(
                Verdict(
                    component=check.component,
                    condition=condition,
                    quantity=f"largest {reading.what} in the event vs {limit.name}",
                    worst=worst,
                    limit=float(limit.value),
                    unit=check.unit,
                    passed=bool(worst <= limit.value),
                    source=limit.source,
                    clause=limit.clause,
                    speed=speed,
                    note="; ".join(x for x in (note, limit.note) if x),
                    margin=1.0 - worst / limit.value,
                    kind=f"event peak vs {limit.name}",
                    error_bound=bound,
                )
            )
    return out
