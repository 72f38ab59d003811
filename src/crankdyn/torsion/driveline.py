"""Drivelines from parts: an engine's crank train joined to shaft lines, several engines on one
gearbox (domain).

A shaft line (couplings, gearbox, shafts, propeller or alternator) is a model of its own, and an
engine's equivalent system another; :func:`join` bolts a mass of one to a mass of the other (a
rigid joint: the two masses become one degree of freedom and their inertias add, like a rigid
gear mesh of ratio 1 that keeps the sense of rotation). So one engine file can drive several
lines and one line serve several engines (docs/torsion-file.md: ``[torsion] shaft_line`` and a
model file's ``[[engine]]`` entries). :func:`rename` prefixes the names of a model's masses, so
that two copies of a model (two identical engines on a twin-input gearbox) can be joined.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

from crankdyn.errors import InputError
from crankdyn.plausibility import merge_warnings
from crankdyn.torsion.elements import GROUND, Gear
from crankdyn.torsion.model import TorsionModel

if TYPE_CHECKING:
    from crankdyn.torsion.sources import EngineSource, HarmonicSource

__all__ = ["join", "rename", "strip_cylinders"]


def _renamed(name: str, mapping: dict[str, str]) -> str:
    """``name`` through ``mapping`` (unchanged when not in it; ``"ground"`` never renamed)."""
    return mapping.get(name, name) if name != GROUND else name


def _rename_pair(pair: tuple[str, str], mapping: dict[str, str]) -> tuple[str, str]:
    """The two ends of a shaft or gear through ``mapping``."""
    return _renamed(pair[0], mapping), _renamed(pair[1], mapping)


def rename(model: TorsionModel, prefix: str) -> TorsionModel:
    """The model with ``prefix`` before every mass and damper-ring name (and every reference to
    them: shafts, gears, dampers, sources, rule checks).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model.
    prefix : str
        Text put before every name (e.g. ``"port "``); empty: the model unchanged.

    Returns
    -------
    crankdyn.torsion.model.TorsionModel
        The renamed model (same values; ``"ground"`` stays ``"ground"``).

    Examples
    --------
    >>> from crankdyn.torsion.model import TorsionModel
    >>> line = TorsionModel.chain_of([1.0, 2.0], [5.0], ground_right=3.0)
    >>> renamed = rename(line, "port ")
    >>> renamed.mass_names, [s.between for s in renamed.shafts]
    (('port 1', 'port 2'), [('port 1', 'port 2'), ('port 2', 'ground')])
    """
    if not prefix:
        return model
    mapping = {m.name: f"{prefix}{m.name}" for m in model.masses}
    mapping.update({d.name: f"{prefix}{d.name}" for d in model.dampers})
    masses = tuple(dataclasses.replace(m, name=mapping[m.name]) for m in model.masses)
    shafts = tuple(
        dataclasses.replace(
            s,
            between=_rename_pair(s.between, mapping),
            segment_of=None if s.segment_of is None else _rename_pair(s.segment_of, mapping),
        )
        for s in model.shafts
    )
    gears = tuple(
        dataclasses.replace(g, between=_rename_pair(g.between, mapping)) for g in model.gears
    )
    dampers = tuple(
        dataclasses.replace(d, name=mapping[d.name], at=mapping[d.at]) for d in model.dampers
    )
    sources = tuple(_rename_source(s, mapping) for s in model.sources)
    rules = model.rules
    if rules is not None:
        rules = dataclasses.replace(
            rules,
            shafts=tuple(
                dataclasses.replace(r, between=_rename_pair(r.between, mapping))
                for r in rules.shafts
            ),
        )
    return dataclasses.replace(
        model,
        masses=masses,
        shafts=shafts,
        gears=gears,
        dampers=dampers,
        sources=sources,
        rules=rules,
    )


def _rename_source(
    source: HarmonicSource | EngineSource, mapping: dict[str, str]
) -> HarmonicSource | EngineSource:
    """An excitation source acting on the renamed masses."""
    from crankdyn.torsion.sources import EngineSource

    if isinstance(source, EngineSource):
        return dataclasses.replace(
            source, cylinders=tuple((c, mapping.get(m, m)) for c, m in source.cylinders)
        )
    return dataclasses.replace(source, at=mapping.get(source.at, source.at))


def strip_cylinders(model: TorsionModel) -> tuple[TorsionModel, tuple[tuple[int, str], ...]]:
    """The model with no cylinders on its masses, and the (cylinder, mass) pairs removed (for an
    engine that becomes an :class:`~crankdyn.torsion.sources.EngineSource` of a larger model).

    Parameters
    ----------
    model : crankdyn.torsion.model.TorsionModel
        The model (an engine's equivalent system).

    Returns
    -------
    stripped : crankdyn.torsion.model.TorsionModel
        The model with no cylinders on its masses.
    pairs : tuple of (int, str)
        (cylinder number, mass name) of every cylinder removed, in listing order.

    Examples
    --------
    >>> from crankdyn.torsion.elements import Mass, Shaft
    >>> from crankdyn.torsion.model import TorsionModel
    >>> engine = TorsionModel(
    ...     masses=(Mass("throw 1", 1.0, cylinders=(1,)), Mass("throw 2", 1.0, cylinders=(2,))),
    ...     shafts=(Shaft(("throw 1", "throw 2"), 1e6),),
    ... )
    >>> stripped, pairs = strip_cylinders(engine)
    >>> pairs, stripped.cylinder_dofs
    (((1, 'throw 1'), (2, 'throw 2')), {})
    """
    pairs = tuple((c, m.name) for m in model.masses for c in m.cylinders)
    masses = tuple(dataclasses.replace(m, cylinders=()) for m in model.masses)
    return dataclasses.replace(model, masses=masses), pairs


def join(
    first: TorsionModel,
    second: TorsionModel,
    at_first: str,
    at_second: str,
    *,
    name: str | None = None,
) -> TorsionModel:
    """``first`` and ``second`` joined rigidly at ``at_first`` (a mass of the first) and
    ``at_second`` (a mass of the second); the first model's excitation, operating range and
    rated speed prevail, the sources, dampers, rule checks and input warnings of both are kept.

    The joint is a rigid gear of ratio 1 that keeps the sense of rotation (``joint=True``): the
    two masses become one degree of freedom and their inertias add (module docstring).

    Parameters
    ----------
    first, second : crankdyn.torsion.model.TorsionModel
        The two models (e.g. an engine and a shaft line); their mass and damper names must
        differ (:func:`rename` gives one a prefix).
    at_first, at_second : str
        The mass of ``first`` and the mass of ``second`` bolted together.
    name : str or None
        Name of the joined model; default ``"<first> + <second>"``.

    Returns
    -------
    crankdyn.torsion.model.TorsionModel
        The driveline: the masses of ``first`` then those of ``second``.

    Raises
    ------
    crankdyn.errors.InputError
        For an unknown joining mass (key ``mass``, the name as value), or a name used in both
        models (key ``name``, the name as value).

    Examples
    --------
    >>> from crankdyn.torsion.model import TorsionModel
    >>> engine = rename(TorsionModel.chain_of([1.0, 4.0], [2e6], name="engine"), "e")
    >>> line = rename(TorsionModel.chain_of([0.5, 9.0], [1e5], name="line"), "l")
    >>> drive = join(engine, line, "e2", "l1")
    >>> drive.name, drive.dof_names
    ('engine + line', ('e1', 'e2 + l1', 'l2'))
    >>> drive.dof_inertia.tolist()
    [1.0, 4.5, 9.0]
    """
    first.index(at_first)
    second.index(at_second)
    names = set(first.mass_names) | {d.name for d in first.dampers}
    clash = next(
        (n for n in (*second.mass_names, *(d.name for d in second.dampers)) if n in names), None
    )
    if clash is not None:
        raise InputError(
            f'"{clash}" is the name of a mass in both models; give the line (or engine) a '
            "prefix, or rename the mass",
            key="name",
            value=clash,
        )
    joint = Gear((at_first, at_second), 1.0, direction="same", joint=True)
    rules = first.rules
    other = second.rules
    if other is not None:
        if rules is None:
            rules = other
        else:
            rules = dataclasses.replace(
                rules,
                rated_speed=rules.rated_speed
                if rules.rated_speed is not None
                else other.rated_speed,
                shafts=rules.shafts + other.shafts,
            )
    return TorsionModel(
        masses=first.masses + second.masses,
        shafts=first.shafts + second.shafts,
        gears=first.gears + second.gears + (joint,),
        name=name or f"{first.name} + {second.name}",
        source=first.source,
        excitation=first.excitation,
        dampers=first.dampers + second.dampers,
        rules=rules,
        operating=first.operating if first.operating is not None else second.operating,
        sources=first.sources + second.sources,
        engine=first.engine,
        tvc=first.tvc if first.tvc is not None else second.tvc,
        input_warnings=merge_warnings(first.input_warnings, second.input_warnings),
    )
