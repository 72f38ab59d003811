"""Design space files (TOML) and coupling catalogues (CSV); see docs/design-file.md.

A design file names a base (an engine or model file, or a built-in example), the discrete
choices (``[[choice]]``: catalogue couplings applied to a named coupling shaft and its two
masses, firing orders, any key's values or bundles of keys), the continuous ranges
(``[[range]]``: any numeric key by its key path, with unit-bearing bounds), the constraints, the
objectives, the ``[analysis]`` settings of a study and the ``[search]`` settings. It becomes a
:class:`crankdyn.design.space.DesignSpace`, a study whose cases are candidate designs.

A coupling catalogue is a CSV table in the makers' data-sheet terms (DIN 740-2), one size a
row, units in the header like every CSV crankdyn reads (``T_KN [kN*m]``): ``size`` (text),
``C_Tdyn`` (the dynamic torsional stiffness, or ``C_Tdyn_<p>`` columns at p % of T_KN for its
torque dependence), ``psi`` (relative damping), ``T_KN``, ``T_KW``, ``T_Kmax``, ``P_KV``,
``J_primary``, ``J_secondary`` and optionally ``cost`` (any unit, kept as text).
"""

from __future__ import annotations

import copy
import re
from pathlib import Path
from typing import Any

from crankdyn.errors import InputError, did_you_mean
from crankdyn.io.csv_tables import read_csv_table, split_header_unit, unit_factor
from crankdyn.io.examples import example_names, example_path
from crankdyn.io.files import display_name, load_toml
from crankdyn.io.schema import Table
from crankdyn.io.study_file import analysis_settings, parse_base
from crankdyn.io.units import convert_magnitude, split_quantity
from crankdyn.study.docpath import KeyPath, apply_values, check_path, parse_path, referenced_files
from crankdyn.study.figures import FIGURES, AnalysisSettings
from crankdyn.study.spec import Base, Distribution, Parameter, StudySpec

__all__ = ["CATALOGUE_COLUMNS", "load_design", "parse_design", "read_coupling_catalogue"]

CATALOGUE_COLUMNS = {
    "size": None,
    "C_Tdyn": "torsional_stiffness",
    "psi": "number",
    "T_KN": "torque",
    "T_KW": "torque",
    "T_Kmax": "torque",
    "P_KV": "power",
    "J_primary": "inertia",
    "J_secondary": "inertia",
    "cost": None,
}
"""The coupling catalogue's columns and their kinds (``C_Tdyn_<p>`` columns: C_Tdyn at p % of
T_KN; None: text, or the cost, whose unit is kept as written)."""

VERDICT_FIGURES = {
    "normal": ("condition_worst_margin", "condition_passed"),
    "all": ("worst_margin", "failed_rows"),
}
"""``[constraints] verdicts`` -> (the worst-margin figure, the passed/failed-rows figure)."""


def load_design(path: str | Path) -> Any:
    """Load a design file (TOML; docs/design-file.md, ``crankdyn docs design-file``).

    Parameters
    ----------
    path
        The design file; relative files it names are looked for beside it.

    Returns
    -------
    crankdyn.design.space.DesignSpace
        The space, checked as far as it can be before a candidate runs.

    Raises
    ------
    InputError
        As :func:`parse_design`, or for an unreadable or malformed file.
    """
    p = Path(path)
    data = load_toml(p, what="design file")
    return parse_design(data, file=display_name(path), base_dir=p.parent, default_name=p.stem)


# ---- the base ---------------------------------------------------------------------------------


def _base(root: Table) -> Base:
    spec = root.string("base")
    folder = root.base_dir or Path(".")
    candidate = Path(spec).expanduser()
    if not candidate.is_absolute():
        candidate = folder / candidate
    if candidate.is_file():
        root.input_file("base", "base file")
        document = load_toml(candidate, what="base file")
        kind = "engine" if "geometry" in document else "model"
        source = display_name(Path(spec))
    else:
        kind = next((k for k in ("engine", "model") if spec in example_names(k)), "")
        if not kind:
            names = [*example_names("engine"), *example_names("model")]
            raise root.error(
                "base",
                "no such engine or model file, nor a built-in example" + did_you_mean(spec, names),
                spec,
            )
        candidate = example_path(spec, kind)
        document = load_toml(candidate, what="base file")
        source = f"{spec} (built-in example)"
    files = []
    for text, path in referenced_files(document, candidate.parent):
        if not Path(text).expanduser().is_absolute():
            files.append((text, path.read_bytes()))
    return Base(kind, document, source, candidate.parent, "", tuple(files))


def _inline_line(base: Base, root: Table) -> Base:
    """The base with its engine's ``[torsion] shaft_line`` file written into the document as
    the table ``[torsion.shaft_line]`` (read the same way), so that key paths reach the line's
    masses and shafts (``torsion.shaft_line.shaft[1].nominal_torque``)."""
    torsion = base.document.get("torsion")
    if not isinstance(torsion, dict) or not isinstance(torsion.get("shaft_line"), str):
        return base
    assert base.base_dir is not None  # the base was read from a file
    path = base.base_dir / torsion["shaft_line"]
    line = load_toml(path, what="shaft-line file")
    if referenced_files(line, path.parent):
        raise root.error(
            "base",
            "the shaft-line file names files of its own; write the line into the engine file "
            "([torsion.shaft_line] as a table) to search over it",
            str(torsion["shaft_line"]),
        )
    document = copy.deepcopy(base.document)
    document["torsion"]["shaft_line"] = line
    return Base(base.kind, document, base.source, base.base_dir, "", base.files)


# ---- finding the coupling ---------------------------------------------------------------------

_CONTAINERS = ("", "torsion.", "torsion.shaft_line.")


def _node(document: dict[str, Any], prefix: str) -> dict[str, Any] | None:
    node: Any = document
    for name in prefix.strip(".").split(".") if prefix else ():
        node = node.get(name) if isinstance(node, dict) else None
    return node if isinstance(node, dict) else None


def _coupling_paths(document: dict[str, Any], t: Table, shaft: str) -> tuple[str, str, str]:
    """(shaft path, primary mass path, secondary mass path) of the coupling shaft named
    ``shaft`` (the masses its ``between`` names)."""
    names: list[str] = []
    for prefix in _CONTAINERS:
        node = _node(document, prefix)
        if node is None:
            continue
        shafts = node.get("shaft") or []
        masses = [m.get("name") for m in node.get("mass") or [] if isinstance(m, dict)]
        for i, s in enumerate(shafts, start=1):
            if not isinstance(s, dict):
                continue
            names.append(str(s.get("name", "")))
            if s.get("name") != shaft:
                continue
            ends = s.get("between") or []
            found = []
            for end in ends:
                if end not in masses:
                    raise t.error("shaft", f'its mass "{end}" is not in the same file section')
                found.append(f"{prefix}mass[{masses.index(end) + 1}]")
            return f"{prefix}shaft[{i}]", found[0], found[1]
    raise t.error("shaft", "no shaft of this name in the base" + did_you_mean(shaft, names), shaft)


# ---- the coupling catalogue -------------------------------------------------------------------


def read_coupling_catalogue(
    path: Path, display: str
) -> tuple[list[str], list[dict[str, Any]], list[float] | None, str]:
    """A coupling catalogue (module docstring).

    Parameters
    ----------
    path
        The CSV file.
    display
        How to name it in messages.

    Returns
    -------
    sizes : list of str
        The sizes, in file order.
    keys : list of dict
        Per size, the coupling's keys as a model file writes them (``stiffness_table`` rows
        [torque, C_Tdyn], ``relative_damping``, ``nominal_torque``...) in SI with units, and
        ``J_primary``, ``J_secondary`` (``"... kg*m^2"``).
    costs : list of float or None
        The cost column, or None.
    cost_unit : str
        The cost's unit as written (``""`` without one).

    Raises
    ------
    InputError
        For a missing or unknown column, a missing unit, a value out of range, a duplicate
        size; naming the file, the line and the cell.
    """
    table = read_csv_table(path, display=display, what="coupling catalogue")
    columns: dict[str, tuple[int, float]] = {}
    stiffness: list[tuple[float, int, float]] = []  # (percent of T_KN, column, factor)
    cost_unit = ""
    for i, cell in enumerate(table.header):
        name, unit = split_header_unit(cell)
        if name == "size" or (name == "cost" and unit is None):
            columns[name] = (i, 1.0)
            continue
        if name == "cost":
            columns[name], cost_unit = (i, 1.0), unit or ""
            continue
        match = re.fullmatch(r"C_Tdyn(?:_(\d+(?:\.\d+)?))?", name)
        kind = "torsional_stiffness" if match else CATALOGUE_COLUMNS.get(name)
        if kind is None and name not in CATALOGUE_COLUMNS:
            raise InputError(
                "unknown column" + did_you_mean(name, list(CATALOGUE_COLUMNS)),
                file=display,
                key="header",
                value=cell,
            )
        factor = 1.0
        if kind not in (None, "number"):
            factor = unit_factor(
                cell,
                unit,
                kind,
                display,
                missing="the column must name its unit, e.g. T_KN [kN*m]",
                unknown="unit {unit} is not a unit of this column's quantity",
            )
        if match:
            percent = float(match.group(1)) if match.group(1) else -1.0
            stiffness.append((percent, i, factor))
        else:
            columns[name] = (i, factor)
    needed = [n for n in ("size", "psi", "T_KN", "J_primary", "J_secondary") if n not in columns]
    if needed or not stiffness:
        missing = needed or ["C_Tdyn"]
        raise InputError(f"missing column {missing[0]}", file=display, key="header")
    sizes = [table.cell(r, columns["size"][0])[1] for r in range(len(table.rows))]
    for r, size in enumerate(sizes):
        if size in sizes[:r]:
            number, _ = table.cell(r, columns["size"][0])
            raise InputError("the size is listed twice", file=display, key=f"line {number}")
    values = {n: table.column(i, f) for n, (i, f) in columns.items() if n not in ("size",)}
    stiff = {p: table.column(i, f) for p, i, f in stiffness}
    out = []
    for r in range(len(sizes)):
        tkn = float(values["T_KN"][r])
        keys: dict[str, Any] = {}
        if -1.0 in stiff:  # one C_Tdyn: no torque dependence
            keys["dynamic_stiffness"] = f"{float(stiff[-1.0][r])!r} N*m/rad"
            keys["stiffness_table"] = None  # removed from the base's coupling
        else:
            rows = [[p / 100.0 * tkn, float(stiff[p][r])] for p in sorted(stiff)]
            if rows[0][0] > 0.0:  # below the lowest torque given: its C_Tdyn (no slope guessed)
                rows.insert(0, [0.0, rows[0][1]])
            keys["stiffness_table"] = [[f"{q!r} N*m", f"{c!r} N*m/rad"] for q, c in rows]
            keys["dynamic_stiffness"] = None
        keys.update(
            {
                "relative_damping": float(values["psi"][r]),
                "nominal_torque": f"{tkn!r} N*m",
                "designation": sizes[r],
            }
        )
        for column, key, unit in (
            ("T_KW", "vibratory_torque", "N*m"),
            ("T_Kmax", "maximum_torque", "N*m"),
            ("P_KV", "power_loss", "W"),
        ):
            if column in values:
                keys[key] = f"{float(values[column][r])!r} {unit}"
        keys["J_primary"] = f"{float(values['J_primary'][r])!r} kg*m^2"
        keys["J_secondary"] = f"{float(values['J_secondary'][r])!r} kg*m^2"
        out.append(keys)
    costs = [float(c) for c in values["cost"]] if "cost" in values else None
    return sizes, out, costs, cost_unit


# ---- choices and ranges -----------------------------------------------------------------------


def _coupling_choice(
    t: Table, document: dict[str, Any]
) -> tuple[Parameter, list[float] | None, str]:
    shaft = t.string("shaft")
    shaft_path, primary, secondary = _coupling_paths(document, t, shaft)
    path = t.input_file("catalogue", "coupling catalogue")
    sizes, rows, costs, cost_unit = read_coupling_catalogue(path, display_name(path))
    bundles = []
    for keys in rows:
        bundle = {f"{shaft_path}.{k}": v for k, v in keys.items() if not k.startswith("J_")}
        bundle[f"{primary}.inertia"] = keys["J_primary"]
        bundle[f"{secondary}.inertia"] = keys["J_secondary"]
        bundles.append(bundle)
    paths = list(bundles[0])
    return _bundle(t, document, paths, bundles, sizes), costs, cost_unit


def _bundle(
    t: Table,
    document: dict[str, Any],
    texts: list[str],
    bundles: list[dict[str, Any]],
    names: list[str] | None,
) -> Parameter:
    paths = [parse_path(text, file=t.file, key=t.label("key")) for text in texts]
    for p in paths:
        check_path(document, p, file=t.file, key=t.label("key"))
    with t.context():
        return Parameter(
            path=paths[0],
            also=tuple(paths[1:]),
            values=tuple(bundles),
            bundle=True,
            names=tuple(names) if names is not None else None,
        )


def _firing_orders(t: Table, base: Base) -> tuple[list[Any], list[str]]:
    """Every even firing order the base engine's crankshaft admits (its throw angles kept)."""
    import numpy as np

    from crankdyn.engine.firing import even_firing_schemes

    engine = parse_base(base.kind, base.document, file=base.source, base_dir=base.base_dir)
    cylinders = getattr(engine, "cylinders", None)
    if cylinders is None:
        raise t.error("values", "needs an engine base (its crank arrangement)", "all")
    schemes = even_firing_schemes(np.asarray(cylinders.throw_angles), cylinders.cycle)
    orders = sorted({tuple(int(c) for c in o) for o in schemes.orders})
    if not orders:
        raise t.error("values", "the crankshaft admits no even firing order", "all")
    keep = {
        k: base.document["cylinders"][k]
        for k in ("throw_angles", "throw_positions")
        if k in base.document.get("cylinders", {})
    }
    throws = [f"{float(np.degrees(a))!r} deg" for a in cylinders.throw_angles]
    bundles = []
    for order in orders:
        bundle: dict[str, Any] = {"cylinders.firing_order": list(order)}
        if not keep:  # derived from the firing order in the base: keep the base's crankshaft
            bundle["cylinders.throw_angles"] = throws
        bundles.append(bundle)
    return bundles, ["-".join(map(str, o)) for o in orders]


def _choice(t: Table, base: Base) -> tuple[str, Parameter, list[float] | None, str]:
    name = t.string("name", None)
    if t.has("catalogue"):
        p, costs, unit = _coupling_choice(t, base.document)
        t.finish()
        return name or "coupling", p, costs, unit
    key = t.string("key")
    raw = t.raw("values", expected='a list of values, or "all" (firing orders)')
    costs = t.raw("costs", None)
    names = t.string_list("names", None)
    if raw == "all":
        if key != "cylinders.firing_order":
            raise t.error("values", '"all" applies to key = "cylinders.firing_order"', raw)
        bundles, names = _firing_orders(t, base)
        p = _bundle(t, base.document, list(bundles[0]), bundles, names)
    elif isinstance(raw, list) and raw and all(isinstance(v, dict) for v in raw):
        texts: list[str] = []
        bundles = []
        for v in raw:
            bundle = {f"{key}.{k}": x for k, x in v.items()}
            texts.extend(x for x in bundle if x not in texts)
            bundles.append(bundle)
        p = _bundle(t, base.document, texts, bundles, names)
    elif isinstance(raw, list) and raw:
        path = parse_path(key, file=t.file, key=t.label("key"))
        check_path(base.document, path, file=t.file, key=t.label("key"))
        with t.context():
            p = Parameter(path=path, values=tuple(raw), names=tuple(names) if names else None)
    else:
        raise t.error("values", 'expected a non-empty list, or "all"', raw)
    if costs is not None and (
        not isinstance(costs, list)
        or len(costs) != len(p.values or ())
        or not all(isinstance(c, int | float) for c in costs)
    ):
        raise t.error("costs", "expected one number per value", costs)
    t.finish()
    return name or key, p, [float(c) for c in costs] if costs else None, ""


def _range(t: Table, document: dict[str, Any]) -> tuple[str, Parameter]:
    raw_key = t.raw("key", expected='a key path such as "torsion.damper[1].inertia"')
    texts = raw_key if isinstance(raw_key, list) and raw_key else [raw_key]
    paths = [parse_path(text, file=t.file, key=t.label("key")) for text in texts]
    for p in paths:
        check_path(document, p, file=t.file, key=t.label("key"))
    bounds = t.raw("bounds", expected='[low, high], e.g. ["10 kg*m^2", "60 kg*m^2"]')
    if not isinstance(bounds, list) or len(bounds) != 2:
        raise t.error("bounds", 'expected [low, high], e.g. ["10 kg*m^2", "60 kg*m^2"]', bounds)
    split = [split_quantity(b, key=t.label("bounds"), file=t.file) for b in bounds]
    if any(s is None for s in split):
        raise t.error("bounds", "expected two numbers or quantities", bounds)
    (low, unit), (high_raw, high_unit) = split  # type: ignore[misc]
    high = convert_magnitude(
        high_raw, high_unit, unit, key=t.label("bounds"), file=t.file, value=bounds[1]
    )
    if not low < high:
        raise t.error("bounds", "the first value must be below the second", bounds)
    integer = t.boolean("integer", False)
    name = t.string("name", texts[0])
    t.finish()
    with t.context():
        parameter = Parameter(
            path=paths[0],
            also=tuple(paths[1:]),
            unit=unit,
            integer=integer,
            distribution=Distribution("uniform", (float(low), float(high))),
        )
    return name, parameter


# ---- constraints and objectives ---------------------------------------------------------------


def _constraints(t: Table | None, settings: list[tuple[str, Any]], verdicts: str) -> list[Any]:
    from crankdyn.design.space import Constraint

    out = []
    passed = VERDICT_FIGURES[verdicts][1] if verdicts != "none" else None
    if passed == "condition_passed":
        out.append(Constraint(passed, low=1.0, label="every verdict row of normal firing passes"))
    elif passed == "failed_rows":
        out.append(Constraint(passed, high=0.0, label="every verdict row of the TVC passes"))
    if t is None:
        return out
    band = t.quantity_list("barred_band", "speed", None, length=2, check="positive")
    if band is not None:
        if not band[0] < band[1]:
            raise t.error(
                "barred_band", "the first speed must be below the second", t.data["barred_band"]
            )
        settings.append(("barred_band", tuple(band)))
        out.append(
            Constraint(
                "barred_width_in_band", high=0.0, label="no barred speed range inside the band"
            )
        )
    limit = t.quantity("max_added_inertia", "inertia", None, check="nonnegative")
    if limit is not None:
        out.append(
            Constraint("installation_inertia", high=limit, label="added inertia within the limit")
        )  # base added later
    for ft in t.tables("figure"):
        name = ft.string("name", choices=tuple(FIGURES))
        low = ft.number("min", None)
        high = ft.number("max", None)
        ft.finish()
        with ft.context():
            out.append(Constraint(name, low=low, high=high, label=f"{name} within its bounds"))
    return out


def _objectives(
    root: Table, verdicts: str, costs: dict[str, Any], units: dict[str, str]
) -> list[Any]:
    from crankdyn.design.space import Objective

    entries = root.tables("objective")
    if not entries:
        name = VERDICT_FIGURES["all" if verdicts == "all" else "normal"][0]
        f = FIGURES[name]
        return [Objective(name, "max", label=f.label, unit=f.unit)]
    out = []
    for t in entries:
        which = t.exclusive("figure", "cost")
        if which == "figure":
            name = t.string("figure")
            if name not in FIGURES:
                raise t.error("figure", "unknown figure" + did_you_mean(name, FIGURES), name)
            f = FIGURES[name]
            sense = t.string("sense", f.better, choices=("min", "max"))
            if sense is None:
                raise t.error("sense", "the figure has no sense of better: give min or max")
            out.append(Objective(name, sense, label=f.label, unit=f.unit))
        else:
            name = t.string("cost")
            if name not in costs:
                raise t.error(
                    "cost",
                    "no choice of this name has costs" + did_you_mean(name, list(costs)),
                    name,
                )
            out.append(
                Objective(
                    name, "min", kind="cost", label=f"Cost of {name}", unit=units.get(name, "")
                )
            )
        t.finish()
    return out


def _search(t: Table | None) -> Any:
    from crankdyn.design.space import MAX_EXHAUSTIVE, SearchSettings

    if t is None:
        return SearchSettings()
    values = dict(
        seed=t.integer("seed", 0, minimum=0),
        max_candidates=t.integer("max_candidates", MAX_EXHAUSTIVE, minimum=1, maximum=1_000_000),
        population=t.integer("population", 10, minimum=1, maximum=1000),
        tolerance=t.number("tolerance", 1e-3, check="positive"),
        method=t.string("method", "auto", choices=("auto", "exhaustive", "differential-evolution")),
        digits=t.integer("digits", 8, minimum=3, maximum=15),
        verify=t.integer("verify", 3, minimum=0, maximum=100),
    )
    t.finish()
    return SearchSettings(**values)


# ---- the whole file ---------------------------------------------------------------------------


def parse_design(
    data: dict[str, Any],
    *,
    file: str | None = None,
    base_dir: Path | None = None,
    default_name: str = "design",
) -> Any:
    """A :class:`crankdyn.design.space.DesignSpace` from a parsed design document (module
    docstring; docs/design-file.md).

    Parameters
    ----------
    data
        The parsed design document.
    file
        The design file's name for messages.
    base_dir
        The folder its relative file names are looked for in.
    default_name
        The design's name when the document gives none.

    Returns
    -------
    crankdyn.design.space.DesignSpace
        The space.

    Raises
    ------
    InputError
        For a missing or unknown base, a key path that does not fit the base, a bad catalogue,
        bounds, constraint, objective or setting, or a candidate the base's reader refuses
        for a key it does not know; naming the file, the key and the value.
    """
    from crankdyn.design.space import DesignSpace

    root = Table(data, file=file, base_dir=base_dir)
    name = root.string("name", default_name)
    base = _base(root)
    choice_tables = root.tables("choice")
    range_tables = root.tables("range")
    wants_line = any(
        "catalogue" in t.data or str(t.data.get("key", "")).startswith("torsion.shaft_line.")
        for t in (*choice_tables, *range_tables)
    )
    if wants_line:
        base = _inline_line(base, root)
    try:
        parse_base(base.kind, base.document, file=base.source, base_dir=base.base_dir)
    except InputError as exc:
        raise exc.within(file=base.source) from None
    names: dict[str, str] = {}
    costs: dict[str, tuple[float, ...]] = {}
    units: dict[str, str] = {}
    parameters: list[Parameter] = []
    for t in choice_tables:
        label, p, cost, unit = _choice(t, base)
        names[p.key] = label
        if cost is not None:
            costs[label], units[label] = tuple(cost), unit
        parameters.append(p)
    choices = tuple(p.key for p in parameters)
    for t in range_tables:
        label, p = _range(t, base.document)
        names[p.key] = label
        parameters.append(p)
    ranges = tuple(p.key for p in parameters if p.key not in choices)
    if not parameters:
        raise root.error(None, "give at least one [[choice]] or [[range]]")
    taken: list[str] = []
    for p in parameters:
        for path in p.paths:
            if path.text in taken:
                raise root.error(None, f"the key {path.text} is set by two choices or ranges")
            taken.append(path.text)
    ct = root.table("constraints")
    verdicts = (
        ct.string("verdicts", "normal", choices=("normal", "all", "none")) if ct else "normal"
    )
    at = root.table("analysis")
    settings = []
    if at is not None:
        settings = analysis_settings(at)
        at.finish()
    constraints = _constraints(ct, settings, verdicts)
    objectives = _objectives(root, verdicts, costs, units)
    search = _search(root.table("search"))
    figures: list[str] = []
    for f in (
        *(c.figure for c in constraints),
        *(o.name for o in objectives if o.kind == "figure"),
    ):
        if f not in figures:
            figures.append(f)
    if verdicts != "none":  # the worst margin of the rows constrained, tabled for every design
        default = VERDICT_FIGURES[verdicts][0]
        if default not in figures:
            figures.append(default)
    if any(c.figure == "installation_inertia" for c in constraints):
        constraints = _added_inertia(constraints, base)
    if ct is not None:
        ct.finish()
    root.finish()
    with root.context():
        study = StudySpec(
            name=name,
            base=base,
            parameters=tuple(parameters),
            figures=tuple(figures),
            settings=AnalysisSettings(tuple(settings)),
            samples=1,
            seed=search.seed,
            source=file,
            verdict_rows=verdicts != "none",
        )
        space = DesignSpace(
            study=study,
            choices=choices,
            ranges=ranges,
            names=names,
            costs=costs,
            cost_unit=units,
            constraints=tuple(constraints),
            objectives=tuple(objectives),
            search=search,
            source=file,
        )
    _probe(space, [*choice_tables, *range_tables])
    return space


def _added_inertia(constraints: list[Any], base: Base) -> list[Any]:
    """The added-inertia limit as a bound on the installation's inertia: the base's plus the
    limit."""
    import dataclasses

    from crankdyn.study.figures import CaseContext

    subject = parse_base(base.kind, base.document, file=base.source, base_dir=base.base_dir)
    ctx = CaseContext(subject, AnalysisSettings(), base.kind)
    own = FIGURES["installation_inertia"].evaluate(ctx) or 0.0
    return [
        dataclasses.replace(c, high=own + c.high) if c.figure == "installation_inertia" else c
        for c in constraints
    ]


def _probe(space: Any, tables: list[Table]) -> None:
    """Stop before the search when a candidate (the first value of every choice, the middle
    of every range) names a key the base file's reader does not know."""
    from crankdyn.design.search import candidate_case

    mids = []
    for key in space.ranges:
        low, high = space.parameter(key).distribution.args
        mids.append(0.5 * (low + high))
    case = candidate_case(space, [0] * len(space.choices), mids)
    payload_values: dict[KeyPath, Any] = {}
    for p in space.parameters:
        payload_values.update(p.assignments(case.params[p.key]))
    document = apply_values(space.study.base.document, payload_values)
    base = space.study.base
    try:
        parse_base(base.kind, document, file=base.source, base_dir=base.base_dir)
    except InputError as exc:
        if not exc.message.startswith("unknown key"):
            return  # a property of that candidate, recorded when it runs
        for t, p in zip(tables, space.parameters, strict=True):
            for path in p.paths:
                if exc.key and exc.key.split(" ")[-1].strip('"') == path.parts[-1][0]:
                    which = "key" if "key" in t.data else "catalogue"
                    raise t.error(
                        which, f"the {base.kind} file has no such key ({exc.message})", path.text
                    ) from None
        raise InputError(
            f"a choice or range names a key the {base.kind} file does not know: {exc}",
            file=space.source,
        ) from None
