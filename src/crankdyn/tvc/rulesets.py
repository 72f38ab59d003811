"""The classification societies' torsional-vibration rule sets, each value with the clause it
was read from (numeric core and domain: data and pure functions; docs/tvc.md, "Rule sets").

A :class:`RuleSet` holds one society's values: the permissible shaft stresses (the IACS UR M68
form tau_C = (sigma_B + 160)/18 C_K C_D (3 - 2 lambda^2), 1.38 from lambda = 0.9 to 1.05, and
tau_T = 1.7 tau_C / sqrt(C_K) up to lambda = 0.8, whose formulas live in
:mod:`crankdyn.torsion.rules`), the caps on sigma_B by material and shaft kind, the C_K table,
the barred-range rules (least range around a critical speed, highest speed ratio of a barred
range, tachometer tolerance), controllable-pitch propellers, generating sets, the crankshaft
limits where the society states them, and the upper end of the shaft limits (the overspeed
condition's top speed). Every value carries a :class:`Clause` (rule, edition, clause, whether it
was verified against the text, a note); a value whose text could not be read says so
(``verified=False``) instead of being passed off as read.

What was read (docs/tvc.md, "Rule sets", has the table):

- **KR**, Rules for Classification of Steel Ships 2025 (RA-05-E), Pt 5 Ch 4 "Torsional vibration
  of shaftings" (the whole chapter, 101-206; a markdown transcription in a public repository):
  the M68 formulas with T_s capped at 600 N/mm^2 for carbon steel forgings (every shaft kind),
  800 N/mm^2 for low alloy steel intermediate and thrust shafts, 600 N/mm^2 for propeller and
  stern tube shafts (202.1(1)); the C_K table (Table 5.4.1); tau_2 = 1.7 tau_1 / sqrt(C_k) below
  0.8 (202.1(2)); crankshafts of main engines tau_1 = 45 - 24 lambda^2 or 45 - 29 lambda^2,
  tau_2 = 2 tau_1 to 0.8, tau_3 above the rated speed to 1.15 (201); generating sets: crankshaft
  21 or 16 N/mm^2 and generator shaft 31 N/mm^2 from 0.9 to 1.1, transient 90 and 118 N/mm^2 at
  and below 0.9 (203); the material factor f_m (201.4); no major critical in 0.8-1.1 (propulsion)
  or 0.9-1.1 (generators) (204); the least barred range 16 N_c/(18 - lambda) to
  (18 - lambda) N_c/16, both full and zero pitch of a controllable-pitch propeller, misfire
  ranges that allow safe navigation (206.1); a measured range "having regard to the tachometer
  accuracy" (206.3, no value stated); calculations up to 120 % of the rated speed (102.1(2)).
- **Lloyd's Register**, Rules for Ships Pt 5 Ch 6 2.1.1-2.1.4 (imorules copy): carbon and
  carbon-manganese steel 400-760 N/mm^2, alloy steel not above 800 N/mm^2, and no higher
  permissible vibration stress from the formulae of Pt 5 Ch 8 2.5 for higher strengths (except
  approved alloy intermediate shafts, Pt 5 Ch 6 5); 500 N/mm^2 where stresses come close to the
  transient limit (2.1.3). LR's Rules for Naval Ships (January 2023) Vol 2 Pt 5 Ch 1 3.1.1-3.1.3:
  the symbols (r = N/N_s, N_s the full-load speed of a generating set, C_d = 0.35 + 0.93 d^-0.2),
  half-range amplitudes of the synthesis of all orders, nominal stress of the plain section,
  and the first rows of the C_k table. LR's Pt 5 Ch 8 2 (the formulas, the margins, the
  tachometer) could not be read: the formulas and the margin are those crankdyn had
  implemented (the margin is the same formula as KR 206.1(1)), marked unverified.
- **IACS UR M68**: M68.1 (scope: crankshafts are M53's, generator rotor shafts are not
  covered) and the start of M68.2 from a copy of the Corr.2 Nov 2012 / Aug 2014 text; M68.3 and
  M68.4 could not be read (the formulas are those printed by KR 202.1, which implements M68).
  The current revision is Rev.3 (Feb 2021); not read.
- **DNV, ABS, BV** (and ClassNK, CCS, RINA, IRS): no torsional-vibration clause could be read;
  their rule sets hold IACS UR M68's values (every IACS member implements the UR), each clause
  marked unverified with the documents whose existence was seen.

The functions are vectorised over speed ratio and diameter (numpy broadcasting) and reuse
:mod:`crankdyn.torsion.rules` (tau_C, tau_T, C_D) and :mod:`crankdyn.tvc.limits` (the
least barred range); the ``"iacs-m68"`` and ``"lr"`` sets reproduce crankdyn's IACS behaviour and
LR margin bit for bit.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from typing import Any, Generic, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from crankdyn.errors import InputError, did_you_mean
from crankdyn.torsion.rules import (
    STRENGTH_CAPS,
    ShaftLimit,
    permissible_continuous,
    permissible_transient,
)
from crankdyn.tvc.limits import DESIGN_FACTORS, barred_limits

__all__ = [
    "DEFAULT_TACHOMETER_TOLERANCE",
    "ENGINE_GROUPS",
    "RULESETS",
    "RULESET_KEYS",
    "Cited",
    "Clause",
    "CrankshaftRule",
    "GensetRule",
    "RuleSet",
    "barred_range_permitted",
    "capped_strength",
    "continuous_limit",
    "cpp_conditions",
    "crankshaft_limits",
    "declared_barred_range",
    "design_factor",
    "engine_group",
    "genset_limits",
    "get",
    "major_critical_permitted",
    "material_factors",
    "shaft_limit",
    "tachometer_tolerance",
    "transient_limit",
    "unverified",
]

T = TypeVar("T")
_MPA = 1e6

DEFAULT_TACHOMETER_TOLERANCE = 0.02
"""crankdyn's tachometer tolerance (2 %, :class:`crankdyn.tvc.spec.TvcSpec`) where neither the
user nor the rule set gives one: no text read states a value (KR 206.3 asks for the accuracy to
be regarded, without a number)."""

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

    Examples
    --------
    >>> c = Clause("KR Rules", "2025", "Pt 5 Ch 4 202.1(1)", True)
    >>> c.cite()
    'KR Rules 2025, Pt 5 Ch 4 202.1(1)'
    >>> Clause("DNV", "2021", "Pt 4 Ch 2", False, "not read").cite()
    'DNV 2021, Pt 4 Ch 2 (not verified: not read)'
    """

    rule: str
    edition: str
    clause: str
    verified: bool
    note: str = ""

    def cite(self) -> str:
        """The citation a verdict row prints: rule, edition and clause, and "not verified" with
        the note where the text could not be read.

        Returns
        -------
        str
            One line.
        """
        head = f"{self.rule} {self.edition}" if self.edition else self.rule
        text = f"{head}, {self.clause}"
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


def _c(rule: tuple[str, str], clause: str, verified: bool = True, note: str = "") -> Clause:
    return Clause(rule[0], rule[1], clause, verified, note)


KR = (
    "KR Rules for Classification of Steel Ships",
    "2025 (RA-05-E)",
)
LR_SHIPS = (
    "LR Rules and Regulations for the Classification of Ships",
    "(imorules.com copies LRSHIP_PT5_CH6_2, LRSHIPS_PT5_CH6_6; edition not shown in the excerpts)",
)
LR_NAVAL = (
    "LR Rules and Regulations for the Classification of Naval Ships",
    "January 2023 (imorules.com, version 9.40)",
)
IACS = (
    "IACS UR M68",
    "Corr.2 Nov 2012 / Aug 2014 text (copy read: M68.1-M68.2; current revision Rev.3 Feb 2021)",
)

_M68_NOT_READ = (
    "M68.3/M68.4 could not be read; the same formula is printed by KR 2025 Pt 5 Ch 4 202.1, "
    "which implements M68"
)
_LR_CH8_NOT_READ = "LR Pt 5 Ch 8 2 could not be read; crankdyn's M68 formula"


def _m68_caps(
    rule: tuple[str, str], verified: bool, note: str
) -> dict[tuple[str, str], Cited[float]]:
    return {
        k: Cited(v, _c(rule, "M68.3 (sigma_B limits)", verified, note))
        for k, v in STRENGTH_CAPS.items()
    }


def _iacs() -> RuleSet:
    """IACS UR M68 (module docstring); crankdyn's behaviour before the rule sets."""
    cap_note = (
        "not read; 760 (carbon, C-Mn), 800 (alloy), 600 (propeller shafts) as LR Pt 5 Ch 6 "
        "2.1.1 reads for LR; KR, implementing M68, caps carbon steel at 600"
    )
    factors = {
        k: Cited(
            v, _c(IACS, "M68.4 (C_K table)", False, "not read; the values KR Table 5.4.1 prints")
        )
        for k, v in DESIGN_FACTORS.items()
    }
    unread = _c(IACS, "M68.4", False, "not stated in the part read")
    return RuleSet(
        key="iacs-m68",
        title="IACS UR M68",
        basis=None,
        scope=_c(
            IACS,
            "M68.1",
            note="intermediate, thrust and propeller shafts of traditional straight forged "
            "design; not crankshafts (M53), generator rotor shafts, gearing shafts",
        ),
        stress_basis=_c(IACS, "M68.4", False, _M68_NOT_READ),
        shaft_formula=_c(IACS, "M68.4", False, _M68_NOT_READ),
        transient_formula=_c(IACS, "M68.4", False, _M68_NOT_READ),
        size_factor=_c(IACS, "M68.4", False, _M68_NOT_READ),
        overspeed=Cited(1.05, _c(IACS, "M68.4", False, _M68_NOT_READ)),
        barred_upper=Cited(0.8, _c(IACS, "M68.4", False, _M68_NOT_READ)),
        strength_caps=_m68_caps(IACS, False, cap_note),
        design_factors=factors,
        widening=Cited("none", _c(IACS, "M68.4", False, "no margin in crankdyn's M68 reading")),
        tachometer=Cited(None, unread),
        cpp=Cited((), unread),
        misfire=Cited(None, unread),
        keyways=Cited(None, unread),
        min_strength_transient=Cited(None, unread),
        calculation_upper=Cited(None, unread),
        crankshaft=Cited(None, _c(IACS, "M68.1", note="crankshafts are IACS UR M53's")),
        genset=Cited(None, _c(IACS, "M68.1", note="generator rotor shafts are not covered")),
        transient_upper_genset=Cited(None, _c(IACS, "M68.1", note="not covered")),
    )


def _lr() -> RuleSet:
    """Lloyd's Register (module docstring): M68 with LR's margin and caps."""
    base = _iacs()
    caps: dict[tuple[str, str], Cited[float]] = {}
    for (material, kind), value in STRENGTH_CAPS.items():
        if kind == "propeller":
            clause = _c(
                LR_SHIPS,
                "Pt 5 Ch 6 3.5.1",
                False,
                "the screwshaft limit (2.1.1 refers to 3.5.1) could not be read; M68's 600",
            )
        else:
            clause = _c(
                LR_SHIPS,
                "Pt 5 Ch 6 2.1.1, 2.1.4",
                note="carbon/C-Mn 400-760, alloy not above 800 N/mm^2; no higher vibration stress "
                "from Pt 5 Ch 8 2.5 for higher strengths unless an alloy intermediate shaft is "
                "approved (Pt 5 Ch 6 5)",
            )
        caps[(material, kind)] = Cited(value, clause)
    read_rows = {"integral flange", "shrink fit", "keyway tapered"}
    factors = {
        k: Cited(
            v,
            _c(LR_NAVAL, "Vol 2 Pt 5 Ch 1 Table 1.3.1")
            if k in read_rows
            else _c(LR_SHIPS, "Pt 5 Ch 8 2 (C_k table)", False, "row not read; M68's value"),
        )
        for k, v in DESIGN_FACTORS.items()
    }
    ch8 = _c(LR_SHIPS, "Pt 5 Ch 8 2.5", False, _LR_CH8_NOT_READ)
    unread = _c(LR_SHIPS, "Pt 5 Ch 8 2", False, "could not be read")
    return replace(
        base,
        key="lr",
        title="Lloyd's Register",
        scope=_c(
            LR_SHIPS,
            "Pt 5 Ch 6 5.2.1",
            note="Pt 5 Ch 8 2.5 'Limiting stress in propulsion shafting' is LR's tau_c clause",
        ),
        stress_basis=_c(
            LR_NAVAL,
            "Vol 2 Pt 5 Ch 1 3.1.2, 3.1.3",
            note="half-range amplitudes of the synthesis of all orders; nominal stress of the "
            "plain section neglecting stress raisers",
        ),
        shaft_formula=ch8,
        transient_formula=ch8,
        size_factor=_c(LR_NAVAL, "Vol 2 Pt 5 Ch 1 3.1.1", note="C_d = 0.35 + 0.93 d^-0.2"),
        overspeed=Cited(1.05, ch8),
        barred_upper=Cited(0.8, ch8),
        strength_caps=caps,
        design_factors=factors,
        widening=Cited(
            "lr",
            _c(
                LR_SHIPS,
                "Pt 5 Ch 8 2.5",
                False,
                "could not be read; crankdyn's LR margin, the formula KR 206.1(1) prints",
            ),
        ),
        tachometer=Cited(None, unread),
        cpp=Cited((), unread),
        misfire=Cited(None, unread),
        keyways=Cited(None, unread),
        min_strength_transient=Cited(
            500e6,
            _c(
                LR_SHIPS,
                "Pt 5 Ch 6 2.1.3",
                note="where vibratory stresses come close to the transient limit",
            ),
        ),
        calculation_upper=Cited(None, unread),
        crankshaft=Cited(None, unread),
        genset=Cited(None, unread),
        transient_upper_genset=Cited(None, unread),
    )


def _kr() -> RuleSet:
    """KR 2025 Pt 5 Ch 4 (module docstring), read whole."""
    tx = "markdown transcription: "
    caps: dict[tuple[str, str], Cited[float]] = {}
    for material in ("carbon", "alloy"):
        for kind in ("intermediate", "thrust", "propeller"):
            value = 800e6 if (material == "alloy" and kind != "propeller") else 600e6
            caps[(material, kind)] = Cited(
                value,
                _c(
                    KR,
                    "Pt 5 Ch 4 202.1(1) (T_s)",
                    note="600 for carbon steel forgings; 800 for low alloy steel in intermediate "
                    "and thrust shafts (unless specially approved); 600 in propeller and stern "
                    "tube shafts",
                ),
            )
    kr_ck = {
        "integral flange": "integral coupling flanges",
        "shrink fit": "shrink fit coupling flanges (note 1)",
        "keyway tapered": "keyways, tapered connection (note 2)",
        "keyway cylindrical": "keyways, cylindrical connection (note 2)",
        "radial hole": "radial hole (note 3)",
        "longitudinal slot": "longitudinal slot (notes 4, 5)",
        "thrust collar": "thrust shafts, on both sides of thrust collar",
        "roller thrust bearing": "thrust shafts, in way of a roller bearing",
        "propeller flange": "propeller shaft (note 6: any fitting)",
        "propeller keyless": "propeller shaft (note 6: any fitting)",
        "propeller key": "propeller shaft (note 6: any fitting)",
        "stern tube": "stern tube shaft",
    }
    factors = {
        k: Cited(v, _c(KR, "Pt 5 Ch 4 Table 5.4.1", note=kr_ck[k]))
        for k, v in DESIGN_FACTORS.items()
    }
    crank = CrankshaftRule(
        a={"A": 45e6, "B": 45e6},
        b={"A": 24e6, "B": 29e6},
        k=2.0,
        transient_upper=0.8,
        c={"A": 21e6, "B": 16e6},
        e=237e6,
        overspeed_upper=1.15,
        clauses={
            "continuous": _c(KR, "Pt 5 Ch 4 201.1", note="0 <= lambda <= 1"),
            "transient": _c(KR, "Pt 5 Ch 4 201.2", note="below and at 0.8"),
            "overspeed": _c(
                KR,
                "Pt 5 Ch 4 201.3",
                note=tx + "tau_3 = 21 (16) + 237 (lambda - 0.8) sqrt(lambda - 1), 1 <= lambda "
                "<= 1.15; check against the PDF",
            ),
            "material": _c(KR, "Pt 5 Ch 4 201.4"),
        },
    )
    genset = GensetRule(
        window=(0.9, 1.1),
        crankshaft={"A": 21e6, "B": 16e6},
        crankshaft_transient=90e6,
        generator=31e6,
        generator_transient=118e6,
        clauses={
            "crankshaft": _c(
                KR,
                "Pt 5 Ch 4 203.1",
                note=tx + "(2) prints 'tau_1 = 90' in the sentence that names tau_2",
            ),
            "generator": _c(KR, "Pt 5 Ch 4 203.2"),
            "material": _c(KR, "Pt 5 Ch 4 203.3"),
        },
    )
    f202 = _c(KR, "Pt 5 Ch 4 202.1(1)", note="0 <= lambda <= 0.9, 1.38 for 0.9 <= lambda <= 1.05")
    return RuleSet(
        key="kr",
        title="Korean Register (KR)",
        basis=None,
        scope=_c(KR, "Pt 5 Ch 4 101.1"),
        stress_basis=_c(KR, "Pt 5 Ch 4 103.1", note="alternating stress amplitude over a cycle"),
        shaft_formula=f202,
        transient_formula=_c(KR, "Pt 5 Ch 4 202.1(2)", note="below 80 % of the rated speed"),
        size_factor=_c(KR, "Pt 5 Ch 4 202.1(1) (C_d)"),
        overspeed=Cited(1.05, f202),
        barred_upper=Cited(0.8, _c(KR, "Pt 5 Ch 4 202.1(2)", note="below 80 %")),
        strength_caps=caps,
        design_factors=factors,
        widening=Cited(
            "lr",
            _c(
                KR,
                "Pt 5 Ch 4 206.1(1)",
                note=tx + "16 N_c/(18 - lambda) <= N <= (18 - lambda) N_c/16, the formula of "
                "crankdyn's LR margin",
            ),
        ),
        tachometer=Cited(
            None,
            _c(KR, "Pt 5 Ch 4 206.3", note="'having regard to the tachometer accuracy', no value"),
        ),
        cpp=Cited(("full pitch", "zero pitch"), _c(KR, "Pt 5 Ch 4 206.1(2)")),
        misfire=Cited(
            True,
            _c(
                KR,
                "Pt 5 Ch 4 102.1(4), 206.1(3)",
                note="any one cylinder misfiring (no injection, with compression); its "
                "restricted ranges must allow safe navigation",
            ),
        ),
        keyways=Cited(
            "keyways are in general not to be used in installations with a barred speed range",
            _c(KR, "Pt 5 Ch 4 Table 5.4.1 note (2)"),
        ),
        min_strength_transient=Cited(
            None, _c(KR, "Pt 5 Ch 4", note="not stated in Ch 4 (Ch 3 not read)")
        ),
        calculation_upper=Cited(1.2, _c(KR, "Pt 5 Ch 4 102.1(2)")),
        major_criticals={
            "propulsion": Cited((0.8, 1.1), _c(KR, "Pt 5 Ch 4 204")),
            "generator": Cited((0.9, 1.1), _c(KR, "Pt 5 Ch 4 204")),
        },
        crankshaft=Cited(crank, _c(KR, "Pt 5 Ch 4 201", note="main engines")),
        genset=Cited(genset, _c(KR, "Pt 5 Ch 4 203")),
        transient_upper_genset=Cited(0.9, _c(KR, "Pt 5 Ch 4 203.1(2), 203.2(2)")),
    )


def _unread(key: str, title: str, rule: str, seen: str) -> RuleSet:
    """A society whose torsional-vibration text could not be read: IACS UR M68's values, every
    clause unverified (module docstring)."""
    note = f"not read ({seen}); IACS UR M68's value, which every IACS member implements"
    base = _iacs()

    def mark(clause: Clause) -> Clause:
        return Clause(rule, "", "torsional vibration", False, note)

    def remap(value: Any) -> Any:
        if isinstance(value, Clause):
            return mark(value)
        if isinstance(value, Cited):
            return Cited(value.value, mark(value.clause))
        if isinstance(value, Mapping):
            return {k: remap(v) for k, v in value.items()}
        return value

    changes = {f.name: remap(getattr(base, f.name)) for f in fields(base)}
    changes.update(key=key, title=title, basis="iacs-m68")
    return RuleSet(**changes)


RULESETS: Mapping[str, RuleSet] = {
    "iacs-m68": _iacs(),
    "lr": _lr(),
    "kr": _kr(),
    "dnv": _unread(
        "dnv",
        "DNV",
        "DNV Rules for Classification of Ships Pt 4 Ch 2 Sec 2 / DNV-CG-0038",
        "seen: the covers of DNV-RU-SHIP Pt 4 Ch 2 July 2021 and DNV-CG-0038 Dec 2015, Aug 2021",
    ),
    "abs": _unread(
        "abs",
        "ABS",
        "ABS Rules for Building and Classing Marine Vessels Pt 4 Ch 3 (4-3-2)",
        "seen: the contents of Part 4, January 2023",
    ),
    "bv": _unread("bv", "Bureau Veritas", "BV NR467 Pt C Ch 1 Sec 9", "no copy found"),
}
"""The rule sets by key (``[tvc] rules``)."""

RULESET_KEYS = tuple(RULESETS)
"""The keys of :data:`RULESETS`."""


def get(key: str) -> RuleSet:
    """The rule set of a key.

    Parameters
    ----------
    key : str
        One of :data:`RULESET_KEYS`.

    Returns
    -------
    RuleSet

    Raises
    ------
    InputError
        Naming the key ``rules`` and the value, with the closest key.

    Examples
    --------
    >>> get("kr").strength_caps[("carbon", "intermediate")].value / 1e6
    600.0
    >>> get("KR ").key
    'kr'
    """
    name = str(key).strip().lower()
    if name not in RULESETS:
        raise InputError(
            f"expected one of {', '.join(RULESET_KEYS)}{did_you_mean(name, RULESET_KEYS)}",
            key="rules",
            value=key,
        )
    return RULESETS[name]


def unverified(rules: RuleSet) -> tuple[tuple[str, Clause], ...]:
    """The clauses of a rule set that could not be verified against its text.

    Parameters
    ----------
    rules : RuleSet

    Returns
    -------
    tuple of (str, Clause)
        Named as in :meth:`RuleSet.clauses`.

    Examples
    --------
    >>> len(unverified(get("dnv"))) == len(get("dnv").clauses())
    True
    >>> [name for name, _ in unverified(get("kr"))]
    []
    """
    return tuple((name, c) for name, c in rules.clauses() if not c.verified)


def capped_strength(
    rules: RuleSet,
    tensile_strength: ArrayLike,
    material: str = "carbon",
    kind: str = "intermediate",
) -> NDArray[np.float64]:
    """sigma_B the society's formula uses: the specified minimum tensile strength, at most the
    society's cap for the material and shaft kind (:attr:`RuleSet.strength_caps`; KR 2025 Pt 5
    Ch 4 202.1(1), LR Pt 5 Ch 6 2.1.1/2.1.4, IACS UR M68.3).

    Parameters
    ----------
    rules : RuleSet
    tensile_strength : float or array_like
        Specified minimum tensile strength (Pa).
    material : str
        ``"carbon"`` (carbon and carbon-manganese steel) or ``"alloy"``.
    kind : str
        ``"intermediate"``, ``"thrust"`` or ``"propeller"`` (KR: propeller and stern tube shafts).

    Returns
    -------
    numpy.ndarray
        sigma_B (Pa), the shape of ``tensile_strength``.

    Raises
    ------
    InputError
        Naming ``material`` or ``kind`` when unknown.

    Examples
    --------
    >>> [float(capped_strength(get(k), 800e6)) / 1e6 for k in ("kr", "lr")]
    [600.0, 760.0]
    """
    if material not in ("carbon", "alloy"):
        raise InputError("expected carbon or alloy", key="material", value=material)
    if kind not in ("intermediate", "thrust", "propeller"):
        raise InputError("expected intermediate, thrust or propeller", key="kind", value=kind)
    cap = rules.strength_caps[(material, kind)].value
    return np.minimum(np.asarray(tensile_strength, dtype=float), cap)


def continuous_limit(
    rules: RuleSet,
    speed_ratio: ArrayLike,
    tensile_strength: ArrayLike,
    design_factor: ArrayLike,
    diameter: ArrayLike,
    material: str = "carbon",
    kind: str = "intermediate",
) -> NDArray[np.float64]:
    """The society's tau_C for continuous running of a propulsion shaft.

    tau_C = (sigma_B + 160)/18 C_K C_D (3 - 2 lambda^2) below lambda = 0.9, the factor 1.38 from
    0.9 to 1.05 (sigma_B in N/mm^2 capped by :func:`capped_strength`, C_D = 0.35 + 0.93 d^-0.2,
    d in mm): KR 2025 Pt 5 Ch 4 202.1(1), IACS UR M68.4 (:attr:`RuleSet.shaft_formula`);
    :func:`crankdyn.torsion.rules.permissible_continuous`.

    Parameters
    ----------
    rules : RuleSet
    speed_ratio : array_like
        lambda = n / n_0 (dimensionless).
    tensile_strength : float or array_like
        Specified minimum tensile strength (Pa), before the cap.
    design_factor : float or array_like
        C_K (dimensionless).
    diameter : float or array_like
        Outer diameter (m).
    material, kind : str
        For the cap (:func:`capped_strength`).

    Returns
    -------
    numpy.ndarray
        tau_C (Pa), broadcast over the arguments; NaN above lambda = 1.05.

    Examples
    --------
    Carbon steel of 800 N/mm^2, a plain 300 mm intermediate shaft at lambda = 0.95 (MPa):

    >>> tau = [continuous_limit(get(k), 0.95, 800e6, 1.0, 0.3) for k in ("kr", "lr")]
    >>> [round(float(t) / 1e6, 4) for t in tau]
    [37.7106, 45.6497]
    """
    sigma = capped_strength(rules, tensile_strength, material, kind)
    ck = np.asarray(design_factor, dtype=float)
    return permissible_continuous(speed_ratio, sigma, ck, diameter)


def transient_limit(
    rules: RuleSet,
    speed_ratio: ArrayLike,
    tensile_strength: ArrayLike,
    design_factor: ArrayLike,
    diameter: ArrayLike,
    material: str = "carbon",
    kind: str = "intermediate",
) -> NDArray[np.float64]:
    """The society's tau_T while passing a barred range: 1.7 tau_C / sqrt(C_K) up to
    lambda = 0.8 (KR 2025 Pt 5 Ch 4 202.1(2), IACS UR M68.4; :attr:`RuleSet.transient_formula`,
    :func:`crankdyn.torsion.rules.permissible_transient`).

    Parameters
    ----------
    rules : RuleSet
    speed_ratio : array_like
        lambda = n / n_0 (dimensionless).
    tensile_strength : float or array_like
        Specified minimum tensile strength (Pa), before the cap.
    design_factor : float or array_like
        C_K (dimensionless).
    diameter : float or array_like
        Outer diameter (m).
    material, kind : str
        For the cap.

    Returns
    -------
    numpy.ndarray
        tau_T (Pa), broadcast; NaN above lambda = 0.8.

    Examples
    --------
    C_K = 0.6, 300 mm, capped at 600: 1.7 x 40.9898 / sqrt(0.6) (MPa):

    >>> round(float(transient_limit(get("kr"), 0.5, 800e6, 0.6, 0.3)) / 1e6, 3)
    89.96
    """
    tau_c = continuous_limit(
        rules, speed_ratio, tensile_strength, design_factor, diameter, material, kind
    )
    return permissible_transient(speed_ratio, tau_c, design_factor)


def design_factor(rules: RuleSet, feature: str) -> float:
    """C_K of a design feature in the society's table (:attr:`RuleSet.design_factors`).

    Parameters
    ----------
    rules : RuleSet
    feature : str
        A key of :data:`crankdyn.tvc.limits.DESIGN_FACTORS`.

    Returns
    -------
    float
        C_K (dimensionless).

    Raises
    ------
    InputError
        Naming the key ``feature`` with the closest feature.

    Examples
    --------
    >>> design_factor(get("kr"), "keyway cylindrical")
    0.45
    """
    return _factor(rules, feature)


def _factor(rules: RuleSet, feature: str) -> float:
    if feature not in rules.design_factors:
        raise InputError(
            f"expected one of {', '.join(rules.design_factors)}"
            f"{did_you_mean(feature, rules.design_factors)}",
            key="feature",
            value=feature,
        )
    return float(rules.design_factors[feature].value)


def shaft_limit(
    rules: RuleSet,
    between: tuple[str, str],
    tensile_strength: float,
    design_factor: float = 1.0,
    material: str = "carbon",
    kind: str = "intermediate",
    feature: str | None = None,
) -> ShaftLimit:
    """The :class:`crankdyn.torsion.rules.ShaftLimit` of a shaft under the society's cap, for
    the rule check (:func:`crankdyn.torsion.rules.check_rules`) and the TVC.

    Parameters
    ----------
    rules : RuleSet
    between : (str, str)
        The shaft's two masses.
    tensile_strength : float
        Specified minimum tensile strength (Pa).
    design_factor : float
        C_K (dimensionless), used where ``feature`` is None.
    material, kind : str
        For the cap (:func:`capped_strength`).
    feature : str or None
        A design feature: C_K from the society's table (:func:`design_factor`).

    Returns
    -------
    ShaftLimit
        With ``strength_cap`` the society's cap.

    Examples
    --------
    >>> shaft_limit(get("kr"), ("a", "b"), 800e6).strength_used / 1e6
    600.0
    """
    ck = design_factor if feature is None else _factor(rules, feature)
    capped_strength(rules, tensile_strength, material, kind)  # validates material and kind
    return ShaftLimit(
        tuple(between),  # type: ignore[arg-type]
        tensile_strength,
        ck,
        material=material,
        kind=kind,
        strength_cap=rules.strength_caps[(material, kind)].value,
        feature=feature,
    )


def tachometer_tolerance(rules: RuleSet, given: float | None = None) -> float:
    """The tachometer tolerance that widens a declared barred range on both sides.

    ``given`` (the user's ``tachometer_tolerance``) where given, else the value the rule set's
    text states (:attr:`RuleSet.tachometer`), else :data:`DEFAULT_TACHOMETER_TOLERANCE` (no
    text read states one; KR 2025 Pt 5 Ch 4 206.3 asks for the accuracy to be regarded).

    Parameters
    ----------
    rules : RuleSet
    given : float or None
        The user's value (fraction of the speed).

    Returns
    -------
    float
        Fraction of the speed.

    Examples
    --------
    >>> tachometer_tolerance(get("kr")), tachometer_tolerance(get("kr"), 0.01)
    (0.02, 0.01)
    """
    if given is not None:
        return float(given)
    stated = rules.tachometer.value
    return float(stated) if stated is not None else DEFAULT_TACHOMETER_TOLERANCE


def declared_barred_range(
    rules: RuleSet,
    critical_speed: ArrayLike,
    rated_speed: float,
    exceeds_start: ArrayLike | None = None,
    exceeds_end: ArrayLike | None = None,
    tolerance: float | None = None,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The barred range to declare around a critical speed: the range where the limit is
    exceeded, widened to the society's least range (:attr:`RuleSet.widening`; KR 2025 Pt 5 Ch 4
    206.1(1), LR's margin: 16 n_c/(18 - lambda_c) to (18 - lambda_c) n_c/16), then by the
    tachometer tolerance on both sides (:func:`tachometer_tolerance`):
    start = min(exceeds_start, low) (1 - tol), end = max(exceeds_end, high) (1 + tol).

    Parameters
    ----------
    rules : RuleSet
    critical_speed : float or array_like
        n_c (rad/s): the speed of the largest response in the range.
    rated_speed : float
        n_0 (rad/s).
    exceeds_start, exceeds_end : float or array_like or None
        Where the limit is exceeded (rad/s); None: the critical speed.
    tolerance : float or None
        The tachometer tolerance (fraction); None: :func:`tachometer_tolerance` of the rules.

    Returns
    -------
    start, end : numpy.ndarray
        The declared range (rad/s), broadcast over the arguments.

    Examples
    --------
    n_c = 500 rpm, n_0 = 750 rpm, no tolerance (rpm): KR's least range
    16 x 500 / 17.3333 = 461.538 to 17.3333 x 500 / 16 = 541.667:

    >>> from crankdyn.constants import RPM
    >>> s, e = declared_barred_range(get("kr"), 500 / RPM, 750 / RPM, tolerance=0.0)
    >>> round(float(s) * RPM, 3), round(float(e) * RPM, 3)
    (461.538, 541.667)
    """
    nc = np.asarray(critical_speed, dtype=float)
    lo, hi = barred_limits(nc, rated_speed, rules.widening.value)
    a = nc if exceeds_start is None else np.asarray(exceeds_start, dtype=float)
    b = nc if exceeds_end is None else np.asarray(exceeds_end, dtype=float)
    tol = tachometer_tolerance(rules) if tolerance is None else float(tolerance)
    return np.minimum(a, lo) * (1.0 - tol), np.maximum(b, hi) * (1.0 + tol)


def barred_range_permitted(
    rules: RuleSet,
    start: ArrayLike,
    end: ArrayLike,
    rated_speed: float,
    application: str = "propulsion",
) -> NDArray[np.bool_]:
    """Whether a declared barred range is permitted where it lies: it ends at or below the
    society's highest speed ratio of a barred range (propulsion shafts 0.8: KR 2025 Pt 5 Ch 4
    202.1(2), IACS UR M68.4; generating sets 0.9: KR 203.1(2), 203.2(2)) and does not contain
    the rated speed. The stress against tau_T is a separate check.

    Parameters
    ----------
    rules : RuleSet
    start, end : float or array_like
        The declared range (rad/s).
    rated_speed : float
        n_0 (rad/s).
    application : str
        ``"propulsion"`` or ``"generator"``.

    Returns
    -------
    numpy.ndarray of bool
        Broadcast over ``start`` and ``end``.

    Raises
    ------
    InputError
        Naming ``application`` when unknown, or ``rules`` where the rule set states no limit
        for generating sets.

    Examples
    --------
    >>> barred_range_permitted(get("kr"), [300.0, 300.0], [400.0, 460.0], 500.0).tolist()
    [True, False]
    >>> bool(barred_range_permitted(get("kr"), 300.0, 450.0, 500.0, "generator"))
    True
    """
    if application == "propulsion":
        upper = rules.barred_upper.value
    elif application == "generator":
        cited = rules.transient_upper_genset
        if cited is None or cited.value is None:
            raise InputError(
                f"{rules.title}: no barred-range limit for generating sets in the text read "
                f"({cited.clause.cite() if cited else 'none'})",
                key="rules",
                value=rules.key,
            )
        upper = cited.value
    else:
        raise InputError("expected propulsion or generator", key="application", value=application)
    s = np.asarray(start, dtype=float)
    e = np.asarray(end, dtype=float)
    n0 = float(rated_speed)
    return (e <= upper * n0) & ~((s <= n0) & (n0 <= e))


def cpp_conditions(rules: RuleSet) -> tuple[str, ...]:
    """The pitch settings of a controllable-pitch propeller the society asks to calculate
    (KR 2025 Pt 5 Ch 4 206.1(2): both full and zero pitch); empty where the text read states
    none (:attr:`RuleSet.cpp` cites why).

    Parameters
    ----------
    rules : RuleSet

    Returns
    -------
    tuple of str

    Examples
    --------
    >>> cpp_conditions(get("kr")), cpp_conditions(get("lr"))
    (('full pitch', 'zero pitch'), ())
    """
    return tuple(rules.cpp.value)


def major_critical_permitted(
    rules: RuleSet,
    critical_speed: ArrayLike,
    rated_speed: float,
    application: str = "propulsion",
) -> NDArray[np.bool_]:
    """Whether a major critical of the one-node mode may lie at a speed: outside the society's
    window (KR 2025 Pt 5 Ch 4 204: 0.8 <= lambda <= 1.1 for propulsion, 0.9 <= lambda <= 1.1 for
    generators, unless specially approved).

    Parameters
    ----------
    rules : RuleSet
    critical_speed : float or array_like
        The major critical (rad/s).
    rated_speed : float
        n_0 (rad/s).
    application : str
        ``"propulsion"`` or ``"generator"``.

    Returns
    -------
    numpy.ndarray of bool
        True outside the window (the window's ends belong to it).

    Raises
    ------
    InputError
        Naming ``rules`` where the text read states no window for the application.

    Examples
    --------
    >>> major_critical_permitted(get("kr"), [85.0, 95.0, 112.0], 100.0, "generator").tolist()
    [True, False, True]
    """
    if application not in rules.major_criticals:
        raise InputError(
            f"{rules.title}: no window for major criticals of {application} shafting in the "
            "text read",
            key="rules",
            value=rules.key,
        )
    low, high = rules.major_criticals[application].value
    lam = np.asarray(critical_speed, dtype=float) / float(rated_speed)
    return ~((lam >= low) & (lam <= high))


def engine_group(cycle: int, vee: bool = False, firing_interval: float | None = None) -> str:
    """KR's engine group of the crankshaft and generating-set limits (KR 2025 Pt 5 Ch 4
    201.1(1)/(2); :data:`ENGINE_GROUPS`): ``"A"`` for 4-stroke in-line engines and 4-stroke
    vee engines firing at 45° or 60° intervals, ``"B"`` for 2-stroke engines and other 4-stroke
    vee engines.

    Parameters
    ----------
    cycle : int
        2 or 4 (strokes per cycle).
    vee : bool
        A vee engine.
    firing_interval : float or None
        The vee engine's firing interval (deg).

    Returns
    -------
    str
        ``"A"`` or ``"B"``.

    Raises
    ------
    InputError
        Naming ``cycle`` when neither 2 nor 4.

    Examples
    --------
    >>> engine_group(4), engine_group(4, vee=True, firing_interval=60), engine_group(2)
    ('A', 'A', 'B')
    """
    if cycle not in (2, 4):
        raise InputError("expected 2 or 4 strokes", key="cycle", value=cycle)
    if cycle == 2:
        return "B"
    if not vee:
        return "A"
    if firing_interval is not None and any(
        math.isclose(firing_interval, x, abs_tol=1e-9) for x in (45.0, 60.0)
    ):
        return "A"
    return "B"


def material_factors(
    rules: RuleSet,
    tensile_strength: ArrayLike,
    yield_strength: ArrayLike,
    material: str = "carbon",
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """KR's material factors on the crankshaft and generator-shaft limits (KR 2025 Pt 5 Ch 4
    201.4, 203.3): for T_s above 440 N/mm^2, f_m = 1 + 2/3 (T_s/440 - 1) on the continuous
    (and overspeed) limits; for Y above 225 N/mm^2, f_m = Y/225 on the transient limit; 1
    otherwise ("may be increased"). Above 590 N/mm^2 (carbon steel forgings) or 835 N/mm^2
    (low alloy) the Society decides the T_s to use: NaN.

    Parameters
    ----------
    rules : RuleSet
    tensile_strength, yield_strength : float or array_like
        Specified minimum tensile and yield strengths (Pa).
    material : str
        ``"carbon"`` or ``"alloy"``.

    Returns
    -------
    f_continuous, f_transient : numpy.ndarray
        Dimensionless, broadcast.

    Raises
    ------
    InputError
        Naming ``rules`` where the rule set has no crankshaft rule with a material factor.

    Examples
    --------
    T_s = 550, Y = 300 N/mm^2: 1 + 2/3 x (1.25 - 1) = 1.16667, 300/225 = 1.33333:

    >>> fc, ft = material_factors(get("kr"), 550e6, 300e6)
    >>> round(float(fc), 5), round(float(ft), 5)
    (1.16667, 1.33333)
    """
    _crank_rule(rules)
    if material not in ("carbon", "alloy"):
        raise InputError("expected carbon or alloy", key="material", value=material)
    ts = np.asarray(tensile_strength, dtype=float) / _MPA
    y = np.asarray(yield_strength, dtype=float) / _MPA
    limit = 590.0 if material == "carbon" else 835.0
    fc = np.where(ts > 440.0, 1.0 + 2.0 / 3.0 * (ts / 440.0 - 1.0), 1.0)
    fc = np.where(ts > limit, np.nan, fc)
    ft = np.where(y > 225.0, y / 225.0, 1.0)
    fc_b, ft_b = np.broadcast_arrays(fc, ft)
    return np.array(fc_b, dtype=float), np.array(ft_b, dtype=float)


def _crank_rule(rules: RuleSet) -> CrankshaftRule:
    cited = rules.crankshaft
    if cited is None or cited.value is None:
        where = cited.clause.cite() if cited is not None else rules.title
        raise InputError(
            f"{rules.title} states no crankshaft limit in the text read ({where}): give the "
            "engine builder's limit ([tvc.crankshaft])",
            key="rules",
            value=rules.key,
        )
    return cited.value


def crankshaft_limits(
    rules: RuleSet,
    speed_ratio: ArrayLike,
    group: str,
    tensile_strength: ArrayLike | None = None,
    yield_strength: ArrayLike | None = None,
    material: str = "carbon",
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """The society's crankshaft limits of a main engine (:class:`CrankshaftRule`; KR 2025 Pt 5
    Ch 4 201): tau_1 = 45 - 24 lambda^2 (group A) or 45 - 29 lambda^2 (group B) N/mm^2 for
    0 <= lambda <= 1; tau_2 = 2 tau_1 for lambda <= 0.8; tau_3 = 21 (A) or 16 (B)
    + 237 (lambda - 0.8) sqrt(lambda - 1) N/mm^2 for 1 <= lambda <= 1.15; each times the
    material factor (:func:`material_factors`) where the strengths are given.

    Parameters
    ----------
    rules : RuleSet
    speed_ratio : array_like
        lambda = n / n_0 (dimensionless).
    group : str
        ``"A"`` or ``"B"`` (:func:`engine_group`).
    tensile_strength, yield_strength : float or array_like or None
        Specified minimum strengths (Pa) for the material factor; None: factor 1.
    material : str
        ``"carbon"`` or ``"alloy"``.

    Returns
    -------
    tau_1, tau_2, tau_3 : numpy.ndarray
        Continuous, transient and above-rated limits (Pa), NaN outside their ranges.

    Raises
    ------
    InputError
        Naming ``rules`` where the rule set states no crankshaft limit (IACS UR M68.1: the
        crankshaft is M53's), ``group`` when unknown.

    Examples
    --------
    Group A at lambda = 0.5: 45 - 24 x 0.25 = 39 N/mm^2, tau_2 = 78:

    >>> t1, t2, t3 = crankshaft_limits(get("kr"), [0.5, 1.1], "A")
    >>> (t1 / 1e6).round(4).tolist(), (t2 / 1e6).round(4).tolist(), (t3 / 1e6).round(4).tolist()
    ([39.0, nan], [78.0, nan], [nan, 43.4838])
    """
    rule = _crank_rule(rules)
    if group not in rule.a:
        raise InputError(f"expected one of {', '.join(rule.a)}", key="group", value=group)
    lam = np.asarray(speed_ratio, dtype=float)
    tau1 = rule.a[group] - rule.b[group] * lam**2
    tau1 = np.where((lam >= 0.0) & (lam <= 1.0), tau1, np.nan)
    tau2 = np.where(lam <= rule.transient_upper, rule.k * tau1, np.nan)
    with np.errstate(invalid="ignore"):
        tau3 = rule.c[group] + rule.e * (lam - 0.8) * np.sqrt(lam - 1.0)
    tau3 = np.where((lam >= 1.0) & (lam <= rule.overspeed_upper), tau3, np.nan)
    if tensile_strength is not None or yield_strength is not None:
        ts = 0.0 if tensile_strength is None else tensile_strength
        y = 0.0 if yield_strength is None else yield_strength
        fc, ft = material_factors(rules, ts, y, material)
        tau1, tau2, tau3 = tau1 * fc, tau2 * ft, tau3 * fc
    return tau1, tau2, tau3


def genset_limits(
    rules: RuleSet,
    speed_ratio: ArrayLike,
    component: str,
    group: str | None = None,
    tensile_strength: ArrayLike | None = None,
    yield_strength: ArrayLike | None = None,
    material: str = "carbon",
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The society's generating-set limits (:class:`GensetRule`; KR 2025 Pt 5 Ch 4 203): from
    0.9 to 1.1 n_0 the crankshaft 21 (group A) or 16 (group B) N/mm^2 and the generator shaft
    31 N/mm^2; at and below 0.9 n_0, while passing, 90 and 118 N/mm^2; each times the material
    factor (203.3, :func:`material_factors`) where the strengths are given.

    Parameters
    ----------
    rules : RuleSet
    speed_ratio : array_like
        lambda = n / n_0 (dimensionless; n_0 the full-load speed).
    component : str
        ``"crankshaft"`` or ``"generator"``.
    group : str or None
        ``"A"`` or ``"B"`` for the crankshaft (:func:`engine_group`).
    tensile_strength, yield_strength : float or array_like or None
        Specified minimum strengths (Pa) for the material factor; None: factor 1.
    material : str
        ``"carbon"`` or ``"alloy"``.

    Returns
    -------
    continuous, transient : numpy.ndarray
        Limits (Pa), NaN outside their speed ranges.

    Raises
    ------
    InputError
        Naming ``rules`` where the rule set states no generating-set limit (IACS UR M68.1:
        generator rotor shafts are not covered), ``component`` or ``group`` when unknown.

    Examples
    --------
    >>> c, t = genset_limits(get("kr"), [0.5, 1.0], "generator")
    >>> (c / 1e6).tolist(), (t / 1e6).tolist()
    ([nan, 31.0], [118.0, nan])
    """
    cited = rules.genset
    rule = cited.value if cited is not None else None
    if rule is None:
        where = cited.clause.cite() if cited is not None else rules.title
        raise InputError(
            f"{rules.title} states no generating-set limit in the text read ({where}): give "
            "the makers' limits ([mass.limits], [tvc.crankshaft])",
            key="rules",
            value=rules.key,
        )
    if component == "crankshaft":
        if group is None or group not in rule.crankshaft:
            raise InputError(
                f"expected one of {', '.join(rule.crankshaft)}", key="group", value=group
            )
        steady, passing = rule.crankshaft[group], rule.crankshaft_transient
    elif component == "generator":
        steady, passing = rule.generator, rule.generator_transient
    else:
        raise InputError("expected crankshaft or generator", key="component", value=component)
    lam = np.asarray(speed_ratio, dtype=float)
    low, high = rule.window
    cont = np.where((lam >= low) & (lam <= high), steady, np.nan)
    trans = np.where(lam <= low, passing, np.nan)
    if tensile_strength is not None or yield_strength is not None:
        ts = 0.0 if tensile_strength is None else tensile_strength
        y = 0.0 if yield_strength is None else yield_strength
        fc, ft = material_factors(rules, ts, y, material)
        cont, trans = cont * fc, trans * ft
    return cont, trans
