"""Torsional model files (TOML), the engine file's [torsion] section and the built-in models.

See docs/torsion-file.md. A model file holds ``name`` and the arrays of tables ``[[mass]]``,
``[[shaft]]`` and ``[[gear]]``; an engine file's ``[torsion]`` section holds the same, and may add
``[torsion.throws]`` to generate the crank throws from the engine (the equivalent system,
:mod:`crankdyn.torsion.equivalent`).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from crankdyn.errors import did_you_mean
from crankdyn.io.schema import Table
from crankdyn.torsion.equivalent import (
    CrankThrowGeometry,
    ThrowSpec,
    equivalent_system,
    throw_name,
)
from crankdyn.torsion.model import GROUND, Gear, Mass, Shaft, ShaftGeometry, TorsionModel

if TYPE_CHECKING:  # pragma: no cover
    from crankdyn.crank.geometry import CrankGeometry
    from crankdyn.crank.masses import Masses
    from crankdyn.engine.model import Cylinders

__all__ = [
    "parse_torsion_model",
    "parse_torsion_section",
]

_CARTER_KEYS = (
    "journal_diameter",
    "journal_length",
    "pin_diameter",
    "pin_length",
    "web_thickness",
    "web_width",
    "shear_modulus",
)


# ---- parsing ------------------------------------------------------------------------------------
def parse_torsion_model(
    data: dict,
    *,
    file: str | None = None,
    base_dir: Path | None = None,
    default_name: str = "torsional model",
) -> TorsionModel:
    """A TorsionModel from a parsed model file (a dict as from tomllib); ``name`` defaults to
    ``default_name``."""
    root = Table(data, file=file, base_dir=base_dir)
    model = _read(root, default_name=default_name, engine=None)
    root.finish()
    return model


def parse_torsion_section(
    t: Table,
    *,
    engine_name: str,
    geometry: CrankGeometry,
    cylinders: Cylinders,
    masses: Masses | None,
) -> TorsionModel:
    """The engine file's [torsion] section (explicit masses, and/or [torsion.throws])."""
    model = _read(t, default_name=engine_name, engine=(geometry, cylinders, masses))
    t.finish()
    return model


def _read(t: Table, *, default_name: str, engine) -> TorsionModel:
    name = t.string("name", default_name)
    mass_tables = t.tables("mass")
    masses = [_mass(mt) for mt in mass_tables]
    throws_table = t.table("throws")
    if throws_table is not None and engine is None:
        raise t.error(
            "throws",
            "crank throws are generated from an engine: put this model in an engine file's "
            "[torsion] section",
        )
    if not masses and throws_table is None:
        raise t.error(None, "missing [[mass]] entries (the model's masses)")
    throw_names: list[str] = []
    spec = None
    if throws_table is not None:
        geometry, cylinders, engine_masses = engine
        if engine_masses is None:
            raise throws_table.error(
                None, "the crank throws need the engine's [masses] (reciprocating and rotating)"
            )
        spec = _throws(throws_table)
        throw_names = [throw_name(i) for i in range(1, cylinders.throw_count + 1)]

    # names: unique, and known to the shafts and gears
    seen: dict[str, Table] = {}
    for mt, m in zip(mass_tables, masses, strict=True):
        if m.name in seen or m.name in throw_names:
            what = "a generated crank throw" if m.name in throw_names else "another mass"
            raise mt.error("name", f"{what} has this name already", m.name)
        seen[m.name] = mt
    known = [*seen, *throw_names]
    if engine is not None:
        _check_cylinders(mass_tables, masses, engine[1], bool(throw_names))

    shafts = []
    for st in t.tables("shaft"):
        shaft = _shaft(st)
        _check_ends(st, shaft.between, known)
        shafts.append(shaft)
    gears = []
    for gt in t.tables("gear"):
        gear = _gear(gt)
        _check_ends(gt, gear.between, known)
        gears.append(gear)

    with t.context():
        if spec is not None:
            geometry, cylinders, engine_masses = engine
            model = equivalent_system(
                geometry,
                cylinders,
                engine_masses,
                spec,
                other_masses=tuple(masses),
                shafts=tuple(shafts),
                gears=tuple(gears),
                name=name,
                source=t.file,
            )
        else:
            model = TorsionModel(
                masses=tuple(masses),
                shafts=tuple(shafts),
                gears=tuple(gears),
                name=name,
                source=t.file,
            )
    # forced-response data (docs/torsion-file.md): excitation, dampers, rules, operating range
    from crankdyn.io.torsion_response_file import read_response_sections

    return read_response_sections(t, model, engine)


def _check_ends(t: Table, ends: tuple[str, str], known: list[str]) -> None:
    for end in ends:
        if end != GROUND and end not in known:
            raise t.error("between", f'no mass named "{end}"{did_you_mean(end, known)}', list(ends))


def _check_cylinders(tables, masses, cylinders: Cylinders, generated: bool) -> None:
    """Cylinders on the masses must exist, and cylinders sharing a throw share a mass."""
    owner: dict[int, int] = {}
    for i, (mt, m) in enumerate(zip(tables, masses, strict=True)):
        for c in m.cylinders:
            if generated:
                raise mt.error(
                    "cylinders",
                    "the generated crank throws carry the cylinders already",
                    list(m.cylinders),
                )
            if c > cylinders.count:
                raise mt.error(
                    "cylinders",
                    f"the engine has {cylinders.count} cylinders (1..{cylinders.count})",
                    list(m.cylinders),
                )
            owner[c] = i
    for c, i in owner.items():
        partners = [
            d + 1
            for d in range(cylinders.count)
            if cylinders.throws[d] == cylinders.throws[c - 1] and d + 1 != c
        ]
        for p in partners:
            if owner.get(p, i) != i:
                raise tables[i].error(
                    "cylinders",
                    f"cylinders {c} and {p} share crank throw {cylinders.throws[c - 1]}, so "
                    "they belong on the same mass",
                    list(masses[i].cylinders),
                )


def _mass(t: Table) -> Mass:
    name = t.string("name")
    inertia = t.quantity("inertia", "inertia", check="positive")
    damping = t.quantity("damping", "torsional_damping", 0.0, check="nonnegative")
    cylinders = t.integer_list("cylinders", ())
    with t.context():
        mass = Mass(name=name, inertia=inertia, damping=damping, cylinders=cylinders)
    t.finish()
    return mass


def _shaft(t: Table) -> Shaft:
    between = t.string_list("between", length=2)
    stiffness = t.quantity("stiffness", "torsional_stiffness", None, check="positive")
    length = t.quantity("length", "length", None, check="positive")
    outer = t.quantity("outer_diameter", "length", None, check="positive")
    inner = t.quantity("inner_diameter", "length", None, check="nonnegative")
    shear = t.quantity("shear_modulus", "pressure", None, check="positive")
    damping = t.quantity("damping", "torsional_damping", 0.0, check="nonnegative")
    loss = t.number("loss_factor", 0.0, check="nonnegative")
    if stiffness is not None:
        for key, value in (("length", length), ("shear_modulus", shear)):
            if value is not None:
                raise t.error(
                    key,
                    "give the stiffness or the shaft's length and shear modulus, not both",
                    t.data[key],
                )
    else:
        for key, value in (("length", length), ("outer_diameter", outer), ("shear_modulus", shear)):
            if value is None:
                raise t.error(
                    key,
                    "missing; give the stiffness, or the length, outer_diameter (and "
                    "inner_diameter) and shear_modulus",
                )
    if inner is not None and outer is None:
        raise t.error("outer_diameter", "missing; a bore needs the outer diameter")
    with t.context():
        geometry = ShaftGeometry(outer, inner or 0.0, length, shear) if outer is not None else None
        shaft = Shaft(
            between=between,
            stiffness=stiffness,
            damping=damping,
            loss_factor=loss,
            geometry=geometry,
        )
    t.finish()
    return shaft


def _gear(t: Table) -> Gear:
    between = t.string_list("between", length=2)
    ratio = t.number("ratio")
    with t.context():
        gear = Gear(between=between, ratio=ratio)
    t.finish()
    return gear


def _throws(t: Table) -> ThrowSpec:
    inertia = t.quantity("inertia", "inertia", check="nonnegative")
    stiffness = t.quantity("stiffness", "torsional_stiffness", None, check="positive")
    given = [k for k in (*_CARTER_KEYS, "journal_bore", "pin_bore") if t.has(k)]
    geometry = None
    if stiffness is not None and given:
        raise t.error(
            given[0],
            "give the crank span's stiffness or its dimensions (Carter's formula), not both",
            t.data[given[0]],
        )
    if stiffness is None:
        missing = [k for k in _CARTER_KEYS if k not in given]
        if missing:
            raise t.error(
                missing[0] if given else "stiffness",
                "missing; give the crank span's stiffness, or "
                + ", ".join(_CARTER_KEYS)
                + " (Carter's formula)",
            )
        values = {
            k: t.quantity(k, "pressure" if k == "shear_modulus" else "length", check="positive")
            for k in _CARTER_KEYS
        }
        values["journal_bore"] = t.quantity("journal_bore", "length", 0.0, check="nonnegative")
        values["pin_bore"] = t.quantity("pin_bore", "length", 0.0, check="nonnegative")
        with t.context():
            geometry = CrankThrowGeometry(**values)
    damping = t.quantity("damping", "torsional_damping", 0.0, check="nonnegative")
    shaft_damping = t.quantity("shaft_damping", "torsional_damping", 0.0, check="nonnegative")
    loss = t.number("loss_factor", 0.0, check="nonnegative")
    with t.context():
        spec = ThrowSpec(
            crank_inertia=inertia,
            stiffness=stiffness,
            geometry=geometry,
            damping=damping,
            shaft_damping=shaft_damping,
            loss_factor=loss,
        )
    t.finish()
    return spec
