"""Report section: speed fluctuation and flywheel (seed 000 §2.4)."""

from __future__ import annotations

from crankdyn.display import number
from crankdyn.report.model import Plot, Section, Table
from crankdyn.report.sections import Context, NotApplicable


def build(ctx: Context) -> Section:
    """The flywheel section: the speed fluctuation, the energy swing and the flywheel (the key
    figures of :class:`crankdyn.engine.flywheel.FlywheelResult`; seed 000 section 2.4).

    Parameters
    ----------
    ctx : crankdyn.report.sections.Context
        The analysis session (SI units) and the optional inputs of the report.

    Returns
    -------
    crankdyn.report.model.Section
        The section: the result's key figures, its plot and its data table.

    Raises
    ------
    NotApplicable
        The engine file has no ``[masses]``.
    """
    if ctx.engine.masses is None:
        raise NotApplicable("flywheel: the engine file has no [masses]")
    r = ctx.analysis.flywheel()
    default = ctx.analysis.flywheel_default_delta()
    target = (
        f"target δ = {number(r.target_delta)}" + (" (the default)" if default else "")
        if r.target_delta is not None
        else "the given flywheel"
    )
    return Section.of(
        "flywheel",
        "Speed fluctuation and flywheel",
        [r],
        intro=f"Rigid crankshaft, steady load torque equal to the mean torque; {target} "
        "(seed 000 §2.4).",
        plots=[
            Plot(
                "flywheel",
                "Energy swing and crank speed",
                r.plot(),
                "Engine torque and its mean, the excess work ∫(M − M_m)dθ whose swing ΔE sizes "
                "the flywheel, and the instantaneous crank speed with it.",
            )
        ],
        tables=[Table("flywheel", "Torque, excess work and speed", result=r, show=False)],
        json={"flywheel": {k: v for k, v in r.to_dict().items() if not isinstance(v, list)}},
    )
