"""Report section: crank-train forces of cylinder 1, crank-pin and main-bearing loads."""

from __future__ import annotations

from crankdyn.constants import RPM
from crankdyn.report.model import Plot, Section, Table
from crankdyn.report.sections import Context, NotApplicable


def build(ctx: Context) -> Section:
    """The forces section: the crank-train forces of cylinder 1, the crank-pin and main-bearing
    loads (the key figures of :class:`crankdyn.engine.forces.ForcesResult` and
    :class:`crankdyn.engine.bearings.BearingsResult`).

    Parameters
    ----------
    ctx : crankdyn.report.sections.Context
        The analysis session (SI units) and the optional inputs of the report.

    Returns
    -------
    crankdyn.report.model.Section
        The section: the results' key figures, plots and data tables.

    Raises
    ------
    NotApplicable
        The engine file has no ``[masses]``.
    """
    if ctx.engine.masses is None:
        raise NotApplicable("forces and bearing loads: the engine file has no [masses]")
    f = ctx.analysis.forces()
    b = ctx.analysis.bearings()
    return Section.of(
        "forces",
        "Forces and bearing loads",
        [f, b],
        intro=f"Forces of cylinder 1 at {ctx.speed * RPM:.0f} rpm (seed 000 §2.2). Main bearings "
        "carry half of each adjacent throw's load (simply supported throws).",
        plots=[
            Plot(
                "forces",
                "Cylinder 1 forces",
                f.plot(),
                "Gas and inertia forces, their orders, rod, side, tangential and radial forces, "
                "torque and crank-pin load against crank angle.",
            ),
            Plot(
                "bearing_polars",
                "Bearing load polar diagrams",
                b.plot(),
                "Crank-pin loads in the crank frame and main-bearing loads in the engine frame.",
            ),
        ],
        tables=[
            Table("forces", "Cylinder 1 forces over the cycle", result=f, show=False),
            Table("bearings", "Crank-pin and main-bearing loads", result=b, show=False),
        ],
        json={"masses": f.masses.to_dict()},
    )
