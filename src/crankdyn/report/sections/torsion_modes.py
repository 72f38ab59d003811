"""Report section: natural frequencies and mode shapes of the engine's torsional model."""

from __future__ import annotations

import numpy as np

from crankdyn.display import number, quantity
from crankdyn.report.model import Check, KeyFigure, Plot, Section, Table
from crankdyn.report.sections import NotApplicable


def build(ctx) -> Section:
    model = ctx.engine.torsion
    if model is None:
        raise NotApplicable("the engine file has no [torsion] model")
    modes = ctx.analysis.modes
    hz = modes.frequencies_hz
    elastic = [i for i, f in enumerate(hz) if f > 0.0]
    figures = []
    for rank, i in enumerate(elastic[:2], start=1):
        figures.append(
            KeyFigure(
                f"natural_frequency_{rank}_hz",
                f"Natural frequency, elastic mode {rank}",
                float(hz[i]),
                f"{quantity(float(hz[i]), 'Hz')} ({number(hz[i] * 60)} cpm)",
            )
        )
    checks = []
    if model.is_chain:
        for solver, label in (("holzer", "Holzer"), ("transfer", "transfer-matrix")):
            other = ctx.analysis.modes_by(solver).frequencies_hz
            scale = np.maximum(np.abs(hz), 1e-300)
            worst = float(np.max(np.abs(other - hz)[hz > 0] / scale[hz > 0])) if elastic else 0.0
            checks.append(
                Check(
                    f"natural frequencies, eigen solver vs {label}",
                    f"largest relative difference {worst:.1e}",
                    worst < 1e-9,
                )
            )
    top = float(np.max(np.abs(hz), initial=0.0))
    rows = [
        [
            str(int(m)),
            number(f, 5, reference=top),
            number(f * 60.0, 5, reference=top * 60.0),
            str(int(n)),
            "; ".join(node.describe() for node in nodes) or "-",
        ]
        for m, f, n, nodes in zip(modes.mode, hz, modes.node_count, modes.nodes, strict=True)
    ]
    return Section(
        key="torsion-modes",
        title="Torsional natural frequencies",
        intro=(
            f"{model.name or 'Torsional model'}: {model.mass_count} masses, "
            f"{'chain' if model.is_chain else 'branched'}, "
            f"{'free' if model.is_free else 'grounded'}; solved by the tridiagonal eigen solver "
            "and checked by Holzer's method and transfer matrices (seed 003)."
        ),
        figures=figures,
        plots=[
            Plot(
                "mode_shapes",
                "Mode shapes",
                modes.plot(modes=[int(modes.mode[i]) for i in elastic[:4]] or None),
                "Relative amplitudes of the first elastic modes, largest amplitude 1.",
            )
        ],
        tables=[
            Table(
                "natural_frequencies",
                "Natural frequencies and nodes",
                header=[
                    "Mode",
                    "Natural frequency (Hz)",
                    "Natural frequency (cycles/min)",
                    "Nodes",
                    "Node positions",
                ],
                rows=rows,
            ),
            Table("modal_data", "Modal data", result=modes, show=False),
        ],
        checks=checks,
        json={"torsion_modes": modes.to_dict()},
    )
