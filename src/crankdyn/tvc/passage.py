"""The passage through barred speed ranges in the time domain (analysis).

A time-domain run-up (:func:`crankdyn.torsion.transient.transient_response`, starting in the
steady state of its first speed) from :data:`LEAD_IN` below to :data:`RUN_OUT` above the declared
range at the acceleration the engine's torque leaves over the load, J_total dOmega/dt =
T_engine - T_load(Omega): the time in the range is the integral of J dOmega / (T_engine -
T_load) over it (trapezoidal rule, 400 points), the run is linear in time with the same duration
(the acceleration torque varies little across a barred range); the largest transient stress
(torque) of every component during the run is checked against its transient limit (tau_T,
T_Kmax) by the component's own check (:mod:`crankdyn.tvc.checks`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.constants import RPM
from crankdyn.summary import Verdict
from crankdyn.tvc.evaluate import merge_intervals
from crankdyn.tvc.result import BarredSpeedRange, Passage

if TYPE_CHECKING:
    from crankdyn.torsion.model import TorsionModel
    from crankdyn.tvc.checks import Check, MeanTorque
    from crankdyn.tvc.spec import TvcSpec

__all__ = ["LEAD_IN", "RUN_OUT", "load_torque", "passages"]

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
    from crankdyn.torsion.solvers import linear_system
    from crankdyn.torsion.transient import transient_response

    passages: list[Passage] = []
    verdicts: list[Verdict] = []
    notes: list[str] = []
    if not barred:
        return passages, verdicts, notes
    inertia = float(np.sum(linear_system(model, cond.dampers).inertia))
    passage_load = spec.passage_load or ("law" if load == "propeller" else "none")

    def load_at(w: ArrayLike) -> NDArray[np.float64]:
        return load_torque(model, w) if passage_load == "law" else np.zeros(np.size(w))

    rated_torque = float(load_torque(model, [n0])[0])

    def engine_at(w: ArrayLike) -> NDArray[np.float64]:
        return spec.engine_torque_at(w, rated_torque)

    if spec.engine_torque_curve is None and not float(engine_at([n0])[0]) > 0.0:
        notes.append(
            f"{cond.name}: the passage through the barred ranges is not calculated: give "
            "[tvc] engine_torque (no load law gives the rated torque)"
        )
        return passages, verdicts, notes
    for a, b in merge_intervals([(x.start, x.end) for x in barred]):
        w = np.linspace(a, b, 401)
        spare = engine_at(w) - load_at(w)
        label = f"{a * RPM:.1f}-{b * RPM:.1f} rpm"
        if np.min(spare) <= 0.0:
            verdicts.append(_cannot_pass(cond.name, label, float(np.min(spare))))
            continue
        t_in = float(np.trapezoid(inertia / spare, w))
        w0, w1 = a * (1.0 - LEAD_IN), b * (1.0 + RUN_OUT)
        ww = np.linspace(w0, w1, 801)
        duration = float(np.trapezoid(inertia / np.maximum(engine_at(ww) - load_at(ww), 1e-9), ww))
        run = transient_response(
            model,
            cond.excitation,
            orders,
            run_up=(w0, w1),
            duration=duration,
            dampers=cond.dampers,
            samples_per_cycle=360,
            start="steady",
        )
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
                    f"run-up at J dΩ/dt = T_engine - T_load, J = {inertia:.6g} kg·m², T_engine "
                    + (
                        "from the engine's torque-speed curve"
                        if spec.engine_torque_curve is not None
                        else f"= {float(engine_at([a])[0]) / 1e3:.6g} kN·m"
                    )
                    + ", load: "
                    f"{'the load law' if passage_load == 'law' else 'none (run up unloaded)'}"
                ),
                transient=run,
            )
        )
        title = f"transient peak passing {label} ({t_in:.3g} s in the range)"
        verdicts += _transient_verdicts(run, a, cond.name, title, checks, barred, mean)
    return passages, verdicts, notes


def _cannot_pass(condition: str, label: str, spare: float) -> Verdict:
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
        clause="[tvc] engine_torque or engine_torque_curve, the load law",
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
) -> list[Verdict]:
    """The largest transient value of every barred component inside the range (from
    ``start``, rad/s) against its transient limit, by the component's own check."""
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
                kind="transient passage",
            )
        )
    return out
