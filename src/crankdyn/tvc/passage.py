"""The passage through barred speed ranges in the time domain (analysis).

A time-domain run-up (:func:`crankdyn.torsion.event_run.event_response`, the exact integrator
of the transient events, starting in the steady state of its first speed; the speed a ramp,
:class:`crankdyn.torsion.events.SpeedChange`) from :data:`LEAD_IN` below to :data:`RUN_OUT`
above the declared range at the acceleration the engine's torque leaves over the load,
J_total dOmega/dt = T_engine - T_load(Omega) (Newton's second law of the whole line,
reflected to the reference shaft): the time in the range is the integral of
J dOmega / (T_engine - T_load) over it (trapezoidal rule, 400 points), the run is linear in
time with the same duration (the acceleration torque varies little across a barred range);
the largest transient stress (torque) of every component during the run, its vibratory part
(less the quasi-static torque of the mean torques), is checked against its transient limit
(tau_T, T_Kmax less the mean torque) by the component's own check
(:mod:`crankdyn.tvc.checks`). The run integrates the modes up to
:data:`crankdyn.tvc.events.EVENT_MODE_FACTOR` times the highest order's frequency at its top
speed, those above quasi-statically (the modal truncation of
:mod:`crankdyn.torsion.integrator`, its bound reported with the run).

The engine's torque (:func:`engine_torque`) is its torque-speed curve (``[tvc]
engine_torque_curve``: the torque limit of the engine builder's load diagram), else a given
constant (``engine_torque``), else, asked for by ``passage_torque = "rated"``, the rated torque
(the load law's at n_0) at every speed. Full rated torque is never assumed at low speed unless
asked: a turbocharged engine's torque limit falls with the charge air at low speed, so without
the curve the passage is not calculated and a note names the keys. The load is the load law
(the propeller law of a propulsion line), or none for a generating set that runs up unloaded
(``passage_load``). Every passage row says which torque and load were used.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import RPM
from crankdyn.summary import Verdict
from crankdyn.tvc.evaluate import merge_intervals, truncation_bound
from crankdyn.tvc.events import EVENT_MODE_FACTOR, decided
from crankdyn.tvc.result import BarredSpeedRange, Passage, truncation_fields

if TYPE_CHECKING:
    from crankdyn.torsion.model import TorsionModel
    from crankdyn.tvc.checks import Check, MeanTorque
    from crankdyn.tvc.spec import TvcSpec

__all__ = ["LEAD_IN", "RUN_OUT", "engine_torque", "load_torque", "passages"]

LEAD_IN = 0.05
"""The passage run starts this fraction below the barred range (the start-up transient of the
integration decays before the range)."""
RUN_OUT = 0.02
"""... and ends this fraction above it."""


def load_torque(model: TorsionModel, speeds: ArrayLike) -> NDArray[np.float64]:
    """The mean load torque of the model's sources' load laws, reflected to the reference shaft.

    Parameters
    ----------
    model : TorsionModel
        The installation.
    speeds : array_like
        Reference-shaft speeds (rad/s).

    Returns
    -------
    numpy.ndarray
        The load torque (N m) at each speed.
    """
    from crankdyn.torsion.sources import HarmonicSource

    n = np.asarray(speeds, dtype=float)
    total = np.zeros(n.shape)
    ratios = model.speed_ratios
    for source in model.sources:
        if not isinstance(source, HarmonicSource) or source.load is None:
            continue  # an engine carries no load law
        r = abs(float(ratios[model.index(source.at)]))
        total = total + r * source.load.at(r * n)
    return total


def engine_torque(
    spec: TvcSpec, model: TorsionModel, n0: float
) -> tuple[Callable[[ArrayLike], NDArray[np.float64]] | None, str]:
    """The engine's torque while passing a barred range, and what it is, in words (module
    docstring).

    Parameters
    ----------
    spec : TvcSpec
        The settings (``engine_torque_curve``, ``engine_torque``, ``passage_torque``).
    model : TorsionModel
        The installation (its load law gives the rated torque).
    n0 : float
        The rated speed (rad/s).

    Returns
    -------
    torque : callable or None
        ``torque(speeds)`` (N m at the reference shaft, speeds in rad/s); None where no torque
        is known (no curve, no constant, not asked for the rated torque).
    words : str
        What the torque is (for the rows), or why there is none.

    Examples
    --------
    >>> from crankdyn.tvc.spec import TvcSpec
    >>> torque, words = engine_torque(TvcSpec(engine_torque=2e4), None, 50.0)
    >>> torque([30.0, 40.0]).tolist(), words
    ([20000.0, 20000.0], 'T_engine = 20 kN·m ([tvc] engine_torque)')
    """
    if spec.engine_torque_curve is not None:
        w, q = spec.engine_torque_curve
        span = f"{q.min() / 1e3:.4g}-{q.max() / 1e3:.4g} kN·m over {w[0] * RPM:.4g}-"
        span += f"{w[-1] * RPM:.4g} rpm"
        return (
            lambda x: spec.engine_torque_at(x, math.nan),
            f"T_engine from the engine's torque-speed curve ([tvc] engine_torque_curve, {span})",
        )
    if spec.engine_torque is not None:
        value = spec.engine_torque
        return (
            lambda x: np.full(np.size(x), value),
            f"T_engine = {value / 1e3:.6g} kN·m ([tvc] engine_torque)",
        )
    if spec.passage_torque == "rated":
        rated = float(load_torque(model, [n0])[0])
        if not rated > 0.0:
            return None, "the rated torque is not known: no load law gives the torque at n_0"
        return (
            lambda x: np.full(np.size(x), rated),
            f"T_engine = {rated / 1e3:.6g} kN·m, the rated torque at every speed, as asked "
            '([tvc] passage_torque = "rated")',
        )
    return None, (
        "the engine's torque-speed curve is not given: give [tvc] engine_torque_curve (the "
        'engine builder\'s torque limit), engine_torque, or passage_torque = "rated" to pass '
        "with the rated torque at every speed"
    )


def passages(
    model: TorsionModel,
    cond: Any,
    orders: NDArray[np.float64],
    checks: Sequence[Check],
    barred: Sequence[BarredSpeedRange],
    spec: TvcSpec,
    n0: float,
    load: str,
    mean: MeanTorque | None,
) -> tuple[list[Passage], list[Verdict], list[str]]:
    """The passages through one condition's barred ranges (module docstring).

    Parameters
    ----------
    model : TorsionModel
        The installation (with its load law's excitation).
    cond : object
        The condition (its name, excitation and dampers).
    orders : numpy.ndarray
        The excitation orders.
    checks : sequence of Check
        The installation's checks (their transient curves and limits).
    barred : sequence of BarredSpeedRange
        The condition's permitted barred ranges.
    spec : TvcSpec
        The settings (the engine's torque, the passage's load).
    n0 : float
        The rated speed (rad/s).
    load : str
        The load law.
    mean : callable or None
        The mean-torque function of the load laws.

    Returns
    -------
    passages : list of Passage
        One per merged barred range run through.
    verdicts : list of crankdyn.summary.Verdict
        The transient peaks against the transient limits, and ranges that cannot be passed.
    notes : list of str
        Why a passage was not calculated.
    """
    from crankdyn.torsion.event_run import event_response
    from crankdyn.torsion.events import SpeedChange
    from crankdyn.torsion.solvers import linear_system

    passages: list[Passage] = []
    verdicts: list[Verdict] = []
    notes: list[str] = []
    if not barred:
        return passages, verdicts, notes
    inertia = float(np.sum(linear_system(model, cond.dampers).inertia))
    passage_load = spec.passage_load or ("law" if load == "propeller" else "none")

    def load_at(w: ArrayLike) -> NDArray[np.float64]:
        return load_torque(model, w) if passage_load == "law" else np.zeros(np.size(w))

    engine_at, words = engine_torque(spec, model, n0)
    if engine_at is None:
        notes.append(
            f"{cond.name}: the passage through the barred ranges is not calculated: {words}"
        )
        return passages, verdicts, notes
    load_words = "load: the load law" if passage_load == "law" else "load: none (run up unloaded)"
    for a, b in merge_intervals([(x.start, x.end) for x in barred]):
        w = np.linspace(a, b, 401)
        spare = engine_at(w) - load_at(w)
        label = f"{a * RPM:.1f}-{b * RPM:.1f} rpm"
        if np.min(spare) <= 0.0:
            verdicts.append(_cannot_pass(cond.name, label, float(np.min(spare)), words))
            continue
        t_in = float(np.trapezoid(inertia / spare, w))
        w0, w1 = a * (1.0 - LEAD_IN), b * (1.0 + RUN_OUT)
        ww = np.linspace(w0, w1, 801)
        duration = float(np.trapezoid(inertia / np.maximum(engine_at(ww) - load_at(ww), 1e-9), ww))
        ramp = SpeedChange(
            "ramp", w0, w1, ramp_time=duration, load=passage_load == "law", name=f"pass {label}"
        )
        title = f"transient peak passing {label} ({t_in:.3g} s in the range)"
        how = f"{words}; {load_words}"

        def run_with(scale: float | None, ramp: SpeedChange = ramp, duration: float = duration,
                     w1: float = w1) -> Any:  # fmt: skip
            return event_response(
                model,
                ramp,
                duration=duration,
                excitation=cond.excitation,
                orders=orders,
                dampers=cond.dampers,
                max_frequency=(scale or 1.0) * EVENT_MODE_FACTOR * float(np.max(orders)) * w1,
                truncate=scale is not None,
            )

        def judge(run: Any, a: float = a, title: str = title, how: str = how) -> list[Verdict]:
            return _transient_verdicts(run, a, cond.name, title, checks, barred, mean, how)

        run, rows = decided(model, run_with, judge)
        passages.append(
            Passage(
                condition=cond.name,
                start=a,
                end=b,
                time_in_range=t_in,
                acceleration_torque=float(np.min(spare)),
                run_from=w0,
                run_to=w1,
                duration=duration,
                elements=next(
                    (
                        c.elements
                        for c in checks
                        if c.elements and any(x.component == c.component for x in barred)
                    ),
                    (),
                ),
                note=(
                    f"run-up at J dΩ/dt = T_engine - T_load, J = {inertia:.6g} kg·m², "
                    f"{words}, {load_words}"
                ),
                transient=run,
                **truncation_fields(run),
            )
        )
        verdicts += rows
    return passages, verdicts, notes


def _cannot_pass(condition: str, label: str, spare: float, words: str) -> Verdict:
    """The verdict on a barred range the engine's torque cannot accelerate through."""
    return Verdict(
        component="installation",
        condition=condition,
        quantity=f"acceleration torque through the barred range {label}",
        worst=spare,
        limit=0.0,
        unit="N·m",
        margin=-math.inf,
        passed=False,
        source="the engine's torque less the load law: the range cannot be passed",
        clause="[tvc] engine_torque_curve, engine_torque or passage_torque, the load law",
        note=words,
        kind="acceleration torque",
    )


def _transient_verdicts(
    run: Any,
    start: float,
    condition: str,
    quantity: str,
    checks: Sequence[Check],
    barred: Sequence[BarredSpeedRange],
    mean: MeanTorque | None,
    how: str,
) -> list[Verdict]:
    """The largest transient value of every barred component inside the range (from
    ``start``, rad/s) against its transient limit, by the component's own check; ``how``
    (the torque and load of the run) goes into each row's note."""
    out: list[Verdict] = []
    inside = run.speed >= start
    for check in checks:
        if check.transient_curve is None or check.transient_limit is None:
            continue
        if not any(x.component == check.component for x in barred):
            continue
        values = check.transient_curve(run, mean)[inside]
        limits = check.transient_limit(run.speed[inside])
        with np.errstate(invalid="ignore", divide="ignore"):
            ratio = np.where(np.isfinite(limits) & (limits > 0), values / limits, np.nan)
        if not np.any(np.isfinite(ratio)):
            continue
        k = int(np.nanargmax(ratio))
        out.append(
            Verdict(
                component=check.component,
                condition=condition,
                quantity=quantity,
                worst=float(values[k]),
                limit=float(limits[k]),
                unit=check.unit,
                margin=1.0 - float(ratio[k]),
                passed=bool(ratio[k] <= 1.0),
                source=check.transient_source,
                clause=check.transient_clause,
                speed=float(run.speed[inside][k]),
                note=how,
                kind="transient passage",
                error_bound=truncation_bound(run, check.event),
            )
        )
    return out
