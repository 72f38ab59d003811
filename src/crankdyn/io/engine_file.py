"""Engine description files (TOML) and the built-in examples; see docs/engine-file.md."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from functools import partial
from pathlib import Path
from typing import Any

from crankdyn.crank.geometry import CrankGeometry
from crankdyn.crank.masses import ROD_SPLITS, Masses, crank_unbalance_from_parts
from crankdyn.crank.pressure import ATMOSPHERE, PressureTrace
from crankdyn.crank.pressure_model import LOAD_KEYS, WiebePressureModel
from crankdyn.crankshaft.beam_inputs import ADDITIONAL_STRESS_SOURCES, THEORIES, BeamInputs
from crankdyn.crankshaft.geometry import (
    CONSTRUCTIONS,
    ENGINE_TYPES,
    MANUFACTURE_FACTORS,
    STRESS_FACTOR_NAMES,
    SURFACE_TREATMENTS,
    YOUNGS_MODULUS_STEEL,
    Crankshaft,
    CrankshaftGeometry,
    CrankshaftMaterial,
    ShrinkFit,
    StressFactors,
)
from crankdyn.engine.firing import throw_angles_from_positions
from crankdyn.engine.force_model import ForceModel
from crankdyn.engine.model import (
    ASPIRATIONS,
    CYCLES,
    FUELS,
    LAYOUTS,
    BalanceInputs,
    Cylinders,
    Engine,
    FlywheelInputs,
)
from crankdyn.errors import InputError, did_you_mean
from crankdyn.io.examples import display_path
from crankdyn.io.files import display_name, load_toml
from crankdyn.io.project_file import with_project
from crankdyn.io.schema import MISSING, Table
from crankdyn.io.torsion_file import (
    parse_torsion_section,
    read_torsion_model,
    with_input_warnings,
)
from crankdyn.io.traces import read_pressure_trace
from crankdyn.torsion.model import TorsionModel

__all__ = [
    "join_engines",
    "load_engine",
    "parse_engine",
    "parse_model_file",
]


def load_engine(path: str | Path) -> Engine:
    """Load an engine description file (TOML; format in docs/engine-file.md, ``crankdyn docs
    engine-file``).

    Parameters
    ----------
    path
        The engine file; the files it names (pressure trace, shaft lines) are looked for
        beside it.

    Returns
    -------
    Engine
        The engine, every quantity in SI (lengths m, masses kg, pressures Pa, speeds rad/s,
        angles rad).

    Raises
    ------
    InputError
        As :func:`parse_engine`, or for an unreadable or malformed file; naming the file, the
        key and the value.
    """
    return _load(Path(path), display_name(path))


def _load(path: Path, name: str) -> Engine:
    data = load_toml(path, what="engine file")
    return parse_engine(data, file=name, base_dir=path.parent)


def parse_engine(
    data: dict[str, Any], *, file: str | None = None, base_dir: Path | None = None
) -> Engine:
    """Build an Engine from a parsed engine document (a dict as from tomllib).

    Tables (docs/engine-file.md): ``name``, ``cycle``, ``[geometry]`` (bore, stroke or crank
    radius, rod length or ratio, offset: lengths), ``[cylinders]`` (count, layout, firing
    order, throw angles or positions, bank angle: angles), ``[masses]`` (kg, kg m^2),
    ``[pressure]`` (a trace file or the Wiebe model; pressures Pa), ``[operating]`` (speeds),
    ``[balance]``, ``[flywheel]``, ``[torsion]`` and ``[crankshaft]`` (the UR M53 check:
    lengths, strengths in Pa); quantities as strings with units (``"86 mm"``) or bare SI
    numbers.

    Parameters
    ----------
    data
        The parsed document.
    file
        The file's name for messages.
    base_dir
        The folder relative file names (traces, shaft lines) are taken from.

    Returns
    -------
    Engine
        The engine, every quantity in SI.

    Raises
    ------
    InputError
        On a missing or unknown key or table, a value of the wrong unit, kind or sign, a
        choice not in the list, alternative keys given together, a data file that does not
        read, or an engine the model classes refuse; naming the file, the key and the value.
    """
    root = Table(data, file=file, base_dir=base_dir)
    name = root.string("name")
    cycle = root.string("cycle", "four-stroke", choices=CYCLES)
    fuel = root.string("fuel", None, choices=FUELS)
    aspiration = root.string("aspiration", None, choices=ASPIRATIONS)
    geometry = _geometry(root.table("geometry", required=True))
    cylinders = _cylinders(root.table("cylinders"), cycle)
    masses = _masses(root.table("masses"), geometry)
    pressure, crankcase = _pressure(root.table("pressure"), cycle, geometry)
    speed, efficiency = _operating(root.table("operating"))
    crankshaft = _crankshaft(root.table("crankshaft"), cylinders.pitch)
    beam = None
    if crankshaft is not None:
        beam = partial(_beam_stiffness, crankshaft, geometry.crank_radius, cylinders.pitch, file)
    torsion = with_project(
        root, _torsion(root.table("torsion"), name, geometry, cylinders, masses, beam)
    )
    balance = _balance(root.table("balance"))
    flywheel = _flywheel(root.table("flywheel"))
    forces = _forces(root.table("forces"))
    if forces is not None and forces.active and masses is None:
        raise root.error("forces", "gravity and piston friction act on the masses: give [masses]")
    warnings = tuple(root.warnings)  # of every section, the shaft lines' among them
    if warnings and torsion is not None:
        with root.context():
            torsion = dataclasses.replace(torsion, input_warnings=warnings)
    with root.context():
        engine = Engine(
            name=name,
            geometry=geometry,
            cylinders=cylinders,
            masses=masses,
            pressure=pressure,
            crankcase_pressure=crankcase,
            speed=speed,
            torsion=torsion,
            mechanical_efficiency=efficiency,
            balance=balance,
            flywheel=flywheel,
            source=file,
            fuel=fuel,
            aspiration=aspiration,
            crankshaft=crankshaft,
            forces=forces,
            input_warnings=warnings,
        )
    root.finish()
    return engine


def _geometry(t: Table) -> CrankGeometry:
    bore = t.quantity("bore", "length", check="positive")
    which = t.exclusive("stroke", "crank_radius")
    radius = t.quantity(which, "length", check="positive") / (2.0 if which == "stroke" else 1.0)
    rod_key = t.exclusive("rod_length", "rod_ratio")
    offset = t.quantity("offset", "length", 0.0)
    intake = t.quantity("intake_area", "area", None, check="positive")
    with t.context():
        if rod_key == "rod_ratio":
            ratio = t.number("rod_ratio", check="positive")
            if ratio >= 1.0:
                raise t.error(
                    "rod_ratio",
                    "the rod ratio R/L must be less than 1 (the rod must be longer than the crank)",
                    ratio,
                )
            rod = radius / ratio
        else:
            rod = t.quantity("rod_length", "length", check="positive")
        try:
            geometry = CrankGeometry(
                bore=bore, crank_radius=radius, rod_length=rod, offset=offset, intake_area=intake
            )
        except InputError as exc:
            if exc.key == "rod_length":  # report against the key the user wrote
                raise t.error(rod_key, exc.message, t.data[rod_key]) from None
            if exc.key == "crank_radius":
                raise t.error(which, exc.message, t.data[which]) from None
            if exc.key in ("bore", "offset"):
                raise t.error(exc.key, exc.message, t.data[exc.key]) from None
            raise
    t.finish()
    return geometry


def _cylinders(t: Table | None, cycle: str) -> Cylinders:
    if t is None:
        return Cylinders(count=1, firing_order=(1,), cycle=cycle)
    count = t.integer("count", 1, minimum=1, maximum=64)
    layout = t.string("layout", "inline", choices=LAYOUTS)
    order = t.integer_list("firing_order", (1,) if count == 1 else None)
    if order is None:
        raise t.error(
            "firing_order",
            f"missing; expected the {count} cylinder numbers in firing order, e.g. [1, 3, 4, 2]",
        )
    throw_angles = t.quantity_list("throw_angles", "angle", None, length=count)
    throw_positions = t.quantity_list("throw_positions", "angle", None)
    pitch = t.quantity("pitch", "length", None, check="positive")
    bank_angle = t.quantity("bank_angle", "angle", None)
    if layout == "V" and bank_angle is None:
        raise t.error("bank_angle", 'missing; a V engine needs its bank angle, e.g. "90 deg"')
    if layout == "inline" and bank_angle is not None:
        raise t.error("bank_angle", "an inline engine has no bank angle", t.data["bank_angle"])
    banks = t.string_list("banks", None, length=count, choices=("A", "B"))
    throws = t.integer_list("throws", None, length=count)
    if throw_positions is not None:
        throw_angles = _from_positions(
            t, throw_positions, throw_angles, layout, bank_angle, banks, throws, count
        )
    with t.context():
        cylinders = Cylinders(
            count=count,
            firing_order=order,
            cycle=cycle,
            throw_angles=throw_angles,
            layout=layout,
            bank_angle=bank_angle or 0.0,
            banks=banks,
            throws=throws,
            pitch=pitch,
        )
    t.finish()
    return cylinders


def _masses(t: Table | None, geometry: CrankGeometry) -> Masses | None:
    if t is None:
        return None
    values = {
        key: t.quantity(key, "mass", None, check="nonnegative")
        for key in ("piston_group", "rod", "crank_unbalance", "reciprocating", "rotating")
    }
    values["rod_cg_from_big_end"] = t.quantity(
        "rod_cg_from_big_end", "length", None, check="positive"
    )
    values["rod_inertia"] = t.quantity("rod_inertia", "inertia", None, check="positive")
    values["rod_split"] = t.string("rod_split", "centre-of-gravity", choices=ROD_SPLITS)
    parts = _crank_parts(t, geometry)
    if parts is not None:
        if values["crank_unbalance"] is not None:
            raise t.error(
                "crank_unbalance",
                "give crank_unbalance or its parts (crank_pin, crank_web, crank_web_radius), "
                "not both",
                t.data["crank_unbalance"],
            )
        values["crank_unbalance"] = parts
    if values["crank_unbalance"] is None:
        values["crank_unbalance"] = 0.0
    with t.context():
        masses = Masses(**values)
    try:
        masses.check_rod(geometry.rod_length)
    except InputError as exc:
        if exc.key in t.data:  # report against the key and value the user wrote
            raise t.error(exc.key, exc.message, t.data[exc.key]) from None
        raise
    t.finish()
    return masses


def _crank_parts(t: Table, geometry: CrankGeometry) -> float | None:
    """m_k from crank_pin, crank_web and crank_web_radius (seed 000 section 2.1), or None."""
    pin = t.quantity("crank_pin", "mass", None, check="nonnegative")
    web = t.quantity("crank_web", "mass", None, check="nonnegative")
    rho = t.quantity("crank_web_radius", "length", None, check="positive")
    given = {"crank_pin": pin, "crank_web": web, "crank_web_radius": rho}
    if all(v is None for v in given.values()):
        return None
    missing = [k for k, v in given.items() if v is None]
    if missing:
        present = next(k for k, v in given.items() if v is not None)
        raise t.error(
            present,
            f"the crank's unbalance from its parts also needs {', '.join(missing)} "
            "(m_k = m_z + 2 m_w rho / R)",
            t.data[present],
        )
    assert pin is not None and web is not None and rho is not None
    return crank_unbalance_from_parts(pin, web, rho, geometry.crank_radius)


def _pressure(
    t: Table | None, cycle: str, geometry: CrankGeometry
) -> tuple[PressureTrace | None, float]:
    """[pressure]: a trace (``file``) or the synthetic model (``model = "wiebe"`` and its
    parameters); neither leaves the engine without a trace (the analyses then use the model
    with every default)."""
    if t is None:
        return None, ATMOSPHERE
    crankcase = t.quantity("crankcase_pressure", "pressure", ATMOSPHERE, check="nonnegative")
    cycle_angle = 4.0 * math.pi if cycle == "four-stroke" else 2.0 * math.pi
    which = t.exclusive("file", "model", required=False)
    given = [k for k in _MODEL_KEYS if k in t.data]
    if which == "file":
        foreign = [k for k in given if k != "compression_ratio"]
        if foreign:
            raise t.error(
                foreign[0],
                'is a parameter of the synthetic model (model = "wiebe"), not of a trace',
                t.data[foreign[0]],
            )
        firing_tdc = t.quantity("firing_tdc", "angle", 0.0)
        eps = t.number("compression_ratio", None)
        trace_path = t.input_file("file", "pressure trace")
        with t.context():
            trace = read_pressure_trace(
                trace_path,
                firing_tdc=firing_tdc,
                cycle_angle=cycle_angle,
                display=display_path(trace_path),
                geometry=geometry,
                compression_ratio=eps,
            )
            if eps is not None:
                trace = PressureTrace(
                    trace.crank_angle, trace.pressure, trace.cycle_angle, trace.source, eps
                )
        t.finish()
        return trace, crankcase
    if which is None and not given:
        t.finish()
        return None, crankcase
    if which == "model":
        t.string("model", choices=("wiebe",))
    if "firing_tdc" in t.data:
        raise t.error("firing_tdc", "applies to a pressure trace (file)", t.data["firing_tdc"])
    values = {}
    for key, (kind, check) in _MODEL_KEYS.items():
        if kind == "number":
            value = t.number(key, None)
        else:
            value = t.quantity(key, kind, None, check=check)
        if value is not None:
            values[key] = value
    load = [k for k in LOAD_KEYS if k in values]
    if len(load) > 1:
        raise t.error(load[1], f"give only one of {', '.join(LOAD_KEYS)}", t.data[load[1]])
    try:
        model = WiebePressureModel(**values)
        trace = model.trace(geometry, cycle)
    except InputError as exc:
        if exc.key in t.data:  # report the value as the user wrote it
            raise t.error(exc.key, exc.message, t.data[exc.key]) from None
        raise exc.within(file=t.file, section=t.name) from None
    t.finish()
    return trace, crankcase


_MODEL_KEYS = {
    "compression_ratio": ("number", None),
    "combustion_start": ("angle", None),
    "combustion_duration": ("angle", "positive"),
    "wiebe_a": ("number", None),
    "wiebe_m": ("number", None),
    "compression_exponent": ("number", None),
    "expansion_exponent": ("number", None),
    "intake_pressure": ("pressure", "positive"),
    "exhaust_pressure": ("pressure", "positive"),
    "exhaust_opens": ("angle", None),
    "valve_overlap": ("angle", "nonnegative"),
    "fuel_energy": ("energy", "nonnegative"),
    "imep": ("pressure", "positive"),
    "peak_pressure": ("pressure", "positive"),
}
"""Keys of the synthetic pressure model in [pressure] and their kinds (docs/forces.md)."""


def _beam_stiffness(
    crankshaft: Crankshaft, crank_radius: float, pitch: float | None, file: str | None
) -> float:
    """The crank span's torsional stiffness (N m/rad) from the beam model of the [crankshaft]
    throw (:func:`crankdyn.crankshaft.beam_engine.beam_throw_stiffness`), built when asked."""
    from crankdyn.crankshaft.beam_engine import beam_throw_stiffness

    return beam_throw_stiffness(crankshaft, crank_radius, pitch, file)


def _torsion(
    t: Table | None,
    name: str,
    geometry: CrankGeometry,
    cylinders: Cylinders,
    masses: Masses | None,
    beam: Callable[[], float] | None = None,
) -> TorsionModel | None:
    """The [torsion] section: the lumped torsional model (docs/torsion-file.md); ``beam``, the
    crank span's stiffness from the [crankshaft] beam model (N m/rad), when there is one."""
    if t is None:
        return None
    return parse_torsion_section(
        t,
        engine_name=name,
        geometry=geometry,
        cylinders=cylinders,
        masses=masses,
        beam_stiffness=beam,
    )


def _from_positions(
    t: Table,
    positions: Sequence[float],
    throw_angles: Sequence[float] | None,
    layout: str,
    bank_angle: float | None,
    banks: Sequence[str] | None,
    throws: Sequence[int] | None,
    count: int,
) -> tuple[float, ...] | None:
    """Throw angles from the crank end view ``throw_positions`` (one angle per throw); None when
    the layout itself is wrong (Cylinders then reports it)."""
    if throw_angles is not None:
        raise t.error(
            "throw_positions",
            "give throw_angles or throw_positions, not both",
            t.data["throw_positions"],
        )
    half = count // 2
    if layout == "inline":
        banks, throws = ("A",) * count, throws or tuple(range(1, count + 1))
    elif count % 2 == 0 or (banks and throws):
        banks = banks or ("A",) * half + ("B",) * half
        throws = throws or tuple(list(range(1, half + 1)) * 2)
    else:
        return None
    if min(throws) < 1 or sorted(set(throws)) != list(range(1, max(throws) + 1)):
        return None
    gamma = bank_angle or 0.0
    alpha = [0.0 if layout == "inline" else (-gamma if b == "A" else gamma) / 2.0 for b in banks]
    if len(positions) != max(throws):
        raise t.error(
            "throw_positions",
            f"expected {max(throws)} angles, one per throw",
            t.data["throw_positions"],
        )
    return tuple(float(a) for a in throw_angles_from_positions(positions, throws, alpha))


def _balance(t: Table | None) -> BalanceInputs | None:
    if t is None:
        return None
    values = {
        "counterweight_ratio": t.number("counterweight_ratio", 0.0, check="nonnegative"),
        "reciprocating_balance_ratio": t.number(
            "reciprocating_balance_ratio", 0.0, check="nonnegative"
        ),
        "rod_offset": t.quantity("rod_offset", "length", 0.0),
        "power": t.quantity("power", "power", None, check="positive"),
    }
    with t.context():
        inputs = BalanceInputs(**values)
    t.finish()
    return inputs


def _flywheel(t: Table | None) -> FlywheelInputs | None:
    if t is None:
        return None
    values = {
        "delta": t.number("delta", None, check="positive"),
        "inertia": t.quantity("inertia", "inertia", None, check="positive"),
        "other_inertia": t.quantity("other_inertia", "inertia", 0.0, check="nonnegative"),
        "density": t.quantity("density", "density", None, check="positive"),
        "max_diameter": t.quantity("max_diameter", "length", None, check="positive"),
        "inner_diameter": t.quantity("inner_diameter", "length", None, check="positive"),
    }
    with t.context():
        inputs = FlywheelInputs(**values)
    t.finish()
    return inputs


def _forces(t: Table | None) -> ForceModel | None:
    """[forces]: gravity and the piston's friction (crankdyn.engine.force_model)."""
    if t is None:
        return None
    values = {
        "gravity": t.boolean("gravity", False),
        "ring_friction": t.quantity("ring_friction", "force", 0.0, check="nonnegative"),
        "skirt_friction": t.number("skirt_friction", 0.0, check="nonnegative"),
    }
    with t.context():
        model = ForceModel(**values)
    t.finish()
    return model


_CRANKSHAFT_LENGTHS = (
    ("pin_diameter", "positive", MISSING),
    ("journal_diameter", "positive", MISSING),
    ("web_thickness", "positive", MISSING),
    ("web_width", "positive", MISSING),
    ("pin_fillet_radius", "positive", MISSING),
    ("journal_fillet_radius", "positive", MISSING),
    ("web_centre_distance", "positive", MISSING),
    ("pin_bore", "nonnegative", 0.0),
    ("journal_bore", "nonnegative", 0.0),
    ("overlap", None, None),
    ("pin_recess", "nonnegative", 0.0),
    ("journal_recess", "nonnegative", 0.0),
    ("oil_bore_diameter", "positive", None),
    ("bearing_span", "positive", None),
)
"""The lengths of [crankshaft]: (key, sign, default; MISSING: required), docs/engine-file.md."""


@contextmanager
def _as_written(t: Table) -> Iterator[None]:
    """Report a domain object's error against the key and the value the user wrote (the
    table's section added in any case)."""
    try:
        with t.context():
            yield
    except InputError as exc:
        key = exc.key.split(" ")[-1] if exc.key else None
        if key is not None and key in t.data:
            raise t.error(key, exc.message, t.data[key]) from None
        raise


def _crankshaft(t: Table | None, pitch: float | None) -> Crankshaft | None:
    """[crankshaft]: the crankshaft of the IACS UR M53 check (docs/engine-file.md), with its
    optional [crankshaft.shrink_fit] and [crankshaft.factors] tables; L_1 checked against the
    cylinder pitch when no bearing span is given."""
    if t is None:
        return None
    lengths = {
        key: t.quantity(key, "length", default, check=sign)
        for key, sign, default in _CRANKSHAFT_LENGTHS
    }
    angle = t.quantity("oil_bore_angle", "angle", 0.0)
    material = {
        "tensile_strength": t.quantity("tensile_strength", "pressure", check="positive"),
        "yield_strength": t.quantity("yield_strength", "pressure", None, check="positive"),
        "manufacture": t.string("manufacture", "free-form", choices=tuple(MANUFACTURE_FACTORS)),
        "surface_treatment": t.string("surface_treatment", "none", choices=SURFACE_TREATMENTS),
        "surface_factor": t.number("surface_factor", 1.0, check="positive"),
        "youngs_modulus": t.quantity(
            "youngs_modulus", "pressure", YOUNGS_MODULUS_STEEL, check="positive"
        ),
    }
    engine_type = t.string("engine_type", "trunk-piston", choices=ENGINE_TYPES)
    construction = t.string("construction", "solid", choices=CONSTRUCTIONS)
    axial = t.quantity("axial_vibration_stress", "pressure", None, check="nonnegative")
    source = t.string("additional_stress", None, choices=ADDITIONAL_STRESS_SOURCES)
    fit = _shrink_fit(t.table("shrink_fit"))
    factors = _stress_factors(t.table("factors"))
    beam = _crankshaft_beam(t.table("beam"))
    with _as_written(t):
        geometry = CrankshaftGeometry(**lengths, oil_bore_angle=angle)
        if geometry.bearing_span is None and pitch is not None:
            geometry.check_span(pitch)
        crankshaft = Crankshaft(
            geometry=geometry,
            material=CrankshaftMaterial(**material),
            engine_type=engine_type,
            construction=construction,
            shrink_fit=fit,
            factors=factors,
            axial_vibration_stress=axial,
            beam=beam,
            additional_stress=source,
        )
    t.finish()
    return crankshaft


def _crankshaft_beam(t: Table | None) -> BeamInputs | None:
    """[crankshaft.beam]: the beam model's own inputs (docs/engine-file.md), every key
    optional."""
    if t is None:
        return None
    values: dict[str, Any] = {
        "poisson_ratio": t.number("poisson_ratio", 0.3, check="nonnegative", maximum=0.4999),
        "density": t.quantity("density", "density", 7850.0, check="positive"),
        "bearing_radial_stiffness": t.quantity(
            "bearing_radial_stiffness", "stiffness", None, check="nonnegative"
        ),
        "bearing_tilting_stiffness": t.quantity(
            "bearing_tilting_stiffness", "torsional_stiffness", 0.0, check="nonnegative"
        ),
        "thrust_axial_stiffness": t.quantity(
            "thrust_axial_stiffness", "stiffness", None, check="nonnegative"
        ),
        "thrust_journal": t.integer("thrust_journal", None, minimum=1),
        "counterweight_mass": t.quantity("counterweight_mass", "mass", 0.0, check="nonnegative"),
        "counterweight_radius": t.quantity(
            "counterweight_radius", "length", None, check="nonnegative"
        ),
        "free_end_mass": t.quantity("free_end_mass", "mass", None, check="nonnegative"),
        "flywheel_mass": t.quantity("flywheel_mass", "mass", None, check="nonnegative"),
        "free_end_distance": t.quantity("free_end_distance", "length", None, check="nonnegative"),
        "flywheel_distance": t.quantity("flywheel_distance", "length", None, check="nonnegative"),
        "axial_damping": t.quantity("axial_damping", "damping", 0.0, check="nonnegative"),
        "elements": t.integer("elements", 2, minimum=1, maximum=64),
        "theory": t.string("theory", "timoshenko", choices=THEORIES),
        "web_rigid_fraction": t.number("web_rigid_fraction", 0.0, check="nonnegative"),
        "modes": t.integer("modes", 24, minimum=1, maximum=500),
        "damping_ratio": t.number("damping_ratio", 0.02, check="nonnegative", maximum=1.0),
    }
    with _as_written(t):
        beam = BeamInputs(**values)
    t.finish()
    return beam


def _shrink_fit(t: Table | None) -> ShrinkFit | None:
    if t is None:
        return None
    values = {
        "diameter": t.quantity("diameter", "length", check="positive"),
        "length": t.quantity("length", "length", check="positive"),
        "web_outer_diameter": t.quantity("web_outer_diameter", "length", check="positive"),
        "oversize": t.quantity("oversize", "length", None, check="positive"),
        "friction": t.number("friction", 0.2, check="positive"),
        "slip_safety": t.number("slip_safety", 2.0, check="positive"),
        "pin_yield_strength": t.quantity("pin_yield_strength", "pressure", None, check="positive"),
        "web_yield_strength": t.quantity("web_yield_strength", "pressure", None, check="positive"),
    }
    with _as_written(t):
        fit = ShrinkFit(**values)
    t.finish()
    return fit


def _stress_factors(t: Table | None) -> StressFactors | None:
    if t is None:
        return None
    values: dict[str, Any] = {
        name: t.number(name, None, check="positive") for name in STRESS_FACTOR_NAMES
    }
    values["source"] = t.string("source", "")
    if all(values[name] is None for name in STRESS_FACTOR_NAMES):
        raise t.error(None, f"give at least one of {', '.join(STRESS_FACTOR_NAMES)}")
    with _as_written(t):
        factors = StressFactors(**values)
    t.finish()
    return factors


def _operating(t: Table | None) -> tuple[float | None, float | None]:
    if t is None:
        return None, None
    speed = t.quantity("speed", "speed", None, check="positive")
    efficiency = t.number("mechanical_efficiency", None, check="positive", maximum=1.0)
    t.finish()
    return speed, efficiency


# ---- model files that join engines to a line (docs/torsion-file.md) ----------------------
def parse_model_file(
    data: dict[str, Any],
    *,
    file: str | None = None,
    base_dir: Path | None = None,
    default_name: str = "torsional model",
) -> TorsionModel:
    """A torsional model file (a dict as from tomllib) with the engine files its ``[[engine]]``
    entries join to the line (:func:`join_engines`); without them the same as
    :func:`crankdyn.io.torsion_file.parse_torsion_model`.

    Parameters
    ----------
    data
        The parsed document.
    file
        The file's name for messages.
    base_dir
        The folder relative file names (engine files, traces, tables) are taken from.
    default_name
        The model's name when the document gives none.

    Returns
    -------
    TorsionModel
        The line with its engines joined, every quantity in SI.

    Raises
    ------
    InputError
        As :func:`crankdyn.io.torsion_file.parse_torsion_model` and :func:`join_engines`;
        naming the file, the key and the value.
    """
    root = Table(data, file=file, base_dir=base_dir)
    model = read_torsion_model(root, default_name=default_name)
    model = join_engines(root, model)
    model = with_project(root, model) or model
    root.finish()
    return with_input_warnings(model, root)


def join_engines(t: Table, line: TorsionModel) -> TorsionModel:
    """A model file's ``[[engine]]`` entries (docs/torsion-file.md): the engine files joined to
    the line's masses, the first as the model's engine, the others as engine sources.

    Keys of an entry: ``file`` (the engine file, with a [torsion] section whose masses carry
    cylinders), ``at`` (the line's mass), ``connect`` (the engine's mass, default its last),
    ``name``, ``prefix``, and for the second engine on, ``phase`` (rad, relative to the first)
    and ``share`` (of the load, a positive factor).

    Parameters
    ----------
    t
        The model file's top-level table.
    line
        The line's model (without cylinders).

    Returns
    -------
    TorsionModel
        The joined model (``line`` itself without ``[[engine]]`` entries), in SI.

    Raises
    ------
    InputError
        For a missing engine file or one without [torsion] cylinders, an unknown mass, a phase
        or share on the first engine, a line whose own masses carry cylinders, or any error of
        the engine file; naming the file, the key and the value.
    """
    tables = t.tables("engine")
    if not tables:
        return line
    from crankdyn.torsion.driveline import join, rename, strip_cylinders
    from crankdyn.torsion.excitation import EngineExcitation
    from crankdyn.torsion.sources import EngineSource

    if line.cylinder_dofs:
        raise tables[0].error(
            None, "the model's own masses carry cylinders; engines joined to it must not"
        )
    model = None
    for k, et in enumerate(tables):
        path = et.path("file")
        if not path.is_file():
            raise et.error("file", f"no such engine file (looked for {path})", et.data["file"])
        engine = load_engine(path)
        t.warnings.extend(w for w in engine.input_warnings if w not in t.warnings)
        if engine.torsion is None:
            raise et.error("file", "the engine file has no [torsion] section", et.data["file"])
        if not engine.torsion.cylinder_dofs:
            raise et.error(
                "file", "the engine's [torsion] masses carry no cylinders", et.data["file"]
            )
        name = et.string("name", engine.name)
        prefix = et.string("prefix", f"{name}: " if len(tables) > 1 else "")
        at = et.string("at")
        if at not in line.mass_names:
            raise et.error("at", f'no mass named "{at}"{did_you_mean(at, line.mass_names)}', at)
        connect = et.string("connect", engine.torsion.masses[-1].name)
        if connect not in engine.torsion.mass_names:
            raise et.error(
                "connect",
                f'the engine has no mass named "{connect}"'
                f"{did_you_mean(connect, engine.torsion.mass_names)}",
                connect,
            )
        phase = et.quantity("phase", "angle", 0.0)
        share = et.number("share", 1.0, check="positive")
        et.finish()
        part = rename(engine.torsion, prefix)
        with et.context():
            if k == 0:
                for key in ("phase", "share"):
                    if key in et.data:
                        raise et.error(
                            key,
                            "the first engine is the reference (phase 0, share 1); give the "
                            "others' relative to it",
                            et.data[key],
                        )
                part = dataclasses.replace(part, engine=engine)
                model = join(part, line, f"{prefix}{connect}", at, name=line.name)
                model = dataclasses.replace(model, operating=line.operating or model.operating)
                continue
            stripped, cylinders = strip_cylinders(part)
            source = EngineSource(
                name=name,
                excitation=EngineExcitation(engine, engine.torsion.excitation),
                cylinders=cylinders,
                phase=math.fmod(phase, engine.cycle_angle),
                share=share,
            )
            assert model is not None  # the first engine (k == 0) made it (type checker)
            model = join(model, stripped, at, f"{prefix}{connect}", name=line.name)
            model = dataclasses.replace(model, sources=(*model.sources, source))
    assert model is not None  # there is at least one engine (type checker)
    return model
