"""The result of a design search: the candidates evaluated, the feasible ones, the chosen design
(the best feasible candidate by the first objective) with its verdict rows, the best designs
with their margin per verdict row, and the Pareto front of several objectives."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from crankdyn.results import Result, scalar
from crankdyn.summary import SummaryColumn, SummaryTable, Verdict, derived

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from crankdyn.design.search import Candidate
    from crankdyn.design.space import DesignSpace

__all__ = ["DesignResult"]


def _value(value: float | None) -> float | None:
    return None if value is None or not math.isfinite(value) else float(value)


@dataclass(frozen=True)
class DesignResult(Result):
    """What a design search found (:func:`crankdyn.design.search.run_search`).

    Parameters
    ----------
    space : crankdyn.design.space.DesignSpace
        The space searched.
    candidates : tuple of crankdyn.design.search.Candidate
        Every candidate evaluated, best first.
    base : crankdyn.design.search.Candidate or None
        The base design, evaluated for reference.
    verdicts : tuple of crankdyn.summary.Verdict
        The chosen design's verdict rows (those its constraints and objective read).
    best_verdicts : tuple of tuple of crankdyn.summary.Verdict
        The verdict rows of each of the best feasible designs (best first), for the table of
        margins per verdict row.
    front : tuple of int
        Indices into ``candidates`` of the Pareto front (several objectives; else empty).
    chosen_number : int or None
        The number of the chosen candidate when the search's best feasible one was not chosen
        (it failed a row of the whole TVC that the search did not constrain); None: the best.
    tvc : crankdyn.tvc.TvcResult or None
        The chosen design's whole TVC, where it was checked.
    """

    title = "Design search"
    name: str = scalar("design", "Design space", "")
    method: str = scalar("method", "Search", "")
    objective: str = scalar("objective", "Objective", "")
    evaluated: int = scalar("candidates", "Candidates evaluated", "")
    computed: int = scalar("computed", "Candidates computed in this run (not in the journal)", "")
    feasible_count: int = scalar("feasible", "Feasible candidates", "")
    failed_count: int = scalar("failed", "Failed candidates", "")
    best_objective: float | None = scalar(
        "best_objective", "Objective of the chosen design", "", headline=True
    )
    base_objective: float | None = scalar("base_objective", "Objective of the base design", "")
    chosen: str = scalar("chosen_design", "Chosen design", "", headline=True)
    space: DesignSpace | None = field(default=None, repr=False, compare=False)
    candidates: tuple[Candidate, ...] = field(default=(), repr=False, compare=False)
    base: Candidate | None = field(default=None, repr=False, compare=False)
    verdicts: tuple[Verdict, ...] = field(default=(), repr=False, compare=False)
    best_verdicts: tuple[tuple[Verdict, ...], ...] = field(default=(), repr=False, compare=False)
    front: tuple[int, ...] = field(default=(), repr=False, compare=False)
    chosen_number: int | None = field(default=None, repr=False, compare=False)
    tvc: Any = field(default=None, repr=False, compare=False)
    tvc_passed: bool | None = scalar(
        "tvc_passed", "Chosen design passes every row of crankdyn tvc", "", default=None
    )
    notes: tuple[str, ...] = scalar("notes", "Notes", "", default=())

    FIGURES = (
        derived(
            "design_found", "design_found", "A feasible design was found", "",
            lambda r: r.feasible_count > 0,
            status=lambda found: "pass" if found else "fail",
        ),
        derived(
            "objective_gain", "objective_gain", "Chosen design's objective - base design's", "",
            lambda r: None if r.best_objective is None or r.base_objective is None
            else r.best_objective - r.base_objective,
            reduction="the first objective, in its own unit",
        ),
    )  # fmt: skip

    @property
    def best(self) -> Candidate | None:
        """The chosen design: the best feasible candidate (the best of those checked against
        the whole TVC that passes it: :attr:`chosen_number`), or None."""
        if self.chosen_number is not None:
            return next(c for c in self.candidates if c.number == self.chosen_number)
        return next((c for c in self.candidates if c.feasible), None)

    @property
    def found(self) -> bool:
        """Whether a feasible design was found."""
        return self.best is not None

    def ranked(self, count: int = 5) -> list[Candidate]:
        """The best feasible candidates.

        Parameters
        ----------
        count : int
            How many (default 5).

        Returns
        -------
        list of crankdyn.design.search.Candidate
            The chosen design first, then the others best first.
        """
        feasible = [c for c in self.candidates if c.feasible]
        chosen = self.best
        if chosen is not None and chosen in feasible:  # the chosen design first
            feasible.remove(chosen)
            feasible.insert(0, chosen)
        return feasible[:count]

    def summary_verdicts(self) -> list[Verdict]:
        """The chosen design's verdict rows.

        Returns
        -------
        list of crankdyn.summary.Verdict
            The rows.
        """
        return list(self.verdicts)

    def summary_tables(self) -> list[SummaryTable]:
        """The best designs (parameters, objectives, figures), their margins per verdict row,
        and the Pareto front of several objectives.

        Returns
        -------
        list of crankdyn.summary.SummaryTable
            The tables.
        """
        if self.space is None:
            return []
        out = [self._table("best_designs", "Best designs", self.ranked())]
        if self.best_verdicts:
            out.append(self._margins())
        if self.front:
            out.append(
                self._table(
                    "pareto_front", "Pareto front", [self.candidates[i] for i in self.front]
                )
            )
        sensitivity = self.sensitivity()
        if sensitivity is not None:
            out.append(sensitivity)
        return out

    def sensitivity(self) -> SummaryTable | None:
        """How the first objective varies with each parameter over the candidates that ran:
        the main effect (the range of the objective's mean over a parameter's values, or five
        equal-count bins of a range; Montgomery, *Design and Analysis of Experiments*, 8th ed.,
        2013, section 5.3) and Spearman's rank correlation of a range with the objective
        (:mod:`crankdyn.study.sensitivity`). The candidates of a differential evolution
        crowd around the good designs, so these are indications near the optimum, not a
        designed experiment's effects.

        Returns
        -------
        crankdyn.summary.SummaryTable or None
            One row per parameter; None with fewer than three candidates that ran.
        """
        from crankdyn.study.sensitivity import main_effect, spearman

        space = self.space
        ran = [c for c in self.candidates if c.ok and c.objectives[0] is not None]
        if space is None or len(ran) < 3:
            return None
        objective = space.objectives[0]
        y = [float(c.objectives[0] or 0.0) for c in ran]  # None filtered above
        rows = []
        for p in space.parameters:
            numeric = p.key in space.ranges
            x: list[Any] = [c.case.numbers[p.key] for c in ran]
            effect = main_effect(x, y, numeric=numeric).effect
            rho = spearman(x, y) if numeric else None
            rows.append((space.name_of(p.key), _value(effect), _value(rho)))
        label = objective.label or objective.name
        return SummaryTable(
            "sensitivity",
            "Sensitivity of the objective to the parameters",
            (
                SummaryColumn("parameter", "Parameter"),
                SummaryColumn("main_effect", f"Main effect on {label}", objective.unit),
                SummaryColumn("spearman_rho", "Spearman ρ (ranges)"),
            ),
            tuple(rows),
            caption="over every candidate that ran; near the optimum, not a designed experiment",
        )

    def _columns(self) -> tuple[list[SummaryColumn], list[Any]]:
        from crankdyn.design.search import column_of
        from crankdyn.study.figures import FIGURES

        space = self.space
        assert space is not None
        columns = [SummaryColumn("candidate", "Candidate")]
        getters: list[Any] = [lambda c: c.number]
        for p in space.parameters:
            unit = (p.unit or "") if p.key in space.ranges else ""
            columns.append(SummaryColumn(column_of(space, p.key), space.name_of(p.key), unit))
            getters.append(lambda c, k=p.key: c.case.numbers.get(k))
        for i, o in enumerate(space.objectives):
            columns.append(SummaryColumn(o.column, o.label or o.name, o.unit))
            getters.append(lambda c, i=i: _value(c.objectives[i]))
        for name in space.study.figures:
            if any(o.name == name for o in space.objectives):
                continue
            f = FIGURES[name]
            columns.append(SummaryColumn(f.key, f.label, f.unit))
            getters.append(lambda c, n=name: _value(c.figures.get(n)))
        return columns, getters

    def _table(self, key: str, title: str, rows: list[Candidate]) -> SummaryTable:
        columns, getters = self._columns()
        return SummaryTable(
            key,
            title,
            tuple(columns),
            tuple(tuple(g(c) for g in getters) for c in rows),
            caption="feasible candidates, best first by the first objective",
        )

    def _margins(self) -> SummaryTable:
        """Margin 1 - worst/limit of every verdict row (rows) of each best design (columns)."""
        ranked = self.ranked(len(self.best_verdicts))
        keys: list[tuple[str, str, str]] = []
        margins: list[dict[tuple[str, str, str], float]] = []
        for rows in self.best_verdicts:
            mine = {}
            for v in rows:
                k = (v.component, v.condition, v.quantity)
                if k not in keys:
                    keys.append(k)
                mine[k] = v.margin
            margins.append(mine)
        columns = [
            SummaryColumn("component", "Component"),
            SummaryColumn("condition", "Condition"),
            SummaryColumn("quantity", "Quantity"),
            *(SummaryColumn(f"margin_{c.number}", f"Margin, candidate {c.number}") for c in ranked),
        ]
        cells: tuple[tuple[Any, ...], ...] = tuple(
            (*k, *(_value(m.get(k)) for m in margins[: len(ranked)])) for k in keys
        )
        return SummaryTable(
            "margins",
            "Margin of every verdict row of the best designs",
            tuple(columns),
            cells,
            caption="margin = 1 - worst/limit; negative where a limit is exceeded",
        )

    def plot(self, fig: Figure | None = None) -> Figure:
        """The candidates in the plane of the first two objectives, the Pareto front marked
        (one objective: the objective of every candidate in evaluation order).

        Parameters
        ----------
        fig : matplotlib.figure.Figure or None
            Figure to draw into (new when None).

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from crankdyn.plots.design import plot_design

        return plot_design(self, fig)
