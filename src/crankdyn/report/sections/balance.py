"""Report section: free forces and moments, counterweights, overturning moment (seed 000 §2.2)."""

from __future__ import annotations

from crankdyn.constants import RPM
from crankdyn.report.model import Plot, Section
from crankdyn.report.sections import Context, NotApplicable


def build(ctx: Context) -> Section:
    """The balance section: free forces and moments order by order, counterweights and the
    overturning moment (the key figures and the table of
    :class:`crankdyn.engine.balance.BalanceResult`; seed 000 section 2.2).

    Parameters
    ----------
    ctx : crankdyn.report.sections.Context
        The analysis session (SI units) and the optional inputs of the report.

    Returns
    -------
    crankdyn.report.model.Section
        The section: the result's key figures, its table and its plot.

    Raises
    ------
    NotApplicable
        The engine file has no ``[masses]``.
    """
    if ctx.engine.masses is None:
        raise NotApplicable("balance: the engine file has no [masses]")
    b = ctx.analysis.balance()
    return Section.of(
        "balance",
        "Balance",
        [b],
        intro=(
            f"Free forces and moments of the mass forces at {b.speed * RPM:.0f} rpm, by order "
            f"(largest magnitude over a revolution; moments about the middle of the engine); "
            f"counterweights c = {b.counterweight_ratio:g}, b = {b.reciprocating_balance_ratio:g} "
            "(seed 000 §2.2)."
        ),
        plots=[
            Plot(
                "balance",
                "Free forces and moments by order",
                b.plot(),
                "Path of the free-force vector (seen from the free end) and of the free-moment "
                "vector over one revolution, order by order; the arrow marks theta = 0.",
            )
        ],
        json={"balance": b.to_dict()},
    )
