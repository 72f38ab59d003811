"""Report section: the mass-elastic system of the engine's torsional model, as analysed: every
mass (inertia, absolute damping, the cylinders on it, its role and speed ratio), every shaft,
coupling, elastic gear mesh and element of a distributed shaft (stiffness, relative damping, loss
factor, diameters, length, shear modulus), the couplings' catalogue data, every gear mesh (ratio,
teeth, sense of rotation), damper and excitation source, so that a reader can check the model
the natural frequencies and the forced response were computed from (seed 003: the equivalent
system; a shaft line joined to the engine is part of it)."""

from __future__ import annotations

import numpy as np

from crankdyn.display import mass_elastic_tables, number, shaft_kind
from crankdyn.report.model import Plot, Section, Table
from crankdyn.report.sections import Context, NotApplicable


def build(ctx: Context) -> Section:
    """The torsional model section: the mass-elastic system as analysed (masses, shafts,
    couplings, gear meshes, elements of distributed shafts).

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
    from crankdyn.plots.schematic import plot_schematic

    ratios = np.asarray(model.speed_ratios, dtype=float)
    masses, shafts = model.masses, model.shafts
    geometry = [s.geometry for s in shafts]
    kinds = [shaft_kind(s) for s in shafts]
    tables = [
        Table(name, title, header=header, rows=rows, caption=caption)
        for name, title, header, rows, caption in mass_elastic_tables(model)
    ]
    total = float(np.sum(ratios**2 * np.array([m.inertia for m in masses])))
    return Section(
        key="torsion-model",
        title="Mass-elastic system",
        intro=(
            f"{model.name or 'Torsional model'}: the lumped model the torsional analyses use "
            f"(seed 003, the equivalent system): {len(masses)} masses, {len(shafts)} shaft(s), "
            f"{len(model.gears)} gear mesh(es), {len(model.dampers)} damper(s), "
            f"{len(model.sources)} excitation source(s) besides the cylinders; "
            f"{'chain' if model.is_chain else 'branched'}, "
            f"{'free' if model.is_free else 'grounded'}; total inertia "
            f"{number(total)} kg·m² (reflected to the reference speed)."
        ),
        tables=tables,
        plots=[
            Plot(
                "torsion-schematic",
                "Schematic of the mass-elastic system",
                plot_schematic(model),
                "Drawn from the model: block heights grow with log10 of the inertia.",
            )
        ],
        json={
            "torsion_model": {
                "name": model.name,
                "masses": [
                    {
                        "name": m.name,
                        "inertia_kg_m2": m.inertia,
                        "damping_Nms_per_rad": m.damping,
                        "cylinders": list(m.cylinders),
                        "role": m.role,
                        "speed_ratio": float(r),
                    }
                    for m, r in zip(masses, ratios, strict=True)
                ],
                "shafts": [
                    {
                        "between": list(s.between),
                        "stiffness_Nm_per_rad": s.stiffness,
                        "damping_Nms_per_rad": s.damping,
                        "loss_factor": s.loss_factor,
                        "outer_diameter_m": g.outer_diameter if g else None,
                        "inner_diameter_m": g.inner_diameter if g else None,
                        "length_m": g.length if g else None,
                        "shear_modulus_Pa": g.shear_modulus if g else None,
                        "kind": kind,
                        "coupling": None if s.coupling is None else s.coupling.designation,
                    }
                    for s, g, kind in zip(shafts, geometry, kinds, strict=True)
                ],
                "gears": [
                    {
                        "between": list(g.between),
                        "ratio": g.ratio,
                        "teeth": None if g.teeth is None else list(g.teeth),
                        "direction": g.direction,
                        "joint": g.joint,
                    }
                    for g in model.gears
                ],
                "sources": [
                    {"name": x.name, "masses": list(x.mass_names()), "excitation": x.describe()}
                    for x in model.sources
                ],
                "dampers": [
                    {
                        "name": x.name,
                        "at": x.at,
                        "inertia_kg_m2": x.inertia,
                        "stiffness_Nm_per_rad": x.stiffness,
                        "damping_Nms_per_rad": x.damping,
                        "loss_factor": x.loss_factor,
                    }
                    for x in model.dampers
                ],
            }
        },
    )
