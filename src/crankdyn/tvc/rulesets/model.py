"""The data of a class society's torsional-vibration rule set: :class:`Clause` (where a value
was read, or why it could not be), :class:`Cited` (a value with its clause),
:class:`CrankshaftRule`, :class:`GensetRule` and :class:`RuleSet` (numeric core and domain: frozen
data; :mod:`crankdyn.tvc.rulesets` has the registry and the formulas, docs/tvc.md "Rule sets").
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, fields
from typing import Generic, TypeVar

from crankdyn.defaults import TACHOMETER_TOLERANCE

__all__ = [
    "DEFAULT_TACHOMETER_TOLERANCE",
    "ENGINE_GROUPS",
    "Cited",
    "Clause",
    "CrankshaftRule",
    "GensetRule",
    "RuleSet",
    "cite_row",
    "clause_of",
]

T = TypeVar("T")

DEFAULT_TACHOMETER_TOLERANCE = TACHOMETER_TOLERANCE
"""crankdyn's tachometer tolerance (2 %, :data:`crankdyn.defaults.TACHOMETER_TOLERANCE`) where
neither the user nor the rule set gives one: no text read states a value (KR 206.3 asks for the
accuracy to be regarded, without a number)."""

ENGINE_GROUPS = {
    "A": "4-stroke in-line engines and 4-stroke vee engines with firing intervals of 45° or 60°",
    "B": "2-stroke engines and 4-stroke vee engines with other firing intervals",
}
"""KR's two engine groups for crankshaft and generating-set limits (KR 2025 Pt 5 Ch 4
201.1(1)/(2), 203.1(1)(A)/(B)); :func:`engine_group`."""


@dataclass(frozen=True)
class Clause:
    """Where a value of a rule set comes from.

    Parameters
    ----------
    rule : str
        The rule text (e.g. ``"KR Rules for Classification of Steel Ships"``).
    edition : str
        Its edition or revision, and the copy read.
    clause : str
        Part, chapter, section and clause.
    verified : bool
        Whether the value was read in that text (False: the text could not be read; the note
        says where the value comes from instead).
    note : str
        What was read or why not, differences, transcription remarks.
    value_as : str
        Where an unverified value is taken from instead (``"IACS UR M68"``, ``"KR 2025 Pt 5
        Ch 4 202.1(1)"``): what a verdict row says in place of the clause's own reading
        (:meth:`row`); empty for a verified value.

    Examples
    --------
    >>> c = Clause("KR Rules", "2025", "Pt 5 Ch 4 202.1(1)", True)
    >>> c.cite()
    'KR Rules 2025, Pt 5 Ch 4 202.1(1)'
    >>> Clause("DNV", "2021", "Pt 4 Ch 2", False, "not read").cite()
    'DNV 2021, Pt 4 Ch 2 (not verified: not read)'
    >>> Clause("IACS UR M68", "", "M68.4", False, "not read", "IACS UR M68").row()
    'M68.4 (not verified against the text: value as IACS UR M68)'
    """

    rule: str
    edition: str
    clause: str
    verified: bool
    note: str = ""
    value_as: str = ""

    @property
    def source(self) -> str:
        """The rule text with its edition (a verdict row's ``source``).

        Returns
        -------
        str
            ``"KR Rules 2025"``.
        """
        return f"{self.rule} {self.edition}" if self.edition else self.rule

    def row(self) -> str:
        """The clause as a verdict row cites it: the clause, and for a value that could not
        be verified "not verified against the text" with where the value is taken from.

        Returns
        -------
        str
            One line.
        """
        if self.verified:
            return self.clause
        where = self.value_as or self.note
        tail = f": value as {where}" if self.value_as else (f": {where}" if where else "")
        return f"{self.clause} (not verified against the text{tail})"

    def cite(self) -> str:
        """The citation a verdict row prints: rule, edition and clause, and "not verified" with
        the note where the text could not be read.

        Returns
        -------
        str
            One line.
        """
        text = f"{self.source}, {self.clause}"
        if not self.verified:
            text += f" (not verified: {self.note})" if self.note else " (not verified)"
        return text


@dataclass(frozen=True)
class Cited(Generic[T]):
    """A value of a rule set with its clause.

    Parameters
    ----------
    value : object
        The value (SI units: Pa, speed ratios dimensionless), None where the society states none.
    clause : Clause
        Where it comes from.
    """

    value: T
    clause: Clause


@dataclass(frozen=True)
class CrankshaftRule:
    """A society's own crankshaft limits (KR 2025 Pt 5 Ch 4 201): with lambda = n / n_0,

    - continuous, 0 <= lambda <= 1: tau_1 = a - b lambda^2;
    - transient (passing a barred range), lambda <= ``transient_upper``: tau_2 = k tau_1;
    - above the rated speed, 1 <= lambda <= ``overspeed_upper``:
      tau_3 = c + e (lambda - 0.8) sqrt(lambda - 1);

    a, b, c by engine group (:data:`ENGINE_GROUPS`), all in Pa.

    Parameters
    ----------
    a, b, c : dict
        Engine group -> Pa.
    k : float
        tau_2 / tau_1 (dimensionless).
    e : float
        (Pa).
    transient_upper, overspeed_upper : float
        Speed ratios (dimensionless).
    clauses : dict
        ``"continuous"``, ``"transient"``, ``"overspeed"`` -> :class:`Clause`.
    """

    a: Mapping[str, float]
    b: Mapping[str, float]
    k: float
    transient_upper: float
    c: Mapping[str, float]
    e: float
    overspeed_upper: float
    clauses: Mapping[str, Clause]


@dataclass(frozen=True)
class GensetRule:
    """A society's generating-set limits (KR 2025 Pt 5 Ch 4 203): constant vibratory stress
    limits over a speed window around the rated speed, and transient limits at and below its
    lower end.

    Parameters
    ----------
    window : (float, float)
        Speed ratios of continuous running (dimensionless).
    crankshaft : dict
        Engine group -> continuous limit of the crankshaft (Pa).
    crankshaft_transient : float
        Transient limit of the crankshaft (Pa).
    generator, generator_transient : float
        Continuous and transient limits of the generator shaft (Pa).
    clauses : dict
        ``"crankshaft"``, ``"generator"`` -> :class:`Clause`.
    """

    window: tuple[float, float]
    crankshaft: Mapping[str, float]
    crankshaft_transient: float
    generator: float
    generator_transient: float
    clauses: Mapping[str, Clause]


@dataclass(frozen=True)
class RuleSet:
    """One society's torsional-vibration values, each with its clause (module docstring).

    Parameters
    ----------
    key, title : str
        The key (``[tvc] rules``) and the society's name.
    basis : str or None
        The key of the rule set whose values this one holds where its own text could not be
        read (``"iacs-m68"``), else None.
    scope, stress_basis, shaft_formula, transient_formula, size_factor : Clause
        Where the UR's scope, the stress basis (half-range, synthesis of all orders, nominal
        stress of the plain section), tau_C, tau_T and C_D are stated.
    overspeed : Cited of float
        The highest speed ratio of the shaft limits (1.05): the top of the overspeed condition.
    barred_upper : Cited of float
        The highest speed ratio a barred range of a propulsion shaft may reach (0.8).
    strength_caps : dict
        (material, kind) -> Cited cap on sigma_B (Pa); material ``"carbon"``/``"alloy"``, kind
        ``"intermediate"``/``"thrust"``/``"propeller"``.
    design_factors : dict
        Design feature (the keys of :data:`crankdyn.tvc.limits.DESIGN_FACTORS`) -> Cited C_K.
    widening : Cited of str
        The least barred range around a critical speed: ``"none"`` or ``"lr"``
        (16 n_c/(18 - lambda_c) to (18 - lambda_c) n_c/16).
    tachometer : Cited of float or None
        The tachometer tolerance the text states (fraction), None where it states none.
    cpp : Cited of tuple
        The propeller pitch settings to calculate for a controllable-pitch propeller
        (``("full pitch", "zero pitch")``), empty where none is stated or read.
    misfire : Cited of bool or None
        Whether a misfiring cylinder must be calculated for propulsion shafts.
    keyways : Cited of str or None
        What the text says of keyways with a barred speed range.
    min_strength_transient : Cited of float or None
        Least specified tensile strength (Pa) of a shaft whose stresses come close to the
        transient limit.
    calculation_upper : Cited of float or None
        Speed ratio up to which the calculation must run.
    major_criticals : dict
        ``"propulsion"``/``"generator"`` -> Cited (low, high) window of speed ratios where no
        major critical may lie.
    crankshaft : Cited of CrankshaftRule or None
        The society's crankshaft limits.
    genset : Cited of GensetRule or None
        The society's generating-set limits.
    transient_upper_genset : Cited of float or None
        The highest speed ratio of a barred range of a generating set.
    """

    key: str
    title: str
    basis: str | None
    scope: Clause
    stress_basis: Clause
    shaft_formula: Clause
    transient_formula: Clause
    size_factor: Clause
    overspeed: Cited[float]
    barred_upper: Cited[float]
    strength_caps: Mapping[tuple[str, str], Cited[float]]
    design_factors: Mapping[str, Cited[float]]
    widening: Cited[str]
    tachometer: Cited[float | None]
    cpp: Cited[tuple[str, ...]]
    misfire: Cited[bool | None]
    keyways: Cited[str | None]
    min_strength_transient: Cited[float | None]
    calculation_upper: Cited[float | None]
    major_criticals: Mapping[str, Cited[tuple[float, float]]] = field(default_factory=dict)
    crankshaft: Cited[CrankshaftRule | None] | None = None
    genset: Cited[GensetRule | None] | None = None
    transient_upper_genset: Cited[float | None] | None = None

    def clauses(self) -> tuple[tuple[str, Clause], ...]:
        """Every clause of the rule set, named by the value it backs.

        Returns
        -------
        tuple of (str, Clause)
            ``("strength_caps carbon/intermediate", Clause)`` and so on, in field order.
        """
        out: list[tuple[str, Clause]] = []
        for f in fields(self):
            value = getattr(self, f.name)
            if isinstance(value, Clause):
                out.append((f.name, value))
            elif isinstance(value, Cited):
                out.append((f.name, value.clause))
                inner = value.value
                if isinstance(inner, (CrankshaftRule, GensetRule)):
                    out.extend((f"{f.name} {k}", c) for k, c in inner.clauses.items())
            elif isinstance(value, Mapping):
                for k, v in value.items():
                    label = "/".join(k) if isinstance(k, tuple) else str(k)
                    out.append((f"{f.name} {label}", v.clause))
        return tuple(out)


def clause_of(
    rule: tuple[str, str],
    clause: str,
    verified: bool = True,
    note: str = "",
    value_as: str = "",
) -> Clause:
    """A :class:`Clause` of a rule text given as (rule, edition).

    Parameters
    ----------
    rule : (str, str)
        The rule text and its edition (the society modules' constants, e.g. ``KR``).
    clause : str
        Part, chapter, section and clause.
    verified : bool
        Whether the value was read in that text.
    note : str
        What was read or why not.
    value_as : str
        Where an unverified value is taken from (:attr:`Clause.value_as`).

    Returns
    -------
    Clause

    Examples
    --------
    >>> clause_of(("KR Rules", "2025"), "Pt 5 Ch 4 204").cite()
    'KR Rules 2025, Pt 5 Ch 4 204'
    """
    return Clause(rule[0], rule[1], clause, verified, note, value_as)


def cite_row(parts: Sequence[tuple[str, Clause]]) -> tuple[str, str]:
    """The ``source`` and ``clause`` of a verdict row whose limit several clauses give: each
    rule text with its edition once, and every clause with what it gives, "not verified
    against the text: value as ..." where the clause could not be read (:meth:`Clause.row`).

    Parameters
    ----------
    parts : sequence of (str, Clause)
        What each clause gives (``"τ_C"``, ``"σ_B cap"``) and the clause; an empty name cites
        the clause alone.

    Returns
    -------
    source, clause : str
        The rule texts (``" / "`` between two texts) and the clauses (``"; "`` between them).

    Examples
    --------
    >>> kr = ("KR Rules", "2025")
    >>> cite_row([("τ_1", clause_of(kr, "202.1(1)")), ("C_k", clause_of(kr, "Table 5.4.1"))])
    ('KR Rules 2025', 'τ_1: 202.1(1); C_k: Table 5.4.1')
    """
    sources = list(dict.fromkeys(c.source for _, c in parts))
    cited = list(dict.fromkeys(f"{name}: {c.row()}" if name else c.row() for name, c in parts))
    return " / ".join(sources), "; ".join(cited)
