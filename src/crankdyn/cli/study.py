"""``crankdyn study``: run a parameter study (docs/study-file.md)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from crankdyn.cli.common import console, deprecated_alias, merge_alias, pool_options
from crankdyn.cli.writer import Output, TextTable, summary_table

if TYPE_CHECKING:
    from rich.progress import Progress, TaskID

    from crankdyn.study.spec import StudySpec


def _list() -> None:
    """``--list``: the example studies, the figures and the [analysis] settings."""
    from crankdyn.cli.examples import print_examples
    from crankdyn.study.figures import FIGURES, SETTINGS

    print_examples("study")
    figures = TextTable(
        "Figures (names for [analysis] figures)",
        ["Name", "Column (SI)", "Shown in", "Better", "Applies to", "Description"],
        [
            [f.name, f.key, f.unit, f.better or "-", ", ".join(f.subjects), f.description]
            for f in FIGURES.values()
        ],
        text_columns={0, 1, 2, 3, 4, 5},
    )
    settings = TextTable(
        "[analysis] settings",
        ["Key", "Kind", "Meaning"],
        [[s.name, s.kind, s.help] for s in SETTINGS.values()],
        text_columns={0, 1, 2},
    )
    Output("table").write(blocks=[figures, settings])


def _dry_run(spec: StudySpec) -> None:
    """``--dry-run``: the parameters and the first five cases of ``spec``."""
    from crankdyn.study.cases import expand

    cases = expand(spec)
    rows = []
    for p in spec.parameters:
        if p.distribution is not None:  # a random parameter (p.is_random)
            how = f"{p.distribution.name} {list(p.distribution.args)} {p.unit}".rstrip()
            count = f"{spec.samples} draws"
        else:
            values = p.values or ()
            shown = ", ".join(str(v) for v in values[:6])
            how = shown + (", ..." if len(values) > 6 else "")
            count = str(len(values))
        rows.append([p.key, how, count])
    table = TextTable(
        f"Study: {spec.name}", ["Parameter", "Varies as", "Values"], rows, text_columns={0, 1}
    )
    first = TextTable(
        "First cases",
        ["Case", "Id", *(p.key for p in spec.parameters)],
        [
            [
                str(case.index + 1),
                case.case_id,
                *(_shown(case.params[p.key]) for p in spec.parameters),
            ]
            for case in cases[:5]
        ],
        text_columns={1},
    )
    line = (
        f"base {spec.base.kind}: {spec.base.source}; {len(cases)} cases; "
        f"figures: {', '.join(spec.figures)}"
    )
    Output("table").write(blocks=[table, line, first])


def _shown(value: Any) -> str:
    """A parameter's value as the case tables show it."""
    from crankdyn.study.cases import label

    return label(value)


def _default_out(study: str) -> Path:
    """The default output folder of the study STUDY: ``<stem>-results``."""
    stem = Path(study).stem if study.endswith(".toml") or "/" in study else study
    return Path(f"{stem}-results")


class _Bar:
    """A rich progress bar on stderr (only when stderr is a terminal)."""

    def __init__(self) -> None:
        """A bar not yet shown."""
        self.console = console(stderr=True)
        self.progress: Progress | None = None
        self.task: TaskID | None = None
        self.failed = 0

    def start(self, to_run: int, skipped: int, executor: str) -> None:
        """Say how many cases run where, and how many an earlier run finished."""
        if skipped:
            click.echo(f"{skipped} cases finished in an earlier run are kept", err=True)
        if not to_run:
            return
        click.echo(f"running {to_run} cases on a {executor}", err=True)
        if not self.console.is_terminal:
            return
        from rich.progress import (
            BarColumn,
            MofNCompleteColumn,
            Progress,
            TextColumn,
            TimeElapsedColumn,
            TimeRemainingColumn,
        )

        progress = Progress(
            TextColumn("cases"),
            BarColumn(),
            MofNCompleteColumn(),
            TextColumn("{task.fields[failed]} failed", style="red", markup=False),
            TimeElapsedColumn(),
            TextColumn("eta"),
            TimeRemainingColumn(),
            console=self.console,
            transient=False,
        )
        self.progress = progress
        progress.start()
        self.task = progress.add_task("cases", total=to_run, failed=0)

    def update(self, done: int, total: int, record: dict[str, Any]) -> None:
        """Count a finished case (``record``, its journal entry) and its failure."""
        if record.get("status") == "failed":
            self.failed += 1
        if self.progress is not None and self.task is not None:
            self.progress.update(self.task, completed=done, failed=self.failed)

    def stop(self) -> None:
        """Remove the bar, if one is shown."""
        if self.progress is not None:
            self.progress.stop()
            self.progress = None


@click.command("study")
@click.argument("study", metavar="STUDY", required=False)
@pool_options("Run")
@click.option(
    "-o",
    "--output",
    "output_dir",
    default=None,
    metavar="DIR",
    help="Output folder (default: STUDY-results); a rerun into it resumes the study.",
)
@deprecated_alias("--out", "--output", "out", "DIR")
@click.option(
    "--force", is_flag=True, help="Discard the results DIR holds and start the study over."
)
@click.option("--retry-failed", is_flag=True, help="Run the cases that failed before again.")
@click.option("--no-summary", is_flag=True, help="Write the tables only, not the HTML summary.")
@click.option("--dry-run", is_flag=True, help="Show the parameters and the first cases; run none.")
@click.option(
    "--list", "list_", is_flag=True, help="List the example studies, figures and settings."
)
@click.option(
    "--format",
    "fmt",
    type=click.Choice(("table", "json")),
    default="table",
    show_default=True,
    help="How to print the run's summary.",
)
def study_command(
    study: str | None,
    workers: int | None,
    scheduler: str | None,
    output_dir: str | None,
    out: str | None,
    force: bool,
    retry_failed: bool,
    no_summary: bool,
    dry_run: bool,
    list_: bool,
    fmt: str,
) -> int:
    """Run the parameter study STUDY (a study file, or a built-in example study; --list shows
    them): every case on a local process pool (all cores) or, with --scheduler, on a Dask
    cluster. Results go to DIR: results.parquet and results.csv (one row per case),
    summary/index.html. Finished cases are kept as they finish; a rerun into the same DIR
    skips them, so an interrupted study resumes."""
    if list_:
        _list()
        return 0
    if study is None:
        raise click.UsageError("missing argument STUDY (or give --list)")
    from crankdyn.io.catalogue import resolve_study

    spec = resolve_study(study)
    if dry_run:
        _dry_run(spec)
        return 0
    out = merge_alias(output_dir, out, "--output", "--out")
    folder = Path(out) if out else _default_out(study)
    from crankdyn.study.run.runner import run_study

    bar = _Bar()
    try:
        run = run_study(
            spec,
            folder,
            workers=workers,
            scheduler=scheduler,
            force=force,
            retry_failed=retry_failed,
            summary=not no_summary,
            progress=bar.update,
            on_start=bar.start,
        )
    except KeyboardInterrupt:  # a second Ctrl-C while the tables or the summary were written
        bar.stop()
        if not (folder / "journal.jsonl").exists():
            raise
        click.echo(
            f"crankdyn: interrupted; the finished cases are kept in {folder / 'journal.jsonl'} "
            "(run the same command again to resume and write the tables)",
            err=True,
        )
        return 130
    finally:
        bar.stop()
    if fmt == "json":
        click.echo(run.to_json())
    else:
        Output("table").write(
            blocks=[summary_table(run, f"Study: {spec.name}"), *_best(spec, folder)]
        )
    for text, count in run.errors:
        click.echo(f"failed ({count} cases): {text}", err=True)
    written = [folder / "results.parquet", folder / "results.csv"]
    if not no_summary:
        written.append(folder / "summary" / "index.html")
    click.echo("wrote " + ", ".join(str(p) for p in written), err=True)
    if run.interrupted:
        click.echo(
            f"crankdyn: interrupted; the {run.finished} finished cases are kept in {folder} "
            "(run the same command again to resume)",
            err=True,
        )
        return 130
    return 0


def _best(spec: StudySpec, folder: Path) -> list[TextTable]:
    """The best case of every figure with a sense of better, from the written table."""
    from crankdyn.display import format_value
    from crankdyn.study.figures import FIGURES
    from crankdyn.study.run.results import read_table
    from crankdyn.study.sensitivity import negligible_spread

    data = read_table(folder / "results.parquet").to_pydict()
    ok = [i for i, s in enumerate(data["status"]) if s == "ok"]
    rows = []
    for name in spec.figures:
        f = FIGURES[name]
        sense = spec.better(name)
        values = [(data[f.key][i], i) for i in ok if data[f.key][i] is not None]
        values = [(v, i) for v, i in values if math.isfinite(v)]
        if sense is None or not values:
            continue
        if negligible_spread([v for v, _ in values]):
            text, unit = format_value(values[0][0], f.si_unit or "")
            rows.append([f.label, f"{text} {unit}".strip(), "all", "the same in every case"])
            continue
        value, i = (min if sense == "min" else max)(values, key=lambda t: t[0])
        params = "; ".join(
            f"{p.key} = {data[p.column][i]:.6g} {p.unit}".rstrip()
            if p.is_numeric
            else f"{p.key} = {data[p.column][i]}"
            for p in spec.parameters
        )
        text, unit = format_value(value, f.si_unit or "")
        rows.append([f.label, f"{text} {unit}".strip(), str(data["case"][i]), params])
    if not rows:
        return []
    return [
        TextTable("Best cases", ["Figure", "Best", "Case", "Parameters"], rows, text_columns={0, 3})
    ]


def register(group: click.Group) -> None:
    """Add ``study`` to the command ``group``."""
    group.add_command(study_command)
