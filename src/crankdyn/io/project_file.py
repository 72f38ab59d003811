"""The ``[project]`` section of a torsional model file or an engine file: the document control of
the torsional vibration calculation (:class:`crankdyn.project.Project`; ``crankdyn docs tvc``).

Keys (all optional): ``project``, ``document``, ``client``, ``yard``, ``hull``,
``classification``, ``engine_type``, ``engine_serial``, ``mcr_power`` (a power, ``"3000 kW"``),
``mcr_speed`` (a speed, ``"750 rpm"``), ``gearbox``, ``propeller``, ``prepared``, ``checked``,
``approved``, ``date`` (a TOML date or a text) and ``[[project.revision]]`` rows with
``revision``, ``date``, ``description`` and ``by``.
"""

from __future__ import annotations

import dataclasses
import datetime as _dt
from typing import TYPE_CHECKING, Any

from crankdyn.io.schema import Table
from crankdyn.project import Project, Revision

if TYPE_CHECKING:
    from crankdyn.torsion.model import TorsionModel

__all__ = ["TEXT_KEYS", "read_project", "with_project"]

TEXT_KEYS = (
    "project",
    "document",
    "client",
    "yard",
    "hull",
    "classification",
    "engine_type",
    "engine_serial",
    "gearbox",
    "propeller",
    "prepared",
    "checked",
    "approved",
)
"""The keys of ``[project]`` that hold a text (shown as written)."""


def _date(t: Table, key: str) -> str:
    """A date as written: a TOML date (``2026-03-01``) or a text (``"March 2026"``)."""
    value: Any = t.raw(key, None, expected="a date")
    if value is None:
        return ""
    if isinstance(value, (_dt.date, _dt.datetime)):
        return value.isoformat()
    return str(t.string(key))


def read_project(t: Table | None) -> Project | None:
    """A :class:`~crankdyn.project.Project` from ``[project]`` (None when the table is absent).

    Parameters
    ----------
    t : crankdyn.io.schema.Table or None
        The ``[project]`` table (its file name and key path are used in messages), or None.

    Returns
    -------
    crankdyn.project.Project or None
        The document control: texts as written, the rating's power in W and speed in rad/s.

    Raises
    ------
    crankdyn.errors.InputError
        An unknown key (with a did-you-mean), a text key that is not a string, a power or
        speed of the wrong unit or not positive, a revision without its mark; naming the file,
        the key and the value.

    Examples
    --------
    >>> t = Table({"project": {"project": "MV Example", "mcr_speed": "750 rpm",
    ...                        "revision": [{"revision": "A", "description": "first issue"}]}},
    ...           file="line.toml")
    >>> p = read_project(t.table("project"))
    >>> p.project, round(p.mcr_speed, 4), p.revision
    ('MV Example', 78.5398, 'A')
    """
    if t is None:
        return None
    texts = {key: t.string(key, "") for key in TEXT_KEYS}
    power = t.quantity("mcr_power", "power", None, check="positive")
    speed = t.quantity("mcr_speed", "speed", None, check="positive")
    revisions = []
    for rt in t.tables("revision"):
        raw = rt.data.get("revision")
        if isinstance(raw, int) and not isinstance(raw, bool):
            rt.data["revision"] = str(raw)  # revision = 0: the mark "0"
        with rt.context():
            revisions.append(
                Revision(
                    rt.string("revision"),
                    date=_date(rt, "date"),
                    description=rt.string("description", ""),
                    by=rt.string("by", ""),
                )
            )
        rt.finish()
    date = _date(t, "date")
    with t.context():
        project = Project(
            **texts, mcr_power=power, mcr_speed=speed, date=date, revisions=tuple(revisions)
        )
    t.finish()
    return project


def with_project(root: Table, model: TorsionModel | None) -> TorsionModel | None:
    """The model with the file's ``[project]`` (:func:`read_project`) attached; the section is
    read (and checked) even where the file has no torsional model.

    Parameters
    ----------
    root : crankdyn.io.schema.Table
        The file's top-level table.
    model : crankdyn.torsion.model.TorsionModel or None
        The file's torsional model, or None.

    Returns
    -------
    crankdyn.torsion.model.TorsionModel or None
        ``model`` with its ``project``, or ``model`` itself when there is no ``[project]``.
    """
    project = read_project(root.table("project"))
    if project is None or model is None:
        return model
    return dataclasses.replace(model, project=project)
