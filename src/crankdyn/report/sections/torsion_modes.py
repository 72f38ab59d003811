"""Report section: natural frequencies and mode shapes of the engine's torsional model."""

from __future__ import annotations

import numpy as np

from crankdyn.report.model import Check, Plot, Section, Table
from crankdyn.report.sections import Context, NotApplicable


def build(ctx: Context) -> Section:
    """The torsional modes section: natural frequencies and mode shapes of the engine's
    torsional model.

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
        The engine file has no ``[torsion]`` model.
    """
    model = ctx.engine.torsion
    if model is None:
        raise NotApplicable("the engine file has no [torsion] model")
    modes = ctx.analysis.modes
    hz = modes.frequencies_hz
    elastic = [i for i, m in enumerate(modes.mode) if m >= 1]
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
    return Section.of(
        "torsion-modes",
        "Torsional natural frequencies",
        [modes],
        intro=(
            f"{model.name or 'Torsional model'}: {model.mass_count} masses, "
            f"{'chain' if model.is_chain else 'branched'}, "
            f"{'free' if model.is_free else 'grounded'}; solved by the tridiagonal eigen solver "
            "and checked by Holzer's method and transfer matrices (seed 003). Elastic modes are "
            "numbered from 1" + (", the rigid-body mode is mode 0." if model.is_free else ".")
        ),
        plots=[
            Plot(
                "mode_shapes",
                "Mode shapes",
                modes.plot(modes=[int(modes.mode[i]) for i in elastic[:4]] or None),
                "Relative amplitudes of the first elastic modes, largest amplitude 1.",
            )
        ],
        tables=[
            Table("modal_data", "Modal data", result=modes, show=False),
        ],
        checks=checks,
        json={"torsion_modes": modes.to_dict()},
    )
