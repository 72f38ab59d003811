"""The ``"kr"`` rule set: Korean Register, Rules for Classification of Steel Ships 2025 (RA-05-E),
Pt 5 Ch 4 "Torsional vibration of shaftings", read whole (101-206) from a markdown transcription
in a public repository (docs/tvc.md, "Rule sets").

The M68 formulas with T_s capped at 600 N/mm^2 for carbon steel forgings (every shaft kind), 800
for low alloy intermediate and thrust shafts, 600 for propeller and stern tube shafts
(202.1(1)); the C_K table (Table 5.4.1); tau_2 = 1.7 tau_1 / sqrt(C_k) below 0.8 (202.1(2));
crankshafts of main engines (201); generating sets (203); the material factor f_m (201.4,
203.3); no major critical in 0.8-1.1 (propulsion) or 0.9-1.1 (generators) (204); the least
barred range 16 N_c/(18 - lambda) to (18 - lambda) N_c/16, both full and zero pitch of a
controllable-pitch propeller, misfire ranges allowing safe navigation (206.1); a measured range
"having regard to the tachometer accuracy" (206.3, no value); calculations to 120 % of the rated
speed (102.1(2)).
"""

from __future__ import annotations

from crankdyn.tvc.limits import DESIGN_FACTORS
from crankdyn.tvc.rulesets.model import Cited, CrankshaftRule, GensetRule, RuleSet
from crankdyn.tvc.rulesets.model import clause_of as _c

__all__ = ["KR", "kr"]

KR = (
    "KR Rules for Classification of Steel Ships",
    "2025 (RA-05-E)",
)
"""The rule text and its edition."""


def kr() -> RuleSet:
    """The ``"kr"`` rule set: KR 2025 Pt 5 Ch 4 (module docstring), read whole.

    Returns
    -------
    RuleSet
    """
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
