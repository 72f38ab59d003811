"""Torsional model files (TOML), the engine file's [torsion] section and the built-in models.

See docs/torsion-file.md. A model file holds ``name`` and the arrays of tables ``[[mass]]``,
``[[shaft]]`` and ``[[gear]]``; an engine file's ``[torsion]`` section holds the same, and may add
``[torsion.throws]`` to generate the crank throws from the engine (the equivalent system,
:mod:`crankdyn.torsion.equivalent`).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from crankdyn.errors import InputError, did_you_mean
from crankdyn.io.examples import display_path
from crankdyn.io.files import load_toml
from crankdyn.io.plausibility import role_of, section_of
from crankdyn.io.project_file import with_project
from crankdyn.io.schema import MISSING, Table
from crankdyn.io.units import check_si_range
from crankdyn.torsion.coupling import Coupling
from crankdyn.torsion.elements import (
    GEAR_DIRECTIONS,
    GROUND,
    MASS_ROLES,
    SHAFT_ROLES,
    Gear,
    Mass,
    MassLimits,
    Shaft,
    ShaftGeometry,
)
from crankdyn.torsion.equivalent import (
    CrankThrowGeometry,
    ThrowParts,
    ThrowSpec,
    equivalent_system,
    throw_name,
)
from crankdyn.torsion.model import TorsionModel

if TYPE_CHECKING:  # pragma: no cover
    from crankdyn.crank.geometry import CrankGeometry
    from crankdyn.crank.masses import Masses
    from crankdyn.engine.model import Cylinders
    from crankdyn.io.torsion_response_file import EngineParts

__all__ = [
    "load_shaft_line",
    "parse_torsion_model",
    "parse_torsion_section",
    "read_torsion_model",
    "with_input_warnings",
]

THROW_MODELS = ("throw", "parts")
"""[torsion.throws] model: one mass per throw, or journals and webs as two inertias and a spring
(seed 003; :class:`crankdyn.torsion.equivalent.ThrowParts`)."""
_PART_KEYS = ("journal_inertia", "web_inertia", "journal_stiffness", "web_stiffness")
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
    data: dict[str, Any],
    *,
    file: str | None = None,
    base_dir: Path | None = None,
    default_name: str = "torsional model",
) -> TorsionModel:
    """A TorsionModel from a parsed model file (a dict as from tomllib); ``name`` defaults to
    ``default_name``. A model file that joins engine files to its masses (``[[engine]]``) is
    read by :func:`crankdyn.io.engine_file.parse_model_file`, which reads engine files.

    Format (docs/torsion-file.md, ``crankdyn docs torsion-file``): ``name``, ``[[mass]]``
    (inertias kg m^2, dampings N m s/rad, cylinders), ``[[shaft]]`` (stiffnesses N m/rad or
    length, diameters in m and shear modulus in Pa; dampings, loss factors, couplings),
    ``[[gear]]`` (speed ratios or tooth numbers), the forced-response tables
    (:func:`crankdyn.io.torsion_response_file.read_response_sections`) and ``input``.

    Parameters
    ----------
    data
        The parsed document.
    file
        The file's name for messages.
    base_dir
        The folder relative file names (traces, tables) are taken from.
    default_name
        The model's name when the document gives none.

    Returns
    -------
    TorsionModel
        The model, every quantity in SI.

    Raises
    ------
    InputError
        On a missing or unknown key or table, a value of the wrong unit, kind or sign, an
        unknown mass, an ``[[engine]]`` entry, or a model the TorsionModel refuses; naming the
        file, the key and the value.
    """
    root = Table(data, file=file, base_dir=base_dir)
    model = read_torsion_model(root, default_name=default_name)
    model = with_project(root, model) or model
    if root.has("engine"):
        raise root.error(
            "engine",
            "engines joined to a line are read with the model file "
            "(crankdyn.io.engine_file.parse_model_file)",
        )
    root.finish()
    return with_input_warnings(model, root)


def with_input_warnings(model: TorsionModel, t: Table) -> TorsionModel:
    """The model carrying the plausibility warnings of the file it was read from (those of
    table ``t`` and its sub-tables, with the files it names: :attr:`crankdyn.io.schema.Table.
    warnings`), as ``input_warnings``.

    Parameters
    ----------
    model
        The model read from the file.
    t
        The file's top-level table.

    Returns
    -------
    TorsionModel
        ``model`` with ``input_warnings``, or ``model`` itself when the file has none.
    """
    if not t.warnings:
        return model
    return dataclasses.replace(model, input_warnings=tuple(t.warnings))


def read_torsion_model(t: Table, *, default_name: str = "torsional model") -> TorsionModel:
    """The model of a model file's top-level table, its ``[[engine]]`` entries left for the
    caller (:func:`crankdyn.io.engine_file.join_engines`); the table is not finished.

    Parameters
    ----------
    t
        The model file's top-level table.
    default_name
        The model's name when the table gives none.

    Returns
    -------
    TorsionModel
        The model, every quantity in SI.

    Raises
    ------
    InputError
        As :func:`parse_torsion_model` (unknown keys are left to the caller's ``finish``).
    """
    return _read(t, default_name=default_name, engine=None)


def parse_torsion_section(
    t: Table,
    *,
    engine_name: str,
    geometry: CrankGeometry,
    cylinders: Cylinders,
    masses: Masses | None,
    beam_stiffness: Callable[[], float] | None = None,
) -> TorsionModel:
    """The engine file's [torsion] section (explicit masses, and/or [torsion.throws]).

    Parameters
    ----------
    t
        The ``[torsion]`` table.
    engine_name
        The engine's name, the model's default name.
    geometry
        The engine's crank geometry (lengths in m), for generated throws.
    cylinders
        The engine's cylinders (count, cycle, firing), for the excitation.
    masses
        The engine's reciprocating and rotating masses (kg), or None.
    beam_stiffness
        The crank span's torsional stiffness (N m/rad) from the beam model of the engine's
        ``[crankshaft]`` (:func:`crankdyn.crankshaft.beam_engine.beam_throw_stiffness`), for
        ``[torsion.throws] stiffness = "beam"``; None without a ``[crankshaft]``.

    Returns
    -------
    TorsionModel
        The engine's torsional model with its excitation, every quantity in SI.

    Raises
    ------
    InputError
        As :func:`parse_torsion_model`, and for cylinders that do not exist or share a throw
        but not a mass; naming the file, the key and the value.
    """
    model = _read(
        t, default_name=engine_name, engine=(geometry, cylinders, masses), beam=beam_stiffness
    )
    t.finish()
    return model


def _read(
    t: Table,
    *,
    default_name: str,
    engine: EngineParts | None,
    beam: Callable[[], float] | None = None,
) -> TorsionModel:
    name = t.string("name", default_name)
    mass_tables = t.tables("mass")
    masses = [_plain_mass(mt) or _mass(mt) for mt in mass_tables]
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
        assert engine is not None  # refused above without an engine (type checker)
        geometry, cylinders, engine_masses = engine
        if engine_masses is None:
            raise throws_table.error(
                None, "the crank throws need the engine's [masses] (reciprocating and rotating)"
            )
        spec = _throws(throws_table, beam)
        throw_names = [throw_name(i) for i in range(1, cylinders.throw_count + 1)]

    # names: unique, and known to the shafts and gears
    seen: dict[str, Table] = {}
    for mt, m in zip(mass_tables, masses, strict=True):
        if m.name in seen or m.name in throw_names:
            what = "a generated crank throw" if m.name in throw_names else "another mass"
            raise mt.error("name", f"{what} has this name already", m.name)
        seen[m.name] = mt
    known = [*seen, *throw_names]
    names = frozenset(known)
    if engine is not None:
        _check_cylinders(mass_tables, masses, engine[1], bool(throw_names))
    else:
        _check_firing_count(t, mass_tables, masses)

    shafts = []
    for st in t.tables("shaft"):
        shaft = _plain_shaft(st) or _shaft(st)
        _check_ends(st, shaft.between, known, names)
        shafts.append(shaft)
    gears = []
    for gt in t.tables("gear"):
        gear = _gear(gt)
        _check_ends(gt, gear.between, known, names)
        gears.append(gear)

    with t.context():
        if spec is not None:
            # spec comes from [torsion.throws], read only with the engine's masses (above)
            assert engine is not None  # type checker
            geometry, cylinders, engine_masses = engine
            assert engine_masses is not None  # type checker
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

    model = read_response_sections(t, model, engine)
    # drivelines: shaft lines joined to an engine, engines joined to a line
    if engine is not None:
        return _tvc_events(t, _join_lines(t, model))
    if t.has("input"):
        line_input = t.string("input")
        if line_input not in model.mass_names:
            raise t.error(
                "input", f'no mass named "{line_input}"{did_you_mean(line_input, model.mass_names)}'
            )
    return _tvc_events(t, model)


def _tvc_events(t: Table, model: TorsionModel) -> TorsionModel:
    """The model with the ``[[tvc.event]]`` events of its ``[tvc]``, read with the whole model
    (:func:`crankdyn.io.tvc_file.read_tvc_events`)."""
    tt = t.table("tvc")
    if tt is None or "event" not in tt.data or model.tvc is None:
        return model
    from crankdyn.io.tvc_file import read_tvc_events

    events = read_tvc_events(tt, model)
    return dataclasses.replace(model, tvc=dataclasses.replace(model.tvc, events=events))


# ---- drivelines ---------------------------------------------------------------------------------
def load_shaft_line(path: Path, display: str) -> tuple[TorsionModel, str]:
    """A shaft-line model file and the mass an engine joins (its ``input``, default its first
    mass).

    Parameters
    ----------
    path
        The shaft-line model file.
    display
        How to name the file in messages.

    Returns
    -------
    tuple of (TorsionModel, str)
        The line's model (SI) and the name of its input mass.

    Raises
    ------
    InputError
        For an engine file given as a line, a line with ``[[engine]]`` entries, or any error
        of :func:`parse_torsion_model`; naming the file, the key and the value.
    """
    data = load_toml(path, what="shaft-line file")
    if "geometry" in data:
        raise InputError(
            "this is an engine file; a shaft line is a model file of masses and shafts",
            file=display,
        )
    if "engine" in data:
        raise InputError(
            "a shaft line joined to an engine cannot include engines itself ([[engine]])",
            file=display,
            key="engine",
        )
    model = parse_torsion_model(data, file=display, base_dir=path.parent, default_name=path.stem)
    line_input = data.get("input", model.masses[0].name)
    return model, line_input


def _inline_shaft_line(t: Table) -> tuple[TorsionModel, str]:
    """A shaft line written in the engine file itself, ``[torsion.shaft_line]`` (the content of
    a shaft-line file as a table; what the design search edits): its model and input mass."""
    for key, why in (
        ("geometry", "an engine's [geometry] has no place in a shaft line"),
        ("engine", "a shaft line joined to an engine cannot include engines itself ([[engine]])"),
    ):
        if t.has(key):
            raise t.error(key, why)
    line = read_torsion_model(t, default_name="shaft line")
    line_input = t.string("input", line.masses[0].name)
    t.finish()
    return with_input_warnings(line, t), line_input


def _join_lines(t: Table, model: TorsionModel) -> TorsionModel:
    """``shaft_line`` (with ``connect_at``) and ``[[torsion.line]]`` of an engine's [torsion]."""
    from crankdyn.torsion.driveline import join, rename

    entries: list[tuple[Table, str, str, str | None]] = []
    if t.has("shaft_line"):
        entries.append((t, "shaft_line", "connect_at", None))
    elif t.has("connect_at"):
        raise t.error("connect_at", "applies with shaft_line", t.data["connect_at"])
    for lt in t.tables("line"):
        entries.append((lt, "file", "at", "prefix"))
    if not entries:
        return model
    base_name = model.name
    for table, file_key, at_key, prefix_key in entries:
        inline = file_key == "shaft_line" and isinstance(table.data.get(file_key), dict)
        if not inline:
            path = table.path(file_key)
            if not path.is_file():
                raise table.error(
                    file_key, f"no such shaft-line file (looked for {path})", table.data[file_key]
                )
        at = table.string(at_key, model.masses[-1].name if at_key == "connect_at" else MISSING)
        if at not in model.mass_names:
            raise table.error(
                at_key, f'no mass named "{at}"{did_you_mean(at, model.mass_names)}', at
            )
        prefix = table.string(prefix_key, "") if prefix_key else ""
        if prefix_key:
            table.finish()
        if inline:
            line, line_input = _inline_shaft_line(table.table(file_key, required=True))
        else:
            line, line_input = load_shaft_line(path, display_path(path))
        t.warnings.extend(w for w in line.input_warnings if w not in t.warnings)
        with table.context():
            line = rename(line, prefix)
            model = join(model, line, at, f"{prefix}{line_input}", name=base_name)
    return model


def _check_ends(
    t: Table, ends: tuple[str, str], known: list[str], names: set[str] | frozenset[str]
) -> None:
    """Both ends of a shaft or gear are masses (``names``, a set: a look-up per end, so that a
    model file is read in time linear in its size) or ground; ``known`` in order, for the
    did-you-mean."""
    for end in ends:
        if end != GROUND and end not in names:
            raise t.error("between", f'no mass named "{end}"{did_you_mean(end, known)}', list(ends))


def _check_cylinders(
    tables: Sequence[Table], masses: Sequence[Mass], cylinders: Cylinders, generated: bool
) -> None:
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


def _check_firing_count(t: Table, tables: Sequence[Table], masses: Sequence[Mass]) -> None:
    """A model without an engine: a cylinder on a mass beyond those its ``[excitation]``
    firing order (or firing angles) names is refused at the mass (the firing order would
    otherwise be blamed for the mass's number)."""
    excitation = t.data.get("excitation")
    if not isinstance(excitation, dict):
        return
    for key in ("firing_order", "firing_angles"):
        given = excitation.get(key)
        if isinstance(given, list) and given:
            break
    else:
        return
    count = len(given)
    for mt, m in zip(tables, masses, strict=True):
        if any(c > count for c in m.cylinders):
            raise mt.error(
                "cylinders",
                f"the [excitation] {key} names {count} cylinders (1..{count})",
                list(m.cylinders),
            )


# ---- the plain entries of a long model: read directly ---------------------------------------
# A long model (a subdivided shaft line, a detailed crank model) is thousands of entries like
# {name = "m12", inertia = 0.5} and {between = ["m12", "m13"], stiffness = 2.1e6}: numbers in
# SI. Such an entry is read directly, with the checks the Table reader makes (a plain number,
# finite, in the SI range, of the right sign, plausible for its role); any other entry, and any
# entry the checks or the element refuse, goes through the Table reader (_mass, _shaft), which
# reads it the same way, records its plausibility warnings or names the file, the entry and the
# key in its error.
_PLAIN_MASS_KEYS = frozenset({"name", "inertia", "damping"})
_PLAIN_SHAFT_KEYS = frozenset({"between", "stiffness", "damping", "loss_factor"})
_KINDS = {
    "inertia": "inertia",
    "stiffness": "torsional_stiffness",
    "damping": "torsional_damping",
    "loss_factor": "ratio",
}
"""The kind of each plain key, as the Table reader reads it (``loss_factor`` a plain number)."""


def _plain(t: Table, key: str, positive: bool) -> float | None:
    """The value of ``key`` in ``t`` as the Table reader takes a bare number
    (:meth:`Table.quantity` of an SI number, :meth:`Table.number`): not a bool, finite, 0 or
    in the SI range, > 0 when ``positive`` else >= 0, plausible for its role
    (:func:`crankdyn.io.plausibility.role_of`); 0.0 when absent (the readers' default); None
    otherwise (the Table reader then reads it, warns or refuses)."""
    if key not in t.data:
        return 0.0
    value = t.data[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return None
    number = float(value)
    if not math.isfinite(number) or not check_si_range(number):
        return None
    if not (number > 0.0 or (number == 0.0 and not positive)):
        return None
    role = role_of(_KINDS[key], key, section_of(t.name))
    return number if role is None or role.holds(number) else None


def _plain_mass(t: Table) -> Mass | None:
    """A ``[[mass]]`` entry of a name, a bare inertia and damping, read directly (above); None
    for any other, or one the checks or :class:`Mass` refuse."""
    if not _PLAIN_MASS_KEYS.issuperset(t.data) or "inertia" not in t.data:
        return None
    name = t.data.get("name")
    inertia = _plain(t, "inertia", True)
    damping = _plain(t, "damping", False)
    if not isinstance(name, str) or inertia is None or damping is None:
        return None
    try:
        return Mass(name=name, inertia=inertia, damping=damping)
    except InputError:
        return None


def _plain_shaft(t: Table) -> Shaft | None:
    """A ``[[shaft]]`` entry of two ends, a bare stiffness, damping and loss factor, read
    directly (above); None for any other, or one the checks or :class:`Shaft` refuse."""
    if not _PLAIN_SHAFT_KEYS.issuperset(t.data) or "stiffness" not in t.data:
        return None
    between = t.data.get("between")
    stiffness = _plain(t, "stiffness", True)
    damping = _plain(t, "damping", False)
    loss = _plain(t, "loss_factor", False)
    if (
        not isinstance(between, list)
        or len(between) != 2
        or not all(isinstance(end, str) for end in between)
        or stiffness is None
        or damping is None
        or loss is None
    ):
        return None
    try:
        return Shaft(between=tuple(between), stiffness=stiffness, damping=damping, loss_factor=loss)
    except InputError:
        return None


def _mass(t: Table) -> Mass:
    name = t.string("name")
    role = t.string("role", None, choices=MASS_ROLES)
    # a gear wheel may have no inertia of its own (merged into its rigid mesh)
    inertia = t.quantity(
        "inertia", "inertia", check="nonnegative" if role == "gear" else "positive"
    )
    damping = t.quantity("damping", "torsional_damping", 0.0, check="nonnegative")
    cylinders = t.integer_list("cylinders", ())
    limits = None
    lt = t.table("limits")
    if lt is not None:
        values = {
            "vibratory_torque": lt.quantity("vibratory_torque", "torque", None, check="positive"),
            "angular_acceleration": lt.quantity(
                "angular_acceleration", "angular_acceleration", None, check="positive"
            ),
            "amplitude": lt.quantity("amplitude", "angle", None, check="positive"),
        }
        source = lt.string("source", None)
        lt.finish()
        if all(v is None for v in values.values()):
            raise lt.error(
                None, "give at least one of vibratory_torque, angular_acceleration, amplitude"
            )
        with lt.context():
            limits = MassLimits(**values, source=source)
    with t.context():
        mass = Mass(
            name=name,
            inertia=inertia,
            damping=damping,
            cylinders=cylinders,
            role=role,
            limits=limits,
        )
    t.finish()
    return mass


_COUPLING_KEYS = (
    "dynamic_stiffness",
    "stiffness_table",
    "relative_damping",
    "damping_ratio",
    "temperature_factor",
    "damping_temperature_factor",
    "reference_torque",
    "nominal_torque",
    "maximum_torque",
    "vibratory_torque",
    "maximum_torque_1",
    "maximum_torque_2",
    "power_loss",
    "designation",
)


def _shaft(t: Table) -> Shaft:
    between = t.string_list("between", length=2)
    kind = t.string("kind", "shaft", choices=("shaft", "coupling"))
    name = t.string("name", None)
    role = t.string("role", None, choices=SHAFT_ROLES)
    coupling = None
    given = [k for k in _COUPLING_KEYS if k in t.data]
    if kind == "coupling":
        for key in ("stiffness", "length", "shear_modulus", "loss_factor", "density", "inertia"):
            if key in t.data:
                raise t.error(
                    key,
                    "a coupling's stiffness and damping come from its catalogue data "
                    "(dynamic_stiffness, relative_damping); put its inertias on its masses",
                    t.data[key],
                )
        coupling = _coupling(t)
    elif given:
        raise t.error(
            given[0], 'is a coupling key: give kind = "coupling" on this shaft', t.data[given[0]]
        )
    stiffness = t.quantity("stiffness", "torsional_stiffness", None, check="positive")
    length = t.quantity("length", "length", None, check="positive")
    outer = t.quantity("outer_diameter", "length", None, check="positive")
    inner = t.quantity("inner_diameter", "length", None, check="nonnegative")
    shear = t.quantity("shear_modulus", "pressure", None, check="positive")
    damping = t.quantity("damping", "torsional_damping", 0.0, check="nonnegative")
    loss = t.number("loss_factor", 0.0, check="nonnegative")
    density = t.quantity("density", "density", None, check="positive")
    own = t.quantity("inertia", "inertia", None, check="positive")
    elements = t.integer("elements", None, minimum=1, maximum=10_000)
    max_frequency = t.quantity("max_frequency", "frequency", None, check="positive")
    if density is not None and own is not None:
        raise t.error(
            "inertia",
            "give the density (with the geometry) or the shaft's inertia, not both",
            t.data["inertia"],
        )
    if stiffness is not None:
        refused = ["shear_modulus"] + ([] if density is not None else ["length"])
        for key in refused:
            if key in t.data:
                raise t.error(
                    key,
                    "give the stiffness or the shaft's length and shear modulus, not both",
                    t.data[key],
                )
    elif coupling is None:
        for key, value in (("length", length), ("outer_diameter", outer), ("shear_modulus", shear)):
            if value is None:
                raise t.error(
                    key,
                    "missing; give the stiffness, or the length, outer_diameter (and "
                    "inner_diameter) and shear_modulus",
                )
    if inner is not None and outer is None:
        raise t.error("outer_diameter", "missing; a bore needs the outer diameter")
    if density is not None and (length is None or outer is None):
        raise t.error(
            "density",
            "the shaft's inertia rho I_p L needs its length and outer_diameter (and "
            "inner_diameter)",
            t.data["density"],
        )
    for key in ("elements", "max_frequency"):
        if key in t.data and density is None and own is None:
            raise t.error(
                key, "subdivides a shaft with inertia: give its density or inertia", t.data[key]
            )
    if elements is not None and max_frequency is not None:
        raise t.error(
            "max_frequency", "give elements or max_frequency, not both", t.data["max_frequency"]
        )
    with t.context():
        geometry = ShaftGeometry(outer, inner or 0.0, length, shear) if outer is not None else None
        if density is not None:
            # density needs the length and outer diameter, so the geometry (checked above)
            own = density * geometry.polar_moment * length  # type: ignore[union-attr]
        shaft = Shaft(
            between=between,
            stiffness=stiffness,
            damping=damping,
            loss_factor=loss,
            geometry=geometry,
            name=name,
            role=role,
            coupling=coupling,
            inertia=own or 0.0,
            elements=elements,
            max_frequency=None if max_frequency is None else 2.0 * math.pi * max_frequency,
        )
    t.finish()
    return shaft


def _coupling(t: Table) -> Coupling:
    """The catalogue keys of a ``kind = "coupling"`` shaft (docs/torsion-file.md)."""
    stiffness = t.quantity("dynamic_stiffness", "torsional_stiffness", None, check="positive")
    table = t.raw("stiffness_table", None)
    torques = stiffnesses = None
    if table is not None:
        if stiffness is not None:
            raise t.error(
                "stiffness_table",
                "give dynamic_stiffness or stiffness_table, not both",
                table,
            )
        if (
            not isinstance(table, list)
            or not table
            or any(not isinstance(row, list) or len(row) != 2 for row in table)
        ):
            raise t.error(
                "stiffness_table",
                'expected rows [mean torque, C_Tdyn], e.g. [["0 kN*m", "90 kN*m/rad"], '
                '["25 kN*m", "160 kN*m/rad"]]',
                table,
            )
        torques = [t.item("stiffness_table", r[0], "torque") for r in table]
        stiffnesses = [t.item("stiffness_table", r[1], "torsional_stiffness") for r in table]
    elif stiffness is None:
        raise t.error(
            "dynamic_stiffness",
            "missing; give the coupling's C_Tdyn, or stiffness_table against the mean torque",
        )
    psi = t.number("relative_damping", None, check="positive")
    zeta = t.number("damping_ratio", None, check="positive")
    values = {
        key: t.quantity(key, "torque", None, check="positive")
        for key in (
            "nominal_torque",
            "maximum_torque",
            "vibratory_torque",
            "maximum_torque_1",
            "maximum_torque_2",
        )
    }
    reference = t.quantity("reference_torque", "torque", None, check="nonnegative")
    power = t.quantity("power_loss", "power", None, check="positive")
    factor = t.number("temperature_factor", 1.0, check="positive")
    damping_factor = t.number("damping_temperature_factor", 1.0, check="positive")
    designation = t.string("designation", None)
    with t.context():
        return Coupling(
            stiffness=stiffness,
            # Coupling takes any sequence for its tables (np.asarray); its annotation names arrays
            table_torque=torques,  # type: ignore[arg-type]
            table_stiffness=stiffnesses,  # type: ignore[arg-type]
            relative_damping=psi,
            damping_ratio=zeta,
            temperature_factor=factor,
            damping_temperature_factor=damping_factor,
            reference_torque=reference,
            power_loss=power,
            designation=designation,
            **values,
        )


def _gear(t: Table) -> Gear:
    between = t.string_list("between", length=2)
    teeth = t.integer_list("teeth", None, length=2)
    ratio = t.number("ratio", None) if "ratio" in t.data or teeth is None else None
    if teeth is None and ratio is None:
        raise t.error("ratio", "missing; give the speed ratio n_b/n_a or the tooth numbers")
    if teeth is not None and "ratio" in t.data:
        raise t.error("ratio", "give the ratio or the tooth numbers, not both", t.data["ratio"])
    if teeth is not None and any(z < 1 for z in teeth):
        raise t.error("teeth", "tooth numbers must be at least 1", list(teeth))
    direction = t.string("direction", "opposite", choices=GEAR_DIRECTIONS)
    stiffness = t.quantity("stiffness", "torsional_stiffness", None, check="positive")
    mesh = t.quantity("mesh_stiffness", "stiffness", None, check="positive")
    base = t.quantity("base_diameter", "length", None, check="positive")
    if mesh is not None and stiffness is not None:
        raise t.error(
            "mesh_stiffness", "give stiffness or mesh_stiffness, not both", t.data["mesh_stiffness"]
        )
    if mesh is not None:
        if base is None:
            raise t.error(
                "base_diameter",
                "missing; the mesh stiffness along the line of action needs the base diameter "
                "of the first wheel (k = c r_b^2)",
            )
        stiffness = mesh * (0.5 * base) ** 2
    elif base is not None:
        raise t.error("base_diameter", "applies with mesh_stiffness", t.data["base_diameter"])
    damping = t.quantity("damping", "torsional_damping", 0.0, check="nonnegative")
    loss = t.number("loss_factor", 0.0, check="nonnegative")
    name = t.string("name", None)
    with t.context():
        gear = Gear(
            between=between,
            ratio=ratio,
            teeth=teeth,
            direction=direction,
            stiffness=stiffness,
            damping=damping,
            loss_factor=loss,
            name=name,
        )
    t.finish()
    return gear


def _span_stiffness(t: Table, beam: Callable[[], float] | None) -> float | None:
    """[torsion.throws] stiffness (N m/rad): a quantity, or "beam", the beam model's."""
    value = t.data.get("stiffness")
    if not (isinstance(value, str) and value.strip().lower() == "beam"):
        return t.quantity("stiffness", "torsional_stiffness", None, check="positive")
    t.string("stiffness")
    if beam is None:
        raise t.error(
            "stiffness",
            "\"beam\" takes the crank span's stiffness from the beam model of the engine file's "
            "[crankshaft] section, which this file does not have",
            value,
        )
    return beam()


def _throws(t: Table, beam: Callable[[], float] | None = None) -> ThrowSpec:
    inertia = t.quantity("inertia", "inertia", check="nonnegative")
    model = t.string("model", "throw", choices=THROW_MODELS)
    parts = None
    if model == "parts":
        j_j = t.quantity("journal_inertia", "inertia", check="nonnegative")
        j_w = t.quantity("web_inertia", "inertia", check="nonnegative")
        k_j = t.quantity("journal_stiffness", "torsional_stiffness", None, check="positive")
        k_w = t.quantity("web_stiffness", "torsional_stiffness", None, check="positive")
        if t.has("stiffness"):
            raise t.error(
                "stiffness",
                'with model = "parts" give journal_stiffness and web_stiffness, or the span\'s '
                "dimensions (Carter's terms)",
                t.data["stiffness"],
            )
        with t.context():
            parts = ThrowParts(j_j, j_w, k_j, k_w)
    else:
        for key in _PART_KEYS:
            if t.has(key):
                raise t.error(key, 'applies with model = "parts"', t.data[key])
    stiffness = _span_stiffness(t, beam)
    given = [k for k in (*_CARTER_KEYS, "journal_bore", "pin_bore") if t.has(k)]
    geometry = None
    if stiffness is not None and given:
        raise t.error(
            given[0],
            "give the crank span's stiffness or its dimensions (Carter's formula), not both",
            t.data[given[0]],
        )
    if parts is not None and parts.journal_stiffness is not None and given:
        raise t.error(
            given[0],
            "give the parts' stiffnesses or the span's dimensions (Carter's terms), not both",
            t.data[given[0]],
        )
    needs_geometry = stiffness is None and (parts is None or parts.journal_stiffness is None)
    if needs_geometry:
        missing = [k for k in _CARTER_KEYS if k not in given]
        if missing:
            first = "journal_stiffness" if parts is not None else "stiffness"
            raise t.error(
                missing[0] if given else first,
                "missing; give the crank span's stiffness"
                + (" (journal_stiffness and web_stiffness)" if parts is not None else "")
                + ", or "
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
            parts=parts,
        )
    t.finish()
    return spec
