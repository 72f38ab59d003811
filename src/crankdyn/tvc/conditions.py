"""The running conditions of a torsional vibration calculation (analysis): what excites the
line, with which dampers and over which speeds, for every condition :func:`crankdyn.tvc.tvc`
calculates (docs/tvc.md, "What is calculated").

- *normal firing* over the condition's speed range;
- *each single cylinder misfiring*: an engine's motored pressure in that cylinder
  (:class:`crankdyn.torsion.excitation.EngineExcitation`), or the misfire coefficients of the
  engine builder's harmonic table of a model without an engine
  (:class:`crankdyn.torsion.excitation.TabulatedExcitation`);
- *damper out of order*, where the model has a damper (the damper left out);
- *overspeed*: normal firing from the top of the normal range to the rule's highest speed of the
  shaft limits, 1.05 n_0 in IACS UR M68.4 (the selected rule set's ``overspeed`` value,
  :mod:`crankdyn.tvc.rulesets`), where the normal range stops below it;
- where a clutch is modelled (``[tvc] clutch``): *declutched* running, the line behind the
  clutch removed (every mass the clutch's element no longer joins to the engine, with its
  shafts, gears, dampers, sources and rule checks), the engine at no load over the speed range;
  and *idle* running, the whole line at the engine's idle speed with no load.

No load: the engine's indicated work equals its friction work, so its pressure is the full-load
pressure scaled by the load factor 1 - eta_m (eta_m the engine's mechanical efficiency; the
same scaling of the absolute pressure as a load curve,
:mod:`crankdyn.torsion.excitation`); the load laws of the model's sources (propeller,
generator) are removed with their harmonic excitation (an unloaded propeller or generator
excites no blade or electrical order). A model without an engine keeps its excitation's
coefficients at these speeds (the notes say so).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from crankdyn.constants import RPM
from crankdyn.defaults import DEFAULTS
from crankdyn.errors import InputError

if TYPE_CHECKING:
    from crankdyn.engine.model import Engine
    from crankdyn.torsion.dampers import Damper
    from crankdyn.torsion.excitation import Excitation
    from crankdyn.torsion.model import TorsionModel
    from crankdyn.tvc.spec import TvcSpec

__all__ = [
    "IDLE_BAND",
    "Condition",
    "conditions",
    "declutched_model",
    "no_load_factor",
    "overspeed_ratio",
    "unloaded_model",
]

IDLE_BAND = float(DEFAULTS["idle_band"].value)
"""The idle condition's range around the idle speed (fraction, both sides)."""


@dataclass(frozen=True, eq=False)
class Condition:
    """One running condition (module docstring).

    Parameters
    ----------
    name : str
        Its name in the verdict rows.
    kind : str
        One of :data:`crankdyn.tvc.spec.CONDITION_KINDS`.
    excitation : Excitation
        What excites the line.
    dampers : tuple of Damper
        The dampers acting.
    low, high : float
        The speed range (rad/s).
    description : str
        What the condition is, for reports.
    misfire : int or None
        The misfiring cylinder of a misfire condition.
    model : TorsionModel or None
        The line of the condition where it is not the installation's (declutched, unloaded).
    """

    name: str
    kind: str
    excitation: Excitation
    dampers: tuple[Damper, ...]
    low: float
    high: float
    description: str
    misfire: int | None = None
    model: TorsionModel | None = None


def overspeed_ratio(spec: TvcSpec) -> tuple[float, str]:
    """The top of the overspeed condition, n/n_0, and its citation: ``[tvc] overspeed_limit``
    where given, else the selected rule set's highest speed ratio of the shaft limits
    (:mod:`crankdyn.tvc.rulesets`; IACS UR M68.4: 1.05).

    Parameters
    ----------
    spec : TvcSpec
        The settings (``overspeed_limit``, and ``rules`` where the settings name a rule set).

    Returns
    -------
    ratio : float
        n/n_0 (dimensionless).
    source : str
        Where it comes from.

    Examples
    --------
    >>> from crankdyn.tvc.spec import TvcSpec
    >>> ratio, source = overspeed_ratio(TvcSpec())
    >>> ratio, source.startswith("IACS UR M68")
    (1.05, True)
    """
    if spec.overspeed_limit is not None:
        return spec.overspeed_limit, "[tvc] overspeed_limit"
    rules = spec.ruleset
    return float(rules.overspeed.value), rules.overspeed.clause.cite()


def no_load_factor(engine: Engine | None) -> float | None:
    """The load factor of no load, 1 - eta_m: the indicated work equal to the friction work
    (module docstring); None without an engine or its mechanical efficiency.

    Parameters
    ----------
    engine : Engine or None
        The engine.

    Returns
    -------
    float or None
        1 - eta_m (dimensionless).
    """
    eta = getattr(engine, "mechanical_efficiency", None)
    return None if eta is None else max(1.0 - float(eta), 1e-3)


def unloaded_model(model: TorsionModel, engine: Engine | None) -> tuple[TorsionModel, str]:
    """The installation with no load (module docstring): the sources' load laws removed with
    their excitation, the engine's pressure at the load factor 1 - eta_m.

    Parameters
    ----------
    model : TorsionModel
        The installation.
    engine : Engine or None
        Its engine.

    Returns
    -------
    model : TorsionModel
        The line without load.
    how : str
        What "no load" is for this line, for the condition's description.
    """
    from crankdyn.torsion.excitation_spec import ExcitationSpec, LoadCurve
    from crankdyn.torsion.sources import HarmonicSource

    loaded = [s for s in model.sources if isinstance(s, HarmonicSource) and s.load is not None]
    kept = tuple(s for s in model.sources if s not in loaded)
    words = []
    if loaded:
        names = ", ".join(s.name or s.at for s in loaded)
        words.append(f"the load and excitation of {names} removed")
    exc: Any = model.excitation
    factor = no_load_factor(engine)
    plain = exc is None or (not exc.traces and exc.harmonics is None)
    if engine is not None and factor is not None and plain:
        curve = LoadCurve(np.ones(1), np.array([factor]), kind="load_factor", source="no load")
        new = (
            ExcitationSpec(load_curve=curve)
            if exc is None
            else dataclasses.replace(exc, load_curve=curve)
        )
        model = dataclasses.replace(model, excitation=new)
        words.append(f"the engine's pressure x {factor:.3g} (1 - eta_m: indicated = friction work)")
    elif engine is not None:
        words.append("the engine's excitation as at load (no mechanical efficiency, or traces)")
    else:
        words.append("the cylinders' excitation as given (its coefficients at these speeds)")
    return dataclasses.replace(model, sources=kept), "; ".join(words)


def declutched_model(model: TorsionModel, clutch: tuple[str, str]) -> TorsionModel:
    """The installation with the line behind the clutch removed (module docstring): the
    clutch's element and every mass it no longer joins to its first half, with their shafts,
    gears, dampers, sources and rule checks.

    Parameters
    ----------
    model : TorsionModel
        The installation.
    clutch : (str, str)
        The clutch element's masses, the engine's half first.

    Returns
    -------
    TorsionModel
        The engine's side.

    Raises
    ------
    InputError
        Naming ``[tvc] clutch`` where no element joins the two masses, or where removing it
        leaves the second half joined to the first (the clutch is not where the line divides).
    """
    ends = {clutch[0], clutch[1]}
    cut = [s for s, sh in enumerate(model.shafts) if set(sh.between) == ends]
    if not cut:
        raise InputError(
            "no shaft or coupling joins these masses: name the clutch's element",
            file=model.source,
            key="[tvc] clutch",
            value=list(clutch),
        )
    links: dict[str, set[str]] = {m.name: set() for m in model.masses}
    for s, sh in enumerate(model.shafts):
        a, b = sh.between
        if s not in cut and a in links and b in links:
            links[a].add(b)
            links[b].add(a)
    for g in model.gears:
        a, b = g.between
        links[a].add(b)
        links[b].add(a)
    keep = {clutch[0]}
    todo = [clutch[0]]
    while todo:  # the masses the engine's half still reaches
        for other in links[todo.pop()] - keep:
            keep.add(other)
            todo.append(other)
    if clutch[1] in keep:
        raise InputError(
            "the line stays joined without this element: the clutch must divide it",
            file=model.source,
            key="[tvc] clutch",
            value=list(clutch),
        )
    shafts = tuple(
        sh
        for s, sh in enumerate(model.shafts)
        if s not in cut and all(e in keep or e == "ground" for e in sh.between)
    )
    rules: Any = model.rules
    if rules is not None:
        names = {tuple(sh.segment_of or sh.between) for sh in shafts}
        limits = tuple(
            lim for lim in rules.shafts if {tuple(lim.between), tuple(lim.between)[::-1]} & names
        )
        rules = dataclasses.replace(rules, shafts=limits) if limits else None
    sources = tuple(s for s in model.sources if set(_source_masses(s)) <= keep)
    return dataclasses.replace(
        model,
        masses=tuple(m for m in model.masses if m.name in keep),
        shafts=shafts,
        gears=tuple(g for g in model.gears if all(e in keep for e in g.between)),
        dampers=tuple(d for d in model.dampers if d.at in keep),
        sources=sources,
        rules=rules,
        name=f"{model.name}, declutched at {clutch[0]} - {clutch[1]}",
    )


def _source_masses(source: Any) -> tuple[str, ...]:
    """The masses a source acts at: an engine source's cylinders' masses, else its one mass."""
    names = getattr(source, "mass_names", None)
    return tuple(names()) if callable(names) else (str(source.at),)


def _misfires(
    model: TorsionModel,
    engine: Engine | None,
    base: Excitation,
    dampers: tuple[Damper, ...],
    span: tuple[float, float],
    notes: list[str],
) -> list[Condition]:
    """Each single cylinder misfiring, where the excitation can say what a misfire is."""
    from crankdyn.torsion.excitation import EngineExcitation, TabulatedExcitation, excitation_for

    if isinstance(base, EngineExcitation):
        try:
            base.__class__(base.engine, base.spec, (1,))._motored_trace  # noqa: B018
        except InputError as exc:
            notes.append(f"misfire not calculated: {exc.message}")
            return []
        how = "motored pressure"
    elif isinstance(base, TabulatedExcitation):
        if base.table.misfire is None:
            notes.append(
                "misfire not calculated: the cylinders' harmonic table gives no misfiring "
                "cylinder's coefficients (misfire_sin and misfire_cos, or misfire_amplitude "
                "and misfire_phase)"
            )
            return []
        how = f"the misfire coefficients of {base.table.source or 'the harmonic table'}"
    else:
        notes.append("misfire not calculated: the excitation is not an engine's pressure")
        return []
    return [
        Condition(
            f"misfire cylinder {c}",
            "misfire",
            excitation_for(model, engine, misfire=(c,)),
            dampers,
            span[0],
            span[1],
            f"cylinder {c} not firing ({how}), the others normal",
            misfire=c,
        )
        for c in range(1, base.cylinder_count + 1)
    ]


def _overspeed(
    model: TorsionModel,
    spec: TvcSpec,
    rated: float,
    base: Excitation,
    dampers: tuple[Damper, ...],
    notes: list[str],
) -> list[Condition]:
    """Normal firing from the top of the normal range to the rule's overspeed limit."""
    ratio, source = overspeed_ratio(spec)
    top = ratio * rated
    reach = spec.range_of("normal", model)[1]
    if "overspeed" in spec.ranges:
        low, high = spec.ranges["overspeed"]
    else:
        low, high = reach, top
    if high <= low * (1.0 + 1e-9):
        notes.append(
            f"overspeed: normal firing reaches {reach * RPM:.6g} rpm, beyond the rule's top "
            f"{ratio:g} n_0 = {top * RPM:.6g} rpm ({source}): no separate condition"
        )
        return []
    return [
        Condition(
            "overspeed",
            "overspeed",
            base,
            dampers,
            low,
            high,
            f"normal firing above the normal range to {ratio:g} n_0 = {top * RPM:.6g} rpm, "
            f"the highest speed of the shaft limits ({source})",
        )
    ]


def _clutched(
    model: TorsionModel,
    engine: Engine | None,
    spec: TvcSpec,
    dampers: tuple[Damper, ...],
    kinds: Sequence[str],
    notes: list[str],
) -> list[Condition]:
    """Declutched and idle running, where a clutch is modelled."""
    from crankdyn.torsion.excitation import excitation_for

    if spec.clutch is None:
        return []
    out = []
    if "declutched" in kinds and spec.declutched:
        line = declutched_model(model, spec.clutch)
        line, how = unloaded_model(line, engine)
        low, high = spec.range_of("declutched", model)
        out.append(
            Condition(
                "declutched",
                "declutched",
                excitation_for(line, engine),
                tuple(d for d in dampers if d in line.dampers),
                low,
                high,
                f"the line behind the clutch {spec.clutch[0]} - {spec.clutch[1]} removed "
                f"({len(line.masses)} of {len(model.masses)} masses kept); no load: {how}",
                model=line,
            )
        )
    if "idle" in kinds and spec.idle:
        line, how = unloaded_model(model, engine)
        idle = spec.idle_speed or spec.range_of("normal", model)[0]
        if "idle" in spec.ranges:
            low, high = spec.ranges["idle"]
        else:
            low, high = idle * (1.0 - IDLE_BAND), idle * (1.0 + IDLE_BAND)
        origin = "[tvc] idle_speed" if spec.idle_speed else "the lowest speed of the range"
        out.append(
            Condition(
                "idle",
                "idle",
                excitation_for(line, engine),
                dampers,
                low,
                high,
                f"the engine idling at {idle * RPM:.6g} rpm ({origin}) ± {IDLE_BAND:.0%}, the "
                f"clutch engaged, no load: {how}",
                model=line,
            )
        )
    if out and engine is None:
        notes.append(
            "declutched and idle running: a model without an engine keeps its excitation's "
            "coefficients (no load cannot be derived from them)"
        )
    return out


def conditions(
    model: TorsionModel,
    engine: Engine | None,
    spec: TvcSpec,
    rated: float,
    notes: list[str],
    kinds: Sequence[str],
) -> list[Condition]:
    """Every running condition of the installation (module docstring).

    Parameters
    ----------
    model : TorsionModel
        The installation, with its load law's excitation.
    engine : Engine or None
        Its engine.
    spec : TvcSpec
        The settings (which conditions, their speed ranges, the clutch, the idle speed).
    rated : float
        The rated speed n_0 (rad/s).
    notes : list of str
        Why a condition is not calculated (appended to).
    kinds : sequence of str
        The kinds to calculate (:data:`crankdyn.tvc.spec.CONDITION_KINDS`).

    Returns
    -------
    list of Condition
        Normal firing first.

    Raises
    ------
    InputError
        As :func:`declutched_model` for a ``[tvc] clutch`` that does not divide the line, and
        without a speed range (:meth:`crankdyn.tvc.spec.TvcSpec.range_of`).
    """
    from crankdyn.torsion.excitation import excitation_for

    base = excitation_for(model, engine)
    dampers = tuple(model.dampers)
    low, high = spec.range_of("normal", model)
    out = [Condition("normal firing", "normal", base, dampers, low, high, "all cylinders firing")]
    if "misfire" in kinds and spec.misfire:
        span = spec.range_of("misfire", model)
        out += _misfires(model, engine, base, dampers, span, notes)
    if "damper-out" in kinds and spec.damper_out and dampers:
        low, high = spec.range_of("damper-out", model)
        names = ", ".join(d.name for d in dampers)
        out.append(
            Condition(
                "damper out of order",
                "damper-out",
                base,
                (),
                low,
                high,
                f"without the damper(s) {names} (a viscous damper's ring runs free)",
            )
        )
    if "overspeed" in kinds and spec.overspeed:
        out += _overspeed(model, spec, rated, base, dampers, notes)
    out += _clutched(model, engine, spec, dampers, kinds, notes)
    return out
