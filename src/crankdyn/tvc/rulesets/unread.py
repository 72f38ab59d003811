"""The rule sets of the societies whose torsional-vibration texts could not be read: DNV, ABS and
Bureau Veritas (docs/tvc.md, "Rule sets").

Each holds IACS UR M68's values (every IACS member implements the UR) with every clause marked
not verified and saying which documents were seen: for DNV the covers and contents of
DNV-RU-SHIP Pt 4 Ch 2 (July 2021) and of DNV-CG-0038 (December 2015, August 2021); for ABS the
contents of the Marine Vessel Rules Part 4 (January 2023); for BV no copy of NR467 Pt C Ch 1
Sec 9. A value is never passed off as read: the verdict rows cite "not verified: not read (...)".
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import fields
from typing import Any

from crankdyn.tvc.rulesets.iacs import iacs_m68
from crankdyn.tvc.rulesets.model import Cited, Clause, RuleSet

__all__ = ["abs_rules", "bv", "dnv", "unread"]


def unread(key: str, title: str, rule: str, seen: str) -> RuleSet:
    """A society whose torsional-vibration text could not be read: IACS UR M68's values (the
    ``"iacs-m68"`` set), every clause unverified (module docstring).

    Parameters
    ----------
    key, title : str
        The rule set's key and the society's name.
    rule : str
        The rule text that holds the society's torsional-vibration clauses.
    seen : str
        What of it could be seen (the note of every clause).

    Returns
    -------
    RuleSet
        With ``basis = "iacs-m68"``.
    """
    note = f"not read ({seen}); IACS UR M68's value, which every IACS member implements"
    base = iacs_m68()

    def mark(clause: Clause) -> Clause:
        return Clause(rule, "", "torsional vibration", False, note, "IACS UR M68")

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


def dnv() -> RuleSet:
    """The ``"dnv"`` rule set: DNV-RU-SHIP Pt 4 Ch 2 Sec 2 and DNV-CG-0038 not read.

    Returns
    -------
    RuleSet
    """
    return unread(
        "dnv",
        "DNV",
        "DNV Rules for Classification of Ships Pt 4 Ch 2 Sec 2 / DNV-CG-0038",
        "seen: the covers and contents of DNV-RU-SHIP Pt 4 Ch 2 July 2021 and DNV-CG-0038 "
        "Dec 2015, Aug 2021",
    )


def abs_rules() -> RuleSet:
    """The ``"abs"`` rule set: the Marine Vessel Rules 4-3-2/7 not read.

    Returns
    -------
    RuleSet
    """
    return unread(
        "abs",
        "ABS",
        "ABS Rules for Building and Classing Marine Vessels Pt 4 Ch 3 (4-3-2)",
        "seen: the contents of Part 4, January 2023",
    )


def bv() -> RuleSet:
    """The ``"bv"`` rule set: NR467 Pt C Ch 1 Sec 9 not found.

    Returns
    -------
    RuleSet
    """
    return unread("bv", "Bureau Veritas", "BV NR467 Pt C Ch 1 Sec 9", "no copy found")
