"""The mass-elastic table as CSV: read and write a chain model in the form engine builders hand
it over (one row per mass, from the free end, with the connection to the next mass).

Columns (the header names the unit of every quantity, as every crankdyn CSV does; only ``name``,
``inertia`` and ``stiffness`` are required)::

    name, inertia [kg*m^2], damping [N*m*s/rad], cylinders, stiffness [N*m/rad],
    shaft_damping [N*m*s/rad], loss_factor, outer_diameter [mm], inner_diameter [mm],
    gear_ratio, gear_direction, ground_stiffness [N*m/rad]

Row i describes mass i (its inertia, absolute damping, the cylinders acting on it, a grounded
shaft's stiffness) and its connection to mass i + 1: a shaft (``stiffness`` with its relative
damping, loss factor and diameters), a rigid gear mesh (``gear_ratio`` n_(i+1)/n_i and
``gear_direction`` ``opposite`` or ``same``, no stiffness) or an elastic mesh (both; the
stiffness referred to mass i). The last row has no connection. ``cylinders`` holds the cylinder
numbers separated by spaces. Written values are the actual (not reflected) ones; a coupling is
written as a shaft of its model stiffness and loss factor psi / 2 pi (its catalogue data stay in
the model file). Every number read is held to the plausible range of its column's role
(:mod:`crankdyn.io.plausibility`): the model carries the warnings as ``input_warnings``, each
naming the file, the line, the column and the cell.
"""

from __future__ import annotations

import io
from collections.abc import Mapping, Sequence
from pathlib import Path

from crankdyn.display import csv_text, printable
from crankdyn.errors import InputError, did_you_mean
from crankdyn.io.csv_tables import cell_value, read_csv_table, split_header_unit, unit_factor
from crankdyn.io.plausibility import check_input
from crankdyn.plausibility import InputWarning
from crankdyn.torsion.elements import GEAR_DIRECTIONS, GROUND, Gear, Mass, Shaft, ShaftGeometry
from crankdyn.torsion.model import TorsionModel

__all__ = ["mass_elastic_csv", "read_mass_elastic"]

_COLUMNS = {  # name: (kind or None for plain, unit written)
    "name": ("text", None),
    "inertia": ("inertia", "kg*m^2"),
    "damping": ("torsional_damping", "N*m*s/rad"),
    "cylinders": ("text", None),
    "stiffness": ("torsional_stiffness", "N*m/rad"),
    "shaft_damping": ("torsional_damping", "N*m*s/rad"),
    "loss_factor": ("ratio", None),
    "outer_diameter": ("length", "mm"),
    "inner_diameter": ("length", "mm"),
    "gear_ratio": ("ratio", None),
    "gear_direction": ("text", None),
    "ground_stiffness": ("torsional_stiffness", "N*m/rad"),
}
_REQUIRED = ("name", "inertia", "stiffness")


def _g(value: float) -> str:
    return f"{value:.10g}"


def mass_elastic_csv(model: TorsionModel) -> str:
    """The mass-elastic table of a chain model (module docstring) as CSV text. Branched models
    and shafts that skip a mass are refused in one line.

    Parameters
    ----------
    model
        A chain model, its masses listed from the free end.

    Returns
    -------
    str
        The CSV text: a comment line, the header with units (inertias kg*m^2, stiffnesses
        N*m/rad, dampings N*m*s/rad, diameters mm) and one row per mass, numbers to 10
        significant digits.

    Raises
    ------
    InputError
        For a branched model, a mass with two grounded shafts, or connections that do not join
        neighbouring masses in listing order (``key="model"``, ``"shaft"`` or ``"between"``,
        with the value), naming the model's file (``model.source``).
    """
    try:
        links, ground = _connections(model)
    except InputError as exc:  # named after the model's file, as it was read
        raise exc.within(file=model.source) from None
    return _table(model, links, ground)


def _connections(
    model: TorsionModel,
) -> tuple[dict[int, Shaft | Gear], dict[int, float]]:
    """The connection from each row to the next and each row's grounded stiffness (N m/rad)."""
    if not model.is_chain:
        raise InputError(
            f'the mass-elastic table holds a chain and the model branches at "{model.junction}"',
            key="model",
            value=model.name,
        )
    names = model.mass_names
    index = {n: i for i, n in enumerate(names)}
    links: dict[int, Shaft | Gear] = {}
    ground: dict[int, float] = {}
    for s in model.shafts:
        if s.grounded:
            i = index[s.between[1] if s.between[0] == GROUND else s.between[0]]
            if i in ground:
                raise InputError(f'mass "{names[i]}" has two grounded shafts', key="shaft")
            assert s.stiffness is not None  # a built Shaft has its stiffness (type checker)
            ground[i] = s.stiffness
            continue
        _link(links, index, s, names)
    for g in model.gears:
        _link(links, index, g, names)
    if len(links) != len(names) - 1:
        raise InputError(
            "the mass-elastic table needs the masses listed in chain order, each joined to the "
            "next by one shaft or gear",
            key="model",
            value=model.name,
        )
    return links, ground


def _table(model: TorsionModel, links: dict[int, Shaft | Gear], ground: dict[int, float]) -> str:
    """The CSV text of a chain's rows (:func:`mass_elastic_csv`)."""
    buffer = io.StringIO()
    buffer.write(
        f"# mass-elastic table of {printable(model.name)} (crankdyn); one row per mass, from the "
        "free end, with the connection to the next mass\n"
    )
    header = [name if unit is None else f"{name} [{unit}]" for name, (_k, unit) in _COLUMNS.items()]
    rows = [header]
    for i, m in enumerate(model.masses):
        link = links.get(i)
        row = {
            "name": m.name,
            "inertia": _g(m.inertia),
            "damping": _g(m.damping) if m.damping else "",
            "cylinders": " ".join(str(c) for c in m.cylinders),
            "ground_stiffness": _g(ground[i]) if i in ground else "",
        }
        if isinstance(link, Gear):
            assert link.ratio is not None  # a built Gear has its ratio (type checker)
            row["gear_ratio"] = _g(link.ratio)
            row["gear_direction"] = link.direction
        elif isinstance(link, Shaft):
            assert link.stiffness is not None  # a built Shaft has its stiffness (type checker)
            row["stiffness"] = _g(link.stiffness)
            row["shaft_damping"] = _g(link.damping) if link.damping else ""
            row["loss_factor"] = _g(link.loss_factor) if link.loss_factor else ""
            if link.geometry is not None:
                row["outer_diameter"] = _g(link.geometry.outer_diameter * 1e3)
                if link.geometry.inner_diameter:
                    row["inner_diameter"] = _g(link.geometry.inner_diameter * 1e3)
            if link.is_mesh:
                row["gear_ratio"] = _g(link.ratio)
                row["gear_direction"] = "opposite" if link.direction < 0 else "same"
        rows.append([row.get(name, "") for name in _COLUMNS])
    buffer.write(csv_text(rows))  # RFC 4180 quoting: a name with a comma, a quote, a leading #
    return buffer.getvalue()


def _link(
    links: dict[int, Shaft | Gear],
    index: Mapping[str, int],
    element: Shaft | Gear,
    names: Sequence[str],
) -> None:
    a, b = index[element.between[0]], index[element.between[1]]
    if abs(a - b) != 1:
        raise InputError(
            f'"{element.between[0]}" - "{element.between[1]}" does not join neighbouring rows: '
            "list the masses in chain order",
            key="between",
            value=list(element.between),
        )
    if a > b:
        raise InputError(
            f'"{element.between[0]}" - "{element.between[1]}" runs against the listing order: '
            "give it from the earlier mass to the later",
            key="between",
            value=list(element.between),
        )
    if a in links:
        raise InputError(
            f'two connections join "{names[a]}" to "{names[b]}": the table has one per row',
            key="between",
            value=list(element.between),
        )
    links[a] = element


def read_mass_elastic(
    path: str | Path, display: str | None = None, *, name: str | None = None
) -> TorsionModel:
    """A chain :class:`TorsionModel` from a mass-elastic CSV table (module docstring).

    Parameters
    ----------
    path
        The CSV file.
    display
        How to name the file in messages (default: the path as given).
    name
        The model's name (default: the file's stem).

    Returns
    -------
    TorsionModel
        The chain, every quantity in SI (inertias kg m^2, stiffnesses N m/rad, dampings
        N m s/rad, diameters m; gear ratios and loss factors bare).

    Raises
    ------
    InputError
        On an unreadable or empty file, an unknown or missing column, a missing or unknown
        unit (or a unit on a plain column), a non-numeric cell, bad cylinder numbers or gear
        direction, a missing connection or one after the last row, or a model the
        TorsionModel refuses; naming the file, the line and column (``key``) and the cell.
    """
    table = read_csv_table(path, display=display, what="mass-elastic table")
    file = table.name
    rows = _Cells(table.rows, _header_columns(table.header, file), table.header, file)
    if not table.rows:
        raise InputError("the mass-elastic table has no rows", file=file)
    masses: list[Mass] = []
    shafts: list[Shaft] = []
    gears: list[Gear] = []
    count = len(table.rows)
    for r in range(count):
        line, _label = rows.cell(r, "name")
        try:
            _read_row(rows, r, count, masses, shafts, gears)
        except InputError as exc:  # the line and the column
            key = f"line {line} {exc.key or ''}".strip()
            if exc.has_value:
                raise InputError(exc.message, file=file, key=key, value=exc.value) from None
            raise InputError(exc.message, file=file, key=key) from None
    try:
        return TorsionModel(
            masses=tuple(masses),
            shafts=tuple(shafts),
            gears=tuple(gears),
            name=name or Path(file).stem,
            source=file,
            input_warnings=tuple(rows.warnings),
        )
    except InputError as exc:
        raise exc.within(file=file) from None


def _header_columns(header: Sequence[str], file: str) -> dict[str, tuple[int, float]]:
    """Column name -> (index, factor to SI) of a mass-elastic table's header (module
    docstring): InputError naming the header cell for an unknown column, a unit on a plain
    column, a missing or unknown unit, or a missing required column."""
    columns: dict[str, tuple[int, float]] = {}
    for i, header_cell in enumerate(header):
        whole = header_cell.strip().lower().replace(" ", "_")
        if whole in _COLUMNS and _COLUMNS[whole][0] in ("text", "ratio"):
            columns[whole] = (i, 1.0)
            continue
        base, unit = split_header_unit(header_cell)
        key = base.strip().lower().replace(" ", "_")
        if key not in _COLUMNS:
            raise InputError(
                f"unknown column{did_you_mean(key, list(_COLUMNS))}",
                file=file,
                key="header",
                value=header_cell,
            )
        kind = _COLUMNS[key][0]
        if kind in ("text", "ratio"):
            if unit:
                raise InputError(
                    "this column takes no unit", file=file, key="header", value=header_cell
                )
            columns[key] = (i, 1.0)
            continue
        factor = unit_factor(
            header_cell,
            unit,
            kind,
            file,
            missing="the column must name its unit, e.g. inertia [kg*m^2]",
            unknown="unknown unit {unit}",
        )
        columns[key] = (i, factor)
    for key in _REQUIRED:
        if key not in columns:
            raise InputError(
                f"expected a column {key!r}", file=file, key="header", value=",".join(header)
            )
    return columns


class _Cells:
    """The cells of a mass-elastic table's rows by column name: text, or numbers in SI."""

    def __init__(
        self,
        rows: Sequence[tuple[int, Sequence[str]]],
        columns: dict[str, tuple[int, float]],
        header: Sequence[str] = (),
        file: str | None = None,
    ) -> None:
        self.rows = rows
        self.columns = columns
        self.header = header
        self.file = file
        self.warnings: list[InputWarning] = []  # cells outside their role's plausible range

    def cell(self, r: int, key: str) -> tuple[int, str]:
        """(line number, stripped text) of row ``r``'s cell in column ``key`` ("" if absent)."""
        if key not in self.columns:
            return self.rows[r][0], ""
        number, cells = self.rows[r]
        i = self.columns[key][0]
        return number, cells[i].strip() if i < len(cells) else ""

    def number(self, r: int, key: str) -> float | None:
        """Row ``r``'s value in column ``key`` in SI, None for an empty cell: finite and within
        the SI range, as every quantity of a TOML file (InputError naming the column and the
        value; the line is added by the caller, with the file)."""
        line, text = self.cell(r, key)
        if not text:
            return None
        i, factor = self.columns[key]
        kind = _COLUMNS[key][0]
        value = cell_value(text, factor, file=None, key=key, column=self.header[i], kind=kind)
        # held to the plausible range of its role, as every quantity of a TOML file
        unit = split_header_unit(self.header[i])[1] if kind != "ratio" else None
        found = check_input(
            value,
            kind,
            key,
            label=f"line {line} {key}",
            file=self.file,
            written=f"{text} {unit}" if unit else text,
        )
        if found is not None:
            self.warnings.append(found)
        return value


def _read_row(
    rows: _Cells, r: int, count: int, masses: list[Mass], shafts: list[Shaft], gears: list[Gear]
) -> None:
    """Row ``r`` of ``count``: its mass (and grounded shaft) and its connection to the next
    mass, appended to ``masses``, ``shafts`` and ``gears`` (module docstring); InputError
    naming the column."""
    _line, label = rows.cell(r, "name")
    inertia = rows.number(r, "inertia")
    if inertia is None:
        raise InputError("missing the inertia", key="inertia")
    _l, cyl_text = rows.cell(r, "cylinders")
    try:
        cylinders = tuple(int(c) for c in cyl_text.split())
    except ValueError:
        raise InputError(
            "expected cylinder numbers separated by spaces", key="cylinders", value=cyl_text
        ) from None
    masses.append(
        Mass(label, inertia, damping=rows.number(r, "damping") or 0.0, cylinders=cylinders)
    )
    g = rows.number(r, "ground_stiffness")
    if g:
        shafts.append(Shaft((GROUND, label), g))
    k = rows.number(r, "stiffness")
    ratio = rows.number(r, "gear_ratio")
    _l, direction = rows.cell(r, "gear_direction")
    if r == count - 1:  # the last row
        if k is not None or ratio is not None:
            raise InputError(
                "the last row has no next mass to connect to", key="stiffness", value=k
            )
        return
    if direction and direction not in GEAR_DIRECTIONS:
        raise InputError(
            f"expected one of {', '.join(GEAR_DIRECTIONS)}",
            key="gear_direction",
            value=direction,
        )
    _l2, following = rows.cell(r + 1, "name")
    if k is None and ratio is None:
        raise InputError(
            "missing; give the stiffness (or gear_ratio) to the next mass", key="stiffness"
        )
    if k is None:
        gears.append(Gear((label, following), ratio, direction=direction or "opposite"))
        return
    outer = rows.number(r, "outer_diameter")
    inner = rows.number(r, "inner_diameter")
    geometry = ShaftGeometry(outer, inner or 0.0) if outer is not None else None
    shafts.append(
        Shaft(
            (label, following),
            k,
            damping=rows.number(r, "shaft_damping") or 0.0,
            loss_factor=rows.number(r, "loss_factor") or 0.0,
            geometry=geometry,
            ratio=ratio or 1.0,
            direction=-1 if (ratio is not None and direction != "same") else 1,
        )
    )
