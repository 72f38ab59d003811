"""Report section: engine torque, journal torques, mean torque and power, with the cross-check
mean torque x cycle = Z x indicated work."""

from __future__ import annotations

from crankdyn.report.model import Check, Plot, Section, Table
from crankdyn.report.sections import Context, NotApplicable


def build(ctx: Context) -> Section:
    """The torque section: engine and journal torques, mean torque and power, with the cross-
    check mean torque x cycle angle = cylinders x indicated work.

    Parameters
    ----------
    ctx : crankdyn.report.sections.Context
        The analysis session (SI units) and the optional inputs of the report.

    Returns
    -------
    crankdyn.report.model.Section
        The section: key figures, tables, plots and checks (numbers shown in the units their
        labels name).

    Raises
    ------
    NotApplicable
        The engine file has no ``[masses]``.
    """
    engine = ctx.engine
    if engine.masses is None:
        raise NotApplicable("torque: the engine file has no [masses]")
    t = ctx.analysis.torque
    work = ctx.analysis.pressure.indicated_work
    expected = engine.cylinders.count * work / engine.cycle_angle
    error = abs(t.mean_torque - expected) / abs(expected) if expected else 0.0
    return Section.of(
        "torque",
        "Torque",
        [t],
        intro=(
            f"Cylinder torques combined by throw angles and firing order "
            f"({'-'.join(str(c) for c in engine.cylinders.firing_order)}); main-journal torques "
            "accumulated from the free end (seed 000 §2.2-2.3)."
        ),
        plots=[
            Plot(
                "torque",
                "Engine torque",
                t.plot(),
                "Cylinder torques, total torque with its gas and inertia parts, and the "
                "main-journal torques.",
            )
        ],
        tables=[Table("torque", "Torques over the cycle", result=t, show=False)],
        checks=[
            Check(
                "mean torque × cycle angle vs cylinders × indicated work",
                f"{error * 100:.2g} %",
                error < 1e-4,
            ),
        ],
        json={"torque_summary": {k: v for k, v in t.to_dict().items() if not isinstance(v, list)}},
    )
