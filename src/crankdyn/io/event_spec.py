"""Transient events from a table of keys: a TOML table (``[[tvc.event]]``) or the command line's
``--event KIND -p KEY=VALUE`` (:mod:`crankdyn.torsion.events`).

Every event has a ``kind`` (:data:`EVENT_KINDS`), an optional ``name`` (the verdicts'
condition) and ``severity`` (``normal`` or ``exceptional``), and the keys of its kind
(quantities with their units, as everywhere: ``torque = "60 kN*m"``, ``rise_time = "0.5 s"``):

- ``clutch``: ``between`` (the clutch element's two masses), ``torque``, ``rise_time``,
  ``speeds`` (the halves' speeds), ``start``, ``drive_torque``, ``drive_at``; the engine's
  speed governor (:class:`crankdyn.torsion.event_governor.Governor`): ``governor`` (true or
  false; default true where a torque curve is known), ``torque_curve`` (a list of [speed,
  torque] pairs; default the model's ``[tvc] engine_torque_curve``), ``set_speed`` (default
  the engine's speed before the event), ``governor_gain``, ``governor_integral_time``,
  ``governor_droop``, ``governor_sample_time`` (defaults: :mod:`crankdyn.defaults`);
- ``short-circuit``: ``at`` (default the model's only alternator or motor), ``phases`` (2 or 3),
  ``rated_torque`` (default the load law's torque at the machine), ``line_frequency``, ``xd2``,
  ``xd1``, ``xd`` (per unit), ``td2``, ``td1``, ``ta``, ``power_factor``, ``voltage``,
  ``angle``, ``start``, ``clearing_time``;
- ``ice``: ``at`` (default the model's only propeller), ``blades`` (default the propeller
  source's), ``case``, and ``q_max`` or the rule's ``ice_class``, ``diameter``,
  ``hub_diameter``, ``pitch``, ``thickness``, ``bollard_speed`` (and ``ducted``);
  ``revolutions`` (default the class's N_Q), ``start``;
- ``start``, ``stop``, ``emergency-stop``, ``ramp``: ``start_speed``, ``end_speed``,
  ``ramp_time``, ``governor_time``, ``hold``, ``brake_torque``, ``load``, ``torque_curve``
  (a list of [speed, torque] pairs);
- ``step``: ``at``, ``torque``, ``start``, ``rise_time``;
- ``table``: ``at``, ``file`` (a CSV torque history, :mod:`crankdyn.io.event_tables`).
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from crankdyn.errors import did_you_mean
from crankdyn.io.schema import Table
from crankdyn.torsion.event_governor import (
    GOVERNOR_DROOP,
    GOVERNOR_GAIN,
    GOVERNOR_INTEGRAL_TIME,
    GOVERNOR_SAMPLE_TIME,
    Governor,
)
from crankdyn.torsion.events import (
    SEVERITIES,
    ClutchEngagement,
    IceImpact,
    ShortCircuit,
    SpeedChange,
    StepTorque,
    TabulatedTorque,
)
from crankdyn.torsion.sources import HarmonicSource

if TYPE_CHECKING:
    from crankdyn.torsion.events import Event
    from crankdyn.torsion.model import TorsionModel

__all__ = ["EVENT_KINDS", "SPEED_KEYS", "event_from_table"]

EVENT_KINDS = (
    "clutch",
    "short-circuit",
    "ice",
    "start",
    "stop",
    "emergency-stop",
    "ramp",
    "step",
    "table",
)
"""The kinds of events a table may name."""

SPEED_KEYS = ("speeds", "start_speed", "end_speed", "bollard_speed", "set_speed")
"""The keys that hold speeds (the command line reads a bare number there in rpm)."""


def _mass(t: Table, key: str, model: TorsionModel | None, roles: tuple[str, ...]) -> str:
    """A mass name (checked against the model), or the model's only mass of ``roles``."""
    if t.has(key):
        name = t.string(key)
        if model is not None and name not in model.mass_names:
            raise t.error(
                key, f"no mass named {name!r}{did_you_mean(name, model.mass_names)}", name
            )
        return str(name)
    found = [] if model is None else [m.name for m in model.masses if m.role in roles]
    if len(found) != 1:
        raise t.error(key, f"missing: name the mass (the model has {len(found)} {roles[0]}s)")
    return found[0]


def _pair(t: Table, key: str) -> tuple[str, str]:
    """Two names: a list or a comma-separated text."""
    value = t.raw(key, expected="two mass names")
    items = value.split(",") if isinstance(value, str) else value
    if not isinstance(items, list | tuple) or len(items) != 2:
        raise t.error(key, "expected two mass names", value)
    names = [str(v).strip() for v in items]
    return names[0], names[1]


def _common(t: Table) -> dict[str, Any]:
    out: dict[str, Any] = {}
    name = t.string("name", None)
    if name is not None:
        out["name"] = name
    severity = t.string("severity", None, choices=SEVERITIES)
    if severity is not None:
        out["severity"] = severity
    return out


def _governor(t: Table, model: TorsionModel | None) -> Governor | None:
    """The clutch's engine governor (module docstring), or None."""
    curve: Any = _curve(t)
    if curve is None and model is not None and model.tvc is not None:
        curve = model.tvc.engine_torque_curve
    on = t.boolean("governor", curve is not None)
    keys = ("set_speed", "governor_gain", "governor_integral_time", "governor_droop",
            "governor_sample_time")  # fmt: skip
    if not on:
        given = [k for k in keys if t.has(k)]
        if given:
            raise t.error(given[0], "a governor setting without a governor (governor = false)")
        return None
    if curve is None:
        raise t.error(
            "torque_curve",
            "missing: the governed engine's torque-speed curve (or the model's [tvc] "
            "engine_torque_curve); a governor is never unlimited",
        )
    return Governor(
        curve,
        set_speed=t.quantity("set_speed", "speed", None, check="positive"),
        gain=t.number("governor_gain", GOVERNOR_GAIN, check="positive"),
        integral_time=t.quantity(
            "governor_integral_time", "time", GOVERNOR_INTEGRAL_TIME, check="positive"
        ),
        droop=t.number("governor_droop", GOVERNOR_DROOP, check="nonnegative"),
        sample_time=t.quantity(
            "governor_sample_time", "time", GOVERNOR_SAMPLE_TIME, check="positive"
        ),
    )


def _clutch(t: Table, model: TorsionModel | None) -> Event:
    return ClutchEngagement(
        _pair(t, "between"),
        t.quantity("torque", "torque", check="positive"),
        t.quantity("rise_time", "time", 0.0, check="nonnegative"),
        speeds=tuple(t.quantity_list("speeds", "speed", length=2)),
        start=t.quantity("start", "time", 0.0, check="nonnegative"),
        drive_torque=t.quantity("drive_torque", "torque", 0.0),
        drive_at=t.string("drive_at", None),
        governor=_governor(t, model),
        **_common(t),
    )


def _short_circuit(t: Table, model: TorsionModel | None) -> Event:
    at = _mass(t, "at", model, ("alternator", "motor"))
    rated = t.quantity("rated_torque", "torque", None, check="positive")
    if rated is None and model is not None:
        laws = [s.load for s in model.sources if getattr(s, "at", None) == at and s.load]
        if laws and laws[0].torque:
            rated = laws[0].torque
    if rated is None:
        raise t.error("rated_torque", "missing: the generator's rated torque")
    return ShortCircuit(
        at,
        rated_torque=rated,
        line_frequency=t.quantity("line_frequency", "frequency", check="positive"),
        xd2=t.number("xd2", check="positive"),
        xd1=t.number("xd1", check="positive"),
        xd=t.number("xd", check="positive"),
        td2=t.quantity("td2", "time", check="positive"),
        td1=t.quantity("td1", "time", check="positive"),
        ta=t.quantity("ta", "time", check="positive"),
        phases=t.integer("phases", 3),
        power_factor=t.number("power_factor", 0.8),
        voltage=t.number("voltage", 1.0, check="positive"),
        angle=t.quantity("angle", "angle", 0.0),
        start=t.quantity("start", "time", 0.0, check="nonnegative"),
        clearing_time=t.quantity("clearing_time", "time", None, check="positive"),
        **_common(t),
    )


def _ice(t: Table, model: TorsionModel | None) -> Event:
    at = _mass(t, "at", model, ("propeller",))
    blades = t.integer("blades", None)
    if blades is None and model is not None:  # a propeller source's first blade order
        found = [
            round(float(min(s.orders)))
            for s in model.sources
            if isinstance(s, HarmonicSource) and s.at == at and s.kind == "propeller"
        ]
        blades = found[0] if found else None
    if blades is None:
        raise t.error("blades", "missing: the propeller's number of blades")
    case = t.integer("case", 1)
    start = t.quantity("start", "time", 0.0, check="nonnegative")
    common = _common(t)
    if t.has("q_max"):
        return IceImpact(
            at,
            q_max=t.quantity("q_max", "torque", check="positive"),
            blades=blades,
            case=case,
            revolutions=t.number("revolutions", 3.0, check="positive"),
            start=start,
            **common,
        )
    event = IceImpact.from_rule(
        at,
        ice_class=t.string("ice_class"),
        diameter=t.quantity("diameter", "length", check="positive"),
        hub_diameter=t.quantity("hub_diameter", "length", check="nonnegative"),
        pitch=t.quantity("pitch", "length", check="positive"),
        thickness=t.quantity("thickness", "length", check="positive"),
        speed=t.quantity("bollard_speed", "speed", check="positive"),
        blades=blades,
        case=case,
        ducted=t.boolean("ducted", False),
        start=start,
    )
    if t.has("revolutions"):
        common["revolutions"] = t.number("revolutions", check="positive")
    from dataclasses import replace

    return replace(event, **common) if common else event


def _curve(t: Table) -> tuple[list[float], list[float]] | None:
    value = t.raw("torque_curve", None, expected="a list of [speed, torque] pairs")
    if value is None:
        return None
    if not isinstance(value, list) or not all(isinstance(p, list) and len(p) == 2 for p in value):
        raise t.error("torque_curve", "expected a list of [speed, torque] pairs", value)
    speeds = [t.item("torque_curve", p[0], "speed") for p in value]
    torques = [t.item("torque_curve", p[1], "torque") for p in value]
    return speeds, torques


def _speed_change(kind: str) -> Any:
    def build(t: Table, model: TorsionModel | None) -> Event:
        return SpeedChange(
            kind.replace("-", " "),
            t.quantity("start_speed", "speed", check="nonnegative"),
            t.quantity("end_speed", "speed", check="nonnegative"),
            ramp_time=t.quantity("ramp_time", "time", 0.0, check="nonnegative"),
            governor_time=t.quantity("governor_time", "time", 0.5, check="positive"),
            torque_curve=_curve(t),
            hold=t.quantity("hold", "time", 0.0, check="nonnegative"),
            brake_torque=t.quantity("brake_torque", "torque", 0.0, check="nonnegative"),
            load=t.boolean("load", True),
            **_common(t),
        )

    return build


def _step(t: Table, model: TorsionModel | None) -> Event:
    return StepTorque(
        _mass(t, "at", model, ()),
        t.quantity("torque", "torque"),
        start=t.quantity("start", "time", 0.0, check="nonnegative"),
        rise_time=t.quantity("rise_time", "time", 0.0, check="nonnegative"),
        **_common(t),
    )


def _table(t: Table, model: TorsionModel | None) -> Event:
    at = _mass(t, "at", model, ())
    path = t.input_file("file", "torque history")
    common = _common(t)
    return TabulatedTorque.from_file(
        path, at, name=common.get("name"), severity=common.get("severity", "normal")
    )


_BUILDERS = {
    "clutch": _clutch,
    "short-circuit": _short_circuit,
    "ice": _ice,
    "start": _speed_change("start"),
    "stop": _speed_change("stop"),
    "emergency-stop": _speed_change("emergency-stop"),
    "ramp": _speed_change("ramp"),
    "step": _step,
    "table": _table,
}


def event_from_table(
    data: Mapping[str, Any],
    *,
    model: TorsionModel | None = None,
    file: str | None = None,
    section: str = "[event]",
    base_dir: Path | None = None,
) -> Event:
    """The event a table describes (module docstring).

    Parameters
    ----------
    data : mapping
        The table's keys and values (TOML values, or the command line's texts).
    model : crankdyn.torsion.model.TorsionModel or None
        The model the event acts on: its masses are checked, and its defaults read (the only
        propeller or alternator, the propeller's blades, a machine's rated torque).
    file : str or None
        The file the table is in, for messages.
    section : str
        The table's name in messages (``"[[tvc.event]]"``).
    base_dir : pathlib.Path or None
        The folder a ``file`` key is relative to.

    Returns
    -------
    Event
        The event (:mod:`crankdyn.torsion.events`).

    Raises
    ------
    InputError
        One line naming the file, the section's key and the value: an unknown kind or key
        (with the nearest), a missing key, a value of the wrong unit or sign, an unknown mass.

    Examples
    --------
    >>> e = event_from_table({"kind": "step", "at": "flywheel", "torque": "2 kN*m"})
    >>> e.at, e.value
    ('flywheel', 2000.0)
    """
    t = Table(dict(data), file=file, name=section, base_dir=base_dir)
    kind = t.string("kind", choices=EVENT_KINDS)
    with t.context():
        event = _BUILDERS[kind](t, model)
    t.finish(also_known=("kind",))
    return event
