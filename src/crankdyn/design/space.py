"""The design space: what a design search may choose (catalogue items, firing orders, dampers,
continuous ranges of any numeric key of the base file), what a design must satisfy
(constraints on study figures) and what makes one design better than another (objectives);
read from a design file by :mod:`crankdyn.io.design_file` (docs/design-file.md).

A design space is a study (:class:`crankdyn.study.spec.StudySpec`) whose parameters are the
*choices* (grid parameters: a list of values, a catalogue item being a *bundle* that sets
several keys at once, :attr:`crankdyn.study.spec.Parameter.bundle`) and the *ranges* (numeric
parameters bounded by a uniform distribution's [low, high], in the file's unit), so a candidate
design is a study case: its parameter values written into the base document, read again by the
base file's reader and evaluated by the study worker, identified by the hash of its values.

Constraints and objectives read the candidates' study figures (the TVC's verdict rows reduced:
``condition_worst_margin``, ``condition_passed``, ``worst_margin``, ``failed_rows``, ... as
:mod:`crankdyn.study.figures` declares them) and the catalogue's cost column.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from crankdyn.errors import InputError
from crankdyn.study.figures import FIGURES
from crankdyn.study.spec import Parameter, StudySpec

__all__ = [
    "MAX_EXHAUSTIVE",
    "Constraint",
    "DesignSpace",
    "Objective",
    "SearchSettings",
]

MAX_EXHAUSTIVE = 2000
"""The default case limit of an exhaustive search (a discrete space with more candidates is
searched by differential evolution)."""


@dataclass(frozen=True)
class Constraint:
    """A bound on a study figure that a feasible design keeps.

    Parameters
    ----------
    figure : str
        A figure of :data:`crankdyn.study.figures.FIGURES`.
    low, high : float or None
        The bounds in the figure's SI unit (None: unbounded on that side).
    label : str
        The constraint for people (``"every verdict row passes"``).

    Raises
    ------
    InputError
        If the figure is unknown, or neither bound or a reversed pair is given.
    """

    figure: str
    low: float | None = None
    high: float | None = None
    label: str = ""

    def __post_init__(self) -> None:
        if self.figure not in FIGURES:
            raise InputError("unknown figure", key="constraint", value=self.figure)
        if self.low is None and self.high is None:
            raise InputError("give a bound", key="constraint", value=self.figure)
        if self.low is not None and self.high is not None and not self.low <= self.high:
            raise InputError("the lower bound exceeds the upper", key="constraint")

    def violation(self, value: float | None) -> float:
        """How far a value lies outside the bounds.

        Parameters
        ----------
        value : float or None
            The figure's value (SI); None or NaN for a figure the candidate does not have.

        Returns
        -------
        float
            0 inside the bounds, else the distance to the nearest bound relative to
            max(1, |bound|) (dimensionless); infinity for a missing value.

        Examples
        --------
        >>> Constraint("condition_worst_margin", low=0.0).violation(-0.25)
        0.25
        """
        if value is None or not math.isfinite(value):
            return math.inf
        out = 0.0
        if self.low is not None and value < self.low:
            out += (self.low - value) / max(1.0, abs(self.low))
        if self.high is not None and value > self.high:
            out += (value - self.high) / max(1.0, abs(self.high))
        return out


@dataclass(frozen=True)
class Objective:
    """What makes a design better: a study figure or the cost of the catalogue items chosen.

    Parameters
    ----------
    name : str
        A figure of :data:`crankdyn.study.figures.FIGURES`, or for ``kind="cost"`` the name of
        the choice whose catalogue cost counts.
    sense : str
        ``"min"`` or ``"max"``.
    kind : str
        ``"figure"`` (default) or ``"cost"``.
    label : str
        For tables (the figure's label; ``"Cost of <choice>"``).
    unit : str
        The value's unit (SI for a figure; the catalogue's for a cost).

    Raises
    ------
    InputError
        If the sense or the kind is unknown, or a figure objective names an unknown figure.
    """

    name: str
    sense: str
    kind: str = "figure"
    label: str = ""
    unit: str = ""

    def __post_init__(self) -> None:
        if self.sense not in ("min", "max"):
            raise InputError("expected min or max", key="sense", value=self.sense)
        if self.kind not in ("figure", "cost"):
            raise InputError("expected figure or cost", key="objective", value=self.kind)
        if self.kind == "figure" and self.name not in FIGURES:
            raise InputError("unknown figure", key="objective", value=self.name)

    @property
    def column(self) -> str:
        """Its column in the results table (``objective_<name>``)."""
        return f"objective_{self.name}" if self.kind == "figure" else f"cost_{self.name}"

    def signed(self, value: float) -> float:
        """The value as a quantity to minimise (negated for ``"max"``).

        Parameters
        ----------
        value : float
            The objective's value.

        Returns
        -------
        float
            ``value`` or ``-value``.
        """
        return value if self.sense == "min" else -value


@dataclass(frozen=True)
class SearchSettings:
    """How the search runs.

    Parameters
    ----------
    seed : int
        The seed of the differential evolution (and nothing else: an exhaustive search is
        deterministic); the same seed gives the same candidates, so a rerun finds them in the
        journal.
    max_candidates : int
        The most candidates evaluated: the limit of an exhaustive search, the budget of the
        differential evolution (population x generations).
    population : int
        Differential evolution: the population size multiplier (scipy's ``popsize``; the
        population is ``population`` x the number of parameters, at least 5).
    tolerance : float
        Differential evolution: scipy's relative convergence tolerance ``tol``.
    method : str
        ``"auto"`` (exhaustive for a discrete space within ``max_candidates``, else
        differential evolution), ``"exhaustive"`` or ``"differential-evolution"``.
    digits : int
        Significant digits a continuous value is written with (a candidate is what is
        written: rounding makes the journal's ids repeat exactly).
    verify : int
        When the search's constraints read the normal-firing rows only: how many of the best
        feasible designs, best first, are checked against the whole TVC (every condition,
        the events, the passages) until one passes every row; that one is chosen. 0: none.

    Raises
    ------
    InputError
        For a value out of range or an unknown method.
    """

    seed: int = 0
    max_candidates: int = MAX_EXHAUSTIVE
    population: int = 10
    tolerance: float = 1e-3
    method: str = "auto"
    digits: int = 8
    verify: int = 3

    def __post_init__(self) -> None:
        if self.method not in ("auto", "exhaustive", "differential-evolution"):
            raise InputError(
                "expected auto, exhaustive or differential-evolution",
                key="method",
                value=self.method,
            )
        if self.max_candidates < 1:
            raise InputError("must be at least 1", key="max_candidates", value=self.max_candidates)
        if self.population < 1:
            raise InputError("must be at least 1", key="population", value=self.population)
        if self.verify < 0:
            raise InputError("must be 0 or more", key="verify", value=self.verify)
        if not 3 <= self.digits <= 15:
            raise InputError("expected 3 to 15", key="digits", value=self.digits)


@dataclass(frozen=True)
class DesignSpace:
    """A design search's space, constraints and objectives (module docstring).

    Parameters
    ----------
    study : crankdyn.study.spec.StudySpec
        The base, the analysis settings and the figures every candidate computes; its
        parameters are the choices then the ranges.
    choices : tuple of str
        The keys of the study's parameters that are discrete choices (their values listed).
    ranges : tuple of str
        The keys of the continuous ranges (their bounds a uniform distribution's).
    names : dict of str to str
        A parameter key -> the name the design file gives it (``"coupling"``).
    costs : dict of str to tuple of float
        A choice's name -> the cost of each of its values (from the catalogue).
    cost_unit : dict of str to str
        A choice's name -> the unit of its costs.
    constraints : tuple of Constraint
        What a feasible design keeps.
    objectives : tuple of Objective
        The first is the search's; with several, the results hold their Pareto front.
    search : SearchSettings
        How the search runs.
    source : str or None
        The design file, for messages.

    Raises
    ------
    InputError
        If there is no choice and no range, a key is neither, or no objective is given.
    """

    study: StudySpec
    choices: tuple[str, ...]
    ranges: tuple[str, ...]
    names: dict[str, str] = field(default_factory=dict)
    costs: dict[str, tuple[float, ...]] = field(default_factory=dict)
    cost_unit: dict[str, str] = field(default_factory=dict)
    constraints: tuple[Constraint, ...] = ()
    objectives: tuple[Objective, ...] = ()
    search: SearchSettings = SearchSettings()
    source: str | None = field(default=None, compare=False)

    def __post_init__(self) -> None:
        keys = {p.key for p in self.study.parameters}
        if set(self.choices) | set(self.ranges) != keys:
            raise InputError("every parameter is a choice or a range", key="parameters")
        if not self.objectives:
            raise InputError("give an objective", key="objective")
        for o in self.objectives:
            if o.kind == "cost" and o.name not in self.costs:
                raise InputError("no catalogue with costs has this name", key="cost", value=o.name)

    def parameter(self, key: str) -> Parameter:
        """The study parameter of a choice or a range.

        Parameters
        ----------
        key : str
            The parameter's key.

        Returns
        -------
        crankdyn.study.spec.Parameter
            The parameter.
        """
        return next(p for p in self.study.parameters if p.key == key)

    @property
    def parameters(self) -> tuple[Parameter, ...]:
        """The choices then the ranges: the order of a candidate's vector."""
        return tuple(self.parameter(k) for k in (*self.choices, *self.ranges))

    @property
    def discrete_count(self) -> int:
        """The number of combinations of the choices (1 without choices)."""
        return math.prod(len(self.parameter(k).values or ()) for k in self.choices)

    def name_of(self, key: str) -> str:
        """The design file's name of a parameter (its key path when it gives none).

        Parameters
        ----------
        key : str
            The parameter's key.

        Returns
        -------
        str
            The name.
        """
        return self.names.get(key, key)

    def method(self) -> str:
        """The search method this space takes (:class:`SearchSettings`).

        Returns
        -------
        str
            ``"exhaustive"`` or ``"differential-evolution"``.

        Raises
        ------
        InputError
            If an exhaustive search is asked for a space with ranges or more candidates than
            ``max_candidates``.
        """
        method = self.search.method
        small = not self.ranges and self.discrete_count <= self.search.max_candidates
        if method == "auto":
            return "exhaustive" if small else "differential-evolution"
        if method == "exhaustive" and not small:
            raise InputError(
                f"an exhaustive search takes a discrete space of at most max_candidates = "
                f"{self.search.max_candidates} designs (this one: "
                f"{'continuous ranges' if self.ranges else self.discrete_count})",
                key="method",
                value=method,
            )
        return method
