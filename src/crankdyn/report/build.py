"""Run every section builder that applies to an engine."""

from __future__ import annotations

import datetime as _dt
import math
from collections.abc import Callable
from typing import TYPE_CHECKING

from numpy.typing import ArrayLike

from crankdyn import __version__
from crankdyn.constants import RPM
from crankdyn.engine.model import Engine
from crankdyn.report.model import Report, Section
from crankdyn.report.sections import Context, NotApplicable, NotRequested, builders
from crankdyn.session import Analysis

if TYPE_CHECKING:
    from crankdyn.report.sections.measurement import MeasurementInput

__all__ = ["build_report", "engine_inputs"]


def engine_inputs(engine: Engine) -> list[tuple[str, str]]:
    """The input echoed with units, for the report's first table.

    Parameters
    ----------
    engine : crankdyn.engine.model.Engine
        The engine (SI units).

    Returns
    -------
    list of (str, str)
        Name and value of every input, the value formatted with its unit (mm, L, kg, kg·m²,
        kPa, MPa, degrees, rpm).
    """
    g, c = engine.geometry, engine.cylinders
    rows = [
        ("Engine", engine.name),
        ("Source", engine.source or "-"),
        ("Cycle", engine.cycle),
        (
            "Cylinders",
            f"{c.count} {c.layout}"
            + (f", bank angle {math.degrees(c.bank_angle):g}°" if c.layout == "V" else ""),
        ),
        ("Firing order", "-".join(str(i) for i in c.firing_order)),
        ("Throw angles", ", ".join(f"{math.degrees(a):g}°" for a in c.throw_angles)),
        ("Bore", f"{g.bore * 1e3:.6g} mm"),
        ("Stroke", f"{g.nominal_stroke * 1e3:.6g} mm (true {g.stroke * 1e3:.6g} mm)"),
        ("Rod length", f"{g.rod_length * 1e3:.6g} mm (λ = {g.lam:.4f})"),
        ("Offset", f"{g.offset * 1e3:.6g} mm"),
        ("Displacement", f"{engine.displacement * 1e3:.4g} L"),
    ]
    if c.pitch is not None:
        rows.append(("Cylinder pitch", f"{c.pitch * 1e3:.6g} mm"))
    m = engine.masses
    if m is not None:
        for label, value in (
            ("Piston group", m.piston_group),
            ("Rod", m.rod),
            ("Crank unbalance", m.crank_unbalance),
            ("Reciprocating mass (given)", m.reciprocating),
            ("Rotating mass (given)", m.rotating),
        ):
            if value is not None:
                rows.append((label, f"{value:.6g} kg"))
        if m.rod_cg_from_big_end is not None:
            rows.append(("Rod CG from big end", f"{m.rod_cg_from_big_end * 1e3:.6g} mm"))
        if m.rod_inertia is not None:
            rows.append(("Rod moment of inertia", f"{m.rod_inertia:.6g} kg·m²"))
        if m.rod_split != "centre-of-gravity":
            rows.append(("Rod split", "m_rod/3 at the small end, 2 m_rod/3 at the big end"))
    if engine.pressure is not None:
        peak, at = engine.pressure.peak
        rows.append(
            (
                "Pressure trace",
                f"{engine.pressure.source} ({len(engine.pressure.pressure)}"
                f" points, peak {peak / 1e6:.4g} MPa at {math.degrees(at):.1f}°)",
            )
        )
        rows.append(("Crankcase pressure", f"{engine.crankcase_pressure / 1e3:.6g} kPa"))
    if engine.speed is not None:
        rows.append(("Operating speed", f"{engine.speed * RPM:.6g} rpm"))
    return rows


def build_report(
    engine: Engine,
    *,
    speed: float | None = None,
    speeds: ArrayLike | None = None,
    progress: Callable[[str], object] | None = None,
    measurement: MeasurementInput | None = None,
    built: Callable[[Section], object] | None = None,
) -> Report:
    """Run every analysis that applies to ``engine``.

    Parameters
    ----------
    engine : crankdyn.engine.model.Engine
        The engine; every number comes from one :class:`crankdyn.session.Analysis` of it.
    speed : float or None
        Operating speed (rad/s); default the engine's [operating] speed.
    speeds : array_like or None
        Speeds of the sweeps (rad/s) for speed-dependent analyses, or None for their defaults.
    progress : callable or None
        ``progress(name)`` is called before each analysis, with the section's name.
    measurement : crankdyn.report.sections.measurement.MeasurementInput or None
        A measurement to hold against the torsional model, or None.
    built : callable or None
        ``built(section)`` is called as each section is made (the command line starts drawing
        its figures while the next analyses run: :class:`crankdyn.plots.render.Renderer`).

    Returns
    -------
    crankdyn.report.model.Report
        The sections that apply, and a note for each analysis that does not (and why).

    Raises
    ------
    crankdyn.errors.InputError
        No operating speed is given or in the engine file.
    """
    analysis = Analysis(engine, speed=speed, speeds=speeds)
    analysis.speed  # noqa: B018  (no speed: the one-line error before any work)
    ctx = Context(analysis, measurement=measurement)
    sections, notes = [], []
    for name, build in builders():
        if progress is not None:
            progress(name)
        try:
            section = build(ctx)
        except NotRequested:
            continue
        except NotApplicable as why:
            notes.append(f"{name}: {why}")
            continue
        sections.append(section)
        if built is not None:
            built(section)
    return Report(
        title=engine.name,
        inputs=engine_inputs(engine),
        sections=sections,
        source=engine.source,
        version=__version__,
        created=_dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC"),
        notes=notes,
    )
