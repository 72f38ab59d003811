"""The design search: candidates made from a design space, evaluated as study cases, scored by
the constraints and objectives, searched exhaustively or by differential evolution.

A candidate is a vector x: for each choice the index of its value (an integer), for each range
its value in the range's unit, rounded to ``digits`` significant digits (what is written into
the document is the candidate: rounding makes the same candidate the same study case, with the
same id, so a rerun of a search finds its candidates in the journal).

Scoring (Deb's feasibility rules as a penalty, K. Deb, *An efficient constraint handling method
for genetic algorithms*, Comput. Methods Appl. Mech. Engrg. 186 (2000) 311-338, eq. 4): a
feasible candidate scores its first objective f (negated when larger is better); an infeasible
one scores f_max + v, with v its total constraint violation (:meth:`Constraint.violation`) and
f_max a bound above every feasible score (:data:`INFEASIBLE`), so every feasible design ranks
above every infeasible one and infeasible ones rank by their violation; a failed case (its file
or analysis refused the variant) scores :data:`FAILED`.

Differential evolution: :func:`scipy.optimize.differential_evolution` (R. Storn and K. Price,
*Differential evolution - a simple and efficient heuristic for global optimization over
continuous spaces*, J. Global Optim. 11 (1997) 341-359), the choices as integer variables
(``integrality``), ``updating="deferred"`` so that a whole generation is handed to the executor
at once (the ``workers`` map), seeded, without the gradient polish (it would evaluate one
candidate at a time and cannot keep integers).

Several objectives: the search minimises the first; the Pareto front (non-dominated feasible
candidates, every objective taken in its sense) is found among every candidate evaluated.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from crankdyn.design.space import DesignSpace
from crankdyn.study.cases import Case, case_id, label

__all__ = [
    "FAILED",
    "INFEASIBLE",
    "Candidate",
    "Evaluate",
    "candidate_case",
    "column_of",
    "pareto_front",
    "run_search",
    "score",
]

INFEASIBLE = 1e6
"""The score of an infeasible candidate before its violation is added (above any feasible
score: objectives are margins, widths, inertias and costs well below it)."""
FAILED = 1e12
"""The score of a candidate whose case failed."""

Evaluate = Callable[[list[Case]], list[dict[str, Any]]]
"""``evaluate(cases) -> records``: the journal record of every case (the study runner's
:meth:`crankdyn.study.run.runner.CaseRunner.run`)."""


@dataclass(frozen=True)
class Candidate:
    """One evaluated design.

    Parameters
    ----------
    number : int
        Its number in the order of first evaluation (1-based; 0 for the base design).
    case : crankdyn.study.cases.Case
        Its study case (parameter values as written into the document).
    record : dict
        The journal record (status, figures, error).
    violation : float
        Total constraint violation (0: feasible; infinity for a failed case).
    objectives : tuple of float or None
        The value of every objective (None where the candidate has none).
    score : float
        What the search minimises (module docstring).
    """

    number: int
    case: Case
    record: dict[str, Any] = field(repr=False)
    violation: float
    objectives: tuple[float | None, ...]
    score: float

    @property
    def ok(self) -> bool:
        """Whether the case ran (its variant was read and analysed)."""
        return self.record.get("status") == "ok"

    @property
    def feasible(self) -> bool:
        """Whether it ran and keeps every constraint."""
        return self.ok and self.violation == 0.0

    @property
    def figures(self) -> dict[str, float | None]:
        """Its study figures (SI)."""
        return dict(self.record.get("figures") or {})


def column_of(space: DesignSpace, key: str) -> str:
    """A parameter's column in the design's tables: its name in the design file, with the
    unit of a range (``damper inertia_kg_m2``).

    Parameters
    ----------
    space : crankdyn.design.space.DesignSpace
        The space.
    key : str
        The parameter's key.

    Returns
    -------
    str
        The column name.
    """
    from crankdyn.study.spec import column_suffix

    p = space.parameter(key)
    name = space.name_of(key).replace(" ", "_")
    return f"{name}_{column_suffix(p.unit)}" if key in space.ranges and p.unit else name


def _round(x: float, digits: int) -> float:
    return float(f"{x:.{digits}g}")


def candidate_case(space: DesignSpace, indices: Sequence[int], numbers: Sequence[float]) -> Case:
    """The study case of a candidate.

    Parameters
    ----------
    space : crankdyn.design.space.DesignSpace
        The space.
    indices : sequence of int
        For each choice, the index of its value.
    numbers : sequence of float
        For each range, its value in the range's unit (rounded to the search's digits here).

    Returns
    -------
    crankdyn.study.cases.Case
        The case (index 0; the search numbers its candidates itself).
    """
    params: dict[str, Any] = {}
    shown: dict[str, Any] = {}
    for key, i in zip(space.choices, indices, strict=True):
        p = space.parameter(key)
        assert p.values is not None  # a choice lists its values
        params[key] = p.values[i]
        shown[key] = p.names[i] if p.names is not None else label(p.values[i])
    for key, x in zip(space.ranges, numbers, strict=True):
        p = space.parameter(key)
        value = _round(float(x), space.search.digits)
        params[key] = p.document_value(value)
        shown[key] = round(value) if p.integer else value
    return Case(index=0, case_id=case_id(params), params=params, numbers=shown)


def score(space: DesignSpace, case: Case, record: dict[str, Any], number: int) -> Candidate:
    """A candidate scored by the space's constraints and objectives (module docstring).

    Parameters
    ----------
    space : crankdyn.design.space.DesignSpace
        The space.
    case : crankdyn.study.cases.Case
        The candidate's case.
    record : dict
        Its journal record.
    number : int
        Its number (order of first evaluation).

    Returns
    -------
    Candidate
        The scored candidate.
    """
    figures = record.get("figures") or {}
    objectives: list[float | None] = []
    for o in space.objectives:
        if o.kind == "cost":
            p = next(k for k in space.choices if space.name_of(k) == o.name)
            values = space.parameter(p).values or ()
            if p not in case.params:  # the base design: no catalogue item chosen
                objectives.append(None)
                continue
            objectives.append(space.costs[o.name][values.index(case.params[p])])
        else:
            objectives.append(figures.get(o.name))
    if record.get("status") != "ok":
        violation, value = math.inf, FAILED
    else:
        violation = sum(c.violation(figures.get(c.figure)) for c in space.constraints)
        first = objectives[0]
        if first is None or not math.isfinite(first):
            violation = math.inf if violation == 0 else violation
        if violation == 0:
            assert first is not None
            value = space.objectives[0].signed(first)
        else:
            value = INFEASIBLE + min(violation, INFEASIBLE)
    return Candidate(number, case, record, violation, tuple(objectives), value)


class _Book:
    """The candidates evaluated so far, by case id, numbered in order of first evaluation."""

    def __init__(self, space: DesignSpace, evaluate: Evaluate) -> None:
        self.space = space
        self.evaluate = evaluate
        self.by_id: dict[str, Candidate] = {}

    def run(self, cases: list[Case]) -> list[Candidate]:
        records = self.evaluate(cases)
        out = []
        for case, record in zip(cases, records, strict=True):
            known = self.by_id.get(case.case_id)
            if known is None:
                known = score(self.space, case, record, len(self.by_id) + 1)
                self.by_id[case.case_id] = known
            out.append(known)
        return out


def _exhaustive(book: _Book) -> None:
    space = book.space
    sizes = [len(space.parameter(k).values or ()) for k in space.choices]
    cases = [candidate_case(space, idx, ()) for idx in itertools.product(*map(range, sizes))]
    book.run(cases)


def _differential_evolution(book: _Book) -> None:
    from scipy.optimize import differential_evolution

    space = book.space
    free = [i for i, k in enumerate(space.choices) if len(space.parameter(k).values or ()) > 1]
    bounds: list[tuple[float, float]] = []
    integrality: list[bool] = []
    for i in free:
        bounds.append((0.0, float(len(space.parameter(space.choices[i]).values or ()) - 1)))
        integrality.append(True)
    for key in space.ranges:
        p = space.parameter(key)
        assert p.distribution is not None  # a range's bounds
        low, high = p.distribution.args
        bounds.append((low, high))
        integrality.append(p.integer)
    dims = len(bounds)

    def case_of(x: Any) -> Case:
        indices = [0] * len(space.choices)
        for j, i in enumerate(free):
            indices[i] = round(float(x[j]))
        return candidate_case(space, indices, [float(v) for v in x[len(free) :]])

    def objective(x: Any) -> float:
        return book.by_id[case_of(x).case_id].score

    def mapper(func: Callable[[Any], float], xs: Any) -> list[float]:
        xs = list(xs)
        book.run([case_of(x) for x in xs])
        return [func(x) for x in xs]

    population = max(5, space.search.population * dims)
    maxiter = max(0, space.search.max_candidates // population - 1)
    differential_evolution(
        objective,
        bounds,
        integrality=integrality,
        popsize=space.search.population,
        maxiter=maxiter,
        tol=space.search.tolerance,
        seed=space.search.seed,
        updating="deferred",
        workers=mapper,
        polish=False,
        init="latinhypercube",
    )


def pareto_front(candidates: Sequence[Candidate], senses: Sequence[str]) -> list[int]:
    """The non-dominated feasible candidates.

    Candidate a dominates b when a is no worse in every objective and better in one (each
    taken in its sense); the front is the feasible candidates no other feasible candidate
    dominates (e.g. K. Deb, *Multi-Objective Optimization using Evolutionary Algorithms*,
    Wiley 2001, section 2.4).

    Parameters
    ----------
    candidates : sequence of Candidate
        The candidates.
    senses : sequence of str
        ``"min"`` or ``"max"`` per objective.

    Returns
    -------
    list of int
        Indices into ``candidates`` of the front, by the first objective (best first).

    Examples
    --------
    >>> from crankdyn.study.cases import Case
    >>> def c(a, b):
    ...     return Candidate(0, Case(0, "", {}, {}), {"status": "ok"}, 0.0, (a, b), 0.0)
    >>> pareto_front([c(1, 5), c(2, 2), c(3, 3), c(0, 9)], ["max", "min"])
    [2, 1]
    """
    rows = []
    for i, c in enumerate(candidates):
        values = [v for v in c.objectives if v is not None and math.isfinite(v)]
        if c.feasible and len(values) == len(c.objectives):
            signed = [v if s == "min" else -v for v, s in zip(values, senses, strict=True)]
            rows.append((i, np.array(signed, dtype=float)))
    front = []
    for i, a in rows:
        dominated = any(np.all(b <= a) and np.any(b < a) for j, b in rows if j != i)
        if not dominated:
            front.append((a[0], i))
    return [i for _, i in sorted(front)]


def run_search(
    space: DesignSpace, evaluate: Evaluate, base: Case | None = None
) -> tuple[str, list[Candidate], Candidate | None]:
    """Search a design space (module docstring).

    Parameters
    ----------
    space : crankdyn.design.space.DesignSpace
        The space.
    evaluate : callable
        ``evaluate(cases) -> records`` (:data:`Evaluate`): the study runner.
    base : crankdyn.study.cases.Case or None
        The base design as a case, evaluated first for reference (None: none).

    Returns
    -------
    method : str
        ``"exhaustive"`` or ``"differential-evolution"``.
    candidates : list of Candidate
        Every candidate evaluated, best first (by score, then by number).
    base : Candidate or None
        The base design, scored.
    """
    method = space.method()
    book = _Book(space, evaluate)
    scored_base = None
    if base is not None:
        record = evaluate([base])[0]
        scored_base = score(space, base, record, 0)
    if method == "exhaustive":
        _exhaustive(book)
    else:
        _differential_evolution(book)
    ranked = sorted(book.by_id.values(), key=lambda c: (c.score, c.number))
    return method, ranked, scored_base
