"""Numbers for people: engineering units and sensible digits, one way for every front end (the
terminal tables, the notebook views).

A value in an SI (or declared) unit is shown in the prefixed unit that puts it between 1 and 1000
(``1.894e6 Pa`` reads ``1.894 MPa``, ``130733 N`` reads ``130.7 kN``); a column of a table shares
one unit and one number of decimals chosen from its largest value, so that the digits line up;
round-off next to the column's (or the table's) magnitude reads ``0``, never ``1.393e-14``.
"""

from __future__ import annotations

import html
import math

import numpy as np

__all__ = [
    "SIGNIFICANT",
    "column_text",
    "engine_html",
    "engineering_unit",
    "format_value",
    "html_table",
    "mass_elastic_rows",
    "mechanism_html",
    "torsion_model_html",
]

SIGNIFICANT = 5
"""Significant digits of a figure (the largest value of a column)."""

ROUND_OFF = 1e-9
"""Values below this fraction of the reference magnitude are round-off and read 0."""

# unit -> ladder of (display unit, factor from the unit), smallest first
_LADDERS: dict[str, tuple[tuple[str, float], ...]] = {
    "N": (("N", 1.0), ("kN", 1e-3), ("MN", 1e-6)),
    "N·m": (("N·m", 1.0), ("kN·m", 1e-3), ("MN·m", 1e-6)),
    "Pa": (("Pa", 1.0), ("kPa", 1e-3), ("MPa", 1e-6), ("GPa", 1e-9)),
    "W": (("W", 1.0), ("kW", 1e-3), ("MW", 1e-6)),
    "kW": (("W", 1e3), ("kW", 1.0), ("MW", 1e-3)),
    "J": (("J", 1.0), ("kJ", 1e-3), ("MJ", 1e-6)),
    "m": (("µm", 1e6), ("mm", 1e3), ("m", 1.0)),
    "m³": (("cm³", 1e6), ("L", 1e3), ("m³", 1.0)),
    "rad": (("µrad", 1e6), ("mrad", 1e3), ("rad", 1.0)),
    "N·m/rad": (("N·m/rad", 1.0), ("kN·m/rad", 1e-3), ("MN·m/rad", 1e-6)),
    "N·m·s/rad": (("N·m·s/rad", 1.0), ("kN·m·s/rad", 1e-3)),
    "N·m²": (("N·m²", 1.0), ("kN·m²", 1e-3)),
}


def engineering_unit(magnitude: float, unit: str) -> tuple[str, float]:
    """(display unit, factor) for values of ``unit`` whose largest magnitude is ``magnitude``:
    the prefixed unit that puts it between 1 and 1000 (the unit itself when it has no ladder,
    e.g. rpm, deg, m/s, or for zero)."""
    ladder = _LADDERS.get(unit)
    if ladder is None or not (math.isfinite(magnitude) and magnitude > 0.0):
        return unit, 1.0
    chosen = ladder[0]
    for name, factor in ladder:
        if magnitude * factor >= 1.0 - 1e-12:
            chosen = (name, factor)
    return chosen


def _decimals(magnitude: float, significant: int = SIGNIFICANT) -> int:
    if not (math.isfinite(magnitude) and magnitude > 0.0):
        return 0
    return max(0, significant - 1 - math.floor(math.log10(magnitude) + 1e-12))


def format_value(
    value, unit: str = "", *, reference: float | None = None, significant: int = SIGNIFICANT
) -> tuple[str, str]:
    """(text, display unit) of one figure: numbers in engineering units with ``significant``
    digits, round-off next to ``reference`` (the magnitude of what it is compared with) as 0;
    booleans as yes/no; text as it is."""
    if value is None:
        return "-", unit
    if isinstance(value, (bool, np.bool_)):
        return ("yes" if value else "no"), unit
    if isinstance(value, (int, np.integer)):
        return str(int(value)), unit
    if isinstance(value, (float, np.floating)):
        v = float(value)
        if not math.isfinite(v):
            return "-", unit
        ref = abs(v) if reference is None else max(abs(reference), abs(v) * 0.0)
        if ref > 0.0 and abs(v) <= ROUND_OFF * ref:
            return "0", engineering_unit(ref, unit)[0]
        shown, factor = engineering_unit(abs(v), unit)
        return _figure(v * factor, significant), shown
    return str(value), unit


def _figure(x: float, significant: int) -> str:
    """``significant`` digits without trailing zeros, in positional notation for everyday
    magnitudes (1e-4 to 1e9)."""
    if x == 0.0:
        return "0"
    if 1e-4 <= abs(x) < 1e9:
        text = f"{x:.{_decimals(abs(x), significant)}f}"
        if "." in text:
            text = text.rstrip("0").rstrip(".")
        return text
    return f"{x:.{significant - 1}e}"


def column_text(
    values, unit: str = "", *, reference: float | None = None, significant: int = SIGNIFICANT
):
    """(texts, display unit) of a numeric column: one unit and one number of decimals for all,
    from the largest magnitude (or ``reference``, the magnitude the values are compared with,
    when that is larger: a column of round-off next to it reads 0); NaN reads "-"."""
    arr = np.asarray(values)
    if arr.dtype.kind not in "fiu":
        return [str(v) for v in arr.tolist()], unit
    arr = arr.astype(float)
    finite = np.isfinite(arr)
    top = float(np.max(np.abs(arr[finite]))) if finite.any() else 0.0
    if reference is not None and top <= ROUND_OFF * abs(reference):
        top = abs(reference)
    shown, factor = engineering_unit(top, unit)
    scaled_top = top * factor
    decimals = _decimals(scaled_top, significant)
    if scaled_top >= 10 ** (significant + 1):
        decimals = 0
    limit = ROUND_OFF * max(top, abs(reference or 0.0))
    out = []
    for v, ok in zip(arr.tolist(), finite.tolist(), strict=True):
        if not ok:
            out.append("-")
        elif limit > 0.0 and abs(v) <= limit:
            out.append("0")
        else:
            text = f"{v * factor:.{decimals}f}"
            out.append("0" if float(text) == 0.0 else text)
    # decimals that are zero in every row say nothing: 10, 20, 30 rather than 10.00, 20.00
    while decimals > 0:
        fractional = [s for s in out if "." in s]
        if not fractional or not all(s.endswith("0") for s in fractional):
            break
        out = [s[:-1].rstrip(".") if "." in s else s for s in out]
        decimals -= 1
    return out, shown


def html_table(header, rows, *, title: str = "", caption: str = "") -> str:
    """A small HTML table (every cell escaped; text left, numbers right)."""

    def cell(tag, text):
        text = str(text)
        numeric = text.replace(".", "", 1).replace("-", "", 1).replace("e", "").isdigit()
        align = "right" if numeric else "left"
        return f"<{tag} style='text-align:{align}'>{html.escape(text)}</{tag}>"

    head = "".join(cell("th", h) for h in header)
    body = "".join("<tr>" + "".join(cell("td", c) for c in row) + "</tr>" for row in rows)
    title_html = f"<strong>{html.escape(title)}</strong>" if title else ""
    cap = f"<p>{html.escape(caption)}</p>" if caption else ""
    return f"<div>{title_html}<table><tr>{head}</tr>{body}</table>{cap}</div>"


def mass_elastic_rows(model) -> tuple[list[str], list[list[str]], list[str], list[list[str]]]:
    """The mass-elastic system of a torsional model as two tables: (mass header, mass rows,
    shaft header, shaft rows), with inertias, cylinders, damping, stiffnesses, loss factors
    and diameters in engineering units."""
    masses = [
        [
            m.name,
            f"{m.inertia:.6g}",
            ", ".join(str(c) for c in m.cylinders) or "-",
            f"{m.damping:.6g}" if m.damping else "-",
        ]
        for m in model.masses
    ]
    shafts = []
    for s in model.shafts:
        a, b = s.between
        geometry = getattr(s, "geometry", None)
        diameter = "-"
        if geometry is not None:
            diameter = format_value(geometry.outer_diameter, "m")
            diameter = f"{diameter[0]} {diameter[1]}"
            inner = getattr(geometry, "inner_diameter", 0.0) or 0.0
            if inner:
                diameter += f" (bore {format_value(inner, 'm')[0]})"
        stiffness = format_value(s.stiffness, "N·m/rad")
        shafts.append(
            [
                f"{a} - {b}",
                f"{stiffness[0]} {stiffness[1]}",
                f"{s.damping:.6g}" if s.damping else "-",
                f"{s.loss_factor:g}" if getattr(s, "loss_factor", 0.0) else "-",
                diameter,
            ]
        )
    return (
        ["Mass", "Inertia (kg·m²)", "Cylinders", "Damping (N·m·s/rad)"],
        masses,
        ["Shaft", "Stiffness", "Damping (N·m·s/rad)", "Loss factor", "Diameter"],
        shafts,
    )


def torsion_model_html(model) -> str:
    """The mass-elastic system of a torsional model: masses and shafts (notebook view)."""
    mass_head, masses, shaft_head, shafts = mass_elastic_rows(model)
    title = (
        f"{model.name}: {model.mass_count} masses, "
        + ("chain" if model.is_chain else "branched")
        + (", free" if model.is_free else ", grounded")
    )
    out = html_table(mass_head, masses, title=title)
    out += html_table(shaft_head, shafts, title="Shafts")
    gears = getattr(model, "gears", ())
    if gears:
        out += html_table(
            ["Gear mesh", "Ratio"],
            [[f"{g.between[0]} - {g.between[1]}", f"{g.ratio:g}"] for g in gears],
            title="Gears",
        )
    return out


def engine_html(engine) -> str:
    """The engine's main data and, with a [torsion] section, its mass-elastic system."""
    from crankdyn.constants import DEG, RPM

    g, c = engine.geometry, engine.cylinders
    layout = f"{c.count} {c.layout}" + (
        f", bank angle {c.bank_angle * DEG:g}°" if c.layout == "V" else ""
    )
    rows = [
        ["Cycle", engine.cycle],
        ["Cylinders", layout],
        ["Firing order", "-".join(str(i) for i in c.firing_order)],
        ["Bore x stroke", f"{g.bore * 1e3:.6g} x {g.nominal_stroke * 1e3:.6g} mm"],
        ["Rod length", f"{g.rod_length * 1e3:.6g} mm (λ = {g.lam:.4f})"],
        ["Displacement", f"{engine.displacement * 1e3:.4g} L"],
    ]
    if engine.speed is not None:
        rows.append(["Operating speed", f"{engine.speed * RPM:.6g} rpm"])
    if engine.masses is not None:
        m = engine.masses
        for label, value in (
            ("Reciprocating mass", m.reciprocating),
            ("Rotating mass", m.rotating),
        ):
            if value is not None:
                rows.append([label, f"{value:.6g} kg"])
    rows.append(
        ["Pressure", engine.pressure.source if engine.pressure is not None else "synthetic"]
    )
    out = html_table(["", ""], rows, title=engine.name)
    if engine.torsion is not None:
        out += torsion_model_html(engine.torsion)
    return out


def mechanism_html(mech) -> str:
    """A planar mechanism's links (masses, inertias) and joints (notebook view)."""
    links = [
        [
            link.name,
            ", ".join(link.points),
            f"{link.mass:.6g}",
            f"{link.inertia:.6g}",
        ]
        for link in mech.links
    ]
    joints = [[j.name, j.kind, " - ".join(j.links)] for j in mech.joints]
    out = html_table(
        ["Link", "Points", "Mass (kg)", "Inertia (kg·m²)"],
        links,
        title=f"{mech.name}: {len(mech.links)} links, {len(mech.joints)} joints",
    )
    return out + html_table(["Joint", "Kind", "Between"], joints, title="Joints")
