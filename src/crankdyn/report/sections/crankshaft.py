"""Report section: the crankshaft's fatigue strength by IACS UR M53, rendered from the session's
result (:meth:`crankdyn.session.Analysis.crankshaft`)."""

from __future__ import annotations

from crankdyn.errors import InputError
from crankdyn.report.model import Section, Table
from crankdyn.report.sections import Context, NotApplicable, NotRequested


def build(ctx: Context) -> Section:
    """The crankshaft section: Q of every fillet and oil bore of every throw with the nominal
    stresses, factors and clauses, and the verdicts (the same rows the TVC shows).

    Parameters
    ----------
    ctx : crankdyn.report.sections.Context
        The analysis session (SI units) and the optional inputs of the report.

    Returns
    -------
    crankdyn.report.model.Section
        The section: the result's key figures, tables and verdicts, and its data tables.

    Raises
    ------
    NotRequested
        The engine file has no ``[crankshaft]`` section.
    NotApplicable
        The check cannot be made (no masses, no bearing span...), with why.
    """
    if ctx.engine.crankshaft is None:
        raise NotRequested("the engine file has no [crankshaft] section")
    try:
        result = ctx.analysis.crankshaft()
    except InputError as exc:
        raise NotApplicable(f"no crankshaft check: {exc}") from None
    return Section.of(
        "crankshaft",
        "Crankshaft fatigue strength (IACS UR M53)",
        [result],
        intro=(
            "The acceptability factor Q = σ_DW / σ_V of the crankpin fillet, the journal fillet "
            "and the oil bore outlet of every throw against the rule's 1.15 (IACS UR M53, read "
            "in KR Rules 2025 Pt 5 Annex 5-3): the throws' bending from the gas and inertia "
            "forces at the maximum continuous rating by the statically determinate method, "
            "their torsion from the forced torsional response over the speed range (the one "
            "the torsional vibration calculation judges), the rule's stress concentration "
            "factors and fatigue strength (crankdyn docs crankshaft)."
        ),
        tables=[
            Table.of(result.quantities_table()),
            Table("m53_cycle", "Web and oil bore loads over the cycle", result=result, show=False),
        ],
        json={"crankshaft": result.to_dict()},
        verdicts_name="crankshaft-verdicts",
    )
