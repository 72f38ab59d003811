"""The ``[tvc]`` table of a torsional model file or an engine's [torsion] section: the settings
of the torsional vibration calculation, and its ``[[tvc.event]]`` transient events
(docs/tvc.md)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from crankdyn.io.schema import Table
from crankdyn.tvc.limits import CrankshaftLimit
from crankdyn.tvc.rulesets import RULESET_KEYS
from crankdyn.tvc.spec import CONDITION_KINDS, LOADS, PASSAGE_TORQUES, TvcEvent, TvcSpec

if TYPE_CHECKING:
    from crankdyn.torsion.campbell import OperatingRange
    from crankdyn.torsion.model import TorsionModel

__all__ = ["EVENT_RUN_KEYS", "read_tvc", "read_tvc_events"]

EVENT_RUN_KEYS = ("speed", "duration", "harmonics")
"""The keys of a ``[[tvc.event]]`` table that say how the line runs into the event (the others
are the event's own, :mod:`crankdyn.io.event_spec`)."""


def read_tvc(t: Table | None, operating: OperatingRange | None = None) -> TvcSpec | None:
    """A :class:`~crankdyn.tvc.TvcSpec` from ``[tvc]`` (None when the table is absent).

    Keys (docs/tvc.md; quantities are strings with units, e.g. ``"750 rpm"``, converted to SI):
    ``speed_range`` [min, max] and ``speed_ranges.<condition>`` (speeds, rad/s), ``speed_step``
    (rad/s), ``load`` (one of the load laws), ``misfire`` and ``damper_out`` (booleans),
    ``tachometer_tolerance`` (fraction, 0 to 0.19), ``rules`` (the rule set, a key of
    :data:`crankdyn.tvc.rulesets.RULESETS`; the old ``widening`` is refused, naming the
    ``rules`` to write instead), ``engine_torque`` (N m) or
    ``engine_torque_curve`` (rows [speed, torque]: rad/s, N m), ``passage_load`` ("law" or
    "none"), ``source`` and the ``[tvc.crankshaft]`` limits: ``permissible_stress`` or
    ``permissible_torque`` (Pa or N m), ``diameter`` (m), ``stress_concentration`` (-, at least
    1), ``transient_stress`` (Pa), ``transient_torque`` (N m), ``source``.

    Every quantity is held to the plausible range of its role, and every speed range's upper
    end to the rated speed of ``operating`` (:mod:`crankdyn.io.plausibility`; warnings in the
    table's ``warnings``).

    Every condition's speed grid (its range at ``speed_step``) holds at most
    :data:`crankdyn.defaults.MAX_SPEEDS` speeds (100,000, as ``--speeds``), checked here
    before any grid is made.

    Parameters
    ----------
    t
        The ``[tvc]`` table of the file (its file name and key path are used in messages), or
        None when the file has none.
    operating
        The file's ``[operating]`` range (speeds rad/s), the last resort of the TVC's speed
        range; None when it has none.

    Returns
    -------
    TvcSpec or None
        The settings, every quantity in SI (speeds rad/s, torques N m, stresses Pa, lengths
        m); None when ``t`` is None.

    Raises
    ------
    InputError
        On an unknown key, a value of the wrong unit, kind or sign, a choice not in the list,
        the retired key ``widening`` (the rule set's least range replaces it),
        both ``engine_torque`` and ``engine_torque_curve``, a malformed curve, crankshaft
        limits with neither or both of the permissible stress and torque, or a speed grid of
        more than 100,000 speeds (naming ``speed_step``, or the range when the step is the
        default); the error names the file, the key and the value.
    """
    if t is None:
        return None
    values = {}
    rated = operating.rated if operating is not None else None
    pair = t.quantity_list("speed_range", "speed", None, length=2, check="positive")
    t.speed_range("speed_range", pair, rated)
    if pair is not None:
        values["speed_range"] = pair
    rt = t.table("speed_ranges")
    if rt is not None:
        ranges = {}
        for kind in CONDITION_KINDS:
            p = rt.quantity_list(kind, "speed", None, length=2, check="positive")
            rt.speed_range(kind, p, rated)
            if p is not None:
                ranges[kind] = p
        rt.finish()
        values["ranges"] = ranges
    step = t.quantity("speed_step", "speed", None, check="positive")
    if step is not None:
        values["step"] = step
    load = t.string("load", None, choices=LOADS)
    if load is not None:
        values["load"] = load
    for key in ("misfire", "damper_out"):
        if t.has(key):
            values[key] = t.boolean(key)
    tol = t.number("tachometer_tolerance", None, check="nonnegative", maximum=0.19)
    if tol is not None:
        values["tachometer_tolerance"] = tol
    if t.has("widening"):
        raise t.error(
            "widening",
            'retired: the barred-range margins come from the rule set; write rules = "lr" '
            '(Lloyd\'s Register), "kr" (the same least range) or "iacs-m68" (none) '
            "(crankdyn docs tvc)",
            t.data["widening"],
        )
    rules = t.string("rules", None, choices=RULESET_KEYS)
    if rules is not None:
        values["rules"] = rules
    torque = t.quantity("engine_torque", "torque", None, check="positive")
    if torque is not None:
        values["engine_torque"] = torque
    curve = t.raw("engine_torque_curve", None)
    if curve is not None:
        if torque is not None:
            raise t.error(
                "engine_torque_curve", "give engine_torque or engine_torque_curve, not both", curve
            )
        if (
            not isinstance(curve, list)
            or not curve
            or any(not isinstance(row, list) or len(row) != 2 for row in curve)
        ):
            raise t.error(
                "engine_torque_curve",
                'expected rows [speed, torque], e.g. [["300 rpm", "20 kN*m"], ["750 rpm", '
                '"38 kN*m"]]',
                curve,
            )
        speeds = [t.item("engine_torque_curve", r[0], "speed") for r in curve]
        torques = [t.item("engine_torque_curve", r[1], "torque") for r in curve]
        values["engine_torque_curve"] = (speeds, torques)
    passage = t.string("passage_load", None, choices=("law", "none"))
    if passage is not None:
        values["passage_load"] = passage
    _read_conditions(t, values)
    values["source"] = t.string("source", None)
    ct = t.table("crankshaft")
    if ct is not None:
        crank = {
            "stress": ct.quantity("permissible_stress", "pressure", None, check="positive"),
            "torque": ct.quantity("permissible_torque", "torque", None, check="positive"),
            "diameter": ct.quantity("diameter", "length", None, check="positive"),
            "stress_concentration": ct.number("stress_concentration", 1.0, minimum=1.0),
            "transient_stress": ct.quantity("transient_stress", "pressure", None, check="positive"),
            "transient_torque": ct.quantity("transient_torque", "torque", None, check="positive"),
            "source": ct.string("source", None),
        }
        if (crank["stress"] is None) == (crank["torque"] is None):
            raise ct.error(
                "permissible_stress", "give the permissible stress or the permissible torque"
            )
        ct.finish()
        with ct.context():
            values["crankshaft"] = CrankshaftLimit(**crank)
    t.tables("event")  # read with the whole model: read_tvc_events
    t.finish()
    with t.context():
        spec = TvcSpec(**values)
    _check_grids(t, spec, operating)
    return spec


def _read_conditions(t: Table, values: dict) -> None:
    """The keys of the passage torque, the overspeed, declutched and idle conditions."""
    torque = t.string("passage_torque", None, choices=PASSAGE_TORQUES)
    if torque is not None:
        values["passage_torque"] = torque
    for key in ("overspeed", "declutched", "idle"):
        if t.has(key):
            values[key] = t.boolean(key)
    limit = t.number("overspeed_limit", None, check="positive")
    if limit is not None:
        values["overspeed_limit"] = limit
    if t.has("clutch"):
        values["clutch"] = tuple(t.string_list("clutch", length=2))
    idle = t.quantity("idle_speed", "speed", None, check="positive")
    if idle is not None:
        values["idle_speed"] = idle


def read_tvc_events(t: Table, model: TorsionModel) -> tuple[TvcEvent, ...]:
    """The ``[[tvc.event]]`` tables of a ``[tvc]`` table, read with the whole model (its
    masses checked, its defaults read: the only propeller or alternator, the propeller's
    blades, a machine's rated torque; :func:`crankdyn.io.event_spec.event_from_table`), and
    the keys of the run: ``speed`` (the reference speed before the event, default n_0),
    ``duration`` (default the event's) and ``harmonics`` (whether the engine's and the sources'
    harmonic torques act, default true except for a clutch).

    Parameters
    ----------
    t
        The ``[tvc]`` table.
    model
        The whole model (an engine's line joined).

    Returns
    -------
    tuple of TvcEvent
        The events, in the file's order.

    Raises
    ------
    InputError
        As :func:`crankdyn.io.event_spec.event_from_table`, and for a speed or duration that
        is not positive; naming the file, the ``[[tvc.event]] #n`` entry, the key and the value.
    """
    from crankdyn.io.event_spec import event_from_table

    out = []
    for et in t.tables("event"):
        data = dict(et.data)
        run = Table(
            {k: data.pop(k) for k in EVENT_RUN_KEYS if k in data},
            file=et.file,
            name=et.name,
            base_dir=et.base_dir,
        )
        event = event_from_table(
            data, model=model, file=et.file, section=et.name, base_dir=et.base_dir
        )
        speed = run.quantity("speed", "speed", None, check="positive")
        duration = run.quantity("duration", "time", None, check="positive")
        harmonics = run.boolean("harmonics", data.get("kind") != "clutch")
        run.finish()
        with run.context():
            out.append(TvcEvent(event, speed, duration, harmonics))
    names = [e.name for e in out]
    for n, name in enumerate(names):
        if name in names[:n]:
            raise t.error("event", f"two events are named {name!r}: give each its own name", name)
    return tuple(out)


def _check_grids(t: Table, spec: TvcSpec, operating: OperatingRange | None) -> None:
    """Refuse a condition whose speed grid would hold more than ``MAX_SPEEDS`` speeds (as
    ``--speeds`` does), naming ``speed_step`` (or the range, at the default step)."""
    from crankdyn.constants import RPM
    from crankdyn.defaults import MAX_SPEEDS

    ranges = [(f"speed_ranges.{k}", r) for k, r in spec.ranges.items()]
    if spec.speed_range is not None:
        ranges.append(("speed_range", spec.speed_range))
    elif operating is not None:
        ranges.append(("[operating] speed_range", (operating.low, operating.high)))
    for key, (low, high) in ranges:
        # as the grid is made: the steps from the start, and the end when they stop short of it
        count = math.floor((high - low) / spec.step * (1 + 1e-12)) + 1
        count += low + spec.step * (count - 1) < high
        if count <= MAX_SPEEDS:
            continue
        span = f"{low * RPM:g} to {high * RPM:g} rpm"
        if "speed_step" in t.data:
            raise t.error(
                "speed_step",
                f"makes {count:,} speeds over {span} ({key}); at most {MAX_SPEEDS:,}, as "
                f"--speeds (a step of at least {(high - low) / (MAX_SPEEDS - 1) * RPM:.3g} rpm)",
                t.data["speed_step"],
            )
        message = (
            f"{span} at the default step of {spec.step * RPM:g} rpm makes {count:,} speeds; "
            f"at most {MAX_SPEEDS:,}: give a coarser speed_step"
        )
        if key == "speed_range":
            raise t.error(key, message, t.data[key])
        if key.startswith("speed_ranges."):
            raise t.error(key, message, t.data["speed_ranges"][key.partition(".")[2]])
        raise t.error("speed_step", f"missing; the {key} {message}")
