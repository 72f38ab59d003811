"""Report section: cylinder pressure (trace or synthetic model), indicated work and IMEP."""

from __future__ import annotations

import math

from crankdyn.report.model import KeyFigure, Plot, Section, Table


def build(ctx) -> Section:
    r = ctx.analysis.pressure
    synthetic = ctx.engine.pressure is None
    figures = [
        KeyFigure(
            "peak_pressure_Pa",
            "Peak cylinder pressure",
            r.peak_pressure,
            f"{r.peak_pressure / 1e6:.4g} MPa at {math.degrees(r.peak_angle):.1f}° after TDC",
        ),
        KeyFigure("imep_Pa", "IMEP", r.imep, f"{r.imep / 1e6:.4g} MPa"),
        KeyFigure(
            "indicated_work_J",
            "Indicated work per cylinder and cycle",
            r.indicated_work,
            f"{r.indicated_work:.5g} J",
        ),
    ]
    intro = (
        f"Cylinder pressure from {r.source}. Indicated work W_i = ∮ p dV with the exact volume "
        "change; IMEP = W_i / V_d."
    )
    if synthetic:
        intro += (
            " The engine file gives no pressure: this is the synthetic Wiebe model with its "
            "default parameters (docs/forces.md), a placeholder until a trace or model "
            "parameters are given."
        )
    return Section(
        key="pressure",
        title="Cylinder pressure",
        intro=intro,
        figures=figures,
        plots=[Plot("pressure", "Cylinder pressure", r.plot(), "p-φ and p-V diagrams.")],
        tables=[Table("pressure", "Cylinder pressure over the cycle", result=r, show=False)],
        json={
            "pressure_summary": {k: v for k, v in r.to_dict().items() if not isinstance(v, list)}
        },
    )
