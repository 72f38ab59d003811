"""Report section: forced torsional response, critical speeds and the verdicts of the
installation's checks."""

from __future__ import annotations

from typing import Any, cast

import numpy as np

from crankdyn.constants import RPM
from crankdyn.errors import InputError
from crankdyn.report.model import Plot, Section, Table
from crankdyn.report.sections import Context, NotApplicable


def build(ctx: Context) -> Section:
    """The torsional response section: the forced response (its key figures and peaks), the
    relative angle between the line's ends, the critical speeds and the verdicts of the
    installation's checks (:meth:`crankdyn.session.Analysis.judged`: the TVC's own evaluation of
    normal firing), each rendered from its result's summary.

    Parameters
    ----------
    ctx : crankdyn.report.sections.Context
        The analysis session (SI units) and the optional inputs of the report.

    Returns
    -------
    crankdyn.report.model.Section
        The section: the results' key figures, tables and verdicts, and the plots.

    Raises
    ------
    NotApplicable
        The engine file has no ``[torsion]`` model (or nothing excites it).
    """
    model = ctx.engine.torsion
    if model is None:
        raise NotApplicable("the engine file has no [torsion] model")
    if not model.cylinder_dofs:
        raise NotApplicable("the [torsion] model has no mass carrying a cylinder")
    a = ctx.analysis
    try:
        speeds = a.speeds
    except InputError:
        raise NotApplicable(
            "no speed range for the forced response: give --speeds or "
            "[torsion.operating] speed_range"
        ) from None
    orders = a.orders  # the engine's orders and those of the model's sources (propellers...)
    result = a.response()
    crit = a.campbell()
    rel = a.relative_angle(response=result)
    judged = a.judged()
    shaft = result.most_loaded_shaft()
    first, last = rel.between
    plots = [
        Plot(
            "torsion_response",
            f"Vibratory torque in {shaft[0]} - {shaft[1]}",
            result.plot(what="torque", item=shaft),
            "Per order and synthesised over all orders (sum of order amplitudes and half the "
            "time-domain peak-to-peak); the most loaded shaft.",
        ),
        Plot(
            "relative_angle",
            f"Relative angle {first} - {last}",
            result.plot(what="relative", item=(first, last)),
            "The relative angle between the ends of the shaft line, per order and synthesised.",
        ),
        Plot(
            "campbell",
            "Campbell diagram",
            crit.plot(),
            "Natural frequencies against engine orders; crossings in the range are the critical "
            "speeds (major orders marked).",
        ),
    ]
    if judged is not None and any(c.m68 for c in judged.curves.values()):
        plots.append(
            Plot(
                "shaft_stress_limits",
                "Shaft stress against the rule limits",
                judged.plot_stress_limits(),
                "IACS UR M68: the synthesised stress against τ_C and τ_T, the barred ranges as "
                "found (hatched) and as declared (shaded).",
            )
        )
    on_grid = int(np.count_nonzero(cast(Any, result.on_grid)))
    added = 0 if result.added_speeds is None else len(result.added_speeds)
    return Section.of(
        "torsion-response",
        "Forced torsional vibration",
        [result, rel, crit, *([judged] if judged is not None else [])],
        intro=(
            f"Steady-state response from {speeds[0] * RPM:.0f} to {speeds[-1] * RPM:.0f} rpm, "
            f"orders {orders[0]:g} to {orders[-1]:g}, excitation: {result.excitation}. Damping "
            f"as in the model (absolute, relative and loss factors). {added} speeds were added "
            f"to the {on_grid}-speed grid (the critical speeds and refinement around every "
            "resonance) so that every peak is resolved to "
            f"{100.0 * (result.tolerance or 1e-3):g} %."
        ),
        plots=plots,
        tables=[Table("torsion_response", "Response against speed", result=result, show=False)],
        json={"critical_speeds": [c.to_dict() for c in crit.critical_speeds]},
    )
