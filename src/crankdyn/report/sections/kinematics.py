"""Report section: piston and rod kinematics (seed 000 §1, seed 002)."""

from __future__ import annotations

from crankdyn.constants import RPM
from crankdyn.report.model import Plot, Section, Table
from crankdyn.report.sections import Context


def build(ctx: Context) -> Section:
    """The kinematics section: the exact piston and rod motion at the operating speed and its
    summary (:class:`crankdyn.crank.kinematics.KinematicsSummary`'s key figures).

    Parameters
    ----------
    ctx : crankdyn.report.sections.Context
        The analysis session (SI units) and the optional inputs of the report.

    Returns
    -------
    crankdyn.report.model.Section
        The section: the result's key figures, its plot and its data table.
    """
    kin = ctx.analysis.kinematics()
    return Section.of(
        "kinematics",
        "Slider-crank kinematics",
        [kin],
        intro=f"Exact piston and rod motion at {ctx.speed * RPM:.0f} rpm (seed 000 §1, seed 002).",
        plots=[
            Plot(
                "kinematics",
                "Piston and rod motion",
                kin.plot(),
                "Displacement, velocity and acceleration of the piston; angle, angular "
                "velocity and angular acceleration of the rod; extrema marked.",
            )
        ],
        tables=[
            Table("kinematics", "Kinematics over one revolution (1° steps)", result=kin, show=False)
        ],
        json={"kinematics_summary": kin.extrema.to_dict()},
    )
