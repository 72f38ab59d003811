"""Report section: cylinder pressure, indicated work and IMEP."""

from __future__ import annotations

from crankdyn.report.model import Plot, Section, Table
from crankdyn.report.sections import Context


def build(ctx: Context) -> Section:
    """The pressure section: the cylinder pressure over the cycle with its key figures
    (:class:`crankdyn.crank.indicated.PressureResult`).

    Parameters
    ----------
    ctx : crankdyn.report.sections.Context
        The analysis session (SI units) and the optional inputs of the report.

    Returns
    -------
    crankdyn.report.model.Section
        The section: the result's key figures, its plot and its data table.
    """
    r = ctx.analysis.pressure
    intro = (
        f"Cylinder pressure from {r.source}. Indicated work W_i = ∮ p dV with the exact volume "
        "change; IMEP = W_i / V_d."
    )
    if ctx.engine.pressure is None:
        intro += (
            " The engine file gives no pressure: this is the synthetic Wiebe model with its "
            "default parameters (crankdyn docs forces), a placeholder until a trace or model "
            "parameters are given."
        )
    return Section.of(
        "pressure",
        "Cylinder pressure",
        [r],
        intro=intro,
        plots=[Plot("pressure", "Cylinder pressure", r.plot(), "p-φ and p-V diagrams.")],
        tables=[Table("pressure", "Cylinder pressure over the cycle", result=r, show=False)],
        json={
            "pressure_summary": {k: v for k, v in r.to_dict().items() if not isinstance(v, list)}
        },
    )
