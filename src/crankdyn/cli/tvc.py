"""``crankdyn tvc MODEL_OR_ENGINE``: the torsional vibration calculation report (HTML, PDF,
summary.json); the numbers come from the analysis session (:meth:`crankdyn.Analysis.tvc`)."""

from __future__ import annotations

from pathlib import Path

import click

from crankdyn.cli.common import (
    console,
    deprecated_alias,
    merge_alias,
    no_fail_option,
    rules_option,
    verdict_status,
)
from crankdyn.cli.torsion import model_session
from crankdyn.cli.writer import Output, summary_blocks
from crankdyn.errors import InputError

_HELP_OUTPUT = "Report folder (default: <name>-tvc); built aside and moved into place."


@click.command("tvc")
@click.argument("model", metavar="MODEL_OR_ENGINE")
@click.option("-o", "--output", "output_dir", default=None, metavar="DIR", help=_HELP_OUTPUT)
@deprecated_alias("--out", "--output", "out", "DIR")
@click.option("--no-pdf", is_flag=True, help="Write no PDF (the HTML page prints to one).")
@click.option(
    "--no-passage",
    is_flag=True,
    help="Leave out the time-domain passage through the barred ranges.",
)
@click.option("--force", is_flag=True, help="Replace an existing report folder.")
@rules_option()
@no_fail_option
def tvc_command(
    model: str,
    output_dir: str | None,
    out: str | None,
    no_pdf: bool,
    no_passage: bool,
    force: bool,
    rules: str | None,
    no_fail: bool,
) -> int:
    """The torsional vibration calculation of MODEL_OR_ENGINE: every running condition (normal
    firing, each cylinder misfiring, damper out of order) against every component's limit
    (the classification society's rule set, the engine builder's, the coupling, gear,
    generator and damper makers'), barred speed ranges and their passage, as a report folder
    with index.html, report.pdf (headless Chromium, where installed) and summary.json
    (crankdyn docs tvc).

    Every verdict row cites its rule, edition and clause (--rules chooses the rule set).
    Exit status: 0 when every verdict passed, 1 when one failed (the report is written), 2 on
    an error; --no-fail gives 0 whatever the verdict."""
    from rich.text import Text

    from crankdyn.report.pdf import print_pdf
    from crankdyn.report.tvc import build_tvc_report
    from crankdyn.report.write import write_drawn

    output_dir = merge_alias(output_dir, out, "--output", "--out")
    stem = Path(model).stem if model.endswith(".toml") else model
    target = Path(output_dir) if output_dir else Path(f"{stem}-tvc")
    if target.exists() and not force:  # fail before the long work
        raise InputError("already exists; not overwritten without --force", file=str(target))
    session = model_session(model, rules=rules)
    err = console(stderr=True)
    title = "Torsional vibration calculation"
    with err.status(title) as status:

        def step(text: str) -> None:
            """The step the calculation is at, beside the spinner (as text, never markup)."""
            status.update(Text(f"{title}: {text}"))

        result = session.tvc(passage=not no_passage, progress=step)
        pdf_note: list[str] = []
        step("the report")

        def finish(folder: Path) -> None:
            """Print the report folder's PDF (unless --no-pdf), or note why not."""
            if no_pdf:
                return
            step("the PDF")
            why = print_pdf(folder / "index.html", folder / "report.pdf")
            if why is not None:
                pdf_note.append(why)

        # the folder written: a numbered sibling when ``target`` appeared meanwhile
        # each section's figures drawn while the next are made
        target = write_drawn(
            lambda built: build_tvc_report(result, built=built), target, force=force, finish=finish
        )
    # the verdict line (with the input warnings it stands on) is the summary's
    blocks: list = summary_blocks(result, f"{result.model_name}: torsional vibration calculation")
    blocks.extend(pdf_note)
    blocks.append(f"Report: {target / 'index.html'}")
    if not no_pdf and not pdf_note:
        blocks.append(f"PDF: {target / 'report.pdf'}")
    Output("table").write(blocks=blocks, warnings=result)
    return verdict_status(result.passed, no_fail)


def register(group: click.Group) -> None:
    """Add ``tvc`` to the command ``group``."""
    group.add_command(tvc_command)
