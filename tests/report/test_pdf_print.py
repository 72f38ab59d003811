"""The PDF's two prints (crankdyn.report.pdf): the first, for the outline only, with the pictures
hidden; the second, the document, with them shown and the contents list's pages filled in.

A page of three headings, each after a picture most of a page high, so that every heading lands
on a page of its own: the contents list names the page each heading is printed on (the same
pages as a print with the pictures shown throughout), and the document holds every picture."""

from __future__ import annotations

import base64
import io
import re
import time

import numpy as np
import pytest

from crankdyn.plots.render import png_file
from crankdyn.report import pdf as pdf_module
from crankdyn.report.pdf_outline import heading_pages

pytestmark = pytest.mark.skipif(
    pdf_module.find_browser() is None, reason="no Chromium: the PDF is not printed"
)


def _page(tmp_path):
    rgba = np.zeros((40, 60, 4), dtype=np.uint8)
    rgba[..., 0], rgba[..., 3] = 200, 255
    picture = base64.b64encode(png_file(rgba.tobytes(), 60, 40, dpi=110)).decode()
    contents = "".join(
        f"<li>{k} <span class='toc-page' data-for='h-{k}'></span></li>" for k in (1, 2, 3)
    )
    body = "".join(
        f"<img src='data:image/png;base64,{picture}' style='width: 100%; height: 180mm'>"
        f"<h2 id='h-{k}'>Section {k}</h2><p>text of section {k}</p>"
        for k in (1, 2, 3)
    )
    html = tmp_path / "index.html"
    html.write_text(
        f"<!doctype html><html><head><title>t</title></head><body><ol>{contents}</ol>{body}"
        "</body></html>",
        encoding="utf-8",
    )
    return html


def _shown_pages(html):
    """The headings' pages of one print with the pictures shown (as before the hiding)."""
    tools = pdf_module._DevTools(pdf_module.find_browser(), time.monotonic() + 60)
    try:
        pdf_module._load(tools, html)
        printed = tools.call("Page.printToPDF", {"generateDocumentOutline": True})["data"]
        return heading_pages(base64.b64decode(printed))
    finally:
        tools.close()


def test_the_contents_name_each_headings_page_and_every_picture_is_printed(tmp_path):
    from pypdf import PdfReader

    html = _page(tmp_path)
    target = tmp_path / "report.pdf"
    assert pdf_module.print_pdf(html, target) is None
    reader = PdfReader(io.BytesIO(target.read_bytes()))
    texts = [page.extract_text() for page in reader.pages]
    listed = dict(re.findall(r"^\d\. (\d) (\d+)$", texts[0], flags=re.M))
    assert sorted(listed) == ["1", "2", "3"], texts[0]
    for k, page in listed.items():
        assert f"Section {k}" in texts[int(page) - 1], (k, page)
    assert len(set(listed.values())) == 3  # a page each: the pictures took their room
    # the same pages as a print with the pictures shown
    assert {k: int(v) for k, v in listed.items()} == {
        title.split()[-1]: page for title, page in _shown_pages(html).items()
    }
    pictures = sum(len(page.images) for page in reader.pages)
    assert pictures == 3
