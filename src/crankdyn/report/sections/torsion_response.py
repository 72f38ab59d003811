"""Report section: forced torsional response, critical speeds and the rule check."""

from __future__ import annotations

import math

import numpy as np

from crankdyn.constants import RPM
from crankdyn.display import number, quantity
from crankdyn.errors import InputError
from crankdyn.report.model import KeyFigure, Plot, Section, Table
from crankdyn.report.sections import NotApplicable


def build(ctx) -> Section:
    engine = ctx.engine
    model = engine.torsion
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
    orders = a.orders
    result = a.response()
    crit = a.campbell()

    torque = np.asarray(result.synthesized_shaft_torque)  # speed x shaft
    s_idx = result.shaft_index(a.most_loaded_shaft())
    v_idx = int(np.argmax(torque[:, s_idx]))
    shaft = " - ".join(result.shafts[s_idx])
    out_sum = np.asarray(result.shaft_torque)[:, -1]  # sum of order amplitudes, output-end shaft
    o_idx = int(np.argmax(out_sum))
    out_shaft = " - ".join(result.shafts[-1])
    first, last = result.masses[0], result.masses[-1]
    rel = a.relative_angle(first, last)
    r_idx = int(np.argmax(rel.synthesized))
    figures = [
        KeyFigure(
            "max_vibratory_shaft_torque_Nm",
            "Max vibratory shaft torque (synthesised)",
            float(torque[v_idx, s_idx]),
            f"{quantity(float(torque[v_idx, s_idx]), 'N·m')} in {shaft} at "
            f"{speeds[v_idx] * RPM:.0f} rpm",
        ),
        KeyFigure(
            "max_output_shaft_torque_order_sum_Nm",
            "Vibratory torque at the output end (sum of order amplitudes)",
            float(out_sum[o_idx]),
            f"{quantity(float(out_sum[o_idx]), 'N·m')} in {out_shaft} at "
            f"{speeds[o_idx] * RPM:.0f} rpm",
        ),
        KeyFigure(
            "max_relative_angle_rad",
            f"Max relative angle {first} - {last}",
            float(rel.synthesized[r_idx]),
            f"{number(math.degrees(rel.synthesized[r_idx]))}° at {speeds[r_idx] * RPM:.0f} rpm",
        ),
    ]
    majors = [c for c in crit.critical_speeds if c.major]
    figures.append(
        KeyFigure(
            "major_critical_speeds_in_range",
            "Major-order critical speeds in the range",
            len(majors),
            ", ".join(f"order {c.order:g} at {number(c.speed * RPM, 5)} rpm" for c in majors)
            or "none",
            status="warn" if majors else "pass",
            note="resonances of major orders inside the operating range",
        )
    )
    plots = [
        Plot(
            "torsion_response",
            f"Vibratory torque in {shaft}",
            result.plot(what="torque", item=result.shafts[s_idx]),
            "Per order and synthesised over all orders (sum of order amplitudes and half the "
            "time-domain peak-to-peak).",
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
    check = result.rule_check
    if check is not None:
        figures.append(
            KeyFigure(
                "rule_check_passed",
                f"Shaft stresses vs {check.rule}",
                bool(check.passed),
                "within the limits" if check.passed else "above the permissible stress",
                status="pass" if check.passed else "fail",
                note="; ".join(
                    f"barred {b.low * RPM:.0f}-{b.high * RPM:.0f} rpm" for b in check.barred_ranges
                )
                if check.barred_ranges
                else "",
            )
        )
        plots.append(
            Plot(
                "shaft_stress_limits",
                "Shaft stress against the rule limits",
                result.plot_stress_limits(),
                check.rule,
            )
        )
    rows = [
        [
            str(c.mode),
            f"{c.order:g}",
            number(c.speed * RPM, 5),
            number(c.frequency / (2 * math.pi), 5),
            "major" if c.major else "minor",
        ]
        for c in crit.critical_speeds
    ]
    return Section(
        key="torsion-response",
        title="Forced torsional vibration",
        intro=(
            f"Steady-state response from {speeds[0] * RPM:.0f} to {speeds[-1] * RPM:.0f} rpm, "
            f"orders {orders[0]:g} to {orders[-1]:g}, excitation: {result.excitation}. Damping "
            "as in the model (absolute, relative and loss factors)."
        ),
        figures=figures,
        plots=plots,
        tables=[
            Table(
                "critical_speeds",
                "Critical speeds in the range",
                header=[
                    "Mode",
                    "Order",
                    "Critical speed (rpm)",
                    "Natural frequency (Hz)",
                    "Order class",
                ],
                rows=rows,
                caption=f"Every mode × order crossing in the range: {len(rows)} critical "
                f"speed(s), {len(majors)} of major orders.",
            ),
            Table("torsion_response", "Response against speed", result=result, show=False),
        ],
        json={"critical_speeds": [c.to_dict() for c in crit.critical_speeds]},
    )
