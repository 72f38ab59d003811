"""The TVC report: a torsional vibration calculation as a report folder (``index.html``,
``summary.json`` with the ``verdicts`` and ``barred_speed_ranges`` lists, ``data/*.csv``,
``plots/``) with
the installation data, the mass-elastic system, natural frequencies and mode shapes, the
Campbell diagram, every condition's components against their limits, every transient event's
time history against its limits, the barred speed ranges, the passages through them and the
verdict table (docs/tvc.md)."""

from __future__ import annotations

import datetime as _dt
from typing import TYPE_CHECKING, Any

from crankdyn import __version__
from crankdyn.constants import RPM
from crankdyn.display import mass_elastic_tables, number
from crankdyn.report.model import Plot, Report, Section, Table
from crankdyn.tvc.evaluate import margins

if TYPE_CHECKING:
    from crankdyn.tvc.result import TvcResult

__all__ = ["BARRED_FIELDS", "VERDICT_FIELDS", "build_tvc_report", "summary_lists"]

VERDICT_FIELDS = (
    "component",
    "condition",
    "quantity",
    "worst",
    "limit",
    "unit",
    "margin",
    "passed",
    "source",
    "clause",
)
"""The fields of every row of summary.json's ``verdicts`` (SI values, the unit named; the
rule with its edition and the clause)."""

BARRED_FIELDS = (
    "component",
    "condition",
    "start_rpm",
    "end_rpm",
    "permitted",
    "source",
    "clause",
)
"""The fields of every row of summary.json's ``barred_speed_ranges``."""


def summary_lists(result: TvcResult) -> dict[str, list[dict[str, Any]]]:
    """``verdicts`` and ``barred_speed_ranges`` with exactly the fields the summary names.

    Parameters
    ----------
    result : crankdyn.tvc.result.TvcResult
        The torsional vibration calculation (SI units).

    Returns
    -------
    dict
        ``"verdicts"``: one dict per verdict row with the fields :data:`VERDICT_FIELDS` (worst
        value and limit in the SI unit the row names, margin as a fraction); and
        ``"barred_speed_ranges"``: one dict per barred range with the fields
        :data:`BARRED_FIELDS` (start and end in rpm).
    """
    verdicts = [
        {
            "component": v.component,
            "condition": v.condition,
            "quantity": v.quantity,
            "worst": float(v.worst),
            "limit": float(v.limit),
            "unit": v.unit,
            "margin": float(v.margin),
            "passed": bool(v.passed),
            "source": v.source,
            "clause": v.clause,
        }
        for v in result.verdicts
    ]
    barred = [
        {
            "component": b.component,
            "condition": b.condition,
            "start_rpm": float(b.start * RPM),
            "end_rpm": float(b.end * RPM),
            "permitted": bool(b.permitted),
            "source": b.source,
            "clause": b.clause,
        }
        for b in result.barred_ranges
    ]
    return {"verdicts": verdicts, "barred_speed_ranges": barred}


def _inputs(result: TvcResult) -> list[tuple[str, str]]:
    # the result keeps its model, engine and settings untyped (TorsionModel, Engine, TvcSpec)
    model: Any = result.model
    engine: Any = result.engine
    spec: Any = result.spec
    rows = [("Installation", model.name), ("Source", model.source or "-")]
    if engine is not None:
        c = engine.cylinders
        rows += [
            ("Engine", engine.name),
            ("Cycle", engine.cycle),
            (
                "Cylinders",
                f"{c.count} {c.layout}, firing order {'-'.join(map(str, c.firing_order))}",
            ),
        ]
    rows += [
        ("Rated speed n_0", f"{number(result.rated_speed * RPM, 6)} rpm"),
        ("Load", result.load),
        (
            "Conditions",
            "; ".join(
                f"{c.name}: {number(c.low * RPM, 6)}-{number(c.high * RPM, 6)} rpm"
                for c in result.conditions
            ),
        ),
        ("Tachometer tolerance", f"±{number(100 * result.tachometer_tolerance, 3)} %"),
        ("Rule set", f"{result.rule_title} (rules = {result.rules})"),
    ]
    if spec is not None:
        rows.append(("Barred-range margins", margins(spec)[0]))
    if spec is not None and spec.source:
        rows.append(("TVC settings from", spec.source))
    return rows


def _verdict_section(result: TvcResult) -> Section:
    """The verdict table: the calculation's key figures, every verdict row, the barred ranges
    as found and as declared with why, the passages (the result's summary)."""
    return Section.of(
        "verdicts",
        "Verdict table",
        [result],
        verdicts_name="verdicts",
        intro=(
            "Every component in every condition: its worst value on the resolved response "
            "(the resonance peaks refined to 0.1 %, the worst value to 1e-6), the limit and "
            "where it comes from; margin = 1 - worst / limit. Barred speed ranges as found (where "
            "the limit is exceeded, ends to 0.01 rpm) and as declared (the society's margins "
            "and the tachometer tolerance added), permitted or not and why."
        ),
    )


def _model_sections(result: TvcResult) -> list[Section]:
    """The mass-elastic system, the natural frequencies and mode shapes, the Campbell diagram."""
    model: Any = result.model  # a TorsionModel
    modes: Any = result.modes  # a ModalResult
    sections = [
        Section(
            key="mass-elastic",
            title="Mass-elastic system",
            intro=(
                f"{model.name}: {len(model.masses)} masses, {len(model.shafts)} shaft(s), "
                f"{len(model.gears)} gear mesh(es), {len(model.dampers)} damper(s)."
            ),
            tables=[
                Table(name, title, header=header, rows=rows, caption=caption)
                for name, title, header, rows, caption in mass_elastic_tables(model)
            ],
        ),
        Section.of(
            "modes",
            "Natural frequencies and mode shapes",
            [modes],
            intro="Undamped natural frequencies (elastic modes numbered from 1).",
            plots=[Plot("mode-shapes", "Mode shapes", modes.plot(), "")],
        ),
    ]
    campbell: Any = result.campbell  # a CampbellResult, or None
    if campbell is not None:
        sections.append(
            Section.of(
                "campbell",
                "Campbell diagram",
                [campbell],
                intro="Engine orders and the orders of the excitation sources (propeller blade "
                "orders, machine harmonics) against the natural frequencies.",
                plots=[Plot("campbell", "Campbell diagram", campbell.plot(), "")],
            )
        )
    return sections


def _condition_sections(result: TvcResult) -> list[Section]:
    """Every condition: its components against their limits (plot), verdicts, barred ranges."""
    return [
        Section.of(
            f"condition-{k + 1}",
            f"Condition: {cond.name}",
            [cond],
            intro=(
                f"{cond.description}; {number(cond.low * RPM, 6)}-{number(cond.high * RPM, 6)} rpm."
            ),
            plots=[
                Plot(
                    f"condition-{k + 1}",
                    f"{cond.name}: components against their limits",
                    cond.plot(),
                    "Value / limit of every check on the resolved response; barred ranges "
                    "shaded (red: not permitted).",
                )
            ],
        )
        for k, cond in enumerate(result.condition_results)
    ]


def _event_sections(result: TvcResult) -> list[Section]:
    """Every transient event (``[[tvc.event]]``): its time history with the limits (plot) and
    its verdict rows."""
    return [
        Section.of(
            f"event-{k + 1}",
            f"Transient event: {event.name}",
            [event],
            intro=f"{event.description}.",
            plots=[
                Plot(
                    f"event-{k + 1}",
                    f"{event.name}: time history against the limits",
                    event.plot(),
                    "Every checked quantity as a fraction of its limit (the line 1), the "
                    "couplings' torques with their maximum torques, and the speeds, over the "
                    "run; the peaks of the verdict rows are refined between the integration "
                    "steps.",
                )
            ],
        )
        for k, event in enumerate(result.events)
    ]


def _passage_section(result: TvcResult) -> Section:
    """The passages through the barred ranges: the runs' plots (the table is the verdict
    section's)."""
    plots = []
    for k, p in enumerate(result.passages):
        if p.transient is not None:
            plots.append(
                Plot(
                    f"passage-{k + 1}",
                    f"Passage {number(p.start * RPM, 5)}-{number(p.end * RPM, 5)} rpm "
                    f"({p.condition})",
                    p.transient.plot(),
                    "Run-up through the barred range in the time domain.",
                )
            )
    return Section(
        key="passage",
        title="Passage through the barred ranges",
        intro="A time-domain run-up through every barred range at the acceleration the "
        "engine's torque leaves over the load: the time in the range and the largest "
        "transient value of every component (rows 'transient peak passing' of the verdict "
        "table). " + ("No barred range: nothing to pass." if not result.passages else ""),
        plots=plots,
        json={"tvc": result.to_dict()},
    )


def build_tvc_report(result: TvcResult) -> Report:
    """The report of a :class:`~crankdyn.tvc.TvcResult` (module docstring): every section
    renders a result's summary (the verdict rows, barred ranges, modes and critical speeds
    are those the result declares, the same as the command line's).

    Parameters
    ----------
    result : crankdyn.tvc.result.TvcResult
        The torsional vibration calculation (SI units; the report shows speeds in rpm,
        margins in percent and every value with its unit).

    Returns
    -------
    crankdyn.report.model.Report
        The report, its summary carrying the ``verdicts`` and ``barred_speed_ranges`` lists
        (:func:`summary_lists`); write it with :func:`crankdyn.report.write.write_report`.
    """
    model: Any = result.model  # a TorsionModel
    sections = [
        _verdict_section(result),
        *_model_sections(result),
        *_condition_sections(result),
        *_event_sections(result),
        _passage_section(result),
    ]
    return Report(
        title=f"Torsional vibration calculation: {model.name}",
        inputs=_inputs(result),
        sections=sections,
        source=model.source,
        version=__version__,
        created=_dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC"),
        notes=list(result.notes),
        data=summary_lists(result),
        subject="installation",
    )
