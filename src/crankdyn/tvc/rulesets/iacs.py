"""The ``"iacs-m68"`` rule set: IACS UR M68 "Dimensions of propulsion shafts and their
permissible torsional vibration stresses" (docs/tvc.md, "Rule sets").

Read: M68.1 (scope: intermediate, thrust and propeller shafts of traditional straight forged
design; not crankshafts, which are M53's, nor generator rotor shafts) and the start of M68.2, from
a public copy of the Corr.2 Nov 2012 / Aug 2014 text. Not read: M68.3 and M68.4 (the sigma_B
limits, tau_C, tau_T, C_D, the C_K table, the barred-range rule), nor Rev.2 (2015) or Rev.3
(Feb 2021, the current revision); every public copy found showed its first page only. The values
are crankdyn's M68 reading (:mod:`crankdyn.torsion.rules`, :mod:`crankdyn.tvc.limits`: the
formulas KR 2025 Pt 5 Ch 4 202.1 prints, which implements M68), each clause marked not verified.
"""

from __future__ import annotations

from crankdyn.torsion.rules import STRENGTH_CAPS
from crankdyn.tvc.limits import DESIGN_FACTORS
from crankdyn.tvc.rulesets.model import Cited, RuleSet
from crankdyn.tvc.rulesets.model import clause_of as _c

__all__ = ["IACS", "M68_AS", "M68_NOT_READ", "iacs_m68", "m68_caps"]

IACS = (
    "IACS UR M68",
    "Corr.2 Nov 2012 / Aug 2014 text (copy read: M68.1-M68.2; current revision Rev.3 Feb 2021)",
)
"""The rule text and the edition read."""

M68_NOT_READ = (
    "M68.3/M68.4 could not be read; the same formula is printed by KR 2025 Pt 5 Ch 4 202.1, "
    "which implements M68"
)
"""The note of every M68.3/M68.4 clause."""

M68_AS = "KR 2025 Pt 5 Ch 4 202.1 (the M68 formula as KR prints it)"
"""Where the unread M68.4 formulas are taken from (:attr:`Clause.value_as`)."""


def m68_caps(
    rule: tuple[str, str], verified: bool, note: str, value_as: str = ""
) -> dict[tuple[str, str], Cited[float]]:
    """crankdyn's caps on sigma_B (:data:`crankdyn.torsion.rules.STRENGTH_CAPS`: 760 N/mm^2
    carbon and C-Mn, 800 alloy, 600 propeller shafts, in Pa) cited to M68.3 of a rule text.

    Parameters
    ----------
    rule : (str, str)
        The rule text and its edition.
    verified : bool
        Whether the caps were read in it.
    note : str
        Where the values come from.
    value_as : str
        Where an unverified value is taken from (:attr:`Clause.value_as`).

    Returns
    -------
    dict
        (material, kind) -> Cited cap (Pa).
    """
    return {
        k: Cited(v, _c(rule, "M68.3 (sigma_B limits)", verified, note, value_as))
        for k, v in STRENGTH_CAPS.items()
    }


def iacs_m68() -> RuleSet:
    """The ``"iacs-m68"`` rule set (module docstring): crankdyn's IACS behaviour before the rule
    sets, M68.1 read, M68.3/M68.4 not.

    Returns
    -------
    RuleSet
    """
    cap_note = (
        "not read; 760 (carbon, C-Mn), 800 (alloy), 600 (propeller shafts) as LR Pt 5 Ch 6 "
        "2.1.1 reads for LR; KR, implementing M68, caps carbon steel at 600"
    )
    factors = {
        k: Cited(
            v,
            _c(
                IACS,
                "M68.4 (C_K table)",
                False,
                "not read; the values KR Table 5.4.1 prints",
                "KR 2025 Pt 5 Ch 4 Table 5.4.1",
            ),
        )
        for k, v in DESIGN_FACTORS.items()
    }
    unread = _c(IACS, "M68.4", False, "not stated in the part read")
    m68 = _c(IACS, "M68.4", False, M68_NOT_READ, M68_AS)
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
        stress_basis=m68,
        shaft_formula=m68,
        transient_formula=m68,
        size_factor=m68,
        overspeed=Cited(1.05, m68),
        barred_upper=Cited(
            0.8, _c(IACS, "M68.4", False, M68_NOT_READ, "KR 2025 Pt 5 Ch 4 202.1(2)")
        ),
        strength_caps=m68_caps(IACS, False, cap_note, "LR Pt 5 Ch 6 2.1.1, 2.1.4"),
        design_factors=factors,
        widening=Cited(
            "none",
            _c(
                IACS,
                "M68.4",
                False,
                "no margin in crankdyn's M68 reading",
                "crankdyn's reading (the range where τ > τ_C, no added margin)",
            ),
        ),
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
