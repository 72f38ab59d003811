"""``crankdyn docs [TOPIC]``: the user documentation, offline, in the terminal or a browser."""

from __future__ import annotations

import os
import re
import shutil
import sys
import webbrowser

import click
from rich.table import Table as RichTable

from crankdyn import docs
from crankdyn.cli.common import console
from crankdyn.errors import InputError

_LINK = re.compile(r"\[([^\]\n]+)\]\(([A-Za-z0-9_.-]+)\.md(#[^)\s]*)?\)")
_WIDTH = 100


def terminal_markdown(text: str) -> str:
    """The page's Markdown with links to other pages turned into the command that shows them.

    ``[the engine file](engine-file.md)`` becomes ``the engine file (`crankdyn docs engine-file`)``;
    a link whose text is the file name becomes the command alone. Other links are kept.
    """
    names = set(docs.topic_names())

    def replace(m: re.Match[str]) -> str:
        """One link, as the command that shows its page (other links as they are)."""
        label, page = m.group(1), m.group(2)
        if page not in names:
            return m.group(0)
        command = f"`{docs.ref(page)}`"
        if label.strip("`") in (page, f"{page}.md"):
            return command
        return f"{label} ({command})"

    return _LINK.sub(replace, text)


def _list() -> None:
    """The topics and their pages' titles, as a table."""
    if not docs.topics():
        docs.topic("")  # raises: the pages are not installed
    out = console()
    table = RichTable(title="crankdyn documentation", header_style="bold")
    table.add_column("Topic")
    table.add_column("Page")
    for t in docs.topics():
        table.add_row(t.name, t.title)  # markup is off: titles as written
    out.print(table)
    out.print(
        "Read one in the terminal: crankdyn docs TOPIC; in a browser: crankdyn docs --html [TOPIC]"
    )


def _show(name: str, raw: bool) -> None:
    """The page of topic ``name``, rendered (paged on a terminal) or, with ``raw``, as
    Markdown."""
    text = docs.read(name)
    if raw:
        click.echo(text, nl=not text.endswith("\n"))
        return
    width = min(shutil.get_terminal_size((_WIDTH, 24)).columns, _WIDTH)
    out = console(width=width)
    from rich.markdown import Markdown  # markdown-it: only when a page is shown

    page = Markdown(terminal_markdown(text), hyperlinks=False, code_theme="ansi_dark")
    if out.is_terminal and sys.stdin.isatty():
        os.environ.setdefault("LESS", "-FRX")  # colours, and no pager for a short page
        with out.pager(styles=True):
            out.print(page)
    else:
        out.print(page)


def _open_html(name: str | None) -> None:
    """Open the built HTML site (the page of topic ``name``) in a browser; a one-line error
    when it is not built here (an InputError: exit status 2)."""
    page = docs.html_page(name)
    if page is None:
        raise InputError(
            "the HTML documentation is not built here: in a crankdyn repository, `make docs` "
            "builds it into docs/_build/html (`crankdyn docs "
            + (name if name else "TOPIC")
            + "` shows the same pages in the terminal)",
            key="--html",
        )
    uri = page.as_uri()
    click.echo(f"opening {uri}", err=True)
    if not webbrowser.open(uri):
        click.echo(f"no web browser found here: open {uri} in one", err=True)


@click.command("docs")
@click.argument("topic", metavar="[TOPIC]", required=False)
@click.option("--html", "html", is_flag=True, help="Open the HTML site (the page of TOPIC).")
@click.option("--raw", is_flag=True, help="Print the page's Markdown source as it is.")
def docs_command(topic: str | None, html: bool, raw: bool) -> int:
    """Read the user documentation offline: without TOPIC, list the topics; with one, show its
    page in the terminal (paged when the output is a terminal). The pages ship with crankdyn;
    --html opens the built HTML site instead (API and command reference, worked examples)."""
    if topic is not None:
        topic = docs.topic(topic).name  # an unknown topic ends here, with a did-you-mean
    if html:
        _open_html(topic)
    elif topic is None:
        _list()
    else:
        _show(topic, raw)
    return 0


def register(group: click.Group) -> None:
    """Add ``docs`` to the command ``group``."""
    group.add_command(docs_command)
