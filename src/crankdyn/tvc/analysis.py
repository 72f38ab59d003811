"""The torsional vibration calculation (TVC) a classification society asks for (analysis).

For an installation (a torsional model with its engine, couplings, gears, dampers, propeller or
generator) the calculation runs every *running condition* over its speed range, each a resolved
forced response (:func:`crankdyn.torsion.sweep.forced_response`: every resonance peak refined
to 0.1 %; the conditions: :mod:`crankdyn.tvc.conditions`):

- normal firing;
- each single cylinder misfiring (no ignition: the motored pressure,
  :class:`crankdyn.torsion.excitation.EngineExcitation`, or the misfire coefficients of the
  engine builder's table of a model without an engine), the worst cylinder reported for every
  check;
- the damper out of order, where the model has one (the damper left out: a viscous damper
  whose fluid is lost leaves its ring free, which no longer acts on the line);
- overspeed, normal firing to the rule's top speed (1.05 n_0 in IACS UR M68.4);
- declutched and idle running, where a clutch is modelled;

under the installation's load law: the propeller law (the gas load following the model's load
curve, the propeller's mean torque ~ n^2) or constant speed (a generating set: full load at
every speed of its range); and every transient event of the settings (``[[tvc.event]]``:
:mod:`crankdyn.tvc.events`).

Every component with a limit is checked against it (the table of check kinds of
:mod:`crankdyn.tvc.checks`; the rule values and their clauses: the rule set selected by
``[tvc] rules``, :mod:`crankdyn.tvc.rulesets`, docs/tvc.md): propulsion shafts against the
society's tau_C and tau_T (the IACS UR M68.4 form; C_K, C_D, the society's cap on sigma_B),
crank spans against the engine builder's permissible vibratory stress or torque (else the
society's crankshaft limits where its text states them), a generating set's alternator shaft
against the society's limit where stated, elastic couplings against T_KW, T_Kmax, T_KN and
P_KV (DIN 740-2, the maker's catalogue), gear meshes against gear hammering (the vibratory
torque at the mesh above the mean transmitted torque reverses the tooth load), generators
against the maker's vibratory torque, angular acceleration and amplitude, and dampers against
the maker's heat load.

Barred speed ranges and the verdict rows of each condition: :mod:`crankdyn.tvc.evaluate` (the
one place a check is evaluated; ``crankdyn torsion response`` uses it too, and the events'
rows come from it). The passage through the barred ranges in the time domain:
:mod:`crankdyn.tvc.passage`.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, TypeAlias

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.defaults import speed_grid
from crankdyn.errors import InputError
from crankdyn.forks import Beside, room_for_a_copy
from crankdyn.summary import Verdict
from crankdyn.threads import free_cores
from crankdyn.tvc.checks import Check, mean_torque_function, model_checks
from crankdyn.tvc.claims import Claims
from crankdyn.tvc.conditions import Condition
from crankdyn.tvc.conditions import conditions as conditions_of
from crankdyn.tvc.evaluate import evaluate_condition
from crankdyn.tvc.installation import installation_verdicts, rule_notes
from crankdyn.tvc.passage import passages as passages_of
from crankdyn.tvc.result import (
    BarredSpeedRange,
    ConditionResult,
    EventCondition,
    Passage,
    TvcResult,
)
from crankdyn.tvc.spec import CONDITION_KINDS, TvcSpec

if TYPE_CHECKING:
    from crankdyn.engine.model import Engine
    from crankdyn.torsion.dampers import Damper
    from crankdyn.torsion.excitation import (
        EngineExcitation,
        SourceExcitation,
        UniformExcitation,
    )
    from crankdyn.torsion.model import TorsionModel
    from crankdyn.torsion.response import ResponseResult

    Excitation: TypeAlias = EngineExcitation | UniformExcitation | SourceExcitation
    # one condition's (condition, verdicts, barred ranges, response)
    Evaluated: TypeAlias = tuple[Condition, list[Verdict], list[BarredSpeedRange], ResponseResult]

__all__ = ["Check", "ResponseOf", "judge", "rated_speed", "tvc", "tvc_model"]

ResponseOf: TypeAlias = (
    "Callable[[TorsionModel, Any, NDArray[np.float64], NDArray[np.float64]], ResponseResult]"
)
"""``response_of(model, condition, speeds, orders)``: a condition's resolved forced response
(the session passes its cached one)."""


def load_of(model: TorsionModel, spec: TvcSpec) -> str:
    """The load law of the installation: the [tvc] ``load``, else ``"propeller"`` when the
    model has a propeller or a load curve, else ``"constant-speed"``."""
    if spec.load is not None:
        return spec.load
    props = [s for s in model.sources if getattr(s, "kind", None) == "propeller"]
    curve = getattr(getattr(model, "excitation", None), "load_curve", None)
    return "propeller" if props or curve is not None else "constant-speed"


def with_load(model: TorsionModel, engine: Engine | None, load: str, rated: float) -> TorsionModel:
    """The model with the excitation's load matching the load law: constant speed drops a load
    curve (full load at every speed); the propeller law adds (n/n_0)^2 where none is given."""
    from crankdyn.torsion.excitation_spec import ExcitationSpec, LoadCurve

    exc: Any = model.excitation  # an ExcitationSpec or None (TorsionModel holds it as an object)
    if engine is None:  # a uniform torque or the sources alone: no gas pressure to load
        return model
    if load == "constant-speed" and exc is not None and exc.load_curve is not None:
        return dataclasses.replace(model, excitation=dataclasses.replace(exc, load_curve=None))
    if load == "propeller" and (exc is None or (exc.load_curve is None and not exc.traces)):
        if exc is not None and exc.harmonics is not None:
            return model
        n = np.linspace(0.2, 1.0, 17) * rated
        curve = LoadCurve(n, (n / rated) ** 2, kind="load_factor", source="propeller law (n/n0)^2")
        new = (
            ExcitationSpec(load_curve=curve)
            if exc is None
            else dataclasses.replace(exc, load_curve=curve)
        )
        return dataclasses.replace(model, excitation=new)
    return model


def _passage_cases(
    group: Sequence[Evaluated], barred: Sequence[BarredSpeedRange]
) -> list[tuple[Condition, list[BarredSpeedRange]]]:
    """(condition, permitted barred ranges) to pass in the time domain: a single condition's
    own; for the misfiring cylinders every united range once, with the cylinder whose own
    range there responds most."""
    permitted = [b for b in barred if b.permitted]
    if len(group) == 1:
        return [(group[0][0], permitted)] if permitted else []
    cases = []
    for u in permitted:
        best, ratio = None, -math.inf
        for cond, _vs, bs, _r in group:
            for b in bs:
                overlaps = b.component == u.component and b.start <= u.end and b.end >= u.start
                if overlaps and b.worst_ratio > ratio:
                    best, ratio = cond, b.worst_ratio
        if best is not None:
            cases.append((best, [u]))
    return cases


def _union(ranges: Sequence[BarredSpeedRange]) -> list[BarredSpeedRange]:
    """The barred ranges of several conditions (the misfiring cylinders) merged per component
    where they overlap: the union of the declared ranges, permitted only where every one is,
    the condition naming the conditions that produce it."""
    out = []
    for component in dict.fromkeys(b.component for b in ranges):
        own = sorted((b for b in ranges if b.component == component), key=lambda b: b.start)
        group: list[BarredSpeedRange] = []
        for b in [*own, None]:
            if b is not None and (not group or b.start <= max(g.end for g in group)):
                group.append(b)
                continue
            worst = max(group, key=lambda g: g.worst_ratio)
            names = list(dict.fromkeys(g.condition for g in group))
            out.append(
                dataclasses.replace(
                    worst,
                    condition=_names(names),
                    start=min(g.start for g in group),
                    end=max(g.end for g in group),
                    exceeds_start=min(g.exceeds_start for g in group),
                    exceeds_end=max(g.exceeds_end for g in group),
                    permitted=all(g.permitted for g in group),
                    reason="; ".join(dict.fromkeys(g.reason for g in group)),
                )
            )
            group = [b] if b is not None else []
    return out


def _names(names: Sequence[str]) -> str:
    """``misfire cylinders 1, 2, 6`` for several misfire conditions, else the names joined."""
    prefix = "misfire cylinder "
    if len(names) > 1 and all(n.startswith(prefix) for n in names):
        numbers = sorted(int(n.removeprefix(prefix)) for n in names)
        return "misfire cylinders " + ", ".join(map(str, numbers))
    return ", ".join(names)


# ---- the calculation --------------------------------------------------------------------------
def rated_speed(model: TorsionModel, engine: Engine | None = None) -> float:
    """The rated speed n_0 (rad/s) of an installation: the [rules] rated speed, else the
    [operating] rated speed, else the engine's speed.

    Parameters
    ----------
    model : TorsionModel
        The installation.
    engine : Engine or None
        Its engine, or None.

    Returns
    -------
    float
        n_0 (rad/s).

    Raises
    ------
    InputError
        Naming the model's file and the key ``rated_speed`` where none is given.
    """
    rules: Any = model.rules  # a RuleSet and an OperatingRange, or None (held as objects)
    operating: Any = model.operating
    if rules is not None and rules.rated_speed is not None:
        return float(rules.rated_speed)
    if operating is not None and operating.rated is not None:
        return float(operating.rated)
    if engine is not None and engine.speed is not None:
        return float(engine.speed)
    raise InputError(
        "the TVC needs the rated speed n_0: give [operating] rated_speed",
        file=model.source,
        key="rated_speed",
    )


def tvc_model(
    model: TorsionModel, engine: Engine | None, spec: TvcSpec
) -> tuple[TorsionModel, str, float]:
    """The installation as the TVC calculates it: the model with its load law's excitation
    (:func:`with_load`), the load law and the rated speed n_0 (rad/s). The analysis session's
    torsional analyses use the same model, so that every front end judges the same response.

    Parameters
    ----------
    model : TorsionModel
        The installation.
    engine : Engine or None
        Its engine, or None.
    spec : TvcSpec
        The settings (the load law, where given).

    Returns
    -------
    model : TorsionModel
        The model with its load law's excitation.
    load : str
        The load law (:data:`crankdyn.tvc.spec.LOADS`).
    rated : float
        n_0 (rad/s).
    """
    rated = rated_speed(model, engine)
    load = load_of(model, spec)
    return with_load(model, engine, load, rated), load, rated


def judge(
    model: TorsionModel,
    response: ResponseResult,
    spec: TvcSpec | None = None,
    *,
    engine: Engine | None = None,
    condition: str = "normal firing",
    dampers: Sequence[Damper] | None = None,
) -> tuple[list[Verdict], list[BarredSpeedRange]]:
    """A forced response judged by the installation's checks: the verdict rows and the barred
    speed ranges (as found and as declared) of one condition, by the TVC's own evaluation
    (:func:`crankdyn.tvc.checks.model_checks`, :func:`crankdyn.tvc.evaluate.
    evaluate_condition`); for normal firing with the rows of the installation as a whole
    (:func:`crankdyn.tvc.installation.installation_verdicts`), as the TVC's normal-firing
    condition has them.

    Parameters
    ----------
    model : TorsionModel
        The installation (its limits: [rules], couplings, machines...).
    response : ResponseResult
        The condition's resolved forced response.
    spec : TvcSpec or None
        The settings (the rule set, the tachometer tolerance); None: the model's ``[tvc]`` or
        the defaults.
    engine : Engine or None
        The engine (for its rated speed where the model gives none).
    condition : str
        The condition's name, for the rows.
    dampers : sequence of Damper or None
        The dampers of the response; None: the model's.

    Returns
    -------
    verdicts : list of crankdyn.summary.Verdict
        The rows.
    barred : list of BarredSpeedRange
        The barred ranges.

    Raises
    ------
    InputError
        Without a rated speed (:func:`rated_speed`).
    """
    spec = spec or getattr(model, "tvc", None) or TvcSpec()
    rated = rated_speed(model, engine)
    load = load_of(model, spec)
    used = model.dampers if dampers is None else dampers
    checks, _notes = model_checks(model, spec, rated, used, engine=engine, load=load)
    verdicts, barred = evaluate_condition(response, condition, checks, spec, rated)
    if condition == "normal firing":
        verdicts += installation_verdicts(model, spec, rated, engine=engine, load=load)
    return verdicts, barred


def _response(
    model: TorsionModel, cond: Condition, speeds: NDArray[np.float64], orders: NDArray[np.float64]
) -> ResponseResult:
    """A condition's resolved forced response (:func:`crankdyn.torsion.response.
    forced_response`)."""
    from crankdyn.torsion.sweep import forced_response

    return forced_response(model, cond.excitation, speeds, orders, dampers=cond.dampers)


def _grouped(results: Sequence[Evaluated]) -> list[list[Evaluated]]:
    """The conditions as the verdict table groups them: normal, the misfiring cylinders
    together (each check reports its worst cylinder), damper out of order."""
    kept = [x for x in results if x[0].kind != "misfire"]
    misfires = [x for x in results if x[0].kind == "misfire"]
    groups = [[x] for x in kept]
    if misfires:
        groups.append(misfires)
    groups.sort(key=lambda g: CONDITION_KINDS.index(g[0][0].kind))
    return groups


def _group_rows(
    group: Sequence[Evaluated], notes: list[str]
) -> tuple[str, str, list[Verdict], ResponseResult, list[BarredSpeedRange]]:
    """(name, description, verdicts, response shown, barred ranges) of a group of conditions:
    one condition as it is; the misfiring cylinders as their worst per check."""
    cond0 = group[0][0]
    barred = [b for _c, _v, bs, _r in group for b in bs]
    if len(group) == 1:
        return cond0.name, cond0.description, list(group[0][1]), group[0][3], barred
    worst_of: dict = {}
    for _cond, vs, _barred, _r in group:
        for v in vs:
            row = (v.component, v.kind or v.quantity)
            if row not in worst_of or v.margin < worst_of[row].margin:
                worst_of[row] = v
    overall = min(group, key=lambda x: min((v.margin for v in x[1]), default=math.inf))
    how = cond0.description.partition("(")[2].partition(")")[0] or "not firing"
    description = (
        f"each of the {len(group)} cylinders not firing in turn ({how}); every "
        "check reports its worst cylinder (named in its condition); the plots show "
        f"{overall[0].name}, the worst overall"
    )
    notes.append(
        f"misfire: each of the {len(group)} cylinders calculated; each check reports the "
        "cylinder with its smallest margin"
    )
    return (
        "misfire (worst cylinder per check)",
        description,
        list(worst_of.values()),
        overall[3],
        _union(barred),
    )


@dataclass
class _Run:
    """What every condition of one calculation shares."""

    model: TorsionModel
    spec: TvcSpec
    orders: NDArray[np.float64]
    rated: float
    load: str
    checks: dict[tuple[int, tuple[Damper, ...]], list[Check]]
    notes: list[str]
    engine: Engine | None = None

    def line(self, cond: Condition) -> TorsionModel:
        """The line a condition runs on: its own (declutched, unloaded) or the installation."""
        return cond.model if cond.model is not None else self.model

    def orders_of(self, cond: Condition) -> NDArray[np.float64]:
        """The orders of a condition: the calculation's, less those its own line has no
        source for (a line without its propeller has no blade orders)."""
        if cond.model is None:
            return self.orders
        from crankdyn.torsion.sources import check_model_orders

        kept = []
        for q in self.orders:  # a few dozen orders, once per condition
            try:
                check_model_orders(cond.model, cond.excitation, [q])
            except InputError:
                continue
            kept.append(q)
        return np.array(kept, dtype=float)

    def checks_of(self, cond: Condition) -> list[Check]:
        """The checks of a condition's line and dampers (made once per line and dampers)."""
        key = (id(self.line(cond)), cond.dampers)
        if key not in self.checks:
            checks, notes = model_checks(
                self.line(cond),
                self.spec,
                self.rated,
                cond.dampers,
                engine=self.engine,
                load=self.load,
            )
            self.checks[key] = checks
            if cond.kind == "normal":
                self.notes.extend(notes)
        return self.checks[key]


def _condition_result(
    run: _Run, group: Sequence[Evaluated], passage: bool
) -> tuple[ConditionResult, list[Passage], list[Verdict]]:
    """One row group of the verdict table: its verdicts, barred ranges and, with ``passage``,
    the passages through them (and their verdicts)."""
    cond0 = group[0][0]
    checks = run.checks_of(cond0)
    name, description, verdicts, response, barred = _group_rows(group, run.notes)
    found: list[Passage] = []
    if passage:
        line = run.line(cond0)
        mean = mean_torque_function(line)
        for cond, bs in _passage_cases(group, barred):
            more, rows, pnotes = passages_of(
                line, cond, run.orders_of(cond), checks, bs, run.spec, run.rated, run.load, mean
            )
            found.extend(more)
            verdicts.extend(rows)
            run.notes.extend(pnotes)
    result = ConditionResult(
        name=name,
        kind=cond0.kind,
        low=cond0.low,
        high=cond0.high,
        description=description,
        verdicts=tuple(verdicts),
        barred_ranges=tuple(barred),
        passages=tuple(found),
        response=response,
        curves={(c.component, c.quantity): c for c in checks},
    )
    return result, found, verdicts


def _judge(run: _Run, cond: Condition, respond: ResponseOf) -> Evaluated:
    """One condition's resolved forced response judged by its checks (normal firing also by
    the installation's own rows)."""
    grid = speed_grid(cond.low, cond.high, run.spec.step)
    r: Any = respond(run.line(cond), cond, grid, run.orders_of(cond))
    verdicts, barred = evaluate_condition(r, cond.name, run.checks_of(cond), run.spec, run.rated)
    if cond.kind == "normal":
        verdicts += installation_verdicts(
            run.model, run.spec, run.rated, engine=run.engine, load=run.load
        )
    return cond, verdicts, barred, r


def _worst_kept(judged: dict[int, Any], worst: int | None, i: int) -> int:
    """Of the misfiring cylinders ``judged`` (index -> Evaluated), the one with the smallest
    margin (the first in the conditions' order of equal ones) keeps its response: the others'
    are let go as soon as they are judged, so that a calculation holds one misfire response,
    not one per cylinder (issue 33). Returns the worst's index after adding ``i``."""

    def margin(k: int) -> float:
        return min((v.margin for v in judged[k][1]), default=math.inf)

    if worst is None:
        return i
    if margin(i) < margin(worst) or (margin(i) == margin(worst) and i < worst):
        worst, i = i, worst
    judged[i] = (*judged[i][:3], None)
    return worst


def _silent(step: str) -> None:
    """No progress display (:func:`tvc`'s default)."""


def _run_conditions(
    run: _Run,
    conds: Sequence[Condition],
    respond: ResponseOf,
    passage: bool,
    claims: Claims,
    away: Callable[[], dict[int, Any]],
    progress: Callable[[str], None],
) -> tuple[list[Any], list[Any], list[Any]]:
    """Every condition judged (:func:`_judge`): those this process claims from the start
    (``claims``: the child beside it takes them from the other end once its events are done,
    ``away()`` returns its), grouped into condition results with their passages in the
    conditions' order; of the misfiring cylinders only the worst keeps its response
    (:func:`_worst_kept`). ``progress`` is told the step this process is at (the condition it
    computes, then the wait for the child's work).

    Returns
    -------
    condition_results, verdicts, passages : list
        The condition results, every verdict row and every passage, in condition order.
    """
    judged: dict[int, Any] = {}
    worst: int | None = None
    while (i := claims.front()) is not None:
        progress(f"condition {i + 1} of {len(conds)}, {conds[i].name}")
        judged[i] = _judge(run, conds[i], respond)
        if conds[i].kind == "misfire":
            worst = _worst_kept(judged, worst, i)
    rest = len(conds) - len(judged)  # the child's (or, where it failed, computed here)
    parts = ["the transient events"] if run.spec.events else []
    if rest:
        parts.append(f"{rest} more condition{'s' if rest > 1 else ''}")
    if parts:
        progress(" and ".join(parts))
    theirs = away()  # the child's conditions (of its cylinders only its worst's response)
    for i in sorted(theirs):
        judged[i] = theirs[i]
        if conds[i].kind == "misfire" and judged[i][3] is not None:
            worst = _worst_kept(judged, worst, i)
    results = [judged[i] for i in range(len(conds))]
    condition_results: list[Any] = []
    verdicts_all: list[Any] = []
    passages_all: list[Any] = []
    for group in _grouped(results):
        result, found, verdicts = _condition_result(run, group, passage)
        condition_results.append(result)
        passages_all.extend(found)
        verdicts_all.extend(verdicts)
    return condition_results, verdicts_all, passages_all


def _beside(
    run: _Run,
    conds: Sequence[Condition],
    respond: ResponseOf,
    events: bool,
    beside: bool | None,
) -> tuple[Claims, Beside[tuple[list[EventCondition], dict[int, Any]]]]:
    """The work of a child beside the conditions, where ``beside`` says so (None: where two
    processors are free and the memory holds a copy): the settings' transient events
    (:func:`crankdyn.tvc.events.event_conditions`; none when ``events`` is false or the
    settings have none), then the conditions it claims from the end while this process claims
    them from the start (:class:`crankdyn.tvc.claims.Claims`), so that both end together
    whatever the events cost; of its misfiring cylinders only the worst's response comes back.
    Without events there is no child (the conditions are all this process's). Every
    condition's checks are made here, before the fork, in the conditions' order (the notes of
    normal firing first)."""
    from crankdyn.tvc.events import event_conditions

    spec = run.spec
    for cond in conds:
        run.checks_of(cond)
    claims = Claims(range(len(conds)))
    if not (events and spec.events):
        return claims, Beside(lambda: ([], {}), fork=False)
    checks = run.checks_of(conds[0])
    base = conds[0].excitation
    if beside is None:
        beside = free_cores() >= 2 and room_for_a_copy()
    beside = beside and claims.shared  # a child shares the claims, or there is none

    def compute() -> tuple[list[EventCondition], dict[int, Any]]:
        found = event_conditions(run.model, spec, run.rated, base, run.orders, checks)
        mine: dict[int, Any] = {}
        worst: int | None = None
        # claimed here or, where a child failed part way, by that child: computed here
        while (i := claims.back()) is not None or (i := claims.unjudged(mine)) is not None:
            mine[i] = _judge(run, conds[i], respond)
            if conds[i].kind == "misfire":
                worst = _worst_kept(mine, worst, i)
        return found, mine

    return claims, Beside(compute, fork=beside)


def _calculated(
    run: _Run,
    conds: Sequence[Condition],
    respond: ResponseOf,
    passage: bool,
    events: bool,
    beside: bool | None,
    progress: Callable[[str], None],
) -> tuple[list[Any], list[Any], list[Any], list[EventCondition]]:
    """The conditions (:func:`_run_conditions`) and the events with the child beside them
    (:func:`_beside`): condition results, verdict rows, passages, events."""
    claims, pending = _beside(run, conds, respond, events, beside)
    outcome: list[tuple[list[EventCondition], dict[int, Any]]] = []

    def away() -> dict[int, Any]:
        outcome.append(pending.result())  # asked for once
        return outcome[0][1]

    with pending:
        found = _run_conditions(run, conds, respond, passage, claims, away, progress)
    return (*found, outcome[0][0])


def _campbell(
    model: TorsionModel,
    orders: NDArray[np.float64],
    speeds: tuple[float, float],
    excitation: Any,
    notes: list[str],
    progress: Callable[[str], None],
) -> Any:
    """The Campbell diagram of the calculation over the conditions' speeds (rad/s), or None
    with a note where it cannot be drawn (``progress`` told so, with the modes next)."""
    from crankdyn.torsion.campbell import campbell

    progress("the Campbell diagram and the natural modes")
    try:
        return campbell(model, orders, speeds, excitation=excitation)
    except InputError as exc:  # pragma: no cover - the same inputs ran the responses
        notes.append(f"Campbell diagram not drawn: {exc.message}")
        return None


def _modes(model: TorsionModel, base: Any, orders: np.ndarray) -> dict[str, Any]:
    """The natural modes of ``model`` and their mode-shape table with the relative vector sums
    of the excitation ``base``'s firing order (:mod:`crankdyn.torsion.mode_table`), as the
    result's fields ``modes`` and ``mode_table``."""
    from crankdyn.torsion.modal import natural_modes
    from crankdyn.torsion.mode_table import excited_mode_table

    modes = natural_modes(model)
    return {"modes": modes, "mode_table": excited_mode_table(modes, model, base, orders)}


def tvc(
    model: TorsionModel,
    engine: Engine | None = None,
    spec: TvcSpec | None = None,
    *,
    passage: bool = True,
    orders: ArrayLike | None = None,
    conditions: Sequence[str] = CONDITION_KINDS,
    response_of: ResponseOf | None = None,
    events: bool = True,
    beside: bool | None = None,
    progress: Callable[[str], None] | None = None,
) -> TvcResult:
    """The torsional vibration calculation of an installation (module docstring).

    Every running condition's resolved forced response, checked component by component
    against its limit, every rule value from the rule set of ``spec.rules`` with its clause:
    propulsion shafts against tau_C and tau_T (the IACS UR M68.4 form, the society's caps on
    sigma_B and C_K table; barred ranges only below 0.8 n_0), elastic couplings against the
    catalogue's T_KW, T_Kmax, T_KN and P_KV (DIN 740-2), crank spans against the builder's or
    the society's limits, gears, machines and dampers against their makers' limits; the
    major criticals against the society's window (normal firing); the barred ranges widened by
    the society's least range (KR 2025 Pt 5 Ch 4 206.1(1), or none) and the tachometer
    tolerance; the passage through them in the time domain.

    Parameters
    ----------
    model : TorsionModel
        The torsional model (an engine file's [torsion] with its shaft line, or a model file).
    engine : Engine or None
        The engine whose cylinders excite it, or None (the model's own engine or excitation).
    spec : TvcSpec or None
        The TVC settings; None: the model's ``[tvc]`` or the defaults.
    passage : bool
        Whether to run the time-domain passage through the barred ranges (default True).
    orders : array_like or None
        The excitation orders (multiples of the crankshaft speed); None: the cycle's harmonics
        to 12 with the orders of the model's sources
        (:func:`crankdyn.torsion.sources.default_orders`).
    conditions : sequence of str
        The kinds of condition to calculate (:data:`crankdyn.tvc.spec.CONDITION_KINDS`);
        default all that apply.
    response_of : callable or None
        ``response_of(model, condition, speeds, orders)`` -> the condition's resolved forced
        response; default :func:`crankdyn.torsion.sweep.forced_response` (the analysis
        session passes its own, cached).
    events : bool
        Whether to run the transient events of the settings (``[[tvc.event]]``,
        :mod:`crankdyn.tvc.events`; default True).
    beside : bool or None
        Whether to run the events in a child process beside the conditions' forced responses
        (:class:`crankdyn.forks.Beside`: the same results, computed from the same state); None:
        where two processors are free (:func:`crankdyn.threads.free_cores`) and the memory
        holds a second process this one's size (:func:`crankdyn.forks.room_for_a_copy`).
    progress : callable or None
        Told each step this process begins (``"condition 2 of 8, misfire cylinder 1"``, the
        work beside it, the modes), for a progress display; it changes no number.

    Returns
    -------
    TvcResult
        ``verdicts`` (every component x condition), ``barred_ranges``, ``passages``,
        ``condition_results`` (with their responses), ``modes`` and ``campbell``.

    Raises
    ------
    InputError
        Naming the model's file and the key ``rated_speed`` where no rated speed n_0 is given
        (``[rules]``, ``[operating]`` or the engine's speed), ``speed_range`` where no condition
        has a speed range, ``[rules] shaft`` (with the shaft's masses) where an M68 shaft has
        no diameter, ``diameter`` where a crank span has none for the nominal stress; and the
        errors of the forced response (orders, speeds).

    Examples
    --------
    Two masses, J_1 = 1 and J_2 = 3 kg m^2, on a 50 mm intermediate shaft (k = 1e5 N m/rad,
    loss factor 0.1, sigma_B = 600 N/mm^2, C_K = 1), a harmonic torque of 100 N m per order
    (orders 1 and 2) on the first mass, n_0 = 400 rad/s:

    >>> from crankdyn.torsion.campbell import OperatingRange
    >>> from crankdyn.torsion.excitation import ExcitationSpec
    >>> from crankdyn.torsion import Mass, Shaft, ShaftGeometry, TorsionModel
    >>> from crankdyn.torsion.rules import RuleSet, ShaftLimit
    >>> model = TorsionModel(
    ...     (Mass("crank", 1.0, cylinders=(1,)), Mass("propeller", 3.0)),
    ...     (Shaft(("crank", "propeller"), stiffness=1e5, loss_factor=0.1,
    ...            geometry=ShaftGeometry(0.05), name="intermediate shaft"),),
    ...     excitation=ExcitationSpec(torque=100.0),
    ...     operating=OperatingRange(100.0, 400.0, rated=400.0),
    ...     rules=RuleSet(None, (ShaftLimit(("crank", "propeller"), 600e6),)),
    ... )
    >>> result = tvc(model, spec=TvcSpec(overspeed=False), orders=[1.0, 2.0])
    >>> result.passed, [c.name for c in result.conditions]
    (True, ['normal firing'])

    The worst stress is the order-1 resonance at omega_n = sqrt(k (1/J_1 + 1/J_2)) = 365.148
    rad/s, where k |dtheta| = T J_2 / (J_1 + J_2) / eta = 750 N m, over W_p = pi d^3/16:
    30.558 MPa, against tau_C = (600 + 160)/18 C_D 1.38 (lambda = 0.91):

    >>> (row,) = result.verdicts
    >>> f"{row.worst / 1e6:.3f} MPa <= {row.limit / 1e6:.3f} MPa at {row.speed:.3f} rad/s"
    '30.558 MPa <= 45.174 MPa at 365.148 rad/s'
    """
    from crankdyn.torsion.sources import default_orders

    spec = spec or getattr(model, "tvc", None) or TvcSpec()
    engine = engine or getattr(model, "engine", None)
    notes: list[str] = []
    model, load, rated = tvc_model(model, engine, spec)
    conds = conditions_of(model, engine, spec, rated, notes, conditions)
    base = conds[0].excitation
    if orders is None:
        orders = default_orders(model, base.cycle, engine=base.cylinder_count > 0)
    run = _Run(model, spec, np.asarray(orders, dtype=float), rated, load, {}, notes, engine)
    say = progress or _silent
    condition_results, verdicts_all, passages_all, found_events = _calculated(
        run, conds, response_of or _response, passage, events, beside, say
    )
    verdicts_all.extend(v for e in found_events for v in e.verdicts)
    low, high = min(c.low for c in conds), max(c.high for c in conds)
    diagram = _campbell(model, run.orders, (low, high), base, notes, say)
    if not verdicts_all:
        notes.append("no component has a limit: nothing was checked")
    notes += rule_notes(
        spec,
        rated=rated,
        high=high,
        misfire=any(c.kind == "misfire" for c in conds),
        propeller=any(getattr(s, "kind", None) == "propeller" for s in model.sources),
    )
    return TvcResult(
        model_name=model.name,
        rated_speed=rated,
        load=load,
        passed=bool(verdicts_all) and all(v.passed for v in verdicts_all),
        verdicts=tuple(verdicts_all),
        barred_ranges=tuple(b for c in condition_results for b in c.barred_ranges),
        passages=tuple(passages_all),
        conditions=tuple(condition_results),
        notes=tuple(notes),
        tachometer_tolerance=spec.tolerance,
        rules=spec.rules,
        events=tuple(found_events),
        model=model,
        engine=engine,
        **_modes(model, base, run.orders),
        campbell=diagram,
        spec=spec,
        condition_results=tuple(condition_results),
    )
