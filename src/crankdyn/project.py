"""The document control of an installation (domain): the project, the yard and hull, the engine's
type, serial number and maximum continuous rating, the gearbox and propeller, the revisions and
who prepared, checked and approved the calculation. A file's ``[project]`` section
(:mod:`crankdyn.io.project_file`; ``crankdyn docs tvc``) fills it; the torsional vibration
calculation's title page shows it (:mod:`crankdyn.report.tvc`). Nothing here enters a
calculation: the numbers of a TVC come from the model, whatever the title page says.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

from crankdyn.constants import RPM
from crankdyn.errors import InputError

__all__ = ["Project", "Revision"]


@dataclass(frozen=True)
class Revision:
    """One row of a document's revision table.

    Parameters
    ----------
    revision : str
        The revision's mark (``"A"``, ``"0"``, ``"1.2"``).
    date : str
        When it was issued (as written, e.g. ``"2026-03-01"``).
    description : str
        What changed.
    by : str
        Who made it.

    Raises
    ------
    crankdyn.errors.InputError
        An empty revision mark (key ``revision``).

    Examples
    --------
    >>> Revision("A", "2026-03-01", "first issue", "J. Smith").revision
    'A'
    """

    revision: str
    date: str = ""
    description: str = ""
    by: str = ""

    def __post_init__(self) -> None:
        if not self.revision.strip():
            raise InputError("a revision needs its mark", key="revision", value=self.revision)


@dataclass(frozen=True)
class Project:
    """The document control of a torsional vibration calculation (module docstring). Every
    field is optional; texts are shown as written.

    Parameters
    ----------
    project : str
        The project's name.
    document : str
        The document's number.
    client : str
        Who the calculation is for (owner, yard, engine builder).
    yard : str
        The shipyard (or plant).
    hull : str
        The hull (newbuilding) number.
    classification : str
        The classification society the calculation is submitted to.
    engine_type : str
        The engine's type designation.
    engine_serial : str
        The engine's serial number.
    mcr_power : float or None
        The maximum continuous rating's power (W), > 0.
    mcr_speed : float or None
        The maximum continuous rating's speed (rad/s), > 0.
    gearbox : str
        The gearbox (maker, type, ratio).
    propeller : str
        The propeller (kind, blades, diameter).
    prepared, checked, approved : str
        Who prepared, checked and approved the calculation.
    date : str
        The document's date (as written).
    revisions : tuple of Revision
        The revision table, oldest first.

    Raises
    ------
    crankdyn.errors.InputError
        A power or speed not positive and finite (key ``mcr_power`` or ``mcr_speed``).

    Examples
    --------
    >>> p = Project(project="MV Example", mcr_power=3.0e6, mcr_speed=750 / RPM,
    ...             revisions=(Revision("A", "2026-03-01", "first issue"),))
    >>> p.revision, p.rows()[1]
    ('A', ('Maximum continuous rating', '3000 kW at 750 rpm'))
    """

    project: str = ""
    document: str = ""
    client: str = ""
    yard: str = ""
    hull: str = ""
    classification: str = ""
    engine_type: str = ""
    engine_serial: str = ""
    mcr_power: float | None = None
    mcr_speed: float | None = None
    gearbox: str = ""
    propeller: str = ""
    prepared: str = ""
    checked: str = ""
    approved: str = ""
    date: str = ""
    revisions: tuple[Revision, ...] = ()

    def __post_init__(self) -> None:
        for key in ("mcr_power", "mcr_speed"):
            value = getattr(self, key)
            if value is not None and not (math.isfinite(value) and value > 0.0):
                raise InputError("must be positive", key=key, value=value)
        object.__setattr__(self, "revisions", tuple(self.revisions))

    @property
    def revision(self) -> str:
        """The current revision's mark (the last row of the revision table), or ``""``."""
        return self.revisions[-1].revision if self.revisions else ""

    @property
    def given(self) -> bool:
        """Whether anything is given."""
        return any(getattr(self, f.name) not in ("", None, ()) for f in fields(self))

    def rows(self) -> list[tuple[str, str]]:
        """The installation's data as (label, text) rows, in the order of a title page: the
        project, yard and hull, the client and the society, the engine with its rating, the
        gearbox and the propeller; rows not given are left out.

        Returns
        -------
        list of (str, str)
            The rows (the power in kW, the speed in rpm).
        """
        rating = ""
        if self.mcr_power is not None:
            rating = f"{self.mcr_power / 1e3:.6g} kW"
        if self.mcr_speed is not None:
            speed = f"{self.mcr_speed * RPM:.6g} rpm"
            rating = f"{rating} at {speed}" if rating else speed
        yard = " / ".join(x for x in (self.yard, f"hull {self.hull}" if self.hull else "") if x)
        serial = f"serial {self.engine_serial}" if self.engine_serial else ""
        engine = ", ".join(x for x in (self.engine_type, serial) if x)
        rows = [
            ("Project", self.project),
            ("Yard / hull", yard),
            ("Client", self.client),
            ("Classification society", self.classification),
            ("Engine", engine),
            ("Maximum continuous rating", rating),
            ("Gearbox", self.gearbox),
            ("Propeller", self.propeller),
        ]
        return [(label, text) for label, text in rows if text]

    def signatures(self) -> list[tuple[str, str]]:
        """(role, name) of who prepared, checked and approved the calculation.

        Returns
        -------
        list of (str, str)
            Three rows; a name not given is ``""`` (a field to sign).
        """
        return [
            ("Prepared", self.prepared),
            ("Checked", self.checked),
            ("Approved", self.approved),
        ]
