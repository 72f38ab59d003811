"""The forced-response tables of a torsional model file or an engine's [torsion] section:
``[excitation]`` (with ``[[excitation.trace]]``), ``[[damper]]``, ``[rules]`` (with
``[[rules.shaft]]``) and ``[operating]``; see docs/torsion-file.md."""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING, Any

from crankdyn.engine.firing import CYCLE_ANGLE
from crankdyn.errors import did_you_mean
from crankdyn.io.examples import display_path
from crankdyn.io.schema import MISSING, Table
from crankdyn.torsion.campbell import OperatingRange
from crankdyn.torsion.dampers import Damper, design_damper
from crankdyn.torsion.excitation_spec import ExcitationSpec, SpeedTrace
from crankdyn.torsion.model import TorsionModel
from crankdyn.torsion.orders import CYCLES
from crankdyn.torsion.rules import RuleSet, ShaftLimit

if TYPE_CHECKING:
    from crankdyn.crank.geometry import CrankGeometry
    from crankdyn.crank.masses import Masses
    from crankdyn.engine.model import Cylinders
    from crankdyn.torsion.sources import HarmonicSource, LoadLaw

    # an engine's parts the [torsion] section reads with (crankdyn.io.torsion_file)
    EngineParts = tuple[CrankGeometry, Cylinders, Masses | None]

__all__ = ["read_response_sections"]

_ENGINE_ONLY = ("load_curve", "harmonics", "imep", "misfire", "trace")
_MODEL_ONLY = ("cycle", "firing_order", "firing_angles", "torque", "cylinder_harmonics")


def read_response_sections(
    t: Table, model: TorsionModel, engine: EngineParts | None
) -> TorsionModel:
    """The model with its excitation (and excitation sources), dampers, rules and operating
    range read from table ``t`` (a model file's top level or an engine's [torsion] section).

    Tables (docs/torsion-file.md, ``crankdyn docs torsion-file``): ``[excitation]`` (a model's
    cycle, firing and torque in N m or the cylinders' harmonic table, ``cylinder_harmonics``;
    or an engine's load curve, harmonic table, imep in Pa, misfiring cylinders and
    ``[[excitation.trace]]`` pressure traces at speeds in rad/s; the
    ``[[excitation.propeller]]``, ``machine`` and ``source`` entries with torques in N m and
    powers in W), ``[[damper]]``, ``[rules]`` with ``[[rules.shaft]]`` limits, ``[operating]``
    (speed range and rated speed, rad/s) and ``[tvc]`` (:func:`crankdyn.io.tvc_file.read_tvc`).

    Parameters
    ----------
    t
        The model file's top-level table or the engine's [torsion] table.
    model
        The model read so far (masses, shafts, gears).
    engine
        The engine's crank geometry, cylinders and masses when ``t`` is an engine's [torsion]
        section; None for a torsional model file.

    Returns
    -------
    TorsionModel
        ``model`` with its excitation, sources, dampers, rules, operating range and TVC
        settings, every quantity in SI.

    Raises
    ------
    InputError
        On an unknown key or table, a key that belongs to the other kind of file, a value of
        the wrong unit, kind or sign, an unknown mass, shaft or cylinder, or a data file
        (trace, load curve, harmonic table) that does not read; naming the file, the key and
        the value.
    """
    operating = _operating(t.table("operating"))
    table = t.table("excitation")
    sources = read_sources(table, model, operating) if table is not None else ()
    excitation = _excitation(table, model, engine, has_sources=bool(sources))
    rules = _rules(t.table("rules"), model, operating)
    from crankdyn.io.tvc_file import read_tvc

    tvc = read_tvc(t.table("tvc"), operating)
    # a model file without these sections keeps the model as built: rebuilding it would check
    # every mass and shaft and walk its topology again
    found = (excitation, rules, operating, model.tvc if tvc is None else tvc)
    old = (model.excitation, model.rules, model.operating, model.tvc)
    if sources or any(a is not b for a, b in zip(found, old, strict=True)):
        with t.context():
            model = dataclasses.replace(
                model,
                excitation=excitation,
                rules=rules,
                operating=operating,
                sources=model.sources + sources,
                tvc=tvc if tvc is not None else model.tvc,
            )
    dampers = tuple(_damper(dt, model) for dt in t.tables("damper"))
    if dampers:
        with t.context():
            model = dataclasses.replace(model, dampers=dampers)
    return model


def _excitation(
    t: Table | None, model: TorsionModel, engine: EngineParts | None, has_sources: bool = False
) -> ExcitationSpec | None:
    if t is None:
        return None
    wrong = _MODEL_ONLY if engine is not None else _ENGINE_ONLY
    for key in wrong:
        if key in t.data:
            where = (
                "a model without an engine (the engine sets its own cycle and firing)"
                if engine is not None
                else "an engine's [torsion.excitation] (it needs the engine's pressure)"
            )
            raise t.error(key, f"applies to {where}", t.data[key])
    if engine is None:
        cycle = t.string("cycle", "four-stroke", choices=CYCLES)
        order = t.integer_list("firing_order", None)
        angles = t.quantity_list("firing_angles", "angle", None)
        if order is not None and angles is not None:
            raise t.error(
                "firing_angles",
                "give firing_order or firing_angles, not both",
                t.data["firing_angles"],
            )
        torque = t.quantity("torque", "torque", None, check="positive")
        cylinder_table = None
        if t.has("cylinder_harmonics"):
            from crankdyn.io.torsion_tables import read_cylinder_harmonics

            path = t.input_file("cylinder_harmonics", "cylinder harmonics")
            cylinder_table = read_cylinder_harmonics(path, display_path(path))
        count = max(model.cylinder_dofs, default=0)
        if count == 0 and not has_sources:
            raise t.error(
                None,
                "the model has no excitation point: no [[mass]] carries cylinders = [...]",
            )
        for key in ("firing_order", "firing_angles", "torque", "cylinder_harmonics"):
            if count == 0 and key in t.data:
                raise t.error(
                    key, "applies to cylinders on the masses, and the model has none", t.data[key]
                )
        if angles is not None and len(angles) != count:
            raise t.error(
                "firing_angles",
                f"expected {count} angles, one per cylinder 1..{count}",
                t.data["firing_angles"],
            )
        if order is not None:
            from crankdyn.engine.firing import check_firing_order

            with t.context():
                check_firing_order(order, count, key="firing_order")
        t.finish()
        with t.context():
            return ExcitationSpec(
                cycle=cycle,
                firing_angles=angles,
                firing_order=order,
                torque=torque,
                cylinder_harmonics=cylinder_table,
            )
    _geometry, cylinders, _masses = engine
    from crankdyn.io.torsion_tables import read_harmonic_table, read_load_curve
    from crankdyn.io.traces import read_pressure_trace

    curve = table = None
    if t.has("load_curve"):
        path = t.input_file("load_curve", "load curve")
        curve = read_load_curve(path, display_path(path))
    if t.has("harmonics"):
        path = t.input_file("harmonics", "harmonic table")
        table = read_harmonic_table(path, display_path(path))
    imep = t.quantity("imep", "pressure", None, check="positive")
    misfire = t.integer_list("misfire", ())
    for c in misfire:
        if not 1 <= c <= cylinders.count:
            raise t.error(
                "misfire", f"the engine has cylinders 1 to {cylinders.count}", list(misfire)
            )
    traces = []
    for tt in t.tables("trace"):
        speed = tt.quantity("speed", "speed", check="positive")
        path = tt.input_file("file", "pressure trace")
        tdc = tt.quantity("firing_tdc", "angle", 0.0)
        with tt.context():
            trace = read_pressure_trace(
                path,
                firing_tdc=tdc,
                cycle_angle=CYCLE_ANGLE[cylinders.cycle],
                display=display_path(path),
            )
        tt.finish()
        traces.append(SpeedTrace(speed, trace))
    traces.sort(key=lambda x: x.speed)
    t.finish()
    with t.context():
        return ExcitationSpec(
            cycle=cylinders.cycle,
            load_curve=curve,
            traces=tuple(traces),
            harmonics=table,
            imep=imep,
            misfire=misfire,
        )


def _operating(t: Table | None) -> OperatingRange | None:
    if t is None:
        return None
    pair = t.quantity_list("speed_range", "speed", None, length=2, check="positive")
    rated = t.quantity("rated_speed", "speed", None, check="positive")
    t.speed_range("speed_range", pair, rated)
    t.finish()
    if pair is None:
        if rated is None:
            return None
        raise t.error(
            "speed_range", 'missing; give the operating range, e.g. ["1000 rpm", "2500 rpm"]'
        )
    with t.context():
        return OperatingRange(pair[0], pair[1], rated)


def _rules(
    t: Table | None, model: TorsionModel, operating: OperatingRange | None
) -> RuleSet | None:
    if t is None:
        return None
    rated = t.quantity("rated_speed", "speed", None, check="positive")
    if rated is None and operating is not None:
        rated = operating.rated
    limits: list[ShaftLimit] = []
    labels: dict[tuple[str, ...], list[Any]] = {}
    for s in model.shafts:  # a subdivided shaft is named by its ends: every element checked
        labels.setdefault(tuple(s.segment_of or s.between), []).append(s)
    for st in t.tables("shaft", required=True):
        between = tuple(st.string_list("between", length=2))
        shafts = labels.get(between) or labels.get(between[::-1])
        if shafts is None:
            names = [f"{a} - {b}" for a, b in labels]
            text = f"{between[0]} - {between[1]}"
            raise st.error(
                "between",
                f"no shaft between these masses{did_you_mean(text, names)}",
                list(between),
            )
        if shafts[0].geometry is None:
            raise st.error(
                "between",
                "this shaft has no diameters: give outer_diameter (and inner_diameter) on its "
                "[[shaft]] for the nominal stress",
                list(between),
            )
        strength = st.quantity("tensile_strength", "pressure", check="positive")
        from crankdyn.tvc.limits import DESIGN_FACTORS

        feature = st.string("feature", None, choices=tuple(DESIGN_FACTORS))
        if feature is not None and st.has("design_factor"):
            raise st.error(
                "design_factor",
                "give the design feature or C_K, not both",
                st.data["design_factor"],
            )
        factor = (
            DESIGN_FACTORS[feature]
            if feature is not None
            else st.number("design_factor", 1.0, check="positive", maximum=1.0)
        )
        material = st.string("material", "carbon", choices=("carbon", "alloy"))
        kind = st.string("kind", "intermediate", choices=("intermediate", "thrust", "propeller"))
        cap = st.quantity("tensile_strength_cap", "pressure", None, check="positive")
        st.finish()
        with st.context():
            limits.extend(
                ShaftLimit(tuple(s.between), strength, factor, material, kind, cap, feature)
                for s in shafts
            )
    t.finish()
    with t.context():
        return RuleSet(rated_speed=rated, shafts=tuple(limits))


def _damper(t: Table, model: TorsionModel) -> Damper:
    name = t.string("name", "damper ring")
    at = t.string("at")
    if at not in model.mass_names:
        raise t.error("at", f'no mass named "{at}"{did_you_mean(at, model.mass_names)}', at)
    kind = t.string("kind", choices=("viscous", "tuned"))
    inertia = t.quantity("inertia", "inertia", check="positive")
    mode = t.integer("tune_mode", None, minimum=1)
    stiffness = t.quantity("stiffness", "torsional_stiffness", None, check="positive")
    damping = t.quantity("damping", "torsional_damping", None, check="positive")
    loss = t.number("loss_factor", 0.0, check="nonnegative")
    permissible = t.quantity("permissible_power", "power", None, check="positive")
    limit_source = t.string("limit_source", None)
    if kind == "viscous" and stiffness is not None:
        raise t.error(
            "stiffness", 'a viscous damper has no stiffness (kind = "tuned"?)', t.data["stiffness"]
        )
    if mode is not None:
        for key, value in (("stiffness", stiffness), ("damping", damping)):
            if value is not None:
                raise t.error(
                    key, "is set by tune_mode (the optimum); give one or the other", t.data[key]
                )
        with t.context():
            design = design_damper(model, at, mode, inertia, kind)
        stiffness, damping = design.stiffness, design.damping
    else:
        if damping is None and (kind == "viscous" or loss == 0.0):
            raise t.error("damping", "missing; give the damping, or tune_mode for the optimum")
        if kind == "tuned" and stiffness is None:
            raise t.error(
                "stiffness", "missing; give the rubber's stiffness, or tune_mode for the optimum"
            )
    t.finish()
    with t.context():
        return Damper(
            name, at, inertia, stiffness or 0.0, damping or 0.0, loss, permissible, limit_source
        )


# ---- excitation sources ------------------------------------------------------------------------
_LOAD_DEFAULT_EXPONENT = {"propeller": 2.0, "machine": 0.0, "source": 2.0}


def read_sources(
    t: Table, model: TorsionModel, operating: OperatingRange | None
) -> tuple[HarmonicSource, ...]:
    """The ``[[excitation.propeller]]``, ``[[excitation.machine]]`` and ``[[excitation.source]]``
    entries of an excitation table (docs/torsion-file.md)."""
    out = []
    names: set[str] = set()
    for kind in ("propeller", "machine", "source"):
        for st in t.tables(kind):
            source = _source(st, kind, model, operating)
            if source.name in names:
                raise st.error("name", "another excitation source has this name", source.name)
            names.add(source.name)
            out.append(source)
    return tuple(out)


def _source(
    t: Table, kind: str, model: TorsionModel, operating: OperatingRange | None
) -> HarmonicSource:
    from crankdyn.torsion.sources import HarmonicSource, electric_machine, propeller

    at = t.string("at")
    if at not in model.mass_names:
        raise t.error("at", f'no mass named "{at}"{did_you_mean(at, model.mass_names)}', at)
    ratio = float(model.speed_ratios[model.index(at)])
    name = t.string("name", "")
    load = _load_law(t, kind, ratio, operating)
    table_path = t.path("table", None) if kind == "source" else None
    amplitude_keys = [k for k in ("fractions", "torques") if k in t.data]
    if table_path is not None:
        for key in ("orders", *amplitude_keys, "phases"):
            if key in t.data:
                raise t.error(key, "the table gives the orders, amplitudes and phases", t.data[key])
        if not table_path.is_file():
            raise t.error("table", f"no such table (looked for {table_path})", t.data["table"])
        from crankdyn.io.torsion_tables import read_source_table

        orders, speed, amplitude, phase = read_source_table(table_path, display_path(table_path))
        t.finish()
        with t.context():
            return HarmonicSource(
                at=at,
                orders=orders,
                amplitude=amplitude,
                phase=phase,
                speed=speed,
                load=load,
                kind="source",
                name=name,
            )
    if len(amplitude_keys) != 1:
        raise t.error(
            "fractions" if not amplitude_keys else amplitude_keys[1],
            "give the amplitudes as fractions of the mean torque (fractions) or as torques, "
            "one of them",
            MISSING if not amplitude_keys else t.data[amplitude_keys[1]],
        )
    fractions = torques = None
    if amplitude_keys[0] == "fractions":
        fractions = _numbers(t, "fractions")
        if load is None:
            raise t.error(
                "fractions",
                "fractions of the mean torque need the load: give power or mean_torque (at speed)",
                t.data["fractions"],
            )
    else:
        torques = t.quantity_list("torques", "torque", check="nonnegative")
    # torques is required (never None) when there are no fractions
    count = len(fractions if fractions is not None else torques)  # type: ignore[arg-type]
    phases = t.quantity_list("phases", "angle", None)
    if phases is not None and len(phases) != count:
        raise t.error("phases", f"expected {count} phases, one per amplitude", t.data["phases"])
    with t.context():
        if kind == "propeller":
            blades = t.integer("blades", minimum=1, maximum=100)
            source = propeller(
                at,
                blades,
                fractions=fractions,
                torques=torques,
                phases=phases,
                load=load,
                name=name,
            )
        elif kind == "machine":
            pairs = t.integer("pole_pairs", minimum=1, maximum=1000)
            harmonics = _numbers(t, "harmonics")
            if len(harmonics) != count:
                raise t.error(
                    "harmonics",
                    f"expected {count} electrical harmonics, one per amplitude",
                    t.data["harmonics"],
                )
            source = electric_machine(
                at,
                pairs,
                harmonics,
                fractions=fractions,
                torques=torques,
                phases=phases,
                load=load,
                name=name,
            )
        else:
            # a list here; HarmonicSource makes its arrays of its lists (__post_init__)
            orders = _numbers(t, "orders")  # type: ignore[assignment]
            if len(orders) != count:
                raise t.error(
                    "orders", f"expected {count} orders, one per amplitude", t.data["orders"]
                )
            source = HarmonicSource(
                at=at,
                orders=orders,
                amplitude=torques,
                fraction=fractions,  # type: ignore[arg-type]
                phase=phases,
                load=load,
                kind="source",
                name=name,
            )
    t.finish()
    return source


def _numbers(t: Table, key: str) -> list[float]:
    value = t.raw(key, expected="a list of numbers")
    if (
        not isinstance(value, list)
        or not value
        or any(isinstance(v, bool) or not isinstance(v, (int, float)) for v in value)
    ):
        raise t.error(key, "expected a list of numbers", value)
    numbers = [float(v) for v in value]
    if any(not (v == v and abs(v) != float("inf")) for v in numbers):
        raise t.error(key, "the values must be finite", value)
    if any(v < 0.0 for v in numbers) or (key in ("orders", "harmonics") and min(numbers) <= 0.0):
        raise t.error(
            key, "must be positive" if key != "fractions" else "must not be negative", value
        )
    return numbers


def _load_law(
    t: Table, kind: str, ratio: float, operating: OperatingRange | None
) -> LoadLaw | None:
    """The mean load torque of a source: ``power`` or ``mean_torque`` at ``speed`` (of the
    source's mass; default the model's rated speed times the mass's speed ratio), with the
    ``exponent`` of Q ∝ n^e (2 for propellers and sources, 0 for machines)."""
    from crankdyn.torsion.sources import LoadLaw

    power = t.quantity("power", "power", None, check="nonnegative")
    torque = t.quantity("mean_torque", "torque", None, check="nonnegative")
    speed = t.quantity("speed", "speed", None, check="positive")
    exponent = t.number("exponent", _LOAD_DEFAULT_EXPONENT[kind], minimum=-10.0, maximum=10.0)
    if power is not None and torque is not None:
        raise t.error("mean_torque", "give power or mean_torque, not both", t.data["mean_torque"])
    if power is None and torque is None:
        for key in ("speed", "exponent"):
            if key in t.data:
                raise t.error(
                    key, "belongs to the load law: give power or mean_torque", t.data[key]
                )
        return None
    if speed is None:
        rated = operating.rated if operating is not None else None
        if rated is None:
            raise t.error(
                "speed",
                "missing; give the speed of this mass at that power or torque (or [operating] "
                "rated_speed)",
            )
        speed = rated * ratio
    if power is not None:
        torque = power / speed
    with t.context():
        return LoadLaw(torque=torque, speed=speed, exponent=exponent)
