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

One module per society says what was read of its text and builds its set:
:mod:`~crankdyn.tvc.rulesets.iacs` (IACS UR M68: M68.1 read, M68.3/M68.4 not),
:mod:`~crankdyn.tvc.rulesets.lr` (Lloyd's Register: Pt 5 Ch 6 2.1 and the Naval Ships rules'
3.1 read, Pt 5 Ch 8 2 not), :mod:`~crankdyn.tvc.rulesets.kr` (KR 2025 Pt 5 Ch 4, read whole),
:mod:`~crankdyn.tvc.rulesets.unread` (DNV, ABS, BV: not read, IACS M68's values marked so).
:mod:`~crankdyn.tvc.rulesets.model` holds the data classes and
:mod:`~crankdyn.tvc.rulesets.formulas` the functions (vectorised over speed ratio and diameter);
this package has the registry (:func:`get`), :func:`unverified` and :func:`differences` (the
values in which two societies differ: the rows a switch of ``[tvc] rules`` changes).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import fields, replace
from typing import Any

from crankdyn.errors import InputError, did_you_mean
from crankdyn.tvc.rulesets.formulas import (
    barred_range_permitted,
    capped_strength,
    continuous_limit,
    cpp_conditions,
    crankshaft_limits,
    declared_barred_range,
    design_factor,
    engine_group,
    genset_limits,
    major_critical_permitted,
    material_factors,
    shaft_limit,
    tachometer_tolerance,
    transient_limit,
)
from crankdyn.tvc.rulesets.iacs import iacs_m68
from crankdyn.tvc.rulesets.kr import kr
from crankdyn.tvc.rulesets.lr import lr
from crankdyn.tvc.rulesets.model import (
    DEFAULT_TACHOMETER_TOLERANCE,
    ENGINE_GROUPS,
    Cited,
    Clause,
    CrankshaftRule,
    GensetRule,
    RuleSet,
    cite_row,
)
from crankdyn.tvc.rulesets.unread import abs_rules, bv, dnv

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
    "cite_row",
    "continuous_limit",
    "cpp_conditions",
    "crankshaft_limits",
    "declared_barred_range",
    "design_factor",
    "differences",
    "engine_group",
    "genset_limits",
    "get",
    "major_critical_permitted",
    "material_factors",
    "shaft_limit",
    "tachometer_tolerance",
    "transient_limit",
    "unverified",
    "values",
]

RULESETS: Mapping[str, RuleSet] = {
    "iacs-m68": iacs_m68(),
    "lr": lr(),
    "kr": kr(),
    "dnv": dnv(),
    "abs": abs_rules(),
    "bv": bv(),
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


def values(rules: RuleSet) -> dict[str, Any]:
    """Every value of a rule set, named as in :meth:`RuleSet.clauses`; the formula citations
    (``scope``, ``stress_basis``, ``shaft_formula``, ``transient_formula``, ``size_factor``),
    which carry no value of their own, are left out, and a crankshaft or generating-set rule is
    one value without its clauses.

    Parameters
    ----------
    rules : RuleSet

    Returns
    -------
    dict
        Name -> value (SI units: Pa, speed ratios dimensionless).

    Examples
    --------
    >>> values(get("kr"))["strength_caps carbon/intermediate"] / 1e6
    600.0
    """
    out: dict[str, Any] = {}
    for f in fields(rules):
        value = getattr(rules, f.name)
        if isinstance(value, Cited):
            inner = value.value
            if isinstance(inner, (CrankshaftRule, GensetRule)):
                inner = replace(inner, clauses={})
            out[f.name] = inner
        elif isinstance(value, Mapping):
            for k, v in value.items():
                label = "/".join(k) if isinstance(k, tuple) else str(k)
                out[f"{f.name} {label}"] = v.value
    return out


def differences(a: RuleSet, b: RuleSet) -> tuple[str, ...]:
    """The values in which two rule sets differ (named as in :func:`values`; a value one set
    states and the other does not counts): the verdict rows a switch of ``[tvc] rules`` from
    ``a`` to ``b`` changes. Every row's citation changes with the society; these are the rows
    whose limit, range or condition changes.

    Parameters
    ----------
    a, b : RuleSet

    Returns
    -------
    tuple of str
        In the order of :func:`values` of ``a``, then those only ``b`` has.

    Examples
    --------
    >>> differences(get("iacs-m68"), get("dnv"))
    ()
    >>> differences(get("iacs-m68"), get("lr"))
    ('widening', 'min_strength_transient')
    """
    va, vb = values(a), values(b)
    names = list(va) + [n for n in vb if n not in va]
    return tuple(n for n in names if va.get(n) != vb.get(n))
