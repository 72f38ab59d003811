"""The TVC report: a torsional vibration calculation as a report folder (``index.html``,
``summary.json`` with the ``verdicts`` and ``barred_speed_ranges`` lists, ``data/*.csv``,
``plots/``) with
the installation data, the mass-elastic system, natural frequencies and mode shapes, the
Campbell diagram, every condition's components against their limits, every transient event's
time history against its limits, the barred speed ranges, the passages through them and the
verdict table (docs/tvc.md)."""

from __future__ import annotations

import datetime as _dt
from collections.abc import Callable, Iterator
from typing import TYPE_CHECKING, Any

from crankdyn import __version__
from crankdyn.constants import RPM
from crankdyn.display import mass_elastic_tables, number
from crankdyn.project import Project
from crankdyn.report.model import FrontMatter, Plot, Report, Section, Table
from crankdyn.summary import Verdict, verdict_cells, verdict_status
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
        ("Rule set", result.rule_title),  # in words, no raw key (issue 32)
    ]
    if spec is not None:
        rows.append(("Barred-range margins", margins(spec)[0]))
    if spec is not None and spec.source:
        rows.append(("TVC settings from", spec.source))
    return rows


def _front(result: TvcResult, created: str) -> FrontMatter:
    """The title page: the project's document control (``[project]``), the installation and
    the overall verdict."""
    model: Any = result.model
    engine: Any = result.engine
    project: Project | None = getattr(model, "project", None)
    p = project or Project()
    rows = list(p.rows())
    rows.append(("Installation (model)", model.name))
    if engine is not None:
        c = engine.cylinders
        firing = "-".join(map(str, c.firing_order))
        rows.append(("Engine (model)", f"{engine.name}: {c.count} {c.layout}, firing {firing}"))
    rows.append(("Rated speed n_0", f"{number(result.rated_speed * RPM, 6)} rpm"))
    failed, count = len(result.failed()), len(result.verdicts)
    said = result.summary().verdict  # the verdict's words are the summary's (crankdyn.summary)
    if not result.verdicts or said is None:
        verdict, status = "nothing checked (no component has a limit)", "warn"
    else:
        tally = f"{failed} of {count} rows failed" if failed else f"all {count} rows"
        verdict, status = f"{said}: {tally}", verdict_status(said) or "warn"
    document = [
        ("Document", p.document or "-"),
        ("Revision", p.revision or "-"),
        ("Date", p.date or created),
    ]
    if getattr(result.spec, "rules", None):
        document.append(("Rule set", result.rule_title))  # in words, no raw key
    return FrontMatter(
        title="Torsional vibration calculation",
        subtitle=p.project or model.name,
        verdict=verdict,
        status=status,
        rows=rows,
        document=document,
        revisions=[(r.revision, r.date, r.description, r.by) for r in p.revisions],
        signatures=p.signatures(),
        note=(
            ""
            if project is not None and project.given
            else "No [project] section: the document control (project, engine type, MCR, "
            "revisions, signatures) is not given (crankdyn docs tvc)."
        ),
    )


def short_clause(clause: str) -> str:
    """A rule clause without its parenthesised remarks (what a value's reading rests on), for
    the verdict table's rows; the numbered note under the table gives it whole.

    Parameters
    ----------
    clause : str
        The verdict row's clause (:attr:`crankdyn.summary.Verdict.clause`).

    Returns
    -------
    str
        The clause's references alone, ``", partly unverified"`` added where a remark said a
        value was not verified against the rule text.

    Examples
    --------
    >>> short_clause("τ_C: Pt 5 Ch 8 2.5 (not verified against the text: value as KR 2025 "
    ...              "Pt 5 Ch 4 202.1 (the M68 formula)); C_D: Vol 2 Pt 5 Ch 1 3.1.1")
    'τ_C: Pt 5 Ch 8 2.5; C_D: Vol 2 Pt 5 Ch 1 3.1.1, partly unverified'
    >>> short_clause("[shaft] power_loss (P_KV, the catalogue)")
    '[shaft] power_loss'
    """
    out: list[str] = []
    depth = 0
    for ch in clause:
        if ch == "(":
            depth += 1
        elif ch == ")" and depth:
            depth -= 1
        elif depth == 0:
            out.append(ch)
    text = " ".join("".join(out).split()).replace(" ;", ";").replace(" ,", ",").strip(" ;,")
    return text + (", partly unverified" if "not verified" in clause else "")


def _verdict_table(verdicts: tuple[Verdict, ...]) -> Table:
    """Every verdict row (:func:`crankdyn.summary.verdict_cells`; the CSV holds the whole rule
    text); the page shows the clause's references (:func:`short_clause`) with a numbered note,
    listed once under the table: the whole clause and the source of the limit."""
    header, rows = verdict_cells(verdicts)
    cited = list(dict.fromkeys((v.clause, v.source) for v in verdicts))
    page = [
        [*row[:-1], f"{short_clause(v.clause)} [{cited.index((v.clause, v.source)) + 1}]".strip()]
        for row, v in zip(rows, verdicts, strict=True)
    ]
    notes = [
        f"[{i + 1}] {clause + ': ' if clause else ''}{source}"
        for i, (clause, source) in enumerate(cited)
    ]
    return Table(
        "verdicts",
        "Verdicts",
        header=header,
        rows=rows,
        page_rows=page,
        notes=notes,
        caption="Rule: the clause and [n], the note under the table with the clause whole and "
        "the source of the limit (with the values it was evaluated with).",
    )


def _verdict_section(result: TvcResult) -> Section:
    """The verdict table: every verdict row, the barred ranges as found and as declared with
    why, the passages (the result's summary; its key figures are the document's summary)."""
    section = Section.of(
        "verdicts",
        "Verdict table",
        [result],
        intro=(
            "Every component in every condition: its worst value on the resolved response "
            "(the resonance peaks refined to 0.1 %, the worst value to 1e-6), the limit and "
            "where it comes from; margin = 1 - worst / limit. Barred speed ranges as found (where "
            "the limit is exceeded, ends to 0.01 rpm) and as declared (the society's margins "
            "and the tachometer tolerance added), permitted or not and why."
        ),
    )
    tables = [t for t in section.tables if t.name not in ("verdicts-verdicts", "conditions")]
    section.tables = [_verdict_table(result.verdicts), *tables] if result.verdicts else tables
    section.show_figures, section.notes = False, []  # the summary shows both once
    return section


def _model_sections(result: TvcResult) -> list[Section]:
    """The mass-elastic system (schematic and tables), the natural frequencies with the mode
    shapes and relative vector sums, the Campbell diagram."""
    model: Any = result.model  # a TorsionModel
    modes: Any = result.modes  # a ModalResult
    from crankdyn.plots.schematic import plot_schematic

    sections = [
        Section(
            key="mass-elastic",
            title="Mass-elastic system",
            intro=(
                f"{model.name}: {len(model.masses)} masses, {len(model.shafts)} shaft(s), "
                f"{len(model.gears)} gear mesh(es), {len(model.dampers)} damper(s). Units as "
                "the class forms give them: inertia kg·m², stiffness MN·m/rad, lengths mm."
            ),
            plots=[
                Plot(
                    "schematic",
                    "Schematic of the mass-elastic system",
                    plot_schematic(model),
                    "Drawn from the model: block heights grow with log10 of the inertia; "
                    "distributed shafts as one double line.",
                )
            ],
            tables=[
                Table(name, title, header=header, rows=rows, caption=caption)
                for name, title, header, rows, caption in mass_elastic_tables(model, elements=False)
            ],
        ),
        Section.of(
            "modes",
            "Natural frequencies, mode shapes and relative vector sums",
            [modes] + ([result.mode_table] if result.mode_table is not None else []),
            intro="Undamped natural frequencies (elastic modes numbered from 1); the lowest "
            "modes' relative amplitudes per mass and nodes; per order the relative vector sum "
            "of the cylinders' amplitudes with the firing order's phase angles.",
            plots=[Plot("mode-shapes", "Mode shapes", modes.plot(), "")],
            # the six elastic modes whose shapes are tabled and drawn (and a rigid-body mode 0)
            limits={"natural_frequencies": 6 + int(len(modes.mode) > 0 and modes.mode[0] == 0)},
        ),
    ]
    campbell: Any = result.campbell  # a CampbellResult, or None
    if campbell is not None:
        sections.append(
            Section.of(
                "campbell",
                "Campbell diagram",
                [campbell],
                intro="Engine orders (half orders included) and the orders of the excitation "
                "sources (propeller blade orders, machine harmonics) against the natural "
                "frequencies; every order labelled at its end.",
                plots=[Plot("campbell", "Campbell diagram", campbell.plot(), "")],
            )
        )
    for s in sections:
        s.show_figures = False  # the headline figures are the summary's
    return sections


def _condition_sections(result: TvcResult) -> Iterator[Section]:
    """Every condition: every component against its limit, and per component the forced
    response per order and synthesised against its limits (the rows and barred ranges are the
    verdict table's), one at a time."""
    for k, cond in enumerate(result.condition_results):
        section = Section.of(
            f"condition-{k + 1}",
            f"Condition: {cond.name}",
            [cond],
            intro=(
                f"{cond.description}; {number(cond.low * RPM, 6)}-"
                f"{number(cond.high * RPM, 6)} rpm. Its verdict rows and barred ranges are in "
                "the verdict table."
            ),
            plots=[
                Plot(
                    f"condition-{k + 1}",
                    f"{cond.name}: every component against its limit",
                    cond.plot(),
                    "Value / limit of every check on the resolved response; barred ranges "
                    "shaded (red: not permitted, amber: permitted).",
                ),
                Plot(
                    f"condition-{k + 1}-orders",
                    f"{cond.name}: forced response per order and synthesised",
                    cond.plot_orders(),
                    "Every component that bars speeds: the largest orders (major solid), the "
                    "synthesised value (black) and its limits (red; transient dashed).",
                ),
            ],
        )
        section.tables, section.show_figures = [], False
        for figure in section.figures:  # the conditions' table of the summary shows them
            figure.headline = False
        yield section


def _event_sections(result: TvcResult) -> Iterator[Section]:
    """Every transient event (``[[tvc.event]]``): its time history with the limits (plot); its
    verdict rows are the verdict table's, its key figures the events' table's (each once); one
    at a time."""
    for k, event in enumerate(result.events):
        section = Section.of(
            f"event-{k + 1}",
            f"Transient event: {event.name}",
            [event],
            intro=f"{event.description}. Its verdict rows are in the verdict table.",
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
        section.tables, section.show_figures = [], False
        for figure in section.figures:  # the verdict table and the events' table show them
            figure.headline = False
        yield section


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


def _sections(result: TvcResult) -> Iterator[Section]:
    """The report's sections in order, each made when it is asked for."""
    yield from _model_sections(result)
    yield _verdict_section(result)
    yield from _condition_sections(result)
    yield from _event_sections(result)
    yield _passage_section(result)


def build_tvc_report(
    result: TvcResult, *, built: Callable[[Section], object] | None = None
) -> Report:
    """The report of a :class:`~crankdyn.tvc.TvcResult` (module docstring): a title page with
    the document control of the model's ``[project]``, a numbered contents list, the summary
    (the key figures and the conditions' table, once), the installation data, the
    mass-elastic system (schematic, tables in the class forms' units), the natural frequencies
    with mode-shape tables and relative vector sums, the Campbell diagram, the verdict table,
    every condition's plots and the passages. Every section renders a result's summary (the
    verdict rows, barred ranges, modes and critical speeds are those the result declares, the
    same as the command line's).

    Parameters
    ----------
    result : crankdyn.tvc.result.TvcResult
        The torsional vibration calculation (SI units; the report shows speeds in rpm,
        margins in percent and every value with its unit).
    built : callable or None
        ``built(section)`` is called as each section is made (the command line starts drawing
        its figures while the next sections' are made: :class:`crankdyn.plots.render.Renderer`).

    Returns
    -------
    crankdyn.report.model.Report
        The report, its summary carrying the ``verdicts`` and ``barred_speed_ranges`` lists
        (:func:`summary_lists`); write it with :func:`crankdyn.report.write.write_report`.
    """
    model: Any = result.model  # a TorsionModel
    created = _dt.datetime.now(_dt.UTC).strftime("%Y-%m-%d %H:%M UTC")
    sections = []
    for section in _sections(result):
        sections.append(section)
        if built is not None:
            built(section)
    front = _front(result, created)
    project: Project = getattr(model, "project", None) or Project()
    left = " · ".join(x for x in ("TVC", project.document, project.project or model.name) if x)
    right = " · ".join(
        x for x in (f"Rev. {project.revision}" if project.revision else "", project.date) if x
    )
    tables = [Table.of(t) for t in result.summary().tables if t.key == "conditions"]
    return Report(
        title=f"Torsional vibration calculation: {model.name}",
        inputs=_inputs(result),
        sections=sections,
        source=model.source,
        version=__version__,
        created=created,
        notes=list(result.notes),
        data=summary_lists(result),
        subject="installation",
        front=front,
        contents=True,
        header=(left, right),
        inputs_title="Installation data and settings",
        notes_title="Notes",
        summary_tables=tables,
    )
