"""Report section: the mass-elastic system of the engine's torsional model, as analysed: every
mass (inertia, absolute damping, the cylinders on it, its speed ratio), every shaft or coupling
(stiffness, relative damping, loss factor, diameters, length, shear modulus), every gear mesh and
damper, so that a reader can check the model the natural frequencies and the forced response
were computed from (seed 003: the equivalent system)."""

from __future__ import annotations

import numpy as np

from crankdyn.format import column, number, unit_label
from crankdyn.report.model import Section, Table
from crankdyn.report.sections import NotApplicable


def _formatted(values, unit: str, digits: int = 5) -> tuple[str, list[str]]:
    """(display unit, cells) of a column of SI values (None for not given: '-')."""
    known = [v for v in values if v is not None]
    factor, shown, scale = column(known, unit)
    cells = ["-" if v is None else number(v / factor, digits, scale=scale) for v in values]
    return shown, cells


def _table(name: str, title: str, columns: list[tuple[str, str, list]], caption: str) -> Table:
    """A table from (label, SI unit, values) columns; text columns have unit None."""
    header, cells = [], []
    for label, unit, values in columns:
        if all(v is None for v in values):
            continue  # not given for any row (e.g. shaft diameters of given stiffnesses)
        if unit is None:
            header.append(label)
            cells.append([str(v) for v in values])
            continue
        shown, col = _formatted(values, unit)
        header.append(unit_label(label, shown))
        cells.append(col)
    rows = [list(r) for r in zip(*cells, strict=True)]
    return Table(name, title, header=header, rows=rows, caption=caption)


def build(ctx) -> Section:
    model = ctx.engine.torsion
    if model is None:
        raise NotApplicable("the engine file has no [torsion] model")
    ratios = np.asarray(model.speed_ratios, dtype=float)
    geared = bool(model.gears)
    masses = model.masses
    mass_columns = [
        ("No.", None, [str(i) for i in range(1, len(masses) + 1)]),
        ("Mass", None, [m.name for m in masses]),
        ("Moment of inertia J", "kg·m²", [m.inertia for m in masses]),
        ("Absolute damping", "N·m·s/rad", [m.damping for m in masses]),
        ("Cylinders", None, [", ".join(str(c) for c in m.cylinders) or "-" for m in masses]),
    ]
    if geared:
        mass_columns.append(("Speed ratio to the reference", "", list(ratios)))
        reflected = ratios**2 * np.array([m.inertia for m in masses])
        mass_columns.append(("Inertia reflected to the reference", "kg·m²", list(reflected)))
    shafts = model.shafts
    geometry = [s.geometry for s in shafts]
    shaft_columns = [
        ("No.", None, [str(i) for i in range(1, len(shafts) + 1)]),
        ("Between", None, [s.label for s in shafts]),
        ("Stiffness k", "N·m/rad", [s.stiffness for s in shafts]),
        ("Relative damping", "N·m·s/rad", [s.damping for s in shafts]),
        ("Loss factor η", "", [s.loss_factor for s in shafts]),
        ("Outer diameter", "m", [g.outer_diameter if g else None for g in geometry]),
        ("Bore", "m", [g.inner_diameter if g else None for g in geometry]),
        ("Length", "m", [g.length if g else None for g in geometry]),
        ("Shear modulus G", "Pa", [g.shear_modulus if g else None for g in geometry]),
    ]
    tables = [
        _table(
            "torsion_masses",
            "Masses",
            mass_columns,
            f"{len(masses)} masses, numbered from the free end.",
        ),
        _table(
            "torsion_shafts",
            "Shafts and couplings",
            shaft_columns,
            f"{len(shafts)} elastic connection(s)"
            + (
                "; '-': diameters, length or shear modulus not given (the stiffness was given "
                "directly)."
                if any(g is not None for g in geometry)
                else "; the stiffnesses were given directly (no shaft dimensions)."
            ),
        ),
    ]
    if geared:
        tables.append(
            _table(
                "torsion_gears",
                "Gear meshes",
                [
                    ("Between", None, [f"{g.between[0]} - {g.between[1]}" for g in model.gears]),
                    ("Speed ratio n_b / n_a", "", [g.ratio for g in model.gears]),
                ],
                "Rigid meshes: the masses beyond a gear are reflected to the reference speed "
                "with the square of the speed ratio.",
            )
        )
    if model.dampers:
        d = model.dampers
        tables.append(
            _table(
                "torsion_dampers",
                "Dampers",
                [
                    ("Damper", None, [x.name for x in d]),
                    ("On mass", None, [x.at for x in d]),
                    ("Ring inertia", "kg·m²", [x.inertia for x in d]),
                    ("Stiffness", "N·m/rad", [x.stiffness for x in d]),
                    ("Damping", "N·m·s/rad", [x.damping for x in d]),
                    ("Loss factor η", "", [x.loss_factor for x in d]),
                ],
                "Added by the forced response (not part of the natural frequencies above).",
            )
        )
    total = float(np.sum(ratios**2 * np.array([m.inertia for m in masses])))
    return Section(
        key="torsion-model",
        title="Mass-elastic system",
        intro=(
            f"{model.name or 'Torsional model'}: the lumped model the torsional analyses use "
            f"(seed 003, the equivalent system): {len(masses)} masses, {len(shafts)} shaft(s), "
            f"{len(model.gears)} gear mesh(es), {len(model.dampers)} damper(s); "
            f"{'chain' if model.is_chain else 'branched'}, "
            f"{'free' if model.is_free else 'grounded'}; total inertia "
            f"{number(total, 4)} kg·m² (reflected to the reference speed)."
        ),
        tables=tables,
        json={
            "torsion_model": {
                "name": model.name,
                "masses": [
                    {
                        "name": m.name,
                        "inertia_kg_m2": m.inertia,
                        "damping_Nms_per_rad": m.damping,
                        "cylinders": list(m.cylinders),
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
                    }
                    for s, g in zip(shafts, geometry, strict=True)
                ],
                "gears": [{"between": list(g.between), "ratio": g.ratio} for g in model.gears],
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
