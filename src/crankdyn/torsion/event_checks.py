"""The checks of a transient event: every peak against its limit, as verdict rows (analysis).

Pure functions of an :class:`crankdyn.torsion.event_result.EventResult` and the limits, each
returning :class:`crankdyn.summary.Verdict` rows whose condition is the event's name (the TVC
lists them with its other conditions):

- :func:`shaft_stress`: a shaft's largest vibratory shear stress |T - T_mean| / W_p over the
  run (beyond the quasi-static torque of the engines' and loads' mean torques) against a given
  transient limit (IACS UR M68.4's tau_T = 1.7 tau_C / sqrt(C_K), or a society's);
- :func:`coupling_torque`: an elastic coupling's largest torque against its maximum torque
  T_Kmax (DIN 740-2: the torque the coupling may carry in transient conditions), and where the
  maker's catalogue gives them, against T_Kmax1 (normal transient conditions: starts, stops,
  clutch engagements, passing resonances) or T_Kmax2 (exceptional ones: short circuits,
  emergency stops) by the event's severity;
- :func:`mesh_reversal`: a gear mesh's torque falling through zero (the tooth load reversing,
  gear hammering: the drop below the mean transmitted torque against that mean, the
  TVC's hammering criterion);
- the time each quantity spends above its limit, in every row's note
  (:meth:`crankdyn.torsion.event_result.EventResult.time_above`).

:func:`model_verdicts` applies them with the limits a model holds: its couplings' T_Kmax, its
gear meshes, and its M68 shafts (``[rules]``) with tau_T at the speed ratio of the peak
(lambda <= 0.8 as M68.4 states it; above, tau_T of lambda = 0.8, said in the note).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from crankdyn.summary import Verdict
from crankdyn.torsion.rules import permissible_continuous, permissible_transient

if TYPE_CHECKING:
    from crankdyn.torsion.event_result import EventResult
    from crankdyn.torsion.model import TorsionModel

__all__ = [
    "COUPLING_RULE",
    "HAMMERING_RULE",
    "M68_RULE",
    "coupling_torque",
    "mesh_reversal",
    "model_verdicts",
    "shaft_stress",
]

M68_RULE = "IACS UR M68 (Corr.2 Nov 2012, Aug 2014 text; formulas kept in Rev.3 Feb 2021)"
"""The rule of the shafts' transient limit (the text :mod:`crankdyn.tvc.limits` cites)."""
COUPLING_RULE = "DIN 740-2 (coupling maker's catalogue)"
"""The source of a coupling's T_Kmax."""
HAMMERING_RULE = "gear hammering: the tooth load reverses where the torque falls through zero"
"""The criterion of a gear mesh's torque reversal."""


def _at(result: EventResult, time: float) -> float:
    """The reference speed (rad/s) at a time of the run."""
    return float(np.interp(time, result.time, result.speed))


def _when(result: EventResult, e: int, level: float) -> str:
    """'at t = ... s; ... s above the limit' for element e's peak."""
    above = result.time_above(e, level) if math.isfinite(level) and level > 0 else 0.0
    return f"peak at t = {result.peak_time(e):.4g} s; {above:.3g} s above the limit"


def shaft_stress(
    result: EventResult,
    elements: int | Sequence[int],
    tau_t: float,
    *,
    component: str | None = None,
    rule: str = M68_RULE,
    clause: str = "M68.4",
    note: str = "",
) -> Verdict:
    """A shaft's largest vibratory shear stress |T - T_mean| / W_p over the event (the torque
    beyond the quasi-static torque of the mean torques, :class:`crankdyn.torsion.event_result.
    EventResult`) against its transient limit (module docstring).

    Parameters
    ----------
    result : crankdyn.torsion.event_result.EventResult
        The event's run.
    elements : int or sequence of int
        The shaft's elements (a subdivided shaft's several), with a diameter.
    tau_t : float
        The transient limit (Pa), > 0.
    component : str or None
        The shaft's name in the row; default its first element's name.
    rule, clause : str
        Where the limit comes from.
    note : str
        Added to the row's note.

    Returns
    -------
    crankdyn.summary.Verdict
        worst = the largest |T - T_mean| / W_p (Pa), limit = tau_T; passed when worst <=
        limit.

    Raises
    ------
    ValueError
        For an element without a diameter (no W_p).
    """
    idx = [elements] if isinstance(elements, (int, np.integer)) else list(elements)
    moduli = result.section_modulus[idx]
    if not np.all(np.isfinite(moduli)):
        raise ValueError("every element of a shaft check needs a diameter (W_p)")
    peaks = [result.vibratory_peak(int(e)) for e in idx]
    stresses = [p / float(w) for p, w in zip(peaks, moduli, strict=True)]
    k = int(np.argmax(stresses))
    e = int(idx[k])
    worst = float(stresses[k])
    when = result.vibratory_peak_time(e)
    text = f"peak at t = {when:.4g} s"
    return Verdict(
        quantity="largest vibratory shear stress |T - T_mean| / W_p in the event vs tau_T",
        component=component or result.element_names[e],
        condition=result.event,
        worst=worst,
        limit=float(tau_t),
        unit="Pa",
        passed=bool(worst <= tau_t),
        source=rule,
        clause=clause,
        speed=_at(result, when),
        note=f"{text}{'; ' + note if note else ''}",
    )


def coupling_torque(
    result: EventResult,
    element: int,
    *,
    t_kmax: float | None = None,
    t_kmax1: float | None = None,
    t_kmax2: float | None = None,
    component: str | None = None,
    rule: str = COUPLING_RULE,
) -> list[Verdict]:
    """An elastic coupling's largest torque (the total it carries) against T_Kmax, and against
    T_Kmax1 (a normal event) or T_Kmax2 (an exceptional one) where given (module docstring).

    Parameters
    ----------
    result : crankdyn.torsion.event_result.EventResult
        The event's run.
    element : int
        The coupling's element.
    t_kmax, t_kmax1, t_kmax2 : float or None
        The maker's maximum torques (N m), > 0, or None where not given.
    component : str or None
        The coupling's name; default the element's.
    rule : str
        The catalogue.

    Returns
    -------
    list of crankdyn.summary.Verdict
        One row per limit that applies (none without limits).
    """
    worst = result.peak(element)
    at = _at(result, result.peak_time(element))
    limits = [("T_Kmax", t_kmax)]
    if result.severity == "exceptional":
        limits.append(("T_Kmax2 (exceptional transient conditions)", t_kmax2))
    else:
        limits.append(("T_Kmax1 (normal transient conditions)", t_kmax1))
    rows = []
    for clause, limit in limits:
        if limit is None:
            continue
        rows.append(
            Verdict(
                quantity=f"largest torque in the event vs {clause.split()[0]}",
                component=component or result.element_names[element],
                condition=result.event,
                worst=worst,
                limit=float(limit),
                unit="N·m",
                passed=bool(worst <= limit),
                source=rule,
                clause=clause,
                speed=at,
                note=_when(result, element, float(limit)),
            )
        )
    return rows


def mesh_reversal(result: EventResult, element: int, *, component: str | None = None) -> Verdict:
    """A gear mesh's torque reversal: its largest drop below the mean transmitted torque (its
    time average over the run) against that mean (module docstring).

    Parameters
    ----------
    result : crankdyn.torsion.event_result.EventResult
        The event's run.
    element : int
        The mesh (an elastic mesh's element or a rigid gear's).
    component : str or None
        The mesh's name; default the element's.

    Returns
    -------
    crankdyn.summary.Verdict
        worst = T_mean - min(T) in the mean's direction (N m), limit = |T_mean|; passed when
        the torque never falls through zero; the note gives how long it is reversed and how
        often.
    """
    mean = _time_mean(result, element)
    sign = 1.0 if mean >= 0.0 else -1.0
    low = result.min_torque[element] if sign > 0 else -result.max_torque[element]
    worst = sign * mean - float(low)
    when = result.min_time[element] if sign > 0 else result.max_time[element]
    along = sign * result.torque[:, element]
    reversed_time = _time_below_zero(result, along)
    crossings = int(np.count_nonzero(np.diff(np.signbit(along).astype(int)) == 1))
    return Verdict(
        quantity="largest drop of the mesh torque below its mean vs the mean (torque reversal)",
        component=component or result.element_names[element],
        condition=result.event,
        worst=worst,
        limit=abs(mean),
        unit="N·m",
        passed=bool(worst < abs(mean)),
        source=HAMMERING_RULE,
        clause="",
        speed=_at(result, float(when)),
        note=(
            f"lowest at t = {float(when):.4g} s; reversed {reversed_time:.3g} s in all, "
            f"{crossings} reversal(s); mean over the run {mean:.6g} N·m"
        ),
    )


def _time_mean(result: EventResult, e: int) -> float:
    """Element e's torque averaged over the run (N m; trapezoidal rule on the kept samples)."""
    t, y = result.time, result.torque[:, e]
    span = float(t[-1] - t[0])
    if span <= 0.0:
        return float(y[0])
    return float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(t)) / span)


def _time_below_zero(result: EventResult, values: np.ndarray) -> float:
    """Seconds a sampled quantity spends below zero."""
    from crankdyn.torsion.event_result import time_above

    return time_above(result.time, -values, 0.0)


def model_verdicts(result: EventResult, model: TorsionModel) -> list[Verdict]:
    """The event's verdicts with the limits the model holds (module docstring): its couplings'
    T_Kmax, its gear meshes' reversals, its M68 shafts against tau_T.

    Parameters
    ----------
    result : crankdyn.torsion.event_result.EventResult
        The event's run on ``model``.
    model : crankdyn.torsion.model.TorsionModel
        The model (its couplings, gears and ``[rules]``).

    Returns
    -------
    list of crankdyn.summary.Verdict
        The rows, shafts first, then couplings, then meshes.
    """
    rows: list[Verdict] = []
    rules = model.rules
    if rules is not None and rules.rated_speed is not None:
        n0 = rules.rated_speed
        groups: dict[tuple[str, float, float, float], list[int]] = {}
        for limit in rules.shafts:
            ends = set(limit.between)
            for e, shaft in enumerate(model.shafts):
                if shaft.geometry is None:
                    continue
                if set(shaft.between) == ends or set(shaft.segment_of or ()) == ends:
                    whole = shaft.segment_of or shaft.between
                    name = shaft.name or f"{whole[0]} - {whole[1]}"
                    key = (
                        name,
                        limit.strength_used,
                        limit.design_factor,
                        shaft.geometry.outer_diameter,
                    )
                    groups.setdefault(key, []).append(e)
        for (name, strength, ck, diameter), idx in groups.items():
            e_peak = max(idx, key=result.vibratory_peak)
            lam = _at(result, result.vibratory_peak_time(e_peak)) / n0
            used = min(lam, 0.8)
            tau_c = permissible_continuous(used, strength, ck, diameter)
            tau_t = float(permissible_transient(used, tau_c, ck))
            note = "" if lam <= 0.8 else f"lambda = {lam:.3g} > 0.8: tau_T of lambda = 0.8"
            rows.append(shaft_stress(result, sorted(set(idx)), tau_t, component=name, note=note))
    for e, shaft in enumerate(model.shafts):
        c = shaft.coupling
        if c is not None and c.maximum_torque is not None:
            rows += coupling_torque(
                result, e, t_kmax=c.maximum_torque, component=shaft.name or shaft.label
            )
    for e, kind in enumerate(result.element_kinds):
        if kind in ("mesh", "gear"):
            rows.append(mesh_reversal(result, e))
    return rows
