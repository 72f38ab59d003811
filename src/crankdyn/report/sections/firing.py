"""Report section: crank arrangement and firing order, and the firing orders the crankshaft
allows, ranked (seed 000 section 2.3)."""

from __future__ import annotations

from crankdyn.report.model import Plot, Section
from crankdyn.report.sections import Context

SHOWN = 20
"""Firing orders listed in the page (the CSV holds all of them)."""


def build(ctx: Context) -> Section:
    """The firing section: the crank arrangement and firing order, and the firing orders the
    crankshaft allows, ranked (seed 000 section 2.3).

    Parameters
    ----------
    ctx : crankdyn.report.sections.Context
        The analysis session (SI units) and the optional inputs of the report.

    Returns
    -------
    crankdyn.report.model.Section
        The section: key figures, tables, plots and checks (numbers shown in the units their
        labels name).
    """
    engine = ctx.engine
    own = ctx.analysis.firing
    ranking = ctx.analysis.firing_orders()
    mode = engine.torsion  # the torsional criterion uses its first mode when there is one
    scheme = f", {own.v_scheme} scheme" if own.v_scheme else ""
    return Section.of(
        "firing",
        "Crank arrangement and firing order",
        [own, ranking],
        intro=(
            f"Firing order {own.order_text}{scheme}. {ranking.count} firing order(s) fit the "
            f"crankshaft ({ranking.even_count} evenly firing), ranked by the seed's criteria: "
            "even intervals, balance, adjacent cylinders firing in a row, main-bearing loading"
            + (
                ", torsional vector sums over the first mode of the [torsion] model"
                if mode is not None
                else ""
            )
            + " (seed 000 §2.3)."
        ),
        plots=[
            Plot(
                "firing",
                "Crank end view and firing diagram",
                own.plot(),
                "Throws seen from the free end at cylinder 1's firing TDC, with the cylinders "
                "on each; expansion strokes of every cylinder over the cycle.",
            )
        ],
        limits={"firing_orders": SHOWN},
        json={"firing_orders": ranking.ranked_list()},
    )
