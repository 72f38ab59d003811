"""Running a design search on the study runner, and writing its outputs.

The search (:mod:`crankdyn.design.search`) runs in this process and hands its candidates, a
generation at a time, to a :class:`crankdyn.study.run.runner.CaseRunner` (one process, the local
pool or a Dask cluster, as a study's cases; every candidate journalled by its case id, so a
second run of the same search reads its candidates back instead of computing them). The
outputs, in the folder ``out``::

    journal.jsonl, study.json   the study runner's journal and manifest
    results.csv                 every candidate: number, id, status, parameters, objectives,
                                feasible, constraint violation, figures, error
    results.parquet             the same (when pyarrow is installed)
    design.json                 the search's key figures (DesignResult.to_dict)
    best.toml                   the chosen design as a file ``crankdyn tvc`` reads (with the
                                files the base names, beside it)
    pareto.png                  the candidates and the Pareto front (several objectives)
    summary/index.html          the search's summary as a crankdyn report: key figures, the
                                chosen design's verdict rows, the best designs with their margin
                                per verdict row, the Pareto front, the sensitivities, the plot
"""

from __future__ import annotations

import io
import math
from pathlib import Path
from typing import Any

from crankdyn.design.result import DesignResult
from crankdyn.design.search import Candidate, column_of, run_search
from crankdyn.design.space import DesignSpace
from crankdyn.display import csv_text
from crankdyn.io.output import write_bytes, write_text
from crankdyn.io.study_file import parse_base
from crankdyn.io.toml_text import dumps
from crankdyn.study.cases import Case, case_id
from crankdyn.study.docpath import apply_values, referenced_files
from crankdyn.study.figures import FIGURES, CaseContext, case_verdicts, reads_whole_tvc
from crankdyn.study.run.runner import CaseRunner, Progress
from crankdyn.study.run.worker import verdicts_of_record

__all__ = [
    "BEST_DESIGNS",
    "candidate_document",
    "run_design",
    "whole_tvc",
    "write_design",
    "write_summary",
]

BEST_DESIGNS = 3
"""The best designs whose verdict rows are tabled (as their workers kept them)."""


def base_case() -> Case:
    """The base design as a case: no parameter set.

    Returns
    -------
    crankdyn.study.cases.Case
        The case with empty parameters.
    """
    return Case(index=0, case_id=case_id({}), params={}, numbers={})


def candidate_document(space: DesignSpace, case: Case) -> dict[str, Any]:
    """The base document with a candidate's values written in.

    Parameters
    ----------
    space : crankdyn.design.space.DesignSpace
        The space.
    case : crankdyn.study.cases.Case
        The candidate.

    Returns
    -------
    dict
        The document (a copy).
    """
    values: dict[Any, Any] = {}
    for p in space.parameters:
        if p.key in case.params:
            values.update(p.assignments(case.params[p.key]))
    return apply_values(space.study.base.document, values, space.study.remove)


def _verdicts(space: DesignSpace, candidate: Candidate) -> tuple[tuple[Any, ...], Any]:
    """The verdict rows a candidate's constraints and objective read (:func:`crankdyn.study.
    figures.case_verdicts`): those its worker kept in its record, else analysed again here
    (a journal of an earlier version), with the whole TVC when it was computed here (None
    otherwise), so that its report need not compute it again."""
    kept = verdicts_of_record(candidate.record)
    if kept is not None:
        return kept, None
    figures = space.study.figures
    if reads_whole_tvc(figures):
        tvc = whole_tvc(space, candidate.case)
        return tuple(tvc.verdicts), tvc
    return case_verdicts(_context(space, candidate.case), figures), None


def _context(space: DesignSpace, case: Case) -> CaseContext:
    """A candidate as a study case (its document read as the base is, the study's settings)."""
    base = space.study.base
    document = candidate_document(space, case)
    subject = parse_base(base.kind, document, file=base.source, base_dir=base.base_dir)
    return CaseContext(subject, space.study.settings, base.kind)


def whole_tvc(space: DesignSpace, case: Case) -> Any:
    """A candidate's whole TVC (:meth:`crankdyn.session.Analysis.tvc`: every condition, the
    events and the passages), as the search's workers compute it (the study's analysis
    settings).

    Parameters
    ----------
    space : crankdyn.design.space.DesignSpace
        The space.
    case : crankdyn.study.cases.Case
        The candidate.

    Returns
    -------
    crankdyn.tvc.TvcResult
        Its whole TVC.
    """
    return _context(space, case).analysis.tvc()


def _text(space: DesignSpace, c: Candidate) -> str:
    parts = []
    for p in space.parameters:
        value = c.case.numbers.get(p.key)
        unit = f" {p.unit}" if p.unit and p.key in space.ranges else ""
        parts.append(f"{space.name_of(p.key)} = {value}{unit}")
    return "; ".join(parts)


def run_design(
    space: DesignSpace,
    out: str | Path,
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    force: bool = False,
    progress: Progress | None = None,
    on_start: Any = None,
) -> DesignResult:
    """Search a design space on the study runner (module docstring).

    Parameters
    ----------
    space : crankdyn.design.space.DesignSpace
        The space.
    out : str or pathlib.Path
        The output folder (its journal makes a rerun resume).
    workers, scheduler, force
        As for :func:`crankdyn.study.run.runner.run_study`.
    progress, on_start
        As for :class:`crankdyn.study.run.runner.CaseRunner`.

    Returns
    -------
    crankdyn.design.result.DesignResult
        The search's result (the chosen design's verdict rows, the best designs').

    Raises
    ------
    InputError
        If the folder cannot be used, the workers or the scheduler are wrong, or the search
        cannot run (an exhaustive search of too large a space).
    """
    from crankdyn.design.search import pareto_front

    method = space.method()
    if method == "exhaustive":
        batch = space.discrete_count
    else:  # a generation of the differential evolution
        batch = max(5, space.search.population * len(space.parameters))
    with CaseRunner(
        space.study,
        out,
        workers=workers,
        scheduler=scheduler,
        force=force,
        batch=batch,
        progress=progress,
        on_start=on_start,
    ) as runner:
        method, candidates, base = run_search(space, runner.run, base_case())
        path = runner.path
        computed = runner.ran
    feasible = [c for c in candidates if c.feasible]
    best = feasible[0] if feasible else None
    chosen_number, tvc, notes = None, None, []
    normal_only = "failed_rows" not in space.study.figures and any(
        c.figure == "condition_passed" for c in space.constraints
    )
    if best is not None and normal_only and space.search.verify:
        for c in feasible[: space.search.verify]:
            tvc = whole_tvc(space, c.case)
            if tvc.passed:
                chosen_number, best = c.number, c
                break
        else:
            tvc = None
            notes.append(
                f"none of the {min(len(feasible), space.search.verify)} best designs passes every "
                "row of the whole TVC (misfires, damper out of order, events, passages); the "
                'best by the search is shown: give [constraints] verdicts = "all"'
            )
        if chosen_number is not None and chosen_number != feasible[0].number:
            notes.append(
                f"candidate {feasible[0].number}, the best by the normal-firing rows, fails a row "
                f"of the whole TVC; candidate {chosen_number} is the best that passes it"
            )
        if chosen_number is not None:
            feasible = [best, *(c for c in feasible if c is not best)]
    analysed = [_verdicts(space, c) for c in feasible[:BEST_DESIGNS]]
    best_verdicts = tuple(rows for rows, _ in analysed)
    if tvc is None and analysed and analysed[0][1] is not None and not notes:
        tvc = analysed[0][1]  # the chosen design's whole TVC, for its report: computed once
    tvc_passed = None if tvc is None and not notes else tvc is not None and bool(tvc.passed)
    figures = space.study.figures
    whole = reads_whole_tvc(figures)
    if tvc is None and not notes and analysed and whole:  # its worker's whole TVC's rows
        tvc_passed = bool(analysed[0][0]) and all(v.passed for v in analysed[0][0])
    front: tuple[int, ...] = ()
    if len(space.objectives) > 1:
        front = tuple(pareto_front(candidates, [o.sense for o in space.objectives]))
    first = space.objectives[0]

    def objective_of(c: Candidate | None) -> float | None:
        if c is None or not c.ok or c.objectives[0] is None:
            return None
        value = c.objectives[0]
        return value if math.isfinite(value) else None

    result = DesignResult(
        name=space.study.name,
        method=method,
        objective=f"{first.sense} {first.label or first.name}",
        evaluated=len(candidates),
        computed=computed,
        feasible_count=len(feasible),
        failed_count=sum(1 for c in candidates if not c.ok),
        best_objective=objective_of(best),
        base_objective=objective_of(base),
        chosen=_text(space, best) if best is not None else "none feasible",
        chosen_number=chosen_number,
        tvc=tvc,
        tvc_passed=tvc_passed,
        notes=tuple(notes),
        space=space,
        candidates=tuple(candidates),
        base=base,
        verdicts=best_verdicts[0] if best_verdicts else (),
        best_verdicts=best_verdicts,
        front=front,
    )
    write_design(result, path)
    return result


def _columns(space: DesignSpace) -> list[tuple[str, Any]]:
    cols: list[tuple[str, Any]] = [
        ("candidate", lambda c: c.number),
        ("case_id", lambda c: c.case.case_id),
        ("status", lambda c: c.record.get("status")),
    ]
    for p in space.parameters:
        cols.append((column_of(space, p.key), lambda c, k=p.key: c.case.numbers.get(k)))
    for i, o in enumerate(space.objectives):
        cols.append((o.column, lambda c, i=i: c.objectives[i]))
    cols.append(("feasible", lambda c: c.feasible))
    cols.append(("violation", lambda c: c.violation))
    for name in space.study.figures:
        cols.append((FIGURES[name].key, lambda c, n=name: c.figures.get(n)))
    cols.append(("error", lambda c: c.record.get("error")))
    cols.append(("elapsed_s", lambda c: c.record.get("elapsed_s")))
    return cols


def _cell(value: Any) -> Any:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value) if math.isfinite(value) else None
    return value


def write_design(result: DesignResult, out: Path) -> list[Path]:
    """Write a design search's tables, its chosen design and its Pareto plot (module
    docstring).

    Parameters
    ----------
    result : crankdyn.design.result.DesignResult
        The search's result.
    out : pathlib.Path
        The output folder.

    Returns
    -------
    list of pathlib.Path
        The files written.
    """
    space = result.space
    assert space is not None  # a search's result
    columns = _columns(space)
    ordered = sorted(result.candidates, key=lambda c: c.number)
    rows = [[name for name, _ in columns]]
    rows.extend([_cell(get(c)) for _, get in columns] for c in ordered)
    written = [write_text(out / "results.csv", csv_text(rows), force=True)]
    written.append(write_text(out / "design.json", result.to_json() + "\n", force=True))
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:  # the studies extra is optional for the table in Parquet
        pa = None
    if pa is not None:
        data = {}
        for name, get in columns:
            values = [get(c) for c in ordered]
            if all(v is None or isinstance(v, bool) for v in values):
                data[name] = pa.array(values, type=pa.bool_())
            elif all(
                v is None or (isinstance(v, int | float) and not isinstance(v, bool))
                for v in values
            ):
                data[name] = pa.array(
                    [
                        None if v is None or not math.isfinite(float(v)) else float(v)
                        for v in values
                    ],
                    type=pa.float64(),
                )
            else:
                data[name] = pa.array([None if v is None else str(v) for v in values])
        sink = io.BytesIO()
        pq.write_table(pa.table(data), sink)
        written.append(write_bytes(out / "results.parquet", sink.getvalue(), force=True))
    best = result.best
    if best is not None:
        base = space.study.base
        document = candidate_document(space, best.case)
        named = {text for text, _ in referenced_files(document, base.base_dir or Path("."))}
        for text, data_bytes in base.files:
            if text in named:  # the files the chosen design names, beside it
                (out / text).parent.mkdir(parents=True, exist_ok=True)
                written.append(write_bytes(out / text, data_bytes, force=True))
        header = (
            f"# The chosen design of the design search {space.study.name!r} (crankdyn design):\n"
            f"# {_text(space, best)}\n# base: {base.source}\n"
        )
        written.append(write_text(out / "best.toml", header + dumps(document), force=True))
    written.append(write_summary(result, out))
    if len(space.objectives) > 1:
        image = io.BytesIO()
        result.plot().savefig(image, format="png", dpi=120)
        written.append(write_bytes(out / "pareto.png", image.getvalue(), force=True))
    return written


def write_summary(result: DesignResult, out: Path) -> Path:
    """The search's summary as a crankdyn report (``summary/index.html``): one section that
    renders the result's summary (its key figures, verdict rows, tables, notes) and the plot of
    the candidates (with the Pareto front of several objectives).

    Parameters
    ----------
    result : crankdyn.design.result.DesignResult
        The search's result.
    out : pathlib.Path
        The output folder.

    Returns
    -------
    pathlib.Path
        The summary's index.html.
    """
    import datetime as _dt

    from crankdyn import __version__
    from crankdyn.plots.render import collector_paused
    from crankdyn.report.model import Plot, Report, Section
    from crankdyn.report.write import write_report

    space = result.space
    assert space is not None  # a search's result
    several = len(space.objectives) > 1
    with collector_paused():  # the figure lives to the end of the writing
        plot = Plot(
            "candidates",
            "Candidates and Pareto front" if several else "Objective of every candidate",
            result.plot(),
            caption="feasible and infeasible candidates"
            + (", the Pareto front joined" if several else ", in the order evaluated"),
        )
        section = Section.of(
            "design",
            "Design search",
            [result],
            intro=(
                f"{result.evaluated} candidates of the design space evaluated on the study "
                f"runner ({result.method}); the chosen design is written to best.toml, its "
                "full TVC report to tvc/index.html."
            ),
            plots=[plot],
            json=result.to_dict(),
        )
        report = Report(
            title=f"Design search: {space.study.name}",
            inputs=[
                ("Base", space.study.base.source),
                *((space.name_of(p.key), _described(space, p.key)) for p in space.parameters),
            ],
            sections=[section],
            source=space.source,
            version=__version__,
            created=_dt.datetime.now().strftime("%Y-%m-%d %H:%M"),
        )
        return write_report(report, out / "summary", force=True) / "index.html"


def _described(space: DesignSpace, key: str) -> str:
    """A choice's values or a range's bounds, for the summary's inputs."""
    p = space.parameter(key)
    if p.distribution is not None:
        low, high = p.distribution.args
        return f"{low:g} to {high:g} {p.unit or ''}".rstrip()
    names = p.names or tuple(str(v) for v in p.values or ())
    return ", ".join(names)
