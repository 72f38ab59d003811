"""``crankdyn design``: search a design space for the design that passes the verdicts with the
widest margin (docs/design-file.md)."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

import click

from crankdyn.cli.common import console, pool_options
from crankdyn.cli.writer import Output, summary_blocks
from crankdyn.errors import InputError

if TYPE_CHECKING:
    from crankdyn.design.space import DesignSpace


def _resolve(space: str) -> DesignSpace:
    """A SPACE argument: a design file, or a built-in example design space's name."""
    from crankdyn.io.catalogue import load_example
    from crankdyn.io.examples import example_kind, example_names

    path = Path(space)
    if space.endswith(".toml") or "/" in space or path.is_file():
        from crankdyn.io.design_file import load_design

        if not path.is_file():
            raise InputError("no such design file", file=space)
        return load_design(path)
    if example_kind(space) == "design":
        return load_example(space, "design")
    from crankdyn.errors import did_you_mean

    names = example_names("design")
    raise InputError(
        f"no such file or built-in design space (examples: {', '.join(names)})"
        + did_you_mean(space, names),
        key="SPACE",
        value=space,
    )


class _Progress:
    """Candidates evaluated, on standard error (a line per generation)."""

    def __init__(self) -> None:
        """Nothing counted yet."""
        self.done = 0
        self.failed = 0

    def start(self, to_run: int, skipped: int, executor: str) -> None:
        """Say where the candidates run, and how many an earlier run evaluated."""
        if skipped:
            click.echo(f"{skipped} candidates evaluated in an earlier run are kept", err=True)
        click.echo(f"evaluating candidates on a {executor}", err=True)

    def update(self, done: int, total: int, record: dict[str, Any]) -> None:
        """Count a finished candidate."""
        self.done += 1
        if record.get("status") == "failed":
            self.failed += 1
        if done == total:
            click.echo(f"  {self.done} candidates evaluated ({self.failed} failed)", err=True)


@click.command("design")
@click.argument("space", metavar="SPACE", required=False)
@click.option(
    "-o",
    "--output",
    "output_dir",
    default=None,
    metavar="DIR",
    help="Output folder (default: SPACE-design); a rerun into it resumes the search.",
)
@pool_options("Evaluate")
@click.option("--seed", type=int, default=None, help="Seed of the search (the file's [search]).")
@click.option(
    "--max-candidates",
    type=int,
    default=None,
    metavar="N",
    help="The most candidates evaluated (the file's [search] max_candidates).",
)
@click.option("--no-report", is_flag=True, help="Write no TVC report of the chosen design.")
@click.option("--force", is_flag=True, help="Discard the results DIR holds and start over.")
@click.option("--list", "list_", is_flag=True, help="List the built-in example design spaces.")
def design_command(
    space: str | None,
    output_dir: str | None,
    workers: int | None,
    scheduler: str | None,
    seed: int | None,
    max_candidates: int | None,
    no_report: bool,
    force: bool,
    list_: bool,
) -> int:
    """Search SPACE's catalogue choices and ranges for the design that passes the verdicts
    with the widest margin. SPACE is a design file or a built-in example (--list shows them);
    by default every verdict row must pass and the worst margin is maximised. Every candidate
    is a case of the study runner (a local pool, or a Dask cluster with --scheduler),
    journalled in DIR, so a rerun resumes. Writes DIR/results.csv (every candidate),
    DIR/summary/index.html, DIR/best.toml (the chosen design, which crankdyn tvc reads),
    DIR/tvc/ (its TVC report) and DIR/pareto.png (several objectives).

    Exit status: 0 when a feasible design was found, 1 when none was, 2 on an error."""
    if list_:
        from crankdyn.cli.examples import print_examples

        print_examples("design")
        return 0
    if space is None:
        raise click.UsageError("missing argument SPACE (or give --list)")
    if max_candidates is not None and max_candidates < 1:
        raise InputError("expected at least 1", key="--max-candidates", value=max_candidates)
    if seed is not None and seed < 0:
        raise InputError("expected a whole number >= 0", key="--seed", value=seed)
    import dataclasses

    spec = _resolve(space)
    changes: dict[str, Any] = {}
    if seed is not None:
        changes["seed"] = seed
    if max_candidates is not None:
        changes["max_candidates"] = max_candidates
    if changes:
        spec = dataclasses.replace(spec, search=dataclasses.replace(spec.search, **changes))
    stem = Path(space).stem if space.endswith(".toml") else space
    folder = Path(output_dir) if output_dir else Path(f"{stem}-design")
    from crankdyn.study.run.design import run_design

    bar = _Progress()
    result = run_design(
        spec,
        folder,
        workers=workers,
        scheduler=scheduler,
        force=force,
        progress=bar.update,
        on_start=bar.start,
    )
    kept = result.evaluated + (result.base is not None) - result.computed
    if kept and not result.computed:
        click.echo(f"{kept} candidates evaluated in an earlier run are kept", err=True)
    blocks: list[Any] = summary_blocks(result, f"Design search: {spec.study.name}")
    written = [folder / "results.csv", folder / "summary" / "index.html"]
    written += [folder / "best.toml"] if result.found else []
    if result.found and not no_report:
        written.append(_report(folder, result))
    Output("table").write(blocks=blocks)
    click.echo("wrote " + ", ".join(str(p) for p in written), err=True)
    return 0 if result.found else 1


def _report(folder: Path, result: Any) -> Path:
    """The chosen design's TVC report (no PDF): its whole TVC where the search computed it
    here, else computed as the search's workers computed it (the study's analysis settings)."""
    from crankdyn.report.tvc import build_tvc_report
    from crankdyn.report.write import write_drawn
    from crankdyn.study.run.design import whole_tvc

    with console(stderr=True).status("TVC report of the chosen design"):
        tvc = result.tvc
        if tvc is None:
            tvc = whole_tvc(result.space, result.best.case)
        written = write_drawn(
            lambda built: build_tvc_report(tvc, built=built), folder / "tvc", force=True
        )
        return written / "index.html"


def register(group: click.Group) -> None:
    """Add ``design`` to the command ``group``."""
    group.add_command(design_command)
