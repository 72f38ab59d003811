"""The ``"lr"`` rule set: Lloyd's Register (docs/tvc.md, "Rule sets").

Read (imorules.com copies): Rules for Ships Pt 5 Ch 6 2.1.1-2.1.4 (carbon and carbon-manganese
steel 400-760 N/mm^2, alloy steel not above 800 N/mm^2; 500 N/mm^2 where stresses come close to
the transient limit; no higher permissible vibration stress from the formulae of Pt 5 Ch 8 2.5
for higher strengths, unless an alloy intermediate shaft is approved under Pt 5 Ch 6 5); Rules
for Naval Ships (January 2023) Vol 2 Pt 5 Ch 1 3.1.1-3.1.3 (symbols, C_d = 0.35 + 0.93 d^-0.2,
half-range amplitudes of the synthesis of all orders, nominal stress of the plain section) and
the first rows of its Table 1.3.1 (C_k). Not read: Rules for Ships Pt 5 Ch 8 2 (the tau_c and
tau_t formulas of 2.5, the barred-range margin, the tachometer, generating sets, crankshafts) and
the screwshaft limit of Pt 5 Ch 6 3.5.1; their values are crankdyn's M68 formulas and LR margin,
marked not verified.
"""

from __future__ import annotations

from dataclasses import replace

from crankdyn.torsion.rules import STRENGTH_CAPS
from crankdyn.tvc.limits import DESIGN_FACTORS
from crankdyn.tvc.rulesets.iacs import M68_AS, iacs_m68
from crankdyn.tvc.rulesets.model import Cited, RuleSet
from crankdyn.tvc.rulesets.model import clause_of as _c

__all__ = ["LR_CH8_NOT_READ", "LR_NAVAL", "LR_SHIPS", "lr"]

LR_SHIPS = (
    "LR Rules and Regulations for the Classification of Ships",
    "(imorules.com copies LRSHIP_PT5_CH6_2, LRSHIPS_PT5_CH6_6; edition not shown in the excerpts)",
)
"""LR's Rules for Ships and the copy read."""

LR_NAVAL = (
    "LR Rules and Regulations for the Classification of Naval Ships",
    "January 2023 (imorules.com, version 9.40)",
)
"""LR's Rules for Naval Ships and the copy read."""

LR_CH8_NOT_READ = "LR Pt 5 Ch 8 2 could not be read; crankdyn's M68 formula"
"""The note of the Pt 5 Ch 8 2.5 clauses."""


def lr() -> RuleSet:
    """The ``"lr"`` rule set (module docstring): M68 with LR's margin and caps.

    Returns
    -------
    RuleSet
    """
    base = iacs_m68()
    caps: dict[tuple[str, str], Cited[float]] = {}
    for (material, kind), value in STRENGTH_CAPS.items():
        if kind == "propeller":
            clause = _c(
                LR_SHIPS,
                "Pt 5 Ch 6 3.5.1",
                False,
                "the screwshaft limit (2.1.1 refers to 3.5.1) could not be read; M68's 600",
                "IACS UR M68 as crankdyn reads it (600)",
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
            else _c(
                LR_SHIPS,
                "Pt 5 Ch 8 2 (C_k table)",
                False,
                "row not read; M68's value",
                "KR 2025 Pt 5 Ch 4 Table 5.4.1",
            ),
        )
        for k, v in DESIGN_FACTORS.items()
    }
    ch8 = _c(LR_SHIPS, "Pt 5 Ch 8 2.5", False, LR_CH8_NOT_READ, M68_AS)
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
                "KR 2025 Pt 5 Ch 4 206.1(1)",
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
