"""A report page printed to PDF by headless Chromium (boundary).

Why Chromium: it is the browser the report is tested in (its print stylesheet, A4, every table
row on paper: tests/report), it renders the page exactly as a reader's browser prints it, and it
needs nothing from pip. The pip-installable HTML-to-PDF renderers either need native libraries
that pip does not install (WeasyPrint: Pango and HarfBuzz) or do not support the page's CSS
(xhtml2pdf: no flexible layout, no print media queries). Where no Chromium is installed the
report is written without the PDF and the command says how to get one (scripts/install-browser.sh
or the browser's own Print to PDF).

Page numbers and running headers: Chromium's print ignores CSS paged media's margin boxes
(``@page { @top-center { content: ... } }``), so the page is printed through the DevTools
protocol's ``Page.printToPDF``, whose ``headerTemplate`` and ``footerTemplate`` put the running
header (the page's ``<meta name="crankdyn-running-header">``: document, revision) on every page
and "Page n of N" at the foot. The protocol is spoken over ``--remote-debugging-pipe`` (file
descriptors 3 and 4, JSON messages ended by a NUL byte), with the standard library only. The
contents list gets its page numbers from a first print: the PDF's outline (bookmarks, written
with ``generateDocumentOutline``) names the page of every heading
(:func:`crankdyn.report.pdf_outline.heading_pages`); they are written into the page's
``.toc-page`` cells and the page is printed again (the contents list has a page of its own, so
the numbers do not move the headings). The first print, read for its outline only, is made with
the pictures hidden (``visibility: hidden``: each keeps its room, so every heading is on the
same page, but none is encoded into that print; tests/report/test_pdf_print.py). Where the
protocol fails (an old Chromium), the page is printed with ``--print-to-pdf`` and without
headers.
"""

from __future__ import annotations

import base64
import contextlib
import fcntl
import html as _html
import json
import os
import select
import shutil
import subprocess
import time
from pathlib import Path
from typing import Any

__all__ = ["BROWSERS", "find_browser", "print_pdf"]

BROWSERS = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable")

_TIMEOUT = 180.0  # s
_MARGIN = 16.0 / 25.4  # in: room for the running header and the page numbers

_ARGS = (
    "--headless=new",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-dev-shm-usage",
    "--no-first-run",
    "--disable-background-networking",
)

_FILL_PAGES = """(pages => {
  for (const cell of document.querySelectorAll('.toc-page')) {
    const target = document.getElementById(cell.dataset.for);
    const title = target ? target.textContent.split(/\\s+/).join(' ').trim() : '';
    if (title in pages) cell.textContent = String(pages[title]);
  }
  return document.querySelectorAll('.toc-page').length;
})"""


# the pictures hidden for the outline's print: the same layout (visibility keeps their room),
# nothing to encode (the marine TVC's first print 2.0 -> 1.2 s; the headings' pages the same)
_HIDE_PICTURES = """(() => {
  const style = document.createElement('style');
  style.id = 'crankdyn-outline-print';
  style.textContent = 'img, svg, canvas { visibility: hidden !important; }';
  document.head.appendChild(style);
  return 1;
})()"""
_SHOW_PICTURES = "document.getElementById('crankdyn-outline-print').remove()"


def _evaluate(tools: _DevTools, expression: str) -> Any:
    """The value of a JavaScript ``expression`` in the attached page."""
    answer = tools.call("Runtime.evaluate", {"expression": expression, "returnByValue": True})
    return answer["result"].get("value")


def find_browser() -> str | None:
    """The path of a headless-capable Chromium (the first of :data:`BROWSERS` on the PATH).

    Returns
    -------
    str or None
        The executable's path, or None when none is installed.
    """
    for name in BROWSERS:
        path = shutil.which(name)
        if path:
            return path
    return None


class _Failed(Exception):
    """The DevTools session did not give a PDF."""


class _DevTools:
    """A headless Chromium driven over ``--remote-debugging-pipe`` (module docstring)."""

    def __init__(self, browser: str, deadline: float) -> None:
        to_browser_r, self._to_browser = os.pipe()
        self._from_browser, from_browser_w = os.pipe()

        def fds() -> None:  # the browser reads fd 3 and writes fd 4 (dup2: kept over exec)
            high = [
                fcntl.fcntl(fd, fcntl.F_DUPFD_CLOEXEC, 10) for fd in (to_browser_r, from_browser_w)
            ]
            os.dup2(high[0], 3)
            os.dup2(high[1], 4)

        self._process = subprocess.Popen(
            [browser, *_ARGS, "--remote-debugging-pipe", "about:blank"],
            close_fds=False,  # the others are close-on-exec (PEP 446); 3 and 4 must stay
            preexec_fn=fds,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        os.close(to_browser_r)
        os.close(from_browser_w)
        self._deadline = deadline
        self._buffer = b""
        self._next = 0
        self.session: str | None = None

    def _read(self) -> dict[str, Any]:
        while b"\0" not in self._buffer:
            left = self._deadline - time.monotonic()
            if left <= 0.0:
                raise _Failed("Chromium took longer than 180 s")
            ready, _, _ = select.select([self._from_browser], [], [], left)
            if not ready:
                continue
            chunk = os.read(self._from_browser, 1 << 16)
            if not chunk:
                raise _Failed("Chromium closed the DevTools pipe")
            self._buffer += chunk
        message, _, self._buffer = self._buffer.partition(b"\0")
        return json.loads(message)

    def call(self, method: str, params: dict[str, Any] | None = None) -> dict[str, Any]:
        """Send one command (to the attached page, if any) and wait for its answer."""
        self._next += 1
        message: dict[str, Any] = {"id": self._next, "method": method, "params": params or {}}
        if self.session is not None and not method.startswith(("Target.", "Browser.")):
            message["sessionId"] = self.session
        os.write(self._to_browser, json.dumps(message).encode() + b"\0")
        while True:
            answer = self._read()
            if answer.get("id") == self._next:
                if "error" in answer:
                    raise _Failed(str(answer["error"].get("message", answer["error"])))
                return answer.get("result", {})

    def wait_for(self, event: str) -> None:
        """Wait for an event of the attached page."""
        while self._read().get("method") != event:
            pass

    def close(self) -> None:
        """Close the browser (and kill it if it does not go)."""
        with contextlib.suppress(_Failed, OSError, ValueError):
            self.call("Browser.close")
        try:
            self._process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self._process.kill()
            self._process.wait()
        for fd in (self._to_browser, self._from_browser):
            with contextlib.suppress(OSError):
                os.close(fd)


def _templates(header: str, right: str) -> tuple[str, str]:
    """The header and footer templates of ``Page.printToPDF`` (font sizes must be given)."""
    style = (
        "font: 7pt system-ui, sans-serif; color: #5b6b7b; width: 100%; margin: 0 12mm; "
        "display: flex; justify-content: space-between;"
    )
    top = (
        f"<div style='{style} border-bottom: 0.5pt solid #d8dee6; padding-bottom: 1mm'>"
        f"<span>{_html.escape(header)}</span><span>{_html.escape(right)}</span></div>"
    )
    foot = (
        f"<div style='{style}'><span>crankdyn torsional vibration calculation</span>"
        "<span>Page <span class='pageNumber'></span> of <span class='totalPages'></span>"
        "</span></div>"
    )
    return top, foot


def _load(tools: _DevTools, html: Path) -> None:
    """Open ``html`` in a new page of the browser, attached, and wait until it has loaded."""
    target = tools.call("Target.createTarget", {"url": "about:blank"})["targetId"]
    tools.session = tools.call("Target.attachToTarget", {"targetId": target, "flatten": True})[
        "sessionId"
    ]
    tools.call("Page.enable")
    tools.call("Page.navigate", {"url": html.resolve().as_uri()})
    tools.wait_for("Page.loadEventFired")


def _print_devtools(browser: str, html: Path) -> bytes:
    """The page printed over the DevTools protocol, the contents list's pages filled in."""
    tools = _DevTools(browser, time.monotonic() + _TIMEOUT)
    try:
        _load(tools, html)
        meta = _evaluate(
            tools,
            "[(document.querySelector('meta[name=crankdyn-running-header]') || {}).content"
            " || document.title, (document.querySelector("
            "'meta[name=crankdyn-running-header-right]') || {}).content || '']",
        ) or ["", ""]
        top, foot = _templates(str(meta[0]), str(meta[1]))
        options = {
            "displayHeaderFooter": True,
            "headerTemplate": top,
            "footerTemplate": foot,
            "printBackground": True,
            "paperWidth": 210 / 25.4,
            "paperHeight": 297 / 25.4,
            "marginTop": _MARGIN,
            "marginBottom": _MARGIN,
            "marginLeft": 12 / 25.4,
            "marginRight": 12 / 25.4,
            "generateDocumentOutline": True,
        }
        cells = _evaluate(tools, "document.querySelectorAll('.toc-page').length")
        if not cells:  # no contents list: one print
            return base64.b64decode(tools.call("Page.printToPDF", options)["data"])
        from crankdyn.report.pdf_outline import heading_pages

        # the first print only for its outline (the headings' pages): the pictures hidden, as
        # they take the same room (visibility, not display) but need not be encoded into it
        _evaluate(tools, _HIDE_PICTURES)
        pages = heading_pages(base64.b64decode(tools.call("Page.printToPDF", options)["data"]))
        _evaluate(tools, _SHOW_PICTURES)
        if pages:
            _evaluate(tools, f"{_FILL_PAGES}({json.dumps(pages)})")
        return base64.b64decode(tools.call("Page.printToPDF", options)["data"])
    finally:
        tools.close()


def _print_plain(browser: str, html: Path, pdf: Path) -> str | None:
    """The page printed with ``--print-to-pdf`` (no running header, no page numbers)."""
    args = [
        browser,
        *_ARGS,
        "--no-pdf-header-footer",
        f"--print-to-pdf={pdf}",
        html.resolve().as_uri(),
    ]
    try:
        run = subprocess.run(args, capture_output=True, timeout=_TIMEOUT, check=False)
    except (OSError, subprocess.TimeoutExpired) as exc:
        return f"no PDF: Chromium did not print the page ({type(exc).__name__})"
    if run.returncode != 0 or not pdf.is_file() or pdf.stat().st_size == 0:
        return f"no PDF: Chromium did not print the page (exit status {run.returncode})"
    return None


def print_pdf(html: Path, pdf: Path, browser: str | None = None) -> str | None:
    """Print ``html`` to ``pdf`` (A4, the page's print stylesheet, a running header and page
    numbers on every page, the contents list's page numbers filled in) with headless Chromium
    (module docstring).

    Parameters
    ----------
    html : pathlib.Path
        The page to print.
    pdf : pathlib.Path
        The PDF file to write.
    browser : str or None
        The Chromium executable; None: :func:`find_browser`.

    Returns
    -------
    str or None
        None when the PDF was written, else one sentence saying why there is none (no browser,
        the browser failed or took longer than 180 s).
    """
    browser = browser or find_browser()
    if browser is None:
        return (
            "no PDF: no Chromium found (install it, e.g. scripts/install-browser.sh, or print "
            "index.html to PDF from a browser)"
        )
    try:
        data = _print_devtools(browser, html)
    except (_Failed, OSError, ValueError, KeyError, TypeError):
        return _print_plain(browser, html, pdf)
    if not data.startswith(b"%PDF-"):
        return _print_plain(browser, html, pdf)
    pdf.write_bytes(data)
    return None
